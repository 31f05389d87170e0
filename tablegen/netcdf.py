"""CF-1.8 netCDF writer for tables (read back by :class:`railcontact.tables.Table`).

Layout (``railcontact_table_format = 1``, or 2 with node values on a block, below), for axes
``A1..AD`` and variables ``V``:

* coordinates ``A`` (dim ``A``): the nodes; attributes ``units``, ``long_name``,
  ``double_knots``, ``out_of_range``, ``spline_knots``;
* ``A_knots`` (dim ``A_knot``): the knot vector of the cubic B-spline along ``A``;
* ``V`` (dims ``A1..AD``): values at the nodes; attributes ``units``, ``long_name``, the method,
  and the recorded accuracy (``max_abs_error``, ``rms_error``, ``error_target``,
  ``error_target_met``, ``n_check_points``). A table with symmetries (format 2, written when
  the spec has ``reduce``) stores them only on the block of nodes that was computed: along an
  axis where that block is not the whole axis the dimension is ``A_block``, with the
  coordinate variable ``A_block`` (a contiguous run of ``A``'s nodes); the other nodes'
  values follow from the symmetries (global attribute ``node_values_block``) or from the
  spline. A table whose spec does not store node values (format 3,
  ``TableSpec.node_values_stored = False``) writes ``V`` as a scalar variable with the same
  attributes (its ``bspline_coefficients`` names the coefficients; no node values), and the
  coefficients with HDF5 Fletcher-32 checksums;
* ``V_bspline_coefficients`` (dims ``A1_bspline..AD_bspline``): tensor-product B-spline
  coefficients, so that ``V(x) = sum c[i1..iD] B_i1(x1) ... B_iD(xD)`` with the cubic B-splines
  of the knot vectors (de Boor 1978).

These attributes alone are enough to evaluate a table in another language:
``examples/table_reader.c`` and ``examples/table_reader.f90`` use nothing else (global
``table_axes``, ``spline_degree``, ``railcontact_table_format``; per axis ``spline_knots``; per
variable ``bspline_coefficients``), and ``tests/test_examples.py`` checks them against the
Python reader. Keep these names when changing the writer.
"""

from __future__ import annotations

import datetime as _dt
import os
import subprocess
from pathlib import Path

import numpy as np

from railcontact import __version__ as _rc_version
from railcontact.tables import (SPLINE_DEGREE, TABLE_FORMAT_SPLINE_ONLY,
                                TABLE_FORMAT_VERSION)

__all__ = ["write_table", "git_revision"]

_REPO = Path(__file__).resolve().parent.parent


def git_revision():
    """Short git revision of the checkout (``+dirty`` if tablegen or railcontact changed)."""
    try:
        rev = subprocess.run(["git", "rev-parse", "--short=12", "HEAD"], cwd=_REPO,
                             capture_output=True, text=True, timeout=10).stdout.strip()
        dirty = subprocess.run(["git", "status", "--porcelain", "--", "tablegen",
                                "fmu_src/railcontact"], cwd=_REPO, capture_output=True,
                               text=True, timeout=10).stdout.strip()
        return (rev or "unknown") + ("+dirty" if dirty else "")
    except (OSError, subprocess.SubprocessError):
        return "unknown"


def write_table(path, spec, axes, knots, values, coefficients, accuracy, command, build_info,
                node_block=None):
    """Write one table file atomically (``path.tmp`` then rename).

    Parameters
    ----------
    path : path-like
    spec : TableSpec
    axes : list of Axis
    knots : list of ndarray
    values, coefficients : ndarray, shape (n_var, n_1, ..., n_D)
    accuracy : dict
        Per variable name: ``max_abs_error``, ``rms_error``, ``n_check_points``.
    command : str
        Command line recorded in ``history``.
    build_info : dict
        Extra global attributes (resolution, build time, workers).
    node_block : tuple of slice, optional
        Per axis, the nodes whose values are stored (format 2; see the module docstring):
        a table with symmetries keeps only the computed block (the exact creep table: a
        quarter, 8 MB less). Default: every node (format 1).
    """
    import xarray as xr  # noqa: PLC0415

    path = Path(path)
    coords, data_vars = {}, {}
    dims = [a.name for a in axes]
    cdims = [f"{a.name}_bspline" for a in axes]
    stored = getattr(spec, "node_values_stored", True)
    block = (tuple(node_block) if node_block is not None and stored
             else (slice(None),) * len(axes))   # (format 3: no node values, no blocks)
    vdims = []
    for a, sl in zip(axes, block):
        part = a.nodes[sl]
        if len(part) == len(a.nodes):
            vdims.append(a.name)
            continue
        vdims.append(f"{a.name}_block")
        coords[f"{a.name}_block"] = (f"{a.name}_block", part, {
            "units": a.units, "long_name": f"the nodes of {a.name} where node values are stored",
            "comment": (f"a contiguous run of the nodes {a.name}: the block of the grid that was "
                        "computed; the other nodes' values follow by the table's symmetries "
                        "(global attribute node_values_block) or from the spline")})
    blocked = vdims != dims
    for a, t in zip(axes, knots):
        coords[a.name] = (a.name, a.nodes, {
            "units": a.units, "long_name": a.long_name,
            "double_knots": np.asarray(a.double_knots, dtype=float),
            "out_of_range": a.out_of_range,
            "spline_knots": f"{a.name}_knots",
            "periodic": np.int32(bool(getattr(a, "periodic", False))),
            "comment": a.comment or "grid nodes (the spline interpolates the values here)"})
        data_vars[f"{a.name}_knots"] = (f"{a.name}_knot", np.asarray(t, float), {
            "units": a.units, "long_name": f"cubic B-spline knot vector along {a.name}",
            "comment": ("periodic cubic interpolation over [first node, last node] (one period; "
                        "the knots continue periodically beyond it, so C2 across the seam)"
                        if getattr(a, "periodic", False) else
                        "not-a-knot interpolation; double knots repeat a node")})
    digits = getattr(spec, "significant_digits", None)
    if digits and not (getattr(spec, "node_values_float32", False)
                       and getattr(spec, "coefficients_float32", False)):
        raise ValueError("significant_digits needs node_values_float32 and coefficients_float32")
    # each quantised variable's digits (its own or the spec's), by data variable name
    quantised = {name: int(v.significant_digits or digits) for v in spec.variables
                 for name in (v.name, f"{v.name}_bspline_coefficients")} if digits else {}
    for k, v in enumerate(spec.variables):
        acc = accuracy[v.name]
        met = acc["max_abs_error"] <= v.error_target
        single = getattr(spec, "node_values_float32", False)
        if not stored:   # format 3: a scalar that carries the attributes
            vdims, node_values = (), np.int32(0)
        else:
            node_values = np.asarray(values[k])[block]
            node_values = node_values.astype(np.float32) if single else node_values
        data_vars[v.name] = (vdims, node_values, {
            "units": v.units, "long_name": v.long_name,
            "bspline_coefficients": f"{v.name}_bspline_coefficients",
            "method": spec.method,
            "interpolation": "tensor-product cubic B-spline interpolating the node values "
                             "(C2; C1 at double knots)",
            "max_abs_error": float(acc["max_abs_error"]),
            "rms_error": float(acc["rms_error"]),
            "error_scale": float(v.error_scale),
            "error_target": float(v.error_target),
            "error_target_met": "yes" if met else "no",
            "n_check_points": np.int32(acc["n_check_points"]),
            "accuracy_comment": (
                "max and RMS of |spline - direct computation| / error_scale on "
                f"{int(acc['n_check_points'])} seeded random off-grid points"
                + ("" if met else "; TARGET NOT MET")),
            "comment": v.comment,
            **({"node_values": "not stored (railcontact_table_format 3): the spline at the "
                               "nodes gives them"} if not stored else {}),
            **({"node_value_precision": "float32"} if single and stored else {}),
            **({"significant_digits": np.int32(quantised[v.name])}
               if digits and stored else {})})
        single_coef = getattr(spec, "coefficients_float32", False)
        data_vars[f"{v.name}_bspline_coefficients"] = (cdims, (
            coefficients[k].astype(np.float32) if single_coef else coefficients[k]), {
            "units": v.units,
            "long_name": f"tensor-product cubic B-spline coefficients of {v.name}",
            "comment": "value = sum over i of c[i1,...,iD] * prod_d B(d, i_d)(x_d), with the "
                       "degree-3 B-splines of the knot vectors <axis>_knots",
            **({"coefficient_precision": "float32"} if single_coef else {}),
            **({"absolute_precision": float(v.absolute_precision),
                "absolute_precision_comment": (
                    "coefficients rounded to multiples of absolute_precision (the spline moves "
                    "by at most half of it) except "
                    + (getattr(spec, "relative_precision_comment", "") or "nowhere"))}
               if getattr(v, "absolute_precision", None) else {}),
            **({"significant_digits": np.int32(quantised[v.name])} if digits else {})})
    now = _dt.datetime.now(_dt.timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ")
    attrs = {
        "Conventions": "CF-1.8",
        "title": spec.title,
        "institution": "railcontact project",
        "source": f"railcontact {_rc_version} (git {git_revision()}), tablegen",
        "history": f"{now}: created by `{command}`",
        "references": spec.references,
        "comment": ("Smooth lookup table. Evaluate the cubic B-spline given by the "
                    "*_bspline_coefficients variables and the <axis>_knots vectors (any de Boor "
                    "evaluator)"
                    + ("; the node values alone allow a cruder linear interpolation"
                       if stored else "; the node values are not stored (the spline at the "
                       "nodes gives them)")
                    + (" (on the block they are stored on)." if blocked else ".")),
        "railcontact_table_format": np.int32(TABLE_FORMAT_SPLINE_ONLY if not stored
                                             else TABLE_FORMAT_VERSION if blocked else 1),
        "table_name": spec.name,
        "table_axes": " ".join(dims),
        "table_variables": " ".join(v.name for v in spec.variables),
        "spline_degree": np.int32(SPLINE_DEGREE),
        "method": spec.method,
    }
    if blocked:
        attrs["node_values_block"] = (
            "node values are stored on the computed block only ("
            + ", ".join(f"{a.name} {a.nodes[sl][0]:.6g} to {a.nodes[sl][-1]:.6g}"
                        for a, sl, d in zip(axes, block, vdims) if d != a.name)
            + "); the rest of the grid follows by the table's symmetries (global attribute "
            "symmetry) or from the B-spline, which covers every node")
    attrs.update({k: v for k, v in spec.attributes.items()})
    if spec.build_attributes is not None:
        attrs.update(spec.build_attributes())
    attrs.update(build_info)
    ds = xr.Dataset(data_vars=data_vars, coords=coords, attrs=attrs)
    encoding = {name: {"_FillValue": None} for name in list(ds.data_vars) + list(ds.coords)}
    for name in ds.data_vars:
        if ds[name].ndim >= 2:
            # one chunk per variable (readers load whole arrays): zlib sees the whole array
            # (creep_exact's coefficients: 15.5 MiB against 20.8 in netCDF's default chunks)
            encoding[name].update(zlib=True, complevel=4, shuffle=True,
                                  chunksizes=tuple(ds[name].shape))
            if name in quantised:
                # netCDF-4 quantisation: trailing mantissa bits zeroed (any reader reads floats)
                encoding[name].update(significant_digits=quantised[name],
                                      quantize_mode="GranularBitRound", complevel=9)
            if not stored:   # format 3: no node values to check the coefficients against
                encoding[name].update(fletcher32=True)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(path.name + ".tmp")
    ds.to_netcdf(tmp, format="NETCDF4", encoding=encoding)
    os.replace(tmp, path)
    return path
