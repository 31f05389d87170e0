"""The run's plot and terminal output (railcontact.run) on synthetic results."""

from pathlib import Path

import numpy as np
import pytest

from railcontact.run import (JACOBIAN_OUTPUTS, VALIDITY_NOTES, creep_curves, figure_results,
                             message_lines, not_computed, plot_layout, plot_results,
                             summary_lines, validity_causes)
from railcontact.scene import INPUTS, load_scene

ROOT = Path(__file__).resolve().parents[1]
SCENES = ROOT / "examples" / "scenes"
SCENE = SCENES / "creep_only_table.toml"


def _synthetic(valid, scene_path=SCENE):
    scene = load_scene(scene_path)
    inputs = scene.input_signals()
    t = inputs["time"]
    fields = (["Fx", "Fy", "a0", "contact_half_width", "Mz", "creep_table_error_estimate",
               "wear_depth_per_passage"] + list(JACOBIAN_OUTPUTS) + ["creep_within_validity"])
    result = np.zeros(t.size, dtype=[("time", float)] + [(n, float) for n in fields])
    result["time"] = t
    result["Fx"] = -1e4 * np.sin(t)
    result["a0"] = 6e-3 + 1e-4 * np.cos(t)
    result["contact_half_width"] = result["a0"]
    result["creep_table_error_estimate"] = 2e-7
    result["creep_within_validity"] = valid
    return scene, result, inputs


def _axes_by_label(fig):
    return {ax.get_ylabel().split("\n")[0]: ax for ax in fig.axes if ax.get_ylabel()}


def _footer(fig):
    return " ".join(" ".join(t.get_text() for t in fig.texts).split())


def test_layout_separates_varying_from_constant_and_groups_equal_outputs():
    scene, result, inputs = _synthetic(valid=1.0)
    layout = plot_layout(scene, result, inputs)
    # creep_only_table drives N, xi_x, xi_y (vary) and rail_position (travel); spin and V fixed
    assert layout["inputs"] == ["normal_force", "creepage_longitudinal", "creepage_lateral",
                                "rail_position"]
    assert layout["constant_inputs"] == {"spin": 0.05, "rolling_speed": 30.0}
    assert layout["outputs"] == ["Fx", "Fy", "a0"]          # Fy stays: Fx, Fy always shown
    assert layout["same_as"] == {"contact_half_width": "a0"}
    assert layout["constant_outputs"] == {"creep_table_error_estimate": 2e-7,
                                          "creep_within_validity": True}
    assert layout["invalid"] == []
    assert set(layout["inputs"]) | set(layout["constant_inputs"]) <= set(INPUTS)


def test_outputs_a_scene_does_not_compute_are_not_drawn_but_named():
    scene, result, inputs = _synthetic(valid=1.0)
    # the modified strip theory gives no spin moment and no Jacobian; wear is off
    missing = not_computed(scene)
    assert {"Mz", "wear_depth_per_passage", *JACOBIAN_OUTPUTS} <= set(missing)
    assert "modified_strip" in missing["Mz"] and missing["wear_depth_per_passage"] == "wear is off"
    layout = plot_layout(scene, result, inputs)
    assert {"Mz", "wear_depth_per_passage", *JACOBIAN_OUTPUTS} <= set(layout["not_computed"])
    shown = set(layout["outputs"]) | set(layout["constant_outputs"]) | set(layout["same_as"])
    assert not shown & set(layout["not_computed"])      # neither drawn nor listed as 0
    fig = figure_results(scene, result, inputs)
    labels = _axes_by_label(fig)
    assert "Mz" not in labels and not set(JACOBIAN_OUTPUTS) & set(labels)
    footer = _footer(fig)
    assert "not computed in this scene" in footer
    assert "Mz (creep method 'modified_strip' gives no spin moment" in footer
    assert "d(Fx, Fy, Mz)/d(xi_x, xi_y, phi)" in footer and "Mz = 0" not in footer
    # the exact theory computes them: Mz and the Jacobian are outputs like any other
    exact = load_scene(SCENES / "creep_exact_table.toml")
    assert not {"Mz", *JACOBIAN_OUTPUTS} & set(not_computed(exact))


def test_not_estimated_samples_are_gaps_and_minus_one_throughout_is_not_computed():
    scene, result, inputs = _synthetic(valid=1.0)
    t = result["time"]
    outside = (t > 0.4) & (t < 0.6)
    result["creep_table_error_estimate"][outside] = -1.0
    layout = plot_layout(scene, result, inputs)
    assert "creep_table_error_estimate" in layout["outputs"]
    np.testing.assert_array_equal(layout["gaps"]["creep_table_error_estimate"], outside)
    fig = figure_results(scene, result, inputs)
    ax = _axes_by_label(fig)["creep_table_error_estimate"]
    (line,) = ax.get_lines()
    y = line.get_ydata()
    assert np.all(np.isnan(y[outside])) and np.all(y[~outside] == 2e-7)   # no -1 drawn
    assert any("not estimated" in txt.get_text() for txt in ax.texts)
    result["creep_table_error_estimate"] = -1.0
    layout = plot_layout(scene, result, inputs)
    assert "creep_table_error_estimate" in layout["not_computed"]
    assert "creep_table_error_estimate" not in layout["constant_outputs"]


def test_layout_finds_the_intervals_where_validity_drops(tmp_path):
    scene, result, inputs = _synthetic(valid=1.0)
    t = result["time"]
    result["creep_within_validity"][(t >= 0.2) & (t < 0.3)] = 0.0
    result["creep_within_validity"][t >= 0.9] = 0.0
    layout = plot_layout(scene, result, inputs)
    assert "creep_within_validity" not in layout["constant_outputs"]
    (a0, a1), (b0, b1) = layout["invalid"]
    assert np.isclose(a0, 0.2) and np.isclose(a1, 0.3)
    assert np.isclose(b0, 0.9) and b1 == t[-1]
    path = plot_results(tmp_path / "p.png", scene, result, inputs, units={"Fx": "N"})
    assert path.stat().st_size > 1000


def test_the_validity_note_names_the_cause_that_applies():
    # modified strip theory: the spin pole, and nothing about the linear theory or line contact
    scene, result, inputs = _synthetic(valid=1.0)
    result["creep_within_validity"][10:20] = 0.0
    assert validity_causes(scene, result, inputs) == ["spin"]
    footer = _footer(figure_results(scene, result, inputs))
    assert "spin pole lies inside the contact" in footer and "modified_strip theory" in footer
    assert "linear" not in footer and "line contact" not in footer
    # the linear theory: |T| > mu N where the force exceeds it, the spin pole elsewhere
    lin, res, ins = _synthetic(valid=1.0, scene_path=SCENES / "creep_linear_fixed_ellipse.toml")
    mu_n = lin.friction_coefficient * np.interp(res["time"], ins["time"], ins["normal_force"])
    res["Fx"] = 0.5 * mu_n
    res["Fx"][5:8] = 1.5 * mu_n[5:8]
    res["creep_within_validity"][5:8] = 0.0
    assert validity_causes(lin, res, ins) == ["saturation"]
    res["creep_within_validity"][30:32] = 0.0
    assert validity_causes(lin, res, ins) == ["saturation", "spin"]
    # a line contact: the ignored lateral creepage or spin
    line, res, ins = _synthetic(valid=0.0, scene_path=SCENES / "velocity_friction_step.toml")
    assert validity_causes(line, res, ins) == ["line"]
    assert "line contact" in VALIDITY_NOTES["line"]
    # valid throughout: no note
    assert validity_causes(*_synthetic(valid=1.0)) == []


def test_a_creep_scene_gets_a_force_versus_creepage_panel():
    scene, result, inputs = _synthetic(valid=1.0)
    result["Fy"] = 2e3 * np.cos(3 * result["time"])
    curves = creep_curves(scene, result, inputs)
    assert [(f, c) for f, c, _, _ in curves] == [("Fx", "creepage_longitudinal"),
                                                  ("Fy", "creepage_lateral")]
    fig = figure_results(scene, result, inputs)
    (ax,) = [a for a in fig.axes if a.get_xlabel() == "creepage [1]"]
    drawn = [ln for ln in ax.get_lines() if ln.get_label().startswith("F")]
    assert [ln.get_label() for ln in drawn] == ["Fx / (mu N) against creepage_longitudinal",
                                                "Fy / (mu N) against creepage_lateral"]
    # the drawn data, recomputed from the scene's own signals: mu = 0.3, N = 80 kN + 20 kN sine
    t = result["time"]
    n_load = 80e3 + 20e3 * np.sin(2 * np.pi * t)
    xi_x = -0.008 + 0.016 * (t - t[0]) / (t[-1] - t[0])
    np.testing.assert_allclose(drawn[0].get_xdata(), xi_x, rtol=0, atol=1e-15)
    np.testing.assert_allclose(drawn[0].get_ydata(), result["Fx"] / (0.3 * n_load), rtol=1e-12)
    np.testing.assert_allclose(drawn[1].get_xdata(), 0.002 * np.sin(4 * np.pi * t), atol=1e-15)
    np.testing.assert_allclose(drawn[1].get_ydata(), result["Fy"] / (0.3 * n_load), rtol=1e-12)
    assert "mu = 0.3" in ax.get_ylabel()


def test_a_scene_without_creep_has_no_creep_panel():
    scene, result, inputs = _synthetic(valid=1.0)
    scene.effects.pop("creep")
    assert creep_curves(scene, result, inputs) == []
    fig = figure_results(scene, result, inputs)
    assert not [a for a in fig.axes if a.get_xlabel() == "creepage [1]"]


def test_the_terminal_output_is_wrapped_and_reads_as_information():
    scene, result, inputs = _synthetic(valid=1.0)
    lines = summary_lines(scene, result, width=100)
    assert all(len(line) <= 100 for line in lines)
    text = " ".join(lines)
    assert "Fx = " in text and "Mz = " not in text and "dFx_dxi_x = " not in text
    assert "not computed in this scene" in text and "Mz" in text
    warning = ("creep table creep_modified_strip.nc: normalised creepage z = 1.769 beyond the "
               "grid (last node 1.5); the reader holds F = 1 there, which is exact (full "
               "sliding)")
    got = message_lines([(1, "logStatusWarning", warning), (3, "logStatusError", "bad input")])
    assert got[0] == ("out", "Notes from the FMU (the run went on; these say where a model or "
                             "a table met its limits):")
    assert all(len(line) <= 100 for _, line in got)
    notes = " ".join(line.strip() for s, line in got[1:] if s == "out")
    assert notes == "- " + warning and "warning" not in notes.lower()
    assert [line for s, line in got if s == "err"] == ["FMU error: bad input"]


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    import matplotlib.pyplot as plt

    plt.close("all")


def test_the_summary_keeps_each_name_with_its_value():
    scene, result, inputs = _synthetic(valid=1.0, scene_path=SCENES / "creep_exact_table.toml")
    result["Fx"][-1] = -23456.6
    lines = summary_lines(scene, result, width=60)
    assert all(len(line) <= 60 for line in lines)
    items = " ".join(line.strip() for line in lines[1:]).split(", ")
    assert "Fx = -23456.6" in items and "dFx_dxi_x = 0" in items     # the exact theory's
    assert not any(line.rstrip().endswith("=") or line.lstrip().startswith("=")
                   for line in lines)


def test_the_default_scene_reads_as_information(built_fmu, tmp_path):
    """README's command 1 (the default scene) through the FMU: every line it prints is at most
    100 characters; the FMU's expected warning (creepage beyond the table's last node, held
    exactly) is a note, not a warning; the outputs the scene does not compute are named as
    such, not printed as values."""
    import os
    import subprocess
    import sys

    env = dict(os.environ, PYTHONPATH=os.pathsep.join(
        [str(ROOT / "fmu_src"), str(ROOT), os.environ.get("PYTHONPATH", "")]))
    proc = subprocess.run([sys.executable, "-m", "railcontact.run", str(SCENE), "--out",
                           str(tmp_path), "--fmu", str(built_fmu)], capture_output=True,
                          text=True, cwd=ROOT, env=env, timeout=600)
    assert proc.returncode == 0, proc.stderr
    assert proc.stderr == ""
    lines = proc.stdout.splitlines()
    assert lines[-2:] == [f"wrote {tmp_path / 'creep_only_table.csv'}",
                          f"  and {tmp_path / 'creep_only_table.png'}"]
    assert max(len(line) for line in lines[:-2]) <= 100     # (the paths are the user's)
    text = " ".join(line.strip() for line in lines)
    assert "Notes from the FMU (the run went on" in text and "warning" not in text.lower()
    assert "normalised creepage z = " in text and "which is exact (full sliding)" in text
    assert "not computed in this scene" in text and "Mz = " not in text
    assert "Fx = " in text and (tmp_path / "creep_only_table.png").stat().st_size > 1000
