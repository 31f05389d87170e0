r"""Creep forces of the 3-D Hertzian rolling contact: linear theory, SHE, strip and modified strip.

Why one module of about 900 lines: it is Secs. 2.5-2.6 of the thesis; the four closed-form
theories share the ellipse normalisation, the validation and the result types, and the exact
solver, the exact table and the comparison methods are reached through thin dispatchers (their
code lives in reference/rolling3d.py, exact_table.py, fastsim.py and polach.py).

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
from pathlib import Path
from types import SimpleNamespace

import numpy as np

from ._validation import (check_choice, check_contact_inputs, check_creep_inputs,
                          check_range)
from ._floats import scaled as _scaled, value as _value
from .creep_common import axis_ratio as _axis_ratio, coulomb_limit as _check_coulomb_limit
from .creep_common import saturation_creepage_scaled as _saturation_scaled
from .creep_common import weighted_creepage_scaled as _weighted_scaled
from .creep_common import (CreepForce3D, CreepSolution3D, ExactCreepSolution3D,
                           spin_coefficient)
from .creep_common import (EXACT_TABLE_LATERAL_ELEMENTS_NARROW,
                           EXACT_TABLE_LATERAL_ELEMENTS_VERY_NARROW,
                           EXACT_TABLE_NARROW_ASPECT_MAX, EXACT_TABLE_VERY_NARROW_ASPECT_MAX)
from .errors import RollingConvergenceError
from .friction import PolachFriction, SmoothFriction
from .kalker import kalker_coefficients

__all__ = ["CreepForce3D", "CreepSolution3D", "ExactCreepSolution3D", "METHODS",
           "COMPARISON_METHODS", "creep_coefficients", "exact_default_grid", "creep_force_3d",
           "creep_solution_3d",
           "load_exact_table", "spin_coefficient", "saturation_creepage_3d",
           "normalised_creepage_3d", "strip_force_function"]

METHODS = ("linear", "she", "strip", "modified_strip")
# method="exact" defaults, the setting on the accuracy-per-cost frontier (see creep_force_3d):
# one Richardson step 30x20 -> 60x20, averaged over two grids moved -1/4 and +1/4 of an element
EXACT_DEFAULT_GRID = (30, 20)  # elements (rolling, lateral) at a0/b0 >= 1 or little spin
# narrower contacts with spin coordinate |tau| > 1: my = 20 (b0/a0)^0.7, at most 48
# (exact_default_grid)
EXACT_DEFAULT_LATERAL_EXPONENT = 0.7
EXACT_DEFAULT_LATERAL_MAX = 48
EXACT_DEFAULT_SPIN_MIN = 1.0
EXACT_DEFAULT_EXTRAPOLATE = True  # one Richardson step in the rolling-direction element size
EXACT_DEFAULT_GRID_SHIFTS = 2  # grids averaged, moved by 1/grid_shifts of an element along x
EXACT_DEFAULT_TOLERANCE = 1e-3  # relative traction change per sweep at which to stop
EXACT_DEFAULT_TRANSPORT_ORDER = 1  # difference of the rolling term
# Methods users compare against, each in its own module (railcontact.fastsim, railcontact.polach);
# creep_force_3d and creep_solution_3d dispatch to them by name.
COMPARISON_METHODS = ("fastsim", "polach", "fastrip")

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


def creep_coefficients(a0, b0, poisson_ratio, method):
    r"""The coefficients C11, C22, C23 of the Kalker-weighted creepage a theory uses.

    ``w = (C11 xi_x, C22 xi_y + sqrt(a0 b0) C23 phi)``: Kalker's coefficients
    (:func:`railcontact.kalker_coefficients` at a0/b0) for every method but the strip theory,
    whose C11 = pi^2 / (4 (1 - nu)) (Nielsen Eq. (2.89)) and C22 = pi^2 / 4 (see the module
    docstring).

    Parameters
    ----------
    a0, b0 : array_like
        Semi-axes, >= 0 (a0 b0 = 0: the placeholder a0/b0 = 1). [m]
    poisson_ratio : array_like
        Poisson's ratio, in [0, 0.5]. [-]
    method : str
        One of :data:`METHODS`.

    Returns
    -------
    tuple of ndarray
        ``(C11, C22, C23)``. [-]
    """
    nu = poisson_ratio
    c11, c22, c23 = kalker_coefficients(_axis_ratio(a0, b0), nu)
    if method == "strip":
        c11 = np.pi**2 / (4.0 * (1.0 - nu)) + 0.0 * c11
        c22 = np.pi**2 / 4.0 + 0.0 * c22
    return c11, c22, c23


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
        z >= 0 [-]; inf if there is creepage but no friction force available (N = 0 or mu = 0)
        or if |w| / w_sat exceeds the float range (full sliding either way), 0 for zero
        creepage.
    """
    check_choice("method", method, ("modified_strip", "strip"))
    xi_x, xi_y, phi, n_load, a0, b0, e_mod, nu, mu = check_creep_inputs(
        creepage_longitudinal, creepage_lateral, spin, normal_load, a0, b0, youngs_modulus,
        poisson_ratio, friction_coefficient)
    c11, c22, c23 = creep_coefficients(a0, b0, nu, method)
    _, _, w_m, w_e = _weighted_scaled(xi_x, xi_y, phi, a0, b0, c11, c22, c23)
    s_m, s_e = _saturation_scaled(n_load, a0, b0, e_mod, nu, mu)
    w_m, w_e, s_m, s_e = np.broadcast_arrays(w_m, w_e, s_m, s_e)
    pos = s_m > 0.0
    return np.where(pos, _value(w_m / np.where(pos, s_m, 1.0), w_e - s_e),
                    np.where(w_m > 0.0, np.inf, 0.0))[()]


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
        Poisson's ratio nu, in [0, 0.5]. [-]
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
    n_load, a0, b0, e_mod, nu, mu = check_contact_inputs(normal_load, a0, b0, youngs_modulus,
                                                         poisson_ratio, friction_coefficient)
    a0 = check_range("a0", a0, "m", 0.0, None, lower_closed=False)
    b0 = check_range("b0", b0, "m", 0.0, None, lower_closed=False)
    theta = check_range("direction", direction, "rad")
    c11, c22, _ = creep_coefficients(a0, b0, nu, method)
    s_m, s_e = _saturation_scaled(n_load, a0, b0, e_mod, nu, mu)
    s_sat = _value(s_m / np.hypot(c11 * np.cos(theta), c22 * np.sin(theta)), s_e)
    if not np.all(np.isfinite(s_sat)):
        bad = np.broadcast_arrays(n_load, a0, b0, e_mod, s_sat)
        i = np.flatnonzero(~np.isfinite(bad[-1]))[0]
        raise ValueError(
            f"saturation creepage pi^2 (1 + nu) mu p0 / (E |C|) must be in "
            f"[0, {np.finfo(float).max:g}] [-]; got inf (overflow at normal_load = "
            f"{bad[0].flat[i]:g}, a0 = {bad[1].flat[i]:g}, b0 = {bad[2].flat[i]:g}, "
            f"youngs_modulus = {bad[3].flat[i]:g})")
    return s_sat[()]


def _solve(xi_x, xi_y, phi, normal_load, a0, b0, youngs_modulus, poisson_ratio,
           friction_coefficient, method):
    check_choice("method", method, METHODS + COMPARISON_METHODS + ("exact", "exact_table"))  # dispatched
    xi_x, xi_y, phi, n_load, a0, b0, e_mod, nu, mu = check_creep_inputs(
        xi_x, xi_y, phi, normal_load, a0, b0, youngs_modulus, poisson_ratio,
        friction_coefficient)
    shape = np.broadcast(xi_x, xi_y, phi, n_load, a0, b0, e_mod, nu, mu).shape
    xi_x, xi_y, phi, n_load, a0, b0, e_mod, nu, mu = (
        np.broadcast_to(v, shape) for v in (xi_x, xi_y, phi, n_load, a0, b0, e_mod, nu, mu))
    if method == "linear":
        with np.errstate(over="ignore"):
            mu_n = mu * n_load                   # (only for within_validity: may be inf)
    else:
        mu_n = _check_coulomb_limit(mu, n_load)
    c11, c22, c23 = creep_coefficients(a0, b0, nu,
                                       "strip" if method == "strip" else "modified_strip")
    # All in (mantissa, exponent) form (see _scaled): no intermediate overflows or underflows,
    # and the same operations in the same order as the scalar path
    # (railcontact._scalar.creep_solution_3d_scalar),
    # so the two agree bit for bit wherever its plain floats stay in the normal range.
    d_x, d_y, w_m, w_e, u_x, u_y, top = _weighted_scaled(xi_x, xi_y, phi, a0, b0, c11, c22,
                                                         c23, parts=True)
    w_abs = _value(w_m, w_e)
    s_m, s_e = _saturation_scaled(n_load, a0, b0, e_mod, nu, mu)
    w_sat = _value(s_m, s_e)
    has_force = (mu_n > 0.0) & (s_m > 0.0)
    # z = |w| / w_sat (inf: no contact with creepage, or beyond the float range: sliding)
    s_safe = (np.where(s_m > 0.0, s_m, 1.0), s_e)
    z = np.where(s_m > 0.0, _value(*_scaled(((w_m, w_e),), (s_safe,))),
                 np.where(w_m > 0.0, np.inf, 0.0))
    stiffness = _scaled((e_mod / (2.0 * (1.0 + nu)), a0, b0))       # G a0 b0 [N]
    w_safe = (np.where(w_m > 0.0, w_m, 1.0), w_e)
    mun_safe = np.where(mu_n > 0.0, mu_n, 1.0)

    if method == "linear":
        f_m, f_e = stiffness
    elif method == "she":
        t_lin = _scaled((stiffness, (w_m, w_e)))
        u = np.where(mu_n > 0.0, _value(*_scaled((t_lin,), (mun_safe,))),
                     np.where(t_lin[0] > 0.0, np.inf, 0.0))
        small = u <= 3.0
        u_c = np.minimum(u, 3.0)
        f_small = _scaled((stiffness, 1.0 - u_c / 3.0 + u_c * u_c / 27.0))
        f_big = _scaled((mun_safe,), (w_safe,))
        f_m = np.where(small, f_small[0], np.where(w_m > 0.0, f_big[0], 0.0))
        f_e = np.where(small, f_small[1], f_big[1])
        f_m = np.where(has_force | (w_m == 0.0), f_m, 0.0)
    else:
        # T = -mu N F(z) w/|w| = -(mu N / w_sat) (F(z)/z) w   (z <= 1),  -mu N w/|w|  (z > 1)
        below = z <= 1.0
        zc = np.minimum(z, 1.0)
        f_small = _scaled((_scaled((mun_safe,), (s_safe,)), _f_over_z(zc)))
        f_big = _scaled((mun_safe,), (w_safe,))
        f_m = np.where(below, f_small[0], np.where(w_m > 0.0, f_big[0], 0.0))
        f_e = np.where(below, f_small[1], f_big[1])
        f_m = np.where(has_force, f_m, 0.0)
    tx = -_value(f_m * u_x, f_e + top)
    ty = -_value(f_m * u_y, f_e + top)
    if method == "linear" and not (np.all(np.isfinite(tx)) and np.all(np.isfinite(ty))):
        i = np.flatnonzero(~(np.isfinite(tx) & np.isfinite(ty)))[0]
        args = ", ".join(f"{n} = {v.flat[i]:g}" for n, v in (
            ("creepage_longitudinal", xi_x), ("creepage_lateral", xi_y), ("spin", phi),
            ("a0", a0), ("b0", b0), ("youngs_modulus", e_mod)))
        raise ValueError(f"the linear theory's force G a0 b0 |w| must be in "
                         f"[0, {np.finfo(float).max:g}] [N] (no Coulomb limit); got inf "
                         f"(overflow at {args})")
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
                   *, grid=None, extrapolate=EXACT_DEFAULT_EXTRAPOLATE,
                   tolerance=EXACT_DEFAULT_TOLERANCE, transport_order=EXACT_DEFAULT_TRANSPORT_ORDER,
                   grid_shifts=EXACT_DEFAULT_GRID_SHIFTS, rolling_speed=None, **method_options):
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
        Poisson's ratio nu of both bodies, in [0, 0.5]. [-]
    friction_coefficient : array_like or friction law
        Coulomb friction coefficient mu, >= 0; or a friction law: a callable ``mu(s)`` of the
        slip magnitude ``s = |slip velocity| / V`` [-] such as
        :class:`railcontact.friction.SmoothFriction` (Eq. (5.16)), or a law in the slip
        velocity ``w`` [m/s] (``needs_rolling_speed = True``), such as
        :class:`railcontact.friction.PolachFriction` (Polach 2005,
        ``mu0 ((1 - A) exp(-B w) + A)``), which needs ``rolling_speed``. A law is honoured by
        ``method="exact"`` (Kalker's exact theory with slip-dependent friction: the bound
        ``mu(|s|) p`` element by element, at the local slip; the force scale is
        ``mu(0) N``) and ``"polach"`` (a :class:`PolachFriction` only: its own 2005 law, at
        the slip velocity ``V |xi|`` of the contact), ``"fastsim"`` (the bound ``mu(q) p``
        per element at the element's slip q: :mod:`railcontact.fastsim`, a crude theory) and
        ``"exact_table"`` (a fast path on the Coulomb table, :mod:`railcontact.falling_table`:
        a model and a correction table of what it misses; within 1 % of mu(0) N of the exact
        theory on 99.96 % of random cases, up to 0.96 % without spin, 1.00 % with spin
        coordinate |tau| <= 1, up to 1.08 % with larger spin and 0.91 % where a strong
        law's stick zone collapses with spin (the smooth law; Polach's up to 1.8 %); about
        8 us a scalar call with a
        :class:`SmoothFriction`, 9 us with a :class:`PolachFriction`, on a contact the
        table keeps a buffer for, one whose a0/b0 stays; 12-13 us where a0/b0 changes at
        every call, as a vehicle's in a co-simulation (the compiled kernel on the table's
        five-dimensional spline; 17-18 us until the table has summed itself over nu, after
        some 7,000 calls of one nu); every other method raises ValueError. The law must give a
        finite ``mu >= 0`` at every slip and ``mu(0) > 0``. [-]
    method : {"modified_strip", "strip", "she", "linear", "exact", "exact_table", "fastsim", "polach", "fastrip"}
        Creep-force model (default "modified_strip", the thesis's method; the module docstring
        gives the formulas):

        * "modified_strip": modified strip theory with spin, Eqs. (2.90)-(2.96), (2.99)
          (Nielsen).
        * "strip": strip theory, Eqs. (2.83)-(2.87) (Haines and Ollerton).
        * "she": Shen, Hedrick and Elkins, Eqs. (2.63)-(2.65).
        * "linear": Kalker's linear theory, Eqs. (2.61)-(2.62) (not saturated).
        * "exact": Kalker's exact theory, discretised
          (:func:`railcontact.reference.rolling3d.solve_rolling_3d`), one solve per element;
          needs ``|creepage| <= 1`` and ``|spin| max(a0, b0) <= 1``.
        * "exact_table": the exact theory from the shipped table ``creep_exact``
          (:class:`railcontact.exact_table.ExactCreepTable`); beyond a0/b0 0.1-10 or spin
          coordinate 20 it calls "exact".
        * "fastsim" (Kalker 1982), "fastrip" (Sichani et al. 2016): :mod:`railcontact.fastsim`.
        * "polach" (Polach 1999/2005): :mod:`railcontact.polach`.

        Speed and error of each: docs/figures.md; the exact solver's settings, measured:
        docs/reference_solvers.md.
    grid : (int, int) or None, keyword-only
        ``method="exact"`` only: elements (mx, my) in the rolling and lateral direction over
        ``[-1.08 a0, 1.08 a0] x [-1.08 b0, 1.08 b0]`` (CONTACT's potential area). Default None:
        :func:`exact_default_grid` per case, (30, 20) where a0/b0 >= 1 or the spin coordinate
        |tau| <= 1, else lateral elements following the ellipse, ``my = ceil(20 (b0/a0)^0.7)``
        up to 48. With ``extrapolate=True, grid_shifts=2, tolerance=1e-3`` within 0.2 % of mu N
        of the converged theory in every a/b x spin class (docs/reference_solvers.md); a plain
        solve on one grid: ``extrapolate=False, grid_shifts=1``.
    extrapolate : bool, keyword-only
        ``method="exact"`` only: one Richardson step in the rolling direction,
        ``2 F(2 mx, my) - F(mx, my)``. Default True.
    grid_shifts : {1, 2, 3, 4}, keyword-only
        ``method="exact"`` only: average over this many grids moved by
        ``(k + 1/2) / grid_shifts - 1/2`` of an element along x, each with its own Richardson
        step. Default 2; needs ``mx >= 30``.
    tolerance : float, keyword-only
        ``method="exact"`` only: relative change of the tractions per Gauss-Seidel sweep at
        which the iteration stops, in (0, 0.1]. Default 1e-3. [-]
    transport_order : {1, 2}, keyword-only
        ``method="exact"`` only: difference of the rolling term, 1 (first-order upwind, as
        Kalker's and CONTACT's; default) or 2 (three-point upwind). [-]
    rolling_speed : array_like, optional, keyword-only
        Rolling speed V > 0 for a friction law in the slip velocity
        (``friction_coefficient`` with ``needs_rolling_speed``; other laws and Coulomb
        friction ignore it); with ``method="polach"`` its ``rolling_speed`` option. [m/s]
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
    railcontact.reference.rolling3d.RollingConvergenceError
        ``method="exact"``: the iteration did not converge (a RuntimeError; never a silent
        unconverged answer).

    References
    ----------
    .. [1] J.B. Nielsen, IMM-PHD-1998-51, DTU, 1998, Secs. 2.5-2.6.
    .. [2] J.J. Kalker, Three-dimensional elastic bodies in rolling contact, Kluwer, 1990.
    .. [3] E.A.H. Vollebregt, CONTACT (the potential area and the reference cases).
    """
    if method == "exact_table" and not method_options and not callable(friction_coefficient):
        table = _EXACT_TABLES.get(_DEFAULT_KEY) or load_exact_table()
        return table.creep_force_3d(creepage_longitudinal, creepage_lateral, spin, normal_load,
                                    a0, b0, youngs_modulus, poisson_ratio, friction_coefficient)
    if method == "exact_table" and callable(friction_coefficient) and not method_options:
        # one contact in plain floats: the compiled path of the package's laws, or of a law
        # the general path has tabulated already (None: the general one)
        got = _falling_compiled_scalar(creepage_longitudinal, creepage_lateral, spin,
                                       normal_load, a0, b0, youngs_modulus, poisson_ratio,
                                       friction_coefficient, rolling_speed)
        if got is not None:
            return got
    friction_coefficient, law, speed, method_options = _friction_input(
        friction_coefficient, rolling_speed, method, method_options)
    if law is not None and method == "exact_table":
        return _falling_table(creepage_longitudinal, creepage_lateral, spin, normal_load, a0,
                              b0, youngs_modulus, poisson_ratio, friction_coefficient, law,
                              speed)
    if method in COMPARISON_METHODS:
        tx, ty = _comparison(creepage_longitudinal, creepage_lateral, spin, normal_load, a0, b0,
                             youngs_modulus, poisson_ratio, friction_coefficient, method,
                             method_options, law, speed)[:2]
        return CreepForce3D(tx, ty)
    _no_options(method, method_options)
    if method == "exact":
        return _exact_force(creepage_longitudinal, creepage_lateral, spin, normal_load, a0, b0,
                            youngs_modulus, poisson_ratio, friction_coefficient, grid,
                            extrapolate, tolerance, transport_order, grid_shifts, law, speed)
    tx, ty = _solve(creepage_longitudinal, creepage_lateral, spin, normal_load, a0, b0,
                    youngs_modulus, poisson_ratio, friction_coefficient, method)[:2]
    return CreepForce3D(tx[()], ty[()])


def _friction_input(friction_coefficient, rolling_speed, method, method_options):
    """``(mu, law, speed, method_options)`` of the ``friction_coefficient`` input.

    Coulomb (a number): ``(friction_coefficient, None, None, options)``. A friction law: ``mu``
    its static value ``mu(0)`` (the force scale), ``law`` a callable of the slip ``s`` [-]
    (a law in the slip velocity is evaluated at ``s V``; ``speed`` is V, broadcastable), and
    for ``method="polach"`` a :class:`railcontact.friction.PolachFriction` as Polach's own
    options. ``rolling_speed`` becomes the option of ``method="polach"`` in any case.
    Raises ValueError for a method that cannot honour a law, a law that is not a callable
    ``mu(s)`` or gives a negative or non-finite mu, or a missing ``rolling_speed``."""
    options = dict(method_options)
    if method == "polach" and rolling_speed is not None:
        if "rolling_speed" in options:
            raise ValueError("rolling_speed given twice (keyword and method option)")
        options["rolling_speed"] = rolling_speed
    if not callable(friction_coefficient):
        return friction_coefficient, None, None, options
    law = friction_coefficient
    if method not in ("exact", "exact_table", "polach", "fastsim"):
        raise ValueError(
            f"method {method!r} cannot honour a friction law (friction_coefficient={law!r}): "
            f"it is a Coulomb-friction theory; use method='exact', 'exact_table' or 'fastsim' "
            f"(or pass a number for friction_coefficient)")
    needs_speed = bool(getattr(law, "needs_rolling_speed", False))
    speed = None
    if method == "polach" and rolling_speed is None:
        rolling_speed = options.get("rolling_speed")      # given as Polach's option
    if needs_speed:
        if rolling_speed is None:
            raise ValueError(f"rolling_speed must be given [m/s] for the friction law {law!r}, "
                             f"a law in the slip velocity; got None")
        speed = check_range("rolling_speed", rolling_speed, "m/s", 0.0, None,
                            lower_closed=False)
    slips = np.concatenate([[0.0], np.logspace(-8, 1, 91)])
    try:
        probe = law(slips * (float(np.max(speed)) if needs_speed else 1.0))
        values = np.broadcast_to(np.asarray(probe, dtype=float), slips.shape)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"friction_coefficient must be a number or a friction law mu(slip) "
                         f"[-] (railcontact.friction); got {law!r}, which fails on an array of "
                         f"slips ({exc})") from None
    bad = ~(np.isfinite(values) & (values >= 0.0))
    if np.any(bad) or not values[0] > 0.0:
        i = int(np.flatnonzero(bad)[0]) if np.any(bad) else 0
        raise ValueError(f"friction_coefficient {law!r} must give a finite mu >= 0 at every "
                         f"slip and mu(0) > 0 [-]; got mu = {values[i]:g} at slip "
                         f"{slips[i]:g}")
    mu0 = float(values[0])
    if method == "polach":
        from .friction import PolachFriction  # noqa: PLC0415
        if not isinstance(law, PolachFriction):
            raise ValueError(f"method 'polach' honours only its own law "
                             f"(railcontact.friction.PolachFriction) as friction_coefficient; "
                             f"got {law!r}: use method='exact' or 'exact_table'")
        clash = sorted({"friction_ratio_limit", "friction_decay"} & set(options))
        if clash:
            raise ValueError(f"method 'polach': {clash} given both as options and by the "
                             f"friction law {law!r}")
        options.update(friction_ratio_limit=law.friction_ratio_limit,
                       friction_decay=law.friction_decay)
        return mu0, None, None, options
    return mu0, law, speed, options


def _falling_compiled_scalar(*args):
    """``CreepForce3D`` of the exact table with a :class:`SmoothFriction` or
    :class:`PolachFriction` (with a float ``rolling_speed`` > 0), or any other law the general
    path has tabulated (:func:`_falling_kernel_law`), for one contact in plain floats by
    :func:`railcontact.falling_table.falling_friction_table_compiled`, or None (other inputs,
    mu_0 = 0, a law not tabulated yet, no contact buffer yet, or a case the table's kernel
    hands to its array path: the caller takes the general path, which checks the inputs)."""
    law, speed = args[8], args[9]
    if not all(type(v) is float for v in args[:8]):
        return None
    if type(law) is PolachFriction or getattr(law, "needs_rolling_speed", False):
        if not (type(speed) is float and 0.0 < speed < math.inf):
            return None
    else:
        speed = None
    got = _falling_kernel_call(_EXACT_TABLES.get(_DEFAULT_KEY) or load_exact_table(),
                               args[:8], law, speed)
    return None if got is None else _new_force(got[0] + 0.0, got[1] + 0.0)


#: Tabulated laws of :func:`_falling_kernel_law`, per (law object, rolling speed): the last few.
_LAW_TABLES = {}


def _falling_kernel_law(law, speed, law_s=None):
    """The law as the compiled fast path takes it, ``(kind, p0, p1, p2, p3, table)``
    (:func:`railcontact.falling_table.falling_friction_table_compiled`): the package's laws in
    closed form, any other on its :func:`railcontact.falling_table.law_table` (made here once
    per law object and rolling speed ``speed``, a float or None, when the general path passes
    ``law_s``, the law in the slip; a law is taken as fixed once passed), or None (a law the
    table cannot hold, or not tabulated yet)."""
    if type(law) is SmoothFriction:
        return 0, law.mu_static, law.mu_kinetic, law.kappa, 0.0, None
    if type(law) is PolachFriction:
        return None if speed is None else (1, law.mu_static, law.friction_ratio_limit,
                                           law.friction_decay, speed, None)
    key = (id(law), speed)
    entry = _LAW_TABLES.get(key)
    if (entry is None or entry[0] is not law) and law_s is not None:
        from .falling_table import law_table  # noqa: PLC0415

        if len(_LAW_TABLES) >= 8:
            _LAW_TABLES.pop(next(iter(_LAW_TABLES)))
        entry = _LAW_TABLES[key] = (law, law_table(law_s))
    if entry is None or entry[0] is not law or entry[1] is None:
        return None
    return 2, float(entry[1][1, 0]), 0.0, 0.0, 0.0, entry[1]


def _falling_kernel_call(table, plain, law, speed, law_s=None):
    """The compiled fast path for one contact (``plain``: the eight checked inputs before the
    friction, floats) with the law of :func:`_falling_kernel_law`: ``(tx, ty, mz, stick, z,
    mu_e)``, or None (the caller's other path)."""
    from .falling_table import falling_friction_table_compiled  # noqa: PLC0415

    kernel_law = _falling_kernel_law(law, speed, law_s)
    if kernel_law is None or not kernel_law[1] > 0.0:
        return None
    try:
        return falling_friction_table_compiled(table, *plain, *kernel_law[:5],
                                               tabulated=kernel_law[5])
    except (TypeError, ValueError, ArithmeticError):
        return None


def _new_force(tx, ty):
    return tuple.__new__(CreepForce3D, (tx, ty))


def _falling_table(xi_x, xi_y, phi, normal_load, a0, b0, youngs_modulus, poisson_ratio, mu0,
                   law, speed, solution=False):
    """``method="exact_table"`` with a friction law: :mod:`railcontact.falling_table` on the
    Coulomb exact table and its correction table (an approximation: within 1 % of mu_0 N on
    99.96 % of random cases, up to 0.96 % without spin, 1.00 % with |tau| <= 1, 1.08 % with
    larger spin, 0.91 % where a strong law's stick zone collapses with spin). Plain floats
    take the table's scalar path."""
    from .falling_table import falling_friction_table, law_family, law_shape  # noqa: PLC0415

    table = _EXACT_TABLES.get(_DEFAULT_KEY) or load_exact_table()
    args = check_creep_inputs(xi_x, xi_y, phi, normal_load, a0, b0, youngs_modulus,
                              poisson_ratio, mu0)
    scalar = all(np.ndim(v) == 0 for v in args) and (speed is None or np.ndim(speed) == 0)
    shape = np.broadcast_shapes(*(np.shape(v) for v in args),
                                () if speed is None else np.shape(speed))
    args = [np.broadcast_to(np.asarray(v, dtype=float), shape) for v in args]
    if scalar:
        plain = [float(v) for v in args[:8]]

        def values(mu):
            mu = float(mu)
            v = table.step_values(*plain, mu, False)
            return v[:5] if v is not None else table.step(*plain, mu, False)[:5]
    else:
        def values(mu):
            sol = table.creep_solution_3d(*args[:8], mu, sensitivities=False)
            return (np.asarray(sol.tx, dtype=float), np.asarray(sol.ty, dtype=float),
                    np.asarray(sol.spin_moment, dtype=float),
                    np.asarray(sol.stick_area_fraction, dtype=float),
                    np.asarray(sol.normalised_creepage, dtype=float))
    factor = None if speed is None else np.broadcast_to(np.asarray(speed, dtype=float),
                                                         shape)[..., None]

    cap = None if factor is None else 0.5 * np.finfo(float).max / np.maximum(factor, 1.0)

    def law_s(slip):    # (a slip velocity s V kept finite at any creepage)
        return law(slip if factor is None else np.minimum(slip, cap) * factor)

    got = (_falling_kernel_call(table, plain, law, None if speed is None else float(speed),
                                law_s) if scalar else None)
    if got is None:     # (arrays; a law the table cannot hold; slips beyond it; no buffer yet)
        got = falling_friction_table(values, *args[:6], law_s, args[8],
                                     (args[6], args[7], *law_shape(law, speed, law_s),
                                      law_family(law)))
    tx, ty, mz, stick, z, _ = (np.asarray(v, dtype=float) for v in got)
    if not solution:
        return CreepForce3D(tx[()] + 0.0, ty[()] + 0.0)
    phi_c = np.broadcast_to(spin_coefficient(args[0], args[1], args[2], args[4], args[5]),
                            shape)
    return ExactCreepSolution3D(tx[()] + 0.0, ty[()] + 0.0, np.asarray(stick)[()], None,
                                np.asarray(z)[()], np.asarray(phi_c)[()],
                                np.ones(shape, dtype=bool)[()], np.asarray(mz)[()], None, None,
                                None)


_OPTIONS = {"fastsim": ("n_strips", "n_elements"), "fastrip": ("n_strips", "n_elements"),
            "polach": ("reduction_adhesion", "reduction_slip", "friction_ratio_limit",
                       "friction_decay", "rolling_speed")}


def _no_options(method, method_options):
    if method_options:
        raise ValueError(f"method {method!r} takes no options; got "
                         f"{sorted(method_options)!r}")


def _comparison(xi_x, xi_y, phi, n_load, a0, b0, e_mod, nu, mu, method, options, law=None,
                speed=None):
    """(tx, ty, stick_area_fraction or None) of a method of COMPARISON_METHODS.

    Inputs are range-checked here, then each case is evaluated on the similar reference
    contact (:func:`_similar_reference`): FASTSIM, FaStrip and Polach's forces over mu N
    depend only on a0/b0, nu and the creepages over mu p0 / G (Polach 2005's slip velocity
    V |xi| is kept by scaling the speed back), so no product of the inputs can overflow.
    ``law`` (FASTSIM only; ``mu`` is then its mu(0)) and ``speed``: a friction law in the slip
    (or, with ``speed``, the slip velocity), carried to the reference contact as for
    ``method="exact"`` (the slip scaled back to the user's, also beyond the creepage cap)."""
    unknown = sorted(set(options) - set(_OPTIONS[method]))
    if unknown:
        raise ValueError(f"method {method!r} takes the options {list(_OPTIONS[method])!r}; "
                         f"got {unknown!r}")
    xi_x, xi_y, phi, n_load, a0, b0, e_mod, nu, mu = check_creep_inputs(
        xi_x, xi_y, phi, n_load, a0, b0, e_mod, nu, mu)
    sim = _similar_reference(xi_x, xi_y, phi, n_load, a0, b0, e_mod, nu, mu, method)
    ref, force_scale, speed_scale = sim["args"], sim["force_scale"], sim["speed_scale"]
    options = dict(options)
    if "rolling_speed" in options:
        speed = check_range("rolling_speed", options["rolling_speed"], "m/s", 0.0, None)
        with np.errstate(over="ignore", invalid="ignore"):
            options["rolling_speed"] = np.where(speed > 0.0, speed * speed_scale, 0.0)
    if law is not None:
        if speed is not None:
            speed = np.broadcast_to(speed, np.broadcast_shapes(np.shape(speed),
                                                               ref[0].shape))
            if speed.shape != ref[0].shape:
                raise ValueError(f"rolling_speed must broadcast with the other inputs (shape "
                                 f"{ref[0].shape}); got shape {speed.shape}")
        ref = ref[:8] + (_reference_law(law, sim["creepage_scale"][..., None],
                                        None if speed is None else speed[..., None],
                                        float(np.max(mu))),)
    if method == "polach":
        from .polach import polach_force_3d
        tx, ty = polach_force_3d(*ref, **options)
        stick = None
    else:
        from . import fastsim
        fun = fastsim.fastsim_force_3d if method == "fastsim" else fastsim.fastrip_force_3d
        tx, ty, stick = fun(*ref, **options)
    if law is not None:   # the bound is max mu(s) N, not mu(0) N: FASTSIM's own clip holds
        tx, ty = tx * force_scale + 0.0, ty * force_scale + 0.0
        return tx[()], ty[()], stick
    tx, ty = _coulomb_clipped(tx * force_scale, ty * force_scale, n_load, mu)
    return tx[()], ty[()], stick


def _coulomb_clipped(tx, ty, n_load, mu):
    """(tx, ty) with |T| <= mu N as the caller computes mu N (the product, rounded; a few ulp
    of scaling back from the reference contact, or a subnormal mu N, could exceed it)."""
    with np.errstate(over="ignore", under="ignore", invalid="ignore", divide="ignore"):
        tx, ty = np.asarray(tx, dtype=float) + 0.0, np.asarray(ty, dtype=float) + 0.0
        mu_n = np.broadcast_to(np.asarray(mu, dtype=float) * np.asarray(n_load, dtype=float),
                               tx.shape)
        t_abs = np.hypot(tx, ty)
        over = t_abs > mu_n
        factor = np.where(over, mu_n / np.where(over, t_abs, 1.0), 1.0)
        tx, ty = tx * factor, ty * factor
        for _ in range(3):     # rounding (a subnormal mu N has few digits): step towards 0
            over = np.hypot(tx, ty) > mu_n
            tx = np.where(over, np.nextafter(tx, 0.0), tx)
            ty = np.where(over, np.nextafter(ty, 0.0), ty)
    return tx, ty


#: The contact every case of method "exact", "fastsim", "polach" and "fastrip" is evaluated
#: on (by similarity, see :func:`_similar_reference`); also the exact table's reference
#: contact (:data:`railcontact.tables.EXACT_REFERENCE_CONTACT`). a0 b0 = area_radius^2.
#: [N, Pa, -, m]
REFERENCE_CONTACT = dict(normal_load=1.0e5, youngs_modulus=210e9, friction_coefficient=0.3,
                         area_radius=6.0e-3)
#: a0/b0 range of the methods evaluated on the reference contact (their grids resolve it). [-]
SIMILAR_AXIS_RATIO_RANGE = (0.01, 100.0)
#: FASTSIM, FaStrip, Polach: creepages beyond this many saturation creepages (mu p0 / G) are
#: evaluated at it, the direction of (xi_x, xi_y, phi) kept: every element slides there, and
#: the force is the full-sliding force to about 1e-4 of mu N. (method "exact" refuses
#: creepages beyond its solver's domain instead.)
SIMILAR_CREEPAGE_CAP = 1e4


def _similar_reference(xi_x, xi_y, phi, n_load, a0, b0, e_mod, nu, mu, method):
    """The similar problem on :data:`REFERENCE_CONTACT` (broadcast arrays) and the factors
    back: a dict with ``args`` (the nine inputs there), ``force_scale``, ``speed_scale``
    (Polach 2005: V_r = V speed_scale keeps the slip velocity), and for ``method="exact"``
    ``moment_scale``, ``creepage_scale`` (d xi_r / d xi) and ``spin_scale`` (d phi_r / d phi).

    Creepages scale with k = (G / (mu p0)) / (G_r / (mu_r p0_r)), p0 = 3 N / (2 pi a0 b0), the
    spin with k sqrt(a0 b0 / A_r), forces with mu N / (mu_r N_r), the spin moment with that
    times sqrt(a0 b0 / A_r); all in logarithms, so no product of the inputs overflows. No load,
    friction or area gives a zero force scale (no force, as the other methods).

    Raises ValueError where a0/b0 is outside :data:`SIMILAR_AXIS_RATIO_RANGE`, where mu N (or
    the spin moment) leaves the float range, and for ``"exact"`` where the similar creepages
    are beyond the solver's domain (|xi| <= 1, |phi| max(a0, b0) <= 1 on the reference
    contact: some 200 times the saturation creepage); the other methods cap them at
    :data:`SIMILAR_CREEPAGE_CAP` saturation creepages instead."""
    ref = REFERENCE_CONTACT
    area_r = ref["area_radius"] ** 2
    xi_x, xi_y, phi, n_load, a0, b0, e_mod, nu, mu = np.broadcast_arrays(
        *(np.asarray(v, dtype=float) for v in (xi_x, xi_y, phi, n_load, a0, b0, e_mod, nu, mu)))
    none = (n_load == 0.0) | (mu == 0.0) | (a0 == 0.0) | (b0 == 0.0)

    def log(v):
        return np.log(np.where(none, 1.0, v))

    # the ratio is checked wherever both semi-axes are > 0, as the analytic methods do; "exact"
    # skips the cases without load or friction, which it answers with zero before solving
    has_area = (a0 > 0.0) & (b0 > 0.0) & ~(none if method == "exact" else False)
    log_ratio = np.where(has_area, np.log(np.where(has_area, a0, 1.0))
                         - np.log(np.where(has_area, b0, 1.0)), 0.0)
    lo, hi = SIMILAR_AXIS_RATIO_RANGE
    check_range("a0/b0", np.exp(np.clip(log_ratio, -700.0, 700.0)), "-", lo, hi,
                condition=f"semi-axis ratio for method={method!r}, the range its grid resolves")
    log_g = np.log(e_mod) - np.log(2.0 * (1.0 + nu))
    log_p0 = np.log(1.5 / np.pi) + log(n_load) - log(a0) - log(b0)
    log_g_r = np.log(ref["youngs_modulus"]) - np.log(2.0 * (1.0 + nu))
    log_p0_r = np.log(1.5 / np.pi) + np.log(ref["normal_load"]) - np.log(area_r)
    log_k = (log_g - log(mu) - log_p0) - (log_g_r - np.log(ref["friction_coefficient"])
                                          - log_p0_r)
    log_spin = log_k + 0.5 * (log(a0) + log(b0) - np.log(area_r))
    a_r = ref["area_radius"] * np.exp(0.5 * log_ratio)
    b_r = ref["area_radius"] * np.exp(-0.5 * log_ratio)
    values = (xi_x, xi_y, phi)
    with np.errstate(divide="ignore"):
        log_parts = np.stack([np.log(np.abs(xi_x)) + log_k, np.log(np.abs(xi_y)) + log_k,
                              np.log(np.abs(phi)) + log_spin + np.log(np.maximum(a_r, b_r))])
    if method == "exact":
        shrink = 0.0
        for part, value, name, unit in zip(log_parts, values,
                                           ("creepage_longitudinal", "creepage_lateral", "spin"),
                                           ("-", "-", "1/m")):
            beyond = ~none & (part > 0.0)       # |similar value| > 1: beyond the domain
            if np.any(beyond):
                raise ValueError(
                    f"{name} must be in the exact solver's domain: at most 1 on the similar "
                    f"reference contact (creepage, or rigid spin slip |phi| max(a0, b0); about "
                    f"200 times the saturation creepage mu p0 / G) [{unit}]; got "
                    f"{value[beyond].flat[0]:g} (similar value e^{part[beyond].flat[0]:.3g})")
    else:
        w_sat_r = (ref["friction_coefficient"] * 1.5 * ref["normal_load"] / (np.pi * area_r)
                   / (ref["youngs_modulus"] / (2.0 * (1.0 + nu))))
        log_cap = np.log(SIMILAR_CREEPAGE_CAP * w_sat_r)
        shrink = np.minimum(0.0, log_cap - log_parts.max(axis=0))   # direction kept
    with np.errstate(under="ignore"):
        xi_r, eta_r, phi_r = (np.where((value == 0.0) | none, 0.0,
                                       np.copysign(np.exp(part + shrink), value))
                              for part, value in zip(log_parts, values))
    phi_r = phi_r / np.maximum(a_r, b_r)
    log_mu_n = log(mu) + log(n_load)
    log_force = log_mu_n - np.log(ref["friction_coefficient"] * ref["normal_load"])
    log_moment = log_force + 0.5 * (log(a0) + log(b0) - np.log(area_r))
    over = ~none & (np.maximum(log_mu_n, log_moment if method == "exact" else -np.inf)
                    > 709.0)
    if np.any(over):
        raise ValueError("friction_coefficient * normal_load must be within the float range "
                         f"[N] (and the spin moment with it); got mu = {mu[over].flat[0]:g}, "
                         f"N = {n_load[over].flat[0]:g}")
    with np.errstate(over="ignore", under="ignore", invalid="ignore"):
        direct = mu * n_load / (ref["friction_coefficient"] * ref["normal_load"])
    usable = np.isfinite(direct) & (np.abs(direct) >= np.finfo(float).tiny)
    full = np.full(xi_r.shape, 1.0)
    return {"args": (xi_r, eta_r, phi_r, ref["normal_load"] * full, a_r, b_r,
                     ref["youngs_modulus"] * full, nu, ref["friction_coefficient"] * full),
            "force_scale": np.where(none, 0.0, np.where(usable, direct, np.exp(log_force))),
            "moment_scale": np.where(none, 0.0, np.exp(np.minimum(log_moment, 709.0))),
            "creepage_scale": np.exp(np.minimum(log_k + shrink, 709.0)),
            "spin_scale": np.exp(np.minimum(log_spin + shrink, 709.0)),
            "speed_scale": np.exp(np.clip(-(log_k + shrink), -709.0, 709.0))}


def creep_solution_3d(creepage_longitudinal, creepage_lateral, spin, normal_load, a0, b0,
                      youngs_modulus, poisson_ratio, friction_coefficient,
                      method="modified_strip", *, grid=None,
                      extrapolate=EXACT_DEFAULT_EXTRAPOLATE, tolerance=EXACT_DEFAULT_TOLERANCE,
                      sensitivities=False, fields=False,
                      transport_order=EXACT_DEFAULT_TRANSPORT_ORDER,
                      grid_shifts=EXACT_DEFAULT_GRID_SHIFTS, rolling_speed=None,
                      **method_options):
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

    With ``method="exact"`` (see :func:`creep_force_3d` for ``grid``, ``extrapolate``,
    ``grid_shifts`` and ``tolerance``, their defaults, cost and accuracy) the exact theory is
    solved and the result also holds the spin moment, and on request:

    sensitivities : bool, keyword-only
        The Jacobian d(tx, ty, M_z)/d(xi_x, xi_y, phi) of the discrete problem, from the
        problem linearised at the converged slip/stick partition (one dense solve per grid,
        growing as the cube of the number of contact elements: about 0.1 s at 40x20; with the
        default four grids up to 30x20 and 60x20, about 1 s), extrapolated and averaged over
        the grid shifts like the forces.
    fields : bool, keyword-only
        The solver's element fields (pressure, tractions, slip, stick/slip masks) of the
        finest grid solved (with ``grid_shifts``, the last shifted one; the forces are the
        extrapolated, averaged ones, not the sum of these tractions). The stick area fraction
        and width ratio are those of the same grid.

    For "fastsim" and "fastrip" the stick area fraction is the method's own (its grid);
    for "polach" (no stick zone) the modified-strip estimate, as for "she"; the other fields
    are the modified-strip ones. Measured errors of all methods against the exact theory:
    docs/accuracy_vs_time.md.

    Returns
    -------
    CreepSolution3D or ExactCreepSolution3D
        See :class:`CreepSolution3D` and, for ``method="exact"``,
        :class:`ExactCreepSolution3D` (the same first seven fields).

    Raises
    ------
    ValueError
        As :func:`creep_force_3d`; also ``sensitivities`` or ``fields`` with another method.
    railcontact.reference.rolling3d.RollingConvergenceError
        ``method="exact"``: the iteration did not converge.
    """
    friction_coefficient, law, speed, method_options = _friction_input(
        friction_coefficient, rolling_speed, method, method_options)
    if law is not None and method == "exact_table":
        if fields or sensitivities:
            raise ValueError("fields and sensitivities need method='exact' and, for "
                             "sensitivities, a constant friction_coefficient; got "
                             "method='exact_table' with a friction law")
        return _falling_table(creepage_longitudinal, creepage_lateral, spin, normal_load, a0,
                              b0, youngs_modulus, poisson_ratio, friction_coefficient, law,
                              speed, solution=True)
    if law is not None and sensitivities:
        raise ValueError("sensitivities need a constant friction_coefficient (the Jacobian of "
                         "the linearised problem); got the friction law "
                         f"{law!r}")
    if method in COMPARISON_METHODS:
        tx, ty, stick_own = _comparison(creepage_longitudinal, creepage_lateral, spin,
                                        normal_load, a0, b0, youngs_modulus, poisson_ratio,
                                        friction_coefficient, method, method_options, law,
                                        speed)
        base = creep_solution_3d(creepage_longitudinal, creepage_lateral, spin, normal_load, a0,
                                 b0, youngs_modulus, poisson_ratio, friction_coefficient)
        stick = base.stick_area_fraction if stick_own is None else stick_own
        return base._replace(tx=tx, ty=ty, stick_area_fraction=stick)
    _no_options(method, method_options)
    if method == "exact_table":
        if fields:
            raise ValueError("fields needs method='exact' (the table holds no traction "
                             "fields); got method='exact_table'")
        return load_exact_table().creep_solution_3d(
            creepage_longitudinal, creepage_lateral, spin, normal_load, a0, b0, youngs_modulus,
            poisson_ratio, friction_coefficient, sensitivities=sensitivities)
    if method == "exact":
        return _exact_solution(creepage_longitudinal, creepage_lateral, spin, normal_load, a0,
                               b0, youngs_modulus, poisson_ratio, friction_coefficient, grid,
                               extrapolate, sensitivities, fields, tolerance, transport_order,
                               grid_shifts, law, speed)
    if sensitivities or fields:
        raise ValueError(f"sensitivities and fields need method='exact'; got method={method!r}")
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
# method="exact": Kalker's exact theory, discretised (railcontact.reference.rolling3d)
# --------------------------------------------------------------------------------------------
def exact_default_grid(a0, b0, spin_coordinate=np.inf):
    """The default grid of ``method="exact"``: ``(30, my)`` elements with ``my = 20`` for
    ``a0/b0 >= 1`` or spin coordinate ``|tau| <= 1`` and ``my = ceil(20 (b0/a0)^0.7)``, at
    most 48, for narrower contacts with more spin (the lateral element follows the ellipse:
    with 20 lateral elements a narrow contact with large spin errs by up to 1.4 % of mu N
    at a0/b0 < 0.2, the discrete solution depending on where the spin pole falls between
    element rows; measured in ``benchmarks/exact_table_accuracy.py --classes``).

    Parameters
    ----------
    a0, b0 : float
        Semi-axes, > 0. [m]
    spin_coordinate : float, optional
        tau = phi hypot(b0 C11, a0 C22) / w_sat, the exact table's spin coordinate
        (:func:`railcontact.exact_table.exact_table_coordinates`); default: large. [-]

    Returns
    -------
    (int, int)
        Elements (rolling, lateral). [-]
    """
    ratio = float(b0) / float(a0)
    my = EXACT_DEFAULT_GRID[1]
    if ratio > 1.0 and abs(spin_coordinate) > EXACT_DEFAULT_SPIN_MIN:
        my = min(EXACT_DEFAULT_LATERAL_MAX,
                 max(my, int(np.ceil(my * ratio ** EXACT_DEFAULT_LATERAL_EXPONENT - 1e-9))))
    return EXACT_DEFAULT_GRID[0], my


def _spin_coordinate(phi, n_load, a0, b0, e_mod, nu, mu):
    """The exact table's spin coordinate tau = phi hypot(b0 C11, a0 C22) / w_sat, w_sat =
    pi^2 (1 + nu) mu p0 / E, of one case (floats; 0 without spin). [-]"""
    if phi == 0.0:
        return 0.0
    c11, c22, _ = kalker_coefficients(a0 / b0, nu)
    p0 = 1.5 * n_load / (np.pi * a0 * b0)
    with np.errstate(over="ignore", divide="ignore"):
        w_sat = np.pi**2 * (1.0 + nu) * mu * p0 / e_mod
        tau = abs(phi) * math.hypot(b0 * float(c11), a0 * float(c22)) / w_sat
    return float(tau) if np.isfinite(tau) else np.inf


def _check_exact_grid(grid):
    try:
        mx, my = (int(v) for v in grid)
        ok = all(float(v) == int(v) for v in grid)
    except (TypeError, ValueError):
        ok = False
    if not ok or not (4 <= mx <= 1024 and 4 <= my <= 1024):
        raise ValueError(f"grid must be a pair (mx, my) of integers in [4, 1024] [-] (elements "
                         f"in rolling and lateral direction); got {grid!r}")
    return mx, my


def _reference_law(law, creepage_scale, speed, mu0):
    """The friction law on the similar reference contact: ``s_r -> mu_r(s_r)``.

    Slips scale like creepages (``s_r = k s``, k = ``creepage_scale``) and the friction bound
    like ``mu / mu0`` (the reference contact's coefficient times ``mu(s) / mu(0)``); a law in
    the slip velocity is evaluated at ``s V``."""
    mu_ref = REFERENCE_CONTACT["friction_coefficient"]
    factor = (1.0 if speed is None else speed) / creepage_scale

    def mu_r(slip_r):
        slip = np.abs(np.asarray(slip_r, dtype=float)) * factor
        mu = np.broadcast_to(np.asarray(law(slip), dtype=float), slip.shape)
        if not np.all(np.isfinite(mu) & (mu >= 0.0)):
            i = np.flatnonzero(~(np.isfinite(mu) & (mu >= 0.0)))[0]
            v = np.broadcast_to(1.0 if speed is None else speed, slip.shape).flat[i]
            raise ValueError(f"friction_coefficient {law!r} must give a finite mu >= 0 at "
                             f"every slip [-]; got {mu.flat[i]:g} at slip "
                             f"{slip.flat[i] / v:g}")
        return mu_ref * mu / mu0
    return mu_r


def _solve_case(case, *args, **kw):
    """``solve_rolling_3d`` on the similar contact; a convergence failure names the user's
    case (not only the similar one)."""
    from .reference.rolling3d import solve_rolling_3d  # noqa: PLC0415

    try:
        return solve_rolling_3d(*args, **kw)
    except RollingConvergenceError as exc:
        note = ""
        if callable(args[8]):   # a law: its steepness on the similar contact
            from .reference.halfspace2d import falling_friction_steepness  # noqa: PLC0415
            p0 = 1.5 * args[3] / (np.pi * args[4] * args[5])
            steep = falling_friction_steepness(args[8], p0, args[6], args[7], slip_max=1.0)
            note = (f" (the law's steepness number (3/2) ln 3 K p0 max|mu'| is {steep:.3g}; "
                    f"above about 1 a falling law can make the discrete problem non-unique, "
                    f"see railcontact.reference.halfspace2d.falling_friction_steepness)")
        raise RollingConvergenceError(f"method='exact' did not converge for the case {case}: "
                                      f"{exc}{note}") from None


def _exact(creepage_longitudinal, creepage_lateral, spin, normal_load, a0, b0, youngs_modulus,
           poisson_ratio, friction_coefficient, grid, extrapolate, sensitivities, fields,
           tolerance, transport_order=EXACT_DEFAULT_TRANSPORT_ORDER, grid_shifts=1, law=None,
           speed=None):
    """Loop of the exact solver over broadcast inputs; see :func:`creep_solution_3d`.
    ``law``: a friction law mu(s) (then ``friction_coefficient`` is its mu(0)), with ``speed``
    (V, broadcast) for a law in the slip velocity."""

    xi_x, xi_y, phi, n_load, a0, b0, e_mod, nu, mu = check_creep_inputs(
        creepage_longitudinal, creepage_lateral, spin, normal_load, a0, b0, youngs_modulus,
        poisson_ratio, friction_coefficient, creepage_bound=1.0)
    mx, my = (0, 0) if grid is None else _check_exact_grid(grid)
    if isinstance(grid_shifts, bool) or grid_shifts not in (1, 2, 3, 4):
        raise ValueError(f"grid_shifts must be an integer in [1, 4] [-] (grids averaged, "
                         f"shifted by 1/grid_shifts of an element); got {grid_shifts!r}")
    # element fractions by which the grids are moved in the rolling direction: -1/4, 1/4 for 2
    shifts = [(k + 0.5) / int(grid_shifts) - 0.5 for k in range(int(grid_shifts))]
    tolerance = float(check_range("tolerance", tolerance, "-", 0.0, 0.1, lower_closed=False))
    if transport_order not in (1, 2) or isinstance(transport_order, bool):
        raise ValueError(f"transport_order must be 1 or 2 [-] (first- or second-order upwind "
                         f"difference of the rolling term); got {transport_order!r}")
    sim = _similar_reference(xi_x, xi_y, phi, n_load, a0, b0, e_mod, nu, mu, "exact")
    args = np.broadcast_arrays(xi_x, xi_y, phi, n_load, a0, b0, e_mod, nu, mu)
    shape = args[0].shape
    speeds = None if speed is None else np.broadcast_to(speed, np.broadcast_shapes(
        shape, np.shape(speed)))
    if speeds is not None and speeds.shape != shape:
        raise ValueError(f"rolling_speed must broadcast with the other inputs (shape {shape}); "
                         f"got shape {np.shape(speed)}")
    tx, ty, mz = np.zeros(shape), np.zeros(shape), np.zeros(shape)
    stick, width = np.ones(shape), np.ones(shape)
    iters = np.zeros(shape, dtype=int)
    sens = np.zeros(shape + (3, 3)) if sensitivities else None
    res = np.empty(shape, dtype=object) if fields else None
    for idx in np.ndindex(shape):
        x_, y_, p_, n_, a_, b_, e_, v_, m_ = (float(arr[idx]) for arr in args)
        if n_ == 0.0 or m_ == 0.0 or a_ == 0.0 or b_ == 0.0:
            continue  # no contact or no friction: no force (as the other methods)
        similar = [float(v[idx]) for v in sim["args"]]   # the case on REFERENCE_CONTACT
        if grid is None:   # the default: the lateral elements follow a0/b0 (with spin)
            mx, my = exact_default_grid(a_, b_, _spin_coordinate(p_, n_, a_, b_, e_, v_, m_))
        case = (f"creepage_longitudinal={x_:g}, creepage_lateral={y_:g}, spin={p_:g}, "
                f"normal_load={n_:g}, a0={a_:g}, b0={b_:g}, youngs_modulus={e_:g}, "
                f"poisson_ratio={v_:g}, friction_coefficient="
                + (f"{m_:g}" if law is None else f"{law!r}")
                + ("" if speeds is None else f", rolling_speed={float(speeds[idx]):g}"))
        if law is not None:
            similar[8] = _reference_law(law, float(sim["creepage_scale"][idx]),
                                        None if speeds is None else float(speeds[idx]), m_)
        kw = dict(tolerance=tolerance, sensitivities=sensitivities,
                  transport_order=int(transport_order))
        total = [0.0, 0.0, 0.0]
        sens_sum = 0.0
        iters[idx] = 0
        one = fine = None
        w_c, w_f = (-1.0, 2.0) if extrapolate else (0.0, 1.0)
        for shift in shifts:  # grids moved along x, their forces averaged (grid_shifts)
            # the first grid starts from a half-size solve, a shifted one from the last grid
            one = _solve_case(case, *similar, mx=mx, my=my, coarse_start=one is None,
                              initial_guess=one, grid_shift=shift, **kw)
            fine = one
            if extrapolate:  # one Richardson step in the rolling-direction element size
                fine = _solve_case(case, *similar, mx=2 * mx, my=my, grid_shift=shift,
                                   initial_guess=one, **kw)  # prolongated coarse start
                iters[idx] += fine.iterations
            iters[idx] += one.iterations
            for k, name in enumerate(("tx", "ty", "mz")):
                total[k] += (w_f * getattr(fine, name) + w_c * getattr(one, name)) / len(shifts)
            if sensitivities:
                sens_sum = sens_sum + (w_f * fine.sensitivity
                                       + w_c * one.sensitivity) / len(shifts)
        if not all(np.isfinite(total)):
            raise RollingConvergenceError(f"method='exact' gave a non-finite force for the "
                                          f"case {case}")
        force, moment = sim["force_scale"][idx], sim["moment_scale"][idx]
        tx[idx] = total[0] * force
        ty[idx] = total[1] * force
        mz[idx] = total[2] * moment
        if sensitivities:
            rows = np.array([force, force, moment])[:, None]
            cols = np.array([sim["creepage_scale"][idx], sim["creepage_scale"][idx],
                             sim["spin_scale"][idx]])[None, :]
            with np.errstate(over="ignore", invalid="ignore"):
                sens[idx] = sens_sum * rows * cols
            if not np.all(np.isfinite(sens[idx])):
                raise ValueError("normal_load, a0, b0, youngs_modulus and "
                                 "friction_coefficient must give creep-force sensitivities "
                                 "within the float range [N, N m per unit creepage]; got "
                                 f"N = {n_:g}, a0 = {a_:g}, b0 = {b_:g}, E = {e_:g}, "
                                 f"mu = {m_:g}")
        a_ref, b_ref = similar[4], similar[5]
        dx = fine.x[1] - fine.x[0]
        dy = fine.y[1] - fine.y[0]
        stick[idx] = fine.adhesion.sum() * dx * dy / (np.pi * a_ref * b_ref)
        rows_ = np.nonzero(fine.adhesion.any(axis=0))[0]
        width[idx] = (rows_[-1] - rows_[0] + 1) * dy / (2.0 * b_ref) if rows_.size else 0.0
        if fields:
            res[idx] = fine
    return (tx, ty, mz, stick, width, sens, res, iters,
            (xi_x, xi_y, phi, n_load, a0, b0, e_mod, nu, mu))


def _exact_force(creepage_longitudinal, creepage_lateral, spin, normal_load, a0, b0,
                 youngs_modulus, poisson_ratio, friction_coefficient, grid, extrapolate,
                 tolerance, transport_order, grid_shifts=1, law=None, speed=None):
    out = _exact(creepage_longitudinal, creepage_lateral, spin, normal_load, a0, b0,
                 youngs_modulus, poisson_ratio, friction_coefficient, grid, extrapolate, False,
                 False, tolerance, transport_order, grid_shifts, law, speed)
    return CreepForce3D(out[0][()], out[1][()])


def _exact_solution(creepage_longitudinal, creepage_lateral, spin, normal_load, a0, b0,
                    youngs_modulus, poisson_ratio, friction_coefficient, grid, extrapolate,
                    sensitivities, fields, tolerance, transport_order, grid_shifts=1,
                    law=None, speed=None):
    tx, ty, mz, stick, width, sens, res, iters, checked = _exact(
        creepage_longitudinal, creepage_lateral, spin, normal_load, a0, b0, youngs_modulus,
        poisson_ratio, friction_coefficient, grid, extrapolate, sensitivities, fields,
        tolerance, transport_order, grid_shifts, law, speed)
    xi_x, xi_y, phi, n_load, a0, b0, e_mod, nu, mu = checked
    z = np.broadcast_to(normalised_creepage_3d(xi_x, xi_y, phi, n_load, a0, b0, e_mod, nu, mu),
                        tx.shape)
    phi_coef = np.broadcast_to(spin_coefficient(xi_x, xi_y, phi, a0, b0), tx.shape)
    return ExactCreepSolution3D(
        tx[()], ty[()], stick[()], width[()], np.asarray(z)[()], np.asarray(phi_coef)[()],
        np.ones(tx.shape, dtype=bool)[()], mz[()], sens, res[()] if fields else None,
        iters[()])


_EXACT_TABLES = {}


_DEFAULT_KEY = (None, None)


def load_exact_table(path=None, directory=None):
    """The exact-theory table with the solver attached beyond its axes.

    :class:`railcontact.exact_table.ExactCreepTable` of ``creep_exact.nc`` (default: the
    shipped file, :func:`railcontact.tables.default_table_path`), loaded once per content
    and process (each FMU extraction's copy of the file gets the same table), its
    coefficients mapped from the user cache (:mod:`railcontact._table_store`). Beyond its a0/b0 range or spin axis it answers with
    ``creep_solution_3d(..., method="exact", tolerance=1e-4)`` (30x20 -> 60x20 on two shifted
    grids; 30x36 -> 60x36 where a0/b0 < 0.87, 30x48 -> 60x48 where a0/b0 < 0.115), the setting the table was built with, so
    every finite input gets the exact theory.

    Parameters
    ----------
    path : str or path-like, optional
        The table file.
    directory : str or path-like, optional
        Directory searched first for ``creep_exact.nc``.

    Returns
    -------
    railcontact.exact_table.ExactCreepTable
    """
    from ._table_store import content_key  # noqa: PLC0415
    from .exact_table import TABLE_NAME, ExactCreepTable  # noqa: PLC0415
    from .tables import default_table_path  # noqa: PLC0415

    if path is None and directory is None:
        # the shipped table, looked up directly by creep_force_3d's fast path
        table = _EXACT_TABLES.get(_DEFAULT_KEY)
        if table is not None:
            return table
    file = default_table_path(TABLE_NAME, directory) if path is None else Path(path)
    # keyed by content: every FMU extraction (another path, the same file) shares one table
    key = content_key(file) if file.is_file() else None
    table = _EXACT_TABLES.get(key)
    if table is None:
        table = ExactCreepTable.from_file(file, solver=_exact_table_solver)
        if key is not None:
            _EXACT_TABLES[key] = table
    if path is None and directory is None:
        _EXACT_TABLES[_DEFAULT_KEY] = table
    return table


def _exact_table_solver(*args, sensitivities=False):
    """The exact solver at the table's setting (the table's answer beyond its axes): 48
    lateral elements where a0/b0 < 0.115, 36 where a0/b0 < 0.87 (``EXACT_TABLE_*`` of
    :mod:`railcontact.creep_common`; beyond the table such a contact has a0/b0 < 0.1 or
    |tau| > 20, which the table's rule gives the same), else 20. Returns the fields the table reads (tx, ty, spin_moment,
    stick_area_fraction, normalised_creepage, sensitivity)."""
    args = np.broadcast_arrays(*(np.asarray(a, dtype=float) for a in args))
    narrow = args[4] < EXACT_TABLE_NARROW_ASPECT_MAX * args[5]
    very = args[4] < EXACT_TABLE_VERY_NARROW_ASPECT_MAX * args[5]
    out = None
    for mask, my in ((~narrow, EXACT_DEFAULT_GRID[1]),
                     (narrow & ~very, EXACT_TABLE_LATERAL_ELEMENTS_NARROW),
                     (very, EXACT_TABLE_LATERAL_ELEMENTS_VERY_NARROW)):
        if not np.any(mask):
            continue
        sol = creep_solution_3d(*(a[mask] for a in args), method="exact", grid=(30, my),
                                extrapolate=True, grid_shifts=2, tolerance=1e-4,
                                sensitivities=sensitivities)
        if out is None:
            out = {k: np.zeros(narrow.shape) for k in (
                "tx", "ty", "spin_moment", "stick_area_fraction", "normalised_creepage")}
            out["sensitivity"] = np.zeros(narrow.shape + (3, 3)) if sensitivities else None
        for k in out:
            if out[k] is not None:
                out[k][mask] = getattr(sol, k)
    return SimpleNamespace(**out)
