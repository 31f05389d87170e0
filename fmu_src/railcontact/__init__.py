r"""railcontact: wheel/rail rolling-contact mechanics after J.B. Nielsen (1998).

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
"""

from ._validation import check_range  # noqa: F401
from .hertz import (Hertz2D, Hertz3D, hertz_2d, hertz_3d,  # noqa: F401
                    curvature_ratio_from_axis_ratio, axis_ratio_from_curvature_ratio)
from .carter import (carter_creep_force, carter_critical_creepage,  # noqa: F401
                     carter_stick_ratio, carter_traction, carter_slip)
from .kalker import KalkerCoefficients, kalker_coefficients  # noqa: F401
from .creep3d import (CreepForce3D, CreepSolution3D, creep_force_3d,  # noqa: F401
                      creep_solution_3d, spin_coefficient, saturation_creepage_3d,
                      normalised_creepage_3d, strip_force_function)
from .creep3d import ExactCreepSolution3D  # noqa: F401
from .errors import RollingConvergenceError  # noqa: F401
from . import polynomial  # noqa: F401
from . import roughness  # noqa: F401
from . import friction, nonsteady  # noqa: F401

__version__ = "0.1.0"
