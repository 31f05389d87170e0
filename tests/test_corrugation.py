"""Tests of railcontact.corrugation (Nielsen Ch. 4.2): every closed form against an independent
computation -- the discretised half-space solver, a Fourier analysis of the exact nonlinear
solution, finite differences, or a limiting case."""

import time

import numpy as np
import pytest
from scipy.optimize import brentq, minimize_scalar
from scipy.special import j0, j1

from railcontact import corrugation as cg
from railcontact.reference.halfspace2d import solve_normal_2d, solve_rolling_2d

E, NU, R, MU = 2.1e11, 0.28, 0.5, 0.3
COMP = 4 * (1 - NU ** 2) / (np.pi * E)
A0 = 0.006
N = A0 ** 2 / (2 * R * COMP)


def _surface(ratio, eps, phase=0.4):
    lam = A0 / ratio
    k = 2 * np.pi / lam
    amp = eps * A0 / (k * R)
    return lam, k, amp * np.cos(phase), amp * np.sin(phase)


def _first_harmonic(values, k, x, za, zb):
    """c with Q_A + i Q_B = c (Z_A + i Z_B) from samples over one period."""
    q = 2 * np.mean(np.asarray(values) * np.exp(1j * k * x))   # Q_A + i Q_B ... conj form
    # Q = Q_A cos + Q_B sin -> 2 mean(Q e^{ikx}) = Q_A + i Q_B
    return q / (za + 1j * zb)


# --------------------------------------------------------------------------------------------
# normal problem
# --------------------------------------------------------------------------------------------
@pytest.mark.parametrize("ratio", [1e-3, 0.05, 0.2, 0.45, 1.0, 2.0])
def test_normal_closed_forms_match_exact_small_amplitude(ratio):
    lam, k, za, zb = _surface(ratio, 1e-4)
    x = np.arange(32) * lam / 32
    a, d, _, _ = cg.solve_normal_exact(x, N * COMP, R, [k], [za], [zb])
    cd, ca = cg.normal_response(ratio)
    assert abs(_first_harmonic(a, k, x, za, zb) / (k * R) - ca) < 1e-3 * max(abs(ca), 1e-2)
    assert abs(_first_harmonic(d, k, x, za, zb) / (k * R) - cd) < 1e-3 * max(abs(cd), 1e-2)


def test_normal_exact_matches_halfspace_solver():
    """Exact (4.31), (4.33) against the discretised solver (400 elements) at 3 positions."""
    lam, k, za, zb = _surface(0.3, 0.05)
    for xc in np.arange(3) * lam / 3 + 0.1 * lam:
        def gap(xb, xc=xc):
            return xb ** 2 / (2 * R) - (za * np.cos(k * (xc + xb)) + zb * np.sin(k * (xc + xb)))
        ref = solve_normal_2d(gap, N, E, NU, -1.5 * A0, 1.5 * A0, 400)
        a, d, _, _ = cg.solve_normal_exact(xc, N * COMP, R, [k], [za], [zb])
        assert abs(0.5 * (ref.contact_end - ref.contact_start) - a) < 1e-3 * A0
        assert abs(0.5 * (ref.contact_end + ref.contact_start) - d) < 1e-3 * A0
        # pressure from the Chebyshev-Bessel series vs the solver's element pressures
        dist = cg.contact_distributions(ref.x - d, xc, N, R, E, NU, MU, 0.0, [za], [zb], [lam])
        p0 = 2 * N / (np.pi * A0)
        inner = np.abs(ref.x - d) < 0.9 * a
        assert np.max(np.abs(dist.pressure - ref.pressure)[inner]) < 0.01 * p0


def test_maximum_of_half_width_amplitude_thesis_text():
    """Text after Fig. 4.4: max of a^ at a0/L ~ 0.293 with a^ ~ 0.582 k R |Z|."""
    res = minimize_scalar(lambda q: -abs(cg.normal_response(q)[1]), bounds=(0.1, 0.5),
                          method="bounded", options={"xatol": 1e-10})
    assert abs(res.x - 0.293) < 5e-4
    assert abs(-res.fun - 0.582) < 5e-4


def test_bessel_zeros_hard_case():
    """At the zeros of J0 (Delta) and J1 (a) the exact first harmonic vanishes (up to O(eps^2))."""
    for zero, which in ((2.404825557695773, 0), (3.831705970207512, 1)):
        ratio = zero / (2 * np.pi)
        lam, k, za, zb = _surface(ratio, 1e-3)
        x = np.arange(32) * lam / 32
        a, d, _, _ = cg.solve_normal_exact(x, N * COMP, R, [k], [za], [zb])
        c = _first_harmonic([d, a][which], k, x, za, zb) / (k * R)
        assert abs(c) < 1e-4
        assert abs(cg.normal_response(ratio)[which]) < 1e-12


def test_contact_point_shift_and_4_42():
    """Delta_c from the tangency condition solved numerically; Delta = J0(k a0) Delta_c (4.42)."""
    ratio = 0.15
    lam, k, za, zb = _surface(ratio, 1e-4)
    for xc in (0.1 * lam, 0.37 * lam):
        def tangency(dc, xc=xc):  # slope of the cylinder = slope of the surface at X + dc
            return dc / np.sqrt(R ** 2 - dc ** 2) - k * (-za * np.sin(k * (xc + dc))
                                                         + zb * np.cos(k * (xc + dc)))
        dc = brentq(tangency, -0.5 * A0, 0.5 * A0, xtol=1e-16)
        lin = np.real(k * R * cg.contact_point_shift_coefficient() * (za + 1j * zb)
                      * np.exp(-1j * k * xc))
        assert abs(dc - lin) < 1e-4 * abs(lin)
        _, d, _, _ = cg.solve_normal_exact(xc, N * COMP, R, [k], [za], [zb])
        assert abs(d - j0(k * A0) * lin) < 1e-3 * abs(lin)


def test_oscillating_normal_load_4_39():
    """(4.39): da = a0/(2 N0) dN, against the exact solve with the load changed."""
    lam, k, za, zb = _surface(0.2, 1e-4)
    dn = 1e-4 * N
    term = cg.half_width_load_term(0.0, A0, N, [dn], [0.0], [lam])
    a_plus, _, _, _ = cg.solve_normal_exact(0.0, (N + dn) * COMP, R, [k], [0.0], [0.0])
    assert abs(term - (a_plus - A0)) < 1e-4 * abs(term)   # O(dN/N) second order


def test_condition_4_2_raises():
    lam = 0.03
    k = 2 * np.pi / lam
    too_big = 1.2 / (k * k * R)
    with pytest.raises(ValueError, match="curvature_amplitude"):
        cg.corrugated_contact(0.0, N, R, E, NU, MU, 1e-3, [too_big], [0.0], [lam])


@pytest.mark.parametrize("name, kwargs", [
    ("a0_over_wavelength", dict(a0_over_wavelength=-1.0, stick_ratio=0.5)),
    ("stick_ratio", dict(a0_over_wavelength=0.1, stick_ratio=1.5)),
])
def test_bad_inputs(name, kwargs):
    with pytest.raises(ValueError, match=name):
        cg.stick_zone_response(**kwargs)


def test_bad_method_and_shapes():
    with pytest.raises(ValueError, match="method"):
        cg.corrugated_contact(0.0, N, R, E, NU, MU, 1e-3, [1e-6], [0.0], [0.05], method="x")
    with pytest.raises(ValueError, match="amplitudes_cos"):
        cg.corrugated_contact(0.0, N, R, E, NU, MU, 1e-3, [1e-6, 1e-6], [0.0], [0.05])
    with pytest.raises(ValueError, match="normal_load"):
        cg.corrugated_contact(0.0, -1.0, R, E, NU, MU, 1e-3, [1e-6], [0.0], [0.05])


# --------------------------------------------------------------------------------------------
# tangential problem
# --------------------------------------------------------------------------------------------
@pytest.mark.parametrize("ratio, r", [(0.05, 0.5), (0.2, 0.3), (0.3, 0.6), (0.5, 0.8),
                                      (1.0, 0.45), (2.0, 0.5)])
def test_stick_and_force_closed_forms_match_exact(ratio, r):
    lam, k, za, zb = _surface(ratio, 1e-4)
    xi = MU * A0 * (1 - r) / R
    x = np.arange(48) * lam / 48
    res = cg.corrugated_contact(x, N, R, E, NU, MU, xi, [za], [zb], [lam])
    cs = cg.stick_zone_response(ratio, r)
    ct = cg.tangential_force_response(ratio, r)
    got_s = _first_harmonic(res.stick_half_width, k, x, za, zb) / (k * R)
    got_t = _first_harmonic(res.tangential_force, k, x, za, zb) / (MU / COMP)
    assert abs(got_s - cs) < 2e-3 * max(abs(cs), 0.05)
    assert abs(got_t - ct) < 2e-3 * max(abs(ct), 0.05)
    assert abs(np.mean(res.tangential_force) - MU * N * (1 - r * r)) < 1e-6 * MU * N


def test_thesis_orientation_is_the_conjugate():
    """(4.61)-(4.62) as printed are the complex conjugate of the package orientation."""
    ratio, r = 0.27, 0.35
    beta = 2 * np.pi * ratio
    a1 = -j1(beta) - j0(beta * r) * np.sin(beta * (r - 1))
    a2 = j0(beta) - j0(beta * r) * np.cos(beta * (r - 1))
    assert abs(np.conj(cg.stick_zone_response(ratio, r)) - (a1 + 1j * a2)) < 1e-14
    t1 = beta * r * (-a1 - j1(beta * r) * np.cos(beta * (r - 1)))        # (4.70)
    t2 = beta * r * (-a2 + j1(beta * r) * np.sin(beta * (r - 1)))        # (4.71)
    assert abs(np.conj(cg.tangential_force_response(ratio, r)) - (t1 + 1j * t2)) < 1e-14


def test_tangential_force_and_slip_match_halfspace_solver():
    """Exact T, traction and slip at 3 positions vs the discretised steady-rolling solver."""
    ratio, r = 0.25, 0.5
    lam, k, za, zb = _surface(ratio, 0.05)
    xi = MU * A0 * (1 - r) / R
    for xc in (0.0, 0.3 * lam, 0.65 * lam):
        def gap(xb, xc=xc):
            return xb ** 2 / (2 * R) - (za * np.cos(k * (xc + xb)) + zb * np.sin(k * (xc + xb)))
        ref_n = solve_normal_2d(gap, N, E, NU, -1.5 * A0, 1.5 * A0, 400)
        ref_t = solve_rolling_2d(ref_n.x, ref_n.pressure, E, NU, creepage=-xi, friction=MU)
        res = cg.corrugated_contact(xc, N, R, E, NU, MU, xi, [za], [zb], [lam])
        assert abs(ref_t.tangential_force - res.tangential_force) < 3e-3 * MU * N
        dist = cg.contact_distributions(ref_n.x - res.patch_shift, xc, N, R, E, NU, MU, xi,
                                        [za], [zb], [lam])
        p0 = 2 * N / (np.pi * A0)
        assert np.max(np.abs(np.abs(ref_t.traction) - dist.traction)) < 0.03 * MU * p0
        smax = np.max(dist.slip)
        inner = (dist.slip > 0.05 * smax)
        assert np.max(np.abs(np.abs(ref_t.slip) - dist.slip)[inner]) < 0.03 * smax


def test_stick_ratio_limits_hard_case():
    """r -> 0 (full slip) and r -> 1 (full stick): finite, continuous coefficients."""
    ratio = np.array([1e-3, 0.1, 0.5, 2.0])
    for r in (0.0, 1e-6, 1.0 - 1e-6, 1.0):
        c = cg.stick_zone_response(ratio, r)
        assert np.all(np.isfinite(c))
    assert np.allclose(cg.stick_zone_response(ratio, 1e-7), cg.stick_zone_response(ratio, 0.0),
                       atol=1e-5)
    # full stick: a* follows a with the patch shift: c_a* = c_a + c_Delta - i J0(0) ... = c_a
    cd, ca = cg.normal_response(ratio)
    assert np.allclose(cg.stick_zone_response(ratio, 1.0), ca, atol=1e-12)
    assert np.allclose(cg.tangential_force_response(ratio, 0.0), 0.0)


# --------------------------------------------------------------------------------------------
# series, many harmonics
# --------------------------------------------------------------------------------------------
def test_series_degree_and_error_estimate():
    lam, k, za, zb = _surface(0.6, 0.05)
    x = np.linspace(-0.95, 0.95, 41) * A0
    best = cg.contact_distributions(x, 0.1 * lam, N, R, E, NU, MU, 0.0, [za], [zb], [lam],
                                    degree=80)
    p0 = 2 * N / (np.pi * A0)
    prev = np.inf
    for deg in (2, 4, 8, 12, 16):
        d = cg.contact_distributions(x, 0.1 * lam, N, R, E, NU, MU, 0.0, [za], [zb], [lam],
                                     degree=deg)
        err = np.max(np.abs(d.pressure - best.pressure)) / p0
        assert err <= prev + 1e-15
        prev = err
        # the estimate bounds the actual error relative to the corrugation part of p
        corr = np.max(np.abs(best.pressure - p0 * np.sqrt(np.clip(1 - (x / A0) ** 2, 0, 1))))
        assert err <= 3 * d.truncation_error * max(corr / p0, 1e-300) + 1e-12
    assert cg.series_truncation_error(2 * np.pi * 0.05, 2)[0] == pytest.approx(
        2 * np.pi * 0.05 / 3)
    # a0/L = 2 (k a0 = 12.6): converges, needs more terms than e k a / 2
    assert 17 < cg.series_degree(4 * np.pi, 1e-10) < 60
    with pytest.raises(ValueError, match="degree"):
        cg.series_degree(4 * np.pi, 1e-10, max_degree=10)


def test_hundred_harmonics_vectorised():
    """M = 100 harmonics at 500 positions: exact vs linear superposition at small amplitude."""
    rng = np.random.default_rng(3)
    lam = np.linspace(0.02, 0.3, 100)
    k = 2 * np.pi / lam
    amp = 1e-6 * A0 / (k * R) / 100
    phase = rng.uniform(0, 2 * np.pi, 100)
    x = np.linspace(0, 0.5, 500)
    t0 = time.perf_counter()
    ex = cg.corrugated_contact(x, N, R, E, NU, MU, 5e-4, amp * np.cos(phase),
                               amp * np.sin(phase), lam)
    elapsed = time.perf_counter() - t0
    li = cg.corrugated_contact(x, N, R, E, NU, MU, 5e-4, amp * np.cos(phase),
                               amp * np.sin(phase), lam, method="linear")
    assert np.max(np.abs(ex.half_width - li.half_width)) < 1e-3 * np.max(
        np.abs(li.half_width - A0))
    assert np.max(np.abs(ex.stick_half_width - li.stick_half_width)) < 2e-3 * np.max(
        np.abs(li.stick_half_width - np.mean(li.stick_half_width)))
    assert elapsed < 20.0   # generous; the benchmark prints the real figure


def test_near_limit_4_2_against_halfspace_solver():
    """Amplitude near the limit (4.2), k^2 R |Z| = 0.8, at a trough (flattest gap)."""
    ratio = 0.1
    lam = A0 / ratio
    k = 2 * np.pi / lam
    za = 0.8 / (k * k * R)
    xc = 0.5 * lam                                     # trough of Z_A cos kX
    def gap(xb):
        return xb ** 2 / (2 * R) - za * np.cos(k * (xc + xb))
    ref = solve_normal_2d(gap, N, E, NU, -3 * A0, 3 * A0, 600)
    res = cg.corrugated_contact(xc, N, R, E, NU, MU, 0.0, [za], [0.0], [lam])
    assert len(ref.zones) == 1
    assert abs(0.5 * (ref.contact_end - ref.contact_start) - res.half_width) < 2e-3 * A0
    assert res.half_width > 1.3 * A0                   # far from Hertz: flattened gap


def test_wear_is_not_computed_by_the_contact_module():
    """The contact on a corrugated rail does not depend on the wear models (the wear module
    depends on it): the former keywords wear_coefficient / wear_model are a TypeError naming
    their replacement, railcontact.wear.corrugated_wear_depth (tests/test_wear.py)."""
    lam, k, za, zb = _surface(0.12, 0.01)
    for kw in ({"wear_coefficient": 1e-10}, {"wear_model": "material_point"}):
        with pytest.raises(TypeError, match=r"railcontact\.wear\.corrugated_wear_depth"):
            cg.corrugated_contact(0.0, N, R, E, NU, MU, 1e-4, [za], [zb], [lam], **kw)
    assert "wear_depth" not in cg.CorrugatedContact._fields


@pytest.mark.parametrize("ratio, degree", [(0.1, 12), (0.3, 20), (0.6, 30)])
def test_bessel_forms_equal_polynomial_series_of_chapter_3(ratio, degree):
    """The thesis' route (4.18)-(4.26): Taylor series of the corrugated gap of degree ``degree``
    solved with the chapter-3 polynomial approach (railcontact.polynomial, (k!)^2 matrices);
    its a, Delta, a*, T converge to the exact Bessel-function solution of (4.31), (4.33), (4.57),
    (4.67)."""
    from math import factorial

    from railcontact.polynomial import solve_normal_polynomial, solve_tangential_polynomial
    lam, k, za, zb = _surface(ratio, 0.05)
    xc = 0.3 * lam
    zeta = (za - 1j * zb) * np.exp(1j * k * xc)
    z = np.array([-np.real(zeta * (1j * k) ** n) / factorial(n) for n in range(degree + 1)])
    z[2] += 1 / (2 * R)
    nc = solve_normal_polynomial(z, N, E, NU, centre_guess=0.0, half_width_guess=A0)
    r = 0.5
    xi = MU * A0 * (1 - r) / R
    tc = solve_tangential_polynomial(nc, MU, creepage=-xi)
    res = cg.corrugated_contact(xc, N, R, E, NU, MU, xi, [za], [zb], [lam])
    assert abs(nc.half_width - res.half_width) < 1e-8 * A0
    assert abs(nc.centre - res.patch_shift) < 1e-8 * A0
    assert abs(tc.stick_half_width - res.stick_half_width) < 1e-7 * A0
    assert abs(abs(tc.tangential_force) - res.tangential_force) < 1e-7 * MU * N


def test_zero_and_tiny_creepage_without_cancellation():
    """xi -> 0: the stick offset a - a* and |T| are computed as differences in closed form
    (second-order Taylor below k (a - a*) = 1e-4), so T = 0 exactly at xi = 0 and Carter's
    2 f - f^2 is reproduced to rounding on a smooth rail down to f = 1e-14."""
    from railcontact.carter import carter_critical_creepage
    res = cg.corrugated_contact(0.01, N, R, E, NU, MU, 0.0, [1e-6], [0.0], [0.05])
    assert float(res.tangential_force) == 0.0
    assert float(res.stick_half_width) == float(res.half_width)
    xi_c = float(carter_critical_creepage(N, R, E, NU, MU))
    for method in ("exact", "linear"):
        for f in (1e-14, 1e-10, 1e-6, 0.3):
            res = cg.corrugated_contact(0.01, N, R, E, NU, MU, f * xi_c, [0.0], [0.0], [0.05],
                                        method=method)
            assert float(res.tangential_force) / (MU * N * (2 * f - f * f)) == pytest.approx(
                1.0, rel=1e-12)
    # corrugated: T / (2 f mu N) is continuous across the Taylor / direct switch
    x = np.linspace(0, 0.05, 5)
    lam = 0.05
    k = 2 * np.pi / lam
    fs = np.geomspace(1e-9, 1e-3, 13)
    ratios = np.array([cg.corrugated_contact(x, N, R, E, NU, MU, f * xi_c, [3e-6], [1e-6],
                                             [lam]).tangential_force / (2 * f * MU * N)
                       for f in fs])
    # linear in f near 0: T/(2 f mu N) changes by O(f) only, smoothly through the switch
    assert np.all(np.abs(ratios - ratios[0]) < 3 * fs[:, None])
    assert np.all(ratios > 0)
    # the switch point k (a - a*) = 1e-4 lies inside the scanned range
    assert k * 1e-9 * xi_c * R / MU < 1e-4 < k * 1e-3 * xi_c * R / MU


# --------------------------------------------------------------------------------------------
# the FMU's per-step call (CorrugatedContactSolver, the same kernels) against corrugated_contact
# --------------------------------------------------------------------------------------------
def _solver(rail_position, normal_load, radius, youngs_modulus, poisson_ratio,
            friction_coefficient, creepage, amplitudes_cos, amplitudes_sin, wavelengths,
            method="exact"):
    """CorrugatedContactSolver.contact (the FMU's per-step call) with corrugated_contact's
    arguments."""
    solver = cg.CorrugatedContactSolver(radius, youngs_modulus, poisson_ratio, method)
    return solver.contact(rail_position, normal_load, friction_coefficient, creepage,
                          amplitudes_cos, amplitudes_sin, wavelengths)


def _scalar_contact_cases():
    """Seeded surfaces and contact states over the regimes the FMU meets: zero, tiny and large
    amplitudes (sum k^2 R |Z| up to 0.95), M = 1, 3, 10 harmonics, k a0 in [0.01, 3], creepage
    0, tiny, r_a0 near 1, partial slip, r_a0 near 0 and full sliding, both signs."""
    rng = np.random.default_rng(2024)
    mu, radius = 0.3, 0.46
    for m in (1, 3, 10):
        for amplitude in ("zero", "tiny", "small", "large"):
            for creep in ("zero", "tiny", "near_stick", "partial", "near_sliding", "sliding"):
                n_load = float(10 ** rng.uniform(5.0, 7.0))
                a0 = float(np.sqrt(8 * (1 - NU ** 2) * radius * n_load / (np.pi * E)))
                ka0 = 10 ** rng.uniform(-2.0, np.log10(3.0), m)
                lam = 2 * np.pi * a0 / ka0
                k = 2 * np.pi / lam
                curv = {"zero": 0.0, "tiny": 1e-12, "small": 1e-3,
                        "large": 0.95}[amplitude] * rng.dirichlet(np.ones(m))
                phase = rng.uniform(0, 2 * np.pi, m)
                amp = curv / (k * k * radius)
                xi_c = mu * a0 / radius
                frac = {"zero": 0.0, "tiny": 1e-9, "near_stick": 1e-5,
                        "partial": rng.uniform(0.1, 0.9), "near_sliding": 1 - 1e-6,
                        "sliding": 3.0}[creep]
                xi = float(rng.choice([-1.0, 1.0])) * frac * xi_c
                x = float(rng.uniform(0.0, 2 * lam.max()))
                yield (x, n_load, radius, E, NU, mu, xi, list(amp * np.cos(phase)),
                       list(amp * np.sin(phase)), list(lam))


def test_scalar_corrugated_contact_equals_array_function():
    """CorrugatedContactSolver.contact (the FMU's per-step call) against corrugated_contact
    (both methods). Bounds: "linear" 8 eps (the same closed forms, operations in the same order
    up to the sums over harmonics; relative to the size of the terms summed); "exact": a,
    Delta, a* within 1e-13 (a0 + R sum k |Z|) -- the Newton step tolerance of both paths (the
    same iterations from the same start; libm's sin/cos and the order of the sums over
    harmonics round differently, so the iterates may differ by ulps and stop one step apart)
    -- and |T| within 1e-13 mu N. Measured: 0.81 eps ("exact"), 0.99 eps ("linear") of those
    scales. (The wear depth's pair, wear.corrugated_wear_depth_unchecked against
    wear.corrugated_wear_depth: tests/test_wear.py.)"""
    eps = float(np.finfo(float).eps)
    worst = {"exact": 0.0, "linear": 0.0}
    for args in _scalar_contact_cases():
        x, n_load, radius, e_mod, nu, mu, xi, za, zb, lam = args
        k = 2 * np.pi / np.asarray(lam)
        a0 = float(np.sqrt(8 * (1 - nu ** 2) * radius * n_load / (np.pi * e_mod)))
        length = a0 + radius * float(np.sum(k * np.hypot(za, zb)))
        for method in ("exact", "linear"):
            ref = cg.corrugated_contact(*args, method=method)
            got = _solver(*args, method)
            assert len(got) == 4 and all(isinstance(v, float) for v in got)
            tol = 1e-13 if method == "exact" else 8 * eps
            for i, scale in ((0, length), (1, length), (2, length), (3, mu * n_load)):
                err = abs(got[i] - float(ref[i])) / scale
                worst[method] = max(worst[method], err / eps)
                assert err <= tol, (method, i, args, err)
    print("worst, in eps of the scales:", worst)


def test_scalar_corrugated_contact_hard_cases_match_array_function():
    """The branches the scalar path hands to corrugated_contact (bracketed fallback, the mirror
    root, condition (4.2) violated) give the public function's results exactly, or its error."""
    ratio, curv = 0.05, 0.99           # long wave at the edge of (4.2): the mirror-root case
    lam = A0 / ratio
    za = curv / ((2 * np.pi / lam) ** 2 * R)
    for x in np.linspace(0.0, lam, 17):
        args = (float(x), N, R, E, NU, MU, 1e-4, [za], [0.0], [lam])
        ref = cg.corrugated_contact(*args)
        got = _solver(*args)
        length = A0 + R * 2 * np.pi / lam * za
        for i in range(4):
            scale = length if i < 3 else MU * N
            assert abs(got[i] - float(ref[i])) <= 1e-13 * scale, (x, i)
    with pytest.raises(ValueError, match="curvature_amplitude"):
        _solver(0.0, N, R, E, NU, MU, 0.0, [za / 0.99 * 1.01], [0.0], [lam])
    # sum k^2 R |Z| > 1 with each harmonic < 1: the public function solves or raises, and
    # so does the scalar path, with the same results
    z2 = 0.6 / ((2 * np.pi / lam) ** 2 * R)
    for x in np.linspace(0.0, lam, 9):
        args = (float(x), N, R, E, NU, MU, 0.0, [z2, z2], [0.0, 0.0], [lam, lam])
        try:
            ref = [float(v) for v in cg.corrugated_contact(*args)[:4]]
        except ValueError as exc:
            with pytest.raises(ValueError, match=str(exc)[:30].replace("(", ".")):
                _solver(*args)
            continue
        got = _solver(*args)
        for i in range(4):
            scale = A0 + R * 4 * np.pi / lam * z2 if i < 3 else MU * N
            assert abs(got[i] - ref[i]) <= 1e-13 * scale, (x, i)


def test_scalar_series_truncation_error_is_bit_identical():
    """The FMU's series estimate (the kernel module's series_relative_error, which the public
    series_truncation_error calls per element) equals the public function's."""
    from railcontact import _corrugation_kernels as kernels
    rng = np.random.default_rng(7)
    for ka in list(rng.uniform(0, 20, 200)) + [0.0, 1e-300, 3.0]:
        degree = int(np.ceil(np.e * ka)) + 12 - int(rng.integers(0, 12))
        got = kernels.series_relative_error(float(ka), max(degree, 1))
        assert isinstance(got, float)
        assert got == float(cg.series_truncation_error(ka, max(degree, 1))[1])


@pytest.mark.parametrize("method", ["linear", "exact"])
@pytest.mark.parametrize("load", [5e-324, 1e-310, 1.0e-297])
def test_underflowing_load_is_rejected_like_the_rest_of_the_package(method, load):
    """A load whose normalised value 8 (1 - nu^2) N / (pi E) is below the smallest normal
    double (N below ~4e-297 N/m here): a0 underflows (5e-324 N/m: a0 = 0, and a0*/a0 divided
    by zero) or loses its precision (subnormal). Both methods and the scalar path raise the
    ValueError of railcontact.roughness.rough_rail_contact naming normal_load."""
    args = (0.01, load, R, E, NU, MU, 1e-3, [2e-5], [0.0], [0.1])
    match = r"normal_load must be > 0 with a normalised load 8 \(1 - nu\^2\) N / \(pi E\)"
    with pytest.raises(ValueError, match=match):
        cg.corrugated_contact(*args, method=method)
    with pytest.raises(ValueError, match=match):
        _solver(*args, method=method)


@pytest.mark.parametrize("method", ["linear", "exact"])
def test_smallest_accepted_load_is_the_zero_load_limit(method):
    """Just above the limit (N~ = 2.3e-308 m) the contact is the zero-load limit: a and a*
    of order sqrt(R N~) ~ 1e-154 m, T = mu N (a0* = 0: full sliding), the shift that of the gap minimum (the value at N = 1e-200 N/m), and the scalar
    path equal to the array path."""
    n_min = 2.3e-308 * np.pi * E / (8 * (1 - NU**2))
    args = (0.01, n_min, R, E, NU, MU, 1e-3, [2e-5], [0.0], [0.1])
    res = cg.corrugated_contact(*args, method=method)
    ref = cg.corrugated_contact(0.01, 1e-200, R, E, NU, MU, 1e-3, [2e-5], [0.0], [0.1],
                                method=method)
    a0 = np.sqrt(2.3e-308 * R)
    assert float(res.half_width) == pytest.approx(a0, rel=0.05)
    # a0* = 0 (full sliding); the linear method adds its O(k R Z) perturbation to it
    assert 0.0 <= float(res.stick_half_width) < 0.05 * a0
    assert float(res.tangential_force) == pytest.approx(MU * n_min, rel=1e-6)
    assert float(res.patch_shift) == pytest.approx(float(ref.patch_shift), rel=1e-9)
    a, d, ast, t = _solver(*args, method=method)
    assert (a, d, ast, t) == pytest.approx((float(res.half_width), float(res.patch_shift),
                                            float(res.stick_half_width),
                                            float(res.tangential_force)), rel=1e-12)


# ---------------------------------------------------------------------------------------------
# the compiled kernels behind solve_normal_exact, solve_stick_zone_exact and the exact method
# ---------------------------------------------------------------------------------------------
def test_kernel_bessel_functions_are_scipys():
    """The kernels' J0, J1 (scipy.special.cython_special linked by symbol name) are the
    ufuncs' values bit for bit, on seeded arguments over the range the contact uses."""
    from railcontact import _corrugation_kernels as kernels
    z = np.random.default_rng(8).uniform(0.0, 80.0, 2000)
    assert np.array_equal([kernels.j0(v) for v in z], j0(z))
    assert np.array_equal([kernels.j1(v) for v in z], j1(z))
    # J_n (the wear series): scipy's cython jv against the ufunc, to 2 ulp of max(|J_n|, 1e-16)
    from scipy.special import jv
    n = np.random.default_rng(9).integers(2, 80, 2000)
    got = np.array([kernels.jv(float(m), v) for m, v in zip(n, z)])
    want = jv(n, z)
    assert np.all(np.abs(got - want) <= 2 * np.finfo(float).eps
                  * np.maximum(np.abs(want), 1e-16))


def test_each_position_is_solved_on_its_own():
    """corrugated_contact (exact) on an array of positions equals the calls at one position
    each, bit for bit: the Newton iterations of one position do not depend on the others
    (several harmonics, long and short waves, partial slip)."""
    rng = np.random.default_rng(12)
    lam = np.array([0.05, 0.013, 0.2])
    k = 2 * np.pi / lam
    za, zb = 0.3 / (k * k * R) * np.array([1.0, 0.5, -0.8]) / 3, 0.2 / (k * k * R) / 3
    x = rng.uniform(-0.1, 0.1, 30)
    for xi in (0.0, 1e-4, 2e-3):
        arr = cg.corrugated_contact(x, N, R, E, NU, MU, xi, za, zb * np.ones(3), lam)
        for i in range(0, 30, 3):
            one = cg.corrugated_contact(x[i], N, R, E, NU, MU, xi, za, zb * np.ones(3), lam)
            assert (arr.half_width[i], arr.patch_shift[i], arr.stick_half_width[i],
                    arr.tangential_force[i]) == (one.half_width, one.patch_shift,
                                                 one.stick_half_width, one.tangential_force)
