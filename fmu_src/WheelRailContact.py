r"""WheelRailContact: FMI 2.0 co-simulation slave (PythonFMU) for one wheel/rail contact.

Thin by design: it registers the variables, reads the scene (TOML file or text, or its own
parameters), builds the effects the scene switches on (:mod:`railcontact.effects`) in
``exit_initialization_mode`` and calls them in ``do_step``. All physics is in ``railcontact``.

Build with ``python build_fmu.py`` (:mod:`railcontact.fmu_build`: it bundles a uniquely named
copy of ``railcontact``, the tables and the scenes, and points the ``railcontact`` imports
below, like those inside the package, at the bundled name).

Semantics of a step: the outputs at the end of ``doStep(t, h)`` are the contact solution for
the inputs set before the step (sample and hold); the outputs after initialisation are the
solution for the start values of the inputs.

Geometry and friction are inputs (:data:`railcontact.fmu_parameters.RUNTIME_INPUTS`): set
before initialisation they override the scene like a parameter, after it they act from the
next step. Every other parameter is fixed: a set after initialisation is refused (an error
status and a message naming it).

Errors: PythonFMU (0.7) turns any Python exception into the status fmi2Fatal (fmi2Error is not
reachable from Python). An invalid parameter makes ``fmi2ExitInitializationMode`` fail, an
invalid input (NaN, inf, negative normal force, speed or friction coefficient, curvature or
semi-axis <= 0) or step size (negative, NaN or inf) makes ``fmi2DoStep`` fail, a fixed
parameter set after initialisation makes ``fmi2Set*`` fail. In each case an error message
naming the scene, parameter, input (and, for a vehicle FMU, the contact) or step size is
logged first through the FMI logger, and also written to the host process's standard error:
PythonFMU 0.7 forwards log messages only when the importer turned debug logging on
(``loggingOn``), and importers leave it off by default (fmpy's ``simulate_fmu``, libcosim), so
without the second copy the user would read only "status 4 (fatal)". No NaN is ever returned.
"""

import ctypes
import json
import math
import operator
import os
from functools import partial
import sys
from pathlib import Path
from xml.etree.ElementTree import Element, SubElement

from pythonfmu import Boolean, DefaultExperiment, Fmi2Causality, Fmi2Slave, Fmi2Variability
from pythonfmu import Integer, Real, String
from pythonfmu.enums import Fmi2Initial, Fmi2Status

#: Number of contacts one instance serves (``build_fmu.py --contacts K`` writes K here; 1: the
#: variables carry their plain names, else ``name[k]``, k = 1..K, FMI 2.0 structured naming).
CONTACTS = 1

# (railcontact.fmu_build rewrites these two imports to the bundled copy's unique name)
import railcontact as _rc
from railcontact import effects as _effects, fmu_parameters as _parameters, scene as _scene

_PACKAGE = _rc.__name__   # "railcontact", or the bundled copy's name inside the FMU

#: Outputs: name -> (unit, description, ContactPoint field).
OUTPUTS = {
    "Fx": ("N", "Longitudinal tangential contact force on the wheel, positive along +x (the "
                "rolling direction); it opposes the longitudinal creepage; |(Fx, Fy)| <= mu N",
           "Fx"),
    "Fy": ("N", "Lateral tangential contact force on the wheel, positive along +y; it "
                "opposes the lateral creepage (0 for a line contact: Carter's theory is 2-D)",
           "Fy"),
    "Mz": ("N.m", "Spin moment on the wheel about the contact normal +z at the contact "
                  "centre (right-handed: x rolling, y lateral): Kalker's exact theory "
                  "(creep_method = 'exact', table) only; 0 for the other methods, which give "
                  "none", "Mz"),
    "a0": ("m", "Hertz semi-axis in the rolling direction (line contact: Hertz half-width)",
           "a0"),
    "b0": ("m", "Hertz lateral semi-axis (line contact: half the contact width)", "b0"),
    "p0": ("Pa", "Maximum Hertz pressure: 3 N / (2 pi a0 b0) for an ellipse, 2-D Hertz "
                 "(Eq. (2.40)) for a line contact", "p0"),
    "stick_area_fraction": ("1", "Stick area over contact area (1 = full stick, 0 = full "
                                 "slip): strip-theory estimate; a*/a0 for a line contact",
                            "stick_area_fraction"),
    "stick_width_ratio": ("1", "Lateral extent of the stick zone b*/b0 = sqrt(1 - z^2) (Nielsen "
                               "Eq. (2.84)); line contact: 1 while a stick zone exists",
                          "stick_width_ratio"),
    "r_a0": ("1", "Stick zone length over contact length, a*/a0: centre line of the 3-D strip "
                  "theories 1 - min(z, 1) (Nielsen Eq. (2.83)), Carter's ratio (2.51) for a "
                  "line contact; 1 = full stick", "r_a0"),
    "contact_half_width": ("m", "Actual contact half-length along the rail: a0, or the "
                                "corrugated contact's a (Nielsen Ch. 4.2), or the rough "
                                "contact's a (Table 6.1; 0 without contact)",
                           "contact_half_width"),
    "patch_shift": ("m", "Shift Delta of the patch centre from the wheel axis along x (the "
                         "rolling direction, Nielsen Ch. 4 sign) on a corrugated "
                         "rail (0 on a smooth rail); on a rough rail the gap minimum's shift "
                         "plus the asperity shift Delta of Table 6.1", "patch_shift"),
    "wear_depth_per_passage": ("m", "Wear depth per wheel passage at the rail point under the "
                                    "contact (Nielsen Eqs. (4.74), (4.94), (4.96)); 0 unless the "
                                    "wear effect is on", "wear_depth_per_passage"),
    "corrugation_amplitude": ("m", "Amplitude |Z| of the first corrugation harmonic of the rail "
                                   "surface (evolves with wear when wear_evolve); 0 without "
                                   "corrugation", "corrugation_amplitude"),
    "corrugation_growth_rate": ("1", "Relative change of the first harmonic's amplitude per "
                                     "passage under the current contact, |1 - W1 - i W2| - 1 "
                                     "(Eqs. (4.103)-(4.104)); < 0 levels, > 0 amplifies; 0 "
                                     "unless corrugation and wear are on",
                                "corrugation_growth_rate"),
    "friction_iteration_residual": ("1", "Final residual of the smooth friction law's iteration "
                                         "(Sec. 5.3): max |mu(s)/mu_0 - mu(x)/mu_0| at the "
                                         "nodes, below friction_tolerance once converged; -1 = "
                                         "no iteration (velocity friction off, step law (closed "
                                         "form) or no contact)",
                                    "friction_iteration_residual"),
    "corrugation_series_error_estimate": (
        "1", "Truncation error of the Chebyshev-Bessel series of the contact distributions "
             "(Nielsen (4.18), (4.27)-(4.28)) that the linearised wear coefficients sum (wear "
             "on, wear_model material_point or patch_coordinate), at its automatic degree "
             "ceil(e k a0) + 12, worst harmonic: neglected |J_n(k a0)| relative to the largest. "
             "-1 = no truncated series in use (the corrugated contact itself is closed-form; "
             "wear off, time-domain wear models, or no contact)",
        "corrugation_series_error_estimate"),
    # non-steady correction (railcontact.effects.NonSteady)
    "relaxation_length": ("m", "Relaxation length sigma = a0* (Lambda(r_a0) - 1) of the "
                               "non-steady correction at the relaxed state (Nielsen Ch. 7, "
                               "low-frequency limit of Eqs. (7.53)-(7.54)); the force follows a "
                               "creepage change over about this rolled distance. 0 = no "
                               "relaxation (nonsteady off, full sliding or no contact)",
                          "relaxation_length"),
    "relaxed_creepage_longitudinal": ("1", "Relaxed longitudinal creepage xi_e the creep forces "
                                           "are computed from: (sigma/V) d xi_e/dt + xi_e = xi "
                                           "(nonsteady on); 0 unless nonsteady is on",
                                      "relaxed_creepage_longitudinal"),
    "relaxed_creepage_lateral": ("1", "Relaxed lateral creepage (nonsteady on; equals the input "
                                      "for a line contact, which relaxes only xi_x); 0 unless "
                                      "nonsteady is on", "relaxed_creepage_lateral"),
    "relaxed_spin": ("1/m", "Relaxed spin creepage (nonsteady on, elliptic contact; equals the "
                            "input for a line contact); 0 unless nonsteady is on",
                     "relaxed_spin"),
    # rough rail (roughness effect, Nielsen Ch. 6)
    "gap_curvature": ("1/m", "Rough rail: curvature lambda2 = 1/R - d2r/dX2 of the local gap at "
                             "its minimum (Eq. (6.1); r = rail roughness height); 0 unless "
                             "roughness is on", "gap_curvature"),
    "gap_skewness": ("1/m2", "Rough rail: skewness lambda3 = -d3r/dX3 of the local gap at its "
                             "minimum (Eq. (6.1)); 0 unless roughness is on", "gap_skewness"),
    "gap_flatness": ("1/m3", "Rough rail: flatness lambda4 = -d4r/dX4 of the local gap at its "
                             "minimum (Eq. (6.1)); 0 unless roughness is on", "gap_flatness"),
    "critical_creepage": ("1", "Rough rail: creepage magnitude at which the contact reaches "
                               "full slip (Eq. (6.40), with its factor mu); 0 unless roughness "
                               "is on, and without contact", "critical_creepage"),
    "creep_table_error_estimate": ("1", "Accuracy of the creep table in use: its recorded max "
                                        "error of |(Fx, Fy)| / (mu N) against the direct "
                                        "solution of the theory it holds (file attributes "
                                        "max_abs_error, read at initialisation; creep_exact: "
                                        "hypot of the two force components' errors, against the "
                                        "discretised solver). -1 = not estimated: analytic "
                                        "source (no interpolation error; the theory's own error "
                                        "against Kalker's exact theory is not estimated), creep "
                                        "off, or a step outside the exact table",
                                   "creep_table_error_estimate"),
    "friction_table_error_estimate": ("1", "Accuracy of the velocity-friction table in use "
                                           "(velocity_friction_source = 'table'): its recorded "
                                           "max error of |Fx| / (mu_0 N) against the direct "
                                           "Sec. 5.3 solution it holds (file attribute "
                                           "max_abs_error). -1 = not estimated: analytic "
                                           "source, velocity friction off, no contact, or a "
                                           "step outside the table (analytic there)",
                                      "friction_table_error_estimate"),
}

#: Boolean outputs: name -> (description, ContactPoint field).
BOOLEAN_OUTPUTS = {
    "creep_within_validity": ("False when the creep theory is used outside its range: spin "
                              "pole inside the contact (spin coefficient > 1, Eq. (2.98)); for "
                              "the linear theory also |T| > mu N; for a line contact any "
                              "lateral creepage or spin (ignored by the 2-D theory)",
                              "creep_within_validity"),
}

#: Bounds and scales the physics gives: name -> {"min", "max", "nominal"} (written into the
#: modelDescription; FMI bounds are inclusive, so a strict "> 0" is declared as min = 0).
#: Nominal values are typical magnitudes of a wheel/rail contact (for importers' error norms).
LIMITS = {
    # parameters
    "youngs_modulus": {"min": 0.0, "nominal": 2.1e11},
    "poisson_ratio": {"min": 0.0, "max": 0.5, "nominal": 0.3},
    "curvature_longitudinal": {"min": 0.0, "nominal": 1.0},
    "curvature_lateral": {"min": 0.0, "nominal": 1.0},
    "semi_axis_longitudinal": {"min": 0.0, "nominal": 5e-3},
    "semi_axis_lateral": {"min": 0.0, "nominal": 5e-3},
    "radius": {"min": 0.0, "nominal": 0.3},
    "contact_width": {"min": 0.0, "nominal": 0.02},
    "friction_coefficient": {"min": 0.0, "nominal": 0.3},
    "kinetic_friction_coefficient": {"min": 0.0, "nominal": 0.2},
    "friction_kappa": {"min": 0.0},
    "friction_series_degree": {"min": 8, "max": 2048},
    "friction_tolerance": {"min": 0.0, "max": 1e-2},
    "wear_coefficient": {"min": 0.0},
    "wear_section_length": {"min": 0.0, "nominal": 1.0},
    "nonsteady_pseudo_width_ratio": {"min": 2.0, "nominal": 20.0},
    # inputs
    "normal_force": {"min": 0.0, "nominal": 1e5},
    "creepage_longitudinal": {"nominal": 1e-3},
    "creepage_lateral": {"nominal": 1e-3},
    "spin": {"nominal": 0.1},
    "rolling_speed": {"min": 0.0, "nominal": 30.0},
    # outputs
    "Fx": {"nominal": 1e4},
    "Fy": {"nominal": 1e4},
    "a0": {"min": 0.0, "nominal": 5e-3},
    "b0": {"min": 0.0, "nominal": 5e-3},
    "p0": {"min": 0.0, "nominal": 1e9},
    "stick_area_fraction": {"min": 0.0, "max": 1.0},
    "stick_width_ratio": {"min": 0.0, "max": 1.0},
    "r_a0": {"min": 0.0, "max": 1.0},
    "contact_half_width": {"min": 0.0, "nominal": 5e-3},
    "corrugation_amplitude": {"min": 0.0},
    "corrugation_growth_rate": {"min": -1.0},
    "friction_iteration_residual": {"min": -1.0},
    "corrugation_series_error_estimate": {"min": -1.0},
    "relaxation_length": {"min": 0.0},
    "critical_creepage": {"min": 0.0},
    "creep_table_error_estimate": {"min": -1.0},
    "friction_table_error_estimate": {"min": -1.0},
}

#: Jacobian outputs d(Fx, Fy, Mz)/d(xi_x, xi_y, phi) (railcontact.effects.JACOBIAN_FIELDS).
for _f, _fu in (("Fx", "N"), ("Fy", "N"), ("Mz", "N.m")):
    for _v, _vn, _per_m in (("xi_x", "longitudinal creepage xi_x", False),
                            ("xi_y", "lateral creepage xi_y", False), ("phi", "spin phi", True)):
        OUTPUTS[f"d{_f}_d{_v}"] = (
            {"N": "N.m", "N.m": "N.m2"}[_fu] if _per_m else _fu,
            f"Derivative of {_f} with respect to the {_vn}, from the spline of the exact-theory "
            "table (creep_method = 'exact', source table; with a friction law, central "
            "differences of its fast path, computed when read; 0 for the other methods): the "
            "creep-force Jacobian for implicit integrators", f"d{_f}_d{_v}")


def _described(description, unit):
    """The description with its unit in brackets (``[1]`` = dimensionless)."""
    return f"{description} [{unit}]" if unit else description


#: Outputs an effect may compute only when read (see railcontact.effects.Creep3D).
_LAZY = {"stick_area_fraction", "stick_width_ratio", "r_a0", "creep_within_validity",
         "corrugation_growth_rate", "Mz", "corrugation_series_error_estimate"}
#: The Jacobian outputs, which an effect may also compute only when read (falling friction:
#: by differences of its fast path, railcontact.effects.Creep3D.jacobian); apart from _LAZY, so
#: that reading the stick outputs does not pay for them.
_JACOBIAN = frozenset(_effects.JACOBIAN_FIELDS)

def _contact_names(pairs):
    """``(names, expressions)`` for generated code over (contact, field) pairs: ``{"c0": contact,
    ...}`` and ``["c0.Fx", ...]`` (the fields are ContactPoint slot names)."""
    names, index, expressions = {}, {}, []
    for c, field in pairs:
        i = index.setdefault(id(c), len(index))
        names[f"c{i}"] = c
        expressions.append(f"c{i}.{field}")
    return names, expressions


def _assigner(pairs):
    """``assign(values)`` setting the (contact, field) ``pairs`` to ``values`` (same length) in
    one statement: a vehicle sets its K x 11 inputs at every step, and one unpacking
    assignment of slots costs a tenth of a loop of setattr calls."""
    names, targets = _contact_names(pairs)
    namespace = dict(names)
    exec(f"def assign(values):\n    {', '.join(targets)}, = values\n", namespace)  # noqa: S102
    return namespace["assign"]


def _reader(pairs):
    """``read()``: the list of the (contact, field) ``pairs``' values (see :func:`_assigner`)."""
    names, sources = _contact_names(pairs)
    namespace = dict(names)
    exec(f"def read():\n    return [{', '.join(sources)}]\n", namespace)  # noqa: S102
    return namespace["read"]


def _no_auxiliary(contact):
    """Before initialisation: no effect computes anything on demand."""


def _on_demand(fields):
    """``(lazy, jacobian)``: whether ``fields`` name an output of :data:`_LAZY` and one of
    :data:`_JACOBIAN`."""
    return any(f in _LAZY for f in fields), any(f in _JACOBIAN for f in fields)


def _name(name, k):
    """The FMI name of variable ``name`` of contact ``k`` (0-based): the plain name for a
    single contact, ``name[k + 1]`` (FMI 2.0 structured naming) for a vehicle."""
    return name if CONTACTS == 1 else f"{name}[{k + 1}]"


#: SI units used by the variables: name -> exponents of kg, m, s.
UNITS = {
    "1": {}, "N": {"kg": 1, "m": 1, "s": -2}, "m": {"m": 1}, "Pa": {"kg": 1, "m": -1, "s": -2},
    "1/m": {"m": -1}, "m/s": {"m": 1, "s": -1}, "N.m": {"kg": 1, "m": 2, "s": -2},
    "s": {"s": 1}, "m2/N": {"kg": -1, "m": 1, "s": 2}, "s/m": {"m": -1, "s": 1},
    "N.m2": {"kg": 1, "m": 3, "s": -2},
    "1/m2": {"m": -2}, "1/m3": {"m": -3},
}

_SCENE_PARAMETERS = (
    ("scene_file", "Scene TOML file (path, or the name of a scene bundled in the FMU such as "
                   "'creep_only_table'); empty: the scene is given by the parameters below"),
    ("scene_toml", "Scene TOML text (used if scene_file is empty); empty: the parameters below "
                   "define the scene"),
)


class WheelRailContact(Fmi2Slave):
    """Wheel/rail rolling contacts (one, or CONTACTS of one vehicle): normal force, creepages,
    geometry and friction in, creep forces out."""

    author = "railcontact contributors"
    description = ("Wheel/rail rolling contact after J.B. Nielsen (1998): Hertz normal "
                   "contact, 3-D creep forces (analytic or tables) and the effects a scene "
                   "switches on")
    license = "MIT"

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self._bundle_dir = _repoint_bundle(self.resources)
        _release_interpreter_guard_at_exit(self.resources, "instantiated")
        self.version = getattr(_rc, "__version__", "unknown")
        self.default_experiment = DefaultExperiment(start_time=0.0, stop_time=1.0,
                                                    step_size=1e-3)
        if not (isinstance(CONTACTS, int) and 1 <= CONTACTS <= _effects.MAX_CONTACTS):
            raise ValueError(f"CONTACTS must be an integer in [1, {_effects.MAX_CONTACTS}]; "
                             f"got {CONTACTS!r}")
        self._units = {}
        self._contacts = [_effects.ContactPoint() for _ in range(CONTACTS)]
        self._contact = self._contacts[0]
        self._pipeline = None
        self._vehicle = None
        self._steps = ()
        self._checked_step = _effects.checked_steps(())    # (no effects before initialisation)
        self._auxiliary_all = _no_auxiliary
        self._jacobian_all = _no_auxiliary
        self._warned = set()
        self._built_from = None
        self._initialised = False
        self._real_getters, self._real_setters = {}, {}
        #: value reference -> (contact index, ContactPoint field) of the Real inputs/outputs
        self._real_map = {}
        #: per contact: runtime inputs set before initialisation (vehicle FMU)
        self._pending = [{} for _ in range(CONTACTS)]
        #: value reference -> name of the fixed parameters (refused after initialisation)
        self._fixed = {}

        self.scene_file = ""
        self.scene_toml = ""
        for name, desc in _SCENE_PARAMETERS:
            self._register_fixed(String(name, causality=Fmi2Causality.parameter,
                                        variability=Fmi2Variability.fixed, description=desc))
        defaults = _parameters.scene_to_parameters()
        runtime = []
        for spec in _parameters.FMU_PARAMETERS:
            setattr(self, spec.name, defaults[spec.name])
            if spec.name in _parameters.RUNTIME_INPUTS:
                runtime.append(spec)
                continue
            cls = {"real": Real, "integer": Integer, "string": String,
                   "boolean": Boolean}[spec.kind]
            self._register_fixed(cls(spec.name, causality=Fmi2Causality.parameter,
                                     variability=Fmi2Variability.fixed,
                                     description=_described(spec.description, spec.unit)))
            if spec.unit:
                self._units[spec.name] = spec.unit

        for k, c in enumerate(self._contacts):
            for name, (unit, desc) in _scene.INPUTS.items():
                setattr(c, name, float(_scene.INPUT_DEFAULTS[name]))
                self._register_real(Real(
                    _name(name, k), causality=Fmi2Causality.input,
                    variability=Fmi2Variability.continuous,
                    description=_described(desc, unit), getter=(lambda n=name, c=c: getattr(c, n)),
                    setter=(lambda v, n=name, c=c: setattr(c, n, v))), k, name, unit)
            for spec in runtime:
                self._register_real(Real(
                    _name(spec.name, k), causality=Fmi2Causality.input,
                    variability=Fmi2Variability.continuous,
                    description=_described(spec.description, spec.unit),
                    getter=(lambda n=spec.name, k=k: self._get_runtime(n, k)),
                    setter=(lambda v, n=spec.name, k=k: self._set_runtime(n, k, v))),
                    k, spec.name, spec.unit)
            for name, (unit, desc, field) in OUTPUTS.items():
                getter = ((lambda f=field, c=c: self._auxiliary(f, c)) if field in _LAZY
                          else (lambda f=field, c=c: self._jacobian(f, c)) if field in _JACOBIAN
                          else (lambda f=field, c=c: getattr(c, f)))
                self._register_real(Real(
                    _name(name, k), causality=Fmi2Causality.output,
                    variability=Fmi2Variability.continuous,
                    initial=Fmi2Initial.calculated, description=_described(desc, unit),
                    getter=getter), k, field, unit)
            for name, (desc, field) in BOOLEAN_OUTPUTS.items():
                self.register_variable(Boolean(
                    _name(name, k), causality=Fmi2Causality.output,
                    variability=Fmi2Variability.discrete,
                    initial=Fmi2Initial.calculated, description=desc,
                    getter=(lambda f=field, c=c: self._auxiliary(f, c))))

    def _register_fixed(self, var):
        self.register_variable(var)
        self._fixed[var.value_reference] = var.name

    def _register_real(self, var, k, field, unit):
        self.register_variable(var)
        self._real_map[var.value_reference] = (k, field)
        if unit:
            self._units[var.name] = unit

    # -- the runtime inputs (geometry, friction): a parameter before initialisation ----------
    def _get_runtime(self, name, k):
        if self._initialised:
            return getattr(self._contacts[k], name)
        return self._pending[k].get(name, getattr(self, name))

    def _set_runtime(self, name, k, value):
        if self._initialised:
            setattr(self._contacts[k], name, value)
        elif CONTACTS == 1:
            setattr(self, name, value)      # overrides the scene, like a parameter
        else:
            self._pending[k][name] = value  # this contact's start value

    # ---------------------------------------------------------------------------------------
    # model description: units, InitialUnknowns (PythonFMU writes neither), structured names
    # ---------------------------------------------------------------------------------------
    def to_xml(self, model_options=None):
        root = super().to_xml(model_options or {})
        if CONTACTS > 1:
            root.set("variableNamingConvention", "structured")
        unit_defs = Element("UnitDefinitions")
        for unit in sorted(set(self._units.values())):
            u = SubElement(unit_defs, "Unit", {"name": unit})
            SubElement(u, "BaseUnit", {k: str(v) for k, v in UNITS[unit].items()})
        children = list(root)
        position = [i for i, ch in enumerate(children) if ch.tag == "CoSimulation"][0] + 1
        root.insert(position, unit_defs)
        names = [v.name for v in self.vars.values()]
        for node in root.find("ModelVariables"):
            unit = self._units.get(node.get("name"))
            real = node.find("Real")
            if unit is not None and real is not None:
                real.set("unit", unit)
            typed = real if real is not None else node.find("Integer")
            for key, value in LIMITS.get(node.get("name").split("[")[0], {}).items():
                typed.set(key, f"{value:.16g}")
        structure = root.find("ModelStructure")
        initial = SubElement(structure, "InitialUnknowns")
        for index, var in enumerate(self.vars.values(), start=1):
            if var.causality == Fmi2Causality.output:
                SubElement(initial, "Unknown", {"index": str(index)})
        assert len(names) == len(set(names))
        return root

    # ---------------------------------------------------------------------------------------
    # errors: the FMI log and the host's standard error
    # ---------------------------------------------------------------------------------------
    def _report(self, message, status=Fmi2Status.error):
        """Log ``message`` with ``status`` and write it to the host's standard error.

        PythonFMU 0.7's native library passes log messages to the importer only when debug
        logging is on (``fmi2Instantiate(..., loggingOn)``, ``fmi2SetDebugLogging``), which
        importers leave off by default: without this second copy a plain ``fmpy.simulate_fmu``
        or a libcosim run would show only the status ("status 4 (fatal)")."""
        self.log(message, status)
        try:
            sys.stderr.write(f"{type(self).__name__} {self.instance_name!r}: "
                             f"{status.name.upper()}: {message}\n")
            sys.stderr.flush()
        except (AttributeError, OSError, ValueError):   # no usable stderr in this host
            pass

    # ---------------------------------------------------------------------------------------
    # initialisation: read the scene, build only the effects it switches on
    # ---------------------------------------------------------------------------------------
    def _parameter_values(self):
        values = {name: getattr(self, name) for name, _ in _SCENE_PARAMETERS}
        for spec in _parameters.FMU_PARAMETERS:
            values[spec.name] = getattr(self, spec.name)
        return values

    def _resolve_scene(self, values):
        base, base_dir = None, None
        if values["scene_file"]:
            path = Path(values["scene_file"])
            bundled = (Path(self.resources) / "scenes" / f"{values['scene_file']}.toml"
                       if self.resources else None)
            if not path.exists() and bundled is not None and bundled.exists():
                path = bundled
            try:
                text = path.read_text(encoding="utf-8")
            except OSError as exc:
                scenes = (sorted(p.stem for p in bundled.parent.glob("*.toml"))
                          if bundled is not None and bundled.parent.is_dir() else [])
                hint = (f"; the scenes bundled in this FMU are {', '.join(scenes)}"
                        if scenes else "")
                raise _scene.SceneError(f"scene_file: cannot read {str(path)!r}: "
                                        f"{exc.strerror}{hint}") from None
            try:
                base = _scene.tomllib.loads(text)
            except _scene.tomllib.TOMLDecodeError as exc:
                raise _scene.SceneError(f"scene_file {str(path)!r}: not valid TOML: "
                                        f"{exc}") from None
            base_dir = path.parent
        elif values["scene_toml"]:
            try:
                base = _scene.tomllib.loads(values["scene_toml"])
            except _scene.tomllib.TOMLDecodeError as exc:
                raise _scene.SceneError(f"scene_toml: not valid TOML: {exc}") from None
        data = _parameters.parameters_to_scene_dict(values, base=base)
        try:
            return _scene.scene_from_dict(data, base_dir=base_dir)
        except _scene.SceneError as exc:
            raise _scene.SceneError(_name_parameter(str(exc))) from None

    def _build(self, values):
        scene = self._resolve_scene(values)
        tables_dir = None
        if self._bundle_dir is not None and (self._bundle_dir / "tables").is_dir():
            tables_dir = self._bundle_dir / "tables"
        geo = scene.geometry
        for c in self._contacts:
            c.friction_coefficient = scene.friction_coefficient
            for name in _effects.ContactPoint.GEOMETRY_FIELDS:
                # (a line scene holds none of them: their defaults, unused there)
                setattr(c, name, float(geo.get(name, _scene.DEFAULT_SCENE["geometry"][name])))
        if CONTACTS > 1:
            self._vehicle = _effects.Vehicle(scene, self._contacts, tables_dir=tables_dir,
                                             warn=self._warn_once)
            self._pipeline = self._vehicle.pipelines[0]
            # (bound to the vehicle, not to self: no reference cycle through the slave)
            self._auxiliary_all = self._vehicle.auxiliary
            self._jacobian_all = (self._vehicle.jacobian
                                  if self._vehicle.pipelines[0].jacobian_on_demand
                                  else _no_auxiliary)
            summary = self._vehicle.summary
            # the whole step without the slave's frames (as for one contact, below)
            self.do_step = self._vehicle.fmu_step(self._do_step_full, self._log_step_failure)
        else:
            self._pipeline = _effects.build_pipeline(scene, tables_dir=tables_dir,
                                                     warn=self._warn_once)
            self._steps = self._pipeline.steps
            self._checked_step = self._pipeline.checked_step
            self._auxiliary_all = self._pipeline.auxiliary
            self._jacobian_all = (self._pipeline.jacobian if self._pipeline.jacobian_on_demand
                                  else _no_auxiliary)     # (a no-op: the step set them)
            # the whole step in one Python frame (an instance attribute shadows the do_step
            # method; PythonFMU looks the method up by name on each step)
            self.do_step = self._pipeline.fmu_step(self._contact, self._do_step_full,
                                                   self._log_step_failure)
            summary = self._pipeline.summary()
        self._built_from = values
        self.log(f"scene {scene.name!r}: effects on: {summary}"
                 + (f" ({CONTACTS} contacts)" if CONTACTS > 1 else ""), Fmi2Status.ok)

    def _warn_once(self, key, message):
        if key not in self._warned:
            self._warned.add(key)
            self.log(message, Fmi2Status.warning)

    def setup_experiment(self, start_time, stop_time=None, tolerance=None):
        """Nothing to set up: the master owns start and stop time, and the slave no tolerance.

        Overridden so that every pythonfmu release the project allows calls it alike: 0.6.x's
        Python base class takes ``start_time`` only, while its native library passes all three.
        """

    def exit_initialization_mode(self):
        try:
            self._build(self._parameter_values())
        except _effects.MissingDependency as exc:
            self._report(f"initialisation failed: {exc}", Fmi2Status.fatal)
            raise
        except ValueError as exc:   # SceneError is a ValueError
            self._report(f"invalid parameter: {exc}", Fmi2Status.error)
            raise
        except Exception as exc:    # report, then let PythonFMU return fmi2Fatal
            self._report(f"initialisation failed: {exc!r}", Fmi2Status.fatal)
            raise
        for c, pending in zip(self._contacts, self._pending):
            for name, value in pending.items():
                setattr(c, name, value)
        try:
            self._check_inputs()
            self._evaluate()
        except ValueError as exc:
            self._report(f"invalid input (start value): {exc}", Fmi2Status.error)
            raise
        self._initialised = True
        self._real_getters.clear()
        self._real_setters.clear()
        _release_interpreter_guard_at_exit(self.resources, "initialised")

    # ---------------------------------------------------------------------------------------
    # stepping
    # ---------------------------------------------------------------------------------------
    def _check_inputs(self):
        if self._vehicle is not None:
            self._vehicle.check_inputs()
            return
        c = self._contact
        total = (c.normal_force + c.creepage_longitudinal + c.creepage_lateral + c.spin
                 + c.rolling_speed + c.rail_position + c.friction_coefficient)
        if math.isfinite(total) and c.normal_force >= 0.0 and c.rolling_speed >= 0.0 \
                and c.friction_coefficient >= 0.0:
            return
        for name, lower in (("normal_force", 0.0), ("creepage_longitudinal", None),
                            ("creepage_lateral", None), ("spin", None),
                            ("rolling_speed", 0.0), ("rail_position", None),
                            ("friction_coefficient", 0.0)):
            unit = _scene.INPUTS[name][0] if name in _scene.INPUTS else "1"
            _rc.check_range(name, getattr(c, name), unit, lower, None)

    def _auxiliary(self, field, c=None):
        """Value of an output some effects compute only when it is read (after a step), of
        contact ``c`` (default: the first)."""
        c = self._contact if c is None else c
        self._auxiliary_all(c)
        return getattr(c, field)

    def _jacobian(self, field, c=None):
        """Value of a Jacobian output (:data:`_JACOBIAN`), of contact ``c`` (default: the
        first)."""
        c = self._contact if c is None else c
        self._jacobian_all(c)
        return getattr(c, field)

    # ---------------------------------------------------------------------------------------
    # reading outputs and setting inputs: a precomputed table per list of value references
    # ---------------------------------------------------------------------------------------
    # PythonFMU's generic get_real/set_real look every variable up and call a lambda per
    # variable; an importer asks for the same lists of value references step after step, so
    # each list gets, on first use after initialisation, one operator.attrgetter over the
    # ContactPoint fields it names (the lazy outputs' auxiliary evaluation made once before
    # it; a vehicle: (contact, field) pairs). Lists with a parameter or a non-Real variable keep
    # the generic path (and its error); a fixed parameter set after initialisation is refused.
    def get_real(self, vrs):
        if not self._initialised:
            return Fmi2Slave.get_real(self, vrs)
        key = tuple(vrs)
        getter = self._real_getters.get(key)
        if getter is None:
            getter = self._real_getters[key] = self._real_getter(key)
        return getter()

    def set_real(self, vrs, values):
        if not self._initialised:
            return Fmi2Slave.set_real(self, vrs, values)
        key = tuple(vrs)
        assign = self._real_setters.get(key)
        if assign is None:
            fields = self._real_fields(key, inputs=True)
            assign = self._real_setters[key] = (
                _assigner(fields if CONTACTS > 1 else [(self._contact, f) for f in fields])
                if fields else False)
        if assign is False:
            self._refuse_fixed(vrs)
            return Fmi2Slave.set_real(self, vrs, values)
        assign(values)

    def set_integer(self, vrs, values):
        self._refuse_fixed(vrs)
        return Fmi2Slave.set_integer(self, vrs, values)

    def set_boolean(self, vrs, values):
        self._refuse_fixed(vrs)
        return Fmi2Slave.set_boolean(self, vrs, values)

    def set_string(self, vrs, values):
        self._refuse_fixed(vrs)
        return Fmi2Slave.set_string(self, vrs, values)

    def _refuse_fixed(self, vrs):
        """After initialisation, a ValueError (fmi2Fatal through PythonFMU) and an error
        message naming each fixed parameter in ``vrs`` (FMI 2.0: variability fixed)."""
        if not self._initialised:
            return
        names = [self._fixed[vr] for vr in vrs if vr in self._fixed]
        if names:
            message = (f"parameter{'s' if len(names) > 1 else ''} {', '.join(names)} "
                       f"{'are' if len(names) > 1 else 'is'} fixed (variability fixed): "
                       "it cannot be set after initialisation; the value is not taken (set "
                       "it before fmi2ExitInitializationMode, or reset the instance). "
                       "Geometry and friction are inputs: "
                       f"{', '.join(_parameters.RUNTIME_INPUTS)}")
            self._report(message, Fmi2Status.error)
            raise ValueError(message)

    _INPUT_NAMES = frozenset(_scene.INPUTS) | frozenset(_parameters.RUNTIME_INPUTS)

    def _real_fields(self, vrs, inputs=False):
        """The (contact, field) of the Real variables ``vrs`` (inputs only if ``inputs``), as
        fields of the one contact for a single-contact FMU, or () if one of them is not such a
        variable."""
        out = []
        for vr in vrs:
            entry = self._real_map.get(vr)
            if entry is None or (inputs and entry[1] not in self._INPUT_NAMES):
                return ()
            k, field = entry
            out.append(field if CONTACTS == 1 else (self._contacts[k], field))
        return tuple(out)

    def _real_getter(self, vrs):
        fields = self._real_fields(vrs)
        if not fields:
            return self._mixed_getter(vrs)
        if CONTACTS > 1:
            lazy, jac = _on_demand([f for _, f in fields])
            aux, jac_all = self._auxiliary_all, self._jacobian_all
            jac = jac and jac_all is not _no_auxiliary

            read = _reader(fields)
            if not (lazy or jac):
                return read

            def get():
                if lazy:
                    aux(None)           # (every contact's, once)
                if jac:
                    jac_all(None)
                return read()
            return get
        c, get = self._contact, operator.attrgetter(*fields)
        lazy, jac = _on_demand(fields)
        if jac and self._jacobian_all is not _no_auxiliary:
            aux, jac_all = self._auxiliary_all, self._jacobian_all

            def get_on_demand():
                if lazy:
                    aux(c)
                jac_all(c)
                return [get(c)] if len(fields) == 1 else list(get(c))
            return get_on_demand
        if len(fields) == 1:
            if lazy:
                return lambda: (self._auxiliary_all(c), [get(c)])[1]
            return lambda: [get(c)]
        if lazy:
            return lambda: (self._auxiliary_all(c), list(get(c)))[1]
        return lambda: list(get(c))

    def _mixed_getter(self, vrs):
        """A list with parameters too (libcosim reads every variable each step): the contacts'
        fields directly, the others through their getters, the lazy outputs evaluated once
        first. A variable that is not Real keeps the generic path (and its TypeError)."""
        calls, lazy, jac = [], False, False
        for vr in vrs:
            entry = self._real_map.get(vr)
            if entry is not None:
                k, field = entry
                calls.append(partial(getattr, self._contacts[k], field))
                lazy = lazy or field in _LAZY
                jac = jac or field in _JACOBIAN
            elif isinstance(self.vars.get(vr), Real):
                calls.append(self.vars[vr].getter)
            else:
                return lambda: Fmi2Slave.get_real(self, list(vrs))
        aux, jac_all, contacts = self._auxiliary_all, self._jacobian_all, self._contacts
        jac = jac and jac_all is not _no_auxiliary

        def get():
            if lazy:
                for c in contacts:
                    aux(c)
            if jac:
                for c in contacts:
                    jac_all(c)
            return [call() for call in calls]
        return get

    def _evaluate(self):
        if self._vehicle is not None:
            self._vehicle.step(0.0)
            return
        c = self._contact
        for step in self._steps:
            step(c)

    def do_step(self, current_time, step_size):
        # The pipeline's checked step (railcontact.effects.Pipeline.checked_step) makes a cheap
        # input check (one isfinite on the sum of the inputs, N >= 0, V >= 0, mu >= 0) and
        # evaluates the effects in one call; it returns False, changing nothing, when that
        # check does not pass: then _do_step_full's range check names the bad input (or finds
        # all valid, e.g. when only their sum overflowed) before the effects run. _build
        # replaces this method by Pipeline.fmu_step, the same in one frame (one contact).
        if self._vehicle is not None or not 0.0 <= step_size < math.inf:   # (NaN fails too)
            return self._do_step_full(current_time, step_size)
        self._contact.step_size = step_size        # (NonSteady: the rolled distance V h)
        try:
            if self._checked_step(self._contact):
                return True
        except ValueError as exc:
            self._log_step_failure(current_time, exc)
            raise
        return self._do_step_full(current_time, step_size)

    def _do_step_full(self, current_time, step_size):
        """The step with the full input check: an error message naming the bad input (or the
        step size: negative, NaN or infinite, which would move the non-steady state by an
        undefined rolled distance)."""
        if not 0.0 <= step_size < math.inf:
            try:
                _rc.check_range("step_size", step_size, "s", 0.0, None)
            except ValueError as exc:
                self._report(f"invalid communication step at t = {current_time:g} s: {exc}",
                             Fmi2Status.error)
                raise
        try:
            self._check_inputs()
        except ValueError as exc:
            self._report(f"invalid input at t = {current_time:g} s: {exc}", Fmi2Status.error)
            raise
        try:
            if self._vehicle is not None:
                self._vehicle.step(step_size)
            else:
                self._contact.step_size = step_size
                for step in self._steps:
                    step(self._contact)
        except ValueError as exc:
            self._log_step_failure(current_time, exc)
            raise
        return True

    def _log_step_failure(self, current_time, exc):
        # a model's own range check (e.g. Eq. (4.2) as the surface evolves, a geometry input
        # <= 0): an error status with the model's message
        self._report(f"step at t = {current_time:g} s failed: {exc}", Fmi2Status.error)

    # ---------------------------------------------------------------------------------------
    # FMU state: everything (parameters, inputs, outputs, effect state, warnings logged)
    # ---------------------------------------------------------------------------------------
    def _get_fmu_state(self):
        return {
            "parameters": dict(self._parameter_values()),
            "contacts": [c.as_dict() for c in self._contacts],
            "pending": [dict(p) for p in self._pending],
            "built_from": None if self._built_from is None else dict(self._built_from),
            "effects": (self._vehicle.get_state() if self._vehicle is not None
                        else None if self._pipeline is None else self._pipeline.get_state()),
            "warned": sorted(self._warned),
            "initialised": self._initialised,
        }

    def _set_fmu_state(self, state):
        for name, value in state["parameters"].items():
            setattr(self, name, value)
        built_from = state["built_from"]
        if built_from is None:
            self._pipeline, self._vehicle, self._steps, self._built_from = None, None, (), None
            self._checked_step = _effects.checked_steps(())
            self._auxiliary_all = self._jacobian_all = _no_auxiliary
            self.__dict__.pop("do_step", None)
        elif built_from != self._built_from:
            self._build(dict(built_from))
        for c, values in zip(self._contacts, state["contacts"]):
            for name, value in values.items():
                setattr(c, name, value)
        self._pending = [dict(p) for p in state["pending"]]
        if state["effects"] is not None:
            (self._vehicle or self._pipeline).set_state(state["effects"])
        self._warned = set(state["warned"])
        self._initialised = state["initialised"]
        self._real_getters.clear()
        self._real_setters.clear()

    @staticmethod
    def _fmu_state_to_bytes(state):
        return json.dumps(state, sort_keys=True).encode("utf-8")

    @staticmethod
    def _fmu_state_from_bytes(state):
        return json.loads(state.decode("utf-8"))


def _repoint_bundle(resources):
    """Make the (cached) bundled package import from this instance's resources directory.

    Python caches modules by name: a second instance of this FMU in the same process (same
    bundle name, same content) reuses the package imported by the first, whose extraction
    directory an importer may already have deleted (fmpy does after each simulation). Lazy
    submodule imports and data files must then come from this instance's copy.

    Returns
    -------
    pathlib.Path or None
        The bundled package directory of this instance (None when running from the sources).
    """
    if not resources:
        return None
    root = Path(resources) / _PACKAGE
    if not root.is_dir():
        return None
    for name, module in list(sys.modules.items()):
        if name == _PACKAGE or name.startswith(_PACKAGE + "."):
            path = getattr(module, "__path__", None)
            if isinstance(path, list):
                path[:] = [str(root.joinpath(*name.split(".")[1:]))]
    return root


def _release_interpreter_guard_at_exit(resources, stage):
    """Have the C library's exit handlers reset PythonFMU's interpreter guard in time (Linux).

    PythonFMU 0.7's native library (``binaries/linux64/*.so``) holds its interpreter guard in
    a namespace-scope ``std::shared_ptr<PyState> pyState``, and also resets it from an
    ``__attribute__((destructor))`` function (``onLibraryUnload`` -> the exported
    ``finalizePythonInterpreter``). The library cannot be unloaded (it defines STB_GNU_UNIQUE
    symbols, so ``dlclose`` keeps it), so both run at process exit, in this order: ``exit()``
    runs the C++ static destructor, which frees the shared_ptr's control block (and, when
    PythonFMU started Python itself, finalises the interpreter from there); ``_dl_fini`` then
    calls ``finalizePythonInterpreter``, which decrements the use count inside the freed block,
    a write into freed heap memory (valgrind: "Invalid read of size 4 at
    finalizePythonInterpreter ... by _dl_fini", upstream NTNU-IHB/PythonFMU#229). Depending on
    the heap's state that corrupts glibc's free lists and the process aborts after all its work
    is done ("corrupted double-linked list"). Where PythonFMU started Python (a non-Python
    host), finalising the interpreter from that static destructor is worse: the static
    destructors of the C++ extension modules loaded since have already run (valgrind: reads of
    memory scipy's ``_uarray`` freed, inside ``Py_Finalize``; a segfault in 1 of 3 exits).

    Registering ``finalizePythonInterpreter`` itself with ``__cxa_atexit`` (what ``atexit()``
    does; no argument, no DSO, so it runs at exit only) puts it *before* both: exit handlers
    run in reverse order of registration, and this one is registered after the library and the
    extension modules were loaded. It then destroys ``PyState`` while everything is alive
    (where PythonFMU started Python, its thread finalises the interpreter at that moment;
    where the host started it, ``PyState`` owns nothing and its thread has long ended), leaves
    ``pyState`` empty, and the two later calls do nothing. docs/fmu_lifecycle.md has the
    measurements.

    The library is found next to ``resources/`` (FMI 2.0 layout) and opened with
    ``RTLD_NOLOAD`` (only the copy the importer already loaded; the handle is kept, so that
    copy stays mapped until exit). Registered once per library copy and ``stage``: at
    instantiation, and again after the first initialisation (which may load more C
    libraries, e.g. netCDF4 for the tables; the later registration runs first). Anything
    unexpected (another layout, no such symbol) leaves things as they are.
    """
    if not sys.platform.startswith("linux") or not resources:
        return
    for path in (Path(resources).parent / "binaries" / "linux64").glob("*.so"):
        try:
            library = ctypes.CDLL(str(path), mode=os.RTLD_NOW | os.RTLD_NOLOAD)
            release = ctypes.cast(library.finalizePythonInterpreter, ctypes.c_void_p).value
            libc = ctypes.CDLL(None)
            register = libc["__cxa_atexit"]
        except (OSError, AttributeError):
            continue
        if (release, stage) in _EXIT_RELEASES:
            continue
        register.argtypes = [ctypes.c_void_p, ctypes.c_void_p, ctypes.c_void_p]
        register.restype = ctypes.c_int
        if register(release, None, None) == 0:
            _EXIT_RELEASES[(release, stage)] = library


# PythonFMU's findClass executes this file a second time in the module's globals (with fresh
# locals), once per instantiation: create the registry only once.
try:
    _EXIT_RELEASES
except NameError:
    _EXIT_RELEASES = {}   # (address of finalizePythonInterpreter, stage) -> library handle


def _name_parameter(message):
    """Prefix a scene error with the FMU parameter that sets the offending key, if any."""
    for spec in _parameters.FMU_PARAMETERS:
        if message.startswith(".".join(spec.path) + " "):
            return f"parameter {spec.name} ({message})"
    return message
