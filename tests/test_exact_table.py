"""Tests of railcontact.exact_table: the exact-theory creep table (coordinates, symmetries,
smoothness across the symmetry planes, slopes at zero against Kalker's published coefficients,
Jacobian, the solver fallback, accuracy against CONTACT's converged values)."""

import csv
import math
from pathlib import Path

import numpy as np
import pytest

from railcontact.creep3d import REFERENCE_CONTACT
from railcontact.exact_table import (ExactCreepTable, creepage_coordinate, creepage_magnitude,
                                     exact_table_coordinates, exact_table_inverse)
from railcontact.kalker import kalker_coefficients, kalker_table
from railcontact.tables import (TensorSpline, fit_tensor_bspline, periodic_bspline_knots,
                                periodic_stored_nodes, tables_directory)

DATA = Path(__file__).parent / "data"
TABLE = tables_directory() / "creep_exact.nc"


def _table_ok():
    try:
        ExactCreepTable.from_file(TABLE)
    except (OSError, ValueError):
        return False
    return True


needs_table = pytest.mark.skipif(not _table_ok(), reason="tables/creep_exact.nc not built")


@pytest.fixture(scope="module")
def table():
    from railcontact.creep3d import load_exact_table

    return load_exact_table(TABLE)          # with the solver beyond the table's axes


CONTACT = dict(normal_load=1e5, a0=6e-3, b0=4e-3, youngs_modulus=210e9, poisson_ratio=0.28,
               friction_coefficient=0.3)
MU_N = 0.3 * 1e5


def _args(xi, eta, phi, **over):
    kw = dict(CONTACT, **over)
    return (xi, eta, phi, kw["normal_load"], kw["a0"], kw["b0"], kw["youngs_modulus"],
            kw["poisson_ratio"], kw["friction_coefficient"])


# --------------------------------------------------------------------------------------------
# Coordinates and symmetries (no table needed)
# --------------------------------------------------------------------------------------------

def test_the_coefficients_are_held_once_in_the_files_precision(table):
    """The reader's coefficients (variables last, for its compiled kernel) are the process's
    one copy of the file's float32 values, mapped read-only from the user cache
    (railcontact._table_store): not widened (330 MB in float64), not copied, shared by the
    table's variable-first view. The spline made from that view gives what the reader
    gives."""
    import netCDF4

    from railcontact import _table_store

    assert table._coef.dtype == np.float32 and table._coef.flags.c_contiguous
    assert not table._coef.flags.writeable
    assert np.shares_memory(table.table.coefficients, table._coef)
    content = _table_store.process_registry().tables[_table_store.content_key(TABLE)]
    assert np.shares_memory(content["coefficients"], table._coef)
    assert isinstance(content["coefficients"], np.memmap)   # (a writable user cache)
    assert table.table.coefficients.shape == (4,) + table._coef.shape[:-1]
    with netCDF4.Dataset(TABLE) as nc:   # the file's own numbers, bit for bit
        want = nc["spin_moment_ratio_bspline_coefficients"][3:5, 1, 2:9, 3, 4:6]
    np.testing.assert_array_equal(table._coef[3:5, 1, 2:9, 3, 4:6, 2], want)
    pts = np.array([[0.3, 0.2, 0.4, 0.5, 1.7], [-1.0, 0.4, -0.2, 2.0, -3.0]])
    tx, ty = [], []
    for p in pts:   # the reader's own path, in table coordinates on the reference contact
        phys = exact_table_inverse(*p, contact=REFERENCE_CONTACT)
        f = table.creep_force_3d(*(float(phys[k]) for k in (
            "creepage_longitudinal", "creepage_lateral", "spin", "normal_load", "a0", "b0",
            "youngs_modulus", "poisson_ratio", "friction_coefficient")))
        mu_n = REFERENCE_CONTACT["normal_load"] * REFERENCE_CONTACT["friction_coefficient"]
        tx.append(f.tx / mu_n)
        ty.append(f.ty / mu_n)
    v = table.table.spline.evaluate(pts)   # (f_par, f_perp) in the creepage frame
    # (the reader takes s >= 0: the second point, s < 0, is read from the other half of the
    # double cover, (-s, theta + pi); the coefficients are symmetric under it bit for bit
    # since 2026-11-27, so the halves agree to the evaluation's round-off)
    c, s = np.cos(pts[:, 3]), np.sin(pts[:, 3])
    np.testing.assert_allclose(-(v[:, 0] * c - v[:, 1] * s), tx, rtol=0, atol=1e-12)
    np.testing.assert_allclose(-(v[:, 0] * s + v[:, 1] * c), ty, rtol=0, atol=1e-12)
    with pytest.raises(ValueError, match=r"coefficients must have shape \(4, "):
        table.table.share_coefficients(table._coef)


def test_creepage_coordinate_inverse_and_limits():
    rho = np.array([0.0, 1e-9, 0.3, 1.0, 7.0, 1e3, 1e6, np.inf])
    s = creepage_coordinate(rho)
    assert s[0] == 0.0 and s[-1] == 1.0 and np.all(np.diff(s) > 0)
    # (the inverse loses digits as s -> 1: tan near pi/2; exact enough up to rho ~ 1e3)
    np.testing.assert_allclose(creepage_magnitude(s[:-2]), rho[:-2], rtol=1e-9)
    assert creepage_coordinate(-2.0) == -creepage_coordinate(2.0)


@pytest.mark.parametrize("tau", [0.0, 0.7, -3.0, 20.0])
def test_creepage_coordinate_with_spin(tau):
    """s = (2 / pi) atan(rho / sqrt(1 + tau^2)): inverse at every spin, even in tau, and with
    large spin the creepage as large as the spin's slip (rho ~ |tau|, where the force turns
    from the spin's direction to the creepage's) sits mid-axis, not in the last interval."""
    rho = np.array([0.0, 1e-6, 0.5, 3.0, 25.0, 400.0])
    s = creepage_coordinate(rho, tau)
    np.testing.assert_allclose(creepage_magnitude(s, tau), rho, rtol=1e-9, atol=1e-15)
    np.testing.assert_array_equal(s, creepage_coordinate(rho, -tau))
    w = math.sqrt(1.0 + tau * tau)
    assert creepage_coordinate(w, tau) == pytest.approx(0.5, rel=1e-12)
    assert creepage_coordinate(np.inf, tau) == 1.0
    # far past saturation 1 - s = (2 / pi) w / rho + O(rho^-3): linear in the 1/rho tail
    big = np.array([1e2, 1e3]) * w
    np.testing.assert_allclose(1.0 - creepage_coordinate(big, tau), 2.0 / np.pi * w / big,
                               rtol=1e-3)


def test_creepage_coordinate_of_earlier_files_maps_onto_the_same_points():
    """--reuse-nodes across the coordinate change: an earlier file's s = r / sqrt(1 + r^2)
    nodes become (2 / pi) atan(r), the same creepages r = rho / w; files that declare the
    arctan form, and the other axes, are left alone."""
    from tablegen.specs import _exact_reuse_coordinates

    r = np.array([0.0, 0.0007, 0.5, 1.03, 6.0])
    u = np.r_[r / np.sqrt(1.0 + r * r), 1.0]     # the old nodes, s = 1 at r = infinity
    old = np.r_[-u[:0:-1], u]
    r = np.r_[r, np.inf]
    new = _exact_reuse_coordinates({}, "creepage_coordinate_block", old)
    np.testing.assert_allclose(new[len(r) - 1:], creepage_coordinate(r), rtol=0, atol=1e-15)
    np.testing.assert_allclose(new, -new[::-1], rtol=0, atol=0)
    assert new[-1] == 1.0
    same = _exact_reuse_coordinates({"creepage_coordinate_form": "arctan"},
                                    "creepage_coordinate", old)
    np.testing.assert_array_equal(same, old)
    np.testing.assert_array_equal(_exact_reuse_coordinates({}, "spin_coordinate", old), old)


def test_a_table_of_the_old_coordinate_is_refused(tmp_path):
    """A file without the creepage coordinate's spin weight (built before it was introduced:
    s = rho / sqrt(1 + rho^2)) would be misread; the reader names the attribute."""
    from railcontact.tables import Table, TableFileError

    class Old:
        axes = [{"name": n} for n in ("log_aspect_ratio", "poisson_ratio",
                                      "creepage_coordinate", "creepage_angle",
                                      "spin_coordinate")]
        variables = ["force_ratio_parallel", "force_ratio_perpendicular",
                     "spin_moment_ratio", "stick_area_fraction"]
        attrs = {}
        path = tmp_path / "creep_exact.nc"

    assert issubclass(TableFileError, ValueError) and Table is not None
    with pytest.raises(TableFileError, match="creepage_coordinate_spin_weight None"):
        ExactCreepTable(Old())
    # with the weight but the algebraic coordinate of the files before 2026-11-27
    Old.attrs = {"creepage_coordinate_spin_weight": 1.0}
    with pytest.raises(TableFileError, match="creepage_coordinate_form None; this reader "
                                             "needs .*'arctan'"):
        ExactCreepTable(Old())


def test_coordinates_round_trip_every_sign():
    """Coordinates of physical inputs (all signs), mapped back to the reference contact, give
    the same coordinates: the reduction to (a0/b0, nu, v, tau) loses nothing."""
    rng = np.random.default_rng(3)
    n = 200
    a0, b0 = rng.uniform(2e-3, 9e-3, n), rng.uniform(2e-3, 9e-3, n)
    nu = rng.uniform(0.0, 0.5, n)
    xi, eta = rng.uniform(-3e-3, 3e-3, (2, n))
    phi = rng.uniform(-2.0, 2.0, n)
    n_load, e_mod, mu = 7e4, 2.0e11, 0.4
    c = kalker_coefficients(a0 / b0, nu)
    w_sat = math.pi * (1 + nu) * mu * 1.5 * n_load / (a0 * b0 * e_mod)
    coords = exact_table_coordinates(xi, eta, phi, a0, b0, nu, w_sat, (c.c11, c.c22, c.c23))
    phys = exact_table_inverse(*coords, contact=REFERENCE_CONTACT)
    c2 = kalker_coefficients(phys["a0"] / phys["b0"], phys["poisson_ratio"])
    w2 = (math.pi * (1 + phys["poisson_ratio"]) * REFERENCE_CONTACT["friction_coefficient"]
          * 1.5 * phys["normal_load"] / (phys["a0"] * phys["b0"] * phys["youngs_modulus"]))
    back = exact_table_coordinates(phys["creepage_longitudinal"], phys["creepage_lateral"],
                                   phys["spin"], phys["a0"], phys["b0"], phys["poisson_ratio"],
                                   w2, (c2.c11, c2.c22, c2.c23))
    for got, want in zip(back, coords):
        np.testing.assert_allclose(got, want, rtol=1e-10, atol=1e-12)


def test_symmetry_fill_matches_the_solver(monkeypatch):
    """The grid filled from the computed quarter by the three symmetries equals the solver
    run directly at nodes of every sign (coarse axes, 20 x 10 elements to be quick)."""
    import tablegen.specs as specs
    from tablegen.registry import get_spec

    monkeypatch.setattr(specs, "EXACT_SOLVER", dict(mx=20, my=10, tolerance=1e-9,
                                                    max_iterations=4000))
    monkeypatch.setattr(specs, "EXACT_RICHARDSON", False)
    spec = get_spec("creep_exact")
    axes, _ = spec.grid("coarse")
    g, nu, s, theta, tau = (a.nodes for a in axes)
    points, assemble = spec.reduce(axes)
    # the quarter restricted to one contact and one nu keeps the test fast
    sel = (points[:, 0] == g[1]) & (points[:, 1] == nu[2])
    values = np.zeros((len(points), 4))
    values[sel] = specs.exact_creep_function(points[sel])
    full = assemble(values)                       # (4, g, nu, s, theta, tau)
    rng = np.random.default_rng(5)
    picks = [(i, j, k) for i in range(len(s)) for j in range(len(theta)) for k in range(len(tau))
             if abs(s[i]) < 1.0 and (s[i] < 0 or abs(theta[j]) > 0.5 * np.pi + 1e-9
                                     or tau[k] < 0)]
    for n in rng.choice(len(picks), 6, replace=False):
        i, j, k = picks[n]
        direct = specs.exact_creep_function(np.array([[g[1], nu[2], s[i], theta[j], tau[k]]]))
        np.testing.assert_allclose(full[:3, 1, 2, i, j, k], direct[0, :3], atol=1e-7)
        assert full[3, 1, 2, i, j, k] == pytest.approx(direct[0, 3], abs=1e-12)


def test_symmetry_fill_gives_the_full_grid_every_symmetry_exactly():
    """Quarter values that break the symmetries on the quarter's own mirror planes (as the
    solver's do, by its tolerance and its shifted grid) come out of ``assemble`` with every
    symmetry exact. Checked as index operations on the full grid, stated from the physics and
    not through the reduction: T(-v, -phi) = -T(v, phi) reverses s and tau (f_par, f_perp,
    moment odd, stick area even); the mirror in y reverses theta and tau (f_perp and moment
    odd); the double cover (s, theta) = (-s, theta + pi) reverses s and shifts theta by half a
    period (both force components odd). Symmetric data pass unchanged (a projection)."""
    from tablegen.registry import get_spec

    spec = get_spec("creep_exact")
    axes, _ = spec.grid("default")
    g, nu, s, theta, tau = (a.nodes for a in axes)
    points, assemble = spec.reduce(axes)
    rng = np.random.default_rng(23)
    full = assemble(rng.normal(size=(len(points), 4)))         # (4, g, nu, s, theta, tau)
    odd = np.array([-1.0, -1.0, -1.0, 1.0]).reshape(4, 1, 1, 1, 1, 1)
    mirror = np.array([1.0, -1.0, -1.0, 1.0]).reshape(4, 1, 1, 1, 1, 1)
    cover = np.array([-1.0, -1.0, 1.0, 1.0]).reshape(4, 1, 1, 1, 1, 1)
    np.testing.assert_allclose(odd * full[:, :, :, ::-1, :, ::-1], full, rtol=0, atol=1e-14)
    circle = theta[:-1]                                         # the seam node once
    n = len(circle)
    assert np.allclose(circle[1:], -circle[:0:-1]) and n % 2 == 0
    neg = (n - np.arange(n)) % n                                # theta -> -theta
    half = (np.arange(n) + n // 2) % n                          # theta -> theta + pi
    assert np.allclose(np.cos(circle[neg]), np.cos(circle)) \
        and np.allclose(np.sin(circle[neg]), -np.sin(circle))
    assert np.allclose(np.cos(circle[half]), -np.cos(circle)) \
        and np.allclose(np.sin(circle[half]), -np.sin(circle), atol=1e-12)
    body = full[:, :, :, :, :-1]
    np.testing.assert_allclose(mirror * body[:, :, :, :, neg][..., ::-1], body, rtol=0,
                               atol=1e-14)
    np.testing.assert_allclose(cover * body[:, :, :, ::-1][:, :, :, :, half], body, rtol=0,
                               atol=1e-14)
    np.testing.assert_array_equal(full[:, :, :, :, -1], full[:, :, :, :, 0])   # the seam
    # a projection: the quarter of a symmetric grid assembles to the same grid
    quarter = full[:, :, :, s >= 0][:, :, :, :, np.abs(theta) <= 0.5 * np.pi + 1e-12]
    quarter = quarter[..., tau >= 0]
    again = assemble(np.moveaxis(quarter, 0, -1).reshape(-1, 4))
    np.testing.assert_allclose(again, full, rtol=0, atol=1e-14)


def test_coefficients_are_symmetric_bit_for_bit():
    """The build makes the coefficients obey the table's symmetries exactly, as the reader
    evaluates them: T(-v, -phi) = -T(v, phi) (-v at theta + pi, -phi at the reversed spin
    index), the double cover (-s, theta + pi) = (s, theta) and the mirror in y (theta and
    tau reversed); rounding to a power of two keeps them (a tie breaks the same way for a
    value and its image). Stated here as index operations on the stored coefficients."""
    from tablegen.build import rounded_coefficients, spline_axes
    from tablegen.registry import get_spec

    spec = get_spec("creep_exact")
    axes, _ = spec.grid("coarse")
    knots, stored = spline_axes(axes)
    shape = (4,) + tuple(len(a.nodes) for a in stored)
    n_c = shape[4]
    n_per = n_c - 3
    rng = np.random.default_rng(29)
    # values on rounding ties of 2^-13, each perturbed by round-off (as a refit makes them)
    raw = (rng.integers(-9000, 9000, shape) + 0.5) * 2.0**-13
    raw *= 1.0 + rng.choice([-1.0, 0.0, 1.0], shape) * 2.0**-52
    raw[:, :, :, :, n_per:] = raw[:, :, :, :, :3]                # periodic wrap
    turn = (np.arange(n_c) + n_per // 2) % n_per                 # theta -> theta + pi

    def check(c):
        sign = np.array([1.0, 1.0, -1.0, 1.0]).reshape(4, 1, 1, 1, 1, 1)
        assert np.array_equal(sign * c[:, :, :, :, turn][..., ::-1], c)
        sign = np.array([-1.0, -1.0, 1.0, 1.0]).reshape(4, 1, 1, 1, 1, 1)
        assert np.array_equal(sign * c[:, :, :, ::-1][:, :, :, :, turn], c)
        sign = np.array([1.0, -1.0, -1.0, 1.0]).reshape(4, 1, 1, 1, 1, 1)
        assert np.array_equal(sign * c[:, :, :, :, ::-1][..., ::-1], c)
        assert np.array_equal(c[:, :, :, :, n_per:], c[:, :, :, :, :3])

    c = spec.coefficient_symmetry(stored, knots, raw)
    check(c)
    assert np.max(np.abs(c - raw)) > 1e-6      # the raw values were not symmetric
    check(rounded_coefficients(spec, stored, c))
    with pytest.raises(ValueError, match="creepage_angle: the knots are not invariant"):
        spec.coefficient_symmetry(stored, [k + 0.01 * np.arange(len(k)) for k in knots], raw)


def test_periodic_axis_fit_is_scipys_periodic_spline_and_c2_across_the_seam():
    from scipy.interpolate import make_interp_spline

    x = np.linspace(-np.pi, np.pi, 13)
    other = np.linspace(0.0, 1.0, 5)
    vals = np.cos(x)[None, :] * (1 + other[:, None]) + 0.3 * np.sin(2 * x)[None, :]
    vals[:, -1] = vals[:, 0]
    knots = [np.r_[[0.0] * 4, other[2:-2], [1.0] * 4], periodic_bspline_knots(x)]
    coef = fit_tensor_bspline(vals[None], [other, x], knots, periodic=(False, True))
    assert coef.shape == (1, 5, 15)
    axes = [dict(name="o", nodes=other, knots=knots[0]),
            dict(name="t", nodes=periodic_stored_nodes(x), knots=knots[1])]
    spl = TensorSpline(axes, coef, ["v"])
    ref = make_interp_spline(x, vals[2], k=3, bc_type="periodic")
    tt = np.linspace(-np.pi, np.pi, 101)
    got = spl.evaluate(np.column_stack([np.full_like(tt, other[2]), tt]))[:, 0]
    np.testing.assert_allclose(got, ref(tt), atol=1e-13)
    # one-sided derivatives at the seam -pi / +pi agree to second order
    for d in (1, 2):
        lo = spl.evaluate([other[2], -np.pi], derivative=(0, d))[0]
        hi = spl.evaluate([other[2], np.pi], derivative=(0, d))[0]
        assert lo == pytest.approx(hi, abs=1e-12)


# --------------------------------------------------------------------------------------------
# The shipped table
# --------------------------------------------------------------------------------------------

def _one_sided(f, x0, h):
    """Left and right difference quotients of f at x0 (second order one-sided)."""
    left = (3 * f(x0) - 4 * f(x0 - h) + f(x0 - 2 * h)) / (2 * h)
    right = (-3 * f(x0) + 4 * f(x0 + h) - f(x0 + 2 * h)) / (2 * h)
    return left, right


@needs_table
@pytest.mark.parametrize("eta", [0.0, 2e-4])
def test_c1_across_zero_spin(table, eta):
    """Issue case: xi = 3e-4, a0 = 6 mm, b0 = 4 mm, N = 100 kN, mu = 0.3; Tx as a function of
    spin is smooth through phi = 0 (the old symmetry-reduced table had slopes -0.0113 /
    +0.0113 per 1/m there). The steps stay inside the first spin interval (tau = 0.003 is
    phi = 4.3e-4 1/m here): across the nodes 0.003 and 0.01 the second-order one-sided
    quotients with h = 1e-3 1/m read the spline's curvature change as 8e-4 (they agree to
    1e-8 at h = 1e-5)."""
    def tx(phi):
        return table.creep_force_3d(*_args(3e-4, eta, phi)).tx / MU_N

    left, right = _one_sided(tx, 0.0, 1e-4)
    assert left == pytest.approx(right, abs=2e-5)      # measured 8e-6


@needs_table
@pytest.mark.parametrize("phi", [0.0, 0.1, -0.4])
def test_c1_across_zero_longitudinal_creepage(table, phi):
    """Ty as a function of xi through xi = 0 with spin (the old table: slope jump 0.003 per
    1e-3 of creepage); Tx too. With eta = 1e-4 the creepage's direction turns by 90 degrees
    within xi ~ 1e-4, so the second-order one-sided quotients read their own error (h^2 times
    the third derivative over 3): for Ty at phi = 0 a "jump" of 7.4e-2 at h = 1e-6 since the
    angle nodes +-86.25 deg (sixth session of 2026-11-27; 2.8e-3 before, 9e-4 on the grid
    before that), 7.4e-4 at 1e-7, 6.7e-5 at 3e-8. It falls as h^2, so the slope is
    continuous; a kink keeps its jump as h falls. At h = 3e-8 the quotients agree to 2e-4,
    and their difference is at most 5 % of the one at h = 3e-7."""
    def ty(xi):
        return table.creep_force_3d(*_args(xi, 1e-4, phi)).ty / MU_N

    def tx(xi):
        return table.creep_force_3d(*_args(xi, 1e-4, phi)).tx / MU_N

    for f in (ty, tx):
        left, right = _one_sided(f, 0.0, 3e-8)
        assert left == pytest.approx(right, abs=2e-4 * max(1.0, abs(left)))
        coarse = np.subtract(*_one_sided(f, 0.0, 3e-7))
        assert abs(left - right) <= 0.05 * abs(coarse) + 2e-6   # falls as h^2: no kink


@needs_table
def test_c1_through_zero_creepage_along_lines(table):
    """Along straight lines through v = 0 (the polar origin is inside the double cover)."""
    for direction in ((1.0, 0.0), (0.0, 1.0), (0.6, -0.8)):
        def fx(t, d=direction):
            return table.creep_force_3d(*_args(t * d[0], t * d[1], 0.2)).tx / MU_N

        left, right = _one_sided(fx, 0.0, 2e-6)
        assert left == pytest.approx(right, rel=1e-3, abs=1e-2)


@needs_table
def test_slopes_at_zero_are_kalkers_coefficients(table):
    """d T / d creepage at zero = -G a b C_ij with Kalker's published coefficients (the shared
    table, Kalker 1990, Table E.3: three digits), at every a0/b0 and nu of his table (57
    entries per coefficient, a0/b0 0.1-10), within 0.5 %, from the Jacobian and from a finite
    difference of the force.

    The table is anchored to the linear limit (tablegen.specs.exact_linear_limit_correction:
    the solver's slope converges only slowly, -0.84 % on C11 at a/b 1 at its setting) and its
    first nodes sit at rho = 0.0007, tau = 0.003, where the force has not yet bent away from the
    linear theory (with the first nodes at 0.006 and 0.03: up to 0.8 % on C22 and C23). The
    nodes in ln(a0/b0) and nu are not Kalker's: between them the spline interpolates. The
    difference quotients take steps of about 1e-3 of the saturation creepage: the stored
    coefficients' rounding (5 significant digits) leaves the spline up to about 1e-8 of mu N
    off zero near v = 0 (the force is set to exactly 0 at v = 0), which a step of 1e-8 in
    the creepage would read as a percent."""
    g_nodes, nu_nodes, c = kalker_table()
    worst = 0.0
    for i, gi in enumerate(g_nodes):
        for j, nu in enumerate(nu_nodes):
            a0, b0 = 6e-3 * math.sqrt(gi), 6e-3 / math.sqrt(gi)
            g_mod = 210e9 / (2 * (1 + nu))
            jac = table.creep_force_jacobian_3d(0.0, 0.0, 0.0, 1e5, a0, b0, 210e9, nu, 0.3)
            scale = g_mod * a0 * b0
            eps = 1e-6      # about 1e-3 of the saturation creepage
            fd = [-table.creep_force_3d(eps, 0.0, 0.0, *_contact(a0, b0, nu)).tx / eps,
                  -table.creep_force_3d(0.0, eps, 0.0, *_contact(a0, b0, nu)).ty / eps,
                  -table.creep_force_3d(0.0, 0.0, 1e2 * eps, *_contact(a0, b0, nu)).ty
                  / (1e2 * eps)]
            want = (c[0, j, i], c[1, j, i], c[2, j, i])
            got = (-jac[0, 0] / scale, -jac[1, 1] / scale,
                   -jac[1, 2] / (scale * math.sqrt(a0 * b0)))
            fd = (fd[0] / scale, fd[1] / scale, fd[2] / (scale * math.sqrt(a0 * b0)))
            for k in range(3):
                worst = max(worst, abs(got[k] / want[k] - 1.0), abs(fd[k] / want[k] - 1.0))
    assert worst < 0.005      # measured 0.47 % (C23 from the Jacobian; C11 0.18, C22 0.20 %)


def _contact(a0, b0, nu):
    return 1e5, a0, b0, 210e9, nu, 0.3


@needs_table
def test_odd_in_the_creepage_vector_and_zero_at_zero(table):
    rng = np.random.default_rng(11)
    xi, eta = rng.uniform(-4e-3, 4e-3, (2, 500))
    phi = rng.uniform(-3.0, 3.0, 500)
    plus = table.creep_solution_3d(*_args(xi, eta, phi), sensitivities=False)
    minus = table.creep_solution_3d(*_args(-xi, -eta, -phi), sensitivities=False)
    # exact to the evaluation's round-off (measured 1e-13 of mu N): the build averages the
    # solver's mirror images on the quarter's planes (theta = +-pi/2, tau = 0, s = 0, each
    # computed on its own) and makes the coefficients symmetric bit for bit before rounding
    # them (until 2026-11-27 the defect was 1e-5 of mu N)
    np.testing.assert_allclose(minus.tx, -plus.tx, rtol=0, atol=1e-12 * MU_N)
    np.testing.assert_allclose(minus.ty, -plus.ty, rtol=0, atol=1e-12 * MU_N)
    np.testing.assert_allclose(minus.spin_moment, -plus.spin_moment, rtol=0,
                               atol=1e-12 * MU_N * 5e-3)
    zero = table.creep_solution_3d(*_args(0.0, 0.0, 0.0), sensitivities=False)
    assert abs(zero.tx) < 1e-12 * MU_N and abs(zero.ty) < 1e-12 * MU_N
    assert zero.stick_area_fraction == pytest.approx(1.0, abs=1e-9)


@needs_table
def test_never_past_the_coulomb_limit(table):
    rng = np.random.default_rng(13)
    n = 20000
    args = (rng.normal(0, 3e-3, n), rng.normal(0, 3e-3, n), rng.normal(0, 2.0, n), 1e5,
            rng.uniform(2e-3, 9e-3, n), rng.uniform(2e-3, 9e-3, n), 210e9,
            rng.uniform(0, 0.5, n), 0.3)
    f = table.creep_force_3d(*args)
    assert np.all(np.hypot(f.tx, f.ty) <= MU_N)
    assert np.all(np.isfinite(f.tx)) and np.all(np.isfinite(f.ty))


@needs_table
def test_scalar_and_vectorised_paths_agree(table):
    rng = np.random.default_rng(17)
    pts = rng.uniform([-3e-3, -3e-3, -2.0], [3e-3, 3e-3, 2.0], (50, 3))
    vec = table.creep_solution_3d(*_args(pts[:, 0], pts[:, 1], pts[:, 2]))
    for k, p in enumerate(pts):
        tx, ty, mz, stick, rho, jac = table.step(*_args(*p))
        assert (tx, ty, mz, stick) == pytest.approx(
            (vec.tx[k], vec.ty[k], vec.spin_moment[k], vec.stick_area_fraction[k]),
            rel=1e-12, abs=1e-9)
        np.testing.assert_allclose(jac, vec.sensitivity[k], rtol=1e-10, atol=1e-6)


def _random_contacts(rng, n):
    """n random scalar calls over the table's domain (a0/b0 0.1-10, nu 0-0.5, spin within
    |tau| <= 20 for the most part)."""
    g = np.exp(rng.uniform(np.log(0.1), np.log(10.0), n))
    b0 = rng.uniform(2e-3, 8e-3, n)
    out = []
    for k in range(n):
        out.append((float(rng.normal(0, 2e-3)), float(rng.normal(0, 2e-3)),
                    float(rng.normal(0, 0.5)), float(rng.uniform(2e4, 1.5e5)),
                    float(g[k] * b0[k]), float(b0[k]), 210e9, float(rng.uniform(0.0, 0.5)),
                    float(rng.uniform(0.1, 0.5))))
    return out


def _assert_same_point(a, b, c):
    """Two step_values lists of contact ``c`` agree to round-off: forces and moment relative to
    mu N (and sqrt(a0 b0)), stick area absolutely, the Jacobian to its largest entry."""
    mu_n = c[3] * c[8]
    scale = max(abs(v) for v in b[5:])
    assert max(abs(x - y) for x, y in zip(a[:2], b[:2])) < 1e-13 * mu_n
    assert abs(a[2] - b[2]) < 1e-13 * mu_n * math.sqrt(c[4] * c[5])
    assert abs(a[3] - b[3]) < 1e-13
    assert max(abs(x - y) for x, y in zip(a[5:], b[5:])) < 1e-11 * scale


def test_kernels_kalker_interpolant_is_kalker_coefficients():
    """The scalar kernel of any contact evaluates Kalker's coefficients itself, from the data
    of railcontact.kalker's interpolant: the same values as kalker_coefficients (random and
    edge points of a0/b0 0.1-10 and nu 0-0.5, the interpolant's breakpoints included)."""
    from railcontact import _exact_kernels as kernels
    from railcontact.kalker import kalker_interpolant

    kx, kc, nu_nodes = kalker_interpolant()
    rng = np.random.default_rng(23)
    g = np.r_[np.exp(rng.uniform(np.log(0.1), np.log(10.0), 400)), np.exp(kx), 0.1, 10.0]
    nu = np.r_[rng.uniform(0.0, 0.5, 400), np.full(kx.size, 0.28), 0.0, 0.5]
    want = kalker_coefficients(g, nu)
    got = np.zeros(3)
    worst = 0.0
    for k in range(g.size):
        kernels._kalker_table_coefficients(kx, kc, nu_nodes, math.log(g[k]), nu[k], got)
        ref = np.array([want.c11[k], want.c22[k], want.c23[k]])
        worst = max(worst, float(np.max(np.abs(got / ref - 1.0))))
    assert worst < 1e-13


@needs_table
def test_a_new_contact_gets_the_tables_values_without_its_buffer(monkeypatch):
    """A contact's first points come from the five-dimensional spline (the kernel of any
    contact), later ones from its buffer (the table summed over a0/b0 and nu once): the same
    values, to round-off, on 300 random contacts over the domain; forces, moment and stick area
    relative to mu N, the Jacobian to its largest entry. Through both scalar entries (step and
    creep_force_3d) and a small batch."""
    import railcontact.exact_table as et

    contacts = _random_contacts(np.random.default_rng(29), 200)
    monkeypatch.setattr(et, "SLAB_AFTER_POINTS", 10**9)
    fresh = ExactCreepTable.from_file(TABLE)
    first = [fresh.step_values(*c) for c in contacts]
    forces = [fresh.creep_force_3d(*c) for c in contacts if fresh.step_values(*c) is not None]
    assert not fresh._buffers                      # none made: every value the 5-D spline's
    monkeypatch.setattr(et, "SLAB_AFTER_POINTS", 1)
    buffered = ExactCreepTable.from_file(TABLE)
    answered = 0
    for c, a, in zip(contacts, first):
        b = buffered.step_values(*c)
        assert (a is None) == (b is None)          # (|tau| > 20: the array path, the solver)
        if a is None:
            continue
        answered += 1
        _assert_same_point(a, b, c)
        assert a[4] == pytest.approx(b[4], rel=1e-14)
    assert answered > 160 and len(forces) == answered
    for c, f in zip((c for c, a in zip(contacts, first) if a is not None), forces):
        assert (f.tx, f.ty) == pytest.approx(buffered.step_values(*c)[:2], rel=1e-12,
                                             abs=1e-13 * c[3] * c[8])
    # a batch of a few points at a new contact: the 5-D spline too, the same values
    monkeypatch.setattr(et, "SLAB_AFTER_POINTS", 10**9)
    c = contacts[0]
    xs = np.array([c[0], -c[0], 0.5 * c[0]])
    vec = fresh.creep_solution_3d(xs, c[1], c[2], *c[3:])
    assert not fresh._buffers
    for k, x in enumerate(xs):
        want = buffered.step_values(float(x), *c[1:])
        assert (vec.tx[k], vec.ty[k]) == pytest.approx(want[:2], rel=1e-12, abs=1e-9)


@needs_table
def test_the_forces_kernel_gives_the_full_kernels_forces_bit_for_bit(monkeypatch):
    """The public scalar call on a contact's buffer (the forces-only kernel
    ``creep_contact_force``: two variables summed, the forces returned) gives the forces of
    the full kernel that the batch and the FMU use, bit for bit, on 40 random contacts x 8
    creepages over the domain, at zero creepage exactly 0; beyond the spin axis the solver
    answers, and non-finite input is a ValueError, as on every other path."""
    import railcontact.exact_table as et
    from railcontact.creep3d import load_exact_table

    monkeypatch.setattr(et, "SLAB_AFTER_POINTS", 1)
    fresh = load_exact_table(TABLE)                      # with the solver
    rng = np.random.default_rng(41)
    compared = 0
    for c in _random_contacts(rng, 40):
        pts = [(float(rng.normal(0, 2e-3)), float(rng.normal(0, 2e-3)),
                float(rng.normal(0, 0.5))) for _ in range(7)] + [(0.0, 0.0, 0.0)]
        for p in pts:
            f = fresh.creep_force_3d(*p, *c[3:])
            assert (c[4] / c[5], c[7]) in fresh._buffers          # the buffer's kernel
            want = fresh.step_values(*p, *c[3:], False)
            if want is None:                                     # |tau| > 20: the solver
                continue
            assert (f.tx, f.ty) == (want[0], want[1])
            compared += 1
        assert fresh.creep_force_3d(0.0, 0.0, 0.0, *c[3:]) == (0.0, 0.0)
    assert compared > 250                 # (the rest beyond |tau| = 20)
    args = _args(1e-4, 0.0, 40.0)
    fresh.creep_force_3d(*_args(1e-4, 0.0, 0.0))                # its buffer exists
    got = fresh.creep_force_3d(*args)
    want = fresh.creep_solution_3d(*args, sensitivities=False)   # the solver
    assert (got.tx, got.ty) == (want.tx, want.ty) and abs(got.tx) > 0
    with pytest.raises(ValueError, match="creepage_lateral"):
        fresh.creep_force_3d(*_args(1e-4, float("nan"), 0.0))
    with pytest.raises(ValueError, match="normal_load must be in"):
        fresh.creep_force_3d(*_args(1e-4, 0.0, 0.0, normal_load=float("inf")))


@needs_table
def test_a_contact_gets_its_buffer_once_it_has_been_asked_enough_points(monkeypatch):
    """Ski rental: a contact's buffer is made once the contact has been asked for
    SLAB_AFTER_POINTS points (scalar calls and batch points together), not before; a contact
    that changes at every call never makes one."""
    import railcontact.exact_table as et

    monkeypatch.setattr(et, "SLAB_AFTER_POINTS", 8)
    fresh = ExactCreepTable.from_file(TABLE)
    args = _args(1e-3, 2e-4, 0.3)
    key = (args[4] / args[5], args[7])
    for _ in range(7):
        fresh.step_values(*args)
    assert key not in fresh._buffers
    fresh.creep_force_3d(*args)
    assert key in fresh._buffers
    other = _args(1e-3, 2e-4, 0.3, a0=5e-3)
    fresh.creep_solution_3d(np.full(8, 1e-3), 2e-4, 0.3, *other[3:])   # 8 points at once
    assert (other[4] / other[5], other[7]) in fresh._buffers
    moving = ExactCreepTable.from_file(TABLE)
    for k in range(40):
        moving.step_values(*_args(1e-3, 2e-4, 0.3, a0=5e-3 + k * 1e-6))
    assert not moving._buffers


@needs_table
@pytest.mark.parametrize("point", [(1e-3, 2e-4, 0.3), (-4e-4, 1e-3, -1.2), (2e-3, -3e-3, 0.05),
                                   (1e-5, 0.0, 2.0)])
def test_jacobian_is_the_derivative_of_the_table(table, point):
    x0 = np.array(point)
    h = np.array([1e-8, 1e-8, 1e-5])
    jac = table.step(*_args(*x0))[5]
    for k in range(3):
        up, dn = x0.copy(), x0.copy()
        up[k] += h[k]
        dn[k] -= h[k]
        fd = (np.array(table.step(*_args(*up))[:3]) - np.array(table.step(*_args(*dn))[:3])) \
            / (2 * h[k])
        np.testing.assert_allclose(jac[:, k], fd, rtol=2e-5,
                                   atol=1e-6 * np.abs(jac).max(axis=1).max())


@needs_table
def test_jacobian_against_finite_differences_of_the_solver(table):
    """The table's Jacobian against central differences of the extrapolated solver (the
    table's own setting), within 2 % of the largest entry of each row."""
    from railcontact import creep_force_3d

    x0 = np.array([6e-4, 3e-4, 0.4])
    h = np.array([3e-5, 3e-5, 3e-2])
    jac = table.creep_force_jacobian_3d(*_args(*x0))
    for k in range(2):
        up, dn = x0.copy(), x0.copy()
        up[k] += h[k]
        dn[k] -= h[k]
        table_setting = dict(tolerance=1e-8)    # the method's default grids, as the table
        fu = creep_force_3d(*_args(*up), method="exact", **table_setting)
        fd_ = creep_force_3d(*_args(*dn), method="exact", **table_setting)
        fd = np.array([fu.tx - fd_.tx, fu.ty - fd_.ty]) / (2 * h[k])
        np.testing.assert_allclose(jac[:2, k], fd, atol=0.02 * np.abs(jac[:2, :2]).max())


@needs_table
def test_beyond_the_spin_axis_the_solver_answers(table):
    """|tau| > 20: the documented fallback, the solver at the table's setting (48 lateral
    elements for a0/b0 < 0.115, 36 for a0/b0 < 0.87); without a solver attached, a ValueError naming the spin and
    the table's range."""
    from railcontact import creep_solution_3d

    args = _args(1e-4, 0.0, 40.0)
    got = table.creep_solution_3d(*args, sensitivities=False)
    want = creep_solution_3d(*args, method="exact", tolerance=1e-4)  # the table's setting
    assert got.tx == want.tx and got.ty == want.ty and got.spin_moment == want.spin_moment
    # a batch with a narrow contact beyond the a0/b0 axis: that one at 48 lateral elements
    # (the table's rule for the narrowest contacts with large spin), the other at 20, both in
    # place
    narrow = _args(1e-4, 0.0, 40.0, a0=1e-3, b0=2e-2)
    both = [np.array([x, y]) for x, y in zip(args, narrow)]
    got = table.creep_solution_3d(*both, sensitivities=False)
    want_n = creep_solution_3d(*narrow, method="exact", grid=(30, 48), tolerance=1e-4)
    assert got.tx[0] == want.tx and got.spin_moment[0] == want.spin_moment
    assert got.tx[1] == want_n.tx and got.ty[1] == want_n.ty
    assert got.stick_area_fraction[1] == want_n.stick_area_fraction
    bare = ExactCreepTable.from_file(TABLE)
    with pytest.raises(ValueError, match=r"spin must give a spin coordinate \|tau\| <= 20"):
        bare.creep_force_3d(*args)
    with pytest.raises(ValueError, match=r"a0/b0 must be in \[0.1, 10\]"):
        bare.creep_force_3d(*_args(1e-4, 0.0, 0.0, a0=2e-2, b0=1e-3))


@needs_table
@pytest.mark.parametrize("name, bad, match", [
    ("poisson_ratio", 0.6, r"poisson_ratio must be in \[0, 0.5\]"),
    ("normal_load", -1.0, r"normal_load must be in"),
    ("friction_coefficient", float("nan"), r"friction_coefficient"),
])
def test_bad_input_names_the_parameter(table, name, bad, match):
    kw = dict(CONTACT, **{name: bad})
    with pytest.raises(ValueError, match=match):
        table.creep_force_3d(1e-3, 0.0, 0.0, kw["normal_load"], kw["a0"], kw["b0"],
                             kw["youngs_modulus"], kw["poisson_ratio"],
                             kw["friction_coefficient"])


def _contact_converged():
    """CONTACT's 21 grid-convergence cases, converged value by one Richardson step from its
    120 x 60 and 240 x 60 rows (first order in the rolling-direction element size)."""
    rows = list(csv.DictReader(l for l in open(DATA / "contact_hertz3d_grid_convergence.csv")
                               if not l.startswith("#")))
    out = {}
    for r in rows:
        key = (r["a_over_b"], r["case"])
        out.setdefault(key, {})[(int(r["mx"]), int(r["my"]))] = r
    cases = []
    for key, grids in out.items():
        if (120, 60) in grids and (240, 60) in grids:
            r1, r2 = grids[(120, 60)], grids[(240, 60)]
            fx = 2 * float(r2["fx_over_mu_fn"]) - float(r1["fx_over_mu_fn"])
            fy = 2 * float(r2["fy_over_mu_fn"]) - float(r1["fy_over_mu_fn"])
            cases.append((r2, fx, fy))
    return cases


@needs_table
def test_against_contacts_converged_values(table):
    """Error against the converged exact theory (CONTACT 120x60 and 240x60 extrapolated) on
    its 21 cases (a/b = 0.2, 1, 5; creepage, spin, pure spin), in units of mu N."""
    cases = _contact_converged()
    assert len(cases) == 21
    errs = []
    for r, fx, fy in cases:
        nu = float(r["nu"])
        e_mod = 2 * float(r["G_Pa"]) * (1 + nu)
        f = table.creep_force_3d(float(r["cksi"]), float(r["ceta"]), float(r["cphi_per_m"]),
                                 float(r["Fn_N"]), float(r["a_m"]), float(r["b_m"]), e_mod, nu,
                                 float(r["mu"]))
        mu_n = float(r["mu"]) * float(r["Fn_N"])
        # CONTACT's forces are on the wheel as ours (docs/conventions.md)
        errs.append(math.hypot(f.tx / mu_n - fx, f.ty / mu_n - fy))
    errs = np.array(errs)
    assert errs.max() < 5e-3
    assert math.sqrt(np.mean(errs**2)) < 2.5e-3


@needs_table
def test_extreme_inputs_give_an_answer_or_a_value_error(table):
    """Inputs anywhere in the float range (the cases found by fuzzing the old reader): a finite
    answer within mu N, or a ValueError naming a parameter; never NaN or another exception."""
    cases = [
        _args(1e-3, 2e-4, 0.1, youngs_modulus=5e-324),        # w_sat beyond the float range
        _args(-1.0, 1.0, 1e300, friction_coefficient=0.0),    # no friction: no force
        (1e-3, -5e-4, 0.1, 1e300, 1.5e96, 1.2e96, 210e9, 0.28, 0.3),  # Mz beyond float range
        _args(1e-3, 1e-4, 0.1, friction_coefficient=5e-324),  # subnormal mu
        _args(0.0, 0.0, 1e-300),
    ]
    for args in cases:
        try:
            sol = table.creep_solution_3d(*args)
        except ValueError as exc:
            assert any(name in str(exc) for name in (
                "normal_load", "a0", "b0", "youngs_modulus", "friction_coefficient", "spin",
                "creepage")), str(exc)
            continue
        mu_n = args[3] * args[8]
        assert np.isfinite(sol.tx) and np.isfinite(sol.ty) and np.isfinite(sol.spin_moment)
        assert math.hypot(sol.tx, sol.ty) <= mu_n * (1 + 1e-12)


def _solve_similar(g, theta, rho, tau=0.0, nu=0.28):
    """The table's solver at table coordinates (mu lowered with the creepages where they
    exceed the solver's domain: T / (mu N) is unchanged, the discrete problem is similar)."""
    from railcontact import creep_force_3d  # noqa: PLC0415

    p = exact_table_inverse(math.log(g), nu, creepage_coordinate(rho, tau), theta, tau,
                            contact=REFERENCE_CONTACT)
    lam = 0.5 / max(abs(float(p["creepage_longitudinal"])), abs(float(p["creepage_lateral"])),
                    0.5)
    scaled = ("creepage_longitudinal", "creepage_lateral", "spin", "friction_coefficient")
    args = [float(p[k]) * (lam if k in scaled else 1.0) for k in (
        "creepage_longitudinal", "creepage_lateral", "spin", "normal_load", "a0", "b0",
        "youngs_modulus", "poisson_ratio", "friction_coefficient")]
    sol = creep_force_3d(*args, method="exact", tolerance=1e-4)   # the table's setting
    return args, sol, args[3] * args[8]


@pytest.mark.parametrize("g,theta_deg", [(0.1, 30.0), (0.2, 60.0), (5.0, -120.0),
                                         (10.0, 30.0)])
def test_full_sliding_limit_against_the_solver(g, theta_deg):
    """At infinite creepage the force opposes the physical creepage (xi_x, xi_y), not the
    Kalker-weighted v: tablegen's s = 1 node values against the solver at rho = 100 (the
    earlier table put the force along -v there and erred by up to 14 % of mu N at a/b = 0.1)."""
    from tablegen.specs import exact_full_sliding_limit  # noqa: PLC0415

    theta = math.radians(theta_deg)
    _, sol, mu_n = _solve_similar(g, theta, 100.0)
    f_par, f_perp, moment, stick = exact_full_sliding_limit(
        np.array([[math.log(g), 0.28, 1.0, theta, 0.0]]))[0]
    c, s = math.cos(theta), math.sin(theta)
    fx, fy = -(f_par * c - f_perp * s), -(f_par * s + f_perp * c)
    assert math.hypot(fx, fy) == pytest.approx(1.0, abs=1e-12)
    assert math.hypot(sol.tx / mu_n - fx, sol.ty / mu_n - fy) < 1e-3
    assert moment == 0.0 and stick == 0.0
    # the double cover: s = -1 at theta + pi is the same creepage
    back = exact_full_sliding_limit(np.array([[math.log(g), 0.28, -1.0, theta + math.pi, 0.0]]))
    np.testing.assert_allclose(back[0, :2], [-f_par, -f_perp], atol=1e-12)


@needs_table
@pytest.mark.parametrize("g,theta_deg,rho", [(0.1, 30.0, 10.0), (0.2, 60.0, 30.0),
                                             (10.0, -120.0, 100.0)])
def test_table_at_large_creepage_against_the_solver(table, g, theta_deg, rho):
    """Far past saturation the table follows the solver's turn of the force towards the
    physical creepage (measured 0.001-0.03 % of mu N)."""
    args, sol, mu_n = _solve_similar(g, math.radians(theta_deg), rho)
    f = table.creep_force_3d(*args)
    assert math.hypot(f.tx - sol.tx, f.ty - sol.ty) / mu_n < 2e-3


@needs_table
def test_against_contacts_tractcurv(table):
    """CONTACT's creep curve (tractcurv series 1, a/b = 0.5, 48x44 elements): the table within
    1 % of mu N at all 30 points, and its slope at zero within 0.5 % of Kalker's C11.

    The curve is CONTACT's 48x44 solution, not the converged theory: in partial slip near
    saturation (xi = 1.2e-3 to 2e-3) it lies 0.81-0.88 % of mu N above the solver's default
    and its (60, 40) and (120, 40) grids, which agree with each other to 0.05 % (measured
    2026-11-26), so the table's 0.93 % there is mostly CONTACT's grid error; the table's error
    against the converged theory is checked on CONTACT's grid-convergence cases."""
    g_mod, nu, mu = 82e9, 0.28, 0.33
    e_mod = 2 * g_mod * (1 + nu)
    a0, b0, n_load = 6.304e-3, 12.61e-3, 106.7e3
    curve = np.loadtxt(DATA / "contact_tractcurv_series1_coulomb.csv", delimiter=",",
                       comments="#", skiprows=5)
    tx = table.creep_force_3d(curve[:, 0], 0.0, 0.0, n_load, a0, b0, e_mod, nu, mu).tx
    err = np.abs(tx / (mu * n_load) - curve[:, 1])
    assert err.max() < 1e-2           # measured 0.93 % (at xi = 1.6e-3)
    assert err[curve[:, 0] >= 3.6e-3].max() < 1e-4    # full sliding: measured 0.005 %
    c11 = float(kalker_coefficients(a0 / b0, nu).c11)
    slope = table.creep_force_jacobian_3d(0.0, 0.0, 0.0, n_load, a0, b0, e_mod, nu, mu)[0, 0]
    assert -slope / (g_mod * a0 * b0) == pytest.approx(c11, rel=0.005)   # measured -0.28 %


@needs_table
@pytest.mark.parametrize("own_contacts", [False, True])
def test_parallel_batches_equal_the_point_by_point_values(table, own_contacts):
    """Batches of at least two PARALLEL_CHUNK tasks run on numba's threads: the same values,
    bit for bit, as the serial kernel on the same points (one contact and every point its own
    contact, forces and Jacobian), also with two Python threads calling at once."""
    import threading

    from railcontact._exact_kernels import PARALLEL_CHUNK

    # (the sum over nu made first: it is made by itself after enough points, and the values
    # on it differ from the file's by round-off; here every call is on the same coefficients)
    table.prepare(CONTACT["poisson_ratio"])
    rng = np.random.default_rng(23)
    n = 2 * PARALLEL_CHUNK + 17
    xi, eta = rng.uniform(-4e-3, 4e-3, (2, n))
    phi = rng.uniform(-3.0, 3.0, n)
    over = {"a0": rng.uniform(3e-3, 8e-3, n)} if own_contacts else {}
    whole = table.creep_solution_3d(*_args(xi, eta, phi, **over))
    parts = [table.creep_solution_3d(*_args(xi[s], eta[s], phi[s], **{
        k: v[s] for k, v in over.items()})) for s in np.array_split(np.arange(n), 9)]
    for field in ("tx", "ty", "spin_moment", "stick_area_fraction", "sensitivity"):
        np.testing.assert_array_equal(getattr(whole, field), np.concatenate(
            [getattr(p, field) for p in parts]), err_msg=field)
    results = [None, None]

    def run(k):
        results[k] = table.creep_force_3d(*_args(xi, eta, phi, **over))

    threads = [threading.Thread(target=run, args=(k,)) for k in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for res in results:
        np.testing.assert_array_equal(res.tx, whole.tx)
        np.testing.assert_array_equal(res.ty, whole.ty)


def test_jacobian_at_the_origin_is_cartesian():
    """Within |v| < JACOBIAN_RHO_MIN of v = 0 the Jacobian comes from the radial derivatives
    along v_x and v_y: the same for either sign of a zero and for any direction of a tiny v,
    and continuous with the polar formula just outside. (Taken along the direction of v, the
    angle derivative at |v| = 1e-6 divided the smallest nodes' rounding by |v|: at a0/b0 = 10,
    nu = 0.25, C23 read -0.51 % at phi = 0 and -0.32 % at phi = 1e-9.)"""
    from railcontact.creep3d import load_exact_table

    table = load_exact_table()
    g, nu = 10.0, 0.25
    a0, b0 = 6e-3 * math.sqrt(g), 6e-3 / math.sqrt(g)

    def jac(xi_x, xi_y, phi):
        return np.asarray(table.creep_force_jacobian_3d(xi_x, xi_y, phi, 1e5, a0, b0, 210e9,
                                                        nu, 0.3))

    origin = jac(0.0, 0.0, 0.0)
    scale = np.abs(origin).max(axis=1, keepdims=True)
    for inside in [(-0.0, -0.0, -0.0), (1e-9, 0.0, 0.0), (0.0, 1e-9, 0.0), (0.0, 0.0, 1e-9),
                   (-7e-10, 7e-10, 0.0)]:          # |v| ~ 1e-7, inside
        np.testing.assert_allclose(jac(*inside) / scale, origin / scale, rtol=0, atol=1e-9)
    for outside in [(1e-7, 0.0, 0.0), (0.0, 1e-7, 0.0), (0.0, 0.0, 1e-7),
                    (-7e-8, -7e-8, 0.0)]:          # |v| ~ 1e-5, the polar formula
        np.testing.assert_allclose(jac(*outside) / scale, origin / scale, rtol=0, atol=2e-3)


@needs_table
def test_a_material_summed_over_nu_gives_the_files_values(monkeypatch):
    """Contacts whose ellipse and load change at every call, one material: once the table is
    summed over Poisson's ratio at its nu (ExactCreepTable.prepare, 4 x 64 products per
    variable instead of 16 x 64), the scalar calls, the forces-only call and the batch of
    varying contacts give the file's values to round-off (forces relative to mu N, the
    Jacobian to its largest entry), on random contacts at nu = 0.28 over a0/b0 0.1-10; the
    forces-only kernel gives the full kernel's forces bit for bit."""
    import railcontact.exact_table as et

    monkeypatch.setattr(et, "NU_SLAB_AFTER_POINTS", 10**9)
    contacts = [c[:7] + (0.28, c[8]) for c in _random_contacts(np.random.default_rng(31), 140)]
    table = ExactCreepTable.from_file(TABLE)
    contacts = [c for c in contacts if table.step_values(*c) is not None]  # (|tau| <= 20)
    file_values = [table.step_values(*c) for c in contacts]
    file_forces = [tuple(table.creep_force_3d(*c)) for c in contacts]
    assert not table._nu_slabs
    table.prepare(0.28)
    assert table._nu_slabs[0.28][0].shape[1] == 1
    answered = 0
    for c, a, fa in zip(contacts, file_values, file_forces):
        b = table.step_values(*c)
        assert (a is None) == (b is None)
        if a is None:
            continue
        answered += 1
        _assert_same_point(a, b, c)
        mu_n = c[3] * c[8]
        fb = tuple(table.creep_force_3d(*c))
        assert max(abs(x - y) for x, y in zip(fa, fb)) < 1e-13 * mu_n
        assert fb == tuple(b[:2])          # forces-only kernel = full kernel, bit for bit
    assert answered > 100
    # the batch of varying contacts (one kernel call, every point its own contact)
    arrays = [np.array(v) for v in zip(*contacts)]
    vec = table.creep_solution_3d(*arrays)
    for k, (c, b) in enumerate(zip(contacts, file_values)):
        if b is not None:
            assert (vec.tx[k], vec.ty[k]) == pytest.approx(b[:2], rel=0,
                                                           abs=1e-13 * c[3] * c[8])
            assert vec.spin_moment[k] == pytest.approx(
                b[2], rel=0, abs=1e-13 * c[3] * c[8] * math.sqrt(c[4] * c[5]))


@needs_table
def test_the_sum_over_nu_is_made_after_enough_points_and_checks_its_input(monkeypatch):
    import railcontact.exact_table as et

    monkeypatch.setattr(et, "NU_SLAB_AFTER_POINTS", 5)
    table = ExactCreepTable.from_file(TABLE)
    args = list(_args(1e-3, 0.0, 0.2))
    for k in range(4):
        args[4] = 6e-3 * (1.0 + 0.1 * k)           # a new ellipse every call
        table.creep_force_3d(*args)
    assert not table._nu_slabs
    table.creep_force_3d(*args)
    assert list(table._nu_slabs) == [CONTACT["poisson_ratio"]]
    with pytest.raises(ValueError, match=r"poisson_ratio must be in \[0, 0\.5\].*got 0\.7"):
        table.prepare(0.7)


@needs_table
def test_evaluate_contacts_gives_each_contact_what_a_single_call_gives(table, monkeypatch):
    """The vehicle's call: K contacts, each its own ellipse, load and friction, in one
    compiled call, equal (to round-off) to K scalar calls of step_values; a contact beyond the
    table's a0/b0 axis is answered by the solver, as creep_solution_3d answers it."""
    import railcontact.exact_table as et

    monkeypatch.setattr(et, "NU_SLAB_AFTER_POINTS", 10**9)   # (the file's coefficients)
    rng = np.random.default_rng(41)
    contacts = [c[:7] + (0.28, c[8]) for c in _random_contacts(rng, 40)]
    contacts = [c for c in contacts if table.step_values(*c) is not None][:12]
    contacts.append((1e-3, 0.0, 0.1, 8e4, 6e-3, 2.5e-4, 210e9, 0.28, 0.3))   # a0/b0 = 24
    cols = [np.array(v) for v in zip(*contacts)]
    res, jac = table.evaluate_contacts(*cols[:6], 210e9, 0.28, cols[8])
    assert res.shape == (len(contacts), 5) and jac.shape == (len(contacts), 3, 3)
    for k, c in enumerate(contacts[:-1]):
        want = table.step_values(*c)
        mu_n = c[3] * c[8]
        np.testing.assert_allclose(res[k, :2], want[:2], rtol=0, atol=1e-13 * mu_n)
        np.testing.assert_allclose(res[k, 3:], want[3:5], rtol=1e-13, atol=1e-13)
        np.testing.assert_allclose(jac[k].ravel(), want[5:], rtol=0,
                                   atol=1e-11 * max(abs(v) for v in want[5:]))
    far = table.creep_solution_3d(*contacts[-1])
    assert (res[-1, 0], res[-1, 1]) == pytest.approx((far.tx, far.ty), rel=1e-9)


@needs_table
def test_a_batch_of_changing_contacts_is_evaluated_in_any_order_alike():
    """From SORT_AFTER_POINTS points the reader evaluates changing contacts in the order of
    their a0/b0 (the table's outermost axis): the values are each point's own, bit for bit
    those of the same points shuffled and of a batch too small to be sorted."""
    import railcontact.exact_table as et

    table = ExactCreepTable.from_file(TABLE)
    rng = np.random.default_rng(57)
    n = et.SORT_AFTER_POINTS + 45
    xi, eta = rng.uniform(-4e-3, 4e-3, (2, n))
    phi = rng.uniform(-3.0, 3.0, n)
    a0 = rng.uniform(2e-3, 9e-3, n)
    whole = table.creep_solution_3d(*_args(xi, eta, phi, a0=a0))
    p = rng.permutation(n)
    shuffled = table.creep_solution_3d(*_args(xi[p], eta[p], phi[p], a0=a0[p]))
    for field in ("tx", "ty", "spin_moment", "stick_area_fraction", "sensitivity"):
        np.testing.assert_array_equal(getattr(shuffled, field), getattr(whole, field)[p],
                                      err_msg=field)
    m = et.SORT_AFTER_POINTS - 1            # (fewer points: in the order given)
    few = table.creep_solution_3d(*_args(xi[:m], eta[:m], phi[:m], a0=a0[:m]))
    np.testing.assert_array_equal(few.tx, whole.tx[:m])
    np.testing.assert_array_equal(few.sensitivity, whole.sensitivity[:m])


@needs_table
def test_the_sum_over_nu_is_made_once_per_machine(tmp_path, monkeypatch):
    """ExactCreepTable.prepare keeps the table summed over nu in the user cache: a second
    process maps it instead of summing again, and both hold the sum of the file's float32
    coefficients weighted by the cubic B-splines of the nu axis at nu (scipy's, an
    independent basis), on sampled a0/b0 planes."""
    import sys

    from scipy.interpolate import BSpline

    from railcontact import _table_store

    monkeypatch.setenv("RAILCONTACT_CACHE_DIR", str(tmp_path))
    monkeypatch.delitem(sys.modules, _table_store.REGISTRY_MODULE, raising=False)
    first = ExactCreepTable.from_file(TABLE)
    first.prepare(0.3)
    assert len(list((tmp_path / "tables").glob("*-nu-*.npy"))) == 1
    monkeypatch.delitem(sys.modules, _table_store.REGISTRY_MODULE)      # a new process
    monkeypatch.setattr(_table_store, "_write_entry",
                        lambda *a, **k: pytest.fail("the sum was made again"))
    second = ExactCreepTable.from_file(TABLE)
    second.prepare(0.3)
    a, b = first._nu_slabs[0.3][0], second._nu_slabs[0.3][0]
    assert isinstance(b.base, np.memmap) or isinstance(b, np.memmap)
    np.testing.assert_array_equal(a, b)
    t = first._knot_list[1]
    weights = BSpline.design_matrix([0.3], t, 3).toarray()[0]
    for plane in (0, 7, len(a) - 1):
        want = np.tensordot(weights, first._coef[plane].astype(np.float64), axes=(0, 0))
        np.testing.assert_allclose(b[plane, 0], want, rtol=0, atol=1e-12)
