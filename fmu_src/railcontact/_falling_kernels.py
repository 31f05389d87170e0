"""Compiled scalar path of :func:`railcontact.falling_table.falling_friction_table` for the
package's two laws on one exact-table contact buffer (the FMU's step and the public scalar call
with a :class:`railcontact.friction.SmoothFriction` or
:class:`~railcontact.friction.PolachFriction`).

The same steps and constants as the numpy function (module docstring of
:mod:`railcontact.falling_table`), with the law in closed form (:func:`_law`: the smooth law
``mu(s) = (mu_0 - mu_k) / (1 + kappa s) + mu_k``, or Polach's
``mu_0 ((1 - A) exp(-B s V) + A)``, the operations of the law objects) or, for any other law,
tabulated (:func:`railcontact.falling_table.law_table`, linear between log-spaced slips, as
the exact solver takes a law) and the table's compiled
contact kernel
(:func:`railcontact._exact_kernels.creep_contact`) called directly: one call instead of five
table calls and some 60 numpy operations. The two agree to round-off (the quadrature sums
run in another order); tests/test_falling_friction_3d.py compares them on a table of cases.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from . import _numba_cache  # noqa: F401  (the user cache, before any njit is compiled)
from ._exact_kernels import (buffer_views, creep_contact, creep_table_point, cubic_basis,
                             kalker_coefficients, saturation_creepage, table_coordinates,
                             table_views)
from ._spline_kernels import find_span

__all__ = ["falling_contact", "falling_table_point", "falling_contacts",
           "falling_correction_batch", "LAW_SMOOTH", "LAW_POLACH",
           "LAW_TABLE", "CORRECTION_HEADER"]

#: Law kinds of :func:`falling_contact`.
LAW_SMOOTH = 0
LAW_POLACH = 1
LAW_TABLE = 2


@njit(cache=True)
def _law(kind, p0, p1, p2, p3, tab, s):
    """mu(s): kind 0 the smooth law (p0, p1, p2) = (mu_0, mu_k, kappa); kind 1 Polach's
    (p0, p1, p2, p3) = (mu_0, A, B [s/m], V [m/s]); kind 2 the table ``tab`` (rows: slips,
    increasing from 0, and mu), linear between its slips, -1 beyond its last (the caller
    then hands the case back). s >= 0."""
    if kind == 0:
        return (p0 - p1) / (1.0 + p2 * s) + p1
    if kind == 1:
        return p0 * ((1.0 - p1) * math.exp(-p2 * (s * p3)) + p1)
    ts = tab[0]
    n = ts.shape[0]
    if not s <= ts[n - 1]:
        return -1.0
    lo = 0
    hi = n - 1
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if ts[mid] <= s:
            lo = mid
        else:
            hi = mid
    f = (s - ts[lo]) / (ts[hi] - ts[lo])
    return tab[1, lo] + f * (tab[1, hi] - tab[1, lo])


#: Length of the header of a packed correction table (:func:`_correction`): the coefficient
#: counts of its five cubic axes (ln(a0/b0), s, theta, tau, kappa number), the node counts of
#: its two linear axes (nu, mu_k/mu_0).
CORRECTION_HEADER = 7


@njit(cache=True)
def _law_shape(kind, p0, p1, p2, p3, tab):
    """``(mu_k / mu_0, kappa)`` of the smooth law (5.16) the correction table takes for the law
    ``(kind, p0..p3, tab)`` of :func:`_law`: the smooth law's own; for another law its ratio
    of the far to the zero-slip friction and ``kappa = 1 / s_half``, ``s_half`` the slip where
    mu is half-way between the two (the smooth law's half-point is at 1 / kappa). Polach's:
    ``(A, B V)``, the same slope at zero slip. A law that does not fall gives ratio 1 (no
    correction)."""
    if kind == 0:
        return p1 / p0, p2
    if kind == 1:
        return p1, p2 * p3
    ts = tab[0]
    mus = tab[1]
    n = ts.shape[0]
    mu0 = mus[0]
    mu_far = mus[n - 1]
    if not (mu0 > 0.0 and mu_far < mu0):
        return 1.0, 0.0
    half = 0.5 * (mu0 + mu_far)
    for i in range(1, n):
        if mus[i] <= half:
            f = (mus[i - 1] - half) / (mus[i - 1] - mus[i])
            s_half = ts[i - 1] + f * (ts[i] - ts[i - 1])
            return mu_far / mu0, 1.0 / s_half if s_half > 0.0 else 1e300
    return 1.0, 0.0


@njit(cache=True)
def _linear_weight(nodes, x):
    """Interval ``i`` and weight ``f`` of ``x`` (held at the ends) between ``nodes[i]`` and
    ``nodes[i + 1]``."""
    n = nodes.shape[0]
    if n == 1 or not x > nodes[0]:
        return 0, 0.0
    if not x < nodes[n - 1]:
        return n - 2, 1.0
    i = 0
    while x >= nodes[i + 1]:
        i += 1
    return i, (x - nodes[i]) / (nodes[i + 1] - nodes[i])


@njit(cache=True)
def _correction(corr, lg, nu, s, theta, tau, m, kn, out, sc):
    """The correction table (:func:`railcontact.falling_table.load_falling_correction`) at one
    point, into ``out[:3]`` (normalised: dT_x, dT_y over mu_0 N, dM_z over mu_0 N sqrt(a0 b0)).

    ``corr``: the header (:data:`CORRECTION_HEADER`), the knots of the five cubic axes (each
    its coefficient count plus 4; a count of 1: the axis summed out, 5 placeholder knots; the
    first axis only), the nodes of the two linear axes, then the coefficients
    (n_nu, n_m, n_g, n_s, n_theta, n_tau, n_kn, 3) in C order (the three variables last: the
    innermost sum runs over 12 neighbouring numbers). Cubic along ln(a0/b0), s, theta
    (periodic), tau and the kappa number (C2 B-splines), linear along nu and mu_k/mu_0 (a
    law's and a material's constants); every coordinate is held at the ends of its axis
    (theta is in [-pi, pi] as atan2 gives it). ``sc``: scratch of at least 41 numbers (no
    allocation per call)."""
    nc0, nc1, nc2, nc3, nc4 = (int(corr[0]), int(corr[1]), int(corr[2]), int(corr[3]),
                               int(corr[4]))
    n_nu = int(corr[5])
    n_m = int(corr[6])
    pos = CORRECTION_HEADER
    bas = sc[:20].reshape((5, 4))
    db = sc[20:24]
    w = sc[24:36]
    spans = sc[36:41]
    for a in range(5):
        n = (nc0, nc1, nc2, nc3, nc4)[a]
        if n == 1:      # an axis summed out for one value (correction_at): weight 1
            bas[a, 0] = 1.0
            spans[a] = 3.0
            pos += 5
            continue
        t = corr[pos:pos + n + 4]
        xa = min(max((lg, s, theta, tau, kn)[a], t[3]), t[n])
        span = find_span(t, np.int64(n), xa)
        spans[a] = span
        cubic_basis(t, span, xa, bas[a], db, w)
        pos += n + 4
    k0 = 1 if nc0 == 1 else 4
    i_nu, f_nu = _linear_weight(corr[pos:pos + n_nu], nu)
    pos += n_nu
    i_m, f_m = _linear_weight(corr[pos:pos + n_m], m)
    pos += n_m
    st3 = nc4 * 3
    st2 = nc3 * st3
    st1 = nc2 * st2
    st0 = nc1 * st1
    st_m = nc0 * st0
    st_nu = n_m * st_m
    # 12 sums in registers (kappa number x variable; an array here would be reloaded)
    c0 = c1 = c2 = c3 = c4 = c5 = c6 = c7 = c8 = c9 = c10 = c11 = 0.0
    for jn in range(2):
        wn = f_nu if jn == 1 else 1.0 - f_nu
        if wn == 0.0:
            continue
        for jm in range(2):
            wm = f_m if jm == 1 else 1.0 - f_m
            if wm == 0.0:
                continue
            base = (pos + (i_nu + jn) * st_nu + (i_m + jm) * st_m
                    + (int(spans[0]) - 3) * st0 + (int(spans[1]) - 3) * st1
                    + (int(spans[2]) - 3) * st2 + (int(spans[3]) - 3) * st3
                    + (int(spans[4]) - 3) * 3)
            for j0 in range(k0):
                w0 = wn * wm * bas[0, j0]
                b0 = base + j0 * st0
                for j1 in range(4):
                    w1 = w0 * bas[1, j1]
                    b1 = b0 + j1 * st1
                    for j2 in range(4):
                        w2 = w1 * bas[2, j2]
                        b2 = b1 + j2 * st2
                        for j3 in range(4):
                            w3 = w2 * bas[3, j3]
                            b3 = b2 + j3 * st3
                            # (a view: constant indices, no negative-index check per load)
                            r = corr[b3:b3 + 12]
                            c0 += w3 * r[0]
                            c1 += w3 * r[1]
                            c2 += w3 * r[2]
                            c3 += w3 * r[3]
                            c4 += w3 * r[4]
                            c5 += w3 * r[5]
                            c6 += w3 * r[6]
                            c7 += w3 * r[7]
                            c8 += w3 * r[8]
                            c9 += w3 * r[9]
                            c10 += w3 * r[10]
                            c11 += w3 * r[11]
    k0, k1, k2, k3 = bas[4, 0], bas[4, 1], bas[4, 2], bas[4, 3]
    out[0] = k0 * c0 + k1 * c3 + k2 * c6 + k3 * c9
    out[1] = k0 * c1 + k1 * c4 + k2 * c7 + k3 * c10
    out[2] = k0 * c2 + k1 * c5 + k2 * c8 + k3 * c11


@njit(cache=True)
def falling_correction_batch(corr, lg, nu, s, theta, tau, m, kn, out):
    """:func:`_correction` at each point of the flat arrays (``out`` (n, 3))."""
    sc = np.empty(41)
    for i in range(lg.shape[0]):
        _correction(corr, lg[i], nu[i], s[i], theta[i], tau[i], m[i], kn[i], out[i], sc)


@njit(cache=True)
def _spin_floor(mu0, tau0, w_sat, spin_edge):
    """mu_0 |tau_0| / spin_edge (less 1e-9), the coefficient at which the table's spin
    coordinate reaches ``spin_edge`` (tau = tau_0 mu_0 / mu, ``tau0`` the contact's at mu_0,
    ``w_sat`` its saturation creepage there), or 0 where |tau_0| > spin_edge or it cannot be
    computed (``w_sat`` 0) (as :func:`railcontact.falling_table.spin_floor`)."""
    tau0 = abs(tau0)
    if not w_sat > 0.0 or tau0 > spin_edge * (1.0 + 1e-9):
        return 0.0
    return mu0 * tau0 / (spin_edge * (1.0 - 1e-9))


@njit(cache=True)
def _table_mu(mu, mu_f, blend):
    """The coefficient the table is called at: mu, kept above mu_f by a C2 smooth maximum of
    half-width ``blend`` mu_f (as :func:`railcontact.falling_table.table_mu`)."""
    if mu_f <= 0.0:
        return mu
    x = mu / mu_f
    if x >= 1.0 + blend:
        return mu
    u = min(max((x - 1.0) / (2.0 * blend) + 0.5, 0.0), 1.0)
    return mu_f * (1.0 + blend * (2.0 * u * u * u - u * u * u * u))


@njit(cache=True)
def _spin_blend_weight(tau0, lo, hi):
    """The quintic smoothstep from ``lo`` to ``hi`` at ``tau0`` (as
    :func:`railcontact.falling_table.spin_blend_weight`)."""
    t = min(max((tau0 - lo) / (hi - lo), 0.0), 1.0)
    return t * t * t * (10.0 + t * (6.0 * t - 15.0))


@njit(cache=True)
def falling_contact(buf, xi_x, xi_y, phi, normal_load, a0, b0, youngs_modulus, kind, p0, p1,
                    p2, p3, tab, corr, gauss, steps, share_min, model, out):
    """Falling friction on one contact buffer of the exact table, the law ``(kind, p0..p3,
    tab)`` of :func:`_law` (mu_0 = mu(0)); slips s are capped where ``p2 s`` would reach
    1e300.

    ``gauss``: rows x/a0, y/b0 and weight (summing to 1) of the Gauss points of
    :mod:`railcontact.falling_table`, then four rows of scratch (the rigid slip's components,
    its magnitude and its magnitude smoothed over the spin pole: no allocation per call);
    ``steps``, ``share_min`` its fixed-point steps and least slip share, ``model`` its
    :data:`~railcontact.falling_table.SPIN_POLE_SMOOTHING`,
    :data:`~railcontact.falling_table.SPIN_COORDINATE_EDGE`,
    :data:`~railcontact.falling_table.TABLE_MU_BLEND` and the two ends of
    :data:`~railcontact.falling_table.SPIN_BLEND` (arguments, not module constants:
    numba's cache would keep a constant of another module frozen at its old value); the
    table is called at :func:`_table_mu` of mu, its force and moment scaled by mu over
    that. Writes ``out[:6] = (tx, ty, mz, stick_area_fraction,
    normalised_creepage, mu_effective)`` and returns True; False where the table's kernel
    hands the case to its array path, or a tabulated law is asked beyond its last slip (the
    caller then takes the numpy function).

    ``corr``: the packed correction table of :func:`_correction` (empty: none), added to the
    model's force and moment at the table coordinates of the contact at mu_0 and the law's
    :func:`_law_shape`."""
    return _falling(buf, buf, buf[:1].reshape((1, 1, 1, 1, 1, 1)), False, 0.0, xi_x, xi_y,
                    phi, normal_load, a0, b0, youngs_modulus, kind, p0, p1, p2, p3, tab, corr,
                    gauss, steps, share_min, model, out)


@njit(cache=True)
def falling_table_point(tbuf, coef, xi_x, xi_y, phi, normal_load, a0, b0, youngs_modulus,
                        poisson_ratio, kind, p0, p1, p2, p3, tab, corr, gauss, steps, share_min,
                        model, out):
    """:func:`falling_contact` for any contact, without a contact buffer: the exact table's
    five-dimensional spline at each of its points
    (:func:`railcontact._exact_kernels.creep_table_point` on the table buffer ``tbuf`` and the
    coefficients ``coef``: the file's, float32, or those summed over nu at ``poisson_ratio``,
    float64), Kalker's coefficients from their interpolant at the contact's a0/b0 and
    ``poisson_ratio`` [-]. The path of a contact whose a0/b0 changes at every call (a
    vehicle's wheel on its rail), which never pays a buffer's slab. Arguments and results as
    :func:`falling_contact`; also False for a0/b0 beyond the table's axis or nu outside
    [0, 0.5]."""
    return _falling(tbuf, tbuf, coef, True, poisson_ratio, xi_x, xi_y, phi, normal_load,
                    a0, b0, youngs_modulus, kind, p0, p1, p2, p3, tab, corr, gauss, steps,
                    share_min, model, out)


#: (the same kernel on the coefficients summed over nu, float64: its own export name)
falling_table_point_nu = falling_table_point


@njit(cache=True)
def falling_contacts(tbuf, coef, buf, on_buffer, xi_x, xi_y, phi, normal_load, a0, b0,
                     youngs_modulus, poisson_ratio, kind, mu0, p1, p2, p3, tab, corr,
                     corr_buffer, gauss, steps, share_min, model, out, ok):
    """:func:`falling_table_point` (``on_buffer[k]`` False) or :func:`falling_contact` on the
    one contact buffer ``buf`` (True; with the correction table ``corr_buffer``) for each
    contact k of the arrays (a vehicle's contacts in one call), mu_0 = ``mu0[k]`` and the
    law's other parameters common; ``out[k, :6]`` as theirs, ``ok[k]`` whether it was
    computed (else the caller takes the contact's own path)."""
    dummy = buf[:1].reshape((1, 1, 1, 1, 1, 1))
    for k in range(xi_x.shape[0]):
        if on_buffer[k]:
            ok[k] = _falling(buf, buf, dummy, False, 0.0, xi_x[k], xi_y[k], phi[k],
                             normal_load[k], a0[k], b0[k], youngs_modulus, kind, mu0[k], p1,
                             p2, p3, tab, corr_buffer, gauss, steps, share_min, model, out[k])
        else:
            ok[k] = _falling(tbuf, tbuf, coef, True, poisson_ratio, xi_x[k], xi_y[k], phi[k],
                             normal_load[k], a0[k], b0[k], youngs_modulus, kind, mu0[k], p1,
                             p2, p3, tab, corr, gauss, steps, share_min, model, out[k])


@njit(cache=True)
def _falling(buf, tbuf, coef, on_table, poisson_ratio, xi_x, xi_y, phi, normal_load, a0, b0,
             youngs_modulus, kind, p0, p1, p2, p3, tab, corr, gauss, steps, share_min, model,
             out):
    """The body of :func:`falling_contact` (``on_table`` False: the contact buffer ``buf``)
    and :func:`falling_table_point` (True: the table buffer ``tbuf``, ``coef`` and
    ``poisson_ratio``); the other's arrays are placeholders (views of the one passed: a
    global array would be a read-only constant, another type)."""
    if on_table:
        nu = poisson_ratio
        if not (0.0 <= nu <= 0.5 and 0.0 < a0 < math.inf and 0.0 < b0 < math.inf):
            return False
        tv = table_views(tbuf)
        res, work = tv[13], tv[14]
        log_g = math.log(a0 / b0)
        if not tbuf[6] <= log_g <= tbuf[7]:
            return False
        c11, c22, c23 = kalker_coefficients(tv[10], tv[11], tv[12], log_g, nu)
    else:
        bv = buffer_views(buf)
        res, work = bv[7], bv[8]
        nu = buf[7]
        c11, c22, c23 = buf[4], buf[5], buf[6]
    gx, gy, gw = gauss[0], gauss[1], gauss[2]
    n = gw.shape[0]
    fmax = 1.7976931348623157e308
    tiny = 2.2250738585072014e-308
    scale = max(max(abs(xi_x), abs(xi_y)), abs(phi) * max(a0, b0))
    has_slip = scale > 0.0 and normal_load > 0.0
    if not has_slip:
        scale = 1.0
    rx, ry, rp = xi_x / scale, xi_y / scale, phi / scale
    wx, wy, wn, w3 = gauss[3], gauss[4], gauss[5], gauss[6]
    eps2 = (model[0] * rp) * (model[0] * rp) * (a0 * b0)
    w_mean = 0.0
    w3_mean = 0.0
    for k in range(n):
        wx[k] = rx - rp * b0 * gy[k]
        wy[k] = ry + rp * a0 * gx[k]
        wn[k] = math.hypot(wx[k], wy[k])
        w3[k] = math.sqrt(wx[k] * wx[k] + wy[k] * wy[k] + eps2)
        w_mean += wn[k] * gw[k]
        w3_mean += w3[k] * gw[k]
    has_slip = has_slip and w_mean > 0.0
    inv = 1.0 / (normal_load * w_mean) if has_slip else 0.0
    s_cap = 0.5 * fmax / max(scale, 1.0)
    kap_cap = 1e300 / max(p2, 1.0) / (max(p3, 1.0) if kind == 1 else 1.0)
    mu0 = _law(kind, p0, p1, p2, p3, tab, 0.0)
    mu = mu0
    # the contact's table coordinates at mu_0: for the spin floor and the correction table
    w_sat = saturation_creepage(xi_x, xi_y, phi, normal_load, a0, b0, youngs_modulus, mu0, nu)
    root_ab, tau, s_c, theta = 0.0, 0.0, 0.0, 0.0
    if w_sat > 0.0:
        root_ab, _, _, _, tau, _, _, _, s_c, theta = table_coordinates(
            xi_x, xi_y, phi, a0, b0, w_sat, c11, c22, c23)
    mu_f = _spin_floor(mu0, tau, w_sat, model[1])
    blend = _spin_blend_weight(abs(tau), model[3], model[4])
    st0 = st1 = st2 = st3 = 0.0     # the Coulomb solution at mu_0 (the first step)
    lam = 0.0
    for step in range(steps + 1):
        mu_t = _table_mu(mu, mu_f, model[2])
        if on_table:
            done = creep_table_point(tbuf, coef, xi_x, xi_y, phi, normal_load, a0, b0,
                                     youngs_modulus, nu, mu_t, False)
        else:
            done = creep_contact(buf, xi_x, xi_y, phi, normal_load, a0, b0, youngs_modulus,
                                 mu_t, False)
        if not done:
            return False
        q = mu / mu_t
        res[0] *= q
        res[1] *= q
        res[2] *= q
        if step == 0:
            st0, st1, st2, st3 = res[0], res[1], res[2], res[3]
        if step == steps:   # the blend with spin (as the numpy function's step 2)
            qs = blend * mu / mu0
            res[0] = res[0] * (1.0 - blend) + st0 * qs
            res[1] = res[1] * (1.0 - blend) + st1 * qs
            res[2] = res[2] * (1.0 - blend) + st2 * qs
            res[3] = res[3] * (1.0 - blend) + st3 * blend
        power = abs(res[0] * rx + res[1] * ry + res[2] * rp)
        share = min(max(1.0 - res[3], share_min), 1.0)
        lam = power * inv / (max(mu, tiny) * share)
        if step == steps:
            break
        new = 0.0
        for k in range(n):
            s = min(min(lam * wn[k], s_cap) * scale, kap_cap)
            m = _law(kind, p0, p1, p2, p3, tab, s)
            if m < 0.0:
                return False
            new += m * gw[k]
        mu = new if step == 0 else 0.5 * (mu + new)
    slide = 1.0 - min(max(res[3], 0.0), 1.0)
    weight = normal_load * slide * slide if has_slip else 0.0
    cx = 0.0
    cy = 0.0
    lam3 = lam * (w_mean / w3_mean) if has_slip else 0.0    # (step 3: the smoothed slip)
    for k in range(n):
        s = min(min(lam3 * w3[k], s_cap) * scale, kap_cap)
        m = _law(kind, p0, p1, p2, p3, tab, s)
        if m < 0.0:
            return False
        dmu = (m - mu) / (w3[k] if w3[k] > 0.0 else 1.0)
        cx += dmu * wx[k] * gw[k]
        cy += dmu * wy[k] * gw[k]
    out[0] = res[0] - weight * cx
    out[1] = res[1] - weight * cy
    out[2] = res[2]
    if corr.shape[0] > 0 and has_slip:
        m_ratio, kappa = _law_shape(kind, p0, p1, p2, p3, tab)
        if m_ratio < 1.0 and w_sat > 0.0:
            p_max = 1.5 * normal_load / (math.pi * a0 * b0)
            shear = youngs_modulus / (2.0 * (1.0 + nu))
            kn = min(kappa, 1e300) * mu0 * p_max / shear
            d = work[41:44]     # (the table kernel's scratch: its calls are done)
            _correction(corr, math.log(a0 / b0), nu, s_c, theta, tau, m_ratio, kn, d,
                        work[:41])
            mu_n = mu0 * normal_load
            out[0] += mu_n * d[0]
            out[1] += mu_n * d[1]
            out[2] += mu_n * root_ab * d[2]
    out[3] = res[3]
    out[4] = res[4]
    out[5] = mu
    inf = math.inf
    return -inf < out[0] < inf and -inf < out[1] < inf
