r"""Rough surfaces: one asperity and two interacting contact patches (Nielsen 1998, Ch. 6).

Built on the polynomial approach (:mod:`railcontact.polynomial`).

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

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import optimize

from . import _roughness_kernels as _kernels
from . import polynomial as _poly
from ._validation import check_choice, check_range

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


# ---------------------------------------------------------------------------------------------
# one asperity: geometry and normal problem (6.1)-(6.10), Table 6.1
# ---------------------------------------------------------------------------------------------
def normalised_load(normal_load, youngs_modulus, poisson_ratio):
    r"""``N~ = N / (pi E / (8 (1 - nu^2)))`` (text after (6.10)). [m]

    Parameters
    ----------
    normal_load : array_like
        Normal load per unit length, >= 0. [N/m]
    youngs_modulus : float
        > 0. [Pa]
    poisson_ratio : float
        In [0, 0.5). [-]
    """
    n = check_range("normal_load", normal_load, "N/m", 0.0, None)
    return n * 2.0 * _poly.kernel_factor(youngs_modulus, poisson_ratio)


def _check_lambdas(curvature, skewness, flatness):
    l2 = float(check_range("curvature", curvature, "1/m"))
    l3 = float(check_range("skewness", skewness, "1/m^2"))
    l4 = float(check_range("flatness", flatness, "1/m^3"))
    return l2, l3, l4


def asperity_gap_coefficients(curvature, skewness=0.0, flatness=0.0, height=0.0):
    r"""Ascending coefficients of the asperity (6.1): ``[l0, 0, l2/2, l3/6, l4/24]``. [m^(1-n)]

    Parameters
    ----------
    curvature : float
        ``lambda2 = Z''(0)``. [1/m]
    skewness : float, optional
        ``lambda3 = Z'''(0)``. [1/m^2]
    flatness : float, optional
        ``lambda4 = Z''''(0)``. [1/m^3]
    height : float, optional
        ``lambda0``. [m]
    """
    l2, l3, l4 = _check_lambdas(curvature, skewness, flatness)
    l0 = float(check_range("height", height, "m"))
    return np.array([l0, 0.0, l2 / 2.0, l3 / 6.0, l4 / 24.0])


def asperity_pressure_coefficients(half_width, shift, curvature, skewness=0.0, flatness=0.0):
    r"""``B_0..B_4`` of (6.4)-(6.8): ``p = (pi E/(4(1-nu^2))) sum B_n x^n / sqrt(a^2 - x^2)``.

    ``x = xbar - Delta`` is measured from the patch centre. B_0 is (6.4) as printed, i.e. it
    already uses the even boundary condition. [m^-n]

    Parameters
    ----------
    half_width : float
        ``a``, > 0. [m]
    shift : float
        ``Delta``. [m]
    curvature, skewness, flatness : float
        ``lambda2, lambda3, lambda4``. [1/m, 1/m^2, 1/m^3]
    """
    a = float(check_range("half_width", half_width, "m", 0.0, None, lower_closed=False))
    d = float(check_range("shift", shift, "m"))
    l2, l3, l4 = _check_lambdas(curvature, skewness, flatness)
    curv = l2 + l3 * d + 0.5 * l4 * d * d  # Z''(Delta)
    odd = d * (l2 + 0.5 * l3 * d + l4 * d * d / 6.0)  # Z'(Delta)
    skew = l3 + l4 * d  # Z'''(Delta)
    return np.array([a * a / np.pi * (curv + l4 * a * a / 12.0),
                     (0.25 * a * a * skew - odd) / np.pi,
                     (l4 * a * a / 12.0 - curv) / np.pi,
                     -skew / (2.0 * np.pi),
                     -l4 / (6.0 * np.pi)])


@dataclass(frozen=True)
class AsperityContact:
    r"""Normal contact of one asperity (result of :func:`asperity_normal_contact`).

    Attributes
    ----------
    half_width : float
        ``a``. [m]
    shift : float
        ``Delta``: patch centre relative to the asperity's contact point ``xbar = 0``. [m]
    normal_load : float
        [N/m]
    curvature, skewness, flatness : float
        ``lambda2, lambda3, lambda4``. [1/m, 1/m^2, 1/m^3]
    youngs_modulus : float
        [Pa]
    poisson_ratio : float
        [-]
    case : str
        Row of Table 6.1 used.
    method : str
        ``"closed form"`` or ``"numerical"``.
    """

    half_width: float
    shift: float
    normal_load: float
    curvature: float
    skewness: float
    flatness: float
    youngs_modulus: float
    poisson_ratio: float
    case: str
    method: str

    @property
    def geometric_coefficients(self):
        """``B_0..B_4`` of (6.4)-(6.8). [m^-n]"""
        return asperity_pressure_coefficients(self.half_width, self.shift, self.curvature,
                                              self.skewness, self.flatness)

    @property
    def normal_contact(self):
        """The same pressure as a :class:`railcontact.polynomial.PolynomialNormalContact`."""
        k = _poly.kernel_factor(self.youngs_modulus, self.poisson_ratio)
        b = self.geometric_coefficients / k * self.half_width ** np.arange(5)
        return _poly.PolynomialNormalContact(self.half_width, self.shift, b, self.normal_load,
                                             self.youngs_modulus, self.poisson_ratio)

    def pressure(self, x):
        """Pressure at ``xbar = x`` (asperity coordinate). [Pa]"""
        return self.normal_contact.pressure(x)


def asperity_normal_contact(normal_load, curvature, skewness, flatness, youngs_modulus,
                            poisson_ratio):
    r"""Contact half-width ``a`` and shift ``Delta`` of one asperity, (6.9)-(6.10), Table 6.1.

    Cases (Table 6.1), with ``N~ = 8 (1-nu^2) N / (pi E)``:

    ======================  ====================================================================
    lambda4 = 0, l3 = 0      Hertz: ``a = sqrt(N~/l2)``, ``Delta = 0``; needs ``l2 > 0``.
    lambda4 = 0, l3 != 0     cubic in ``a^2`` (closed form, corrected, see module erratum);
                             needs ``l2 > 0`` and ``(27/16) N~^2 l3^4 / l2^6 < 1``.
    l4 != 0, l3 = 0          ``a^2 = 4 (l2/l4)(sqrt(1 + l4 N~/(2 l2^2)) - 1)``; needs ``l2 > 0``
                             and ``l4 N~/(2 l2^2) > -1``; or, for ``l2 = 0``,
                             ``a = (8 N~/l4)^(1/4)`` with ``l4 > 0``.
    l4, l3 != 0, l2 = l3^2/(3 l4)
                             ``Delta = -l3/l4``, ``a^2 = 2 (l2/l4)(sqrt(1 + 2 l4 N~/l2^2) + 1)``
                             (corrected), a single patch bridging the two minima of this
                             symmetric double well; valid only if its pressure is >= 0.
    l4, l3 != 0, other l2 > 0
                             numerical: ``a^2(Delta)`` from (6.9), then (6.10) solved for
                             ``Delta`` by bracketing from ``Delta = 0`` (continuation from zero
                             load) and Brent's method.
    l2 = 0 with l3 != 0, or l2 < 0
                             "asperity is not convex": ``ValueError``.
    ======================  ====================================================================

    Parameters
    ----------
    normal_load : float
        Normal load per unit length, > 0. [N/m]
    curvature : float
        ``lambda2``, >= 0. [1/m]
    skewness : float
        ``lambda3``. [1/m^2]
    flatness : float
        ``lambda4``. [1/m^3]
    youngs_modulus : float
        > 0. [Pa]
    poisson_ratio : float
        In [0, 0.5). [-]

    Returns
    -------
    AsperityContact

    Raises
    ------
    ValueError
        Bad input, a restriction of Table 6.1 violated, or a negative pressure (contact not
        coherent); the message names the parameter and the restriction.
    """
    load = float(check_range("normal_load", normal_load, "N/m", 0.0, None, lower_closed=False))
    l2 = float(check_range("curvature", curvature, "1/m", 0.0, None,
                           condition="Table 6.1: asperity must be convex"))
    l3 = float(check_range("skewness", skewness, "1/m^2"))
    l4 = float(check_range("flatness", flatness, "1/m^3"))
    nt = float(normalised_load(load, youngs_modulus, poisson_ratio))
    kfac = float(_poly.kernel_factor(youngs_modulus, poisson_ratio))
    a, d, case = _kernels.asperity_normal(nt, l2, l3, l4, kfac)
    if case < 0:
        raise _asperity_normal_error(case, load, nt, l2, l3, l4)
    return AsperityContact(a, d, normal_load=load, curvature=l2, skewness=l3, flatness=l4,
                           youngs_modulus=float(youngs_modulus),
                           poisson_ratio=float(poisson_ratio), case=_CASES[case][0],
                           method=_CASES[case][1])


#: Table 6.1's case names and methods by the kernel's case code.
_CASES = {_kernels.CASE_HERTZ: ("l4 = 0, l3 = 0 (Hertz)", "closed form"),
          _kernels.CASE_A: ("l4 = 0, l3 != 0, l2 > 0", "closed form"),
          _kernels.CASE_B_FLAT: ("l4 != 0, l3 = 0, l2 = 0", "closed form"),
          _kernels.CASE_B: ("l4 != 0, l3 = 0, l2 > 0", "closed form"),
          _kernels.CASE_DOUBLE_WELL: ("l4, l3 != 0, l2 = l3^2/(3 l4)", "closed form"),
          _kernels.CASE_NUMERICAL: ("l4, l3 != 0, l2 > 0", "numerical")}


def _asperity_normal_error(case, load, nt, l2, l3, l4):
    """The ValueError for a failure code of the kernel ``asperity_normal``."""
    k = _kernels
    if case == k.NOT_CONVEX:
        return ValueError("curvature must be > 0 [1/m] when skewness != 0 or flatness = 0 "
                          f"(Table 6.1: asperity is not convex); got {l2:g}")
    if case == k.LOAD_TOO_LARGE_A:
        x = 27.0 / 16.0 * (nt * nt * l3**4 / l2**6)
        return ValueError("normal_load too large for this skewness: Table 6.1(A) needs "
                          f"(27/16) N~^2 l3^4 / l2^6 < 1 [N/m]; got {x:g} "
                          f"(normal_load = {load:g})")
    if case == k.FLATNESS_NOT_POSITIVE:
        return ValueError(f"flatness must be > 0 [1/m^3] when curvature = skewness = 0 "
                          f"(Table 6.1(B)); got {l4:g}")
    if case == k.LOAD_TOO_LARGE_B:
        return ValueError("normal_load too large for this negative flatness: Table 6.1(B) "
                          f"needs l4 N~ / (2 l2^2) > -1 [N/m]; got {0.5 * l4 * nt / l2**2:g} "
                          f"(normal_load = {load:g})")
    if case == k.NEGATIVE_PRESSURE_B:
        return ValueError("normal_load too large for this negative flatness [N/m]: "
                          "negative pressure (contact not coherent)")
    if case == k.NEGATIVE_PRESSURE_DOUBLE_WELL:
        return ValueError("normal_load too small: with curvature = skewness^2/(3 flatness) "
                          "the asperity is a symmetric double well and the single bridging "
                          "patch of Table 6.1(B) has negative pressure [N/m]; got "
                          f"normal_load = {load:g} (use two_patch_normal_contact)")
    if case == k.NEGATIVE_PRESSURE:
        return ValueError("normal_load: the single-patch solution has negative pressure "
                          f"(contact not coherent) [N/m]; got normal_load = {load:g}")
    return ValueError("normal_load: no coherent single-patch solution of (6.9)-(6.10) for "
                      f"these lambdas [N/m]; got normal_load = {load:g}")


# ---------------------------------------------------------------------------------------------
# one asperity: tangential problem (6.29)-(6.41)
# ---------------------------------------------------------------------------------------------
def _check_asperity(contact):
    if not isinstance(contact, AsperityContact):
        raise ValueError("contact must be an AsperityContact (from asperity_normal_contact); got "
                         f"{type(contact).__name__}")
    return contact


def asperity_tangential_state(contact, friction_coefficient, stick_ratio):
    r"""Creepage and force for a given stick ratio ``a*/a``, Eqs. (6.38)-(6.39) (mirrored).

    With the stick zone at the leading edge ``+x`` the stick-zone centre is
    ``Delta* = Delta + a - a*`` and (branch ``T >= 0``)

    ``xi = -mu [Delta* (l2 + l3 Delta*/2 + l4 Delta*^2/6) + a*^2 (l3 + l4 Delta*)/4]``,
    ``T = mu N - mu (pi E/(8(1-nu^2))) [(l2 + l3 Delta* + l4 Delta*^2/2) a*^2 + l4 a*^4/8]``.

    Parameters
    ----------
    contact : AsperityContact
        Normal solution.
    friction_coefficient : float
        >= 0. [-]
    stick_ratio : array_like
        ``a*/a`` in [0, 1]. [-]

    Returns
    -------
    creepage : ndarray
        (<= 0 on this branch). [-]
    tangential_force : ndarray
        (>= 0). [N/m]
    """
    c = _check_asperity(contact)
    mu = float(check_range("friction_coefficient", friction_coefficient, "-", 0.0, None))
    r = check_range("stick_ratio", stick_ratio, "-", 0.0, 1.0)
    xi, force = _kernels.tangential_state_array(*_asperity_args(c, mu), r.ravel())
    return xi.reshape(r.shape), force.reshape(r.shape)


def _asperity_args(c, mu):
    """The kernels' description of the asperity contact ``c``: ``(a, Delta, N, l2, l3, l4,
    pi E / (8 (1 - nu^2)), mu)``."""
    ref = np.pi * c.youngs_modulus / (8.0 * (1.0 - c.poisson_ratio**2))
    return (float(c.half_width), float(c.shift), float(c.normal_load), float(c.curvature),
            float(c.skewness), float(c.flatness), ref, mu)


def asperity_critical_creepage(contact, friction_coefficient):
    r"""Creepage magnitude at full slip, Eq. (6.40) (mirrored, with the factor ``mu``).

    ``xi_c = mu (Delta + a) (l2 + l3 (Delta + a)/2 + l4 (Delta + a)^2/6)``, i.e. ``mu`` times the
    asperity slope at the leading edge ``Z'(Delta + a)``.

    # erratum: (6.40) as printed lacks the factor mu of (6.38); verified against
    # railcontact.polynomial.tangential_state_polynomial in tests/test_roughness.py.

    Parameters
    ----------
    contact : AsperityContact
    friction_coefficient : float
        >= 0. [-]

    Returns
    -------
    float
        [-]
    """
    c = _check_asperity(contact)
    mu = float(check_range("friction_coefficient", friction_coefficient, "-", 0.0, None))
    return _kernels.critical_creepage(float(c.half_width), float(c.shift), c.curvature,
                                      c.skewness, c.flatness, mu)


def asperity_initial_slope(contact):
    r"""Initial slope of the creep curve, Eq. (6.41): ``dT/dxi -> -(pi E/(8(1-nu^2))) 2 a``. [N/m]

    Exact for a 4th-order asperity: proportional to the contact width, independent of the
    lambdas (checked by finite differences of (6.38)-(6.39) and of the general solver).
    """
    c = _check_asperity(contact)
    return -np.pi * c.youngs_modulus / (8.0 * (1.0 - c.poisson_ratio**2)) * 2.0 * c.half_width


@dataclass(frozen=True)
class AsperityTangentialContact:
    """Steady rolling on one asperity (result of :func:`asperity_tangential_contact`).

    Attributes
    ----------
    contact : AsperityContact
    friction_coefficient : float
        [-]
    creepage : float
        [-]
    tangential_force : float
        On the wheel, opposing the creepage. [N/m]
    stick_ratio : float
        ``a*/a``. [-]
    """

    contact: AsperityContact
    friction_coefficient: float
    creepage: float
    tangential_force: float
    stick_ratio: float

    def traction(self, x):
        r"""Traction on the wheel at ``xbar = x``, (6.29)-(6.37) mirrored. [Pa]

        ``q = -sign(xi) mu (p(x) - p*(x))`` with ``p*`` the pressure that the same asperity
        produces on the stick zone ``|x - Delta*| < a*`` ((6.33)-(6.37) with the creepage term
        absorbed by the boundary condition).
        """
        c = self.contact
        x = check_range("x", x, "m")
        r = self.stick_ratio
        p = c.pressure(x)
        if r > 0.0:
            a_s = r * c.half_width
            d_s = c.shift + c.half_width - a_s
            geo = asperity_pressure_coefficients(a_s, d_s, c.curvature, c.skewness, c.flatness)
            # (6.34): the creepage term moves B*_1 so that the odd boundary condition holds
            geo = geo.copy()
            geo[1] = -geo[3] * a_s**2
            k = _poly.kernel_factor(c.youngs_modulus, c.poisson_ratio)
            form = _poly.polynomial_form(geo / k, x - d_s, a_s)
            p = p - form
        return -np.sign(self.creepage) * self.friction_coefficient * p


def asperity_tangential_contact(contact, friction_coefficient, creepage=None,
                                tangential_force=None):
    r"""Steady rolling on one asperity: stick ratio and force (or creepage), (6.38)-(6.39).

    Parameters
    ----------
    contact : AsperityContact
        Normal solution.
    friction_coefficient : float
        >= 0. [-]
    creepage : float, optional
        [-]
    tangential_force : float, optional
        ``|T| <= mu N``. [N/m]  Exactly one of the two.

    Returns
    -------
    AsperityTangentialContact
        ``a*`` is the largest root in ``[0, a]`` (continuation from full stick); ``|xi| >= xi_c``
        (6.40) is full slip.
    """
    c = _check_asperity(contact)
    mu = float(check_range("friction_coefficient", friction_coefficient, "-", 0.0, None))
    if (creepage is None) == (tangential_force is None):
        raise ValueError("creepage and tangential_force: give exactly one of them; got "
                         f"creepage={creepage!r}, tangential_force={tangential_force!r}")

    args = _asperity_args(c, mu)
    tiny = _poly._SERIES_LIMIT
    if creepage is not None:
        xi = float(check_range("creepage", creepage, "-"))
        force, r, _, status = _kernels.asperity_tangential(*args, xi, tiny)
        if status == _kernels.SERIES_NEEDED:
            # (6.38)-(6.39) cancel as a* -> a: use the full-stick series of the Ch. 3 solver
            t = _poly.solve_tangential_polynomial(c.normal_contact, mu, creepage=creepage)
            return AsperityTangentialContact(c, mu, t.creepage, t.tangential_force,
                                             t.stick_ratio)
    else:
        force = float(check_range("tangential_force", tangential_force, "N/m",
                                  -mu * c.normal_load, mu * c.normal_load,
                                  condition="|T| <= mu N"))
        target = abs(force)
        if mu > 0 and 0 < target < tiny * mu * c.normal_load:
            t = _poly.solve_tangential_polynomial(c.normal_contact, mu,
                                                  tangential_force=tangential_force)
            return AsperityTangentialContact(c, mu, t.creepage, t.tangential_force,
                                             t.stick_ratio)
        r, status = 1.0, 0
        if target > 0:
            r, ok = _kernels.stick_ratio(*args, target, True)
            status = 0 if ok else _kernels.NO_ROOT
        # xi = sgn(-T) |xi(a*)|: the creepage of (6.38) has the sign of -T
        xi = float(np.sign(force) * _kernels.tangential_state(*args, r)[0]) if target > 0 \
            else 0.0
    if status == _kernels.NO_ROOT:
        raise ValueError("creepage: the stick ratio a*/a of (6.38)-(6.39) was not found "
                         f"(no sign change or no convergence) [-]; got creepage = {creepage}, "
                         f"tangential_force = {tangential_force}")
    return AsperityTangentialContact(c, mu, float(xi), float(force), float(r))


def asperity_creep_curve(contact, friction_coefficient, creepage):
    r"""Creep force on one asperity for an array of creepages (Fig. 6.8). [N/m]

    Parameters
    ----------
    contact : AsperityContact
    friction_coefficient : float
        >= 0. [-]
    creepage : array_like
        [-]
    """
    xi = check_range("creepage", creepage, "-")
    out = [asperity_tangential_contact(contact, friction_coefficient, creepage=float(v))
           .tangential_force for v in xi.ravel()]
    return np.asarray(out).reshape(xi.shape)


# ---------------------------------------------------------------------------------------------
# two patches with cross influence (6.12)-(6.28), (6.42)-(6.54)
# ---------------------------------------------------------------------------------------------
def double_asperity_coefficients(curvature):
    r"""The asperity ``A`` of Fig. 6.5: ``lambda3 = 0``, ``lambda4 = -1536 lambda2^3``, (6.26)-(6.28).

    Parameters
    ----------
    curvature : float
        ``lambda2 < 0`` (a trough between two minima at ``+-1/(16 |lambda2|)``). [1/m]

    Returns
    -------
    ndarray
        Gap coefficients ``[0, 0, l2/2, 0, l4/24]``. [m^(1-n)]
    """
    l2 = float(check_range("curvature", curvature, "1/m", None, 0.0, upper_closed=False))
    return asperity_gap_coefficients(l2, 0.0, -1536.0 * l2**3)


def _pv_basis(degree, s):
    """Matrix F[j, n] = PV int_-1^1 s'^n / ((s_j - s') sqrt(1 - s'^2)) ds' (stable outside)."""
    s = np.asarray(s, dtype=float)
    n = degree
    inside_vals = np.zeros((s.size, n + 1))
    if n >= 1:
        amat = _poly._unit_matrices(n)[0]
        vand = np.vander(s, n, increasing=True)
        inside_vals[:, 1:] = vand @ amat
    outside = np.abs(s) > 1.0
    so = np.where(outside, s, 2.0)
    root = np.sqrt(so * so - 1.0)
    w = np.sign(so) / (np.abs(so) + root)
    p2c = np.zeros((n + 1, n + 1))  # column k: Chebyshev coefficients of s^k
    for k in range(n + 1):
        p2c[: k + 1, k] = np.polynomial.chebyshev.poly2cheb(np.eye(n + 1)[k])[: k + 1]
    far = (np.pi * np.sign(so) / root)[:, None] * (np.vander(w, n + 1, increasing=True) @ p2c)
    return np.where(outside[:, None], far, inside_vals)


def _pv_basis_complex(degree, z):
    """Analytic continuation of the field of s^n off the cut [-1, 1] (for Taylor expansion)."""
    n = degree
    vals = np.zeros((z.size, n + 1), dtype=complex)
    if n >= 1:
        vals[:, 1:] = np.vander(z, n, increasing=True) @ _poly._unit_matrices(n)[0]
    factor = np.pi / (np.sqrt(z - 1.0) * np.sqrt(z + 1.0))
    return vals + factor[:, None] * np.vander(z, n + 1, increasing=True)


@dataclass(frozen=True)
class _Form:
    centre: float
    half_width: float


def _cross_matrix(target, source, degree, nodes, expansion):
    """Field of each normalised basis form of ``source`` at the ``nodes`` (target-normalised),
    as seen by the target patch: exact values ("chebyshev" = collocation) or the values of its
    Taylor polynomial of degree ``len(nodes)-1`` about the target centre ("taylor", thesis)."""
    m = nodes.size
    if expansion == "chebyshev":
        s = (target.centre + target.half_width * nodes - source.centre) / source.half_width
        return _pv_basis(degree, s) / source.half_width
    # Taylor coefficients by the Cauchy integral on a circle inside the convergence radius
    dist = (abs(target.centre - source.centre) - source.half_width) / target.half_width
    rho = 0.5 * dist
    nfft = max(64, 4 * m)
    theta = 2.0 * np.pi * np.arange(nfft) / nfft
    z = rho * np.exp(1j * theta)
    s = (target.centre + target.half_width * z - source.centre) / source.half_width
    vals = _pv_basis_complex(degree, s) / source.half_width
    coef = np.fft.fft(vals, axis=0)[:m] / nfft / rho ** np.arange(m)[:, None]
    return np.real(np.vander(nodes, m, increasing=True) @ coef)


def _nodes(m):
    return np.cos(np.pi * (np.arange(m) + 0.5) / m)


@dataclass(frozen=True)
class TwoPatchContact:
    r"""Normal contact with two separate patches (result of :func:`two_patch_normal_contact`).

    Attributes
    ----------
    patches : tuple of railcontact.polynomial.PolynomialNormalContact
        The two patches, ordered by position (``patches[1]`` is the leading one, the thesis'
        "first" patch). Each carries its own polynomial form; the pressure of the contact is
        their sum.
    normal_load : float
        Total load. [N/m]
    cross_influence : bool
        Whether the field of each patch acts on the other.
    expansion : str
        ``"chebyshev"`` or ``"taylor"``.
    degree : int
        Degree of the polynomial forms. [-]
    """

    patches: tuple
    normal_load: float
    cross_influence: bool
    expansion: str
    degree: int

    @property
    def loads(self):
        """Load on each patch. [N/m]"""
        return tuple(p.normal_load for p in self.patches)

    def pressure(self, x):
        """Total pressure at ``x``. [Pa]"""
        return self.patches[0].pressure(x) + self.patches[1].pressure(x)


def _slope_at(z, x):
    return np.polynomial.polynomial.polyval(x, np.polynomial.polynomial.polyder(z))


def _two_patch_linear(z, geo, loads, kern, degree, cross, expansion):
    """Solve the collocation + force equations for the two coefficient vectors."""
    m = degree
    nodes = _nodes(m)
    forms = [_Form(c, a) for a, c in geo]
    c_k = np.asarray(_poly.moment_ratios(m // 2 + 1))
    size = 2 * (m + 1)
    mat = np.zeros((size, size))
    rhs = np.zeros(size)
    for i in range(2):
        rows = slice(i * m, (i + 1) * m)
        own = _pv_basis(m, nodes) / forms[i].half_width
        mat[rows, i * (m + 1):(i + 1) * (m + 1)] = own
        if cross:
            j = 1 - i
            mat[rows, j * (m + 1):(j + 1) * (m + 1)] = _cross_matrix(forms[i], forms[j], m,
                                                                      nodes, expansion)
        rhs[rows] = _slope_at(z, forms[i].centre + forms[i].half_width * nodes) / kern
        row = 2 * m + i
        mat[row, i * (m + 1) + np.arange(0, m + 1, 2)] = np.pi * c_k[: m // 2 + 1]
        rhs[row] = loads[i]
    sol = np.linalg.solve(mat, rhs)
    return sol[: m + 1], sol[m + 1:]


def _outside_field_antiderivative(b, s):
    """Antiderivative in s of the normalised field PV int b(s')/((s - s') sqrt(1-s'^2)) ds' for
    |s| >= 1 (one side). With the Chebyshev coefficients c_k of b and w = 1/(t + sqrt(t^2-1)),
    t = |s|: pi w^k / sqrt(t^2-1) = -(pi/k) d(w^k)/dt and pi / sqrt(t^2-1) = -pi d(ln w)/dt."""
    cheb = np.polynomial.chebyshev.poly2cheb(b)
    t = abs(float(s))
    if s < 0:
        cheb = cheb * (-1.0) ** np.arange(cheb.size)
    w = 1.0 / (t + np.sqrt(max(t * t - 1.0, 0.0)))
    k = np.arange(1, cheb.size)
    return -np.pi * (cheb[0] * np.log(w) + (cheb[1:] * w**k / k).sum())


def _deformed_gap_jump(z, patches, kern):
    """h(inner edge of right patch) - h(inner edge of left patch) = int (Z' - K field) dX,
    with the field integrated in closed form (it is the outside field of both patches)."""
    lo = patches[0].centre + patches[0].half_width
    hi = patches[1].centre - patches[1].half_width
    jump = float(np.polynomial.polynomial.polyval(hi, z) - np.polynomial.polynomial.polyval(lo, z))
    for p in patches:
        s_lo = (lo - p.centre) / p.half_width
        s_hi = (hi - p.centre) / p.half_width
        b = p.normalised_coefficients
        jump -= kern * (_outside_field_antiderivative(b, s_hi)
                        - _outside_field_antiderivative(b, s_lo))
    return jump


def two_patch_normal_contact(gap_coefficients, normal_load, youngs_modulus, poisson_ratio,
                             centre_guesses, *, load_split=0.5, cross_influence=True, degree=8,
                             expansion="chebyshev"):
    r"""Normal contact of a gap with two minima and two separate patches, (6.12)-(6.25).

    Unknowns: the two polynomial forms (degree ``M = degree``), half-widths ``a1, a2`` and
    centres. For given geometry the forms follow linearly from the slope condition (6.20)-(6.21)
    at ``M`` Chebyshev nodes of each patch plus the load of each patch (6.24)-(6.25); the four
    boundary conditions (6.22)-(6.23) are then solved for the geometry by Powell's hybrid method,
    started from the solution without cross influence.

    Parameters
    ----------
    gap_coefficients : array_like
        Global gap ``Z(X)`` ascending, degree <= ``degree``. [m^(1-n)]
    normal_load : float
        Total load, > 0. [N/m]
    youngs_modulus : float
        > 0. [Pa]
    poisson_ratio : float
        In [0, 0.5). [-]
    centre_guesses : sequence of 2 floats
        Positions of the two minima of ``Z`` (start values). [m]
    load_split : float or "compatible", optional
        Fraction of the load carried by the patch at the smaller ``X`` (the thesis leaves this
        open and uses equal shares for its symmetric example: 0.5). ``"compatible"``: the share
        that makes the deformed gap close at both patches (one more equation, the relative
        displacement between the patches integrated from the exact fields).
    cross_influence : bool, optional
        Include the field of each patch on the other (default) or not (independent patches).
    degree : int, optional
        Degree ``M`` of the polynomial forms, >= degree of the gap (thesis: 4). With cross
        influence a higher ``M`` represents the other patch's field better. [-]
    expansion : {"chebyshev", "taylor"}, optional
        How the other patch's field is made polynomial: interpolation at the Chebyshev nodes
        (default) or Taylor expansion about the patch centre (thesis, text after (6.21)).

    Returns
    -------
    TwoPatchContact

    Raises
    ------
    ValueError
        Bad input; patches overlapping or merged; no convergence; negative pressure.
    """
    z = _poly._check_coefficients("gap_coefficients", gap_coefficients, "m^(1-n)", 3)
    load = float(check_range("normal_load", normal_load, "N/m", 0.0, None, lower_closed=False))
    kern = float(_poly.kernel_factor(youngs_modulus, poisson_ratio))
    m = _poly._check_degree(degree, lower=max(2, z.size - 1))
    check_choice("expansion", expansion, {"chebyshev", "taylor"})
    guesses = np.sort(check_range("centre_guesses", centre_guesses, "m"))
    if guesses.shape != (2,) or guesses[0] == guesses[1]:
        raise ValueError(f"centre_guesses must be two distinct positions [m]; got {centre_guesses!r}")
    compatible = isinstance(load_split, str)
    if compatible:
        check_choice("load_split", load_split, {"compatible"})
        if not cross_influence:
            raise ValueError("load_split='compatible' needs cross_influence=True")
        frac0 = 0.5
    else:
        frac0 = float(check_range("load_split", load_split, "-", 0.0, 1.0, lower_closed=False,
                                  upper_closed=False))
    zp = np.zeros(m + 1)
    zp[: z.size] = z

    def independent(frac, total):
        out = []
        for g, share in zip(guesses, (frac, 1.0 - frac)):
            nc = _poly.solve_normal_polynomial(z, share * total, youngs_modulus, poisson_ratio,
                                               centre_guess=g)
            out.append((nc.half_width, nc.centre))
        return np.array([out[0][0], out[1][0], out[0][1], out[1][1], frac])

    def build(v, total):
        geo = [(v[0], v[2]), (v[1], v[3])]
        frac = v[4]
        b, g = _two_patch_linear(zp, geo, (frac * total, (1 - frac) * total), kern, m,
                                 cross_influence, expansion)
        return geo, frac, b, g

    def coupled(total, v0):
        """Powell hybrid solve for (a1, a2, c1, c2[, frac]) at the load ``total`` from v0."""
        scale = np.array([v0[0], v0[1], v0[0], v0[1], 1.0])
        nvar = 5 if compatible else 4

        def unpack(u):
            v = v0.copy()
            v[:nvar] = v0[:nvar] + scale[:nvar] * u
            return v

        def residual(u):
            v = unpack(u)
            if v[0] <= 0 or v[1] <= 0 or not 0 < v[4] < 1 or v[2] + v[0] >= v[3] - v[1]:
                return np.full(nvar, 1e3)
            geo, frac, b, g = build(v, total)
            sign = (-1.0) ** np.arange(m + 1)
            res = [b.sum() / total, (sign * b).sum() / total, g.sum() / total,
                   (sign * g).sum() / total]
            if compatible:
                patches = _patches(geo, b, g, youngs_modulus, poisson_ratio)
                res.append(_deformed_gap_jump(z, patches, kern) / (kern * total))
            return np.array(res)

        sol = optimize.root(residual, np.zeros(nvar), method="hybr", tol=1e-13)
        res = np.abs(residual(sol.x)).max()
        return res < 1e-9, unpack(sol.x), res

    ok = False
    res = np.inf
    try:
        v = independent(frac0, load)
    except ValueError:
        v = None
    if v is not None:
        if v[2] + v[0] >= v[3] - v[1]:
            raise ValueError("normal_load: the patches overlap already without cross influence "
                             "(one coherent patch: use railcontact.polynomial."
                             f"solve_normal_polynomial) [N/m]; got {load:g}")
        ok, v, res = coupled(load, v)
    if not ok:
        # continuation in the load, starting where the independent patches are small and far
        # apart (needed when a patch reaches the concave flank between the minima, where the
        # independent single-patch problem has no solution)
        for first in (0.5, 0.2, 0.05, 1e-2, 1e-3, 1e-4):
            try:
                v = independent(frac0, first * load)
            except ValueError:
                continue
            for total in load * np.geomspace(first, 1.0, 10)[1:]:
                ok, v, res = coupled(total, v)
                if not ok:
                    break
            break
    if not ok:
        raise ValueError("normal_load: the two-patch problem did not converge (residual "
                         f"{res:.3g}); the patches may have merged [N/m]; got {load:g}")
    geo, frac, b, g = build(v, load)
    patches = _patches(geo, b, g, youngs_modulus, poisson_ratio)
    if patches[0].centre + patches[0].half_width >= patches[1].centre - patches[1].half_width:
        raise ValueError(f"normal_load: the two patches merge [N/m]; got {load:g}")
    for p in patches:
        if not _poly._pressure_is_physical(p.normalised_coefficients, tol=1e-7):
            raise ValueError(f"normal_load: negative pressure in a patch [N/m]; got {load:g}")
    return TwoPatchContact(tuple(patches), load, bool(cross_influence), expansion, m)


def _patches(geo, b, g, e, nu):
    out = []
    for (a, c), coef in zip(geo, (b, g)):
        out.append(_poly.PolynomialNormalContact(float(a), float(c), coef,
                                                 _poly._force_from_normalised(coef),
                                                 float(e), float(nu)))
    return out


@dataclass(frozen=True)
class TwoPatchTangentialContact:
    r"""Steady rolling on two patches (result of :func:`two_patch_tangential_contact`).

    Attributes
    ----------
    normal : TwoPatchContact
    friction_coefficient : float
        [-]
    creepage : float
        Common creepage of both patches (stationary contact). [-]
    forces : tuple of float
        Force on the wheel per patch (ordered like ``normal.patches``). [N/m]
    stick_ratios : tuple of float
        ``a_i*/a_i``. [-]
    stick_coefficients : tuple of ndarray
        Normalised coefficients of each stick-zone form in ``(x - c_i*)/a_i*``. [N/m]
    cross_influence : bool
    """

    normal: TwoPatchContact
    friction_coefficient: float
    creepage: float
    forces: tuple
    stick_ratios: tuple
    stick_coefficients: tuple
    cross_influence: bool

    @property
    def tangential_force(self):
        """Total force. [N/m]"""
        return float(sum(self.forces))

    def traction(self, x):
        """Traction on the wheel at ``x``. [Pa]"""
        x = check_range("x", x, "m")
        total = self.normal.pressure(x)
        for p, r, e in zip(self.normal.patches, self.stick_ratios, self.stick_coefficients):
            if r > 0:
                a_s = r * p.half_width
                c_s = p.centre + p.half_width - a_s
                total = total + _poly.polynomial_form(e / a_s ** np.arange(e.size), x - c_s, a_s)
        return -np.sign(self.creepage) * self.friction_coefficient * total


def two_patch_tangential_contact(normal, friction_coefficient, creepage, *, cross_influence=None):
    r"""Steady rolling with a common creepage on two patches, (6.42)-(6.51).

    Each patch gets ``q_i = mu p_i + q_i*`` with a stick zone at its leading edge (6.46)-(6.47).
    The stick conditions (6.48)-(6.49) include the fields of all four forms; the other patch's
    fields are made polynomial as in the normal problem (``normal.expansion``). For given stick
    ratios the two stick forms are linear (collocation at ``M`` Chebyshev nodes per stick zone +
    even boundary conditions); the odd boundary conditions are solved for the two stick ratios by
    Powell's hybrid method from the solution without cross influence.

    Parameters
    ----------
    normal : TwoPatchContact
        Normal solution (the thesis uses the one *with* cross influence for both variants).
    friction_coefficient : float
        > 0. [-]
    creepage : float
        Common creepage ``xi != 0``; both patches must be in partial slip. [-]
    cross_influence : bool, optional
        Default: ``normal.cross_influence``.

    Returns
    -------
    TwoPatchTangentialContact

    Raises
    ------
    ValueError
        Bad input, a patch in full slip (stick zone vanishing) or no convergence.
    """
    if not isinstance(normal, TwoPatchContact):
        raise ValueError("normal must be a TwoPatchContact (from two_patch_normal_contact); got "
                         f"{type(normal).__name__}")
    mu = float(check_range("friction_coefficient", friction_coefficient, "-", 0.0, None,
                           lower_closed=False))
    xi = float(check_range("creepage", creepage, "-"))
    if xi == 0.0:
        raise ValueError("creepage must be non-zero [-]; got 0")
    cross = normal.cross_influence if cross_influence is None else bool(cross_influence)
    patches = normal.patches
    m = normal.degree
    e_mod, nu = patches[0].youngs_modulus, patches[0].poisson_ratio
    kern = float(_poly.kernel_factor(e_mod, nu))
    target = abs(xi) / (kern * mu)
    nodes = _nodes(m)
    # independent solutions: start values, and the answer without cross influence
    indep = [_poly.solve_tangential_polynomial(p, mu, creepage=xi) for p in patches]
    r0 = np.array([t.stick_ratio for t in indep])
    if np.any(r0 <= 0.0):
        raise ValueError("creepage: a patch is in full slip; the two-patch tangential problem "
                         f"needs partial slip on both [-]; got {xi:g}")
    c_k = np.asarray(_poly.moment_ratios(m // 2 + 1))
    pforms = [_Form(p.centre, p.half_width) for p in patches]

    def stick_forms(r):
        return [_Form(p.centre + p.half_width * (1 - ri), p.half_width * ri)
                for p, ri in zip(patches, r)]

    def linear(r):
        sforms = stick_forms(r)
        size = 2 * (m + 1)
        mat = np.zeros((size, size))
        rhs = np.zeros(size)
        for i in range(2):
            rows = slice(i * m, (i + 1) * m)
            x = sforms[i].centre + sforms[i].half_width * nodes
            known = np.zeros(m)
            for j in range(2):
                if j == i or cross:
                    sj = (x - pforms[j].centre) / pforms[j].half_width
                    if j != i and normal.expansion == "taylor":
                        known += _cross_matrix(sforms[i], pforms[j], m, nodes, "taylor") @ \
                            patches[j].normalised_coefficients
                    else:
                        known += (_pv_basis(m, sj) / pforms[j].half_width) @ \
                            patches[j].normalised_coefficients
            mat[rows, i * (m + 1):(i + 1) * (m + 1)] = _pv_basis(m, nodes) / sforms[i].half_width
            if cross:
                j = 1 - i
                mat[rows, j * (m + 1):(j + 1) * (m + 1)] = _cross_matrix(
                    sforms[i], sforms[j], m, nodes, normal.expansion)
            rhs[rows] = target - known
            row = 2 * m + i
            mat[row, i * (m + 1) + np.arange(0, m + 1, 2)] = 1.0  # even boundary condition
        sol = np.linalg.solve(mat, rhs)
        return sol[: m + 1], sol[m + 1:]

    def residual(r):
        if np.any(r <= 0) or np.any(r > 1):
            return np.array([1e3, 1e3])
        e1, e2 = linear(r)
        return np.array([e1[1::2].sum(), e2[1::2].sum()]) / (
            patches[0].normal_load + patches[1].normal_load)

    if cross:
        sol = optimize.root(residual, r0, method="hybr", tol=1e-13)
        r = sol.x
        res = residual(r)
        if not (np.all(np.abs(res) < 1e-9) and np.all((r > 0) & (r <= 1))):
            raise ValueError("creepage: the two-patch tangential problem did not converge "
                             f"(residual {np.abs(res).max():.3g}) [-]; got {xi:g}")
        e1, e2 = linear(r)
        coefs = (e1, e2)
    else:
        r = r0
        coefs = tuple(t.stick_coefficients * ri ** np.arange(m + 1) for t, ri in zip(indep, r0))
    forces = tuple(float(-np.sign(xi) * mu * (p.normal_load + np.pi * (c_k @ e[0::2])))
                   for p, e in zip(patches, coefs))
    return TwoPatchTangentialContact(normal, mu, xi, forces, tuple(float(v) for v in r),
                                     tuple(coefs), cross)


# ---------------------------------------------------------------------------------------------
# a rough rail under a rolling wheel: local 4th-order gap at a wheel position
# ---------------------------------------------------------------------------------------------
def _surface_derivatives(roughness, rail_position):
    """``r .. r''''`` of a HarmonicRoughness or ProfileRoughness at ``rail_position``."""
    x = np.asarray(rail_position, dtype=float)
    out = _kernels.surface_derivatives_array(*roughness._kernel_surface,
                                             np.ascontiguousarray(x.ravel()))
    return out.reshape((5,) + x.shape)


class HarmonicRoughness:
    r"""Rail roughness as a sum of harmonics, the rail surface height of Eq. (4.1).

    ``r(X) = sum_m Z_A,m cos(k_m X) + Z_B,m sin(k_m X)``, ``k_m = 2 pi / L_m``: the same surface
    (height up, towards the wheel) as :mod:`railcontact.corrugation` describes with the same
    three lists. Derivatives are exact: ``r^(n)(X) = Re[(Z_A - i Z_B) (i k)^n e^(i k X)]``.

    Parameters
    ----------
    wavelengths : array_like, shape (M,)
        ``L_m``, > 0. [m]
    amplitudes_cos, amplitudes_sin : array_like, shape (M,)
        ``Z_A,m``, ``Z_B,m``. [m]
    """

    def __init__(self, wavelengths, amplitudes_cos, amplitudes_sin):
        lam = np.atleast_1d(check_range("wavelengths", wavelengths, "m", 0.0, None,
                                        lower_closed=False))
        za = np.atleast_1d(check_range("amplitudes_cos", amplitudes_cos, "m"))
        zb = np.atleast_1d(check_range("amplitudes_sin", amplitudes_sin, "m"))
        if not (lam.shape == za.shape == zb.shape) or lam.ndim != 1 or lam.size == 0:
            raise ValueError("wavelengths, amplitudes_cos, amplitudes_sin must be non-empty 1-D "
                             f"of equal length [m]; got shapes {lam.shape}, {za.shape}, "
                             f"{zb.shape}")
        self.wavelengths, self.amplitudes_cos, self.amplitudes_sin = lam, za, zb
        self._k = 2.0 * np.pi / lam
        self._zeta = za - 1j * zb
        # (i k)^n (Z_A - i Z_B) for n = 0..4, shape (5, M)
        coef = (1j * self._k) ** np.arange(5)[:, None] * self._zeta
        self._kernel_surface = (_kernels.HARMONIC, self._k, np.stack((coef.real, coef.imag)),
                                np.zeros(2))

    def derivatives(self, rail_position):
        r"""``r, r', r'', r''', r''''`` at ``rail_position``. [m, -, 1/m, 1/m^2, 1/m^3]

        ``r^(n)(X) = sum_m Re[(i k_m)^n (Z_A,m - i Z_B,m) e^(i k_m X)]``.

        Returns
        -------
        ndarray, shape (5,) + shape of rail_position
        """
        return _surface_derivatives(self, rail_position)

    def max_height_curvature(self):
        r"""``sum_m k_m^2 |Z_m|``, an upper bound of ``r''(X)``. [1/m]

        Exact (the supremum over X) for one harmonic and for rationally independent wave
        numbers (Kronecker); for commensurate wave lengths it may overestimate.
        """
        return float(np.sum(self._k**2 * np.abs(self._zeta)))

    def max_slope(self):
        """``sum_m k_m |Z_m|``, an upper bound of ``|r'(X)|``. [-]"""
        return float(np.sum(self._k * np.abs(self._zeta)))


class ProfileRoughness:
    r"""Rail roughness from a sampled height profile, interpolated by a quintic (C4) spline.

    :func:`scipy.interpolate.make_interp_spline` with ``k = 5`` through the samples; the
    derivatives up to 4th order are continuous inside the profile.

    Outside the sampled range (``extension``):

    * ``"periodic"``: the profile repeats with period ``positions[-1] - positions[0]``; the
      spline has periodic end conditions, so the surface is C4 everywhere. Needs
      ``heights[-1] == heights[0]`` (within 1e-12 of the largest height).
    * ``"hold"``: the spline has zero 1st and 2nd derivatives at both ends and the end heights
      are held outside (a flat rail): the surface is C2 at the ends (``r'''`` and ``r''''`` jump
      there, so the 4th-order gap coefficients do).

    Parameters
    ----------
    positions : array_like, shape (n,)
        Rail positions of the samples, strictly increasing, n >= 6. [m]
    heights : array_like, shape (n,)
        Rail surface height at them (up, towards the wheel, as in Eq. (4.1)). [m]
    extension : {"periodic", "hold"}
        See above.
    """

    def __init__(self, positions, heights, extension="periodic"):
        from scipy.interpolate import PPoly, make_interp_spline

        x = check_range("positions", positions, "m")
        y = check_range("heights", heights, "m")
        check_choice("extension", extension, {"periodic", "hold"})
        if x.ndim != 1 or x.shape != y.shape or x.size < 6:
            raise ValueError("positions and heights must be 1-D of equal length >= 6 (quintic "
                             f"spline) [m]; got shapes {x.shape}, {y.shape}")
        if np.any(np.diff(x) <= 0.0):
            raise ValueError("positions must be strictly increasing [m]")
        if extension == "periodic":
            tol = 1e-12 * max(np.abs(y).max(), np.finfo(float).tiny)
            if abs(y[-1] - y[0]) > tol:
                raise ValueError("heights: a periodic profile needs heights[-1] == heights[0] "
                                 f"[m]; got {y[0]:g} and {y[-1]:g} (use extension = 'hold')")
            y = y.copy()
            y[-1] = y[0]
            spline = make_interp_spline(x, y, k=5, bc_type="periodic")
        else:
            ends = [(1, 0.0), (2, 0.0)]
            spline = make_interp_spline(x, y, k=5, bc_type=(ends, ends))
        self.positions, self.heights, self.extension = x, y, extension
        self.spline = spline
        self._start, self._period = float(x[0]), float(x[-1] - x[0])
        self._ppoly = PPoly.from_spline(spline)
        # piecewise-polynomial coefficients of r, r', ..., r^(4) (highest power first, padded
        # with leading zeros to the quintic's 6) for a direct Horner evaluation of all five
        c = self._ppoly.c
        coef = np.zeros((5,) + c.shape)
        for n in range(5):
            cn = self._ppoly.derivative(n).c if n else c
            coef[n, c.shape[0] - cn.shape[0]:] = cn
        kind = _kernels.PERIODIC_PROFILE if extension == "periodic" else _kernels.HELD_PROFILE
        self._kernel_surface = (kind, np.ascontiguousarray(self._ppoly.x), coef,
                                np.array([self._start, self._period]))
        self._max_curvature = self._max_of_derivative(2)
        self._max_slope = self._max_of_derivative(1, absolute=True)

    def derivatives(self, rail_position):
        r"""``r, r', r'', r''', r''''`` at ``rail_position``. [m, -, 1/m, 1/m^2, 1/m^3]

        Returns
        -------
        ndarray, shape (5,) + shape of rail_position
        """
        return _surface_derivatives(self, rail_position)

    def _max_of_derivative(self, order, absolute=False):
        """Exact max of ``r^(order)`` (or of its magnitude) over the profile (critical points
        of the piecewise polynomial and the knots)."""
        p = self._ppoly.derivative(order)
        crit = self._ppoly.derivative(order + 1).roots(extrapolate=False)
        pts = np.concatenate((self._ppoly.x, crit[np.isfinite(crit)]))
        pts = pts[(pts >= self._start) & (pts <= self._start + self._period)]
        v = p(pts)
        if absolute:
            v = np.abs(v)
        best = float(v.max())
        return max(best, 0.0) if self.extension == "hold" else best

    def max_height_curvature(self):
        """``max_X r''(X)`` (exact, over the profile and its extension). [1/m]"""
        return self._max_curvature

    def max_slope(self):
        """``max_X |r'(X)|`` (exact). [-]"""
        return self._max_slope


@dataclass(frozen=True)
class LocalGap:
    r"""The gap between wheel and rough rail expanded about its minimum (:func:`local_gap`).

    ``Z(x) = l0 + l2 x^2/2 + l3 x^3/6 + l4 x^4/24`` with ``x`` from the contact point, which
    lies ``contact_point_shift`` ahead (+X) of the wheel axis.

    Attributes
    ----------
    contact_point_shift : ndarray
        ``x_c``: gap minimum relative to the wheel axis. [m]
    curvature : ndarray
        ``lambda2 = 1/R - r''(X + x_c)``. [1/m]
    skewness : ndarray
        ``lambda3 = -r'''(X + x_c)``. [1/m^2]
    flatness : ndarray
        ``lambda4 = -r''''(X + x_c)``. [1/m^3]
    rail_height : ndarray
        ``r(X + x_c)``. [m]
    """

    contact_point_shift: np.ndarray
    curvature: np.ndarray
    skewness: np.ndarray
    flatness: np.ndarray
    rail_height: np.ndarray


def _check_gap(roughness, radius):
    """The surface type, ``radius > 0`` and the convexity ``R max r'' < 1``: the radius."""
    if not isinstance(roughness, (HarmonicRoughness, ProfileRoughness)):
        raise ValueError("roughness must be a HarmonicRoughness or ProfileRoughness; got "
                         f"{type(roughness).__name__}")
    big_r = float(check_range("radius", radius, "m", 0.0, None, lower_closed=False))
    check_range("radius * max_height_curvature", big_r * roughness.max_height_curvature(), "-",
                None, 1.0, upper_closed=False,
                condition="the gap x^2/(2R) - r(X + x) must be convex: R max r'' < 1, "
                          "Eq. (4.2) generalised")
    return big_r


def local_gap(roughness, rail_position, radius, *, max_iter=60):
    r"""Local 4th-order gap of a wheel (equivalent radius R) on a rough rail, about its minimum.

    In the frame of the wheel axis at rail position ``X`` the undeformed gap is
    ``h(x) = x^2/(2R) - r(X + x)`` (the wheel's parabola (4.3) and the rail height ``r``, up
    positive, as in :func:`railcontact.reference.halfspace2d.solve_quasistatic_corrugated_2d`).
    Its minimum ``x_c`` (``h'(x_c) = x_c/R - r'(X + x_c) = 0``, unique because ``h`` is convex)
    is found by a safeguarded Newton iteration (bisection inside the bracket
    ``|x_c| <= R max|r'|``), and ``h`` is expanded there to 4th order: the lambdas of Nielsen's
    asperity (6.1) with no linear term, ``lambda2 = 1/R - r''``, ``lambda3 = -r'''``,
    ``lambda4 = -r''''`` at ``X + x_c``. The patch of the asperity solution is centred at
    ``x_c + Delta`` from the wheel axis.

    Parameters
    ----------
    roughness : HarmonicRoughness or ProfileRoughness
        Rail surface height.
    rail_position : array_like
        Wheel axis position(s) ``X``. [m]
    radius : float
        Equivalent radius ``R``, > 0. [m]
    max_iter : int, optional
        Newton/bisection iterations at most. [-]

    Returns
    -------
    LocalGap

    Raises
    ------
    ValueError
        Bad input, or the gap is not convex everywhere: ``R max r'' >= 1`` (the generalisation of
        condition (4.2); the rail is then more curved than the wheel somewhere and a second
        contact can appear).
    """
    big_r = _check_gap(roughness, radius)
    x_axis = check_range("rail_position", rail_position, "m")
    bound = big_r * roughness.max_slope()
    out, converged = _kernels.local_gap_array(*roughness._kernel_surface,
                                              np.ascontiguousarray(x_axis.ravel()), big_r,
                                              bound, int(max_iter))
    if not converged:
        raise ValueError("rail_position: the gap minimum did not converge in max_iter = "
                         f"{max_iter} iterations [m]")
    out = out.reshape((5,) + x_axis.shape)
    return LocalGap(contact_point_shift=out[0], curvature=out[1], skewness=out[2],
                    flatness=out[3], rail_height=out[4])


@dataclass(frozen=True)
class RoughRailContact:
    r"""Contact of a wheel on a rough rail at one position (:func:`rough_rail_contact`).

    Attributes
    ----------
    gap : LocalGap
        The local 4th-order gap (its lambdas and the contact point ``x_c``).
    normal : AsperityContact
        Ch. 6 normal solution of that gap (half-width ``a``, shift ``Delta``).
    tangential : AsperityTangentialContact
        Ch. 6 steady rolling solution (stick ratio ``a*/a``, force).
    critical_creepage : float
        Full-slip creepage magnitude, Eq. (6.40) (with its factor mu). [-]
    """

    gap: LocalGap
    normal: AsperityContact
    tangential: AsperityTangentialContact
    critical_creepage: float

    @property
    def half_width(self):
        """``a``. [m]"""
        return self.normal.half_width

    @property
    def patch_shift(self):
        """Patch centre relative to the wheel axis, ``x_c + Delta``. [m]"""
        return float(self.gap.contact_point_shift) + self.normal.shift

    @property
    def stick_ratio(self):
        """``a*/a``. [-]"""
        return self.tangential.stick_ratio

    @property
    def tangential_force(self):
        """Force on the wheel, opposing the creepage. [N/m]"""
        return self.tangential.tangential_force


def rough_rail_contact(roughness, rail_position, normal_load, radius, youngs_modulus,
                       poisson_ratio, friction_coefficient, creepage):
    r"""Normal and steady tangential contact of a wheel on a rough rail at one position.

    :func:`local_gap` gives the 4th-order gap about the gap minimum; Nielsen's single-asperity
    solution (:func:`asperity_normal_contact`, Table 6.1, and
    :func:`asperity_tangential_contact`, (6.38)-(6.40)) gives the contact and the creep force.
    Quasi-static: the rail surface is frozen at each position (as in Ch. 4's quasi-static
    corrugated contact). The 4th-order gap is the Taylor expansion of the true gap, so the
    result converges to the exact contact as the half-width becomes small against the
    roughness wave lengths (measured in ``tests/test_roughness.py``: errors of order
    ``(k a)^2`` relative).

    Parameters
    ----------
    roughness : HarmonicRoughness or ProfileRoughness
    rail_position : float
        Wheel axis position ``X``. [m]
    normal_load : float
        Normal load per unit length, > 0. [N/m]
    radius : float
        Equivalent radius ``R``, > 0. [m]
    youngs_modulus : float
        > 0. [Pa]
    poisson_ratio : float
        In [0, 0.5). [-]
    friction_coefficient : float
        >= 0. [-]
    creepage : float
        Longitudinal creepage. [-]

    Returns
    -------
    RoughRailContact

    Raises
    ------
    ValueError
        Bad input (a load whose normalised value underflows counts as no contact and is
        rejected); the gap not convex (see :func:`local_gap`); or a restriction of Table 6.1
        fails at this position (the local quartic gap has no single coherent patch for this
        load, typically a strongly negative flatness on a crest when the half-width is not
        small against the roughness wave length): the message names ``rail_position`` and the
        restriction.
    """
    x = float(check_range("rail_position", rail_position, "m"))
    if float(normalised_load(normal_load, youngs_modulus, poisson_ratio)) < np.finfo(float).tiny:
        raise ValueError("normal_load must be > 0 with a normalised load 8 (1 - nu^2) N / (pi E) "
                         "of at least 2.2e-308 m (no contact below) [N/m]; got "
                         f"{float(normal_load):g}")
    gap = local_gap(roughness, x, radius)
    l2, l3, l4 = float(gap.curvature), float(gap.skewness), float(gap.flatness)
    try:
        normal = asperity_normal_contact(normal_load, l2, l3, l4, youngs_modulus, poisson_ratio)
    except ValueError as exc:
        raise ValueError(f"rail_position = {x:g} m: the local 4th-order gap (curvature {l2:.6g} "
                         f"1/m, skewness {l3:.6g} 1/m^2, flatness {l4:.6g} 1/m^3) has no "
                         f"single-patch solution of Table 6.1: {exc}") from None
    tangential = asperity_tangential_contact(normal, friction_coefficient, creepage=creepage)
    return RoughRailContact(gap, normal, tangential,
                            float(asperity_critical_creepage(normal, friction_coefficient)))


class RoughRailSolver:
    r""":func:`rough_rail_contact` at many positions, for a fixed surface, radius and material.

    The FMU's Roughness effect calls it once per step. The surface, radius and material are
    checked once here; :meth:`contact` returns plain floats from one compiled kernel (the same
    kernels as :func:`local_gap`, :func:`asperity_normal_contact` and
    :func:`asperity_tangential_contact`) and calls :func:`rough_rail_contact` itself where
    that raises (a non-finite position or creepage, an underflowing normalised load, a
    restriction of Table 6.1) or uses the full-stick series of Ch. 3 (``0 < |creepage| <
    1e-4 critical creepage``), so the errors and results are the public function's.

    Parameters
    ----------
    roughness : HarmonicRoughness or ProfileRoughness
    radius : float
        Equivalent radius ``R``, > 0, with ``R max r'' < 1``. [m]
    youngs_modulus : float
        > 0. [Pa]
    poisson_ratio : float
        In [0, 0.5). [-]
    """

    def __init__(self, roughness, radius, youngs_modulus, poisson_ratio):
        self.radius = _check_gap(roughness, radius)
        self.roughness = roughness
        self.youngs_modulus, self.poisson_ratio = float(youngs_modulus), float(poisson_ratio)
        kfac = float(_poly.kernel_factor(youngs_modulus, poisson_ratio))
        e, nu = self.youngs_modulus, self.poisson_ratio
        self._constants = (self.radius * roughness.max_slope(), kfac,
                           np.pi * e / (8.0 * (1.0 - nu**2)))
        self._surface = roughness._kernel_surface
        self._nt_per_load = 2.0 * kfac              # normalised_load: n * 2.0 * K

    def contact(self, rail_position, normal_load, friction_coefficient, creepage):
        """:func:`rough_rail_contact` as floats.

        Returns
        -------
        tuple of float
            ``(x_c, lambda2, lambda3, lambda4, a, Delta, force, stick_ratio,
            critical_creepage)``: the gap minimum's shift [m], the lambdas, the half-width
            and shift [m], the tangential force [N/m], ``a*/a`` and Eq. (6.40)'s critical
            creepage.
        """
        nt = normal_load * self._nt_per_load
        if (2.2250738585072014e-308 <= nt < math.inf and math.isfinite(rail_position)
                and math.isfinite(creepage) and 0.0 <= friction_coefficient < math.inf):
            bound, kfac, ref = self._constants
            *values, status = _kernels.rough_rail_contact(
                *self._surface, rail_position, normal_load, nt, self.radius, bound, kfac, ref,
                friction_coefficient, creepage, _poly._SERIES_LIMIT)
            if status == 0:
                return tuple(values)
        res = rough_rail_contact(self.roughness, rail_position, normal_load, self.radius,
                                 self.youngs_modulus, self.poisson_ratio, friction_coefficient,
                                 creepage)
        gap = res.gap
        return (float(gap.contact_point_shift), float(gap.curvature), float(gap.skewness),
                float(gap.flatness), float(res.half_width), float(res.normal.shift),
                float(res.tangential_force), float(res.stick_ratio),
                float(res.critical_creepage))

    def local_gap(self, rail_position):
        """:func:`local_gap` at one position as floats: ``(x_c, lambda2, lambda3, lambda4)``."""
        if math.isfinite(rail_position):
            xc, l2, l3, l4, _, converged = _kernels.local_gap(
                *self._surface, rail_position, self.radius, self._constants[0], 60)
            if converged:
                return xc, l2, l3, l4
        gap = local_gap(self.roughness, rail_position, self.radius)
        return (float(gap.contact_point_shift), float(gap.curvature), float(gap.skewness),
                float(gap.flatness))
