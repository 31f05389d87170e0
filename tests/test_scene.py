"""Scene files: parsing, defaults, validation errors naming the key, input signals."""

import glob
from pathlib import Path

import numpy as np
import pytest

from railcontact.fmu_parameters import (FMU_PARAMETERS, parameters_to_scene_dict,
                                        scene_to_parameters)
from railcontact.scene import (DEFAULT_SCENE, INPUTS, SceneError, load_scene, parse_scene,
                               scene_from_dict)

ROOT = Path(__file__).resolve().parents[1]
SCENES = sorted(glob.glob(str(ROOT / "examples" / "scenes" / "*.toml")))


@pytest.mark.parametrize("path", SCENES, ids=lambda p: Path(p).stem)
def test_bundled_scenes_load(path):
    scene = load_scene(path)
    assert scene.name == Path(path).stem
    assert scene.description
    signals = scene.input_signals()
    assert signals.dtype.names == ("time",) + tuple(INPUTS)
    assert len(signals) == len(scene.time_grid())
    for name in INPUTS:
        assert np.all(np.isfinite(signals[name]))
    assert np.all(signals["normal_force"] >= 0) and np.all(signals["rolling_speed"] >= 0)


def test_defaults_fill_missing_sections():
    scene = parse_scene("")
    assert scene.youngs_modulus == DEFAULT_SCENE["material"]["youngs_modulus"]
    # the default creep method: Kalker's exact theory from its table
    assert scene.effects == {"creep": {"enabled": True, "method": "exact",
                                       "source": "table", "spin": True,
                                       "table": "creep_exact"}}
    assert scene.geometry["kind"] == "curvatures"
    assert scene.inputs == {}


def test_effect_switched_off_is_absent():
    scene = parse_scene("[effects.creep]\nenabled = false\n")
    assert scene.effects == {} and not scene.enabled("creep")


@pytest.mark.parametrize("text, match", [
    ("[material]\npoisson_ratio = 0.6\n", r"material.poisson_ratio must be in \[0, 0.5\) "
                                          r"\[-\]; got 0.6"),
    ("[material]\nyoungs_modulus = 0\n", "material.youngs_modulus"),
    ("[material]\nyoungs_modulus = 'steel'\n", "material.youngs_modulus must be a number"),
    ("[material]\nyoung = 1\n", "material: unknown key 'young'"),
    ("[materials]\n", "unknown key 'materials'"),
    ("[geometry]\nkind = 'ellipse'\n", "geometry.kind must be one of"),
    ("[geometry]\ncurvature_lateral = -1\n", "geometry.curvature_lateral"),
    ("[geometry]\nkind = 'semi_axes'\nsemi_axis_longitudinal = 0\n",
     "geometry.semi_axis_longitudinal"),
    ("[friction]\nfriction_coefficient = -0.1\n", "friction.friction_coefficient"),
    ("[effects.creep]\nmethod = 'kalker'\n", "effects.creep.method must be one of"),
    ("[effects.creep]\nsource = 'lookup'\n", "effects.creep.source must be one of"),
    ("[effects.creep]\nspin = 1\n", "effects.creep.spin must be true or false"),
    ("[effects.magic]\n", "effects: unknown key 'magic'"),
    ("[effects.creep]\nmethod = 'exact'\nsource = 'analytic'\n",
     "effects.creep.source must be 'table' with method"),
    ("[effects.creep]\nenabled = false\n[effects.corrugation]\nwavelengths = [0.05]\n"
     "[geometry]\nkind = 'line'\n", "effects.creep.enabled must be true"),
    ("[effects.wear]\nwear_coefficient = 1e-9\n", "effects.wear needs geometry.kind = 'line'"),
    ("[geometry]\nkind = 'line'\n", "effects.creep.method must be 'carter' exactly when"),
    ("[effects.creep]\nmethod = 'carter'\n", "effects.creep.method must be 'carter' exactly"),
    ("[geometry]\nkind = 'line'\n[effects.creep]\nmethod = 'carter'\n[effects.corrugation]\n"
     "wavelengths = [0.05, 0.1]\namplitudes_cos = [1e-6]\n", "equal length"),
    ("[geometry]\nkind = 'line'\n[effects.creep]\nmethod = 'carter'\n[effects.corrugation]\n"
     "wavelengths = [-0.05]\n", r"effects.corrugation.wavelengths\[0\] must be in"),
    ("[geometry]\nkind = 'line'\n[effects.creep]\nmethod = 'carter'\n[effects.wear]\n"
     "wear_coefficient = 1e-9\nevolve = true\nsection_length = 1.0\n", "needs effects.corrugation"),
    ("[geometry]\nkind = 'line'\n[effects.creep]\nmethod = 'carter'\n[effects.wear]\n"
     "wear_coefficient = 1e-9\nwear_model = 'archard'\n", "effects.wear.wear_model must be"),
    ("[simulation]\nstop_time = 0\n", "simulation.stop_time"),
    ("[simulation]\nstep_size = 0.3\n", "simulation.step_size must divide"),
    ("[inputs]\nforce = 1\n", "inputs: unknown key 'force'"),
    ("[inputs]\nnormal_force = { kind = 'square' }\n", "inputs.normal_force.kind"),
    ("[inputs]\nnormal_force = { kind = 'ramp', start_value = 1 }\n",
     "inputs.normal_force.end_value must be a number"),
    ("[inputs]\nspin = { kind = 'travel' }\n", "only allowed for rail_position"),
    ("[inputs]\nspin = { kind = 'points', time = [0, 0], value = [1, 2] }\n",
     "strictly increasing"),
    ("[inputs]\nspin = { kind = 'points', time = [0, 1], value = [1] }\n", "equal length"),
    ("[inputs]\nspin = nan\n", "inputs.spin must be in"),
    ("x = [", "not valid TOML"),
])
def test_invalid_scene_names_the_key(text, match):
    with pytest.raises(SceneError, match=match):
        parse_scene(text)


def test_scene_error_is_value_error():
    assert issubclass(SceneError, ValueError)


def test_missing_file_names_scene_file(tmp_path):
    with pytest.raises(SceneError, match="scene_file: cannot read"):
        load_scene(tmp_path / "nope.toml")


def test_signals():
    scene = parse_scene("""
[simulation]
start_time = 0.0
stop_time = 1.0
step_size = 0.25
[inputs]
normal_force = { kind = "ramp", start_value = 0.0, end_value = 100.0, start_time = 0.25, end_time = 0.75 }
creepage_longitudinal = { kind = "sine", mean = 1.0, amplitude = 2.0, frequency = 1.0 }
creepage_lateral = { kind = "points", time = [0.0, 1.0], value = [0.0, -4.0] }
spin = 0.5
rolling_speed = { kind = "points", time = [0.0, 0.5, 1.0], value = [10.0, 20.0, 20.0] }
rail_position = { kind = "travel", start_value = 3.0 }
""")
    s = scene.input_signals()
    np.testing.assert_array_equal(s["time"], [0.0, 0.25, 0.5, 0.75, 1.0])
    np.testing.assert_array_equal(s["normal_force"], [0.0, 0.0, 50.0, 100.0, 100.0])
    np.testing.assert_allclose(s["creepage_longitudinal"], [1.0, 3.0, 1.0, -1.0, 1.0],
                               atol=1e-15)
    np.testing.assert_array_equal(s["creepage_lateral"], [0.0, -1.0, -2.0, -3.0, -4.0])
    np.testing.assert_array_equal(s["spin"], 0.5)
    # travel = 3 + integral of the (piecewise linear) speed: exact for the trapezoidal rule
    np.testing.assert_allclose(s["rail_position"], [3.0, 6.125, 10.5, 15.5, 20.5])
    np.testing.assert_array_equal(s["creepage_lateral"], scene.input_signals(s["time"])[
        "creepage_lateral"])


def test_undriven_inputs_take_fmu_start_values():
    from railcontact.scene import NoContactWarning

    with pytest.warns(NoContactWarning):            # (normal_force undriven: 0 N)
        s = parse_scene("").input_signals()
    assert np.all(s["rolling_speed"] == 20.0) and np.all(s["normal_force"] == 0.0)


def test_fmu_parameters_round_trip_and_override():
    defaults = scene_to_parameters()
    assert set(defaults) == {p.name for p in FMU_PARAMETERS}
    # without a base, the parameters define the scene completely
    scene = scene_from_dict(parameters_to_scene_dict(dict(defaults, poisson_ratio=0.3)))
    assert scene.poisson_ratio == 0.3
    # with a base scene, parameters left at their start value do not override it ...
    base = {"material": {"poisson_ratio": 0.25}, "effects": {"creep": {"method": "she"}}}
    scene = scene_from_dict(parameters_to_scene_dict(defaults, base=base))
    assert scene.poisson_ratio == 0.25 and scene.effects["creep"]["method"] == "she"
    # ... changed ones do
    scene = scene_from_dict(parameters_to_scene_dict(dict(defaults, creep_method="linear"),
                                                     base=base))
    assert scene.effects["creep"]["method"] == "linear" and scene.poisson_ratio == 0.25


def test_corrugation_surface_file(tmp_path):
    (tmp_path / "surface.csv").write_text("# measured rail, two harmonics\n"
                                          "wavelength,amplitude_cos,amplitude_sin\n"
                                          "0.05, 1e-5, 0\n0.08, 5e-6, 2e-6\n")
    (tmp_path / "s.toml").write_text(
        "[geometry]\nkind = 'line'\n[effects.creep]\nmethod = 'carter'\n"
        "[effects.corrugation]\nsurface_file = 'surface.csv'\n")
    scene = load_scene(tmp_path / "s.toml")       # relative to the scene file's directory
    opts = scene.effects["corrugation"]
    assert opts["wavelengths"] == [0.05, 0.08]
    assert opts["amplitudes_cos"] == [1e-5, 5e-6] and opts["amplitudes_sin"] == [0.0, 2e-6]
    (tmp_path / "bad.csv").write_text("0.05, 1e-5\n")
    with pytest.raises(SceneError, match="three numbers"):
        parse_scene("[geometry]\nkind = 'line'\n[effects.creep]\nmethod = 'carter'\n"
                    "[effects.corrugation]\nsurface_file = 'bad.csv'\n", base_dir=tmp_path)
    with pytest.raises(SceneError, match="surface_file: cannot read"):
        parse_scene("[geometry]\nkind = 'line'\n[effects.creep]\nmethod = 'carter'\n"
                    "[effects.corrugation]\nsurface_file = 'none.csv'\n", base_dir=tmp_path)


VF = ("[geometry]\nkind = 'line'\n[effects.creep]\nmethod = 'carter'\n"
      "[effects.velocity_friction]\nlaw = 'smooth'\nkinetic_friction_coefficient = 0.2\n"
      "kappa = 1.0\n")


def test_friction_accuracy_knobs_default_and_parse():
    opts = parse_scene(VF).effects["velocity_friction"]
    assert (opts["series_degree"], opts["tolerance"]) == (128, 1e-10)
    opts = parse_scene(VF + "series_degree = 32\ntolerance = 1e-8\n").effects["velocity_friction"]
    assert (opts["series_degree"], opts["tolerance"]) == (32, 1e-8)
    assert isinstance(opts["series_degree"], int)


@pytest.mark.parametrize("extra, match", [
    ("series_degree = 4\n", r"effects.velocity_friction.series_degree must be in \[8, 2048\]"),
    ("series_degree = 32.5\n", "effects.velocity_friction.series_degree must be an integer"),
    ("series_degree = 'high'\n", "effects.velocity_friction.series_degree must be an integer"),
    ("series_degree = nan\n", "effects.velocity_friction.series_degree must be an integer"),
    ("tolerance = 0\n", r"effects.velocity_friction.tolerance must be in \(0, 0.01\]"),
    ("tolerance = 0.5\n", "effects.velocity_friction.tolerance"),
])
def test_invalid_friction_accuracy_knob_names_the_key(extra, match):
    with pytest.raises(SceneError, match=match):
        parse_scene(VF + extra)


def test_friction_knobs_as_fmu_parameters():
    values = scene_to_parameters()
    assert (values["friction_series_degree"], values["friction_tolerance"]) == (128, 1e-10)
    values.update(geometry_kind="line", creep_method="carter", velocity_friction_enabled=True,
                  friction_kappa=1.0, friction_series_degree=40, friction_tolerance=1e-9)
    opts = scene_from_dict(parameters_to_scene_dict(values)).effects["velocity_friction"]
    assert (opts["series_degree"], opts["tolerance"]) == (40, 1e-9)


# ---------------------------------------------------------------- table sources
_LINE = "[geometry]\nkind = 'line'\n[effects.creep]\nmethod = 'carter'\n"
_CORR = "[effects.corrugation]\nwavelengths = [0.05]\namplitudes_cos = [1e-6]\n"
_VF = "[effects.velocity_friction]\nkinetic_friction_coefficient = 0.2\nkappa = 10\n"


@pytest.mark.parametrize("text, match", [
    (_LINE + _CORR + "source = 'table'\n",            # method defaults to "exact"
     r"effects.corrugation.method must be 'linear' with source = 'table'.*got 'exact'"),
    (_LINE + _CORR + "source = 'table'\nmethod = 'linear'\n[effects.wear]\n"
     "wear_coefficient = 1e-9\nwear_model = 'patch_coordinate'\n",
     r"effects.wear.wear_model must be 'material_point' with effects.corrugation.source = "
     r"'table'.*got 'patch_coordinate'"),
    (_LINE + "[effects.wear]\nsource = 'table'\nwear_coefficient = 1e-9\n"
     "wear_model = 'nielsen1998'\n",
     r"effects.wear.wear_model must be 'material_point' with effects.wear.source = 'table'"),
    (_LINE + _VF + "law = 'step'\nsource = 'table'\n",
     r"effects.velocity_friction.source must be 'analytic' with law = 'step'"),
    (_LINE + _VF + "source = 'table'\nseries_degree = 64\n",
     r"effects.velocity_friction.series_degree has no effect with source = 'table'.*got 64"),
    (_LINE + _VF + "source = 'table'\ntolerance = 1e-6\n",
     r"effects.velocity_friction.tolerance has no effect with source = 'table'"),
])
def test_table_source_combinations_name_the_key(text, match):
    with pytest.raises(SceneError, match=match):
        parse_scene(text)


@pytest.mark.parametrize("text", [
    _LINE + _CORR + "source = 'table'\nmethod = 'linear'\n[effects.wear]\nsource = 'table'\n"
    "wear_coefficient = 1e-9\n",
    _LINE + _CORR + "method = 'exact'\n[effects.wear]\nsource = 'table'\n"   # exact contact,
    "wear_coefficient = 1e-9\n",                                             # table wear
    _LINE + _CORR + "source = 'table'\nmethod = 'linear'\n[effects.wear]\n"
    "wear_coefficient = 1e-9\n",
    _LINE + "[effects.wear]\nsource = 'table'\nwear_coefficient = 1e-9\n",
    _LINE + _VF + "source = 'table'\nseries_degree = 128\n",
])
def test_allowed_table_source_combinations(text):
    parse_scene(text)


def test_table_source_fmu_parameters():
    """The FMU parameters corrugation_source, wear_source and velocity_friction_source set the
    scene keys (default 'analytic')."""
    values = scene_to_parameters()
    assert {values[k] for k in ("corrugation_source", "wear_source",
                                "velocity_friction_source")} == {"analytic"}
    values.update(geometry_kind="line", creep_method="carter", velocity_friction_enabled=True,
                  velocity_friction_source="table", friction_kappa=10.0)
    scene = scene_from_dict(parameters_to_scene_dict(values))
    assert scene.effects["velocity_friction"]["source"] == "table"


# --------------------------------------------------------------------------------------------
# [effects.nonsteady]
# --------------------------------------------------------------------------------------------
NS = ("[geometry]\nkind = 'line'\nradius = 0.46\ncontact_width = 0.02\n"
      "[effects.creep]\nmethod = 'carter'\n[effects.nonsteady]\n")


def test_nonsteady_defaults_and_options():
    opts = parse_scene(NS).effects["nonsteady"]
    assert (opts["source"], opts["model"], opts["pseudo_width_ratio"]) == ("analytic", "carter",
                                                                          20.0)
    opts = parse_scene(NS + "model = 'johnson'\npseudo_width_ratio = 5\n").effects["nonsteady"]
    assert (opts["model"], opts["pseudo_width_ratio"]) == ("johnson", 5.0)
    assert "nonsteady" not in parse_scene(NS + "enabled = false\n").effects
    assert "nonsteady" in parse_scene("[effects.nonsteady]\n").effects        # 3-D: allowed


@pytest.mark.parametrize("extra, match", [
    ("source = 'table'\n", r"effects.nonsteady.source must be 'analytic': the relaxation "
                           r"length .* is a closed form"),
    ("pseudo_width_ratio = 1.5\n", r"effects.nonsteady.pseudo_width_ratio must be in \[2, "),
    ("pseudo_width_ratio = 'wide'\n", r"effects.nonsteady.pseudo_width_ratio must be a number"),
    ("model = 'hertz'\n", r"effects.nonsteady.model must be one of \['carter', 'johnson'\]"),
    ("modell = 'carter'\n", r"effects.nonsteady: unknown key 'modell'"),
    ("enabled = 1\n", r"effects.nonsteady.enabled must be true or false"),
    ("[effects.corrugation]\nwavelengths = [0.05]\n",
     r"effects.nonsteady cannot be combined with corrugation or wear .*quasi-static"),
    ("[effects.wear]\nwear_coefficient = 1e-9\n",
     r"effects.nonsteady cannot be combined with corrugation or wear"),
])
def test_invalid_nonsteady_names_the_key(extra, match):
    with pytest.raises(SceneError, match=match):
        parse_scene(NS + extra)


def test_nonsteady_needs_creep():
    with pytest.raises(SceneError, match="effects.creep.enabled must be true when .*nonsteady"):
        parse_scene("[effects.creep]\nenabled = false\n[effects.nonsteady]\n")


def test_nonsteady_as_fmu_parameters():
    values = scene_to_parameters()
    assert (values["nonsteady_enabled"], values["nonsteady_pseudo_width_ratio"],
            values["nonsteady_model"]) == (False, 20.0, "carter")
    assert "nonsteady" not in scene_from_dict(parameters_to_scene_dict(values)).effects
    values.update(nonsteady_enabled=True, nonsteady_pseudo_width_ratio=8.0,
                  nonsteady_model="johnson")
    opts = scene_from_dict(parameters_to_scene_dict(values)).effects["nonsteady"]
    assert (opts["pseudo_width_ratio"], opts["model"]) == (8.0, "johnson")
    # a scene file that switches it on, seen as parameters
    values = scene_to_parameters({"effects": {"nonsteady": {"model": "johnson"}}})
    assert values["nonsteady_model"] == "johnson"


# --------------------------------------------------------------------------------------------
# roughness (Ch. 6 asperity model on a rough rail)
# --------------------------------------------------------------------------------------------
ROUGH_LINE = "[geometry]\nkind = 'line'\n[effects.creep]\nmethod = 'carter'\n"
ROUGH = ROUGH_LINE + ("[effects.roughness]\nwavelengths = [0.1, 0.05]\n"
                      "amplitudes_cos = [2e-5, 0]\namplitudes_sin = [0, 1e-5]\n")


def _profile_csv(path, n=12, last=None):
    x = np.linspace(0.0, 0.11, n)
    y = 1e-5 * np.sin(2 * np.pi * x / 0.11)
    y[-1] = y[0] if last is None else last
    path.write_text("# profile\nrail_position_m,height_m\n"
                    + "".join(f"{float(a)!r}, {float(b)!r}\n" for a, b in zip(x, y)))
    return x, y


def test_roughness_harmonics_and_profile_file(tmp_path):
    opts = parse_scene(ROUGH).effects["roughness"]
    assert opts["wavelengths"] == [0.1, 0.05] and opts["amplitudes_sin"] == [0.0, 1e-5]
    assert opts["profile_file"] == "" and opts["profile_extension"] == "periodic"
    x, y = _profile_csv(tmp_path / "p.csv")
    (tmp_path / "s.toml").write_text(ROUGH_LINE + "[effects.roughness]\nprofile_file = 'p.csv'\n")
    opts = load_scene(tmp_path / "s.toml").effects["roughness"]   # relative to the scene file
    assert opts["profile_positions"] == x.tolist() and opts["profile_heights"] == y.tolist()
    assert opts["wavelengths"] == []


@pytest.mark.parametrize("extra, match", [
    ("[effects.corrugation]\nwavelengths = [0.05]\n",
     "effects.roughness cannot be combined with effects.corrugation"),
    ("[effects.wear]\nwear_coefficient = 1e-9\n",
     "effects.roughness cannot be combined with effects.wear"),
    ("[effects.velocity_friction]\nlaw = 'step'\nkinetic_friction_coefficient = 0.2\n",
     "effects.roughness cannot be combined with effects.velocity_friction"),
    ("[effects.nonsteady]\n", "effects.roughness cannot be combined with effects.nonsteady"),
])
def test_roughness_rejects_combinations(extra, match):
    with pytest.raises(SceneError, match=match):
        parse_scene(ROUGH + extra)


@pytest.mark.parametrize("text, match", [
    ("[effects.roughness]\nwavelengths = [0.1]\n", "effects.roughness needs geometry.kind = "
                                                   "'line'"),
    (ROUGH_LINE.replace("method = 'carter'", "enabled = false")
     + "[effects.roughness]\nwavelengths = [0.1]\n",
     "effects.creep.enabled must be true when roughness is on"),
    (ROUGH_LINE + "[effects.roughness]\n", "effects.roughness.wavelengths, amplitudes_cos and "
                                           "amplitudes_sin must be non-empty"),
    (ROUGH_LINE + "[effects.roughness]\nwavelengths = [0.1, 0.2]\namplitudes_cos = [1e-6]\n",
     "equal length"),
    (ROUGH_LINE + "[effects.roughness]\nwavelengths = [0]\n",
     r"effects.roughness.wavelengths\[0\] must be in"),
    (ROUGH + "profile_extension = 'mirror'\n", "effects.roughness.profile_extension must be one"),
    (ROUGH + "profile_file = 'p.csv'\n", "give either a profile file or harmonics, not both"),
    (ROUGH + "amplitude = 1\n", "effects.roughness: unknown key 'amplitude'"),
    (ROUGH_LINE + "[effects.roughness]\nprofile_file = 3\n",
     "effects.roughness.profile_file must be a string"),
])
def test_invalid_roughness_names_the_key(text, match):
    with pytest.raises(SceneError, match=match):
        parse_scene(text)


@pytest.mark.parametrize("write, match", [
    (lambda p: _profile_csv(p, last=3e-6), "needs equal first and last heights"),
    (lambda p: _profile_csv(p, n=5), "at least 6 samples"),
    (lambda p: p.write_text("0, 0\n0.1, 0, 1\n"), "two numbers"),
    (lambda p: p.write_text("0, 0\n0.1, x\n"), "two numbers"),
    (lambda p: p.write_text("".join(f"{v}, 0\n" for v in (0, 1, 1, 2, 3, 4))),
     "strictly increasing"),
    (lambda p: None, "effects.roughness.profile_file: cannot read"),
])
def test_roughness_profile_file_errors(tmp_path, write, match):
    write(tmp_path / "p.csv")
    with pytest.raises(SceneError, match=match):
        parse_scene(ROUGH_LINE + "[effects.roughness]\nprofile_file = 'p.csv'\n",
                    base_dir=tmp_path)


def test_roughness_hold_extension_accepts_unequal_ends(tmp_path):
    _profile_csv(tmp_path / "p.csv", last=3e-6)
    scene = parse_scene(ROUGH_LINE + "[effects.roughness]\nprofile_file = 'p.csv'\n"
                        "profile_extension = 'hold'\n", base_dir=tmp_path)
    assert scene.effects["roughness"]["profile_heights"][-1] == 3e-6


def test_roughness_as_fmu_parameters():
    values = dict(scene_to_parameters(), geometry_kind="line", creep_method="carter",
                  roughness_enabled=True, roughness_wavelengths="0.1 0.05",
                  roughness_amplitudes_cos="2e-5 0", roughness_amplitudes_sin="0 1e-5")
    opts = scene_from_dict(parameters_to_scene_dict(values)).effects["roughness"]
    assert opts["wavelengths"] == [0.1, 0.05] and opts["amplitudes_cos"] == [2e-5, 0.0]
    # off by default: a parameter-only scene does not switch it on
    assert "roughness" not in scene_from_dict(parameters_to_scene_dict(
        dict(scene_to_parameters(), geometry_kind="line", creep_method="carter"))).effects


def test_missing_table_is_a_scene_error_at_load():
    """A creep table that does not exist failed only at FMU initialisation, naming a temporary
    extraction path; now the scene is refused when read, naming the key, the table and where
    tables are looked up."""
    with pytest.raises(SceneError, match=r"effects.creep.table must name an existing table; got "
                                         r"'no_such_table': table file 'no_such_table.nc' not "
                                         r"found in \[.*\]; build it with"):
        parse_scene("[effects.creep]\nsource = 'table'\ntable = 'no_such_table'\n")
    # the analytic source does not read the table: no check
    assert parse_scene("[effects.creep]\nmethod = 'modified_strip'\ntable = 'no_such_table'\n"
                       ).effects["creep"]


def test_input_signals_without_normal_force_warn():
    from railcontact.scene import NoContactWarning

    with pytest.warns(NoContactWarning, match=r"normal_force is 0 N at every time"):
        signals = parse_scene("[inputs]\ncreepage_longitudinal = 1e-3\n").input_signals()
    assert np.all(signals["normal_force"] == 0.0)
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("error", NoContactWarning)
        parse_scene("[inputs]\nnormal_force = 8e4\n").input_signals()


def test_creep_friction_law_keys_are_checked():
    from railcontact.scene import SceneError, scene_from_dict

    def scene(**creep):
        return scene_from_dict({"effects": {"creep": dict(method="exact", **creep)}})

    opts = scene(friction_law="smooth", kinetic_friction_coefficient=0.15,
                 kappa=300.0).effects["creep"]
    assert (opts["friction_law"], opts["kinetic_friction_coefficient"], opts["kappa"]) == (
        "smooth", 0.15, 300.0)
    assert "friction_law" not in scene(friction_law="coulomb").effects["creep"]
    with pytest.raises(SceneError, match="effects.creep.friction_law must be one of"):
        scene(friction_law="polach")
    with pytest.raises(SceneError, match=r"effects.creep.kappa must be in \[0, inf\)"):
        scene(friction_law="smooth", kinetic_friction_coefficient=0.1, kappa=-1.0)
    with pytest.raises(SceneError, match="effects.creep.kinetic_friction_coefficient must be "
                                         "a number"):
        scene(friction_law="smooth", kappa=1.0)
    with pytest.raises(SceneError, match="kappa applies to friction_law = 'smooth' only"):
        scene(kappa=1.0)
    with pytest.raises(SceneError, match="friction_law = 'smooth' needs method = 'exact'"):
        scene_from_dict({"effects": {"creep": dict(method="modified_strip",
                                                   friction_law="smooth",
                                                   kinetic_friction_coefficient=0.1,
                                                   kappa=1.0)}})
