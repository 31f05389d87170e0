r"""Scenes: which effects a WheelRailContact run switches on, and the input signals that drive it.

Why one module of about 980 lines: the scene schema is one table of keys, ranges and messages
per effect, and the effect registry EFFECTS that both scene validation and the FMU pipeline
read; most of its length is those tables and the error messages that name each key.

A scene is a small TOML file (``examples/scenes/*.toml``) read with :mod:`tomllib`. It names the
material, the contact geometry, the friction coefficient, the effects that are on (and for each
whether the answer comes from the analytic solver or from a shipped table) and, for
``python -m railcontact.run``, the time grid and the input signals. The FMU reads the same text
(parameter ``scene_file`` or ``scene_toml``) or builds the same structure from its individual
parameters (:data:`railcontact.fmu_parameters.FMU_PARAMETERS`).

Example (``examples/scenes/creep_only_analytic.toml``)::

    [scene]
    name = "creep_only_analytic"
    description = "3-D creep forces, modified strip theory, analytic"

    [material]
    youngs_modulus = 210e9      # [Pa]
    poisson_ratio = 0.28        # [-]

    [geometry]
    kind = "curvatures"
    curvature_longitudinal = 1.25   # A' = 1/(2 R'_x) [1/m]
    curvature_lateral = 3.3         # B' = 1/(2 R'_y) [1/m]

    [friction]
    friction_coefficient = 0.3  # [-]

    [effects.creep]
    method = "exact"            # exact (default) | linear | she | strip | modified_strip | ...
    source = "table"            # analytic | table (default: table for exact, else analytic)
    spin = true

    [simulation]
    start_time = 0.0
    stop_time = 1.0
    step_size = 1e-3

    [inputs]
    normal_force = 80e3
    creepage_longitudinal = { kind = "ramp", start_value = -0.01, end_value = 0.01 }

Every error is a :class:`SceneError` (a ``ValueError``) naming the offending key by its dotted
TOML path (``material.poisson_ratio must be in [0, 0.5) [-]; got 0.6``).

Table sources
-------------
``effects.<name>.source = "table"`` takes the answer from a shipped table (``tables/*.nc``,
built by ``python -m tablegen build``, read by :mod:`railcontact.tables`) instead of the
analytic solver. Allowed combinations (anything else is a :class:`SceneError` naming the key):

* ``creep``: ``method = "exact"`` (the default method; table ``creep_exact``, the exact theory
  is table-only, and its source defaults to the table) or ``"modified_strip"`` (table
  ``creep_modified_strip``; the thesis's method, analytic unless ``source = "table"``).
* ``corrugation``: ``method = "linear"`` only: the table ``corrugation_response`` holds the
  normalised first-harmonic response coefficients of the *linearised* theory
  (:func:`railcontact.wear.linear_response`), superposed over the harmonics exactly as
  :func:`railcontact.corrugation.corrugated_contact` does with ``method = "linear"``. The exact
  nonlinear contact has no table source (the table ``corrugation_exact`` holds exact first
  harmonics per unit amplitude, which do not superpose; it is not used by the FMU). With wear
  on, ``effects.wear.wear_model`` must be ``"material_point"`` (the only model the table holds).
* ``wear``: ``wear_model = "material_point"`` only; the wear coefficients W1 + i W2 (growth
  rate, evolution) come from the same table's wear variables. The smooth-rail mean wear (4.96)
  is a closed form in both sources. The sources of corrugation and wear are independent (e.g.
  the exact corrugated contact with table wear coefficients is allowed).
* ``velocity_friction``: ``law = "smooth"`` only (the step law is a closed form: ``source =
  "table"`` with it is an error); table ``velocity_friction`` (force, saturation creepage and
  stick ratio over mu_k/mu_0, kappa xi_c0 and |xi|/xi_sat), built with degree 128 and
  tolerance 1e-10, so ``series_degree``/``tolerance`` other than their defaults are an error
  with the table; ``mu_k/mu_0`` must lie in the table's range [0.2, 1.8] (checked when the FMU
  initialises).

Inputs outside a table's grid get the reader's documented behaviour (modified-strip creep table:
held at full sliding, exact; the others raise) and the FMU logs a warning once; where the reader
raises, that step uses the analytic solver instead (exact creep table: modified strip theory;
corrugation table: the linear closed forms for that harmonic, a0/L outside [0.01, 1]; velocity
friction table: the Sec. 5.3 iteration, kappa xi_c0 > 6 or |xi|/xi_sat > 6). Never NaN.
FMU parameters: ``creep_source``, ``corrugation_source``, ``wear_source``,
``velocity_friction_source``.

Input signals
-------------
Each entry of ``[inputs]`` is a number (constant) or an inline table with ``kind``:

* ``"constant"``: ``value``;
* ``"ramp"``: ``start_value`` at ``start_time`` to ``end_value`` at ``end_time`` (defaults: the
  simulation interval), held constant outside;
* ``"sine"``: ``mean + amplitude sin(2 pi frequency t + phase)``;
* ``"points"``: ``time = [...]``, ``value = [...]``, piecewise linear, held outside;
* ``"travel"`` (``rail_position`` only): ``start_value + integral of rolling_speed dt``
  (trapezoidal rule on the output grid).

Inputs not named are held at the FMU's start values (:data:`INPUT_DEFAULTS`).

Accuracy knobs and error outputs
--------------------------------
Where an effect has an accuracy setting, the scene (and the FMU parameter in brackets) exposes
it; where an error estimate exists, the FMU reports it as an output (-1 = not estimated):

* Creep tables (``effects.creep.source = "table"``): the table's resolution is fixed when it is
  built (``python -m tablegen build --resolution ...``); the output
  ``creep_table_error_estimate`` is the max error of ``|(Fx, Fy)| / (mu N)`` the file records
  against the direct solution of the theory it holds (netCDF attributes ``max_abs_error``, read
  at initialisation; ``creep_modified_strip``: about 2e-7; ``creep_exact``: its recorded
  interpolation error against the extrapolated solver it was built from, docs/tables.md; the
  solver's own error against the converged theory: 0.13 % on CONTACT's 21 converged cases,
  0.51 % at most on 300 random ones, docs/tables.md). With
  ``source = "analytic"`` it is -1: there is no interpolation error, and the error of the
  strip, modified strip, SHE and linear theories against Kalker's exact theory is not
  estimated at run time (the package's tests and benchmarks measure it).
* Velocity-dependent friction, smooth law (5.16): ``effects.velocity_friction.series_degree``
  (``friction_series_degree``, integer in [8, 2048], default 128) is the number of Chebyshev
  nodes of the friction polynomial (5.7), ``effects.velocity_friction.tolerance``
  (``friction_tolerance``, in (0, 1e-2], default 1e-10) the tolerance of the iteration of Sec.
  5.3; the output ``friction_iteration_residual`` is the converged residual. The cost of a
  step grows like ``series_degree^3`` (dense Newton solves). Measured (largest change of
  T / (mu_0 N) against degree 512 over creepage ratios 0.1-1.2, mu_k/mu_0 in {0.3, 0.7, 1.5},
  kappa xi_c0 in {0.5, 3, 20}): degree 128: 2.2e-4, 64: 3.2e-4, 32: 3.2e-4, 16: 2.0e-2 (a steep
  law, kappa xi_c0 = 20, needs a degree well above it). The solver's own accuracy against the
  discretised reference is about 1e-3 mu_0 N at degree 128 (:mod:`railcontact.friction`), so
  degree 32 is the cheap setting for laws with kappa xi_c0 up to about 3. The step law is a
  closed form and has no knob.
* Corrugation: the corrugated contact itself
  (:func:`railcontact.corrugation.corrugated_contact`, methods "exact" and "linear") uses
  closed forms only: the Chebyshev series of the contact distributions is summed in closed form
  through Bessel functions, and the nonlinear conditions (4.31), (4.33), (4.57), (4.67) are
  solved by Newton to 1e-13; there is no truncated series and no knob. With the wear effect on
  (``wear_model`` "material_point" or "patch_coordinate") the linearised wear coefficients
  (:func:`railcontact.wear.wear_coefficients`: wear depth, growth rate, evolution) do sum that
  series, truncated at the automatic degree ``ceil(e k a0) + 12`` of the largest ``k a0``; the
  output ``corrugation_series_error_estimate`` is its truncation error
  (:func:`railcontact.corrugation.series_truncation_error`: the neglected ``|J_n(k a0)|``
  relative to the largest, the size (4.27) whose term ratio is the estimate (4.28)), below
  1e-16 at that degree (measured for k a0 from 0.01 to 12); -1 without wear, with the
  time-domain wear models or without contact. It is an estimate of the right size, not a
  strict bound: for k a0 = 0.5-6, r_a0 = 0.2-0.6 and degrees 2-12 the actual relative change
  of the wear coefficient against the default degree is 0.003 to 1.03 times it
  (``tests/test_effects.py``). The degree is not a scene/FMU knob: ``corrugated_contact``
  takes no degree argument, and a knob that reached the growth rate but not the wear depth
  would be inconsistent. With ``effects.corrugation.source = "table"`` and
  ``effects.wear.source = "table"`` no series is summed at run time and the output is -1; the
  table ``corrugation_response`` records its own accuracy (max error 3.6e-5 of the normalised
  coefficients, which are of order 0.1-1; it multiplies the first-order harmonic part only).
* Velocity-friction table (``effects.velocity_friction.source = "table"``): no iteration runs,
  so ``friction_iteration_residual`` is -1; the output ``friction_table_error_estimate`` is the
  table's recorded max error of ``|Fx| / (mu_0 N)`` against the Sec. 5.3 iteration it holds
  (1.7e-4; the iteration's own error is about 1e-3 mu_0 N). The stick ratio ``r_a0`` from the
  table has a recorded max error of 7.9e-3 (the iteration's own stick ratio jumps by up to
  ~1e-2 for steep falling laws). A step outside the table's grid reports the iteration's
  residual and -1 for the table error.
* Non-steady correction (``[effects.nonsteady]``, keys ``model`` = "carter" | "johnson" and
  ``pseudo_width_ratio`` = b/a0 >= 2, default 20; FMU parameters ``nonsteady_enabled``,
  ``nonsteady_model``, ``nonsteady_pseudo_width_ratio``): the first-order relaxation law of
  :class:`railcontact.effects.NonSteady` is within 1 % of the thesis' frequency response
  (Ch. 7) while ``k a0* < 0.155`` (wave length of the creepage variation L > 40 a0*, i.e.
  a0/L < 0.025 at full stick), 5 % for ``k a0* < 0.47``, at most 27 % at any frequency (table in
  :mod:`railcontact.nonsteady`); its time stepping is exact for constant sigma and second
  order otherwise, with sub-steps where sigma changes by more than 25 % in a step. There is
  no knob: the output ``relaxation_length`` shows sigma, and the step length that resolves the
  lag is ``h << relaxation_length / rolling_speed``. ``source`` must be "analytic" (sigma is a
  closed form; the table ``nonsteady_transfer`` is the frequency response, which a time step
  cannot use); it cannot be combined with corrugation or wear (quasi-static Ch. 4 models).
* Roughness (``[effects.roughness]``, Nielsen Ch. 6): no knob. The local gap is the 4th-order
  Taylor expansion of the true gap about its minimum (:func:`railcontact.roughness.local_gap`,
  exact derivatives of the harmonics or of the quintic spline through the profile), and the
  single-asperity solution of that quartic is exact (Table 6.1 closed forms or a bracketed
  root to 1e-15). The truncation is the model's error: against the exact corrugated contact
  of one harmonic it is of order ``(a0/L)^4`` in the half-width and ``(a0/L)^3`` in the patch
  shift and the force (measured: 1.2e-4, 6.9e-4 a0 and 1.5e-4 mu N at a0/L = 0.1 with
  ``k^2 R |Z| = 0.18``; ``tests/test_roughness.py``), so roughness wave lengths should be
  long against the contact (a0/L <~ 0.1). It is not estimated at run time.

Roughness
---------
``[effects.roughness]`` (line contact, with ``effects.creep.method = "carter"``, whose force it
replaces) takes either harmonics ``wavelengths``, ``amplitudes_cos``, ``amplitudes_sin`` (the
format and the surface of ``[effects.corrugation]``, Eq. (4.1): rail height, up positive) or
``profile_file``, a CSV of rail position [m] and height [m] (``#`` comments, optional header;
relative to the scene file's directory) interpolated by a quintic spline, extended
``profile_extension = "periodic"`` (default; equal first and last heights) or ``"hold"``. It
cannot be combined with corrugation, wear, velocity-dependent friction or the non-steady
correction. The gap must be convex everywhere (``R max r'' < 1``, checked when the FMU builds
the effect).
"""

from __future__ import annotations

import copy
import math
import tomllib
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from types import MappingProxyType
from typing import NamedTuple

import numpy as np

from ._validation import check_range

__all__ = [
    "SceneError", "Scene", "load_scene", "parse_scene", "scene_from_dict", "EFFECTS",
    "EffectSpec",    "CREEP_METHODS", "SOURCES", "INPUTS", "INPUT_DEFAULTS", "NoContactWarning",
    "DEFAULT_SCENE", "scene_with_defaults",
]


class NoContactWarning(UserWarning):
    """A scene's input signals have no normal force: every force of the run is 0."""


class SceneError(ValueError):
    """A scene (TOML text or FMU parameters) is invalid; the message names the key."""


#: Creep theories: the 3-D ones of :func:`railcontact.creep3d.creep_force_3d` (elliptic
#: contact), Kalker's exact theory (``"exact"``, the default, from the shipped table
#: ``creep_exact`` of :class:`railcontact.exact_table.ExactCreepTable`) and Carter's 2-D theory
#: (:func:`railcontact.carter.carter_creep_force`, line contact, ``geometry.kind = "line"``).
CREEP_METHODS = ("linear", "she", "strip", "modified_strip", "exact", "carter", "fastsim",
                 "polach", "fastrip")
#: Polach's 2005 parameters in ``[effects.creep]`` (method = "polach" only): scene key ->
#: (keyword of :func:`railcontact.polach.polach_force_3d`, unit, lower, upper, lower_closed,
#: default). Defaults: Polach 1999 (no reduction, constant friction).
POLACH_KEYS = {
    "polach_reduction_adhesion": ("reduction_adhesion", "-", 0.0, 1.0, False, 1.0),
    "polach_reduction_slip": ("reduction_slip", "-", 0.0, 1.0, False, 1.0),
    "polach_friction_ratio_limit": ("friction_ratio_limit", "-", 0.0, 1.0, True, 1.0),
    "polach_friction_decay": ("friction_decay", "s/m", 0.0, None, True, 0.0),
}
#: Falling friction on the 3-D exact table (``[effects.creep]``, method = "exact" only; the
#: fast path :mod:`railcontact.falling_table`): ``friction_law`` "coulomb" (default) or
#: "smooth" (Eq. (5.16) with mu_0 = ``friction.friction_coefficient``), with
#: ``kinetic_friction_coefficient`` mu_k >= 0 and ``kappa`` >= 0 (per unit slip s = |w|/V).
CREEP_FRICTION_LAWS = ("coulomb", "smooth")
CREEP_FRICTION_LAW_KEYS = ("friction_law", "kinetic_friction_coefficient", "kappa")
#: Defaults of the accuracy knobs of the smooth friction law's iteration (those of
#: :func:`railcontact.friction.solve_velocity_friction_normalised`).
FRICTION_SERIES_DEGREE = 128
FRICTION_TOLERANCE = 1e-10
#: Wear models of :func:`railcontact.wear.wear_coefficients`.
WEAR_MODELS = ("material_point", "patch_coordinate", "nielsen1998", "time_domain_carter")
#: Where an effect takes its answer from.
SOURCES = ("analytic", "table")
#: FMU inputs: name -> (unit, description).
INPUTS = {
    "normal_force": ("N", "Normal contact force N pressing wheel and rail together, >= 0"),
    "creepage_longitudinal": ("1", "Longitudinal creepage xi_x = (V_x1 - V_x2)/V_m, rigid "
                                   "velocity of the wheel (1) relative to the rail (2) along "
                                   "+x, the rolling direction (Nielsen Eq. (2.15)); > 0 when "
                                   "the wheel surface moves faster than the rail's"),
    "creepage_lateral": ("1", "Lateral creepage xi_y = (V_y1 - V_y2)/V_m, wheel relative to "
                              "rail along +y (lateral)"),
    "spin": ("1/m", "Spin creepage phi = (Omega_z1 - Omega_z2)/V_m, wheel relative to rail "
                    "about the contact normal +z (right-handed x, y, z)"),
    "rolling_speed": ("m/s", "Mean rolling speed V_m of the contact along the rail, >= 0"),
    "rail_position": ("m", "Position of the wheel axis along the rail (corrugated rail "
                           "surface; completed passages for wear_evolve)"),
}
#: Start values of the inputs (used when a scene does not drive them).
INPUT_DEFAULTS = {"normal_force": 0.0, "creepage_longitudinal": 0.0, "creepage_lateral": 0.0,
                  "spin": 0.0, "rolling_speed": 20.0, "rail_position": 0.0}

_SIGNAL_KINDS = ("constant", "ramp", "sine", "points", "travel")

DEFAULT_SCENE = {
    "scene": {"name": "default", "description": ""},
    "material": {"youngs_modulus": 210e9, "poisson_ratio": 0.28},
    "geometry": {"kind": "curvatures", "curvature_longitudinal": 1.25,
                 "curvature_lateral": 3.3, "semi_axis_longitudinal": 6e-3,
                 "semi_axis_lateral": 5e-3, "radius": 0.3, "contact_width": 0.02},
    "friction": {"friction_coefficient": 0.3},
    "effects": {"creep": {"enabled": True, "method": "exact", "source": "table",
                          "spin": True, "table": "creep_modified_strip"}},
    "simulation": {"start_time": 0.0, "stop_time": 1.0, "step_size": 1e-3},
    "inputs": {},
}

# Allowed keys per section (typos are errors, not silently ignored).
_SECTION_KEYS = {
    "scene": {"name", "description"},
    "material": {"youngs_modulus", "poisson_ratio"},
    "geometry": {"kind", "curvature_longitudinal", "curvature_lateral",
                 "semi_axis_longitudinal", "semi_axis_lateral", "radius", "contact_width"},
    "friction": {"friction_coefficient"},
    "simulation": {"start_time", "stop_time", "step_size"},
}


class EffectSpec(NamedTuple):
    """One effect a scene can switch on: an entry of :data:`EFFECTS`."""

    #: Name: the scene section ``[effects.<name>]`` and the key of the FMU's effect object.
    name: str
    #: Keys allowed in ``[effects.<name>]``.
    keys: frozenset
    #: Effects whose results this one supplies in their place when both are on: the pipeline
    #: does not compute those (:func:`railcontact.effects.build_pipeline`).
    replaces: tuple
    #: What the effect does to the contact point, in one line.
    summary: str


#: The effects a scene can switch on, in the order the FMU evaluates them (name ->
#: :class:`EffectSpec`): the one registry that scene validation (allowed sections and keys;
#: :attr:`Scene.effects` is in this order) and the FMU's pipeline
#: (:func:`railcontact.effects.build_pipeline`) both read. The normal contact (Hertz) is always
#: on and comes before all of them; the non-steady correction also has a last step that puts
#: the input creepages back. An effect that ``replaces`` another is evaluated in its place: with
#: velocity friction or roughness on, Carter's force (``creep``) is not computed at all.
EFFECTS = MappingProxyType({spec.name: spec for spec in (
    EffectSpec("nonsteady", frozenset({"enabled", "source", "pseudo_width_ratio", "model"}), (),
               "relaxed creepages in place of the input creepages for every later effect "
               "(Ch. 7); the inputs are put back after the last effect"),
    EffectSpec("creep", frozenset({"enabled", "method", "source", "spin", "table",
                                   *POLACH_KEYS, *CREEP_FRICTION_LAW_KEYS}), (),
               "creep forces and stick measures (3-D theories; Carter on a line contact)"),
    EffectSpec("velocity_friction", frozenset({"enabled", "source", "law",
                                               "kinetic_friction_coefficient", "kappa",
                                               "series_degree", "tolerance"}), ("creep",),
               "slip-velocity dependent friction (Ch. 5): force and stick ratio in place of "
               "Carter's"),
    EffectSpec("roughness", frozenset({"enabled", "source", "wavelengths", "amplitudes_cos",
                                       "amplitudes_sin", "profile_file",
                                       "profile_extension"}), ("creep",),
               "rough rail (Ch. 6): contact half-width, patch shift, force and stick ratio in "
               "place of Carter's"),
    EffectSpec("corrugation", frozenset({"enabled", "source", "method", "wavelengths",
                                         "amplitudes_cos", "amplitudes_sin",
                                         "surface_file"}), (),
               "corrugated rail (Ch. 4.2): contact half-width, patch shift and Fx of the "
               "corrugated contact (creep's stick measures, which wear reads, stay)"),
    EffectSpec("wear", frozenset({"enabled", "source", "wear_coefficient", "wear_model",
                                  "evolve", "section_length"}), (),
               "wear per passage (Ch. 4.3) and, optionally, the surface evolution (Ch. 4.4)"),
)})
#: Displacement models of the non-steady correction
#: (:func:`railcontact.nonsteady.relaxation_length`).
NONSTEADY_MODELS = ("carter", "johnson")


@dataclass(frozen=True)
class Scene:
    """A validated scene.

    Attributes
    ----------
    name, description : str
        Identification.
    youngs_modulus : float
        Young's modulus of wheel and rail. [Pa]
    poisson_ratio : float
        Poisson's ratio of wheel and rail. [-]
    geometry : dict
        ``kind`` ("curvatures" or "semi_axes") and the values it needs. [1/m] or [m]
    friction_coefficient : float
        Coulomb friction coefficient mu. [-]
    effects : dict
        Effect name -> options (``enabled``, ``source``, ...), only effects switched on.
    simulation : dict
        ``start_time``, ``stop_time``, ``step_size``. [s]
    inputs : dict
        Input name -> signal specification (validated).
    """

    name: str
    description: str
    youngs_modulus: float
    poisson_ratio: float
    geometry: dict
    friction_coefficient: float
    effects: dict
    simulation: dict
    inputs: dict = field(default_factory=dict)

    def enabled(self, effect):
        """Whether ``effect`` is switched on."""
        return effect in self.effects

    def time_grid(self):
        """Communication points from ``start_time`` to ``stop_time`` by ``step_size``. [s]"""
        sim = self.simulation
        n = int(round((sim["stop_time"] - sim["start_time"]) / sim["step_size"]))
        return sim["start_time"] + sim["step_size"] * np.arange(n + 1)

    def input_signals(self, time=None):
        """Input values on ``time`` (default :meth:`time_grid`) as a structured array.

        Returns
        -------
        ndarray
            Fields ``time`` and every input of :data:`INPUTS`, float64, the layout
            :func:`fmpy.simulate_fmu` takes as ``input``.

        Warns
        -----
        NoContactWarning
            If the normal force is 0 at every time (``[inputs] normal_force`` not set: its
            default is 0 N): every force of the run would be 0.
        """
        t = self.time_grid() if time is None else np.asarray(time, dtype=float)
        out = np.zeros(t.shape, dtype=[("time", float)] + [(k, float) for k in INPUTS])
        out["time"] = t
        for name in INPUTS:
            if name == "rail_position":
                continue
            out[name] = _evaluate_signal(self.inputs.get(name, INPUT_DEFAULTS[name]), t,
                                         self.simulation)
        spec = self.inputs.get("rail_position", INPUT_DEFAULTS["rail_position"])
        if isinstance(spec, dict) and spec["kind"] == "travel":
            speed = out["rolling_speed"]
            steps = 0.5 * (speed[1:] + speed[:-1]) * np.diff(t)
            out["rail_position"] = spec.get("start_value", 0.0) + np.concatenate(
                ([0.0], np.cumsum(steps)))
        else:
            out["rail_position"] = _evaluate_signal(spec, t, self.simulation)
        if out.size and np.all(out["normal_force"] <= 0.0):
            warnings.warn(f"scene {self.name!r}: normal_force is 0 N at every time ([inputs] "
                          "normal_force not set, its default is 0 N): no contact, every force "
                          "of the run is 0", NoContactWarning, stacklevel=2)
        return out


def load_scene(path):
    """Read and validate a scene TOML file.

    Parameters
    ----------
    path : str or path-like
        The ``.toml`` file.

    Returns
    -------
    Scene

    Raises
    ------
    SceneError
        If the file is missing, is not TOML, or a value is invalid (the message names the key).
    """
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as exc:
        raise SceneError(f"scene_file: cannot read {str(path)!r}: {exc.strerror}") from exc
    return parse_scene(text, origin=str(path), base_dir=path.parent)


def parse_scene(text, origin="<scene_toml>", base_dir=None):
    """Parse and validate scene TOML text (see the module docstring for the format)."""
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise SceneError(f"{origin}: not valid TOML: {exc}") from exc
    return scene_from_dict(data, base_dir=base_dir)


def scene_with_defaults(data):
    """The scene dict ``data`` with the values of :data:`DEFAULT_SCENE` for every section and
    key it does not give (a deep merge; no validation: :func:`scene_from_dict` validates)."""
    return _merge(DEFAULT_SCENE, data)


def _merge(base, update):
    out = copy.deepcopy(base)
    for key, value in update.items():
        if isinstance(value, dict) and isinstance(out.get(key), dict):
            out[key] = _merge(out[key], value)
        else:
            out[key] = copy.deepcopy(value)
    return out


def _number(path, value, unit, lower=None, upper=None, **kwargs):
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise SceneError(f"{path} must be a number [{unit}]; got {value!r}")
    try:
        return float(check_range(path, value, unit, lower, upper, **kwargs))
    except ValueError as exc:
        raise SceneError(str(exc)) from None


def _integer(path, value, unit, lower, upper):
    if (isinstance(value, bool) or not isinstance(value, (int, float))
            or not (math.isfinite(value) and float(value).is_integer())):
        raise SceneError(f"{path} must be an integer in [{lower}, {upper}] [{unit}]; got "
                         f"{value!r}")
    return int(_number(path, value, unit, lower, upper))


def _number_list(path, value, unit, lower=None, **kwargs):
    if isinstance(value, str):
        try:
            value = [float(v) for v in value.replace(",", " ").split()]
        except ValueError:
            raise SceneError(f"{path} must be a list of numbers [{unit}]; got {value!r}") from None
    if not isinstance(value, list):
        raise SceneError(f"{path} must be a list of numbers [{unit}]; got {value!r}")
    return [_number(f"{path}[{i}]", v, unit, lower, None, **kwargs) for i, v in enumerate(value)]


def _choice(path, value, choices):
    if value not in choices:
        raise SceneError(f"{path} must be one of {list(choices)}; got {value!r}")
    return value


def _boolean(path, value):
    if not isinstance(value, bool):
        raise SceneError(f"{path} must be true or false; got {value!r}")
    return value


def _check_table_exists(key, name):
    """A table the scene names must exist where the readers look for it
    (:func:`railcontact.tables.default_table_path`), checked when the scene is read rather
    than when an FMU first loads it."""
    from . import tables  # noqa: PLC0415  (numba, netCDF4: only for scenes that use a table)

    try:
        tables.default_table_path(name)
    except FileNotFoundError as exc:
        raise SceneError(f"{key} must name an existing table; got {name!r}: {exc}") from None


def _check_keys(path, table, allowed):
    if not isinstance(table, dict):
        raise SceneError(f"{path} must be a table; got {table!r}")
    unknown = sorted(set(table) - set(allowed))
    if unknown:
        raise SceneError(f"{path}: unknown key {unknown[0]!r}; allowed keys are "
                         f"{sorted(allowed)}")


def _read_csv_table(key, name, base_dir, columns):
    """Rows of numbers from a small CSV file of the scene (``#`` comments, blank lines and an
    optional header line skipped; commas or blanks separate), each with ``len(columns)`` values.

    ``key`` is the dotted scene key named in errors, ``columns`` the column descriptions
    (e.g. ``"wavelength [m]"``); a relative ``name`` is resolved against ``base_dir``."""
    path = Path(name)
    if not path.is_absolute() and base_dir is not None:
        path = Path(base_dir) / path
    try:
        rows = [line.split("#")[0].strip() for line in
                path.read_text(encoding="utf-8").splitlines()]
    except OSError as exc:
        raise SceneError(f"{key}: cannot read {str(path)!r}: {exc.strerror}") from None
    rows = [r for r in rows if r]
    if rows:
        try:
            [float(v) for v in rows[0].replace(",", " ").split()]
        except ValueError:
            rows = rows[1:]                                # header line
    words = {2: "two", 3: "three"}.get(len(columns), str(len(columns)))
    message = (f"{key} {str(path)!r}: every line must hold {words} numbers: "
               f"{', '.join(columns)}")
    try:
        table = [[float(v) for v in r.replace(",", " ").split()] for r in rows]
    except ValueError:
        raise SceneError(message) from None
    if any(len(r) != len(columns) for r in table):
        raise SceneError(message)
    return path, table


def _read_surface_file(name, base_dir):
    """Rail surface harmonics from a CSV file: columns wavelength, amplitude_cos, amplitude_sin
    [m] (one harmonic per line, ``#`` comments, an optional header line)."""
    path, table = _read_csv_table("effects.corrugation.surface_file", name, base_dir,
                                  ("wavelength", "amplitude_cos", "amplitude_sin [m]"))
    if not table:
        raise SceneError(f"effects.corrugation.surface_file {str(path)!r}: every line must "
                         "hold three numbers: wavelength, amplitude_cos, amplitude_sin [m]")
    return {"wavelengths": [r[0] for r in table], "amplitudes_cos": [r[1] for r in table],
            "amplitudes_sin": [r[2] for r in table]}


#: Extensions of a sampled roughness profile beyond its ends (see
#: :class:`railcontact.roughness.ProfileRoughness`).
ROUGHNESS_PROFILE_EXTENSIONS = ("periodic", "hold")


def _read_roughness_profile(name, base_dir):
    """Rail roughness profile from a CSV file: columns rail position [m], height [m] (one
    sample per line, ``#`` comments, an optional header line)."""
    key = "effects.roughness.profile_file"
    path, table = _read_csv_table(key, name, base_dir, ("rail position [m]", "height [m]"))
    positions = [r[0] for r in table]
    heights = [r[1] for r in table]
    if len(table) < 6:
        raise SceneError(f"{key} {str(path)!r}: needs at least 6 samples (quintic spline); got "
                         f"{len(table)}")
    if not all(math.isfinite(v) for v in positions + heights):
        raise SceneError(f"{key} {str(path)!r}: positions and heights must be finite [m]")
    if any(b <= a for a, b in zip(positions, positions[1:])):
        raise SceneError(f"{key} {str(path)!r}: rail positions must be strictly increasing [m]")
    return positions, heights


def _roughness_options(opts, base_dir):
    """Validated ``effects.roughness`` options: the harmonics (same format as corrugation) or a
    sampled profile (``profile_file``, read here into ``profile_positions``/``profile_heights``)."""
    out = {}
    profile = opts.get("profile_file", "")
    if not isinstance(profile, str):
        raise SceneError(f"effects.roughness.profile_file must be a string; got {profile!r}")
    waves = _number_list("effects.roughness.wavelengths", opts.get("wavelengths", []), "m", 0.0,
                         lower_closed=False)
    za = _number_list("effects.roughness.amplitudes_cos",
                      opts.get("amplitudes_cos", [0.0] * len(waves)), "m")
    zb = _number_list("effects.roughness.amplitudes_sin",
                      opts.get("amplitudes_sin", [0.0] * len(waves)), "m")
    out["profile_extension"] = _choice("effects.roughness.profile_extension",
                                       opts.get("profile_extension", "periodic"),
                                       ROUGHNESS_PROFILE_EXTENSIONS)
    if profile:
        if waves or any(za) or any(zb):
            raise SceneError("effects.roughness.profile_file and effects.roughness.wavelengths: "
                             "give either a profile file or harmonics, not both")
        positions, heights = _read_roughness_profile(profile, base_dir)
        if out["profile_extension"] == "periodic":
            tol = 1e-12 * max(max(abs(h) for h in heights), 1e-300)
            if abs(heights[-1] - heights[0]) > tol:
                raise SceneError(f"effects.roughness.profile_file {profile!r}: a periodic "
                                 "profile (profile_extension = 'periodic') needs equal first "
                                 f"and last heights [m]; got {heights[0]:g} and "
                                 f"{heights[-1]:g} (or set profile_extension = 'hold')")
        out.update(profile_file=profile, profile_positions=positions, profile_heights=heights,
                   wavelengths=[], amplitudes_cos=[], amplitudes_sin=[])
        return out
    if not (len(waves) == len(za) == len(zb)) or not waves:
        raise SceneError("effects.roughness.wavelengths, amplitudes_cos and amplitudes_sin must "
                         "be non-empty lists of equal length [m] (or give "
                         f"effects.roughness.profile_file); got {len(waves)}, {len(za)}, "
                         f"{len(zb)}")
    out.update(profile_file="", wavelengths=waves, amplitudes_cos=za, amplitudes_sin=zb)
    return out


def scene_from_dict(data, base_dir=None):
    """Validate a scene given as nested dicts (the parsed TOML), filling defaults.

    Missing sections and keys take the values of :data:`DEFAULT_SCENE`; the creep effect is on
    unless ``effects.creep.enabled = false``; other effects are on when their table is present
    (and ``enabled`` is not false). ``base_dir``: directory relative file names in the scene
    (``effects.corrugation.surface_file``) are resolved against (default: the working
    directory).
    """
    if not isinstance(data, dict):
        raise SceneError(f"scene must be a table; got {data!r}")
    allowed_sections = set(_SECTION_KEYS) | {"effects", "inputs"}
    _check_keys("scene", data, allowed_sections)
    for section, keys in _SECTION_KEYS.items():
        if section in data:
            _check_keys(section, data[section], keys)
    effects_in = data.get("effects", {})
    _check_keys("effects", effects_in, set(EFFECTS))
    for name, opts in effects_in.items():
        _check_keys(f"effects.{name}", opts, EFFECTS[name].keys)
    merged = _merge(DEFAULT_SCENE, data)

    meta = merged["scene"]
    for key in ("name", "description"):
        if not isinstance(meta[key], str):
            raise SceneError(f"scene.{key} must be a string; got {meta[key]!r}")
    mat = merged["material"]
    youngs = _number("material.youngs_modulus", mat["youngs_modulus"], "Pa", 0.0, None,
                     lower_closed=False)
    nu = _number("material.poisson_ratio", mat["poisson_ratio"], "-", 0.0, 0.5,
                 upper_closed=False)

    geo = merged["geometry"]
    kind = _choice("geometry.kind", geo["kind"], ("curvatures", "semi_axes", "line"))
    if kind == "line":
        geometry = {"kind": kind,
                    "radius": _number("geometry.radius", geo["radius"], "m", 0.0, None,
                                      lower_closed=False),
                    "contact_width": _number("geometry.contact_width", geo["contact_width"],
                                             "m", 0.0, None, lower_closed=False)}
    elif kind == "curvatures":
        geometry = {"kind": kind,
                    "curvature_longitudinal": _number(
                        "geometry.curvature_longitudinal", geo["curvature_longitudinal"],
                        "1/m", 0.0, None, lower_closed=False),
                    "curvature_lateral": _number(
                        "geometry.curvature_lateral", geo["curvature_lateral"], "1/m", 0.0,
                        None, lower_closed=False)}
    else:
        geometry = {"kind": kind,
                    "semi_axis_longitudinal": _number(
                        "geometry.semi_axis_longitudinal", geo["semi_axis_longitudinal"], "m",
                        0.0, None, lower_closed=False),
                    "semi_axis_lateral": _number(
                        "geometry.semi_axis_lateral", geo["semi_axis_lateral"], "m", 0.0,
                        None, lower_closed=False)}
    mu = _number("friction.friction_coefficient", merged["friction"]["friction_coefficient"],
                 "-", 0.0, None)

    effects = {}
    for name in EFFECTS:                      # (the registry's order: Scene.effects keeps it)
        if name not in merged["effects"]:
            continue
        opts = merged["effects"][name]
        enabled = _boolean(f"effects.{name}.enabled", opts.get("enabled", True))
        if not enabled:
            continue
        opts = dict(opts)
        opts["enabled"] = True
        # the exact theory comes from its table; every other method's default source is
        # the closed form (a scene that names only a method gets that method's usual source)
        source = opts.get("source", "analytic")
        if name == "creep" and "source" not in data.get("effects", {}).get("creep", {}):
            source = "table" if opts.get("method") == "exact" else "analytic"
        opts["source"] = _choice(f"effects.{name}.source", source, SOURCES)
        if name == "creep":
            opts["method"] = _choice("effects.creep.method", opts.get("method"),
                                     CREEP_METHODS)
            opts["spin"] = _boolean("effects.creep.spin", opts.get("spin", True))
            if opts["method"] == "exact":
                if opts["source"] != "table":
                    raise SceneError("effects.creep.source must be 'table' with method = "
                                     "'exact' (Kalker's exact theory is shipped as the table "
                                     "creep_exact; the discretised solver is far too slow for a "
                                     f"co-simulation step); got {opts['source']!r}")
                if "table" not in data.get("effects", {}).get("creep", {}):
                    opts["table"] = "creep_exact"
            if not isinstance(opts.get("table"), str):
                raise SceneError(f"effects.creep.table must be a string; got "
                                 f"{opts['table']!r}")
            if opts["source"] == "table":
                _check_table_exists("effects.creep.table", opts["table"])
            _check_polach_keys(opts)
            _check_creep_friction_law(opts)
        elif name == "corrugation":
            opts["method"] = _choice("effects.corrugation.method", opts.get("method", "exact"),
                                     ("exact", "linear"))
            if opts.get("surface_file"):
                opts.update(_read_surface_file(opts["surface_file"], base_dir))
            waves = _number_list("effects.corrugation.wavelengths", opts.get("wavelengths"),
                                 "m", 0.0, lower_closed=False)
            za = _number_list("effects.corrugation.amplitudes_cos",
                              opts.get("amplitudes_cos", [0.0] * len(waves)), "m")
            zb = _number_list("effects.corrugation.amplitudes_sin",
                              opts.get("amplitudes_sin", [0.0] * len(waves)), "m")
            if not (len(waves) == len(za) == len(zb)) or not waves:
                raise SceneError("effects.corrugation.wavelengths, amplitudes_cos and "
                                 "amplitudes_sin must be non-empty lists of equal length [m]; "
                                 f"got {len(waves)}, {len(za)}, {len(zb)}")
            opts.update(wavelengths=waves, amplitudes_cos=za, amplitudes_sin=zb)
        elif name == "velocity_friction":
            opts["law"] = _choice("effects.velocity_friction.law", opts.get("law", "smooth"),
                                  ("step", "smooth"))
            opts["kinetic_friction_coefficient"] = _number(
                "effects.velocity_friction.kinetic_friction_coefficient",
                opts.get("kinetic_friction_coefficient"), "-", 0.0)
            if opts["law"] == "smooth":
                opts["kappa"] = _number("effects.velocity_friction.kappa", opts.get("kappa"),
                                        "-", 0.0)
            opts["series_degree"] = _integer("effects.velocity_friction.series_degree",
                                             opts.get("series_degree", FRICTION_SERIES_DEGREE),
                                             "-", 8, 2048)
            opts["tolerance"] = _number("effects.velocity_friction.tolerance",
                                        opts.get("tolerance", FRICTION_TOLERANCE), "-", 0.0,
                                        1e-2, lower_closed=False)
        elif name == "wear":
            opts["wear_coefficient"] = _number("effects.wear.wear_coefficient",
                                               opts.get("wear_coefficient"), "m^2/N", 0.0)
            opts["wear_model"] = _choice("effects.wear.wear_model",
                                         opts.get("wear_model", "material_point"), WEAR_MODELS)
            opts["evolve"] = _boolean("effects.wear.evolve", opts.get("evolve", False))
            if opts["evolve"]:
                opts["section_length"] = _number("effects.wear.section_length",
                                                 opts.get("section_length"), "m", 0.0,
                                                 lower_closed=False)
        elif name == "roughness":
            opts.update(_roughness_options(opts, base_dir))
        elif name == "nonsteady":
            _nonsteady_options(opts)
        effects[name] = opts
    line = geometry["kind"] == "line"
    if "creep" in effects and (effects["creep"]["method"] == "carter") != line:
        raise SceneError("effects.creep.method must be 'carter' exactly when geometry.kind = "
                         "'line' (Carter's theory is the 2-D one); got method "
                         f"{effects['creep']['method']!r} with geometry.kind {geometry['kind']!r}")
    if "velocity_friction" in effects and any(e in effects for e in ("corrugation", "wear")):
        raise SceneError("effects.velocity_friction cannot be combined with corrugation or wear "
                         "(Nielsen's Ch. 4 models assume Coulomb friction)")
    if "velocity_friction" in effects and "creep" not in effects:
        raise SceneError("effects.creep.enabled must be true when velocity_friction is on")
    for name in ("corrugation", "wear", "velocity_friction"):
        if name in effects and not line:
            raise SceneError(f"effects.{name} needs geometry.kind = 'line' (Nielsen's Ch. 4 "
                             f"theory is 2-D); got {geometry['kind']!r}")
    _check_table_sources(effects, data)
    if "wear" in effects and effects["wear"]["evolve"] and "corrugation" not in effects:
        raise SceneError("effects.wear.evolve = true needs effects.corrugation (the surface "
                         "that evolves)")
    if "nonsteady" in effects and any(e in effects for e in ("corrugation", "wear")):
        raise SceneError("effects.nonsteady cannot be combined with corrugation or wear "
                         "(their Ch. 4 models are quasi-static: the corrugated contact and the "
                         "wear per passage assume steady rolling at the input creepage)")
    if "creep" not in effects and any(e in effects for e in ("nonsteady", "wear",
                                                             "corrugation")):
        raise SceneError("effects.creep.enabled must be true when corrugation, nonsteady or "
                         "wear is on (they act on the creep solution)")

    if "roughness" in effects:
        _check_roughness_combination(effects, geometry)

    sim = merged["simulation"]
    start = _number("simulation.start_time", sim["start_time"], "s")
    stop = _number("simulation.stop_time", sim["stop_time"], "s", start, None,
                   lower_closed=False)
    step = _number("simulation.step_size", sim["step_size"], "s", 0.0, stop - start,
                   lower_closed=False)
    n_steps = (stop - start) / step
    if abs(n_steps - round(n_steps)) > 1e-9 * max(1.0, n_steps):
        raise SceneError(f"simulation.step_size must divide stop_time - start_time [s]; "
                         f"got {step:g} for an interval of {stop - start:g}")

    inputs = {}
    ins = merged["inputs"]
    _check_keys("inputs", ins, set(INPUTS))
    for name, spec in ins.items():
        inputs[name] = _validate_signal(f"inputs.{name}", name, spec)

    return Scene(name=meta["name"], description=meta["description"], youngs_modulus=youngs,
                 poisson_ratio=nu, geometry=geometry, friction_coefficient=mu,
                 effects=effects, simulation={"start_time": start, "stop_time": stop,
                                              "step_size": step},
                 inputs=inputs)


def _check_roughness_combination(effects, geometry):
    """The rough-rail effect (Ch. 6 asperity model) is a line-contact effect that replaces
    Carter's force; the Ch. 4 surface models and the Ch. 5/7 force models are not combined
    with it."""
    if geometry["kind"] != "line":
        raise SceneError("effects.roughness needs geometry.kind = 'line' (Nielsen's Ch. 6 "
                         f"asperity model is 2-D); got {geometry['kind']!r}")
    if "creep" not in effects:
        raise SceneError("effects.creep.enabled must be true when roughness is on (the rough "
                         "contact replaces Carter's force)")
    for other, why in (("corrugation", "both describe the rail surface; put the harmonics in "
                                       "effects.roughness"),
                       ("wear", "the wear models of Ch. 4 are linearised about a smooth or "
                                "corrugated contact, not the rough-rail asperity model"),
                       ("velocity_friction", "the Ch. 6 asperity solution assumes Coulomb "
                                             "friction"),
                       ("nonsteady", "the non-steady correction acts on the smooth contact")):
        if other in effects:
            raise SceneError(f"effects.roughness cannot be combined with effects.{other} "
                             f"({why})")
def _check_creep_friction_law(opts):
    """``friction_law`` of [effects.creep]: "smooth" needs method = "exact" (the table's
    falling-friction fast path) and its two parameters; "coulomb" takes neither."""
    law = _choice("effects.creep.friction_law", opts.get("friction_law", "coulomb"),
                  CREEP_FRICTION_LAWS)
    if law == "coulomb":
        extra = [k for k in CREEP_FRICTION_LAW_KEYS[1:] if k in opts]
        if extra:
            raise SceneError(f"effects.creep.{extra[0]} applies to friction_law = 'smooth' "
                             f"only; got it with friction_law = 'coulomb'")
        opts.pop("friction_law", None)      # (Coulomb: the scene dict as before)
        return
    opts["friction_law"] = law
    if opts["method"] != "exact":
        raise SceneError(f"effects.creep.friction_law = 'smooth' needs method = 'exact' (the "
                         f"exact table's falling-friction path; FASTSIM and the exact solver "
                         f"take a law through the Python API only); got method "
                         f"{opts['method']!r}")
    opts["kinetic_friction_coefficient"] = _number(
        "effects.creep.kinetic_friction_coefficient",
        opts.get("kinetic_friction_coefficient"), "-", 0.0)
    opts["kappa"] = _number("effects.creep.kappa", opts.get("kappa"), "-", 0.0)


def _check_polach_keys(opts):
    """Polach's falling friction and reduction factors: ranges, k_S <= k_A (Polach 2005), only
    with method = "polach" (a non-default value with another method is a SceneError)."""
    for key, (_, unit, lower, upper, lower_closed, default) in POLACH_KEYS.items():
        value = _number(f"effects.creep.{key}", opts.get(key, default), unit, lower, upper,
                        lower_closed=lower_closed)
        if opts["method"] != "polach":
            if value != default:
                raise SceneError(f"effects.creep.{key} applies to method = 'polach' only; got "
                                 f"{value:g} with method {opts['method']!r}")
            opts.pop(key, None)          # (the FMU passes every parameter at its start value)
        else:
            opts[key] = value
    if opts["method"] == "polach" and (opts["polach_reduction_slip"]
                                       > opts["polach_reduction_adhesion"]):
        raise SceneError("effects.creep.polach_reduction_slip must be <= "
                         "effects.creep.polach_reduction_adhesion (k_S <= k_A, Polach 2005); "
                         f"got {opts['polach_reduction_slip']:g} > "
                         f"{opts['polach_reduction_adhesion']:g}")


def _check_table_sources(effects, data):
    """The method/source combinations the shipped tables allow (see "Table sources" in the
    module docstring); SceneError naming the dotted key otherwise."""
    corr, wear, vf = (effects.get(n) for n in ("corrugation", "wear", "velocity_friction"))
    if corr and corr["source"] == "table":
        if corr["method"] != "linear":
            raise SceneError("effects.corrugation.method must be 'linear' with source = "
                             "'table' (the table corrugation_response holds the linearised "
                             "theory; the exact nonlinear contact has no table source, use "
                             f"source = 'analytic'); got {corr['method']!r}")
        if wear and wear["wear_model"] != "material_point":
            raise SceneError("effects.wear.wear_model must be 'material_point' with "
                             "effects.corrugation.source = 'table' (the table "
                             "corrugation_response holds that wear model only); got "
                             f"{wear['wear_model']!r}")
    if wear and wear["source"] == "table" and wear["wear_model"] != "material_point":
        raise SceneError("effects.wear.wear_model must be 'material_point' with "
                         "effects.wear.source = 'table' (the table corrugation_response holds "
                         f"that wear model only); got {wear['wear_model']!r}")
    if vf and vf["source"] == "table":
        if vf["law"] != "smooth":
            raise SceneError("effects.velocity_friction.source must be 'analytic' with law = "
                             "'step' (the step law is a closed form; the table "
                             "velocity_friction holds the smooth law (5.16)); got 'table'")
        given = data.get("effects", {}).get("velocity_friction", {})
        for key, default in (("series_degree", FRICTION_SERIES_DEGREE),
                             ("tolerance", FRICTION_TOLERANCE)):
            if key in given and vf[key] != default:
                raise SceneError(f"effects.velocity_friction.{key} has no effect with source = "
                                 f"'table' (the table was built with the defaults degree "
                                 f"{FRICTION_SERIES_DEGREE}, tolerance {FRICTION_TOLERANCE:g}); "
                                 f"got {vf[key]!r}: remove it or use source = 'analytic'")


def _nonsteady_options(opts):
    """Validate ``[effects.nonsteady]`` in place (see :class:`railcontact.effects.NonSteady`)."""
    if opts["source"] != "analytic":
        raise SceneError("effects.nonsteady.source must be 'analytic': the relaxation length "
                         "sigma = a0* (Lambda(r_a0) - 1) is a closed form, and the shipped table "
                         "nonsteady_transfer holds the frequency response H(a0/L, r_a0), which a "
                         "time step cannot use (a co-simulation input has no single wave length "
                         f"L); got {opts['source']!r}")
    opts["pseudo_width_ratio"] = _number("effects.nonsteady.pseudo_width_ratio",
                                         opts.get("pseudo_width_ratio", 20.0), "-", 2.0, None)
    opts["model"] = _choice("effects.nonsteady.model", opts.get("model", "carter"),
                            NONSTEADY_MODELS)


_SIGNAL_KEYS = {
    "constant": {"kind", "value"},
    "ramp": {"kind", "start_value", "end_value", "start_time", "end_time"},
    "sine": {"kind", "mean", "amplitude", "frequency", "phase"},
    "points": {"kind", "time", "value"},
    "travel": {"kind", "start_value"},
}


def _validate_signal(path, name, spec):
    unit = INPUTS[name][0]
    if not isinstance(spec, dict):
        return _number(path, spec, unit)
    kind = _choice(f"{path}.kind", spec.get("kind"), _SIGNAL_KINDS)
    _check_keys(path, spec, _SIGNAL_KEYS[kind])
    out = {"kind": kind}
    if kind == "constant":
        out["value"] = _number(f"{path}.value", spec.get("value"), unit)
    elif kind == "ramp":
        for key in ("start_value", "end_value"):
            out[key] = _number(f"{path}.{key}", spec.get(key), unit)
        for key in ("start_time", "end_time"):
            if key in spec:
                out[key] = _number(f"{path}.{key}", spec[key], "s")
        if "start_time" in out and "end_time" in out and out["end_time"] <= out["start_time"]:
            raise SceneError(f"{path}.end_time must be > start_time [s]; got "
                             f"{out['end_time']:g}")
    elif kind == "sine":
        out["mean"] = _number(f"{path}.mean", spec.get("mean", 0.0), unit)
        out["amplitude"] = _number(f"{path}.amplitude", spec.get("amplitude"), unit)
        out["frequency"] = _number(f"{path}.frequency", spec.get("frequency"), "Hz", 0.0)
        out["phase"] = _number(f"{path}.phase", spec.get("phase", 0.0), "rad")
    elif kind == "points":
        try:
            t = check_range(f"{path}.time", spec.get("time"), "s")
            v = check_range(f"{path}.value", spec.get("value"), unit)
        except ValueError as exc:
            raise SceneError(str(exc)) from None
        if t.ndim != 1 or t.shape != v.shape or t.size < 2:
            raise SceneError(f"{path}.time and {path}.value must be lists of equal length >= 2")
        if np.any(np.diff(t) <= 0):
            raise SceneError(f"{path}.time must be strictly increasing [s]")
        out["time"], out["value"] = t.tolist(), v.tolist()
    else:  # travel
        if name != "rail_position":
            raise SceneError(f"{path}.kind = 'travel' is only allowed for rail_position")
        out["start_value"] = _number(f"{path}.start_value", spec.get("start_value", 0.0), unit)
    return out


def _evaluate_signal(spec, t, simulation):
    if not isinstance(spec, dict):
        return np.full(t.shape, float(spec))
    kind = spec["kind"]
    if kind == "constant":
        return np.full(t.shape, spec["value"])
    if kind == "ramp":
        t0 = spec.get("start_time", simulation["start_time"])
        t1 = spec.get("end_time", simulation["stop_time"])
        return np.interp(t, [t0, t1], [spec["start_value"], spec["end_value"]])
    if kind == "sine":
        return spec["mean"] + spec["amplitude"] * np.sin(
            2.0 * math.pi * spec["frequency"] * t + spec["phase"])
    return np.interp(t, spec["time"], spec["value"])
