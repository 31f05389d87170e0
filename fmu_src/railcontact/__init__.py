r"""railcontact: wheel/rail rolling-contact mechanics after J.B. Nielsen (1998).

Map of the package (``railcontact.__all__`` lists the public names of this top level)
--------------------------------------------------------------------------------------
Top level: Hertz contact and the 3-D creep theories (chapter 2)
    hertz_2d, hertz_3d, Hertz2D, Hertz3D           Hertz semi-axes and peak pressure
    curvature_ratio_from_axis_ratio,               B'/A' <-> a0/b0
    axis_ratio_from_curvature_ratio
    carter_creep_force, carter_critical_creepage,  Carter's 2-D rolling contact
    carter_stick_ratio, carter_traction, carter_slip
    kalker_coefficients, KalkerCoefficients        Kalker's C11, C22, C23 (C2-smooth)
    creep_force_3d, creep_solution_3d,             3-D creep forces: linear, SHE, strip,
    CreepForce3D, CreepSolution3D                  modified strip (+ stick zone, validity),
    ExactCreepSolution3D                           and Kalker's exact theory (method="exact":
                                                   + spin moment, sensitivities, fields)
    RollingConvergenceError                        the exact solver did not converge
    spin_coefficient, saturation_creepage_3d,      pieces of the modified strip theory
    normalised_creepage_3d, strip_force_function
Submodules, one per model family (``railcontact.<name>``; each lists its own ``__all__``)
    polynomial    ch. 3: the polynomial approach, non-Hertzian 2-D normal and tangential contact
    corrugation   ch. 4.2: contact on a corrugated rail
    wear          ch. 4.3: wear per passage (wear models, linear response)
    evolution     ch. 4.4: corrugation growth over many passages
    filters       ch. 4.5: Remington and Hempelmann contact filters
    friction      ch. 5: velocity-dependent friction
    roughness     ch. 6: one asperity, two patches, rough rail
    nonsteady     ch. 7: non-steady 2-D rolling, relaxation
    kalker        Kalker's coefficient table and asymptotes
    creep3d       the 3-D creep theories behind creep_force_3d (METHODS, load_exact_table)
    fastsim       Kalker's FASTSIM (simplified theory), for comparison
    polach        Polach's creep force model, for comparison
    tables        the C2 spline tables: fitting, evaluation, files (Table, default_table_path)
    strip_table   the modified strip theory's table (CreepTable)
    exact_table   Kalker's exact theory's table (ExactCreepTable; creep3d.load_exact_table)
Not in ``__all__`` (importable, but tools rather than the modelling API):
    reference     independent discretised half-space solvers (halfspace2d, rolling3d) and the
                  brute-force wear checks (wear_direct); used by tests and the accuracy
                  report, never by the FMU
    scene, effects, run   the FMU's scenes, its effect pipeline, and
                  ``python -m railcontact.run SCENE`` (the scene through the FMU with fmpy)
    fmu_parameters   the FMU's parameters and the scene keys they set
    fmu_build     builds WheelRailContact.fmu from a checkout (``python build_fmu.py``)
Everything is imported on first use: ``import railcontact`` loads numpy only, a name such as
``railcontact.hertz_3d`` its module on first access, and a submodule (``railcontact.wear``,
also through ``from railcontact import *``) runs when its first attribute is read.

Conventions (one set, used by every function, table and the FMU)
-----------------------------------------------------------------
* SI units everywhere: N, m, Pa, s. 2-D functions take loads per unit length [N/m].
* Coordinates: x is the rolling direction, y lateral, z normal (into body 1). The contact patch
  is |x| <= a (2-D) or the ellipse (x/a)^2 + (y/b)^2 <= 1 (3-D); the leading edge is x = +a.
* Creepage (Nielsen Eq. (2.15)): xi_x = (V_x1 - V_x2)/V_m, xi_y = (V_y1 - V_y2)/V_m and spin
  phi = (Omega_z1 - Omega_z2)/V_m [1/m], i.e. rigid relative velocity of body 1 (wheel) with
  respect to body 2 (rail), normalised by the mean rolling speed V_m.
* Force: the tangential force (and traction) **acting on body 1 (the wheel)**. It opposes the
  creepage: in the linear regime T_x = -G a b C11 xi_x, T_y = -G a b (C22 xi_y + sqrt(a b) C23 phi)
  (Kalker). This is also CONTACT's convention, so CONTACT's FX/FN compares directly.
  The thesis (Ch. 2) writes positive forces for negative creepage; its formulas are applied
  with that sign flipped where they are implemented.
* Friction: |T| <= mu N always (Coulomb bound), with mu the friction coefficient.
* r_a0 = a*/a0: stick-zone half-width over contact half-width (1 = full stick, 0 = full slip).

More: README.md (recipes) and docs/conventions.md (nomenclature: symbol -> API name -> unit).
"""

import importlib as _importlib

from ._lazy import lazy_submodule as _lazy_module

__version__ = "0.1.0"

#: The top-level names and the submodule that defines each (imported on first access:
#: ``import railcontact`` costs numpy only, which the FMU and a first call pay for).
_NAMES = {
    "hertz": ("Hertz2D", "Hertz3D", "hertz_2d", "hertz_3d", "curvature_ratio_from_axis_ratio",
              "axis_ratio_from_curvature_ratio"),
    "carter": ("carter_creep_force", "carter_critical_creepage", "carter_stick_ratio",
               "carter_traction", "carter_slip"),
    "kalker": ("KalkerCoefficients", "kalker_coefficients"),
    "creep3d": ("CreepForce3D", "CreepSolution3D", "creep_force_3d", "creep_solution_3d",
                "spin_coefficient", "saturation_creepage_3d", "normalised_creepage_3d",
                "strip_force_function", "ExactCreepSolution3D"),
    "errors": ("RollingConvergenceError",),
    "_validation": ("check_range",),     # used by the FMU slave; not public API
}
_WHERE = {name: module for module, names in _NAMES.items() for name in names}

#: The public submodules (``__all__``; each lists its own).
_PUBLIC_SUBMODULES = ("polynomial", "corrugation", "wear", "evolution", "filters", "friction",
                      "roughness", "nonsteady", "kalker", "creep3d", "fastsim", "polach",
                      "tables", "strip_table", "exact_table")
#: Submodules that are importable as attributes but not public API.
_OTHER_SUBMODULES = ("creep_common", "reference", "scene", "effects", "run", "fmu_parameters",
                     "fmu_build")
_LAZY_SUBMODULES = _PUBLIC_SUBMODULES + _OTHER_SUBMODULES

__all__ = [
    # chapter 2: Hertz, Carter, Kalker, 3-D creep
    "Hertz2D", "Hertz3D", "hertz_2d", "hertz_3d", "curvature_ratio_from_axis_ratio",
    "axis_ratio_from_curvature_ratio",
    "carter_creep_force", "carter_critical_creepage", "carter_stick_ratio", "carter_traction",
    "carter_slip",
    "KalkerCoefficients", "kalker_coefficients",
    "CreepForce3D", "CreepSolution3D", "creep_force_3d", "creep_solution_3d",
    "spin_coefficient", "saturation_creepage_3d", "normalised_creepage_3d",
    "strip_force_function", "ExactCreepSolution3D", "RollingConvergenceError",
    # submodules
    *_PUBLIC_SUBMODULES,
]


def __getattr__(name):
    if name in _WHERE:
        value = getattr(_importlib.import_module(f"{__name__}.{_WHERE[name]}"), name)
    elif name in _LAZY_SUBMODULES:
        value = _lazy_module(name)
    else:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    globals()[name] = value
    return value


def __dir__():
    return sorted(set(globals()) | set(_WHERE) | set(_LAZY_SUBMODULES))
