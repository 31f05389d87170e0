"""One asperity (Nielsen 1998, Sec. 6.3 and 6.5.1): normal problem (6.1)-(6.10) with every
case of Table 6.1, tangential problem (6.29)-(6.41). The errata and conventions are listed in
:mod:`railcontact.roughness`; the arithmetic is in the compiled kernels of
:mod:`railcontact.roughness._kernels`, which the FMU step calls too.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .. import polynomial as _poly
from .._validation import check_range
from . import _kernels


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
    tiny = _poly.SERIES_LIMIT
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
