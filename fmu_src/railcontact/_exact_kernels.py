"""The compiled kernels of the exact-theory creep table (numba): one source for the scalar (FMU)
path and the vectorised path of :class:`railcontact.exact_table.ExactCreepTable`.

Internal module; the reader reaches these through :mod:`railcontact._compiled`, which uses the
ahead-of-time compiled copies an FMU build makes (no numba import in the FMU's table scenes)
and these otherwise. The coordinates and the buffer layout are those of
:mod:`railcontact.exact_table` (its module docstring).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit, prange

from . import _numba_cache  # noqa: F401  (the user cache, before any njit is compiled)
from ._spline_kernels import find_span
from .creep_common import JACOBIAN_RHO_MIN, SPIN_WEIGHT

_TWO_OVER_PI = 2.0 / math.pi

__all__ = ["buffer_views", "saturation_creepage", "table_coordinates", "table_views",
           "kalker_coefficients", "cubic_basis",
           "spline_point", "creep_contact", "creep_contact_force",
           "creep_table_point", "creep_table_force", "creep_table_batch",
           "creep_table_batch_parallel",
           "creep_contact_batch",
           "creep_contact_batch_parallel", "creep_batch", "creep_batch_parallel",
           "PARALLEL_CHUNK", "HEAD", "TABLE_HEAD"]

#: Points per task of the parallel batch kernels (each task has its own scratch); the reader
#: takes them for batches of at least two tasks.
PARALLEL_CHUNK = 4096


@njit(cache=True)
def cubic_basis(t, i, x, b, db, w):
    """The four non-zero cubic B-splines at ``x`` in span ``i`` into ``b`` and their first
    derivatives into ``db`` (Cox-de Boor; The NURBS Book, Algs. A2.2/A2.3); ``w`` (12,) is
    scratch."""
    # w[0:4] left, w[4:8] right, w[8:11] the degree-2 basis (for the derivative)
    b[0] = 1.0
    for j in range(1, 4):
        w[j] = x - t[i + 1 - j]
        w[4 + j] = t[i + j] - x
        saved = 0.0
        for r in range(j):
            temp = b[r] / (w[5 + r] + w[j - r])
            b[r] = saved + w[5 + r] * temp
            saved = w[j - r] * temp
        b[j] = saved
        if j == 2:
            w[8] = b[0]
            w[9] = b[1]
            w[10] = b[2]
    # d/dx N_{i-3+r,3} = 3 (N_{i-3+r,2} / (t[i+r] - t[i-3+r]) - N_{i-2+r,2} / (t[i+r+1] - t[i-2+r]))
    for r in range(4):
        d = 0.0
        if r >= 1:
            d += w[7 + r] / (t[i + r] - t[i - 3 + r])
        if r <= 2:
            d -= w[8 + r] / (t[i + r + 1] - t[i - 2 + r])
        db[r] = 3.0 * d


@njit(cache=True, inline="always")
def _poly_basis(t, poly, i, x, b, db):
    """The four non-zero cubic B-splines at ``x`` in span ``i`` and their derivatives, from
    the span's power-form coefficients ``poly[i]`` (see :func:`railcontact.exact_table.basis_polynomials`): Horner in
    ``u = x - t[i]``, no division."""
    u = x - t[i]
    for r in range(4):
        p0 = poly[i, r, 0]
        p1 = poly[i, r, 1]
        p2 = poly[i, r, 2]
        p3 = poly[i, r, 3]
        b[r] = ((p3 * u + p2) * u + p1) * u + p0
        db[r] = (3.0 * p3 * u + 2.0 * p2) * u + p1


@njit(cache=True, inline="always")
def _accumulate(src, b2, d2, b3, d3, b4, d4, derivs, n_var, out):
    """``out`` (4, 4) <- value and d/ds, d/dtheta, d/dtau (rows) of the first ``n_var``
    variables (columns) from the 4 x 4 x 4 coefficient block ``src`` (s, theta, tau,
    variable) and the bases; only the value row when not ``derivs``."""
    for k in range(4):
        for v in range(4):
            out[k, v] = 0.0
    for a in range(4):
        for c in range(4):
            w23 = b2[a] * b3[c]
            if derivs:
                w2d = d2[a] * b3[c]
                w3d = b2[a] * d3[c]
                for v in range(n_var):
                    s_e = 0.0
                    ds_e = 0.0
                    for e in range(4):
                        x = src[a, c, e, v]
                        s_e += b4[e] * x
                        ds_e += d4[e] * x
                    out[0, v] += w23 * s_e
                    out[1, v] += w2d * s_e
                    out[2, v] += w3d * s_e
                    out[3, v] += w23 * ds_e
            else:
                for v in range(n_var):
                    s_e = 0.0
                    for e in range(4):
                        s_e += b4[e] * src[a, c, e, v]
                    out[0, v] += w23 * s_e


@njit(cache=True, inline="always")
def _contact_bases(t2, t3, t4, p2, p3, p4, x2, x3, x4, work):
    """The spans ``i2, i3, i4`` of (s, theta, tau) and their bases and derivatives ``b2, d2,
    b3, d3, b4, d4`` (views of ``work[12:36]``)."""
    b2 = work[12:16]
    d2 = work[16:20]
    b3 = work[20:24]
    d3 = work[24:28]
    b4 = work[28:32]
    d4 = work[32:36]
    i2 = find_span(t2, t2.shape[0] - 4, x2)
    i3 = find_span(t3, t3.shape[0] - 4, x3)
    i4 = find_span(t4, t4.shape[0] - 4, x4)
    _poly_basis(t2, p2, i2, x2, b2, d2)
    _poly_basis(t3, p3, i3, x3, b3, d3)
    _poly_basis(t4, p4, i4, x4, b4, d4)
    return i2, i3, i4, b2, d2, b3, d3, b4, d4


@njit(cache=True, inline="always")
def _slab_point(slab, t2, t3, t4, p2, p3, p4, x2, x3, x4, derivs, n_var, out, work):
    """:func:`spline_point` on one contact's ``slab`` (n2, n3, n4, 4), for the first
    ``n_var`` variables: ``out`` as there."""
    i2, i3, i4, b2, d2, b3, d3, b4, d4 = _contact_bases(t2, t3, t4, p2, p3, p4, x2, x3, x4,
                                                        work)
    _accumulate(slab[i2 - 3:i2 + 1, i3 - 3:i3 + 1, i4 - 3:i4 + 1], b2, d2, b3, d3, b4, d4,
                derivs, n_var, out)


@njit(cache=True, inline="always")
def spline_point(coef, slab, use_slab, t0, t1, t2, t3, t4, p0, p1, p2, p3, p4, x0, x1, x2,
                  x3, x4, derivs, out, work, n_var=4):
    """Values and (``derivs``) first partials in (s, theta, tau) of the four variables at one
    point.

    ``coef`` (n0, n1, n2, n3, n4, 4): the file's coefficients, variable last (or, with
    n1 = 1, already summed over the nu axis at the contact's nu: 4 x 64 instead of 16 x 64
    products per variable; ``t1``, ``x1`` are then not read); ``slab``
    (n2, n3, n4, 4): the coefficients already summed over (ln g, nu) for one contact (used
    when ``use_slab``; then ``coef``, ``t0``, ``t1``, ``x0``, ``x1`` are not read); ``t0`` ..
    ``t4`` the knot vectors, ``p0`` .. ``p4`` their :func:`railcontact.exact_table.basis_polynomials`. ``out`` (4, 4):
    rows value, d/ds, d/dtheta, d/dtau. ``work``: scratch of at least 320 floats. Only the
    first ``n_var`` variables (columns) are summed.
    """
    if use_slab:
        _slab_point(slab, t2, t3, t4, p2, p3, p4, x2, x3, x4, derivs, n_var, out, work)
        return
    _any_point(coef, t0, t1, t2, t3, t4, p0, p1, p2, p3, p4, x0, x1, x2, x3, x4, derivs, out,
               work, n_var)


@njit(cache=True, inline="always")
def _basis_at(t, poly, x, work, o):
    """The span ``i`` of ``x`` on the knots ``t`` (returned), the four non-zero cubic B-splines
    at ``x`` into ``work[o:o + 4]`` and their derivatives into ``work[o + 4:o + 8]``: as
    :func:`_poly_basis`, written by index (a view of ``work`` per point costs two atomic
    reference counts)."""
    i = find_span(t, t.shape[0] - 4, x)
    u = x - t[i]
    for r in range(4):
        p0 = poly[i, r, 0]
        p1 = poly[i, r, 1]
        p2 = poly[i, r, 2]
        p3 = poly[i, r, 3]
        work[o + r] = ((p3 * u + p2) * u + p1) * u + p0
        work[o + 4 + r] = (3.0 * p3 * u + 2.0 * p2) * u + p1
    return i


@njit(cache=True, inline="always")
def _column_sums(coef, i0, i1, n_q, j2, j3, j4, v, work):
    """``sum_(p, q) b0[p] b1[q] coef[i0 - 3 + p, i1 - 3 + q, j2, j3, j4 + e, v + k]`` for e =
    0..3 (the four values of each k = 0, 1: ``(r0, r1, r2, r3, q0, q1, q2, q3)``), the a0/b0
    (and nu) axes contracted in registers; ``b0``, ``b1`` in ``work[36:40]``, ``work[44:48]``
    (:func:`_any_point`). Summed in the order (p, q) from 0.0, as a scratch block was."""
    r0 = 0.0
    r1 = 0.0
    r2 = 0.0
    r3 = 0.0
    q0 = 0.0
    q1 = 0.0
    q2 = 0.0
    q3 = 0.0
    for p in range(4):
        j0 = i0 - 3 + p
        for q in range(n_q):
            w = work[36 + p] * work[44 + q]
            k = i1 - 3 + q
            r0 += w * coef[j0, k, j2, j3, j4, v]
            q0 += w * coef[j0, k, j2, j3, j4, v + 1]
            r1 += w * coef[j0, k, j2, j3, j4 + 1, v]
            q1 += w * coef[j0, k, j2, j3, j4 + 1, v + 1]
            r2 += w * coef[j0, k, j2, j3, j4 + 2, v]
            q2 += w * coef[j0, k, j2, j3, j4 + 2, v + 1]
            r3 += w * coef[j0, k, j2, j3, j4 + 3, v]
            q3 += w * coef[j0, k, j2, j3, j4 + 3, v + 1]
    return r0, r1, r2, r3, q0, q1, q2, q3


@njit(cache=True, inline="always")
def _any_point(coef, t0, t1, t2, t3, t4, p0, p1, p2, p3, p4, x0, x1, x2, x3, x4, derivs, out,
               work, n_var):
    """:func:`spline_point` on the five-dimensional coefficients (or those summed over nu):
    for each (s, theta) pair of the 4 x 4 support the 4 (tau) x 2 (variables) coefficients
    contracted over the a0/b0 (and nu) axes in registers (:func:`_column_sums`), then with the
    tau bases: no scratch block, no views. Bases in ``work[12:52]`` (b at o, derivative at
    o + 4; o = 12, 20, 28 for s, theta, tau, 36, 44 for a0/b0, nu). The same products, summed
    in the same order, as the scratch block and :func:`_accumulate` did (the same bits)."""
    i2 = _basis_at(t2, p2, x2, work, 12)
    i3 = _basis_at(t3, p3, x3, work, 20)
    i4 = _basis_at(t4, p4, x4, work, 28)
    i0 = _basis_at(t0, p0, x0, work, 36)
    if coef.shape[1] == 1:  # the coefficients already summed over nu at the contact's nu
        work[44] = 1.0      # (ExactCreepTable.prepare): the one "span" weighs 1
        _contract(coef, i0, 3, 1, i2, i3, i4, derivs, n_var, out, work)
    else:
        i1 = _basis_at(t1, p1, x1, work, 44)
        # n_q = 4 (a cubic axis has at least 4 coefficients) as a run-time value: the (p, q)
        # loop unrolled 16-fold made the kernels take minutes more to compile
        _contract(coef, i0, i1, min(coef.shape[1], 4), i2, i3, i4, derivs, n_var, out, work)


@njit(cache=True, inline="always")
def _contract(coef, i0, i1, n_q, i2, i3, i4, derivs, n_var, out, work):
    """``out`` of :func:`_any_point` from the spans and the bases in ``work`` (``n_q`` 1, a
    constant there, or 4)."""
    for k in range(4):
        for v in range(4):
            out[k, v] = 0.0
    for a in range(4):
        for c in range(4):
            w23 = work[12 + a] * work[20 + c]
            w2d = work[16 + a] * work[20 + c]
            w3d = work[12 + a] * work[24 + c]
            for v in range(0, n_var, 2):     # two variables at a time (the pair shares lines)
                r0, r1, r2, r3, q0, q1, q2, q3 = _column_sums(
                    coef, i0, i1, n_q, i2 - 3 + a, i3 - 3 + c, i4 - 3, v, work)
                s_e = 0.0
                s_e += work[28] * r0
                s_e += work[29] * r1
                s_e += work[30] * r2
                s_e += work[31] * r3
                t_e = 0.0
                t_e += work[28] * q0
                t_e += work[29] * q1
                t_e += work[30] * q2
                t_e += work[31] * q3
                pair = v + 1 < n_var
                out[0, v] += w23 * s_e
                if pair:
                    out[0, v + 1] += w23 * t_e
                if derivs:
                    ds_e = 0.0
                    ds_e += work[32] * r0
                    ds_e += work[33] * r1
                    ds_e += work[34] * r2
                    ds_e += work[35] * r3
                    out[1, v] += w2d * s_e
                    out[2, v] += w3d * s_e
                    out[3, v] += w23 * ds_e
                    if pair:
                        dt_e = 0.0
                        dt_e += work[32] * q0
                        dt_e += work[33] * q1
                        dt_e += work[34] * q2
                        dt_e += work[35] * q3
                        out[1, v + 1] += w2d * t_e
                        out[2, v + 1] += w3d * t_e
                        out[3, v + 1] += w23 * dt_e


@njit(cache=True, inline="always")
def _table_coordinates(xi_x, xi_y, phi, a0, b0, w_sat, c11, c22, c23):
    """The table's coordinates of one contact (:mod:`railcontact.exact_table`, as
    :func:`railcontact.exact_table.exact_table_coordinates`): ``(sqrt(a0 b0), h, v_x, v_y,
    tau, rho, w2, w, s, theta)`` with ``h = hypot(b0 C11, a0 C22)`` [m], the normalised
    creepage ``v`` and its modulus ``rho`` [-], the spin coordinate ``tau`` [-], ``w2 = 1 +
    (SPIN_WEIGHT tau)^2``, ``w = sqrt(w2)``, ``s = (2 / pi) atan(rho / w)`` and ``theta``, the
    direction of ``v`` [rad]."""
    root_ab = math.sqrt(a0 * b0)
    h = math.hypot(b0 * c11, a0 * c22)
    v_x = c11 * xi_x / w_sat
    v_y = (c22 * xi_y + root_ab * c23 * phi) / w_sat
    tau = phi * h / w_sat
    rho = math.hypot(v_x, v_y)
    w2 = 1.0 + (SPIN_WEIGHT * tau) ** 2
    w = math.sqrt(w2)
    s = 1.0 if rho > 1e150 else _TWO_OVER_PI * math.atan(rho / w)
    theta = math.atan2(v_y, v_x)
    return root_ab, h, v_x, v_y, tau, rho, w2, w, s, theta


@njit(cache=True, inline="always")
def _wheel_forces(f_par, f_perp, rho, tau, s, v_x, v_y, theta, mu_n):
    """The creep force on the wheel ``(tx, ty)`` [N] from the table's force over mu N along
    and across the creepage direction (``f_par``, ``f_perp``), and what the Jacobian reuses:
    ``(tx, ty, f_par, f_perp, |f|, at_limit, k, cos theta, sin theta)``, ``k`` the scale that
    keeps |T| <= mu N."""
    if rho == 0.0 and tau == 0.0:
        # no creepage, no spin: no force (nor moment, and full adhesion: the caller); the
        # table's float32 coefficients hold these only to their rounding
        f_par = 0.0
        f_perp = 0.0
    mag = math.hypot(f_par, f_perp)
    # |T| <= mu N; at s = 1 (full sliding) |T| = mu N exactly, which the float32 coefficients
    # hold only to their rounding
    at_limit = s >= 1.0 and mag > 0.0
    k = (1.0 - 2.0**-51) / mag if (mag > 1.0 or at_limit) else 1.0
    if 0.0 < rho < math.inf:   # cos, sin of theta = atan2(v_y, v_x) without the calls
        c = v_x / rho
        sn = v_y / rho
    else:   # (at rho = 0 the signed zeros decide theta = 0 or pi)
        c = math.cos(theta)
        sn = math.sin(theta)
    return (-mu_n * k * (f_par * c - f_perp * sn), -mu_n * k * (f_par * sn + f_perp * c),
            f_par, f_perp, mag, at_limit, k, c, sn)


@njit(cache=True, inline="always")
def _creep_point(coef, slab, use_slab, t0, t1, t2, t3, t4, p0, p1, p2, p3, p4, tau_max, xi_x,
                 xi_y, phi, mu_n, a0, b0, w_sat, c11, c22, c23, log_g, nu, want_jacobian, res,
                 work, n_var=4):
    """Forces, moment, stick fraction and their Jacobian at one contact, from the table.

    ``res`` (14,) <- tx [N], ty [N], mz [N m], stick fraction, |v|, then the (3, 3)
    d(tx, ty, mz)/d(xi_x, xi_y, phi) row by row (rows tx, ty, mz; columns xi_x, xi_y, phi).
    ``work``: scratch of at least 336 floats. Returns False when |tau| > tau_max (the caller
    falls back to the solver).
    """
    root_ab, h, v_x, v_y, tau, rho, w2, w, s, theta = _table_coordinates(
        xi_x, xi_y, phi, a0, b0, w_sat, c11, c22, c23)
    if not abs(tau) <= tau_max:
        return False
    out = work[320:336].reshape((4, 4))
    small = want_jacobian and rho < JACOBIAN_RHO_MIN
    spline_point(coef, slab, use_slab, t0, t1, t2, t3, t4, p0, p1, p2, p3, p4, log_g, nu, s,
                  theta, tau, want_jacobian and not small, out, work,
                  4 if want_jacobian else n_var)
    moment = out[0, 2]
    st = out[0, 3]
    if rho == 0.0 and tau == 0.0:   # (see _wheel_forces)
        moment = 0.0
        st = 1.0
    res[0], res[1], f_par, f_perp, mag, at_limit, k, c, sn = _wheel_forces(
        out[0, 0], out[0, 1], rho, tau, s, v_x, v_y, theta, mu_n)
    res[2] = mu_n * root_ab * moment
    res[3] = 0.0 if st < 0.0 else (1.0 if st > 1.0 else st)
    res[4] = rho
    if not want_jacobian:
        return True
    if small:
        _origin_jacobian(coef, slab, use_slab, t0, t1, t2, t3, t4, p0, p1, p2, p3, p4, log_g,
                         nu, w, tau, c11, c22, c23, h, root_ab, w_sat, mu_n, res, out, work)
        return True
    # Cartesian force over mu N and its partials in (s, theta, tau)
    fx_s = -(out[1, 0] * c - out[1, 1] * sn)
    fy_s = -(out[1, 0] * sn + out[1, 1] * c)
    fx_t = -(out[2, 0] * c - f_par * sn - out[2, 1] * sn - f_perp * c)
    fy_t = -(out[2, 0] * sn + f_par * c + out[2, 1] * c - f_perp * sn)
    fx_u = -(out[3, 0] * c - out[3, 1] * sn)
    fy_u = -(out[3, 0] * sn + out[3, 1] * c)
    if mag > 1.0 or at_limit:   # scaled: d(f / |f|) = (I - f^ f^T) df / |f|  (k = 1/|f|)
        fx = -(f_par * c - f_perp * sn) / mag
        fy = -(f_par * sn + f_perp * c) / mag
        dot = fx * fx_s + fy * fy_s
        fx_s, fy_s = fx_s - fx * dot, fy_s - fy * dot
        dot = fx * fx_t + fy * fy_t
        fx_t, fy_t = fx_t - fx * dot, fy_t - fy * dot
        dot = fx * fx_u + fy * fy_u
        fx_u, fy_u = fx_u - fx * dot, fy_u - fy * dot
    # s depends on tau too: d/dtau at fixed rho = d/dtau at fixed s + ds/dtau d/ds
    ds, ds_u = _s_partials(rho, w, w2, tau)
    fx_u += fx_s * ds_u
    fy_u += fy_s * ds_u
    # d/dv_x = cos ds/drho d/ds - sin/rho d/dtheta ; d/dv_y = sin ds/drho d/ds + cos/rho d/dtheta
    m_s, m_t, m_u = out[1, 2], out[2, 2], out[3, 2] + out[1, 2] * ds_u
    for j in range(3):
        dvx = c11 / w_sat if j == 0 else 0.0
        dvy = 0.0 if j == 0 else (c22 / w_sat if j == 1 else root_ab * c23 / w_sat)
        dtu = h / w_sat if j == 2 else 0.0
        gs = (c * dvx + sn * dvy) * ds         # ds-part weight
        gt = (-sn * dvx + c * dvy) / rho       # dtheta-part weight
        res[5 + j] = mu_n * k * (fx_s * gs + fx_t * gt + fx_u * dtu)
        res[8 + j] = mu_n * k * (fy_s * gs + fy_t * gt + fy_u * dtu)
        res[11 + j] = mu_n * root_ab * (m_s * gs + m_t * gt + m_u * dtu)
    return True


@njit(cache=True, inline="always")
def _s_partials(rho, w, w2, tau):
    """``(ds/drho, ds/dtau at fixed rho)`` of the creepage coordinate ``s = (2 / pi) atan(rho /
    w)``, ``w = sqrt(w2)``, ``w2 = 1 + (SPIN_WEIGHT tau)^2``: ``(2 / pi) w / (w2 + rho^2)`` and
    ``-(2 / pi) rho / (w2 + rho^2) dw/dtau``; both 0 at rho = inf (s = 1)."""
    q = 0.0 if rho > 1e150 else _TWO_OVER_PI / (w2 + rho * rho)
    return q * w, -q * rho * SPIN_WEIGHT**2 * tau / w


@njit(cache=True)
def _origin_jacobian(coef, slab, use_slab, t0, t1, t2, t3, t4, p0, p1, p2, p3, p4, log_g, nu,
                     w, tau, c11, c22, c23, h, root_ab, w_sat, mu_n, res, out, work):
    """``res[5:14]`` <- the Jacobian within |v| < JACOBIAN_RHO_MIN of v = 0 (where the polar
    coordinates divide by |v|), in Cartesian form: the column of v_x from the radial
    derivative along theta = 0, that of v_y from the radial derivative along theta = pi/2, the
    spin's from the latter and d/dtau, each at |v| = JACOBIAN_RHO_MIN. (The angle derivative
    there, which the polar formula would use for the column across the direction of v,
    divides the node values' rounding and the solver's tolerance at the smallest s by
    JACOBIAN_RHO_MIN; with angle nodes 3.75 degrees apart that moved C23 at a0/b0 = 10 by
    0.2 %, and the Jacobian at v = 0 depended on the sign of a zero.)"""
    rho = JACOBIAN_RHO_MIN
    s = _TWO_OVER_PI * math.atan(rho / w)
    ds, ds_u = _s_partials(rho, w, w * w, tau)
    # along e_x (theta = 0): T/(mu N) = -(f_par, f_perp)
    spline_point(coef, slab, use_slab, t0, t1, t2, t3, t4, p0, p1, p2, p3, p4, log_g, nu, s,
                 0.0, tau, True, out, work)
    fx = -out[0, 0]
    fy = -out[0, 1]
    ax_x = -out[1, 0] * ds           # d(T_x, T_y, m)/dv_x
    ay_x = -out[1, 1] * ds
    am_x = out[1, 2] * ds
    ux = -(out[3, 0] + out[1, 0] * ds_u)   # d/dtau at fixed v (the average of both rays)
    uy = -(out[3, 1] + out[1, 1] * ds_u)
    um = out[3, 2] + out[1, 2] * ds_u
    # along e_y (theta = pi/2): T/(mu N) = -(-f_perp, f_par)
    spline_point(coef, slab, use_slab, t0, t1, t2, t3, t4, p0, p1, p2, p3, p4, log_g, nu, s,
                 0.5 * math.pi, tau, True, out, work)
    ax_y = out[1, 1] * ds            # d(T_x, T_y, m)/dv_y
    ay_y = -out[1, 0] * ds
    am_y = out[1, 2] * ds
    ux = 0.5 * (ux + out[3, 1] + out[1, 1] * ds_u)
    uy = 0.5 * (uy - out[3, 0] - out[1, 0] * ds_u)
    um = 0.5 * (um + out[3, 2] + out[1, 2] * ds_u)
    mag = math.hypot(fx, fy)
    if mag > 1.0:    # scaled to mu N: d(f / |f|) = (I - f^ f^T) df / |f|
        fx /= mag
        fy /= mag
        dot = fx * ax_x + fy * ay_x
        ax_x, ay_x = (ax_x - fx * dot) / mag, (ay_x - fy * dot) / mag
        dot = fx * ax_y + fy * ay_y
        ax_y, ay_y = (ax_y - fx * dot) / mag, (ay_y - fy * dot) / mag
        dot = fx * ux + fy * uy
        ux, uy = (ux - fx * dot) / mag, (uy - fy * dot) / mag
    dvx = c11 / w_sat
    dvy = c22 / w_sat
    dvp = root_ab * c23 / w_sat      # dv_y/dphi
    dtu = h / w_sat                  # dtau/dphi
    res[5] = mu_n * ax_x * dvx
    res[6] = mu_n * ax_y * dvy
    res[7] = mu_n * (ax_y * dvp + ux * dtu)
    res[8] = mu_n * ay_x * dvx
    res[9] = mu_n * ay_y * dvy
    res[10] = mu_n * (ay_y * dvp + uy * dtu)
    res[11] = mu_n * root_ab * am_x * dvx
    res[12] = mu_n * root_ab * am_y * dvy
    res[13] = mu_n * root_ab * (am_y * dvp + um * dtu)


#: Header of a contact buffer (see :func:`creep_contact`): n_s, n_theta, n_tau, tau_max,
#: C11, C22, C23, nu, then the knots of s, theta, tau, their basis polynomials, the slab, res
#: (14) and scratch (336).
HEAD = 8
_NO_COEF = np.zeros((1, 1, 1, 1, 1, 1))    # the 5-D coefficients, unused on the slab path
_NO_KNOTS = np.zeros(1)
_NO_POLY = np.zeros((1, 4, 4))


@njit(cache=True, inline="always")
def _knots_at(buf, o, n):
    """The knot vector of an axis of ``n`` coefficients at offset ``o`` of a buffer, and the
    offset after it."""
    return buf[o:o + n + 4], o + n + 4


@njit(cache=True, inline="always")
def _polys_at(buf, o, n):
    """The basis polynomials (n, 4, 4) of an axis of ``n`` coefficients at offset ``o`` of a
    buffer, and the offset after them."""
    return buf[o:o + n * 16].reshape((n, 4, 4)), o + n * 16


@njit(cache=True, inline="always")
def _buffer_views(buf):
    """Views into a contact buffer: (t2, t3, t4, p2, p3, p4, slab, res, work)."""
    n2 = int(buf[0])
    n3 = int(buf[1])
    n4 = int(buf[2])
    t2, o = _knots_at(buf, HEAD, n2)
    t3, o = _knots_at(buf, o, n3)
    t4, o = _knots_at(buf, o, n4)
    p2, o = _polys_at(buf, o, n2)
    p3, o = _polys_at(buf, o, n3)
    p4, o = _polys_at(buf, o, n4)
    slab = buf[o:o + n2 * n3 * n4 * 4].reshape((n2, n3, n4, 4))
    o += n2 * n3 * n4 * 4
    return t2, t3, t4, p2, p3, p4, slab, buf[o:o + 14], buf[o + 14:o + 14 + 336]


@njit(cache=True, inline="always")
def _saturation_creepage(xi_x, xi_y, phi, normal_load, a0, b0, youngs_modulus,
                         friction_coefficient, nu):
    """``w_sat = pi^2 (1 + nu) mu p0 / E`` [-] of one contact, or 0 where the inputs are not
    finite or out of range, or it under- or overflows (the caller takes the array path)."""
    inf = math.inf
    if not (-inf < xi_x < inf and -inf < xi_y < inf and -inf < phi < inf
            and 0.0 < normal_load < inf and 0.0 < a0 < inf and 0.0 < b0 < inf
            and 0.0 < youngs_modulus < inf and 0.0 < friction_coefficient < inf):
        return 0.0
    mu_n = friction_coefficient * normal_load
    den = a0 * b0 * youngs_modulus
    if not (0.0 < den < inf and mu_n < inf):   # underflow or overflow: the array path
        return 0.0
    w_sat = 1.5 * math.pi * (1.0 + nu) * mu_n / den
    return w_sat if 0.0 < w_sat < inf else 0.0


@njit(cache=True, inline="always")
def _finite_forces(res):
    """Whether tx, ty and mz in ``res`` are finite (else the caller takes the array path)."""
    inf = math.inf
    return -inf < res[0] < inf and -inf < res[1] < inf and -inf < res[2] < inf


@njit(cache=True, inline="always")
def _contact_point(buf, t2, t3, t4, p2, p3, p4, slab, xi_x, xi_y, phi, normal_load, a0, b0,
                   youngs_modulus, friction_coefficient, want_jacobian, res, work):
    """Checks, the saturation creepage and :func:`_creep_point` at one point of the contact
    in ``buf``; False where the caller takes the array path (inputs not finite or out of
    range, overflow, |tau| beyond the table)."""
    nu = buf[7]
    w_sat = _saturation_creepage(xi_x, xi_y, phi, normal_load, a0, b0, youngs_modulus,
                                 friction_coefficient, nu)
    if w_sat == 0.0:
        return False
    done = _creep_point(_NO_COEF, slab, True, _NO_KNOTS, _NO_KNOTS, t2, t3, t4, _NO_POLY,
                        _NO_POLY, p2, p3, p4, buf[3], xi_x, xi_y, phi,
                        friction_coefficient * normal_load, a0, b0, w_sat, buf[4], buf[5],
                        buf[6], 0.0, nu, want_jacobian, res, work)
    return done and _finite_forces(res)


@njit(cache=True)
def creep_contact(buf, xi_x, xi_y, phi, normal_load, a0, b0, youngs_modulus,
                   friction_coefficient, want_jacobian):
    """The scalar (FMU) path in one call on one contact's buffer ``buf`` (everything the
    contact needs in one array: a numba call costs about 0.1 us per array argument). Writes
    ``res`` inside ``buf``; see :func:`_contact_point`."""
    t2, t3, t4, p2, p3, p4, slab, res, work = _buffer_views(buf)
    return _contact_point(buf, t2, t3, t4, p2, p3, p4, slab, xi_x, xi_y, phi, normal_load, a0,
                          b0, youngs_modulus, friction_coefficient, want_jacobian, res, work)


@njit(cache=True)
def creep_contact_force(buf, xi_x, xi_y, phi, normal_load, a0, b0, youngs_modulus,
                        friction_coefficient):
    """The creep force ``(tx, ty)`` [N] of :func:`creep_contact` alone, returned (the public
    scalar call's path: only the two forces are summed, no Jacobian, and the tuple saves
    reading ``res``). Raises ArithmeticError where :func:`creep_contact` returns False (the
    caller takes the array path)."""
    t2, t3, t4, p2, p3, p4, slab, _, work = _buffer_views(buf)
    nu = buf[7]
    w_sat = _saturation_creepage(xi_x, xi_y, phi, normal_load, a0, b0, youngs_modulus,
                                 friction_coefficient, nu)
    if w_sat == 0.0:
        raise ArithmeticError("creep_contact_force: the array path")
    root_ab, h, v_x, v_y, tau, rho, w2, w, s, theta = _table_coordinates(
        xi_x, xi_y, phi, a0, b0, w_sat, buf[4], buf[5], buf[6])
    if not abs(tau) <= buf[3]:
        raise ArithmeticError("creep_contact_force: the array path")
    out = work[320:336].reshape((4, 4))
    _slab_point(slab, t2, t3, t4, p2, p3, p4, s, theta, tau, False, 2, out, work)
    tx, ty = _wheel_forces(out[0, 0], out[0, 1], rho, tau, s, v_x, v_y, theta,
                           friction_coefficient * normal_load)[:2]
    inf = math.inf
    if not (-inf < tx < inf and -inf < ty < inf):
        raise ArithmeticError("creep_contact_force: the array path")
    return tx, ty


#: Header of a table buffer (see :func:`creep_table_point`): the coefficient counts n0 .. n4
#: of the five axes, tau_max, the a0/b0 axis's ends in ln(a0/b0), the count m of the
#: breakpoints of Kalker's interpolant and its three nodes in nu; then the knots of the five
#: axes, their basis polynomials, the interpolant's breakpoints (m) and coefficients
#: (4 (m - 1) 9), res (14) and scratch (336).
TABLE_HEAD = 12
_NO_SLAB = np.zeros((1, 1, 1, 4))


@njit(cache=True, inline="always")
def _kalker_coefficients(kx, kc, nu_nodes, log_g, nu):
    """Kalker's ``(C11, C22, C23)`` within his table's a0/b0 range, from the
    interpolant of :func:`railcontact.kalker.kalker_coefficients` (its ``_table_log``):
    ``1 / C_k = sum_j L_j(nu) exp(-S_kj(ln g))``, ``S_kj`` the not-a-knot cubic spline of
    ln C_kj at nu_j as scipy's CubicSpline holds it (breakpoints ``kx``, coefficients ``kc``
    (4, m - 1, 3, 3), highest power first), ``L_j`` the quadratic Lagrange weights on
    ``nu_nodes``. (The same data and form: the tests check it against kalker_coefficients.)"""
    m = kx.shape[0]
    lo = 0
    hi = m - 2
    while lo < hi:      # the last breakpoint <= log_g (scipy's interval, clipped to the ends)
        mid = (lo + hi + 1) // 2
        if kx[mid] <= log_g:
            lo = mid
        else:
            hi = mid - 1
    d = log_g - kx[lo]
    n0 = nu_nodes[0]
    n1 = nu_nodes[1]
    n2 = nu_nodes[2]
    l0 = (nu - n1) * (nu - n2) / ((n0 - n1) * (n0 - n2))
    l1 = (nu - n0) * (nu - n2) / ((n1 - n0) * (n1 - n2))
    l2 = (nu - n0) * (nu - n1) / ((n2 - n0) * (n2 - n1))
    return (1.0 / _kalker_sum(kc, lo, 0, d, l0, l1, l2),
            1.0 / _kalker_sum(kc, lo, 1, d, l0, l1, l2),
            1.0 / _kalker_sum(kc, lo, 2, d, l0, l1, l2))


@njit(cache=True, inline="always")
def _kalker_sum(kc, lo, k, d, l0, l1, l2):
    """``sum_j L_j(nu) exp(-S_kj(ln g))`` of :func:`_kalker_coefficients`."""
    u = 0.0
    for j in range(3):
        sp = ((kc[0, lo, k, j] * d + kc[1, lo, k, j]) * d + kc[2, lo, k, j]) * d \
            + kc[3, lo, k, j]
        lj = l0 if j == 0 else (l1 if j == 1 else l2)
        u += lj * math.exp(-sp)
    return u


@njit(cache=True, inline="always")
def _kalker_table_coefficients(kx, kc, nu_nodes, log_g, nu, out):
    """``out`` <- :func:`_kalker_coefficients` (the tests' entry)."""
    out[0], out[1], out[2] = _kalker_coefficients(kx, kc, nu_nodes, log_g, nu)


@njit(cache=True, inline="always")
def _table_views(tbuf):
    """Views into a table buffer: (t0 .. t4, p0 .. p4, kx, kc, nu_nodes, res, work)."""
    n0 = int(tbuf[0])
    n1 = int(tbuf[1])
    n2 = int(tbuf[2])
    n3 = int(tbuf[3])
    n4 = int(tbuf[4])
    m = int(tbuf[8])
    t0, o = _knots_at(tbuf, TABLE_HEAD, n0)
    t1, o = _knots_at(tbuf, o, n1)
    t2, o = _knots_at(tbuf, o, n2)
    t3, o = _knots_at(tbuf, o, n3)
    t4, o = _knots_at(tbuf, o, n4)
    p0, o = _polys_at(tbuf, o, n0)
    p1, o = _polys_at(tbuf, o, n1)
    p2, o = _polys_at(tbuf, o, n2)
    p3, o = _polys_at(tbuf, o, n3)
    p4, o = _polys_at(tbuf, o, n4)
    kx = tbuf[o:o + m]
    o += m
    kc = tbuf[o:o + 36 * (m - 1)].reshape((4, m - 1, 3, 3))
    o += 36 * (m - 1)
    return (t0, t1, t2, t3, t4, p0, p1, p2, p3, p4, kx, kc, tbuf[9:12], tbuf[o:o + 14],
            tbuf[o + 14:o + 14 + 336])


@njit(cache=True)
def creep_table_point(tbuf, coef, xi_x, xi_y, phi, normal_load, a0, b0, youngs_modulus,
                      poisson_ratio, friction_coefficient, want_jacobian):
    """The scalar path of any contact, without a contact buffer: the five-dimensional spline
    ``coef`` (n0, .., n4, 4) at one point, with Kalker's coefficients of a0/b0 and nu from
    their interpolant (:func:`_kalker_coefficients`); everything else the table needs
    is in ``tbuf`` (:data:`TABLE_HEAD`). ``coef`` may also be the coefficients summed over nu
    at ``poisson_ratio`` (float64, n1 = 1:
    :meth:`railcontact.exact_table.ExactCreepTable.prepare`), a quarter of the products. Writes ``res`` inside ``tbuf`` (as :func:`creep_contact`);
    False where the caller takes the array path (also a0/b0 beyond the table's axis, nu
    outside [0, 0.5])."""
    t0, t1, t2, t3, t4, p0, p1, p2, p3, p4, kx, kc, nu_nodes, res, work = _table_views(tbuf)
    return _table_point(t0, t1, t2, t3, t4, p0, p1, p2, p3, p4, kx, kc, nu_nodes, tbuf[5],
                        tbuf[6], tbuf[7], coef, xi_x, xi_y, phi, normal_load, a0, b0,
                        youngs_modulus, poisson_ratio, friction_coefficient, want_jacobian,
                        res, work)


@njit(cache=True, inline="always")
def _table_point(t0, t1, t2, t3, t4, p0, p1, p2, p3, p4, kx, kc, nu_nodes, tau_max, log_g_min,
                 log_g_max, coef, xi_x, xi_y, phi, normal_load, a0, b0, youngs_modulus,
                 poisson_ratio, friction_coefficient, want_jacobian, res, work, n_var=4):
    """:func:`creep_table_point` on unpacked views, results in ``res`` (14,); with
    ``n_var = 2`` (and no Jacobian) the forces only (the moment and stick fraction then 0)."""
    nu = poisson_ratio
    if not 0.0 <= nu <= 0.5:
        return False
    w_sat = _saturation_creepage(xi_x, xi_y, phi, normal_load, a0, b0, youngs_modulus,
                                 friction_coefficient, nu)
    if w_sat == 0.0:        # (also a0, b0 not positive finite numbers)
        return False
    log_g = math.log(a0 / b0)
    if not (log_g_min <= log_g <= log_g_max):
        return False
    c11, c22, c23 = _kalker_coefficients(kx, kc, nu_nodes, log_g, nu)
    done = _creep_point(coef, _NO_SLAB, False, t0, t1, t2, t3, t4, p0, p1, p2, p3, p4,
                        tau_max, xi_x, xi_y, phi, friction_coefficient * normal_load, a0, b0,
                        w_sat, c11, c22, c23, log_g, nu, want_jacobian, res, work, n_var)
    return done and _finite_forces(res)


@njit(cache=True)
def creep_table_force(tbuf, coef, xi_x, xi_y, phi, normal_load, a0, b0, youngs_modulus,
                      poisson_ratio, friction_coefficient):
    """The creep force ``(tx, ty)`` [N] of :func:`creep_table_point` alone, returned (the
    public scalar call's path for any contact, as :func:`creep_contact_force` is on a
    contact's buffer: only the two forces are summed). Raises ArithmeticError where
    :func:`creep_table_point` returns False (the caller takes the array path)."""
    t0, t1, t2, t3, t4, p0, p1, p2, p3, p4, kx, kc, nu_nodes, _, work = _table_views(tbuf)
    nu = poisson_ratio
    if not 0.0 <= nu <= 0.5:
        raise ArithmeticError("creep_table_force: the array path")
    w_sat = _saturation_creepage(xi_x, xi_y, phi, normal_load, a0, b0, youngs_modulus,
                                 friction_coefficient, nu)
    log_g = math.log(a0 / b0) if w_sat != 0.0 else 0.0
    if w_sat == 0.0 or not (tbuf[6] <= log_g <= tbuf[7]):
        raise ArithmeticError("creep_table_force: the array path")
    c11, c22, c23 = _kalker_coefficients(kx, kc, nu_nodes, log_g, nu)
    root_ab, h, v_x, v_y, tau, rho, w2, w, s, theta = _table_coordinates(
        xi_x, xi_y, phi, a0, b0, w_sat, c11, c22, c23)
    if not abs(tau) <= tbuf[5]:
        raise ArithmeticError("creep_table_force: the array path")
    out = work[320:336].reshape((4, 4))
    spline_point(coef, _NO_SLAB, False, t0, t1, t2, t3, t4, p0, p1, p2, p3, p4, log_g, nu, s,
                 theta, tau, False, out, work, 2)
    tx, ty = _wheel_forces(out[0, 0], out[0, 1], rho, tau, s, v_x, v_y, theta,
                           friction_coefficient * normal_load)[:2]
    inf = math.inf
    if not (-inf < tx < inf and -inf < ty < inf):
        raise ArithmeticError("creep_table_force: the array path")
    return tx, ty


@njit(cache=True, inline="always")
def _table_points(tbuf, coef, xi_x, xi_y, phi, normal_load, a0, b0, youngs_modulus,
                  poisson_ratio, friction_coefficient, want_jacobian, n_var, res, ok, lo, hi,
                  work):
    """:func:`creep_table_point` at the points ``lo`` .. ``hi - 1`` (every input an array).
    The forces alone (no Jacobian, ``n_var`` 2: the public call's arrays) have their own copy
    of the loop with the flags constant in it: as run-time values they kept the Jacobian's
    branches in the innermost loops, about a fifth more time per point. (A copy for each
    case made the kernels take minutes more to compile.)"""
    if not want_jacobian and n_var == 2:
        _table_loop(tbuf, coef, xi_x, xi_y, phi, normal_load, a0, b0, youngs_modulus,
                    poisson_ratio, friction_coefficient, False, 2, res, ok, lo, hi, work)
    else:
        _table_loop(tbuf, coef, xi_x, xi_y, phi, normal_load, a0, b0, youngs_modulus,
                    poisson_ratio, friction_coefficient, want_jacobian, n_var, res, ok, lo,
                    hi, work)


@njit(cache=True, inline="always")
def _table_loop(tbuf, coef, xi_x, xi_y, phi, normal_load, a0, b0, youngs_modulus,
                poisson_ratio, friction_coefficient, want_jacobian, n_var, res, ok, lo, hi,
                work):
    """The loop of :func:`_table_points`."""
    t0, t1, t2, t3, t4, p0, p1, p2, p3, p4, kx, kc, nu_nodes, _, _ = _table_views(tbuf)
    for i in range(lo, hi):
        ok[i] = _table_point(t0, t1, t2, t3, t4, p0, p1, p2, p3, p4, kx, kc, nu_nodes,
                             tbuf[5], tbuf[6], tbuf[7], coef, xi_x[i], xi_y[i], phi[i],
                             normal_load[i], a0[i], b0[i], youngs_modulus[i],
                             poisson_ratio[i], friction_coefficient[i], want_jacobian, res[i],
                             work, n_var)


@njit(cache=True)
def creep_table_batch(tbuf, coef, xi_x, xi_y, phi, normal_load, a0, b0, youngs_modulus,
                      poisson_ratio, friction_coefficient, want_jacobian, n_var, res, ok):
    """:func:`creep_table_point` over flat arrays, every point its own contact (a vehicle's
    contacts, a sweep over ellipses): ``res`` (n, 14), ``ok`` (n,) False where the caller
    takes its fallback; ``n_var`` 4, or 2 for the forces only (no Jacobian: the moment and
    stick fraction are then 0). No contact buffer, no Kalker coefficients from Python: the
    same kernel as the scalar path."""
    _table_points(tbuf, coef, xi_x, xi_y, phi, normal_load, a0, b0, youngs_modulus,
                  poisson_ratio, friction_coefficient, want_jacobian, n_var, res, ok, 0,
                  xi_x.shape[0], np.empty(336))


@njit(cache=True, parallel=True)
def creep_table_batch_parallel(tbuf, coef, xi_x, xi_y, phi, normal_load, a0, b0,
                               youngs_modulus, poisson_ratio, friction_coefficient,
                               want_jacobian, n_var, res, ok):
    """:func:`creep_table_batch` on numba's threads (see :func:`creep_contact_batch_parallel`)."""
    n = xi_x.shape[0]
    for c in prange((n + PARALLEL_CHUNK - 1) // PARALLEL_CHUNK):
        _table_points(tbuf, coef, xi_x, xi_y, phi, normal_load, a0, b0, youngs_modulus,
                      poisson_ratio, friction_coefficient, want_jacobian, n_var, res, ok,
                      c * PARALLEL_CHUNK, min(n, (c + 1) * PARALLEL_CHUNK), np.empty(336))


#: The kernels of any contact on the table summed over nu (float64:
#: :meth:`railcontact.exact_table.ExactCreepTable.prepare`): the same functions, under the
#: names their ahead-of-time copies for that coefficient type have
#: (:data:`railcontact._compiled.EXPORTS`).
creep_table_point_nu = creep_table_point
creep_table_force_nu = creep_table_force
creep_table_batch_nu = creep_table_batch
creep_table_batch_nu_parallel = creep_table_batch_parallel


@njit(cache=True, inline="always")
def _contact_points(buf, xi_x, xi_y, phi, normal_load, a0, b0, youngs_modulus,
                    friction_coefficient, want_jacobian, res, ok, lo, hi, work):
    """:func:`_contact_point` at the points ``lo`` .. ``hi - 1``."""
    t2, t3, t4, p2, p3, p4, slab, _, _ = _buffer_views(buf)
    for i in range(lo, hi):
        ok[i] = _contact_point(buf, t2, t3, t4, p2, p3, p4, slab, xi_x[i], xi_y[i], phi[i],
                               normal_load, a0, b0, youngs_modulus, friction_coefficient,
                               want_jacobian, res[i], work)


@njit(cache=True)
def creep_contact_batch(buf, xi_x, xi_y, phi, normal_load, a0, b0, youngs_modulus,
                        friction_coefficient, want_jacobian, res, ok):
    """:func:`creep_contact` over the creepages of one contact (flat arrays, any strides);
    ``res`` (n, 14)."""
    _contact_points(buf, xi_x, xi_y, phi, normal_load, a0, b0, youngs_modulus,
                    friction_coefficient, want_jacobian, res, ok, 0, xi_x.shape[0],
                    np.empty(336))


@njit(cache=True, parallel=True)
def creep_contact_batch_parallel(buf, xi_x, xi_y, phi, normal_load, a0, b0, youngs_modulus,
                                 friction_coefficient, want_jacobian, res, ok):
    """:func:`creep_contact_batch` on numba's threads, in tasks of :data:`PARALLEL_CHUNK`
    points with their own scratch (the contact buffer is only read). Not for concurrent calls
    from several Python threads (numba's default threading layer aborts then):
    :class:`railcontact.exact_table.ExactCreepTable` serialises its calls."""
    n = xi_x.shape[0]
    for c in prange((n + PARALLEL_CHUNK - 1) // PARALLEL_CHUNK):
        _contact_points(buf, xi_x, xi_y, phi, normal_load, a0, b0, youngs_modulus,
                        friction_coefficient, want_jacobian, res, ok, c * PARALLEL_CHUNK,
                        min(n, (c + 1) * PARALLEL_CHUNK), np.empty(336))


@njit(cache=True, inline="always")
def _creep_points(coef, slab, use_slab, knots, kstart, poly, tau_max, xi_x, xi_y, phi, mu_n,
                  a0, b0, w_sat, c11, c22, c23, log_g, nu, want_jacobian, res, ok, lo, hi,
                  work):
    """:func:`_creep_point` at the points ``lo`` .. ``hi - 1``."""
    t0 = knots[kstart[0]:kstart[1]]
    t1 = knots[kstart[1]:kstart[2]]
    t2 = knots[kstart[2]:kstart[3]]
    t3 = knots[kstart[3]:kstart[4]]
    t4 = knots[kstart[4]:]
    p0 = poly[kstart[0]:kstart[1] - 4]
    p1 = poly[kstart[1] - 4:kstart[2] - 8]
    p2 = poly[kstart[2] - 8:kstart[3] - 12]
    p3 = poly[kstart[3] - 12:kstart[4] - 16]
    p4 = poly[kstart[4] - 16:]
    for i in range(lo, hi):
        ok[i] = _creep_point(coef, slab, use_slab, t0, t1, t2, t3, t4, p0, p1, p2, p3, p4,
                             tau_max, xi_x[i], xi_y[i], phi[i], mu_n[i], a0[i], b0[i],
                             w_sat[i], c11[i], c22[i], c23[i], log_g[i], nu[i],
                             want_jacobian, res[i], work)


@njit(cache=True)
def creep_batch(coef, slab, use_slab, knots, kstart, poly, tau_max, xi_x, xi_y, phi, mu_n, a0,
                 b0, w_sat, c11, c22, c23, log_g, nu, want_jacobian, res, ok):
    """:func:`_creep_point` over flat arrays (the same kernel as the scalar path); ``poly``:
    the five axes' :func:`railcontact.exact_table.basis_polynomials` stacked (axis d from row
    ``kstart[d] - 4 d``); ``res`` (n, 14)."""
    _creep_points(coef, slab, use_slab, knots, kstart, poly, tau_max, xi_x, xi_y, phi, mu_n,
                  a0, b0, w_sat, c11, c22, c23, log_g, nu, want_jacobian, res, ok, 0,
                  xi_x.shape[0], np.empty(336))


@njit(cache=True, parallel=True)
def creep_batch_parallel(coef, slab, use_slab, knots, kstart, poly, tau_max, xi_x, xi_y, phi,
                         mu_n, a0, b0, w_sat, c11, c22, c23, log_g, nu, want_jacobian, res,
                         ok):
    """:func:`creep_batch` on numba's threads (see :func:`creep_contact_batch_parallel`)."""
    n = xi_x.shape[0]
    for c in prange((n + PARALLEL_CHUNK - 1) // PARALLEL_CHUNK):
        _creep_points(coef, slab, use_slab, knots, kstart, poly, tau_max, xi_x, xi_y, phi,
                      mu_n, a0, b0, w_sat, c11, c22, c23, log_g, nu, want_jacobian, res, ok,
                      c * PARALLEL_CHUNK, min(n, (c + 1) * PARALLEL_CHUNK), np.empty(336))


#: The views of a contact buffer (:func:`_buffer_views`), for compiled callers in other
#: modules (railcontact._falling_kernels).
buffer_views = _buffer_views
#: A contact's saturation creepage (:func:`_saturation_creepage`) and table coordinates
#: (:func:`_table_coordinates`), for the same callers (the falling-friction correction table).
saturation_creepage = _saturation_creepage
table_coordinates = _table_coordinates
#: The views of a table buffer (:func:`_table_views`) and Kalker's coefficients from their
#: interpolant (:func:`_kalker_coefficients`), for the falling kernel without a contact buffer
#: (:func:`railcontact._falling_kernels.falling_table_point`).
table_views = _table_views
kalker_coefficients = _kalker_coefficients
