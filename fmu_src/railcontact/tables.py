r"""Reader for the smooth (C2) lookup tables built by ``tablegen`` (``python -m tablegen build``).

A table file is a CF-1.8 netCDF file (see :data:`TABLE_FORMAT_VERSION`) holding, for each
tabulated variable,

* its values at the grid nodes (a variable on the coordinate dimensions; a table with
  symmetries, format 2, stores them on the block of the grid that was computed; format 3
  stores none: the variable is a scalar carrying the attributes, for a table that would pass
  its size limit with them), and
* the coefficients of the tensor-product cubic B-spline that interpolates them
  (``<variable>_bspline_coefficients``), with one knot vector per axis (``<axis>_knots``).

The spline is exact at the nodes (it *interpolates* them: not-a-knot end conditions), C2
everywhere except at the double knots (listed per axis in the ``double_knots`` attribute, e.g.
the saturation line of a creep curve normalised by its saturation creepage), where it is C1 and
does not ring past the kink. The file therefore describes its own interpolant completely: any
de Boor evaluator (e.g. ``scipy.interpolate.NdBSpline``, or 30 lines of C) reproduces it from the
attributes alone.

Evaluation here is pure numpy/numba (no netCDF or xarray after loading): a compiled
tensor-product de Boor kernel (:mod:`railcontact._spline_kernels`, loaded on the first
evaluation) evaluates all variables of a table at once, with first and second partial
derivatives. Loading checks the stored spline against the node values with the same kernel
(compiled ahead of time in a wheel or an FMU: no numba, and no scipy; a format-3 file: the
HDF5 checksums of its coefficients, and that they are finite).

Out-of-grid behaviour (an explicit choice per axis, attribute ``out_of_range``):

``"error"``
    a coordinate outside ``[first node, last node]`` raises ``ValueError`` naming the axis,
    its range, unit and the offending value (the default);
``"hold"``
    the variable is constant beyond the last node (used only where the physics makes it so,
    e.g. full sliding beyond the saturation creepage; the file states it). The derivative
    along that axis is zero there.

No silent clamping is done anywhere else.

References
----------
.. [1] J.B. Nielsen, New Developments in the Theory of Wheel/Rail Contact Mechanics,
   IMM-PHD-1998-51, DTU, 1998, Sec. 2.5.4 (USETAB and the kinks of linear interpolation).
.. [2] C. de Boor, A Practical Guide to Splines, Springer, 1978 (B-spline evaluation).
.. [3] L. Piegl, W. Tiller, The NURBS Book, 2nd ed., Springer, 1997, Algorithm A2.3.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

import numpy as np

from ._validation import check_range

__all__ = [
    "TABLE_FORMAT_VERSION", "TABLE_FORMAT_SPLINE_ONLY", "TableFileError",
    "TableAccuracyWarning", "bspline_knots",
    "fit_tensor_bspline", "TensorSpline", "Table", "default_table_path",
    "tables_directory", "periodic_bspline_knots", "periodic_stored_nodes",
]

#: Version of the table file layout written for tables whose node values are stored on a
#: block of the grid (global attribute ``railcontact_table_format``; see
#: :mod:`tablegen.netcdf`). Bumped when the layout changes incompatibly. Version 1 (every
#: node's value stored) is still written for the other tables and read.
TABLE_FORMAT_VERSION = 2
#: Version of the layout without node values (the spline's coefficients only, with HDF5
#: Fletcher-32 checksums; each variable a scalar that carries its attributes): tables whose
#: file would pass its size limit with the node values (``creep_exact`` since 2026-11-27).
TABLE_FORMAT_SPLINE_ONLY = 3
#: The versions this reader understands.
TABLE_FORMAT_VERSIONS_READ = (1, 2, 3)

#: Environment variable naming a directory searched first for table files.
TABLES_DIR_ENV = "RAILCONTACT_TABLES_DIR"

SPLINE_DEGREE = 3

#: Node values a table load re-evaluates at most (integrity check; every node below it).
_INTEGRITY_NODES = 20000


class TableFileError(ValueError):
    """A table file is missing, unreadable, truncated or of an incompatible version."""


class TableAccuracyWarning(UserWarning):
    """A table file's recorded accuracy is worse than that of the table the project ships
    (a coarse or trial build): issued when it is built and whenever it is loaded."""


#: Global attribute in which ``tablegen`` records how a build's accuracy compares with the
#: shipped table's; a value starting with "worse" makes every load warn.
ACCURACY_VERSUS_SHIPPED_ATTR = "accuracy_versus_shipped"


def _warn_if_less_accurate(table):
    """Warn (:class:`TableAccuracyWarning`) when the file records that its accuracy is worse
    than the shipped table's (written by ``tablegen`` at build time)."""
    note = str(table.attrs.get(ACCURACY_VERSUS_SHIPPED_ATTR, ""))
    if note.startswith("worse"):
        import warnings  # noqa: PLC0415

        warnings.warn(f"table file {str(table.path)!r}: {note}", TableAccuracyWarning,
                      stacklevel=3)


# --------------------------------------------------------------------------------------------
# Spline construction (shared by the reader and by tablegen)
# --------------------------------------------------------------------------------------------

def bspline_knots(nodes, double_knots=()):
    """Knot vector of the cubic interpolating spline on ``nodes`` with double knots.

    Not-a-knot at both ends (the interior knots are ``nodes[2:-2]``); each value in
    ``double_knots`` (which must be an interior node) gets a second knot, and to keep as many
    coefficients as nodes the single knot at the next node to its right (or, failing that, to
    its left) is removed. The spline is then C1 at the double knot and C2 elsewhere.

    Parameters
    ----------
    nodes : array_like
        Strictly ascending grid nodes, at least 4 (5 with a double knot).
    double_knots : sequence of float
        Interior nodes where the interpolated function has a kink in its second derivative.

    Returns
    -------
    ndarray
        Knot vector of length ``len(nodes) + 4``.
    """
    x = np.asarray(nodes, dtype=float)
    if x.ndim != 1 or x.size < 4 or not np.all(np.diff(x) > 0):
        raise ValueError("nodes must be a strictly ascending 1-D array of at least 4 values")
    interior = list(x[2:-2])
    for value in double_knots:
        i = int(np.argmin(np.abs(x - value)))
        if not (0 < i < x.size - 1) or abs(x[i] - value) > 1e-12 * max(1.0, abs(value)):
            raise ValueError(f"double knot {value!r} must be an interior node of the grid")
        interior.append(x[i])
        if i + 1 < x.size and x[i + 1] in interior:
            interior.remove(x[i + 1])
        elif x[i - 1] in interior and x[i - 1] not in double_knots:
            interior.remove(x[i - 1])
        else:
            raise ValueError(f"too few nodes around the double knot {value!r}")
    interior.sort()
    return np.concatenate([np.full(4, x[0]), interior, np.full(4, x[-1])])


def periodic_bspline_knots(nodes):
    """Knot vector of the periodic cubic interpolating spline on uniform ``nodes``.

    ``nodes[0]`` and ``nodes[-1]`` are one period apart (the same point); the knots are the
    nodes continued periodically by three on each side, as
    ``scipy.interpolate.make_interp_spline(..., bc_type="periodic")`` makes them, so the
    spline has ``len(nodes) + 2`` coefficients and is C2 everywhere, the seam included.
    """
    x = np.asarray(nodes, dtype=float)
    period = x[-1] - x[0]
    return np.concatenate([x[-4:-1] - period, x, x[1:4] + period])


def periodic_stored_nodes(nodes):
    """The nodes a periodic axis is stored with: ``nodes`` plus the midpoints of the first
    and last intervals.

    A table file keeps as many nodes as coefficients along each axis (``len(knots) ==
    len(nodes) + 4``); the periodic spline has two coefficients more than distinct nodes, so
    two points inside the period, where the file stores the spline's values, fill the count.
    Any de Boor evaluator reading the stored knots gives the periodic spline on
    ``[nodes[0], nodes[-1]]``.
    """
    x = np.asarray(nodes, dtype=float)
    return np.concatenate([x[:1], [0.5 * (x[0] + x[1])], x[1:-1],
                           [0.5 * (x[-2] + x[-1])], x[-1:]])


def fit_tensor_bspline(values, nodes, knots, periodic=()):
    """Coefficients of the tensor-product cubic B-spline interpolating ``values``.

    Parameters
    ----------
    values : array_like, shape (n_1, ..., n_D) or (n_var, n_1, ..., n_D)
        Values at the grid nodes (a leading variable axis is allowed when ``values.ndim`` is
        ``len(nodes) + 1``).
    nodes, knots : sequence of array_like
        Per axis: the nodes and the knot vector (from :func:`bspline_knots`, or
        :func:`periodic_bspline_knots` for a periodic axis).
    periodic : sequence of bool, optional
        Per axis (missing entries False): periodic interpolation (the values at the first and
        last node must be equal); that axis then has ``len(nodes) + 2`` coefficients.

    Returns
    -------
    ndarray
        Coefficients, same shape as ``values`` (two more along each periodic axis).
    """
    from scipy.interpolate import make_interp_spline  # noqa: PLC0415  (fitting: tablegen)

    c = np.asarray(values, dtype=float)
    lead = c.ndim - len(nodes)
    periodic = tuple(periodic) + (False,) * (len(nodes) - len(periodic))
    for axis, (x, t, per) in enumerate(zip(nodes, knots, periodic)):
        if per:   # values at both ends equal; coefficients: len(x) + 2
            spl = make_interp_spline(np.asarray(x, float), c, k=SPLINE_DEGREE,
                                     bc_type="periodic", axis=axis + lead)
            if not np.allclose(spl.t, t, rtol=0.0, atol=1e-12 * max(1.0, np.abs(t).max())):
                raise ValueError("knots of a periodic axis must be periodic_bspline_knots(nodes)")
        else:
            spl = make_interp_spline(np.asarray(x, float), c, k=SPLINE_DEGREE,
                                     t=np.asarray(t, float), axis=axis + lead)
        c = np.moveaxis(spl.c, 0, axis + lead)  # BSpline.c has the spline axis first
    return np.ascontiguousarray(c)


# --------------------------------------------------------------------------------------------
# Evaluation: the compiled de Boor kernel (railcontact._spline_kernels, numba) is loaded on the
# first evaluation, so that a table that is read but evaluated another way (the modified-strip
# table's piecewise polynomial) needs no numba at all
# --------------------------------------------------------------------------------------------

_tensor_eval = None


def _kernel():
    """The compiled tensor-product evaluator, loaded on first use: the FMU build's
    ahead-of-time copy, else numba's (:mod:`railcontact._compiled`)."""
    global _tensor_eval
    if _tensor_eval is None:
        from . import _compiled  # noqa: PLC0415  (numba, its user cache: only when needed)

        _tensor_eval = _compiled.tensor_eval()
    return _tensor_eval


def _offsets(shape):
    """Strides of the flattened coefficient grid and the relative flat offsets of the
    (SPLINE_DEGREE+1)**D coefficients one point touches (last axis fastest)."""
    p1 = SPLINE_DEGREE + 1
    strides = np.ones(len(shape), dtype=np.int64)
    for d in range(len(shape) - 2, -1, -1):
        strides[d] = strides[d + 1] * shape[d + 1]
    offset = np.zeros(1, dtype=np.int64)
    for d in range(len(shape)):            # first axis slowest: combination c = (j_0 ... j_D-1)
        offset = (offset[:, None] + np.arange(p1) * strides[d]).ravel()
    return strides, offset


class TensorSpline:
    """Tensor-product cubic B-spline of several variables on one grid, with derivatives.

    Parameters
    ----------
    axes : sequence of dict
        Per axis: ``name``, ``nodes``, ``knots``, ``units``, ``out_of_range`` ("error" or
        "hold").
    coefficients : ndarray, shape (n_var, n_1, ..., n_D)
        B-spline coefficients.
    variables : sequence of str
        Names of the variables (first axis of ``coefficients``).
    source : str
        Where the spline came from (file name), used in error messages.
    """

    def __init__(self, axes, coefficients, variables, source="<memory>"):
        self.axes = [dict(a) for a in axes]
        self.variables = list(variables)
        self.source = str(source)
        coef = np.asarray(coefficients, dtype=float)
        self.ndim = len(self.axes)
        self._shape = np.array(coef.shape[1:], dtype=np.int64)
        self._coef = np.ascontiguousarray(coef.reshape(coef.shape[0], -1))
        self._knots = np.ascontiguousarray(np.concatenate([a["knots"] for a in self.axes]))
        self._knot_start = np.cumsum([0] + [len(a["knots"]) for a in self.axes[:-1]]).astype(np.int64)
        self._lower = np.array([a["nodes"][0] for a in self.axes])
        self._upper = np.array([a["nodes"][-1] for a in self.axes])
        for a in self.axes:
            if a.get("out_of_range", "error") not in OUT_OF_RANGE_CHOICES:
                raise ValueError(f"out_of_range of axis {a.get('name')!r} must be one of "
                                 f"{list(OUT_OF_RANGE_CHOICES)}; got {a['out_of_range']!r}")
        self._hold = np.array([a.get("out_of_range", "error") == "hold" for a in self.axes])
        self._zero = np.zeros(self.ndim, dtype=np.int64)
        self._strides, self._offset = _offsets(self._shape)
        self._work = np.zeros(4**self.ndim + 40)
        self._pt_buf = np.zeros((1, self.ndim))
        self._out_buf = np.zeros((1, self._coef.shape[0]))

    def _check(self, pts):
        upper = np.where(self._hold, np.inf, self._upper)
        if np.all((pts >= self._lower) & (pts <= upper)):  # fast path, one vector test
            return
        for d, axis in enumerate(self.axes):
            col = pts[:, d]
            upper = None if self._hold[d] else self._upper[d]
            check_range(axis["name"], col, axis.get("units", "1"), self._lower[d], upper,
                        condition=f"range of table {self.source}")

    def evaluate(self, points, derivative=None, check=True):
        """Values (or partial derivatives) of all variables at ``points``.

        Parameters
        ----------
        points : array_like, shape (n_pts, D) or (D,)
            Table coordinates, in the order of :attr:`axes`.
        derivative : sequence of int, optional
            Derivative order per axis (0, 1 or 2); default all zero.
        check : bool
            Validate the range (raise ``ValueError`` outside the grid, see the module
            docstring). Only turn off when the caller has already checked.

        Returns
        -------
        ndarray, shape (n_pts, n_var) or (n_var,)
        """
        pts = np.asarray(points, dtype=float)
        single = pts.ndim == 1
        pts = np.ascontiguousarray(pts.reshape(-1, self.ndim))
        if check:
            self._check(pts)
        deriv = self._zero if derivative is None else np.asarray(derivative, dtype=np.int64)
        if np.any(self._hold):
            beyond = pts > self._upper
            if np.any(beyond & self._hold):
                pts = np.where(beyond & self._hold, self._upper, pts)
                out = np.empty((pts.shape[0], self._coef.shape[0]))
                self._eval(pts, deriv, out)
                held = np.any(beyond[:, self._hold & (deriv > 0)], axis=1)
                out[held] = 0.0
                return out[0] if single else out
        out = np.empty((pts.shape[0], self._coef.shape[0]))
        self._eval(pts, deriv, out)
        return out[0] if single else out

    def _eval(self, pts, deriv, out):
        if deriv.shape != (self.ndim,) or np.any((deriv < 0) | (deriv > 2)):
            raise ValueError(f"derivative must be {self.ndim} orders in 0..2; got {deriv}")
        (_tensor_eval or _kernel())(self._coef, self._shape, self._knots, self._knot_start,
                                    self._strides, self._offset, pts, deriv, out,
                                    np.empty_like(self._work))

    def kernel_arrays(self):
        """The arrays the compiled evaluator takes: ``(coefficients (n_var, n_coef), shape,
        knots, knot_start, strides, offset, work)`` (see ``_spline_kernels.tensor_eval``), for
        a caller that packs them into its own compiled call."""
        return (self._coef, self._shape, self._knots, self._knot_start, self._strides,
                self._offset, self._work)

    def evaluate_unchecked(self, points):
        """Values of all variables at several points inside the grid, in one compiled call.

        ``points``: float64 array, shape (n_pts, D), C-contiguous, every coordinate within its
        axis' nodes (not checked: the caller guarantees it). Returns a new (n_pts, n_var)
        array. Uses a preallocated work buffer: not thread-safe (one object per thread).
        """
        out = np.empty((points.shape[0], self._coef.shape[0]))
        (_tensor_eval or _kernel())(self._coef, self._shape, self._knots, self._knot_start,
                                    self._strides, self._offset, points, self._zero, out,
                                    self._work)
        return out

    def warm_up(self):
        """Load the compiled evaluator now (numba and its cached machine code, or a first
        compilation) by evaluating the lower corner of the grid, so that the first evaluation
        a caller times (an FMU's first step) does not pay for it."""
        self.evaluate_point(self._lower)

    def evaluate_point(self, point, derivative=None):
        """One point, no range check (fast path; the caller guarantees the range).

        Returns a new (n_var,) array. Uses preallocated buffers: not thread-safe (use one
        object per thread).
        """
        buf = self._pt_buf
        buf[0, :] = point
        deriv = self._zero if derivative is None else np.asarray(derivative, dtype=np.int64)
        (_tensor_eval or _kernel())(self._coef, self._shape, self._knots, self._knot_start,
                                    self._strides, self._offset, buf, deriv, self._out_buf,
                                    self._work)
        return self._out_buf[0].copy()


# --------------------------------------------------------------------------------------------
# Files
# --------------------------------------------------------------------------------------------

def _package_directory():
    """This package's directory now: its ``__path__``, which the FMU slave points at each new
    instance's extraction, rather than ``__file__``: a second load of the same FMU in one
    process reuses the imported module, whose first extraction an importer may have deleted."""
    package = sys.modules.get(__package__)
    paths = list(getattr(package, "__path__", None) or ())
    return Path(paths[0]) if paths else Path(__file__).resolve().parent


def tables_directory():
    """The shipped tables: ``railcontact/tables/`` inside an installed wheel (package data)
    or an FMU (the current instance's, :func:`_package_directory`), else the ``tables/``
    directory of the checkout (an editable install; may not exist)."""
    here = _package_directory()
    for candidate in (here / "tables", here.parent.parent / "tables"):
        if candidate.is_dir():
            return candidate
    return here.parent.parent / "tables"


def default_table_path(name, directory=None):
    """Path of the table file ``<name>.nc``.

    Searched in order: ``directory`` (if given), the directory named by the environment
    variable ``RAILCONTACT_TABLES_DIR``, ``railcontact/tables/`` inside the installed package
    (a wheel carries the shipped tables there as package data; an FMU bundles them there),
    and the ``tables/`` directory of the source checkout (an editable install).

    Parameters
    ----------
    name : str
        Table name, e.g. ``"creep_modified_strip"`` (with or without ``.nc``).
    directory : str or path-like, optional
        Directory searched first.

    Returns
    -------
    pathlib.Path

    Raises
    ------
    FileNotFoundError
        Naming every place searched and the command that builds the table.
    """
    fname = name if str(name).endswith(".nc") else f"{name}.nc"
    here = _package_directory()
    places = []
    if directory is not None:
        places.append(Path(directory))
    if os.environ.get(TABLES_DIR_ENV):
        places.append(Path(os.environ[TABLES_DIR_ENV]))
    places += [here / "tables", here.parent.parent / "tables"]
    for place in places:
        if (place / fname).is_file():
            return place / fname
    stem = fname[:-3]
    raise FileNotFoundError(
        f"table file {fname!r} not found in {[str(p) for p in places]}; build it with "
        f"`python -m tablegen build --only {stem}` (it writes ./tables-build) and set "
        f"{TABLES_DIR_ENV} to that directory")


def _read_netcdf_file(path):
    import netCDF4  # noqa: PLC0415  (load-time dependency only)

    try:
        with netCDF4.Dataset(str(path), "r") as nc:
            nc.set_auto_mask(False)
            attrs = {k: nc.getncattr(k) for k in nc.ncattrs()}
            variables = {}
            for vname, var in nc.variables.items():
                # (netCDF4 returns a new array: no second copy of 165 MB)
                variables[vname] = (tuple(var.dimensions), np.asarray(var[...]),
                                    {k: var.getncattr(k) for k in var.ncattrs()})
    except (OSError, RuntimeError, IndexError, KeyError, AttributeError, ValueError,
            TypeError) as exc:   # a damaged header or attribute: netCDF4 raises any of these
        raise TableFileError(
            f"table file {str(path)!r} cannot be read as netCDF (truncated or corrupt?): "
            f"{exc}") from exc
    return attrs, variables


#: The out-of-grid behaviours an axis may state (attribute ``out_of_range``).
OUT_OF_RANGE_CHOICES = ("error", "hold")


def _as_int(value):
    """An integer attribute (e.g. ``spline_degree``); None if it is not one (the caller then
    reports the file, the attribute and the value)."""
    try:
        number = float(np.asarray(value).item()) if np.ndim(value) == 0 else None
    except (TypeError, ValueError):
        return None
    return int(number) if number is not None and number.is_integer() else None


def _fmt_attr(value):
    """An attribute value for a message: numbers plain, text quoted."""
    return repr(value) if isinstance(value, str) else str(value)


def _check_float64(where, name, values):
    """Table data must be float64: the B-spline coefficients reproduce the node values to
    ~1e-15 only in double precision (a float32 copy misfits by ~1e-8)."""
    if np.asarray(values).dtype != np.float64:
        raise TableFileError(
            f"{where}: variable {name!r} is stored as {np.asarray(values).dtype} where float64 "
            "is expected (a converted copy?); the spline needs double precision: use the "
            "original file or rebuild it with `python -m tablegen build`")


def _declared_digits(where, name, attrs, coef_attrs):
    """Significant digits a float32 table's variable declares (attribute
    ``significant_digits`` on the node values and the coefficients alike: netCDF-4
    quantisation, see tablegen.spec.TableSpec.significant_digits), or None."""
    got = attrs.get("significant_digits"), coef_attrs.get("significant_digits")
    if got == (None, None):
        return None
    try:
        digits = {int(np.asarray(g).item()) for g in got}
    except (TypeError, ValueError):
        digits = set()
    if len(digits) != 1 or not 2 <= next(iter(digits)) <= 7:
        raise TableFileError(
            f"{where}: variable {name!r} and its coefficients must declare the same "
            f"significant_digits, an integer in [2, 7]; got {got}")
    return digits.pop()


def _node_block(where, name, dims, axes, ncvars):
    """Per axis, the slice of its nodes a variable's node values are stored on: the whole
    axis (dimension ``<axis>``) or a block (format 2: dimension ``<axis>_block``, whose
    coordinate variable must be a contiguous run of the axis's nodes)."""
    if len(dims) != len(axes):
        raise TableFileError(f"{where}: variable {name!r} has dimensions {list(dims)}, "
                             f"expected one per axis {[a['name'] for a in axes]}")
    block = []
    for dim, a in zip(dims, axes):
        if dim == a["name"]:
            block.append(slice(None))
            continue
        if dim != f"{a['name']}_block" or dim not in ncvars:
            raise TableFileError(f"{where}: variable {name!r} has the dimension {dim!r} where "
                                 f"{a['name']!r} or {a['name'] + '_block'!r} (with its "
                                 "coordinate variable) is expected")
        part = np.asarray(ncvars[dim][1], dtype=float)
        nodes = a["nodes"]
        start = int(np.argmin(np.abs(nodes - part[0]))) if len(part) else 0
        stop = start + len(part)
        if not len(part) or stop > len(nodes) or np.any(nodes[start:stop] != part):
            raise TableFileError(f"{where}: the nodes of {dim!r} are not a contiguous run of "
                                 f"the nodes of {a['name']!r}")
        block.append(slice(start, stop))
    return tuple(block)


def _attr_list(value):
    arr = np.atleast_1d(np.asarray(value))
    if arr.dtype.kind in "US":
        text = " ".join(str(v) for v in arr).replace(",", " ").split()
        return [float(v) for v in text]
    return [float(v) for v in arr]


def _read_table_content(path):
    """Read and check a table file (:meth:`Table.from_file` through
    :func:`railcontact._table_store.load`): a dict of plain objects and arrays, the
    coefficients in the file's precision with the variable axis last."""
    path = Path(path)
    where = f"table file {str(path)!r}"
    attrs, ncvars = _read_netcdf_file(path)
    version = attrs.get("railcontact_table_format")
    if version is None:
        raise TableFileError(f"{where} has no 'railcontact_table_format' attribute; it was "
                             "not written by tablegen")
    if _as_int(version) not in TABLE_FORMAT_VERSIONS_READ:
        raise TableFileError(
            f"{where} has table format version {_fmt_attr(version)}, this reader understands "
            f"versions {list(TABLE_FORMAT_VERSIONS_READ)}; rebuild it with `python -m "
            "tablegen build`")
    for key in ("table_axes", "table_variables", "spline_degree"):
        if key not in attrs:
            raise TableFileError(f"{where} lacks the global attribute {key!r}")
    if _as_int(attrs["spline_degree"]) != SPLINE_DEGREE:
        raise TableFileError(f"{where}: attribute spline_degree must be {SPLINE_DEGREE}; got "
                             f"{attrs['spline_degree']!r}")
    axis_names = str(attrs["table_axes"]).split()
    var_names = str(attrs["table_variables"]).split()
    axes = []
    for name in axis_names:
        for needed in (name, f"{name}_knots"):
            if needed not in ncvars:
                raise TableFileError(f"{where} lacks the variable {needed!r}")
        _, nodes, a = ncvars[name]
        _, knots, _ = ncvars[f"{name}_knots"]
        for vname, arr in ((name, nodes), (f"{name}_knots", knots)):
            _check_float64(where, vname, arr)
        if len(knots) != len(nodes) + 4 or not np.all(np.diff(nodes) > 0):
            raise TableFileError(f"{where}: axis {name!r} has inconsistent nodes/knots")
        try:
            double_knots = _attr_list(a.get("double_knots", []))
        except ValueError:
            raise TableFileError(
                f"{where}: attribute {name}:double_knots must be a list of numbers; got "
                f"{a.get('double_knots')!r}") from None
        out_of_range = str(a.get("out_of_range", "error"))
        if out_of_range not in OUT_OF_RANGE_CHOICES:
            raise TableFileError(
                f"{where}: attribute {name}:out_of_range must be one of "
                f"{list(OUT_OF_RANGE_CHOICES)}; got {out_of_range!r}")
        axes.append(dict(name=name, nodes=np.asarray(nodes, float),
                         knots=np.asarray(knots, float), units=str(a.get("units", "1")),
                         long_name=str(a.get("long_name", name)),
                         double_knots=double_knots, out_of_range=out_of_range))
    values, vattrs, tolerance = {}, {}, []
    # one array, variable axis last (the layout of the exact table's kernels), in the file's
    # precision: float32 coefficients (creep_exact's, 165 MB) are evaluated as they are,
    # accumulating in float64; widening them would add memory and no information
    shape = tuple(len(a["nodes"]) for a in axes)
    single_coefficients = all(f"{v}_bspline_coefficients" in ncvars and np.asarray(
        ncvars[f"{v}_bspline_coefficients"][1]).dtype == np.float32 for v in var_names)
    coefs = np.empty(shape + (len(var_names),),
                     dtype=np.float32 if single_coefficients else np.float64)
    block = None
    spline_only = _as_int(version) == TABLE_FORMAT_SPLINE_ONLY
    for k_var, name in enumerate(var_names):
        cname = f"{name}_bspline_coefficients"
        for needed in (name, cname):
            if needed not in ncvars:
                raise TableFileError(f"{where} lacks the variable {needed!r}")
        vdims, val, a = ncvars[name]
        _, coef, ca = ncvars[cname]
        if spline_only:   # format 3: the coefficients alone (checksummed by HDF5)
            if vdims != () or coef.shape != shape:
                raise TableFileError(
                    f"{where}: variable {name!r} must be a scalar (format 3) and its "
                    f"coefficients of shape {shape}; got dimensions {list(vdims)} and "
                    f"{coef.shape} (truncated?)")
            if not np.all(np.isfinite(coef)):
                raise TableFileError(f"{where}: variable {cname!r} holds values that are "
                                     "not finite; the file is corrupt")
            single = True        # (no node values: float32 coefficients may stand alone)
        else:
            var_block = _node_block(where, name, vdims, axes, ncvars)
            block = var_block if block is None else block
            want = tuple(len(range(*sl.indices(n))) for sl, n in zip(var_block, shape))
            if var_block != block or val.shape != want or coef.shape != shape:
                raise TableFileError(f"{where}: variable {name!r} has shape {val.shape}, "
                                     f"expected {want} (truncated?)")
            single = str(a.get("node_value_precision", "")) == "float32"
            digits = _declared_digits(where, name, a, ca) if single else None
            if single and val.dtype == np.float32:
                # declared float32 node values (viewers only); declared quantised to
                # ``digits`` significant digits (node values and coefficients):
                # 10^(1 - digits)
                tolerance.append(1e-6 if digits is None else 10.0 ** (1 - digits))
            else:
                _check_float64(where, name, val)
                tolerance.append(1e-9)
            values[name] = np.asarray(val, float)
        if not (str(ca.get("coefficient_precision", "")) == "float32"
                and coef.dtype == np.float32 and single):
            _check_float64(where, cname, coef)     # (declared float32 coefficients: a
            # large table halved again; evaluated in float64, checked to 1e-6 below)
        coefs[..., k_var] = coef
        vattrs[name] = a
    content = dict(attrs=attrs, axes=axes, variables=var_names, variable_attrs=vattrs,
                   values=values, coefficients=coefs,
                   node_block=tuple(block) if block is not None else None)
    if spline_only:      # checked above (shapes, finite) and by HDF5 (checksums)
        return content
    # integrity: the stored spline reproduces the stored node values (every node, or for
    # large tables the corners and a fixed sample of 20,000: a load stays fast)
    vshape = next(iter(values.values())).shape
    n_nodes = int(np.prod(vshape))
    flat = np.arange(n_nodes) if n_nodes <= _INTEGRITY_NODES else np.unique(np.r_[
        np.ravel_multi_index(tuple(np.array(c) * (vshape[d] - 1) for d, c in enumerate(
            zip(*np.ndindex(*(2,) * len(vshape))))), vshape),
        np.random.default_rng(0).integers(0, n_nodes, _INTEGRITY_NODES)])
    idx = np.unravel_index(flat, vshape)
    pts = np.stack([a["nodes"][sl][i] for a, sl, i in zip(axes, block, idx)], axis=1)
    # the compiled evaluator the table is read with (faster here than scipy's NdBSpline, and
    # without scipy.interpolate's import: about 0.5 s of a fresh process, an FMU's start too)
    got = TensorSpline(axes, np.moveaxis(coefs, -1, 0), var_names,
                       source=str(path)).evaluate(pts, check=False)
    want = np.stack([values[v][idx] for v in var_names], axis=1)
    scale = np.maximum(1.0, np.abs(want).max(axis=0))
    bad = np.abs(got - want).max(axis=0) / scale
    if np.any(~np.isfinite(bad)) or np.any(bad > np.array(tolerance)):
        raise TableFileError(f"{where}: the stored spline coefficients do not reproduce "
                             f"the node values (max relative misfit {bad.max():.3g}); the "
                             "file is corrupt")
    return content


class Table:
    """A loaded table: axes, variables at the nodes, accuracy attributes and the C2 spline.

    Use :meth:`from_file`. ``table.spline`` evaluates every variable at once;
    ``table(name, points, derivative)`` evaluates one.

    Attributes
    ----------
    name : str
        Table name (global attribute ``table_name``).
    path : pathlib.Path
    attrs : dict
        Global attributes.
    axes : list of dict
        ``name``, ``nodes``, ``knots``, ``units``, ``long_name``, ``double_knots``,
        ``out_of_range``.
    variables : list of str
    variable_attrs : dict of dict
        Per-variable attributes, including the recorded accuracy (``max_abs_error``,
        ``rms_error``, ``error_target``, ``error_target_met``).
    values : dict of ndarray
        Node values per variable, at the nodes ``node_block`` selects (empty for a file
        without node values, format 3: evaluate ``spline`` at the nodes).
    node_block : tuple of slice
        Per axis, the nodes whose values the file stores: every node (``slice(None)``), or,
        for a table with symmetries (format 2), the block that was computed (the spline
        covers the whole grid either way).
    """

    def __init__(self, path, attrs, axes, variables, variable_attrs, values, coefficients,
                 node_block=None):
        self.path = Path(path)
        self.attrs = attrs
        self.name = str(attrs.get("table_name", self.path.stem))
        self.axes = axes
        self.variables = list(variables)
        self.variable_attrs = variable_attrs
        self.values = values
        self.node_block = (tuple(node_block) if node_block is not None
                           else (slice(None),) * len(axes))
        #: B-spline coefficients, shape (n_var, n_1, ..., n_D), in the file's precision
        #: (float32 or float64; loaded from a file: a read-only view of the process's one
        #: copy, see :meth:`from_file`). [variable units]
        self.coefficients = np.asarray(coefficients)
        self._spline = None

    @property
    def spline(self):
        """The :class:`TensorSpline` of every variable (made on first use, from
        :attr:`coefficients`)."""
        if self._spline is None:
            self._spline = TensorSpline(self.axes, self.coefficients, self.variables,
                                        source=str(self.path))
        return self._spline

    def share_coefficients(self, coefficients):
        """Hold ``coefficients`` (the same values, e.g. a view of a reader's own layout) in
        place of this table's copy, and drop the spline made from it (made again on first
        use): a large table is then held once. [variable units]"""
        coefficients = np.asarray(coefficients)
        if coefficients.shape != self.coefficients.shape:
            raise ValueError(f"coefficients must have shape {self.coefficients.shape}; got "
                             f"{coefficients.shape}")
        self.coefficients = coefficients
        self._spline = None

    @classmethod
    def from_file(cls, path, expected_name=None, variables_last=False):
        """Load and validate a table file.

        The file's content is loaded once per process (every copy of this package, e.g. each
        FMU extraction, shares it) and a large file is decompressed once per machine and
        memory-mapped read-only (:mod:`railcontact._table_store`): the coefficients keep the
        file's precision (float32 for ``creep_exact``) and are held variable axis last;
        :attr:`coefficients` is a read-only view of them, variable first.

        Parameters
        ----------
        path : str or path-like
        expected_name : str, optional
            If given, the file's ``table_name`` attribute must equal it.
        variables_last : bool, optional
            Kept for compatibility: the coefficients are always held variable axis last (the
            layout of :class:`railcontact.exact_table.ExactCreepTable`'s kernels), once.

        Raises
        ------
        TableFileError
            File missing, unreadable/truncated, wrong format version, wrong table, missing
            attributes or variables, or node values not reproduced by the stored spline.
        """
        from . import _table_store  # noqa: PLC0415

        path = Path(path)
        if not path.is_file():
            raise TableFileError(f"table file {str(path)!r} does not exist")
        content = _table_store.load(path, _read_table_content)
        attrs = content["attrs"]
        if expected_name is not None and attrs.get("table_name") != expected_name:
            raise TableFileError(f"table file {str(path)!r} holds table "
                                 f"{attrs.get('table_name')!r}, expected {expected_name!r}")
        table = cls(path, attrs, content["axes"], content["variables"],
                    content["variable_attrs"], content["values"],
                    np.moveaxis(content["coefficients"], -1, 0),
                    node_block=content["node_block"])
        _warn_if_less_accurate(table)
        return table

    def __call__(self, variable, points, derivative=None):
        """Evaluate one variable (see :meth:`TensorSpline.evaluate`)."""
        i = self.variables.index(variable)
        out = self.spline.evaluate(points, derivative)
        return out[..., i]

    def accuracy(self):
        """Recorded accuracy per variable: dict of (max_abs_error, rms_error, target, met)."""
        out = {}
        for v in self.variables:
            a = self.variable_attrs[v]
            out[v] = dict(max_abs_error=float(a.get("max_abs_error", np.nan)),
                          rms_error=float(a.get("rms_error", np.nan)),
                          error_target=float(a.get("error_target", np.nan)),
                          error_target_met=str(a.get("error_target_met", "unknown")))
        return out
