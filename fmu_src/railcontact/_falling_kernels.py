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

from numba import njit

from . import _numba_cache  # noqa: F401  (the user cache, before any njit is compiled)
from ._exact_kernels import buffer_views, creep_contact

__all__ = ["falling_contact", "LAW_SMOOTH", "LAW_POLACH", "LAW_TABLE"]

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


@njit(cache=True)
def falling_contact(buf, xi_x, xi_y, phi, normal_load, a0, b0, youngs_modulus, kind, p0, p1,
                    p2, p3, tab, gauss, steps, share_min, out):
    """Falling friction on one contact buffer of the exact table, the law ``(kind, p0..p3,
    tab)`` of :func:`_law` (mu_0 = mu(0)); slips s are capped where ``p2 s`` would reach
    1e300.

    ``gauss``: rows x/a0, y/b0 and weight (summing to 1) of the Gauss points of
    :mod:`railcontact.falling_table`; ``steps``, ``share_min`` its fixed-point steps and least
    slip share (arguments, not module constants: numba's cache would keep a constant of
    another module frozen at its old value). Writes ``out[:6] = (tx, ty, mz, stick_area_fraction,
    normalised_creepage, mu_effective)`` and returns True; False where the table's kernel
    hands the case to its array path, or a tabulated law is asked beyond its last slip (the
    caller then takes the numpy function)."""
    res = buffer_views(buf)[7]
    gx, gy, gw = gauss[0], gauss[1], gauss[2]
    n = gw.shape[0]
    fmax = 1.7976931348623157e308
    tiny = 2.2250738585072014e-308
    scale = max(max(abs(xi_x), abs(xi_y)), abs(phi) * max(a0, b0))
    has_slip = scale > 0.0 and normal_load > 0.0
    if not has_slip:
        scale = 1.0
    rx, ry, rp = xi_x / scale, xi_y / scale, phi / scale
    wx = gw.copy()
    wy = gw.copy()
    wn = gw.copy()
    w_mean = 0.0
    for k in range(n):
        wx[k] = rx - rp * b0 * gy[k]
        wy[k] = ry + rp * a0 * gx[k]
        wn[k] = math.hypot(wx[k], wy[k])
        w_mean += wn[k] * gw[k]
    has_slip = has_slip and w_mean > 0.0
    inv = 1.0 / (normal_load * w_mean) if has_slip else 0.0
    s_cap = 0.5 * fmax / max(scale, 1.0)
    kap_cap = 1e300 / max(p2, 1.0) / (max(p3, 1.0) if kind == 1 else 1.0)
    mu = _law(kind, p0, p1, p2, p3, tab, 0.0)
    for step in range(steps + 1):
        if not creep_contact(buf, xi_x, xi_y, phi, normal_load, a0, b0, youngs_modulus, mu,
                             False):
            return False
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
    for k in range(n):
        s = min(min(lam * wn[k], s_cap) * scale, kap_cap)
        m = _law(kind, p0, p1, p2, p3, tab, s)
        if m < 0.0:
            return False
        dmu = (m - mu) / (wn[k] if wn[k] > 0.0 else 1.0)
        cx += dmu * wx[k] * gw[k]
        cy += dmu * wy[k] * gw[k]
    out[0] = res[0] - weight * cx
    out[1] = res[1] - weight * cy
    out[2] = res[2]
    out[3] = res[3]
    out[4] = res[4]
    out[5] = mu
    inf = math.inf
    return -inf < out[0] < inf and -inf < out[1] < inf
