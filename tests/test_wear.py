"""Tests of railcontact.wear (Nielsen Sec. 4.3): the linearised wear coefficients against
(a) the exact nonlinear wear integral at small amplitude, (b) the exact (4.92) with passage times
solved from (4.76)-(4.78), (c) a brute-force evaluation of (4.74) with the discretised half-space
solver (tests/test_reference_wear_direct.py), and (d) limiting cases derived independently (local Carter solution for long waves)."""

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.special import j0, j1, jv

from railcontact import corrugation as cg
from railcontact import wear


# --------------------------------------------------------------------------------------------
# (4.96): Carter slip-zone integral
# --------------------------------------------------------------------------------------------
@pytest.mark.parametrize("r", [0.0, 0.2, 0.5, 0.9])
def test_wear_shape_function_by_quadrature(r):
    """int_slip q s dx for Carter (stick zone [a-2a*, a]) = (pi/2) a^3 f(r) mu^2/R."""
    a, ast = 1.0, r

    def integrand(x):   # sqrt(a^2 - x^2) * sqrt(x*^2 - a*^2), x* = x - (a - a*)
        xs = x - (a - ast)
        return np.sqrt(a * a - x * x) * np.sqrt(xs * xs - ast * ast)

    val, _ = quad(integrand, -a, a - 2 * ast, limit=200)
    assert val == pytest.approx(0.5 * np.pi * wear.wear_shape_function(r), rel=1e-8)


def test_mean_wear_value():
    w0 = wear.mean_wear(1e-9, 0.3, 1e5, 0.5, 0.006, 0.5)
    assert w0 == pytest.approx(1e-9 * 0.09 * 1e5 * 0.006 / 0.5 * 0.375)


# --------------------------------------------------------------------------------------------
# (a) linearisation vs the exact nonlinear wear integral
# --------------------------------------------------------------------------------------------
@pytest.mark.parametrize("ratio, r", [(1e-3, 0.5), (0.05, 0.5), (0.15, 0.3), (0.3, 0.6),
                                      (0.1, 0.8), (0.5, 0.45), (1.0, 0.5), (2.0, 0.4)])
def test_linear_matches_exact_wear_integral(ratio, r):
    lin_mp = wear.wear_coefficients(ratio, r, "material_point")
    lin_pc = wear.wear_coefficients(ratio, r, "patch_coordinate")
    eps = min(1e-3, 0.05 / (2 * np.pi * ratio))
    ex = wear.wear_first_harmonic_exact(ratio, r, eps, phase=0.7, n_positions=48)
    scale = max(abs(lin_mp), abs(lin_pc), 1e-9)
    assert abs(ex["material_point"] - lin_mp) < 1e-4 * scale
    assert abs(ex["patch_coordinate"] - lin_pc) < 1e-4 * scale
    assert ex["mean"] == pytest.approx(wear.wear_shape_function(r), rel=1e-6)   # (4.96)


def test_quadrature_and_degree_converged():
    q = np.array([0.01, 0.3, 1.0, 2.0])
    r = np.array([0.1, 0.5, 0.7, 0.95])
    a = wear.wear_coefficients(q, r)
    b = wear.wear_coefficients(q, r, n_nodes=128, degree=80)
    assert np.max(np.abs(a - b) / np.abs(b)) < 1e-8


def test_long_wave_limits_local_carter():
    """a0/L -> 0: Carter with the local radius 1/R_eff = 1/R + k^2 Z gives, per rail position,
    dW/W0 = -r/(1+r) k^2 R Z (derived by hand from (2.52), (2.53), (4.96)); the material point adds
    the dwell factor 1 - Delta' = 1 + k^2 R Z: w1 / (k a0)^2 / f(r) -> -r/(1+r) and 1/(1+r)."""
    ratio = 1e-3
    for r in (0.1, 0.5, 0.9):
        f = wear.wear_shape_function(r)
        scale = (2 * np.pi * ratio) ** 2 * f
        pc = wear.wear_coefficients(ratio, r, "patch_coordinate") / scale
        mp = wear.wear_coefficients(ratio, r, "material_point") / scale
        assert pc.real == pytest.approx(-r / (1 + r), abs=1e-3)
        assert mp.real == pytest.approx(1 / (1 + r), abs=1e-3)


def test_stick_ratio_limits():
    q = np.array([1e-3, 0.2, 2.0])
    for model in wear.WEAR_MODELS:
        assert np.all(wear.wear_coefficients(q, 1.0, model) == 0)
        w0 = wear.wear_coefficients(q, 0.0, model)
        w_small = wear.wear_coefficients(q, 1e-6, model)
        assert np.all(np.isfinite(w0))
        assert np.allclose(w0, w_small, rtol=1e-3, atol=1e-8)
        w_near1 = wear.wear_coefficients(q, 1 - 1e-6, model)
        assert np.all(np.abs(w_near1) < 1e-3)


def test_material_point_levels_everywhere_patch_does_not():
    """The finding: W1 > 0 on the whole (r, L/a0) grid for (4.74) at a material point."""
    la = np.geomspace(2, 30, 60)
    r = np.linspace(0.1, 0.9, 17)
    w = wear.wear_coefficients(1 / la[None, :], r[:, None], "material_point")
    assert np.all(w.real > 0)
    pc = wear.wear_coefficients(1 / la[None, :], r[:, None], "patch_coordinate")
    assert np.any(pc.real < 0)


# --------------------------------------------------------------------------------------------
# passage times (4.76)-(4.87)
# --------------------------------------------------------------------------------------------
def _exact_state(x, k, za, zb, r, orientation):
    """Exact a, Delta, a* at axis positions x (R = a0 = 1, N C = 1/2)."""
    a, d, _, _ = cg.solve_normal_exact(x, 0.5, 1.0, [k], [za], [zb])
    if orientation == "ours":
        ast = cg.solve_stick_zone_exact(x, a, d, 1 - r, 1.0, [k], [za], [zb])
    else:   # thesis orientation: mirror image (stick zone at -a): a*(X) of the mirrored surface
        am, dm, _, _ = cg.solve_normal_exact(-x, 0.5, 1.0, [k], [za], [-zb])
        ast = cg.solve_stick_zone_exact(-x, am, dm, 1 - r, 1.0, [k], [za], [-zb])
    return a, d, ast


def _solve_position(x0, k, za, zb, r, orientation, offset):
    """Fixed point X_c = X0 - offset(a, Delta, a*)(X_c) (a contraction for small amplitude)."""
    xc = np.array(x0, dtype=float)
    for _ in range(40):
        a, d, ast = _exact_state(xc, k, za, zb, r, orientation)
        xc = x0 - offset(a, d, ast)
    return xc


def _passage_times(ratio, r, eps, phase, convention, n=32):
    k = 2 * np.pi * ratio
    amp = eps / k
    za, zb = amp * np.cos(phase), amp * np.sin(phase)
    lam = 1 / ratio
    x0 = np.arange(n) * lam / n
    if convention == "consistent":   # rolling +X: enter at +a, stick boundary, leave at -a
        te = _solve_position(x0, k, za, zb, r, "ours", lambda a, d, s: d + a)
        ts = _solve_position(x0, k, za, zb, r, "ours", lambda a, d, s: d + a - 2 * s)
        tx = _solve_position(x0, k, za, zb, r, "ours", lambda a, d, s: d - a)
        tau, taus = 0.5 * (tx - te), 0.5 * (ts - te)
    else:   # the thesis' (4.76)-(4.78) with Delta -> -Delta (the reading that gives (4.83))
        t0 = _solve_position(x0, k, za, zb, r, "thesis", lambda a, d, s: -d - a)
        tst = _solve_position(x0, k, za, zb, r, "thesis", lambda a, d, s: -d + 2 * s - a)
        t1 = _solve_position(x0, k, za, zb, r, "thesis", lambda a, d, s: -d + a)
        tau, taus = -0.5 * (t1 - t0), -0.5 * (tst - t0)
    return x0, k, za, zb, tau, taus


@pytest.mark.parametrize("convention", ["consistent", "nielsen1998"])
def test_passage_times_match_solved_kinematics(convention):
    ratio, r, eps = 0.2, 0.4, 1e-4
    x0, k, za, zb, tau, taus = _passage_times(ratio, r, eps, 0.3, convention)
    c_tau, c_taus = wear.passage_time_response(ratio, r, convention=convention)
    zc = za + 1j * zb
    got_tau = 2 * np.mean(tau * np.exp(1j * k * x0)) / zc / k      # units k R / V, R = V = 1
    got_taus = 2 * np.mean(taus * np.exp(1j * k * x0)) / zc / k
    assert np.mean(tau) == pytest.approx(1.0, abs=1e-6)
    assert np.mean(taus) == pytest.approx(r, abs=1e-6)
    assert abs(got_tau - c_tau) < 2e-3 * abs(c_tau)
    assert abs(got_taus - c_taus) < 2e-3 * abs(c_taus)


def test_nielsen_passage_times_reproduce_printed_4_83_4_86():
    """(4.83) and tau*_2 of (4.86) as printed follow from (4.76)-(4.78) only with Delta -> -Delta;
    tau*_1 as printed differs by the sign of J0(k a0) sin(k a0) (erratum)."""
    ratio = np.array([0.05, 0.2, 0.45, 0.8])
    r = np.array([0.3, 0.6, 0.45, 0.8])
    beta = 2 * np.pi * ratio
    t_n, ts_n = wear.passage_time_response(ratio, r, convention="nielsen1998")
    t_p, ts_p = wear.passage_time_response(ratio, r, convention="printed")
    assert np.allclose(t_n, t_p, atol=1e-14)
    assert np.allclose(ts_n.imag, ts_p.imag, atol=1e-14)
    assert np.allclose(ts_p.real - ts_n.real, j0(beta) * np.sin(beta), atol=1e-14)
    # the consistent kinematics differ from the thesis in the sign of the Delta term
    t_c, _ = wear.passage_time_response(ratio, r, convention="consistent")
    assert np.allclose(t_c.real, j0(beta) * np.sin(beta) - j1(beta) * np.cos(beta), atol=1e-14)
    assert np.allclose(t_n.real, -(j0(beta) * np.sin(beta) + j1(beta) * np.cos(beta)),
                       atol=1e-14)


# --------------------------------------------------------------------------------------------
# (b) (4.92) exact vs its linearisation (models nielsen1998 and time_domain_carter)
# --------------------------------------------------------------------------------------------
@pytest.mark.parametrize("model", ["nielsen1998", "time_domain_carter"])
def test_linearised_4_92_matches_exact_4_92(model):
    ratio, r, eps, phase = 0.15, 0.45, 1e-4, 0.9
    conv = "consistent" if model == "time_domain_carter" else "nielsen1998"
    x0, k, za, zb, tau, taus = _passage_times(ratio, r, eps, phase, conv)
    # B0 = C a p(0) = (a/pi) sum c_n sin(n pi/2) at the material point's axis position X0
    a, d, _, _ = cg.solve_normal_exact(x0, 0.5, 1.0, [k], [za], [zb])
    n = np.arange(1, 40)
    zeta = za - 1j * zb
    ipow = (1j) ** ((n + 1) % 4)
    cn = -2 * k * jv(n[None, :], k * a[:, None]) * np.real(
        ipow[None, :] * zeta * np.exp(1j * k * (x0 + d))[:, None])
    cn[:, 0] += a
    b0 = a / np.pi * np.sum(cn * np.sin(n * np.pi / 2), -1)
    rt = taus / tau
    # (4.92) with K = V = mu = R = a0 = 1, N = 1/2: W = (1/2) (pi B0/a)^2 tau f(r_tau); the
    # normalised coefficient divides by K mu^2 N / a0 = 1/2
    w = (np.pi * b0 / a) ** 2 * tau * (1 - rt) ** 2 * (1 + rt)
    got = 2 * np.mean(w * np.exp(1j * k * x0)) / (za + 1j * zb)
    if model == "nielsen1998":
        got = np.conj(got)                                           # thesis orientation -> ours
    lin = wear.wear_coefficients(ratio, r, model)
    assert np.mean(w) == pytest.approx(wear.wear_shape_function(r), rel=1e-4)
    assert abs(got - lin) < 3e-3 * abs(lin)


def test_bad_model_and_inputs():
    with pytest.raises(ValueError, match="wear_model"):
        wear.wear_coefficients(0.1, 0.5, "archard")
    with pytest.raises(ValueError, match="stick_ratio"):
        wear.wear_coefficients(0.1, -0.1)
    with pytest.raises(ValueError, match="a0_over_wavelength"):
        wear.wear_coefficients(0.0, 0.5)
    with pytest.raises(ValueError, match="convention"):
        wear.passage_time_response(0.1, 0.5, convention="x")
    with pytest.raises(ValueError, match="curvature_amplitude"):
        wear.wear_first_harmonic_exact(0.5, 0.5, 1.0)


def test_linear_response_bundle_matches_exact():
    """The table/FMU entry point against the exact nonlinear first harmonics (amplitude 1e-3)."""
    ex = wear.wear_first_harmonic_exact(0.3, 0.6, 1e-3, phase=0.3)
    lr = wear.linear_response(0.3, 0.6, wear_number=1e-3)
    for name in ("half_width", "patch_shift", "stick_half_width", "tangential_force"):
        assert abs(ex[name] - getattr(lr, name)) < 1e-5
    assert abs(ex["material_point"] - lr.wear) < 1e-5
    assert lr.growth_factor == pytest.approx(1 - 2e-3 * lr.wear.real)
    grid = wear.linear_response(np.linspace(0.01, 1, 5)[:, None], np.linspace(0, 1, 4)[None, :],
                                "nielsen1998", 1e-4)
    assert grid.wear.shape == (5, 4) and np.all(np.isfinite(grid.growth_factor))
    with pytest.raises(ValueError, match="wear_number"):
        wear.linear_response(0.1, 0.5, wear_number=-1)


# ------------------------------------------------------------------ scalar path (FMU per step)
def test_scalar_mean_wear_equals_array_function():
    """wear.mean_wear_unchecked (the FMU's call; mean_wear calls it after its checks) on
    floats returns a float equal to mean_wear (4 eps; measured: bit-identical)."""
    eps = float(np.finfo(float).eps)
    rng = np.random.default_rng(91)
    cases = []
    for regime in ("stick", "partial", "sliding", "near_stick", "no_load", "no_friction"):
        for _ in range(30):
            args = [float(10 ** rng.uniform(-12, -6)), float(rng.uniform(0.0, 1.0)),
                    float(10 ** rng.uniform(1.0, 7.5)), float(rng.uniform(0.05, 1.0)),
                    float(10 ** rng.uniform(-5, -2)), float(rng.uniform(0.0, 1.0))]
            if regime == "stick":
                args[5] = 1.0
            elif regime == "sliding":
                args[5] = 0.0
            elif regime == "near_stick":
                args[5] = 1.0 - float(10 ** rng.uniform(-16, -4))
            elif regime == "no_load":
                args[2] = 0.0
            elif regime == "no_friction":
                args[1] = 0.0
            cases.append(tuple(args))
    for args in cases:
        one = wear.mean_wear_unchecked(*args)
        ref = float(wear.mean_wear(*args))
        assert isinstance(one, float)
        assert one == ref or abs(one - ref) <= 4 * eps * abs(ref), args


# --------------------------------------------------------------------------------------------
# corrugated_wear_depth: the wear per passage on a corrugated rail, (4.94)-(4.96)
# --------------------------------------------------------------------------------------------
_E, _NU, _R, _MU = 2.1e11, 0.28, 0.5, 0.3
_A0 = 0.006
_N = _A0 ** 2 * np.pi * _E / (8 * (1 - _NU ** 2) * _R)      # load per length giving a0 = _A0


def test_corrugated_wear_depth_physical_units():
    """W(X) = W0 + Re[(K mu^2 N/a0) w (Z_A+iZ_B) e^{-ikX}] with W0 (4.96); checked by its mean
    (mean_wear) and its first harmonic over one wave length (wear_coefficients)."""
    ratio, r, kw = 0.12, 0.4, 1e-10
    lam = _A0 / ratio
    k = 2 * np.pi / lam
    amp = 0.01 * _A0 / (k * _R)
    za, zb = amp * np.cos(0.4), amp * np.sin(0.4)
    xi = _MU * _A0 * (1 - r) / _R
    x = np.arange(64) * lam / 64
    depth = wear.corrugated_wear_depth(x, _N, _R, _E, _NU, _MU, xi, [za], [zb], [lam], kw)
    assert depth.shape == x.shape
    assert np.mean(depth) == pytest.approx(wear.mean_wear(kw, _MU, _N, _R, _A0, r), rel=1e-12)
    c = 2 * np.mean(depth * np.exp(1j * k * x)) / (za + 1j * zb) / (kw * _MU ** 2 * _N / _A0)
    assert abs(c - wear.wear_coefficients(ratio, r)) < 1e-9
    # a smooth rail (zero amplitude): Carter's mean wear everywhere
    flat = wear.corrugated_wear_depth(x, _N, _R, _E, _NU, _MU, xi, [0.0], [0.0], [lam], kw)
    assert np.allclose(flat, wear.mean_wear(kw, _MU, _N, _R, _A0, r), rtol=1e-12, atol=0)


def test_corrugated_wear_depth_bad_input_names_it():
    args = [0.0, _N, _R, _E, _NU, _MU, 1e-4, [1e-7], [0.0], [0.05]]
    with pytest.raises(ValueError, match=r"wear_coefficient must be in \[0, inf\) \[m\^2/N\]"):
        wear.corrugated_wear_depth(*args, -1.0)
    with pytest.raises(ValueError, match="wear_model must be one of"):
        wear.corrugated_wear_depth(*args, 1e-9, "archard")
    with pytest.raises(ValueError, match="friction_coefficient"):
        wear.corrugated_wear_depth(*args[:5], 0.0, *args[6:], 1e-9)
    with pytest.raises(ValueError, match="curvature_amplitude"):
        wear.corrugated_wear_depth(*args[:7], [1.0], [0.0], [0.05], 1e-9)


def test_scalar_corrugated_wear_depth_equals_array_function():
    """wear.corrugated_wear_depth_unchecked (the FMU's per-step call) against
    corrugated_wear_depth, every wear model, seeded surfaces (M = 1, 3, 10 harmonics, k a0 in
    [0.01, 3], sum k^2 R |Z| up to 0.95) and creepages from zero to full sliding: 8 eps of the
    size of the terms summed (the same compiled kernels; the series models' coefficients from
    the kernel's list entry point, the same nodes and degree as wear_coefficients)."""
    eps = float(np.finfo(float).eps)
    rng = np.random.default_rng(2024)
    mu, radius = 0.3, 0.46
    for m in (1, 3, 10):
        for frac in (0.0, 1e-9, 1e-5, 0.4, 1 - 1e-6, 3.0):
            n_load = float(10 ** rng.uniform(5.0, 7.0))
            a0 = float(np.sqrt(8 * (1 - _NU ** 2) * radius * n_load / (np.pi * _E)))
            lam = 2 * np.pi * a0 / 10 ** rng.uniform(-2.0, np.log10(3.0), m)
            k = 2 * np.pi / lam
            amp = 0.95 * rng.dirichlet(np.ones(m)) / (k * k * radius)
            phase = rng.uniform(0, 2 * np.pi, m)
            za, zb = list(amp * np.cos(phase)), list(amp * np.sin(phase))
            xi = float(rng.choice([-1.0, 1.0])) * frac * mu * a0 / radius
            x = float(rng.uniform(0.0, 2 * lam.max()))
            r = max(a0 - abs(xi) * radius / mu, 0.0) / a0
            for model in wear.WEAR_MODELS:
                args = (x, n_load, radius, _E, _NU, mu, xi, za, zb, list(lam), 1e-9, model)
                ref = float(wear.corrugated_wear_depth(*args))
                got = wear.corrugated_wear_depth_unchecked(*args)
                assert isinstance(got, float)
                scale = 1e-9 * mu * mu * n_load / a0 * (a0 ** 2 / radius + float(np.sum(
                    np.abs(wear.wear_coefficients(a0 / lam, r, model)) * np.hypot(za, zb))))
                assert abs(got - ref) <= 8 * eps * scale, (model, m, frac, got, ref)


def test_wear_depth_raises_at_huge_loads_like_wear_coefficients():
    """A load so large that a0/L needs a wear series beyond degree 100000: the wear depth on a
    corrugated rail and its float path (the FMU's call, through the series kernel's list entry
    point) raise wear_coefficients' ValueError instead of summing it."""
    args = (0.013, 1e17, _R, _E, _NU, _MU, 1e-3, [1e-5, 5e-6], [0.0, 2e-6], [0.05, 0.08], 1e-9)
    with pytest.raises(ValueError, match=r"degree must be in \[1, 100000\]"):
        wear.corrugated_wear_depth(*args)
    with pytest.raises(ValueError, match=r"degree must be in \[1, 100000\]"):
        wear.corrugated_wear_depth_unchecked(*args)
