"""Compiled kernels of the corrugated contact and its wear (Nielsen 1998, Secs. 4.2-4.3).

Internal module. :func:`railcontact.corrugation.solve_normal_exact`,
:func:`~railcontact.corrugation.solve_stick_zone_exact` and
:func:`~railcontact.corrugation.corrugated_contact` check their inputs in Python and call these
kernels (one rail position per call of the scalar kernels, a loop over positions in the
``*_array`` ones); the FMU's corrugation effect calls the same kernels once per step. The
kernels assume checked inputs and report failures by a status code; the Python callers raise
the documented ``ValueError``. :func:`railcontact.wear.wear_coefficients` calls
:func:`wear_coefficients_array` (the linearised wear of the series models).

The Bessel functions J0, J1 and J_n are scipy's (``scipy.special.cython_special``: ``j0``,
``j1`` are the ufuncs' routines bit for bit, ``jv`` agrees with the ufunc to 2 ulp), linked
by symbol name so that numba's cache stays valid across processes. Division by zero gives
inf/NaN as in numpy (``error_model="numpy"``): a singular Newton step is detected as a
non-finite result.

Harmonics are passed as 1-D arrays ``k`` (wave numbers ``2 pi / L`` [1/m]), ``za``, ``zb``
(``Z_A``, ``Z_B`` of Eq. (4.1) [m]).
"""

from __future__ import annotations

import cmath
import math

import llvmlite.binding as _llvm
import numpy as np
from numba import njit, types
from numba.extending import get_cython_function_address
from scipy.special import jv as _scipy_jv

from . import _numba_cache  # noqa: F401  (numba's cache in a user cache directory)
from ._validation import check_range

# the C functions of cython_special: double j0(double, int skip_dispatch), the same for j1,
# and the real variant of the fused jv, double jv(double, double, int skip_dispatch)
for _name, _symbol in (("j0", "j0"), ("j1", "j1"), ("jv", "__pyx_fuse_1jv")):
    _llvm.add_symbol(f"railcontact_scipy_{_name}",
                     get_cython_function_address("scipy.special.cython_special", _symbol))
_j0 = types.ExternalFunction("railcontact_scipy_j0", types.float64(types.float64, types.intc))
_j1 = types.ExternalFunction("railcontact_scipy_j1", types.float64(types.float64, types.intc))
_jv = types.ExternalFunction("railcontact_scipy_jv",
                             types.float64(types.float64, types.float64, types.intc))

TWO_PI = 2.0 * np.pi

#: k delta below which the Taylor forms of the stick-zone differences are used (so that
#: neither delta nor T is the difference of two nearly equal O(1) numbers; xi -> 0 gives
#: delta = 0 and T = 0 exactly).
TAYLOR_LIMIT = 1e-4

OK, NOT_CONVERGED, NO_SINGLE_PATCH = 0, 1, 2

_jit = njit(cache=True, error_model="numpy")


@_jit
def j0(z):
    """J0(z), scipy's."""
    return _j0(z, 0)


@_jit
def j1(z):
    """J1(z), scipy's."""
    return _j1(z, 0)


@_jit
def jv(n, z):
    """J_n(z), scipy's (order ``n`` a float)."""
    return _jv(n, z, 0)


@_jit
def _j1_over_z(z):
    return j1(z) / z if z > 1e-8 else 0.5


@_jit
def _shift_for_half_width(x, a, big_r, k, za, zb, atol, max_iter, d):
    """Delta(a) from (4.31) at fixed half-width, bracketed.

    ``h(Delta) = Delta + R sum k J0(k a) S(X + Delta)`` satisfies ``h(-B) <= 0 <= h(B)`` with
    ``B = R sum k |J0(k a)| |Z|`` and ``h' = 1 + R sum k^2 J0(k a) Zc >= 1 - sum k^2 R |Z| > 0``
    under (4.2): one root, found by Newton safeguarded by bisection."""
    m = k.size
    jz = np.empty(m)
    bound = 0.0
    for i in range(m):
        jz[i] = j0(k[i] * a)
        bound += k[i] * abs(jz[i]) * math.hypot(za[i], zb[i])
    bound *= big_r
    lo, hi = -bound, bound
    d = min(max(d, lo), hi)
    for _ in range(max_iter):
        y = x + d
        h = dh = 0.0
        for i in range(m):
            sn, cs = math.sin(k[i] * y), math.cos(k[i] * y)
            h += k[i] * jz[i] * (za[i] * sn - zb[i] * cs)
            dh += k[i] * k[i] * jz[i] * (za[i] * cs + zb[i] * sn)
        h = d + big_r * h
        dh = 1.0 + big_r * dh
        if h <= 0.0:
            lo = d
        if h >= 0.0:
            hi = d
        new = d - h / dh
        if not (lo < new < hi):
            new = 0.5 * (lo + hi)
        done = abs(new - d) <= atol or hi - lo <= atol or h == 0.0
        if h != 0.0:
            d = new
        if done:
            break
    return d


@_jit
def _normal_terms(x, a, d, big_r, k, za, zb):
    """Residuals of (4.31), (4.33) (without ``- N C``) and their Jacobian in (Delta, a):
    ``(f1, f2, j11, j12, j21, j22)``, and ``(g1, g2)``, their derivatives in X."""
    y = x + d
    f1 = f2 = s11 = s12 = s21 = s22 = 0.0
    for i in range(k.size):
        ki = k[i]
        sn, cs = math.sin(ki * y), math.cos(ki * y)
        s, c = za[i] * sn - zb[i] * cs, za[i] * cs + zb[i] * sn
        ka = ki * a
        jz, jo = j0(ka), j1(ka)
        f1 += ki * jz * s
        f2 += ki * a * jo * c
        s11 += ki * ki * jz * c
        s12 += ki * ki * jo * s
        s21 += ki * ki * a * jo * s
        s22 += ki * ki * a * jz * c
    return (d + big_r * f1, a * a / (2 * big_r) + f2, 1.0 + big_r * s11, -big_r * s12, -s21,
            a / big_r + s22, big_r * s11, -s21)


@_jit
def _normal_bracketed(x, nc, big_r, k, za, zb, atol, max_iter):
    """(4.31), (4.33) as a bracketed 1-D problem in a (the globally convergent fallback):
    ``(a, Delta, converged)``.

    For each a, Delta(a) is the unique root of (4.31); then ``P(a) = a^2/(2R) + sum k a J1(k a)
    Zc(X + Delta(a)) - N C`` has ``P(0) < 0 < P(a_hi)`` for ``a_hi = R s + sqrt((R s)^2 +
    2 R N C)``, ``s = 0.582 sum k |Z|`` (``max |J1| = 0.5819``); Newton on ``P`` with
    ``dP/da = det / j11`` (total derivative), safeguarded by bisection."""
    s_j1 = 0.0
    for i in range(k.size):
        s_j1 += k[i] * math.hypot(za[i], zb[i])
    s_j1 *= 0.582
    lo = 0.0
    hi = big_r * s_j1 + math.sqrt((big_r * s_j1) ** 2 + 2.0 * big_r * nc)
    a = min(math.sqrt(2.0 * big_r * nc), 0.5 * hi)
    d = 0.0
    converged = False
    for _ in range(max_iter):
        d = _shift_for_half_width(x, a, big_r, k, za, zb, atol, max_iter, d)
        _, f2, j11, j12, j21, j22, _, _ = _normal_terms(x, a, d, big_r, k, za, zb)
        p = f2 - nc
        if p <= 0.0:
            lo = a
        if p >= 0.0:
            hi = a
        new = a - p * j11 / (j11 * j22 - j12 * j21)
        if not (lo < new < hi):
            new = 0.5 * (lo + hi)
        done = abs(new - a) <= atol or hi - lo <= atol or p == 0.0
        if p != 0.0:
            a = new
        if done:
            converged = True
            break
    d = _shift_for_half_width(x, a, big_r, k, za, zb, atol, max_iter, d)
    return a, d, converged


@_jit
def solve_normal(x, nc, big_r, k, za, zb, a_start, tol, max_iter):
    """(4.31) and (4.33) at one rail position: ``(a, Delta, da/dX, dDelta/dX, status)``.

    Newton from ``(a_start, 0)``; the equations are even in ``a``, so a root with ``a < 0`` is
    the mirror of the physical one and is returned as ``|a|``. Where Newton does not converge
    in ``max_iter`` steps (or is not finite), the bracketed reduction re-solves it (status
    :data:`NOT_CONVERGED` if that fails too); :data:`NO_SINGLE_PATCH` if the root fails the
    single-patch check (``a > 0``, ``det > 0``, ``j11 > 0``)."""
    a0 = math.sqrt(2.0 * big_r * nc)
    # steps are compared with tol * (a0 + R sum k |Z|): the residual of (4.31) is a sum of
    # terms of size |Delta| <= R sum k |Z| (see solve_normal_exact)
    spread = 0.0
    for i in range(k.size):
        spread += k[i] * math.hypot(za[i], zb[i])
    atol = tol * (a0 + big_r * spread)
    a, d = a_start, 0.0
    step = math.inf
    for _ in range(max_iter):
        f1, f2, j11, j12, j21, j22, _, _ = _normal_terms(x, a, d, big_r, k, za, zb)
        f2 -= nc
        det = j11 * j22 - j12 * j21
        dd = (f1 * j22 - f2 * j12) / det
        da = (j11 * f2 - j21 * f1) / det
        d = d - dd
        a = a - da
        step = abs(dd) + abs(da)
        if step < atol:
            break
    a = abs(a)
    if not (step < atol and math.isfinite(a) and math.isfinite(d)):
        a, d, converged = _normal_bracketed(x, nc, big_r, k, za, zb, atol,
                                            max(4 * max_iter, 200))
        if not converged:
            return a, d, math.nan, math.nan, NOT_CONVERGED
    _, _, j11, j12, j21, j22, g1, g2 = _normal_terms(x, a, d, big_r, k, za, zb)
    det = j11 * j22 - j12 * j21
    if not (a > 0.0 and det > 0.0 and j11 > 0.0):
        return a, d, math.nan, math.nan, NO_SINGLE_PATCH
    return a, d, -(j11 * g2 - j21 * g1) / det, -(g1 * j22 - g2 * j12) / det, OK


@_jit
def stick_offset(x, a, d, xi, big_r, k, za, zb, tol, max_iter):
    """``delta = a - a*`` from ``delta/R + [G(delta) - G(0)] = xi/mu``, delta in [0, a]
    (the creepage condition, mirrored (4.57), minus the normal condition (4.31));
    ``G(delta) = sum k J0(k (a - delta)) S(X + Delta + delta)``; ``xi`` is ``|xi| / mu``."""
    m = k.size
    y = x + d
    g1 = g2 = 0.0
    jzs0 = np.empty(m)            # J0(k a) S(y) per harmonic, G(0)'s terms
    for i in range(m):
        ki = k[i]
        sn, cs = math.sin(ki * y), math.cos(ki * y)
        s0, c0 = za[i] * sn - zb[i] * cs, za[i] * cs + zb[i] * sn
        z = ki * a
        jz, jo = j0(z), j1(z)
        jzs0[i] = jz * s0
        g1 += ki * ki * (jo * s0 + jz * c0)
        g2 += ki ** 3 * (-(2 * jz - _j1_over_z(z)) * s0 + 2 * jo * c0)
    k_max = 0.0
    for i in range(m):
        k_max = max(k_max, k[i])
    delta = min(max(xi * big_r, 0.0), a)
    for _ in range(max_iter):
        small = k_max * delta < TAYLOR_LIMIT
        direct = deriv = 0.0
        for i in range(m):
            ki = k[i]
            zs = ki * (a - delta)
            js0 = j0(zs)
            sn, cs = math.sin(ki * (y + delta)), math.cos(ki * (y + delta))
            s1, c1 = za[i] * sn - zb[i] * cs, za[i] * cs + zb[i] * sn
            if not small:
                direct += ki * (js0 * s1 - jzs0[i])
            deriv += ki * ki * (j1(zs) * s1 + js0 * c1)
        bracket = delta * g1 + 0.5 * delta * delta * g2 if small else direct
        f = delta / big_r + bracket - xi
        df = 1.0 / big_r + deriv
        new = min(max(delta - f / df, 0.0), a)
        done = abs(new - delta) <= tol * max(abs(new), 1e-300) + 1e-15 * tol * a
        delta = new
        if done:
            break
    return delta


@_jit
def tangential_force(x, a, d, delta, mu, comp, big_r, k, za, zb):
    """``|T| = (mu/C) [delta (2a - delta)/(2R) + H(0) - H(delta)]``, (4.67) minus (4.33),
    ``H(delta) = sum k (a - delta) J1(k (a - delta)) Zc(X + Delta + delta)``. [N/m]"""
    m = k.size
    y = x + d
    k_max = 0.0
    for i in range(m):
        k_max = max(k_max, k[i])
    small = k_max * delta < TAYLOR_LIMIT
    h1 = h2 = direct = 0.0
    ast = a - delta
    for i in range(m):
        ki = k[i]
        sn, cs = math.sin(ki * y), math.cos(ki * y)
        s0, c0 = za[i] * sn - zb[i] * cs, za[i] * cs + zb[i] * sn
        z = ki * a
        jz, jo = j0(z), j1(z)
        if small:
            h1 += ki * ki * a * (jz * c0 + jo * s0)
            h2 += (ki * ki * (jz * c0 + jo * s0)
                   - ki ** 3 * a * (2 * jo * c0 - (2 * jz - _j1_over_z(z)) * s0))
        else:
            sn1, cs1 = math.sin(ki * (y + delta)), math.cos(ki * (y + delta))
            c1 = za[i] * cs1 + zb[i] * sn1
            direct += ki * (a * jo * c0 - ast * j1(ki * ast) * c1)
    diff = -(delta * -h1 + 0.5 * delta * delta * h2) if small else direct
    return mu / comp * (delta * (2 * a - delta) / (2 * big_r) + diff)


@_jit
def contact_exact(x, nc, big_r, k, za, zb, xi_over_mu, mu, comp):
    """The exact contact at one rail position: ``(a, Delta, a*, |T|, status)``."""
    a, d, _, _, status = solve_normal(x, nc, big_r, k, za, zb, math.sqrt(2.0 * big_r * nc),
                                      1e-13, 60)
    if status != OK:
        return a, d, math.nan, math.nan, status
    offset = stick_offset(x, a, d, xi_over_mu, big_r, k, za, zb, 1e-13, 60)
    return a, d, a - offset, tangential_force(x, a, d, offset, mu, comp, big_r, k, za, zb), OK


@_jit
def solve_normal_array(x, nc, big_r, k, za, zb, a_start, tol, max_iter):
    """:func:`solve_normal` at every element of the 1-D arrays ``x`` and ``a_start``: four
    arrays and the status per element."""
    n = x.size
    out = np.empty((4, n))
    status = np.empty(n, dtype=np.int64)
    for j in range(n):
        out[0, j], out[1, j], out[2, j], out[3, j], status[j] = solve_normal(
            x[j], nc, big_r, k, za, zb, a_start[j], tol, max_iter)
    return out, status


@_jit
def stick_offset_array(x, a, d, xi, big_r, k, za, zb, tol, max_iter):
    """:func:`stick_offset` at every element of the 1-D arrays ``x``, ``a``, ``d``."""
    out = np.empty(x.size)
    for j in range(x.size):
        out[j] = stick_offset(x[j], a[j], d[j], xi, big_r, k, za, zb, tol, max_iter)
    return out


@_jit
def tangential_force_array(x, a, d, delta, mu, comp, big_r, k, za, zb):
    """:func:`tangential_force` at every element of the 1-D arrays ``x``, ``a``, ``d``,
    ``delta``."""
    out = np.empty(x.size)
    for j in range(x.size):
        out[j] = tangential_force(x[j], a[j], d[j], delta[j], mu, comp, big_r, k, za, zb)
    return out


# ---------------------------------------------------------------------------------------------
# the linearised theory: closed forms of one harmonic and their superposition
# ---------------------------------------------------------------------------------------------
@_jit
def linear_response(beta, r):
    """Normalised linear responses of one harmonic at ``beta = k a0`` and ``r = a0*/a0``:
    ``(c_Delta/(k R), c_a/(k R), c_a*/(k R), c_T)``, (4.36)-(4.37), (4.58)-(4.64) and
    (4.68)-(4.73) in the package orientation (see :mod:`railcontact.corrugation`)."""
    jb0, jb1 = j0(beta), j1(beta)
    kd = beta * (1.0 - r)
    js = j0(beta * r)
    cs = complex(-jb1 + js * math.sin(kd), -(jb0 - js * math.cos(kd)))
    ct = -beta * r * (cs + j1(beta * r) * cmath.exp(-1j * kd))
    return complex(0.0, -jb0), complex(-jb1, 0.0), cs, ct


@_jit
def linear_response_array(beta, r):
    """:func:`linear_response` at every element of the 1-D arrays ``beta``, ``r``: shape
    (4, n), complex."""
    out = np.empty((4, beta.size), dtype=np.complex128)
    for j in range(beta.size):
        out[0, j], out[1, j], out[2, j], out[3, j] = linear_response(beta[j], r[j])
    return out


@_jit
def contact_linear(x, a0, a0s, t0, big_r, force_scale, k, za, zb, beta):
    """The linearised contact at one rail position, (4.36)-(4.37), (4.59)-(4.62),
    (4.68)-(4.71): ``(a, Delta, a*, |T|)``, each ``Q0 + sum Re[c (Z_A + i Z_B) e^(-i k X)]``
    (``k R c`` for the lengths, ``mu / C c_T`` for the force: ``force_scale = mu / C``), with
    ``beta = k a0``, ``r = a0*/a0`` and ``t0 = mu N (1 - r^2)``."""
    r = a0s / a0
    a, d, ast, t = a0, 0.0, a0s, t0
    for i in range(k.size):
        cd, ca, cs, ct = linear_response(beta[i], r)
        zc = complex(za[i], zb[i]) * cmath.exp(-1j * k[i] * x)
        kr = k[i] * big_r
        a += (kr * ca * zc).real
        d += (kr * cd * zc).real
        ast += (kr * cs * zc).real
        t += (force_scale * ct * zc).real
    return a, d, ast, t


@_jit
def contact_linear_array(x, a0, a0s, t0, big_r, force_scale, k, za, zb, beta):
    """:func:`contact_linear` at every element of the 1-D array ``x``: shape (4, n)."""
    out = np.empty((4, x.size))
    for j in range(x.size):
        out[0, j], out[1, j], out[2, j], out[3, j] = contact_linear(
            x[j], a0, a0s, t0, big_r, force_scale, k, za, zb, beta)
    return out


# ---------------------------------------------------------------------------------------------
# the linearised wear of one harmonic (Sec. 4.3): slip-zone integrals of the perturbations
# ---------------------------------------------------------------------------------------------
#: (1j) ** m for m = 0..3 (the Jacobi-Anger factors i^(n+1))
_IPOW = (1.0 + 0.0j, 1.0j, -1.0 + 0.0j, -1.0j)


@_jit
def patch_integrals(beta, r, n_nodes, degree):
    """``I = int h_P(x) e^(-i k x) dx`` and ``I0 = int P0(x) e^(-i k x) dx`` over the slip zone
    ``[-1, 1 - 2 r]`` (normalised units a0 = R = C = mu = K = V = 1, so N = 1/2), for
    ``beta = k a0`` and ``r = a0*/a0`` in (0, 1): the perturbation of the frictional power
    ``h_P = h_p s0 + p0 h_s`` (pressure and slip perturbations as Chebyshev-Bessel series of
    ``degree`` terms), Gauss-Chebyshev quadrature with ``n_nodes`` nodes."""
    k = beta
    e_kd = cmath.exp(1j * k * (1.0 - r))
    h_d = 1j * k * j0(beta)
    h_a = complex(-k * j1(beta), 0.0)
    h_as = h_d + h_a - 1j * k * j0(beta * r) * e_kd
    h_c1 = k * j1(k)
    h_d1 = h_as + 2 * k * j1(k * r) * e_kd
    cp = np.empty(max(degree - 1, 0), dtype=np.complex128)
    cs = np.empty(max(degree - 1, 0), dtype=np.complex128)
    for n in range(2, degree + 1):
        two_ipow_k = 2 * _IPOW[(n + 1) % 4] * k
        cp[n - 2] = two_ipow_k * jv(float(n), k)
        cs[n - 2] = two_ipow_k * jv(float(n), k * r) * e_kd
    half = 1.0 - r
    integral = integral0 = 0.0j
    for j in range(1, n_nodes + 1):
        t = math.cos((2 * j - 1) * math.pi / (2 * n_nodes))
        wq = math.pi / n_nodes * math.sqrt(1 - t * t)
        x = -r + half * t                      # slip zone [-1, 1 - 2r]
        u = x
        sin_t = math.sqrt(1.0 - u * u)
        theta = math.acos(u)
        xm1 = x - 1.0
        s0 = math.sqrt(xm1 * (xm1 + 2 * r))    # r sqrt(v^2 - 1)
        v = xm1 / r + 1.0
        root = math.sqrt(v * v - 1.0)
        w = 1.0 / (v - root)                   # v + sqrt(v^2 - 1), computed stably
        p0 = sin_t / math.pi
        hp = u * u * h_a / sin_t + h_c1 * sin_t                 # pressure perturbation
        hs = (h_d1 * w + (w / root) * (-h_a + (1.0 - v) * h_as)  # slip perturbation
              - (h_d - 1j * k * cmath.exp(1j * k * x)))
        wn = w
        for n in range(2, degree + 1):
            hp = hp - cp[n - 2] * math.sin(n * theta)
            wn = wn * w
            hs = hs - cs[n - 2] * wn
        hp = hp / math.pi
        phase = cmath.exp(-1j * k * x)
        integral += (hp * s0 + p0 * hs) * phase * wq
        integral0 += p0 * s0 * phase * wq
    return integral * half, integral0 * half


@_jit
def wear_coefficients_array(beta, r, n_nodes, degree, material_point):
    """Linearised wear coefficients ``w = 2 conj(I)`` (model "patch_coordinate") or
    ``2 conj(I + beta^2 J0(beta) I0)`` ("material_point") at every element of the 1-D arrays
    ``beta``, ``r`` (``r`` in [0, 1]; 0 at r = 1, r clipped to [1e-9, 1 - 1e-9])."""
    out = np.empty(beta.size, dtype=np.complex128)
    for j in range(beta.size):
        if r[j] >= 1.0:
            out[j] = 0.0
            continue
        rj = min(max(r[j], 1e-9), 1.0 - 1e-9)
        integral, integral0 = patch_integrals(beta[j], rj, n_nodes, degree)
        if material_point:
            integral = integral + beta[j] * beta[j] * j0(beta[j]) * integral0
        out[j] = 2.0 * integral.conjugate()
    return out


def wear_coefficients_series(a0_over_wavelengths, stick_ratio, wear_model):
    """:func:`railcontact.wear.wear_coefficients` of the series models ("material_point",
    "patch_coordinate") for a sequence of ``a0/L`` at one ``r_a0`` in [0, 1], unchecked (the
    FMU's per-step call; the scene checked the inputs): a complex array. The same kernel, nodes
    (24), default series degree ``ceil(e max k a0) + 12`` and limit of that degree (100000,
    the same ValueError) as the public function."""
    beta = TWO_PI * np.asarray(a0_over_wavelengths, dtype=float)
    degree = math.ceil(math.e * max(float(beta.max()), 0.0)) + 12
    if not 1 <= degree <= 100000:
        check_range("degree", degree, "-", 1, 100000)          # raises, naming the degree
    return wear_coefficients_array(beta, np.full(beta.size, float(stick_ratio)), 24,
                                   int(degree), wear_model == "material_point")


def wear_coefficients_list(a0_over_wavelengths, stick_ratio, wear_model):
    """:func:`wear_coefficients_series` as a list of complex."""
    return wear_coefficients_series(a0_over_wavelengths, stick_ratio, wear_model).tolist()


@_jit
def wear_depth_array(x, w0, scale, k, za, zb, w):
    """Linearised wear per passage at the material points ``x``, (4.94)-(4.96):
    ``W0 + sum Re[scale w (Z_A + i Z_B) e^(-i k X)]`` with ``scale = K mu^2 N / a0``."""
    out = np.empty(x.size)
    for j in range(x.size):
        depth = w0
        for i in range(k.size):
            depth += (scale * w[i] * (complex(za[i], zb[i]) * cmath.exp(-1j * k[i] * x[j]))).real
        out[j] = depth
    return out


def series_relative_error(ka, degree):
    """The ``relative_error`` of :func:`railcontact.corrugation.series_truncation_error` for
    one float ``ka >= 0`` and int ``degree >= 1``: ``sum_{j > degree} |J_j(ka)| / max_j
    |J_j(ka)|`` over ``j <= degree + 60 + 2 int(ka)``. [-]"""
    j = np.arange(1, degree + 60 + int(ka) * 2 + 1)
    terms = np.abs(_scipy_jv(j, ka))
    biggest = max(float(terms.max()), 1e-300)
    tail = float(np.where(j > degree, terms, 0.0).sum())
    return tail / biggest if ka > 0 else 0.0
