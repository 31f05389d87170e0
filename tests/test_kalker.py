"""Tests of railcontact.kalker: table nodes, smoothness, asymptotes, nu = 0 symmetry."""

import numpy as np
import pytest

from railcontact import kalker_coefficients
from railcontact.kalker import kalker_asymptotes, kalker_table

# Nielsen (1998) Appendix B, nu = 0.25, typed from the thesis (rows a0/b0 = 0.1 and 0.2 are
# garbled by OCR; corrected values from the seed erratum list / Kalker 1990 Table E.3).
# Columns: a0/b0, C11, C22, C23. Published to 3 significant digits.
NIELSEN_APPENDIX_B = [
    (0.1, 3.31, 2.52, 0.473), (0.2, 3.37, 2.63, 0.603), (0.3, 3.44, 2.75, 0.715),
    (0.4, 3.53, 2.88, 0.823), (0.5, 3.62, 3.01, 0.929), (0.6, 3.72, 3.14, 1.03),
    (0.7, 3.81, 3.28, 1.14), (0.8, 3.91, 3.41, 1.25), (0.9, 4.01, 3.54, 1.36),
    (1 / 1.0, 4.12, 3.67, 1.47), (1 / 0.9, 4.22, 3.81, 1.59), (1 / 0.8, 4.36, 3.99, 1.75),
    (1 / 0.7, 4.54, 4.21, 1.95), (1 / 0.6, 4.78, 4.50, 2.23), (1 / 0.5, 5.10, 4.90, 2.62),
    (1 / 0.4, 5.57, 5.48, 3.24), (1 / 0.3, 6.34, 6.40, 4.32), (1 / 0.2, 7.78, 8.14, 6.63),
    (1 / 0.1, 11.7, 12.8, 14.6)]


def test_all_57_table_nodes_reproduced():
    g, nu, c = kalker_table()
    assert g.size == 19 and c.shape == (3, 3, 19)
    gg, nn = np.meshgrid(g, nu)
    got = np.array(kalker_coefficients(gg, nn))
    np.testing.assert_allclose(got, c, rtol=1e-12)


def test_nielsen_appendix_b_nu_025():
    rows = np.array(NIELSEN_APPENDIX_B)
    got = np.array(kalker_coefficients(rows[:, 0], 0.25)).T
    np.testing.assert_allclose(got, rows[:, 1:], rtol=1e-12)


def _derivatives(f, x, h):
    return ((f(x + h) - f(x - h)) / (2 * h), (f(x + h) - 2 * f(x) + f(x - h)) / h**2)


@pytest.mark.parametrize("nu", [0.0, 0.13, 0.25, 0.28, 0.45])
def test_c2_in_log_axis_ratio(nu):
    """First and second s-derivatives (s = ln a0/b0) are continuous at every knot and at the
    blend edges 0.1 and 10: one-sided difference quotients from the left and the right agree."""
    g, _, _ = kalker_table()
    knots = np.concatenate([np.log(g), [np.log(0.05), np.log(20.0)]])
    h = 1e-4
    for k in range(3):
        def f(s):
            return np.log(kalker_coefficients(np.exp(s), nu)[k])
        for s0 in knots:
            # derivative estimates centred slightly left and right of the knot
            d1_l, d2_l = _derivatives(f, s0 - 2 * h, h)
            d1_r, d2_r = _derivatives(f, s0 + 2 * h, h)
            assert d1_r == pytest.approx(d1_l, abs=1e-3)   # measured <= 4.3e-4
            # a jump in f'' would show up as O(1); continuity leaves O(h) * f''' ~ 1e-3
            assert d2_r == pytest.approx(d2_l, abs=1e-2)   # measured <= 1.7e-3; |f"| ~ 1


def test_smooth_in_nu():
    nus = np.linspace(0.0, 0.5, 101)
    for g in (0.07, 0.3, 1.0, 4.0, 15.0):
        c = np.array(kalker_coefficients(g, nus))
        second = np.diff(c, 2, axis=1)
        assert np.all(np.isfinite(c)) and np.all(c > 0)
        assert np.max(np.abs(np.diff(second, axis=1))) < 1e-4 * np.max(c)


def test_nu_zero_gives_c11_equal_c22():
    g = np.geomspace(0.01, 100, 301)
    c = kalker_coefficients(g, 0.0)
    np.testing.assert_array_equal(c.c11, c.c22)


def test_asymptotes():
    # far outside the table the blend has decayed onto Kalker's asymptotes (P ~ t -> 0)
    for nu in (0.0, 0.25, 0.5):
        for g in (1e-4, 1e4):
            c = np.array(kalker_coefficients(g, nu))
            a = np.array(kalker_asymptotes(g, nu))
            np.testing.assert_allclose(c, a, rtol=2e-3)
    # the asymptotes themselves (Kalker 1990 Table E.3, as coded in CONTACT's linrol) agree with
    # the table at its edges to within 6 % -- checks that the formulas were typed correctly
    g, nu, c = kalker_table()
    for j, n in enumerate(nu):
        for i in (0, -1):
            a = np.array(kalker_asymptotes(g[i], n))
            np.testing.assert_allclose(a, c[:, j, i], rtol=0.06)
    # strip-theory limit quoted by Nielsen Eq. (2.89): C11 -> pi^2 / (4 (1 - nu))
    assert kalker_asymptotes(1e-6, 0.3).c11 == pytest.approx(np.pi**2 / (4 * 0.7), rel=1e-14)


def test_blend_region_bounded_between_table_edge_and_asymptote():
    """Over 0.05..0.1 and 10..20 the result stays within 2 % of the band spanned by the
    table-edge value and the asymptote (the blend is a cubic in t, it may overshoot slightly)."""
    for nu in (0.0, 0.25, 0.5):
        for g_edge, gs in ((0.1, np.linspace(0.05, 0.1, 11)), (10.0, np.linspace(10, 20, 11))):
            edge = np.array(kalker_coefficients(g_edge, nu))
            for g in gs:
                c = np.array(kalker_coefficients(g, nu))
                a = np.array(kalker_asymptotes(g, nu))
                ratio_edge = edge / np.array(kalker_asymptotes(g_edge, nu))
                ratio = c / a
                lo = np.minimum(ratio_edge, 1.0) * 0.98
                hi = np.maximum(ratio_edge, 1.0) * 1.02
                assert np.all((ratio >= lo) & (ratio <= hi))


def test_vectorised_equals_scalar():
    rng = np.random.default_rng(1)
    g = np.exp(rng.uniform(np.log(0.05), np.log(20), 50))
    nu = rng.uniform(0, 0.5, 50)
    vec = np.array(kalker_coefficients(g, nu))
    for i in range(0, 50, 7):
        assert np.array_equal(np.array(kalker_coefficients(g[i], nu[i])), vec[:, i])
    assert np.shape(kalker_coefficients(g[:, None], nu[None, :5]).c11) == (50, 5)


@pytest.mark.parametrize("g,nu,name", [(0.0, 0.25, "a0_over_b0"), (np.nan, 0.25, "a0_over_b0"),
                                       (1.0, 0.6, "poisson_ratio"), (1.0, -0.1, "poisson_ratio"),
                                       (np.inf, 0.2, "a0_over_b0")])
def test_errors(g, nu, name):
    with pytest.raises(ValueError, match=name):
        kalker_coefficients(g, nu)


def test_extreme_axis_ratios_finite_or_clear_error():
    """a0/b0 anywhere in (0, 1e100]: finite coefficients; towards 0 they reach Kalker's limits
    C11 = pi^2 / (4 (1 - nu)), C22 = pi^2 / 4 (Kalker 1990, Table E.3; ln(16/g) overflowed for
    g < 1e-307 and gave C23 = inf). Beyond 1e100 a ValueError (C23 ~ g^1.5 overflows by
    ~1e205; g = 1e300 gave (0, 0, NaN))."""
    nu = 0.28
    c = kalker_coefficients([5e-324, 1e-300, 1e50, 1e100], nu)
    assert all(np.all(np.isfinite(v)) and np.all(np.asarray(v) > 0.0) for v in c)
    assert c.c11[:2] == pytest.approx(np.pi**2 / (4 * (1 - nu)), rel=1e-12)
    assert c.c22[:2] == pytest.approx(np.pi**2 / 4, rel=1e-12)
    with pytest.raises(ValueError, match=r"a0_over_b0 must be in \(0, 1e\+100\] \[-\]; got "
                                         r"1e\+300"):
        kalker_coefficients(1e300, nu)
    with pytest.raises(ValueError, match=r"a0_over_b0 must be in \(0, 1e\+100\]"):
        kalker_asymptotes(1e300, nu)


def test_the_shipped_spline_is_scipys_fit_of_the_shipped_table():
    """data/kalker_spline.npz (read at run time without scipy) holds exactly what scipy's
    CubicSpline fits to kalker_coefficients.csv now (else: kalker.write_spline_data())."""
    import hashlib

    import numpy as np

    from railcontact import kalker
    from railcontact._files import package_directory

    x, c = kalker.fit_spline()
    with np.load(package_directory() / "data" / kalker.SPLINE_DATA) as data:
        np.testing.assert_array_equal(data["x"], x)
        np.testing.assert_array_equal(data["c"], c)
        csv = package_directory() / "data" / "kalker_coefficients.csv"
        assert str(data["table_sha256"]) == hashlib.sha256(csv.read_bytes()).hexdigest()


def test_the_spline_evaluates_as_scipys_with_its_derivatives():
    import numpy as np
    from scipy.interpolate import CubicSpline

    from railcontact import kalker

    g, _, c = kalker_table()
    ref = CubicSpline(np.log(g), np.log(np.moveaxis(c, -1, 0)), axis=0, bc_type="not-a-knot")
    ours = kalker._spline()
    s = np.r_[np.log(g), np.random.default_rng(3).uniform(np.log(0.05), np.log(20.0), 200)]
    for nu in (0, 1, 2):
        want = ref(s, nu)
        np.testing.assert_allclose(ours(s, nu), want, rtol=1e-13,
                                   atol=1e-13 * np.abs(want).max())
    assert ours(0.3).shape == (3, 3)


def test_the_creep_paths_need_no_scipy():
    """Kalker's coefficients (and so the creep theories and the exact table's contact) come
    from the shipped spline: a fresh interpreter evaluates them without importing scipy."""
    import subprocess
    import sys

    code = ("import sys, railcontact as rc; rc.kalker_coefficients(0.7, 0.28); "
            "rc.creep_force_3d(1e-3, 0.0, 0.0, normal_load=1e5, a0=6e-3, b0=4e-3, "
            "youngs_modulus=2.1e11, poisson_ratio=0.28, friction_coefficient=0.3); "
            "print('scipy' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], check=True, capture_output=True,
                         text=True).stdout.strip()
    assert out == "False"
