"""Tests of railcontact.friction (Nielsen 1998, Ch. 5): laws, step law, smooth-law iteration.

Independent checks used here:
* Carter (railcontact.carter) for mu_k = mu_0, kappa = 0 and the step-law limits;
* the discretised 2-D half-space solver (railcontact.reference.halfspace2d) run with the same
  slip-dependent law (its error is that of its element discretisation, ~1e-3 mu_0 N at 200
  elements);
* the governing equations re-evaluated on the returned traction with an element quadrature of the
  principal-value integral (a discretisation independent of the Chebyshev identities used inside);
* finite differences of the creep curve at its maximum.
"""

import numpy as np
import pytest

from railcontact.carter import carter_creep_force
from railcontact.friction import (
    CoulombFriction, SmoothFriction, StepFriction, normalised_inputs,
    ohyama_creep_force_normalised, ohyama_traction_normalised, solve_velocity_friction_normalised,
    step_law_creep_force_normalised, step_law_traction_normalised,
    velocity_friction_creep_force, velocity_friction_creep_force_normalised,
    velocity_friction_peak_creepage, velocity_friction_peak_normalised,
    velocity_friction_traction)
from railcontact.hertz import hertz_2d
from railcontact.reference.halfspace2d import solve_rolling_2d

E, NU, R, N, MU0 = 210e9, 0.28, 0.5, 1.0e6, 0.3
A0 = float(hertz_2d(N, R, E, NU).a0)
P0 = float(hertz_2d(N, R, E, NU).p0)
XIC = MU0 * A0 / R


def _carter_ratio(chi, m=1.0):
    r = np.clip(1.0 - np.abs(chi) / m, 0.0, 1.0)
    return -np.sign(chi) * m * (1.0 - r * r)


def _pv_quadrature(t, n=4000):
    """(1/pi) PV int t(z)/(x - z) dz on [-1, 1], piecewise-constant t, at element centres."""
    e = np.linspace(-1.0, 1.0, n + 1)
    xc = 0.5 * (e[:-1] + e[1:])
    kern = np.log(np.abs((xc[:, None] - e[None, :-1]) / (xc[:, None] - e[None, 1:]))) / np.pi
    return xc, kern @ t(xc)


# --------------------------------------------------------------------------------- laws
def test_laws_values_and_derivative():
    law = SmoothFriction(0.4, 0.2, 50.0)
    s = np.array([0.0, 1e-3, 0.01, 1.0, 1e6])
    np.testing.assert_allclose(law(s), 0.2 / (1 + 50 * s) + 0.2)
    assert law(0.0) == pytest.approx(0.4) and law(1e12) == pytest.approx(0.2, abs=1e-9)
    h = 1e-7
    fd = (law(s[:4] + h) - law(s[:4] - h + (s[:4] == 0) * h)) / (2 * h - (s[:4] == 0) * h)
    np.testing.assert_allclose(law.derivative(s[:4]), fd, rtol=1e-4)
    step = StepFriction(0.4, 0.25)
    np.testing.assert_array_equal(step([0.0, 1e-12, 3.0]), [0.4, 0.25, 0.25])
    np.testing.assert_array_equal(CoulombFriction(0.3)([0.0, 2.0]), [0.3, 0.3])
    assert np.all(SmoothFriction(0.4, 0.2, 0.0)(s) == 0.4)   # kappa = 0: Coulomb


def test_polach_law_in_slip_velocity():
    """Polach 2005: mu0 ((1 - A) exp(-B w) + A), written out here; as a law in s at speed V."""
    from railcontact.friction import PolachFriction

    law = PolachFriction(0.3, 0.4, 0.6)
    w = np.array([0.0, 0.5, 2.0, 100.0])
    np.testing.assert_allclose(law(w), 0.3 * (0.6 * np.exp(-0.6 * w) + 0.4), rtol=1e-15)
    assert law.needs_rolling_speed and law.mu_kinetic == pytest.approx(0.12)
    in_slip = law.at_rolling_speed(20.0)
    np.testing.assert_allclose(in_slip(w / 20.0), law(w), rtol=1e-15)
    assert in_slip.mu_static == 0.3 and "rolling_speed=20" in repr(in_slip)
    for ctor, name in ((lambda: PolachFriction(0.0, 0.4, 0.6), "mu_static"),
                       (lambda: PolachFriction(0.3, 1.4, 0.6), "friction_ratio_limit"),
                       (lambda: PolachFriction(0.3, 0.4, -1.0), "friction_decay"),
                       (lambda: law.at_rolling_speed(0.0), "rolling_speed")):
        with pytest.raises(ValueError, match=name):
            ctor()


@pytest.mark.parametrize("ctor, name", [
    (lambda: SmoothFriction(-0.1, 0.2, 1.0), "mu_static"),
    (lambda: SmoothFriction(0.1, -0.2, 1.0), "mu_kinetic"),
    (lambda: SmoothFriction(0.1, 0.2, -1.0), "kappa"),
    (lambda: StepFriction(0.1, np.nan), "mu_kinetic"),
    (lambda: CoulombFriction(np.inf), "mu"),
])
def test_law_errors(ctor, name):
    with pytest.raises(ValueError, match=name):
        ctor()


# --------------------------------------------------------------------------------- step law
def test_ohyama_features_stated_in_thesis():
    """Sec. 5.2 / Fig. 5.2: zero at xi = 0, mu_k N at full sliding, maximum above mu_k N for
    mu_k < mu_0, and a curve outside the band of the two Carter curves for mu_k > mu_0."""
    chi = np.linspace(0.0, 1.2, 241)
    f = -ohyama_creep_force_normalised(chi, 0.6)
    assert f[0] == 0.0 and f[-1] == pytest.approx(0.6)
    assert f.max() > 0.6 + 0.01 and 0.0 < chi[f.argmax()] < 1.0
    up = -ohyama_creep_force_normalised(0.1, 1.4)
    assert up > -_carter_ratio(0.1, 1.0) and up > -_carter_ratio(0.1, 1.4)


@pytest.mark.parametrize("func_f, func_t, m", [
    (ohyama_creep_force_normalised, ohyama_traction_normalised, 0.6),
    (ohyama_creep_force_normalised, ohyama_traction_normalised, 1.4),
    (step_law_creep_force_normalised, step_law_traction_normalised, 0.6),
    (step_law_creep_force_normalised, step_law_traction_normalised, 1.4),
])
@pytest.mark.parametrize("chi", [-0.7, 0.05, 0.4, 0.9, 2.0])
def test_step_law_force_is_integral_of_traction(func_f, func_t, m, chi):
    """T/(mu_0 N) = (2/pi) int q/(mu_0 p0) d(x/a0): closed-form force vs quadrature of the
    traction."""
    from scipy.integrate import quad
    pts = [1 - 2 * max(0.0, 1 - abs(chi)), 1 - 2 * max(0.0, 1 - abs(chi) / m)]
    val = quad(lambda x: float(func_t(x, chi, m)), -1, 1, points=pts, limit=200)[0]
    assert (2 / np.pi) * val == pytest.approx(float(func_f(chi, m)), abs=1e-9)


def test_step_law_equals_carter_with_mu_k():
    chi = np.linspace(-2, 2, 41)
    for m in (0.6, 1.4):
        np.testing.assert_allclose(
            step_law_creep_force_normalised(chi, m),
            carter_creep_force(chi * XIC, N, R, E, NU, m * MU0) / (MU0 * N), atol=1e-12)


def test_step_law_peak_point_fig_5_3():
    """Fig. 5.3: Carter with mu_k plus the value mu_0 p at the single stick/slip point."""
    chi, m = 0.3, 0.6
    rk = 1 - chi / m
    xb = 1 - 2 * rk
    q = -step_law_traction_normalised(np.array([xb - 1e-9, xb, xb + 1e-9]), chi, m)
    p = np.sqrt(1 - xb ** 2)
    assert q[1] == pytest.approx(p) and q[0] == pytest.approx(m * p, rel=1e-6)
    assert q[2] == pytest.approx(m * p, rel=1e-3)   # sqrt approach on the stick side


# --------------------------------------------------------------------------------- smooth law
def test_mu_k_equal_mu_0_and_kappa_zero_reduce_to_carter_exactly():
    chi = np.array([-1.3, -0.5, 0.0, 1e-4, 0.2, 0.7, 0.999, 1.0, 3.0])
    ref = carter_creep_force(chi * XIC, N, R, E, NU, MU0) / (MU0 * N)
    np.testing.assert_array_equal(velocity_friction_creep_force_normalised(chi, 1.0, 7.0),
                                  velocity_friction_creep_force_normalised(chi, 0.6, 0.0))
    np.testing.assert_allclose(velocity_friction_creep_force_normalised(chi, 1.0, 7.0), ref,
                               atol=1e-14)
    # the polynomial iteration itself (no short cut) reproduces Carter to round-off
    t = velocity_friction_creep_force(chi * XIC, N, R, E, NU, CoulombFriction(MU0))
    np.testing.assert_allclose(t, ref * MU0 * N, atol=1e-9 * MU0 * N)
    x = np.linspace(-A0, A0, 7)
    from railcontact.carter import carter_traction
    np.testing.assert_allclose(
        velocity_friction_traction(x, 0.4 * XIC, N, R, E, NU, SmoothFriction(MU0, MU0, 3.0)),
        carter_traction(x, 0.4 * XIC, N, R, E, NU, MU0), atol=1e-9 * P0)


@pytest.mark.parametrize("m, kap, chis", [
    (1.4, 10.0, [0.1, 0.5, 1.2]),   # rising law: partial slip and full sliding
    (0.6, 5.0, [0.05, 0.8, 1.2]),   # falling law: partial slip (small creepage), full sliding
])
def test_against_reference_solver(m, kap, chis):
    """Same law in the discretised half-space solver at 100 and 200 elements; its error is
    first order in the element size, so the Richardson extrapolation 2 T_200 - T_100 is compared
    (measured: |difference| <= 1.7e-4 mu_0 N; the 200-element value alone differs by <= 1.4e-3)."""
    law = SmoothFriction(MU0, m * MU0, kap / XIC)
    ours = velocity_friction_creep_force_normalised(np.array(chis), m, kap)
    refs = []
    for nel in (100, 200):
        dx = 2 * A0 / nel
        x = np.arange(-A0 + dx / 2, A0, dx)
        p = P0 * np.sqrt(np.clip(1 - (x / A0) ** 2, 0, None))
        refs.append(np.array([solve_rolling_2d(x, p, E, NU, creepage=c * XIC, friction=law)
                              .tangential_force / (MU0 * N) for c in chis]))
    assert np.max(np.abs(refs[1] - ours)) < 2e-3
    np.testing.assert_allclose(2 * refs[1] - refs[0], ours, atol=3e-4)


def test_falling_law_satisfies_governing_equations():
    """Falling law in partial slip at a creepage where the reference solver's continuation does
    not converge (200 elements, creepage 0.3 xi_c0): the returned traction, put into an
    independent element quadrature of
    the PV integral, has s = 0 in the stick zone, q = mu(s) p in the slip zone (away from the
    square-root kink at the stick/slip limit) and |q| <= mu_0 p in the stick zone."""
    m, kap, chi = 0.6, 10.0, 0.3
    sol = solve_velocity_friction_normalised(chi, m, kap, degree=256)
    b = 1 - 2 * sol.stick_ratio
    xc, h = _pv_quadrature(lambda x: -sol.traction(x))
    sig = chi - h
    p = np.sqrt(1 - xc ** 2)
    st, sl = xc > b + 0.05, xc < b - 0.05
    assert np.abs(sig[st]).max() < 2e-3                    # quadrature error of the check
    assert sig[sl].min() > 0
    res = -sol.traction(xc[sl]) - ((1 - m) / (1 + kap * sig[sl]) + m) * p[sl]
    assert np.abs(res).max() < 0.015
    assert np.all(-sol.traction(xc[st]) <= p[st] + 1e-9)
    # force from the coefficients vs the integral of the returned traction (whose slip zone is
    # mu(s(x)) p(x), not the polynomial): the two differ by the polynomial error, ~1e-4
    assert -sol.force_ratio == pytest.approx(
        (2 / np.pi) * np.sum(-sol.traction(xc)) * (xc[1] - xc[0]), rel=3e-4)
    # the closed-form slip of the solution agrees with the quadrature slip
    assert np.abs(sol.slip(xc[sl]) - sig[sl]).max() < 0.03
    assert np.all(sol.slip(xc[st]) == 0.0)


def test_creep_curve_between_carter_curves_and_initial_slope():
    """Sec. 5.3 / Fig. 5.4: initial slope equals Carter's; the force lies between the Carter
    curves for mu_0 and mu_k and tends to mu(xi) N only as xi -> inf."""
    chi = np.array([1e-4, 0.2, 0.5, 0.8, 1.5, 30.0])
    for m in (0.6, 1.4):
        f = -velocity_friction_creep_force_normalised(chi, m, 5.0)
        assert f[0] == pytest.approx(2e-4 * (1 - 0.5e-4), rel=2e-3)
        lo = np.minimum(-_carter_ratio(chi), -_carter_ratio(chi, m))
        hi = np.maximum(-_carter_ratio(chi), -_carter_ratio(chi, m))
        assert np.all(f >= lo - 1e-9) and np.all(f <= hi + 1e-9)
        mu_xi = (1 - m) / (1 + 5.0 * chi[-1]) + m
        assert f[-1] == pytest.approx(mu_xi, rel=5e-3)


def test_vectorised_equals_scalar_and_odd():
    chi = np.array([[-0.6], [0.25]])
    m = np.array([0.7, 1.3])
    vec = velocity_friction_creep_force_normalised(chi, m, 4.0)
    assert vec.shape == (2, 2)
    for i in range(2):
        for j in range(2):
            assert vec[i, j] == pytest.approx(
                float(velocity_friction_creep_force_normalised(chi[i, 0], m[j], 4.0)), abs=1e-12)
    assert float(velocity_friction_creep_force_normalised(-0.25, 0.7, 4.0)) == pytest.approx(
        -float(velocity_friction_creep_force_normalised(0.25, 0.7, 4.0)), abs=1e-12)


def test_physical_equals_normalised():
    law = SmoothFriction(MU0, 0.7 * MU0, 2000.0)
    nrm = normalised_inputs(0.6 * XIC, N, R, E, NU, MU0, 0.7 * MU0, 2000.0)
    assert float(nrm["creepage_ratio"]) == pytest.approx(0.6)
    t = velocity_friction_creep_force(0.6 * XIC, N, R, E, NU, law)
    tn = velocity_friction_creep_force_normalised(0.6, nrm["friction_ratio"],
                                                  nrm["kappa_normalised"])
    assert t == pytest.approx(tn * MU0 * N, rel=1e-9)
    # a user callable without derivative (finite-difference Jacobian) gives the same
    user = lambda s: MU0 * (0.3 / (1 + 2000.0 * np.abs(s)) + 0.7)  # noqa: E731
    assert velocity_friction_creep_force(0.6 * XIC, N, R, E, NU, user) == pytest.approx(t, rel=1e-7)


def test_peak_before_full_sliding_and_trends():
    """Sec. 5.3: the maximum occurs before complete sliding; larger kappa or smaller mu_k/mu_0
    move it to smaller creepage. dT/dxi = 0 there (finite differences)."""
    chi_p, f_p = velocity_friction_peak_normalised([0.6, 0.6, 0.8], [5.0, 20.0, 5.0])
    sat = solve_velocity_friction_normalised(10.0, 0.6, 5.0)   # saturation bound check below
    assert sat.stick_ratio == 0.0
    s05 = solve_velocity_friction_normalised(chi_p[0], 0.6, 5.0)
    assert s05.stick_ratio > 0.01                              # before full sliding
    assert chi_p[1] < chi_p[0] and chi_p[0] < chi_p[2]
    # a maximum of the creep curve: the force drops on both sides (the curve is flat there and
    # the polynomial discretisation wiggles it by ~1e-5, so the step is 0.05)
    h = 0.05
    f = -velocity_friction_creep_force_normalised(chi_p[0] + np.array([-h, 0, h]), 0.6, 5.0)
    assert f[1] > f[0] and f[1] > f[2]
    assert f[1] == pytest.approx(f_p[0], abs=2e-5)
    # regression pin (computed once by this code, degree 128): peak of (m, K) = (0.6, 5)
    assert chi_p[0] == pytest.approx(0.71292, abs=2e-4)
    assert f_p[0] == pytest.approx(0.69860, abs=2e-4)
    # Carter and rising laws
    c, f = velocity_friction_peak_normalised([1.0, 1.4], 5.0)
    assert c[0] == 1.0 and f[0] == 1.0 and np.isinf(c[1]) and f[1] == 1.4


def test_peak_physical():
    law = SmoothFriction(MU0, 0.6 * MU0, 5.0 / XIC)
    xi, t = velocity_friction_peak_creepage(N, R, E, NU, law)
    assert xi / XIC == pytest.approx(0.71292, abs=2e-4)
    assert t / (MU0 * N) == pytest.approx(0.69860, abs=2e-4)


# --------------------------------------------------------------------------------- hard cases
def test_kappa_to_zero_and_to_infinity():
    chi = np.array([0.2, 0.45, 0.9])
    np.testing.assert_allclose(velocity_friction_creep_force_normalised(chi, 0.6, 1e-9),
                               _carter_ratio(chi), atol=1e-8)
    # kappa -> inf: the step-law (corrected) solution, Carter with mu_k, for both m < 1 and m > 1
    for m in (0.6, 1.4):
        np.testing.assert_allclose(velocity_friction_creep_force_normalised(chi, m, 1000.0),
                                   _carter_ratio(chi, m), atol=3e-3)


def test_near_complete_sliding_is_continuous():
    sat = solve_velocity_friction_normalised(100.0, 0.6, 5.0)
    s_chi = 0.7792550801  # saturation creepage of (0.6, 5) (regression pin, degree 128)
    lo = velocity_friction_creep_force_normalised(s_chi - 1e-7, 0.6, 5.0)
    hi = velocity_friction_creep_force_normalised(s_chi + 1e-7, 0.6, 5.0)
    assert abs(lo - hi) < 1e-6
    r = solve_velocity_friction_normalised(s_chi - 1e-4, 0.6, 5.0).stick_ratio
    assert 0.0 < r < 1e-3
    assert sat.force_ratio < 0 and sat.residual < 1e-10


def test_zero_friction_and_zero_kinetic():
    assert velocity_friction_creep_force([0.0, 1e-3], N, R, E, NU, SmoothFriction(0, 0, 5.0)) \
        .tolist() == [0.0, 0.0]
    np.testing.assert_array_equal(
        velocity_friction_traction([0.0, 0.5 * A0], 1e-3, N, R, E, NU, CoulombFriction(0.0)),
        [0.0, 0.0])
    assert velocity_friction_creep_force(1e-3, 0.0, R, E, NU, SmoothFriction(0.3, 0.2, 5)) == 0.0
    f = velocity_friction_creep_force_normalised([0.3, 5.0], 0.0, 5.0)   # mu_k = 0
    assert np.all(np.isfinite(f)) and -f[1] < -f[0]


def test_non_convergence_raises_naming_parameters():
    with pytest.raises(ValueError, match="friction_ratio = 1.4, kappa_normalised = 1000"):
        velocity_friction_creep_force_normalised(0.5, 1.4, 1000.0, max_iter=1)
    step = lambda s: np.where(np.abs(s) > 0, 0.6 * MU0, MU0)  # noqa: E731
    with pytest.raises(ValueError, match="friction_law = <function"):
        velocity_friction_creep_force(0.7 * XIC, N, R, E, NU, step, max_iter=1)


@pytest.mark.parametrize("m", [0.6, 1.4])
def test_general_iteration_with_step_law_finds_minimum_solution(m):
    """The step law (5.3) given as a plain callable to the general iteration (no closed form
    involved) converges, where it converges, to Carter with mu_k: an independent confirmation of
    the thesis' corrected solution (5.4)-(5.6) for mu_k < mu_0 and mu_k > mu_0."""
    step = lambda s: np.where(np.abs(s) > 0, m * MU0, MU0)  # noqa: E731
    chi = np.array([0.01, 0.05, 0.2, 2.0])
    t = velocity_friction_creep_force(chi * XIC, N, R, E, NU, step) / (MU0 * N)
    np.testing.assert_allclose(t, step_law_creep_force_normalised(chi, m), atol=2e-4)


def test_step_friction_object_uses_minimum_solution():
    law = StepFriction(MU0, 0.6 * MU0)
    chi = np.array([-0.4, 0.1, 0.5, 1.0])
    np.testing.assert_allclose(velocity_friction_creep_force(chi * XIC, N, R, E, NU, law),
                               MU0 * N * step_law_creep_force_normalised(chi, 0.6), rtol=1e-12)
    x = np.linspace(-A0, A0, 5)[1:-1]
    np.testing.assert_allclose(velocity_friction_traction(x, 0.3 * XIC, N, R, E, NU, law),
                               MU0 * P0 * step_law_traction_normalised(x / A0, 0.3, 0.6),
                               rtol=1e-12)
    xi, t = velocity_friction_peak_creepage(N, R, E, NU, law)
    assert xi == pytest.approx(0.6 * XIC) and t == pytest.approx(0.6 * MU0 * N)


@pytest.mark.parametrize("kwargs, name", [
    (dict(creepage_ratio=np.nan, friction_ratio=0.5, kappa_normalised=1.0), "creepage_ratio"),
    (dict(creepage_ratio=0.1, friction_ratio=-0.5, kappa_normalised=1.0), "friction_ratio"),
    (dict(creepage_ratio=0.1, friction_ratio=0.5, kappa_normalised=-1.0), "kappa_normalised"),
    (dict(creepage_ratio=0.1, friction_ratio=0.5, kappa_normalised=1.0, degree=4), "degree"),
    (dict(creepage_ratio=0.1, friction_ratio=0.5, kappa_normalised=1.0, degree=20.5), "degree"),
    (dict(creepage_ratio=0.1, friction_ratio=0.5, kappa_normalised=1.0, tol=0.0), "tol"),
    (dict(creepage_ratio=0.1, friction_ratio=0.5, kappa_normalised=1.0, max_iter=0), "max_iter"),
])
def test_input_errors(kwargs, name):
    with pytest.raises(ValueError, match=name):
        velocity_friction_creep_force_normalised(**kwargs)


def test_physical_input_errors():
    with pytest.raises(ValueError, match="friction_law"):
        velocity_friction_creep_force(0.1, N, R, E, NU, 0.3)
    with pytest.raises(ValueError, match="radius"):
        velocity_friction_creep_force(0.1, N, -1.0, E, NU, CoulombFriction(0.3))
    with pytest.raises(ValueError, match="poisson_ratio"):
        velocity_friction_creep_force(0.1, N, R, E, 0.6, CoulombFriction(0.3))
    with pytest.raises(ValueError, match="creepage"):
        velocity_friction_traction([0.0], [0.1, 0.2], N, R, E, NU, CoulombFriction(0.3))


# ------------------------------------------------- saturation creepage and the table's curve
from railcontact.friction import (  # noqa: E402
    velocity_friction_saturation_creepage, velocity_friction_saturation_curve)


def test_saturation_curve_is_carter_for_coulomb_laws():
    """m = 1 or kappa = 0: xi_sat = xi_c0 and Carter's force and stick ratio (2.51)-(2.53)."""
    z = np.array([0.0, 0.2, 0.7, 1.0, 2.5])
    for m, kap in ((1.0, 3.0), (0.4, 0.0)):
        res = velocity_friction_saturation_curve(z, m, kap)
        np.testing.assert_array_equal(res.saturation_creepage_ratio, 1.0)
        np.testing.assert_allclose(res.force_ratio, -_carter_ratio(z), rtol=0, atol=1e-15)
        np.testing.assert_allclose(res.stick_ratio, np.clip(1.0 - z, 0.0, 1.0), atol=1e-15)
    assert velocity_friction_saturation_creepage(1.0, 3.0) == 1.0


def test_saturation_creepage_tends_to_carter_for_a_flat_law():
    """kappa -> 0 with m != 1 goes through the iteration (not the Carter shortcut): the limit
    must be Carter's xi_c0, the force 1 - (1 - z)^2 and the stick ratio 1 - z."""
    kap = 1e-6
    assert float(velocity_friction_saturation_creepage(0.5, kap)) == pytest.approx(1.0, abs=1e-5)
    z = np.array([0.25, 0.6, 0.9])
    res = velocity_friction_saturation_curve(z, 0.5, kap)
    np.testing.assert_allclose(res.force_ratio, 1 - (1 - z) ** 2, atol=1e-5)
    np.testing.assert_allclose(res.stick_ratio, 1 - z, atol=1e-5)


@pytest.mark.parametrize("m, kap", [(0.6, 2.0), (1.4, 2.0)])
def test_saturation_curve_against_reference_solver(m, kap):
    """Stick ratio and saturation creepage against the discretised half-space solver (200
    elements, same law): the stick zone it finds (element count x dx / (2 a0)) matches r to
    about two elements (0.02), it has no stick element just above xi_sat and still has one
    just below; the force agrees as in test_against_reference_solver."""
    law = SmoothFriction(MU0, m * MU0, kap / XIC)
    sat = float(velocity_friction_saturation_creepage(m, kap))
    assert sat != pytest.approx(1.0, abs=0.02)          # not Carter: the law changes it
    nel = 200
    dx = 2 * A0 / nel
    x = np.arange(-A0 + dx / 2, A0, dx)
    p = P0 * np.sqrt(np.clip(1 - (x / A0) ** 2, 0, None))
    z = np.array([0.3, 0.7, 0.95, 1.03])
    res = velocity_friction_saturation_curve(z, m, kap)
    for zi, force, r in zip(z, res.force_ratio, res.stick_ratio):
        ref = solve_rolling_2d(x, p, E, NU, creepage=zi * sat * XIC, friction=law)
        r_ref = np.count_nonzero(ref.stick) * dx / (2 * A0)
        assert r == pytest.approx(r_ref, abs=0.02)
        assert force == pytest.approx(-ref.tangential_force / (MU0 * N), abs=2e-3)
        if zi > 1.0:
            assert r == 0.0 and r_ref == 0.0
        if zi == 0.95:
            assert r_ref > 0.0


def test_saturation_curve_matches_the_vectorised_creep_curve():
    """The table's curve at z is the creep curve of velocity_friction_creep_force_normalised at
    |xi|/xi_c0 = z xi_sat/xi_c0 (same solver, different entry point) and the stick ratio of
    solve_velocity_friction_normalised."""
    m, kap = 0.7, 4.0
    z = np.array([0.1, 0.5, 0.99, 1.5, 4.0])
    res = velocity_friction_saturation_curve(z, m, kap)
    chi = z * res.saturation_creepage_ratio
    np.testing.assert_allclose(res.force_ratio,
                               -velocity_friction_creep_force_normalised(chi, m, kap), atol=1e-9)
    for c, r in zip(chi, res.stick_ratio):
        assert r == pytest.approx(solve_velocity_friction_normalised(c, m, kap).stick_ratio,
                                  abs=1e-8)


def test_saturation_curve_bad_input_names_parameter():
    with pytest.raises(ValueError, match="normalised_creepage"):
        velocity_friction_saturation_curve(-0.1, 0.5, 1.0)
    with pytest.raises(ValueError, match="kappa_normalised"):
        velocity_friction_saturation_creepage(0.5, -1.0)
    with pytest.raises(ValueError, match="degree"):
        velocity_friction_saturation_creepage(0.5, 1.0, degree=4)
