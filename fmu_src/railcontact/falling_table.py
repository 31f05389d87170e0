r"""Falling (slip-dependent) friction on the Coulomb exact table: the fast path of
``creep_force_3d(..., method="exact_table", friction_coefficient=law)``.

An approximation, measured against Kalker's exact theory with the same law
(``method="exact"``; ``benchmarks/bench_falling_friction_3d.py``, 150 random cases over a0/b0
0.2-5, nu 0-0.5, every creepage direction and size, spin coordinate |tau| 0-10,
mu_k/mu_0 0.3-1, kappa mu_0 p0 / G 0-2 of Eq. (5.16)): max error 0.90 % of mu_0 N without
spin, 0.93 % with |tau| <= 1, **5.4 % with |tau| > 1** (RMS 0.84 % over all; a second
sample, seed 12: 0.83, 0.83, 5.3 %), where the
target of 1 % is not met. Three steps, each one call of the Coulomb table
(:class:`railcontact.exact_table.ExactCreepTable`):

1. **Effective coefficient.** The table's Coulomb solution at mu_e gives the frictional power
   of steady rolling per rolling speed, ``P = |T_x xi_x + T_y xi_y + M_z phi|``, dissipated
   in the slip zone, whose load is taken as ``N (1 - A_stick)`` (the stick area fraction of
   the same solution). Its traction-weighted mean slip is ``s_m = P / (mu_e N (1 - A_stick))``.
   The slip is spread over the contact like the rigid slip ``|w(x, y)|``
   (``w = (xi_x - phi y, xi_y + phi x)``): ``s(x, y) = lambda |w(x, y)|`` with
   ``lambda = s_m / <|w|>``, ``<.>`` the Hertz-pressure-weighted mean over the ellipse. Then
   ``mu_e = <mu(lambda |w|)>``, a fixed point found by :data:`EFFECTIVE_MU_STEPS` steps,
   relaxed by 1/2 from the second (3, 4, 6 or 10 steps: max errors within 0.03 % of mu_0 N, so 3;
   the law at the mean slip instead, Jensen's inequality makes mu_e too low for a convex law
   where spin spreads the slip).
2. **Coulomb force there**: ``T_c(mu_e)`` from the table.
3. **Spread correction** for the spin: where friction varies over the contact, the parts with
   larger slip carry less traction: ``T = T_c(mu_e) - N (1 - A_stick)^2
   <(mu(lambda |w|) - mu_e) w / |w|>``, the full-sliding force of the varying part of mu,
   weighted by the sliding share squared (zero without spin, where |w| is uniform).

Limits (exact): Coulomb friction (a constant law) gives the Coulomb table; zero creepage
gives zero; in full sliding without spin |T| -> mu(|xi|) N. The means over the ellipse use
Gauss points (:data:`GAUSS_POINTS`: 5 radial Gauss-Legendre x 10 angular, weights
``(3/(2 pi)) sqrt(1 - r^2)``).

Speed: this numpy function takes any Python law (about 200 us per scalar call: four table
calls and some 60 numpy operations on the 50 Gauss points). For the package's laws (the
smooth law (5.16), Polach's) :func:`falling_friction_table_compiled` runs the same steps in
one compiled call (:mod:`railcontact._falling_kernels`); the two agree to round-off (1e-15 of
the force). Any other law runs the same compiled call on its :func:`law_table` (the law
evaluated once on 562 slips per law object and rolling speed, then linear between them, as
the exact solver takes a law: within 2e-4 of mu_0 N of the law itself). The public
``creep_force_3d`` with plain floats, one contact (``benchmarks/bench_falling_friction_3d.py``,
load 0.8): 12 us with a :class:`railcontact.friction.SmoothFriction`, 16 us with a
:class:`~railcontact.friction.PolachFriction`, 17 us with a function of the user's, against
2.5 us for the Coulomb table in the same run.

Also measured, not adopted (too slow for a table's call): the Coulomb table at mu_e plus the
difference between the exact solver with the law and with mu_e on one coarse grid
(``solve_rolling_3d``; its discretisation error largely cancels in the difference): over the
|tau| > 1 cases of the benchmark's first sample (seed 11) max 1.84 % of mu_0 N at 12 x 8
elements, 1.17 % at 20 x 12, 0.99 % at 24 x 16, against 5.4 % here, at milliseconds per call.
The same first-order correction with the exact Coulomb solution's own slip field (directions
and sizes, 40 x 30 elements) still leaves up to 2 % on the worst cases: the error at large
spin is not only the rigid-slip proxy of this model but the elastic feedback of the changed
friction on the slip directions.

This is not Nielsen's or Kalker's method: it is this package's own cheap model, chosen among
the candidates of ``benchmarks/bench_falling_friction_3d.py`` (the law at the rigid slip,
Polach's approach: 8.3 %; a full-sliding ratio: 6.4 %; the effective coefficient alone:
8.1 %; the correction with (1 - A_stick) instead of its square: 5.4 % but 1.1 % at
|tau| <= 1).
"""

from __future__ import annotations

import numpy as np

__all__ = ["falling_friction_table", "falling_friction_table_smooth",
           "falling_friction_table_compiled", "law_table",
           "EFFECTIVE_MU_STEPS", "GAUSS_POINTS", "LAW_TABLE_SLIPS"]

#: Fixed-point steps for the effective friction coefficient (relaxed by 1/2 from the second).
EFFECTIVE_MU_STEPS = 3
#: The slip load share (1 - A_stick) is kept >= this (the first step from mu_0 may be all
#: stick, with no slip zone to dissipate in). [-]
SLIP_SHARE_MIN = 1e-3

# Gauss points over the unit disc: r Gauss-Legendre on [0, 1], theta midpoint rule, weights
# of the Hertz pressure (3 / (2 pi)) sqrt(1 - r^2) r dr dtheta, summing to 1.
#: Gauss points over the ellipse: radial (Gauss-Legendre) x angular (midpoint rule). 5 x 10:
#: as accurate as 8 x 16 against the exact theory (max errors within 0.15 % of mu_0 N on the
#: benchmark's 150 cases, 8 x 16 0.05 % worse with large spin), 2.5 times fewer points.
GAUSS_POINTS = (5, 10)
_R, _WR = np.polynomial.legendre.leggauss(GAUSS_POINTS[0])
_R, _WR = 0.5 * (_R + 1.0), 0.5 * _WR
_TH = 2.0 * np.pi * (np.arange(GAUSS_POINTS[1]) + 0.5) / GAUSS_POINTS[1]
_RR, _TT = np.meshgrid(_R, _TH, indexing="ij")
_W = ((_WR[:, None] * (2.0 * np.pi / GAUSS_POINTS[1])) * _RR * np.sqrt(1.0 - _RR**2)
      * 1.5 / np.pi).ravel()
_W = _W / _W.sum()
_CX, _SY = (_RR * np.cos(_TT)).ravel(), (_RR * np.sin(_TT)).ravel()


def _law_at(law_s, slip):
    mu = np.broadcast_to(np.asarray(law_s(slip), dtype=float), slip.shape)
    if not np.all(np.isfinite(mu) & (mu >= 0.0)):
        i = np.flatnonzero(~(np.isfinite(mu) & (mu >= 0.0)))[0]
        raise ValueError(f"friction_coefficient must give a finite mu >= 0 at every slip [-]; "
                         f"got mu = {mu.flat[i]:g} at slip {slip.flat[i]:g}")
    return mu


def falling_friction_table(values, xi_x, xi_y, phi, normal_load, a0, b0, law_s, mu0):
    """Force and moment with a friction law from a Coulomb table (module docstring).

    Parameters
    ----------
    values : callable
        ``values(mu) -> (tx, ty, mz, stick_area_fraction, normalised_creepage)`` of the
        Coulomb table at the friction coefficient ``mu`` (an array of the cases' shape, or a
        float for one case) [N, N, N m, -, -].
    xi_x, xi_y, phi, normal_load, a0, b0 : ndarray
        The checked inputs, broadcast to one shape ([-], [-], [1/m], [N], [m], [m]).
    law_s : callable
        ``mu(s)`` of the slip magnitude s [-] (a law in the slip velocity already multiplied
        by the rolling speed), taking arrays of the cases' shape plus one axis (the Gauss
        points). [-]
    mu0 : ndarray
        mu(0) per case, > 0. [-]

    Returns
    -------
    tuple of ndarray
        ``(tx, ty, mz, stick_area_fraction, normalised_creepage, mu_effective)``
        [N, N, N m, -, -, -]; all but the forces are the Coulomb table's at mu_effective (no
        spread correction).

    Raises
    ------
    ValueError
        If the law gives a negative or non-finite mu at a slip it is evaluated at.
    """
    xi_x, xi_y, phi, n_load, a0, b0, mu0 = (np.asarray(v, dtype=float) for v in (
        xi_x, xi_y, phi, normal_load, a0, b0, mu0))
    ex = (Ellipsis, None)
    # the rigid slip over its scale (every product O(1): no overflow for any finite input)
    scale = np.maximum(np.maximum(abs(xi_x), abs(xi_y)), abs(phi) * np.maximum(a0, b0))
    has_slip = (scale > 0.0) & (n_load > 0.0)
    scale = np.where(has_slip, scale, 1.0)
    rx, ry, rp = xi_x / scale, xi_y / scale, phi / scale
    wx = rx[ex] - rp[ex] * b0[ex] * _SY
    wy = ry[ex] + rp[ex] * a0[ex] * _CX
    wn = np.hypot(wx, wy)
    w_mean = wn @ _W
    has_slip = has_slip & (w_mean > 0.0)
    # 1 / (N <|w|>) (w over its scale) where there is slip, else 0 (the law at zero slip)
    inv = has_slip / np.where(has_slip, n_load * w_mean, 1.0)
    tiny = np.finfo(float).tiny
    s_cap = 0.5 * np.finfo(float).max / np.maximum(scale, 1.0)   # slips kept finite

    def slips(v, mu):
        """The modelled slip lambda |w(x, y)| [-] of the table's solution v at mu."""
        power = abs(v[0] * rx + v[1] * ry + v[2] * rp)     # frictional power / (V scale)
        share = np.minimum(np.maximum(1.0 - v[3], SLIP_SHARE_MIN), 1.0)   # (not np.clip: slow)
        lam = power * inv / (np.maximum(mu, tiny) * share)
        return np.minimum(lam[ex] * wn, s_cap[ex]) * scale[ex]

    mu = mu0
    for step in range(EFFECTIVE_MU_STEPS):
        new = np.asarray(law_s(slips(values(mu), mu)), dtype=float) @ _W
        mu = new if step == 0 else 0.5 * (mu + new)
    v = values(mu)
    mu_w = _law_at(law_s, slips(v, mu))         # checked: finite, >= 0 (so is mu, a mean)
    wn_safe = np.where(wn > 0.0, wn, 1.0)
    dmu = (mu_w - mu[ex]) / wn_safe             # (w = 0 has wx = wy = 0: no term)
    # (without spin |w| is uniform and the term is (mu(lambda |w|) - mu_e) along -w: what
    # the relaxed fixed point has left, weighted by the sliding share)
    slide = 1.0 - np.minimum(np.maximum(v[3], 0.0), 1.0)
    weight = has_slip * n_load * slide * slide
    tx = v[0] - weight * ((dmu * wx) @ _W)
    ty = v[1] - weight * ((dmu * wy) @ _W)
    if not (np.all(np.isfinite(tx)) and np.all(np.isfinite(ty)) and np.all(np.isfinite(mu))):
        raise ValueError("friction_coefficient must give a finite mu >= 0 at every slip [-]; "
                         "the falling-friction table path got a non-finite force")
    return tx, ty, v[2], v[3], v[4], mu


_OUT = np.zeros(6)
_KERNEL = [None]
_GAUSS = np.ascontiguousarray(np.stack([_CX, _SY, _W]))
_NO_LAW_TABLE = np.zeros((2, 1))

#: The slips a law other than the package's two is tabulated at for the compiled path
#: (:func:`law_table`): 0 and 1e-10 .. 1e4, 40 per decade (the exact solver's spacing,
#: :mod:`railcontact.reference.rolling3d`, over a wider range). A case whose slips go beyond
#: the last takes the numpy path, which evaluates the law itself. [-]
LAW_TABLE_SLIPS = np.concatenate([[0.0], np.logspace(-10.0, 4.0, 561)])


def law_table(law_s):
    """A friction law tabulated for the compiled fast path: rows :data:`LAW_TABLE_SLIPS` and
    ``law_s`` there (linear between them in the kernel, as the exact solver takes a law;
    against the law itself the fast path then differs by about 1e-4 of mu_0 N, far inside its
    own error, ``tests/test_falling_friction_3d.py``), or None where the law fails on them or
    gives a negative or non-finite mu (the numpy path then evaluates it and names the slip).

    Parameters
    ----------
    law_s : callable
        ``mu(s)`` of the slip s [-] (a law in the slip velocity already multiplied by the
        rolling speed), taking an array. [-]

    Returns
    -------
    ndarray of shape (2, 562) or None
        Slips [-] and mu [-].
    """
    try:
        mu = np.broadcast_to(np.asarray(law_s(LAW_TABLE_SLIPS), dtype=float),
                             LAW_TABLE_SLIPS.shape)
    except (TypeError, ValueError, ArithmeticError):
        return None
    if not (np.all(np.isfinite(mu)) and np.all(mu >= 0.0)):
        return None
    return np.ascontiguousarray(np.stack([LAW_TABLE_SLIPS, mu]))


def falling_friction_table_smooth(table, xi_x, xi_y, phi, normal_load, a0, b0, youngs_modulus,
                                  poisson_ratio, mu0, mu_k, kappa, eager=False):
    """One contact (plain floats, checked), the smooth law (5.16), compiled: see
    :func:`falling_friction_table_compiled` (``mu0, mu_k, kappa`` [-])."""
    return falling_friction_table_compiled(table, xi_x, xi_y, phi, normal_load, a0, b0,
                                           youngs_modulus, poisson_ratio, 0, mu0, mu_k, kappa,
                                           0.0, eager)


def falling_friction_table_compiled(table, xi_x, xi_y, phi, normal_load, a0, b0,
                                    youngs_modulus, poisson_ratio, kind, p0, p1, p2, p3,
                                    eager=False, tabulated=None):
    """One contact (plain floats, checked), a closed-form or tabulated law, compiled
    (:func:`railcontact._falling_kernels.falling_contact`: ``kind`` 0 the smooth law with
    ``(p0, p1, p2) = (mu_0, mu_k, kappa)``, 1 Polach's with ``(mu_0, A, B [s/m], V [m/s])``,
    2 the table ``tabulated`` of :func:`law_table` (None for the others) with ``p0`` = mu_0 and
    ``p1 .. p3`` 0):
    ``(tx, ty, mz, stick_area_fraction, normalised_creepage, mu_effective)`` as
    :func:`falling_friction_table`, or None where the table has no contact buffer for
    (a0/b0, nu) yet (its first points of a contact, a0/b0 beyond it) or hands the case to its
    array path: the caller then takes :func:`falling_friction_table`. ``table`` is a
    :class:`railcontact.exact_table.ExactCreepTable` (its contact buffers are read). The
    buffer of a new contact is made at once with ``eager`` (the FMU: some 10 ms once), else
    after the table's ski rental (its :data:`~railcontact.exact_table.SLAB_AFTER_POINTS`
    points, each call counting its ``EFFECTIVE_MU_STEPS + 1`` table points)."""
    key = (a0 / b0, poisson_ratio)
    entry = table._buffers.get(key)
    if entry is None:
        entry = table._buffer(*key) if eager else table._entry(key, EFFECTIVE_MU_STEPS + 1)
        if entry is None:
            return None
    kernel = _KERNEL[0]
    if kernel is None:     # (compiled ahead of time in a wheel or FMU; else numba's, imported
        from . import _compiled  # noqa: PLC0415                 on the first call only)
        kernel = _KERNEL[0] = _compiled.falling_contact()
    out = _OUT
    if not kernel(entry[0], xi_x, xi_y, phi, normal_load, a0, b0, youngs_modulus, kind, p0,
                  p1, p2, p3, _NO_LAW_TABLE if tabulated is None else tabulated, _GAUSS,
                  EFFECTIVE_MU_STEPS, SLIP_SHARE_MIN, out):
        return None
    return out[0], out[1], out[2], out[3], out[4], out[5]
