"""railcontact.run: the plot's layout (inputs apart from outputs, constants listed, the validity
flag shown where it drops), without an FMU: synthetic results of a creep scene."""

import numpy as np

from railcontact.run import VALIDITY_NOTE, plot_layout, plot_results
from railcontact.scene import INPUTS, parse_scene


def _data():
    t = np.linspace(0.0, 1.0, 101)
    inputs = np.zeros(t.size, dtype=[("time", float)] + [(n, float) for n in INPUTS])
    inputs["time"] = t
    inputs["normal_force"] = 80e3 + 20e3 * np.sin(2 * np.pi * t)
    inputs["creepage_longitudinal"] = -8e-3 + 16e-3 * t
    inputs["spin"] = 0.05
    inputs["rolling_speed"] = 30.0
    names = ["Fx", "Fy", "a0", "p0", "wear_depth_per_passage", "friction_iteration_residual",
             "creep_table_error_estimate", "creep_within_validity"]
    result = np.zeros(t.size, dtype=[("time", float)] + [(n, float) for n in names])
    result["time"] = t
    result["Fx"] = -2e4 * np.tanh(inputs["creepage_longitudinal"] / 2e-3)
    result["a0"] = 6e-3 + 1e-3 * np.sin(2 * np.pi * t)
    result["p0"] = 1.1e9 + 1e8 * np.sin(2 * np.pi * t)
    result["friction_iteration_residual"] = -1.0          # "not in use": left out
    result["creep_table_error_estimate"] = 2e-7           # constant: listed
    result["creep_within_validity"] = np.where(np.abs(t - 0.5) < 0.021, 0.0, 1.0)
    return inputs, result


def test_layout_separates_inputs_outputs_and_lists_constants():
    inputs, result = _data()
    layout = plot_layout(parse_scene(""), result, inputs, units={"Fx": "N", "a0": "m"})
    in_titles = [p[0] for p in layout["inputs"]]
    out_titles = [p[0] for p in layout["outputs"]]
    assert in_titles == ["normal force", "creepages"]          # varying inputs only
    assert ("creepage_longitudinal", 1.0) in layout["inputs"][1][1]
    assert out_titles == ["forces on the wheel", "contact size", "peak pressure"]
    assert layout["outputs"][0][1] == [("Fx", 1e-3)]           # Fy is 0 throughout: not drawn
    assert "spin = 0.05 1/m" in layout["constants"]
    assert "rolling_speed = 30 m/s" in layout["constants"]
    assert "creep_table_error_estimate = 2e-07" in layout["constants"]
    assert not any(c.startswith(("Fy", "wear_depth", "friction_iteration"))
                   for c in layout["constants"])
    (t0, t1), = layout["invalid_spans"]
    assert t0 == 0.48 and t1 == 0.53


def test_plot_writes_png_with_the_validity_note(tmp_path):
    inputs, result = _data()
    path = plot_results(tmp_path / "run.png", parse_scene(""), result, inputs)
    assert path.stat().st_size > 10_000
    assert "spin coefficient > 1" in VALIDITY_NOTE
