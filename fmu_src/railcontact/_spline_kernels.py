"""The compiled tensor-product cubic B-spline evaluator of the tables (numba).

Internal module of :mod:`railcontact.tables`, which imports it on the first evaluation of a
table (so that reading a table, or a table evaluated otherwise, needs no numba): the span search
:func:`find_span` (also used by :mod:`railcontact.exact_table`'s kernels), the basis functions
and their derivatives (The NURBS Book, Algorithm A2.3) and :func:`tensor_eval`, which evaluates
all variables of a table at many points.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from . import _numba_cache  # noqa: F401  (numba's cache in a user cache directory)

__all__ = ["SPLINE_DEGREE", "find_span", "tensor_eval"]

#: Degree of every table spline (cubic; the same as ``railcontact.tables.SPLINE_DEGREE``).
SPLINE_DEGREE = 3


@njit(cache=True)
def find_span(t, n_coef, x):
    """Index ``i`` with ``t[i] <= x < t[i+1]``, ``3 <= i <= n_coef - 1`` (x clamped to range)."""
    lo = np.int64(SPLINE_DEGREE)  # an int64, not a literal: numba.pycc types it strictly
    hi = n_coef  # t[n_coef] is the right end
    if x >= t[hi]:
        return hi - 1
    if x <= t[lo]:
        return lo
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if t[mid] <= x:
            lo = mid
        else:
            hi = mid
    return lo


@njit(cache=True)
def _basis_ders(t, span, x, nder, out, ndu, a, left, right):
    """Non-zero cubic basis functions and derivatives (The NURBS Book, Algorithm A2.3).

    ``out[k, j]`` is the k-th derivative of N_{span-3+j,3}(x), k <= nder <= 2. ``ndu`` (4, 4),
    ``a`` (2, 4), ``left``, ``right`` (4,) are work arrays.
    """
    p = SPLINE_DEGREE
    ndu[0, 0] = 1.0
    for j in range(1, p + 1):
        left[j] = x - t[span + 1 - j]
        right[j] = t[span + j] - x
        saved = 0.0
        for r in range(j):
            ndu[j, r] = right[r + 1] + left[j - r]
            temp = ndu[r, j - 1] / ndu[j, r]
            ndu[r, j] = saved + right[r + 1] * temp
            saved = left[j - r] * temp
        ndu[j, j] = saved
    for j in range(p + 1):
        out[0, j] = ndu[j, p]
    if nder == 0:
        return
    for r in range(p + 1):
        s1 = 0
        s2 = 1
        a[0, 0] = 1.0
        for k in range(1, nder + 1):
            d = 0.0
            rk = r - k
            pk = p - k
            if r >= k:
                a[s2, 0] = a[s1, 0] / ndu[pk + 1, rk]
                d = a[s2, 0] * ndu[rk, pk]
            j1 = 1 if rk >= -1 else -rk
            j2 = k - 1 if r - 1 <= pk else p - r
            for j in range(j1, j2 + 1):
                a[s2, j] = (a[s1, j] - a[s1, j - 1]) / ndu[pk + 1, rk + j]
                d += a[s2, j] * ndu[rk + j, pk]
            if r <= pk:
                a[s2, k] = -a[s1, k - 1] / ndu[pk + 1, r]
                d += a[s2, k] * ndu[r, pk]
            out[k, r] = d
            s1, s2 = s2, s1
    fac = float(p)
    for k in range(1, nder + 1):
        for j in range(p + 1):
            out[k, j] *= fac
        fac *= p - k


@njit(cache=True, fastmath=True)
def tensor_eval(coef, shape, knots, knot_start, strides, offset, points, deriv, out, work):
    """Evaluate a tensor-product cubic spline (all variables) at many points.

    coef : (n_var, prod(shape)) C-ordered coefficients (variable first); knots: all knot
    vectors concatenated, axis d starting at knot_start[d] (length shape[d] + 4); strides,
    offset from ``railcontact.tables._offsets``; points (n_pts, D); deriv (D,) derivative orders (0, 1 or
    2); out (n_pts, n_var); work: float scratch of length >= 4**D + 40.
    """
    ndim = shape.shape[0]
    nvar = coef.shape[0]
    p1 = SPLINE_DEGREE + 1
    ncomb = offset.shape[0]
    weight = work[:ncomb]
    tmp = work[ncomb:ncomb + 12].reshape((3, p1))
    ndu = work[ncomb + 12:ncomb + 28].reshape((p1, p1))
    wrk = work[ncomb + 28:ncomb + 36].reshape((2, p1))
    left = work[ncomb + 36:ncomb + 40]
    right = np.empty(p1)
    for ip in range(points.shape[0]):
        base = 0
        block = 1
        for d in range(ndim - 1, -1, -1):
            t = knots[knot_start[d]:knot_start[d] + shape[d] + p1]
            span = find_span(t, shape[d], points[ip, d])
            _basis_ders(t, span, points[ip, d], deriv[d], tmp, ndu, wrk, left, right)
            base += (span - SPLINE_DEGREE) * strides[d]
            if block == 1:
                for j in range(p1):
                    weight[j] = tmp[deriv[d], j]
            else:
                for j in range(p1 - 1, -1, -1):
                    bj = tmp[deriv[d], j]
                    for c in range(block):
                        weight[j * block + c] = bj * weight[c]
            block *= p1
        for v in range(nvar):
            cv = coef[v]
            acc = 0.0
            for c in range(ncomb):
                acc += weight[c] * cv[base + offset[c]]
            out[ip, v] = acc
