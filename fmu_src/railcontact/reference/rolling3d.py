r"""Three-dimensional exact steady rolling contact (Kalker's discretised theory) with spin.

Why one module of about 1,340 lines: the 3-D reference solver's influence coefficients, normal
problem, line-block sweeps, grid shifts and Richardson steps share the grid data structures and
caches.

The project's 3-D "exact theory": quasi-identical elastic half-spaces, a Hertzian normal problem
solved numerically on the grid, and the frictional steady rolling problem with longitudinal and
lateral creepage and spin, discretised with piecewise-constant tractions (Kalker 1990, ch. 5).

Method
------
* **Potential contact area**: ``mx x my`` rectangular elements of size ``dx x dy`` covering
  ``[-scale a0, scale a0] x [-scale b0, scale b0]`` (CONTACT's Hertzian cases use
  ``scale = 1.08``); element centres ``x_i = -scale a0 + (i + 1/2) dx``. Rolling is in +x, the
  leading edge is ``x = +a0`` (the package convention).
* **Influence coefficients**: exact surface displacement difference at an element centre due to
  a uniform traction on a rectangular element (Love 1929 for the normal load; Kalker 1990 for the
  Boussinesq-Cerruti tangential load), obtained by integrating the point-load kernels of two
  quasi-identical half-spaces (Nielsen Eqs. (2.25)-(2.30) with ``2 (1 + nu) / E = 1 / G``, as
  printed -- checked; Johnson 1985 Eqs. (3.19), (3.86) summed over both bodies)::

      u_x = 1/(pi G) [ (1-nu)/r + nu x^2/r^3 ] Q_x + 1/(pi G) nu x y / r^3 Q_y
      u_y = 1/(pi G) nu x y / r^3 Q_x + 1/(pi G) [ (1-nu)/r + nu y^2/r^3 ] Q_y
      u_z = (1-nu)/(pi G) / r P

  over the rectangle with the corner functions ``x asinh(y/|x|)``, ``y asinh(x/|y|)`` and
  ``-r``. Quasi-identity means no coupling between normal and tangential problems.
  The coefficients are checked against numerical quadrature of the point-load kernels in
  ``tests/test_reference_rolling3d.py``.
* **Normal problem**: solved numerically on the same grid (as CONTACT does), for the prescribed
  normal load, with the undeformed distance ``h = A x^2 + B y^2`` whose curvatures are those of
  the Hertzian ellipse ``(a0, b0)`` under that load (Hertz 1882; curvatures from Carlson's
  elliptic integrals). The constrained conjugate-gradient method of Polonsky and Keer (1999)
  with FFT matrix-vector products is used. So the discrete pressure is not exactly Hertz's, but
  the one CONTACT computes on the same grid.
* **Steady state kinematics** (Kalker 1990; Nielsen Eqs. (2.16)-(2.24)): the slip of element I
  is ``s_I = w_I + (u(x_I) - u(x_I + dx)) / dx`` -- first-order upwind difference of
  ``s = w - du/dx`` with the material entering at the leading edge -- with rigid slip
  ``w = (xi - phi y, eta + phi (x + dx/6))`` (Nielsen (2.23)-(2.24); the spin term is taken
  ``dx/6`` upstream of the element centre because that reproduces CONTACT's published values to
  5e-6 of mu N, see ``spin_offset``; the offset is O(dx) and vanishes with grid refinement).
  Option ``transport_order=2``: the three-point upwind difference
  ``s_I = w_I + (3 u(x_I) - 4 u(x_I + dx) + u(x_I + 2 dx)) / (2 dx)``, centred on the element
  centre (rigid slip at the centre, ``spin_offset = 0``), second order where the fields are
  smooth -- the idea of Vollebregt and Wilders' FASTSIM2 (second-order integration along the
  rolling direction) applied to the exact theory. Only the kernels change (one more offset);
  the solver is the same. Measured over the 21 grid-convergence cases of CONTACT
  (``benchmarks/bench_rolling3d.py``), max / RMS error in % of mu N against converged values
  from this solver's fine grids (O: order 2 on 160x80 and 240x80; for the six cases with spin
  and creepage, which converge slowly, the mean of orders 1 and 2 on 960x60, which differ by
  0.04-0.05 % there) and, in brackets, against the Richardson value of CONTACT's 120x60 and
  240x60 rows (C; C and O agree to 0.13 %): first order 40x20 0.93 / 0.64 (0.86 / 0.61);
  second order 40x20 1.33 / 0.50 (1.46 / 0.55), 60x20 0.58 / 0.19 (0.71 / 0.23), 70x20
  0.92 / 0.44, 80x20 0.50 / 0.17 (0.63 / 0.21), 80x40 0.39 / 0.16 (0.52 / 0.20). So the same
  grid gives a smaller error on average, but not a smaller maximum, and the error is not a
  clean power of the element size: (1) where the contact edge of the central rows falls
  inside its element shifts it by +-0.1-0.4 % of mu N from one grid to the next (measured by
  changing ``scale`` at 40x40: about 0 to 0.55 %), which a Richardson step amplifies instead of
  removing; (2) lateral creepage with spin (Phi = 1) converges as the square of the element
  size but with a large constant (a0 = b0, 40 lateral elements: about 0.95, 0.31, 0.09 % at
  40, 80, 160 elements along x), and dominates the maximum. Not the default for these reasons: one Richardson step of
  the first-order scheme, 30x20 -> 60x20, costs the same as second order at 60x20 and has the
  smaller maximum (0.34 / 0.16 %, (0.45 / 0.19 %)).
  Spin cases converge slowly with either difference: for a0 = b0, lateral creepage with
  Phi = 1, Fy / (mu N) at 120x40, 240x40, 480x40, 960x40 is -0.8811, -0.8804, -0.8796,
  -0.8795 (first order) and -0.8782 (240x40), -0.8784, -0.8789 (second order); at 960x60
  -0.8797 and -0.8792. The Richardson value of CONTACT's rows is -0.8803.
* **Grid shift** (``grid_shift``): the grid may be moved a fraction of an element along x.
  Part of the grid error depends on where the contact edge of each row of elements falls
  inside its element, which is not a smooth function of the element size, so a Richardson
  step does not remove it; the average over grids moved -1/4 and +1/4 of an element removes
  most of it (measured over CONTACT's 21 grid-convergence cases, one Richardson step
  30x20 -> 60x20: max 0.45 % of mu N on one grid, 0.17 % averaged over the two;
  ``creep_force_3d(..., method="exact", grid_shifts=2)``, ``benchmarks/bench_rolling3d.py``).
* **Friction**: ``|p| <= g = mu pn``; ``s = 0`` where ``|p| < g`` (adhesion), else
  ``p = -g s/|s|`` (slip, traction opposes slip). ``mu`` is a constant (Coulomb) or a function of
  the slip magnitude ``|s|`` [-] (slip velocity over rolling speed).
* **Solver**: block (line) Gauss-Seidel. Plain Gauss-Seidel on the element tractions diverges
  for this problem: the steady-state matrix is dominated by its upwind-difference part, so the
  error of the not-yet-updated downstream elements is summed along the rolling direction.
  Measured on a 20x16 linear (full-adhesion) case, the spectral radius of the element-wise
  iteration is 205; with the unknowns taken as traction increments along the rolling direction
  (Vollebregt's idea in SteadyGS) it is 2.1 in column order and 0.95 in row order; with a whole
  line of elements along the rolling direction as one block it is 0.16 (0.26 at 30x28, 0.19 at
  64x20). So the blocks here are the lines along x (one per y-row), visited in turn; each line's
  frictional problem (all its elements, both traction components) is solved by a semismooth
  Newton method on ``p = Proj_{|p| <= g}(p - rho s)`` with backtracking; each Newton system is
  solved for ``v = R dp`` (R the line matrix, whose inverses are computed once per row length
  and grid): the sticking elements' ``v`` is known at once, so only the slipping elements
  enter a dense solve. The slip of all elements is computed by FFT before each sweep, and after
  each line the slip of the lines still to be visited in the sweep is corrected by the line's
  traction change (exact block Gauss-Seidel).
  The sweeps start with one Newton step per line and sweep (cheap, and enough
  while the sweeps contract); from the first sweep (after the third) that reduces the
  residual by less than a factor 0.8, every line is solved to convergence (Newton until the
  step is below a tenth of the line's first step or the absolute traction tolerance; at
  most 30 steps, typically 2-4).
  Why: with one Newton step only, the outer iteration is an *inexact* block Gauss-Seidel,
  which is not a contraction when the lines' slip/stick partitions are far from final. On
  fine grids with lateral creepage and spin of the opposite sign (the slip direction turns
  through the patch) it stalled with relative traction changes of 0.1-0.9 per sweep
  (a0 = 3.5 mm, b0 = 7 mm, eta = 2.533e-3, phi = -0.6472 1/m: 15, 22, 42 and 142 sweeps at
  40x20, 80x40, 100x50, 120x60; the cases (7 mm, 7 mm, 1.034e-3, -0.2089) and
  (3.5 mm, 7 mm, 1.266e-3, -0.3236) did not converge in 300 sweeps at 120x60). With the
  switch (measured): 15, 22, 23, 25, 28 sweeps at 40x20, 80x40, 100x50, 120x60, 160x80 for
  the first case, 19, 29, 32, 35, 40 and 15, 23, 25, 27, 33 for the others; solving every
  line to convergence from the start converges too but costs 1.4-1.6x more per case on the
  ordinary cases (40x20: 26 instead of 17 ms). The switch on stagnation follows the idea of
  CONTACT's tangential driver (eve70a/CONTACT, ``src/m_solvpt.f90``, ``tang_solver``: a cheap
  solver, GDsteady, restarts with SteadyGS when it detects stagnation); CONTACT's element
  solves (``plstrc``) iterate Newton on the slip equations with relaxation factors
  (``omegah``, ``omegas``), which this solver does not need once its line blocks are solved
  (read for the idea; no code taken). For a line the block
  solve makes the choice between tractions and traction increments immaterial. Designed from
  the published descriptions of the method family (Kalker 1990; Vollebregt 2013 and CONTACT's
  user guide) and the measurements above; not a transcription of SteadyGS, and no code of any
  program was used. Stopping rule: the relative change of the tractions in one sweep,
  ``|dp|_2 / |p|_2 < tolerance`` (CONTACT's EPS). Typically 12-30 sweeps for 1e-6 (up to ~60
  for a/b = 5 on fine grids, where neighbouring lines couple strongly).
- Falling friction: with a strongly falling law ``mu(|s|)`` the sweeps can stall in a cycle
  (elements flipping between stick and slip; the relative change per sweep stays at
  1e-2..1e-1 while the forces change by some 1e-3 of mu N). After ``_RELAX_STALL`` sweeps
  without halving the best residual, each sweep's change is applied times ``omega``, halved at
  each further stall down to 1/32 (CONTACT's element solves use relaxation factors too: see
  above). The stopping rule is unchanged (the full sweep's change, not the relaxed one), so a
  relaxed solution is as converged as any; a case that converges without a stall is not
  touched. Measured (2026-11-29) on 16 nodes drawn from those of the falling-friction
  correction table that ``method="exact"`` did not converge on (``tablegen.falling_correction``,
  mostly mu_k/mu_0 0.3 with kappa mu_0 p0 / G 2): 2 of the 13 attempted ones converge with the
  relaxation (the others stall on one of the default's grids still: the ladder of grids of
  ``tablegen.falling_correction`` estimates those nodes). A node of a0/b0 1.50, nu 0.5,
  spin coordinate -1.625: its 30x20 grid (shift 0) stalled at 1.8e-2 for hundreds of sweeps;
  relaxed it converges in 27, within 1e-3 of mu N of the 36x24 grid's solution (which
  converges without a stall; ``tests/test_reference_rolling3d.py``).

References
----------
J.J. Kalker, Three-dimensional elastic bodies in rolling contact, Kluwer 1990.
E.A.H. Vollebregt, A Gauss-Seidel type solver for special convex programs, with application to
frictional contact mechanics, J. Optim. Theory Appl. 157 (2013).
I.A. Polonsky, L.M. Keer, A numerical method for solving rough contact problems based on the
multi-level multi-summation and conjugate gradient techniques, Wear 231 (1999) 206-219.
K.L. Johnson, Contact Mechanics, Cambridge 1985.
"""

from __future__ import annotations

import copy
import dataclasses
import math
from dataclasses import dataclass, field
from functools import lru_cache
import warnings

import numpy as np
from numba import njit
import scipy.fft
from scipy.special import elliprd, elliprf

from .. import _compiled
from .. import _numba_cache  # noqa: F401  (numba's cache in a user cache directory)
from .._validation import check_range
from ..errors import RollingConvergenceError

__all__ = [
    "Rolling3DResult",
    "RollingConvergenceError",
    "solve_rolling_3d",
    "solve_normal_3d",
    "influence_coefficients_3d",
    "hertz_curvatures",
    "clear_setup_cache",
]


@dataclass(frozen=True)
class Rolling3DResult:
    """Solution of one 3-D steady rolling case. Forces act on body 1 (the wheel).

    Attributes
    ----------
    tx, ty : float
        Tangential forces on the wheel (oppose the creepage). [N]
    mz : float
        Spin moment about the grid origin (the ellipse centre), ``sum (x py - y px) dA``. [N m]
    normal_load : float
        Sum of the discrete pressures times element area (equals the prescribed load). [N]
    px, py, pn : ndarray, shape (mx, my)
        Tangential tractions and pressure per element. [Pa]
    adhesion, slip : ndarray of bool, shape (mx, my)
        Elements in contact that stick / slip.
    x, y : ndarray
        Element centres along the rolling (mx,) and lateral (my,) directions. [m]
    slip_x, slip_y : ndarray, shape (mx, my)
        Relative slip (velocity over rolling speed) of body 1 w.r.t. body 2. [-]
    approach : float
        Normal approach (penetration) of the discrete normal solution. [m]
    iterations : int
        Gauss-Seidel sweeps of the tangential problem (sum of both grids with Richardson).
    residual : float
        Relative change of the tractions in the last sweep, ``|dp|_2 / |p|_2``. [-]
    richardson : bool
        Whether ``tx, ty, mz`` are Richardson-extrapolated from (mx, my) and (2 mx, 2 my); the
        arrays then belong to the finer grid.
    sensitivity : ndarray, shape (3, 3), or None
        With ``sensitivities=True``: the Jacobian ``d(tx, ty, mz) / d(xi, eta, phi)`` (rows
        tx [N], ty [N], mz [N m]; columns per unit xi [-], eta [-], phi [1/m]) of the discrete
        problem, from the problem linearised at the converged slip/stick partition (see
        :func:`solve_rolling_3d`); Richardson-extrapolated like the forces when
        ``richardson`` is True.
    """

    tx: float
    ty: float
    mz: float
    normal_load: float
    px: np.ndarray = field(repr=False)
    py: np.ndarray = field(repr=False)
    pn: np.ndarray = field(repr=False)
    adhesion: np.ndarray = field(repr=False)
    slip: np.ndarray = field(repr=False)
    x: np.ndarray = field(repr=False)
    y: np.ndarray = field(repr=False)
    slip_x: np.ndarray = field(repr=False)
    slip_y: np.ndarray = field(repr=False)
    approach: float = 0.0
    iterations: int = 0
    residual: float = 0.0
    richardson: bool = False
    sensitivity: np.ndarray | None = field(default=None, repr=False)


# ----------------------------------------------------------------------------------------------
# Hertz
# ----------------------------------------------------------------------------------------------
def hertz_curvatures(a0, b0, normal_load, youngs_modulus, poisson_ratio):
    r"""Curvatures A, B and approach of the Hertzian contact with semi-axes ``(a0, b0)``.

    The undeformed distance is ``h = A x^2 + B y^2``. For the Hertz pressure
    ``p0 sqrt(1 - x^2/a0^2 - y^2/b0^2)``, ``p0 = 3 N / (2 pi a0 b0)``, the displacement
    difference of two identical half-spaces is ``delta - A x^2 - B y^2`` in the ellipse with
    (the ellipsoid potential; Johnson 1985, Sec. 3.4; Carlson's symmetric integrals)::

        delta = p0 a0 b0 / E* R_F(0, a0^2, b0^2)
        A = p0 a0 b0 / (3 E*) R_D(0, b0^2, a0^2)
        B = p0 a0 b0 / (3 E*) R_D(0, a0^2, b0^2)

    with ``1/E* = 2 (1 - nu^2) / E``. Verified in the tests against the discrete normal solver
    and the circular limit ``A = pi p0 / (4 a E*)``, ``delta = pi p0 a / (2 E*)``.

    Parameters
    ----------
    a0, b0 : float
        Semi-axes in rolling and lateral direction. [m]
    normal_load : float
        Normal load. [N]
    youngs_modulus : float
        Young's modulus of both bodies. [Pa]
    poisson_ratio : float
        Poisson's ratio of both bodies. [-]

    Returns
    -------
    (A, B, delta) : tuple of float
        Curvatures [1/m] and approach [m].
    """
    estar = youngs_modulus / (2.0 * (1.0 - poisson_ratio**2))
    p0 = 3.0 * normal_load / (2.0 * math.pi * a0 * b0)
    c = p0 * a0 * b0 / estar
    return (c / 3.0 * float(elliprd(0.0, b0 * b0, a0 * a0)),
            c / 3.0 * float(elliprd(0.0, a0 * a0, b0 * b0)),
            c * float(elliprf(0.0, a0 * a0, b0 * b0)))


# ----------------------------------------------------------------------------------------------
# Influence coefficients
# ----------------------------------------------------------------------------------------------
def _corner_f1(x, y):
    """x asinh(y/|x|) (= x ln(y + r) up to a term that cancels in the corner sum); 0 at x = 0."""
    ax = np.abs(x)
    with np.errstate(divide="ignore", invalid="ignore"):
        v = x * np.arcsinh(y / np.where(ax > 0, ax, 1.0))
    return np.where(ax > 0, v, 0.0)


def _rect_sum(fun, x, y, dx, dy):
    return (fun(x + dx / 2, y + dy / 2) - fun(x - dx / 2, y + dy / 2)
            - fun(x + dx / 2, y - dy / 2) + fun(x - dx / 2, y - dy / 2))


def influence_coefficients_3d(x, y, dx, dy, shear_modulus, poisson_ratio):
    r"""Displacement difference at ``(x, y)`` due to unit uniform traction on the rectangle
    ``[-dx/2, dx/2] x [-dy/2, dy/2]`` of two quasi-identical half-spaces.

    Integrals of the point-load kernels (module docstring) over the rectangle
    (Love 1929; Kalker 1990): with corner sums ``[F] = F(x+,y+) - F(x-,y+) - F(x+,y-) + F(x-,y-)``
    and ``F1 = X asinh(Y/|X|)``, ``F2 = Y asinh(X/|Y|)``, ``F3 = -R``::

        int 1/r = [F1 + F2],  int X^2/r^3 = [F2],  int Y^2/r^3 = [F1],  int X Y/r^3 = [F3]

    Parameters
    ----------
    x, y : array_like
        Observation point relative to the element centre. [m]
    dx, dy : float
        Element size. [m]
    shear_modulus : float
        Combined shear modulus G. [Pa]
    poisson_ratio : float
        Combined Poisson's ratio. [-]

    Returns
    -------
    (axx, axy, ayy, azz) : tuple of ndarray
        Displacement per unit traction. [m/Pa]
    """
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    nu = poisson_ratio
    f1 = _rect_sum(_corner_f1, x, y, dx, dy)
    f2 = _rect_sum(lambda u, v: _corner_f1(v, u), x, y, dx, dy)
    f3 = _rect_sum(lambda u, v: -np.hypot(u, v), x, y, dx, dy)
    k = 1.0 / (math.pi * shear_modulus)
    return (k * ((1 - nu) * f1 + f2), k * nu * f3, k * (f1 + (1 - nu) * f2),
            k * (1 - nu) * (f1 + f2))


@lru_cache(maxsize=16)
def _kernels(mx, my, dx, dy, shear_modulus, poisson_ratio, transport_order=1):
    """Toeplitz kernels on offsets. Index [i + mx - 1, j + my - 1] for offsets i = -mx+1..mx-1.

    Returns azz (normal) and the steady-state slip kernels bxx, bxy, byy where
    ``s_I = w_I + sum_J b(I - J) p_J``: first order ``b(d) = (a(d) - a(d + dx)) / dx``;
    second order (``transport_order=2``, three-point upwind difference)
    ``b(d) = (3 a(d) - 4 a(d + dx) + a(d + 2 dx)) / (2 dx)``.
    """
    ix = np.arange(-mx + 1, mx + 2)  # two more offsets for the upwind differences
    iy = np.arange(-my + 1, my)
    xx, yy = np.meshgrid(ix * dx, iy * dy, indexing="ij")
    axx, axy, ayy, azz = influence_coefficients_3d(xx, yy, dx, dy, shear_modulus, poisson_ratio)

    def shift(a):
        if transport_order == 1:
            return np.ascontiguousarray((a[:-2] - a[1:-1]) / dx)
        return np.ascontiguousarray((3.0 * a[:-2] - 4.0 * a[1:-1] + a[2:]) / (2.0 * dx))

    out = (np.ascontiguousarray(azz[:-2]), shift(axx), shift(axy), shift(ayy))
    for arr in out:
        arr.setflags(write=False)
    return out


# ----------------------------------------------------------------------------------------------
# Normal problem (Polonsky & Keer 1999, FFT products)
# ----------------------------------------------------------------------------------------------
#: contacts (and for the normal problem, grids) of at most this many elements take the
#: products ``B p`` (``A p``) as dense products (O(n^2), the matrices cached per contact)
#: instead of FFT products: on small grids the FFTs' fixed cost per call dominates
#: (measured per product, FFT against dense: 16x8, nc = 92, 68 against 9 us; 20x10,
#: nc = 140, 78 against 16 us; 30x20, nc = 404, 121 against 189 us; 40x20, nc = 540, 136
#: against 383 us)
DENSE_SLIP_MAX_ELEMENTS = 250


def _dense_toeplitz(kernel, i, j, mx, my):
    """The Toeplitz kernel on offsets (index ``[di + mx - 1, dj + my - 1]``) as the dense
    matrix between the elements ``(i, j)``: ``M[I, J] = kernel(i_I - i_J, j_I - j_J)``."""
    return np.ascontiguousarray(kernel[i[:, None] - i[None, :] + mx - 1,
                                       j[:, None] - j[None, :] + my - 1])


class _Convolver:
    """``u = A p`` on the whole grid for a Toeplitz kernel on offsets: FFT products of the
    circulant embedding, or on grids of at most ``DENSE_SLIP_MAX_ELEMENTS`` elements a dense
    product (the FFTs' fixed cost per call dominates there)."""

    def __init__(self, kernel, mx, my):
        self.mx, self.my = mx, my
        self.dense = None
        if mx * my <= DENSE_SLIP_MAX_ELEMENTS:
            self.dense = _dense_toeplitz(kernel, *np.divmod(np.arange(mx * my), my), mx, my)
            return
        # circulant embedding of the Toeplitz kernel: size (2mx, 2my)
        emb = np.zeros((2 * mx, 2 * my))
        ix = np.arange(-mx + 1, mx) % (2 * mx)
        iy = np.arange(-my + 1, my) % (2 * my)
        emb[np.ix_(ix, iy)] = kernel
        self.khat = scipy.fft.rfft2(emb)

    def __call__(self, p):
        if self.dense is not None:
            return (self.dense @ p.ravel()).reshape(self.mx, self.my)
        out = scipy.fft.irfft2(scipy.fft.rfft2(p, s=(2 * self.mx, 2 * self.my)) * self.khat,
                               s=(2 * self.mx, 2 * self.my))
        return out[: self.mx, : self.my]


def solve_normal_3d(h, azz, normal_load, element_area, tolerance=1e-13, max_iterations=2000,
                    initial_pressure=None):
    """Discrete frictionless normal contact with prescribed load (Polonsky & Keer 1999).

    Parameters
    ----------
    h : ndarray, shape (mx, my)
        Undeformed distance at the element centres. [m]
    azz : ndarray, shape (2 mx - 1, 2 my - 1)
        Normal influence kernel on offsets. [m/Pa]
    normal_load : float
        Prescribed normal load. [N]
    element_area : float
        dx dy. [m^2]
    initial_pressure : ndarray, shape (mx, my), optional
        Start of the iteration (e.g. the Hertz pressure at the element centres); only the
        number of iterations changes (the problem is convex). Default: a uniform pressure
        where ``h`` is in the lower half of its range. [Pa]

    Returns
    -------
    (pn, approach) : (ndarray, float)
        Pressure [Pa] and approach [m].
    """
    mx, my = h.shape
    conv = _Convolver(azz, mx, my)
    if initial_pressure is None:
        p = np.where(h <= np.min(h) + 0.5 * (np.max(h) - np.min(h)), 1.0, 0.0)
    else:
        p = np.array(initial_pressure, dtype=float)
    p *= normal_load / (p.sum() * element_area)
    t = np.zeros_like(p)
    g_old = 1.0
    delta_flag = 0.0
    u = conv(p)
    for iteration in range(max_iterations):
        gap = u + h
        act = p > 0
        gap = gap - gap[act].mean()
        g_new = float(np.sum(gap[act] ** 2))
        t = np.where(act, gap + delta_flag * (g_new / g_old) * t, 0.0)
        g_old = g_new
        r_raw = conv(t)
        r = r_raw - r_raw[act].mean()
        denom = float(np.sum(r[act] * t[act]))
        tau = float(np.sum(gap[act] * t[act])) / denom if denom != 0 else 0.0
        p_old = p
        p = np.where(act, p - tau * t, 0.0)
        clipped = bool((p < 0.0).any())
        p = np.maximum(p, 0.0)
        overlap = (p == 0) & (gap < 0)
        if overlap.any():
            delta_flag = 0.0
            p = np.where(overlap, p - tau * gap, p)
        else:
            delta_flag = 1.0
        factor = normal_load / (p.sum() * element_area)
        p *= factor
        err = float(np.abs(p - p_old).sum() * element_area / normal_load)
        if err < tolerance:
            break
        if clipped or delta_flag == 0.0 or iteration % 16 == 15:
            u = conv(p)
        else:
            # p = factor (p_old - tau t) exactly: the displacement follows by linearity, one
            # FFT product per iteration instead of two once the active set has settled
            u = factor * (u - tau * r_raw)
    else:  # pragma: no cover - defensive
        raise RollingConvergenceError(
            f"normal problem did not converge in max_iterations={max_iterations}; "
            f"last relative change {err:.3g}")
    u = conv(p)
    act = p > 0
    approach = float(np.mean((u + h)[act]))
    return p, approach


# ----------------------------------------------------------------------------------------------
# Tangential problem: line-block Gauss-Seidel, semismooth Newton per line
# ----------------------------------------------------------------------------------------------
@njit(cache=True)
def _interp(tab_s, tab_mu, s):
    n = tab_s.shape[0]
    if n == 1 or s <= tab_s[0]:
        return tab_mu[0]
    if s >= tab_s[n - 1]:
        return tab_mu[n - 1]
    lo, hi = 0, n - 1
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if tab_s[mid] <= s:
            lo = mid
        else:
            hi = mid
    f = (s - tab_s[lo]) / (tab_s[hi] - tab_s[lo])
    return tab_mu[lo] + f * (tab_mu[hi] - tab_mu[lo])


@njit(cache=True)
def _row_residual(e_x, e_y, rbx, rby, rho, g, qx, qy, out):
    """F = p - Proj_{|p| <= g}(p - rho s) of one line; returns |F|^2 and fills ``out``."""
    n = e_x.shape[0]
    tot = 0.0
    for k in range(n):
        ax = e_x[k]
        ay = e_y[k]
        for m in range(n):
            ax += rbx[k, m] * qx[m]
            ay += rby[k, m] * qy[m]
        zx = qx[k] - rho[k] * ax
        zy = qy[k] - rho[k] * ay
        zn = math.sqrt(zx * zx + zy * zy)
        if zn <= g[k]:
            fx = qx[k] - zx
            fy = qy[k] - zy
        else:
            fx = qx[k] - g[k] * zx / zn
            fy = qy[k] - g[k] * zy / zn
        out[2 * k] = fx
        out[2 * k + 1] = fy
        tot += fx * fx + fy * fy
    return tot


@njit(cache=True)
def _row_newton(e_x, e_y, rbx, rby, ibx, iby, pn, px, py, tab_s, tab_mu, tol_p, max_newton,
                forcing):
    """Frictional problem of one line of elements along the rolling direction, in place.

    s_x = e_x + rbx p_x, s_y = e_y + rby p_y (no x-y coupling within a line); complementarity
    written as p = Proj_{|p| <= g}(p - rho s) and solved by a semismooth Newton method with a
    backtracking line search on |F|. g = mu(|s|) pn is lagged for a slip-dependent friction law.
    ``ibx, iby`` are the inverses of ``rbx, rby``: the Newton system is solved for
    ``v = R dp`` (known directly on the sticking elements), so only the slipping elements'
    unknowns enter a dense solve (see the comment at the solve).
    """
    n = e_x.shape[0]
    nn = 2 * n
    rho = np.empty(n)
    for k in range(n):
        rho[k] = 2.0 / (rbx[k, k] + rby[k, k])
    f = np.zeros(nn)
    vx = np.empty(n)
    vy = np.empty(n)
    isl = np.empty(n, dtype=np.int64)
    slk = np.empty(n, dtype=np.int64)
    dxx = np.empty(n)
    dxy = np.empty(n)
    dyy = np.empty(n)
    exx = np.empty(n)
    exy = np.empty(n)
    eyy = np.empty(n)
    sx = np.empty(n)
    sy = np.empty(n)
    g = np.empty(n)
    trial_x = np.empty(n)
    trial_y = np.empty(n)
    step = np.empty(nn)

    ftmp = np.zeros(nn)
    dmax0 = 0.0
    for it in range(max_newton):
        # slip and friction bound
        for k in range(n):
            ax = e_x[k]
            ay = e_y[k]
            for m in range(n):
                ax += rbx[k, m] * px[m]
                ay += rby[k, m] * py[m]
            sx[k] = ax
            sy[k] = ay
            g[k] = pn[k] * _interp(tab_s, tab_mu, math.sqrt(ax * ax + ay * ay))
        fnorm2 = _row_residual(e_x, e_y, rbx, rby, rho, g, px, py, f)
        # all elements on the adhesion branch: F = rho s, x and y decouple (two n x n solves)
        allstick = True
        for k in range(n):
            zx = px[k] - rho[k] * sx[k]
            zy = py[k] - rho[k] * sy[k]
            if zx * zx + zy * zy > g[k] * g[k]:
                allstick = False
                break
        if allstick:
            for k in range(n):
                ax = 0.0
                ay = 0.0
                for m in range(n):
                    ax -= ibx[k, m] * sx[m]
                    ay -= iby[k, m] * sy[m]
                step[2 * k] = ax
                step[2 * k + 1] = ay
        else:
            # J dp = -F with J = D + E R per element (R = diag(rbx, rby) in x and y): sticking
            # elements D = 0, E = rho I; slipping ones D = I - P, E = rho P, P = c (I - n n^T)
            # the derivative of the projection. With v = R dp the sticking rows give
            # v_k = -F_k / rho_k at once, and the slipping rows
            #   D_k (R^-1 v)_k + E_k v_k = -F_k
            # a dense system in the slipping elements' v only (2 n_slip unknowns instead of
            # 2 n); then dp = R^-1 v.
            nsl = 0
            for k in range(n):
                zx = px[k] - rho[k] * sx[k]
                zy = py[k] - rho[k] * sy[k]
                zn = math.sqrt(zx * zx + zy * zy)
                if zn <= g[k]:
                    isl[k] = -1
                    vx[k] = -f[2 * k] / rho[k]
                    vy[k] = -f[2 * k + 1] / rho[k]
                else:
                    nx = zx / zn
                    ny = zy / zn
                    c = g[k] / zn
                    dxx[nsl] = 1.0 - c + c * nx * nx
                    dxy[nsl] = c * nx * ny
                    dyy[nsl] = 1.0 - c + c * ny * ny
                    exx[nsl] = rho[k] * c * (1.0 - nx * nx)
                    exy[nsl] = -rho[k] * c * nx * ny
                    eyy[nsl] = rho[k] * c * (1.0 - ny * ny)
                    isl[k] = nsl
                    slk[nsl] = k
                    vx[k] = 0.0
                    vy[k] = 0.0
                    nsl += 1
            ns2 = 2 * nsl
            mat = np.empty((ns2, ns2))
            rhs = np.empty(ns2)
            for a in range(nsl):
                k = slk[a]
                # known part: D_k (R^-1 v_stick)_k
                wx_ = 0.0
                wy_ = 0.0
                for m in range(n):
                    wx_ += ibx[k, m] * vx[m]
                    wy_ += iby[k, m] * vy[m]
                rhs[2 * a] = -f[2 * k] - dxx[a] * wx_ - dxy[a] * wy_
                rhs[2 * a + 1] = -f[2 * k + 1] - dxy[a] * wx_ - dyy[a] * wy_
                for bb in range(nsl):
                    m = slk[bb]
                    ix_ = ibx[k, m]
                    iy_ = iby[k, m]
                    mat[2 * a, 2 * bb] = dxx[a] * ix_
                    mat[2 * a, 2 * bb + 1] = dxy[a] * iy_
                    mat[2 * a + 1, 2 * bb] = dxy[a] * ix_
                    mat[2 * a + 1, 2 * bb + 1] = dyy[a] * iy_
                mat[2 * a, 2 * a] += exx[a]
                mat[2 * a, 2 * a + 1] += exy[a]
                mat[2 * a + 1, 2 * a] += exy[a]
                mat[2 * a + 1, 2 * a + 1] += eyy[a]
            sol = np.linalg.solve(mat, rhs)
            for a in range(nsl):
                vx[slk[a]] = sol[2 * a]
                vy[slk[a]] = sol[2 * a + 1]
            for k in range(n):
                ax = 0.0
                ay = 0.0
                for m in range(n):
                    ax += ibx[k, m] * vx[m]
                    ay += iby[k, m] * vy[m]
                step[2 * k] = ax
                step[2 * k + 1] = ay
        t = 1.0
        for _ls in range(_LINE_SEARCH):
            for k in range(n):
                trial_x[k] = px[k] + t * step[2 * k]
                trial_y[k] = py[k] + t * step[2 * k + 1]
            if _row_residual(e_x, e_y, rbx, rby, rho, g, trial_x, trial_y, ftmp) <= (1.0 - 1e-4 * t) ** 2 * fnorm2:
                break
            t *= 0.5
        dmax = 0.0
        for k in range(n):
            dmax = max(dmax, abs(trial_x[k] - px[k]), abs(trial_y[k] - py[k]))
            px[k] = trial_x[k]
            py[k] = trial_y[k]
        if it == 0:
            dmax0 = dmax
        if dmax <= tol_p or dmax <= forcing * dmax0:
            break


@njit(cache=True)
def _sweep(cix, ciy, row_start, sx, sy, pn, tbxx, tbxy, tbyy, inv_x, inv_y, row_inv, mx, my,
           tab_s, tab_mu, px, py, tol_p, newton, forcing):
    """One block Gauss-Seidel sweep over the lines along the rolling direction (one block per
    y-row), in place; returns ``|dp|_2^2`` of the sweep.

    Contact elements are stored row by row (``row_start``), each row leading edge first.
    ``sx, sy`` must hold the slip of the current tractions on entry (the driver recomputes it
    by FFT before every sweep). After a row's tractions change, the slip of the rows visited
    later in this sweep is corrected by the row's influence (the rows visited before get
    theirs from the next FFT): exact block Gauss-Seidel at half the work of correcting every
    row. ``tbxx, tbxy, tbyy`` are the transposed slip kernels (contiguous in x);
    ``inv_x[row_inv[r], :n, :n]`` (and ``inv_y``) the inverse of row r's line matrix.
    """
    nrow = row_start.shape[0] - 1
    nc = cix.shape[0]
    num = 0.0
    dpx = np.empty(nc)
    dpy = np.empty(nc)
    # the line matrices are leading blocks of one Toeplitz matrix (the kernel along x in the
    # same row)
    nmax = 0
    for r in range(nrow):
        nmax = max(nmax, row_start[r + 1] - row_start[r])
    lin_x = np.empty((nmax, nmax))
    lin_y = np.empty((nmax, nmax))
    for k in range(nmax):
        for m in range(nmax):
            lin_x[k, m] = tbxx[my - 1, m - k + mx - 1]
            lin_y[k, m] = tbyy[my - 1, m - k + mx - 1]
    for r in range(nrow):
        a = row_start[r]
        b = row_start[r + 1]
        n = b - a
        rbx = lin_x[:n, :n]
        rby = lin_y[:n, :n]
        e_x = np.empty(n)
        e_y = np.empty(n)
        qx = np.empty(n)
        qy = np.empty(n)
        for k in range(n):
            ax = sx[a + k]
            ay = sy[a + k]
            for m in range(n):
                ax -= rbx[k, m] * px[a + m]
                ay -= rby[k, m] * py[a + m]
            e_x[k] = ax
            e_y[k] = ay
            qx[k] = px[a + k]
            qy[k] = py[a + k]
        _row_newton(e_x, e_y, rbx, rby, inv_x[row_inv[r], :n, :n], inv_y[row_inv[r], :n, :n],
                    pn[a:b], qx, qy, tab_s, tab_mu, tol_p, newton, forcing)
        for k in range(n):
            nx = qx[k]
            ny = qy[k]
            dpx[k] = nx - px[a + k]
            dpy[k] = ny - py[a + k]
            px[a + k] = nx
            py[a + k] = ny
            num += dpx[k] * dpx[k] + dpy[k] * dpy[k]
        # slip of the rows still to be visited: per target row a 1-D correlation along x with
        # the kernel row of the row offset
        for r2 in range(r + 1, nrow):
            a2 = row_start[r2]
            j = ciy[a2] - ciy[a] + my - 1
            for l in range(a2, row_start[r2 + 1]):
                i0 = cix[l] - cix[a] + mx - 1
                ax = 0.0
                ay = 0.0
                for k in range(n):
                    i = i0 + k
                    ax += tbxx[j, i] * dpx[k] + tbxy[j, i] * dpy[k]
                    ay += tbxy[j, i] * dpx[k] + tbyy[j, i] * dpy[k]
                sx[l] += ax
                sy[l] += ay
    return num


def _sweep_solver(cix, ciy, row_start, pn, kern_t, line_inverses, mx, my, tab_s, tab_mu, px, py,
                  tolerance, max_iterations, max_newton, forcing, history, slip):
    """Block Gauss-Seidel sweeps (:func:`_sweep`) until the relative traction change of a sweep
    is below ``tolerance``. ``slip()`` returns the slip of the current tractions (FFT
    products). Returns (iterations, residual)."""
    tbxx, tbxy, tbyy = kern_t
    inv_x, inv_y, row_inv = line_inverses
    gmax = float(np.max(pn)) * float(tab_mu[0])
    tol_p = 1e-3 * tolerance * gmax
    residual = np.inf
    prev = np.inf
    newton = 1
    it = 0
    omega, best, stalled = 1.0, np.inf, 0
    for it in range(1, max_iterations + 1):
        sx, sy = slip()
        if omega < 1.0:
            old_x, old_y = px.copy(), py.copy()
        args = (cix, ciy, row_start, sx, sy, pn, tbxx, tbxy, tbyy, inv_x, inv_y, row_inv, mx, my,
                tab_s, tab_mu, px, py, tol_p, newton, forcing)
        # a wheel's copy compiled ahead of time (railcontact._compiled.SOLVER_EXPORTS: no
        # compile on a first call) where it loads and the arguments match, else numba's
        num = (_compiled.aot_kernel("_sweep", args) or _sweep)(*args)
        den = float(px @ px + py @ py)
        residual = math.sqrt(num / max(den, 1e-24 * gmax * gmax + 1e-300))
        if omega < 1.0:     # the relaxed step (the residual is the full sweep's change)
            px[:] = old_x + omega * (px - old_x)
            py[:] = old_y + omega * (py - old_y)
        if it <= history.shape[0]:
            history[it - 1] = residual
        if not np.isfinite(residual):
            break
        # one Newton step per line while the sweeps contract; solved lines from the first
        # sweep that does not (see the module docstring)
        if it >= 3 and residual > _SWITCH_RATIO * prev:
            newton = max_newton
        prev = residual
        if residual < tolerance:
            break
        # a stall (no halving of the best residual in _RELAX_STALL sweeps): relax the sweeps
        # (module docstring, "Falling friction")
        if residual < 0.5 * best:
            best, stalled = residual, 0
        else:
            stalled += 1
        if stalled >= _RELAX_STALL and omega > _RELAX_MIN:
            omega, best, stalled = omega * _RELAX_FACTOR, residual, 0
    return it, residual


# ----------------------------------------------------------------------------------------------
# Public driver
# ----------------------------------------------------------------------------------------------
_LINE_SEARCH = 12  # backtracking halvings of the Newton step
_MAX_NEWTON = 30  # cap on the Newton steps per line once lines are solved (module docstring)
_SWITCH_RATIO = 0.8  # a sweep reducing the residual by less than this switches to solved lines
_NEWTON_FORCING = 0.1  # a line is solved when its Newton step is < 0.1 x its first step
_RELAX_STALL = 10  # sweeps without halving the best residual that count as a stall
_RELAX_FACTOR = 0.5  # each stall halves the relaxation factor of the sweeps ...
_RELAX_MIN = 1.0 / 32.0  # ... down to this
_HISTORY = np.zeros(0)  # diagnostics: set to np.zeros(n) to record the first n sweep residuals
_FRICTION_TABLE_SLIP = np.concatenate([[0.0], np.logspace(-8, 1, 361)])


def _friction_table(friction_coefficient):
    if callable(friction_coefficient):
        mu = np.asarray(friction_coefficient(_FRICTION_TABLE_SLIP), dtype=float)
        mu = np.broadcast_to(mu, _FRICTION_TABLE_SLIP.shape).copy()
        check_range("friction_coefficient", mu, "-", 0.0, None, lower_closed=False)
        return _FRICTION_TABLE_SLIP.copy(), mu
    mu = float(check_range("friction_coefficient", friction_coefficient, "-", 0.0, None,
                           lower_closed=False))
    return np.zeros(1), np.array([mu])


#: Relative change of the pressure at which the rolling solver's normal problem stops. 1e-10
#: changes the pressure by at most 7e-10 of its peak against 1e-13 (40x20-60x20 grids, a0/b0
#: 0.2-5), far below the tangential tolerance (1e-3 by default), and takes a third to a half
#: of the iterations (measured 26 -> 7.5 ms at 60x20): most of a first call's set-up.
NORMAL_TOLERANCE = 1e-10


def clear_setup_cache():
    """Forget every cached set-up (influence coefficients, normal solutions, line inverses),
    e.g. to time a first call on a new contact."""
    for cached in (_kernels, _unit_normal_solution, _unit_setup, _normal_solution):
        cached.cache_clear()
    _UNIT_STARTS.clear()


def _grid(mx, my, scale, a0, b0, grid_shift):
    """Element centres ``(x, y)`` and sizes ``(dx, dy)`` of the grid over ``[-scale a0,
    scale a0] x [-scale b0, scale b0]``, moved ``grid_shift`` of an element along x. [m]"""
    dx = 2.0 * scale * a0 / mx
    dy = 2.0 * scale * b0 / my
    x = -scale * a0 + (np.arange(mx) + 0.5 + grid_shift) * dx
    y = -scale * b0 + (np.arange(my) + 0.5) * dy
    return x, y, dx, dy


def _shape_key(a0, b0):
    """The contact's shape a0/b0 rounded to 12 significant digits: the key of the normalised
    set-up (semi-axes from ``hertz_3d`` at another load have the same ratio to the last bits;
    the rounding moves b0 by at most 5e-13 of itself)."""
    return float(f"{a0 / b0:.12g}")


#: normalised normal solutions kept per grid for warm starts of a new shape (the nearest
#: a0/b0 solved on the same grid)
_UNIT_STARTS = {}


@lru_cache(maxsize=32)
def _unit_normal_solution(mx, my, scale, ratio, grid_shift):
    """The discrete Hertzian normal problem in normalised form: a0 = 1, b0 = 1/ratio,
    G = 1, N = 1, nu = 0 (its solution does not depend on nu: the kernel is ``(1 - nu)/G``
    times a geometric factor and so are the Hertz curvatures; E* = 1). Returns (pn, approach)
    on the grid; a real contact of the same shape scales them (``_normal_solution``).
    Started from the normalised solution of the nearest shape already solved on this grid,
    else from the Hertz pressure at the element centres."""
    if grid_shift > 0.0:
        # the grid moved +s is the mirror image (x -> -x) of the grid moved -s:
        # x_i(+s) = -x_(mx-1-i)(-s), and the normal problem is even in x (h and azz are), so
        # its pressure is the mirrored one: one normal solve for the pair (grid_shifts=2)
        pn, approach = _unit_normal_solution(mx, my, scale, ratio, -grid_shift)
        pn = np.ascontiguousarray(pn[::-1])
        pn.setflags(write=False)
        return pn, approach
    a0, b0 = 1.0, 1.0 / ratio
    x, y, dx, dy = _grid(mx, my, scale, a0, b0, grid_shift)
    azz = _kernels(mx, my, dx, dy, 1.0, 0.0, 1)[0]
    a_curv, b_curv, _ = hertz_curvatures(a0, b0, 1.0, 2.0, 0.0)
    h = a_curv * x[:, None] ** 2 + b_curv * y[None, :] ** 2
    starts = _UNIT_STARTS.setdefault((mx, my, scale, grid_shift), {})
    if starts:
        # the nearest shape solved on this grid: the pressures differ smoothly with the shape
        # (measured 30x20 and 60x20, a0/b0 1 -> 1.1: about half the iterations of the Hertz
        # start)
        near = min(starts, key=lambda r: abs(math.log(r / ratio)))
        start = starts[near]
    else:
        # the Hertz pressure at the element centres: 25-35 % fewer iterations than a flat
        # start (measured 40x20 and 60x20, a0/b0 = 0.2, 1, 5), same solution to 1e-12
        start = np.sqrt(np.maximum(1.0 - (x[:, None] / a0) ** 2 - (y[None, :] / b0) ** 2, 0.0))
        if not start.any():  # no element centre inside the ellipse: the flat start
            start = None
    pn, approach = solve_normal_3d(h, azz, 1.0, dx * dy, tolerance=NORMAL_TOLERANCE,
                                   initial_pressure=start)
    pn.setflags(write=False)
    if len(starts) >= 16:
        starts.pop(next(iter(starts)))
    starts[ratio] = pn
    return pn, approach


@lru_cache(maxsize=32)
def _unit_setup(mx, my, scale, ratio, poisson_ratio, transport_order):
    """Tangential kernels and FFT products of the normalised contact (a0 = 1, G = 1)."""
    _, _, dx, dy = _grid(mx, my, scale, 1.0, 1.0 / ratio, 0.0)
    kern = _kernels(mx, my, dx, dy, 1.0, poisson_ratio, transport_order)
    return kern, _SlipProduct(kern[1], kern[2], kern[3], mx, my)


@lru_cache(maxsize=16)
def _normal_solution(mx, my, scale, a0, b0, normal_load, youngs_modulus, poisson_ratio,
                     transport_order=1, grid_shift=0.0):
    """Grid, discrete normal solution, kernels and FFT products of one contact: the
    normalised set-up of its shape (``_unit_normal_solution``, ``_unit_setup``; one per
    a0/b0 and grid, and for the kernels nu) scaled to its size, load and material. Lengths
    scale with a0, the pressure with N/a0^2, the normal kernel with a0/G, the slip kernels
    with 1/G (the influence functions are 1/G times a length: Boussinesq-Cerruti), so a new
    load or size on a known shape costs no solve (checked against the direct solve in
    tests/test_reference_rolling3d.py)."""
    shear_modulus = youngs_modulus / (2.0 * (1.0 + poisson_ratio))
    ratio = _shape_key(a0, b0)
    x, y, dx, dy = _grid(mx, my, scale, a0, a0 / ratio, grid_shift)
    pn_unit, approach_unit = _unit_normal_solution(mx, my, scale, ratio, grid_shift)
    kern_unit, conv_unit = _unit_setup(mx, my, scale, ratio, poisson_ratio, transport_order)
    estar = youngs_modulus / (2.0 * (1.0 - poisson_ratio ** 2))
    pn = pn_unit * (normal_load / a0 ** 2)
    # displacements (and the approach) scale with N / (a0 E*) (unit problem: N = a0 = E* = 1)
    approach = approach_unit * normal_load / (a0 * estar)
    kern = (kern_unit[0] * (a0 / shear_modulus),) + tuple(k / shear_modulus
                                                          for k in kern_unit[1:])
    conv = conv_unit.scaled(1.0 / shear_modulus)
    for arr in (x, y, pn) + kern:
        arr.setflags(write=False)
    return x, y, dx, dy, pn, approach, kern, conv


class _SlipProduct:
    """``(u_x, u_y) = B p`` on the whole grid by FFT (circulant embedding of the Toeplitz
    kernels bxx, bxy, byy): two forward and two inverse real FFTs of size (2 mx, 2 my). Also
    holds the transposed kernels (contiguous in x) for the sweeps."""

    def __init__(self, bxx, bxy, byy, mx, my):
        self.shape = (2 * mx, 2 * my)
        ix = np.arange(-mx + 1, mx) % (2 * mx)
        iy = np.arange(-my + 1, my) % (2 * my)
        hats = []
        for kernel in (bxx, bxy, byy):
            emb = np.zeros(self.shape)
            emb[np.ix_(ix, iy)] = kernel
            hats.append(np.fft.rfft2(emb))
        self.hxx, self.hxy, self.hyy = hats
        self.mx, self.my = mx, my
        self.transposed = tuple(np.ascontiguousarray(k.T) for k in (bxx, bxy, byy))
        self._inverses = {}
        self._unit, self._factor = None, 1.0
        self._dense = None

    def scaled(self, factor):
        """The same products for the kernels times ``factor`` (a contact of the same shape,
        another material or size): shares the unit object's line inverses (divided by
        ``factor``)."""
        new = copy.copy(self)
        new.hxx, new.hxy, new.hyy = (h * factor for h in (self.hxx, self.hxy, self.hyy))
        new.transposed = tuple(k * factor for k in self.transposed)
        new._inverses, new._dense = {}, None
        new._unit, new._factor = self, factor
        return new

    def dense(self, cix, ciy):
        """The slip kernels between the contact elements as three dense (nc, nc) matrices
        ``(bxx, bxy, byy)[I, J] = b(x_I - x_J, y_I - y_J)``, cached for the last contact."""
        key = (cix.tobytes(), ciy.tobytes())
        if self._dense is None or self._dense[0] != key:    # (transposed kernels: y first)
            self._dense = (key,) + tuple(_dense_toeplitz(k, ciy, cix, self.my, self.mx)
                                         for k in self.transposed)
        return self._dense[1:]

    def line_inverses(self, lengths):
        """Inverses of the line matrices (the Toeplitz kernel of offsets along x in the same
        row, leading ``n x n`` block) for rows of the given lengths: ``(inv_x, inv_y,
        row_index)`` with ``inv_x[row_index[r], :n, :n]`` for row r. Cached (the rows of a
        grid's contact are the same for every creepage); memory ``2 k n_max^2`` doubles for k
        distinct row lengths (about 2 MB at 80x40)."""
        key = tuple(int(v) for v in lengths)
        if key not in self._inverses and self._unit is not None:
            inv_x, inv_y, row_index = self._unit.line_inverses(lengths)
            self._inverses = {key: (inv_x / self._factor, inv_y / self._factor, row_index)}
        if key not in self._inverses:
            tbxx, _, tbyy = self.transposed
            unique = sorted(set(key))
            nmax = unique[-1]
            inv_x = np.zeros((len(unique), nmax, nmax))
            inv_y = np.zeros((len(unique), nmax, nmax))
            for i, n in enumerate(unique):
                idx = np.arange(n)
                off = idx[None, :] - idx[:, None] + self.mx - 1
                inv_x[i, :n, :n] = np.linalg.inv(tbxx[self.my - 1][off])
                inv_y[i, :n, :n] = np.linalg.inv(tbyy[self.my - 1][off])
            row_index = np.searchsorted(unique, key).astype(np.int64)
            self._inverses = {key: (inv_x, inv_y, row_index)}  # one contact per grid
        return self._inverses[key]

    def __call__(self, pxa, pya):
        # scipy's FFT: about 1.5x faster than numpy's at these sizes (measured, 120 x 40)
        fx = scipy.fft.rfft2(pxa, s=self.shape)
        fy = scipy.fft.rfft2(pya, s=self.shape)
        ux = scipy.fft.irfft2(fx * self.hxx + fy * self.hxy, s=self.shape)
        uy = scipy.fft.irfft2(fx * self.hxy + fy * self.hyy, s=self.shape)
        return ux[: self.mx, : self.my], uy[: self.mx, : self.my]


def _slip(conv, px, py, cix, ciy, mx, my, wx, wy):
    """Slip ``w + B p`` of the contact elements: by FFT products (O(n log n)), or on small
    contacts by dense products (``DENSE_SLIP_MAX_ELEMENTS``)."""
    if cix.shape[0] <= DENSE_SLIP_MAX_ELEMENTS:
        bxx, bxy, byy = conv.dense(cix, ciy)
        return wx + bxx @ px + bxy @ py, wy + bxy @ px + byy @ py
    pxa = np.zeros((mx, my))
    pya = np.zeros((mx, my))
    pxa[cix, ciy] = px
    pya[cix, ciy] = py
    ux, uy = conv(pxa, pya)
    return wx + ux[cix, ciy], wy + uy[cix, ciy]


def _linearised_sensitivity(cix, ciy, xc, yc, px, py, sx, sy, gbound, stick, bxx, bxy, byy,
                            mx, my, dx, dy, spin_offset):
    """d(tx, ty, mz)/d(xi, eta, phi) of the discrete problem at its converged partition.

    Linearisation of the converged solution (Coulomb friction, fixed pressure): with
    ``s = w + B p`` and ``dw/d(xi, eta, phi) = (1, 0), (0, 1), (-y, x + spin_offset dx)``,
    a sticking element keeps ``ds = 0``; a slipping one keeps ``p = -g s/|s|``, so
    ``dp = -(g/|s|) (I - n n^T) ds`` with ``n = s/|s|``. One dense linear system of
    ``2 nc`` unknowns (nc contact elements), three right-hand sides (CONTACT's ``sens_tang``,
    ``src/m_solvpt.f90``, instead re-solves with perturbed creepages to about 1 %).
    The partition is assumed
    not to change under the perturbation (true almost everywhere; the derivative is one-sided
    where an element sits exactly on the stick/slip boundary).
    """
    nc = cix.shape[0]
    di = cix[:, None] - cix[None, :] + mx - 1
    dj = ciy[:, None] - ciy[None, :] + my - 1
    bm = np.empty((2 * nc, 2 * nc))
    bm[0::2, 0::2] = bxx[di, dj]
    bm[0::2, 1::2] = bxy[di, dj]
    bm[1::2, 0::2] = bxy[di, dj]
    bm[1::2, 1::2] = byy[di, dj]
    dw = np.zeros((2 * nc, 3))
    dw[0::2, 0] = 1.0
    dw[1::2, 1] = 1.0
    dw[0::2, 2] = -yc
    dw[1::2, 2] = xc + spin_offset * dx
    smag = np.hypot(sx, sy)
    slip = ~stick
    # slip rows: dp + K (B dp) = -K dw with K = (g/|s|)(I - n n^T); stick rows: B dp = -dw
    k = np.zeros((nc, 2, 2))
    safe = np.where(slip & (smag > 0), smag, 1.0)
    nx, ny = sx / safe, sy / safe
    c = np.where(slip & (smag > 0), gbound / safe, 0.0)
    k[:, 0, 0] = c * (1 - nx * nx)
    k[:, 0, 1] = -c * nx * ny
    k[:, 1, 0] = k[:, 0, 1]
    k[:, 1, 1] = c * (1 - ny * ny)
    # rows of the slip elements: [K_k B_k] and [K_k dw_k]
    b3 = bm.reshape(nc, 2, 2 * nc)
    kb = np.einsum("kab,kbn->kan", k, b3)
    w3 = dw.reshape(nc, 2, 3)
    kw = np.einsum("kab,kbn->kan", k, w3)
    mat = np.where(slip[:, None, None], kb, b3)
    rhs = np.where(slip[:, None, None], -kw, -w3)
    mat = mat.reshape(2 * nc, 2 * nc)
    idx = np.nonzero(np.repeat(slip, 2))[0]
    mat[idx, idx] += 1.0
    dp = np.linalg.solve(mat, rhs.reshape(2 * nc, 3))
    area = dx * dy
    dpx, dpy = dp[0::2], dp[1::2]
    return np.array([dpx.sum(axis=0) * area, dpy.sum(axis=0) * area,
                     (xc @ dpy - yc @ dpx) * area])


def _solve_grid(xi, eta, phi, normal_load, a0, b0, youngs_modulus, poisson_ratio, table,
                mx, my, scale, tolerance, max_iterations, spin_offset, initial=None,
                sensitivities=False, transport_order=1, grid_shift=0.0):
    x, y, dx, dy, pn, approach, kern, conv = _normal_solution(
        mx, my, scale, a0, b0, normal_load, youngs_modulus, poisson_ratio, transport_order,
        grid_shift)
    _, bxx, bxy, byy = kern
    contact = pn > 0
    if contact[0, :].any() or contact[-1, :].any() or contact[:, 0].any() or contact[:, -1].any():
        warnings.warn(
            f"the discrete contact reaches the edge of the potential contact area "
            f"(scale={scale:g}, {mx}x{my} grid); the solution may be truncated: increase scale "
            f"or the number of elements", RuntimeWarning, stacklevel=3)
    ncon_x = contact.any(axis=1).sum()
    ncon_y = contact.any(axis=0).sum()
    if ncon_x < 3 or ncon_y < 3:
        raise ValueError(f"mx and my must give at least 3 elements across the contact patch; "
                         f"got {ncon_x} x {ncon_y} with mx={mx}, my={my}")
    # contact elements stored row by row (lines along the rolling direction), leading edge first
    ix_all, iy_all = np.nonzero(contact)
    order = np.lexsort((-ix_all, iy_all))
    cix = ix_all[order].astype(np.int64)
    ciy = iy_all[order].astype(np.int64)
    row_start = np.concatenate([[0], np.nonzero(np.diff(ciy))[0] + 1, [cix.size]]).astype(np.int64)
    # the line solver needs each row's contact elements contiguous in x (a convex patch)
    if np.any(np.diff(cix)[np.diff(ciy) == 0] != -1):  # pragma: no cover - Hertzian is convex
        raise ValueError("the contact area must be convex along the rolling direction")
    xc = x[cix]
    yc = y[ciy]
    wx = xi - phi * yc
    wy = eta + phi * (xc + spin_offset * dx)
    pnc = pn[cix, ciy].astype(float)
    tab_s, tab_mu = table
    if initial is not None:
        if initial.px.shape == (mx, my):
            # warm start from a neighbouring case on the same grid
            px = np.array(initial.px[cix, ciy], dtype=float)
            py = np.array(initial.py[cix, ciy], dtype=float)
        else:
            # prolongation from another grid: each element takes the traction of the element
            # of that grid holding its centre, scaled by the ratio of the pressures (so the
            # ratio traction / friction bound is carried over)
            dxc = initial.x[1] - initial.x[0]
            dyc = initial.y[1] - initial.y[0]
            ic = np.clip(np.floor((xc - initial.x[0] + dxc / 2) / dxc).astype(int), 0,
                         initial.x.size - 1)
            jc = np.clip(np.floor((yc - initial.y[0] + dyc / 2) / dyc).astype(int), 0,
                         initial.y.size - 1)
            pn_c = initial.pn[ic, jc]
            ratio = np.where(pn_c > 0, pnc / np.where(pn_c > 0, pn_c, 1.0), 0.0)
            px = initial.px[ic, jc] * ratio
            py = initial.py[ic, jc] * ratio
        # clipped to the friction bound
        bound = tab_mu[0] * pnc
        mag = np.hypot(px, py)
        fac = np.where(mag > bound, bound / np.where(mag > 0, mag, 1.0), 1.0)
        px *= fac
        py *= fac
    else:
        px = np.zeros(cix.shape[0])
        py = np.zeros(cix.shape[0])
    iters, residual = _sweep_solver(
        cix, ciy, row_start, pnc, conv.transposed, conv.line_inverses(np.diff(row_start)), mx,
        my, tab_s, tab_mu, px, py, tolerance,
        max_iterations, _MAX_NEWTON, _NEWTON_FORCING, _HISTORY,
        lambda: _slip(conv, px, py, cix, ciy, mx, my, wx, wy))
    sx, sy = _slip(conv, px, py, cix, ciy, mx, my, wx, wy)  # from scratch: no round-off
    if not (residual < tolerance):
        raise RollingConvergenceError(
            f"3-D rolling solver did not converge: residual {residual:.3g} > tolerance="
            f"{tolerance:g} after max_iterations={max_iterations} sweeps (creepage_longitudinal="
            f"{xi:g}, creepage_lateral={eta:g}, spin={phi:g}, a0={a0:g}, b0={b0:g}, "
            f"mx={mx}, my={my})")
    area = dx * dy
    pxa = np.zeros((mx, my))
    pya = np.zeros((mx, my))
    sxa = np.zeros((mx, my))
    sya = np.zeros((mx, my))
    pxa[cix, ciy] = px
    pya[cix, ciy] = py
    sxa[cix, ciy] = sx
    sya[cix, ciy] = sy
    gmax = tab_mu[0] * pnc
    mag = np.hypot(px, py)
    slip_c = mag >= gmax * (1.0 - 1e-9)
    slip_c &= gmax > 0
    if tab_s.size > 1:
        # mu(|s|): slip where the traction is at its bound mu(|s|) pn. The bound is lagged by
        # one Newton step in the line solves, so to 1e-3 (measured: the stick elements' slip is
        # below 1e-3 of the creepage at tolerance 1e-3, not below the 1e-9 once used here,
        # which counted nearly every element as slipping)
        g_s = pnc * np.interp(np.hypot(sx, sy), tab_s, tab_mu)
        slip_c = (mag >= g_s * (1.0 - 1e-3)) & (g_s > 0)
    slip = np.zeros((mx, my), dtype=bool)
    slip[cix, ciy] = slip_c
    adhesion = contact & ~slip
    tx = float(px.sum() * area)
    ty = float(py.sum() * area)
    mz = float(np.sum(xc * py - yc * px) * area)
    sens = None
    if sensitivities:
        if tab_s.size > 1:
            raise ValueError("sensitivities are available for a constant friction_coefficient "
                             "only; got a slip-dependent one")
        sens = _linearised_sensitivity(cix, ciy, xc, yc, px, py, sx, sy, gmax, ~slip_c,
                                       bxx, bxy, byy, mx, my, dx, dy, spin_offset)
    return Rolling3DResult(
        tx=tx, ty=ty, mz=mz, normal_load=float(pn.sum() * area), px=pxa, py=pya,
        pn=np.array(pn), adhesion=adhesion, slip=slip, x=np.array(x), y=np.array(y),
        slip_x=sxa, slip_y=sya, approach=approach, iterations=int(iters),
        residual=float(residual), richardson=False, sensitivity=sens)


def solve_rolling_3d(creepage_longitudinal, creepage_lateral, spin, normal_load, a0, b0,
                     youngs_modulus, poisson_ratio, friction_coefficient, mx=40, my=20,
                     scale=1.08, tolerance=1e-6, max_iterations=500, richardson=False,
                     spin_offset=None, initial_guess=None, sensitivities=False,
                     transport_order=1, coarse_start=False, grid_shift=0.0):
    r"""Steady rolling of two quasi-identical elastic bodies: Kalker's exact theory, discretised.

    Solves the Hertzian normal problem numerically on the grid, then the frictional steady
    rolling problem with creepages and spin (see the module docstring for the method).
    Influence matrices and the normal solution are cached per grid and shape a0/b0 in
    normalised form (the kernels also per Poisson ratio) and scaled to each contact's size,
    load and material, so a batch of creepage cases on one contact, or a new load on a known
    shape, costs only the tangential iterations (``clear_setup_cache`` forgets them).

    Parameters
    ----------
    creepage_longitudinal : float
        Longitudinal creepage xi. [-]
    creepage_lateral : float
        Lateral creepage eta. [-]
    spin : float
        Spin creepage phi. [1/m]
    normal_load : float
        Normal load, > 0. [N]
    a0, b0 : float
        Hertzian semi-axes in rolling and lateral direction (e.g. from ``hertz_3d``). [m]
    youngs_modulus : float
        Young's modulus of both bodies. [Pa]
    poisson_ratio : float
        Poisson's ratio of both bodies, in [0, 0.5] (0.5: incompressible; nothing in the
        half-space influence functions is singular there). [-]
    friction_coefficient : float or callable
        Coulomb friction coefficient, or a vectorised function ``mu(slip)`` of the slip
        magnitude ``|s|`` (slip velocity over rolling speed) [-] (tabulated on 0 and
        1e-8..10 log-spaced, linear interpolation). [-]
    mx, my : int
        Elements in rolling and lateral direction. The error is first order in ``mx``.
    scale : float
        Potential contact area ``[-scale a0, scale a0] x [-scale b0, scale b0]``. [-]
    tolerance : float
        Relative change of the tractions per sweep at which to stop. [-]
    max_iterations : int
        Maximum number of Gauss-Seidel sweeps.
    richardson : bool
        If True, also solve on ``(2 mx, 2 my)`` and return ``2 F_fine - F_coarse`` for the
        forces and moment (the arrays are those of the fine grid).
    spin_offset : float, optional
        The rigid slip of the spin, ``w = (xi - phi y, eta + phi (x + spin_offset dx))``, is
        evaluated this fraction of an element upstream (towards the leading edge) of the
        element centre. Default: ``1/6`` with ``transport_order=1``, which reproduces CONTACT's
        published values to 5e-6 of mu N on every spin case of ``hertz3d_grid_convergence``
        (found by fitting; ``0``, the element centre, differs from CONTACT by up to 1e-2 of
        mu N at 30x30, halving with each grid refinement: an O(dx) difference that vanishes in
        the continuum limit); ``0`` with ``transport_order=2`` (its difference is centred on
        the element centre; measured: +-0.5 moves the pure-spin force by about 2 % of mu N at
        40x20, away from the converged value). [-]
    initial_guess : Rolling3DResult, optional
        Solution of a neighbouring case (e.g. the previous point of a creep curve or table)
        or of the same case on another grid over the same area (a coarse solve as the fine
        grid's start: each element takes the traction of the element holding its centre,
        scaled by the pressure ratio); its tractions, clipped to the friction bound, start
        the iteration.
        Only the number of sweeps changes, not the converged solution (to the tolerance).
    transport_order : {1, 2}
        Difference of the rolling (transport) term ``du/dx`` in the slip. 1 (default):
        Kalker's and CONTACT's first-order upwind difference ``(u(x) - u(x + dx)) / dx``,
        which reproduces CONTACT's published values. 2: the three-point upwind (BDF2-type)
        difference ``(3 u(x) - 4 u(x + dx) + u(x + 2 dx)) / (2 dx)``, centred on the element
        centre (so ``spin_offset`` defaults to 0), second order for smooth fields: the idea of
        Vollebregt and Wilders' FASTSIM2 (second-order integration along the rolling
        direction) applied to the exact theory. It converges to the same continuum (checked
        against CONTACT's converged values in the tests) with a much smaller error on the same
        grid on average, not a smaller maximum: the rest depends on where the contact edge
        falls inside its element, which is not a smooth function of the grid, and lateral
        creepage with spin has a large second-order error (measured over the 21
        grid-convergence cases: module docstring, ``benchmarks/bench_rolling3d.py``; max /
        RMS % of mu N: 40x20 1.33 / 0.50, 60x20 0.58 / 0.19, 70x20 0.92 / 0.44, 80x20
        0.50 / 0.17, against 0.93 / 0.64 at 40x20 with order 1). The cost per sweep is the
        same as order 1.
    coarse_start : bool
        Without ``initial_guess`` and for ``mx >= 32``, ``my >= 16``: first solve the case on
        ``(mx // 2, my // 2)`` to a relative traction change of 1e-2 and start from its
        prolongated solution (measured over the 21 grid-convergence cases: 9 instead of 13
        sweeps on the fine grid at 60x20; per case with the set-ups cached 40x20 9.0 -> 7.3 ms,
        80x40 101 -> 63 ms; the first call on a grid pays the coarse grid's set-up too). Only
        the number of sweeps changes, not the converged solution (to the tolerance).
        ``iterations`` then counts the sweeps of both grids.
    grid_shift : float
        The grid is moved this fraction of an element in the rolling direction, in
        [-0.5, 0.5]: element centres ``x_i = -scale a0 + (i + 1/2 + grid_shift) dx`` (the
        potential area moves with it; with ``richardson`` and ``coarse_start`` the other grid
        is moved the same fraction of its own element). Averaging the forces of
        ``grid_shift = -1/4`` and ``+1/4`` removes most of the error that depends on where the
        contact edges fall inside their elements (see ``creep_force_3d(..., grid_shifts=2)``);
        0 (default) is CONTACT's grid. [-]
    sensitivities : bool
        Also compute ``d(tx, ty, mz)/d(xi, eta, phi)`` (``Rolling3DResult.sensitivity``) by
        solving the problem linearised at the converged slip/stick partition: one dense
        solve of ``2 nc`` unknowns, nc the number of contact elements (measured: about 0.1 s
        at 40x20, nc = 540; it grows as nc^3, so several seconds at 80x40). Constant
        friction only. Checked against central differences of converged solutions in
        ``tests/test_reference_rolling3d.py``.

    Returns
    -------
    Rolling3DResult

    Raises
    ------
    ValueError
        Bad input, or a grid whose potential contact area does not contain the contact patch.
    RollingConvergenceError
        The iteration did not reach ``tolerance`` in ``max_iterations`` sweeps.

    Examples
    --------
    >>> r = solve_rolling_3d(1e-3, 0.0, 0.0, 1e5, 6e-3, 5e-3, 210e9, 0.28, 0.3)
    >>> round(r.tx / (0.3 * 1e5), 3)
    -0.329

    A creep curve: the influence matrices and the normal solution are computed once (cached
    on grid and shape), each further point costs the tangential sweeps only.

    >>> [round(solve_rolling_3d(xi, 0.0, 0.0, 1e5, 6e-3, 5e-3, 210e9, 0.28, 0.3).tx / 3e4, 3)
    ...  for xi in (5e-4, 1e-3, 2e-3)]
    [-0.174, -0.329, -0.582]
    """
    xi = float(check_range("creepage_longitudinal", creepage_longitudinal, "-", -1.0, 1.0))
    eta = float(check_range("creepage_lateral", creepage_lateral, "-", -1.0, 1.0))
    phi = float(check_range("spin", spin, "1/m"))
    normal_load = float(check_range("normal_load", normal_load, "N", 0.0, None,
                                    lower_closed=False))
    a0 = float(check_range("a0", a0, "m", 0.0, None, lower_closed=False))
    b0 = float(check_range("b0", b0, "m", 0.0, None, lower_closed=False))
    youngs_modulus = float(check_range("youngs_modulus", youngs_modulus, "Pa", 0.0, None,
                                       lower_closed=False))
    poisson_ratio = float(check_range("poisson_ratio", poisson_ratio, "-", 0.0, 0.5))
    mx = int(check_range("mx", mx, "-", 4, 4096))
    my = int(check_range("my", my, "-", 4, 4096))
    scale = float(check_range("scale", scale, "-", 1.0, 10.0,
                               condition="the potential contact area must contain the Hertzian ellipse"))
    tolerance = float(check_range("tolerance", tolerance, "-", 0.0, 0.1, lower_closed=False))
    max_iterations = int(check_range("max_iterations", max_iterations, "-", 1, None))
    if abs(phi) * max(a0, b0) > 1.0:
        raise ValueError(f"spin must be in [-1/max(a0, b0), 1/max(a0, b0)] [1/m] "
                         f"(rigid slip |phi| max(a0, b0) <= 1); got {phi:g}")
    table = _friction_table(friction_coefficient)
    args = (xi, eta, phi, normal_load, a0, b0, youngs_modulus, poisson_ratio, table)
    if transport_order not in (1, 2) or isinstance(transport_order, bool):
        raise ValueError(f"transport_order must be 1 or 2 [-]; got {transport_order!r}")
    transport_order = int(transport_order)
    if spin_offset is None:
        spin_offset = 1.0 / 6.0 if transport_order == 1 else 0.0
    spin_offset = float(check_range("spin_offset", spin_offset, "-", -1.0, 1.0))
    grid_shift = float(check_range("grid_shift", grid_shift, "-", -0.5, 0.5))
    start, start_sweeps = initial_guess, 0
    if coarse_start and initial_guess is None and mx >= 32 and my >= 16:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)  # a coarse grid may touch the edge
            try:
                start = _solve_grid(*args, mx // 2, my // 2, scale, max(tolerance, 1e-2),
                                    max_iterations, spin_offset, None, False, transport_order,
                                    grid_shift)
                start_sweeps = start.iterations
            except (RollingConvergenceError, ValueError):  # pragma: no cover - defensive
                start = None
    coarse = _solve_grid(*args, mx, my, scale, tolerance, max_iterations, spin_offset,
                         start, sensitivities, transport_order, grid_shift)
    if start_sweeps:
        coarse = dataclasses.replace(coarse, iterations=coarse.iterations + start_sweeps)
    if not richardson:
        return coarse
    # the coarse solution, prolongated, starts the fine grid
    fine = _solve_grid(*args, 2 * mx, 2 * my, scale, tolerance, max_iterations, spin_offset,
                       coarse, sensitivities, transport_order, grid_shift)
    return Rolling3DResult(
        tx=2 * fine.tx - coarse.tx, ty=2 * fine.ty - coarse.ty, mz=2 * fine.mz - coarse.mz,
        normal_load=fine.normal_load, px=fine.px, py=fine.py, pn=fine.pn,
        adhesion=fine.adhesion, slip=fine.slip, x=fine.x, y=fine.y, slip_x=fine.slip_x,
        slip_y=fine.slip_y, approach=fine.approach,
        iterations=coarse.iterations + fine.iterations, residual=max(coarse.residual,
                                                                      fine.residual),
        richardson=True,
        sensitivity=None if fine.sensitivity is None else 2 * fine.sensitivity - coarse.sensitivity)
