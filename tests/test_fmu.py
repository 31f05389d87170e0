"""WheelRailContact.fmu through real importers: fmpy (in process) and libcosimpy (subprocess).

The FMU is built once per session into a temporary directory (``build_fmu.py --dest``). Each
bundled scene is simulated with :func:`fmpy.simulate_fmu` and compared with results computed by
calling ``railcontact`` directly (Hertz per load with :func:`railcontact.hertz.hertz_3d`, creep
with :func:`railcontact.creep3d.creep_solution_3d`), both with :func:`fmpy.util.validate_result`
and point by point.
"""

import glob
import json
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

fmpy = pytest.importorskip("fmpy")
from fmpy import read_model_description, extract  # noqa: E402
from fmpy.fmi1 import FMICallException  # noqa: E402
from fmpy.fmi2 import FMU2Slave  # noqa: E402
from fmpy.util import validate_result  # noqa: E402
from fmpy.validation import validate_fmu  # noqa: E402

from railcontact.carter import carter_creep_force, carter_stick_ratio  # noqa: E402
from railcontact.corrugation import corrugated_contact  # noqa: E402
from railcontact.creep3d import creep_solution_3d  # noqa: E402
from railcontact.evolution import evolve_harmonics, wear_number  # noqa: E402
from railcontact.friction import SmoothFriction  # noqa: E402
from railcontact.friction import (normalised_inputs,  # noqa: E402
                                  solve_velocity_friction_normalised,
                                  step_law_creep_force_normalised)
from railcontact.hertz import hertz_2d, hertz_3d  # noqa: E402
from railcontact.nonsteady import relaxation_length, relaxation_step  # noqa: E402
from railcontact.wear import corrugated_wear_depth, mean_wear, wear_coefficients  # noqa: E402
from railcontact import roughness as rough_mod  # noqa: E402
from railcontact.scene import INPUTS, load_scene  # noqa: E402
from railcontact.exact_table import ExactCreepTable  # noqa: E402
from railcontact.strip_table import CreepTable  # noqa: E402
from railcontact.tables import Table, tables_directory  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
SCENES = sorted(glob.glob(str(ROOT / "examples" / "scenes" / "*.toml")))
MAIN_SCENE = str(ROOT / "examples" / "scenes" / "creep_only_analytic.toml")
CORRUGATION_SCENE = str(ROOT / "examples" / "scenes" / "corrugation_wear.toml")
ROUGHNESS_SCENE = str(ROOT / "examples" / "scenes" / "roughness.toml")
OUTPUTS = ["Fx", "Fy", "a0", "b0", "p0", "stick_area_fraction", "stick_width_ratio", "r_a0",
           "Mz"]


@pytest.fixture(scope="session")
def fmu_path(built_fmu):
    """The FMU built by ``build_fmu.py`` for the current sources (conftest.py)."""
    return built_fmu


def _collect():
    messages = []

    def logger(_env, _instance, status, category, message):
        messages.append((int(status), message.decode(errors="replace")))
    return messages, logger


def simulate(fmu_path, scene_path, **kwargs):
    scene = load_scene(scene_path)
    messages, logger = _collect()
    sim = scene.simulation
    start_values = {"scene_file": str(scene_path)}
    start_values.update(kwargs.pop("start_values", {}))
    try:
        result = fmpy.simulate_fmu(str(fmu_path), start_time=sim["start_time"],
                                   stop_time=sim["stop_time"], output_interval=sim["step_size"],
                                   input=kwargs.pop("input", scene.input_signals()),
                                   start_values=start_values, debug_logging=True,
                                   logger=logger, **kwargs)
    except FMICallException as exc:
        exc.add_note(f"FMU log: {messages}")
        raise
    return scene, result, messages


def reference_line(scene, held):
    """Line contact (Carter, corrugation, wear, evolution) by calling railcontact directly."""
    geo = scene.geometry
    width, radius = geo["contact_width"], geo["radius"]
    e_mod, nu, mu = scene.youngs_modulus, scene.poisson_ratio, scene.friction_coefficient
    corr = scene.effects.get("corrugation")
    wear = scene.effects.get("wear")
    za = list(corr["amplitudes_cos"]) if corr else None
    zb = list(corr["amplitudes_sin"]) if corr else None
    section = None
    rough_surface = "roughness" in scene.effects
    rows = []
    relaxed = (reference_relaxed_line(scene, held)[0] if "nonsteady" in scene.effects
               else held["creepage_longitudinal"])
    for row, xi in zip(held, relaxed):
        n_line = row["normal_force"] / width
        x = row["rail_position"]
        a0, p0 = (float(v) for v in hertz_2d(n_line, radius, e_mod, nu))
        fx = float(carter_creep_force(xi, n_line, radius, e_mod, nu, mu)) * width
        r = float(carter_stick_ratio(xi, n_line, radius, e_mod, nu, mu))
        a, shift, depth, amp, growth = a0, 0.0, 0.0, 0.0, 0.0
        vf = scene.effects.get("velocity_friction")
        if vf and n_line > 0 and vf["law"] == "smooth":
            # table or analytic source: the reference is the Sec. 5.3 iteration itself
            norm = normalised_inputs(xi, n_line, radius, e_mod, nu, mu,
                                     vf["kinetic_friction_coefficient"], vf["kappa"])
            sol = solve_velocity_friction_normalised(
                float(norm["creepage_ratio"]), float(norm["friction_ratio"]),
                float(norm["kappa_normalised"]), degree=vf["series_degree"],
                tol=vf["tolerance"])
            fx = float(sol.force_ratio) * float(norm["force_scale"]) * width
            r = float(sol.stick_ratio)
        elif vf and n_line > 0:
            assert vf["law"] == "step"
            norm = normalised_inputs(xi, n_line, radius, e_mod, nu, mu,
                                     vf["kinetic_friction_coefficient"])
            fx = float(step_law_creep_force_normalised(norm["creepage_ratio"],
                                                       norm["friction_ratio"]))
            fx *= float(norm["force_scale"]) * width
            r = float(carter_stick_ratio(xi, n_line, radius, e_mod, nu,
                                         vf["kinetic_friction_coefficient"]))
        if wear and not corr:
            depth = float(mean_wear(wear["wear_coefficient"], mu, n_line, radius, a0, r))
        if corr:
            args = (x, n_line, radius, e_mod, nu, mu, xi, za, zb, corr["wavelengths"])
            res = corrugated_contact(*args, method=corr["method"])
            a, shift = float(res.half_width), float(res.patch_shift)
            fx = -np.sign(xi) * float(res.tangential_force) * width
            depth = (float(corrugated_wear_depth(*args, wear["wear_coefficient"],
                                                 wear["wear_model"])) if wear else 0.0)
            amp = float(np.hypot(za[0], zb[0]))
        if wear and corr:
            number = float(wear_number(wear["wear_coefficient"], mu, n_line, a0))
            w = number * wear_coefficients(a0 / np.asarray(corr["wavelengths"]), r,
                                           wear["wear_model"])
            growth = abs(1.0 - w[0]) - 1.0
            if wear["evolve"]:
                sec = np.floor(x / wear["section_length"])
                if section is None:
                    section = sec
                elif sec > section:
                    za_n, zb_n = evolve_harmonics(za, zb, w.real, w.imag, [sec - section])
                    za, zb, section = list(za_n[0]), list(zb_n[0]), sec
                    amp = float(np.hypot(za[0], zb[0]))
        rough = _reference_roughness(scene, x, n_line, xi) if rough_surface else None
        if rough is not None:
            fx, r, a, shift = rough[:4]
        rows.append((fx, 0.0, a0, width / 2, p0, r, 1.0 if r > 0 else 0.0, r, 0.0, a, shift,
                     depth, amp, growth) + (rough[4:] if rough else (0.0,) * 4))
    return np.array(rows)


def _reference_roughness_surface(scene):
    """The rail roughness of a scene, built directly (harmonics or the profile's spline)."""
    opts = scene.effects.get("roughness")
    if not opts:
        return None
    if opts["profile_file"]:
        return rough_mod.ProfileRoughness(opts["profile_positions"], opts["profile_heights"],
                                          opts["profile_extension"])
    return rough_mod.HarmonicRoughness(opts["wavelengths"], opts["amplitudes_cos"],
                                       opts["amplitudes_sin"])


def _reference_roughness(scene, x, n_line, xi):
    """(Fx, r, a, patch shift, curvature, skewness, flatness, critical creepage) on a rough
    rail: local gap + Table 6.1 + (6.38)-(6.40), called one by one."""
    geo = scene.geometry
    e_mod, nu, mu = scene.youngs_modulus, scene.poisson_ratio, scene.friction_coefficient
    gap = rough_mod.local_gap(_reference_roughness_surface(scene), x, geo["radius"])
    lam = (float(gap.curvature), float(gap.skewness), float(gap.flatness))
    if n_line <= 0:
        return (0.0, 1.0, 0.0, float(gap.contact_point_shift)) + lam + (0.0,)
    normal = rough_mod.asperity_normal_contact(n_line, *lam, e_mod, nu)
    tang = rough_mod.asperity_tangential_contact(normal, mu, creepage=xi)
    return (tang.tangential_force * geo["contact_width"], tang.stick_ratio, normal.half_width,
            float(gap.contact_point_shift) + normal.shift) + lam + (
        float(rough_mod.asperity_critical_creepage(normal, mu)),)
def reference_relaxed_line(scene, held):
    """Relaxed creepage and relaxation length of the non-steady correction, line contact.

    :func:`railcontact.nonsteady.relaxation_step` (exact exponential over the rolled distance
    V h with the inputs held, sigma by the predictor-corrector) with sigma from the public
    vectorised functions: Carter's stick ratio (2.51) and ``relaxation_length``. Row 0: the
    steady state (initialisation); N = 0: xi_e = 0.
    """
    geo, opts = scene.geometry, scene.effects["nonsteady"]
    width, radius = geo["contact_width"], geo["radius"]
    e_mod, nu, mu = scene.youngs_modulus, scene.poisson_ratio, scene.friction_coefficient
    h = scene.simulation["step_size"]

    def sigma(xi, n_line, a0):
        r = carter_stick_ratio(xi, n_line, radius, e_mod, nu, mu)
        return relaxation_length(a0, r, poisson_ratio=nu, model=opts["model"],
                                 pseudo_width_ratio=opts["pseudo_width_ratio"])

    xi_e, lengths, state = [], [], None
    for k, row in enumerate(held):
        n_line, xi = row["normal_force"] / width, row["creepage_longitudinal"]
        a0 = float(hertz_2d(n_line, radius, e_mod, nu).a0)
        if n_line <= 0:
            state = 0.0
        elif k == 0 or state is None:
            state = xi
        else:
            state = relaxation_step((state,), (xi,), row["rolling_speed"] * h,
                                    lambda s: float(sigma(s[0], n_line, a0)))[0]
        xi_e.append(state)
        lengths.append(float(sigma(state, n_line, a0)) if n_line > 0 else 0.0)
    return np.array(xi_e), np.array(lengths)


def _with_fields(out, columns):
    """``out`` (structured array) with the extra float fields ``columns`` (name -> values)."""
    new = np.zeros(out.shape, dtype=out.dtype.descr + [(k, float) for k in columns])
    for name in out.dtype.names:
        new[name] = out[name]
    for name, values in columns.items():
        new[name] = values
    return new


LINE_OUTPUTS = OUTPUTS + ["contact_half_width", "patch_shift", "wear_depth_per_passage",
                          "corrugation_amplitude", "corrugation_growth_rate",
                          "gap_curvature", "gap_skewness", "gap_flatness", "critical_creepage"]


def reference_result(scene, inputs=None, source=None):
    """Outputs computed by calling railcontact directly, on the FMU's output grid.

    Co-simulation sample and hold: the row at t_k (k >= 1) is the solution for the inputs at
    t_(k-1); the row at t_0 the solution for the inputs at t_0 (after initialisation).
    """
    inputs = scene.input_signals() if inputs is None else inputs
    held = np.concatenate((inputs[:1], inputs[:-1]))
    if scene.geometry["kind"] == "line":
        cols = reference_line(scene, held)
        out = np.zeros(len(inputs), dtype=[("time", float)] + [(k, float) for k in LINE_OUTPUTS])
        out["time"] = inputs["time"]
        for i, k in enumerate(LINE_OUTPUTS):
            out[k] = cols[:, i]
        if "nonsteady" in scene.effects:
            xi_e, lengths = reference_relaxed_line(scene, held)
            out = _with_fields(out, {"relaxed_creepage_longitudinal": xi_e,
                                     "relaxation_length": lengths,
                                     "relaxed_creepage_lateral": held["creepage_lateral"],
                                     "relaxed_spin": held["spin"]})
        return out
    n_load = held["normal_force"]
    geo = scene.geometry
    if geo["kind"] == "curvatures":
        a0, b0, p0 = hertz_3d(n_load, geo["curvature_longitudinal"], geo["curvature_lateral"],
                              scene.youngs_modulus, scene.poisson_ratio)
    else:
        a0 = np.full(n_load.shape, geo["semi_axis_longitudinal"])
        b0 = np.full(n_load.shape, geo["semi_axis_lateral"])
        p0 = 1.5 * n_load / (np.pi * a0 * b0)
    opts = scene.effects["creep"]
    spin = held["spin"] if opts["spin"] else np.zeros(n_load.shape)
    args = (held["creepage_longitudinal"], held["creepage_lateral"], spin, n_load, a0, b0,
            scene.youngs_modulus, scene.poisson_ratio, scene.friction_coefficient)
    contact = n_load > 0
    mz = np.zeros(n_load.shape)
    if opts.get("friction_law") == "smooth" and source != "analytic":
        # falling friction: the public fast path (its array path; the FMU its scalar one)
        law = SmoothFriction(scene.friction_coefficient, opts["kinetic_friction_coefficient"],
                             opts["kappa"])
        sol = creep_solution_3d(*args[:8], law, method="exact_table")
        tx, ty, mz, stick, z = (sol.tx, sol.ty, sol.spin_moment, sol.stick_area_fraction,
                                sol.normalised_creepage)
        width = np.sqrt(1.0 - np.minimum(z, 1.0) ** 2)
    elif opts["method"] == "exact" and source != "analytic":
        table = ExactCreepTable.from_file(ROOT / "tables" / f"{opts['table']}.nc")
        sol = table.creep_solution_3d(*args, sensitivities=False)
        tx, ty, mz, stick, z = (sol.tx, sol.ty, sol.spin_moment, sol.stick_area_fraction,
                                sol.normalised_creepage)
        width = np.sqrt(1.0 - np.minimum(z, 1.0) ** 2)
    elif source == "table" or (source is None and opts["source"] == "table"):
        table = CreepTable.from_file(ROOT / "tables" / f"{opts['table']}.nc")
        tx, ty, stick, z = table.creep_solution_3d(*args)
        width = np.sqrt(1.0 - np.minimum(z, 1.0) ** 2)
    else:
        sol = creep_solution_3d(*args, "modified_strip" if opts["method"] == "exact"
                                else opts["method"])
        tx, ty, stick, width, z = (sol.tx, sol.ty, sol.stick_area_fraction,
                                   sol.stick_width_ratio, sol.normalised_creepage)
    r_a0 = np.ones(n_load.shape) if opts["method"] == "linear" else 1.0 - np.minimum(z, 1.0)
    cols = {"Fx": tx, "Fy": ty, "a0": a0, "b0": b0, "p0": p0,
            "stick_area_fraction": np.where(contact, stick, 1.0),
            "stick_width_ratio": np.where(contact, width, 1.0),
            "r_a0": np.where(contact, r_a0, 1.0), "Mz": np.where(contact, mz, 0.0)}
    out = np.zeros(len(inputs), dtype=[("time", float)] + [(k, float) for k in OUTPUTS])
    out["time"] = inputs["time"]
    for k in OUTPUTS:
        out[k] = cols[k]
    return out


def _table_source_tolerance(scene, reference):
    """Output name -> absolute tolerance for the outputs a table source of corrugation, wear or
    velocity-dependent friction computes (empty for analytic scenes): twice the table's
    recorded max error (file attributes, railcontact.tables.Table.accuracy) propagated to the
    output, plus rounding. The reference (reference_line) is the theory the table holds."""
    out = {}
    geo = scene.geometry
    if geo["kind"] != "line":
        return out
    width, big_r = geo["contact_width"], geo["radius"]
    e_mod, nu, mu = scene.youngs_modulus, scene.poisson_ratio, scene.friction_coefficient
    n_max = float(scene.input_signals()["normal_force"].max()) / width
    a0_min = float(np.min(reference["a0"][reference["a0"] > 0]))
    corr, wear = scene.effects.get("corrugation"), scene.effects.get("wear")
    vf = scene.effects.get("velocity_friction")
    if vf and vf["source"] == "table":
        acc = Table.from_file(tables_directory() / "velocity_friction.nc").accuracy()
        out["Fx"] = 2 * acc["force_ratio"]["max_abs_error"] * mu * n_max * width + 1e-9
        for name in ("r_a0", "stick_area_fraction"):
            out[name] = 2 * acc["stick_ratio"]["max_abs_error"]
    if (corr and corr["source"] == "table") or (wear and wear["source"] == "table"):
        acc = Table.from_file(tables_directory() / "corrugation_response.nc").accuracy()
        err = {k: v["max_abs_error"] for k, v in acc.items()}
        lam = np.asarray(corr["wavelengths"]) if corr else np.ones(1)
        k = 2 * np.pi / lam
        # amplitudes may grow by evolution: allow 2x the initial ones
        amp = 2 * np.hypot(corr["amplitudes_cos"], corr["amplitudes_sin"]) if corr else 0 * k
        comp = 4 * (1 - nu ** 2) / (np.pi * e_mod)
        if corr and corr["source"] == "table":
            out["contact_half_width"] = 2 * np.sum(k * big_r * amp) * err["half_width_real"]
            out["patch_shift"] = 2 * np.sum(k * big_r * amp) * err["patch_shift_imag"]
            out["Fx"] = (2 * mu / comp * np.sum(amp) * width
                         * np.hypot(err["tangential_force_real"], err["tangential_force_imag"])
                         + 1e-9)
            if wear:
                out["wear_depth_per_passage"] = (
                    2 * wear["wear_coefficient"] * mu ** 2 * n_max / a0_min * np.sum(amp)
                    * np.hypot(err["wear_real"], err["wear_imag"]) + 1e-22)
        if wear and wear["source"] == "table":
            number = wear["wear_coefficient"] * mu ** 2 * n_max / a0_min   # wear number bound
            e_w = np.hypot(err["wear_real"], err["wear_imag"])
            out["corrugation_growth_rate"] = 2 * number * e_w + 1e-15
            if wear["evolve"]:
                # per passage the amplitude changes by at most number x e_w relative
                passages = scene.input_signals()["rail_position"].max() / wear["section_length"]
                out["corrugation_amplitude"] = (2 * (passages + 1) * number * e_w
                                                * float(np.max(amp)) + 1e-18)
                for name, scale in (("contact_half_width", np.sum(k * big_r)),
                                    ("patch_shift", np.sum(k * big_r)),
                                    ("Fx", mu / comp * width)):
                    out[name] = out.get(name, 0.0) + scale * out["corrugation_amplitude"]
    return out


def _ab(out, name):
    return 1e-12 * np.abs(out[name]).max()


def test_fmpy_validate_is_clean(fmu_path):
    assert validate_fmu(str(fmu_path)) == []
    proc = subprocess.run([sys.executable, "-m", "fmpy", "validate",
                           str(fmu_path)], capture_output=True, text=True)
    assert "No problems found" in proc.stdout, proc.stdout + proc.stderr


def test_every_variable_has_description_and_unit(fmu_path):
    md = read_model_description(str(fmu_path))
    for v in md.modelVariables:
        assert v.description, v.name
        if v.type == "Real":
            assert v.unit, v.name
    names = {v.name for v in md.modelVariables}
    assert set(INPUTS) <= names
    assert set(OUTPUTS) <= names
    assert md.coSimulation.canGetAndSetFMUstate and md.coSimulation.canSerializeFMUstate


def test_descriptions_state_unit_and_sign_and_bounds_come_from_the_physics(fmu_path):
    md = read_model_description(str(fmu_path))
    by_name = {v.name: v for v in md.modelVariables}
    for v in md.modelVariables:
        if v.type == "Real":
            assert v.description.endswith(f"[{v.unit}]"), v.name
    # signed quantities say which way is positive (docs/conventions.md)
    for name in ("Fx", "Fy", "creepage_longitudinal", "creepage_lateral"):
        assert "+x" in by_name[name].description or "+y" in by_name[name].description, name
    for name in ("Mz", "spin"):
        assert "+z" in by_name[name].description, name
    assert "opposes" in by_name["Fx"].description and "opposes" in by_name["Fy"].description
    # bounds the physics gives (FMI bounds are inclusive)
    expected = {"poisson_ratio": ("0", "0.5"), "normal_force": ("0", None),
                "rolling_speed": ("0", None), "r_a0": ("0", "1"),
                "stick_area_fraction": ("0", "1"), "friction_coefficient": ("0", None),
                "friction_series_degree": ("8", "2048"), "creep_table_error_estimate": ("-1", None)}
    for name, (lo, hi) in expected.items():
        v = by_name[name]
        assert v.min == lo and v.max == hi, (name, v.min, v.max)
    assert float(by_name["Fx"].nominal) == 1e4 and float(by_name["p0"].nominal) == 1e9


def test_bundled_names_cannot_collide(fmu_path):
    import zipfile
    with zipfile.ZipFile(fmu_path) as zf:
        module = zf.read("resources/slavemodule.txt").decode().strip()
        names = zf.namelist()
    assert module.startswith("wheelrailcontact_") and len(module) > len("wheelrailcontact_")
    assert f"resources/{module}.py" in names
    assert f"resources/{module}_railcontact/__init__.py" in names
    assert not any(n.startswith("resources/railcontact/") for n in names)
    assert "resources/requirements.txt" in names
    # the falling-friction scene's correction table, not Polach's, which no scene takes
    assert f"resources/{module}_railcontact/data/falling_correction.nc" in names
    assert not any(n.endswith("falling_correction_polach.nc") for n in names)


def _needs_missing_table(scene_path):
    opts = load_scene(scene_path).effects.get("creep", {})
    return (opts.get("source") == "table"
            and not (tables_directory() / f"{opts['table']}.nc").exists())


@pytest.mark.parametrize("scene_path", SCENES, ids=lambda s: Path(s).stem)
def test_scene_matches_direct_railcontact(fmu_path, scene_path):
    if _needs_missing_table(scene_path):
        pytest.skip(f"{Path(scene_path).name}: its table is not built (tablegen)")
    scene, result, messages = simulate(fmu_path, scene_path)
    reference = reference_result(scene)
    assert validate_result(result, reference) == 0
    table_atol = _table_source_tolerance(scene, reference)
    for name in reference.dtype.names[1:]:
        if name in table_atol:       # a table source: its recorded accuracy, not rounding
            np.testing.assert_allclose(result[name], reference[name], rtol=0,
                                       atol=table_atol[name], err_msg=name)
            continue
        np.testing.assert_allclose(result[name], reference[name], rtol=1e-12,
                                   atol=1e-12 * np.abs(reference[name]).max(), err_msg=name)
    for name in result.dtype.names:
        assert np.all(np.isfinite(result[name].astype(float))), name
    assert any("effects on: normal, " in m and "creep" in m for _, m in messages)


def test_table_scene_agrees_with_analytic_solver_and_warns_once(fmu_path):
    scene_path = str(ROOT / "examples" / "scenes" / "creep_only_table.toml")
    scene, result, messages = simulate(fmu_path, scene_path)
    analytic = reference_result(scene, source="analytic")
    mu_n = scene.friction_coefficient * scene.input_signals()["normal_force"].max()
    for name in ("Fx", "Fy"):
        err = np.abs(result[name] - analytic[name]).max()
        assert err <= 1e-3 * mu_n, (name, err / mu_n)
    for name in ("stick_area_fraction", "r_a0", "stick_width_ratio"):
        assert np.abs(result[name] - analytic[name]).max() <= 2e-3, name
    warnings = [m for s, m in messages if s == 1]
    assert len(warnings) == 1 and "beyond the grid" in warnings[0], messages


def test_switched_off_creep_is_not_built(fmu_path, tmp_path):
    scene_file = tmp_path / "normal_only.toml"
    scene_file.write_text('[effects.creep]\nenabled = false\n[simulation]\nstop_time = 0.02\n'
                          'step_size = 0.01\n[inputs]\nnormal_force = 1e5\n'
                          'creepage_longitudinal = 0.01\n')
    _, result, messages = simulate(fmu_path, scene_file)
    assert any(m.endswith("effects on: normal") for _, m in messages)
    assert np.all(result["Fx"] == 0.0) and np.all(result["a0"] > 0.0)


@pytest.mark.parametrize("start_values, name", [
    ({"poisson_ratio": 0.6}, "poisson_ratio"),
    ({"youngs_modulus": -1.0}, "youngs_modulus"),
    ({"creep_method": "bogus"}, "creep_method"),
    ({"friction_coefficient": float("nan")}, "friction_coefficient"),
    ({"geometry_kind": "semi_axes", "semi_axis_lateral": 0.0}, "semi_axis_lateral"),
    ({"scene_file": "/nonexistent/scene.toml"}, "scene_file"),
    ({"scene_file": "", "scene_toml": "[effects.creep]\nmethodd = 'she'\n"}, "methodd"),
    ({"scene_file": str(ROOT / "examples" / "scenes" / "velocity_friction_step.toml"),
      "friction_series_degree": 4}, "parameter friction_series_degree"),
    ({"scene_file": str(ROOT / "examples" / "scenes" / "velocity_friction_step.toml"),
      "friction_tolerance": 0.5}, "parameter friction_tolerance"),
    ({"scene_file": str(ROOT / "examples" / "scenes" / "velocity_friction_step.toml"),
      "velocity_friction_source": "table"}, "parameter velocity_friction_source"),
    ({"scene_file": str(ROOT / "examples" / "scenes" / "corrugation_wear.toml"),
      "corrugation_source": "table"}, "parameter corrugation_method"),
    ({"scene_file": str(ROOT / "examples" / "scenes" / "velocity_friction_table.toml"),
      "kinetic_friction_coefficient": 0.9}, "kinetic_friction_coefficient"),
])
def test_bad_parameter_gives_fmi_error_naming_it(fmu_path, start_values, name):
    # fmpy raises on the failed FMI call and surfaces the FMU's log, which names the parameter
    messages, logger = _collect()
    with pytest.raises(FMICallException, match="fmi2ExitInitializationMode"):
        fmpy.simulate_fmu(str(fmu_path), start_values={"scene_file": MAIN_SCENE, **start_values},
                          stop_time=0.01, output_interval=0.01, debug_logging=True,
                          logger=logger)
    errors = [m for s, m in messages if s == 3]
    assert errors and name in errors[0], messages


@pytest.mark.parametrize("name, value", [("creepage_longitudinal", np.nan),
                                         ("creepage_lateral", -np.inf),
                                         ("normal_force", -5.0), ("normal_force", np.nan),
                                         ("spin", np.inf), ("rolling_speed", -1.0),
                                         ("rail_position", np.nan)])
def test_invalid_input_gives_fmi_error_not_nan(fmu_path, name, value):
    scene = load_scene(MAIN_SCENE)
    inputs = scene.input_signals()
    inputs[name][10:] = value
    messages, logger = _collect()
    with pytest.raises(FMICallException, match="fmi2DoStep"):
        fmpy.simulate_fmu(str(fmu_path), stop_time=scene.simulation["stop_time"],
                          output_interval=scene.simulation["step_size"], input=inputs,
                          start_values={"scene_file": MAIN_SCENE}, debug_logging=True,
                          logger=logger)
    errors = [m for s, m in messages if s == 3]
    assert errors and name in errors[0], messages


def _instantiate_logged(fmu_path, scene_path, unzipdir, messages):
    """As :func:`_instantiate`, with a logger that appends (status, message) to ``messages``
    (the callbacks object is returned too: it must outlive the instance)."""
    from ctypes import byref

    from fmpy import calloc, free
    from fmpy.fmi2 import (fmi2CallbackAllocateMemoryTYPE, fmi2CallbackFreeMemoryTYPE,
                           fmi2CallbackFunctions, fmi2CallbackLoggerTYPE)
    from fmpy.logging import addLoggerProxy

    def logger(_env, _instance, status, _category, message):
        messages.append((int(status), message.decode(errors="replace")))

    cb = fmi2CallbackFunctions()
    cb.logger = fmi2CallbackLoggerTYPE(logger)
    cb.allocateMemory = fmi2CallbackAllocateMemoryTYPE(calloc)
    cb.freeMemory = fmi2CallbackFreeMemoryTYPE(free)
    addLoggerProxy(byref(cb))
    md = read_model_description(str(fmu_path))
    fmu = FMU2Slave(guid=md.guid, unzipDirectory=unzipdir,
                    modelIdentifier=md.coSimulation.modelIdentifier, instanceName="logged")
    vr = {v.name: v.valueReference for v in md.modelVariables}
    fmu.instantiate(callbacks=cb, loggingOn=True)
    fmu.setupExperiment(startTime=0.0)
    fmu.setString([vr["scene_file"]], [str(scene_path)])
    fmu.setReal([vr["normal_force"]], [8e4])
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    return fmu, vr, cb


@pytest.mark.parametrize("stem", ["creep_only_table", "creep_exact_table"])
def test_huge_creepage_gives_sliding_force_not_nan(fmu_path, tmp_path, stem):
    """creepage_longitudinal = 1e308 gave Fx = NaN with status OK in both table scenes: it is
    full sliding, |(Fx, Fy)| = mu N."""
    scene_path = ROOT / "examples" / "scenes" / f"{stem}.toml"
    messages = []
    fmu, vr, _cb = _instantiate_logged(fmu_path, scene_path, extract(str(fmu_path),
                                                                     str(tmp_path)), messages)
    try:
        for xi in (1e308, -1e308):
            fmu.setReal([vr["creepage_longitudinal"]], [xi])
            fmu.doStep(0.0, 1e-3)
            fx, fy = fmu.getReal([vr["Fx"], vr["Fy"]])
            mu_n = load_scene(str(scene_path)).friction_coefficient * 8e4
            assert math.hypot(fx, fy) == pytest.approx(mu_n, rel=1e-12)
            assert math.copysign(1.0, fx) == -math.copysign(1.0, xi)
    finally:
        fmu.terminate()
        fmu.freeInstance()


@pytest.mark.parametrize("step_size", [-1e-3, math.nan, math.inf])
def test_bad_step_size_gives_fmi_error_naming_it(fmu_path, tmp_path, step_size):
    """A negative, NaN or infinite communication step returned OK."""
    messages = []
    fmu, vr, _cb = _instantiate_logged(fmu_path, ROOT / "examples" / "scenes"
                                       / "creep_only_table.toml",
                                       extract(str(fmu_path), str(tmp_path)), messages)
    try:
        with pytest.raises(FMICallException, match="fmi2DoStep") as info:
            fmu.doStep(0.0, step_size)
        assert info.value.status >= 3
        errors = [m for s, m in messages if s >= 3]
        assert errors and "step_size must be in [0, inf) [s]" in errors[0], messages
    finally:
        fmu.freeInstance()


def _instantiate(fmu_path, scene_path, unzipdir):
    md = read_model_description(str(fmu_path))
    fmu = FMU2Slave(guid=md.guid, unzipDirectory=unzipdir,
                    modelIdentifier=md.coSimulation.modelIdentifier, instanceName="state")
    vr = {v.name: v.valueReference for v in md.modelVariables}
    fmu.instantiate()
    fmu.setupExperiment(startTime=0.0)
    fmu.setString([vr["scene_file"]], [str(scene_path)])
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    return fmu, vr


def _passages(fmu, vr):
    """Passages the wear effect has counted, read from the serialised FMU state."""
    state = fmu.getFMUState()
    blob = fmu.serializeFMUstate(state)
    fmu.freeFMUState(state)
    return json.loads(bytes(blob).decode())["effects"]["wear"]["passages"]


@pytest.mark.parametrize("scene_path", SCENES, ids=lambda s: Path(s).stem)
def test_state_save_restore_is_bit_identical(fmu_path, tmp_path, scene_path):
    if _needs_missing_table(scene_path):
        pytest.skip(f"{Path(scene_path).name}: its table is not built (tablegen)")
    scene = load_scene(scene_path)
    inputs = scene.input_signals()
    h = scene.simulation["step_size"]
    unzipdir = extract(str(fmu_path), str(tmp_path / "x"))
    fmu, vr = _instantiate(fmu_path, scene_path, unzipdir)
    in_refs = [vr[n] for n in INPUTS]
    out_refs = [vr[n] for n in LINE_OUTPUTS]
    # t1 = step 50 and t2 = step 120, or proportionally less for a short scene (51 points)
    k1, end = min(50, len(inputs) // 2), min(120, len(inputs))

    def run(k0, k1):
        rows = []
        for k in range(k0, k1):
            fmu.setReal(in_refs, [float(inputs[n][k]) for n in INPUTS])
            fmu.doStep(inputs["time"][k], h)
            rows.append(fmu.getReal(out_refs))
        return np.array(rows)

    try:
        run(0, k1)
        at_t1 = fmu.getReal(out_refs)
        state = fmu.getFMUState()
        first = run(k1, end)
        fmu.setFMUState(state)
        assert fmu.getReal(out_refs) == at_t1
        second = run(k1, end)
        blob = fmu.serializeFMUstate(state)
        fmu.freeFMUState(state)
        state2 = fmu.deSerializeFMUstate(blob)
        fmu.setFMUState(state2)
        third = run(k1, end)
        fmu.freeFMUState(state2)
        saved = json.loads(bytes(blob).decode())["effects"]
        force = next(n for n in ("creep", "velocity_friction", "roughness") if n in saved)
        assert saved[force]["calls"] == k1 + 1
        if "wear" in saved:   # the surface evolved between t1 and t2: state is not trivial
            assert saved["wear"]["passages"] < _passages(fmu, vr)
    finally:
        fmu.terminate()
        fmu.freeInstance()
    assert first.tobytes() == second.tobytes() == third.tobytes()
    assert not np.array_equal(first[0], first[-1])


def _run_libcosim_and_fmpy(fmu_path, tmp_path, scene_path):
    """The scene through libcosimpy (in a subprocess: two importers in one process can abort
    at exit) and through fmpy; libcosim's rows start after initialisation."""
    out_csv = tmp_path / "cosim.csv"
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([str(ROOT / "fmu_src"), env.get("PYTHONPATH", "")])
    proc = subprocess.run([sys.executable, str(ROOT / "tests" / "_cosim_runner.py"),
                           str(fmu_path), scene_path, str(out_csv)],
                          capture_output=True, text=True, env=env, timeout=300)
    assert proc.returncode == 0, proc.stderr[-3000:]
    cosim = np.genfromtxt(out_csv, delimiter=",", names=True)
    _, result, _ = simulate(fmu_path, scene_path)
    assert len(cosim) == len(result) - 1
    return cosim, result


@pytest.mark.parametrize("scene_path", SCENES, ids=lambda s: Path(s).stem)
def test_libcosim_agrees_with_fmpy(fmu_path, tmp_path, scene_path):
    pytest.importorskip("libcosimpy")
    if _needs_missing_table(scene_path):
        pytest.skip(f"{Path(scene_path).name}: its table is not built (tablegen)")
    cosim, result = _run_libcosim_and_fmpy(fmu_path, tmp_path, scene_path)
    np.testing.assert_allclose(cosim["time"], result["time"][1:], rtol=0, atol=1e-12)
    # the non-steady correction integrates over the rolled length V h: fmpy passes
    # h = t_(k+1) - t_k (differences of the rounded grid), libcosim h from integer nanoseconds,
    # so the step lengths differ in the last bits (measured: 9e-14 relative in Fx)
    rtol = 1e-12 if "nonsteady" in load_scene(scene_path).effects else 1e-14
    for name in LINE_OUTPUTS:
        np.testing.assert_allclose(cosim[name], result[name][1:], rtol=rtol, atol=0,
                                   err_msg=name)


def _loaded_library_release_address(unzipdir):
    """Address of finalizePythonInterpreter in the FMU library fmpy loaded from ``unzipdir``."""
    import ctypes

    (so,) = glob.glob(os.path.join(unzipdir, "binaries", "linux64", "*.so"))
    library = ctypes.CDLL(so, mode=os.RTLD_NOW | os.RTLD_NOLOAD)   # fails unless loaded
    return ctypes.cast(library.finalizePythonInterpreter, ctypes.c_void_p).value


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="Linux-only workaround")
def test_fmu_registers_its_interpreter_guard_release_with_the_exit_handlers(fmu_path,
                                                                            tmp_path):
    # the PythonFMU 0.7 exit-time use-after-free (docs/fmu_lifecycle.md): the slave registers
    # the library's own finalizePythonInterpreter with __cxa_atexit, once at instantiation and
    # once after the first initialisation, per library copy -- not once per instance
    import build_fmu

    unzipdir = extract(str(fmu_path), str(tmp_path / "fmu"))
    for _ in range(3):   # same extraction directory: the same library copy every time
        result = fmpy.simulate_fmu(unzipdir, stop_time=2e-3, output_interval=1e-3,
                                   start_values={"scene_file": "creep_only_table"})
        assert len(result) == 3
    address = _loaded_library_release_address(unzipdir)
    module = sys.modules[build_fmu.bundle_names(build_fmu.fmu_digest(fmu_path))[0]]
    assert sorted(module._EXIT_RELEASES) == [(address, "initialised"),
                                             (address, "instantiated")]


def test_data_file_read_after_the_first_extraction_is_gone(fmu_path):
    """Kalker's data files are read on first use, which may come in a later instance of
    the same FMU in the same process, after fmpy deleted the extraction the package was first
    imported from: it is read from the package's current directory (the slave points the
    bundled package's __path__ at each new extraction), and from the bundled copy, not from the
    host's railcontact."""
    import build_fmu

    package = build_fmu.bundle_names(build_fmu.fmu_digest(fmu_path))[1]
    simulate(fmu_path, CORRUGATION_SCENE)              # imports the bundle; extraction deleted
    kalker = sys.modules[f"{package}.kalker"]
    for cached in (kalker.kalker_table, kalker._spline, kalker.kalker_coefficients_cached):
        cached.cache_clear()
    scene, result, _ = simulate(fmu_path, MAIN_SCENE)  # first read of the file: now
    reference = reference_result(scene)
    np.testing.assert_allclose(result["Fx"], reference["Fx"], rtol=1e-12,
                               atol=1e-12 * np.abs(reference["Fx"]).max())
    # (the fitted spline's file, data/kalker_spline.npz, and the table's digest: read now)
    assert kalker._spline.cache_info().currsize == 1


def test_interpreter_guard_release_leaves_unknown_layouts_alone(tmp_path):
    # no binaries directory, or a library that is not loaded: nothing registered, no error,
    # and nothing loaded (RTLD_NOLOAD)
    import WheelRailContact as slave   # the slave's source (fmu_src is on the test path)

    before = dict(slave._EXIT_RELEASES)
    slave._release_interpreter_guard_at_exit(str(tmp_path / "resources"), "instantiated")
    binaries = tmp_path / "binaries" / "linux64"
    binaries.mkdir(parents=True)
    (binaries / "WheelRailContact.so").write_bytes(b"not a library")
    slave._release_interpreter_guard_at_exit(str(tmp_path / "resources"), "instantiated")
    slave._release_interpreter_guard_at_exit("", "instantiated")
    assert slave._EXIT_RELEASES == before


_EXIT_CHILD = r"""
import sys
import fmpy
for _ in range(int(sys.argv[2])):
    result = fmpy.simulate_fmu(sys.argv[1], stop_time=2e-3, output_interval=1e-3,
                               start_values={"scene_file": "creep_only_table"})
print("done", len(result), flush=True)
"""


def test_process_that_ran_the_fmu_exits_cleanly(fmu_path):
    # a Python host that loads the FMU several times (each simulate_fmu extracts and loads a
    # new copy of the library) and exits normally: status 0, nothing on stderr from glibc.
    # Before the workaround about 1 process in 30 aborted at exit with 20 loads each, so this
    # guards against a handler that breaks the exit rather than proving the fix
    # (benchmarks/fmu_exit_check.py counts many processes and runs valgrind).
    for _ in range(2):
        proc = subprocess.run([sys.executable, "-c", _EXIT_CHILD, str(fmu_path), "3"],
                              capture_output=True, text=True, timeout=300)
        assert proc.returncode == 0 and "done 3" in proc.stdout, proc.stderr[-2000:]
        assert "corrupted" not in proc.stderr and "free()" not in proc.stderr


def test_run_command_writes_csv_and_plot(fmu_path, tmp_path):
    out = tmp_path / "out"
    proc = subprocess.run([sys.executable, "-m", "railcontact.run", MAIN_SCENE, "--out",
                           str(out), "--fmu", str(fmu_path)], capture_output=True, text=True,
                          cwd=ROOT)
    assert proc.returncode == 0, proc.stderr
    name = load_scene(MAIN_SCENE).name
    data = np.genfromtxt(out / f"{name}.csv", delimiter=",", names=True)
    assert set(INPUTS) <= set(data.dtype.names) and "Fx" in data.dtype.names
    assert (out / f"{name}.png").stat().st_size > 1000


def test_run_plot_labels_take_the_units_of_the_model_description(fmu_path):
    from railcontact.run import output_units

    units = output_units(fmu_path)
    assert units["Fx"] == "N" and units["Mz"] == "N.m" and units["a0"] == "m"
    assert units["relaxed_spin"] == "1/m" and units["gap_flatness"] == "1/m3"
    assert "normal_force" not in units          # inputs are labelled from railcontact.scene


def test_run_command_reports_bad_scene(tmp_path, fmu_path):
    bad = tmp_path / "bad.toml"
    bad.write_text("[material]\npoisson_ratio = 0.7\n")
    proc = subprocess.run([sys.executable, "-m", "railcontact.run", str(bad), "--fmu",
                           str(fmu_path)], capture_output=True, text=True, cwd=ROOT)
    assert proc.returncode == 2
    assert "material.poisson_ratio must be in [0, 0.5)" in proc.stderr


def _long_run(fmu_path, tmp_path, n_steps):
    """Table scene, inputs sweeping the hard regions; returns (RSS samples [MB], bad count)."""
    import math
    import resource
    unzipdir = extract(str(fmu_path), str(tmp_path / "long"))
    scene_path = str(ROOT / "examples" / "scenes" / "creep_only_table.toml")
    fmu, vr = _instantiate(fmu_path, scene_path, unzipdir)
    ins = [vr[n] for n in INPUTS]
    outs = [vr[n] for n in LINE_OUTPUTS]
    cycle = 10007
    k = np.arange(cycle)
    sweep = np.column_stack([
        np.maximum(0.0, 1e5 * np.sin(2 * np.pi * k / cycle)),   # through N = 0 (no contact)
        0.05 * np.sin(2 * np.pi * 3 * k / cycle),               # far past saturation
        0.01 * np.cos(2 * np.pi * 5 * k / cycle),
        5.0 * np.sin(2 * np.pi * 7 * k / cycle),                # spin pole inside the patch
        30.0 + 0.0 * k, 1e-3 * k]).tolist()

    def rss():
        with open("/proc/self/statm") as f:
            return int(f.read().split()[1]) * resource.getpagesize() / 2**20

    samples, bad, t = {}, 0, 0.0
    try:
        for i in range(n_steps):
            fmu.setReal(ins, sweep[i % cycle])
            fmu.doStep(t, 1e-4)
            t += 1e-4
            if i % 997 == 0:
                values = fmu.getReal(outs)
                bad += sum(not math.isfinite(v) for v in values)
                mu_n = 0.3 * sweep[i % cycle][0]
                bad += math.hypot(values[0], values[1]) > mu_n * (1 + 1e-12)
            if (i + 1) % (n_steps // 10) == 0:
                samples[i + 1] = rss()
    finally:
        fmu.terminate()
        fmu.freeInstance()
    return samples, bad


def test_long_run_is_finite_bounded_and_flat_in_memory(fmu_path, tmp_path):
    samples, bad = _long_run(fmu_path, tmp_path, 30000)
    assert bad == 0
    values = list(samples.values())
    assert values[-1] - values[1] < 5.0, samples      # MB, after warm-up


@pytest.mark.slow
def test_long_run_1e6_steps(fmu_path, tmp_path):
    samples, bad = _long_run(fmu_path, tmp_path, 10**6)
    assert bad == 0
    assert samples[10**6] - samples[10**5] < 5.0, samples


def test_creep_table_error_estimate_output_is_the_file_attribute(fmu_path):
    import netCDF4
    scene_path = str(ROOT / "examples" / "scenes" / "creep_only_table.toml")
    _, result, _ = simulate(fmu_path, scene_path, output=["creep_table_error_estimate"])
    with netCDF4.Dataset(tables_directory() / "creep_modified_strip.nc") as nc:
        expected = float(nc.variables["force_ratio"].getncattr("max_abs_error"))
    assert np.all(result["creep_table_error_estimate"] == expected)
    _, result, _ = simulate(fmu_path, MAIN_SCENE, output=["creep_table_error_estimate"])
    assert np.all(result["creep_table_error_estimate"] == -1.0)      # analytic: not estimated


def test_friction_accuracy_knobs_reach_the_fmu(fmu_path):
    from railcontact.effects import ContactPoint, build_pipeline
    from railcontact.scene import parse_scene
    text = ("[geometry]\nkind = 'line'\nradius = 0.46\ncontact_width = 0.02\n"
            "[effects.creep]\nmethod = 'carter'\n[effects.velocity_friction]\nlaw = 'smooth'\n"
            "kinetic_friction_coefficient = 0.15\nkappa = 400.0\n"
            "[simulation]\nstop_time = 0.02\nstep_size = 0.01\n"
            "[inputs]\nnormal_force = 1e5\ncreepage_longitudinal = 6e-4\n")
    params = dict(geometry_kind="line", creep_method="carter", radius=0.46, contact_width=0.02,
                  velocity_friction_enabled=True, velocity_friction_law="smooth",
                  kinetic_friction_coefficient=0.15, friction_kappa=400.0)
    scene = parse_scene(text)
    out = {}
    for degree in (128, 32):
        result = fmpy.simulate_fmu(
            str(fmu_path), start_time=0.0, stop_time=0.02, output_interval=0.01,
            input=scene.input_signals(),
            start_values=dict(params, friction_series_degree=degree, friction_tolerance=1e-9),
            output=["Fx", "friction_iteration_residual"])
        pipe = build_pipeline(parse_scene(text.replace(
            "kappa = 400.0\n", f"kappa = 400.0\nseries_degree = {degree}\ntolerance = 1e-9\n")))
        c = ContactPoint()
        c.normal_force, c.creepage_longitudinal, c.friction_coefficient = 1e5, 6e-4, 0.3
        pipe.step(c)
        np.testing.assert_allclose(result["Fx"], c.Fx, rtol=1e-12)
        assert np.all(result["friction_iteration_residual"] == c.friction_iteration_residual)
        assert np.all((result["friction_iteration_residual"] >= 0)
                      & (result["friction_iteration_residual"] < 1e-9))
        out[degree] = result["Fx"][-1]
    assert out[32] != out[128] and abs(out[32] - out[128]) <= 1e-3 * 0.3 * 1e5


def test_corrugation_series_error_estimate_output(fmu_path):
    from railcontact.corrugation import series_truncation_error
    from railcontact.effects import wear_series_degree
    scene, result, _ = simulate(fmu_path, CORRUGATION_SCENE,
                                output=["corrugation_series_error_estimate", "a0"])
    ka = 2.0 * np.pi * result["a0"] / min(scene.effects["corrugation"]["wavelengths"])
    expected = [float(series_truncation_error(v, wear_series_degree(v))[1]) for v in ka]
    assert np.array_equal(result["corrugation_series_error_estimate"], expected)
    assert np.all((result["corrugation_series_error_estimate"] >= 0.0)
                  & (result["corrugation_series_error_estimate"] < 1e-16))
    _, result, _ = simulate(fmu_path, MAIN_SCENE, output=["corrugation_series_error_estimate"])
    assert np.all(result["corrugation_series_error_estimate"] == -1.0)


def test_friction_table_outputs_and_out_of_grid_warning(fmu_path, tmp_path):
    """velocity_friction_table: friction_table_error_estimate is the file attribute of
    force_ratio, friction_iteration_residual -1 (no iteration), no warning inside the grid; the
    same scene driven past |xi|/xi_sat = 6 logs one warning and reports the iteration's
    residual there (table error -1)."""
    import netCDF4
    scene_path = ROOT / "examples" / "scenes" / "velocity_friction_table.toml"
    out = ["friction_table_error_estimate", "friction_iteration_residual", "Fx"]
    _, result, messages = simulate(fmu_path, str(scene_path), output=out)
    with netCDF4.Dataset(tables_directory() / "velocity_friction.nc") as nc:
        expected = float(nc.variables["force_ratio"].getncattr("max_abs_error"))
    assert np.all(result["friction_table_error_estimate"] == expected)
    assert np.all(result["friction_iteration_residual"] == -1.0)
    assert not [m for s, m in messages if s == 1]
    text = scene_path.read_text().replace("start_value = -0.006, end_value = 0.006",
                                          "start_value = 0.0, end_value = 0.03")
    text = text.replace("step_size = 0.02", "step_size = 0.1")
    wide = tmp_path / "wide.toml"
    wide.write_text(text)
    _, result, messages = simulate(fmu_path, str(wide), output=out)
    warnings = [m for s, m in messages if s == 1]
    assert len(warnings) == 1 and "outside the table" in warnings[0], messages
    outside = result["friction_table_error_estimate"] == -1.0
    assert outside.any() and not outside.all()
    assert np.all((result["friction_iteration_residual"][outside] >= 0)
                  & (result["friction_iteration_residual"][outside] < 1e-9))
    assert np.all(np.isfinite(result["Fx"]))


# --------------------------------------------------------------------------------------------
# non-steady correction (railcontact.effects.NonSteady): state, second importer, outputs
# --------------------------------------------------------------------------------------------
NONSTEADY_SCENE = str(ROOT / "examples" / "scenes" / "nonsteady_creep.toml")


def test_nonsteady_libcosim_agrees_with_fmpy(fmu_path, tmp_path):
    """As test_libcosim_agrees_with_fmpy, to 1e-12 instead of 1e-14: with nonsteady the step
    size enters the result (the rolled distance V h), and fmpy passes h = t_(k+1) - t_k (off
    from 2e-4 by rounding, step by step) where libcosim passes the exact 200000 ns."""
    pytest.importorskip("libcosimpy")
    cosim, result = _run_libcosim_and_fmpy(fmu_path, tmp_path, NONSTEADY_SCENE)
    for name in LINE_OUTPUTS + ["relaxation_length", "relaxed_creepage_longitudinal"]:
        np.testing.assert_allclose(cosim[name], result[name][1:], rtol=1e-12,
                                   atol=1e-12 * np.abs(result[name]).max(), err_msg=name)


def test_nonsteady_outputs_lag_and_inputs_stay_as_set(fmu_path):
    """The force lags the creepage steps by about sigma/V; with nonsteady off it does not; the
    input variables read back are the importer's (not the relaxed) creepages."""
    scene, result, messages = simulate(fmu_path, NONSTEADY_SCENE, output=[
        "Fx", "relaxed_creepage_longitudinal", "relaxation_length", "creepage_longitudinal"])
    assert any("effects on: normal, nonsteady, creep" in m for _, m in messages)
    text = Path(NONSTEADY_SCENE).read_text().replace("[effects.nonsteady]\n",
                                                     "[effects.nonsteady]\nenabled = false\n")
    _, steady, _ = simulate(fmu_path, NONSTEADY_SCENE, output=["Fx", "relaxation_length"],
                            start_values={"scene_file": "", "scene_toml": text})
    held = np.concatenate((scene.input_signals()[:1], scene.input_signals()[:-1]))
    # (fmpy records the input variable after each step: the value it set before it)
    np.testing.assert_array_equal(result["creepage_longitudinal"],
                                  held["creepage_longitudinal"])
    lag = np.abs(result["relaxed_creepage_longitudinal"] - held["creepage_longitudinal"])
    assert lag.max() > 1e-3 and lag[-1] < 1e-12          # lags, then catches up (full slip)
    assert np.abs(result["Fx"] - steady["Fx"]).max() > 0.2 * 0.3 * 1e5
    assert np.all(steady["relaxation_length"] == 0.0)
    sigma0 = result["relaxation_length"][0]                # full stick, xi = 0
    assert 0.015 < sigma0 < 0.03                           # 4.27 a0, a0 = 5.07 mm


@pytest.mark.parametrize("start_values, name", [
    ({"nonsteady_enabled": True, "nonsteady_pseudo_width_ratio": 1.0},
     "parameter nonsteady_pseudo_width_ratio"),
    ({"nonsteady_enabled": True, "nonsteady_model": "hertz"}, "parameter nonsteady_model"),
])
def test_nonsteady_bad_parameter_gives_fmi_error_naming_it(fmu_path, start_values, name):
    messages, logger = _collect()
    with pytest.raises(FMICallException, match="fmi2ExitInitializationMode"):
        fmpy.simulate_fmu(str(fmu_path), start_values={"scene_file": MAIN_SCENE, **start_values},
                          stop_time=0.01, output_interval=0.01, debug_logging=True,
                          logger=logger)
    errors = [m for s, m in messages if s == 3]
    assert errors and name in errors[0], messages


def test_nonsteady_through_fmu_parameters_only(fmu_path):
    """nonsteady_enabled on a 3-D scene given by parameters: the relaxed creepages follow
    the input, the Coulomb bound holds, and the outputs are finite."""
    scene = load_scene(MAIN_SCENE)
    result = fmpy.simulate_fmu(
        str(fmu_path), start_time=0.0, stop_time=0.2, output_interval=1e-3,
        input=scene.input_signals(np.arange(0.0, 0.2 + 1e-9, 1e-3)),
        start_values={"nonsteady_enabled": True, "nonsteady_model": "johnson"},
        output=["Fx", "Fy", "relaxation_length", "relaxed_creepage_longitudinal",
                "relaxed_creepage_lateral", "relaxed_spin", "normal_force"])
    for name in result.dtype.names:
        assert np.all(np.isfinite(result[name])), name
    assert np.all(np.hypot(result["Fx"], result["Fy"])
                  <= 0.3 * result["normal_force"] * (1 + 1e-12))
    # the ramp starts in full sliding (sigma = 0) and leaves it as |xi| falls
    assert result["relaxation_length"][0] == 0.0 and result["relaxation_length"][-1] > 1e-3
    assert np.all(result["relaxation_length"] >= 0.0)
    assert np.any(result["relaxed_spin"] != 0.0)


def test_bundled_roughness_scene_finds_its_profile_inside_the_fmu(fmu_path):
    """scene_file = 'roughness' (the bundled copy): its relative profile_file resolves against
    resources/scenes/ inside the FMU, and the run equals the one from the source tree."""
    import zipfile
    with zipfile.ZipFile(fmu_path) as zf:
        assert "resources/scenes/roughness_profile.csv" in zf.namelist()
    scene, from_source, _ = simulate(fmu_path, ROUGHNESS_SCENE)
    _, bundled, messages = simulate(fmu_path, ROUGHNESS_SCENE,
                                    start_values={"scene_file": "roughness"})
    assert any("scene 'roughness': effects on: normal, roughness (in place of creep)" in m
               for _, m in messages)
    for name in LINE_OUTPUTS:
        assert np.array_equal(bundled[name], from_source[name]), name
    # the rough rail is visible: half-width, force and curvature vary along the rail
    for name in ("contact_half_width", "Fx", "gap_curvature", "patch_shift"):
        values = bundled[name]
        assert values.max() - values.min() > 0.02 * np.abs(values).max(), name


@pytest.mark.parametrize("method", ["fastsim", "polach", "fastrip"])
def test_comparison_methods_through_the_fmu_equal_the_api(fmu_path, method):
    """FASTSIM, Polach and FaStrip chosen by name in a scene (``scene_toml``): the FMU's forces
    are those of :func:`railcontact.creep_force_3d` at the same inputs and Hertz semi-axes."""
    toml = f"[effects.creep]\nmethod = '{method}'\n"
    time = np.linspace(0.0, 0.01, 11)
    names = ["time"] + list(INPUTS)
    signals = np.zeros(time.size, dtype=[(n, float) for n in names])
    signals["time"] = time
    signals["normal_force"] = 1e5
    signals["creepage_longitudinal"] = 2e-3
    signals["creepage_lateral"] = -1e-3
    signals["spin"] = 0.2
    signals["rolling_speed"] = 30.0
    result = fmpy.simulate_fmu(str(fmu_path), stop_time=0.01, output_interval=1e-3,
                               start_values={"scene_toml": toml}, input=signals,
                               output=["Fx", "Fy", "a0", "b0"])
    last = result[-1]
    from railcontact import creep_force_3d
    from railcontact.scene import parse_scene
    scene = parse_scene(toml)
    want = creep_force_3d(2e-3, -1e-3, 0.2, 1e5, last["a0"], last["b0"], scene.youngs_modulus,
                          scene.poisson_ratio, scene.friction_coefficient, method=method)
    assert last["Fx"] == pytest.approx(float(want.tx), rel=1e-12)
    assert last["Fy"] == pytest.approx(float(want.ty), rel=1e-12)
    assert -0.3e5 < last["Fx"] < 0.0 < last["Fy"]


_AOT_CHECK = r"""
import json, sys
from fmpy import extract
import numpy as np

unzip = extract(sys.argv[1], sys.argv[2])
resources = f"{unzip}/resources"
sys.path.insert(0, resources)
module_name = open(f"{resources}/slavemodule.txt").read().strip()
package = module_name + "_railcontact"
import importlib
module = importlib.import_module(module_name)
out = {}
for scene in ("velocity_friction_table", "creep_exact_table", "corrugation_wear_table"):
    slave = module.WheelRailContact(instance_name="aot", resources=resources)
    slave.scene_file = scene
    slave.enter_initialization_mode()
    slave.exit_initialization_mode()
    setters = {v.name: v.setter for v in slave.vars.values() if v.setter is not None}
    getters = {v.name: v.getter for v in slave.vars.values() if v.getter is not None}
    for name, value in (("normal_force", 8e4), ("creepage_longitudinal", 1e-3),
                        ("creepage_lateral", 4e-4), ("spin", 0.3), ("rolling_speed", 30.0),
                        ("rail_position", 0.37)):
        setters[name](value)
    slave.do_step(0.0, 1e-3)
    out[scene] = [getters["Fx"](), getters["Fy"]()]
    if scene == "creep_exact_table":
        # (the corrugation scene imports numba: its contact module's kernels have no
        # ahead-of-time copy; its table step does)
        out["numba_imported"] = "numba" in sys.modules
compiled = importlib.import_module(f"{package}._compiled")
out["aot"] = compiled.aot_module() is not None
# the same kernels just in time (numba), on the same inputs: both scalar kernels, the one of
# any contact (every contact new) and the one on a contact's buffer (made at once)
exact_table = importlib.import_module(f"{package}.exact_table")


def values_of(table, rng):
    out = []
    for _ in range(200):
        args = (float(rng.normal(0, 2e-3)), float(rng.normal(0, 2e-3)), float(rng.normal(0, 1.0)),
                1e5, float(rng.uniform(3e-3, 8e-3)), 5e-3, 2.1e11, 0.28, 0.3)
        values = table.step_values(*args)
        if values is not None:      # and the public call's forces-only kernel
            out.append(values + list(table.creep_force_3d(*args)))
    return out


for name, after in (("exact", 10**9), ("exact_buffer", 1)):
    exact_table.SLAB_AFTER_POINTS = after
    compiled._AOT[:] = []                       # the ahead-of-time copy
    pairs = values_of(exact_table.ExactCreepTable.from_file(), np.random.default_rng(5))
    compiled._AOT[:] = [None]                   # numba's kernels
    other = values_of(exact_table.ExactCreepTable.from_file(), np.random.default_rng(5))
    diff = 0.0
    for values, jit in zip(pairs, other):
        scale = max(abs(v) for v in jit)
        diff = max(diff, max(abs(a - b) for a, b in zip(values, jit)) / scale)
    out[name + "_max_relative_difference"] = diff
# beyond the spin axis the ahead-of-time forces kernel raises, and the table's array path
# names the input (no solver attached here)
compiled._AOT[:] = []
exact_table.SLAB_AFTER_POINTS = 1
beyond = exact_table.ExactCreepTable.from_file()
beyond.creep_force_3d(1e-4, 0.0, 0.0, 1e5, 5e-3, 5e-3, 2.1e11, 0.28, 0.3)   # its buffer
out["force_kernel_aot"] = beyond._force_kernel is compiled.aot_module().creep_contact_force
try:
    beyond.creep_force_3d(1e-4, 0.0, 40.0, 1e5, 5e-3, 5e-3, 2.1e11, 0.28, 0.3)
except ValueError as exc:
    out["beyond_message"] = str(exc)
# the corrugation response table's step kernel, both copies on the same random surfaces
response = importlib.import_module(f"{package}.effects.response_table")
compiled._AOT[:] = []                           # the ahead-of-time copy again
aot_table = response.ResponseTable(None, "corrugation", None)
compiled._AOT[:] = [None]
jit_table = response.ResponseTable(None, "corrugation", None)
rng = np.random.default_rng(11)
diff = 0.0
for _ in range(200):
    lam = list(rng.uniform(0.02, 0.3, 3))
    harm = aot_table.harmonics(lam, list(rng.normal(0, 2e-6, 3)), list(rng.normal(0, 2e-6, 3)),
                               0.46)
    args = (float(rng.uniform(4e-3, 7e-3)), float(rng.uniform(0, 10)), float(rng.uniform(0, 1)))
    got, want = np.zeros(4), np.zeros(4)
    assert aot_table.superpose(harm.copy(), *args, got)
    assert jit_table.superpose(harm.copy(), *args, want)
    diff = max(diff, float(np.max(np.abs(got - want) / np.abs(want))))
out["response_max_relative_difference"] = diff
out["response_aot_used"] = aot_table._superpose is not jit_table._superpose
print("AOT", json.dumps(out))
"""


def test_table_scenes_run_without_numba_on_the_ahead_of_time_kernels(fmu_path, tmp_path):
    # The build compiles the table kernels ahead of time from their numba source
    # (railcontact._compiled): a table scene then imports no numba, and the compiled copy
    # gives the numba kernel's values (the exact table's two scalar kernels with the
    # Jacobian, 200 random contacts each, relative to the largest entry, and the public call's
    # forces-only kernel on a contact's buffer; the corrugation response table's step,
    # 200 random three-harmonic surfaces, relative to each sum).
    proc = subprocess.run([sys.executable, "-c", _AOT_CHECK, str(fmu_path),
                           str(tmp_path / "x")], capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, proc.stderr[-3000:]
    out = json.loads(proc.stdout.split("AOT ", 1)[1])
    if not out["aot"]:
        pytest.skip("the FMU was built without ahead-of-time kernels (no C compiler)")
    assert out["numba_imported"] is False
    assert all(np.isfinite(out[s]).all() and out[s][0] < 0 for s in
               ("velocity_friction_table", "creep_exact_table", "corrugation_wear_table"))
    # (the ahead-of-time copy targets a generic CPU, numba's this one: the last bits may differ)
    assert out["exact_max_relative_difference"] < 1e-12
    assert out["exact_buffer_max_relative_difference"] < 1e-12
    assert out["force_kernel_aot"]
    assert "spin must give a spin coordinate |tau| <= 20" in out["beyond_message"]
    assert out["response_aot_used"]
    assert out["response_max_relative_difference"] < 1e-12
