"""Table specifications: grid axes, tabulated variables, the point function, and the registry.

A :class:`TableSpec` says *what* to tabulate; :mod:`tablegen.build` does the (parallel) work and
:mod:`tablegen.netcdf` writes the file that :mod:`railcontact.tables` reads.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable

import numpy as np

__all__ = ["Axis", "Variable", "TableSpec", "RESOLUTIONS"]



#: Resolution names accepted by every spec (the spec maps them to node counts).
RESOLUTIONS = ("coarse", "default", "fine")


@dataclass
class Axis:
    """One grid axis.

    Attributes
    ----------
    name : str
        Variable name of the coordinate in the file (snake_case).
    nodes : ndarray
        Strictly ascending nodes.
    units : str
        UDUNITS string ("1" for dimensionless).
    long_name : str
        Human-readable description, saying what a dimensionless axis is normalised by.
    double_knots : tuple of float
        Interior nodes that get a double knot (the spline is C1 there, C2 elsewhere).
    out_of_range : {"error", "hold"}
        Behaviour beyond the last node (see :mod:`railcontact.tables`); below the first node
        it is always an error.
    comment : str
        Why the nodes are where they are.
    periodic : bool
        The tabulated functions are periodic along this axis with period
        ``nodes[-1] - nodes[0]`` (the values at both ends are equal): the spline is the
        periodic cubic interpolant, C2 across the seam (stored with two extra nodes, see
        :func:`railcontact.tables.periodic_stored_nodes`).
    """

    name: str
    nodes: np.ndarray
    units: str
    long_name: str
    double_knots: tuple = ()
    out_of_range: str = "error"
    comment: str = ""
    periodic: bool = False

    def __post_init__(self):
        self.nodes = np.asarray(self.nodes, dtype=float)
        if self.nodes.ndim != 1 or self.nodes.size < 4 or not np.all(np.diff(self.nodes) > 0):
            raise ValueError(f"axis {self.name!r}: nodes must be strictly ascending, >= 4")
        if self.out_of_range not in ("error", "hold"):
            raise ValueError(f"axis {self.name!r}: out_of_range must be 'error' or 'hold'")
        if self.periodic and self.double_knots:
            raise ValueError(f"axis {self.name!r}: a periodic axis has no double knots")


@dataclass
class Variable:
    """One tabulated variable.

    Attributes
    ----------
    name, units, long_name : str
    error_scale : float
        Errors are reported in units of this value (1 for variables already normalised by
        mu N), i.e. ``max |table - solver| / error_scale``.
    error_target : float
        Target for the maximum error on the off-grid check points, in units of error_scale.
    comment : str
    significant_digits : int, optional
        This variable's digits where the spec quantises (``TableSpec.significant_digits``);
        default the spec's.
    absolute_precision : float, optional
        A power of two ``q``: the spline coefficients are rounded to multiples of ``q`` (the
        B-splines sum to one, so the spline moves by at most ``q / 2``, in units of the
        variable) except where ``TableSpec.relative_precision_region`` keeps them to the
        significant digits. Many small coefficients then cost few bits, where relative digits
        would keep each of them to ``10^-digits`` of its own size. Declared by the coefficient
        variable's attribute ``absolute_precision``; the build's accuracy check measures the
        rounded spline.
    """

    name: str
    units: str
    long_name: str
    error_scale: float = 1.0
    error_target: float = 1e-4
    comment: str = ""
    significant_digits: int | None = None
    absolute_precision: float | None = None

    def __post_init__(self):
        q = self.absolute_precision
        if q is not None and not (q > 0.0 and np.log2(q) == np.round(np.log2(q))):
            raise ValueError(f"variable {self.name!r}: absolute_precision must be a power of "
                             f"two > 0 [units of the variable]; got {q!r}")


@dataclass
class TableSpec:
    """What to tabulate.

    Attributes
    ----------
    name : str
        Table name; the file is ``<name>.nc``.
    title : str
    axes : callable
        ``axes(resolution) -> list[Axis]``.
    function : callable
        ``function(points) -> ndarray (n, n_var)``, vectorised over ``points`` (n, D) in table
        coordinates. Must be a module-level function (it is shipped to dask workers by
        reference).
    variables : list of Variable
    references : str
        Thesis section and method.
    method : str
        How the values are computed (the direct solver and its settings).
    check_points : callable, optional
        ``check_points(axes, n, rng) -> ndarray (n, D)``: off-grid points where the table is
        compared with ``function``. Default: uniform random in the grid box.
    n_check : dict
        Number of check points per resolution.
    chunk_size : int
        Grid points per dask task.
    requires : tuple of str
        Modules that must import for the spec to be buildable.
    attributes : dict
        Extra global attributes (e.g. the fixed Poisson ratio).
    hidden : bool
        Not built by ``build`` without ``--only`` (self-tests).
    build_attributes : callable, optional
        ``build_attributes() -> dict`` of global attributes computed at build time (e.g. the
        hash of the solver's source file).
    node_values_float32 : bool
        Store the node values (for viewers; the spline uses the float64 coefficients only) in
        float32, flagged by the variable attribute ``node_value_precision = "float32"``: halves
        a large table's file.
    coefficients_float32 : bool
        Store the spline coefficients in float32 too, flagged by the coefficient variable's
        attribute ``coefficient_precision = "float32"`` (readers evaluate in float64; the
        rounding, 6e-8 relative, is far below a table's interpolation error): halves the file
        again.
    significant_digits : int, optional
        With float32 node values and coefficients: keep only this many significant decimal
        digits of each stored number (netCDF-4 quantisation, GranularBitRound; the trailing
        mantissa bits are zeroed, so zlib compresses them away and any netCDF reader reads
        plain floats). Declared by the variables' attribute ``significant_digits``; the
        reader checks the nodes to ``10^(1 - digits)``. The spline stays exactly C2 (its
        coefficients change by at most about ``10^-digits`` of their size).
    node_values_stored : bool
        Store the node values (default). False writes only the spline (format 3): each
        variable ``V`` is then a scalar variable that carries the attributes and names its
        coefficient array, and the coefficients carry HDF5 Fletcher-32 checksums in place of
        the load's check against the node values; the node values are the spline at the
        nodes. For a table whose file would pass its size limit with them.
    reduce : callable, optional
        ``reduce(axes) -> (points, assemble)`` for tables with symmetries: ``function`` is
        called only on ``points`` (m, D), and ``assemble(values)`` maps the (m, n_var) results
        to the values on the whole grid, shape (n_var, n_1, ..., n_D). Default: every grid
        point is computed.
    reuse_coordinates : callable, optional
        ``reuse_coordinates(attrs, name, nodes) -> nodes``: an earlier file's node coordinates
        (its global attributes ``attrs``, the coordinate variable ``name``) in this spec's
        coordinates, for ``build_table(reuse_nodes=...)`` across a change of an axis's
        coordinate that keeps its nodes' physical points. Default: unchanged.
    reusable_points : callable, optional
        ``reusable_points(attrs, points) -> bool mask or None``: for
        ``build_table(reuse_nodes=...)`` with an earlier file whose ``method`` differs from
        this spec's (a solver setting changed in part of the domain), the grid points whose
        earlier values this method would give too; ``None`` refuses the file. Default: only a
        file of the same ``method`` is reused.
    relative_precision_region : callable, optional
        ``relative_precision_region(axes) -> bool array`` broadcastable to the coefficient
        grid (one entry per stored node of each axis): the coefficients that keep their
        significant digits although their variable has an ``absolute_precision`` (next to a
        zero of the function, where combinations of coefficients cancel and the slope is read
        from values far below the absolute quantum). Default: none.
    relative_precision_comment : str
        Where ``relative_precision_region`` is, in words (the coefficient attribute
        ``absolute_precision_comment`` quotes it).
    coefficient_symmetry : callable, optional
        ``coefficient_symmetry(stored_axes, knots, coefficients) -> coefficients``, applied
        to the fitted coefficients (n_var, n_1, ..., n_D) before they are rounded: makes a
        symmetry of the table hold bit for bit in the coefficients, so that rounding (which
        is odd, round(-x) = -round(x)) keeps it. The fit of exactly symmetric values is
        symmetric only to round-off, and a coefficient that lies within round-off of a
        rounding tie (as a rebuild's reused node values make many) rounds one way and its
        image the other. Default: none.
    analytic_points : callable, optional
        ``analytic_points(points) -> bool mask`` of the points that ``function`` answers
        without its expensive solver (limits). A build that reuses an earlier file's node
        values (``build_table(reuse_nodes=...)``) recomputes only these.
    """

    name: str
    title: str
    axes: Callable
    function: Callable
    variables: list
    references: str
    method: str
    check_points: Callable | None = None
    n_check: dict = field(default_factory=lambda: {"coarse": 200, "default": 1000,
                                                   "fine": 4000})
    chunk_size: int = 64
    requires: tuple = ()
    attributes: dict = field(default_factory=dict)
    hidden: bool = False
    build_attributes: Callable | None = None
    reduce: Callable | None = None
    node_values_float32: bool = False
    coefficients_float32: bool = False
    significant_digits: int | None = None
    node_values_stored: bool = True
    relative_precision_region: Callable | None = None
    relative_precision_comment: str = ""
    coefficient_symmetry: Callable | None = None
    analytic_points: Callable | None = None
    reuse_coordinates: Callable | None = None
    reusable_points: Callable | None = None

    def available(self):
        """``None`` if buildable, else the reason (a module that does not import)."""
        import importlib  # noqa: PLC0415

        for mod in self.requires:
            try:
                importlib.import_module(mod)
            except Exception as exc:  # noqa: BLE001  (any import failure makes it unavailable)
                return f"{mod} does not import ({exc.__class__.__name__}: {exc})"
        return None

    def grid(self, resolution):
        """Axes and the (n, D) array of all grid points (C order, last axis fastest)."""
        if resolution not in RESOLUTIONS:
            raise ValueError(f"resolution must be one of {list(RESOLUTIONS)}; got "
                             f"{resolution!r}")
        axes = self.axes(resolution)
        mesh = np.meshgrid(*[a.nodes for a in axes], indexing="ij")
        return axes, np.stack([m.ravel() for m in mesh], axis=1)

    def make_check_points(self, axes, resolution, seed=20261122):
        rng = np.random.default_rng(seed)
        n = self.n_check[resolution]
        if self.check_points is not None:
            return np.asarray(self.check_points(axes, n, rng), dtype=float)
        lo = np.array([a.nodes[0] for a in axes])
        hi = np.array([a.nodes[-1] for a in axes])
        return lo + (hi - lo) * rng.random((n, len(axes)))
