"""Build a table: a (dask) map over grid points, spline fit, accuracy check, netCDF file.

The grid points and the off-grid check points are cut into chunks; each chunk is one dask task
(``TableSpec.function`` on an (n, D) array). Every finished chunk is saved at once under the
work directory (``<workdir>/<table>-<resolution>-<hash>/``), so an interrupted build resumes
where it stopped: rerunning the same command recomputes only the missing chunks. The hash
covers the grid, the check points and the spec's method string, so a changed grid never reuses
stale chunks.

Schedulers: ``None`` starts a local ``dask.distributed`` cluster (``workers`` processes, one
thread each); an address (``tcp://host:8786``) connects to an existing cluster (its workers
must be able to ``import tablegen`` and ``railcontact``, e.g. from the same editable
checkout); ``"synchronous"`` computes in this process (tests, debugging).

Where the file goes: ``output_dir``, by default :func:`default_output_dir` (``./tables-build``),
never the checkout's shipped ``tables/`` unless that directory is given explicitly (the
command line's ``--replace-shipped``). A build whose accuracy is worse than the shipped
table's warns (:class:`railcontact.tables.TableAccuracyWarning`) and records it in the file's
``accuracy_versus_shipped`` attribute, so that every load of the file warns too.
"""

from __future__ import annotations

import dataclasses
import hashlib
import os
import sys
import time
import warnings
from pathlib import Path

import numpy as np

from railcontact.tables import (ACCURACY_VERSUS_SHIPPED_ATTR, TableAccuracyWarning,
                                TensorSpline, bspline_knots, fit_tensor_bspline,
                                periodic_bspline_knots, periodic_stored_nodes)

from .netcdf import write_table
from .registry import get_spec

__all__ = ["build_table", "check_table", "evaluate_chunk", "default_workdir",
           "default_output_dir", "SHIPPED_TABLES_DIR", "SchedulerUnreachable"]

_REPO = Path(__file__).resolve().parent.parent

#: The checkout's shipped tables (bundled into the FMU by ``build_fmu.py``): written only when
#: asked explicitly (``output_dir=SHIPPED_TABLES_DIR``, the command line's
#: ``--replace-shipped``); a build's accuracy is compared with the file here.
SHIPPED_TABLES_DIR = _REPO / "tables"

#: A build whose max error exceeds the shipped table's by more than this factor is "worse"
#: (a rebuild at the shipped resolution reproduces the shipped errors: same check points).
WORSE_FACTOR = 1.1

#: Seconds to wait for a ``--scheduler`` address before giving up.
SCHEDULER_TIMEOUT = 10.0


class SchedulerUnreachable(RuntimeError):
    """The dask scheduler address given cannot be reached."""


def default_output_dir():
    """``$TABLEGEN_OUTPUT_DIR``, else ``./tables-build`` (in the current directory): where a
    build writes its file unless told otherwise. Never the shipped ``tables/``: to use a
    table built here, point ``RAILCONTACT_TABLES_DIR`` at this directory (searched first by
    :func:`railcontact.tables.default_table_path`)."""
    if os.environ.get("TABLEGEN_OUTPUT_DIR"):
        return Path(os.environ["TABLEGEN_OUTPUT_DIR"])
    return Path.cwd() / "tables-build"


def _shipped_accuracy(name, shipped_dir):
    """Per variable, the max error the shipped table ``<shipped_dir>/<name>.nc`` records, or
    None if there is no such file (or it cannot be read)."""
    path = Path(shipped_dir) / f"{name}.nc"
    if not path.is_file():
        return None
    import netCDF4  # noqa: PLC0415

    try:
        with netCDF4.Dataset(str(path)) as ds:
            return {v: float(ds[v].getncattr("max_abs_error"))
                    for v in str(ds.getncattr("table_variables")).split()}
    except (OSError, RuntimeError, KeyError, AttributeError, IndexError, ValueError):
        return None


def accuracy_versus_shipped(accuracy, shipped, targets=None):
    """The text of the ``accuracy_versus_shipped`` attribute: "worse than the shipped table
    ..." naming each variable whose max error exceeds the shipped one's by more than
    :data:`WORSE_FACTOR` (and, given ``targets`` per variable, whether it still meets its
    error target), else "as accurate as the shipped table ..."; None without a shipped table
    to compare with."""
    if shipped is None:
        return None
    targets = targets or {}

    def target(v, err):
        if v not in targets:
            return ""
        return (f", within its target {targets[v]:.3g}" if err <= targets[v]
                else f", TARGET {targets[v]:.3g} NOT MET")

    worse = [f"{v} max {a['max_abs_error']:.3g} (shipped {shipped[v]:.3g}"
             f"{target(v, a['max_abs_error'])})"
             for v, a in accuracy.items()
             if v in shipped and a["max_abs_error"] > WORSE_FACTOR * shipped[v]]
    if worse:
        return ("worse than the shipped table (max |error| / error_scale on the check points): "
                + ", ".join(worse) + "; fine for a trial, not to replace the shipped table")
    return "as accurate as the shipped table or better (max |error| / error_scale per variable)"


def _check_scheduler(address):
    """Raise :class:`SchedulerUnreachable` (one line) unless ``address`` (``tcp://host:port``
    or ``host:port``) accepts a connection within :data:`SCHEDULER_TIMEOUT` seconds."""
    import socket  # noqa: PLC0415
    from urllib.parse import urlsplit  # noqa: PLC0415

    text = address if "://" in address else f"tcp://{address}"
    try:
        parts = urlsplit(text)
        host, port = parts.hostname, parts.port or 8786
    except ValueError as exc:
        raise SchedulerUnreachable(f"--scheduler {address!r} is not an address "
                                   f"(tcp://host:port): {exc}") from None
    if parts.scheme not in ("tcp", "tls") or not host:
        return    # another transport (inproc://, ucx://): let dask connect
    try:
        with socket.create_connection((host, port), timeout=SCHEDULER_TIMEOUT):
            pass
    except OSError as exc:
        raise SchedulerUnreachable(
            f"dask scheduler {address!r} is not reachable ({exc.strerror or exc}); start one "
            "(`dask scheduler`, with workers that can import tablegen and railcontact), or "
            "omit --scheduler for a local cluster") from None


def default_workdir():
    """``$TABLEGEN_WORKDIR``, else ``$XDG_CACHE_HOME/railcontact-tablegen`` (default
    ``~/.cache/railcontact-tablegen``): chunks of unfinished builds."""
    if os.environ.get("TABLEGEN_WORKDIR"):
        return Path(os.environ["TABLEGEN_WORKDIR"])
    cache = os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache"
    return Path(cache) / "railcontact-tablegen"


def evaluate_chunk(spec_name, points):
    """Run a spec's point function on one chunk (the dask task; importable by workers)."""
    spec = get_spec(spec_name)
    out = np.asarray(spec.function(np.asarray(points, dtype=float)), dtype=float)
    if out.shape != (len(points), len(spec.variables)):
        raise ValueError(f"table {spec_name}: point function returned shape {out.shape}, "
                         f"expected {(len(points), len(spec.variables))}")
    if not np.all(np.isfinite(out)):
        raise ValueError(f"table {spec_name}: point function returned non-finite values")
    return out


def _chunks(n, size):
    return [(i, min(i + size, n)) for i in range(0, n, size)]


def _run(spec, tasks, workdir, scheduler, workers, progress):
    """Compute the chunks ``tasks`` (list of (file, points)), skipping finished files."""
    todo = [(f, p) for f, p in tasks if not f.exists()]
    show = progress if progress is not None else sys.stderr.isatty()
    from tqdm.auto import tqdm  # noqa: PLC0415

    # counted in cases (points), so the bar shows cases per second and the time left
    bar = tqdm(total=sum(len(p) for _, p in tasks),
               initial=sum(len(p) for f, p in tasks if f.exists()), desc=spec.name,
               unit="case", disable=not show)

    def save(fname, result):
        tmp = fname.with_name(fname.stem + ".part.npy")
        np.save(tmp, result)
        os.replace(tmp, fname)
        bar.update(len(result))

    try:
        if not todo:
            return
        if scheduler == "synchronous":
            for fname, pts in todo:
                save(fname, evaluate_chunk(spec.name, pts))
            return
        from dask.distributed import Client, LocalCluster, as_completed  # noqa: PLC0415

        if scheduler is None:
            cluster = LocalCluster(n_workers=workers or os.cpu_count() or 1,
                                   threads_per_worker=1, processes=True,
                                   dashboard_address=":0")
            client = Client(cluster)
        else:
            cluster = None
            _check_scheduler(scheduler)
            try:
                client = Client(scheduler, timeout=SCHEDULER_TIMEOUT)
            except Exception as exc:  # noqa: BLE001  (a timeout, or not a dask scheduler)
                raise SchedulerUnreachable(
                    f"dask scheduler {scheduler!r} did not answer as a dask scheduler within "
                    f"{SCHEDULER_TIMEOUT:g} s ({type(exc).__name__}: "
                    f"{str(exc).splitlines()[0][:120] if str(exc) else ''})") from None
        try:
            futures = {}
            for fname, pts in todo:
                fut = client.submit(evaluate_chunk, spec.name, pts, pure=False)
                futures[fut] = fname
            for fut in as_completed(futures):
                save(futures[fut], fut.result())
        finally:
            client.close()
            if cluster is not None:
                cluster.close()
    finally:
        bar.close()


def _reused_node_values(spec, path, points):
    """Node values of an earlier build of the same table (same name and ``method``) at the
    grid ``points`` it holds: ``(values (n, n_var), compute (n,) bool, attributes)``.
    ``compute`` marks the points to compute anew: those that are not nodes of that file (a
    finer grid reuses a coarser build's nodes), those ``spec.analytic_points`` marks, and, for
    a file of another method that ``spec.reusable_points`` accepts, those it does not mark."""
    import netCDF4  # noqa: PLC0415

    path = Path(path)
    with netCDF4.Dataset(path) as ds:
        attrs = {k: ds.getncattr(k) for k in ds.ncattrs()}
        reusable = None
        same = attrs.get("method") == spec.method
        if attrs.get("table_name") == spec.name:
            if same:
                reusable = np.ones(len(points), dtype=bool)
            elif spec.reusable_points is not None:
                reusable = spec.reusable_points(attrs, points)
        if reusable is None:
            raise ValueError(f"reuse_nodes must be a file of table {spec.name!r} built with the "
                             f"same method ({spec.method!r}) or one its spec's reusable_points "
                             f"accepts; got {path} (table {attrs.get('table_name')!r}, method "
                             f"{attrs.get('method')!r})")
        index, found = [], np.ones(len(points), dtype=bool)
        # the node values' own dimensions: the axes, or the blocks of them a table with
        # symmetries stores (``<axis>_block``, coordinates the nodes there); a file without
        # node values (format 3): the axes, and the spline at the nodes
        spline_only = ds[spec.variables[0].name].ndim == 0
        dims = (str(attrs["table_axes"]).split() if spline_only
                else ds[spec.variables[0].name].dimensions)
        for k, name in enumerate(dims):
            nodes = np.asarray(ds[name][:], dtype=float)
            if spec.reuse_coordinates is not None:     # a changed coordinate, same points
                nodes = np.asarray(spec.reuse_coordinates(attrs, name, nodes), dtype=float)
            j = np.abs(points[:, k][:, None] - nodes[None, :]).argmin(axis=1)
            found &= np.abs(nodes[j] - points[:, k]) <= 1e-12
            index.append(j)
        if not spline_only:
            values = np.stack([np.asarray(ds[v.name][:], dtype=float)[tuple(index)]
                               for v in spec.variables], axis=-1)
    if spline_only:   # the file's own nodes, through its spline
        from railcontact.tables import Table  # noqa: PLC0415

        table = Table.from_file(path, expected_name=spec.name)
        at = np.stack([a["nodes"][j] for a, j in zip(table.axes, index)], axis=1)
        values = table.spline.evaluate(np.ascontiguousarray(at), check=False)
    analytic = (np.asarray(spec.analytic_points(points), dtype=bool)
                if spec.analytic_points is not None else np.zeros(len(points), dtype=bool))
    reusable = np.asarray(reusable, dtype=bool)
    compute = analytic | ~found | ~reusable
    values[compute] = np.nan
    n_new = int((~found & ~analytic).sum())
    n_changed = int((found & ~analytic & ~reusable).sum())
    info = {"build_reused_nodes": (
        f"{int((~compute).sum())} of {len(points)} points' node values taken from an earlier "
        f"build of this table with "
        f"{'the same method' if same else 'the method ' + repr(attrs.get('method'))} "
        f"({path.name}, source {attrs.get('source')}, "
        f"history {attrs.get('history')!r}; "
        + ("the spline at its nodes (a file without node values)" if spline_only else
           f"stored in {'float32' if spec.node_values_float32 else 'float64'}") + "), "
        f"{int(analytic.sum())} analytic points recomputed, {n_new} points that are not nodes "
        f"of that file computed, {n_changed} points whose method changed computed; the check "
        "points are computed anew")}
    for key in ("build_seconds", "solver_source_sha1", "build_chunks_reused"):
        if key in attrs:
            info[f"reused_nodes_{key}"] = attrs[key]
    return values, compute, info


def build_table(name, resolution="default", output_dir=None, scheduler=None, workers=None,
                workdir=None, progress=None, command=None, keep_chunks=False,
                reuse_nodes=None, shipped_dir=None):
    """Build table ``name`` and write ``<output_dir>/<name>.nc``.

    Parameters
    ----------
    name : str
        Registered table name (``python -m tablegen list``).
    resolution : {"coarse", "default", "fine"}
    output_dir : path-like, optional
        Default :func:`default_output_dir` (``./tables-build``), never the shipped
        ``tables/``; pass :data:`SHIPPED_TABLES_DIR` to replace a shipped table.
    scheduler : None, "synchronous" or str
        See the module docstring.
    workers : int, optional
        Worker processes of the local cluster (default: all cores).
    workdir : path-like, optional
        Where finished chunks are kept until the file is written (default
        :func:`default_workdir`).
    progress : bool, optional
        Progress bar (default: only on a terminal).
    command : str, optional
        Recorded in the file's ``history``.
    keep_chunks : bool
        Keep the chunk files after success.
    reuse_nodes : path-like, optional
        An earlier build of the same table (same ``method``, or one whose points
        ``spec.reusable_points`` accepts): its node values are taken
        instead of computed at every grid point that is one of its nodes, except at the
        points ``spec.analytic_points`` marks (limits computed without the solver), which are
        recomputed; grid points that are not its nodes (a refined axis) and the check points
        are computed, in chunks of their own (resumable as any build). For a fix in an
        analytic limit, or a finer axis, without rerunning hours of solves; recorded in the
        file's ``build_reused_nodes``.
    shipped_dir : path-like, optional
        Where the shipped table to compare the accuracy with is (default
        :data:`SHIPPED_TABLES_DIR`). A build worse than it warns
        (:class:`railcontact.tables.TableAccuracyWarning`).

    Returns
    -------
    dict
        ``path``, ``seconds`` (wall time of the point evaluations in this run),
        ``n_points``, ``n_check``, ``n_computed`` (cases, grid and check, computed in this
        run), ``n_resumed`` (cases found computed by an earlier, interrupted run),
        ``n_reused_nodes`` (node values taken from ``reuse_nodes``), ``accuracy`` (per
        variable), ``accuracy_versus_shipped`` (text, or None without a shipped table),
        ``size_bytes``.
    """
    spec = get_spec(name)
    why = spec.available()
    if why:
        raise RuntimeError(f"table {name!r} cannot be built: {why}")
    axes, points = spec.grid(resolution)
    assemble = None
    if spec.reduce is not None:   # symmetries: compute a fundamental part only
        points, assemble = spec.reduce(axes)
    check = spec.make_check_points(axes, resolution)
    h = hashlib.sha1()
    for arr in (points, check):
        h.update(np.ascontiguousarray(arr).tobytes())
    h.update(spec.method.encode())
    key = f"{name}-{resolution}-{h.hexdigest()[:12]}"
    work = Path(workdir or default_workdir()) / key
    work.mkdir(parents=True, exist_ok=True)
    if reuse_nodes is None:
        grid_vals, reuse_info = None, {}
        compute = np.arange(len(points))
        prefix = "grid"
    else:   # the points an earlier build does not give, in chunks of their own (resumable)
        grid_vals, mask, reuse_info = _reused_node_values(spec, reuse_nodes, points)
        compute = np.nonzero(mask)[0]
        prefix = "reuse_" + hashlib.sha1(compute.tobytes()
                                         + Path(reuse_nodes).read_bytes()).hexdigest()[:12]
    tasks = [(work / f"{prefix}_{i:06d}.npy", points[compute[a:b]])
             for i, (a, b) in enumerate(_chunks(len(compute), spec.chunk_size))]
    n_grid_chunks = len(tasks)
    tasks += [(work / f"check_{i:06d}.npy", check[a:b])
              for i, (a, b) in enumerate(_chunks(len(check), spec.chunk_size))]
    reused = sum(f.exists() for f, _ in tasks)
    n_resumed = sum(len(p) for f, p in tasks if f.exists())
    n_cases = sum(len(p) for _, p in tasks)
    t0 = time.perf_counter()
    _run(spec, tasks, work, scheduler, workers, progress)
    seconds = time.perf_counter() - t0
    computed = (np.concatenate([np.load(f) for f, _ in tasks[:n_grid_chunks]])
                if n_grid_chunks else np.zeros((0, len(spec.variables))))
    if grid_vals is None:
        grid_vals = computed
    else:
        grid_vals[compute] = computed
    check_vals = np.concatenate([np.load(f) for f, _ in tasks[n_grid_chunks:]])
    values, axes, knots, coefs, spline = fit_grid_values(spec, axes, grid_vals, assemble)
    block = computed_node_block(axes, points) if assemble is not None else None
    got = spline.evaluate(np.ascontiguousarray(check[:, :len(axes)]), check=False)
    accuracy = {}
    for k, v in enumerate(spec.variables):
        err = np.abs(got[:, k] - check_vals[:, k]) / v.error_scale
        worst = int(np.argmax(err))
        accuracy[v.name] = dict(max_abs_error=float(err.max()),
                                rms_error=float(np.sqrt(np.mean(err**2))),
                                n_check_points=len(check), worst_point=check[worst].tolist())
    out_dir = Path(output_dir) if output_dir is not None else default_output_dir()
    path = out_dir / f"{name}.nc"
    versus = accuracy_versus_shipped(accuracy, _shipped_accuracy(
        name, SHIPPED_TABLES_DIR if shipped_dir is None else shipped_dir),
        {v.name: v.error_target for v in spec.variables})
    info = {"resolution": resolution, "grid_points": np.int32(len(points)),
            "build_seconds": float(round(seconds, 3)),
            "build_chunks_reused": (f"{reused} of {len(tasks)} chunks were computed by an "
                                    "earlier run (resumed build; build_seconds is this run's "
                                    "time only)") if reused else "none (one run)",
            "build_scheduler": "local cluster" if scheduler is None else str(scheduler),
            **({ACCURACY_VERSUS_SHIPPED_ATTR: versus} if versus else {}),
            **reuse_info}
    write_table(path, spec, axes, knots, values, coefs, accuracy,
                command or f"python -m tablegen build --only {name} --resolution {resolution}",
                info, node_block=block)
    if not keep_chunks:
        for f, _ in tasks:
            f.unlink(missing_ok=True)
        try:
            work.rmdir()
        except OSError:
            pass
    if versus and versus.startswith("worse"):
        warnings.warn(f"table {name!r} ({resolution}) written to {str(path)!r} is {versus}",
                      TableAccuracyWarning, stacklevel=2)
    return dict(path=path, seconds=seconds, n_points=len(points), n_check=len(check),
                n_computed=n_cases - n_resumed, n_resumed=n_resumed,
                n_reused_nodes=len(points) - len(compute), accuracy=accuracy,
                accuracy_versus_shipped=versus, size_bytes=path.stat().st_size)


def computed_node_block(axes, points):
    """Per axis, the slice of the stored nodes that spans the computed points: the block a
    table with symmetries (``spec.reduce``) stores its node values on (the rest of the grid
    follows from them by the symmetries, or from the spline). Raises if a computed point is
    not a node of the block."""
    block = []
    for k, a in enumerate(axes):
        x = np.asarray(points[:, k], dtype=float)
        inside = np.nonzero((a.nodes >= x.min() - 1e-12) & (a.nodes <= x.max() + 1e-12))[0]
        sl = slice(int(inside[0]), int(inside[-1]) + 1)
        j = np.abs(x[:, None] - a.nodes[sl][None, :]).argmin(axis=1)
        if not np.all(np.abs(a.nodes[sl][j] - x) <= 1e-12):
            raise ValueError(f"axis {a.name}: the computed points are not nodes of the grid")
        block.append(sl)
    return tuple(block)


def spline_axes(axes):
    """The knot vectors of a spec's axes and the axes as stored: a periodic axis gets
    :func:`railcontact.tables.periodic_bspline_knots` and its stored nodes
    (:func:`railcontact.tables.periodic_stored_nodes`, as many as its coefficients), the
    others :func:`railcontact.tables.bspline_knots` and their own nodes."""
    knots = [periodic_bspline_knots(a.nodes) if a.periodic
             else bspline_knots(a.nodes, a.double_knots) for a in axes]
    stored = [dataclasses.replace(a, nodes=periodic_stored_nodes(a.nodes)) if a.periodic
              else a for a in axes]
    return knots, stored


def fit_grid_values(spec, axes, grid_vals, assemble=None):
    """Spline of a spec's computed values: ``(values, stored_axes, knots, coefficients,
    spline)``.

    ``grid_vals`` (m, n_var) are the point function's results, on every grid point in C order
    or, with ``assemble`` (from ``spec.reduce``), on the fundamental points only. Periodic axes
    are fitted periodically and stored with :func:`railcontact.tables.periodic_stored_nodes`
    (their stored values are the spline's).
    """
    if assemble is None:
        shape = tuple(len(a.nodes) for a in axes)
        values = np.moveaxis(grid_vals.reshape(shape + (len(spec.variables),)), -1, 0)
    else:
        values = np.asarray(assemble(grid_vals), dtype=float)
    knots, stored = spline_axes(axes)
    coefs = fit_tensor_bspline(values, [a.nodes for a in axes], knots,
                               periodic=[a.periodic for a in axes])
    if getattr(spec, "coefficient_symmetry", None) is not None:
        coefs = spec.coefficient_symmetry(stored, knots, coefs)
    coefs = rounded_coefficients(spec, stored, coefs)
    spline = TensorSpline([dict(name=a.name, nodes=a.nodes, knots=t, units=a.units,
                                out_of_range=a.out_of_range) for a, t in zip(stored, knots)],
                          coefs, [v.name for v in spec.variables], source=spec.name)
    if any(a.periodic for a in axes):
        mesh = np.meshgrid(*[a.nodes for a in stored], indexing="ij")
        pts = np.ascontiguousarray(np.stack([m.ravel() for m in mesh], axis=1))
        values = np.moveaxis(spline.evaluate(pts, check=False).reshape(
            coefs.shape[1:] + (len(spec.variables),)), -1, 0)
    return values, stored, knots, coefs, spline


def rounded_coefficients(spec, stored_axes, coefs):
    """The coefficients (n_var, n_1, ..., n_D) with each variable's ``absolute_precision``
    applied: rounded to multiples of it outside ``spec.relative_precision_region`` (see
    :class:`tablegen.spec.Variable`); unchanged for variables without one."""
    precisions = [getattr(v, "absolute_precision", None) for v in spec.variables]
    if all(q is None for q in precisions):
        return coefs
    region = getattr(spec, "relative_precision_region", None)
    keep = (np.zeros((1,) * (coefs.ndim - 1), dtype=bool) if region is None
            else np.asarray(region(stored_axes), dtype=bool))
    out = np.array(coefs, dtype=float, copy=True)
    for k, q in enumerate(precisions):
        if q is not None:
            out[k] = np.where(keep, out[k], np.round(out[k] / q) * q)
    return out


def check_table(name, path=None, n_points=None, seed=1, scheduler=None, workers=None,
                workdir=None, progress=None, command=None):
    """Re-measure a table file's accuracy on fresh seeded off-grid points and rewrite its
    accuracy attributes (``max_abs_error``, ``rms_error``, ``n_check_points``,
    ``error_target_met``, ``accuracy_comment``) in place; ``history`` gets a line.

    Parameters
    ----------
    name : str
        Registered table name.
    path : path-like, optional
        Default: ``<default_output_dir()>/<name>.nc`` (a shipped table is rewritten only
        when its path, ``SHIPPED_TABLES_DIR / "<name>.nc"``, is given).
    n_points : int, optional
        Number of check points (default: the spec's count for the file's resolution).
    seed : int
        Seed of the check points (the build uses another seed).
    scheduler, workers, workdir, progress, command
        As in :func:`build_table`.

    Returns
    -------
    dict
        Per variable: ``max_abs_error``, ``rms_error``, ``n_check_points``.
    """
    import datetime as _dt  # noqa: PLC0415

    import netCDF4  # noqa: PLC0415

    from railcontact.tables import Table  # noqa: PLC0415

    spec = get_spec(name)
    path = Path(path) if path is not None else default_output_dir() / f"{name}.nc"
    table = Table.from_file(path, expected_name=name)
    resolution = str(table.attrs.get("resolution", "default"))
    axes, _ = spec.grid(resolution)
    if n_points is not None:
        spec_n = dict(spec.n_check)
        spec.n_check[resolution] = int(n_points)
    try:
        check = spec.make_check_points(axes, resolution, seed=seed)
    finally:
        if n_points is not None:
            spec.n_check.clear()
            spec.n_check.update(spec_n)
    h = hashlib.sha1(np.ascontiguousarray(check).tobytes() + spec.method.encode())
    work = Path(workdir or default_workdir()) / f"{name}-check-{h.hexdigest()[:12]}"
    work.mkdir(parents=True, exist_ok=True)
    tasks = [(work / f"check_{i:06d}.npy", check[a:b])
             for i, (a, b) in enumerate(_chunks(len(check), spec.chunk_size))]
    _run(spec, tasks, work, scheduler, workers, progress)
    ref = np.concatenate([np.load(f) for f, _ in tasks])
    got = table.spline.evaluate(np.ascontiguousarray(check[:, :len(axes)]), check=False)
    result = {}
    now = _dt.datetime.now(_dt.timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ")
    with netCDF4.Dataset(str(path), "a") as nc:
        for k, v in enumerate(spec.variables):
            err = np.abs(got[:, k] - ref[:, k]) / v.error_scale
            acc = dict(max_abs_error=float(err.max()), rms_error=float(np.sqrt(np.mean(err**2))),
                       n_check_points=len(check))
            result[v.name] = acc
            var = nc.variables[v.name]
            met = acc["max_abs_error"] <= v.error_target
            var.setncattr("max_abs_error", acc["max_abs_error"])
            var.setncattr("rms_error", acc["rms_error"])
            var.setncattr("n_check_points", np.int32(len(check)))
            var.setncattr("error_target_met", "yes" if met else "no")
            var.setncattr("accuracy_comment", (
                "max and RMS of |spline - direct computation| / error_scale on "
                f"{len(check)} seeded random off-grid points (seed {seed}, re-checked "
                f"{now})" + ("" if met else "; TARGET NOT MET")))
        nc.setncattr("history", f"{nc.getncattr('history')}\n{now}: accuracy re-checked by "
                     f"`{command or f'python -m tablegen check --only {name}'}`")
    for f, _ in tasks:
        f.unlink(missing_ok=True)
    try:
        work.rmdir()
    except OSError:
        pass
    return result
