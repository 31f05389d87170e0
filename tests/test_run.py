"""The run plot's layout (railcontact.run.plot_layout, plot_results) on synthetic results."""

from pathlib import Path

import numpy as np

from railcontact.run import VALIDITY_NOTE, plot_layout, plot_results
from railcontact.scene import INPUTS, load_scene

ROOT = Path(__file__).resolve().parents[1]
SCENE = ROOT / "examples" / "scenes" / "creep_only_table.toml"


def _synthetic(valid):
    scene = load_scene(SCENE)
    inputs = scene.input_signals()
    t = inputs["time"]
    fields = ["Fx", "Fy", "a0", "contact_half_width", "Mz", "creep_within_validity"]
    result = np.zeros(t.size, dtype=[("time", float)] + [(n, float) for n in fields])
    result["time"] = t
    result["Fx"] = -1e4 * np.sin(t)
    result["a0"] = 6e-3 + 1e-4 * np.cos(t)
    result["contact_half_width"] = result["a0"]
    result["creep_within_validity"] = valid
    return scene, result, inputs


def test_layout_separates_varying_from_constant_and_groups_equal_outputs():
    scene, result, inputs = _synthetic(valid=1.0)
    layout = plot_layout(scene, result, inputs)
    # creep_only_table drives N, xi_x, xi_y (vary) and rail_position (travel); spin and V fixed
    assert layout["inputs"] == ["normal_force", "creepage_longitudinal", "creepage_lateral",
                                "rail_position"]
    assert layout["constant_inputs"] == {"spin": 0.05, "rolling_speed": 30.0}
    assert layout["outputs"] == ["Fx", "Fy", "a0"]          # Fy stays: Fx, Fy always shown
    assert layout["same_as"] == {"contact_half_width": "a0"}
    assert layout["constant_outputs"] == {"Mz": 0.0, "creep_within_validity": True}
    assert layout["invalid"] == []
    assert set(layout["inputs"]) | set(layout["constant_inputs"]) <= set(INPUTS)


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
    assert "spin coefficient > 1" in VALIDITY_NOTE
    path = plot_results(tmp_path / "p.png", scene, result, inputs, units={"Fx": "N"})
    assert path.stat().st_size > 1000
