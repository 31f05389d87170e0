r"""Rough surfaces: one asperity and two interacting contact patches (Nielsen 1998, Ch. 6).

Built on the polynomial approach (:mod:`railcontact.polynomial`). Modules: ``asperity`` (one
asperity), ``two_patch`` (two interacting patches), ``rough_rail`` (a wheel on a rough rail,
and :class:`RoughRailSolver`, the FMU step) and ``_kernels`` (the compiled arithmetic that the
public functions and the FMU step share); every public name is importable from here.

One asperity (Sec. 6.3)
    ``Z(x) = lambda0 + lambda2 x^2/2 + lambda3 x^3/6 + lambda4 x^4/24`` (6.1): curvature
    ``lambda2``, skewness ``lambda3``, flatness ``lambda4`` [1/m, 1/m^2, 1/m^3]. The contact is
    the strip ``|x - Delta| < a``; the pressure (6.3)-(6.8) is a polynomial form of degree 4; ``a``
    and ``Delta`` solve (6.9)-(6.10). Every case of Table 6.1 is implemented (closed forms where
    the table has one, a bracketed 1-D root otherwise); its restrictions raise ``ValueError``.
Tangential problem for one asperity (Sec. 6.5.1)
    Creepage and force as functions of the stick half-width ``a*``, (6.38)-(6.39); critical
    creepage (6.40); initial slope of the creep curve (6.41).
Two adjacent patches (Sec. 6.4, 6.5.2)
    Each patch carries a polynomial form; the field of the *other* patch (the ``I_-1`` term of
    (3.4), (6.16)-(6.21)) is made polynomial on each patch, either by its Taylor expansion about
    the patch centre (the thesis' choice) or by Chebyshev interpolation (collocation at the
    Chebyshev nodes, the default: it converges faster when the patches nearly touch).
    The split of the load between the patches is an explicit input (``load_split``), because the
    thesis' method does not determine it (text after (6.25)); ``load_split="compatible"`` instead
    determines it from the condition that the deformed gap closes at both patches (the relative
    displacement between two surface points *is* finite in 2-D, only the absolute approach is
    not), which is what the discretised reference solver does.

A rough rail under a rolling wheel (time domain, the thesis' use of the asperity model)
    :class:`HarmonicRoughness` (harmonics in the format of :mod:`railcontact.corrugation`,
    Eq. (4.1)) and :class:`ProfileRoughness` (a sampled profile, C4 quintic spline) describe the
    rail surface height ``r(X)``; :func:`local_gap` expands the gap between the wheel's parabola
    and the rail to 4th order about the gap minimum at a wheel position, giving the lambdas of
    (6.1) for :func:`asperity_normal_contact` and :func:`asperity_tangential_contact`.

Limits (hard cases, tested): a single coherent patch on the concave flank of a gap does not
exist beyond a fold load (``ValueError`` naming ``normal_load``); the two-patch solver then starts
from a smaller load and continues in the load, and refuses once the reference solver would merge
the patches. Taylor expansion converges only geometrically in (target half-width)/(distance to
the other patch), Chebyshev collocation faster; with the inner gap 0.73 a they differ by 1.6e-4.

Conventions: package convention (see :mod:`railcontact`). The leading edge is at ``+x``, so
stick zones touch the *right* edge of each patch, and the force on the wheel opposes the creepage.
The thesis draws the leading edge at ``-x``; its (6.33)-(6.40) are the mirror image
(``x -> -x``, ``lambda3 -> -lambda3``, ``Delta -> -Delta``). Its "first" patch (Table 6.2) is the
leading one, i.e. the patch at larger ``x`` here.

Errata found (each verified in ``tests/test_roughness.py``):

* Table 6.1(A) (``lambda4 = 0``, ``lambda3 != 0``): the printed ``a = ((2/3)(lambda2/lambda3)
  (2 cos Theta - 1))^(1/2)`` is dimensionally wrong (``lambda2/lambda3`` must be squared) and, even
  squared, is the magnitude of the *negative* root of the cubic ``lambda3^2 u^3 - 2 lambda2^2 u^2
  + 2 N~^2 = 0`` (``u = a^2``) that (6.9)-(6.10) reduce to. Correct:
  ``a^2 = (2/3)(lambda2/lambda3)^2 (1 + 2 cos(Theta + pi/3))`` with the printed ``Theta``.
* Table 6.1(B), ``lambda3 + lambda4 Delta = 0``: the printed ``(sqrt(1 + 2 lambda4 N~/lambda2^2)
  - 1)`` must be ``+ 1`` (the printed root is negative for ``lambda4 > 0``, which the restriction
  ``lambda2 = lambda3^2/(3 lambda4)`` with ``lambda2 > 0`` implies).
* (6.40) lacks the factor ``mu`` that (6.38) carries.

References
----------
.. [1] J.B. Nielsen, New Developments in the Theory of Wheel/Rail Contact Mechanics,
   IMM-PHD-1998-51, DTU, 1998, Ch. 6.
.. [2] K. Knothe, F. Theiler, Rolling contact of rough surfaces, 1995 (Nielsen's [42]).
"""

from .asperity import (AsperityContact, AsperityTangentialContact, asperity_creep_curve,
                       asperity_critical_creepage, asperity_gap_coefficients,
                       asperity_initial_slope, asperity_normal_contact,
                       asperity_pressure_coefficients, asperity_tangential_contact,
                       asperity_tangential_state, normalised_load)
from .rough_rail import (HarmonicRoughness, LocalGap, ProfileRoughness, RoughRailContact,
                         RoughRailSolver, local_gap, rough_rail_contact)
from .two_patch import (TwoPatchContact, TwoPatchTangentialContact,
                        double_asperity_coefficients, two_patch_normal_contact,
                        two_patch_tangential_contact)

__all__ = [
    "normalised_load",
    "asperity_gap_coefficients",
    "asperity_pressure_coefficients",
    "AsperityContact",
    "asperity_normal_contact",
    "asperity_tangential_state",
    "asperity_critical_creepage",
    "asperity_initial_slope",
    "AsperityTangentialContact",
    "asperity_tangential_contact",
    "asperity_creep_curve",
    "double_asperity_coefficients",
    "TwoPatchContact",
    "two_patch_normal_contact",
    "TwoPatchTangentialContact",
    "two_patch_tangential_contact",
    "HarmonicRoughness",
    "ProfileRoughness",
    "LocalGap",
    "local_gap",
    "RoughRailContact",
    "rough_rail_contact",
    "RoughRailSolver",
]
