"""Tests of the table builder (tablegen): spec registry, chunked/resumable build, dask, CLI."""

import numpy as np
import pytest

import tablegen
from tablegen.__main__ import main
from tablegen.build import build_table
from tablegen.registry import REGISTRY, get_spec
from tablegen.spec import Axis
from tablegen.specs import selftest_function
from railcontact.tables import Table, TableFileError

# builds of shipped tables at other resolutions in this file warn that they are less accurate
# than the shipped ones (as they should; asserted where it is the point)
pytestmark = pytest.mark.filterwarnings("ignore::railcontact.tables.TableAccuracyWarning")


def test_registry_lists_builtin_specs():
    assert "creep_modified_strip" in REGISTRY and "selftest" in REGISTRY
    with pytest.raises(ValueError, match="table name must be one of"):
        get_spec("no_such_table")
    spec = get_spec("creep_modified_strip")
    with pytest.raises(ValueError, match="resolution must be one of"):
        spec.grid("huge")
    axes, pts = spec.grid("coarse")
    assert pts.shape == (len(axes[0].nodes), 1)
    assert 1.0 in axes[0].nodes  # the saturation lies on a grid line


def test_axis_validation():
    with pytest.raises(ValueError, match="strictly ascending"):
        Axis("x", [0.0, 1.0, 0.5, 2.0], "1", "x")
    with pytest.raises(ValueError, match="out_of_range"):
        Axis("x", [0.0, 1.0, 1.5, 2.0], "1", "x", out_of_range="clamp")


def test_build_selftest_file_is_exact_and_records_accuracy(tmp_path):
    res = build_table("selftest", "coarse", output_dir=tmp_path, scheduler="synchronous",
                      workdir=tmp_path / "work", progress=False)
    table = Table.from_file(res["path"])
    spec = get_spec("selftest")
    axes, pts = spec.grid("coarse")
    want = selftest_function(pts)
    got = table.spline.evaluate(pts)
    assert np.max(np.abs(got - want)) < 1e-13              # exact at the nodes
    # recorded accuracy equals an independent recomputation on the same check points
    check = spec.make_check_points(axes, "coarse")
    err = np.abs(table.spline.evaluate(check) - selftest_function(check))
    for k, v in enumerate(table.variables):
        assert table.variable_attrs[v]["max_abs_error"] == pytest.approx(err[:, k].max(),
                                                                         rel=1e-12, abs=1e-300)
    # f has a C1 kink at x = 1 with a double knot: no overshoot past 1 anywhere
    x = np.linspace(0.0, 3.0, 30001)
    dense = np.stack([x, np.full_like(x, 1.3)], axis=1)
    assert table("f", dense).max() <= 1.0 + 1e-15
    # "hold" beyond the last node of x; error below the first node and beyond s
    assert table("f", [[5.0, 1.0]]) == pytest.approx(1.0)
    with pytest.raises(ValueError, match="s must be in"):
        table("f", [[0.5, 3.0]])
    assert not (tmp_path / "work").exists() or not any((tmp_path / "work").rglob("*.npy"))


def test_build_resumes_from_finished_chunks(tmp_path, monkeypatch):
    work = tmp_path / "work"
    build_table("selftest", "coarse", output_dir=tmp_path, scheduler="synchronous",
                workdir=work, progress=False, keep_chunks=True)
    chunks = sorted(work.rglob("grid_*.npy"))
    assert len(chunks) > 2
    chunks[1].unlink()
    calls = []
    spec = REGISTRY["selftest"]

    def counting(points):
        calls.append(len(points))
        return selftest_function(points)

    monkeypatch.setattr(spec, "function", counting)
    res = build_table("selftest", "coarse", output_dir=tmp_path, scheduler="synchronous",
                      workdir=work, progress=False)
    assert calls == [spec.chunk_size]           # only the missing chunk was recomputed
    Table.from_file(res["path"])


def test_failing_chunk_keeps_finished_ones(tmp_path, monkeypatch):
    spec = REGISTRY["selftest"]
    count = {"n": 0}

    def flaky(points):
        count["n"] += 1
        if count["n"] == 3:
            raise RuntimeError("worker died")
        return selftest_function(points)

    monkeypatch.setattr(spec, "function", flaky)
    with pytest.raises(RuntimeError, match="worker died"):
        build_table("selftest", "coarse", output_dir=tmp_path, scheduler="synchronous",
                    workdir=tmp_path / "work", progress=False)
    assert len(list((tmp_path / "work").rglob("grid_*.npy"))) == 2
    assert not (tmp_path / "selftest.nc").exists()


def test_build_on_local_dask_cluster(tmp_path):
    """One worker process of a dask.distributed LocalCluster (the default scheduler)."""
    res = build_table("selftest", "coarse", output_dir=tmp_path, scheduler=None, workers=1,
                      workdir=tmp_path / "work", progress=False)
    ref = build_table("selftest", "coarse", output_dir=tmp_path / "sync",
                      scheduler="synchronous", workdir=tmp_path / "work2", progress=False)
    a, b = Table.from_file(res["path"]), Table.from_file(ref["path"])
    for v in a.variables:
        np.testing.assert_array_equal(a.values[v], b.values[v])
    assert a.attrs["build_scheduler"] == "local cluster"


def test_cli_list_and_build(tmp_path, capsys):
    assert main(["list"]) == 0
    out = capsys.readouterr().out
    assert "creep_modified_strip" in out
    assert main(["build", "--only", "selftest", "--resolution", "coarse", "--scheduler",
                 "synchronous", "--output-dir", str(tmp_path), "--workdir",
                 str(tmp_path / "w"), "--no-progress"]) == 0
    table = Table.from_file(tmp_path / "selftest.nc")
    assert "python -m tablegen build --only selftest" in table.attrs["history"]
    assert table.attrs["railcontact_table_format"] == 1
    with pytest.raises(SystemExit):
        main(["build", "--only", "bogus", "--scheduler", "synchronous"])


def test_package_exports():
    assert tablegen.build_table is build_table


def test_exact_spec_grid_covers_every_sign_and_computes_a_quarter():
    """The exact creep table's axes: a0/b0 in [0.1, 10], nu in [0, 0.5], the signed creepage
    coordinate over [-1, 1] (1: full sliding) with rho = 1.03 near the saturation, the
    creepage angle periodic over [-pi, pi], the signed spin coordinate to +-20; the solver is
    called on the quarter s >= 0, |theta| <= pi/2, tau >= 0 only, and the check points lie
    there."""
    from railcontact.exact_table import creepage_magnitude

    spec = get_spec("creep_exact")
    axes, full = spec.grid("default")
    assert [a.name for a in axes] == ["log_aspect_ratio", "poisson_ratio",
                                      "creepage_coordinate", "creepage_angle",
                                      "spin_coordinate"]
    g, nu, s, theta, tau = (a.nodes for a in axes)
    assert np.exp(g[[0, -1]]) == pytest.approx([0.1, 10.0])
    assert nu[[0, -1]] == pytest.approx([0.0, 0.5])
    assert s[[0, -1]] == pytest.approx([-1.0, 1.0]) and np.all(s == -s[::-1])
    assert np.all(tau == -tau[::-1]) and tau[-1] == 20.0
    assert axes[3].periodic and theta[[0, -1]] == pytest.approx([-np.pi, np.pi])
    assert np.any(np.abs(creepage_magnitude(s[np.abs(s) < 1]) - 1.03) < 1e-12)
    points, assemble = spec.reduce(axes)
    assert np.all(points[:, 2] >= 0) and np.all(np.abs(points[:, 3]) <= np.pi / 2 + 1e-12)
    assert np.all(points[:, 4] >= 0)
    assert len(points) * 4 < len(full)       # a quarter (plus the planes it shares)
    check = spec.make_check_points(axes, "coarse")
    assert check.shape[1] == 5
    assert np.all(check[:, 2] >= 0) and np.all(np.abs(check[:, 3]) <= np.pi / 2)
    assert np.all((check[:, 1] >= 0) & (check[:, 1] <= 0.5))


def test_check_table_rewrites_accuracy_attributes(tmp_path):
    from tablegen.build import check_table

    res = build_table("selftest", "coarse", output_dir=tmp_path, scheduler="synchronous",
                      workdir=tmp_path / "w", progress=False)
    out = check_table("selftest", res["path"], n_points=37, seed=5, scheduler="synchronous",
                      workdir=tmp_path / "w", progress=False)
    table = Table.from_file(res["path"])
    spec = get_spec("selftest")
    axes, _ = spec.grid("coarse")
    rng = np.random.default_rng(5)
    lo = np.array([a.nodes[0] for a in axes])
    hi = np.array([a.nodes[-1] for a in axes])
    pts = lo + (hi - lo) * rng.random((37, 2))
    err = np.abs(table.spline.evaluate(pts) - selftest_function(pts))
    for k, v in enumerate(table.variables):
        assert table.variable_attrs[v]["n_check_points"] == 37
        assert table.variable_attrs[v]["max_abs_error"] == pytest.approx(err[:, k].max(),
                                                                         abs=1e-300)
        assert out[v]["max_abs_error"] == table.variable_attrs[v]["max_abs_error"]
    assert "accuracy re-checked" in table.attrs["history"]


def test_float32_node_values_are_declared_and_read(tmp_path, monkeypatch):
    """A spec that stores its node values in float32 (the exact creep table: under 20 MB)
    writes them flagged per variable; the reader accepts them (integrity to 1e-6) and the
    float64 coefficients give the same spline as a float64 file."""
    import netCDF4

    spec = get_spec("selftest")
    ref = build_table("selftest", "coarse", output_dir=tmp_path / "a", scheduler="synchronous",
                      workdir=tmp_path / "w", progress=False, keep_chunks=True)
    monkeypatch.setattr(spec, "node_values_float32", True)
    res = build_table("selftest", "coarse", output_dir=tmp_path / "b", scheduler="synchronous",
                      workdir=tmp_path / "w", progress=False)
    with netCDF4.Dataset(res["path"]) as nc:
        for v in spec.variables:
            assert nc.variables[v.name].dtype == np.float32
            assert nc.variables[v.name].getncattr("node_value_precision") == "float32"
            assert nc.variables[f"{v.name}_bspline_coefficients"].dtype == np.float64
    a, b = Table.from_file(ref["path"]), Table.from_file(res["path"])
    pts = np.array([[0.3, 0.9], [1.1, 1.7]])
    np.testing.assert_array_equal(a.spline.evaluate(pts), b.spline.evaluate(pts))


def test_reuse_nodes_computes_only_what_the_earlier_build_lacks(tmp_path, monkeypatch):
    """``reuse_nodes``: node values come from an earlier file of the same table, the points
    the spec marks analytic and the check points are computed, and the new file equals a
    fresh build; on a finer grid only the points that are not the file's nodes are computed
    (equal to a fresh fine build too); a file of another solver is refused by name."""
    fresh = build_table("selftest", "coarse", output_dir=tmp_path / "fresh",
                        scheduler="synchronous", workdir=tmp_path / "w0", progress=False)
    spec = REGISTRY["selftest"]
    calls = []

    def counting(points):
        calls.append(np.asarray(points).copy())
        return selftest_function(points)

    monkeypatch.setattr(spec, "function", counting)
    monkeypatch.setattr(spec, "analytic_points", lambda p: np.asarray(p)[:, 0] >= 1.5)
    res = build_table("selftest", "coarse", output_dir=tmp_path / "new", scheduler="synchronous",
                      workdir=tmp_path / "w1", progress=False, reuse_nodes=fresh["path"])
    axes, points = spec.grid("coarse")
    n_analytic = int(np.count_nonzero(points[:, 0] >= 1.5))
    n_check = spec.n_check["coarse"]
    computed = np.concatenate(calls)
    assert len(computed) == n_analytic + n_check
    assert np.all(computed[:n_analytic, 0] >= 1.5)
    old, new = Table.from_file(fresh["path"]), Table.from_file(res["path"])
    pts = np.column_stack([np.linspace(0.0, 2.0, 41), np.linspace(0.5, 2.0, 41)])
    np.testing.assert_allclose(new.spline.evaluate(pts), old.spline.evaluate(pts), rtol=0,
                               atol=1e-12)
    import netCDF4  # noqa: PLC0415
    with netCDF4.Dataset(res["path"]) as ds:
        note = ds.getncattr("build_reused_nodes")
    assert f"{len(points) - n_analytic} of {len(points)}" in note
    assert f"{n_analytic} analytic points recomputed" in note

    # a finer grid: the coarse file's nodes are taken, only the new points computed, and the
    # file equals a fresh fine build
    calls.clear()
    monkeypatch.setattr(spec, "analytic_points", None)
    finer = build_table("selftest", "fine", output_dir=tmp_path / "fine", scheduler="synchronous",
                        workdir=tmp_path / "w3", progress=False, reuse_nodes=fresh["path"])
    _, fine_points = spec.grid("fine")
    _, coarse_points = spec.grid("coarse")
    on_coarse = (np.abs(fine_points[:, None, :] - coarse_points[None, :, :]).max(axis=2)
                 <= 1e-12).any(axis=1)
    computed = np.concatenate(calls)
    assert 0 < on_coarse.sum() < len(fine_points)
    assert len(computed) == int((~on_coarse).sum()) + spec.n_check["fine"]
    monkeypatch.setattr(spec, "function", selftest_function)
    full = build_table("selftest", "fine", output_dir=tmp_path / "full", scheduler="synchronous",
                       workdir=tmp_path / "w4", progress=False)
    np.testing.assert_allclose(Table.from_file(finer["path"]).spline.evaluate(pts),
                               Table.from_file(full["path"]).spline.evaluate(pts), rtol=0,
                               atol=1e-12)
    with netCDF4.Dataset(finer["path"]) as ds:
        assert f"{int((~on_coarse).sum())} points that are not nodes" in ds.getncattr(
            "build_reused_nodes")

    monkeypatch.setattr(spec, "method", "another solver")
    with pytest.raises(ValueError, match="reuse_nodes must be a file of table 'selftest'"):
        build_table("selftest", "coarse", output_dir=tmp_path / "x", scheduler="synchronous",
                    workdir=tmp_path / "w2", progress=False, reuse_nodes=fresh["path"])


def test_reuse_nodes_across_a_method_change_recomputes_what_the_spec_marks(tmp_path,
                                                                           monkeypatch):
    """A file of another method is reused only where ``spec.reusable_points`` says its
    values stand: the solver changed for s >= 1.5 here, so exactly those grid points (and
    the check points) are computed, and their values are the new method's; a spec without
    the hook, or a hook that returns None, refuses the file."""
    old = build_table("selftest", "coarse", output_dir=tmp_path / "old", scheduler="synchronous",
                      workdir=tmp_path / "w0", progress=False)
    spec = REGISTRY["selftest"]
    calls = []

    def changed(points):       # the "new method": g doubled where s >= 1.5
        calls.append(np.asarray(points).copy())
        out = selftest_function(points)
        out[:, 1] *= np.where(np.asarray(points)[:, 1] >= 1.5, 2.0, 1.0)
        return out

    monkeypatch.setattr(spec, "function", changed)
    monkeypatch.setattr(spec, "method", "new method")
    seen = []

    def reusable(attrs, points):
        seen.append(attrs["method"])
        return (np.asarray(points)[:, 1] < 1.5) if attrs["method"] == (
            "tablegen.specs.selftest_function") else None

    monkeypatch.setattr(spec, "reusable_points", reusable)
    res = build_table("selftest", "coarse", output_dir=tmp_path / "new", scheduler="synchronous",
                      workdir=tmp_path / "w1", progress=False, reuse_nodes=old["path"])
    assert seen == ["tablegen.specs.selftest_function"]
    _, points = spec.grid("coarse")
    n_changed = int(np.count_nonzero(points[:, 1] >= 1.5))
    assert 0 < n_changed < len(points)
    computed = np.concatenate(calls)
    assert len(computed) == n_changed + spec.n_check["coarse"]
    assert np.all(computed[:n_changed, 1] >= 1.5)
    # equal to a fresh build of the new method
    full = build_table("selftest", "coarse", output_dir=tmp_path / "full",
                       scheduler="synchronous", workdir=tmp_path / "w2", progress=False)
    pts = np.column_stack([np.linspace(0.0, 2.0, 41), np.linspace(0.5, 2.0, 41)])
    np.testing.assert_allclose(Table.from_file(res["path"]).spline.evaluate(pts),
                               Table.from_file(full["path"]).spline.evaluate(pts), rtol=0,
                               atol=1e-12)
    import netCDF4  # noqa: PLC0415
    with netCDF4.Dataset(res["path"]) as ds:
        note = ds.getncattr("build_reused_nodes")
    assert f"{n_changed} points whose method changed computed" in note
    assert "the method 'tablegen.specs.selftest_function'" in note

    monkeypatch.setattr(spec, "method", "a third method")   # the hook refuses the new file
    with pytest.raises(ValueError, match="reusable_points accepts; got .*method 'new method'"):
        build_table("selftest", "coarse", output_dir=tmp_path / "x", scheduler="synchronous",
                    workdir=tmp_path / "w3", progress=False, reuse_nodes=res["path"])
    monkeypatch.setattr(spec, "reusable_points", None)
    with pytest.raises(ValueError, match="built with the same method"):
        build_table("selftest", "coarse", output_dir=tmp_path / "x", scheduler="synchronous",
                    workdir=tmp_path / "w4", progress=False, reuse_nodes=old["path"])


def test_float32_coefficients_are_declared_and_read(tmp_path, monkeypatch):
    """A spec that stores its coefficients in float32 too (the exact creep table with its
    finer angle axis: under 20 MB) flags them per variable; the reader accepts them (integrity
    to 1e-6) and evaluates the same spline to float32 rounding; an undeclared float32
    coefficient variable is still refused by name."""
    import netCDF4

    spec = get_spec("selftest")
    ref = build_table("selftest", "coarse", output_dir=tmp_path / "a", scheduler="synchronous",
                      workdir=tmp_path / "w", progress=False, keep_chunks=True)
    monkeypatch.setattr(spec, "node_values_float32", True)
    monkeypatch.setattr(spec, "coefficients_float32", True)
    res = build_table("selftest", "coarse", output_dir=tmp_path / "b", scheduler="synchronous",
                      workdir=tmp_path / "w", progress=False)
    with netCDF4.Dataset(res["path"]) as nc:
        for v in spec.variables:
            coef = nc.variables[f"{v.name}_bspline_coefficients"]
            assert coef.dtype == np.float32
            assert coef.getncattr("coefficient_precision") == "float32"
    a, b = Table.from_file(ref["path"]), Table.from_file(res["path"])
    pts = np.column_stack([np.linspace(0.0, 2.0, 41), np.linspace(0.5, 2.0, 41)])
    np.testing.assert_allclose(b.spline.evaluate(pts), a.spline.evaluate(pts), rtol=0,
                               atol=1e-6)
    assert not np.array_equal(b.spline.evaluate(pts), a.spline.evaluate(pts))
    with netCDF4.Dataset(res["path"], "a") as nc:
        nc.variables["f_bspline_coefficients"].delncattr("coefficient_precision")
    with pytest.raises(TableFileError, match="'f_bspline_coefficients' is stored as float32"):
        Table.from_file(res["path"])


def test_quantised_tables_are_declared_read_and_smaller(tmp_path, monkeypatch):
    """A spec with ``significant_digits`` (the exact creep table: 5) stores its float32 node
    values and coefficients quantised (netCDF-4 GranularBitRound, trailing mantissa bits
    zeroed, so zlib compresses them), declares the digits on both, and the reader accepts the
    file and evaluates the same spline to the declared digits (not bit for bit); a declaration
    on one of the two only is refused by name."""
    import netCDF4

    spec = get_spec("selftest")
    monkeypatch.setattr(spec, "node_values_float32", True)
    monkeypatch.setattr(spec, "coefficients_float32", True)
    ref = build_table("selftest", "coarse", output_dir=tmp_path / "a", scheduler="synchronous",
                      workdir=tmp_path / "w", progress=False, keep_chunks=True)
    monkeypatch.setattr(spec, "significant_digits", 4)
    if len(spec.variables) > 1:    # a variable may keep its own digits
        monkeypatch.setattr(spec.variables[-1], "significant_digits", 3)
    res = build_table("selftest", "coarse", output_dir=tmp_path / "b", scheduler="synchronous",
                      workdir=tmp_path / "w", progress=False)
    with netCDF4.Dataset(res["path"]) as nc:
        for v in spec.variables:
            for name in (v.name, f"{v.name}_bspline_coefficients"):
                var = nc.variables[name]
                assert int(var.getncattr("significant_digits")) == (v.significant_digits or 4)
                assert int(var.getncattr(
                    "_QuantizeGranularBitRoundNumberOfSignificantDigits")) == (
                        v.significant_digits or 4)
                data = np.asarray(var[:], dtype=np.float32)
                # GranularBitRound: at most ~4 digits' worth of mantissa bits are kept
                low_bits = data.view(np.uint32) & np.uint32((1 << 8) - 1)
                assert np.all(low_bits == 0)
    a, b = Table.from_file(ref["path"]), Table.from_file(res["path"])
    pts = np.column_stack([np.linspace(0.0, 2.0, 41), np.linspace(0.5, 2.0, 41)])
    want = a.spline.evaluate(pts)
    for k, v in enumerate(spec.variables):     # within the variable's own digits
        digits = v.significant_digits or 4
        np.testing.assert_allclose(b.spline.evaluate(pts)[:, k], want[:, k], rtol=0,
                                   atol=2.0 * 10.0**-digits * np.abs(want[:, k]).max())
    assert not np.array_equal(b.spline.evaluate(pts), a.spline.evaluate(pts))
    with netCDF4.Dataset(res["path"], "a") as nc:
        nc.variables["f_bspline_coefficients"].delncattr("significant_digits")
    with pytest.raises(TableFileError, match="'f' and its coefficients must declare the same "
                                             "significant_digits"):
        Table.from_file(res["path"])
    monkeypatch.setattr(spec, "coefficients_float32", False)
    with pytest.raises(ValueError, match="significant_digits needs node_values_float32"):
        build_table("selftest", "coarse", output_dir=tmp_path / "c", scheduler="synchronous",
                    workdir=tmp_path / "w", progress=False)


def _cheap_exact_values(points):
    """A smooth stand-in for the exact solver with the exact table's symmetries."""
    p = np.asarray(points, dtype=float)
    g, nu, s, th, tau = p.T
    return np.column_stack([s * (1.0 + 0.1 * g) * (1.0 + 0.2 * np.cos(2 * th)),
                            0.3 * s * np.sin(2 * th) * (1.0 + nu) + 0.01 * tau * s * np.cos(th),
                            0.05 * tau / (1.0 + tau) * (1.0 - s ** 2),
                            (1.0 - s) * (1.0 + 0.0 * tau)])


def test_absolute_precision_rounds_the_coefficients_outside_the_relative_region(
        tmp_path, monkeypatch):
    """A variable's ``absolute_precision`` q (the exact table's forces and moment: 2^-11)
    rounds its coefficients to multiples of q, except in the spec's relative-precision region
    (next to zero creepage), where they equal the unrounded fit's; the spline moves by at most
    q / 2 (the B-splines sum to one), checked at random points against the unrounded build;
    the file declares q; a q that is not a power of two is refused by name."""
    import netCDF4  # noqa: PLC0415

    from tablegen.spec import Variable  # noqa: PLC0415

    spec = REGISTRY["creep_exact"]
    q = 2.0**-11
    assert [v.absolute_precision for v in spec.variables] == [q, q, q, 2.0**-6]
    monkeypatch.setattr(spec.variables[3], "absolute_precision", None)   # (one variable kept)
    monkeypatch.setattr(spec, "function", _cheap_exact_values)
    # without the decimal quantisation on top (GranularBitRound keeps 5 digits from the
    # leading decimal digit: up to 3e-5 at |c| ~ 1), so that only q and float32 act
    monkeypatch.setattr(spec, "significant_digits", None)
    res = build_table("creep_exact", "coarse", output_dir=tmp_path / "a",
                      scheduler="synchronous", workdir=tmp_path / "w0", progress=False)
    for v in spec.variables:
        monkeypatch.setattr(v, "absolute_precision", None)
    ref = build_table("creep_exact", "coarse", output_dir=tmp_path / "b",
                      scheduler="synchronous", workdir=tmp_path / "w0", progress=False)
    got, want = Table.from_file(res["path"]), Table.from_file(ref["path"])
    s = np.asarray(got.axes[2]["nodes"])
    near = np.abs(s) < 0.005
    assert 1 <= np.count_nonzero(near) < len(s)
    for k in range(3):
        c, c0 = got.coefficients[k], want.coefficients[k]
        np.testing.assert_array_equal(c[:, :, near], c0[:, :, near])
        far = c[:, :, ~near]
        np.testing.assert_array_equal(far / q, np.round(far / q))
        assert np.abs(far - c0[:, :, ~near]).max() <= 0.5 * q + 1e-6   # + float32
        assert not np.array_equal(far, c0[:, :, ~near])
    np.testing.assert_array_equal(got.coefficients[3], want.coefficients[3])
    pts = np.random.default_rng(5).uniform([-2.3, 0.0, -1.0, -np.pi, -20.0],
                                           [2.3, 0.5, 1.0, np.pi, 20.0], (400, 5))
    diff = np.abs(got.spline.evaluate(pts) - want.spline.evaluate(pts))
    assert diff[:, :3].max() <= 0.5 * q + 1e-6 and diff[:, 3].max() == 0.0
    with netCDF4.Dataset(res["path"]) as ds:
        coef = ds["force_ratio_perpendicular_bspline_coefficients"]
        assert coef.getncattr("absolute_precision") == q
        assert "creepage_coordinate| < 0.005" in coef.getncattr("absolute_precision_comment")
        assert "absolute_precision" not in ds["stick_area_fraction_bspline_coefficients"].ncattrs()
    with pytest.raises(ValueError, match=r"'f': absolute_precision must be a power of two > 0 "
                                         r"\[units of the variable\]; got 3e-05"):
        Variable("f", "1", "f", absolute_precision=3e-5)


def test_table_with_symmetries_stores_node_values_on_the_computed_block(tmp_path,
                                                                        monkeypatch):
    """A table with symmetries (``spec.reduce``; the exact creep table, coarse, with a cheap
    point function) stores its node values on the computed block only (format 2:
    ``<axis>_block`` dimensions, s >= 0, |theta| <= pi/2, tau >= 0); the reader takes them,
    checks the spline against them, and the spline still covers every sign by the
    symmetries; a rebuild reusing the file computes only the analytic and check points; a
    block that is not a run of the axis's nodes is refused."""
    import netCDF4  # noqa: PLC0415

    spec = REGISTRY["creep_exact"]
    cheap = _cheap_exact_values
    calls = []

    def counting(points):
        calls.append(len(points))
        return cheap(points)

    monkeypatch.setattr(spec, "function", counting)
    monkeypatch.setattr(spec, "node_values_stored", True)   # format 2 (the shipped: 3)
    res = build_table("creep_exact", "coarse", output_dir=tmp_path / "a",
                      scheduler="synchronous", workdir=tmp_path / "w0", progress=False)
    axes, _ = spec.grid("coarse")
    quarter, _ = spec.reduce(axes)
    with netCDF4.Dataset(res["path"]) as ds:
        assert int(ds.getncattr("railcontact_table_format")) == 2
        assert "symmetries" in ds.getncattr("node_values_block")
        assert ds["force_ratio_parallel"].dimensions == (
            "log_aspect_ratio", "poisson_ratio", "creepage_coordinate_block",
            "creepage_angle_block", "spin_coordinate_block")
        s_b, th_b, tau_b = (np.asarray(ds[f"{n}_block"][:]) for n in (
            "creepage_coordinate", "creepage_angle", "spin_coordinate"))
    np.testing.assert_array_equal(s_b, np.unique(quarter[:, 2]))
    np.testing.assert_allclose(th_b, np.unique(quarter[:, 3]), rtol=0, atol=1e-12)
    np.testing.assert_array_equal(tau_b, np.unique(quarter[:, 4]))

    table = Table.from_file(res["path"])
    shape = tuple(len(np.unique(quarter[:, k])) for k in range(5))
    assert table.values["force_ratio_parallel"].shape == shape
    want = cheap(quarter).reshape(shape + (4,))
    # stored to 5 (stick area 2) digits, the forces and moment to multiples of their
    # absolute_precision q (the spline at a node moves by at most q / 2: 2.4e-4 at 2^-11)
    atol = 0.5 * spec.variables[0].absolute_precision + 5e-5
    for k, v in enumerate(table.variables):
        np.testing.assert_allclose(table.values[v], want[..., k], rtol=0,
                                   atol=atol if k < 3 else 5e-2)
    # the spline at a point and at its mirror images (the symmetries the file states)
    p = np.array([[0.3, 0.2, 0.4, 0.5, 1.7]])
    mirrors = np.array([[0.3, 0.2, -0.4, 0.5 - np.pi, 1.7],      # (-s, theta + pi): -, -
                        [0.3, 0.2, 0.4, -0.5, -1.7],             # mirror y: +, -, -
                        [0.3, 0.2, 0.4, np.pi - 0.5, 1.7]])      # reversed x: +, -, +
    base = table.spline.evaluate(p)[0]
    got = table.spline.evaluate(mirrors)
    np.testing.assert_allclose(got[0, :3], base[:3] * [-1, -1, 1], atol=2e-4)
    np.testing.assert_allclose(got[1, :3], base[:3] * [1, -1, -1], atol=2e-4)
    np.testing.assert_allclose(got[2, :3], base[:3] * [1, -1, 1], atol=2e-4)

    calls.clear()
    monkeypatch.setattr(spec, "analytic_points", lambda pts: np.asarray(pts)[:, 2] >= 1.0)
    again = build_table("creep_exact", "coarse", output_dir=tmp_path / "b",
                        scheduler="synchronous", workdir=tmp_path / "w1", progress=False,
                        reuse_nodes=res["path"])
    assert sum(calls) == int(np.count_nonzero(quarter[:, 2] >= 1.0)) + spec.n_check["coarse"]
    pts = np.random.default_rng(3).uniform([-2.3, 0.0, -1.0, -np.pi, -20.0],
                                           [2.3, 0.5, 1.0, np.pi, 20.0], (50, 5))
    np.testing.assert_allclose(Table.from_file(again["path"]).spline.evaluate(pts)[:, :3],
                               table.spline.evaluate(pts)[:, :3], rtol=0, atol=2e-4)

    bad = tmp_path / "bad.nc"
    bad.write_bytes(res["path"].read_bytes())
    with netCDF4.Dataset(bad, "a") as ds:
        ds["creepage_angle_block"][0] = ds["creepage_angle_block"][0] - 0.01
    with pytest.raises(TableFileError, match="not a contiguous run of the nodes of "
                                             "'creepage_angle'"):
        Table.from_file(bad)


def test_table_without_node_values_stores_the_spline_only(tmp_path, monkeypatch):
    """Format 3 (``node_values_stored = False``, the shipped exact table since 2026-11-27):
    each variable is a scalar carrying its attributes and naming its coefficients, the
    coefficients carry Fletcher-32 checksums, and the spline is the one format 2 stores
    (the same coefficients) in a smaller file; a rebuild reusing the file takes the spline at
    the nodes and computes only the analytic and check points; a corrupted file is refused."""
    import netCDF4  # noqa: PLC0415

    spec = REGISTRY["creep_exact"]
    assert spec.node_values_stored is False
    calls = []

    def counting(points):
        calls.append(len(points))
        return _cheap_exact_values(points)

    monkeypatch.setattr(spec, "function", counting)
    res = build_table("creep_exact", "coarse", output_dir=tmp_path / "a",
                      scheduler="synchronous", workdir=tmp_path / "w0", progress=False)
    with netCDF4.Dataset(res["path"]) as ds:
        assert int(ds.getncattr("railcontact_table_format")) == 3
        assert "node_values_block" not in ds.ncattrs()
        assert not any(d.endswith("_block") for d in ds.dimensions)
        for v in spec.variables:
            assert ds[v.name].ndim == 0
            assert ds[v.name].getncattr("bspline_coefficients") == \
                f"{v.name}_bspline_coefficients"
            assert "not stored" in ds[v.name].getncattr("node_values")
            assert 0.0 <= float(ds[v.name].getncattr("max_abs_error")) < 1.0
            assert ds[f"{v.name}_bspline_coefficients"].filters()["fletcher32"]
    table = Table.from_file(res["path"])
    assert table.values == {}
    monkeypatch.setattr(spec, "node_values_stored", True)
    res2 = build_table("creep_exact", "coarse", output_dir=tmp_path / "b",
                       scheduler="synchronous", workdir=tmp_path / "w0", progress=False)
    np.testing.assert_array_equal(table.coefficients, Table.from_file(res2["path"]).coefficients)
    assert res["size_bytes"] < res2["size_bytes"]
    axes, _ = spec.grid("coarse")
    quarter, _ = spec.reduce(axes)
    got = table.spline.evaluate(quarter)
    want = _cheap_exact_values(quarter)
    # 5 digits and multiples of q: the spline at a node within q / 2 of the values
    atol = 0.5 * spec.variables[0].absolute_precision + 5e-5
    np.testing.assert_allclose(got[:, :3], want[:, :3], rtol=0, atol=atol)
    np.testing.assert_allclose(got[:, 3], want[:, 3], rtol=0, atol=5e-2)   # 2 digits

    monkeypatch.setattr(spec, "node_values_stored", False)
    calls.clear()
    monkeypatch.setattr(spec, "analytic_points", lambda pts: np.asarray(pts)[:, 2] >= 1.0)
    again = build_table("creep_exact", "coarse", output_dir=tmp_path / "c",
                        scheduler="synchronous", workdir=tmp_path / "w1", progress=False,
                        reuse_nodes=res["path"])
    assert sum(calls) == int(np.count_nonzero(quarter[:, 2] >= 1.0)) + spec.n_check["coarse"]
    with netCDF4.Dataset(again["path"]) as ds:
        assert "the spline at its nodes" in ds.getncattr("build_reused_nodes")
    pts = np.random.default_rng(3).uniform([-2.3, 0.0, -1.0, -np.pi, -20.0],
                                           [2.3, 0.5, 1.0, np.pi, 20.0], (50, 5))
    np.testing.assert_allclose(Table.from_file(again["path"]).spline.evaluate(pts)[:, :3],
                               table.spline.evaluate(pts)[:, :3], rtol=0, atol=2e-4)

    # one flipped byte at each of 24 places: refused, or (metadata the reader does not use,
    # free space) the same coefficients; never other numbers read silently
    original = res["path"].read_bytes()
    refused = []
    for i, at in enumerate(np.linspace(0.05, 0.95, 24) * len(original)):
        data = bytearray(original)
        data[int(at)] ^= 0xFF
        bad = tmp_path / f"bad{i}.nc"
        bad.write_bytes(bytes(data))
        try:
            read = Table.from_file(bad)
        except TableFileError as exc:
            refused.append(str(exc))
        else:
            np.testing.assert_array_equal(read.coefficients, table.coefficients)
            for a, b in zip(read.axes, table.axes):
                np.testing.assert_array_equal(a["knots"], b["knots"])
                np.testing.assert_array_equal(a["nodes"], b["nodes"])
    assert any("truncated or corrupt" in m for m in refused), refused


def _tree_state(directory):
    """Every file under ``directory`` with its size, mtime and content hash."""
    import hashlib

    return {str(p.relative_to(directory)): (p.stat().st_size, p.stat().st_mtime_ns,
                                            hashlib.sha1(p.read_bytes()).hexdigest())
            for p in sorted(directory.rglob("*")) if p.is_file()}


def test_a_default_build_leaves_the_shipped_tables_untouched(tmp_path, monkeypatch, capsys):
    from railcontact.tables import TableAccuracyWarning
    from tablegen.build import SHIPPED_TABLES_DIR

    assert (SHIPPED_TABLES_DIR / "creep_modified_strip.nc").is_file()
    before = _tree_state(SHIPPED_TABLES_DIR)
    monkeypatch.chdir(tmp_path)
    monkeypatch.delenv("TABLEGEN_OUTPUT_DIR", raising=False)
    # a shipped table, coarse (21 nodes, a fraction of a second): the shipped file's name
    assert main(["build", "--only", "creep_modified_strip", "--resolution", "coarse",
                 "--scheduler", "synchronous", "--workdir", str(tmp_path / "w"),
                 "--no-progress"]) == 0
    assert _tree_state(SHIPPED_TABLES_DIR) == before
    built = tmp_path / "tables-build" / "creep_modified_strip.nc"
    out, err = capsys.readouterr()
    assert str(built) in out and "shipped tables/ are unchanged" in out
    assert f"RAILCONTACT_TABLES_DIR={tmp_path / 'tables-build'}" in out
    # coarser than the shipped default build: said when built (once) and at every load
    assert err.count("WARNING: worse than the shipped table") == 1
    assert "force_ratio max" in err and "within its target" in err
    with pytest.warns(TableAccuracyWarning, match="worse than the shipped table"):
        table = Table.from_file(built)
    assert table.attrs["accuracy_versus_shipped"].startswith("worse")
    # replacing a shipped table is asked for explicitly (here the shipped directory is a copy)
    fake = tmp_path / "shipped"
    monkeypatch.setattr("tablegen.build.SHIPPED_TABLES_DIR", fake)
    assert main(["build", "--only", "selftest", "--resolution", "coarse", "--scheduler",
                 "synchronous", "--workdir", str(tmp_path / "w"), "--no-progress",
                 "--replace-shipped"]) == 0
    assert (fake / "selftest.nc").is_file()
    with pytest.raises(SystemExit):    # one or the other
        main(["build", "--only", "selftest", "--replace-shipped", "--output-dir", "x"])


def test_accuracy_is_compared_with_the_shipped_table(tmp_path):
    import warnings

    import netCDF4

    from railcontact.tables import TableAccuracyWarning

    # the "shipped" table: a build of the same table whose record of g says 1e-5
    shipped = build_table("selftest", "coarse", output_dir=tmp_path / "shipped",
                          scheduler="synchronous", workdir=tmp_path / "w", progress=False)
    with netCDF4.Dataset(shipped["path"], "a") as ds:
        ds["g"].setncattr("max_abs_error", 1e-5)
    with pytest.warns(TableAccuracyWarning, match="worse than the shipped table") as got:
        trial = build_table("selftest", "coarse", output_dir=tmp_path / "trial",
                            scheduler="synchronous", workdir=tmp_path / "w", progress=False,
                            shipped_dir=tmp_path / "shipped")
    # the message names the worse variable (g, 2.1e-3 against 1e-5, within its target 1e-2)
    # with both errors; f, as accurate as shipped, is not named
    g = trial["accuracy"]["g"]["max_abs_error"]
    assert g == pytest.approx(shipped["accuracy"]["g"]["max_abs_error"], rel=1e-12)
    assert g > 1e-3
    text = str(got[0].message)
    assert f"g max {g:.3g} (shipped 1e-05, within its target 0.01)" in text
    assert "f max" not in text
    with pytest.warns(TableAccuracyWarning, match=f"g max {g:.3g} "):
        Table.from_file(trial["path"])
    # as accurate as the shipped one: no warning at build or load
    with warnings.catch_warnings():
        warnings.simplefilter("error", TableAccuracyWarning)
        same = build_table("selftest", "coarse", output_dir=tmp_path / "again",
                           scheduler="synchronous", workdir=tmp_path / "w", progress=False,
                           shipped_dir=trial["path"].parent)
        assert same["accuracy_versus_shipped"].startswith("as accurate")
        Table.from_file(same["path"])
        # nothing to compare with: nothing recorded
        alone = build_table("selftest", "coarse", output_dir=tmp_path / "alone",
                            scheduler="synchronous", workdir=tmp_path / "w", progress=False,
                            shipped_dir=tmp_path / "none")
        assert alone["accuracy_versus_shipped"] is None
        assert "accuracy_versus_shipped" not in Table.from_file(alone["path"]).attrs


def test_a_resumed_build_says_what_it_did(tmp_path, capsys):
    work = tmp_path / "w"
    args = ["build", "--only", "selftest", "--resolution", "coarse", "--scheduler",
            "synchronous", "--output-dir", str(tmp_path), "--workdir", str(work),
            "--no-progress"]
    res = build_table("selftest", "coarse", output_dir=tmp_path, scheduler="synchronous",
                      workdir=work, progress=False, keep_chunks=True)
    n_all = res["n_points"] + res["n_check"]
    assert (res["n_computed"], res["n_resumed"]) == (n_all, 0)
    assert main(args) == 0      # every chunk still there: nothing to compute
    out = capsys.readouterr().out
    assert f"{n_all} cases resumed from an interrupted run, nothing left to compute" in out
    assert " in 0.0 s" not in out
    build_table("selftest", "coarse", output_dir=tmp_path, scheduler="synchronous",
                workdir=work, progress=False, keep_chunks=True)
    first = sorted(work.rglob("grid_*.npy"))[0]
    n_first = len(np.load(first))
    first.unlink()
    assert main(args) == 0
    out = capsys.readouterr().out
    assert (f"{n_all - n_first} cases resumed from an interrupted run, {n_first} cases "
            "computed in ") in out


def test_an_unreachable_scheduler_is_one_line(tmp_path, capsys):
    import socket

    with socket.socket() as s:        # a free port, then closed: nothing listens there
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    assert main(["build", "--only", "selftest", "--resolution", "coarse", "--scheduler",
                 f"tcp://127.0.0.1:{port}", "--output-dir", str(tmp_path), "--workdir",
                 str(tmp_path / "w"), "--no-progress"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err
    assert f"dask scheduler 'tcp://127.0.0.1:{port}' is not reachable" in err
    assert not (tmp_path / "selftest.nc").exists()


def test_the_help_states_what_workers_need(capsys):
    with pytest.raises(SystemExit):
        main(["build", "--help"])
    out = " ".join(capsys.readouterr().out.split())
    assert "workers must be able to import tablegen and railcontact" in out
    assert "./tables-build" in out and "--replace-shipped" in out
