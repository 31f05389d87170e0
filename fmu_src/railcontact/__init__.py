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
    tables        the C2 spline tables: fitting, evaluation, files (Table, default_table_path)
    strip_table   the modified strip theory's table (CreepTable)
    exact_table   Kalker's exact theory's table (ExactCreepTable; creep3d.load_exact_table)
    reference     independent discretised half-space solvers (halfspace2d, rolling3d) and the
                  brute-force wear checks (wear_direct); used by tests and the accuracy
                  report, never by the FMU
    scene, effects, run   the FMU's scenes, its effect pipeline, and
                  ``python -m railcontact.run SCENE`` (the scene through the FMU with fmpy)
    fmu_parameters   the FMU's parameters and the scene keys they set
    fmu_build     builds WheelRailContact.fmu from a checkout (``python build_fmu.py``)
Submodules other than polynomial, friction and nonsteady are imported on first
attribute access (``railcontact.wear``) or with ``import railcontact.wear``.

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

from ._validation import check_range  # noqa: F401  (used by the FMU slave; not public API)
from .hertz import (Hertz2D, Hertz3D, hertz_2d, hertz_3d,
                    curvature_ratio_from_axis_ratio, axis_ratio_from_curvature_ratio)
from .carter import (carter_creep_force, carter_critical_creepage,
                     carter_stick_ratio, carter_traction, carter_slip)
from .kalker import KalkerCoefficients, kalker_coefficients
from .creep3d import (CreepForce3D, CreepSolution3D, creep_force_3d,
                      creep_solution_3d, spin_coefficient, saturation_creepage_3d,
                      normalised_creepage_3d, strip_force_function)
from .creep3d import ExactCreepSolution3D
from .errors import RollingConvergenceError
from . import polynomial
from . import friction, nonsteady

__version__ = "0.1.0"

#: Submodules imported on first access (kept out of ``import railcontact``, which the FMU
#: pays for at load time).
_LAZY_SUBMODULES = ("corrugation", "wear", "roughness", "evolution", "filters", "kalker",
                    "tables", "strip_table", "exact_table", "creep_common",
                    "reference", "scene", "effects", "run", "fmu_parameters",
                    "fmu_build")

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
    "polynomial", "corrugation", "wear", "evolution", "filters", "friction", "roughness",
    "nonsteady", "kalker", "tables", "reference", "scene", "effects", "run", "fmu_parameters",
    "fmu_build",
]


def __getattr__(name):
    if name in _LAZY_SUBMODULES:
        module = _importlib.import_module(f"{__name__}.{name}")
        globals()[name] = module
        return module
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(_LAZY_SUBMODULES))
