"""The compiled Hertz ellipse for changing curvatures (numba): the kernel of
:func:`railcontact.effects.normal.unit_ellipses`.

Internal module; :mod:`railcontact._compiled` gives its ahead-of-time copy where a build made
one (an FMU's, a wheel's), else these numba functions (one source for both).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from . import _numba_cache  # noqa: F401  (numba's cache in a user cache directory)

__all__ = ["carlson_rd", "unit_ellipses_kernel"]

#: Relative tolerance r of Carlson's duplication (his bound on the error of the truncated
#: series; the round-off of the arithmetic is of the same order).
_RD_TOLERANCE = 1e-17
#: (r / 4)^(-1/6), Carlson (1995) Eq. (2.27) for R_D.
_RD_Q = (0.25 * _RD_TOLERANCE) ** (-1.0 / 6.0)


@njit(cache=True)
def carlson_rd(x, y, z):
    """Carlson's symmetric elliptic integral of the second kind R_D(x, y, z) (x, y >= 0, at
    most one of them 0, z > 0) by his duplication algorithm (B.C. Carlson, Numerical
    computation of real or complex elliptic integrals, Numer. Algorithms 10 (1995) 13-26,
    Sec. 2, Eqs. (2.26)-(2.29)): the same algorithm as ``scipy.special.elliprd`` (agreement to
    a few ulp, tests/test_fmu_vehicle.py)."""
    a0 = (x + y + 3.0 * z) / 5.0
    q = _RD_Q * max(abs(a0 - x), abs(a0 - y), abs(a0 - z))
    xm, ym, zm, am = x, y, z, a0
    total = 0.0
    scale = 1.0             # 4^-m
    while q * scale >= abs(am):
        sx, sy, sz = math.sqrt(xm), math.sqrt(ym), math.sqrt(zm)
        lam = sx * (sy + sz) + sy * sz
        total += scale / (sz * (zm + lam))
        scale *= 0.25
        xm = 0.25 * (xm + lam)
        ym = 0.25 * (ym + lam)
        zm = 0.25 * (zm + lam)
        am = 0.25 * (am + lam)
    xx = (a0 - x) * scale / am
    yy = (a0 - y) * scale / am
    zz = -(xx + yy) / 3.0
    xy = xx * yy
    z2 = zz * zz
    e2 = xy - 6.0 * z2
    e3 = (3.0 * xy - 8.0 * z2) * zz
    e4 = 3.0 * (xy - z2) * z2
    e5 = xy * z2 * zz
    series = (1.0 - 3.0 * e2 / 14.0 + e3 / 6.0 + 9.0 * e2 * e2 / 88.0 - 3.0 * e4 / 22.0
              - 9.0 * e2 * e3 / 52.0 + 3.0 * e5 / 26.0)
    return scale * series / (am * math.sqrt(am)) + 3.0 * total


@njit(cache=True)
def unit_ellipses_kernel(c_x, c_y, e_star, nodes, coefficients, out):
    """The Hertz ellipses at N = 1 N of the curvature pairs ``c_x``, ``c_y`` (> 0, finite,
    checked by the caller) into ``out`` (n, 3): a1, b1 [m], p1 [Pa]; the method of
    :func:`railcontact.effects.normal.unit_ellipses` (``nodes``, ``coefficients``: its inverse
    grid). Returns the number of pairs beyond the grid (a0/b0 beyond 1e6 either way), whose
    rows are left NaN for the caller."""
    beyond = 0
    last = nodes.shape[0] - 2
    for i in range(c_x.shape[0]):
        cx = c_x[i]
        cy = c_y[i]
        c_major = min(cx, cy)       # the smaller curvature: the major axis along it
        log_ratio = math.log(max(cx, cy) / c_major)
        if not log_ratio <= nodes[last + 1]:
            out[i, 0] = out[i, 1] = out[i, 2] = math.nan
            beyond += 1
            continue
        lo = 0                      # the interval: nodes[lo] <= log_ratio < nodes[lo + 1]
        hi = last + 1
        while hi - lo > 1:
            mid = (lo + hi) // 2
            if nodes[mid] <= log_ratio:
                lo = mid
            else:
                hi = mid
        c = coefficients[lo]
        t = (log_ratio - c[0]) * c[1]
        u = c[2] + t * (c[3] + t * (c[4] + t * c[5]))
        k2 = math.exp(2.0 * u)
        f = carlson_rd(0.0, 1.0, k2) / carlson_rd(0.0, k2, 1.0)
        u = u - (math.log(f) - log_ratio) * (c[6] + t * c[7])
        k = math.exp(u)
        c_max = np.cbrt(carlson_rd(0.0, k * k, 1.0) / (2.0 * math.pi * e_star * c_major))
        c_min = k * c_max
        if cy >= cx:                # the major axis along x
            a1, b1 = c_max, c_min
        else:
            a1, b1 = c_min, c_max
        out[i, 0] = a1
        out[i, 1] = b1
        out[i, 2] = 1.5 * (1.0 / (math.pi * a1 * b1))
    return beyond
