"""Tests of the table reader railcontact.tables and of the shipped tables in tables/.

Independent checks: the compiled de Boor evaluator against scipy's NdBSpline; the shipped
tables against the direct models (railcontact.creep3d) on seeded random off-grid points; the
Jacobian against finite differences; the linear-theory limit; ncdump (a non-Python reader).
"""

import shutil
import subprocess

import math

import numpy as np
import pytest
from scipy.interpolate import NdBSpline

from railcontact import creep_force_3d, creep_solution_3d, kalker_coefficients
from railcontact.strip_table import CreepTable
from railcontact.tables import (Table, TableFileError, TensorSpline,
                                bspline_knots, default_table_path, fit_tensor_bspline,
                                tables_directory)

SHIPPED = sorted(tables_directory().glob("*.nc"))


# --------------------------------------------------------------------------------------------
# Spline machinery
# --------------------------------------------------------------------------------------------

def _spline_3d():
    x1 = np.r_[np.linspace(0.0, 1.0, 9), 1.2, 1.5, 2.0]
    x2 = np.linspace(-1.0, 1.0, 7)
    x3 = np.geomspace(0.1, 10.0, 6)
    nodes = [x1, x2, x3]
    knots = [bspline_knots(x1, [1.0]), bspline_knots(x2), bspline_knots(x3)]
    g = np.meshgrid(*nodes, indexing="ij")
    vals = np.stack([np.sin(2 * g[0]) * np.cos(g[1]) * np.log(g[2]), g[0] ** 2 + g[1] * g[2]])
    coef = fit_tensor_bspline(vals, nodes, knots)
    axes = [dict(name=n, nodes=x, knots=t, units="1") for n, x, t in zip("abc", nodes, knots)]
    return TensorSpline(axes, coef, ["f", "g"]), nodes, knots, vals, coef


def test_tensor_spline_exact_at_nodes():
    ts, nodes, _, vals, _ = _spline_3d()
    g = np.meshgrid(*nodes, indexing="ij")
    pts = np.stack([m.ravel() for m in g], axis=1)
    got = ts.evaluate(pts)
    assert np.max(np.abs(got - vals.reshape(2, -1).T)) < 1e-13


@pytest.mark.parametrize("deriv", [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 2), (2, 0, 0),
                                   (1, 1, 1)])
def test_tensor_spline_matches_scipy_ndbspline(deriv):
    """The numba de Boor kernel against scipy's independent NdBSpline (values, derivatives)."""
    ts, nodes, knots, _, coef = _spline_3d()
    rng = np.random.default_rng(3)
    pts = np.stack([rng.uniform(x[0], x[-1], 500) for x in nodes], axis=1)
    got = ts.evaluate(pts, deriv)
    for k in range(2):
        ref = NdBSpline(tuple(knots), coef[k], 3)(pts, nu=deriv)
        assert np.max(np.abs(got[:, k] - ref)) < 1e-10 * max(1.0, np.max(np.abs(ref)))


def test_tensor_spline_point_equals_batch():
    ts, nodes, *_ = _spline_3d()
    rng = np.random.default_rng(4)
    pts = np.stack([rng.uniform(x[0], x[-1], 20) for x in nodes], axis=1)
    batch = ts.evaluate(pts)
    for p, b in zip(pts, batch):
        np.testing.assert_array_equal(ts.evaluate_point(p), b)


def test_tensor_spline_out_of_range_raises_naming_axis():
    ts, *_ = _spline_3d()
    with pytest.raises(ValueError, match=r"b must be in \[-1, 1\] \[1\]"):
        ts.evaluate([0.5, 1.5, 1.0])
    with pytest.raises(ValueError, match="a must be in"):
        ts.evaluate([np.nan, 0.0, 1.0])


def test_c2_second_differences_bounded_across_knots():
    """Second differences (f(t+h) - 2 f(t) + f(t-h))/h^2 stay bounded as h -> 0 at every
    interior knot (C2), and first differences are continuous at the double knot (C1)."""
    ts, nodes, knots, *_ = _spline_3d()
    p = np.array([0.0, 0.3, 2.0])
    for t in np.unique(knots[0][4:-4]):
        vals = []
        for h in (1e-2, 1e-3, 1e-4):
            pts = np.array([p + [t - h, 0, 0], p + [t, 0, 0], p + [t + h, 0, 0]])
            f = ts.evaluate(pts)[:, 0]
            vals.append(abs(f[2] - 2 * f[1] + f[0]) / h**2)
        assert vals[-1] < 2 * vals[0] + 1.0, (t, vals)
    # C1 at the double knot x = 1: one-sided slopes agree as h -> 0
    h = 1e-6
    f = ts.evaluate(np.array([p + [1 - h, 0, 0], p + [1, 0, 0], p + [1 + h, 0, 0]]))[:, 0]
    assert abs((f[2] - f[1]) / h - (f[1] - f[0]) / h) < 1e-3


def test_double_knot_removes_overshoot_at_saturation():
    """A 1-D saturation model: a single knot rings past the limit, a double knot
    does not (beyond rounding)."""
    from railcontact.creep3d import strip_force_function

    z = np.r_[np.linspace(0.0, 1.0, 11), 1.25, 1.5, 2.0]
    zz = np.linspace(0.0, 2.0, 200001)
    over = {}
    for name, dk in (("plain", ()), ("double", (1.0,))):
        t = bspline_knots(z, dk)
        c = fit_tensor_bspline(strip_force_function(z), [z], [t])
        ts = TensorSpline([dict(name="z", nodes=z, knots=t)], c[None], ["F"])
        over[name] = ts.evaluate(zz[:, None], check=False)[:, 0].max() - 1.0
    assert over["plain"] > 1e-4
    assert over["double"] < 1e-15


def test_bspline_knots_errors():
    with pytest.raises(ValueError, match="strictly ascending"):
        bspline_knots([0.0, 1.0, 1.0, 2.0])
    with pytest.raises(ValueError, match="interior node"):
        bspline_knots(np.linspace(0, 1, 6), [0.55])


# --------------------------------------------------------------------------------------------
# Files
# --------------------------------------------------------------------------------------------

def test_shipped_tables_exist():
    names = {p.stem for p in SHIPPED}
    assert "creep_modified_strip" in names
    for p in SHIPPED:
        # keep the shipped tables small: 2 MB each, the 5-D exact creep table 20 MB (issue 16)
        limit = 20_000_000 if p.stem == "creep_exact" else 2_000_000
        assert p.stat().st_size < limit, p


@pytest.mark.parametrize("path", SHIPPED, ids=[p.stem for p in SHIPPED])
def test_shipped_tables_load_and_record_accuracy(path):
    table = Table.from_file(path)
    assert table.attrs["Conventions"] == "CF-1.8"
    for key in ("title", "source", "history", "references"):
        assert table.attrs[key]
    for v, acc in table.accuracy().items():
        assert np.isfinite(acc["max_abs_error"]) and acc["rms_error"] <= acc["max_abs_error"]
        assert acc["error_target_met"] == ("yes" if acc["max_abs_error"] <= acc["error_target"]
                                           else "no")


@pytest.mark.skipif(shutil.which("ncdump") is None,
                    reason="ncdump (Debian netcdf-bin) is not installed")
@pytest.mark.parametrize("path", SHIPPED, ids=[p.stem for p in SHIPPED])
def test_ncdump_reads_table_and_attributes(path):
    out = subprocess.run(["ncdump", "-h", str(path)], capture_output=True, text=True,
                         check=True).stdout
    assert ':Conventions = "CF-1.8"' in out
    # format 3: no node values (creep_exact: the spline's coefficients, checksummed, and
    # the symmetries it was filled by), described for any reader
    fmt = 3 if path.stem == "creep_exact" else 1
    assert f":railcontact_table_format = {fmt}" in out
    if fmt == 3:
        assert ":symmetry = " in out and ":node_values = \"not stored" in out
    for key in ("title", "source", "history", "references"):
        assert f":{key} = " in out
    table = Table.from_file(path)
    for name in [a["name"] for a in table.axes] + table.variables:
        assert f"{name}:units = " in out and f"{name}:long_name = " in out
    for name in table.variables:
        assert f"{name}:max_abs_error = " in out and f"{name}:rms_error = " in out
    # the data too: ncdump -v of the first axis prints its nodes
    data = subprocess.run(["ncdump", "-v", table.axes[0]["name"], str(path)],
                          capture_output=True, text=True, check=True).stdout
    assert "data:" in data


def test_missing_file_clear_error(tmp_path):
    with pytest.raises(TableFileError, match="does not exist"):
        Table.from_file(tmp_path / "nope.nc")
    with pytest.raises(FileNotFoundError, match="python -m tablegen build --only nope"):
        default_table_path("nope", directory=tmp_path)
    # a build goes to ./tables-build, not where the reader looks: the message says how to use it
    with pytest.raises(FileNotFoundError, match=r"writes \./tables-build\) and set "
                                                "RAILCONTACT_TABLES_DIR to that directory"):
        default_table_path("nope", directory=tmp_path)


def test_truncated_file_clear_error(tmp_path):
    src = default_table_path("creep_modified_strip")
    bad = tmp_path / "truncated.nc"
    bad.write_bytes(src.read_bytes()[: src.stat().st_size // 2])
    with pytest.raises(TableFileError, match="truncated.nc"):
        Table.from_file(bad)
    with pytest.raises(TableFileError, match="truncated.nc"):
        CreepTable.from_file(bad)


def _copy_with(tmp_path, edit):
    import netCDF4

    src = default_table_path("creep_modified_strip")
    dst = tmp_path / "edited.nc"
    shutil.copy(src, dst)
    with netCDF4.Dataset(dst, "a") as nc:
        edit(nc)
    return dst


def test_wrong_version_clear_error(tmp_path):
    dst = _copy_with(tmp_path, lambda nc: nc.setncattr("railcontact_table_format", np.int32(99)))
    with pytest.raises(TableFileError, match=r"edited.nc.*version 99.*versions \[1, 2, 3\]"):
        Table.from_file(dst)


def test_not_a_table_and_corrupt_coefficients(tmp_path):
    dst = _copy_with(tmp_path, lambda nc: nc.delncattr("railcontact_table_format"))
    with pytest.raises(TableFileError, match="not written by tablegen"):
        Table.from_file(dst)

    def corrupt(nc):
        nc.variables["force_ratio_bspline_coefficients"][3] += 0.01
    dst = _copy_with(tmp_path, corrupt)
    with pytest.raises(TableFileError, match="corrupt"):
        Table.from_file(dst)


def test_default_table_path_env_override(tmp_path, monkeypatch):
    src = default_table_path("creep_modified_strip")
    shutil.copy(src, tmp_path / "creep_modified_strip.nc")
    monkeypatch.setenv("RAILCONTACT_TABLES_DIR", str(tmp_path))
    assert default_table_path("creep_modified_strip") == tmp_path / "creep_modified_strip.nc"
    assert default_table_path("creep_modified_strip.nc", directory=tmp_path).parent == tmp_path


# --------------------------------------------------------------------------------------------
# Modified strip creep table against the direct model
# --------------------------------------------------------------------------------------------

@pytest.fixture(scope="module")
def creep_table():
    return CreepTable.from_file()


def _random_cases(n, seed, scale=6e-3):
    rng = np.random.default_rng(seed)
    return dict(
        creepage_longitudinal=rng.uniform(-scale, scale, n),
        creepage_lateral=rng.uniform(-scale, scale, n),
        spin=rng.uniform(-1.0, 1.0, n),
        normal_load=rng.uniform(1e3, 1.5e5, n),
        a0=rng.uniform(1e-3, 1e-2, n), b0=rng.uniform(1e-3, 1e-2, n),
        youngs_modulus=rng.uniform(1.5e11, 2.2e11, n),
        poisson_ratio=rng.uniform(0.2, 0.35, n),
        friction_coefficient=rng.uniform(0.05, 0.6, n))


def test_creep_table_matches_direct_model_within_recorded_accuracy(creep_table):
    """Off-grid re-check of the recorded accuracy against railcontact.creep_force_3d."""
    case = _random_cases(20000, seed=11)
    tab = creep_table.creep_force_3d(**case)
    ref = creep_force_3d(**case, method="modified_strip")
    mu_n = case["normal_load"] * case["friction_coefficient"]
    err = np.hypot(tab.tx - ref.tx, tab.ty - ref.ty) / mu_n
    recorded = creep_table.table.accuracy()["force_ratio"]["max_abs_error"]
    assert err.max() <= 1e-4
    assert err.max() <= 2.0 * recorded + 1e-12, (err.max(), recorded)
    sol_t = creep_table.creep_solution_3d(**case)
    sol_r = creep_solution_3d(**case, method="modified_strip")
    assert np.max(np.abs(sol_t[2] - sol_r.stick_area_fraction)) <= 1e-4
    np.testing.assert_allclose(sol_t[3], sol_r.normalised_creepage, rtol=1e-12)


def test_creep_table_never_exceeds_coulomb(creep_table):
    case = _random_cases(50000, seed=12, scale=3e-2)
    tab = creep_table.creep_force_3d(**case)
    mu_n = case["normal_load"] * case["friction_coefficient"]
    assert np.all(np.hypot(tab.tx, tab.ty) <= mu_n)
    z = np.linspace(0.0, 3.0, 300001)
    f = creep_table.table("force_ratio", np.minimum(z, 1.5)[:, None])
    assert f.max() <= 1.0 + 2e-16 * 4  # spline itself: at most a few ulps above 1
    # full sliding beyond the grid: exactly mu N in magnitude (held asymptote)
    t = creep_table.creep_force_3d(0.5, 0.0, 0.0, 1e5, 6e-3, 5e-3, 210e9, 0.28, 0.3)
    assert abs(np.hypot(t.tx, t.ty) - 3e4) <= 1e-9 * 3e4


def test_creep_table_scalar_path_equals_vector_path(creep_table):
    case = _random_cases(50, seed=13)
    vec = creep_table.creep_force_3d(**case)
    for i in range(50):
        one = creep_table.creep_force_3d(**{k: float(v[i]) for k, v in case.items()})
        assert one.tx == pytest.approx(vec.tx[i], rel=1e-12, abs=1e-9)
        assert one.ty == pytest.approx(vec.ty[i], rel=1e-12, abs=1e-9)


def test_creep_table_linear_regime_relative_accuracy(creep_table):
    """Tiny creepage: T -> -G a0 b0 (C11 xi_x, C22 xi_y + sqrt(a0 b0) C23 phi) (Kalker)."""
    n_load, a0, b0, e_mod, nu, mu = 1e5, 6e-3, 5e-3, 210e9, 0.28, 0.3
    c = kalker_coefficients(a0 / b0, nu)
    g_mod = e_mod / (2 * (1 + nu))
    for xi in (1e-12, 1e-10):
        t = creep_table.creep_force_3d(xi, -0.5 * xi, 0.0, n_load, a0, b0, e_mod, nu, mu)
        lin_x = -g_mod * a0 * b0 * c.c11 * xi
        lin_y = g_mod * a0 * b0 * c.c22 * 0.5 * xi
        assert t.tx / lin_x == pytest.approx(1.0, abs=1e-6)
        assert t.ty / lin_y == pytest.approx(1.0, abs=1e-6)
    for xi in (1e-7, 1e-6, 1e-5):  # small but nonlinear: relative to the direct model
        t = creep_table.creep_force_3d(xi, -0.5 * xi, 0.0, n_load, a0, b0, e_mod, nu, mu)
        d = creep_force_3d(xi, -0.5 * xi, 0.0, n_load, a0, b0, e_mod, nu, mu)
        assert t.tx / d.tx == pytest.approx(1.0, abs=1e-6)
        assert t.ty / d.ty == pytest.approx(1.0, abs=1e-6)
    zero = creep_table.creep_force_3d(0.0, 0.0, 0.0, n_load, a0, b0, e_mod, nu, mu)
    assert zero.tx == 0.0 and zero.ty == 0.0
    nothing = creep_table.creep_force_3d(1e-3, 0.0, 0.0, 0.0, a0, b0, e_mod, nu, mu)
    assert nothing.tx == 0.0 and nothing.ty == 0.0


def test_creep_table_jacobian_matches_finite_differences(creep_table):
    rng = np.random.default_rng(14)
    for _ in range(20):
        q = np.array([rng.uniform(-4e-3, 4e-3), rng.uniform(-4e-3, 4e-3), rng.uniform(-1, 1)])
        rest = (rng.uniform(1e4, 1e5), 6e-3, 4e-3, 210e9, 0.28, 0.3)
        jac = creep_table.creep_force_jacobian_3d(*q, *rest)
        for j, h in enumerate((1e-8, 1e-8, 1e-5)):
            qp, qm = q.copy(), q.copy()
            qp[j] += h
            qm[j] -= h
            tp = creep_table.creep_force_3d(*qp, *rest)
            tm = creep_table.creep_force_3d(*qm, *rest)
            fd = np.array([tp.tx - tm.tx, tp.ty - tm.ty]) / (2 * h)
            scale = rest[0] * rest[-1] / 1e-3 * (1e-3 if j == 2 else 1.0) + 1.0
            assert np.allclose(jac[:, j], fd, rtol=1e-4, atol=1e-6 * scale), (q, j)


@pytest.mark.parametrize("name, value", [("normal_load", -1.0), ("poisson_ratio", 0.5),
                                         ("youngs_modulus", 0.0), ("spin", np.nan),
                                         ("friction_coefficient", -0.1)])
def test_creep_table_bad_input_names_parameter(creep_table, name, value):
    args = dict(creepage_longitudinal=1e-3, creepage_lateral=0.0, spin=0.0, normal_load=1e5,
                a0=6e-3, b0=5e-3, youngs_modulus=210e9, poisson_ratio=0.28,
                friction_coefficient=0.3)
    args[name] = value
    with pytest.raises(ValueError, match=name):
        creep_table.creep_force_3d(**args)


# --------------------------------------------------------------------------------------------
# Corrugation / wear response table against railcontact.wear.linear_response
# --------------------------------------------------------------------------------------------

@pytest.mark.skipif(not (tables_directory() / "corrugation_response.nc").exists(),
                    reason="tables/corrugation_response.nc not built")
def test_corrugation_table_rechecked_against_linear_response():
    from railcontact.wear import linear_response

    table = Table.from_file(default_table_path("corrugation_response"))
    rng = np.random.default_rng(31)
    ratio = np.exp(rng.uniform(np.log(0.01), np.log(1.0), 3000))
    r = rng.uniform(0.0, 1.0, 3000)
    ref = linear_response(ratio, r)
    got = table.spline.evaluate(np.column_stack([ratio, r]))
    acc = table.accuracy()
    for k, name in enumerate(table.variables):
        field, part = name.rsplit("_", 1)
        want = getattr(np.asarray(getattr(ref, field), dtype=complex), part)
        err = np.max(np.abs(got[:, k] - want))
        assert err <= 1e-4 and err <= 2.0 * acc[name]["max_abs_error"] + 1e-12, (name, err)
    with pytest.raises(ValueError, match="a0_over_wavelength must be in"):
        table("wear_real", [[1.5, 0.5]])


def test_subnormal_friction_coefficient_gives_zero_or_clear_error():
    """mu ~ 5e-324: w_sat (carried as mantissa and exponent) no longer underflows, so the
    modified-strip reader gives the saturated force, |T| = mu N ~ 5e-319 N (the analytic
    theory's value), no ZeroDivisionError (found by the FMU speed work; the exact-table
    reader's case is in tests/test_exact_table.py)."""
    from railcontact import creep_force_3d
    from railcontact.strip_table import CreepTable
    from railcontact.tables import default_table_path

    args = (1e-3, 1e-4, 0.1, 1e5, 6e-3, 9e-3, 210e9, 0.28, 5e-324)
    strip = CreepTable.from_file(default_table_path("creep_modified_strip"))
    got = tuple(float(v) for v in strip.creep_force_3d(*args))
    assert got == tuple(float(v) for v in creep_force_3d(*args))
    assert 0.0 < math.hypot(*got) <= 5e-324 * 1e5


# --------------------------------------------------------------------------------------------
# Scalar paths of the stick outputs (the FMU's lazily computed outputs)
# --------------------------------------------------------------------------------------------
_EPS = float(np.finfo(float).eps)


def _scalar_cases(seed, n):
    """Plain-float inputs over every regime: the random cases, scaled from full stick (1e-9)
    to far beyond the grid (x 50, z up to ~100 > z_max = 1.5), zero creepage, pure spin,
    N = 0, mu = 0, and a0/b0 from 0.05 to 20."""
    rng = np.random.default_rng(seed)
    case = _random_cases(n, seed)
    g = np.exp(rng.uniform(np.log(0.05), np.log(20.0), n))
    case["a0"], case["b0"] = 5e-3 * np.sqrt(g), 5e-3 / np.sqrt(g)
    scale = 10.0 ** rng.uniform(-9.0, 1.7, n)
    for k in ("creepage_longitudinal", "creepage_lateral", "spin"):
        case[k] = case[k] * scale
    rows = [tuple(float(v[i]) for v in case.values()) for i in range(n)]
    for i, row in enumerate(rows):
        kind = i % 8
        if kind == 1:
            rows[i] = (0.0, 0.0, 0.0) + row[3:]                       # zero creepage
        elif kind == 2:
            rows[i] = (0.0, 0.0) + row[2:]                            # pure spin
        elif kind == 3:
            rows[i] = row[:3] + (0.0,) + row[4:]                      # N = 0
        elif kind == 4:
            rows[i] = row[:8] + (0.0,)                                # mu = 0
    return rows


def test_creep_table_scalar_stick_equals_array_path(creep_table):
    """Bound: 4 eps absolute for the stick fraction (in [0, 1]; the scalar path evaluates the
    piecewise-polynomial copy of the B-spline, measured <= 2.6 eps), 4 eps relative for z
    (libm's hypot against numpy's)."""
    seen_beyond = seen_full_stick = 0
    for args in _scalar_cases(71, 4000):
        stick, z = creep_table.stick_unchecked(*args)
        _, _, ref_stick, ref_z = creep_table.creep_solution_3d(*args)
        assert isinstance(stick, float) and isinstance(z, float)
        assert abs(stick - ref_stick) <= 4 * _EPS, args
        assert abs(z - ref_z) <= 4 * _EPS * ref_z, args
        seen_beyond += z > 1.5
        seen_full_stick += z < 1e-6
    assert seen_beyond > 100 and seen_full_stick > 100


# --------------------------------------------------------------------------------------------
# Inputs anywhere in the float range (the creep3d mantissa/exponent arithmetic)
# --------------------------------------------------------------------------------------------
_EXTREME = (1e-3, 0.0, 0.0, 1e5, 6e-3, 5e-3, 210e9, 0.28, 0.3)


def _with(index, value):
    args = list(_EXTREME)
    args[index] = value
    return args


def test_creep_table_huge_creepage_is_full_sliding():
    """xi = 1e308 gave NaN (C11 xi overflowed): it is full sliding, |T| = mu N."""
    table = CreepTable.from_file()
    for args in (_with(0, 1e308), _with(0, np.array([1e308, -1e308]))):
        tx, ty = table.creep_force_3d(*args)
        assert np.all(np.hypot(tx, ty) == pytest.approx(0.3 * 1e5, rel=1e-12))
        assert np.all(np.sign(tx) == -np.sign(args[0]))


def test_creep_table_huge_load_gives_the_linear_theory():
    """N = 1e308 on a fixed ellipse: p0 overflowed (force 0); now z ~ 1e-300, and the table's
    initial slope F'(0) = 3 pi / 4 gives the linear theory (independent of N)."""
    got = CreepTable.from_file().creep_force_3d(*_with(3, 1e308))
    want = creep_force_3d(*_with(3, 1e308), method="linear")
    assert float(got.tx) == pytest.approx(float(want.tx), rel=1e-6)


@pytest.mark.parametrize("method", ["creep_force_3d", "creep_force_jacobian_3d",
                                    "creep_solution_3d"])
def test_creep_table_array_b0_1e_300(method):
    """An array b0 holding 1e-300 raised ZeroDivisionError in the compiled evaluator (NaN
    coordinates): a0/b0 = 6e297 is beyond Kalker's coefficients, a ValueError naming it; with
    a0 = 1e-300 too the ratio is fine and the answer finite."""
    table = CreepTable.from_file()
    with pytest.raises(ValueError, match=r"a0/b0 must be in \(0, 1e\+100\] \[-\]"):
        getattr(table, method)(*_with(5, np.array([1e-300, 5e-3])))
    args = _with(5, np.array([1e-300, 5e-3]))
    args[4] = np.array([1e-300, 6e-3])
    out = getattr(table, method)(*args)
    assert all(np.all(np.isfinite(v)) for v in out[:2])


@pytest.mark.parametrize("edit, match", [
    (lambda nc: nc.setncattr("railcontact_table_format", "abc"),
     r"edited.nc' has table format version 'abc', this reader understands versions \[1, 2, 3\]"),
    (lambda nc: nc.setncattr("spline_degree", "three"),
     r"edited.nc': attribute spline_degree must be 3; got 'three'"),
    (lambda nc: nc.variables["normalised_creepage"].setncattr("double_knots", "abc"),
     r"edited.nc': attribute normalised_creepage:double_knots must be a list of numbers; got "
     r"'abc'"),
    (lambda nc: nc.variables["normalised_creepage"].setncattr("out_of_range", "bogus"),
     r"edited.nc': attribute normalised_creepage:out_of_range must be one of \['error', "
     r"'hold'\]; got 'bogus'"),
    (lambda nc: nc.setncattr("table_variables", "force_ratio"),
     r"edited.nc': attribute table_variables \('force_ratio'\) lacks "
     r"\['stick_area_fraction'\]"),
])
def test_malformed_attribute_is_a_table_file_error_naming_the_file(tmp_path, edit, match):
    dst = _copy_with(tmp_path, edit)
    with pytest.raises(TableFileError, match=match):
        CreepTable.from_file(dst)


def test_float32_copy_is_refused_precisely(tmp_path):
    """A float32 copy misfits its own nodes by ~4e-8: refused as float32, not as 'corrupt'."""
    import netCDF4

    src = default_table_path("creep_modified_strip")
    dst = tmp_path / "single.nc"
    with netCDF4.Dataset(src) as a, netCDF4.Dataset(dst, "w") as b:
        b.setncatts({k: a.getncattr(k) for k in a.ncattrs()})
        for name, dim in a.dimensions.items():
            b.createDimension(name, len(dim))
        for name, var in a.variables.items():
            out = b.createVariable(name, "f4" if var.dtype == np.float64 else var.dtype,
                                   var.dimensions)
            out.setncatts({k: var.getncattr(k) for k in var.ncattrs()})
            out[...] = var[...]
    with pytest.raises(TableFileError, match=r"single.nc': variable 'normalised_creepage' is "
                                             r"stored as float32 where float64 is expected"):
        CreepTable.from_file(dst)


def test_tensor_spline_refuses_unknown_out_of_range():
    axis = dict(name="x", nodes=np.arange(5.0), knots=bspline_knots(np.arange(5.0)),
                out_of_range="bogus")
    with pytest.raises(ValueError, match=r"out_of_range of axis 'x' must be one of \['error', "
                                         r"'hold'\]; got 'bogus'"):
        TensorSpline([axis], np.zeros((1, 5)), ["v"])
