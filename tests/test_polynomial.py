"""Tests of railcontact.polynomial (Nielsen 1998, Ch. 3, App. D).

Independent checks used here:
* adaptive quadrature of the principal-value integral (3.4): scipy ``quad(weight='cauchy')`` in
  the angle variable, and mpmath tanh-sinh at 40 digits with the pole subtracted;
* [A][A]^-1 = I, [D(d)][D(-d)] = I, direct polynomial evaluation;
* Hertz (2.40)-(2.42) and Carter (2.51)-(2.54) limits;
* the discretised 2-D half-space solver ``railcontact.reference.halfspace2d`` on a 4th-order gap.
"""

import mpmath as mp
import numpy as np
import pytest
from scipy import integrate

from railcontact import polynomial as P
from railcontact.reference.halfspace2d import solve_normal_2d, solve_rolling_2d

pytestmark = pytest.mark.filterwarnings("ignore::scipy.integrate.IntegrationWarning")

E, NU, R, N = 2.1e11, 0.28, 0.5, 2e5
K = 4 * (1 - NU**2) / (np.pi * E)


# ---------------------------------------------------------------------------------------------
# independent quadratures of (3.4), normalised a = 1:  PV int_-1^1 P(z) / ((s - z) sqrt(1-z^2)) dz
# z = cos(t):  PV int_0^pi P(cos t) / (s - cos t) dt
# ---------------------------------------------------------------------------------------------
def pv_scipy(coef, s):
    f = np.polynomial.Polynomial(coef)
    if abs(s) > 1:
        return integrate.quad(lambda t: f(np.cos(t)) / (s - np.cos(t)), 0, np.pi,
                              epsabs=0, epsrel=2e-14, limit=200)[0]
    t0 = np.arccos(s)

    # s - cos t = 2 sin((t+t0)/2) sin((t-t0)/2); h = P(cos t) (t - t0) / (s - cos t), smooth
    def h(t):
        return f(np.cos(t)) / (np.sin(0.5 * (t + t0)) * np.sinc((t - t0) / (2 * np.pi)))

    return integrate.quad(h, 0, np.pi, weight="cauchy", wvar=t0, epsabs=0, epsrel=2e-14,
                          limit=200)[0]


def pv_mpmath(coef, s, dps=40):
    with mp.workdps(dps):
        c = [mp.mpf(float(v)) for v in coef]
        s = mp.mpf(s)

        def f(t):
            return mp.polyval(c, mp.cos(t), asc=True)

        if abs(s) > 1:
            return float(mp.quad(lambda t: f(t) / (s - mp.cos(t)), [0, mp.pi]))
        t0 = mp.acos(s)

        def g(t):  # smooth: f (t - t0) / (s - cos t)
            return f(t) / (mp.sin((t + t0) / 2) * mp.sinc((t - t0) / 2))

        g0 = g(t0)
        reg = mp.quad(lambda t: (g(t) - g0) / (t - t0), [0, t0, mp.pi])
        return float(reg + g0 * mp.log((mp.pi - t0) / t0))


# ---------------------------------------------------------------------------------------------
# transform coefficients, matrices (3.6)-(3.13)
# ---------------------------------------------------------------------------------------------
@pytest.mark.parametrize("n", range(0, 13))
def test_transform_matrix_columns_match_cauchy_quadrature(n):
    """Each monomial z^n through (3.4): [A] (with the (k!)^2 erratum fix) vs scipy QAWC."""
    coef = np.zeros(n + 1)
    coef[n] = 1.0
    for s in (-0.93, -0.4, 0.0, 0.17, 0.71, 0.995, 1.0005, 1.3, -2.5, 40.0):
        got = P.principal_value_integral(coef, s)
        ref = pv_scipy(coef, s)
        assert got == pytest.approx(ref, rel=1e-12, abs=1e-12 * np.pi)


def test_outside_strip_stable_against_cancellation():
    """Hard case: (3.4) evaluated literally outside the strip cancels like |s|^N (4.5e-11 at
    s = -2.5, N = 12; total loss at N = 40, s = 5); the Chebyshev form used stays at 1e-13."""
    for n, s in ((12, -2.5), (40, 5.0), (25, 1.01)):
        coef = np.zeros(n + 1)
        coef[n] = 1.0
        ref = pv_mpmath(coef, s)
        literal = (np.polynomial.polynomial.polyval(s, P.transform_matrix(n) @ coef[1:])
                   + np.sign(s) * np.pi / np.sqrt(s * s - 1) * s**n)
        got = P.principal_value_integral(coef, s)
        assert got == pytest.approx(ref, rel=1e-13)
        if n >= 12 and abs(s) > 2:
            assert abs(literal - ref) > 1e-12 * abs(ref)


def test_erratum_single_factorial_is_wrong():
    """The printed (3.10) with (2k)!/k! disagrees with quadrature by O(1) (seed erratum 1)."""
    coef = np.zeros(6)
    coef[5] = 1.0  # z^5 -> beta_0 = A_2
    ref = pv_scipy(coef, 0.0)
    printed = -np.pi * 24 / 2 * (0.5) ** 4  # (2k)!/k! (a/2)^2k with k = 2, a = 1
    assert abs(printed - ref) > 0.5
    assert P.transform_coefficients(3)[2] == pytest.approx(ref, rel=1e-13)


def test_physical_half_width_scaling_matches_quadrature():
    a = 3.7e-3
    rng = np.random.default_rng(1)
    coef = rng.normal(size=7)
    x = 0.3 * a
    # int over [-a, a] of B(z)/((x-z) sqrt(a^2-z^2)) = (1/a) int over s of b(s)/(...)
    b = coef * a ** np.arange(7)
    assert P.principal_value_integral(coef, x, a) == pytest.approx(pv_scipy(b, x / a) / a,
                                                                   rel=1e-12)


@pytest.mark.parametrize("degree,a", [(1, 1.0), (6, 1.0), (7, 2.5e-3), (40, 1.0), (201, 1.0),
                                      (25, 0.3)])
def test_inverse_matrix_is_inverse(degree, a):
    ident = P.transform_matrix(degree, a) @ P.inverse_transform_matrix(degree, a)
    assert np.abs(ident - np.eye(degree)).max() < 1e-13


@pytest.mark.parametrize("degree", [30, 100])
def test_high_degree_agrees_with_mpmath(degree):
    """Normalised [A] at high degree vs 40-digit quadrature: no loss of accuracy (1e-12)."""
    rng = np.random.default_rng(degree)
    coef = rng.normal(size=degree + 1) / np.sqrt(np.arange(1, degree + 2))
    for s in (-0.6, 0.35, 0.9):
        got = P.principal_value_integral(coef, s)
        ref = pv_mpmath(coef, s)
        assert got == pytest.approx(ref, rel=1e-12, abs=1e-12)


def test_physical_units_underflow_at_high_degree():
    """Documented conditioning limit: a = 5 mm, (a/2)^(2k) underflows; normalised does not."""
    coef = P.transform_coefficients(200, 5e-3)
    assert coef[-1] == 0.0  # underflow in physical units (k = 199: 2.5e-3^398)
    assert np.all(P.transform_coefficients(200) < 0)  # normalised: all finite, O(k^-1/2)


def test_force_vector_matches_quadrature():
    rng = np.random.default_rng(7)
    coef = rng.normal(size=9)
    a = 0.8
    ref = integrate.quad(lambda t: np.polynomial.polynomial.polyval(a * np.cos(t), coef), 0,
                         np.pi, epsabs=0, epsrel=2e-14)[0]
    assert P.polynomial_form_force(coef, a) == pytest.approx(ref, rel=1e-13)
    assert -P.force_vector(8, a) @ coef == pytest.approx(ref, rel=1e-13)


def test_moment_ratios_exact():
    from math import comb
    c = P.moment_ratios(60)
    exact = np.array([comb(2 * k, k) / 4.0**k for k in range(60)])
    np.testing.assert_allclose(c, exact, rtol=1e-14)


# ---------------------------------------------------------------------------------------------
# base change (3.17)-(3.22)
# ---------------------------------------------------------------------------------------------
def test_base_change_matches_direct_evaluation_and_inverse():
    rng = np.random.default_rng(3)
    g = rng.normal(size=6)
    d = 0.37
    gamma = P.base_change_matrix(5, d) @ g
    x = np.linspace(-1, 1, 11)
    np.testing.assert_allclose(np.polynomial.polynomial.polyval(x, gamma),
                               np.polynomial.polynomial.polyval(x + d, g), rtol=1e-13, atol=1e-13)
    ident = P.base_change_matrix(5, d) @ P.base_change_matrix(5, -d)  # (3.22)
    np.testing.assert_allclose(ident, np.eye(6), atol=1e-14)


@pytest.mark.parametrize("degree,tol", [(10, 1e-12), (30, 1e-9)])
def test_base_change_conditioning(degree, tol):
    """Shift by a full half-width (|d| = 1 normalised): error grows ~ 2^N eps (measured)."""
    rng = np.random.default_rng(degree)
    g = rng.normal(size=degree + 1)
    gamma = P.base_change_matrix(degree, 1.0) @ g
    x = np.linspace(-1, 0, 7)
    with mp.workdps(50):
        exact = np.array([float(mp.polyval([mp.mpf(v) for v in g], mp.mpf(xx) + 1, asc=True))
                          for xx in x])
    err = np.abs(np.polynomial.polynomial.polyval(x, gamma) - exact).max() / np.abs(g).sum()
    assert err < tol


# ---------------------------------------------------------------------------------------------
# normal problem (3.27)-(3.29)
# ---------------------------------------------------------------------------------------------
def test_normal_hertz_limit():
    nc = P.solve_normal_polynomial([0.0, 0.0, 1 / (2 * R)], N, E, NU)
    a0 = np.sqrt(8 * (1 - NU**2) * R * N / (np.pi * E))
    assert nc.half_width == pytest.approx(a0, rel=1e-12)
    assert nc.centre == pytest.approx(0.0, abs=1e-15)
    assert nc.pressure(0.0) == pytest.approx(2 * N / (np.pi * a0), rel=1e-12)


def test_normal_shifted_and_tilted_hertz():
    """Z = (X - X0)^2 / 2R + const: same a, centre at X0 (rigid shift handled by [D])."""
    x0 = 3e-3
    z = [x0**2 / (2 * R) + 1e-5, -x0 / R, 1 / (2 * R)]
    nc = P.solve_normal_polynomial(z, N, E, NU)
    a0 = np.sqrt(8 * (1 - NU**2) * R * N / (np.pi * E))
    assert nc.half_width == pytest.approx(a0, rel=1e-11)
    assert nc.centre == pytest.approx(x0, rel=1e-10)


def test_normal_quartic_only_closed_form():
    """Z = l4 X^4 / 24: a = (8 N~ / l4)^(1/4) (Table 6.1 B, last row; derived independently:
    B_4 = -l4/(6 pi), B_2 = -a^2 l4/(12 pi), load from the Chebyshev moments)."""
    l4 = 3e4
    nc = P.solve_normal_polynomial([0, 0, 0, 0, l4 / 24], N, E, NU, centre_guess=0.0)
    n_tilde = N / (np.pi * E / (8 * (1 - NU**2)))
    assert nc.half_width == pytest.approx((8 * n_tilde / l4) ** 0.25, rel=1e-11)


@pytest.fixture(scope="module")
def quartic():
    z4 = np.array([0.0, 0.0, 1 / (2 * R), 300.0, 2e5])
    return z4, P.solve_normal_polynomial(z4, N, E, NU)


def test_normal_quartic_slope_condition_by_quadrature(quartic):
    """The solved pressure reproduces dZ/dX inside the patch (quadrature of (3.28))."""
    z4, nc = quartic
    a, d = nc.half_width, nc.centre
    for s in (-0.8, -0.2, 0.5, 0.93):
        slope = K / a * pv_scipy(nc.normalised_coefficients, s)
        dz = np.polynomial.polynomial.polyval(d + a * s, np.polynomial.polynomial.polyder(z4))
        assert slope == pytest.approx(dz, rel=1e-11)
    load = integrate.quad(nc.pressure, d - a, d + a, epsabs=0, epsrel=1e-12, limit=200)[0]
    assert load == pytest.approx(N, rel=1e-9)
    assert nc.pressure(d - a * 0.999999) >= 0 and nc.pressure(d + a * 0.999999) >= 0


def test_normal_quartic_against_reference_solver(quartic):
    """4th-order gap vs the discretised half-space (exact log-kernel elements), 800 elements:
    a and the centre to 1e-3 relative (measured 4e-4 / 1e-3 of a); pressure to 1 % of p_max in
    the interior."""
    z4, nc = quartic
    ref = solve_normal_2d(lambda x: np.polynomial.polynomial.polyval(x, z4), N, E, NU,
                          -1.6e-3, 1.4e-3, 800)
    a_ref = 0.5 * (ref.contact_end - ref.contact_start)
    c_ref = 0.5 * (ref.contact_end + ref.contact_start)
    assert nc.half_width == pytest.approx(a_ref, rel=1e-3)
    assert abs(nc.centre - c_ref) < 1e-3 * nc.half_width
    interior = np.abs(ref.x - nc.centre) < 0.9 * nc.half_width
    p = nc.pressure(ref.x)
    assert np.abs(p - ref.pressure)[interior].max() < 0.01 * p.max()


def test_normal_nonconvex_raises():
    with pytest.raises(ValueError, match="gap_coefficients"):
        P.solve_normal_polynomial([0, 0, -1.0], N, E, NU)
    with pytest.raises(ValueError, match="normal_load"):
        P.solve_normal_polynomial([0, 0, 1.0], -1.0, E, NU)
    with pytest.raises(ValueError, match="poisson_ratio"):
        P.solve_normal_polynomial([0, 0, 1.0], N, E, 0.6)
    with pytest.raises(ValueError, match="gap_coefficients"):
        P.solve_normal_polynomial([0, 1.0], N, E, NU)


def test_bad_inputs_raise():
    with pytest.raises(ValueError, match="degree"):
        P.transform_matrix(0)
    with pytest.raises(ValueError, match="degree"):
        P.transform_matrix(2.5)
    with pytest.raises(ValueError, match="half_width"):
        P.inverse_transform_matrix(3, -1.0)
    with pytest.raises(ValueError, match="shift"):
        P.base_change_matrix(3, np.nan)
    with pytest.raises(ValueError, match="pressure_coefficients"):
        P.normal_contact_from_coefficients([1.0, 0.0, 0.0], 1e-3, E, NU)  # BC violated


# ---------------------------------------------------------------------------------------------
# tangential problem (3.30)-(3.44)
# ---------------------------------------------------------------------------------------------
def test_tangential_carter_limit():
    nc = P.solve_normal_polynomial([0, 0, 1 / (2 * R)], N, E, NU)
    mu = 0.3
    xi_c = mu * nc.half_width / R  # (2.54)
    for frac in (0.0, 0.1, 0.5, 0.9, 1.0, 1.5):
        t = P.solve_tangential_polynomial(nc, mu, creepage=-frac * xi_c)
        r = max(0.0, 1 - frac)
        assert t.stick_ratio == pytest.approx(r, abs=1e-12)
        assert t.tangential_force == pytest.approx(mu * N * (1 - r**2), rel=1e-11, abs=1e-9)
    t = P.solve_tangential_polynomial(nc, mu, tangential_force=-0.75 * mu * N)
    assert t.creepage == pytest.approx(0.5 * xi_c, rel=1e-11)


def test_tangential_stick_condition_by_quadrature(quartic):
    """In the stick zone the slip xi + K PV int q/(x - z) dz vanishes (independent quadrature)."""
    _, nc = quartic
    mu = 0.3
    t = P.solve_tangential_polynomial(nc, mu, creepage=-3e-4)
    a, r = nc.half_width, t.stick_ratio
    assert 0.05 < r < 0.95
    for u in (-0.9, 0.0, 0.7):
        x = t.stick_centre + u * t.stick_half_width
        pv1 = pv_scipy(nc.normalised_coefficients, (x - nc.centre) / a) / a
        # stick part: int Q2 / (x - z) with Q2 = sum e_n s*^n / (a sqrt(r^2 - s*^2)); scale to r
        e_scaled = t.stick_coefficients * r ** np.arange(nc.degree + 1)
        pv2 = pv_scipy(e_scaled, u) / (a * r)
        slip = t.creepage + K * (-np.sign(t.creepage)) * mu * (pv1 + pv2)
        assert abs(slip) < 1e-10 * abs(t.creepage)


def test_tangential_traction_bounded_and_force_integral(quartic):
    _, nc = quartic
    mu = 0.3
    t = P.solve_tangential_polynomial(nc, mu, creepage=-3e-4)
    x = nc.centre + nc.half_width * np.cos(np.linspace(0.001, np.pi - 0.001, 400))
    q = t.traction(x)
    assert np.all(np.abs(q) <= mu * nc.pressure(x) * (1 + 1e-9) + 1e-6)
    force = integrate.quad(t.traction, nc.centre - nc.half_width, nc.centre + nc.half_width,
                           points=[t.stick_centre - t.stick_half_width], limit=400,
                           epsrel=1e-10)[0]
    assert force == pytest.approx(t.tangential_force, rel=1e-7)


def test_tangential_against_reference_solver(quartic):
    """Creep force on the 4th-order profile vs the discretised rolling solver fed the same
    pressure. The element solution converges O(1/n); Richardson from n = 300/600 agrees with
    the polynomial approach to 2e-4 relative (measured ~1e-5); stick edge to 2e-3 a."""
    _, nc = quartic
    mu = 0.3
    a = nc.half_width
    for xi in (-2e-4, -6e-4):
        t = P.solve_tangential_polynomial(nc, mu, creepage=xi)
        f = []
        for n in (300, 600):
            x = nc.centre + np.linspace(-a, a, n + 1)
            x = 0.5 * (x[1:] + x[:-1])
            rr = solve_rolling_2d(x, nc.pressure(x), E, NU, creepage=xi, friction=mu)
            f.append(rr.tangential_force / rr.normal_load)
        extrap = 2 * f[1] - f[0]
        assert extrap == pytest.approx(t.tangential_force / N, rel=2e-4)
        assert abs(rr.stick_start - (t.stick_centre - t.stick_half_width)) < 2e-3 * a


def test_creep_curve_odd_and_saturates(quartic):
    _, nc = quartic
    mu = 0.3
    xi_c = -P.tangential_state_polynomial(nc, mu, 0.0)[0]
    xi = np.array([-2 * xi_c, -0.5 * xi_c, 0.0, 0.5 * xi_c, 2 * xi_c])
    t = P.creep_curve_polynomial(nc, mu, xi)
    assert t[0] == pytest.approx(mu * N) and t[-1] == pytest.approx(-mu * N)
    assert t[1] == pytest.approx(-t[3]) and t[2] == 0.0
    # initial slope by finite differences vs. the stick-ratio derivative: dT/dxi < 0 and |T| grows
    xs, ts = P.tangential_state_polynomial(nc, mu, np.linspace(1, 0, 50))
    assert np.all(np.diff(xs) < 0) and np.all(np.diff(ts) > 0)  # branch xi <= 0, T >= 0


def test_tangential_bad_inputs():
    nc = P.solve_normal_polynomial([0, 0, 1 / (2 * R)], N, E, NU)
    with pytest.raises(ValueError, match="creepage"):
        P.solve_tangential_polynomial(nc, 0.3)
    with pytest.raises(ValueError, match="tangential_force"):
        P.solve_tangential_polynomial(nc, 0.3, tangential_force=0.31 * N)
    with pytest.raises(ValueError, match="friction_coefficient"):
        P.solve_tangential_polynomial(nc, -0.1, creepage=1e-4)
    with pytest.raises(ValueError, match="normal_contact"):
        P.solve_tangential_polynomial(None, 0.3, creepage=1e-4)
    with pytest.raises(ValueError, match="stick_ratio"):
        P.tangential_state_polynomial(nc, 0.3, 1.2)


def test_high_degree_normal_and_tangential_converge():
    """Hard case, large degree: gap (cosh(k X) - 1)/k^2 truncated at N = 24 and N = 40 (k a ~
    2.3): the normal and tangential answers converge and agree to 1e-13 (no loss of accuracy
    from [A]^-1 or the base change [D] at these degrees; see benchmarks/bench_polynomial.py)."""
    from math import factorial
    kappa = 2000.0

    def gap(n):
        z = np.zeros(n + 1)
        for j in range(2, n + 1, 2):
            z[j] = kappa ** (j - 2) / factorial(j)
        return z

    res = []
    for n in (24, 40):
        nc = P.solve_normal_polynomial(gap(n), N, E, NU, centre_guess=0.0)
        xi, t = P.tangential_state_polynomial(nc, 0.3, 0.5)
        res.append((nc.half_width, float(xi), float(t)))
    np.testing.assert_allclose(res[0], res[1], rtol=1e-13)
    # and the truncation at N = 8 is visibly different (the high-order terms matter)
    nc8 = P.solve_normal_polynomial(gap(8), N, E, NU, centre_guess=0.0)
    assert abs(nc8.half_width / res[1][0] - 1) > 1e-5


def test_normal_contact_from_coefficients_hertz_and_admissible():
    """A given Hertz pressure (b = p0 a [1, 0, -1]) wrapped and rolled: Carter, admissible."""
    a0 = np.sqrt(8 * (1 - NU**2) * R * N / (np.pi * E))
    p0 = 2 * N / (np.pi * a0)
    nc = P.normal_contact_from_coefficients([p0 * a0, 0.0, -p0 * a0], a0, E, NU, centre=1e-3,
                                            normalised=True)
    assert nc.normal_load == pytest.approx(N, rel=1e-14)
    assert nc.pressure(1e-3) == pytest.approx(p0, rel=1e-14)
    phys = P.normal_contact_from_coefficients(nc.coefficients, a0, E, NU, centre=1e-3)
    np.testing.assert_allclose(phys.normalised_coefficients, nc.normalised_coefficients,
                               rtol=1e-14)
    t = P.solve_tangential_polynomial(nc, 0.3, creepage=-0.4 * 0.3 * a0 / R)
    assert t.stick_ratio == pytest.approx(0.6, rel=1e-12) and t.is_admissible
    assert t.stick_centre == pytest.approx(1e-3 + 0.4 * a0, rel=1e-12)


@pytest.mark.parametrize("frac", [1e-3, 0.99e-4, 1.01e-4, 1e-10, 1e-14, 1e-20, 1e-300])
def test_tiny_creepage_relative_accuracy(frac):
    """Hard case: |xi| << xi_c. N + force2 cancels as a* -> a; below 1e-4 xi_c the state comes
    from the exact Taylor series about full stick (FFT of the polynomials in a*/a). Carter:
    T = mu N (2 f - f^2) for xi = -f xi_c, to 1e-12 relative down to 1e-300."""
    nc = P.solve_normal_polynomial([0.0, 0.0, 1.0], 2e5, E, NU)
    xi_c = -float(P.tangential_state_polynomial(nc, 0.3, 0.0)[0])
    t = P.solve_tangential_polynomial(nc, 0.3, creepage=-frac * xi_c)
    assert t.tangential_force == pytest.approx(0.3 * 2e5 * (2 * frac - frac * frac), rel=1e-12)
    back = P.solve_tangential_polynomial(nc, 0.3, tangential_force=t.tangential_force)
    assert back.creepage == pytest.approx(-frac * xi_c, rel=1e-12)


def test_initial_slope_is_a_over_k_for_any_pressure(quartic):
    """Generalises (6.41): dT/dxi -> -a / K = -(pi E / (4 (1-nu^2))) a at full stick for any
    polynomial-form pressure (the full-stick problem does not involve p). Checked on the
    4th-order profile with the series and with a finite difference of the closed path."""
    _, nc = quartic
    xi = -1e-9
    t = P.solve_tangential_polynomial(nc, 0.3, creepage=xi)
    assert t.tangential_force / xi == pytest.approx(-nc.half_width / K, rel=1e-6)
    xs, ts = P.tangential_state_polynomial(nc, 0.3, np.array([1 - 2e-4, 1 - 1e-4]))
    slope = 2 * ts[1] / xs[1] - ts[0] / xs[0]  # Richardson on the chord from (0, 0)
    assert slope == pytest.approx(-nc.half_width / K, rel=1e-6)
