"""Tests of railcontact.hertz against independent computations.

* 2-D: the pressure (2.40)-(2.42) is put back into the integral equation (2.39), whose Cauchy
  principal value is evaluated by QUADPACK (scipy.integrate.quad, weight="cauchy"); and force
  balance by quadrature.
* 3-D: the Boussinesq displacement of the returned Hertz pressure is integrated numerically
  (polar coordinates around the field point, the radial integral in closed form, the angular one
  by the trapezoidal rule, which converges exponentially for this periodic integrand); the
  surface must then follow ``delta - A' x^2 - B' y^2`` inside the ellipse.
"""

import numpy as np
import pytest
from scipy.integrate import quad

from railcontact import (axis_ratio_from_curvature_ratio, curvature_ratio_from_axis_ratio,
                         hertz_2d, hertz_3d)

E, NU = 210e9, 0.3
E_STAR = E / (2 * (1 - NU**2))


# ---------------------------------------------------------------- 2-D
def test_2d_satisfies_integral_equation_2_39():
    n_load, radius = 1.2e6, 0.45
    a0, p0 = hertz_2d(n_load, radius, E, NU)
    for x in (-0.7 * a0, -0.2 * a0, 0.35 * a0, 0.9 * a0):
        # PV int p(z)/(x - z) dz = -PV int p(z)/(z - x) dz ; quad's cauchy weight is 1/(z - x)
        pv, _ = quad(lambda z: p0 / a0 * np.sqrt(a0**2 - z**2), -a0, a0, weight="cauchy",
                     wvar=x, epsabs=0, epsrel=1e-12, limit=200)
        lhs = 4 * (1 - NU**2) / (np.pi * E) * (-pv)
        assert lhs == pytest.approx(x / radius, rel=1e-9)


def test_2d_force_balance():
    n_load, radius = 8e5, 0.6
    a0, p0 = hertz_2d(n_load, radius, E, NU)
    total, _ = quad(lambda x: p0 * np.sqrt(1 - (x / a0) ** 2), -a0, a0, epsrel=1e-12)
    assert total == pytest.approx(n_load, rel=1e-9)


def test_2d_contact_reference_pmax():
    # CONTACT carter2d example (Vollebregt, Apache-2.0): a = 1 mm, R = 500 mm, G = 82000 N/mm^2,
    # nu = 0.28 -> PMAX = 113.9 N/mm^2 (carter2d.ref_out). Load per unit length from a0:
    nu, g = 0.28, 82e9
    e_mod = 2 * g * (1 + nu)
    n_load = (1e-3) ** 2 * np.pi * e_mod / (8 * (1 - nu**2) * 0.5)
    a0, p0 = hertz_2d(n_load, 0.5, e_mod, nu)
    assert a0 == pytest.approx(1e-3, rel=1e-12)
    assert p0 == pytest.approx(113.9e6, rel=5e-4)


def test_2d_zero_load_and_vectorised():
    a0, p0 = hertz_2d(0.0, 0.5, E, NU)
    assert a0 == 0 and p0 == 0
    loads = np.array([1e5, 5e5, 1e6])
    a_vec, p_vec = hertz_2d(loads, 0.5, E, NU)
    for i, n in enumerate(loads):
        a_s, p_s = hertz_2d(n, 0.5, E, NU)
        assert a_vec[i] == a_s and p_vec[i] == p_s


@pytest.mark.parametrize("name,args", [
    ("normal_load", (-1.0, 0.5, E, NU)), ("radius", (1e5, 0.0, E, NU)),
    ("youngs_modulus", (1e5, 0.5, np.nan, NU)), ("poisson_ratio", (1e5, 0.5, E, 0.5)),
    ("normal_load", (np.inf, 0.5, E, NU))])
def test_2d_errors(name, args):
    with pytest.raises(ValueError, match=name):
        hertz_2d(*args)


# ---------------------------------------------------------------- 3-D
def _displacement(x, y, a0, b0, p0, n_theta=4096):
    """Boussinesq: u(x,y) = 1/(pi E*) int int p / r dA for the Hertz pressure (independent)."""
    theta = np.linspace(0.0, 2 * np.pi, n_theta, endpoint=False)
    c, s = np.cos(theta), np.sin(theta)
    # p(x + rho c, y + rho s) = p0 sqrt(alpha - 2 beta rho - gamma rho^2)
    alpha = 1 - (x / a0) ** 2 - (y / b0) ** 2
    beta = x * c / a0**2 + y * s / b0**2
    gamma = (c / a0) ** 2 + (s / b0) ** 2
    # sqrt(gamma) sqrt(R^2 - (rho - m)^2) with m = -beta/gamma, R^2 = alpha/gamma + m^2
    m = -beta / gamma
    big_r = np.sqrt(alpha / gamma + m**2)
    v_lo, v_hi = -m, big_r                   # rho from 0 to the positive root m + R

    def prim(v):
        return 0.5 * v * np.sqrt(np.maximum(big_r**2 - v**2, 0)) + 0.5 * big_r**2 * np.arcsin(
            np.clip(v / big_r, -1, 1))

    radial = np.sqrt(gamma) * (prim(v_hi) - prim(v_lo))
    return p0 * radial.mean() * 2 * np.pi / (np.pi * E_STAR)


@pytest.mark.parametrize("ratio", [0.05, 0.3, 1.0, 2.5, 20.0])
def test_3d_displacement_matches_gap(ratio):
    """Numerical Boussinesq integral of the returned pressure reproduces A' x^2 + B' y^2."""
    a_curv = 2.0                                    # A' [1/m]
    b_curv = a_curv * curvature_ratio_from_axis_ratio(ratio)
    n_load = 1e5
    a0, b0, p0 = hertz_3d(n_load, a_curv, b_curv, E, NU)
    assert a0 / b0 == pytest.approx(ratio, rel=1e-12)
    assert p0 == pytest.approx(1.5 * n_load / (np.pi * a0 * b0), rel=1e-14)
    u0 = _displacement(0, 0, a0, b0, p0)
    for fx, fy in ((0.5, 0.0), (0.0, 0.6), (0.4, -0.5), (-0.8, 0.1)):
        x, y = fx * a0, fy * b0
        gap = a_curv * x**2 + b_curv * y**2
        assert u0 - _displacement(x, y, a0, b0, p0) == pytest.approx(gap, rel=1e-7)


def test_3d_circle_matches_johnson():
    # Johnson (1985) Eq. (3.68): a^3 = 3 N R / (4 E*), R = 1/(2 A')
    n_load, radius = 1e5, 0.45
    a0, b0, p0 = hertz_3d(n_load, 1 / (2 * radius), 1 / (2 * radius), E, NU)
    assert a0 == pytest.approx((3 * n_load * radius / (4 * E_STAR)) ** (1 / 3), rel=1e-14)
    assert b0 == a0
    assert p0 == pytest.approx(1.5 * n_load / (np.pi * a0**2), rel=1e-14)


def test_3d_elliptic_integral_form():
    """f(k) via Carlson R_D equals the textbook [(a/b)^2 E(e) - K(e)] / [K(e) - E(e)]."""
    from scipy.special import ellipe, ellipk
    for ratio in (1.3, 2.0, 5.0, 20.0):
        m = 1 - 1 / ratio**2
        textbook = (ratio**2 * ellipe(m) - ellipk(m)) / (ellipk(m) - ellipe(m))
        assert curvature_ratio_from_axis_ratio(ratio) == pytest.approx(textbook, rel=1e-12)
        assert curvature_ratio_from_axis_ratio(1 / ratio) == pytest.approx(1 / textbook,
                                                                          rel=1e-12)


def test_3d_round_trip_and_vectorised():
    ratios = np.geomspace(0.05, 20, 41)
    curv = curvature_ratio_from_axis_ratio(ratios)
    assert np.all(np.diff(curv) > 0)
    np.testing.assert_allclose(axis_ratio_from_curvature_ratio(curv), ratios, rtol=1e-12)
    a0, b0, p0 = hertz_3d(5e4, 1.0, curv, E, NU)
    np.testing.assert_allclose(a0 / b0, ratios, rtol=1e-12)
    for i in (0, 17, 40):
        single = hertz_3d(5e4, 1.0, curv[i], E, NU)
        assert single.a0 == a0[i] and single.b0 == b0[i] and single.p0 == p0[i]
    assert curvature_ratio_from_axis_ratio(1.0) == 1.0


def test_3d_load_scaling_and_zero_load():
    one = hertz_3d(1e5, 1.0, 3.0, E, NU)
    eight = hertz_3d(8e5, 1.0, 3.0, E, NU)
    assert eight.a0 == pytest.approx(2 * one.a0, rel=1e-13)
    assert eight.p0 == pytest.approx(2 * one.p0, rel=1e-13)
    zero = hertz_3d(0.0, 1.0, 3.0, E, NU)
    assert zero.a0 == 0 and zero.b0 == 0 and zero.p0 == 0


@pytest.mark.parametrize("name,args", [
    ("normal_load", (np.nan, 1.0, 1.0, E, NU)), ("curvature_longitudinal", (1e5, 0.0, 1.0, E, NU)),
    ("curvature_lateral", (1e5, 1.0, -1.0, E, NU)), ("poisson_ratio", (1e5, 1.0, 1.0, E, -0.1)),
    ("youngs_modulus", (1e5, 1.0, 1.0, 0.0, NU))])
def test_3d_errors(name, args):
    with pytest.raises(ValueError, match=name):
        hertz_3d(*args)


def test_ratio_errors():
    with pytest.raises(ValueError, match="a0_over_b0"):
        curvature_ratio_from_axis_ratio(0.0)
    with pytest.raises(ValueError, match="curvature_ratio"):
        axis_ratio_from_curvature_ratio(np.inf)


def test_3d_against_contact_tractcurv_header():
    """CONTACT (Vollebregt, Apache-2.0) tractcurv.ref_out, 3-D Hertzian geometry: A1 = 0.8e-3
    /mm and AA/BB = 0.5 prescribed, Fn = 106.7 kN, G = 82000 N/mm^2, nu = 0.28 -> B1 = 0.2814e-3
    /mm, AA = 6.304 mm, BB = 12.61 mm (printed to 4 digits). CONTACT's A1, B1 are the gap
    coefficients h = A1 x^2 + B1 y^2, i.e. the same A', B' as here."""
    g_mod, nu = 82e9, 0.28
    e_mod = 2 * g_mod * (1 + nu)
    ratio = curvature_ratio_from_axis_ratio(0.5)
    assert 0.8 * ratio == pytest.approx(0.2814, rel=2e-4)
    a0, b0, p0 = hertz_3d(106.7e3, 0.8, 0.8 * ratio, e_mod, nu)
    assert a0 == pytest.approx(6.304e-3, rel=1e-4)
    assert b0 == pytest.approx(12.61e-3, rel=5e-4)
    assert p0 == pytest.approx(640.7e6, rel=1e-3)      # CONTACT's PMAX on its 48x44 grid


def test_hertz_2d_beyond_the_float_range_of_its_products():
    """N R ~ 1e600: the products overflowed (a0 = inf); Hertz's scaling a0 ~ sqrt(N R),
    p0 ~ sqrt(N / R) gives the answer from the unit case. A result beyond the float range is
    a ValueError naming the inputs."""
    unit = hertz_2d(1.0, 1.0, 210e9, 0.28)
    big = hertz_2d(1e300, 1e300, 210e9, 0.28)
    assert big.a0 == pytest.approx(unit.a0 * 1e300, rel=1e-14)
    assert big.p0 == pytest.approx(unit.p0, rel=1e-14)
    with pytest.raises(ValueError, match=r"Hertz half-width a0 must be in \[0, 1.79769e\+308\] "
                                         r"\[m\]; got inf \(overflow at normal_load = 1e\+300, "
                                         r"radius = 1e\+300, youngs_modulus = 1e-300\)"):
        hertz_2d(1e300, 1e300, 1e-300, 0.28)


def test_hertz_3d_beyond_the_float_range_of_its_products():
    """E and the curvatures both scaled by 1e-162: E* C_major ~ 1e-313 underflowed (a0 = inf).
    Scaling (Johnson Sec. 4.2): a0, b0 ~ (N / (E C))^(1/3), p0 ~ N^(1/3) (E C)^(2/3), so
    a0, b0 grow by 1e108 and p0 falls by 1e-216."""
    unit = hertz_3d(8e4, 1.087, 1.667, 210e9, 0.28)
    got = hertz_3d(8e4, 1.087e-162, 1.667e-162, 210e9 * 1e-162, 0.28)
    assert got.a0 == pytest.approx(unit.a0 * 1e108, rel=1e-13)
    assert got.b0 == pytest.approx(unit.b0 * 1e108, rel=1e-13)
    assert got.p0 == pytest.approx(unit.p0 * 1e-216, rel=1e-13)
    with pytest.raises(ValueError, match=r"Hertz pressure p0 must be in \[0, 1.79769e\+308\] "
                                         r"\[Pa\]; got inf \(overflow at normal_load = 1e\+300"):
        hertz_3d(1e300, 1e300, 1e300, 1e300, 0.28)
