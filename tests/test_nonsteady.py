"""Tests of railcontact.nonsteady (Nielsen 1998, Ch. 7).

Independent checks:
* (7.15) and (7.20) against a quadrature of the Cerruti kernel (2.26) over a finite rectangle;
* the linearised coefficients (7.37)-(7.45) and the transfer function against a time-domain
  simulation of the same model that uses no Bessel function and no linearisation: a*(t) from the
  solvability condition of (7.27) by root finding with Gauss-Chebyshev quadrature, T(t) from the
  bounded polynomial-form solution by quadrature, u_x(x0, t) from (7.14)/(7.19) with the moving
  stick zone, the time derivative in (7.10) spectrally, first harmonics by FFT;
* Gross-Thebing's (7.57): equal at J0(k a0) = 0 and as a0/L -> 0, as the thesis states.
"""

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq
from scipy.special import jn_zeros

from railcontact.hertz import hertz_2d
from railcontact.nonsteady import (
    displacement_factor, gross_thebing_transfer_function_normalised,
    nonsteady_amplitude_phase_normalised,
    nonsteady_coefficients, nonsteady_time_response, nonsteady_transfer_function_normalised)

E, NU, R, N, MU = 210e9, 0.28, 0.5, 1.0e6, 0.3
A0 = float(hertz_2d(N, R, E, NU).a0)
GAMMA = 4 * (1 - NU ** 2) / (np.pi * E)


def _g_quadrature(x0, a, b, shape):
    """u at (x0, 0) per unit force per length, over Gamma: Cerruti g11 (2.26) integrated exactly
    in y over [-b, b] and numerically in x with the uniform or elliptic weight."""
    def inner(d):
        d = abs(d)
        return 2 * (1 - NU) * np.arcsinh(b / d) + 2 * NU * b / np.hypot(d, b)

    if shape == "uniform":
        w = lambda z: 1 / (2 * a)  # noqa: E731
    else:
        w = lambda z: 2 / (np.pi * a * a) * np.sqrt(max(a * a - z * z, 0.0))  # noqa: E731
    f = lambda z: w(z) * inner(x0 - z)  # noqa: E731
    val = quad(f, -a, x0, limit=400)[0] + quad(f, x0, a, limit=400)[0]
    return val * (2 * (1 + NU) / (np.pi * E)) / GAMMA   # (the kernel factor of (2.26))


@pytest.mark.parametrize("x0_ratio", [0.0, 0.3, -0.6])
@pytest.mark.parametrize("shape", ["uniform", "elliptic"])
def test_displacement_functions_7_15_and_7_20_by_quadrature(x0_ratio, shape):
    a, b = 2e-3, 2e-3 * 400
    x0 = x0_ratio * a
    if shape == "uniform":   # (7.15)
        g = (1 / (1 - NU) + np.log(2 * b) + 0.5 * (x0 / a) * np.log((a - x0) / (a + x0))
             - 0.5 * np.log(a * a - x0 * x0))
    else:                    # (7.20)
        g = (1 + NU) / (2 * (1 - NU)) + np.log(4 * b) - np.log(a) - (x0 / a) ** 2
    assert _g_quadrature(x0, a, b, shape) == pytest.approx(g, abs=1e-4)
    if x0 == 0.0:
        model = "johnson" if shape == "uniform" else "carter"
        lam = displacement_factor(model, NU, b / a, 1.0)
        assert lam == pytest.approx(g, abs=1e-12)


# ------------------------------------------------------------------ time-domain simulation
def _simulate(k, r, ua, ub, model, n_t=64, n_q=64, bq=20.0):
    """First harmonics of a*(t), T(t), xi(t) of the non-linearised model (see module doc)."""
    c = MU * np.pi * E / (4 * (1 - NU ** 2))
    a_s0 = r * A0
    xi0 = MU * (A0 - a_s0) / R
    v = 1.0
    w = k * v
    yq = np.cos((2 * np.arange(1, n_q + 1) - 1) * np.pi / (2 * n_q))
    b = bq * A0
    x0 = A0 - a_s0

    def fprime(z, t):
        return MU * k * (ua * np.cos(k * (z + v * t)) + ub * np.sin(k * (z + v * t)))

    def solv(a_s, t):
        xc = A0 - a_s
        return MU * xc / R + np.mean(fprime(xc + a_s * yq, t)) - xi0

    if model == "carter":
        def g(x, a):
            return (1 + NU) / (2 * (1 - NU)) + np.log(4 * b) - np.log(a) - (x / a) ** 2
    else:
        def g(x, a):
            return (1 / (1 - NU) + np.log(2 * b) + 0.5 * (x / a) * np.log((a - x) / (a + x))
                    - 0.5 * np.log(a * a - x * x))

    ts = np.arange(n_t) * (2 * np.pi / w) / n_t
    a_t, f_t, u_t = [], [], []
    for t in ts:
        a_s = brentq(solv, 0.5 * a_s0, min(1.5 * a_s0, 2 * A0), args=(t,), xtol=1e-16,
                     rtol=1e-15)
        xc = A0 - a_s
        y = a_s * yq
        p_y = xi0 - fprime(xc + y, t) - MU * (xc + y) / R
        force = MU * N + (a_s / GAMMA) * np.mean(p_y * yq)
        u = GAMMA * (MU * N * g(x0, A0) + (force - MU * N) * g(x0 - xc, a_s))
        a_t.append(a_s)
        f_t.append(force)
        u_t.append(u)
    a_t, f_t, u_t = map(np.asarray, (a_t, f_t, u_t))
    dudt = np.fft.ifft(1j * w * np.fft.fftfreq(n_t, 1.0 / n_t) * np.fft.fft(u_t)).real
    xi_t = MU * (A0 - a_t) / R + dudt / v

    def harm(x):
        return 2 * np.mean(x * np.exp(-1j * w * ts))
    return harm(a_t), harm(f_t), harm(xi_t), np.mean(f_t), np.mean(xi_t)


@pytest.mark.parametrize("model", ["carter", "johnson"])
@pytest.mark.parametrize("ka_star, r", [(0.7, 0.6), (3.0, 0.6), (2.404825557695773, 1.0),
                                        (1.3, 0.25)])
def test_coefficients_against_time_domain_simulation(model, ka_star, r):
    k = ka_star / (r * A0)
    ua, ub = 0.6, -0.8
    scale = 1e-5 * r * A0 / (k * R)            # a* amplitude ~ 1e-5 a0*
    a_h, t_h, x_h, t_mean, x_mean = _simulate(k, r, ua * scale, ub * scale, model)
    co = nonsteady_coefficients(k, N, R, E, NU, MU, r, model=model)
    z = (ua - 1j * ub) * scale
    a_c = (co.stick_1 - 1j * co.stick_2) * z
    t_c = (co.force_1 - 1j * co.force_2) * z
    x_c = (co.creepage_1 - 1j * co.creepage_2) * z
    tol = 1e-6   # measured: ~1e-10 (linearisation error at this amplitude)
    assert abs(a_h - a_c) <= tol * abs(a_c) + 1e-12 * A0
    assert abs(t_h - t_c) <= tol * abs(t_c)
    assert abs(x_h - x_c) <= tol * abs(x_c)
    assert t_mean == pytest.approx(co.force_steady, rel=1e-6, abs=1e-9 * MU * N)
    assert x_mean == pytest.approx(co.creepage_steady, rel=1e-6, abs=1e-9)
    # the normalised transfer function is the same ratio
    h = nonsteady_transfer_function_normalised(k * A0 / (2 * np.pi), r, poisson_ratio=NU,
                                               model=model)
    assert (t_c / x_c) / (r * A0 * np.pi * E / (4 * (1 - NU ** 2))) == pytest.approx(h, rel=1e-9)
    # and the time response reproduces the same harmonics
    ts = np.linspace(0, 2 * np.pi / k, 65)[:-1]
    a_t, f_t, xi_t = nonsteady_time_response(ts, 1.0, ua * scale, ub * scale, co)
    assert 2 * np.mean(f_t * np.exp(-1j * k * ts)) == pytest.approx(t_c, rel=1e-9)
    assert 2 * np.mean(xi_t * np.exp(-1j * k * ts)) == pytest.approx(x_c, rel=1e-9)


# ------------------------------------------------------------------ claims of Sec. 7.2
@pytest.mark.parametrize("variant", ["derived", "printed"])
def test_equal_to_gross_thebing_at_bessel_zeros(variant):
    """Fig. 7.2: identical to (7.57) where J0(k a0) = 0 (r_a0 = 1, Johnson)."""
    ka = jn_zeros(0, 4)
    h = nonsteady_transfer_function_normalised(ka / (2 * np.pi), 1.0, model="johnson",
                                               variant=variant, poisson_ratio=NU)
    g = gross_thebing_transfer_function_normalised(ka / (2 * np.pi), poisson_ratio=NU)
    np.testing.assert_allclose(np.abs(h), np.abs(g), rtol=1e-12)
    np.testing.assert_allclose(np.exp(1j * np.angle(h)), np.exp(1j * np.angle(g)), atol=1e-12)
    # elsewhere they differ (the slip zone at the trailing edge)
    h1 = nonsteady_transfer_function_normalised(0.5 / (2 * np.pi), 1.0, model="johnson")
    g1 = gross_thebing_transfer_function_normalised(0.5 / (2 * np.pi))
    assert abs(abs(h1) - abs(g1)) > 0.01


def test_equal_to_gross_thebing_as_wave_ratio_to_zero():
    """Both -> Carter's quasi-static slope; the difference vanishes linearly in a0/L."""
    wr = np.array([1e-2, 1e-3, 1e-4])
    for model in ("johnson", "carter"):
        for r in (1.0, 0.4):
            h = nonsteady_transfer_function_normalised(wr, r, model=model)
            g = gross_thebing_transfer_function_normalised(wr, stick_ratio=r)
            d = np.abs(h - g)
            assert d[-1] < 2e-3 and d[1] / d[0] < 0.2 and d[2] / d[1] < 0.2
            assert abs(h[-1] - 1) < 1e-2
    assert nonsteady_transfer_function_normalised(0.0, 0.3) == 1.0


def test_printed_variant_mirror_of_derived():
    """The printed (7.47)-(7.48) / (7.50)-(7.51): same quasi-static amplitude, phase pi - phase
    (mirrored frame and the thesis' force sign); amplitude within 15 % of the derivation."""
    wr = np.linspace(0.001, 1.5, 60)
    for model in ("johnson", "carter"):
        hd = nonsteady_transfer_function_normalised(wr, 1.0, model=model)
        hp = nonsteady_transfer_function_normalised(wr, 1.0, model=model, variant="printed")
        assert abs(hp[0]) == pytest.approx(abs(hd[0]), rel=1e-3)
        assert np.cos(np.angle(hp[0]) - (np.pi - np.angle(hd[0]))) > 1 - 1e-4
        assert np.all(np.abs(np.abs(hp) / np.abs(hd) - 1) < 0.15)


def test_gross_thebing_close_with_a0_star_fig_7_3():
    """Fig. 7.3: Gross-Thebing with a0 -> a0* is close to the Carter-based result for all r_a0
    (measured: |H| within 7 %, phase within 0.06 rad for a0/L <= 2)."""
    wr = np.linspace(0.001, 2.0, 200)[:, None]
    r = np.array([0.1, 0.5, 0.8, 1.0])[None, :]
    h = nonsteady_transfer_function_normalised(wr, r)
    g = gross_thebing_transfer_function_normalised(wr, stick_ratio=r)
    assert h.shape == (200, 4)
    assert np.max(np.abs(np.abs(h) / np.abs(g) - 1)) < 0.07
    assert np.max(np.abs(np.angle(h) - np.angle(g))) < 0.06


def test_vectorised_amplitude_phase_equals_scalar():
    wr = np.array([0.05, 0.3, 1.1])
    r = np.array([[0.2], [0.9]])
    amp, ph = nonsteady_amplitude_phase_normalised(wr, r, model="carter")
    assert amp.shape == (2, 3)
    for i in range(2):
        for j in range(3):
            a1, p1 = nonsteady_amplitude_phase_normalised(wr[j], r[i, 0])
            assert amp[i, j] == pytest.approx(a1, rel=1e-14) and ph[i, j] == pytest.approx(p1)


def test_large_wave_ratio():
    """a0/L large: finite, decaying like 1/(k a0* Lambda); the force lags by about 90 deg."""
    wr = np.array([5.0, 20.0, 100.0])
    for r in (1.0, 0.3):
        amp, ph = nonsteady_amplitude_phase_normalised(wr, r)
        lam = displacement_factor("carter", 0.28, 20.0, r)
        prod = amp * 2 * np.pi * wr * r * lam
        assert np.all(np.isfinite(amp))
        assert np.all((prod > 0.95) & (prod < 1.1))   # measured 1.03-1.05
        assert np.all(np.abs(ph + np.pi / 2) < 0.35)


def test_time_response_amplitude_guard_and_errors():
    co = nonsteady_coefficients(2 * np.pi / 0.05, N, R, E, NU, MU, 0.5)
    with pytest.raises(ValueError, match="amplitude_a"):
        nonsteady_time_response([0.0, 1e-3], 10.0, 1.0, 0.0, co)
    with pytest.raises(ValueError, match="stick_ratio"):
        nonsteady_transfer_function_normalised(0.1, 0.0)
    with pytest.raises(ValueError, match="stick_ratio"):
        nonsteady_transfer_function_normalised(0.1, 1.2)
    with pytest.raises(ValueError, match="wave_ratio"):
        nonsteady_transfer_function_normalised(-0.1, 0.5)
    with pytest.raises(ValueError, match="pseudo_width_ratio"):
        nonsteady_transfer_function_normalised(0.1, 0.5, pseudo_width_ratio=1.0)
    with pytest.raises(ValueError, match="model"):
        nonsteady_transfer_function_normalised(0.1, 0.5, model="kalker")
    with pytest.raises(ValueError, match="variant"):
        nonsteady_transfer_function_normalised(0.1, 0.5, variant="x")
    with pytest.raises(ValueError, match="poisson_ratio"):
        gross_thebing_transfer_function_normalised(0.1, poisson_ratio=0.5)
    with pytest.raises(ValueError, match="friction_coefficient"):
        nonsteady_coefficients(10.0, N, R, E, NU, 0.0, 0.5)
    with pytest.raises(ValueError, match="velocity"):
        nonsteady_time_response([0.0], 0.0, 1e-9, 0.0, co)


def test_johnson_and_carter_almost_identical_at_full_stick():
    """Sec. 7.2: for r_a0 = 1 the two approximations of u_x(x0, t) give almost the same result
    (they differ only in Lambda by ln 2 - 1/2; measured: |H| within 4.5 %, phase 0.023 rad)."""
    wr = np.linspace(0.0, 2.0, 400)
    hj = nonsteady_transfer_function_normalised(wr, 1.0, model="johnson")
    hc = nonsteady_transfer_function_normalised(wr, 1.0, model="carter")
    assert np.max(np.abs(np.abs(hj) / np.abs(hc) - 1)) < 0.05
    assert np.max(np.abs(np.angle(hj) - np.angle(hc))) < 0.03
    lam_j = displacement_factor("johnson", 0.28, 20.0)
    lam_c = displacement_factor("carter", 0.28, 20.0)
    assert lam_j - lam_c == pytest.approx(0.5 - np.log(2.0), abs=1e-12)


# --------------------------------------------------------------------------------------------
# time-domain relaxation model: sigma from H (independently), accuracy, the step factor
# --------------------------------------------------------------------------------------------
from railcontact.nonsteady import (  # noqa: E402
    relaxation_factor, relaxation_length, relaxation_length_function,
    relaxation_step_error_bound, relaxation_transfer_function_normalised)


@pytest.mark.parametrize("model", ["carter", "johnson"])
@pytest.mark.parametrize("r", [1.0, 0.6, 0.2, 0.03])
@pytest.mark.parametrize("bq", [20.0, 5.0])
def test_relaxation_length_is_the_first_order_term_of_h(model, r, bq):
    """Complex polynomial fit of 1/H (thesis' transfer function) at a0/L in [1e-5, 1e-4]:
    1/H = 1 + i k sigma - (k a0*)^2/2 + O(k^3); sigma from the fit, not from the formula."""
    ratio = np.linspace(1e-5, 1e-4, 10)
    k_a0 = 2 * np.pi * ratio
    inv = 1.0 / nonsteady_transfer_function_normalised(ratio, r, model=model,
                                                      pseudo_width_ratio=bq)
    coef = np.polyfit(k_a0, inv, 3)                 # complex least squares, c0 + c1 x + ...
    assert coef[3] == pytest.approx(1.0, abs=1e-12)
    sigma_fit = coef[2].imag                        # sigma / a0
    assert abs(coef[2].real) < 1e-8
    want = relaxation_length(1.0, r, poisson_ratio=0.28, pseudo_width_ratio=bq, model=model)
    assert sigma_fit == pytest.approx(want, rel=1e-7)
    assert coef[1].real == pytest.approx(-r * r / 2, rel=1e-4)     # the term the model lacks
    # (the brief's a0* (1 + Lambda) is not the expansion: Lambda - 1 is)
    lam = displacement_factor(model, 0.28, bq, r)
    assert want == pytest.approx(r * (lam - 1.0), rel=1e-14)


def test_relaxation_length_limits_and_scalar_function():
    r = np.array([0.0, 1e-300, 1e-12, 1e-3, 0.1, 0.5, 0.9, 1.0])
    s = relaxation_length(0.005, r, poisson_ratio=0.28)
    assert s[0] == 0.0 and np.all(np.isfinite(s)) and np.all(s[1:] > 0)
    assert np.all(np.diff(s) > 0)                   # grows with the stick zone
    assert s[2] < 0.005 * 1e-10                     # sigma -> 0 in full sliding (r ln r)
    for model in ("carter", "johnson"):
        f = relaxation_length_function(0.3, 7.0, model)
        for a0 in (0.0, 1e-4, 7e-3):
            for ri in r:
                assert f(a0, float(ri)) == pytest.approx(float(relaxation_length(
                    a0, ri, poisson_ratio=0.3, pseudo_width_ratio=7.0, model=model)),
                    rel=1e-15, abs=0.0)
    with pytest.raises(ValueError, match="stick_ratio must be in"):
        relaxation_length(0.005, 1.2, poisson_ratio=0.28)
    with pytest.raises(ValueError, match="contact_half_width must be in"):
        relaxation_length(-1.0, 0.5, poisson_ratio=0.28)
    with pytest.raises(ValueError, match="pseudo_width_ratio must be in"):
        relaxation_length(0.005, 0.5, poisson_ratio=0.28, pseudo_width_ratio=1.5)
    with pytest.raises(ValueError, match="model"):
        relaxation_length_function(0.28, 20.0, "hertz")
    with pytest.raises(ValueError, match="poisson_ratio must be in"):
        relaxation_length_function(0.5)


# documented in the module docstring: r_a0 -> a0/L below which |H_model/H - 1| < 1, 5, 10 %
_ACCURACY = {1.0: (0.0246, 0.0756, 0.140), 0.7: (0.0357, 0.114, 0.215),
             0.5: (0.0508, 0.169, 0.320), 0.3: (0.0869, 0.304, 0.585),
             0.1: (0.277, 1.07, 2.09)}


@pytest.mark.parametrize("r", sorted(_ACCURACY))
def test_first_order_model_accuracy_table(r):
    ratio = np.logspace(-5, 0.5, 40001)
    h = nonsteady_transfer_function_normalised(ratio, r)
    hm = relaxation_transfer_function_normalised(ratio, r)
    err = np.abs(hm / h - 1.0)
    assert err.max() < 0.27
    for tol, limit in zip((0.01, 0.05, 0.10), _ACCURACY[r]):
        first = ratio[np.argmax(err >= tol)]
        assert first == pytest.approx(limit, rel=0.01), tol
        assert np.all(err[ratio < 0.99 * limit] < tol)
    # in k a0*: 1 % up to ~0.155, 5 % up to ~0.46, 10 % up to ~0.85 (all r_a0 <= 1)
    k_star = 2 * np.pi * ratio * r
    assert np.all(err[k_star < 0.15] < 0.01) and np.all(err[k_star < 0.45] < 0.05)
    assert np.all(err[k_star < 0.84] < 0.10)
    # the Johnson stress gives the same picture within 3 % of the limits
    hj = nonsteady_transfer_function_normalised(ratio, r, model="johnson")
    ej = np.abs(relaxation_transfer_function_normalised(ratio, r, model="johnson") / hj - 1)
    assert ratio[np.argmax(ej >= 0.01)] == pytest.approx(_ACCURACY[r][0], rel=0.03)


def test_relaxation_factor_edge_cases_and_scalar_equal():
    from railcontact.nonsteady import _relaxation_factor
    d = np.array([0.0, 1e-300, 1e-9, 0.01, 1.0, 1e300, np.inf])
    for s0, s1 in ((0.02, 0.02), (0.02, 0.005), (1e-320, 0.02), (0.0, 0.02), (0.02, 0.0),
                   (5e-324, 5e-324)):
        q = relaxation_factor(d, s0, s1)
        assert np.all((q >= 0) & (q <= 1)) and np.all(np.isfinite(q))
        if s0 > 0 and s1 > 0:
            assert q[0] == 1.0 and q[-1] == 0.0              # V = 0: held; long step: xi
            np.testing.assert_allclose(q[1:5], np.exp(-d[1:5] * (0.5 / s0 + 0.5 / s1)),
                                       rtol=1e-15)
        else:
            assert np.all(q == 0.0)                          # sigma = 0: no memory
        # the scalar path uses math.exp/expm1, the array path numpy's: equal to a few ulp
        scalar = np.array([_relaxation_factor(float(di), s0, s1) for di in d])
        np.testing.assert_array_max_ulp(scalar, q, maxulp=4)
    with pytest.raises(ValueError, match="rolled_distance must be in"):
        relaxation_factor(-1.0, 0.02)
    with pytest.raises(ValueError, match="relaxation_length_end must be in"):
        relaxation_factor(1.0, 0.02, np.nan)


@pytest.mark.parametrize("rho", [1e-6, 0.01, 0.3, 0.5, 0.9, 0.999])
def test_step_error_bound_is_the_max_over_step_lengths(rho):
    x = np.logspace(-6, 8, 200001)                  # d / sigma_min
    brute = np.max(np.exp(-rho * x) - np.exp(-x))
    got = relaxation_step_error_bound(rho * 0.02, 0.02)
    assert got == pytest.approx(brute, rel=1e-6)
    assert relaxation_step_error_bound(0.02, 0.02) == 0.0
    assert relaxation_step_error_bound(0.0, 0.02) == 1.0
    with pytest.raises(ValueError, match="relaxation_length_min must be <="):
        relaxation_step_error_bound(0.03, 0.02)


def test_relax_creepage_accurate_bounded_and_equal_to_the_scalar_path():
    from railcontact.nonsteady import _relax, _relaxation_exponent
    from railcontact.nonsteady import relax_creepage
    rng = np.random.default_rng(11)
    ratio = np.concatenate(([0.0, 1e-300], np.logspace(-12, 12, 300), [np.inf]))
    # constant sigma from 0 to 1: exactly 1 - exp(-d/sigma), no cancellation at small d
    got = relax_creepage(0.0, 1.0, ratio * 0.02, 0.02)
    np.testing.assert_allclose(got, -np.expm1(-ratio), rtol=2e-16, atol=0)
    assert got[0] == 0.0 and got[-1] == 1.0
    for _ in range(2000):
        old, xi = rng.normal(0, 1e-3, 2) * 10.0 ** rng.integers(-6, 3, 2)
        d = float(rng.choice(ratio)) * 0.02
        s0, s1 = (float(v) for v in rng.choice([0.0, 1e-30, 0.004, 0.02], 2))
        new = relax_creepage(old, xi, d, s0, s1)
        assert min(old, xi) <= new <= max(old, xi)
        # scalar path (math.expm1) against numpy's: a few ulp of the creepages' scale
        one = _relax(float(old), float(xi), _relaxation_exponent(d, s0, s1))
        assert abs(one - new) <= 4 * np.finfo(float).eps * max(abs(old), abs(xi))
        if s0 == 0.0 or s1 == 0.0:
            assert new == xi
    with pytest.raises(ValueError, match="relaxed_creepage must be"):
        relax_creepage(np.nan, 0.0, 1.0, 0.02)


def test_relax_creepage_between_creepages_near_the_float_limit():
    """xi_e = 1e308, xi = -1.8e308: xi - xi_e overflowed, and on a full-sliding step (sigma = 0,
    q = 0) inf * 0 gave NaN (the FMU's non-steady scene returned Fx = NaN). The result lies
    between the two and is xi exactly for sigma = 0."""
    from railcontact.nonsteady import _relax, relax_creepage

    big = float(np.finfo(float).max)
    assert relax_creepage(1e308, -big, 1e-3, 0.0) == -big
    for d in (1e-6, 1e-3, 1.0):
        got = float(relax_creepage(1e308, -big, d, 5e-3))
        assert -big <= got <= 1e308
        assert _relax(1e308, -big, d / 5e-3) == got
