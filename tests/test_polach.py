"""Tests of railcontact.polach (Polach 1999 with spin; 2005 falling friction, k_A, k_S).

Independent checks: Kalker's linear theory at small creepage (C11, C22 and, through Polach's
spin formula, C23, also for lateral creepage with spin of either sign); mu N at full sliding; the
initial slope (k_A + k_S)/2 that the 2005 reduction factors give by their definition; the
falling-friction limit A mu0 N; Polach's recommended parameter sets (tests/data/
polach2005_parameters.csv); CONTACT's converged exact theory (tests/data/
contact_hertz3d_grid_convergence.csv). No numeric creep-force values of Polach's method are
published in a form we could obtain (his papers show measured-vs-computed curves only), so the
formulas are tested against these limits, not against printed forces.
"""

from pathlib import Path

import numpy as np
import pytest

from railcontact import creep_force_3d, kalker_coefficients
from railcontact.polach import POLACH_DRY, POLACH_WET, polach_force_3d, polach_friction

DATA = Path(__file__).parent / "data"
E, NU, MU, N = 210e9, 0.28, 0.3, 1e5
G = E / (2 * (1 + NU))


@pytest.mark.parametrize("a0, b0", [(2e-3, 8e-3), (6e-3, 6e-3), (8e-3, 2e-3)])
def test_linear_limit_is_kalker(a0, b0):
    c = kalker_coefficients(a0 / b0, NU)
    s = 1e-9
    tx = creep_force_3d(s, 0, 0, N, a0, b0, E, NU, MU, method="polach").tx
    ty = creep_force_3d(0, s, 0, N, a0, b0, E, NU, MU, method="polach").ty
    tp = creep_force_3d(0, 0, s, N, a0, b0, E, NU, MU, method="polach").ty
    assert tx == pytest.approx(-G * a0 * b0 * c.c11 * s, rel=1e-6)
    assert ty == pytest.approx(-G * a0 * b0 * c.c22 * s, rel=1e-6)
    assert tp == pytest.approx(-G * a0 * b0 * np.sqrt(a0 * b0) * c.c23 * s, rel=1e-6)


@pytest.mark.parametrize("a0, b0", [(2e-3, 8e-3), (6e-3, 6e-3), (8e-3, 2e-3)])
@pytest.mark.parametrize("sign", [1.0, -1.0])
def test_linear_limit_with_spin_is_kalker(a0, b0, sign):
    """Lateral creepage with spin of the same or the opposite sign (both branches of Polach's
    s_yC): T_y -> -G a0 b0 (C22 xi_y + sqrt(a0 b0) C23 phi), Kalker's linear theory; with
    longitudinal creepage and spin, T_x stays -G a0 b0 C11 xi_x (the resultant creepage s_C
    enters eps and the components alike)."""
    c = kalker_coefficients(a0 / b0, NU)
    xi_y, phi = 1e-9, sign * 0.5e-9 / max(a0, b0)
    ty = creep_force_3d(0, xi_y, phi, N, a0, b0, E, NU, MU, method="polach").ty
    assert ty == pytest.approx(-G * a0 * b0 * (c.c22 * xi_y + np.sqrt(a0 * b0) * c.c23 * phi),
                               rel=1e-6)
    tx = creep_force_3d(xi_y, 0, phi, N, a0, b0, E, NU, MU, method="polach").tx
    assert tx == pytest.approx(-G * a0 * b0 * c.c11 * xi_y, rel=1e-6)


def test_reduction_factors_scale_the_initial_slope():
    """dF/deps at 0 = (2 Q mu/pi)(k_A + k_S): the slope is (k_A + k_S)/2 of Kalker's."""
    a0, b0, s = 5e-3, 6e-3, 1e-9
    c = kalker_coefficients(a0 / b0, NU)
    for k_a, k_s in ((1.0, 0.4), (0.3, 0.1)):
        tx, _ = polach_force_3d(s, 0, 0, N, a0, b0, E, NU, MU, reduction_adhesion=k_a,
                                reduction_slip=k_s)
        assert tx == pytest.approx(-G * a0 * b0 * c.c11 * s * (k_a + k_s) / 2, rel=1e-6)


def test_full_sliding_and_falling_friction():
    """Large creepage: |T| -> mu N (1999); with the 2005 law, -> A mu0 N at large slip
    velocity and mu0 N at zero speed."""
    th = np.linspace(0.0, 2 * np.pi, 8, endpoint=False)
    args = (N, 5e-3, 6e-3, E, NU, MU)
    t = creep_force_3d(0.5 * np.cos(th), 0.5 * np.sin(th), 0.0, *args, method="polach")
    np.testing.assert_allclose(np.hypot(t.tx, t.ty), MU * N, rtol=1e-3)
    np.testing.assert_allclose(np.arctan2(-t.ty, -t.tx), np.angle(np.exp(1j * th)), atol=1e-12)
    # with spin too: at creepage 0.5 and phi a0 = 5e-3 the spin part has decayed (K_M -> 0) and
    # s / s_C -> 1, so |T| -> mu N in the direction of the creepage
    t = creep_force_3d(0.5 * np.cos(th), 0.5 * np.sin(th), 1.0, *args, method="polach")
    np.testing.assert_allclose(np.hypot(t.tx, t.ty), MU * N, rtol=1e-2)
    tx, _ = polach_force_3d(0.5, 0, 0, *args, friction_ratio_limit=0.4, friction_decay=0.6,
                            rolling_speed=30.0)
    assert -tx == pytest.approx(0.4 * MU * N, rel=1e-3)
    tx0, _ = polach_force_3d(0.5, 0, 0, *args, friction_ratio_limit=0.4, friction_decay=0.6,
                             rolling_speed=0.0)
    assert -tx0 == pytest.approx(MU * N, rel=1e-3)
    # the 2005 creep curve has a maximum and then falls (Polach 2005: the adhesion optimum)
    s = np.geomspace(1e-4, 0.3, 200)
    tx, _ = polach_force_3d(s, 0, 0, N, 5e-3, 6e-3, E, NU, 0.55, rolling_speed=20.0,
                            **POLACH_DRY)
    k = np.argmax(-tx)
    assert 0 < k < len(s) - 1 and -tx[-1] < 0.8 * -tx[k]


def test_polach_friction():
    assert polach_friction(0.55, 0.0, 0.4, 0.6) == pytest.approx(0.55)
    assert polach_friction(0.55, 1e3, 0.4, 0.6) == pytest.approx(0.22)
    # mu0 ((1 - A) e^{-B w} + A) at w = 1 m/s, B = 0.2 s/m
    assert polach_friction(0.3, 1.0, 0.4, 0.2) == pytest.approx(0.3 * (0.6 * 0.8187307531 + 0.4))
    with pytest.raises(ValueError,
                       match=r"friction_ratio_limit must be in \[0, 1\] \[-\]; got 1.5"):
        polach_friction(0.3, 1.0, 1.5, 0.2)


def test_pure_spin_odd_and_bounded():
    """Pure spin: s = 0, the force is Polach's spin part alone (rises, then decays); odd in all
    creepages; |T| <= mu N (scaled onto it where the superposed parts exceed it)."""
    phi = np.array([0.1, 1.0, 100.0])
    t = creep_force_3d(0.0, 0.0, phi, N, 6e-3, 6e-3, E, NU, MU, method="polach")
    assert np.all(t.tx == 0.0) and np.all(t.ty < 0.0) and -t.ty[2] < -t.ty[1] / 5
    rng = np.random.default_rng(18)
    xi = rng.normal(0, 3e-3, (3, 200))
    args = (N, 4e-3, 6e-3, E, NU, MU)
    plus = creep_force_3d(xi[0], xi[1], 300 * xi[2], *args, method="polach")
    minus = creep_force_3d(-xi[0], -xi[1], -300 * xi[2], *args, method="polach")
    np.testing.assert_allclose(minus.tx, -plus.tx, rtol=1e-13, atol=1e-9)
    np.testing.assert_allclose(minus.ty, -plus.ty, rtol=1e-13, atol=1e-9)
    assert np.all(np.hypot(plus.tx, plus.ty) <= MU * N)
    for n_load, a0, mu in ((0.0, 4e-3, MU), (N, 0.0, MU), (N, 4e-3, 0.0)):
        t = creep_force_3d(1e-3, 1e-3, 0.1, n_load, a0, 6e-3, E, NU, mu, method="polach")
        assert (t.tx, t.ty) == (0.0, 0.0)


def test_published_parameter_sets():
    """POLACH_DRY / POLACH_WET are Polach's recommended sets (tests/data/
    polach2005_parameters.csv, source and cross-check there); with them the creep curve rises
    with the reduced slope (k_A + k_S)/2 of Kalker's, peaks below mu0 N and falls towards
    A mu0 N at large slip velocity."""
    import csv
    with open(DATA / "polach2005_parameters.csv") as f:
        rows = {r["condition"]: r for r in csv.DictReader(
            line for line in f if not line.startswith("#"))}
    for name, params in (("dry", POLACH_DRY), ("wet", POLACH_WET)):
        r = rows[name]
        assert params == {"reduction_adhesion": float(r["k_A"]),
                          "reduction_slip": float(r["k_S"]),
                          "friction_ratio_limit": float(r["A"]),
                          "friction_decay": float(r["B_s_per_m"])}
        mu0 = float(r["mu0"])
        s = np.geomspace(1e-5, 1.0, 400)
        tx, _ = polach_force_3d(s, 0, 0, N, 5e-3, 6e-3, E, NU, mu0, rolling_speed=20.0,
                                **params)
        f = -tx / (mu0 * N)
        # at s = 1 (w = 20 m/s) exp(-B w) < 0.02 and (2/pi)(k_A eps/(1 + (k_A eps)^2) +
        # arctan(k_S eps)) is within 2 % of 1 (wet, k_S = 0.1; 0.3 % dry)
        assert np.all(f < 1.0) and f.max() > 0.5 and f[-1] == pytest.approx(
            float(r["A"]), abs=0.01)
        assert f.argmax() < len(s) - 1 and f[-1] < 0.85 * f.max()


# Measured over the 21 cases (% of mu N): max 15.6 (a/b = 5, lateral creepage with spin,
# Phi = 1: Polach's creep part F xi_y / s_C shrinks as the spin raises s_C while his spin part
# saturates, -0.779 against -0.935), 13.4 (a/b = 1, the same case), 11.9 (a/b = 5, longitudinal
# creepage with spin: |s_yC| < s_C reduces the spin part), 11.7 (a/b = 0.2, pure spin), 8.6
# (a/b = 0.2, combined creepage: Polach's force is parallel to (xi_x, xi_y), the exact one closer
# to (C11 xi_x, C22 xi_y)); RMS 6.9. Tolerance 16 %.
def test_against_contact_exact():
    import csv
    with open(DATA / "contact_hertz3d_grid_convergence.csv") as f:
        rows = [r for r in csv.DictReader(line for line in f if not line.startswith("#"))
                if (r["mx"], r["my"]) == ("240", "60")]
    errors = []
    for r in rows:
        e_mod = 2 * float(r["G_Pa"]) * (1 + float(r["nu"]))
        mu_n = float(r["mu"]) * float(r["Fn_N"])
        t = creep_force_3d(float(r["cksi"]), float(r["ceta"]), float(r["cphi_per_m"]),
                           float(r["Fn_N"]), float(r["a_m"]), float(r["b_m"]), e_mod,
                           float(r["nu"]), float(r["mu"]), method="polach")
        errors.append(np.hypot(t.tx / mu_n - float(r["fx_over_mu_fn"]),
                               t.ty / mu_n - float(r["fy_over_mu_fn"])))
    errors = np.array(errors)
    print(f"polach max {errors.max() * 100:.2f} % rms {np.sqrt(np.mean(errors**2)) * 100:.2f} %")
    assert len(errors) == 21 and errors.max() < 0.16


def test_input_errors():
    args = (N, 5e-3, 6e-3, E, NU, MU)
    with pytest.raises(ValueError, match=r"reduction_adhesion must be in \(0, 1\] \[-\]; got 0"):
        creep_force_3d(1e-3, 0, 0, *args, method="polach", reduction_adhesion=0.0)
    with pytest.raises(ValueError, match=r"friction_decay must be in \[0, inf\) \[s/m\]"):
        polach_force_3d(1e-3, 0, 0, *args, friction_decay=-1.0)
    with pytest.raises(ValueError, match=r"rolling_speed must be .*got nan"):
        polach_force_3d(1e-3, 0, 0, *args, rolling_speed=np.nan)
    with pytest.raises(ValueError, match=r"spin must be .*got inf"):
        creep_force_3d(1e-3, 0, np.inf, *args, method="polach")
