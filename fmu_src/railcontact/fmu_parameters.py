r"""The FMU's parameters and the scene keys they set (the slave's parameter map).

Besides a scene file or text (parameters ``scene_file``, ``scene_toml``), the WheelRailContact
FMU takes every structural scene key as a parameter of its own (:data:`FMU_PARAMETERS`: name,
scene key, FMI type, unit, description). :func:`scene_to_parameters` gives their start values
from a scene dict (default :data:`railcontact.scene.DEFAULT_SCENE`);
:func:`parameters_to_scene_dict` builds the scene dict the slave validates with
:func:`railcontact.scene.scene_from_dict`. With a scene file or text, a parameter overrides it
only if it differs from its start value (some importers set every parameter to its start value
at initialisation; that must not wipe out the scene).
"""

from __future__ import annotations

import copy
from dataclasses import dataclass

from .scene import (DEFAULT_SCENE, FRICTION_SERIES_DEGREE, FRICTION_TOLERANCE,
                    scene_with_defaults)

__all__ = ["ParameterSpec", "FMU_PARAMETERS", "RUNTIME_INPUTS", "scene_to_parameters",
           "parameters_to_scene_dict"]


@dataclass(frozen=True)
class ParameterSpec:
    """One FMU parameter and the scene key it sets."""

    name: str
    path: tuple
    kind: str          # "real", "integer", "string" or "boolean"
    unit: str          # FMI unit ("" for strings and booleans)
    description: str


#: The FMU's structural parameters, each mapped to a scene key. Their start values are those
#: of :data:`DEFAULT_SCENE`.
FMU_PARAMETERS = (
    ParameterSpec("youngs_modulus", ("material", "youngs_modulus"), "real", "Pa",
                  "Young's modulus E of wheel and rail"),
    ParameterSpec("poisson_ratio", ("material", "poisson_ratio"), "real", "1",
                  "Poisson's ratio nu of wheel and rail, in [0, 0.5)"),
    ParameterSpec("geometry_kind", ("geometry", "kind"), "string", "",
                  "Contact geometry: 'curvatures' (Hertz ellipse from A', B' and the normal "
                  "force), 'semi_axes' (fixed ellipse a0, b0) or 'line' (2-D line contact of "
                  "radius R and width contact_width)"),
    ParameterSpec("curvature_longitudinal", ("geometry", "curvature_longitudinal"), "real",
                  "1/m", "A' = 1/(2 R'_x): HALF the relative curvature 1/R'_x = 1/R_x1 + 1/R_x2 "
                  "in the rolling direction (the gap is h = A' x^2 + B' y^2; entering 1/R'_x "
                  "doubles the curvature), > 0; geometry_kind = 'curvatures'. An input: may "
                  "change at every step (effective from the next step), start value from the "
                  "scene"),
    ParameterSpec("curvature_lateral", ("geometry", "curvature_lateral"), "real", "1/m",
                  "B' = 1/(2 R'_y): HALF the lateral relative curvature 1/R'_y = 1/R_y1 + "
                  "1/R_y2 (entering 1/R'_y doubles the curvature), > 0; geometry_kind = "
                  "'curvatures'. An input: may change at every step (effective from the next "
                  "step), start value from the scene"),
    ParameterSpec("semi_axis_longitudinal", ("geometry", "semi_axis_longitudinal"), "real",
                  "m", "Semi-axis a0 along the rolling direction, > 0 (geometry_kind = "
                  "'semi_axes'). An input: may change at every step (effective from the next "
                  "step), start value from the scene"),
    ParameterSpec("semi_axis_lateral", ("geometry", "semi_axis_lateral"), "real", "m",
                  "Lateral semi-axis b0, > 0 (geometry_kind = 'semi_axes'). An input: may "
                  "change at every step (effective from the next step), start value from the "
                  "scene"),
    ParameterSpec("radius", ("geometry", "radius"), "real", "m",
                  "Equivalent radius R of a line contact, 1/R = 1/R_wheel + 1/R_rail "
                  "(geometry_kind = 'line', Carter and Ch. 4 models)"),
    ParameterSpec("contact_width", ("geometry", "contact_width"), "real", "m",
                  "Length of a line contact across the rail; the load per unit length is "
                  "normal_force / contact_width (geometry_kind = 'line')"),
    ParameterSpec("friction_coefficient", ("friction", "friction_coefficient"), "real", "1",
                  "Coulomb friction coefficient mu, >= 0. An input: may change at every step "
                  "(wet rail, leaves, sand; effective from the next step), start value from "
                  "the scene"),
    ParameterSpec("creep_method", ("effects", "creep", "method"), "string", "",
                  "Creep theory: exact (default: Kalker's exact theory from the table "
                  "creep_exact; 0.15 % of mu N on CONTACT's converged cases, up to about 1.2 % "
                  "with spin) | linear | she | strip | modified_strip "
                  "(the thesis's method) | fastsim | polach | fastrip (3-D), carter (2-D, "
                  "geometry_kind = 'line')"),
    ParameterSpec("polach_reduction_adhesion", ("effects", "creep", "polach_reduction_adhesion"),
                  "real", "1", "Polach 2005 k_A, reduction of the initial slope, in (0, 1] "
                               "(creep_method = 'polach'; 1 = Polach 1999)"),
    ParameterSpec("polach_reduction_slip", ("effects", "creep", "polach_reduction_slip"),
                  "real", "1", "Polach 2005 k_S, reduction of the slope in the slip area, in "
                               "(0, k_A] (creep_method = 'polach')"),
    ParameterSpec("polach_friction_ratio_limit",
                  ("effects", "creep", "polach_friction_ratio_limit"), "real", "1",
                  "Polach 2005 A = mu_inf/mu0 of mu = mu0 ((1 - A) exp(-B w) + A), w the slip "
                  "velocity, in [0, 1]; 1 = constant friction (creep_method = 'polach')"),
    ParameterSpec("polach_friction_decay", ("effects", "creep", "polach_friction_decay"),
                  "real", "s/m", "Polach 2005 B, rate of the friction decrease with slip "
                                 "velocity, >= 0 (creep_method = 'polach')"),
    ParameterSpec("creep_source", ("effects", "creep", "source"), "string", "",
                  "Creep forces from the 'analytic' solver or the shipped 'table'; at its start "
                  "value the method's own (the table for exact, the closed form otherwise)"),
    ParameterSpec("creep_spin", ("effects", "creep", "spin"), "boolean", "",
                  "Include the spin input in the creep forces"),
    ParameterSpec("velocity_friction_enabled", ("effects", "velocity_friction", "enabled"),
                  "boolean", "", "Slip-velocity dependent friction (Nielsen Ch. 5; needs "
                                 "geometry_kind = 'line'); friction_coefficient is mu(0)"),
    ParameterSpec("velocity_friction_law", ("effects", "velocity_friction", "law"), "string", "",
                  "Friction law: 'step' (Eq. (5.3), corrected solution (5.4)-(5.6)) or "
                  "'smooth' (Eq. (5.16), iteration of Sec. 5.3)"),
    ParameterSpec("kinetic_friction_coefficient",
                  ("effects", "velocity_friction", "kinetic_friction_coefficient"), "real", "1",
                  "Kinetic friction coefficient mu_k (large slip)"),
    ParameterSpec("friction_kappa", ("effects", "velocity_friction", "kappa"), "real", "1",
                  "Slope parameter kappa of the smooth law (5.16) per unit of slip s"),
    ParameterSpec("friction_series_degree", ("effects", "velocity_friction", "series_degree"),
                  "integer", "", "Accuracy knob of the smooth law (5.16): number of Chebyshev "
                  "nodes of the friction polynomial (5.7), integer in [8, 2048] (default 128: "
                  "about 1e-3 mu_0 N; cost grows like its cube)"),
    ParameterSpec("friction_tolerance", ("effects", "velocity_friction", "tolerance"), "real",
                  "1", "Accuracy knob of the smooth law (5.16): convergence tolerance of the "
                  "friction iteration on max |mu(s)/mu_0 - mu(x)/mu_0| at the nodes, in "
                  "(0, 1e-2]"),
    ParameterSpec("corrugation_enabled", ("effects", "corrugation", "enabled"), "boolean", "",
                  "Corrugated rail surface (Nielsen Ch. 4.2; needs geometry_kind = 'line')"),
    ParameterSpec("corrugation_method", ("effects", "corrugation", "method"), "string", "",
                  "Corrugated contact: 'exact' (nonlinear Eqs. (4.31), (4.33), (4.57), (4.67)) "
                  "or 'linear' (closed forms (4.36)-(4.71))"),
    ParameterSpec("corrugation_wavelengths", ("effects", "corrugation", "wavelengths"), "string",
                  "", "Wave lengths L_m of the rail surface harmonics, space-separated [m]"),
    ParameterSpec("corrugation_amplitudes_cos", ("effects", "corrugation", "amplitudes_cos"),
                  "string", "", "Initial cosine amplitudes Z_A,m of Eq. (4.1), space-separated "
                                "[m]"),
    ParameterSpec("corrugation_amplitudes_sin", ("effects", "corrugation", "amplitudes_sin"),
                  "string", "", "Initial sine amplitudes Z_B,m of Eq. (4.1), space-separated "
                                "[m]"),
    ParameterSpec("corrugation_surface_file", ("effects", "corrugation", "surface_file"),
                  "string", "", "CSV file of rail surface harmonics (columns wavelength, "
                                "amplitude_cos, amplitude_sin [m]); replaces the three lists "
                                "above"),
    ParameterSpec("roughness_enabled", ("effects", "roughness", "enabled"), "boolean", "",
                  "Rough rail surface (Nielsen Ch. 6 single-asperity model on the local "
                  "4th-order gap; needs geometry_kind = 'line'; replaces Carter's force)"),
    ParameterSpec("roughness_wavelengths", ("effects", "roughness", "wavelengths"), "string",
                  "", "Wave lengths L_m of the rail roughness harmonics, space-separated [m] "
                      "(same format as the corrugation harmonics, Eq. (4.1))"),
    ParameterSpec("roughness_amplitudes_cos", ("effects", "roughness", "amplitudes_cos"),
                  "string", "", "Cosine amplitudes of the roughness harmonics (rail height, "
                                "up positive), space-separated [m]"),
    ParameterSpec("roughness_amplitudes_sin", ("effects", "roughness", "amplitudes_sin"),
                  "string", "", "Sine amplitudes of the roughness harmonics, space-separated "
                                "[m]"),
    ParameterSpec("roughness_profile_file", ("effects", "roughness", "profile_file"), "string",
                  "", "CSV file of a sampled rail roughness profile (columns rail position, "
                      "height [m]; a relative name is resolved against the scene file's "
                      "directory, or the working directory without a scene file), "
                      "interpolated by a quintic spline; replaces the harmonics"),
    ParameterSpec("roughness_profile_extension", ("effects", "roughness", "profile_extension"),
                  "string", "", "Roughness profile beyond its ends: 'periodic' (repeated; "
                                "first and last heights equal) or 'hold' (flat at the end "
                                "heights)"),
    ParameterSpec("wear_enabled", ("effects", "wear", "enabled"), "boolean", "",
                  "Frictional wear per passage (Nielsen Sec. 4.3; needs geometry_kind = 'line')"),
    ParameterSpec("wear_coefficient", ("effects", "wear", "wear_coefficient"), "real", "m2/N",
                  "Wear coefficient K of Eq. (4.74) (wear depth = K x frictional work per "
                  "area)"),
    ParameterSpec("wear_model", ("effects", "wear", "wear_model"), "string", "",
                  "Wear model: material_point | patch_coordinate | nielsen1998 | "
                  "time_domain_carter (see railcontact.wear)"),
    ParameterSpec("wear_evolve", ("effects", "wear", "evolve"), "boolean", "",
                  "Evolve the corrugated surface by the wear of every completed passage "
                  "(Eq. (4.103))"),
    ParameterSpec("wear_section_length", ("effects", "wear", "section_length"), "real", "m",
                  "Rail section length: one passage is completed each time rail_position "
                  "advances by it (wear_evolve)"),
    ParameterSpec("corrugation_source", ("effects", "corrugation", "source"), "string", "",
                  "Corrugated contact from the 'analytic' closed forms or the shipped 'table' "
                  "corrugation_response (linearised theory: needs corrugation_method = "
                  "'linear'; wear_model 'material_point')"),
    ParameterSpec("wear_source", ("effects", "wear", "source"), "string", "",
                  "Wear coefficients W1 + i W2 (growth rate, evolution) from the 'analytic' "
                  "series or the shipped 'table' corrugation_response (wear_model "
                  "'material_point' only)"),
    ParameterSpec("velocity_friction_source", ("effects", "velocity_friction", "source"),
                  "string", "", "Smooth-law creep force and stick ratio from the 'analytic' "
                  "iteration of Sec. 5.3 or the shipped 'table' velocity_friction (law "
                  "'smooth' only; friction_series_degree and friction_tolerance then unused)"),
    ParameterSpec("nonsteady_enabled", ("effects", "nonsteady", "enabled"), "boolean", "",
                  "Non-steady rolling correction (Nielsen Ch. 7): the creep forces are the "
                  "steady ones at relaxed creepages that follow the inputs over the relaxation "
                  "length sigma = a0* (Lambda(r_a0) - 1)"),
    ParameterSpec("nonsteady_pseudo_width_ratio", ("effects", "nonsteady", "pseudo_width_ratio"),
                  "real", "1", "b/a0 of the long rectangle of the non-steady displacement "
                               "approximation (Eqs. (7.14)-(7.20)), >= 2 (thesis: 20)"),
    ParameterSpec("nonsteady_model", ("effects", "nonsteady", "model"), "string", "",
                  "Stress for the non-steady displacement u_x(x0, t): 'carter' (Eqs. "
                  "(7.16)-(7.20)) or 'johnson' (Eqs. (7.11)-(7.15))"),
)


#: Scene keys of :data:`FMU_PARAMETERS` that the FMU takes as *inputs* (causality input,
#: continuous): geometry and friction change along a track. Set before initialisation they
#: override the scene like a parameter; after it, they change the contact from the next step.
#: Every other entry of :data:`FMU_PARAMETERS` is a fixed parameter.
RUNTIME_INPUTS = ("curvature_longitudinal", "curvature_lateral", "semi_axis_longitudinal",
                  "semi_axis_lateral", "friction_coefficient")


#: Start values of the FMU parameters whose scene key :data:`DEFAULT_SCENE` does not hold.
_EFFECT_PARAMETER_DEFAULTS = {
    "velocity_friction_enabled": False, "velocity_friction_law": "smooth",
    "kinetic_friction_coefficient": 0.2, "friction_kappa": 0.0,
    "friction_series_degree": FRICTION_SERIES_DEGREE, "friction_tolerance": FRICTION_TOLERANCE,
    "corrugation_enabled": False, "corrugation_method": "exact", "corrugation_wavelengths": "",
    "corrugation_amplitudes_cos": "", "corrugation_amplitudes_sin": "",
    "corrugation_surface_file": "", "wear_enabled": False,
    "wear_coefficient": 0.0, "wear_model": "material_point", "wear_evolve": False,
    "wear_section_length": 1.0,
    "roughness_enabled": False, "roughness_wavelengths": "", "roughness_amplitudes_cos": "",
    "roughness_amplitudes_sin": "", "roughness_profile_file": "",
    "roughness_profile_extension": "periodic",
    "corrugation_source": "analytic", "wear_source": "analytic",
    "velocity_friction_source": "analytic",
    "nonsteady_enabled": False, "nonsteady_pseudo_width_ratio": 20.0,
    "nonsteady_model": "carter",
    "polach_reduction_adhesion": 1.0, "polach_reduction_slip": 1.0,
    "polach_friction_ratio_limit": 1.0, "polach_friction_decay": 0.0,
}


def _default(spec, scene=DEFAULT_SCENE):
    if spec.name in _EFFECT_PARAMETER_DEFAULTS:
        try:
            return _get_path(scene, spec.path)
        except KeyError:
            return _EFFECT_PARAMETER_DEFAULTS[spec.name]
    return _get_path(scene, spec.path)


def _get_path(d, path):
    for key in path:
        d = d[key]
    return d


def _set_path(d, path, value):
    for key in path[:-1]:
        d = d.setdefault(key, {})
    d[path[-1]] = value


def parameters_to_scene_dict(values, base=None, only_changed=True):
    """Scene dict from FMU parameter values.

    Parameters
    ----------
    values : dict
        FMU parameter name -> value.
    base : dict, optional
        Parsed scene TOML the parameters override (default: :data:`DEFAULT_SCENE`).
    only_changed : bool
        With a ``base``, only parameters whose value differs from their start value override
        it (a parameter left at its start value does not touch the scene).
    """
    out = copy.deepcopy(DEFAULT_SCENE if base is None else base)
    if base is None:
        # creep_source and creep_table at their start values mean "the method's own"
        # (the exact theory from creep_exact, the closed form otherwise): not set here
        for key in ("source", "table"):
            out["effects"]["creep"].pop(key, None)
    for spec in FMU_PARAMETERS:
        if spec.name not in values:
            continue
        value = values[spec.name]
        if (base is not None or spec.name in _METHOD_DEFAULTED) and only_changed \
                and value == _default(spec):
            continue
        _set_path(out, spec.path, value)
    return out


#: FMU parameters whose start value defers to the creep method's own default.
_METHOD_DEFAULTED = ("creep_source", "creep_table")


def scene_to_parameters(scene_dict=None):
    """FMU parameter start values from a scene dict (default :data:`DEFAULT_SCENE`)."""
    merged = scene_with_defaults(scene_dict or {})
    return {spec.name: _default(spec, merged) for spec in FMU_PARAMETERS}
