r"""Discretised 2-D elastic half-space solver (plane strain): the project's "exact theory" in 2-D.

Why one module of about 1,430 lines: the 2-D reference solver's normal and steady-rolling
tangential problems (any gap, any friction law) share one discretisation: the influence
coefficients, the element grid and the active-set iterations.

Normal contact (frictionless / quasi-identical, Nielsen Sec. 2.3.2, Eqs. (2.3)-(2.8)) and steady
rolling tangential contact (Sec. 2.3.3, Eqs. (2.18), (2.20)-(2.22)) of two elastic bodies with the
same Young's modulus ``E`` and Poisson ratio ``nu`` (quasi-identical, so the normal and tangential
problems decouple). Loads are per unit length [N/m]; traction and pressure in [Pa].

Discretisation
--------------
The potential contact ``[x_min, x_max]`` is cut into ``n`` equal elements of width ``dx`` carrying
a piecewise-constant pressure ``p_j`` and traction ``q_j``. Displacements are evaluated at the
element centres with the *exact* element integrals of the 2-D kernels of Appendix C
(Eqs. (C.1)-(C.2); Johnson, Contact Mechanics, Eq. (2.19)),

.. math::

    u(x) = -K \int p(\zeta)\,\ln\frac{|x-\zeta|}{L}\,d\zeta, \qquad K = \frac{4(1-\nu^2)}{\pi E},

for both bodies together (``u = u_1 - u_2``). The element integral is
``L [F((x - lo)/L) - F((x - hi)/L)]`` with ``F(t) = t ln|t| - t``. The derivative ``du/dx`` (the
Cauchy kernel ``1/(x - zeta)`` of (C.3)-(C.4)) is used in its exact element-averaged form, i.e. as a
difference of exact element displacements (Kalker's discretisation of steady rolling, also used by
CONTACT).

Conventions (read these before comparing with a closed form)
-------------------------------------------------------------
* **Rolling direction.** The bodies move in ``-x`` relative to the contact: material enters at the
  leading edge ``x = +a`` and leaves at ``x = -a``. The slip is then
  ``s(x) = xi - du_x/dx`` with ``u_x = u_x1 - u_x2`` of the wheel (body 1) relative to the rail.
  The thesis (2.18) writes ``s = xi + du_x/dx``; that form belongs to the mirrored orientation
  (leading edge at ``-a``, as in its (2.55)-(2.56), where the stick zone starts at ``-a0``). With
  ``x -> -x`` both agree. Carter's stick zone is therefore ``[a - 2 a*, a]`` here (leading edge).
* **Sign of traction.** ``traction`` is the tangential stress *acting on the wheel* (body 1), the
  package convention (same as CONTACT): it opposes the slip, ``q s <= 0``, and the total force
  ``T = sum(q) dx`` opposes the creepage (``T > 0`` for ``xi < 0``; Carter ``T = mu N (1 - (a*/a)^2)``).
* **Approach.** In 2-D the rigid approach is defined only up to the datum of the log kernel
  (Nielsen, text after (2.35)). Here ``approach = h(x) + u_z(x)`` in the contact with the kernel
  ``ln(|x - zeta| / L)``, ``L = reference_length`` (default 1 m, i.e. (C.1) with ``C1 = 0`` in SI).
  For Hertz this gives ``delta = K N (1/2 - ln(a0 / (2 L)))``. Changing ``L`` adds
  ``K N ln(L'/L)``. CONTACT's 2-D cases (a strip of length ``DY`` with the 3-D kernel) correspond
  to ``L = DY`` up to ``O((a/DY)^2)``.

What is here
------------
* :func:`solve_normal_2d` -- normal contact for any gap (several zones, conformal, punch).
* :func:`solve_rolling_2d` -- steady rolling for a given pressure, creepage or force
  controlled; Coulomb friction or a slip-dependent law ``mu(|s|)`` (Ch. 5).
* :func:`solve_quasistatic_corrugated_2d` -- both at many positions on a moving rail profile
  (Ch. 4 set-up, quasi-static).
* :func:`solve_transient_rolling_2d` -- non-steady rolling (the ``du/dt`` term of (2.16)) by
  time stepping, with an explicit displacement datum (Ch. 7).

Accuracy (measured, see tests/test_reference_halfspace2d.py and benchmarks/bench_reference2d.py)
------------------------------------------------------------------------------------------------
Hertz at 400 elements over 2.54 a0: half-width 3e-4, p0 < 1e-5, approach 3e-7 (relative).
Carter: force error first order, ``(0.1 ... 0.45) dx/a`` depending on where the contact edge
falls inside its element (0.05 % at 400 elements); stick-zone start within ~0.3 dx. CONTACT's
``carter2d`` case (55 elements) is reproduced element by element (pressure within 1e-4 p0,
traction within 3e-5 p0, same stick/slip elements, FX/(mu FN) 0.64798 vs 0.6480).

References
----------
.. [1] J.B. Nielsen, New Developments in the Theory of Wheel/Rail Contact Mechanics,
   IMM-PHD-1998-51, DTU, 1998, Secs. 2.3-2.4 and Appendix C.
.. [2] K.L. Johnson, Contact Mechanics, Cambridge University Press, 1985, Secs. 2.2, 5.2, 8.2.
.. [3] J.J. Kalker, Three-Dimensional Elastic Bodies in Rolling Contact, Kluwer, 1990, Ch. 2
   (discretised steady rolling; algorithms NORM and TANG).
.. [4] F.W. Carter, On the action of a locomotive driving wheel, Proc. R. Soc. A 112 (1926) 151-157.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .._validation import check_range

__all__ = [
    "NormalContact2D",
    "RollingContact2D",
    "solve_normal_2d",
    "solve_rolling_2d",
    "log_influence_matrix",
    "combined_compliance",
    "QuasiStatic2D",
    "solve_quasistatic_corrugated_2d",
    "TransientRolling2D",
    "solve_transient_rolling_2d",
    "tangential_reference_length",
    "falling_friction_steepness",
]


# ---------------------------------------------------------------------------------------------
# kernels
# ---------------------------------------------------------------------------------------------
def combined_compliance(youngs_modulus, poisson_ratio):
    r"""Kernel factor ``K = 4 (1 - nu^2) / (pi E)`` of (C.1)-(C.4) for two identical bodies.

    Parameters
    ----------
    youngs_modulus : float
        Young's modulus of both bodies, > 0. [Pa]
    poisson_ratio : float
        Poisson's ratio of both bodies, in [0, 0.5). [-]

    Returns
    -------
    float
        ``K``. [1/Pa]
    """
    e = check_range("youngs_modulus", youngs_modulus, "Pa", 0.0, None, lower_closed=False)
    nu = check_range("poisson_ratio", poisson_ratio, "-", 0.0, 0.5, upper_closed=False)
    return float(4.0 * (1.0 - nu**2) / (np.pi * e))


def _f_log(t):
    """Antiderivative ``t ln|t| - t`` of ``ln|t|`` (0 at t = 0)."""
    t = np.asarray(t, dtype=float)
    at = np.abs(t)
    return t * np.log(np.where(at > 0.0, at, 1.0)) - t


def log_influence_matrix(x_obs, element_lo, element_hi, reference_length=1.0):
    r"""Exact element integrals ``-int_lo^hi ln(|x - zeta| / L) d zeta`` of the 2-D log kernel.

    ``u = K * (matrix @ p)`` is the displacement (C.1)/(C.2) at ``x_obs`` due to piecewise-constant
    loads ``p_j`` on ``[element_lo_j, element_hi_j]``.

    Parameters
    ----------
    x_obs : array_like, shape (m,)
        Observation points. [m]
    element_lo, element_hi : array_like, shape (n,)
        Element edges. [m]
    reference_length : float
        Datum length ``L`` of the log kernel. [m]

    Returns
    -------
    ndarray, shape (m, n)
        Influence coefficients. [m]
    """
    x = np.asarray(x_obs, dtype=float)[:, None]
    lo = np.asarray(element_lo, dtype=float)[None, :]
    hi = np.asarray(element_hi, dtype=float)[None, :]
    ell = float(reference_length)
    return -ell * (_f_log((x - lo) / ell) - _f_log((x - hi) / ell))


# ---------------------------------------------------------------------------------------------
# results
# ---------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class NormalContact2D:
    """Result of :func:`solve_normal_2d` (all SI).

    Attributes
    ----------
    x : ndarray
        Element centres. [m]
    element_width : float
        Element width. [m]
    pressure : ndarray
        Element pressures, >= 0. [Pa]
    gap : ndarray
        Undeformed separation ``h`` at the centres. [m]
    deformed_gap : ndarray
        ``h + u_z - approach`` at the centres: 0 in contact, >= 0 outside. [m]
    displacement : ndarray
        ``u_z`` (both bodies, datum ``reference_length``). [m]
    contact_mask : ndarray of bool
        Elements with ``pressure > 0``.
    contact_start, contact_end : float
        Outermost contact edges (``p**2`` extrapolated linearly to 0 from the loaded elements
        next to the edge: exact for a square-root edge; see ``_edge``). [m]
    zones : list of (float, float)
        ``(start, end)`` of every separate contact zone (same edge estimate). [m]
    approach : float
        Rigid approach ``delta`` of (2.3) in the datum of ``reference_length``. [m]
    normal_load : float
        ``sum(pressure) * element_width`` (equals the load asked for). [N/m]
    reference_length : float
        Datum of the log kernel. [m]
    iterations : int
        Active-set iterations used.
    """

    x: np.ndarray
    element_width: float
    pressure: np.ndarray
    gap: np.ndarray
    deformed_gap: np.ndarray
    displacement: np.ndarray
    contact_mask: np.ndarray
    contact_start: float
    contact_end: float
    zones: list
    approach: float
    normal_load: float
    reference_length: float
    iterations: int
    youngs_modulus: float = field(default=np.nan)
    poisson_ratio: float = field(default=np.nan)


@dataclass(frozen=True)
class RollingContact2D:
    """Result of :func:`solve_rolling_2d` (all SI).

    Attributes
    ----------
    x : ndarray
        Element centres. [m]
    element_width : float
        [m]
    pressure : ndarray
        Input pressure. [Pa]
    traction : ndarray
        Tangential stress on the wheel, opposing the slip. [Pa]
    slip : ndarray
        Dimensionless slip ``s = xi - du_x/dx`` per element (0 in stick, 0 outside contact). [-]
    stick : ndarray of bool
        Stick elements (``s = 0``, ``|q| <= mu p``).
    contact_mask : ndarray of bool
        ``pressure > 0``.
    creepage : float
        Longitudinal creepage ``xi``. [-]
    tangential_force : float
        ``sum(traction) dx`` on the wheel; opposes the creepage. [N/m]
    normal_load : float
        ``sum(pressure) dx``. [N/m]
    stick_start, stick_end : float
        Extent of the stick region: from the first to the last stick element, each limit refined
        inside one element (``s**2`` extrapolated to 0 next to a slip zone, ``p**2`` at a contact
        edge; see ``_stick_limit``); ``nan`` if full slip. Several stick regions (possible with
        non-Hertzian pressure or falling friction) are spanned as one. [m]
    friction_bound : ndarray
        ``mu(|s|) p`` used for every element. [Pa]
    iterations : int
        Active-set iterations (Coulomb), or continuation steps for a callable law.
    """

    x: np.ndarray
    element_width: float
    pressure: np.ndarray
    traction: np.ndarray
    slip: np.ndarray
    stick: np.ndarray
    contact_mask: np.ndarray
    creepage: float
    tangential_force: float
    normal_load: float
    stick_start: float
    stick_end: float
    friction_bound: np.ndarray
    iterations: int


# ---------------------------------------------------------------------------------------------
# normal problem
# ---------------------------------------------------------------------------------------------
def _zone_edges(x, dx, pressure, mask):
    """Start/end of each run of ``mask``; edge from p**2 extrapolation, clipped to one element."""
    idx = np.flatnonzero(mask)
    if idx.size == 0:
        return []
    breaks = np.flatnonzero(np.diff(idx) > 1)
    starts = np.concatenate([[idx[0]], idx[breaks + 1]])
    ends = np.concatenate([idx[breaks], [idx[-1]]])
    zones = []
    for i0, i1 in zip(starts, ends):
        zones.append((_edge(x, dx, pressure, i0, -1, i1 - i0 + 1),
                      _edge(x, dx, pressure, i1, +1, i1 - i0 + 1)))
    return zones


def _edge(x, dx, pressure, i_out, direction, n_zone):
    """Edge beyond the outermost loaded element ``i_out`` of a zone (``direction`` = +-1).

    ``p**2`` is extrapolated linearly to zero through the two elements just inside ``i_out``
    (the outermost element's own value is biased by the discretisation). A square-root edge
    (smooth non-conformal contact) makes ``p**2`` linear, so the estimate is then within ~0.05
    element widths (measured on Hertz, see the tests). Clipped to ``[-dx/2, dx]`` around the
    centre of ``i_out``; zones of fewer than 3 elements use the element edge.
    """
    if n_zone < 3:
        return float(x[i_out] + direction * 0.5 * dx)
    i1, i2 = i_out - direction, i_out - 2 * direction
    p21, p22 = pressure[i1] ** 2, pressure[i2] ** 2
    if not p22 > p21:
        return float(x[i_out] + direction * 0.5 * dx)
    dist = dx * p21 / (p22 - p21) - dx      # distance beyond the centre of i_out
    dist = min(max(dist, -0.5 * dx), dx)
    return float(x[i_out] + direction * dist)


def _stick_limit(x, dx, pressure, slip, stick, mask, i_st, direction):
    """Limit of the stick region beyond its outermost element ``i_st`` (``direction`` = +-1).

    * Stick element at a contact edge: the contact-edge estimate of ``_edge``.
    * Slip next to it: ``s**2`` (square-root behaviour at a stick/slip boundary, (2.55)) is
      extrapolated linearly to zero from the 2nd and 3rd slip elements, each placed at its upwind
      point ``x + dx/2`` where the difference ``(u_{i+1} - u_i)/dx`` is centred. Measured on
      Carter: within ~0.3 dx (edge of the element alone: up to 0.5 dx). Clipped to one element.
    """
    n = x.size
    j = i_st + direction
    if j < 0 or j >= n or not mask[j]:
        k = i_st
        count = 1
        while 0 <= k - direction < n and mask[k - direction] and count < 3:
            k -= direction
            count += 1
        return _edge(x, dx, pressure, i_st, direction, count)
    j1, j2 = i_st + 2 * direction, i_st + 3 * direction
    fallback = float(x[i_st] + direction * 0.5 * dx)
    if not (0 <= j2 < n and all(mask[k] and not stick[k] for k in (j, j1, j2))):
        return fallback
    s1, s2 = slip[j1] ** 2, slip[j2] ** 2
    if not s2 > s1:
        return fallback
    x1 = x[j1] + 0.5 * dx
    est = x1 - direction * dx * s1 / (s2 - s1)
    lo, hi = sorted((x[i_st] - direction * 0.5 * dx, x[i_st] + direction * 1.5 * dx))
    return float(min(max(est, lo), hi))


def _solve_eqp(a_ff, w_f, rhs_f, load):
    """Solve [A_FF, -1; w_F^T, 0] [p_F; delta] = [rhs_F; load]."""
    m = a_ff.shape[0]
    mat = np.empty((m + 1, m + 1))
    mat[:m, :m] = a_ff
    mat[:m, m] = -1.0
    mat[m, :m] = w_f
    mat[m, m] = 0.0
    sol = np.linalg.solve(mat, np.concatenate([rhs_f, [load]]))
    return sol[:m], sol[m]


def _normal_active_set(amat, gap, width, load, max_iter):
    """Force-controlled frictionless contact: primal-dual active set, primal fallback.

    Solves ``amat p + gap - delta >= 0``, ``p >= 0``, complementarity, ``width . p = load``.
    ``amat`` is symmetric and positive definite on ``sum p = 0`` (log kernel), so the solution of
    this strictly convex QP is unique.
    """
    n = gap.size
    scale = 1.0 / np.mean(np.diag(amat))
    active = np.ones(n, dtype=bool)
    seen = set()
    p = np.zeros(n)
    delta = 0.0
    for it in range(1, max_iter + 1):
        p = np.zeros(n)
        p[active], delta = _solve_eqp(amat[np.ix_(active, active)], np.full(active.sum(), width),
                                      -gap[active], load)
        g = amat @ p + gap - delta
        new_active = (p - scale * g) > 0.0
        if np.array_equal(new_active, active):
            return p, delta, it
        key = new_active.tobytes()
        if key in seen or not new_active.any():
            break
        seen.add(key)
        active = new_active
    # fallback: primal active-set method (Nocedal & Wright, Alg. 16.3), finite, from feasible start
    p = np.clip(p, 0.0, None)
    total = p.sum() * width
    p = p * (load / total) if total > 0 else np.full(n, load / (width * n))
    free = p > 0.0
    for it2 in range(1, 20 * n + 1):
        pf, delta = _solve_eqp(amat[np.ix_(free, free)], np.full(free.sum(), width),
                               -gap[free], load)
        step_dir = np.zeros(n)
        step_dir[free] = pf - p[free]
        if np.max(np.abs(step_dir)) <= 1e-14 * max(np.max(np.abs(p)), 1e-300):
            g = amat @ p + gap - delta
            viol = np.where(free, np.inf, g)
            j = int(np.argmin(viol))
            if viol[j] >= -1e-14 * np.max(np.abs(gap) + 1e-300):
                return p, delta, max_iter + it2
            free[j] = True
            continue
        dec = free & (step_dir < 0.0)
        alpha = 1.0
        if dec.any():
            ratios = -p[dec] / step_dir[dec]
            k = int(np.argmin(ratios))
            if ratios[k] < 1.0:
                alpha = ratios[k]
                blocking = np.flatnonzero(dec)[k]
                p = p + alpha * step_dir
                p[blocking] = 0.0
                free[blocking] = False
                continue
        p = p + step_dir
    raise RuntimeError("normal contact active-set solver did not converge")


def solve_normal_2d(gap, normal_load, youngs_modulus, poisson_ratio, x_min, x_max,
                    n_elements=400, *, reference_length=1.0, max_iter=200):
    r"""Frictionless 2-D (plane strain) normal contact with a given load, Eqs. (2.3)-(2.8), (C.1).

    Solves, on ``n_elements`` equal elements of ``[x_min, x_max]`` with piecewise-constant
    pressure and the exact log-kernel influence coefficients, the complementarity problem

    ``h_i + u_i - delta >= 0``, ``p_i >= 0``, ``p_i (h_i + u_i - delta) = 0``, ``sum p_i dx = N``

    by a primal-dual active-set iteration (exact on the final contact set), with a finite primal
    active-set method as a fallback. Any gap profile works: several zones, conformal shapes.

    Parameters
    ----------
    gap : callable or array_like
        Undeformed separation ``h(x)`` (2.2): a function of ``x`` [m] returning [m] (vectorised),
        or an array of its values at the element centres. Only differences of ``h`` matter.
    normal_load : float
        Normal load per unit length, > 0. [N/m]
    youngs_modulus : float
        Young's modulus of both bodies, > 0. [Pa]
    poisson_ratio : float
        Poisson's ratio of both bodies, in [0, 0.5). [-]
    x_min, x_max : float
        Potential contact region, ``x_min < x_max``; must contain the contact. [m]
    n_elements : int
        Number of elements, >= 4. [-]
    reference_length : float, optional
        Datum ``L`` of the log kernel used for ``approach`` (module docstring), > 0. [m]
    max_iter : int, optional
        Maximum primal-dual active-set iterations before the fallback. [-]

    Returns
    -------
    NormalContact2D

    Raises
    ------
    ValueError
        On bad input, or if the contact reaches ``x_min``/``x_max`` (domain too small).

    Examples
    --------
    >>> r = solve_normal_2d(lambda x: x**2 / (2 * 0.5), 2e5, 2.1e11, 0.28, -2e-3, 2e-3, 200)
    >>> round(r.contact_end * 1e3, 2)   # Hertz a0 = sqrt(8 N R (1 - nu^2) / (pi E)) = 1.06 mm
    1.06
    """
    e = check_range("youngs_modulus", youngs_modulus, "Pa", 0.0, None, lower_closed=False)
    nu = check_range("poisson_ratio", poisson_ratio, "-", 0.0, 0.5, upper_closed=False)
    load = float(check_range("normal_load", normal_load, "N/m", 0.0, None, lower_closed=False))
    x_lo = float(check_range("x_min", x_min, "m"))
    x_hi = float(check_range("x_max", x_max, "m", x_lo, None, lower_closed=False,
                             condition="x_max > x_min"))
    n = int(check_range("n_elements", n_elements, "-", 4, 100000))
    if n != n_elements:
        raise ValueError(f"n_elements must be an integer [-]; got {n_elements!r}")
    ell = float(check_range("reference_length", reference_length, "m", 0.0, None,
                            lower_closed=False))
    dx = (x_hi - x_lo) / n
    x = x_lo + dx * (np.arange(n) + 0.5)
    h = np.asarray(gap(x) if callable(gap) else gap, dtype=float)
    if h.shape != (n,):
        h = np.broadcast_to(h, (n,)) if h.ndim == 0 else h
        if h.shape != (n,):
            raise ValueError(f"gap must be callable or have n_elements = {n} values [m]; "
                             f"got shape {np.shape(h)}")
    check_range("gap", h, "m")
    kern = 4.0 * (1.0 - float(nu) ** 2) / (np.pi * float(e))
    # internal datum 2 (x_max - x_min): the log kernel is then positive definite on the domain
    ell_int = 2.0 * (x_hi - x_lo)
    amat = kern * log_influence_matrix(x, x - 0.5 * dx, x + 0.5 * dx, ell_int)
    h0 = h - h.min()
    p, delta_int, iters = _normal_active_set(amat, h0, dx, load, max_iter)
    p = np.where(p > 0.0, p, 0.0)
    u_int = amat @ p
    deformed = h0 + u_int - delta_int
    mask = p > 0.0
    if mask[0] or mask[-1]:
        raise ValueError("x_min, x_max must enclose the contact [m]; the contact reaches "
                         f"the domain edge (x_min = {x_lo:g}, x_max = {x_hi:g})")
    # convert datum: u_L = u_int + K N ln(L/ell_int)
    shift = kern * load * np.log(ell / ell_int)
    u = u_int + shift
    approach = delta_int + h.min() + shift
    zones = _zone_edges(x, dx, p, mask)
    return NormalContact2D(
        x=x, element_width=dx, pressure=p, gap=h, deformed_gap=np.where(mask, 0.0, deformed),
        displacement=u, contact_mask=mask, contact_start=zones[0][0], contact_end=zones[-1][1],
        zones=zones, approach=float(approach), normal_load=float(p.sum() * dx),
        reference_length=ell, iterations=iters, youngs_modulus=float(e),
        poisson_ratio=float(nu))


# ---------------------------------------------------------------------------------------------
# steady rolling tangential problem
# ---------------------------------------------------------------------------------------------
def _slip_matrix(x, dx, kern):
    """``M`` with ``du_x/dx`` at element ``i`` = ``-(M q)_i``, so ``s = xi + M q``.

    Note on (2.18): with ``u = u1 - u2`` from (2.46) and ``s = xi + du/dx``, Carter's
    (2.55)-(2.56) put the stick zone at ``x = -a0``, i.e. the thesis' Ch. 2 leading edge is
    ``-a0``; its Ch. 7 derivation (7.1)-(7.2) obtains the same (2.18) from ``x = X - V t``
    (material moving towards ``-x``, leading edge ``+a``). Both cannot hold with the same signs
    of ``u`` and ``q``. Here (leading edge ``+a``, ``q`` on the wheel) the kinematics is
    ``s = xi - du/dx``, verified by quadrature of Carter's traction and by CONTACT's output.

    Upwind (Kalker) difference of exact element displacements: the particle now at ``x_i`` was at
    ``x_{i+1}`` one element-passage earlier (rolling direction: material moves towards ``-x``),
    ``du/dx|_i = (u_{i+1} - u_i) / dx`` = exact average of the Cauchy kernel (C.4) over
    ``[x_i, x_{i+1}]``.
    """
    # erratum (convention): (2.18) s = xi + du/dx belongs to the leading edge at -a (see above);
    # for the leading edge +a used here s = xi - du/dx; verified by
    # test_carter_traction_satisfies_kinematics_by_quadrature and test_contact_carter2d_*.
    ell = 2.0 * (x[-1] - x[0] + 2 * dx)
    obs = np.concatenate([x, [x[-1] + dx]])
    a = kern * log_influence_matrix(obs, x - 0.5 * dx, x + 0.5 * dx, ell)
    return (a[:-1] - a[1:]) / dx  # -(u_{i+1} - u_i)/dx per unit q; positive diagonal


def _rolling_active_set(mmat, bound, creepage, force, dx, max_iter, offset=0.0, stick0=None):
    """Coulomb rolling on the contact elements, creepage or force controlled.

    Unknown ``q`` (traction on the wheel), ``s = xi + offset + M q``; stick ``s = 0, |q| <= g``;
    slip ``q = -g sign(s)``. For steady rolling ``M`` has a positive definite symmetric part (the
    upwind difference of the log kernel; checked in the tests), for a transient step ``M`` is
    the symmetric positive definite log-kernel matrix: for given creepage the discrete problem
    is then a strongly monotone variational inequality with a unique solution (the discrete
    Carter solution in steady rolling). Primal-dual active set (semismooth Newton) iteration,
    retried with other scalings if it cycles. A force at the Coulomb bound gives full sliding
    with the creepage at the saturation point.
    """
    offset = np.broadcast_to(np.asarray(offset, dtype=float), bound.shape)
    if force is not None and abs(force) >= dx * bound.sum() * (1 - 1e-12):
        q = np.sign(force) * bound
        s0 = offset + mmat @ q
        # smallest |xi| with sign(s) = -sign(q) everywhere (saturation point)
        xi = float(-(s0.max() if force > 0 else s0.min()))
        return q, xi + s0, xi, np.zeros(bound.size, bool), 1
    for c_factor in (1.0, 0.1, 10.0, 0.01):
        try:
            return _rolling_pdas(mmat, bound, creepage, force, dx, max_iter, c_factor, offset,
                                 stick0)
        except RuntimeError:
            continue
    raise RuntimeError("rolling active-set iteration cycled")


def _rolling_pdas(mmat, bound, creepage, force, dx, max_iter, c_factor, offset, stick0):
    m = bound.size
    force_control = force is not None
    q = np.zeros(m)
    xi = 0.0 if force_control else creepage
    stick = np.ones(m, dtype=bool) if stick0 is None else stick0.copy()
    sign = np.zeros(m)
    if stick0 is not None:  # warm start: slip direction from the rigid part
        sign = np.where(stick, 0.0, np.where(offset + xi >= 0, 1.0, -1.0))
    c = c_factor / np.mean(np.diag(mmat))
    seen = set()
    for it in range(1, max_iter + 1):
        st = np.flatnonzero(stick)
        sl = np.flatnonzero(~stick)
        q = np.zeros(m)
        q[sl] = -bound[sl] * sign[sl]
        if force_control:
            ns = st.size
            mat = np.zeros((ns + 1, ns + 1))
            mat[:ns, :ns] = mmat[np.ix_(st, st)]
            mat[:ns, ns] = 1.0
            mat[ns, :ns] = dx
            rhs = np.concatenate([-offset[st] - mmat[np.ix_(st, sl)] @ q[sl],
                                  [force - dx * q[sl].sum()]])
            if ns:  # (all-slip trial set: keep the previous creepage; the sets then change)
                sol = np.linalg.solve(mat, rhs)
                q[st] = sol[:ns]
                xi = sol[ns]
        else:
            if st.size:
                q[st] = np.linalg.solve(mmat[np.ix_(st, st)],
                                        -xi - offset[st] - mmat[np.ix_(st, sl)] @ q[sl])
        s = xi + offset + mmat @ q
        # new sets: r = -q in box [-g, g]; stick if |q - c s| < g
        trial = q - c * s
        new_stick = np.abs(trial) < bound
        new_sign = np.where(new_stick, 0.0, -np.sign(trial))
        if np.array_equal(new_stick, stick) and np.array_equal(new_sign, sign):
            return q, s, xi, stick, it
        key = new_stick.tobytes() + new_sign.tobytes()
        if key in seen:
            break
        seen.add(key)
        stick, sign = new_stick, new_sign
    raise RuntimeError("rolling active-set iteration cycled")


def _mu_and_slope(law, s_abs):
    """``mu(|s|)`` and ``d mu / d|s|`` (central difference, step relative to |s|)."""
    h = 1e-7 * np.maximum(s_abs, 1e-6)
    mu = np.asarray(law(s_abs), dtype=float)
    lo = np.maximum(s_abs - h, 0.0)
    slope = (np.asarray(law(s_abs + h), dtype=float) - np.asarray(law(lo), dtype=float)) / (
        s_abs + h - lo)
    return mu, slope


def _law_newton(mmat, pc, law_t, mu0, xi_fixed, force, dx, q, xi, stick, sigma, tol,
                newton_max):
    """Newton iteration for a fixed stick/slip partition with friction law ``law_t``.

    Stick rows: ``s_i = 0`` (scaled by ``1/M_ii``); slip rows: ``q_i + p_i sigma_i mu(|s_i|) = 0``;
    with force control one more row ``dx sum q = T`` and unknown ``xi``. Backtracking line search
    on the residual norm. Returns ``(q, xi, ok)``.
    """
    m = q.size
    fc = force is not None
    diag = np.diag(mmat)
    length = dx * m
    scale = tol * mu0 * pc.max()

    def resid(q_, xi_):
        s_ = xi_ + mmat @ q_
        # slip magnitude along the assumed direction; a reversed slip (sigma s < 0) is left to
        # the partition update (mu(0) there, no spurious roots of |s|)
        mu_, slope_ = _mu_and_slope(law_t, np.maximum(sigma * s_, 0.0))
        slope_ = np.where(sigma * s_ > 0.0, slope_, 0.0)
        f = np.where(stick, s_ / diag, q_ + pc * sigma * mu_)
        if fc:
            f = np.append(f, (dx * q_.sum() - force) / length)
        return f, s_, slope_

    f, s, slope = resid(q, xi)
    for _ in range(newton_max):
        norm = np.linalg.norm(f, np.inf)
        if norm <= scale:
            return q, xi, True
        jac = np.zeros((m + fc, m + fc))
        rows_slip = (pc * slope)[:, None]   # d(p sigma mu(sigma s))/ds = p mu' (sigma^2 = 1)
        jac[:m, :m] = np.where(stick[:, None], mmat / diag[:, None], rows_slip * mmat)
        jac[np.arange(m), np.arange(m)] += np.where(stick, 0.0, 1.0)
        if fc:
            jac[:m, m] = np.where(stick, 1.0 / diag, rows_slip[:, 0])
            jac[m, :m] = dx / length
        try:
            d = np.linalg.solve(jac, -f)
        except np.linalg.LinAlgError:
            return q, xi, False
        alpha, n2 = 1.0, np.linalg.norm(f)
        while alpha > 1e-4:
            q_new = q + alpha * d[:m]
            xi_new = xi + alpha * d[m] if fc else xi
            f_new, s_new, slope_new = resid(q_new, xi_new)
            if np.linalg.norm(f_new) < (1 - 1e-4 * alpha) * n2:
                break
            alpha *= 0.5
        else:
            return q, xi, False
        q, xi, f, s, slope = q_new, xi_new, f_new, s_new, slope_new
    return q, xi, np.linalg.norm(f, np.inf) <= scale


def _law_partition(mmat, pc, law_t, mu0, xi_in, force, dx, q, xi, stick, tol, max_outer,
                   newton_max=60):
    """Stick/slip partition iteration around :func:`_law_newton`; ``None`` on failure."""
    sigma = np.where(stick, 0.0, -np.sign(q))
    sigma[(sigma == 0) & ~stick] = 1.0
    seen = set()
    for _ in range(max_outer):
        q, xi, ok = _law_newton(mmat, pc, law_t, mu0, xi_in, force, dx, q, xi, stick, sigma,
                                tol, newton_max)
        if not ok:
            return None
        s = xi + mmat @ q
        to_slip = stick & (np.abs(q) > mu0 * pc * (1 + 1e-10))
        to_stick = ~stick & (sigma * s < 0)
        if not (to_slip.any() or to_stick.any()):
            return q, s, xi, stick
        key = stick.tobytes() + sigma.tobytes()
        if key in seen:   # cycling: change only the worst element
            viol = np.where(to_slip, np.abs(q) / (mu0 * pc + 1e-300) - 1, 0.0) + np.where(
                to_stick, -sigma * s / np.abs(s).max(), 0.0)
            k = int(np.argmax(viol))
            to_slip = to_slip & (np.arange(q.size) == k)
            to_stick = to_stick & (np.arange(q.size) == k)
        seen.add(key)
        sigma = np.where(to_slip, -np.sign(q), np.where(to_stick, 0.0, sigma))
        stick = (stick & ~to_slip) | to_stick
        q = np.where(to_stick, q, q)  # start values kept
    return None


def _graph_newton(mmat, pc, law_t, mu0, xi_in, force, dx, z, xi, tol, max_iter):
    """Semismooth Newton on the friction graph of every element (velocity-dependent friction).

    Each element is parametrised by ``z`` along its (continuous) friction graph: ``|z| <= 1`` is
    stick (``s = 0``, ``q = -z mu(0) p``), ``|z| > 1`` slip (``s = s_ref sign(z)(|z| - 1)``,
    ``q = -sign(z) mu(|s|) p``). The discrete problem ``s(z) = xi + M q(z)`` (plus
    ``dx sum q = T`` with unknown ``xi`` under force control) is then a continuous,
    piecewise-smooth system solved by Newton's method with a backtracking line search; the stick/
    slip partition changes continuously. Returns ``(z, xi, ok)``.
    """
    m = z.size
    fc = force is not None
    s_ref = mu0 * pc.max() * float(np.mean(np.diag(mmat)))
    length = dx * m

    def parts(z_):
        slip_ = np.abs(z_) > 1.0
        s_ = s_ref * np.sign(z_) * np.maximum(np.abs(z_) - 1.0, 0.0)
        mu_, slope_ = _mu_and_slope(law_t, np.abs(s_))
        q_ = np.where(slip_, -np.sign(z_) * mu_ * pc, -z_ * mu0 * pc)
        return slip_, s_, q_, slope_

    def resid(z_, xi_):
        slip_, s_, q_, slope_ = parts(z_)
        f = (s_ - xi_ - mmat @ q_) / s_ref
        if fc:
            f = np.append(f, (dx * q_.sum() - force) / (length * mu0 * pc.max()))
        return f

    f = resid(z, xi)
    for _ in range(max_iter):
        if np.linalg.norm(f, np.inf) <= tol:
            return z, xi, True
        slip, s, q, slope = parts(z)
        ds = np.where(slip, s_ref, 0.0)
        dq = np.where(slip, -slope * s_ref * pc, -mu0 * pc)
        jac = np.zeros((m + fc, m + fc))
        jac[:m, :m] = -mmat * dq[None, :] / s_ref
        jac[np.arange(m), np.arange(m)] += ds / s_ref
        if fc:
            jac[:m, m] = -1.0 / s_ref
            jac[m, :m] = dx * dq / (length * mu0 * pc.max())
        try:
            d = np.linalg.solve(jac, -f)
        except np.linalg.LinAlgError:
            d = np.linalg.lstsq(jac, -f, rcond=None)[0]
        n2 = np.linalg.norm(f)
        alpha = 1.0
        while alpha > 1e-6:
            z_new = z + alpha * d[:m]
            xi_new = xi + alpha * d[m] * s_ref if fc else xi
            f_new = resid(z_new, xi_new)
            if np.linalg.norm(f_new) < (1 - 1e-4 * alpha) * n2:
                break
            alpha *= 0.5
        else:
            return z, xi, False
        z, xi, f = z_new, xi_new, f_new
    return z, xi, bool(np.linalg.norm(f, np.inf) <= tol)


def _law_system(mmat, pc, law, mu0, force, dx, s_ref):
    """Residual ``G(y)`` and Jacobian of the friction-graph system with homotopy parameter.

    ``y = (z, [xi/s_ref], t)``, ``mu_t(s) = mu(0) + t (mu(s) - mu(0))``; see
    :func:`_graph_newton` for ``z``. Returns ``fun(y) -> (G, J)`` with ``J`` of shape
    ``(m + fc, m + fc + 1)``.
    """
    m = pc.size
    fc = force is not None
    length = dx * m
    fscale = length * mu0 * pc.max()

    def fun(y, xi_fixed):
        z = y[:m]
        xi = y[m] * s_ref if fc else xi_fixed
        t = y[-1]
        slip = np.abs(z) > 1.0
        s = s_ref * np.sign(z) * np.maximum(np.abs(z) - 1.0, 0.0)
        mu, slope = _mu_and_slope(law, np.abs(s))
        mu_t = mu0 + t * (mu - mu0)
        q = np.where(slip, -np.sign(z) * mu_t * pc, -z * mu0 * pc)
        g = (s - xi - mmat @ q) / s_ref
        dq_dz = np.where(slip, -t * slope * s_ref * pc, -mu0 * pc)
        dq_dt = np.where(slip, -np.sign(z) * (mu - mu0) * pc, 0.0)
        jac = np.zeros((m + fc, m + fc + 1))
        jac[:m, :m] = -mmat * dq_dz[None, :] / s_ref
        jac[np.arange(m), np.arange(m)] += np.where(slip, 1.0, 0.0)
        jac[:m, -1] = -(mmat @ dq_dt) / s_ref
        if fc:
            jac[:m, m] = -1.0
            g = np.append(g, (dx * q.sum() - force) / fscale)
            jac[m, :m] = dx * dq_dz / fscale
            jac[m, -1] = dx * dq_dt.sum() / fscale
        return g, jac

    return fun


def _tangent(jac, previous=None):
    """Unit null vector of the (k, k+1) Jacobian, oriented along ``previous`` (or t increasing)."""
    k = jac.shape[0]
    aug = np.vstack([jac, previous if previous is not None else np.eye(k + 1)[-1]])
    rhs = np.zeros(k + 1)
    rhs[-1] = 1.0
    try:
        tau = np.linalg.solve(aug, rhs)
    except np.linalg.LinAlgError:
        tau = np.linalg.lstsq(aug, rhs, rcond=None)[0]
    tau /= np.linalg.norm(tau)
    ref = previous if previous is not None else np.eye(k + 1)[-1]
    return tau if tau @ ref >= 0 else -tau


def _rolling_law_arclength(mmat, pc, law, mu0, xi_in, force, dx, z0, xi0, tol, max_steps):
    """Pseudo-arclength continuation in ``t`` of the friction-graph system (passes folds).

    Used when the plain continuation of :func:`_rolling_law_homotopy` stalls at a fold (turning
    point in ``t``) of a falling law: the branch from the Coulomb solution with ``mu(0)`` at
    ``t = 0`` is followed through its turning points to its first crossing of ``t = 1``.
    Returns ``(z, xi, steps)``; raises ``RuntimeError`` if the branch is lost.
    """
    m = pc.size
    fc = force is not None
    s_ref = mu0 * pc.max() * float(np.mean(np.diag(mmat)))
    fun = _law_system(mmat, pc, law, mu0, force, dx, s_ref)
    y = np.concatenate([z0, [xi0 / s_ref] if fc else [], [0.0]])
    g, jac = fun(y, xi_in)
    tau = _tangent(jac)
    h = 0.05
    for step in range(1, max_steps + 1):
        y_pred = y + h * tau
        yc = y_pred.copy()
        ok = False
        for _ in range(12):
            g, jac = fun(yc, xi_in)
            big = np.vstack([jac, tau])
            rhs = -np.append(g, tau @ (yc - y_pred))
            try:
                d = np.linalg.solve(big, rhs)
            except np.linalg.LinAlgError:
                break
            yc = yc + d
            if np.linalg.norm(d) <= 1e-10 * (1 + np.linalg.norm(yc)):
                g, jac = fun(yc, xi_in)
                ok = np.linalg.norm(g, np.inf) <= max(tol, 1e-9)
                break
        if not ok or np.linalg.norm(yc - y) > 3 * h:
            h *= 0.5
            if h < 1e-6:
                raise RuntimeError(f"t = {y[-1]:.4g} (arclength step too small)")
            continue
        if yc[-1] >= 1.0:
            # land exactly on t = 1 by Newton at fixed t from the interpolated point
            w = (1.0 - y[-1]) / (yc[-1] - y[-1])
            yt = y + w * (yc - y)
            zt = yt[:m]
            xt = yt[m] * s_ref if fc else xi_in
            law_1 = law
            z1, x1, ok1 = _graph_newton(mmat, pc, law_1, mu0, xi_in, force, dx, zt.copy(), xt,
                                        tol, 60)
            if ok1:
                return z1, x1, step
            h *= 0.5
            continue
        if yc[-1] < -0.5:
            raise RuntimeError("t < 0 (the branch turned back)")
        tau = _tangent(jac, tau)
        y = yc
        h = min(2.0 * h, 0.5)
    raise RuntimeError(f"t = {y[-1]:.4g} (friction_max_iter continuation steps)")


def _rolling_law_homotopy(mmat, pc, law, mu0, xi_in, force, dx, q, xi, stick, tol, max_steps,
                          max_outer):
    """Velocity-dependent friction by continuation from the Coulomb solution with ``mu(0)``.

    ``mu_t(s) = mu(0) + t (mu(s) - mu(0))``, ``t`` from 0 to 1; each step is solved by
    :func:`_graph_newton` starting from the previous step; the step in ``t`` is halved on
    failure, and below 1/64 the branch is followed by :func:`_rolling_law_arclength` instead.
    The branch returned is the one connected to the static-friction Carter solution.
    """
    s_ref = mu0 * pc.max() * float(np.mean(np.diag(mmat)))
    s0 = xi + mmat @ q
    z = np.where(stick, -q / np.where(pc > 0, mu0 * pc, 1.0),
                 np.sign(s0) * (1.0 + np.abs(s0) / s_ref))
    xi_state = xi
    z_start, xi_start = z.copy(), xi
    t, dt, steps = 0.0, 1.0, 0
    while t < 1.0:
        steps += 1
        if steps > max_steps:
            raise RuntimeError(f"t = {t:.4g}")
        t_new = min(1.0, t + dt)
        law_t = (lambda tt: (lambda s_: mu0 + tt * (np.asarray(law(s_), dtype=float) - mu0)))(
            t_new)
        z_new, xi_new, ok = _graph_newton(mmat, pc, law_t, mu0, xi_in, force, dx, z.copy(),
                                          xi_state, tol, 60)
        if not ok:
            dt *= 0.5
            if dt < 1.0 / 64:   # a fold in t: follow the branch by arclength from t = 0
                z, xi_state, more = _rolling_law_arclength(
                    mmat, pc, law, mu0, xi_in, force, dx, z_start, xi_start, tol, max_steps)
                steps += more
                break
            continue
        z, xi_state, t = z_new, xi_new, t_new
        dt = min(1.0, 2.0 * dt)
    stick = np.abs(z) <= 1.0
    s = np.where(stick, 0.0, s_ref * np.sign(z) * (np.abs(z) - 1.0))
    mu_el = np.asarray(law(np.abs(s)), dtype=float)
    q = np.where(stick, -z * mu0 * pc, -np.sign(z) * mu_el * pc)
    return q, s, xi_state, stick, steps


def falling_friction_steepness(friction, max_pressure, youngs_modulus, poisson_ratio,
                               slip_max=1.0e-2, n_samples=2001):
    r"""Steepness number ``(3/2) ln(3) K p_max max(-mu'(|s|))`` of a falling friction law.

    In the steady 2-D discretisation the diagonal of the slip matrix is ``M_ii = (3/2) ln(3) K``
    for every element width (``K = 4 (1 - nu^2)/(pi E)``), so an element with pressure ``p``
    whose friction falls with slope ``mu'`` has a locally monotone friction graph
    (``s - M_ii q`` increasing along it) only if ``(3/2) ln 3 K p |mu'| < 1``. Above 1 the
    element problem has several solutions (the discrete counterpart of the instability of a
    falling creep curve, Nielsen Ch. 5) and :func:`solve_rolling_2d` may fail to follow the
    law; the number does not depend on the grid.

    Parameters
    ----------
    friction : callable
        ``mu(|s|)``, vectorised.
    max_pressure : float
        Largest pressure in the contact. [Pa]
    youngs_modulus, poisson_ratio : float
        [Pa], [-] (nu in [0, 0.5], 0.5 included: the 3-D exact solver's note on a case it
        does not converge on takes any nu the 3-D API takes).
    slip_max : float, optional
        Slips sampled in ``[0, slip_max]``. [-]
    n_samples : int, optional
        Number of samples (geometric spacing from 1e-9). [-]

    Returns
    -------
    float
        The steepness number (0 for a law that never falls). [-]
    """
    e = check_range("youngs_modulus", youngs_modulus, "Pa", 0.0, None, lower_closed=False)
    nu = check_range("poisson_ratio", poisson_ratio, "-", 0.0, 0.5)
    kern = float(4.0 * (1.0 - nu**2) / (np.pi * e))     # combined_compliance, nu = 0.5 too
    p = float(check_range("max_pressure", max_pressure, "Pa", 0.0, None))
    s = np.concatenate([[0.0], np.geomspace(1e-9, float(slip_max), int(n_samples))])
    mu = np.asarray(friction(s), dtype=float)
    slope = np.diff(mu) / np.diff(s)
    return float(1.5 * np.log(3.0) * kern * p * max(0.0, -slope.min()))


def solve_rolling_2d(x, pressure, youngs_modulus, poisson_ratio, creepage=None,
                     tangential_force=None, friction=0.3, *, max_iter=200,
                     friction_tol=1e-10, friction_max_iter=200):
    r"""Steady 2-D rolling (Carter problem) for a given pressure, Eqs. (2.18), (2.20)-(2.22), (C.4).

    Rolling direction: material moves in ``-x`` through the contact (leading edge at the largest
    ``x``); ``s = xi - du_x/dx`` (the thesis' (2.18) mirrored, see the module docstring).
    Traction ``q`` acts on the wheel and opposes the slip; stick ``s = 0, |q| <= mu(0) p``,
    slip ``q = -mu(|s|) p sign(s)``.

    Parameters
    ----------
    x : array_like
        Uniformly spaced element centres (e.g. ``solve_normal_2d(...).x``). [m]
    pressure : array_like
        Element pressures, >= 0 (same length as ``x``; elements with 0 carry no traction). [Pa]
    youngs_modulus : float
        Young's modulus of both bodies, > 0. [Pa]
    poisson_ratio : float
        Poisson's ratio of both bodies, in [0, 0.5). [-]
    creepage : float, optional
        Longitudinal creepage ``xi`` (2.15). [-]
    tangential_force : float, optional
        Tangential force on the wheel, ``|T| <= mu(0) N``. [N/m]
        Exactly one of ``creepage`` and ``tangential_force`` must be given.
    friction : float or callable
        Coulomb coefficient (>= 0), or a vectorised function ``mu(|s|)`` of the dimensionless slip
        magnitude (velocity-dependent friction, Ch. 5, e.g. (5.16)). Stick elements may carry up to
        ``mu(0) p``; slip elements carry exactly ``mu(|s|) p``. A callable law is solved by
        continuation ``mu_t = mu(0) + t (mu - mu(0))``, ``t = 0 -> 1``, from the (unique)
        Coulomb solution with ``mu(0)``, each step by Newton's method on the stick/slip
        partition (step halved on failure). With a falling law the problem may have several
        solutions; the one returned is the branch connected to the static-friction Carter
        solution. Rising laws work up to the step-law limit (where the creep curve is Carter's
        with ``mu_k``, as Nielsen states in Sec. 5.2). A falling law is followed through
        turning points by pseudo-arclength continuation; this always works while
        :func:`falling_friction_steepness` is below 1 and sometimes up to ~2 (the fold then sits
        on the stick/slip corner of an element's friction graph); otherwise a ValueError names
        the parameters and that number.
    max_iter : int, optional
        Active-set iterations per inner solve. [-]
    friction_tol : float, optional
        Velocity-dependent friction: Newton tolerance on the residual, relative to
        ``mu(0) max(p)``. [-]
    friction_max_iter : int, optional
        Velocity-dependent friction: maximum number of continuation steps. [-]

    Returns
    -------
    RollingContact2D

    Raises
    ------
    ValueError
        Bad input (naming the parameter), ``|tangential_force| > mu(0) N``, or no convergence of
        the velocity-dependent friction iteration (naming ``friction`` and the creepage/force).
    """
    xs = check_range("x", x, "m")
    if xs.ndim != 1 or xs.size < 4:
        raise ValueError(f"x must be a 1-D array of >= 4 element centres [m]; got shape {xs.shape}")
    dxs = np.diff(xs)
    dx = float(dxs.mean())
    if not (dx > 0 and np.allclose(dxs, dx, rtol=1e-6, atol=0.0)):
        raise ValueError("x must be uniformly spaced and increasing [m]")
    p = check_range("pressure", pressure, "Pa", 0.0, None)
    if p.shape != xs.shape:
        raise ValueError(f"pressure must have the shape of x {xs.shape} [Pa]; got {p.shape}")
    e = check_range("youngs_modulus", youngs_modulus, "Pa", 0.0, None, lower_closed=False)
    nu = check_range("poisson_ratio", poisson_ratio, "-", 0.0, 0.5, upper_closed=False)
    if (creepage is None) == (tangential_force is None):
        raise ValueError("creepage and tangential_force: give exactly one of them; got "
                         f"creepage={creepage!r}, tangential_force={tangential_force!r}")
    law = friction if callable(friction) else None
    if law is None:
        mu0 = float(check_range("friction", friction, "-", 0.0, None))
    else:
        mu0 = float(check_range("friction", law(np.zeros(1)), "-", 0.0, None)[0])
    if creepage is not None:
        xi_in = float(check_range("creepage", creepage, "-"))
        force_in = None
    else:
        xi_in = None
        force_in = float(check_range("tangential_force", tangential_force, "N/m"))
    tol = float(check_range("friction_tol", friction_tol, "-", 0.0, None, lower_closed=False))
    kern = 4.0 * (1.0 - float(nu) ** 2) / (np.pi * float(e))
    mask = p > 0.0
    n_load = float(p.sum() * dx)
    nx = xs.size
    zero = np.zeros(nx)
    if force_in is not None and abs(force_in) > mu0 * n_load * (1.0 + 1e-12):
        raise ValueError(f"tangential_force must be in [-{mu0 * n_load:g}, {mu0 * n_load:g}] "
                         f"[N/m] (|T| <= mu(0) N); got {force_in:g}")
    if not mask.any() or mu0 * n_load == 0.0:
        return RollingContact2D(xs, dx, p, zero, zero.copy(), np.zeros(nx, bool), mask,
                                0.0 if xi_in is None else xi_in, 0.0, n_load, np.nan, np.nan,
                                zero.copy(), 0)
    idx = np.flatnonzero(mask)
    mfull = _slip_matrix(xs, dx, kern)
    mmat = mfull[np.ix_(idx, idx)]
    pc = p[idx]

    def inner(mu_el):
        try:
            return _rolling_active_set(mmat, mu_el * pc, xi_in, force_in, dx, max_iter)
        except RuntimeError:
            ctl = (f"creepage = {xi_in:g}" if xi_in is not None
                   else f"tangential_force = {force_in:g} N/m")
            raise ValueError(f"max_iter: the steady-rolling active-set iteration did not converge "
                             f"({ctl}, max_iter = {max_iter}, {idx.size} contact elements)"
                             ) from None

    mu_el = np.full(idx.size, mu0)
    q, s, xi, st, iters = inner(mu_el)
    if law is not None:
        try:
            q, s, xi, st, iters = _rolling_law_homotopy(
                mmat, pc, law, mu0, xi_in, force_in, dx, q, xi, st, tol,
                int(friction_max_iter), max_iter)
        except RuntimeError as exc:
            ctl = (f"creepage = {xi_in:g}" if xi_in is not None
                   else f"tangential_force = {force_in:g} N/m")
            steep = falling_friction_steepness(law, pc.max(), youngs_modulus, poisson_ratio)
            raise ValueError(
                "friction: the velocity-dependent friction law could not be followed from "
                f"mu(0) = {mu0:g} to the full law (continuation stopped at {exc}; {ctl}, "
                f"friction_max_iter = {friction_max_iter}, friction_tol = {friction_tol:g}, "
                f"{idx.size} contact elements). Falling-law steepness "
                f"(3/2) ln(3) K max(p) max|mu'| = {steep:.3g}; above 1 the discrete problem is "
                "non-unique element by element (see falling_friction_steepness)"
            ) from None
        mu_el = np.where(st, mu0, np.asarray(law(np.abs(s)), dtype=float))
    traction = zero.copy()
    traction[idx] = q
    slip = zero.copy()
    slip[idx] = np.where(st, 0.0, s)
    stick = np.zeros(nx, bool)
    stick[idx] = st
    bound_full = zero.copy()
    bound_full[idx] = mu_el * pc
    if st.any():
        sidx = idx[st]
        stick_start = _stick_limit(xs, dx, p, slip, stick, mask, sidx[0], -1)
        stick_end = _stick_limit(xs, dx, p, slip, stick, mask, sidx[-1], +1)
    else:
        stick_start = stick_end = np.nan
    return RollingContact2D(
        x=xs, element_width=dx, pressure=p, traction=traction, slip=slip, stick=stick,
        contact_mask=mask, creepage=float(xi), tangential_force=float(traction.sum() * dx),
        normal_load=n_load, stick_start=stick_start, stick_end=stick_end,
        friction_bound=bound_full, iterations=int(iters))


# ---------------------------------------------------------------------------------------------
# quasi-static series over rail positions (moving corrugated profile)
# ---------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class QuasiStatic2D:
    """Result of :func:`solve_quasistatic_corrugated_2d`, one row per rail position (all SI).

    Attributes
    ----------
    rail_position : ndarray, shape (m,)
        Rail coordinate ``X_c`` of the wheel axis. [m]
    x : ndarray, shape (n,)
        Element centres in the wheel-axis frame (``x = X - X_c``). [m]
    pressure, traction, slip : ndarray, shape (m, n)
        Per position (``traction``/``slip`` zero if no tangential problem was asked). [Pa], [-]
    stick : ndarray of bool, shape (m, n)
    contact_start, contact_end : ndarray, shape (m,)
        Outermost contact edges in the axis frame. [m]
    half_width : ndarray, shape (m,)
        ``(contact_end - contact_start) / 2``. [m]
    centre_shift : ndarray, shape (m,)
        ``(contact_start + contact_end) / 2``: contact centre relative to the wheel axis,
        positive towards the leading edge (+x, the rolling direction). Nielsen's ``Delta`` (4.7)
        is measured positive *behind* the axis, i.e. ``Delta = -centre_shift``. [m]
    approach : ndarray, shape (m,)
        Rigid approach in the datum ``reference_length``. [m]
    n_zones : ndarray of int, shape (m,)
        Number of separate contact zones.
    normal_load, creepage, tangential_force : ndarray, shape (m,)
        [N/m], [-], [N/m] (creepage/force ``nan`` if no tangential problem).
    stick_start, stick_end : ndarray, shape (m,)
        [m] (``nan`` for full slip or no tangential problem).
    """

    rail_position: np.ndarray
    x: np.ndarray
    pressure: np.ndarray
    traction: np.ndarray
    slip: np.ndarray
    stick: np.ndarray
    contact_start: np.ndarray
    contact_end: np.ndarray
    half_width: np.ndarray
    centre_shift: np.ndarray
    approach: np.ndarray
    n_zones: np.ndarray
    normal_load: np.ndarray
    creepage: np.ndarray
    tangential_force: np.ndarray
    stick_start: np.ndarray
    stick_end: np.ndarray


def solve_quasistatic_corrugated_2d(rail_positions, rail_profile, radius, normal_load,
                                    youngs_modulus, poisson_ratio, x_min, x_max,
                                    n_elements=400, creepage=None, tangential_force=None,
                                    friction=0.3, *, reference_length=1.0):
    r"""Normal (+ steady tangential) 2-D contact of a cylinder at many positions on a rail profile.

    Quasi-static: at every rail position the contact is solved as if steady (the ``du/dt`` term
    of (2.16) is neglected), Nielsen Sec. 4.2 set-up (4.3)-(4.10): the wheel (body 1) is the
    parabola ``x**2 / (2R)`` (second-order Taylor expansion of (4.3)) and the rail (body 2) has
    the surface height ``Z2(X) = rail_profile(X)`` (positive towards the wheel), so the gap in
    the frame of the wheel axis at ``X_c`` is ``h(x) = x**2/(2R) - rail_profile(X_c + x)`` (2.2).
    The wheel rolls towards ``+x`` (leading edge at ``+x``), the convention of this module.

    Parameters
    ----------
    rail_positions : array_like, shape (m,)
        Positions ``X_c`` of the wheel axis along the rail. [m]
    rail_profile : callable
        Vectorised rail surface height ``Z2(X)`` [m] of the rail coordinate ``X`` [m], e.g.
        ``lambda X: 20e-6 * np.cos(2 * np.pi * X / 0.05)``.
    radius : float
        Wheel radius ``R`` (equivalent radius), > 0. [m]
    normal_load : float or array_like, shape (m,)
        Normal load per unit length at each position, > 0. [N/m]
    youngs_modulus, poisson_ratio : float
        [Pa], [-].
    x_min, x_max : float
        Potential contact region in the axis frame; must contain the contact at every
        position. [m]
    n_elements : int
        Number of elements. [-]
    creepage, tangential_force : float or array_like, optional
        At most one; if given, the steady tangential problem is solved at every position with
        :func:`solve_rolling_2d`. [-], [N/m]
    friction : float or callable
        As in :func:`solve_rolling_2d`.
    reference_length : float, optional
        Datum of ``approach``. [m]

    Returns
    -------
    QuasiStatic2D
    """
    xc = check_range("rail_positions", rail_positions, "m")
    if xc.ndim != 1 or xc.size == 0:
        raise ValueError(f"rail_positions must be a non-empty 1-D array [m]; got shape {xc.shape}")
    if not callable(rail_profile):
        raise ValueError("rail_profile must be a callable Z2(X) [m]")
    rad = float(check_range("radius", radius, "m", 0.0, None, lower_closed=False))
    loads = np.broadcast_to(check_range("normal_load", normal_load, "N/m", 0.0, None,
                                        lower_closed=False), xc.shape)
    if creepage is not None and tangential_force is not None:
        raise ValueError("creepage and tangential_force: give at most one of them")
    tang = creepage is not None or tangential_force is not None
    xis = None if creepage is None else np.broadcast_to(
        check_range("creepage", creepage, "-"), xc.shape)
    forces = None if tangential_force is None else np.broadcast_to(
        check_range("tangential_force", tangential_force, "N/m"), xc.shape)
    m = xc.size
    n = int(n_elements)
    out = {k: np.full(m, np.nan) for k in ("contact_start", "contact_end", "approach",
                                           "creepage", "tangential_force", "stick_start",
                                           "stick_end")}
    n_zones = np.zeros(m, dtype=int)
    pressure = np.zeros((m, n))
    traction = np.zeros((m, n))
    slip = np.zeros((m, n))
    stick = np.zeros((m, n), dtype=bool)
    x = None
    for k in range(m):
        r = solve_normal_2d(lambda xx, _c=xc[k]: xx**2 / (2 * rad) - rail_profile(_c + xx),
                            loads[k], youngs_modulus, poisson_ratio, x_min, x_max, n,
                            reference_length=reference_length)
        x = r.x
        pressure[k] = r.pressure
        out["contact_start"][k] = r.contact_start
        out["contact_end"][k] = r.contact_end
        out["approach"][k] = r.approach
        n_zones[k] = len(r.zones)
        if tang:
            rr = solve_rolling_2d(r.x, r.pressure, youngs_modulus, poisson_ratio,
                                  creepage=None if xis is None else float(xis[k]),
                                  tangential_force=None if forces is None else float(forces[k]),
                                  friction=friction)
            traction[k], slip[k], stick[k] = rr.traction, rr.slip, rr.stick
            out["creepage"][k] = rr.creepage
            out["tangential_force"][k] = rr.tangential_force
            out["stick_start"][k] = rr.stick_start
            out["stick_end"][k] = rr.stick_end
    return QuasiStatic2D(
        rail_position=xc, x=x, pressure=pressure, traction=traction, slip=slip, stick=stick,
        contact_start=out["contact_start"], contact_end=out["contact_end"],
        half_width=0.5 * (out["contact_end"] - out["contact_start"]),
        centre_shift=0.5 * (out["contact_end"] + out["contact_start"]),
        approach=out["approach"], n_zones=n_zones, normal_load=np.array(loads, dtype=float),
        creepage=out["creepage"], tangential_force=out["tangential_force"],
        stick_start=out["stick_start"], stick_end=out["stick_end"])


# ---------------------------------------------------------------------------------------------
# transient (non-steady) rolling, Kalker's time stepping with the du/dt term of (2.16)
# ---------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class TransientRolling2D:
    """Result of :func:`solve_transient_rolling_2d`, one row per time step (all SI).

    Step ``k`` is at ``t_k = (k + 1) dx / V`` after the initial state (the material moves one
    element width per step).

    Attributes
    ----------
    x : ndarray, shape (n,)
        Element centres. [m]
    traction, slip, displacement : ndarray, shape (steps, n)
        Traction on the wheel [Pa], dimensionless slip [-], and ``u_x = u_x1 - u_x2`` at the
        centres in the datum ``reference_length`` [m].
    stick, contact_mask : ndarray of bool, shape (steps, n)
    creepage, tangential_force, normal_load : ndarray, shape (steps,)
        [-], [N/m], [N/m].
    reference_length : float
        Datum of the log kernel. [m]
    """

    x: np.ndarray
    traction: np.ndarray
    slip: np.ndarray
    displacement: np.ndarray
    stick: np.ndarray
    contact_mask: np.ndarray
    creepage: np.ndarray
    tangential_force: np.ndarray
    normal_load: np.ndarray
    reference_length: float


def tangential_reference_length(strip_half_width, poisson_ratio):
    r"""Datum ``L`` of the 2-D log kernel equivalent to a 3-D strip of width ``2b`` (Appendix C).

    Integrating the 3-D Cerruti kernel ``g11`` (C.8) over ``-b < y < b`` at the strip centre gives
    ``K [ln(2b / |x|) + nu/(1 - nu)]`` for ``|x| << b``, i.e. the 2-D kernel ``-K ln(|x| / L)``
    with ``L = 2 b exp(nu / (1 - nu))``. With it, the 2-D displacement of a uniform and of an
    elliptic traction reproduce Nielsen's (7.15) and (7.20) (checked in the tests). For the
    normal kernel (C.5) the same integration gives ``L = 2b`` (CONTACT's 2-D cases).

    Parameters
    ----------
    strip_half_width : float
        ``b``, > 0. [m]
    poisson_ratio : float
        [-]

    Returns
    -------
    float
        ``L``. [m]
    """
    b = float(check_range("strip_half_width", strip_half_width, "m", 0.0, None,
                          lower_closed=False))
    nu = float(check_range("poisson_ratio", poisson_ratio, "-", 0.0, 0.5, upper_closed=False))
    return 2.0 * b * np.exp(nu / (1.0 - nu))


def solve_transient_rolling_2d(x, pressure, youngs_modulus, poisson_ratio, creepage=None,
                               tangential_force=None, friction=0.3, *, reference_length,
                               initial_traction=None, max_iter=200):
    r"""Non-steady 2-D rolling, Coulomb friction: time stepping of (2.16) (Kalker's scheme).

    The material moves one element width ``dx`` towards ``-x`` per step (``dt = dx / V``). The
    slip of the particle now at ``x_i``, which was at ``x_{i+1}`` one step earlier, is

    ``s_i^k = xi^k + (u_i^k - u_{i+1}^{k-1}) / dx``,

    the discrete form of ``s = xi - du/dx + (1/V) du/dt`` ((2.16) for this module's rolling
    direction). Unlike the steady problem this depends on the datum of the displacement (the 2-D
    difficulty stated after (2.46)): ``reference_length`` ``L`` fixes it (a 3-D strip of width
    ``2b`` corresponds to ``L = tangential_reference_length(b, nu)``, the model behind Nielsen's
    (7.14)-(7.20)). A constant input reaches the steady solution of :func:`solve_rolling_2d`
    exactly once the material has crossed the contact; the first step from rest under a force is
    Cattaneo's shift problem.

    Parameters
    ----------
    x : array_like, shape (n,)
        Uniformly spaced element centres. [m]
    pressure : array_like, shape (n,) or (steps, n)
        Pressure, constant or per step (>= 0). [Pa]
    youngs_modulus, poisson_ratio : float
        [Pa], [-].
    creepage, tangential_force : array_like, shape (steps,)
        Exactly one: creepage history or tangential-force history on the wheel. [-], [N/m]
    friction : float
        Coulomb coefficient, >= 0. [-]
    reference_length : float
        Datum ``L`` of the log kernel; must exceed a quarter of the grid length (so that the
        kernel is positive definite). [m]
    initial_traction : array_like, shape (n,), optional
        Traction before the first step (default zero: starting from rest). [Pa]
    max_iter : int, optional
        Active-set iterations per step. [-]

    Returns
    -------
    TransientRolling2D
    """
    xs = check_range("x", x, "m")
    if xs.ndim != 1 or xs.size < 4:
        raise ValueError(f"x must be a 1-D array of >= 4 element centres [m]; got shape {xs.shape}")
    dxs = np.diff(xs)
    dx = float(dxs.mean())
    if not (dx > 0 and np.allclose(dxs, dx, rtol=1e-6, atol=0.0)):
        raise ValueError("x must be uniformly spaced and increasing [m]")
    n = xs.size
    e = check_range("youngs_modulus", youngs_modulus, "Pa", 0.0, None, lower_closed=False)
    nu = check_range("poisson_ratio", poisson_ratio, "-", 0.0, 0.5, upper_closed=False)
    mu = float(check_range("friction", friction, "-", 0.0, None))
    if (creepage is None) == (tangential_force is None):
        raise ValueError("creepage and tangential_force: give exactly one of them")
    ctrl_name = "creepage" if creepage is not None else "tangential_force"
    ctrl = check_range(ctrl_name, creepage if creepage is not None else tangential_force,
                       "-" if creepage is not None else "N/m")
    ctrl = np.atleast_1d(ctrl)
    if ctrl.ndim != 1:
        raise ValueError(f"{ctrl_name} must be a 1-D history (one value per step)")
    steps = ctrl.size
    p = check_range("pressure", pressure, "Pa", 0.0, None)
    if p.shape == (n,):
        p = np.broadcast_to(p, (steps, n))
    if p.shape != (steps, n):
        raise ValueError(f"pressure must have shape ({n},) or ({steps}, {n}) [Pa]; got {p.shape}")
    grid_length = n * dx
    ell = float(check_range("reference_length", reference_length, "m", 0.25 * grid_length, None,
                            lower_closed=False,
                            condition="> (x[-1] - x[0] + dx)/4: positive definite log kernel"))
    q_prev = np.zeros(n) if initial_traction is None else check_range(
        "initial_traction", initial_traction, "Pa").reshape(n)
    kern = 4.0 * (1.0 - float(nu) ** 2) / (np.pi * float(e))
    obs = np.concatenate([xs, [xs[-1] + dx]])
    a_ext = kern * log_influence_matrix(obs, xs - 0.5 * dx, xs + 0.5 * dx, ell)
    a_now = a_ext[:-1]            # u_i^k = (a_now @ q^k)_i
    a_up = a_ext[1:]              # u_{i+1}^{k-1} = (a_up @ q^{k-1})_i
    traction = np.zeros((steps, n))
    slip = np.zeros((steps, n))
    disp = np.zeros((steps, n))
    stick = np.zeros((steps, n), dtype=bool)
    xi_out = np.zeros(steps)
    stick_prev = None
    for k in range(steps):
        mask = p[k] > 0.0
        idx = np.flatnonzero(mask)
        offset_full = -(a_up @ q_prev) / dx
        q = np.zeros(n)
        if idx.size and mu * p[k, idx].sum() > 0.0:
            mmat = a_now[np.ix_(idx, idx)] / dx
            bound = mu * p[k, idx]
            warm = None
            if stick_prev is not None and stick_prev.shape == idx.shape:
                warm = stick_prev
            if tangential_force is not None and abs(ctrl[k]) > dx * bound.sum() * (1 + 1e-12):
                raise ValueError(f"tangential_force must be <= mu N = {dx * bound.sum():g} "
                                 f"[N/m] at every step; got {ctrl[k]:g} at step {k}")
            try:
                qc, sc, xi, st, _ = _rolling_active_set(
                    mmat, bound, float(ctrl[k]) if creepage is not None else None,
                    float(ctrl[k]) if tangential_force is not None else None, dx, max_iter,
                    offset=offset_full[idx], stick0=warm)
            except RuntimeError:
                raise ValueError(f"max_iter: the transient active-set iteration did not converge "
                                 f"at step {k} ({ctrl_name} = {ctrl[k]:g})") from None
            q[idx] = qc
            slip[k, idx] = np.where(st, 0.0, sc)
            stick[k, idx] = st
            stick_prev = st
        else:
            xi = float(ctrl[k]) if creepage is not None else 0.0
            stick_prev = None
        xi_out[k] = xi
        traction[k] = q
        disp[k] = a_now @ q
        q_prev = q
    forces = traction.sum(axis=1) * dx
    return TransientRolling2D(
        x=xs, traction=traction, slip=slip, displacement=disp, stick=stick,
        contact_mask=p > 0.0, creepage=xi_out, tangential_force=forces,
        normal_load=p.sum(axis=1) * dx, reference_length=ell)
