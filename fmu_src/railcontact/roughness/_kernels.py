"""Compiled kernels of the rough-rail contact (Nielsen 1998, Ch. 6): one implementation.

Internal module. The modules of :mod:`railcontact.roughness` check the inputs in Python and
call these kernels; the FMU's Roughness effect calls the same kernels once per step through
:class:`railcontact.roughness.RoughRailSolver` (the pattern of pvlib's ``spa.py``, one source
for both speeds, and of scipy's ``_ndbspline``, validation in Python and evaluation in one
compiled kernel). The kernels assume checked inputs and report failures by a status code
(the constants below); the Python callers turn a code into the documented ``ValueError``.

Contents: the rail surface (harmonics, Eq. (4.1), or a quintic spline) and its first four
derivatives; the local 4th-order gap about the gap minimum; the single-asperity normal
problem, every case of Table 6.1 ((6.9)-(6.10), with the module errata of
:mod:`railcontact.roughness`); its tangential problem ((6.38)-(6.40), mirrored to the package
convention); Brent's root finder; and the whole step of a wheel on a rough rail.

Surfaces are passed as ``(kind, nodes, coefficients, params)``: for harmonics
(``kind = HARMONIC``) ``nodes`` are the wave numbers ``k_m`` and ``coefficients[0/1, n, m]``
the real and imaginary parts of ``(i k_m)^n (Z_A,m - i Z_B,m)``; for a spline profile
(``kind = PERIODIC_PROFILE`` or ``HELD_PROFILE``) ``nodes`` are the break points and
``coefficients[n, j, i]`` the local power coefficients (highest power first, padded with
leading zeros) of ``r^(n)`` on piece ``i``; ``params = (start, period)``.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from .. import _numba_cache  # noqa: F401  (numba's cache in a user cache directory)

HARMONIC, PERIODIC_PROFILE, HELD_PROFILE = 0, 1, 2

#: Stick ratios a*/a scanned (from full stick down) for the first sign change of a residual.
SCAN_GRID = np.linspace(1.0, 0.0, 65)
#: Nodes s = cos(theta) at which the normalised pressure polynomial must be >= 0.
PRESSURE_NODES = np.cos(np.linspace(0.0, np.pi, 201))[1:-1]

# asperity_normal: the case of Table 6.1 used (>= 0) or why there is no solution (< 0)
CASE_HERTZ, CASE_A, CASE_B_FLAT, CASE_B, CASE_DOUBLE_WELL, CASE_NUMERICAL = 0, 1, 2, 3, 4, 5
NOT_CONVEX = -1            # l2 = 0 with l3 != 0 or l4 = 0 (or l2 < 0)
FLATNESS_NOT_POSITIVE = -2  # l2 = l3 = 0 and l4 <= 0
LOAD_TOO_LARGE_A = -3      # (27/16) N~^2 l3^4 / l2^6 >= 1
LOAD_TOO_LARGE_B = -4      # l4 N~ / (2 l2^2) <= -1
NEGATIVE_PRESSURE_B = -5   # case (B), l4 < 0: negative pressure
NEGATIVE_PRESSURE_DOUBLE_WELL = -6
NO_BRACKET = -7            # numerical case: no coherent single-patch solution found
NEGATIVE_PRESSURE = -8     # numerical case: negative pressure
NO_ROOT = -9               # Brent's method failed (sign, NaN or iteration limit)

# local_gap / rough_rail_contact
GAP_NOT_CONVERGED = -10
SERIES_NEEDED = 1          # 0 < |creepage| < 1e-4 critical: the Ch. 3 full-stick series

# residuals of brent()
_NORMAL_LOAD, _CREEPAGE, _FORCE = 0, 1, 2

# division by zero gives inf/NaN as in C and numpy (Brent's interpolation relies on it)
_jit = njit(cache=True, error_model="numpy")


@_jit
def surface_derivatives(kind, nodes, coefficients, params, x):
    """``(r, r', r'', r''', r'''')`` of the rail surface at rail position ``x``.
    [m, -, 1/m, 1/m^2, 1/m^3]"""
    r0 = r1 = r2 = r3 = r4 = 0.0
    if kind == HARMONIC:
        for m in range(nodes.size):
            t = nodes[m] * x
            c, s = math.cos(t), math.sin(t)
            r0 += coefficients[0, 0, m] * c - coefficients[1, 0, m] * s
            r1 += coefficients[0, 1, m] * c - coefficients[1, 1, m] * s
            r2 += coefficients[0, 2, m] * c - coefficients[1, 2, m] * s
            r3 += coefficients[0, 3, m] * c - coefficients[1, 3, m] * s
            r4 += coefficients[0, 4, m] * c - coefficients[1, 4, m] * s
        return r0, r1, r2, r3, r4
    start, period = params[0], params[1]
    if kind == PERIODIC_PROFILE:
        xe = start + (x - start) % period
    else:
        xe = min(max(x, start), start + period)
    pieces = coefficients.shape[2]
    i = min(max(np.searchsorted(nodes, xe, side="right") - 1, 0), pieces - 1)
    t = xe - nodes[i]
    out = np.empty(5)
    for n in range(5):
        v = coefficients[n, 0, i]
        for j in range(1, coefficients.shape[1]):
            v = v * t + coefficients[n, j, i]
        out[n] = v
    if kind == HELD_PROFILE and xe != x:      # a flat rail outside the held profile
        return out[0], 0.0, 0.0, 0.0, 0.0
    return out[0], out[1], out[2], out[3], out[4]


@_jit
def surface_derivatives_array(kind, nodes, coefficients, params, x):
    """:func:`surface_derivatives` at every element of the 1-D array ``x``: shape (5, n)."""
    out = np.empty((5, x.size))
    for j in range(x.size):
        out[0, j], out[1, j], out[2, j], out[3, j], out[4, j] = surface_derivatives(
            kind, nodes, coefficients, params, x[j])
    return out


@_jit
def local_gap(kind, nodes, coefficients, params, x_axis, big_r, bound, max_iter):
    """Gap minimum and 4th-order gap there: ``(x_c, l2, l3, l4, r, converged)``.

    ``h'(x) = x/R - r'(X + x) = 0`` by Newton's method safeguarded by bisection inside
    ``|x| <= bound (1 + 1e-9)``, ``bound = R max|r'|``; then ``l2 = 1/R - r''``,
    ``l3 = -r'''``, ``l4 = -r''''`` and the rail height ``r`` at ``X + x_c``."""
    x = 0.0
    converged = True
    if bound > 0.0:
        converged = False
        lo, hi = -bound * (1.0 + 1e-9), bound * (1.0 + 1e-9)
        tol = 1e-14 * bound
        for _ in range(max_iter):
            d = surface_derivatives(kind, nodes, coefficients, params, x_axis + x)
            g1 = x / big_r - d[1]
            if g1 == 0.0:
                converged = True
                break
            if g1 < 0.0:
                lo = x
            else:
                hi = x
            new = x - g1 / (1.0 / big_r - d[2])
            if not (lo < new < hi):
                new = 0.5 * (lo + hi)
            done = abs(new - x) <= tol
            x = new
            if done:
                converged = True
                break
    d = surface_derivatives(kind, nodes, coefficients, params, x_axis + x)
    return x, 1.0 / big_r - d[2], -d[3], -d[4], d[0], converged


@_jit
def local_gap_array(kind, nodes, coefficients, params, x_axis, big_r, bound, max_iter):
    """:func:`local_gap` at every element of the 1-D array ``x_axis``: shape (5, n) of
    ``x_c, l2, l3, l4, r`` and whether every element converged."""
    out = np.empty((5, x_axis.size))
    ok = True
    for j in range(x_axis.size):
        xc, l2, l3, l4, r, converged = local_gap(kind, nodes, coefficients, params, x_axis[j],
                                                 big_r, bound, max_iter)
        out[0, j], out[1, j], out[2, j], out[3, j], out[4, j] = xc, l2, l3, l4, r
        ok = ok and converged
    return out, ok


@_jit
def _residual(which, x, p):
    if which == _NORMAL_LOAD:
        # N~(Delta)/N~ - 1 at Delta = scale x ((6.9) solved for a^2, then (6.10)); scaled so
        # that tiny loads do not underflow in Brent's interpolation
        scale, l2, l3, l4, nt = p[0], p[1], p[2], p[3], p[4]
        d = scale * x
        a2 = -4.0 * d * (l2 + 0.5 * l3 * d + l4 * d * d / 6.0) / (l3 + l4 * d)
        return ((l2 + l3 * d + 0.5 * l4 * d * d) * a2 + l4 * a2 * a2 / 8.0 - nt) / nt
    xi, force = tangential_state(p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7], x)
    if which == _CREEPAGE:
        return -xi - p[8]
    return force - p[8]


@_jit
def brent(which, p, xa, xb, xtol, rtol, maxiter):
    """Root of residual ``which`` (parameters ``p``) in ``[xa, xb]`` by Brent's method:
    ``(root, ok)``.

    R.P. Brent, Algorithms for Minimization without Derivatives, 1973, Ch. 4, in the form of
    scipy's ``brentq`` (inverse quadratic interpolation, bisection, the same tolerances
    ``xtol + rtol |x|``); ``ok`` is False for no sign change, a NaN or no convergence."""
    xpre, xcur = xa, xb
    xblk = fblk = spre = scur = 0.0
    fpre = _residual(which, xpre, p)
    fcur = _residual(which, xcur, p)
    if fpre != fpre or fcur != fcur:
        return xcur, False
    if fpre == 0.0:
        return xpre, True
    if fcur == 0.0:
        return xcur, True
    if math.copysign(1.0, fpre) == math.copysign(1.0, fcur):
        return xcur, False
    for _ in range(maxiter):
        if fpre != 0.0 and fcur != 0.0 and math.copysign(1.0, fpre) != math.copysign(1.0, fcur):
            xblk = xpre
            fblk = fpre
            spre = scur = xcur - xpre
        if abs(fblk) < abs(fcur):
            xpre, xcur, xblk = xcur, xblk, xcur
            fpre, fcur, fblk = fcur, fblk, fcur
        delta = (xtol + rtol * abs(xcur)) / 2.0
        sbis = (xblk - xcur) / 2.0
        if fcur == 0.0 or abs(sbis) < delta:
            return xcur, True
        if abs(spre) > delta and abs(fcur) < abs(fpre):
            if xpre == xblk:        # secant
                stry = -fcur * (xcur - xpre) / (fcur - fpre)
            else:                   # inverse quadratic interpolation
                dpre = (fpre - fcur) / (xpre - xcur)
                dblk = (fblk - fcur) / (xblk - xcur)
                stry = -fcur * (fblk * dblk - fpre * dpre) / (dblk * dpre * (fblk - fpre))
            if 2.0 * abs(stry) < min(abs(spre), 3.0 * abs(sbis) - delta):
                spre = scur
                scur = stry
            else:                   # bisection
                spre = sbis
                scur = sbis
        else:
            spre = sbis
            scur = sbis
        xpre = xcur
        fpre = fcur
        if abs(scur) > delta:
            xcur += scur
        else:
            xcur += delta if sbis > 0.0 else -delta
        fcur = _residual(which, xcur, p)
        if fcur != fcur:
            return xcur, False
    return xcur, False


@_jit
def pressure_nonnegative(a, d, l2, l3, l4, kfac):
    """Whether the asperity pressure of the contact ``(a, Delta)`` is >= 0 across the patch:
    ``sum b_n s^n >= -1e-9 max|.|`` at :data:`PRESSURE_NODES`, ``b_n = B_n a^n / K`` with the
    ``B_n`` of (6.4)-(6.8)."""
    curv = l2 + l3 * d + 0.5 * l4 * d * d            # Z''(Delta)
    odd = d * (l2 + 0.5 * l3 * d + l4 * d * d / 6.0)  # Z'(Delta)
    skew = l3 + l4 * d                                # Z'''(Delta)
    b0 = a * a / np.pi * (curv + l4 * a * a / 12.0) / kfac
    b1 = (0.25 * a * a * skew - odd) / np.pi / kfac * a
    b2 = (l4 * a * a / 12.0 - curv) / np.pi / kfac * (a * a)
    b3 = -skew / (2.0 * np.pi) / kfac * (a * a * a)
    b4 = -l4 / (6.0 * np.pi) / kfac * (a * a * a * a)
    low, top = math.inf, 0.0
    for s in PRESSURE_NODES:
        v = (((b4 * s + b3) * s + b2) * s + b1) * s + b0
        low = min(low, v)
        top = max(top, abs(v))
    return low >= -1e-9 * top


@_jit
def asperity_normal(nt, l2, l3, l4, kfac):
    """Half-width and shift of one asperity, (6.9)-(6.10), Table 6.1: ``(a, Delta, case)``.

    ``nt = N~ > 0`` [m]; ``case`` is one of the ``CASE_*`` constants, or a negative code (no
    coherent single patch; ``a`` and ``Delta`` are then NaN)."""
    nan = math.nan
    if not l2 >= 0.0 or (l2 == 0.0 and not (l3 == 0.0 and l4 != 0.0)):
        return nan, nan, NOT_CONVEX
    if l4 == 0.0 and l3 == 0.0:
        return math.sqrt(nt / l2), 0.0, CASE_HERTZ
    if l4 == 0.0:
        x = nt * nt * l3**4 / l2**6
        if not 27.0 / 16.0 * x < 1.0:
            return nan, nan, LOAD_TOO_LARGE_A
        theta = math.acos(27.0 / 8.0 * x - 1.0) / 3.0
        # erratum: Table 6.1(A) prints a = ((2/3)(l2/l3)(2 cos(Theta) - 1))^(1/2): l2/l3 must
        # be squared and the bracket is 1 + 2 cos(Theta + pi/3) (the printed one is minus the
        # negative root of the cubic); verified in tests/test_roughness.py.
        a2 = 2.0 / 3.0 * (l2 / l3) ** 2 * (1.0 + 2.0 * math.cos(theta + np.pi / 3.0))
        return math.sqrt(a2), (nt / a2 - l2) / l3, CASE_A
    if l3 == 0.0 and l2 == 0.0:
        if not l4 > 0.0:
            return nan, nan, FLATNESS_NOT_POSITIVE
        return (8.0 * nt / l4) ** 0.25, 0.0, CASE_B_FLAT
    if l3 == 0.0:
        arg = 0.5 * l4 * nt / l2**2
        if not arg > -1.0:
            return nan, nan, LOAD_TOO_LARGE_B
        # 4 (l2/l4)(sqrt(1 + arg) - 1) written without cancellation for small arg
        a2 = 4.0 * (l2 / l4) * arg / (math.sqrt(1.0 + arg) + 1.0)
        a = math.sqrt(a2)
        if l4 < 0.0 and not pressure_nonnegative(a, 0.0, l2, l3, l4, kfac):
            return nan, nan, NEGATIVE_PRESSURE_B
        return a, 0.0, CASE_B
    if abs(l2 - l3 * l3 / (3.0 * l4)) <= 1e-12 * abs(l2):
        # erratum: Table 6.1(B) prints (sqrt(1 + 2 l4 N~/l2^2) - 1); with l4 > 0 (implied by
        # l2 = l3^2/(3 l4) > 0) that root is negative.
        a2 = 2.0 * (l2 / l4) * (math.sqrt(1.0 + 2.0 * l4 * nt / l2**2) + 1.0)
        a, d = math.sqrt(a2), -l3 / l4
        if not pressure_nonnegative(a, d, l2, l3, l4, kfac):
            return nan, nan, NEGATIVE_PRESSURE_DOUBLE_WELL
        return a, d, CASE_DOUBLE_WELL

    # general case: a^2(Delta) from (6.9), then N~(Delta) = target, bracketed from Delta = 0
    # (continuation from zero load). First step: a tenth of the smaller of the Hertz half-width
    # and the small-load shift |Delta| ~ N~ |l3| / (4 l2^2) (so that the bracket is found, and
    # Brent converges, for any load down to N~ ~ 1e-300 m, where Delta << a).
    direction = -1.0 if l3 > 0.0 else 1.0
    step = 0.1 * min(math.sqrt(nt / l2), nt * abs(l3) / (4.0 * l2 * l2))
    # with l4 > 0, a^2(Delta) has a pole at Delta = -l3/l4 on the search side and the whole
    # load range lies before it (N~ -> inf there): approach it by halving the remaining
    # distance (needed when |l3| is small, e.g. a rail trough, where the pole is far closer
    # than step)
    c_pole = abs(l3) / l4 if l4 > 0.0 else math.inf
    lo = 0.0
    hi = -1.0
    for _ in range(200):
        cand = lo + step
        if cand >= c_pole:
            cand = lo + 0.5 * (c_pole - lo)
            if cand <= lo:
                break
        d = direction * cand
        denominator = l3 + l4 * d
        if denominator == 0.0 or (denominator > 0.0) != (l3 > 0.0):
            break
        a2 = -4.0 * d * (l2 + 0.5 * l3 * d + l4 * d * d / 6.0) / denominator
        if not a2 > 0.0:
            break
        if (l2 + l3 * d + 0.5 * l4 * d * d) * a2 + l4 * a2 * a2 / 8.0 - nt >= 0.0:
            hi = cand
            break
        lo, step = cand, step * 1.5
    if hi < 0.0:
        return nan, nan, NO_BRACKET
    # Brent in scaled variables (|Delta| / hi and N~ / target of order 1): with tiny loads the
    # products of residuals in its interpolation would otherwise underflow
    p = (direction * hi, l2, l3, l4, nt, 0.0, 0.0, 0.0, 0.0)
    u, ok = brent(_NORMAL_LOAD, p, lo / hi, 1.0, 1e-300, 1e-15, 100)
    if not ok:
        return nan, nan, NO_ROOT
    d = direction * (hi * u)
    a = math.sqrt(-4.0 * d * (l2 + 0.5 * l3 * d + l4 * d * d / 6.0) / (l3 + l4 * d))
    if not pressure_nonnegative(a, d, l2, l3, l4, kfac):
        return nan, nan, NEGATIVE_PRESSURE
    return a, d, CASE_NUMERICAL


@_jit
def tangential_state(a, d, load, l2, l3, l4, ref, mu, r):
    """Creepage and force at stick ratio ``r = a*/a``, (6.38)-(6.39) mirrored: ``(xi, T)``.

    Stick zone at the leading edge, centre ``Delta* = Delta + a - a*``;
    ``xi = -mu Z'*`` and ``T = mu (N - ref N~*)`` with ``ref = pi E / (8 (1 - nu^2))``."""
    a_s = r * a
    d_s = (d + a) - a_s
    a2 = a_s * a_s
    xi = -mu * (d_s * (l2 + 0.5 * l3 * d_s + l4 * d_s * d_s / 6.0) + 0.25 * a2 * (l3 + l4 * d_s))
    force = mu * (load - ref * ((l2 + l3 * d_s + 0.5 * l4 * d_s * d_s) * a2
                                + l4 * a2 * a2 / 8.0))
    return xi, force


@_jit
def tangential_state_array(a, d, load, l2, l3, l4, ref, mu, r):
    """:func:`tangential_state` at every element of the 1-D array ``r``."""
    xi = np.empty(r.size)
    force = np.empty(r.size)
    for j in range(r.size):
        xi[j], force[j] = tangential_state(a, d, load, l2, l3, l4, ref, mu, r[j])
    return xi, force


@_jit
def critical_creepage(a, d, l2, l3, l4, mu):
    """Full-slip creepage magnitude, (6.40) with its factor mu: ``mu Z'(Delta + a)``. [-]"""
    e = d + a
    return mu * e * (l2 + 0.5 * l3 * e + l4 * e * e / 6.0)


@_jit
def stick_ratio(a, d, load, l2, l3, l4, ref, mu, target, force_given):
    """Stick ratio at which the creepage magnitude (or the force, if ``force_given``) equals
    ``target > 0``: the largest root in [0, 1] (continuation from full stick: the first sign
    change scanning :data:`SCAN_GRID` from 1 down, then Brent), 0 if none: ``(r, ok)``."""
    which = _FORCE if force_given else _CREEPAGE
    p = (a, d, load, l2, l3, l4, ref, mu, target)
    prev = _residual(which, SCAN_GRID[0], p)
    if prev == 0.0:
        return 1.0, True
    for j in range(1, SCAN_GRID.size):
        v = _residual(which, SCAN_GRID[j], p)
        if np.sign(v) != np.sign(prev):
            return brent(which, p, SCAN_GRID[j], SCAN_GRID[j - 1], 1e-15, 1e-14, 100)
        prev = v
    return 0.0, True


@_jit
def asperity_tangential(a, d, load, l2, l3, l4, ref, mu, creepage, series_limit):
    """Steady rolling at a given creepage: ``(force, stick_ratio, critical_creepage, status)``.

    ``status`` is 0, :data:`SERIES_NEEDED` (0 < |xi| < series_limit xi_c: (6.38)-(6.39)
    cancel, the caller uses the full-stick series of Ch. 3) or :data:`NO_ROOT`."""
    critical = critical_creepage(a, d, l2, l3, l4, mu)
    target = abs(creepage)
    if mu > 0.0 and 0.0 < target < series_limit * critical:
        return math.nan, math.nan, critical, SERIES_NEEDED
    ok = True
    if target == 0.0 or mu == 0.0:
        r = 1.0
    elif target >= -tangential_state(a, d, load, l2, l3, l4, ref, mu, 0.0)[0]:
        r = 0.0
    else:
        r, ok = stick_ratio(a, d, load, l2, l3, l4, ref, mu, target, False)
    if not ok:
        return math.nan, math.nan, critical, NO_ROOT
    force = 0.0
    if target > 0.0:
        force = -np.sign(creepage) * tangential_state(a, d, load, l2, l3, l4, ref, mu, r)[1]
    return force, r, critical, 0


@_jit
def rough_rail_contact(kind, nodes, coefficients, params, x_axis, load, nt, big_r, bound,
                       kfac, ref, mu, creepage, series_limit):
    """One step of a wheel on a rough rail: :func:`local_gap`, :func:`asperity_normal`,
    :func:`asperity_tangential`. Returns ``(x_c, l2, l3, l4, a, Delta, force, stick_ratio,
    critical_creepage, status)``; ``status != 0`` where one of them fails or needs the
    series (the caller then takes the checked Python path)."""
    nan = math.nan
    xc, l2, l3, l4, _, converged = local_gap(kind, nodes, coefficients, params, x_axis, big_r,
                                             bound, 60)
    if not converged:
        return xc, l2, l3, l4, nan, nan, nan, nan, nan, GAP_NOT_CONVERGED
    a, d, case = asperity_normal(nt, l2, l3, l4, kfac)
    if case < 0:
        return xc, l2, l3, l4, a, d, nan, nan, nan, case
    force, r, critical, status = asperity_tangential(a, d, load, l2, l3, l4, ref, mu,
                                                     creepage, series_limit)
    return xc, l2, l3, l4, a, d, force, r, critical, status
