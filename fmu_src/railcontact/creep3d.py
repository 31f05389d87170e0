r"""Creep forces of the 3-D Hertzian rolling contact: linear theory, SHE, strip and modified strip.

Package convention (see :mod:`railcontact`): forces act on the wheel and oppose the creepage,
``T_x = -G a0 b0 C11 xi_x`` in the linear regime, with ``G = E / (2 (1 + nu))``.

All four methods are written with the *Kalker-weighted creepage vector*

    w = (C11 xi_x, C22 xi_y + sqrt(a0 b0) C23 phi)            [-]

(the spin enters through the small-spin substitution (2.99)) and differ only in the magnitude
function applied to it:

``"linear"`` (Kalker, Eqs. (2.61)-(2.62))
    ``T = -G a0 b0 w``; unbounded (no Coulomb limit).
``"she"`` (Shen, Hedrick and Elkins, Eqs. (2.63)-(2.65))
    ``T = T_lin (1 - u/3 + u^2/27)`` for ``u = |T_lin|/(mu N) <= 3``, else ``T_lin mu N/|T_lin|``.
``"modified_strip"`` (Nielsen, Eqs. (2.90)-(2.96) with (2.99))
    With p0 = 3 N/(2 pi a0 b0) and the normalised modified creepage

        z = |w| / w_sat,   w_sat = pi^2 (1 + nu) mu p0 / E = pi^2 mu p0 / (2 G),

    the two component equations (2.91)-(2.92) with the constraint (2.95) and the ratio
    assumption (2.96) give ``p0x = p0 |w_x| / |w|``, ``p0y = p0 |w_y| / |w|``, and then both
    modified creepages (2.93)-(2.94) equal z. Hence

        T = -mu N F(min(z, 1)) w / |w|,
        F(z) = 1 - (1 + z^2/2) sqrt(1 - z^2) + (3/2) z arccos(z)        (Eq. (2.87))

    (Eq. (2.87) with its creepage -z, in the package sign convention). F is evaluated as
    ``z^4 (2 + r) / (2 (1 + r)^2) + (3/2) z arccos z``, r = sqrt(1 - z^2), which is the same
    function without the cancellation of the printed form at small z. The initial slope is
    ``F'(0) = 3 pi / 4``, which makes the initial slope equal to the linear theory's (Eq. (2.88)).
``"strip"`` (Haines and Ollerton; Nielsen Eqs. (2.83)-(2.87))
    The same with the *strip* coefficients, i.e. the 2-D (plane-strain) compliance of each
    strip: C11 -> pi^2 / (4 (1 - nu)) (Eq. (2.89)) and, for lateral creepage (anti-plane
    compliance of a strip, 1/(1 - nu) times the in-plane one), C22 -> pi^2/4. These are
    Kalker's a0/b0 -> 0 limits. The thesis gives the strip theory for longitudinal creepage
    only; the lateral extension and the spin (kept as C23 via (2.99)) are this package's.

Where the saturation kink comes from (modified strip and strip theory): full sliding sets in
exactly at z = 1, i.e. ``|w| = w_sat``. F has ``F(1) = 1``, ``F'(z) = (3/2)(arccos z -
z sqrt(1 - z^2))`` and ``F''(z) = -3 sqrt(1 - z^2)``, so F, F' and F'' are continuous at z = 1
(all vanish except F = 1) while ``F'''`` = 3 z / sqrt(1 - z^2) diverges: the creep curve is C2
but not C3 at the saturation point, with a square-root singularity of the curvature. A table
sampled on z therefore must put z = 1 on a grid line; :func:`normalised_creepage_3d` and
:func:`saturation_creepage_3d` give the coordinate. SHE saturates at u = |T_lin|/(mu N) = 3:
``S(u) = u - u^2/3 + u^3/27`` has ``S' = (1 - u/3)^2`` and ``S'' = -(2/3)(1 - u/3)``, both 0 at
u = 3, and ``S''' = 2/9`` jumps to 0 -- also C2, with a finite jump of the third derivative.
The linear theory has no kink.

Stick zone (strip theories): the stick zone of strip y is ``a*(y) = a(y) - a0 z`` with
``a(y) = a0 sqrt(1 - (y/b0)^2)`` (Eq. (2.83)); it exists for ``|y| < b* = b0 sqrt(1 - z^2)``
(Eq. (2.84)), and its area fraction is ``(2/pi)(arccos z - z sqrt(1 - z^2))``.

Spin coefficient (Eq. (2.98)): ``Phi = sqrt(a0^2 + b0^2) |phi| / sqrt(xi_x^2 + xi_y^2)``; the spin
pole lies outside the ellipse for Phi <= 1. The small-spin substitution only keeps the initial
slope right; for Phi > 1 the same formulas are evaluated (|T| <= mu N still holds) but
``within_validity`` is False -- large spin makes the real creep curve decay (Kalker 1990), which
these theories do not model.

References
----------
.. [1] J.B. Nielsen, IMM-PHD-1998-51, DTU, 1998, Secs. 2.5.1-2.5.2 and 2.6.
.. [2] J.J. Kalker, Three-dimensional elastic bodies in rolling contact, Kluwer, 1990.
.. [3] Z.Y. Shen, J.K. Hedrick, J.A. Elkins, A comparison of alternative creep force models for
   rail vehicle dynamic analysis, Proc. 8th IAVSD Symposium, 1983, 591-605.
.. [4] K.D. Haines, E. Ollerton, Contact stress distributions on elliptical contact surfaces
   subjected to radial and tangential forces, Proc. Inst. Mech. Eng. 177 (1963) 95-114.
"""

from __future__ import annotations

import math
from collections import namedtuple

import numpy as np

from ._validation import check_choice, check_range
from .kalker import _coefficients_cached, kalker_coefficients

__all__ = ["CreepForce3D", "CreepSolution3D", "METHODS", "COMPARISON_METHODS", "creep_force_3d",
           "creep_solution_3d",
           "spin_coefficient", "saturation_creepage_3d", "normalised_creepage_3d",
           "strip_force_function"]

METHODS = ("linear", "she", "strip", "modified_strip")
# Methods users compare against, each in its own module (railcontact.fastsim, railcontact.polach);
# creep_force_3d and creep_solution_3d dispatch to them by name.
COMPARISON_METHODS = ("fastsim", "polach", "fastrip")

CreepForce3D = namedtuple("CreepForce3D", ["tx", "ty"])
CreepForce3D.__doc__ = "Tangential creep force on the wheel, components tx, ty. [N]"

CreepSolution3D = namedtuple("CreepSolution3D", [
    "tx", "ty", "stick_area_fraction", "stick_width_ratio", "normalised_creepage",
    "spin_coefficient", "within_validity"])
CreepSolution3D.__doc__ = """Full result of :func:`creep_solution_3d`.

tx, ty : force on the wheel [N].
stick_area_fraction : stick area / (pi a0 b0) [-], strip-theory estimate (see module docstring);
    1 for "linear" (full stick by assumption); for "she", which has no stick zone, the
    modified-strip estimate at the same creepages.
stick_width_ratio : b*/b0 = sqrt(1 - z^2) [-], lateral extent of the stick zone (Eq. (2.84)).
normalised_creepage : z = |w| / w_sat [-] of the method ("strip" uses its own coefficients; the
    modified-strip value for the others); 1 = onset of full sliding.
spin_coefficient : Phi, Eq. (2.98) [-] (inf for pure spin, 0 without spin).
within_validity : bool, Phi <= 1 (spin pole outside the ellipse) and, for "linear",
    |T| <= mu N.
"""


def strip_force_function(z):
    r"""Normalised creep-force magnitude of the strip theory, F(z) = |T| / (mu N), Eq. (2.87).

    Parameters
    ----------
    z : array_like
        Normalised (modified) creepage magnitude >= 0; z >= 1 is full sliding. [-]

    Returns
    -------
    ndarray
        F in [0, 1]. [-] ``F(0) = 0``, ``F'(0) = 3 pi/4``, ``F(z >= 1) = 1`` exactly.
    """
    z = check_range("z", z, "-", 0.0, None)
    return np.where(z >= 1.0, 1.0, z * _f_over_z(np.minimum(z, 1.0)))[()]


def _f_over_z(z):
    """F(z)/z for 0 <= z <= 1, without cancellation; = 3 pi/4 at z = 0 and 1 at z = 1."""
    # erratum: (2.82) as printed reads du/dx = 4(1-nu^2)/(pi E) (mu p0 / a) (a(y) - a*(y)); the
    # per-strip Carter solution gives 4(1-nu^2)/E (mu p0 / a0) (a(y) - a*(y)) (no pi, a0 not a),
    # which is what (2.83)-(2.85) use. F here (from (2.83)-(2.87)) is verified by quadrature of
    # the strip tractions in tests/test_creep3d.py::test_strip_formula_2_87_against_quadrature.
    r = np.sqrt(np.maximum(1.0 - z * z, 0.0))
    return z**3 * (2.0 + r) / (2.0 * (1.0 + r) ** 2) + 1.5 * np.arccos(z)


def _check_common(normal_load, a0, b0, youngs_modulus, poisson_ratio, friction_coefficient):
    n_load = check_range("normal_load", normal_load, "N", 0.0, None)
    a0 = check_range("a0", a0, "m", 0.0, None)
    b0 = check_range("b0", b0, "m", 0.0, None)
    e_mod = check_range("youngs_modulus", youngs_modulus, "Pa", 0.0, None, lower_closed=False)
    nu = check_range("poisson_ratio", poisson_ratio, "-", 0.0, 0.5, upper_closed=False)
    mu = check_range("friction_coefficient", friction_coefficient, "-", 0.0, None)
    return n_load, a0, b0, e_mod, nu, mu


def _coefficients(a0, b0, nu, method):
    has_area = (a0 > 0.0) & (b0 > 0.0)
    g = np.where(has_area, a0 / np.where(has_area, b0, 1.0), 1.0)
    c11, c22, c23 = kalker_coefficients(g, nu)
    if method == "strip":
        c11 = np.pi**2 / (4.0 * (1.0 - nu)) + 0.0 * c11
        c22 = np.pi**2 / 4.0 + 0.0 * c22
    return c11, c22, c23


def _weighted(xi_x, xi_y, phi, a0, b0, c11, c22, c23):
    return c11 * xi_x, c22 * xi_y + np.sqrt(a0 * b0) * c23 * phi


def _saturation_w(n_load, a0, b0, e_mod, nu, mu):
    """w_sat = pi^2 (1 + nu) mu p0 / E, p0 = 3 N / (2 pi a0 b0); 0 if there is no contact."""
    area = np.pi * a0 * b0
    p0 = np.divide(1.5 * n_load, area, out=np.zeros(np.broadcast(n_load, area).shape),
                   where=area > 0.0)
    return np.pi**2 * (1.0 + nu) * mu * p0 / e_mod


def spin_coefficient(creepage_longitudinal, creepage_lateral, spin, a0, b0):
    r"""Spin coefficient Phi, Eq. (2.98): ``sqrt(a0^2 + b0^2) |phi| / sqrt(xi_x^2 + xi_y^2)``.

    Parameters
    ----------
    creepage_longitudinal, creepage_lateral : array_like
        Creepages xi_x, xi_y. [-]
    spin : array_like
        Spin creepage phi. [1/m]
    a0, b0 : array_like
        Semi-axes of the contact ellipse, >= 0. [m]

    Returns
    -------
    ndarray
        Phi >= 0 [-]; 0 when phi = 0 (also with zero creepage), inf for pure spin. The spin pole
        (-xi_y/phi, xi_x/phi), Eq. (2.97), lies outside the ellipse when Phi <= 1.
    """
    xi_x = check_range("creepage_longitudinal", creepage_longitudinal, "-")
    xi_y = check_range("creepage_lateral", creepage_lateral, "-")
    phi = check_range("spin", spin, "1/m")
    a0 = check_range("a0", a0, "m", 0.0, None)
    b0 = check_range("b0", b0, "m", 0.0, None)
    num = np.hypot(a0, b0) * np.abs(phi)
    den = np.hypot(xi_x, xi_y)
    num, den = np.broadcast_arrays(num, den)
    out = np.where(num > 0.0, np.inf, 0.0)
    return np.divide(num, den, out=out, where=den > 0.0)[()]


def normalised_creepage_3d(creepage_longitudinal, creepage_lateral, spin, normal_load, a0, b0,
                           youngs_modulus, poisson_ratio, friction_coefficient,
                           method="modified_strip"):
    r"""Normalised modified creepage ``z = |w| / w_sat`` (1 = onset of full sliding).

    ``w = (C11 xi_x, C22 xi_y + sqrt(a0 b0) C23 phi)``, ``w_sat = pi^2 (1 + nu) mu p0 / E``
    (Eqs. (2.93)-(2.96) and (2.99); for ``method="strip"`` the strip coefficients of Eq. (2.85)).
    This is the table coordinate that puts the saturation kink of the (modified) strip theory
    on the grid line z = 1.

    Parameters
    ----------
    creepage_longitudinal, creepage_lateral, spin, normal_load, a0, b0, youngs_modulus,
    poisson_ratio, friction_coefficient
        As in :func:`creep_force_3d`.
    method : {"modified_strip", "strip"}
        Which coefficients define w.

    Returns
    -------
    ndarray
        z >= 0 [-]; inf if there is creepage but no friction force available (N = 0 or mu = 0),
        0 for zero creepage.
    """
    check_choice("method", method, ("modified_strip", "strip"))
    xi_x = check_range("creepage_longitudinal", creepage_longitudinal, "-")
    xi_y = check_range("creepage_lateral", creepage_lateral, "-")
    phi = check_range("spin", spin, "1/m")
    n_load, a0, b0, e_mod, nu, mu = _check_common(normal_load, a0, b0, youngs_modulus,
                                                  poisson_ratio, friction_coefficient)
    c11, c22, c23 = _coefficients(a0, b0, nu, method)
    w_x, w_y = _weighted(xi_x, xi_y, phi, a0, b0, c11, c22, c23)
    w_abs = np.hypot(w_x, w_y)
    w_sat = _saturation_w(n_load, a0, b0, e_mod, nu, mu)
    w_abs, w_sat = np.broadcast_arrays(w_abs, w_sat)
    out = np.where(w_abs > 0.0, np.inf, 0.0)
    return np.divide(w_abs, w_sat, out=out, where=w_sat > 0.0)[()]


def saturation_creepage_3d(normal_load, a0, b0, youngs_modulus, poisson_ratio,
                           friction_coefficient, direction=0.0, method="modified_strip"):
    r"""Creepage magnitude at which full sliding sets in (z = 1), for a direction of (xi_x, xi_y).

    For creepage ``xi = s (cos theta, sin theta)`` without spin, full sliding of the
    (modified) strip theory begins at

        s_sat = pi^2 (1 + nu) mu p0 / (E sqrt((C11 cos theta)^2 + (C22 sin theta)^2)),

    p0 = 3 N / (2 pi a0 b0) (Eqs. (2.85), (2.93)-(2.96)). For theta = 0 this is the
    longitudinal value ``pi^2 mu p0 / (2 G C11)``. The creep curve is C2 but not C3 there
    (see the module docstring).

    Parameters
    ----------
    normal_load : array_like
        Normal load N, >= 0. [N]
    a0, b0 : array_like
        Semi-axes of the Hertz ellipse (x rolling, y lateral), > 0. [m]
    youngs_modulus : array_like
        Young's modulus E, > 0. [Pa]
    poisson_ratio : array_like
        Poisson's ratio nu, in [0, 0.5). [-]
    friction_coefficient : array_like
        Coulomb friction coefficient mu, >= 0. [-]
    direction : array_like, optional
        Direction theta of the creepage vector in the (xi_x, xi_y) plane; 0 = longitudinal,
        pi/2 = lateral. [rad]
    method : {"modified_strip", "strip"}
        Which coefficients (Kalker's or the strip theory's).

    Returns
    -------
    ndarray
        s_sat >= 0. [-] (0 when N = 0 or mu = 0.)
    """
    check_choice("method", method, ("modified_strip", "strip"))
    n_load, a0, b0, e_mod, nu, mu = _check_common(normal_load, a0, b0, youngs_modulus,
                                                  poisson_ratio, friction_coefficient)
    a0 = check_range("a0", a0, "m", 0.0, None, lower_closed=False)
    b0 = check_range("b0", b0, "m", 0.0, None, lower_closed=False)
    theta = check_range("direction", direction, "rad")
    c11, c22, _ = _coefficients(a0, b0, nu, method)
    w_sat = _saturation_w(n_load, a0, b0, e_mod, nu, mu)
    return (w_sat / np.hypot(c11 * np.cos(theta), c22 * np.sin(theta)))[()]


def _solve(xi_x, xi_y, phi, normal_load, a0, b0, youngs_modulus, poisson_ratio,
           friction_coefficient, method):
    check_choice("method", method, METHODS + COMPARISON_METHODS)
    xi_x = check_range("creepage_longitudinal", xi_x, "-")
    xi_y = check_range("creepage_lateral", xi_y, "-")
    phi = check_range("spin", phi, "1/m")
    n_load, a0, b0, e_mod, nu, mu = _check_common(normal_load, a0, b0, youngs_modulus,
                                                  poisson_ratio, friction_coefficient)
    shape = np.broadcast(xi_x, xi_y, phi, n_load, a0, b0, e_mod, nu, mu).shape
    g_mod = e_mod / (2.0 * (1.0 + nu))
    mu_n = mu * n_load
    c11, c22, c23 = _coefficients(a0, b0, nu, "strip" if method == "strip" else "modified_strip")
    w_x, w_y = _weighted(xi_x, xi_y, phi, a0, b0, c11, c22, c23)
    w_x, w_y = np.broadcast_to(w_x, shape), np.broadcast_to(w_y, shape)
    w_abs = np.hypot(w_x, w_y)
    w_sat = np.broadcast_to(_saturation_w(n_load, a0, b0, e_mod, nu, mu), shape)
    has_force = (mu_n > 0.0) & (w_sat > 0.0)
    with np.errstate(over="ignore"):             # w_sat ~ 1e-300 (N -> 0): z = inf is meant
        z = np.divide(w_abs, w_sat, out=np.where(w_abs > 0.0, np.inf, 0.0), where=w_sat > 0.0)
    stiffness = np.broadcast_to(g_mod * a0 * b0, shape)     # G a0 b0 [N]

    if method == "linear":
        factor = stiffness
    elif method == "she":
        t_lin = stiffness * w_abs
        with np.errstate(over="ignore"):         # mu N ~ 1e-300: u = inf is meant (sliding)
            u = np.divide(t_lin, mu_n, out=np.where(t_lin > 0.0, np.inf, 0.0),
                          where=mu_n > 0.0)
        small = u <= 3.0
        u_c = np.minimum(u, 3.0)
        factor_small = stiffness * (1.0 - u_c / 3.0 + u_c * u_c / 27.0)
        factor_big = np.divide(mu_n, w_abs, out=np.zeros(shape), where=(w_abs > 0.0) & ~small)
        factor = np.where(small, factor_small, factor_big)
        factor = np.where(has_force | (w_abs == 0.0), factor, 0.0)
    else:
        # T = -mu N F(z) w/|w| = -(mu N / w_sat) (F(z)/z) w   (z <= 1),  -mu N w/|w|  (z > 1)
        below = z <= 1.0
        zc = np.minimum(z, 1.0)
        k_sat = np.divide(mu_n, w_sat, out=np.zeros(shape), where=w_sat > 0.0)
        factor_small = k_sat * _f_over_z(zc)
        factor_big = np.divide(mu_n, w_abs, out=np.zeros(shape), where=(w_abs > 0.0) & ~below)
        factor = np.where(below, factor_small, factor_big)
        factor = np.where(has_force, factor, 0.0)
    tx = -factor * w_x
    ty = -factor * w_y
    if method != "linear":
        # full sliding: |T| = mu N up to rounding of the unit vector; never above mu N
        t_abs = np.hypot(tx, ty)
        # With two non-zero components np.hypot may round |T| down onto mu N while the exact
        # |(tx, ty)| is a few ulp above it: rescale those with a 4 eps margin too. A single
        # component is exact (|tx| <= mu N is then what hypot checks).
        margin = np.where((tx != 0.0) & (ty != 0.0), 1.0 - 4.0 * np.finfo(float).eps, 1.0)
        over = t_abs > mu_n * margin
        # (1 - 4 eps): the rescaled hypot must not round above mu N again
        scale = np.divide(mu_n * (1.0 - 4.0 * np.finfo(float).eps), t_abs, out=np.ones(shape),
                          where=over)
        tx, ty = tx * scale, ty * scale
    return tx + 0.0, ty + 0.0, z, w_abs, w_sat, has_force, mu_n, xi_x, xi_y, phi, a0, b0


def creep_force_3d(creepage_longitudinal, creepage_lateral, spin, normal_load, a0, b0,
                   youngs_modulus, poisson_ratio, friction_coefficient, method="modified_strip",
                   **method_options):
    r"""Creep force on the wheel for a Hertzian contact ellipse, Eqs. (2.61)-(2.99).

    See the module docstring for the four methods and their formulas. Inputs broadcast.

    Parameters
    ----------
    creepage_longitudinal : array_like
        Longitudinal creepage xi_x (Eq. (2.15)). [-]
    creepage_lateral : array_like
        Lateral creepage xi_y. [-]
    spin : array_like
        Spin creepage phi. [1/m]
    normal_load : array_like
        Normal load N, >= 0. [N]
    a0 : array_like
        Semi-axis of the contact ellipse in the rolling direction, >= 0. [m]
    b0 : array_like
        Lateral semi-axis, >= 0. [m]
    youngs_modulus : array_like
        Young's modulus E of both bodies, > 0. [Pa]
    poisson_ratio : array_like
        Poisson's ratio nu of both bodies, in [0, 0.5). [-]
    friction_coefficient : array_like
        Coulomb friction coefficient mu, >= 0. [-]
    method : {"modified_strip", "strip", "she", "linear", "fastsim", "polach", "fastrip"}
        Creep-force model. "fastsim" (Kalker 1982), "fastrip" (Sichani et al. 2016):
        :mod:`railcontact.fastsim`; "polach" (Polach 1999/2005): :mod:`railcontact.polach`.
    **method_options
        Only for "fastsim"/"fastrip" (``n_strips``, ``n_elements``) and "polach"
        (``reduction_adhesion``, ``reduction_slip``, ``friction_ratio_limit``,
        ``friction_decay``, ``rolling_speed``): see :func:`railcontact.fastsim.fastsim_force_3d`,
        :func:`railcontact.fastsim.fastrip_force_3d`, :func:`railcontact.polach.polach_force_3d`.

    Returns
    -------
    CreepForce3D
        ``tx``, ``ty`` [N]. Zero creepage gives exactly zero; N = 0, mu = 0 or a0 b0 = 0 give
        zeros; odd in the creepage vector; ``|T| <= mu N`` for all methods but "linear".
        The maximum pressure used by the strip theories is ``p0 = 3 N / (2 pi a0 b0)`` (Hertz),
        so N, a0, b0 should come from :func:`railcontact.hertz_3d`.

    Raises
    ------
    ValueError
        If an input is outside the range stated above (NaN and inf included) or the method is
        unknown.

    References
    ----------
    .. [1] J.B. Nielsen, IMM-PHD-1998-51, DTU, 1998, Secs. 2.5-2.6.
    """
    if method in COMPARISON_METHODS:
        tx, ty = _comparison(creepage_longitudinal, creepage_lateral, spin, normal_load, a0, b0,
                             youngs_modulus, poisson_ratio, friction_coefficient, method,
                             method_options)[:2]
        return CreepForce3D(tx, ty)
    _no_options(method, method_options)
    tx, ty = _solve(creepage_longitudinal, creepage_lateral, spin, normal_load, a0, b0,
                    youngs_modulus, poisson_ratio, friction_coefficient, method)[:2]
    return CreepForce3D(tx[()], ty[()])


_OPTIONS = {"fastsim": ("n_strips", "n_elements"), "fastrip": ("n_strips", "n_elements"),
            "polach": ("reduction_adhesion", "reduction_slip", "friction_ratio_limit",
                       "friction_decay", "rolling_speed")}


def _no_options(method, method_options):
    if method_options:
        raise ValueError(f"method {method!r} takes no options; got "
                         f"{sorted(method_options)!r}")


def _comparison(xi_x, xi_y, phi, n_load, a0, b0, e_mod, nu, mu, method, options):
    """(tx, ty, stick_area_fraction or None) of a method of COMPARISON_METHODS."""
    unknown = sorted(set(options) - set(_OPTIONS[method]))
    if unknown:
        raise ValueError(f"method {method!r} takes the options {list(_OPTIONS[method])!r}; "
                         f"got {unknown!r}")
    if method == "polach":
        from .polach import polach_force_3d
        return polach_force_3d(xi_x, xi_y, phi, n_load, a0, b0, e_mod, nu, mu, **options) + (
            None,)
    from . import fastsim
    fun = fastsim.fastsim_force_3d if method == "fastsim" else fastsim.fastrip_force_3d
    return fun(xi_x, xi_y, phi, n_load, a0, b0, e_mod, nu, mu, **options)


def creep_solution_3d(creepage_longitudinal, creepage_lateral, spin, normal_load, a0, b0,
                      youngs_modulus, poisson_ratio, friction_coefficient,
                      method="modified_strip", **method_options):
    r"""Creep force plus stick zone, spin coefficient and validity flag.

    Same inputs as :func:`creep_force_3d`.

    Range of validity: Hertzian, steady rolling, quasi-identical materials, Coulomb friction;
    spin small enough that the spin pole lies outside the contact (Phi <= 1, Eq. (2.98));
    a0/b0 in [0.05, 20] (Kalker coefficients, see :func:`railcontact.kalker_coefficients`).
    Measured against CONTACT's exact theory (tests/test_creep3d.py), in units of mu N:
    modified strip 0.35 % (a0/b0 = 0.5, pure longitudinal, 30 points) and up to 2.0 % for
    a0/b0 = 0.2, 1, 5 without spin, 6.4 % at Phi = 1; SHE 3.8 %, 2.9 % and 9.9 % on the same
    cases; the plain strip theory is exact only in its initial slope for b0 >> a0 (4.2 % at
    a0/b0 = 0.5); the linear theory only for |T| << mu N. For Phi > 1 the same formulas are
    evaluated (|T| <= mu N still holds) and ``within_validity`` is False; pure spin is off by
    up to 59 % (large spin makes the true curve decay, which these theories do not model).

    For "fastsim" and "fastrip" the stick area fraction is the method's own (its grid);
    for "polach" (no stick zone) the modified-strip estimate, as for "she"; the other fields
    are the modified-strip ones. Measured errors of all methods against the exact theory:
    docs/accuracy_vs_time.md.

    Returns
    -------
    CreepSolution3D
        See :class:`CreepSolution3D`.
    """
    if method in COMPARISON_METHODS:
        tx, ty, stick_own = _comparison(creepage_longitudinal, creepage_lateral, spin,
                                        normal_load, a0, b0, youngs_modulus, poisson_ratio,
                                        friction_coefficient, method, method_options)
        base = creep_solution_3d(creepage_longitudinal, creepage_lateral, spin, normal_load, a0,
                                 b0, youngs_modulus, poisson_ratio, friction_coefficient)
        stick = base.stick_area_fraction if stick_own is None else stick_own
        return base._replace(tx=tx, ty=ty, stick_area_fraction=stick)
    _no_options(method, method_options)
    (tx, ty, z, w_abs, w_sat, has_force, mu_n, xi_x, xi_y, phi, a0, b0) = _solve(
        creepage_longitudinal, creepage_lateral, spin, normal_load, a0, b0, youngs_modulus,
        poisson_ratio, friction_coefficient, method)
    phi_coef = np.broadcast_to(spin_coefficient(xi_x, xi_y, phi, a0, b0), z.shape)
    zc = np.minimum(z, 1.0)
    root = np.sqrt(1.0 - zc * zc)
    stick = (2.0 / np.pi) * (np.arccos(zc) - zc * root)
    if method == "linear":
        stick = np.ones(z.shape)
        root = np.ones(z.shape)
        valid = (phi_coef <= 1.0) & (np.hypot(tx, ty) <= mu_n)
    else:
        valid = phi_coef <= 1.0
    return CreepSolution3D(tx[()], ty[()], stick[()], root[()], z[()], phi_coef[()],
                           np.asarray(valid)[()])


# --------------------------------------------------------------------------------------------
# Scalar paths (plain Python floats): the FMU's per-step calls
# --------------------------------------------------------------------------------------------
# numpy's per-call overhead (array creation, ufunc dispatch, broadcasting, the input checks)
# is ~100 us per call of creep_solution_3d on scalars, for ~1 us of arithmetic. The helpers
# below repeat the array paths' arithmetic operation for operation on floats with the math
# module, for callers that have already range-checked their inputs (the FMU slave: see
# railcontact.effects._inputs_plausible, the scene's checks and Hertz's a0, b0). They ASSUME,
# and do not check: every input a finite float (or int, not bool), normal_load >= 0, a0 >= 0,
# b0 >= 0, youngs_modulus > 0, 0 <= poisson_ratio < 0.5, friction_coefficient >= 0, method in
# METHODS, and a0/b0 in the range kalker_coefficients accepts (> 0, any value; for a0 b0 = 0
# the array path's placeholder 1 is used). Outside that the result is undefined (possibly NaN
# or an exception); use the public functions there. Agreement with the array paths to a few
# ulp (libm's hypot, acos and pow may round differently from numpy's) is tested in
# tests/test_creep3d.py.


def _f_over_z_scalar(z, _sqrt=math.sqrt, _acos=math.acos):
    """:func:`_f_over_z` for one float 0 <= z <= 1."""
    q = 1.0 - z * z
    r = _sqrt(q if q > 0.0 else 0.0)
    return z**3 * (2.0 + r) / (2.0 * (1.0 + r) ** 2) + 1.5 * _acos(z)


def _spin_coefficient_scalar(xi_x, xi_y, phi, a0, b0, _hypot=math.hypot, _inf=math.inf):
    """:func:`spin_coefficient` for plain floats (inputs assumed in range, see above)."""
    num = _hypot(a0, b0) * abs(phi)
    den = _hypot(xi_x, xi_y)
    if den > 0.0:
        return num / den
    return _inf if num > 0.0 else 0.0


_EPS4 = 4.0 * float(np.finfo(float).eps)
_STRIP_C22 = np.pi**2 / 4.0


def _creep_solution_scalar(xi_x, xi_y, phi, n_load, a0, b0, e_mod, nu, mu, method,
                           _kalker=_coefficients_cached, _sqrt=math.sqrt, _hypot=math.hypot,
                           _acos=math.acos, _pi=math.pi, _inf=math.inf):
    """:func:`creep_solution_3d` for plain floats (inputs assumed in range, see above).

    The same operations in the same order as :func:`_solve` and :func:`creep_solution_3d`;
    Kalker's coefficients from the cache :func:`railcontact.kalker._coefficients_cached` (per
    (a0/b0, nu); an FMU asks for the same ellipse shape step after step).

    Returns
    -------
    CreepSolution3D
        Fields as plain floats (``within_validity`` a bool).
    """
    mu_n = mu * n_load
    has_area = a0 > 0.0 and b0 > 0.0
    c11, c22, c23 = _kalker(a0 / b0 if has_area else 1.0, nu)
    if method == "strip":
        c11 = _pi**2 / (4.0 * (1.0 - nu)) + 0.0 * c11
        c22 = _STRIP_C22 + 0.0 * c22
    w_x = c11 * xi_x
    w_y = c22 * xi_y + _sqrt(a0 * b0) * c23 * phi
    w_abs = _hypot(w_x, w_y)
    area = _pi * a0 * b0
    p0 = 1.5 * n_load / area if area > 0.0 else 0.0
    w_sat = _pi**2 * (1.0 + nu) * mu * p0 / e_mod
    has_force = mu_n > 0.0 and w_sat > 0.0
    if w_sat > 0.0:
        z = w_abs / w_sat                                   # (inf on overflow, as meant)
    else:
        z = _inf if w_abs > 0.0 else 0.0
    stiffness = e_mod / (2.0 * (1.0 + nu)) * a0 * b0        # G a0 b0 [N]
    if method == "linear":
        factor = stiffness
    elif method == "she":
        t_lin = stiffness * w_abs
        if mu_n > 0.0:
            u = t_lin / mu_n
        else:
            u = _inf if t_lin > 0.0 else 0.0
        if u <= 3.0:
            factor = stiffness * (1.0 - u / 3.0 + u * u / 27.0)
        else:
            factor = mu_n / w_abs if w_abs > 0.0 else 0.0
        if not (has_force or w_abs == 0.0):
            factor = 0.0
    elif has_force:
        if z <= 1.0:
            factor = (mu_n / w_sat) * _f_over_z_scalar(z)
        else:
            factor = mu_n / w_abs if w_abs > 0.0 else 0.0
    else:
        factor = 0.0
    tx = -factor * w_x
    ty = -factor * w_y
    if method != "linear":                  # never above mu N (see _solve)
        t_abs = _hypot(tx, ty)
        margin = 1.0 - _EPS4 if (tx != 0.0 and ty != 0.0) else 1.0
        if t_abs > mu_n * margin:
            scale = mu_n * (1.0 - _EPS4) / t_abs
            tx, ty = tx * scale, ty * scale
    tx, ty = tx + 0.0, ty + 0.0
    phi_coef = _spin_coefficient_scalar(xi_x, xi_y, phi, a0, b0)
    if method == "linear":
        return CreepSolution3D(tx, ty, 1.0, 1.0, z, phi_coef,
                               phi_coef <= 1.0 and _hypot(tx, ty) <= mu_n)
    zc = z if z < 1.0 else 1.0
    root = _sqrt(1.0 - zc * zc)
    stick = (2.0 / _pi) * (_acos(zc) - zc * root)
    return CreepSolution3D(tx, ty, stick, root, z, phi_coef, phi_coef <= 1.0)

