r"""Falling (slip-dependent) friction on the Coulomb exact table: the fast path of
``creep_force_3d(..., method="exact_table", friction_coefficient=law)``.

An approximation, measured against Kalker's exact theory with the same law
(``method="exact"``; ``benchmarks/bench_falling_friction_3d.py --n 150 --seeds 11-40``, random
cases over a0/b0 0.2-5, nu 0-0.5, every creepage direction and size, spin coordinate |tau|
0-10, mu_k/mu_0 0.3-1, kappa mu_0 p0 / G 0-2 of Eq. (5.16); 2026-11-29, with the blend with
spin of step 2, the table's s node 0.05, its ln(a0/b0) nodes 0.25 and 0.75 ln 5, the
ladder at its unconverged nodes of tau <= 5.5 and its theta nodes every 15 degrees, step 4):
of 4,491 cases 4,489 (99.96 %) are within issue 38's 1 % of mu_0 N; max 0.96 % without
spin, 1.00 % with |tau| <= 1, **1.02 % with |tau| > 1** (RMS 0.12 % over all; with theta
nodes 30 degrees apart 4,487 and 1.32 %; before the blend 4,477, max 0.96 / 0.96 / 2.20 %).
Twenty more samples (seeds 41-60, 2,992 cases): 2,991 within 1 %, max 0.93 / 0.70 / 1.08 %
(before the blend 2,987 of 2,991, 2.08 %). The three misses are at a strong law
(mu_k/mu_0 < 0.5, kappa number > 1.7), two beside the table's unconverged nodes. A sample
drawn where the stick zone collapses with spin under a strong law (``--region collapse --n
300 --seeds 101-102``: |tau| 1-2.5, mu_k/mu_0 0.3-0.8, kappa number 0.5-2; 591 cases): all
591 within 1 %, max 0.91 %, RMS 0.19 % (with theta nodes 30 degrees apart 589, 1.79 %,
0.23 %; before the blend 564 of 587, 2.55 %, 0.42 %): the exact force peaks just before the
stick zone collapses (tau near 1.4-1.5), and where and how high moves with every axis of the
table, along theta fastest (``benchmarks/diagnose_falling_misses.py``).
With Polach's law on its own correction table (since 2026-11-30: solved at every node, with
an s node of its own at 0.375 and a mu_k/mu_0 node of its own at 0.45, the ladder at its
unconverged nodes of tau 0-0.75, in part at tau 1-2.5 so far, the others filled; ``--law
polach``): seeds 11-20 (1,496 cases) all within 1 %, max 0.76 / 0.80 / 0.78 % without spin /
with |tau| <= 1 / beyond (RMS 0.13 %); seeds 21-40 (2,990) all, max 0.69 / 0.60 / 0.84 %;
seeds 41-50 (1,495) all, max 0.87 / 0.70 / 0.71 %; seeds 51-60 (1,497, drawn after the node
0.45 was chosen) all, max 0.61 / 0.55 / 0.93 % (RMS 0.12-0.13 % each). Without the node 0.45
(linear between 0.3 and 0.65, where the exact correction falls steeply just above 0.3 and is
nearly flat from 0.4 up) 7,474 of these 7,478 within 1 %, max 2.57 %, all four misses at
mu_k/mu_0 0.41-0.51 with large spin. On the table solved at |tau| <= 2.5 only (the smooth
law's beyond), seeds 11-20 and 21-40: 1,483 and 2,958 within 1 %, max 1.50 and 1.83 %;
before, on the smooth law's table (:func:`law_shape`): 1,473 and 2,932 within 1 %, max 1.80
and 2.31 %, RMS 0.28 and 0.30 % (before the blend 1,450 of 1,493 and 2.90 %). (Each sample
counts the cases ``method="exact"`` converges on: 9, 8, 9 and 4 of them do not, in the order
of the smooth law's samples above, and 5 and 3 of Polach's seeds 41-50 and 51-60; the
relaxed sweeps of :mod:`railcontact.reference.rolling3d` converge on 8 that had not.)
A model in three steps, each one call of the Coulomb table
(:class:`railcontact.exact_table.ExactCreepTable`), and a table of what the model misses:

1. **Effective coefficient.** The table's Coulomb solution at mu_e gives the frictional power
   of steady rolling per rolling speed, ``P = |T_x xi_x + T_y xi_y + M_z phi|``, dissipated
   in the slip zone, whose load is taken as ``N (1 - A_stick)`` (the stick area fraction of
   the same solution). Its traction-weighted mean slip is ``s_m = P / (mu_e N (1 - A_stick))``.
   The slip is spread over the contact like the rigid slip ``|w(x, y)|``
   (``w = (xi_x - phi y, xi_y + phi x)``): ``s(x, y) = lambda |w(x, y)|`` with
   ``lambda = s_m / <|w|>``, ``<.>`` the Hertz-pressure-weighted mean over the ellipse. Then
   ``mu_e = <mu(lambda |w|)>``, a fixed point found by :data:`EFFECTIVE_MU_STEPS` steps,
   relaxed by 1/2 from the second (with the correction table 1, 2 and 3 steps gave max errors
   0.70 / 1.17, 0.67 / 1.20 and 0.65 / 1.22 % of mu_0 N at |tau| > 1 on the two samples, and
   1 step 0.43 / 0.30 % without spin: so 2, three table calls in all; the law at the mean slip
   instead, Jensen's inequality makes mu_e too low for a convex law where spin spreads the
   slip). The table is called at :func:`table_mu` (mu kept above :func:`spin_floor`, its
   force and moment scaled back to mu), so that a low mu_e never takes the table's spin
   coordinate beyond its axis (where it would answer with the exact solver, 60-150 ms).
2. **Coulomb force there**: ``T_c(mu_e)`` from the table, blended with spin
   (:func:`spin_blend_weight`, weight ``b`` from 0 at the spin coordinate at mu_0
   ``|tau_0|`` <= 0.75 to 1 from 1.25, :data:`SPIN_BLEND`) with the Coulomb solution at mu_0
   scaled: ``(1 - b) T_c(mu_e) + b (mu_e / mu_0) T_c(mu_0)`` (the stick area fraction
   likewise). The exact theory's stick zone is bounded by the static coefficient mu_0: with
   large spin it collapses where the Coulomb solution at mu_0 collapses (near tau 1.5),
   where the solution at mu_e collapses at a spin coordinate mu_e / mu_0 as large; the
   difference to the exact theory (step 4's table) stepped by some 5 % of mu_0 N within 0.15
   of tau between the two (seed 31's case 29, a0/b0 2.5, tau 1.3: 2.2 % with the table,
   0.46 % with the blend). ``T_c(mu_0)`` is step 1's first table call: no call is added.
3. **Spread correction** for the spin: where friction varies over the contact, the parts with
   larger slip carry less traction: ``T = T_c(mu_e) - N (1 - A_stick)^2
   <(mu(lambda' |w|') - mu_e) w / |w|'>``, the full-sliding force of the varying part of mu,
   weighted by the sliding share squared (zero without spin, where |w| is uniform). Here
   ``|w|'`` is the rigid slip's magnitude smoothed over the spin pole
   (:data:`SPIN_POLE_SMOOTHING`) and ``lambda'`` keeps its mean slip that of step 1: the
   direction w / |w| turns over at the pole, and with a sharp pole the Gauss sum rippled as
   the pole moved between its points (0.7 % of mu_0 N between creepages 0.01 of the
   saturation apart), which no table of the model's error (step 4) can follow.
4. **Correction table** (:func:`load_falling_correction`, the package data
   ``railcontact/data/falling_correction.nc``, built by ``python -m
   tablegen.falling_correction build``): the exact theory with the smooth law minus steps
   1-3, tabulated on a grid of the exact table's coordinates at mu_0 (ln(a0/b0) at a0/b0
   0.2, 0.30, 0.45, 1, 1.50, 2.24, 3.34 and 5, nu 0, 0.25 and 0.5, the creepage coordinate s 9 nodes in
   [0, 1], the creepage angle every 15 degrees, tau 21 nodes in [0, 20], 0.75 in the blend
   of step 2 and every 0.125 in [1, 2] where spin's lateral force under a strong law rises
   steeply, mirrored to [-20, 20]) and of the law's
   two numbers (mu_k/mu_0 0.3, 0.65, 1; kappa mu_0 p0 / G 0, 0.125, 0.5, 1.125, 2): the
   forces over mu_0 N and the moment over mu_0 N sqrt(a0 b0). The nodes the exact solver's
   default grid does not converge on or the builder does not try (of the 30-degree nodes
   8,018 of 342,720, nearly all of the strongest law, mu_k/mu_0 0.3 with kappa number 2, at
   large spin): at tau <= 5.5 the exact theory on a ladder of coarser grids extrapolated to
   zero element size where at least 3 of them converge (5,319 nodes, flagged
   ``ladder_node`` in the file; ``tablegen.falling_correction.ladder_point``: within
   0.16-0.28 % of mu_0 N of the default grid where that converges), the others filled
   (:func:`_filled`; 4,183). The 15-degree nodes (2026-11-29) are solved; where the default
   grid did not converge at tau <= 5.5 (the ladder not run there yet) they hold the
   30-degree table's spline (6,168 nodes, flagged ``source_node``: a partial build,
   ``tablegen.falling_correction.build``). Interpolated by C2 cubic
   B-splines along the five axes a contact's state moves along in a simulation (no kink in
   the forces), linearly along nu and mu_k/mu_0 (a material's and a law's constants); held
   at the ends of each axis. **Polach's law** has a table of its own (since 2026-11-30,
   :data:`CORRECTION_FAMILIES`, ``railcontact/data/falling_correction_polach.nc``, built by
   ``python -m tablegen.falling_correction build --law polach``): the exact theory with
   Polach's ``mu_0 ((1 - A) exp(-B w) + A)`` at ``A`` = mu_k/mu_0 and ``B V`` = kappa (the
   same slope at zero slip) minus the model, solved at theta every 30 degrees and written
   on the smooth law's table (its difference to it, interpolated along theta onto the
   smooth table's 15-degree nodes, ``tablegen.falling_correction.on_base``; at its own s
   node 0.375, which the smooth table has not, that table's spline along s). The
   exponential falls
   faster than the smooth law's ``1 / (1 + kappa s)`` at the same slope: the smooth law's
   table taken for Polach's law (before; still where the package has no Polach table)
   missed by up to 2.3 % of mu_0 N over 4,486 random cases, and no choice of the smooth
   law's two numbers for it did better than 1.24 % even case by case (1,496 cases). Any
   other law is taken as the smooth law of :func:`law_shape`. Without the table the model's
   errors were 0.90 / 0.83 % without spin, 0.93 / 0.83 % with |tau| <= 1 and 5.44 / 5.34 %
   beyond (RMS 0.84 / 0.99 %; Polach's law 1.48 / 0.99, 1.35 / 1.29, 6.87 / 7.27 %): mostly
   where spin dominates and the stick zone shrinks (the model's rigid-slip spread puts the
   falling friction's effect at the front and back alike, where the exact slip sits at the
   rear: pure spin, a0/b0 = 3.5, tau = 2, mu_k/mu_0 0.76, kappa number 1.6: the exact
   lateral force is 1.4 % of mu_0 N above the Coulomb force at mu_0, the model's 3.8 % below
   it).

Limits (exact): Coulomb friction (a constant law) gives the Coulomb table (while the spin
coordinate |tau| <= 18.2, where :func:`table_mu` leaves mu as it is); zero creepage
gives zero; in full sliding without spin |T| -> mu(|xi|) N. The means over the ellipse use
Gauss points (:data:`GAUSS_POINTS`: 5 radial Gauss-Legendre x 10 angular, weights
``(3/(2 pi)) sqrt(1 - r^2)``).

Speed: this numpy function takes any Python law (about 200 us per scalar call: three table
calls and some 60 numpy operations on the 50 Gauss points). For the package's laws (the
smooth law (5.16), Polach's) :func:`falling_friction_table_compiled` runs the same steps in
one compiled call (:mod:`railcontact._falling_kernels`); the two agree to round-off (1e-15 of
the force). Any other law runs the same compiled call on its :func:`law_table` (the law
evaluated once on 562 slips per law object and rolling speed, then linear between them, as
the exact solver takes a law: within 2e-4 of mu_0 N of the law itself). The correction table
adds one compiled evaluation (its nu and mu_k/mu_0 axes summed out once per pair, and its
a0/b0 axis once a contact's a0/b0 has come back :data:`CORRECTION_AT_ASPECT_AFTER` times,
:func:`correction_at`: 4 x 4 x 4 x 4 (x 4) x 3 coefficients per call). The public
``creep_force_3d`` with plain floats, one contact (best of 7 rounds, 2026-11-28 evening,
``benchmarks/bench_falling_friction_3d.py``): 8.9 us with a
:class:`railcontact.friction.SmoothFriction`, 10.0 us with a
:class:`~railcontact.friction.PolachFriction`, 11.0 us with a function of the user's,
against 1.4 us for the Coulomb table in the same run (with 3 fixed-point steps and no spin
floor: 9.3, 10.2, 12.5 us). That is on the contact buffer of a contact whose a0/b0 stays; a
contact whose a0/b0 changes at every call (a vehicle's) takes the same steps on the table's
five-dimensional spline (:func:`railcontact._falling_kernels.falling_table_point`): 12.1 us
with a :class:`~railcontact.friction.SmoothFriction`, 12.8 us with a
:class:`~railcontact.friction.PolachFriction` on the table summed over nu, 17.0 / 17.6 us
before that sum is made (2026-11-29, night; the array path's 0.6 ms before that kernel).

Also measured, not adopted (too slow for a table's call): the Coulomb table at mu_e plus the
difference between the exact solver with the law and with mu_e on one coarse grid
(``solve_rolling_3d``; its discretisation error largely cancels in the difference): over the
|tau| > 1 cases of the benchmark's first sample (seed 11) max 1.84 % of mu_0 N at 12 x 8
elements, 1.17 % at 20 x 12, 0.99 % at 24 x 16, against 5.4 % for steps 1-3, at
milliseconds per call.
The same first-order correction with the exact Coulomb solution's own slip field (directions
and sizes, 40 x 30 elements) still leaves up to 2 % on the worst cases: the error at large
spin is not only the rigid-slip proxy of this model but the elastic feedback of the changed
friction on the slip directions.

Steps 1-3 are not Nielsen's or Kalker's method: they are this package's own cheap model
(and step 4 its table of the exact theory's difference to it), chosen among the candidates of
``benchmarks/bench_falling_friction_3d.py`` (the law at the rigid slip,
Polach's approach: 8.3 %; a full-sliding ratio: 6.4 %; the effective coefficient alone:
8.1 %; the correction with (1 - A_stick) instead of its square: 5.4 % but 1.1 % at
|tau| <= 1).
"""

from __future__ import annotations

import math
import warnings

import numpy as np

__all__ = ["falling_friction_table", "falling_friction_table_smooth", "spin_floor", "table_mu",
           "static_spin_coordinate", "spin_blend_weight", "SPIN_BLEND",
           "falling_friction_table_compiled", "kernel_model_arguments", "law_table", "law_shape",
           "load_falling_correction", "falling_correction", "CORRECTION_TABLE",
           "CORRECTION_FAMILIES", "CORRECTION_FILES", "law_family",
           "EFFECTIVE_MU_STEPS", "GAUSS_POINTS", "LAW_TABLE_SLIPS"]

#: Fixed-point steps for the effective friction coefficient (relaxed by 1/2 from the second).
EFFECTIVE_MU_STEPS = 2
#: Smoothing of the rigid slip over the spin pole in step 3 (the spread correction):
#: ``|w|`` taken as ``sqrt(|w|^2 + (d phi)^2 a0 b0)`` with d this number (a pole region of
#: some 0.3 of the semi-axes), its mean scaled back to that of ``|w|``. The direction
#: ``w / |w|`` turns over at the pole, where the slip of spin and creepage cancels; with the
#: 50 Gauss points a pole moving between them made the force ripple by up to 0.7 % of
#: mu_0 N between creepages 0.01 of the saturation apart (a0/b0 0.27, tau 1.7, mu_k/mu_0 0.3,
#: kappa number 1.7), a ripple no table of the model's error can follow; smoothed, 0.01 %.
#: 0 without spin (the rigid slip uniform: the limits unchanged). [-]
SPIN_POLE_SMOOTHING = 0.3
#: The model calls the Coulomb table at a spin coordinate at most this (:func:`spin_floor`):
#: the end of the shipped exact table's spin axis. [-]
SPIN_COORDINATE_EDGE = 20.0
#: Spin coordinates ``|tau_0|`` (at mu_0) between which the model's step 2 moves from the
#: Coulomb solution at mu_e to that at mu_0 scaled by mu_e / mu_0 (:func:`spin_blend_weight`).
#: The exact theory's stick zone is bounded by the static mu_0: with large spin it collapses
#: where the Coulomb solution at mu_0 collapses (near tau 1.5), the solution at mu_e at a spin
#: coordinate mu_e / mu_0 as large; the difference the correction table holds then stepped by
#: some 5 % of mu_0 N within 0.15 of tau (seed 31's case 29). Blended over [0.75, 1.25]:
#: 4,480 of 4,491 random cases within 1 % of mu_0 N, max 1.37 % (seeds 11-40), against
#: [0, 1] 4,482 / 1.51 %, [0.5, 1.125] 4,475 / 1.52 %, [0, 0.5] 4,439 / 2.11 %, no blend
#: 4,477 / 2.20 %, the solution at mu_0 alone (no blend, one effective-mu step) 4,479 /
#: 1.72 % (1.06 % without spin, where the solution at mu_e is within 0.96 %). [-]
SPIN_BLEND = (0.75, 1.25)
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


def falling_friction_table(values, xi_x, xi_y, phi, normal_load, a0, b0, law_s, mu0,
                           correction=None, material=None):
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
    correction : tuple of ndarray, optional
        ``(youngs_modulus, poisson_ratio, friction_ratio, kappa)`` [Pa, -, -, -] of the cases,
        and optionally the law family (:func:`law_family`, default ``"smooth"``): the
        correction table's value (:func:`falling_correction`) is added to the force and
        the moment. None: the model alone (what the correction table is built against).
    material : tuple of ndarray, optional
        ``(youngs_modulus, poisson_ratio)`` [Pa, -] of the cases, for the table's spin edge
        (:func:`spin_floor`); default those of ``correction``; neither: no floor.

    Returns
    -------
    tuple of ndarray
        ``(tx, ty, mz, stick_area_fraction, normalised_creepage, mu_effective)``
        [N, N, N m, -, -, -]; the stick area fraction and the normalised creepage are the
        Coulomb table's at mu_effective.

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

    def slips(v, mu, w=wn, factor=1.0):
        """The modelled slip lambda |w(x, y)| [-] of the table's solution v at mu (``w``
        the rigid slip's magnitude over its scale, ``factor`` times lambda)."""
        power = abs(v[0] * rx + v[1] * ry + v[2] * rp)     # frictional power / (V scale)
        share = np.minimum(np.maximum(1.0 - v[3], SLIP_SHARE_MIN), 1.0)   # (not np.clip: slow)
        lam = factor * power * inv / (np.maximum(mu, tiny) * share)
        return np.minimum(lam[ex] * w, s_cap[ex]) * scale[ex]

    if material is None and correction is not None:
        material = correction[:2]
    tau0 = (np.zeros_like(scale) if material is None else static_spin_coordinate(
        xi_x, xi_y, phi, n_load, a0, b0, *material, mu0))
    mu_f = 0.0 if material is None else _floor_at(tau0, mu0)

    def values_at(mu):      # the table at table_mu(mu), its force and moment scaled to mu
        mu_t = table_mu(mu, mu_f)
        v = values(mu_t)
        q = mu / mu_t
        return v[0] * q, v[1] * q, v[2] * q, v[3], v[4]

    mu = mu0
    for step in range(EFFECTIVE_MU_STEPS):
        v = values_at(mu)
        if step == 0:
            v_static = v        # the Coulomb solution at mu_0
        new = np.asarray(law_s(slips(v, mu)), dtype=float) @ _W
        mu = new if step == 0 else 0.5 * (mu + new)
    v = values_at(mu)
    # step 2's blend with spin: the Coulomb solution at mu_0 scaled by mu_e / mu_0
    # (its stick zone that of mu_0)
    blend = spin_blend_weight(tau0)
    q = blend * mu / np.where(mu0 > 0.0, mu0, 1.0)
    v = (v[0] * (1.0 - blend) + v_static[0] * q, v[1] * (1.0 - blend) + v_static[1] * q,
         v[2] * (1.0 - blend) + v_static[2] * q, v[3] * (1.0 - blend) + v_static[3] * blend,
         v[4])
    # step 3 on the rigid slip smoothed over the spin pole (SPIN_POLE_SMOOTHING), scaled to
    # the same mean slip
    eps2 = (SPIN_POLE_SMOOTHING * rp) ** 2 * (a0 * b0)
    w3 = np.sqrt(wx * wx + wy * wy + eps2[ex])
    w3_mean = w3 @ _W
    ratio = np.where(has_slip, w_mean / np.where(w3_mean > 0.0, w3_mean, 1.0), 0.0)
    mu_w = _law_at(law_s, slips(v, mu, w3, ratio))  # checked: finite, >= 0 (so is mu, a mean)
    w3_safe = np.where(w3 > 0.0, w3, 1.0)
    dmu = (mu_w - mu[ex]) / w3_safe             # (w3 = 0 has wx = wy = 0: no term)
    # (without spin |w| is uniform and the term is (mu(lambda |w|) - mu_e) along -w: what
    # the relaxed fixed point has left, weighted by the sliding share)
    slide = 1.0 - np.minimum(np.maximum(v[3], 0.0), 1.0)
    weight = has_slip * n_load * slide * slide
    tx = v[0] - weight * ((dmu * wx) @ _W)
    ty = v[1] - weight * ((dmu * wy) @ _W)
    mz = v[2]
    if correction is not None:
        d = falling_correction(xi_x, xi_y, phi, n_load, a0, b0, *correction[:2], mu0,
                               *correction[2:])
        on = has_slip
        tx, ty, mz = tx + on * d[0], ty + on * d[1], mz + on * d[2]
    if not (np.all(np.isfinite(tx)) and np.all(np.isfinite(ty)) and np.all(np.isfinite(mu))):
        raise ValueError("friction_coefficient must give a finite mu >= 0 at every slip [-]; "
                         "the falling-friction table path got a non-finite force")
    return tx, ty, mz, v[3], v[4], mu


def spin_floor(xi_x, xi_y, phi, normal_load, a0, b0, youngs_modulus, poisson_ratio, mu0):
    """The least friction coefficient the model calls the Coulomb table at: ``mu_0 |tau_0| /``
    :data:`SPIN_COORDINATE_EDGE` (less 1e-9: the table's spin coordinate ``tau = tau_0 mu_0 /
    mu``, ``tau_0`` at mu_0 (:func:`railcontact.exact_table.exact_table_coordinates`), then
    stays within its axis); 0 where ``|tau_0|`` is beyond the edge (beyond the table's own
    domain, where it answers with the exact solver) or there is no load. [-]

    A falling law's mu_e < mu_0 raises the spin coordinate: with mu_e = 0.3 mu_0 a contact
    at tau_0 = 7 is at tau = 23, beyond the Coulomb table's axis (20), where the table
    answers with the exact solver (60-150 ms a call: 2 or 3 cases in 150 of the benchmark's
    samples). Spin that large leaves little stick (the contact slides nearly all over, its
    force nearly proportional to mu), so the model calls the table at :func:`table_mu`
    instead and scales its force and moment by mu over that: within 0.02-3.6 % of mu_0 N of
    the exact Coulomb force at tau 22-45 (checked on 6 cases, the largest at small
    creepage), what the correction table (built on the same model) then takes up within
    |tau_0| <= 20.
    """
    return _floor_at(static_spin_coordinate(xi_x, xi_y, phi, normal_load, a0, b0,
                                            youngs_modulus, poisson_ratio, mu0), mu0)


def _floor_at(tau0, mu0):
    """:func:`spin_floor` of the spin coordinate at mu_0 ``tau0`` [-] and ``mu0`` [-]."""
    ok = tau0 <= SPIN_COORDINATE_EDGE * (1.0 + 1e-9)
    return np.where(ok, mu0 * tau0 / (SPIN_COORDINATE_EDGE * (1.0 - 1e-9)), 0.0)


def static_spin_coordinate(xi_x, xi_y, phi, normal_load, a0, b0, youngs_modulus, poisson_ratio,
                           mu0):
    """``|tau_0|``, the exact table's spin coordinate of the contact at the static
    coefficient mu_0 (:func:`railcontact.exact_table.exact_table_coordinates`); 0 where there
    is no load, a semi-axis, a modulus or mu_0 is not positive, or it is not finite. [-]"""
    xi_x, xi_y, phi, n_load, a0, b0, e_mod, nu, mu0 = np.broadcast_arrays(*(
        np.asarray(v, dtype=float) for v in (xi_x, xi_y, phi, normal_load, a0, b0,
                                             youngs_modulus, poisson_ratio, mu0)))
    ok = (n_load > 0.0) & (a0 > 0.0) & (b0 > 0.0) & (e_mod > 0.0) & (mu0 > 0.0)
    safe = [np.where(ok, v, 1.0) for v in (n_load, a0, b0, e_mod, mu0)]  # (0 where not ok)
    tau0 = np.abs(_coordinates_at(xi_x, xi_y, phi, *safe[:4], nu, safe[4])[3])
    return np.where(ok & np.isfinite(tau0), tau0, 0.0)


def spin_blend_weight(tau0):
    """The share of the Coulomb solution at mu_0 (scaled by mu_e / mu_0) in the model's step 2
    at the spin coordinate ``tau0`` = ``|tau_0|`` [-] (:func:`static_spin_coordinate`): 0 up
    to :data:`SPIN_BLEND`\\ [0], 1 from :data:`SPIN_BLEND`\\ [1], the quintic smoothstep
    ``t^3 (10 - 15 t + 6 t^2)`` between (C2: no kink in the forces). [-]"""
    lo, hi = SPIN_BLEND
    t = np.minimum(np.maximum((np.asarray(tau0, dtype=float) - lo) / (hi - lo), 0.0), 1.0)
    return t * t * t * (10.0 + t * (6.0 * t - 15.0))


def _coordinates_at(xi_x, xi_y, phi, normal_load, a0, b0, youngs_modulus, poisson_ratio,
                    mu0):
    """The exact table's coordinates at mu_0 (:func:`railcontact.exact_table.
    exact_table_coordinates`, Kalker's coefficients at (a0/b0, nu)) and the peak pressure:
    ``(ln(a0/b0), s, theta, tau, p_max)`` ([-], [-], [rad], [-], [Pa]); inputs > 0."""
    from .exact_table import exact_table_coordinates  # noqa: PLC0415
    from .kalker import kalker_coefficients  # noqa: PLC0415

    c = kalker_coefficients(a0 / b0, poisson_ratio)
    p_max = 1.5 * normal_load / (np.pi * a0 * b0)
    w_sat = np.pi**2 * (1.0 + poisson_ratio) * mu0 * p_max / youngs_modulus
    lg, _, s, theta, tau = exact_table_coordinates(
        xi_x, xi_y, phi, a0, b0, poisson_ratio, w_sat,
        tuple(np.asarray(getattr(c, k), dtype=float) for k in ("c11", "c22", "c23")))
    return lg, s, theta, tau, p_max


def table_mu(mu, mu_floor):
    """The coefficient the model calls the Coulomb table at: ``mu`` kept above ``f =
    mu_floor`` (:func:`spin_floor`) by a C2 smooth maximum: ``f h(mu / f)``, ``h(x) = x`` for
    x >= 1.1, 1 for x <= 0.9 and between them ``1 + 0.1 p((x - 1) / 0.1)``, ``p`` the integral
    of the smoothstep (``p(t) = 2 u^3 - u^4``, ``u = (t + 1) / 2``); mu where f = 0. So mu
    itself wherever mu >= 1.1 f: a law that does not fall (mu = mu_0) gives the Coulomb table
    exactly while ``|tau_0| <= SPIN_COORDINATE_EDGE / 1.1`` (18.2). [-]"""
    mu, f = np.asarray(mu, dtype=float), np.asarray(mu_floor, dtype=float)
    x = mu / np.where(f > 0.0, f, 1.0)
    u = np.minimum(np.maximum((x - 1.0) / (2.0 * TABLE_MU_BLEND) + 0.5, 0.0), 1.0)
    h = 1.0 + TABLE_MU_BLEND * (2.0 * u**3 - u**4)
    return np.where((f > 0.0) & (x < 1.0 + TABLE_MU_BLEND), f * h, mu)


#: Half-width of :func:`table_mu`'s blend, in units of the floor. [-]
TABLE_MU_BLEND = 0.1


#: Name of the correction table's file (``railcontact/data/falling_correction.nc``, built by
#: ``python -m tablegen.falling_correction build``).
CORRECTION_TABLE = "falling_correction"
#: Its axes (in the file's order) and variables.
CORRECTION_AXES = ("log_aspect_ratio", "poisson_ratio", "creepage_coordinate",
                   "creepage_angle", "spin_coordinate", "friction_ratio",
                   "friction_decay_number")
CORRECTION_VARIABLES = ("force_correction_longitudinal", "force_correction_lateral",
                        "spin_moment_correction")
#: The law families with a correction table of their own: the smooth law (5.16) and
#: Polach's exponential law (2005), each ``(mu_k / mu_0, kappa)`` with the same slope at zero
#: slip (:func:`law_shape`); every other law takes the smooth law's table.
CORRECTION_FAMILIES = ("smooth", "polach")
#: Their files' names (package data ``railcontact/data/<name>.nc``).
CORRECTION_FILES = {"smooth": CORRECTION_TABLE, "polach": CORRECTION_TABLE + "_polach"}
_CORRECTION = {}


def law_family(law):
    """The correction table's family of a friction law (:data:`CORRECTION_FAMILIES`):
    ``"polach"`` for a :class:`railcontact.friction.PolachFriction`, else ``"smooth"``."""
    from .friction import PolachFriction  # noqa: PLC0415

    return "polach" if type(law) is PolachFriction else "smooth"


def falling_correction(xi_x, xi_y, phi, normal_load, a0, b0, youngs_modulus, poisson_ratio,
                       mu0, friction_ratio, kappa, family="smooth"):
    """The correction table's force and moment (:func:`load_falling_correction`) for the
    smooth law (5.16) ``(mu0, friction_ratio mu0, kappa)`` (or the smooth law a law is taken
    as, :func:`law_shape`) on the given contacts: ``(dtx, dty, dmz)`` [N, N, N m], zero where
    there is no table or ``friction_ratio >= 1``.

    Parameters
    ----------
    xi_x, xi_y, phi, normal_load, a0, b0, youngs_modulus, poisson_ratio : array_like
        The checked inputs ([-], [-], [1/m], [N], [m], [m], [Pa], [-]).
    mu0, friction_ratio, kappa : array_like
        mu_0 [-], mu_k / mu_0 [-] and kappa [-] of the smooth law.
    family : str, optional
        The law family's table (:data:`CORRECTION_FAMILIES`, :func:`law_family`): with
        ``"polach"`` the three numbers are Polach's ``mu_0``, ``A`` and ``B V``.
    """
    from ._compiled import falling_correction_batch  # noqa: PLC0415

    args = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (
        xi_x, xi_y, phi, normal_load, a0, b0, youngs_modulus, poisson_ratio, mu0,
        friction_ratio, kappa)))
    shape = args[0].shape
    xi_x, xi_y, phi, n_load, a0, b0, e_mod, nu, mu0, ratio, kappa = (a.ravel() for a in args)
    corr = load_falling_correction(family=family)
    out = np.zeros((xi_x.size, 3))
    on = (ratio < 1.0) & (n_load > 0.0) & (mu0 > 0.0)
    if corr.size and on.any():
        i = np.flatnonzero(on)
        nu_i = nu[i]
        lg, s, theta, tau, p_max = _coordinates_at(xi_x[i], xi_y[i], phi[i], n_load[i], a0[i],
                                                   b0[i], e_mod[i], nu_i, mu0[i])
        kn = np.minimum(kappa[i], 1e300) * mu0[i] * p_max * 2.0 * (1.0 + nu_i) / e_mod[i]
        d = np.zeros((i.size, 3))
        falling_correction_batch()(corr, *(np.ascontiguousarray(v, dtype=float) for v in (
            lg, nu_i, s, theta, tau, ratio[i], kn)), d)
        mu_n = mu0[i] * n_load[i]
        out[i] = d * np.stack([mu_n, mu_n, mu_n * np.sqrt(a0[i] * b0[i])], axis=1)
    return tuple(out[:, k].reshape(shape) for k in range(3))


def law_shape(law, speed, law_s):
    """``(mu_k / mu_0, kappa)`` of the smooth law (5.16) the correction table takes for a law
    (as the compiled kernel's ``_law_shape``): a
    :class:`railcontact.friction.SmoothFriction`'s own; Polach's ``(A, B V)`` (the same slope
    at zero slip: over the benchmark's Polach sample at |tau| <= 1.5 this gave max errors
    0.87 / 0.68 % of mu_0 N on its two seeds, the same half-way slip (``kappa = B V / ln 2``)
    1.04 / 1.48 %, 0.8 B V 0.77 / 0.59 %); any other law's far-to-zero-slip ratio on
    :data:`LAW_TABLE_SLIPS` and ``kappa = 1 / s_half``, ``s_half`` the slip (linear between
    those slips) where mu is half-way between its value at 0 and at the last slip; ratio 1
    (no correction) for a law that does not fall.

    Parameters
    ----------
    law : callable
        The friction law object.
    speed : array_like or None
        Rolling speed where the law needs it. [m/s]
    law_s : callable
        The law in the slip, taking arrays of the cases' shape plus one axis. [-]

    Returns
    -------
    tuple of ndarray or float
    """
    from .friction import PolachFriction, SmoothFriction  # noqa: PLC0415

    if type(law) is SmoothFriction:
        return law.mu_kinetic / law.mu_static, law.kappa
    if type(law) is PolachFriction:
        return law.friction_ratio_limit, law.friction_decay * np.asarray(speed)
    mus = np.asarray(law_s(LAW_TABLE_SLIPS), dtype=float)
    mu0, far = mus[..., 0], mus[..., -1]
    half = 0.5 * (mu0 + far)
    below = mus <= half[..., None]
    i = np.maximum(np.argmax(below[..., 1:], axis=-1) + 1, 1)
    m_lo = np.take_along_axis(mus, (i - 1)[..., None], -1)[..., 0]
    m_hi = np.take_along_axis(mus, i[..., None], -1)[..., 0]
    with np.errstate(divide="ignore", invalid="ignore"):
        f = (m_lo - half) / (m_lo - m_hi)
        s_half = LAW_TABLE_SLIPS[i - 1] + f * (LAW_TABLE_SLIPS[i] - LAW_TABLE_SLIPS[i - 1])
        falls = (mu0 > 0.0) & (far < mu0) & below[..., 1:].any(axis=-1) & (s_half > 0.0)
        ratio = np.where(falls, far / np.where(mu0 > 0.0, mu0, 1.0), 1.0)
        kappa = np.where(falls, 1.0 / np.where(s_half > 0.0, s_half, 1.0), 0.0)
    return ratio, kappa


#: Length of a packed correction table's header (as
#: :data:`railcontact._falling_kernels.CORRECTION_HEADER`, which is numba's).
CORRECTION_HEADER = 7
_EMPTY = np.zeros(0)
_AT = {}
#: Correction tables kept by :func:`correction_at`: per nu, and per (nu, a0/b0).
CORRECTION_AT_KEPT = 16


#: Calls with one (nu, a0/b0) after which :func:`correction_at` sums out the a0/b0 axis too
#: for them (a ski rental: about 0.2 ms once, then a quarter of the work per call; a contact
#: whose a0/b0 changes at every call never pays it).
CORRECTION_AT_ASPECT_AFTER = 64
_SEEN = {}

#: Calls with one nu after which :func:`correction_at` sums out the nu axis for it (a ski
#: rental again: some 10 ms once, then a third of the work per call; a sweep over nu, one
#: call each, never pays it).
CORRECTION_AT_NU_AFTER = 16


def _at_key(family, poisson_ratio, aspect_ratio=None):
    """The key of :func:`correction_at`'s store for a family's table at nu (and a0/b0)."""
    tag = () if family == "smooth" else (family,)
    if aspect_ratio is None:
        return (*tag, poisson_ratio) if tag else poisson_ratio
    return (*tag, poisson_ratio, aspect_ratio)


def correction_at(poisson_ratio, friction_ratio, aspect_ratio=None, now=False,
                  family="smooth"):
    """The correction table at one nu (its nu axis summed out once the nu has been asked
    :data:`CORRECTION_AT_NU_AFTER` times, or at once with ``now``: a third of the numbers,
    kept for the last :data:`CORRECTION_AT_KEPT`; before, the whole table), packed as
    :func:`load_falling_correction`, for a law of ``friction_ratio = mu_k / mu_0``. Its
    mu_k/mu_0 axis stays (the kernel interpolates along it: a friction coefficient that
    changes at every call, as a vehicle's, costs nothing to set up; summed out per ratio it
    cost 11 ms a new ratio). With ``aspect_ratio`` (a0/b0) seen in
    :data:`CORRECTION_AT_ASPECT_AFTER` calls, its a0/b0 axis summed out at that value too (a
    contact of fixed shape, as a scene's), or at once with ``now`` (the FMU: its numbers then
    depend on its inputs and state alone, so that a restored state replays bit for bit).
    Empty where there is no table or the law does not fall (``friction_ratio >= 1``).
    ``family``: the law family's table (:func:`load_falling_correction`)."""
    if not friction_ratio < 1.0:
        return _EMPTY
    if aspect_ratio is not None:
        key = _at_key(family, poisson_ratio, aspect_ratio)
        got = _AT.get(key)
        if got is not None:
            return got
        seen = CORRECTION_AT_ASPECT_AFTER if now else _SEEN.get(key, 0) + 1
        if seen < CORRECTION_AT_ASPECT_AFTER:
            if len(_SEEN) >= 4 * CORRECTION_AT_KEPT:
                _SEEN.clear()
            _SEEN[key] = seen
        else:
            base = correction_at(poisson_ratio, friction_ratio, now=True, family=family)
            if not base.size:
                return base
            if len(_AT) >= CORRECTION_AT_KEPT:
                _AT.pop(next(iter(_AT)))
            got = _AT[key] = _aspect_collapsed(base, math.log(aspect_ratio))
            return got
    at = _at_key(family, poisson_ratio)
    got = _AT.get(at)
    if got is None:
        corr = load_falling_correction(family=family)
        if not corr.size:
            return _EMPTY
        key = ("nu", at)
        seen = CORRECTION_AT_NU_AFTER if now else _SEEN.get(key, 0) + 1
        if seen < CORRECTION_AT_NU_AFTER:   # (the whole table: the kernel sums nu itself)
            if len(_SEEN) >= 4 * CORRECTION_AT_KEPT:
                _SEEN.clear()
            _SEEN[key] = seen
            return corr
        if len(_AT) >= CORRECTION_AT_KEPT:
            _AT.pop(next(iter(_AT)))
        got = _AT[at] = _collapsed(corr, poisson_ratio)
        from ._table_store import release_pages  # noqa: PLC0415

        release_pages(corr)     # (the mapped table's pages back: the sum is what is used)
    return got


def _cubic_weights(t, n, x):
    """Span and the four cubic B-splines at x (held in [t[3], t[n]]) of knots t (Cox-de Boor,
    as the kernel's cubic_basis)."""
    x = min(max(x, t[3]), t[n])
    i = int(np.searchsorted(t, x, side="right")) - 1
    i = min(max(i, 3), n - 1)
    b = [1.0, 0.0, 0.0, 0.0]
    left, right = [0.0] * 4, [0.0] * 4
    for j in range(1, 4):
        left[j] = x - t[i + 1 - j]
        right[j] = t[i + j] - x
        saved = 0.0
        for r in range(j):
            temp = b[r] / (right[r + 1] + left[j - r])
            b[r] = saved + right[r + 1] * temp
            saved = left[j - r] * temp
        b[j] = saved
    return i, b


def _aspect_collapsed(corr, log_g):
    # the a0/b0 axis (the first cubic one) of a nu-collapsed table summed out at
    # ln(a0/b0) = log_g: count 1 and five placeholder knots (the mu_k/mu_0 axis kept)
    head = CORRECTION_HEADER
    counts = [int(v) for v in corr[:head]]
    n_g = counts[0]
    t = corr[head:head + n_g + 4]
    i, b = _cubic_weights(t, n_g, log_g)
    pos = head + sum(n + 4 for n in counts[:5]) + counts[5] + counts[6]
    coef = corr[pos:].reshape(counts[5] * counts[6], n_g, -1)
    block = ((b[0] * coef[:, i - 3] + b[1] * coef[:, i - 2])
             + (b[2] * coef[:, i - 1] + b[3] * coef[:, i]))
    return np.ascontiguousarray(np.concatenate(
        [[1.0], corr[1:head], np.zeros(5), corr[head + n_g + 4:pos], block.ravel()]))


def _linear_weight(nodes, x):
    # as railcontact._falling_kernels._linear_weight
    n = nodes.size
    if n == 1 or not x > nodes[0]:
        return 0, 0.0
    if not x < nodes[-1]:
        return n - 2, 1.0
    i = 0
    while x >= nodes[i + 1]:
        i += 1
    return i, (x - nodes[i]) / (nodes[i + 1] - nodes[i])


def _collapsed(corr, nu):
    # the nu axis (the first linear one) summed out at nu: count 1, its node nu
    head = CORRECTION_HEADER
    counts = [int(v) for v in corr[:head]]
    pos = head + sum(n + 4 for n in counts[:5])
    n_nu, n_m = counts[5], counts[6]
    i_nu, f_nu = _linear_weight(corr[pos:pos + n_nu], nu)
    coef = corr[pos + n_nu + n_m:].reshape(n_nu, -1)
    block = (1.0 - f_nu) * coef[i_nu] + f_nu * coef[min(i_nu + 1, n_nu - 1)]
    return np.ascontiguousarray(np.concatenate(
        [corr[:5], [1.0, n_m], corr[head:pos], [nu], corr[pos + n_nu:pos + n_nu + n_m],
         block]))


def _filled(vals, friction_ratio, friction_decay_number):
    """Nodes the exact solver did not converge on (NaN) filled, in three steps, each only where
    the one before left NaN:

    1. the mean of their neighbours along theta, where their row along theta has converged
       nodes (repeated while any is left);
    2. the straight line along the kappa number through the two nodes below, in
       sqrt(kappa number) (the nodes are uniform there, 0 ... sqrt 2);
    3. along mu_k/mu_0 (the reader is linear along it), from the top: at an inner node the
       straight line between its two neighbours (as if the node were not there), else
       through the two nodes above it; at the lowest, the line through the two nodes above
       it; 0 where none of these is there.

    Nearly all unconverged nodes are the strongest law of the grid (mu_k/mu_0 = 0.3, kappa
    number 2), whole rows of them at s = 0. Step 2 was chosen on the converged nodes of that
    law, each layer left out and estimated from the rest (31,013 nodes, 2026-11-29: error
    max / 95th percentile / RMS in % of mu_0 N: the line along the kappa number 3.15 / 0.73 /
    0.36, a parabola along it 4.24 / 1.20 / 0.51, the line along mu_k/mu_0 8.09 / 1.65 /
    0.76): the correction varies more slowly along the kappa number than along mu_k/mu_0.
    Over random cases it changes little (seeds 11-40, 4,491 cases, on the table of five
    ln(a0/b0) nodes: 4,477 within 1 % of mu_0 N against 4,475 with step 3 alone, which
    overshoots where the exact correction flattens towards mu_k/mu_0 0.3: seed 11's case
    46, 1.04 % -> 0.69 %). Filled with 0 (before 2026-11-29), they pulled converged cases at
    mu_k/mu_0 0.41-0.6 by up to 6.6 % of mu_0 N. A fill is a middle course, not the truth:
    where the solver does not converge the problem is hard or non-unique (continuation along
    the kappa number from converged neighbours loses convergence too, between kappa numbers
    1.375 and 1.875 on four such nodes).
    """
    vals = vals.copy()
    for _ in range(12):
        bad = np.isnan(vals)
        if not bad.any():
            break
        nb = np.stack([np.roll(vals, 1, axis=4), np.roll(vals, -1, axis=4)])
        with warnings.catch_warnings():     # (a node whose neighbours are NaN stays NaN)
            warnings.simplefilter("ignore", RuntimeWarning)
            mean = np.nanmean(nb, axis=0)
        vals = np.where(bad, mean, vals)
    r = np.sqrt(np.asarray(friction_decay_number, dtype=float))
    for j in range(2, r.size):          # (the last axis)
        _fill_by_line(vals[..., j], vals[..., j - 1], vals[..., j - 2], r[j], r[j - 1],
                      r[j - 2])
    m = np.asarray(friction_ratio, dtype=float)
    for j in range(m.size - 2, 0, -1):  # (the inner nodes, from the top)
        _fill_by_line(vals[..., j, :], vals[..., j + 1, :], vals[..., j - 1, :], m[j], m[j + 1],
                      m[j - 1])
        if j + 2 < m.size:
            _fill_by_line(vals[..., j, :], vals[..., j + 1, :], vals[..., j + 2, :], m[j],
                          m[j + 1], m[j + 2])
    _fill_by_line(vals[..., 0, :], vals[..., 1, :], vals[..., 2, :], m[0], m[1], m[2])
    return np.nan_to_num(vals, nan=0.0)


def _fill_by_line(target, near, far, x, x_near, x_far):
    """NaN of ``target`` (a view, in place), the node at ``x``, set to the straight line through
    the nodes ``near`` at ``x_near`` and ``far`` at ``x_far``."""
    line = near + (x - x_near) / (x_far - x_near) * (far - near)
    target[...] = np.where(np.isnan(target), line, target)


def _mirrored(vals, nodes):
    """The values on tau < 0 too (y -> -y: theta -> -theta, tau -> -tau, the lateral force
    and the moment change sign): (values, tau nodes)."""
    tau = nodes["spin_coordinate"]
    theta = nodes["creepage_angle"]
    n_th = theta.size
    flip = (n_th - np.arange(n_th)) % n_th          # the node at -theta (theta = -pi + k dth)
    if not np.allclose(theta[flip], np.where(theta > -np.pi, -theta, -np.pi)):
        raise ValueError("the correction table's theta nodes must be uniform from -pi")
    sign = np.array([1.0, -1.0, -1.0]).reshape(3, 1, 1, 1, 1, 1, 1, 1)
    # tau = 0 is its own mirror image: the mean of its two (the solver's, independent per
    # theta node, agree to its own noise), so that the spline is the mirror image exactly
    zero = vals[:, :, :, :, :, :1]
    vals = np.concatenate([0.5 * (zero + sign * zero[:, :, :, :, flip]), vals[:, :, :, :, :, 1:]],
                          axis=5)
    neg = vals[:, :, :, :, flip][:, :, :, :, :, :0:-1] * sign
    return (np.concatenate([neg, vals], axis=5),
            np.concatenate([-tau[:0:-1], tau]))


def load_falling_correction(path=None, family="smooth"):
    """The correction table, packed for :func:`railcontact._falling_kernels._correction`
    (the file's ``packed_bspline``, made by :func:`pack_correction` when the table was
    built): the exact theory with the law family's law minus this module's model
    (``tablegen.falling_correction``). An empty array where there is no such file (the model
    alone). Read once per machine: decompressed into the user cache and memory-mapped
    (:func:`railcontact._table_store.derived`), so that every process and FMU instance shares
    its pages and a process after the first reads nothing (in memory, once per process,
    where the cache cannot be written).

    Parameters
    ----------
    path : str or path-like, optional
        The file; default the package's ``railcontact/data/falling_correction.nc`` (package
        data, not one of the shipped ``tables/``: its two linear axes are not the tables'
        all-cubic format that other languages' readers take).
    family : str, optional
        The law family of the default file (:data:`CORRECTION_FAMILIES`): ``"smooth"`` the
        smooth law (5.16), ``"polach"`` Polach's exponential law
        (``railcontact/data/falling_correction_polach.nc``; where the package has no such
        file, the smooth law's table, taken at the same mu_k/mu_0 and initial slope).

    Returns
    -------
    ndarray
        The packed table (float64, 1-D).
    """
    key = family if path is None else str(path)
    got = _CORRECTION.get(key)
    if got is None:
        if path is None:
            from pathlib import Path  # noqa: PLC0415

            if family not in CORRECTION_FAMILIES:
                raise ValueError(f"family must be one of {CORRECTION_FAMILIES}; got "
                                 f"{family!r}")
            path = Path(__file__).resolve().parent / "data" / f"{CORRECTION_FILES[family]}.nc"
            if not path.is_file() and family != "smooth":
                got = _CORRECTION[key] = load_falling_correction()
                return got
            path = path if path.is_file() else None
        if path is None:
            got = np.zeros(0)
        else:
            from ._table_store import derived  # noqa: PLC0415

            # (decompressed once per machine into the user cache and mapped: every process
            # and FMU instance shares its pages, and a process after the first reads nothing)
            got = derived(path, "falling-packed", lambda: _read_packed(path))
        _CORRECTION[key] = got
    return got


def _read_packed(path):
    """The packed table of the file ``path`` (float64, 1-D), read into one array without
    masked-array copies (the file's float32 coefficients the one transient)."""
    import netCDF4  # noqa: PLC0415

    with netCDF4.Dataset(path) as ds:
        ds.set_auto_mask(False)
        head = np.asarray(ds.variables["packed_bspline"][:], dtype=float)
        coef = ds.variables["packed_bspline_coefficients"]
        got = np.empty(head.size + coef.shape[0])
        got[:head.size] = head
        got[head.size:] = coef[:]
    return got


def pack_correction(values, nodes):
    """The packed correction table (:func:`railcontact._falling_kernels._correction`) of the
    node values ``values`` (3, n_g, n_nu, n_s, n_theta, n_tau, n_m, n_kn) on ``nodes`` (a
    dict of :data:`CORRECTION_AXES`, tau >= 0): unconverged nodes (NaN) filled (:func:`_filled`),
    mirrored to tau < 0, and interpolated by C2 cubic B-splines (not-a-knot; periodic in
    theta) along ln(a0/b0), s, theta, tau and the kappa number, linearly along nu and
    mu_k/mu_0 (the build's step; needs scipy)."""
    from scipy.interpolate import make_interp_spline  # noqa: PLC0415

    nodes = {k: np.asarray(nodes[k], dtype=float) for k in CORRECTION_AXES}
    vals, tau = _mirrored(_filled(np.asarray(values, dtype=float), nodes["friction_ratio"],
                                  nodes["friction_decay_number"]), nodes)
    # axes now (var, g, nu, s, theta, tau, m, kn) -> (var, nu, m, g, s, theta, tau, kn)
    vals = np.ascontiguousarray(vals.transpose(0, 2, 6, 1, 3, 4, 5, 7))
    theta = np.append(nodes["creepage_angle"], np.pi)       # (the seam: theta = pi is -pi)
    knots = []
    for axis, x in ((3, nodes["log_aspect_ratio"]), (4, nodes["creepage_coordinate"]),
                    (5, theta), (6, tau), (7, nodes["friction_decay_number"])):
        # the interpolating spline's coefficients are linear in the values: the spline of
        # each unit vector gives the matrix, applied along the axis (one product)
        unit = np.eye(vals.shape[axis])
        sp = make_interp_spline(x, unit if axis != 5 else np.vstack([unit, unit[:1]]), k=3,
                                bc_type="periodic" if axis == 5 else None)
        vals = np.ascontiguousarray(np.moveaxis(
            np.tensordot(np.asarray(sp.c, dtype=float), vals, axes=([1], [axis])), 0, axis))
        knots.append(np.asarray(sp.t, dtype=float))
    head = [float(t.size - 4) for t in knots] + [float(nodes["poisson_ratio"].size),
                                                  float(nodes["friction_ratio"].size)]
    return np.ascontiguousarray(np.concatenate(
        [head, *knots, nodes["poisson_ratio"], nodes["friction_ratio"],
         np.moveaxis(vals, 0, -1).ravel()]))


_OUT = np.zeros(6)
_KERNEL = [None]
_GAUSS = np.ascontiguousarray(np.concatenate([np.stack([_CX, _SY, _W]), np.zeros((4, _W.size))]))
_NO_LAW_TABLE = np.zeros((2, 1))
_MODEL = np.array([SPIN_POLE_SMOOTHING, SPIN_COORDINATE_EDGE, TABLE_MU_BLEND, *SPIN_BLEND])

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
                                  poisson_ratio, mu0, mu_k, kappa, path="auto"):
    """One contact (plain floats, checked), the smooth law (5.16), compiled: see
    :func:`falling_friction_table_compiled` (``mu0, mu_k, kappa`` [-])."""
    return falling_friction_table_compiled(table, xi_x, xi_y, phi, normal_load, a0, b0,
                                           youngs_modulus, poisson_ratio, 0, mu0, mu_k, kappa,
                                           0.0, path)


def falling_friction_table_compiled(table, xi_x, xi_y, phi, normal_load, a0, b0,
                                    youngs_modulus, poisson_ratio, kind, p0, p1, p2, p3,
                                    path="auto", tabulated=None, buffer=None):
    """One contact (plain floats, checked), a closed-form or tabulated law, compiled: ``kind``
    0 the smooth law with ``(p0, p1, p2) = (mu_0, mu_k, kappa)``, 1 Polach's with
    ``(mu_0, A, B [s/m], V [m/s])``, 2 the table ``tabulated`` of :func:`law_table` (None for
    the others) with ``p0`` = mu_0 and ``p1 .. p3`` 0.
    ``[tx, ty, mz, stick_area_fraction, normalised_creepage, mu_effective]`` (a list of
    floats) as :func:`falling_friction_table`, or None where the table hands the case to its
    array path (a0/b0 beyond its axis, |tau| beyond it, overflow): the caller then takes
    :func:`falling_friction_table`. ``table`` is a
    :class:`railcontact.exact_table.ExactCreepTable`.

    ``path`` chooses how the table is evaluated, all to round-off the same numbers:

    - ``"auto"`` (the public scalar call): the contact's buffer where the table has it or its
      ski rental makes it (:data:`~railcontact.exact_table.SLAB_AFTER_POINTS` points of one
      a0/b0, each call counting its ``EFFECTIVE_MU_STEPS + 1``;
      :func:`railcontact._falling_kernels.falling_contact`), else the five-dimensional
      spline (:func:`railcontact._falling_kernels.falling_table_point`), so that a contact
      whose a0/b0 changes at every call never pays a buffer's slab;
    - ``"contact_buffer"``: the contact's buffer, made at once for a new a0/b0 (some 20 ms);
    - ``"table_point"``: always the five-dimensional spline, on the coefficients summed over
      nu (made now if need be: :meth:`~railcontact.exact_table.ExactCreepTable.prepare`),
      the correction table summed over nu only. Its numbers depend on the
      inputs alone, not on what was called before.

    ``buffer``: ``(shape, entry)``, a contact buffer the caller holds
    (``table._buffer(shape, poisson_ratio)``, ``shape`` an a0/b0 [-]) for a contact whose
    a0/b0 stays within round-off of ``shape``; evaluated on it, with the correction table
    summed out at ``shape`` too (``path`` then unused). The FMU's step: its numbers depend on
    the inputs and the held shape alone (a restored state replays bit for bit), and a vehicle
    of many held shapes does not rebuild them when the table's own store of buffers is full."""
    g = a0 / b0
    if kind == 0:
        ratio = p1 / p0
    elif kind == 1:
        ratio = p1
    else:
        ratio = tabulated[1, -1] / tabulated[1, 0] if tabulated[1, 0] > 0.0 else 1.0
    law = _NO_LAW_TABLE if tabulated is None else tabulated
    family = "polach" if kind == 1 else "smooth"
    out = _OUT
    if buffer is None and path != "table_point":
        key = (g, poisson_ratio)
        entry = table._buffers.get(key)
        if entry is None:
            entry = (table._buffer(*key) if path == "contact_buffer"
                     else table._entry(key, EFFECTIVE_MU_STEPS + 1))
        if entry is not None:
            buffer = (g, entry)
        elif path == "contact_buffer":    # (a0/b0 beyond the table, nu outside [0, 0.5])
            return None
    if buffer is not None:
        shape, entry = buffer
        kernel = _KERNEL[0]
        if kernel is None:   # (compiled ahead of time in a wheel or FMU; else numba's,
            from . import _compiled  # noqa: PLC0415          imported on the first call only)
            kernel = _KERNEL[0] = _compiled.falling_contact()
        corr = _AT.get((poisson_ratio, shape) if family == "smooth"    # (a fixed shape:
                       else (family, poisson_ratio, shape))     # kept; _at_key, inlined)
        if corr is None:
            corr = correction_at(poisson_ratio, ratio, shape, path != "auto", family)
        done = kernel(entry[0], xi_x, xi_y, phi, normal_load, a0, b0, youngs_modulus, kind,
                      p0, p1, p2, p3, law, corr, _GAUSS, EFFECTIVE_MU_STEPS, SLIP_SHARE_MIN,
                      _MODEL, out)
    else:
        coef, kernel = _point_kernel(table, poisson_ratio, path == "table_point")
        if kernel is None:
            return None
        corr = (correction_at(poisson_ratio, ratio, g, family=family) if path == "auto"
                else correction_at(poisson_ratio, ratio, now=True, family=family))
        done = kernel(table._tbuf, coef, xi_x, xi_y, phi, normal_load, a0, b0, youngs_modulus,
                      poisson_ratio, kind, p0, p1, p2, p3, law, corr, _GAUSS,
                      EFFECTIVE_MU_STEPS, SLIP_SHARE_MIN, _MODEL, out)
    if not done:
        return None
    return out.tolist()     # (floats, one call)


_POINT_KERNELS = {}


def kernel_model_arguments():
    """The arguments of the compiled falling kernels (:mod:`railcontact._falling_kernels`)
    that carry this module's model, in their order after the correction table: ``(gauss,
    steps, share_min, model)``, and the placeholder law table of a closed-form law (for a
    compiled caller of its own: the vehicle's batch, :mod:`railcontact.effects.vehicle`)."""
    return (_GAUSS, EFFECTIVE_MU_STEPS, SLIP_SHARE_MIN, _MODEL), _NO_LAW_TABLE


def _point_kernel(table, poisson_ratio, now):
    """``(coefficients, falling_table_point kernel)`` of ``table`` at ``poisson_ratio``: the
    coefficients summed over nu where the table has them (made at once with ``now``, else by
    its ski rental, :meth:`~railcontact.exact_table.ExactCreepTable._nu_coefficients`), else
    the file's; ``(None, None)`` for nu outside [0, 0.5]."""
    summed = table._nu_slabs.get(poisson_ratio)     # (the sum made: nothing else to do)
    if summed is None:
        if not 0.0 <= poisson_ratio <= 0.5:
            return None, None
        if now:
            table.prepare(poisson_ratio)
        if table._tbuf is None:
            table._make_table_buffer()
        summed = table._nu_coefficients(poisson_ratio, EFFECTIVE_MU_STEPS + 1)
    coef = table._coef if summed is None else summed[0]
    kernel = _POINT_KERNELS.get(coef.dtype)
    if kernel is None:
        from . import _compiled  # noqa: PLC0415

        kernel = _POINT_KERNELS[coef.dtype] = _compiled.falling_table_point(coef)
    return coef, kernel
