"""Coordinates and reader of the exact-theory creep table (``tables/creep_exact.nc``).

The reader's compiled kernels (one source for its scalar and vectorised paths) are in
:mod:`railcontact._exact_kernels`; they read the per-contact buffer that
:class:`ExactCreepTable` fills, and this module imports no numba (an FMU build's
ahead-of-time copy of the kernels serves it, see :mod:`railcontact._compiled`).

The steady rolling problem of Kalker's exact theory with Hertzian pressure depends on the
inputs only through a0/b0, Poisson's ratio and three normalised creepages (scale invariance of
the half-space equations; J.J. Kalker, *Three-dimensional elastic bodies in rolling contact*,
Kluwer, 1990, Ch. 2). With Kalker's coefficients C_ij(a0/b0, nu), the saturation creepage
``w_sat = pi^2 (1 + nu) mu p0 / E`` and ``p0 = 3 N / (2 pi a0 b0)``:

    u_x = C11 xi_x / w_sat,   u_y = C22 xi_y / w_sat,   sigma = sqrt(a0 b0) C23 phi / w_sat,
    v = (u_x, u_y + sigma),   tau = sign(phi) |phi| sqrt((b0 C11)^2 + (a0 C22)^2) / w_sat.

In these units Kalker's linear theory reads ``T / (mu N) = -(3 pi / 4) v``. The table's five
axes are

    log_aspect_ratio  ln(a0/b0)
    poisson_ratio     nu
    creepage_coordinate  s = (2 / pi) atan(rho / w), w = sqrt(1 + tau^2), rho = |v|, *signed*
                         (see below)
    creepage_angle    theta = atan2(v_y, v_x), periodic over [-pi, pi]
    spin_coordinate   tau (signed with phi)

and the variables are the force in the frame of v, ``T / (mu N) = -(f_par e + f_perp e_perp)``
with ``e = (cos theta, sin theta)``, ``e_perp = (-sin theta, cos theta)``, the spin moment
``M_z / (mu N sqrt(a0 b0))`` and the stick area fraction.

**Why these coordinates (smoothness).** A table that evaluates only a symmetry-reduced part
through absolute values has kinks on the symmetry planes (xi_x = 0, phi = 0). This table
instead covers every sign, and computes only a quarter with the solver:

* ``theta`` runs over the full circle with a periodic spline (C2 across xi_x = 0 and the seam
  at theta = +-pi);
* ``tau`` is signed and the table symmetric data on both sides of 0 (C2 across phi = 0);
* ``s`` is signed: the point (-s, theta + pi) is the same creepage as (s, theta), with the frame
  components negated. Fitting that double cover makes every straight line through v = 0 a
  C2 curve of the spline (the polar origin is not an end of the grid);
* ``s`` reaches 1 (|v| = infinity), where the force is mu N against the physical creepage
  (xi_x, xi_y), a direction proportional to (v_x / C11, v_y / C22), and the moment and the
  stick area vanish (full sliding with the spin negligible against the creepage), so every
  finite creepage is inside the grid; the saturation near rho = 1 has crowded nodes.
* ``s`` measures the creepage against ``w = sqrt(1 + tau^2)``: with large spin the force turns
  from the spin's to the creepage's direction where |v| is about |tau| (both are rigid slips
  over the saturation creepage), so that transition stays in the middle of the axis at every
  spin (with ``s = rho / sqrt(1 + rho^2)`` it fell into the last interval, and a table of that
  kind erred by up to 18 % of mu N at |tau| > 5). ``w`` is smooth and even in tau, so the
  spline stays C2 across phi = 0.
* ``s`` is the arctangent of rho / w: far past saturation the force approaches its
  full-sliding limit like 1/rho (the spin's share), which is *linear* in 1 - s, so the last
  interval (rho / w from 6 to infinity) interpolates it; with the algebraic form
  ``rho / sqrt(rho^2 + w^2)`` of the tables before 2026-11-27, 1/rho went like sqrt(1 - s)
  and that interval erred by up to 1.6 % of mu N (a 1-D fit through the same nodes:
  0.002 %). atan is odd and analytic, so the double cover stays C2 through v = 0.

Symmetries used to fill the grid from the computed quarter (v_x >= 0, tau >= 0, s >= 0):
S1, mirroring y: (v_x, v_y, tau) -> (v_x, -v_y, -tau), (f_par, f_perp, M) -> (f_par, -f_perp,
-M); S3, reversing x at fixed spin: (v_x, v_y, tau) -> (-v_x, v_y, tau), (f_par, f_perp, M) ->
(f_par, -f_perp, M); the double cover (s, theta) -> (-s, theta + pi), (f_par, f_perp) -> -(f_par,
f_perp). The stick fraction is unchanged by all three.
"""

from __future__ import annotations

import threading

import numpy as np

__all__ = ["exact_table_coordinates", "exact_table_inverse", "creepage_coordinate",
           "creepage_magnitude"]


from .creep_common import (  # noqa: E402,F401  (the kernels' too)
    CREEPAGE_COORDINATE_FORM, JACOBIAN_RHO_MIN, SPIN_WEIGHT)

# Large batches run their points on numba's threads; numba's default threading layer
# (workqueue) aborts the process when two Python threads launch parallel loops at once, so the
# reader's batch calls take this lock (each call already uses every core).
_BATCH_LOCK = threading.Lock()
_new_tuple = tuple.__new__

#: Points a contact (a0/b0, nu) is asked for before the reader makes its buffer, the table
#: summed over the a0/b0 and nu axes (a slab of the other three; 3.9 MB on the grid of
#: 2026-11-27). The slab costs about as much as this many points cost more without it
#: (measured 2026-11-27: 14-19 ms for the slab; a scalar point 7.7-8.6 us on the
#: five-dimensional spline, 1.1-1.9 us on the slab), so a contact that stays pays at most
#: about twice the least, and one whose a0/b0 changes at every call (a wheel profile's
#: contact) pays no slab: until then every call made one, 14-17 ms a call.
SLAB_AFTER_POINTS = 4096

#: Points of changing contacts in one batch from which the reader evaluates them in the order
#: of their a0/b0 (the table's outermost axis): 10-15 % less time per point on a batch of
#: random contacts (2026-11-28), more than the sort costs from about this many points.
SORT_AFTER_POINTS = 256

#: Points asked at one Poisson's ratio (any contacts) before the reader sums the table over
#: nu there (:meth:`ExactCreepTable.prepare`: 0.1-0.3 s, after which a point of a changing
#: contact costs about a third).
NU_SLAB_AFTER_POINTS = 20000


def _table_batch(coef):
    """The batch kernel of any contact for ``coef``: the file's coefficients (float32) or
    those summed over nu (float64, its own ahead-of-time copy)."""
    return "creep_table_batch" if coef.dtype == np.float32 else "creep_table_batch_nu"


def _batch(name, n, *args):
    """Run the batch kernel ``name`` of :mod:`railcontact._exact_kernels` on ``n`` points:
    its threaded copy ``<name>_parallel`` (under the lock) for at least two tasks of
    ``PARALLEL_CHUNK`` points, else the serial one (same values, bit for bit). Where the
    serial kernel was compiled ahead of time (a wheel) that copy runs every batch: no
    numba import and no compilation on a first call (:mod:`railcontact._compiled`)."""
    aot = _compiled.aot_batch(name, args)
    if aot is not None:
        aot(*args)
        return
    kernels = _compiled.exact_kernels()
    if n < 2 * kernels.PARALLEL_CHUNK:
        getattr(kernels, name)(*args)
        return
    with _BATCH_LOCK:
        getattr(kernels, name + "_parallel")(*args)


def creepage_coordinate(rho, tau=0.0):
    """Compactified creepage magnitude ``s = (2 / pi) atan(rho / w)``, ``w^2 = 1 + tau^2``
    (1 at rho = inf; odd in rho). [-]"""
    rho = np.asarray(rho, dtype=float)
    w = np.sqrt(1.0 + (SPIN_WEIGHT * np.asarray(tau, dtype=float)) ** 2)
    with np.errstate(over="ignore", invalid="ignore"):
        big = np.abs(rho) > 1e150
        r = np.where(big, 0.0, rho)
        return np.where(big, np.sign(rho), (2.0 / np.pi) * np.arctan(r / w))


def creepage_magnitude(s, tau=0.0):
    """Inverse of :func:`creepage_coordinate`: ``rho = w tan(pi s / 2)`` (inf at |s| = 1)."""
    s = np.asarray(s, dtype=float)
    w = np.sqrt(1.0 + (SPIN_WEIGHT * np.asarray(tau, dtype=float)) ** 2)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(np.abs(s) >= 1.0, np.sign(s) * np.inf, w * np.tan(0.5 * np.pi * s))


def exact_table_inverse(log_aspect_ratio, poisson_ratio, creepage_coordinate_, creepage_angle,
                        spin_coordinate, contact):
    """Physical inputs on a reference contact for table coordinates.

    Parameters
    ----------
    log_aspect_ratio, poisson_ratio, creepage_coordinate_, creepage_angle, spin_coordinate :
        array_like
        Table coordinates (see the module docstring); ``|s| < 1``.
    contact : dict
        ``area_radius`` sqrt(a0 b0) [m], ``normal_load`` [N], ``youngs_modulus`` [Pa],
        ``friction_coefficient`` [-] of the reference contact.

    Returns
    -------
    dict
        ``creepage_longitudinal``, ``creepage_lateral``, ``spin``, ``normal_load``, ``a0``,
        ``b0``, ``youngs_modulus``, ``poisson_ratio``, ``friction_coefficient`` (arrays).
    """
    from .kalker import kalker_coefficients  # noqa: PLC0415

    g = np.exp(np.asarray(log_aspect_ratio, dtype=float))
    nu = np.broadcast_to(np.asarray(poisson_ratio, dtype=float), g.shape)
    a0 = contact["area_radius"] * np.sqrt(g)
    b0 = contact["area_radius"] / np.sqrt(g)
    c = kalker_coefficients(g, nu)
    c11, c22, c23 = (np.asarray(getattr(c, k), dtype=float) for k in ("c11", "c22", "c23"))
    n_load, e_mod = contact["normal_load"], contact["youngs_modulus"]
    mu = contact["friction_coefficient"]
    p0 = 1.5 * n_load / (np.pi * a0 * b0)
    w_sat = np.pi**2 * (1.0 + nu) * mu * p0 / e_mod
    rho = creepage_magnitude(creepage_coordinate_, spin_coordinate)
    v_x = rho * np.cos(creepage_angle)
    v_y = rho * np.sin(creepage_angle)
    phi = np.asarray(spin_coordinate, dtype=float) * w_sat / np.hypot(b0 * c11, a0 * c22)
    sigma = np.sqrt(a0 * b0) * c23 * phi / w_sat
    return dict(creepage_longitudinal=v_x * w_sat / c11,
                creepage_lateral=(v_y - sigma) * w_sat / c22,
                spin=phi,
                normal_load=np.full(g.shape, n_load), a0=a0, b0=b0,
                youngs_modulus=np.full(g.shape, e_mod), poisson_ratio=nu,
                friction_coefficient=np.full(g.shape, mu))


def exact_table_coordinates(creepage_longitudinal, creepage_lateral, spin, a0, b0,
                            poisson_ratio, saturation_creepage, coefficients):
    """Table coordinates ``(ln(a0/b0), nu, s, theta, tau)`` of physical inputs.

    Parameters
    ----------
    creepage_longitudinal, creepage_lateral : array_like
        xi_x, xi_y. [-]
    spin : array_like
        phi. [1/m]
    a0, b0 : array_like
        Semi-axes. [m]
    poisson_ratio : array_like
        nu. [-]
    saturation_creepage : array_like
        ``w_sat = pi^2 (1 + nu) mu p0 / E``, > 0. [-]
    coefficients : tuple of array_like
        Kalker's (C11, C22, C23) at (a0/b0, nu). [-]

    Returns
    -------
    tuple of ndarray
    """
    xi_x, xi_y, phi, a0, b0, nu, w_sat = (np.asarray(v, dtype=float) for v in (
        creepage_longitudinal, creepage_lateral, spin, a0, b0, poisson_ratio,
        saturation_creepage))
    c11, c22, c23 = coefficients
    v_x = c11 * xi_x / w_sat
    v_y = (c22 * xi_y + np.sqrt(a0 * b0) * c23 * phi) / w_sat
    tau = phi * np.hypot(b0 * c11, a0 * c22) / w_sat
    rho = np.hypot(v_x, v_y)
    return (np.log(a0 / b0), nu, creepage_coordinate(rho, tau), np.arctan2(v_y, v_x), tau)


# --------------------------------------------------------------------------------------------
# Reader: one compiled kernel for the scalar (FMU) and the vectorised path
# --------------------------------------------------------------------------------------------

import math  # noqa: E402
from functools import lru_cache  # noqa: E402

from . import _compiled  # noqa: E402  (the compiled kernels: ahead of time, else numba)
from .creep_common import CreepForce3D, ExactCreepSolution3D, spin_coefficient  # noqa: E402

#: Table name and the axes it must have, in order.
TABLE_NAME = "creep_exact"
AXES = ("log_aspect_ratio", "poisson_ratio", "creepage_coordinate", "creepage_angle",
        "spin_coordinate")
VARIABLES = ("force_ratio_parallel", "force_ratio_perpendicular", "spin_moment_ratio",
             "stick_area_fraction")


def _cubic_basis_values(t, i, x):
    """The four cubic B-splines that do not vanish on span ``i`` of the knot vector ``t``,
    at ``x`` (arrays of the same shape): shape ``x.shape + (4,)``, ``N_{i-3+r}(x)`` in column
    ``r``. Cox-de Boor's triangular recurrence (Piegl and Tiller, *The NURBS Book*,
    Algorithm A2.2), in numpy: the exact table loads without a compiled kernel."""
    n = np.zeros(np.shape(x) + (4,))
    n[..., 0] = 1.0
    left = np.zeros_like(n)
    right = np.zeros_like(n)
    for j in range(1, 4):
        left[..., j] = x - t[i + 1 - j]
        right[..., j] = t[i + j] - x
        saved = np.zeros(np.shape(x))
        for r in range(j):
            temp = n[..., r] / (right[..., r + 1] + left[..., j - r])
            n[..., r] = saved + right[..., r + 1] * temp
            saved = left[..., j - r] * temp
        n[..., j] = saved
    return n


def basis_polynomials(t):
    """Power-form coefficients of the cubic B-splines on every span of the knot vector ``t``.

    Returns ``(n_coef, 4, 4)``: for span ``i`` (``t[i] <= x < t[i+1]``, 3 <= i < n_coef) and
    ``r`` = 0..3, ``N_{i-3+r}(x) = sum_k P[i, r, k] (x - t[i])^k`` (rows 0-2 and empty spans
    are zero). Computed from Cox-de Boor (:func:`_cubic_basis_values`) at four Chebyshev
    points of the span in the scaled variable ``(x - t[i]) / h`` (well conditioned), then
    rescaled; the evaluator then needs no division (C. de Boor, *A Practical Guide to
    Splines*, Ch. X: the pp-form of a B-spline).
    """
    t = np.ascontiguousarray(t, dtype=float)
    n = t.size - 4
    poly = np.zeros((n, 4, 4))
    spans = np.arange(3, n)
    h = t[spans + 1] - t[spans]
    spans, h = spans[h > 0.0], h[h > 0.0]
    w_nodes = 0.5 - 0.5 * np.cos(np.pi * (np.arange(4) + 0.5) / 4.0)
    x = t[spans, None] + h[:, None] * w_nodes                     # (span, point)
    vals = _cubic_basis_values(t, spans[:, None], x)              # (span, point, r)
    q = np.linalg.solve(np.vander(w_nodes, 4, increasing=True), vals)   # (span, k, r)
    poly[spans] = np.swapaxes(q / (h[:, None] ** np.arange(4))[:, :, None], 1, 2)
    return poly


def _packed(head, knots, polys, data):
    """A kernel buffer (:mod:`railcontact._exact_kernels`: ``HEAD`` / ``TABLE_HEAD``): the
    header, the axes' knots and basis polynomials, ``data``, then res (14) and scratch (336).
    Returns ``(buffer, res, the view of the last data block)``."""
    buf = np.concatenate([np.asarray(head, dtype=float)] + list(knots)
                         + [p.ravel() for p in polys] + list(data) + [np.zeros(14 + 336)])
    o = buf.size - 350
    return buf, buf[o:o + 14], buf[o - data[-1].size:o]


@lru_cache(maxsize=256)
def _kalker_pair(a0_over_b0, poisson_ratio):
    """Kalker's (C11, C22, C23) for one contact (cached: a vehicle's contact keeps its a0/b0)."""
    from .kalker import kalker_coefficients  # noqa: PLC0415

    c = kalker_coefficients(a0_over_b0, poisson_ratio)
    return float(c.c11), float(c.c22), float(c.c23)


class ExactCreepTable:
    """Kalker's exact theory from the table ``creep_exact``: forces, spin moment, stick area
    and their Jacobian, at the speed of a lookup.

    The table (see the module docstring for its coordinates) was computed by the discretised
    solver :func:`railcontact.reference.rolling3d.solve_rolling_3d` at the exact method's
    default setting (Richardson-extrapolated from 30 x 20 and 60 x 20 elements on two grids
    moved -1/4 and +1/4 of an element; 36 lateral elements where a0/b0 < 0.87 and |tau| >
    2.75; the file attribute ``solver_grid`` says which setting a file was built with); its
    recorded accuracy (file attributes, per variable: ``max_abs_error``, ``rms_error`` on
    off-node check points against that solver) and the solver's own error against the
    converged exact theory are in ``docs/tables.md``.

    **Domain.** Every creepage and spin of either sign; Poisson's ratio 0-0.5; a0/b0 and the
    spin coordinate |tau| within the file's axes (0.1-10 and 20). Outside them the ``solver``
    answers: :func:`railcontact.creep3d.load_exact_table` (what ``creep_force_3d(...,
    method="exact_table")`` and the FMU use) attaches ``creep_solution_3d(method="exact",
    tolerance=1e-4)``, the table's own setting (milliseconds per call), so every finite input gets an answer; without a solver a
    ValueError names the input and the range. |T| <= mu N always; the spline is C2 in every
    input (across xi_x = 0 and phi = 0 too), C1 only where it clips an overshoot to mu N. (The
    exact theory itself is only C1 at zero creepage without spin, where the force bends as
    Carter's 2 r - r |r|: the C2 spline follows it on nodes graded towards zero.)

    **Speed.** A contact (a0/b0, nu) is first evaluated on the five-dimensional spline (about
    8 us a scalar call, Kalker's coefficients included); once it has been asked for
    :data:`SLAB_AFTER_POINTS` points (scalar calls and batch points together) the reader sums
    the table over a0/b0 and nu for it once (its buffer, 14-19 ms; 16 kept) and its calls
    take about 1.5-2 us. The values are the same to round-off either way (tested).

    Parameters
    ----------
    table : railcontact.tables.Table
        The loaded file ``creep_exact.nc``.
    solver : callable, optional
        ``solver(xi_x, xi_y, phi, N, a0, b0, E, nu, mu, sensitivities=bool)`` returning an
        object with the fields tx, ty, spin_moment, stick_area_fraction, normalised_creepage
        and sensitivity of :class:`railcontact.creep_common.ExactCreepSolution3D`, used beyond
        the table's axes.
    """

    def __init__(self, table, solver=None):
        names = tuple(a["name"] for a in table.axes)
        attrs = getattr(table, "attrs", {})
        weight = attrs.get("creepage_coordinate_spin_weight")
        form = attrs.get("creepage_coordinate_form")
        if names != AXES or tuple(table.variables) != VARIABLES or weight is None \
                or float(weight) != SPIN_WEIGHT or form != CREEPAGE_COORDINATE_FORM:
            from .tables import TableFileError  # noqa: PLC0415

            raise TableFileError(f"table file {str(table.path)!r} has axes {names}, "
                                 f"variables {tuple(table.variables)}, "
                                 f"creepage_coordinate_spin_weight {weight!r} and "
                                 f"creepage_coordinate_form {form!r}; this reader needs "
                                 f"{AXES}, {VARIABLES}, {SPIN_WEIGHT} and "
                                 f"{CREEPAGE_COORDINATE_FORM!r} (rebuild with `python -m "
                                 "tablegen build --only creep_exact`)")
        self.table = table
        self.path = table.path
        #: Callable answering beyond the table (``solver(xi_x, xi_y, phi, N, a0, b0, E, nu,
        #: mu, sensitivities=...)`` -> ExactCreepSolution3D), or None: a ValueError there.
        self.solver = solver
        self._knot_list = [np.ascontiguousarray(a["knots"], dtype=float) for a in table.axes]
        self._knots = np.ascontiguousarray(np.concatenate(self._knot_list))
        self._kstart = np.cumsum([0] + [len(t) for t in self._knot_list[:-1]]).astype(np.int64)
        self._poly_list = [basis_polynomials(t) for t in self._knot_list]
        self._poly = np.ascontiguousarray(np.concatenate(self._poly_list))
        # the file's float32 coefficients, variable last, as the process holds them once
        # (memory-mapped from the user cache: :mod:`railcontact._table_store`); the kernels
        # evaluate them as they are, accumulating in float64
        self._coef = np.ascontiguousarray(np.moveaxis(table.coefficients, 0, -1))
        self._empty_slab = np.zeros((1, 1, 1, 4))
        self._g_range = tuple(float(np.exp(table.axes[0]["nodes"][k])) for k in (0, -1))
        self._log_g = (float(table.axes[0]["nodes"][0]), float(table.axes[0]["nodes"][-1]))
        self.tau_max = float(table.axes[4]["nodes"][-1])
        self._buffers = {}
        self._uses = {}       # points asked of each contact without a buffer yet
        self._kernel = None   # the compiled scalar kernels, resolved with the first contact
        self._force_kernel = None
        self._point = None
        self._table_force = None
        self._tbuf = None     # the table buffer of creep_table_point, made with the first call
        self._nu_slabs = {}   # nu -> (coefficients summed over nu (n0, 1, n2, n3, n4, 4),
        #                               their kernels creep_table_point, creep_table_force)
        self._nu_uses = {}    # points asked at each nu without its sum yet

    @classmethod
    def from_file(cls, path=None, directory=None, solver=None):
        """Load ``creep_exact.nc`` (default: :func:`railcontact.tables.default_table_path`).

        ``solver``: what answers beyond the table's a0/b0 and spin axes (see the class
        docstring); :func:`railcontact.creep3d.load_exact_table` passes the exact solver at
        the table's own setting.
        """
        from .tables import Table, default_table_path  # noqa: PLC0415

        path = default_table_path(TABLE_NAME, directory) if path is None else path
        return cls(Table.from_file(path, expected_name=TABLE_NAME), solver)

    # -- one contact's (ln g, nu) summed out once -------------------------------------------
    def _slab_of(self, log_g, nu):
        """The coefficients summed over the (ln g, nu) axes at one contact: (n_s, n_theta,
        n_tau, 4)."""
        w = []
        find_span, cubic_basis = _compiled.find_span(), _compiled.cubic_basis()
        for d, x in ((0, log_g), (1, nu)):
            t = self._knot_list[d]
            i = find_span(t, self._coef.shape[d], x)
            b, db = np.empty(4), np.empty(4)
            cubic_basis(t, i, x, b, db, np.empty(12))
            w.append((i, b))
        (i0, w0), (i1, w1) = w
        block = self._coef[i0 - 3:i0 + 1, i1 - 3:i1 + 1]
        return np.ascontiguousarray(np.einsum("p,q,pq...->...", w0, w1, block))

    # -- scalar path (FMU) ------------------------------------------------------------------
    def step(self, xi_x, xi_y, phi, normal_load, a0, b0, youngs_modulus, poisson_ratio,
             friction_coefficient, jacobian=True):
        """One contact, plain floats: ``(tx, ty, mz, stick_area_fraction,
        normalised_creepage, jacobian)``.

        The FMU's path: one kernel call evaluates forces [N], moment [N m], stick area
        fraction [-], the normalised creepage |v| (the modified strip theory's z) [-] and
        (``jacobian=True``) the (3, 3) array d(tx, ty, mz)/d(xi_x, xi_y, phi) [N, N, N m per
        unit creepage and per 1/m] together. Inputs are checked as in
        :meth:`creep_solution_3d` (same errors); beyond the table the solver answers.
        """
        values = self.step_values(xi_x, xi_y, phi, normal_load, a0, b0, youngs_modulus,
                                   poisson_ratio, friction_coefficient, jacobian)
        if values is None:      # not plain floats, no contact, or beyond the table
            return self._step_array((xi_x, xi_y, phi, normal_load, a0, b0, youngs_modulus,
                                     poisson_ratio, friction_coefficient), jacobian)
        return (values[0], values[1], values[2], values[3], values[4],
                np.array(values[5:]).reshape(3, 3) if jacobian else None)

    def step_values(self, xi_x, xi_y, phi, normal_load, a0, b0, youngs_modulus,
                     poisson_ratio, friction_coefficient, jacobian=True):
        """:meth:`step`'s fast path, flat: the list ``[tx, ty, mz, stick_area_fraction,
        normalised_creepage, d(tx, ty, mz)/d(xi_x, xi_y, phi) row by row (9 entries)]``
        (units as :meth:`step`; the Jacobian entries are stale unless ``jacobian``), or None
        where :meth:`step` takes its array path instead (inputs not finite numbers in range,
        no contact, a0/b0 beyond the table, overflow, |tau| beyond the table). The FMU's creep
        effect calls this once per step."""
        try:    # NaN, inf, out-of-range and non-numbers all fail (or raise) here
            key = (a0 / b0, poisson_ratio)
            entry = self._buffers.get(key)
            if entry is None:
                entry = self._entry(key, 1)
                if entry is None:       # the five-dimensional spline (any contact)
                    if not self._table_point(xi_x, xi_y, phi, normal_load, a0, b0,
                                             youngs_modulus, poisson_ratio,
                                             friction_coefficient, jacobian):
                        return None
                    return self._tres.tolist()
            if not self._kernel(entry[0], xi_x, xi_y, phi, normal_load, a0, b0,
                                youngs_modulus, friction_coefficient, jacobian):
                return None
        except (TypeError, ValueError, ArithmeticError):
            return None
        return entry[1].tolist()

    def _entry(self, key, n):
        """The contact buffer of ``key = (a0/b0, nu)`` once the contact has been asked for
        :data:`SLAB_AFTER_POINTS` points in all (then made, memoised), else None: the caller
        evaluates the five-dimensional spline. (Ski rental: the buffer's slab costs about as
        much as that many points cost more without it, so a contact that stays pays at most
        twice the best, and one that changes every step, as a0/b0 of a wheel profile does,
        never pays the slab.)"""
        uses = self._uses.get(key, 0) + n
        if uses < SLAB_AFTER_POINTS:
            if len(self._uses) >= 1024:
                self._uses.clear()
            self._uses[key] = uses
            return None
        self._uses.pop(key, None)
        return self._buffer(*key)

    def _table_point(self, *args):
        """:func:`railcontact._exact_kernels.creep_table_point` at one point (results in
        ``self._tres``, ``self._tmv``): on the coefficients summed over nu at the point's nu
        where that sum is made (:meth:`prepare`), else on the file's."""
        if self._tbuf is None:
            self._make_table_buffer()
        nu_slab = self._nu_coefficients(args[7], 1)
        if nu_slab is not None:
            return nu_slab[1](self._tbuf, nu_slab[0], *args)
        return self._point(self._tbuf, self._coef, *args)

    def _nu_coefficients(self, nu, n):
        """``(coefficients summed over nu at nu, their kernel)`` once Poisson's ratio ``nu``
        has been asked for :data:`NU_SLAB_AFTER_POINTS` points (any contacts), else None.
        (Ski rental again: the sum costs about what that many points cost more without it.
        A material keeps its nu while its ellipses change; the FMU prepares its nu at
        initialisation.)"""
        entry = self._nu_slabs.get(nu)
        if entry is not None:
            return entry
        try:
            uses = self._nu_uses.get(nu, 0) + n
        except TypeError:
            return None
        if uses < NU_SLAB_AFTER_POINTS:
            if len(self._nu_uses) >= 1024:
                self._nu_uses.clear()
            self._nu_uses[nu] = uses
            return None
        self.prepare(nu)
        return self._nu_slabs.get(nu)

    def prepare(self, poisson_ratio):
        """Sum the table over Poisson's ratio at ``poisson_ratio`` now, so that every contact
        of that material, however its ellipse and load change, is evaluated on 4 x 64
        instead of 16 x 64 coefficients per variable (:meth:`step_values`, the public scalar
        call and the arrays of changing contacts).

        The values are the file's to round-off (the sum is held in float64). The sum is made
        once per machine and Poisson's ratio: about 0.1-0.5 s and a 66 MB file in the user
        cache (:func:`railcontact._table_store.derived`), which every later process maps
        read-only (the pages of the mapped table it reads are given back to the operating
        system as it goes; the two most recent Poisson's ratios are kept per process). Made by the
        reader itself once a Poisson's ratio has been asked for :data:`NU_SLAB_AFTER_POINTS`
        points of changing contacts.

        Parameters
        ----------
        poisson_ratio : float
            Poisson's ratio, in [0, 0.5]. [-]
        """
        from ._table_store import derived, release_pages  # noqa: PLC0415
        from ._validation import check_range  # noqa: PLC0415

        nu = float(poisson_ratio)
        check_range("poisson_ratio", nu, "-", 0.0, 0.5)
        if nu in self._nu_slabs:
            return
        t = self._knot_list[1]
        i = _compiled.find_span()(t, self._coef.shape[1], nu)
        w, dw = np.empty(4), np.empty(4)
        _compiled.cubic_basis()(t, i, nu, w, dw, np.empty(12))
        coef = self._coef

        def summed():
            out = np.empty((coef.shape[0], 1) + coef.shape[2:])
            for p in range(coef.shape[0]):     # one a0/b0 plane at a time (9 MB of the file)
                block = coef[p, i - 3:i + 1]
                plane = out[p, 0]
                np.multiply(block[0], w[0], out=plane)
                for q in range(1, 4):
                    plane += w[q] * block[q]
                release_pages(block)
            return out

        # once per machine and Poisson's ratio (mapped from the user cache, shared by every
        # process and FMU instance), like the table's own coefficients
        from pathlib import Path  # noqa: PLC0415

        out = (derived(self.path, f"nu-{nu.hex()}", summed)
               if self.path is not None and Path(self.path).is_file() else summed())
        if self._tbuf is None:
            self._make_table_buffer()
        if len(self._nu_slabs) >= 2:
            self._nu_slabs.pop(next(iter(self._nu_slabs)))
        self._nu_slabs[nu] = (out, _compiled.creep_table_point(self._tbuf, out),
                              _compiled.creep_table_force(self._tbuf, out))
        self._nu_uses.pop(nu, None)

    def _make_table_buffer(self):
        """The buffer of :func:`railcontact._exact_kernels.creep_table_point`: the five axes'
        knots and basis polynomials, Kalker's interpolant (the data of
        :func:`railcontact.kalker.kalker_coefficients` within its table), res and scratch."""
        from .kalker import kalker_interpolant  # noqa: PLC0415

        kx, kc, nu_nodes = kalker_interpolant()
        head = [len(t) - 4 for t in self._knot_list] + [
            self.tau_max, self._log_g[0], self._log_g[1], kx.size] + list(nu_nodes)
        tbuf, self._tres, _ = _packed(head, self._knot_list, self._poly_list,
                                      [kx, kc.ravel()])
        # (indexing the memoryview gives Python floats, cheaper than numpy's scalars)
        self._tmv = memoryview(self._tres)
        if self._point is None:
            self._point = _compiled.creep_table_point(tbuf, self._coef)
            self._table_force = _compiled.creep_table_force(tbuf, self._coef)
        self._tbuf = tbuf

    def _buffer(self, g, nu):
        """``(buffer, res view, slab view)`` of one contact for the kernels ``creep_contact``
        and ``creep_contact_force``, memoised, or None (a0/b0 beyond the table, nu outside
        [0, 0.5], not plain numbers)."""
        g, nu = float(g), float(nu)
        got = self._buffers.get((g, nu))
        if got is not None:
            return got
        if not (0.0 <= nu <= 0.5 and 0.0 < g < math.inf):
            return None
        log_g = math.log(g)
        if not self._log_g[0] <= log_g <= self._log_g[1]:
            return None
        c11, c22, c23 = _kalker_pair(g, nu)
        slab = self._slab_of(log_g, nu)
        t2, t3, t4 = self._knot_list[2:]
        head = [slab.shape[0], slab.shape[1], slab.shape[2], self.tau_max, c11, c22, c23, nu]
        buf, res, data = _packed(head, [t2, t3, t4], self._poly_list[2:], [slab.ravel()])
        entry = (buf, res, data.reshape(slab.shape))
        if self._kernel is None:
            self._kernel = _compiled.creep_contact(buf)
            self._force_kernel = _compiled.creep_contact_force(buf)
        if len(self._buffers) >= 16:
            self._buffers.clear()
        self._buffers[(g, nu)] = entry
        return entry

    def _step_array(self, args, jacobian):
        res, jac, _ = self._evaluate(args, jacobian)
        if res.ndim != 1:
            raise ValueError("step takes one contact (scalar inputs); got arrays of shape "
                             f"{res.shape[:-1]} (use creep_solution_3d)")
        return (float(res[0]), float(res[1]), float(res[2]), float(res[3]), float(res[4]),
                jac if jacobian else None)

    # -- many contacts, checked by the caller (the vehicle FMU) -------------------------------
    def evaluate_contacts(self, xi_x, xi_y, phi, normal_load, a0, b0, youngs_modulus,
                          poisson_ratio, friction_coefficient, jacobian=True):
        """K contacts, each its own ellipse, load and friction, in one compiled call: the
        vehicle FMU's step.

        The inputs are length-K float64 arrays (``youngs_modulus`` and ``poisson_ratio`` may
        be scalars) that the caller has checked: finite, normal load > 0, a0, b0 and the
        friction coefficient > 0. No further checks are made here. Contacts that the table
        does not cover (a0/b0 or spin beyond its axes) are answered by the attached solver,
        as :meth:`creep_solution_3d` does.

        Returns
        -------
        res : ndarray, shape (K, 5)
            tx [N], ty [N], mz [N m], stick area fraction [-], normalised creepage |v| [-].
        jac : ndarray, shape (K, 3, 3)
            d(tx, ty, mz)/d(xi_x, xi_y, phi) (stale unless ``jacobian``).
        """
        k = len(xi_x)
        args = [np.ascontiguousarray(v, dtype=float) for v in (
            xi_x, xi_y, phi, normal_load, a0, b0)]
        e_mod = np.ascontiguousarray(np.broadcast_to(np.asarray(youngs_modulus, float), (k,)))
        nu = np.ascontiguousarray(np.broadcast_to(np.asarray(poisson_ratio, float), (k,)))
        mu = np.ascontiguousarray(friction_coefficient, dtype=float)
        if self._tbuf is None:
            self._make_table_buffer()
        coef = self._coef
        if k and np.all(nu == nu[0]):        # one material: its sum over nu, when made
            nu_slab = self._nu_coefficients(float(nu[0]), k)
            coef = coef if nu_slab is None else nu_slab[0]
        r = np.empty((k, 14))
        ok = np.zeros(k, dtype=bool)
        _batch(_table_batch(coef), k, self._tbuf, coef, *args, e_mod, nu, mu,
               bool(jacobian), 4, r, ok)
        if not ok.all():      # beyond the table (or an overflow): the checked array path
            f = np.nonzero(~ok)[0]
            res_f, jac_f, _ = self._evaluate(tuple(v[f] for v in (*args, e_mod, nu, mu)),
                                             jacobian)
            r[f, :5] = res_f
            r[f, 5:] = jac_f.reshape(-1, 9)
        return r[:, :5], r[:, 5:].reshape(k, 3, 3)

    # -- vectorised path ----------------------------------------------------------------------
    def _one_contact(self, checked, jacobian):
        """``(res, jac)`` when the contact inputs are scalars and every point is answered by
        the table (one compiled loop over the creepages on the contact's buffer), else
        None."""
        xi_x, xi_y, phi, n_load, a0, b0, e_mod, nu, mu = checked
        if not all(np.ndim(v) == 0 for v in (n_load, a0, b0, e_mod, nu, mu)):
            return None
        n_load, a0, b0, e_mod, nu, mu = (float(v) for v in (n_load, a0, b0, e_mod, nu, mu))
        if not (b0 > 0.0 and a0 > 0.0):
            return None
        cre = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (xi_x, xi_y, phi)))
        shape = cre[0].shape
        key = (a0 / b0, nu)
        entry = self._buffers.get(key) or self._entry(key, max(cre[0].size, 1))
        if entry is None:       # (a new contact, few points: the five-dimensional spline)
            return None
        flat = [np.array(c, dtype=float).reshape(-1) for c in cre]  # copies: no broadcast
        # views into the compiled kernel (numba warns: they become read-only in numpy)
        r = np.empty((flat[0].size, 14))
        ok = np.empty(flat[0].size, dtype=bool)
        _batch("creep_contact_batch", flat[0].size, entry[0], flat[0], flat[1], flat[2],
               n_load, a0, b0, e_mod, mu, jacobian, r, ok)
        if not ok.all():
            return None
        return r[:, :5].reshape(shape + (5,)), r[:, 5:].reshape(shape + (3, 3))

    def _evaluate(self, args, jacobian, forces_only=False):
        from ._validation import check_creep_inputs  # noqa: PLC0415

        checked = check_creep_inputs(*args)   # any creepage: the table reaches full sliding
        one = self._one_contact(checked, jacobian)
        if one is not None:
            return one + (checked,)
        arrays = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in checked))
        shape = arrays[0].shape
        xi_x, xi_y, phi, n_load, a0, b0, e_mod, nu, mu = (np.ravel(v) for v in arrays)
        n = xi_x.size
        res = np.zeros((n, 5))
        res[:, 3] = 1.0
        jac = np.zeros((n, 3, 3))
        contact = (n_load > 0.0) & (mu > 0.0) & (a0 > 0.0) & (b0 > 0.0)
        with np.errstate(all="ignore"):
            g = np.where(contact, a0 / np.where(b0 > 0.0, b0, 1.0), 1.0)
            log_g = np.log(g)
            w_sat = np.pi * (1.0 + nu) * mu * 1.5 * n_load / (a0 * b0 * e_mod)
        inside = contact & (log_g >= self._log_g[0]) & (log_g <= self._log_g[1]) \
            & np.isfinite(w_sat) & (w_sat > 0.0)
        idx = np.nonzero(inside)[0]
        ok = np.zeros(n, dtype=bool)
        if idx.size:
            one = bool(np.all(log_g[idx] == log_g[idx[0]]) and np.all(nu[idx] == nu[idx[0]]))
            r = np.zeros((idx.size, 14))
            o = np.zeros(idx.size, dtype=bool)
            if one:     # one contact (without its buffer yet: the five-dimensional spline)
                key = (float(g[idx[0]]), float(nu[idx[0]]))
                entry = self._buffers.get(key)
                slab = self._empty_slab if entry is None else entry[2]
                c = [np.full(idx.size, v) for v in _kalker_pair(*key)]
                with np.errstate(all="ignore"):
                    _batch("creep_batch", idx.size, self._coef, slab, entry is not None,
                           self._knots, self._kstart, self._poly, self.tau_max, xi_x[idx],
                           xi_y[idx], phi[idx], mu[idx] * n_load[idx], a0[idx], b0[idx],
                           w_sat[idx], c[0], c[1], c[2], log_g[idx], nu[idx], jacobian, r, o)
            else:       # every point its own contact: the scalar path's kernel, in a loop
                if self._tbuf is None:
                    self._make_table_buffer()
                coef = self._coef
                if np.all(nu[idx] == nu[idx[0]]):   # one material, many contacts
                    nu_slab = self._nu_coefficients(float(nu[idx[0]]), idx.size)
                    coef = coef if nu_slab is None else nu_slab[0]
                if idx.size >= SORT_AFTER_POINTS:
                    # in the order of a0/b0, the coefficients' outermost axis: neighbouring
                    # points read neighbouring planes (each point's values are its own: the
                    # same bits in any order); grouped into 256 bins of ln(a0/b0) across the
                    # table's range, which numpy sorts by radix (10,001 points: 44 us against
                    # 700 us for a sort of the floats, 70 ns a point)
                    lo, hi = self._log_g
                    bins = ((log_g[idx] - lo) * (255.0 / (hi - lo))).astype(np.uint8)
                    idx = idx[np.argsort(bins, kind="stable")]
                with np.errstate(all="ignore"):
                    _batch(_table_batch(coef), idx.size, self._tbuf, coef, xi_x[idx],
                           xi_y[idx], phi[idx], n_load[idx], a0[idx], b0[idx], e_mod[idx],
                           nu[idx], mu[idx], jacobian, 2 if forces_only else 4, r, o)
            o &= np.isfinite(r[:, :3]).all(axis=1)
            res[idx[o]] = r[o, :5]
            jac[idx[o]] = r[o, 5:].reshape(-1, 3, 3)
            ok[idx[o]] = True
        fallback = contact & ~ok
        if np.any(fallback):    # beyond the table: the solver at the table's own setting
            f = np.nonzero(fallback)[0]
            if self.solver is None:
                self._refuse(g[f], phi[f], n_load[f], a0[f], b0[f], e_mod[f], nu[f], mu[f])
            sol = self.solver(xi_x[f], xi_y[f], phi[f], n_load[f], a0[f], b0[f], e_mod[f],
                              nu[f], mu[f], sensitivities=jacobian)
            res[f, 0], res[f, 1], res[f, 2] = sol.tx, sol.ty, sol.spin_moment
            res[f, 3] = sol.stick_area_fraction
            res[f, 4] = sol.normalised_creepage
            if jacobian:
                jac[f] = sol.sensitivity
        return res.reshape(shape + (5,)), jac.reshape(shape + (3, 3)), checked

    def _refuse(self, g, phi, n_load, a0, b0, e_mod, nu, mu):
        """ValueError for inputs beyond the table when no solver is attached."""
        lo, hi = self._g_range
        bad_g = (g < lo) | (g > hi)
        if np.any(bad_g):
            raise ValueError(f"a0/b0 must be in [{lo:g}, {hi:g}] [-] (range of the table "
                             f"{self.path.name}; creep3d.load_exact_table attaches the solver "
                             f"beyond it); got {g[bad_g][0]:g}")
        raise ValueError(f"spin must give a spin coordinate |tau| <= {self.tau_max:g} [1/m] "
                         f"(range of the table {self.path.name}; creep3d.load_exact_table "
                         f"attaches the solver beyond it); got {phi[0]:g}")

    def creep_force_3d(self, creepage_longitudinal, creepage_lateral, spin, normal_load, a0, b0,
                       youngs_modulus, poisson_ratio, friction_coefficient):
        """Creep force on the wheel, ``CreepForce3D(tx, ty)`` [N]; inputs as
        :func:`railcontact.creep_force_3d`."""
        try:    # the scalar path of step_values, summing only the two forces
            key = (a0 / b0, poisson_ratio)
            entry = self._buffers.get(key) or self._entry(key, 1)
            if entry is not None:
                # the kernel returns (tx, ty) or raises ArithmeticError (the array path);
                # CreepForce3D(tx, ty) without namedtuple's Python-level __new__: 0.2 us
                return _new_tuple(CreepForce3D, self._force_kernel(
                    entry[0], creepage_longitudinal, creepage_lateral, spin, normal_load, a0,
                    b0, youngs_modulus, friction_coefficient))
            # any contact: the forces-only kernel on the coefficients summed over nu (once
            # the reader has made that sum) or on the file's
            if self._tbuf is None:
                self._make_table_buffer()
            nu_slab = self._nu_coefficients(poisson_ratio, 1)
            coef, kernel = (self._coef, self._table_force) if nu_slab is None \
                else (nu_slab[0], nu_slab[2])
            return _new_tuple(CreepForce3D, kernel(
                self._tbuf, coef, creepage_longitudinal, creepage_lateral, spin, normal_load,
                a0, b0, youngs_modulus, poisson_ratio, friction_coefficient))
        except (TypeError, ValueError, ArithmeticError):
            pass
        res = self._evaluate((creepage_longitudinal, creepage_lateral, spin, normal_load, a0,
                              b0, youngs_modulus, poisson_ratio, friction_coefficient),
                             False, forces_only=True)[0]
        return CreepForce3D(res[..., 0][()], res[..., 1][()])

    def creep_solution_3d(self, creepage_longitudinal, creepage_lateral, spin, normal_load, a0,
                          b0, youngs_modulus, poisson_ratio, friction_coefficient,
                          sensitivities=True):
        """Forces, spin moment, stick area and (``sensitivities``) the Jacobian, as
        :class:`railcontact.creep3d.ExactCreepSolution3D` (``stick_width_ratio``, ``fields``
        and ``iterations`` are not tabulated: None)."""
        res, jac, checked = self._evaluate(
            (creepage_longitudinal, creepage_lateral, spin, normal_load, a0, b0, youngs_modulus,
             poisson_ratio, friction_coefficient), sensitivities)
        xi_x, xi_y, phi, n_load, a0_, b0_, e_mod, nu, mu = checked
        shape = res.shape[:-1]
        phi_c = np.broadcast_to(spin_coefficient(xi_x, xi_y, phi, a0_, b0_), shape)
        return ExactCreepSolution3D(
            res[..., 0][()], res[..., 1][()], res[..., 3][()], None, res[..., 4][()],
            np.asarray(phi_c)[()], np.ones(shape, dtype=bool)[()], res[..., 2][()],
            jac[()] if sensitivities else None, None, None)

    def creep_force_jacobian_3d(self, creepage_longitudinal, creepage_lateral, spin,
                                normal_load, a0, b0, youngs_modulus, poisson_ratio,
                                friction_coefficient):
        """d(tx, ty, mz)/d(xi_x, xi_y, phi), shape ``(..., 3, 3)``: rows tx [N], ty [N],
        mz [N m]; columns per unit xi_x [-], xi_y [-], phi [1/m]."""
        return self._evaluate((creepage_longitudinal, creepage_lateral, spin, normal_load, a0,
                               b0, youngs_modulus, poisson_ratio, friction_coefficient),
                              True)[1][()]
