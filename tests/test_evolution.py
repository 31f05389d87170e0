"""Tests of railcontact.evolution (Nielsen Sec. 4.4): the closed-form map against an explicit
passage-by-passage loop of (4.103), the first-order forms (4.104), (4.111), superposition and
mixed traffic (4.110), and the zones / characteristic wave length against direct scans."""

import numpy as np
import pytest

from railcontact import evolution as ev
from railcontact import wear


def _loop(za, zb, w1, w2, n):
    """(4.103) applied n times with the 2x2 matrix, one passage at a time."""
    z = np.array([za, zb], dtype=float)
    mat = np.array([[1 - w1, w2], [-w2, 1 - w1]])
    for _ in range(n):
        z = mat @ z
    return z


def test_closed_form_equals_loop_of_4_103():
    za, zb, w1, w2 = 3e-6, -1e-6, 2e-3, -5e-4
    za_n, zb_n = ev.evolve_harmonics([za], [zb], [w1], [w2], [0, 1, 7, 250])
    for i, n in enumerate([0, 1, 7, 250]):
        ref = _loop(za, zb, w1, w2, n)
        assert za_n[i, 0] == pytest.approx(ref[0], rel=1e-10)
        assert zb_n[i, 0] == pytest.approx(ref[1], rel=1e-10)


def test_growth_and_phase_first_order_forms():
    za, zb, w1, w2 = 1.0, 0.5, 1e-4, 3e-5
    za1, zb1 = ev.evolve_harmonics([za], [zb], [w1], [w2], [1])
    ratio = np.hypot(za1, zb1) / np.hypot(za, zb)
    assert ratio[0, 0] == pytest.approx(np.sqrt(1 - 2 * w1), abs=2 * (w1 ** 2 + w2 ** 2))  # (4.104)
    t0 = zb / za
    assert zb1[0, 0] / za1[0, 0] == pytest.approx(t0 - w2 * (1 + t0 ** 2), abs=1e-8)   # (4.111)
    # (4.105) over many passages
    n = 3000
    zan, zbn = ev.evolve_harmonics([za], [zb], [w1], [0.0], [n])
    assert np.hypot(zan, zbn)[0, 0] == pytest.approx((1 - 2 * w1) ** (n / 2) * np.hypot(za, zb),
                                                     rel=5e-3)


def test_moving_corrugation_direction():
    """W2 > 0: the phase decreases and the crest travels towards -X (against rolling)."""
    za, zb = ev.evolve_harmonics([1.0], [0.0], [0.0], [1e-3], [100])
    assert np.arctan2(zb, za)[0, 0] < 0


def test_mixed_traffic_is_order_independent_superposition():
    rng = np.random.default_rng(1)
    w1 = rng.uniform(-1e-3, 1e-3, (3, 5))
    w2 = rng.uniform(-1e-3, 1e-3, (3, 5))
    counts = np.array([10, 4, 7])
    f = ev.mixed_traffic_factor(w1, w2, counts)
    z = np.ones(5) + 0.3j
    seq = [0] * 10 + [1] * 4 + [2] * 7
    rng.shuffle(seq)
    zz = z.copy()
    for j in seq:
        zz = zz * (1 - w1[j] - 1j * w2[j])
    assert np.allclose(zz, f * z, rtol=1e-12)


def test_white_noise_surface_reproducible_and_rms():
    lam, za, zb = ev.white_noise_surface(1000, 0.01, 0.5, 1e-5, seed=7)
    lam2, za2, _ = ev.white_noise_surface(1000, 0.01, 0.5, 1e-5, seed=7)
    assert np.array_equal(za, za2) and np.array_equal(lam, lam2)
    x = np.linspace(0, 100, 200001)
    z = ev.surface_profile(x[:2000], lam, za, zb)
    assert np.sqrt(np.mean(za ** 2 + zb ** 2) / 2 * 1000) == pytest.approx(1e-5, rel=1e-12)
    assert z.shape == (2000,)


def test_white_noise_filtered_to_characteristic_wavelength():
    """Fig. 4.13: with the thesis' model a white-noise surface ends up dominated by the
    characteristic wave length (the maximum of 1 - 2 W1)."""
    a0, r, eps = 0.006, 0.5, 2e-3
    lam, za, zb = ev.white_noise_surface(400, 2.5 * a0, 30 * a0, 1e-6, seed=2)
    w = eps * wear.wear_coefficients(a0 / lam, r, "nielsen1998")
    zan, zbn = ev.evolve_harmonics(za, zb, w.real, w.imag, [2000])
    dominant = lam[np.argmax(np.hypot(zan[0], zbn[0]))] / a0
    char, _, interior = ev.characteristic_wavelength(r, "nielsen1998")
    assert interior
    assert dominant == pytest.approx(char, rel=0.05)
    # with the default (material point) model everything decays
    w_mp = eps * wear.wear_coefficients(a0 / lam, r)
    zan, zbn = ev.evolve_harmonics(za, zb, w_mp.real, w_mp.imag, [2000])
    assert np.all(np.hypot(zan[0], zbn[0]) < np.hypot(za, zb))


def test_stability_boundary_is_a_zero_of_w1():
    r = np.array([0.2, 0.4, 0.6])
    for model in ("patch_coordinate", "nielsen1998"):
        la = ev.stability_boundary(r, model)
        assert np.all(np.isfinite(la))
        w = wear.wear_coefficients(1 / la, r, model).real
        assert np.all(np.abs(w) < 1e-9)
        # amplification just above the boundary, levelling just below
        assert np.all(wear.wear_coefficients(1 / (la * 1.05), r, model).real < 0)
        assert np.all(wear.wear_coefficients(1 / (la * 0.95), r, model).real > 0)
    assert np.all(np.isinf(ev.stability_boundary(r)))


def test_characteristic_wavelength_against_dense_scan():
    r = 0.4
    la = np.geomspace(2, 40, 4001)
    for model in ("patch_coordinate", "nielsen1998"):
        w = wear.wear_coefficients(1 / la, r, model).real
        best, wbest, interior = ev.characteristic_wavelength(r, model)
        assert interior
        assert best == pytest.approx(la[np.argmin(w)], rel=2e-3)
        assert wbest == pytest.approx(w.min(), rel=1e-4)
    best, wbest, interior = ev.characteristic_wavelength(r)
    assert not interior and wbest > 0


def test_phase_change_boundary_is_a_zero_of_w2():
    r = np.array([0.3, 0.6])
    la = ev.phase_change_boundary(r, "nielsen1998")
    assert np.all(np.abs(wear.wear_coefficients(1 / la, r, "nielsen1998").imag) < 1e-9)


def test_growth_factor_and_wear_number():
    eps = ev.wear_number(1e-9, 0.3, 1e5, 0.006)
    assert eps == pytest.approx(1e-9 * 0.09 * 1e5 / 0.006)
    g = ev.growth_factor(0.1, 0.5, eps, "nielsen1998")
    assert g == pytest.approx(1 - 2 * eps * wear.wear_coefficients(0.1, 0.5, "nielsen1998").real)


def test_errors():
    with pytest.raises(ValueError, match="w1"):
        ev.evolve_harmonics([1.0], [0.0], [2.0], [0.0], [1])
    with pytest.raises(ValueError, match="n_passages"):
        ev.evolve_harmonics([1.0], [0.0], [0.0], [0.0], [-1])
    with pytest.raises(ValueError, match="wavelength_max"):
        ev.white_noise_surface(10, 0.5, 0.1, 1e-6)
    with pytest.raises(ValueError, match="wear_number"):
        ev.growth_factor(0.1, 0.5, -1.0)
    with pytest.raises(ValueError, match="stick_ratio"):
        ev.stability_boundary(1.0)


# ------------------------------------------------------------------ scalar path (FMU per step)
def test_scalar_wear_number_equals_array_function():
    """evolution.wear_number_unchecked (the FMU's call; wear_number calls it after its checks)
    on floats returns a float equal to wear_number (4 eps; measured: bit-identical)."""
    eps = float(np.finfo(float).eps)
    rng = np.random.default_rng(92)
    for i in range(200):
        args = [float(10 ** rng.uniform(-12, -6)), float(rng.uniform(0.0, 1.0)),
                float(10 ** rng.uniform(1.0, 7.5)), float(10 ** rng.uniform(-5, -2))]
        if i % 10 == 0:
            args[1] = 0.0                                    # mu = 0
        elif i % 10 == 1:
            args[2] = 0.0                                    # N = 0
        one = ev.wear_number_unchecked(*args)
        ref = float(ev.wear_number(*args))
        assert isinstance(one, float)
        assert one == ref or abs(one - ref) <= 4 * eps * abs(ref), args
