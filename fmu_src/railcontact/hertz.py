r"""Hertz's solution of the normal contact problem, 2-D (cylinders) and 3-D (ellipse).

Both bodies have the same elastic constants (E, nu), so the combined modulus is
``E* = E / (2 (1 - nu^2))``.

* 2-D: Nielsen (1998) Eqs. (2.40)-(2.42), after Hertz (1882).
* 3-D: the elliptic Hertz contact, Nielsen (1998) Eqs. (2.59)-(2.60), whose semi-axes follow from
  Johnson (1985), Sec. 4.2, Eqs. (3.60)-(3.64) and (4.17)-(4.19). The gap between the undeformed
  surfaces is ``h(x, y) = A' x^2 + B' y^2`` with the *relative* principal curvature coefficients
  A', B' (A' = 1/(2 R'_x), B' = 1/(2 R'_y) in Johnson's notation, R' the relative radii of
  curvature). The complete elliptic integrals are written with Carlson's symmetric integral R_D
  (``scipy.special.elliprd``) so that no difference of nearly equal numbers appears when the
  ellipse is nearly circular:

  ``K(m) - E(m) = m R_D(0, 1-m, 1) / 3``,  ``E(m) - (1-m) K(m) = m (1-m) R_D(0, 1, 1-m) / 3``.

  With k = c_min / c_max (ratio of minor to major semi-axis) the ratio of the curvature across
  the major axis to the curvature along it is

  ``f(k) = R_D(0, 1, k^2) / R_D(0, k^2, 1)``  (decreasing from inf at k -> 0 to 1 at k = 1),

  and the major semi-axis is ``c_max^3 = N R_D(0, k^2, 1) / (2 pi E* C_major)`` with C_major
  the curvature coefficient along the major axis; ``p0 = 3 N / (2 pi a0 b0)``.

References
----------
.. [1] J.B. Nielsen, New Developments in the Theory of Wheel/Rail Contact Mechanics,
   IMM-PHD-1998-51, DTU, 1998, Secs. 2.4.1 and 2.5.1.
.. [2] H. Hertz, Ueber die Beruehrung fester elastischer Koerper, J. reine angew. Math. 92 (1882).
.. [3] K.L. Johnson, Contact Mechanics, Cambridge University Press, 1985, Secs. 3.5 and 4.2.
.. [4] B.C. Carlson, Numerical computation of real or complex elliptic integrals,
   Numer. Algorithms 10 (1995) 13-26.
"""

from __future__ import annotations

from collections import namedtuple

import numpy as np

from ._floats import finite_or_scaled as _finite_or_scaled
from ._floats import overflow_error as _overflow_error
from ._floats import root as _root, scaled as _scaled, value as _value
from ._validation import check_range

__all__ = ["Hertz2D", "Hertz3D", "hertz_2d", "hertz_3d", "curvature_ratio_from_axis_ratio",
           "axis_ratio_from_curvature_ratio"]

Hertz2D = namedtuple("Hertz2D", ["a0", "p0"])
Hertz2D.__doc__ = """2-D Hertz contact: half-width ``a0`` [m] and maximum pressure ``p0`` [Pa]."""

Hertz3D = namedtuple("Hertz3D", ["a0", "b0", "p0"])
Hertz3D.__doc__ = ("3-D Hertz contact: semi-axes ``a0`` (rolling direction x) and ``b0`` "
                   "(lateral y) [m], maximum pressure ``p0`` [Pa].")

# Axis-ratio range in which the 3-D solver is guaranteed (brief: 0.05..20); the bisection
# brackets k = c_min/c_max in [K_MIN, 1], far wider than that.
#: Smallest axis ratio k = min(a0, b0)/max(a0, b0) the Hertz ellipse solver considers. [-]
AXIS_RATIO_MIN = 1e-6
_K_MIN = AXIS_RATIO_MIN
_BISECTION_STEPS = 64


def _check_material(youngs_modulus, poisson_ratio):
    e_mod = check_range("youngs_modulus", youngs_modulus, "Pa", 0.0, None, lower_closed=False)
    nu = check_range("poisson_ratio", poisson_ratio, "-", 0.0, 0.5, upper_closed=False)
    return e_mod, nu


def hertz_2d(normal_load, radius, youngs_modulus, poisson_ratio):
    r"""Hertz contact of two cylinders (line contact), Eqs. (2.40)-(2.42) in [1]_.

    ``a0 = sqrt(8 (1-nu^2) R N / (pi E))`` and ``p0 = sqrt(N E / (2 (1-nu^2) pi R))``, i.e.
    ``a0^2 = 4 N R / (pi E*)`` and ``p0 = 2 N / (pi a0)`` with ``E* = E / (2 (1-nu^2))``.

    Parameters
    ----------
    normal_load : array_like
        Normal load per unit length N, >= 0. [N/m]
    radius : array_like
        Equivalent radius R, 1/R = 1/R1 + 1/R2 (Eq. (2.38)), > 0. [m]
    youngs_modulus : array_like
        Young's modulus E of both bodies, > 0. [Pa]
    poisson_ratio : array_like
        Poisson's ratio nu of both bodies, in [0, 0.5). [-]

    Returns
    -------
    Hertz2D
        ``a0`` half-width of the contact strip [m]; ``p0`` maximum pressure [Pa]. The pressure
        is ``p(x) = p0 sqrt(1 - (x/a0)^2)`` (Eq. (2.40)). N = 0 gives zeros.

    Raises
    ------
    ValueError
        If an input is outside the range stated above (NaN and inf included).

    References
    ----------
    .. [1] J.B. Nielsen, IMM-PHD-1998-51, DTU, 1998, Sec. 2.4.1; H. Hertz (1882).
    """
    n_load = check_range("normal_load", normal_load, "N/m", 0.0, None)
    r = check_range("radius", radius, "m", 0.0, None, lower_closed=False)
    e_mod, nu = _check_material(youngs_modulus, poisson_ratio)
    with np.errstate(over="ignore", under="ignore", invalid="ignore", divide="ignore"):
        a0 = np.sqrt(8.0 * (1.0 - nu**2) * r * n_load / (np.pi * e_mod))
        p0 = np.sqrt(n_load * e_mod / (2.0 * (1.0 - nu**2) * np.pi * r))
    # products beyond the float range (e.g. N R ~ 1e600 with E ~ 1e300): the same expressions
    # in (mantissa, exponent) form; a result that itself overflows is a ValueError
    a0 = _finite_or_scaled(a0, lambda: _root(_scaled(
        (8.0 * (1.0 - nu**2), r, n_load), (_scaled((np.pi, e_mod)),)), 2), n_load == 0.0)
    p0 = _finite_or_scaled(p0, lambda: _root(_scaled(
        (n_load, e_mod), (_scaled((2.0 * (1.0 - nu**2), np.pi, r)),)), 2), n_load == 0.0)
    names = dict(normal_load=n_load, radius=r, youngs_modulus=e_mod)
    for value, what, unit in ((a0, "Hertz half-width a0", "m"), (p0, "Hertz pressure p0", "Pa")):
        if not np.all(np.isfinite(value)):
            raise _overflow_error(what, unit, value, names)
    return Hertz2D(a0[()], p0[()])


def _ratio_across_over_along(k):
    """f(k) = C_minor/C_major = R_D(0,1,k^2)/R_D(0,k^2,1), k = c_min/c_max in (0, 1]."""
    k2 = k * k
    from scipy.special import elliprd  # noqa: PLC0415  (scipy: on first use)

    return elliprd(0.0, 1.0, k2) / elliprd(0.0, k2, 1.0)


def _k_from_ratio(ratio):
    """Invert f(k) = ratio (>= 1) for k in (0, 1] by vectorised bisection in log k."""
    ratio = np.asarray(ratio, dtype=float)
    lo = np.full(ratio.shape, np.log(_K_MIN))
    hi = np.zeros(ratio.shape)
    for _ in range(_BISECTION_STEPS):
        mid = 0.5 * (lo + hi)
        too_elongated = _ratio_across_over_along(np.exp(mid)) > ratio  # f decreasing in k
        lo = np.where(too_elongated, mid, lo)
        hi = np.where(too_elongated, hi, mid)
    return np.where(ratio <= 1.0, 1.0, np.exp(0.5 * (lo + hi)))


def axis_ratio_from_curvature_ratio(curvature_ratio):
    r"""Axis ratio a0/b0 of the Hertz ellipse for a curvature ratio B'/A' (inverse of
    :func:`curvature_ratio_from_axis_ratio`).

    Parameters
    ----------
    curvature_ratio : array_like
        B'/A' > 0. [-] Values giving a0/b0 outside [1e-6, 1e6] are clipped there.

    Returns
    -------
    ndarray
        a0/b0. [-] B'/A' > 1 gives a0/b0 > 1 (ellipse elongated in the rolling direction).
    """
    r = check_range("curvature_ratio", curvature_ratio, "-", 0.0, None, lower_closed=False)
    k = _k_from_ratio(np.maximum(r, 1.0 / r))
    return np.where(r >= 1.0, 1.0 / k, k)


def curvature_ratio_from_axis_ratio(a0_over_b0):
    r"""Curvature ratio B'/A' that produces a Hertz ellipse with the axis ratio a0/b0.

    For a0 >= b0 (k = b0/a0): ``B'/A' = f(k) = R_D(0, 1, k^2) / R_D(0, k^2, 1)``
    (= ``[(a0/b0)^2 E(e) - K(e)] / [K(e) - E(e)]``, e^2 = 1 - k^2, Johnson (1985) Eq. (4.17));
    for a0 < b0 the roles of the axes swap: ``B'/A' = 1 / f(a0/b0)``.

    Parameters
    ----------
    a0_over_b0 : array_like
        Semi-axis ratio a0/b0 > 0 (rolling over lateral). [-]

    Returns
    -------
    ndarray
        B'/A', the ratio of the lateral to the longitudinal relative curvature. [-]
        Equal to 1 for a circle; > 1 for a0 > b0.
    """
    g = check_range("a0_over_b0", a0_over_b0, "-", 0.0, None, lower_closed=False)
    f = _ratio_across_over_along(np.minimum(g, 1.0 / g))
    return np.where(g >= 1.0, f, 1.0 / f)


def hertz_3d(normal_load, curvature_longitudinal, curvature_lateral, youngs_modulus,
             poisson_ratio):
    r"""Hertz contact ellipse of two bodies with principal relative curvatures A', B'.

    Solves Johnson (1985) Eqs. (4.17)-(4.19) (Nielsen's Sec. 2.5.1 refers to it for Eqs.
    (2.59)-(2.60)): the eccentricity from the curvature ratio (vectorised bisection on
    ``f(k)``, see the module docstring, 64 steps: relative accuracy ~1e-15), then the major
    semi-axis, the minor one and ``p0 = 3 N / (2 pi a0 b0)``.

    Parameters
    ----------
    normal_load : array_like
        Normal load N, >= 0. [N]
    curvature_longitudinal : array_like
        A' > 0, the gap coefficient in the rolling direction: the undeformed gap is
        ``h = A' x^2 + B' y^2``, so A' = 1/(2 R'_x) = (1/R_x1 + 1/R_x2)/2, **half** the
        relative curvature 1/R'_x, not 1/R'_x itself (a wheel of radius 0.46 m on a straight
        rail: A' = 1.087, not 2.17; passing 1/R'_x doubles the curvature and gives the
        wrong ellipse). [1/m]
    curvature_lateral : array_like
        B' > 0, the lateral gap coefficient, B' = 1/(2 R'_y) = (1/R_y1 + 1/R_y2)/2, likewise
        half the relative curvature (a rail head of radius 0.3 m against a flat wheel
        profile: 1.667). [1/m]
    youngs_modulus : array_like
        Young's modulus E of both bodies, > 0. [Pa]
    poisson_ratio : array_like
        Poisson's ratio nu of both bodies, in [0, 0.5). [-]

    Returns
    -------
    Hertz3D
        ``a0`` semi-axis along x (rolling) [m], ``b0`` along y [m], ``p0`` maximum pressure [Pa].
        The pressure is ``p = p0 sqrt(1 - (x/a0)^2 - (y/b0)^2)`` (Eq. (2.60)). The circle
        (A' = B') gives Johnson's ``a^3 = 3 N R / (4 E*)`` with R = 1/(2A'). N = 0 gives zeros.
        Guaranteed for 1e-6 <= a0/b0 <= 1e6 (B'/A' between ~1e-10 and ~1e10); tested for
        a0/b0 in [0.05, 20].

    Raises
    ------
    ValueError
        If an input is outside the range stated above (NaN and inf included).

    References
    ----------
    .. [1] K.L. Johnson, Contact Mechanics, 1985, Sec. 4.2; H. Hertz (1882).
    .. [2] J.B. Nielsen, IMM-PHD-1998-51, DTU, 1998, Sec. 2.5.1.
    """
    n_load = check_range("normal_load", normal_load, "N", 0.0, None)
    c_x = check_range("curvature_longitudinal", curvature_longitudinal, "1/m", 0.0, None,
                      lower_closed=False)
    c_y = check_range("curvature_lateral", curvature_lateral, "1/m", 0.0, None,
                      lower_closed=False)
    e_mod, nu = _check_material(youngs_modulus, poisson_ratio)
    n_load, c_x, c_y, e_mod, nu = np.broadcast_arrays(n_load, c_x, c_y, e_mod, nu)
    e_star = e_mod / (2.0 * (1.0 - nu**2))
    x_major = c_y >= c_x                      # smaller curvature along x -> major axis along x
    c_major = np.where(x_major, c_x, c_y)
    c_minor = np.where(x_major, c_y, c_x)
    with np.errstate(over="ignore", under="ignore"):   # (a ratio beyond the range: clipped)
        k = _k_from_ratio(c_minor / c_major)
    # c_major = p0 c_min (K - E) / (E* c_max^2 m), p0 = 3N/(2 pi c_max c_min),
    # (K - E)/m = R_D(0, k^2, 1)/3  ->  c_max^3 = N R_D(0, k^2, 1) / (2 pi E* C_major)
    # cbrt of each factor: cbrt(N * ...) underflows for N below ~1e-297 N although a0 ~ N^(1/3)
    from scipy.special import elliprd  # noqa: PLC0415  (scipy: on first use)

    rd = elliprd(0.0, k * k, 1.0)
    with np.errstate(over="ignore", under="ignore", invalid="ignore", divide="ignore"):
        c_max = np.cbrt(n_load) * np.cbrt(rd / (2.0 * np.pi * e_star * c_major))
    # E* C_major beyond the float range: the quotient in (mantissa, exponent) form
    with np.errstate(over="ignore"):                    # (inf: a ValueError below)
        c_max = _finite_or_scaled(c_max, lambda: np.cbrt(n_load) * _root(_scaled(
            (rd,), (_scaled((2.0 * np.pi, e_star, c_major)),)), 3), n_load == 0.0)
    c_min = k * c_max
    a0 = np.where(x_major, c_max, c_min)
    b0 = np.where(x_major, c_min, c_max)
    with np.errstate(over="ignore", under="ignore"):
        area = np.pi * a0 * b0
        # N / area first: 1.5 N would round in the subnormal range for N < ~1e-308 N
        p0 = 1.5 * np.divide(n_load, area, out=np.zeros_like(area), where=area > 0)
    p0 = _finite_or_scaled(p0, lambda: np.where(
        n_load > 0.0, _value(*_scaled((1.5, n_load), (_scaled((np.pi, a0, b0)),))), 0.0),
        n_load == 0.0)
    names = dict(normal_load=n_load, curvature_longitudinal=c_x, curvature_lateral=c_y,
                 youngs_modulus=e_mod)
    for value, what, unit in ((a0, "Hertz semi-axis a0", "m"), (b0, "Hertz semi-axis b0", "m"),
                              (p0, "Hertz pressure p0", "Pa")):
        if not np.all(np.isfinite(value)):
            raise _overflow_error(what, unit, value, names)
    return Hertz3D(a0[()], b0[()], p0[()])
