"""Tests of railcontact.carter.

Independent checks: the force against quadrature of the traction; the slip against the
constitutive principal-value integral evaluated by QUADPACK (weight="cauchy"), which also fixes
where the stick zone must be (leading edge x = +a0); the Coulomb bounds; CONTACT's carter2d
reference output (E.A.H. Vollebregt, Apache-2.0); the 3-D linear theory in the strip limit.
"""

import numpy as np
import pytest
from scipy.integrate import quad

from railcontact import (carter_creep_force, carter_critical_creepage, carter_slip,
                         carter_stick_ratio, carter_traction, hertz_2d, kalker_coefficients)

G_MOD, NU, MU, R = 82e9, 0.28, 0.3, 0.5
E = 2 * G_MOD * (1 + NU)
A0 = 1e-3
N = A0**2 * np.pi * E / (8 * (1 - NU**2) * R)      # load per unit length giving a0 = 1 mm
ARGS = (N, R, E, NU, MU)


def test_critical_creepage_and_force_at_saturation():
    xi_c = carter_critical_creepage(*ARGS)
    assert xi_c == pytest.approx(MU * A0 / R, rel=1e-12)
    assert carter_creep_force(xi_c, *ARGS) == pytest.approx(-MU * N, rel=1e-14)
    assert carter_creep_force(-10 * xi_c, *ARGS) == MU * N          # exactly, never above
    assert carter_stick_ratio(0.0, *ARGS) == 1.0
    assert carter_stick_ratio(2 * xi_c, *ARGS) == 0.0


@pytest.mark.parametrize("frac", [0.05, 0.4, 0.8, 0.999])
def test_force_equals_quadrature_of_traction(frac):
    xi = frac * carter_critical_creepage(*ARGS)
    a0, p0 = hertz_2d(N, R, E, NU)
    r_a0 = carter_stick_ratio(xi, *ARGS)
    a_star = r_a0 * a0
    edge = a0 - 2 * a_star            # stick/slip boundary: split the quadrature there
    total = sum(quad(lambda x: carter_traction(x, xi, *ARGS), lo, hi, epsabs=0,
                     epsrel=1e-12)[0] for lo, hi in ((-a0, edge), (edge, a0)))
    assert total == pytest.approx(carter_creep_force(xi, *ARGS), rel=1e-9)
    # Coulomb: |q| <= mu p, and q = -mu p in the slip zone (force on wheel opposes creepage)
    x = np.linspace(-a0, a0, 401)
    q = carter_traction(x, xi, *ARGS)
    p = p0 * np.sqrt(np.clip(1 - (x / a0) ** 2, 0, None))
    assert np.all(np.abs(q) <= MU * p * (1 + 1e-12) + 1e-9)
    slip_zone = x < edge - 1e-9 * a0
    np.testing.assert_allclose(q[slip_zone], -MU * p[slip_zone], rtol=1e-10, atol=1e-6)


@pytest.mark.parametrize("frac", [0.3, 0.7])
def test_slip_matches_quadrature(frac):
    """s = xi + 4(1-nu^2)/(pi E) PV int q(z)/(x-z) dz, evaluated numerically."""
    xi = frac * carter_critical_creepage(*ARGS)
    a0, _ = hertz_2d(N, R, E, NU)
    edge = a0 - 2 * carter_stick_ratio(xi, *ARGS) * a0
    xs = np.array([-1.5, -0.95, -0.6, edge / a0 - 0.05, edge / a0 + 0.05, 0.2, 0.9, 1.3]) * a0
    for x in xs:
        if abs(x) < a0:
            pv = quad(lambda z: carter_traction(z, xi, *ARGS), -a0, a0, weight="cauchy", wvar=x,
                      epsabs=0, epsrel=1e-11, limit=400, points=None)[0]
        else:
            pv = quad(lambda z: carter_traction(z, xi, *ARGS) / (z - x), -a0, a0, epsabs=0,
                      epsrel=1e-11, limit=400, points=[edge])[0]
        slip = xi + 4 * (1 - NU**2) / (np.pi * E) * (-pv)
        assert carter_slip(x, xi, *ARGS) == pytest.approx(slip, rel=1e-7, abs=1e-9 * xi)
        # in the slip zone the traction opposes the slip
        if -a0 < x < edge:
            assert carter_slip(x, xi, *ARGS) > 0 and carter_traction(x, xi, *ARGS) < 0
        if edge < x < a0:
            assert carter_slip(x, xi, *ARGS) == 0.0
    # far field: s -> xi (Eq. (2.58)), as xi - (mu/R)(a0^2 - a*^2)/(2x)
    a_star = carter_stick_ratio(xi, *ARGS) * a0
    for x in (1e3 * a0, 1e6 * a0):
        far = xi - MU / R * (a0**2 - a_star**2) / (2 * x)
        assert carter_slip(x, xi, *ARGS) == pytest.approx(far, rel=1e-6)
        assert carter_slip(-x, xi, *ARGS) == pytest.approx(2 * xi - far, rel=1e-6)


# CONTACT carter2d.ref_out (Vollebregt, Apache-2.0): a = 1 mm, R = 500 mm, G = 82000 N/mm^2,
# nu = 0.28, mu = 0.3, CKSI = -0.024 %  ->  FX/FSTAT/FN = 0.6480 (50 elements; Carter: 0.64);
# rows (x [mm], |PT| [N/mm^2], |S| [-]) with the slip zone at x < -0.19 (stick at the leading edge)
CONTACT_ROWS = np.array([
    (-0.97, 8.47, 0.728e-3), (-0.73, 23.4, 0.563e-3), (-0.49, 29.8, 0.382e-3),
    (-0.29, 32.7, 0.186e-3), (-0.09, 22.6, 0.0), (0.03, 18.3, 0.0), (0.31, 12.4, 0.0),
    (0.59, 8.38, 0.0), (0.87, 4.46, 0.0)])


def test_contact_carter2d_reference():
    xi = -0.00024
    assert carter_creep_force(xi, *ARGS) / (MU * N) == pytest.approx(0.64, rel=1e-12)
    assert carter_creep_force(xi, *ARGS) / (MU * N) == pytest.approx(0.6480, abs=0.01)
    x = CONTACT_ROWS[:, 0] * 1e-3
    q = carter_traction(x, xi, *ARGS) / 1e6
    assert np.all(q > 0)                                       # opposes the negative creepage
    np.testing.assert_allclose(q, CONTACT_ROWS[:, 1], atol=0.02 * MU * 113.9)
    s = carter_slip(x, xi, *ARGS)
    np.testing.assert_allclose(np.abs(s), CONTACT_ROWS[:, 2], atol=0.03 * 0.728e-3)


def test_initial_slope_equals_3d_linear_theory_in_strip_limit():
    """Integrating Carter's initial slope over the strips of a narrow ellipse gives Kalker's
    linear theory with C11 -> pi^2/(4(1-nu)) (a0/b0 -> 0)."""
    h = 1e-9 * carter_critical_creepage(*ARGS)
    slope_2d = (carter_creep_force(h, *ARGS) - carter_creep_force(-h, *ARGS)) / (2 * h)
    assert slope_2d == pytest.approx(-np.pi * E * A0 / (4 * (1 - NU**2)), rel=1e-7)
    # strips: a(y) = a0 sqrt(1 - (y/b0)^2); slope per unit length is proportional to a(y)
    b0 = 20 * A0
    slope_3d_strips = slope_2d / A0 * quad(lambda y: A0 * np.sqrt(1 - (y / b0) ** 2), -b0, b0)[0]
    c11_strip = -slope_3d_strips / (G_MOD * A0 * b0)
    assert c11_strip == pytest.approx(np.pi**2 / (4 * (1 - NU)), rel=1e-6)
    # Kalker's table + asymptote at a0/b0 = 0.05 is within 2 % of the strip value
    assert kalker_coefficients(0.05, NU).c11 == pytest.approx(c11_strip, rel=0.02)


def test_odd_zero_and_vectorised():
    half = np.linspace(0, 2, 21)[1:] * carter_critical_creepage(*ARGS)
    xi = np.concatenate([-half[::-1], [0.0], half])
    t = carter_creep_force(xi, *ARGS)
    np.testing.assert_array_equal(t, -t[::-1])
    assert carter_creep_force(0.0, *ARGS) == 0.0
    assert np.all(np.abs(t) <= MU * N)
    for i in (0, 13, 20, 33):
        assert carter_creep_force(xi[i], *ARGS) == t[i]
    # N = 0 and mu = 0 give zeros, not NaN
    assert carter_creep_force(1e-3, 0.0, R, E, NU, MU) == 0.0
    assert carter_creep_force(1e-3, N, R, E, NU, 0.0) == 0.0
    assert carter_stick_ratio(1e-3, N, R, E, NU, 0.0) == 0.0
    assert np.all(carter_traction(np.linspace(-1, 1, 5) * A0, 1e-3, 0.0, R, E, NU, MU) == 0)
    assert carter_slip(0.0, 1e-3, 0.0, R, E, NU, MU) == 1e-3


def test_saturation_is_c1_kink():
    """dT/dxi -> 0 at xi_c from below (stick zone vanishes), 0 beyond: the creep curve is C1,
    its second derivative jumps from 2 mu N / xi_c^2 to 0."""
    xi_c = carter_critical_creepage(*ARGS)
    h = 1e-6 * xi_c
    left = (carter_creep_force(xi_c, *ARGS) - carter_creep_force(xi_c - h, *ARGS)) / h
    assert abs(left) < 1e-5 * MU * N / xi_c


@pytest.mark.parametrize("func,name,bad", [
    (carter_creep_force, "creepage", np.nan), (carter_stick_ratio, "creepage", np.inf)])
def test_errors_creepage(func, name, bad):
    with pytest.raises(ValueError, match=name):
        func(bad, *ARGS)


@pytest.mark.parametrize("index,name", [(0, "normal_load"), (1, "radius"),
                                        (2, "youngs_modulus"), (3, "poisson_ratio"),
                                        (4, "friction_coefficient")])
def test_errors_parameters(index, name):
    args = list(ARGS)
    args[index] = -1.0
    with pytest.raises(ValueError, match=name):
        carter_creep_force(1e-4, *args)
    with pytest.raises(ValueError, match="x"):
        carter_traction(np.nan, 1e-4, *ARGS)


def test_overflowing_results_raise_naming_the_inputs():
    with pytest.raises(ValueError, match=r"friction_coefficient \* normal_load .* must be in "
                                         r"\[0, 1.79769e\+308\] \[N/m\]; got inf"):
        carter_creep_force(1e-3, 1e300, 0.46, 210e9, 0.28, 1e10)
    with pytest.raises(ValueError, match=r"critical creepage mu a0 / R must be in "
                                         r"\[0, 1.79769e\+308\] \[-\]; got inf \(overflow at "
                                         r"friction_coefficient = 1e\+300"):
        carter_critical_creepage(1e6, 1e-100, 210e9, 0.28, 1e300)   # 1e300 * 1e-52 / 1e-100
    # a subnormal product is fine: mu a0 / R with mu = 5e-324 is 0 or subnormal, and the force
    # is then full sliding (|T| = mu N, rounded)
    force = carter_creep_force(1e-3, 1e6, 0.46, 210e9, 0.28, 5e-324)
    assert np.isfinite(force) and abs(force) <= 5e-324 * 1e6
