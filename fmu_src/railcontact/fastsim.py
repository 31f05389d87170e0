r"""FASTSIM (Kalker 1982) and FaStrip (Sichani, Enblom and Berg 2016): strip-wise creep forces.

Package convention (see :mod:`railcontact`): forces act on the wheel and oppose the creepage;
x is the rolling direction with the leading edge at x = +a(y), y lateral, and the rigid slip is

    w_x = xi_x - phi y,   w_y = xi_y + phi x                                   [-]

so that the linear limit is ``T = -G a0 b0 (C11 xi_x, C22 xi_y + sqrt(a0 b0) C23 phi)`` with
Kalker's coefficients (:func:`railcontact.kalker_coefficients`).

FASTSIM ([1], Kalker's simplified theory)
    Surface displacement u = L p (p the traction). With three flexibilities ([1], [2]; the
    variant CONTACT uses, [5] ``m_solvpt.f90``)

        L1 = 8 a0 / (3 G C11),  L2 = 8 a0 / (3 G C22),  L3 = pi a0 sqrt(a0/b0) / (4 G C23),

    the steady-state stick condition ``d(L p)/dx = w`` integrates from the leading edge,
    p(a(y)) = 0, towards the trailing edge, ``p(x - dx) = p(x) - dx (w_x/L1 - phi y/L3 ...)``,
    precisely ``dp_x = -(xi_x/L1 - phi y/L3) dx``, ``dp_y = -(xi_y/L2 + phi x/L3) dx``; where
    ``|p|`` exceeds the traction bound ``mu p_z`` it is scaled back onto it (slip). With the
    three flexibilities the full-stick result is Kalker's linear theory exactly for every
    combination of xi_x, xi_y, phi (Kalker's single weighted flexibility ``L = (|xi_x| L1 +
    |xi_y| L2 + sqrt(a0 b0) |phi| L3) / |(xi_x, xi_y, sqrt(a0 b0) phi)|`` of [1] only for one
    creepage at a time).

    Traction bound: the *parabolic* one, ``p_z = 2 N / (pi a0 b0) (1 - x^2/a0^2 - y^2/b0^2)``
    ([1]), as Kalker: it is the pressure of the simplified theory itself (constant
    flexibility), its integral is N, and with FASTSIM's linear-in-x stick traction it gives a
    smooth stick/slip transition; the elliptic (Hertz) bound makes the traction slip at the
    leading edge with an infinite slope and gives worse force/creepage curves ([2],
    [5] example ``fastsim.inp``).

    Discretisation: ``n_strips`` strips of equal width in y (centres y_j), each with
    ``n_elements`` equal steps of length dx_j = 2 a(y_j)/n_elements from the leading to the
    trailing edge (Kalker's element division [1]); the traction is integrated at the
    nodes and the force by the trapezoidal rule along x (exact in the stick zone for creepage)
    and the midpoint rule across y.

FaStrip ([3], [4]; CONTACT's "original FaStrip", [5] ``m_solvpt.f90: original_fastrip``)
    Per strip, the 2-D (Carter) strip solution with Kalker's coefficients and with the spin
    shifting the stick zone: with p0 = 3 N / (2 pi a0 b0) and the non-dimensional creepages

        xi'  = -4 (1 - nu) G C11 xi_x / (2 pi^2 mu p0),
        eta' = -4 (1 - nu) G C22 xi_y / (2 pi^2 mu p0),
        phi' = -3 G sqrt(a0 b0) C23 phi / (2 pi mu p0),

    the slip length of strip y (length 2 d, stick zone ``x > -a(y) + 2 d``) is

        d = (sqrt(eta'^2 + (1 - phi'^2)(xi' - phi' y/a0)^2) + eta' phi') / (1 - phi'^2)
            * a0 / (1 - nu)

    and the stick-zone traction, with (kappa, lambda) the unit vector of (xi' - phi' y/a0,
    eta' + phi' d/a0) and lambda' = lambda - phi',

        p_x = mu p0 kappa  (sqrt(a(y)^2 - x^2) - sqrt((a(y) - d)^2 - (x - d)^2)) / a0,
        p_y = mu p0 (lambda sqrt(a(y)^2 - x^2) - lambda' sqrt((a(y) - d)^2 - (x - d)^2)) / a0.

    In the slip zone the traction is mu p (Hertz, elliptic) in the direction FASTSIM's
    traction has there (three flexibilities, parabolic bound with Sichani's heuristic normal
    force ``N (1 + (1 - a0/b0)^4)`` for a0 < b0, as in [5]). For |phi'| >= 1 the strip is taken
    in full sliding (CONTACT's "full sliding correction", [5] option 7; the printed d is not
    real there), and d < 0 means full sliding too. Without spin the stick zone is the modified
    strip theory's (d = a0 z, Nielsen Eq. (2.83)), so FaStrip then equals
    ``method="modified_strip"`` up to the discretisation. In strips whose leading element
    slips, FASTSIM's direction is taken with Kalker's single weighted flexibility ([1], [5]), so
    that full sliding acts against the rigid slip.

    Sources. Sichani et al.'s papers [3], [4] were not available to us; the equations above are
    those of CONTACT's implementation of the original method ([5], ``original_fastrip``, which
    CONTACT's user guide lists as "Original FaStrip method cf. Sichani", M = 6, and "with full
    sliding correction", M = 7), checked term by term: the non-dimensional creepages, d, kappa,
    lambda, lambda', the stick tractions, Sichani's heuristic normal force for FASTSIM's
    parabolic bound, the one-flexibility pass for strips whose leading element slips, and the
    Hertz bound in the slip zone. CONTACT publishes output only of its *modified* FaStrip (M = 5,
    examples/fastsim.ref_out), so no printed number of the original method could be compared;
    the tests compare with the exact theory instead (tests/test_fastsim.py: CONTACT's 21
    converged cases, max 4.3 % of mu N; six contacts with spin against ``method="exact"``, max
    5.6 % of mu N on CONTACT's FASTSIM example, a/b = 2 with lateral creepage and spin, where
    CONTACT's modified FaStrip is 1.9 % off).

    FASTSIM with three flexibilities, by contrast, keeps the direction of the *weighted* rigid
    slip (w_x/L1, w_y/L2) even in full sliding: for pure creepage at full sliding its force is
    parallel to (C11 xi_x, C22 xi_y), not to (xi_x, xi_y) as in the exact theory (a known
    property of the three-flexibility variant; Kalker's single flexibility avoids it at the
    cost of the linear limit of combined creepages).

FASTSIM with a friction law (slip-dependent, falling friction)
    ``friction_coefficient`` may be a law mu(s) of the slip magnitude s [-] (creepage units;
    ``creep_force_3d`` turns a law in the slip velocity into one in s with ``rolling_speed``).
    The local bound becomes ``mu(q) p`` element by element, q the element's slip, as in the
    extensions of FASTSIM to slip-dependent friction by Giménez, Alonso and Gómez [6] (local
    slip per element); Spiryagin, Polach and Cole [7] (and CONTACT's "modified FASTSIM", [5]
    ``fastsim_params``) take instead one coefficient for the whole contact, mu at the rigid
    slip velocity ``V |(xi_x, xi_y)|``, as Polach 2005 does. The papers [6], [7] were not
    available to us; the element rule here is our own statement of the local extension:

    * an element sticks where the trial traction is within the static bound ``mu(0) p``;
    * a sliding element's slip q is the share of its rigid-slip increment that the traction
      cannot take up elastically, ``q = (L / dx) (|p_trial| - mu(q) p)``, with
      ``L = |w| / |g|`` the flexibility the rigid slip w sees (``g`` the stick increment per
      length above: L1 for longitudinal creepage, L3 for spin), so that in full sliding q -> |w|
      and ``|T| -> mu(|xi|) N``; the traction is put on ``mu(q) p`` in the trial traction's
      direction (the Coulomb projection);
    * an element whose predecessor in the strip slid slides on while that is consistent
      (a root q >= q_prev of the equation above), else a falling law would let it re-stick at
      once under ``mu(0) p`` and the strip would chatter between stick and slip, which the
      exact theory does not show (without this rule the creep curve stays 10-20 % of mu_0 N
      above the exact one after its peak).

    Coulomb friction (a constant law) gives Coulomb FASTSIM to the bit. Against the exact
    theory (``method="exact"`` with the same law) the curve peaks and falls, but higher: max
    3 % of mu_0 N under Coulomb friction on a round contact, 3.3-8.4 % with a moderately
    falling law (mu_k/mu_0 = 0.5, kappa mu_0 p0 / G = 1), 10-18 % with a strongly falling
    one (0.3, 2), 1.8-7.1 % with Polach's law of [8] (A = 0.4, B = 0.6 s/m at 30 m/s), a0/b0
    0.5-2, longitudinal, lateral and lateral creepage with spin, 0.1-20 saturation creepages
    (tests/test_falling_friction_3d.py, docs/accuracy_vs_time.md). With very steep laws the
    result depends on the grid (the slip of an element is L / dx times a traction excess:
    refining folds the element's friction graph, a known trouble of the local model): on the
    report's Polach case (B = 6.93 s/m at 30 m/s) 8.8 % at 20 x 20, 12 % at 40 x 40.

Both are computed for many contacts at once: the broadcast inputs form the leading axes, the
strips one more axis, and only the n_elements steps along x are a Python loop.

References
----------
.. [1] J.J. Kalker, A fast algorithm for the simplified theory of rolling contact, Vehicle
   System Dynamics 11 (1982) 1-13.
.. [2] E.A.H. Vollebregt, J.A. Wilders, FASTSIM2: a second-order accurate frictional rolling
   contact algorithm, Computational Mechanics 47 (2011) 105-116.
.. [3] M. Sichani, R. Enblom, M. Berg, An alternative to FASTSIM for tangential solution of the
   wheel-rail contact, Vehicle System Dynamics 54 (2016) 748-764.
.. [4] M. Sichani, R. Enblom, M. Berg, A fast wheel-rail contact model for detailed damage
   analysis in dynamics simulation, Wear 366-367 (2016) 123-130.
.. [5] E.A.H. Vollebregt, CONTACT (Apache-2.0), github.com/eve70a/CONTACT, src/m_solvpt.f90
   (subroutines for FASTSIM and original_fastrip), read for the formulas above; no code taken.
.. [6] J.G. Giménez, A. Alonso, E. Gómez, Introduction of a friction coefficient dependent on
   the slip in the FastSim algorithm, Vehicle System Dynamics 43 (2005) 233-244.
.. [7] M. Spiryagin, O. Polach, C. Cole, Creep force modelling for rail traction vehicles based
   on the Fastsim algorithm, Vehicle System Dynamics 51 (2013) 1765-1783.
.. [8] O. Polach, Creep forces in simulations of traction vehicles running on adhesion limit,
   Wear 258 (2005) 992-1000.
"""

from __future__ import annotations

import numpy as np

from ._validation import check_creep_inputs
from .kalker import kalker_coefficients

__all__ = ["fastsim_force_3d", "fastrip_force_3d", "FASTSIM_STRIPS", "FASTSIM_ELEMENTS"]

FASTSIM_STRIPS = 40      # default number of strips across the ellipse
FASTSIM_ELEMENTS = 40    # default number of steps along each strip


def _check_inputs(xi_x, xi_y, phi, normal_load, a0, b0, youngs_modulus, poisson_ratio,
                  friction_coefficient, n_strips, n_elements):
    law = friction_coefficient if callable(friction_coefficient) else None
    if law is not None:   # mu(0) for the range checks; the law itself is checked per call
        friction_coefficient = _law_values(law, np.zeros(np.broadcast_shapes(*(
            np.shape(v) for v in (xi_x, xi_y, phi, normal_load, a0, b0, youngs_modulus,
                                  poisson_ratio))) + (1,)), None)[..., 0]
    xi_x, xi_y, phi, n_load, a0, b0, e_mod, nu, mu = check_creep_inputs(
        xi_x, xi_y, phi, normal_load, a0, b0, youngs_modulus, poisson_ratio,
        friction_coefficient)
    for name, n in (("n_strips", n_strips), ("n_elements", n_elements)):
        if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or not 2 <= n <= 10000:
            raise ValueError(f"{name} must be an integer in [2, 10000] [-]; got {n!r}")
    arrays = np.broadcast_arrays(xi_x, xi_y, phi, n_load, a0, b0, e_mod, nu, mu)
    return [np.asarray(v, dtype=float)[..., None] for v in arrays] + [law]   # strip axis last


def _law_values(law, slip, where):
    """``law(slip)`` as a float array of slip's shape, checked finite and >= 0 (ValueError
    naming the law and the slip otherwise; ``where`` masks the entries that count)."""
    try:
        mu = np.broadcast_to(np.asarray(law(slip), dtype=float), np.shape(slip))
    except (TypeError, ValueError) as exc:
        raise ValueError(f"friction_coefficient must be a number or a friction law mu(slip) "
                         f"[-]; got {law!r}, which fails on an array of slips ({exc})") from None
    bad = ~(np.isfinite(mu) & (mu >= 0.0))
    if where is not None:
        bad &= where
    if np.any(bad):
        i = np.flatnonzero(bad)[0]
        raise ValueError(f"friction_coefficient {law!r} must give a finite mu >= 0 at every "
                         f"slip [-]; got mu = {mu.flat[i]:g} at slip {np.ravel(slip)[i]:g}")
    return mu


#: The slip of a sliding element with a friction law (:func:`_sliding_slip`): halvings of the
#: scan from q_max down (to 2^-40 q_max), and most steps of the regula falsi that follows.
LAW_SCAN_STEPS = 40
LAW_ROOT_STEPS = 60


def _sliding_slip(law, t_abs, bound_unit, flex, step, q_prev):
    """Slip magnitude q [-] of an element with a friction law: the largest root q > 0 of

        G(q) = q - (L / dx) (|p_trial| - mu(q) p_bound) = 0

    (q is the share of the element's rigid-slip increment that its traction cannot take up
    elastically; ``flex`` = L [m/Pa], ``bound_unit`` = p_bound, the parabolic bound per unit
    friction [Pa]). The element slides where G(0) < 0 (the trial traction exceeds the static
    bound mu(0) p_bound, as under Coulomb friction), or where the element before it in the
    strip slid (``q_prev > 0``) and G < 0 somewhere: it slides on at the lower friction
    mu(q), where a falling law would otherwise let it re-stick at once under the static bound
    (a stick/slip chatter the exact theory does not show). The largest root is the stable one
    (G' >= 0; G >= 0 at L |p_trial| / dx): it is bracketed on the grid ``q_max 2^-k``,
    k = 0..:data:`LAW_SCAN_STEPS`, then found by regula falsi (Illinois) to round-off. Returns
    (slides, q, mu(q)) (q = 0 where the element sticks; mu None if no element slides)."""
    c = flex / step
    g_0 = -c * (t_abs - _law_values(law, np.zeros(t_abs.shape), None) * bound_unit)
    candidates = (g_0 < 0.0) | (q_prev > 0.0)
    if not np.any(candidates):
        return candidates, np.zeros(t_abs.shape), None
    q_max = np.where(candidates, c * t_abs, 0.0)
    hi, g_hi = q_max, q_max - c * (t_abs - _law_values(law, q_max, candidates) * bound_unit)
    lo = np.zeros(t_abs.shape)
    g_lo = np.where(g_0 < 0.0, g_0, 1.0)      # 1: no negative G seen yet
    found = np.zeros(t_abs.shape, dtype=bool)
    q_k = q_max
    for _ in range(LAW_SCAN_STEPS):           # from q_max down: the first G < 0 brackets
        q_k = 0.5 * q_k
        g_k = q_k - c * (t_abs - _law_values(law, q_k, candidates) * bound_unit)
        new = candidates & ~found & (g_k < 0.0)
        lo, g_lo = np.where(new, q_k, lo), np.where(new, g_k, g_lo)
        found |= new
        higher = candidates & ~found
        hi, g_hi = np.where(higher, q_k, hi), np.where(higher, g_k, g_hi)
        if not np.any(candidates & ~found & (g_0 >= 0.0)):
            break
    slides = candidates & (found | (g_0 < 0.0))
    lo = np.where(found, lo, 0.0)
    g_lo = np.where(slides, np.where(found, g_lo, g_0), -1.0)
    g_hi = np.where(slides, g_hi, 1.0)
    hi = np.where(slides, hi, 0.0)
    width = hi - lo
    side = np.zeros(t_abs.shape)              # Illinois: the end replaced last (-1 lo, +1 hi)
    for _ in range(LAW_ROOT_STEPS):
        q = np.where(g_hi > g_lo, (lo * g_hi - hi * g_lo) / np.where(g_hi > g_lo,
                                                                     g_hi - g_lo, 1.0),
                     0.5 * (lo + hi))
        q = np.where((q > lo) & (q < hi), q, 0.5 * (lo + hi))
        g = q - c * (t_abs - _law_values(law, q, slides) * bound_unit)
        below = g < 0.0
        g_hi = np.where(below & (side < 0.0), 0.5 * g_hi, g_hi)
        g_lo = np.where(~below & (side > 0.0), 0.5 * g_lo, g_lo)
        lo, g_lo = np.where(below, q, lo), np.where(below, g, g_lo)
        hi, g_hi = np.where(below, hi, q), np.where(below, g_hi, g)
        side = np.where(below, -1.0, 1.0)
        if not np.any(slides & (hi - lo > 1e-13 * width) & (hi - lo > 1e-15 * hi)):
            break
    q = np.where(slides, np.where(-g_lo < g_hi, lo, hi), 0.0)
    return slides, q, _law_values(law, q, None)


def _geometry(a0, b0, nu, e_mod, n_strips):
    """Kalker coefficients, G, strip centres y_j and half-lengths a(y_j) (axis -1: strips)."""
    has_area = (a0 > 0.0) & (b0 > 0.0)
    a_s = np.where(has_area, a0, 1.0)
    b_s = np.where(has_area, b0, 1.0)
    c11, c22, c23 = kalker_coefficients(a_s / b_s, nu)
    g_mod = e_mod / (2.0 * (1.0 + nu))
    eta = -1.0 + (2.0 * np.arange(n_strips) + 1.0) / n_strips        # y_j / b0, midpoints
    y = eta * b_s
    a_y = a_s * np.sqrt(1.0 - eta * eta)
    dy = 2.0 * b_s / n_strips
    return has_area, a_s, b_s, c11, c22, c23, g_mod, y, a_y, dy


def _fastsim_points(xi_x, xi_y, phi, a_s, b_s, y, a_y, l1, l2, l3, bound_peak, mu, n_elements,
                    law=None, mu_used=None):
    """FASTSIM tractions at the element centres, from the leading edge on.

    Yields ``(x_k, px_k, py_k, slip_k)`` for k = 1..n_elements, x_k = a(y) - (k - 1/2) dx,
    dx = 2 a(y)/n_elements; ``bound_peak`` is the peak of the parabolic pressure [Pa]. The
    increment between two points integrates the rigid slip exactly (it is linear in x), so the
    stick traction is exact at the points and the midpoint rule integrates it exactly.

    With a friction ``law`` (``mu`` then being its static value mu(0)) an element sticks where
    the trial traction is within ``mu(0) p``; a sliding one is put on ``mu(q) p`` with q its
    slip (:func:`_sliding_slip`), in the trial traction's direction as under Coulomb friction.
    ``mu_used`` (an array, optional) is raised in place to the largest mu applied.
    """
    dx = 2.0 * a_y / n_elements
    px = np.zeros(np.broadcast(xi_x, a_y).shape)
    py = np.zeros_like(px)
    gx = xi_x / l1 - phi * y / l3                  # -dp_x/dx, constant along the strip
    x_prev = a_y
    q_prev = np.zeros(px.shape)                    # slip of the element before (a law)
    for k in range(1, n_elements + 1):
        x = a_y - (k - 0.5) * dx
        step = x_prev - x
        px = px - step * gx
        gy = xi_y / l2 + phi * 0.5 * (x + x_prev) / l3
        py = py - step * gy
        shape = np.maximum(1.0 - (x / a_s) ** 2 - (y / b_s) ** 2, 0.0)
        bound = mu * bound_peak * shape
        t_abs = np.hypot(px, py)
        slip = t_abs > bound
        if law is not None and (np.any(slip) or np.any(q_prev > 0.0)):
            # the element's flexibility seen by the rigid slip: |w| / |dp/dx of stick|
            g_abs = np.hypot(gx, gy)
            w_abs = np.hypot(xi_x - phi * y, xi_y + phi * 0.5 * (x + x_prev))
            flex = np.divide(w_abs, g_abs, out=np.broadcast_to(l1, g_abs.shape).copy(),
                             where=g_abs > 0.0)
            slip, q_prev, mu_q = _sliding_slip(law, t_abs, bound_peak * shape, flex, step,
                                               q_prev)
            if mu_q is not None:
                bound = np.where(slip, mu_q, mu) * bound_peak * shape
                if mu_used is not None:
                    np.maximum(mu_used, np.where(slip, mu_q, 0.0), out=mu_used)
        elif law is not None:
            q_prev = np.zeros(t_abs.shape)
        scale = np.divide(bound, t_abs, out=np.ones(px.shape), where=slip)
        px, py = px * scale, py * scale
        x_prev = x
        yield x, px, py, slip


def fastsim_force_3d(creepage_longitudinal, creepage_lateral, spin, normal_load, a0, b0,
                     youngs_modulus, poisson_ratio, friction_coefficient,
                     n_strips=FASTSIM_STRIPS, n_elements=FASTSIM_ELEMENTS):
    r"""Creep force by Kalker's FASTSIM with three flexibilities and the parabolic bound [1].

    See the module docstring for the algorithm, the flexibilities L1, L2, L3 and why the
    parabolic traction bound. Inputs broadcast.

    Parameters
    ----------
    creepage_longitudinal, creepage_lateral, spin, normal_load, a0, b0, youngs_modulus,
    poisson_ratio
        As in :func:`railcontact.creep_force_3d` ([-], [-], [1/m], [N], [m], [m], [Pa], [-]).
    friction_coefficient : array_like or callable
        Coulomb coefficient mu >= 0, or a friction law ``mu(s)`` of the slip magnitude s [-]
        giving a finite mu >= 0 (module docstring, "FASTSIM with a friction law"); it is
        called with arrays of slips shaped like the broadcast inputs plus a strip axis. [-]
    n_strips : int, optional
        Number of strips of equal width across the ellipse (y), in [2, 10000]. [-]
    n_elements : int, optional
        Number of steps along each strip (x), in [2, 10000]. [-] The discretisation error of
        the force is first order (the slip zone's edge falls inside an element): max 1.4 % of
        mu N at 10 x 10, 0.4 % at 40 x 40 (default), 0.2 % at 80 x 80 (200 random creepages
        with spin, against 400 x 400; 0.03 % in the linear limit).

    Returns
    -------
    tuple of ndarray
        ``(tx, ty, stick_area_fraction)``: force on the wheel [N] (|T| <= mu N, with a law
        the largest mu applied; zero creepage, N = 0, mu = 0 or a0 b0 = 0 give zeros) and
        the stick share of the ellipse's area [-].

    Raises
    ------
    ValueError
        If an input is outside its range (NaN and inf included), or a law fails on an array
        of slips or gives a negative or non-finite mu.

    References
    ----------
    .. [1] J.J. Kalker, Vehicle System Dynamics 11 (1982) 1-13.
    .. [2] J.G. Giménez, A. Alonso, E. Gómez, Vehicle System Dynamics 43 (2005) 233-244.
    """
    xi_x, xi_y, phi, n_load, a0, b0, e_mod, nu, mu, law = _check_inputs(
        creepage_longitudinal, creepage_lateral, spin, normal_load, a0, b0, youngs_modulus,
        poisson_ratio, friction_coefficient, n_strips, n_elements)
    has_area, a_s, b_s, c11, c22, c23, g_mod, y, a_y, dy = _geometry(a0, b0, nu, e_mod, n_strips)
    l1 = 8.0 * a_s / (3.0 * g_mod * c11)
    l2 = 8.0 * a_s / (3.0 * g_mod * c22)
    l3 = np.pi * a_s * np.sqrt(a_s / b_s) / (4.0 * g_mod * c23)
    peak = 2.0 * n_load / (np.pi * a_s * b_s)
    fx = np.zeros(np.broadcast(xi_x, a_y).shape)
    fy = np.zeros_like(fx)
    stick = np.zeros_like(fx)
    dx = 2.0 * a_y / n_elements
    mu_used = np.broadcast_to(mu, fx.shape).copy() if law is not None else None
    for _, px, py, slip in _fastsim_points(xi_x, xi_y, phi, a_s, b_s, y, a_y, l1, l2, l3, peak,
                                           mu, n_elements, law, mu_used):
        fx = fx + px * dx
        fy = fy + py * dx
        stick = stick + np.where(slip, 0.0, dx)
    # |T| <= max(mu) N: a law's largest coefficient applied in the case (mu(0) for Coulomb)
    mu_cap = mu if law is None else mu_used.max(axis=-1, keepdims=True)
    return _finish(fx, fy, stick, dy, has_area, n_load, mu_cap, a_s, b_s)


def _half_disc(x, a_y, a_safe):
    """int_{-a}^{x} sqrt(a^2 - t^2) dt for a = a(y) (x clipped to [-a, a])."""
    u = np.clip(x / a_safe, -1.0, 1.0)
    return 0.5 * a_y**2 * (u * np.sqrt(1.0 - u * u) + np.arcsin(u) + 0.5 * np.pi)


def _finish(fx, fy, stick, dy, has_area, n_load, mu, a_s, b_s):
    tx = (fx * dy).sum(axis=-1)
    ty = (fy * dy).sum(axis=-1)
    stick = (stick * dy).sum(axis=-1) / (np.pi * a_s[..., 0] * b_s[..., 0])
    ok = has_area[..., 0] & (n_load[..., 0] * mu[..., 0] > 0.0)
    tx, ty = np.where(ok, tx, 0.0), np.where(ok, ty, 0.0)
    # |T| <= mu N: the quadrature of tractions on the bound may round a few ulp above it
    mu_n = (mu * n_load)[..., 0]
    t_abs = np.hypot(tx, ty)
    cap = mu_n * (1.0 - 4.0 * np.finfo(float).eps)     # hypot must not round above mu N
    scale = np.divide(cap, t_abs, out=np.ones(t_abs.shape), where=t_abs > cap)
    return ((tx * scale + 0.0)[()], (ty * scale + 0.0)[()],
            np.where(has_area[..., 0], np.minimum(stick, 1.0), 1.0)[()])


def fastrip_force_3d(creepage_longitudinal, creepage_lateral, spin, normal_load, a0, b0,
                     youngs_modulus, poisson_ratio, friction_coefficient,
                     n_strips=FASTSIM_STRIPS, n_elements=FASTSIM_ELEMENTS):
    r"""Creep force by FaStrip (Sichani, Enblom and Berg 2016) [1], [2].

    Strip theory with Kalker's coefficients for the stick zone of every strip (spin shifting
    it), the Hertz traction bound in the slip zone and FASTSIM's traction direction there; see
    the module docstring for the equations. Inputs broadcast.

    Parameters
    ----------
    creepage_longitudinal, creepage_lateral, spin, normal_load, a0, b0, youngs_modulus,
    poisson_ratio, friction_coefficient
        As in :func:`railcontact.creep_force_3d`.
    n_strips : int, optional
        Number of strips across the ellipse, in [2, 10000]. [-]
    n_elements : int, optional
        Number of steps along each strip for FASTSIM's slip direction and the slip-zone
        quadrature, in [2, 10000]. [-] (The stick zone is integrated in closed form.) First
        order: max 1.9 % of mu N at 10 x 10, 0.5 % at 40 x 40 (default), 0.25 % at 80 x 80
        (same test as :func:`fastsim_force_3d`).

    Returns
    -------
    tuple of ndarray
        ``(tx, ty, stick_area_fraction)`` as :func:`fastsim_force_3d`.

    Raises
    ------
    ValueError
        If an input is outside its range (NaN and inf included).

    References
    ----------
    .. [1] M. Sichani, R. Enblom, M. Berg, Vehicle System Dynamics 54 (2016) 748-764 (strip
       theory with spin for the stick zone, FASTSIM's direction in the slip zone).
    .. [2] E.A.H. Vollebregt, CONTACT, src/m_solvpt.f90, ``original_fastrip`` (option 7).
    """
    if callable(friction_coefficient):
        raise ValueError(f"fastrip_force_3d takes a Coulomb friction_coefficient (a number >= 0) "
                         f"[-]; got the friction law {friction_coefficient!r} (FASTSIM takes "
                         f"one: fastsim_force_3d)")
    xi_x, xi_y, phi, n_load, a0, b0, e_mod, nu, mu, _ = _check_inputs(
        creepage_longitudinal, creepage_lateral, spin, normal_load, a0, b0, youngs_modulus,
        poisson_ratio, friction_coefficient, n_strips, n_elements)
    has_area, a_s, b_s, c11, c22, c23, g_mod, y, a_y, dy = _geometry(a0, b0, nu, e_mod, n_strips)
    l1 = 8.0 * a_s / (3.0 * g_mod * c11)
    l2 = 8.0 * a_s / (3.0 * g_mod * c22)
    l3 = np.pi * a_s * np.sqrt(a_s / b_s) / (4.0 * g_mod * c23)
    gamma = a_s / b_s
    n_mod = np.where(gamma < 1.0, 1.0 + (1.0 - gamma) ** 4, 1.0) * n_load   # Sichani's heuristic
    peak_parab = 2.0 * n_mod / (np.pi * a_s * b_s)
    p0 = 1.5 * n_load / (np.pi * a_s * b_s)
    mu_p0 = mu * p0
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        inv = np.where(mu_p0 > 0.0, 1.0 / np.where(mu_p0 > 0.0, mu_p0, 1.0), 0.0)
        xi_p = -4.0 * (1.0 - nu) * g_mod * c11 * xi_x * inv / (2.0 * np.pi**2)
        eta_p = -4.0 * (1.0 - nu) * g_mod * c22 * xi_y * inv / (2.0 * np.pi**2)
        phi_p = -3.0 * g_mod * np.sqrt(a_s * b_s) * c23 * phi * inv / (2.0 * np.pi)
        one_m = 1.0 - phi_p * phi_p
        sliding = np.abs(phi_p) >= 1.0
        k_y = xi_p - phi_p * y / a_s
        root = np.sqrt(np.maximum(eta_p**2 + one_m * k_y**2, 0.0))
        d = np.where(sliding, a_y, (root + eta_p * phi_p) / np.where(sliding, 1.0, one_m)
                     * a_s / (1.0 - nu))
        d = np.where(d < 0.0, 2.0 * a_y + 1.0, d)
        l_y = eta_p + phi_p * d / a_s
        norm = np.sqrt(np.maximum(k_y**2 + l_y**2, 1e-300))
    kappa, lam = k_y / norm, l_y / norm
    lam_p = lam - phi_p
    x_intf = -a_y + 2.0 * d
    # stick zone [x_intf, a(y)], integrated in closed form: int sqrt(a(y)^2 - x^2) dx and the
    # half disc int sqrt((a(y) - d)^2 - (x - d)^2) dx = pi (a(y) - d)^2 / 2 (0 <= d <= a(y))
    has_stick = (d >= 0.0) & (d < a_y)
    r_adh = np.where(has_stick, a_y - d, 0.0)
    a_safe = np.where(a_y > 0.0, a_y, 1.0)
    i_cnt = np.where(has_stick, 0.5 * np.pi * a_y**2 - _half_disc(x_intf, a_y, a_safe), 0.0)
    i_adh = 0.5 * np.pi * r_adh**2
    fx = mu_p0 * kappa * (i_cnt - i_adh) / a_s
    fy = mu_p0 * (lam * i_cnt - lam_p * i_adh) / a_s
    stick = 2.0 * r_adh
    # slip zone [-a(y), x_intf]: mu p (Hertz) in FASTSIM's direction at the element's point;
    # the pressure integrated in closed form over each element's part in the slip zone. Strips
    # whose leading element slips with three flexibilities take the direction from FASTSIM with
    # Kalker's one weighted flexibility (as CONTACT's original_fastrip): in full sliding that
    # direction is the rigid slip's, as in the exact theory.
    dx = 2.0 * a_y / n_elements
    a_safe = np.where(a_y > 0.0, a_y, 1.0)
    lead_slip = next(_fastsim_points(xi_x, xi_y, phi, a_s, b_s, y, a_y, l1, l2, l3,
                                     peak_parab, mu, n_elements))[3]
    c_ab = np.sqrt(a_s * b_s)
    denom = np.sqrt(np.maximum(xi_x**2 + xi_y**2 + (c_ab * phi) ** 2, 1e-20))
    l_one = (np.abs(xi_x) * l1 + np.abs(xi_y) * l2 + c_ab * np.abs(phi) * l3) / denom
    l_one = np.where(l_one > 0.0, l_one, l1)
    l1, l2, l3 = (np.where(lead_slip, l_one, v) for v in (l1, l2, l3))
    for x, px, py, _ in _fastsim_points(xi_x, xi_y, phi, a_s, b_s, y, a_y, l1, l2, l3,
                                        peak_parab, mu, n_elements):
        lo = x - 0.5 * dx
        hi = np.minimum(x + 0.5 * dx, x_intf)
        load = np.maximum(_half_disc(hi, a_y, a_safe) - _half_disc(lo, a_y, a_safe), 0.0)
        t_abs = np.hypot(px, py)
        scale = np.divide(mu_p0 * load / a_s, t_abs, out=np.zeros(t_abs.shape),
                          where=t_abs > 0.0)
        fx = fx + px * scale
        fy = fy + py * scale
    return _finish(fx, fy, stick, dy, has_area, n_load, mu, a_s, b_s)
