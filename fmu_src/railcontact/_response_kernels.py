"""Compiled step of the corrugation effect from the table ``corrugation_response`` (numba).

Internal module of :mod:`railcontact.effects.response_table`. One call evaluates the table's
spline at every harmonic's ``(a0/L, r_a0)`` and superposes the harmonics' contributions to the
half-width, the patch shift, the tangential force and the wear depth, as
:func:`railcontact.corrugation.corrugated_contact` (method "linear") and
:func:`railcontact.wear.corrugated_wear_depth` (model "material_point") do with the closed-form
coefficients (Nielsen 1998, Eqs. (4.36)-(4.71), (4.94)-(4.95)). In real arithmetic, with
``z = (Z_A + i Z_B) e^{-i k x} = z_r + i z_i`` and the coefficients ``c_a = hw``,
``c_Delta = i ps``, ``c_T = tr + i ti``, ``w = wr + i wi``, each term is ``Re(c z)``.

The table and the harmonics travel in three flat arrays (a compiled call pays for each array
argument; :func:`railcontact.effects.response_table.pack_table` and
:func:`~railcontact.effects.response_table.pack_harmonics` make them), so that one FMU step
makes one call with four arrays. Compiled ahead of time by the FMU build with the table kernels
(:data:`railcontact._compiled.EXPORTS`).
"""

from __future__ import annotations

import math

from numba import njit

from . import _numba_cache  # noqa: F401  (numba's cache in a user cache directory)
from ._spline_kernels import tensor_eval

__all__ = ["superposed_response"]

_HEADER = 5          # ibuf: ndim, nvar, ncoef, ncomb, nknots (see response_table.pack_table)


@njit(cache=True, fastmath=False)
def superposed_response(fbuf, ibuf, harm, a0, x, r, out):
    """Sums over the harmonics of the linearised corrugation response, from the table.

    ``out[0]``: ``sum hw k R z_r`` (half-width change [m]); ``out[1]``: ``-sum ps k R z_i``
    (patch shift [m]); ``out[2]``: ``sum (tr z_r - ti z_i)`` (force change, times mu / C
    [N/m]); ``out[3]``: ``sum (wr z_r - wi z_i)`` (wear change, times K mu^2 N / a0). ``a0``
    [m], ``x`` rail position [m], ``r`` = a0*/a0 [-]. Returns False, with ``out`` untouched,
    when a point is outside the bounds packed with the table (or NaN): then the caller uses
    the closed forms.
    """
    ndim = ibuf[0]
    nvar = ibuf[1]
    ncoef = ibuf[2]
    ncomb = ibuf[3]
    nknots = ibuf[4]
    p = _HEADER
    shape = ibuf[p:p + ndim]
    knot_start = ibuf[p + ndim:p + 2 * ndim]
    strides = ibuf[p + 2 * ndim:p + 3 * ndim]
    offset = ibuf[p + 3 * ndim:p + 3 * ndim + ncomb]
    deriv = ibuf[p + 3 * ndim + ncomb:p + 4 * ndim + ncomb]
    cols = ibuf[p + 4 * ndim + ncomb:p + 4 * ndim + ncomb + 6]
    coef = fbuf[:nvar * ncoef].reshape((nvar, ncoef))
    knots = fbuf[nvar * ncoef:nvar * ncoef + nknots]
    nwork = 4 ** ndim + 40
    work = fbuf[nvar * ncoef + nknots:nvar * ncoef + nknots + nwork]
    q = nvar * ncoef + nknots + nwork
    lo = fbuf[q]
    hi = fbuf[q + 1]
    r_lo = fbuf[q + 2]
    r_hi = fbuf[q + 3]
    n = harm.shape[0] // (7 + nvar)
    if not (r_lo <= r <= r_hi):
        return False
    pts = harm[5 * n:7 * n].reshape((n, 2))
    for i in range(n):
        ratio = a0 / harm[4 * n + i]
        if not (lo <= ratio <= hi):
            return False
        pts[i, 0] = ratio
        pts[i, 1] = r
    rows = harm[7 * n:7 * n + n * nvar].reshape((n, nvar))
    tensor_eval(coef, shape, knots, knot_start, strides, offset, pts, deriv, rows, work)
    sa = 0.0
    sd = 0.0
    st = 0.0
    sw = 0.0
    for i in range(n):
        kx = harm[i] * x
        ckx = math.cos(kx)
        skx = math.sin(kx)
        za = harm[2 * n + i]
        zb = harm[3 * n + i]
        z_r = za * ckx + zb * skx
        z_i = zb * ckx - za * skx
        kr = harm[n + i]
        sa += rows[i, cols[0]] * kr * z_r
        sd -= rows[i, cols[1]] * kr * z_i
        st += rows[i, cols[2]] * z_r - rows[i, cols[3]] * z_i
        sw += rows[i, cols[4]] * z_r - rows[i, cols[5]] * z_i
    out[0] = sa
    out[1] = sd
    out[2] = st
    out[3] = sw
    return True
