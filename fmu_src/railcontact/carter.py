r"""Carter's (1926) solution of the 2-D steady rolling contact of two cylinders.

Nielsen (1998) Sec. 2.4.2, Eqs. (2.47)-(2.57), written in the package convention (see
:mod:`railcontact`): the traction and force act on the wheel and oppose the creepage, and the
leading edge is x = +a0. The thesis places the stick zone at x = -a0 (its kinematic constraint
(2.45) has material flowing in +x); here the picture is mirrored so that the stick zone
``a0 - 2 a* < x < a0`` touches the leading edge x = +a0, which is the configuration that satisfies
the slip constraint of the package convention,

    s(x) = xi - d(u1 - u2)/dx = xi + (4 (1-nu^2) / (pi E)) PV int q(z) / (x - z) dz,

with traction opposing slip in the slip zone (checked in ``tests/test_carter.py`` by quadrature of
the principal-value integral).

With ``xi_c = mu a0 / R`` (magnitude of Eq. (2.54)), ``a* = a0 (1 - |xi| / xi_c)`` (Eq. (2.51),
sign flipped), the traction is the difference of two ellipses (Eqs. (2.48)-(2.50))

    q(x) = -sign(xi) mu p0 / a0 [ sqrt(a0^2 - x^2) - sqrt(a*^2 - x*^2) ],  x* = x - a0 + a*,

and the force per unit length (Eq. (2.53)) is ``T = -sign(xi) mu N (1 - (a*/a0)^2)``;
``|xi| >= xi_c`` is full sliding, ``T = -sign(xi) mu N``.

References
----------
.. [1] J.B. Nielsen, New Developments in the Theory of Wheel/Rail Contact Mechanics,
   IMM-PHD-1998-51, DTU, 1998, Sec. 2.4.2.
.. [2] F.W. Carter, On the action of a locomotive driving wheel, Proc. R. Soc. Lond. A 112
   (1926) 151-157.
.. [3] K.L. Johnson, Contact Mechanics, 1985, Sec. 8.3.
"""

from __future__ import annotations

import numpy as np

from ._floats import finite_or_scaled as _finite_or_scaled
from ._floats import overflow_error as _overflow_error
from ._floats import scaled as _scaled, value as _value
from ._validation import check_range
from .hertz import hertz_2d

__all__ = ["carter_creep_force", "carter_critical_creepage", "carter_stick_ratio",
           "carter_traction", "carter_slip"]


def _inputs(normal_load, radius, youngs_modulus, poisson_ratio, friction_coefficient):
    a0, p0 = hertz_2d(normal_load, radius, youngs_modulus, poisson_ratio)
    mu = check_range("friction_coefficient", friction_coefficient, "-", 0.0, None)
    r = np.asarray(radius, dtype=float)
    return a0, p0, mu, r


def _creepage(creepage):
    return check_range("creepage", creepage, "-")


def carter_critical_creepage(normal_load, radius, youngs_modulus, poisson_ratio,
                             friction_coefficient):
    r"""Creepage magnitude at which full sliding sets in, ``xi_c = mu a0 / R``, Eq. (2.54).

    Parameters
    ----------
    normal_load : array_like
        Normal load per unit length N, >= 0. [N/m]
    radius : array_like
        Equivalent radius R, > 0. [m]
    youngs_modulus : array_like
        Young's modulus E, > 0. [Pa]
    poisson_ratio : array_like
        Poisson's ratio nu, in [0, 0.5). [-]
    friction_coefficient : array_like
        Coulomb friction coefficient mu, >= 0. [-]

    Returns
    -------
    ndarray
        xi_c >= 0. [-] (The thesis prints ``xi_c = -mu a0 / R`` because it writes positive forces
        for negative creepage; the magnitude is returned here.)
    """
    a0, _, mu, r = _inputs(normal_load, radius, youngs_modulus, poisson_ratio,
                           friction_coefficient)
    with np.errstate(over="ignore", under="ignore"):
        xi_c = _finite_or_scaled(mu * a0 / r, lambda: _value(*_scaled((mu, a0), (r,))),
                                 (mu == 0.0) | (a0 == 0.0))
    if not np.all(np.isfinite(xi_c)):
        raise _overflow_error("critical creepage mu a0 / R", "-", xi_c,
                              dict(friction_coefficient=mu, normal_load=normal_load,
                                   radius=r, youngs_modulus=youngs_modulus))
    return xi_c


def carter_stick_ratio(creepage, normal_load, radius, youngs_modulus, poisson_ratio,
                       friction_coefficient):
    r"""Stick-zone ratio ``r_a0 = a*/a0 = max(0, 1 - |xi| / xi_c)``, Eq. (2.51).

    Parameters
    ----------
    creepage : array_like
        Longitudinal creepage xi (any real). [-]
    normal_load, radius, youngs_modulus, poisson_ratio, friction_coefficient
        As in :func:`carter_creep_force`.

    Returns
    -------
    ndarray
        r_a0 in [0, 1]. [-] 1 for xi = 0 (full stick), 0 for |xi| >= xi_c (full sliding). If
        ``xi_c = 0`` (mu = 0 or N = 0) there is no stick zone unless xi = 0: 0 for xi != 0, 1 for
        xi = 0.
    """
    frac = _sliding_fraction(_creepage(creepage), normal_load, radius, youngs_modulus,
                             poisson_ratio, friction_coefficient)
    return (1.0 - frac)[()]


def carter_creep_force(creepage, normal_load, radius, youngs_modulus, poisson_ratio,
                       friction_coefficient):
    r"""Longitudinal creep force of two rolling cylinders (Carter 1926), Eqs. (2.51)-(2.54).

    ``T = -sign(xi) mu N [1 - (a*/a0)^2]``, ``a*/a0 = max(0, 1 - |xi|/xi_c)``; the initial slope
    is ``dT/dxi = -2 mu N / xi_c = -pi E a0 / (4 (1 - nu^2))`` (per unit length).

    Parameters
    ----------
    creepage : array_like
        Longitudinal creepage xi. [-]
    normal_load : array_like
        Normal load per unit length N, >= 0. [N/m]
    radius : array_like
        Equivalent radius R, > 0. [m]
    youngs_modulus : array_like
        Young's modulus E, > 0. [Pa]
    poisson_ratio : array_like
        Poisson's ratio nu, in [0, 0.5). [-]
    friction_coefficient : array_like
        Coulomb friction coefficient mu, >= 0. [-]

    Returns
    -------
    ndarray
        Tangential force per unit length on the wheel; |T| <= mu N, opposite in sign to xi.
        [N/m]

    Raises
    ------
    ValueError
        If an input is outside the range stated above (NaN and inf included).

    References
    ----------
    .. [1] J.B. Nielsen, IMM-PHD-1998-51, DTU, 1998, Sec. 2.4.2; F.W. Carter (1926).
    """
    xi = _creepage(creepage)
    # 1 - r^2 written as f (2 - f) with f = 1 - r computed directly: no cancellation at tiny
    # creepage (1 - r**2 loses all digits below |xi|/xi_c ~ 1e-16).
    frac = _sliding_fraction(xi, normal_load, radius, youngs_modulus, poisson_ratio,
                             friction_coefficient)
    mu = np.asarray(friction_coefficient, dtype=float)
    n_load = np.asarray(normal_load, dtype=float)
    with np.errstate(over="ignore"):
        mu_n = mu * n_load
    if not np.all(np.isfinite(mu_n)):
        raise _overflow_error("friction_coefficient * normal_load (the Coulomb limit mu N)",
                              "N/m", mu_n, dict(friction_coefficient=mu, normal_load=n_load))
    return (-np.sign(xi) * mu * n_load * (frac * (2.0 - frac)))[()]


def _sliding_fraction(xi, normal_load, radius, youngs_modulus, poisson_ratio,
                      friction_coefficient):
    """``f = 1 - a*/a0 = min(|xi| / xi_c, 1)``, computed directly (not as 1 - r).

    ``xi_c = 0`` (mu = 0 or N = 0): 0 for xi = 0, else 1 (no stick zone).
    """
    xi_c = carter_critical_creepage(normal_load, radius, youngs_modulus, poisson_ratio,
                                    friction_coefficient)
    xi, xi_c = np.broadcast_arrays(xi, xi_c)
    with np.errstate(over="ignore"):        # |xi| / xi_c beyond 1.8e308: full sliding (1)
        frac = np.divide(np.abs(xi), xi_c, out=np.where(xi == 0.0, 0.0, np.inf),
                         where=xi_c > 0)
    return np.minimum(frac, 1.0)


def _half_ellipse(x, a):
    """sqrt(a^2 - x^2) inside |x| < a, else 0."""
    return np.sqrt(np.clip(a * a - x * x, 0.0, None))


def _pv_ellipse(x, a):
    """(1/pi) PV int_{-a}^{a} sqrt(a^2 - z^2) / (x - z) dz = x - sign(x) sqrt(x^2 - a^2)^+ .

    Outside |x| <= a written as a^2 / (x + sign(x) sqrt(x^2 - a^2)) (no cancellation far away).
    """
    x, a = np.broadcast_arrays(x, a)
    inside = np.abs(x) <= a
    den = x + np.sign(x) * np.sqrt(np.clip(x * x - a * a, 0.0, None))
    outside = np.divide(a * a, den, out=np.zeros(x.shape), where=~inside)
    return np.where(inside, x, outside)


def carter_traction(x, creepage, normal_load, radius, youngs_modulus, poisson_ratio,
                    friction_coefficient):
    r"""Tangential traction q(x) on the wheel, Eqs. (2.47)-(2.50) (mirrored: stick at x = +a0).

    ``q(x) = -sign(xi) mu p0/a0 [sqrt(a0^2 - x^2) - sqrt(a*^2 - x*^2)]``, ``x* = x - a0 + a*``.

    Parameters
    ----------
    x : array_like
        Position along the rolling direction (leading edge at +a0). [m]
    creepage : array_like
        Longitudinal creepage xi. [-]
    normal_load, radius, youngs_modulus, poisson_ratio, friction_coefficient
        As in :func:`carter_creep_force`.

    Returns
    -------
    ndarray
        Traction on the wheel [Pa]; zero outside |x| < a0; |q| <= mu p(x).
    """
    x = check_range("x", x, "m")
    xi = _creepage(creepage)
    a0, p0, mu, _ = _inputs(normal_load, radius, youngs_modulus, poisson_ratio,
                            friction_coefficient)
    r_a0 = carter_stick_ratio(xi, normal_load, radius, youngs_modulus, poisson_ratio,
                              friction_coefficient)
    a_star = r_a0 * a0
    x_star = x - a0 + a_star
    shape = np.broadcast(mu, p0, a0).shape
    scale = np.divide(mu * p0, a0, out=np.zeros(shape), where=a0 > 0)
    q = -np.sign(xi) * scale * (_half_ellipse(x, a0) - _half_ellipse(x_star, a_star))
    return q[()] if np.ndim(q) == 0 else q


def carter_slip(x, creepage, normal_load, radius, youngs_modulus, poisson_ratio,
                friction_coefficient):
    r"""Local slip (relative velocity over V_m) of the Carter solution, Eq. (2.55).

    In the package convention (leading edge x = +a0):
    ``s(x) = sign(xi) [|xi| - (mu/R) (g(x, a0) - g(x*, a*))]``,
    ``g(x, a) = x - sign(x) sqrt(x^2 - a^2)`` for |x| > a and ``x`` inside, i.e. (1/pi) times the
    principal-value integral of a unit half-ellipse. So ``s = 0`` in the stick zone
    ``a0 - 2a* < x < a0``, ``s = sign(xi) (mu/R) sqrt(x*^2 - a*^2)`` in the slip zone, and
    ``s -> xi`` for |x| -> inf (Eq. (2.58)).

    Parameters
    ----------
    x : array_like
        Position along the rolling direction. [m]
    creepage : array_like
        Longitudinal creepage xi. [-]
    normal_load, radius, youngs_modulus, poisson_ratio, friction_coefficient
        As in :func:`carter_creep_force`.

    Returns
    -------
    ndarray
        Slip s [-] (same sign as xi where non-zero; the traction opposes it). When N = 0 or
        mu = 0 there is no traction and s = xi everywhere.
    """
    x = check_range("x", x, "m")
    xi = _creepage(creepage)
    a0, _, mu, r = _inputs(normal_load, radius, youngs_modulus, poisson_ratio,
                           friction_coefficient)
    r_a0 = carter_stick_ratio(xi, normal_load, radius, youngs_modulus, poisson_ratio,
                              friction_coefficient)
    a_star = r_a0 * a0
    x_star = x - a0 + a_star
    # note (convention, not an OCR error): (2.55) as printed puts the stick zone at x = -a0, the
    # trailing edge of the package convention; mirrored here, verified by quadrature of the
    # constitutive PV integral in tests/test_carter.py::test_slip_matches_quadrature.
    s = np.sign(xi) * (np.abs(xi) - mu / r * (_pv_ellipse(x, a0) - _pv_ellipse(x_star, a_star)))
    # inside the stick zone the two terms cancel analytically; remove round-off
    in_stick = (x_star > -a_star) & (x < a0)
    s = np.where(in_stick, 0.0, s)
    return s[()] if np.ndim(s) == 0 else s
