"""Tests of railcontact.fastsim (FASTSIM, Kalker 1982; FaStrip, Sichani et al. 2016).

Independent checks: Kalker's linear theory (the coefficients' own table) at small creepage;
mu N at full sliding; CONTACT's published FASTSIM output (tests/data/contact_fastsim_example.csv);
CONTACT's converged exact theory (tests/data/contact_hertz3d_grid_convergence.csv, 240 x 60
grid); FaStrip without spin against the closed-form modified strip theory (Nielsen Eq. (2.87)),
which its stick zone reduces to; FaStrip with spin against the project's exact solver
(``method="exact"``, extrapolated, 0.33 % of mu N) on CONTACT's published example and five
more contacts, and against CONTACT's published (modified) FaStrip output on that example.
FaStrip's formulas follow CONTACT's implementation of the original method (src/m_solvpt.f90,
``original_fastrip``); Sichani et al.'s paper was not available to us.
"""

from pathlib import Path

import numpy as np
import pytest

from railcontact import (creep_force_3d, creep_solution_3d, kalker_coefficients,
                         normalised_creepage_3d)
from railcontact.fastsim import fastrip_force_3d, fastsim_force_3d
import railcontact as rc

DATA = Path(__file__).parent / "data"
E, NU, MU, N = 210e9, 0.28, 0.3, 1e5
G = E / (2 * (1 + NU))
METHODS = ("fastsim", "fastrip")


def _exact_cases():
    """CONTACT's converged (240 x 60) exact forces of 21 cases, in units of mu N."""
    import csv
    with open(DATA / "contact_hertz3d_grid_convergence.csv") as f:
        rows = [r for r in csv.DictReader(line for line in f if not line.startswith("#"))]
    return [r for r in rows if (r["mx"], r["my"]) == ("240", "60")]


def _run(method, r, **kw):
    e_mod = 2 * float(r["G_Pa"]) * (1 + float(r["nu"]))
    t = creep_force_3d(float(r["cksi"]), float(r["ceta"]), float(r["cphi_per_m"]),
                       float(r["Fn_N"]), float(r["a_m"]), float(r["b_m"]), e_mod,
                       float(r["nu"]), float(r["mu"]), method=method, **kw)
    mu_n = float(r["mu"]) * float(r["Fn_N"])
    return t.tx / mu_n, t.ty / mu_n


@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize("a0, b0", [(2e-3, 8e-3), (6e-3, 6e-3), (8e-3, 2e-3)])
def test_linear_limit_is_kalker(method, a0, b0):
    """At creepage 1e-8 the force is Kalker's linear theory, each of C11, C22, C23 (FASTSIM's
    three flexibilities make it exact; the residue is the quadrature: 0.04 % FASTSIM at
    40 x 40, 0.13 % FaStrip)."""
    c = kalker_coefficients(a0 / b0, NU)
    s = 1e-8
    tx = creep_force_3d(s, 0, 0, N, a0, b0, E, NU, MU, method=method).tx
    ty = creep_force_3d(0, s, 0, N, a0, b0, E, NU, MU, method=method).ty
    tp = creep_force_3d(0, 0, s, N, a0, b0, E, NU, MU, method=method).ty
    tol = 1e-3 if method == "fastsim" else 2e-3
    assert tx == pytest.approx(-G * a0 * b0 * c.c11 * s, rel=tol)
    assert ty == pytest.approx(-G * a0 * b0 * c.c22 * s, rel=tol)
    assert tp == pytest.approx(-G * a0 * b0 * np.sqrt(a0 * b0) * c.c23 * s, rel=tol)


@pytest.mark.parametrize("method", METHODS)
def test_full_sliding_gives_mu_n(method):
    """Creepage 0.5 (all elements slip): |T| = mu N within the quadrature of the bound (0.1 %).
    FaStrip's force is opposite to the creepage (one flexibility in sliding strips); FASTSIM's
    with three flexibilities opposite to the weighted creepage (C11 xi_x, C22 xi_y)."""
    a0, b0 = 5e-3, 7e-3
    th = np.linspace(0.0, 2 * np.pi, 9)[:-1]
    t = creep_force_3d(0.5 * np.cos(th), 0.5 * np.sin(th), 0.0, N, a0, b0, E, NU, MU,
                       method=method)
    np.testing.assert_allclose(np.hypot(t.tx, t.ty), MU * N, rtol=1e-3)
    c = kalker_coefficients(a0 / b0, NU)
    expected = th if method == "fastrip" else np.arctan2(c.c22 * np.sin(th),
                                                         c.c11 * np.cos(th))
    np.testing.assert_allclose(np.angle(np.exp(1j * (np.arctan2(-t.ty, -t.tx) - expected))),
                               0.0, atol=2e-3)


@pytest.mark.parametrize("method", METHODS)
def test_odd_bounded_and_zero_cases(method):
    rng = np.random.default_rng(18)
    xi = rng.normal(0, 2e-3, (3, 50))
    args = (N, 4e-3, 6e-3, E, NU, MU)
    plus = creep_force_3d(xi[0], xi[1], 300 * xi[2], *args, method=method)
    minus = creep_force_3d(-xi[0], -xi[1], -300 * xi[2], *args, method=method)
    np.testing.assert_allclose(minus.tx, -plus.tx, rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(minus.ty, -plus.ty, rtol=1e-12, atol=1e-9)
    assert np.all(np.hypot(plus.tx, plus.ty) <= MU * N)
    zero = creep_force_3d(0.0, 0.0, 0.0, *args, method=method)
    assert (zero.tx, zero.ty) == (0.0, 0.0)
    for n_load, a0, mu in ((0.0, 4e-3, MU), (N, 0.0, MU), (N, 4e-3, 0.0)):
        t = creep_force_3d(1e-3, 1e-3, 0.1, n_load, a0, 6e-3, E, NU, mu, method=method)
        assert (t.tx, t.ty) == (0.0, 0.0)


@pytest.mark.parametrize("method", METHODS)
def test_pure_spin(method):
    """Pure spin: no longitudinal force (symmetry in y); a lateral force opposite to phi that
    first grows (linear theory, C23) and then decays at large spin, as the exact theory's does
    (Kalker 1990): the spin is then carried by the moment, the lateral tractions cancel."""
    phi = np.array([0.1, 0.5, 1.0, 3.0, 10.0, 100.0])
    t = creep_force_3d(0.0, 0.0, phi, N, 6e-3, 6e-3, E, NU, MU, method=method)
    np.testing.assert_allclose(t.tx, 0.0, atol=1e-9 * MU * N)
    ty = -t.ty / (MU * N)
    assert np.all(ty > 0.0) and np.all(ty < 1.0)
    assert np.argmax(ty) == 2                      # maximum near phi = 1 1/m (a0 phi ~ 0.006)
    assert ty[-1] < ty[2] / 5.0


def test_fastsim_against_contact_published_example():
    """CONTACT's FASTSIM (parabolic bound, three flexibilities) on its example: 44 x 44 and
    220 x 220 grids (first-order element division), Richardson-extrapolated -0.6419. Ours,
    converged in n (200 x 200): -0.6480; within 1.5 % of mu N of the extrapolated value; the
    rest is CONTACT's coarse grid (its own 44 -> 220 step is 2.4 %)."""
    import csv
    with open(DATA / "contact_fastsim_example.csv") as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    val = {(r["method"], int(r["grid"])): float(r["fy_over_mu_fn"]) for r in rows}
    coarse, fine = val[("fastsim_parabolic", 44)], val[("fastsim_parabolic", 220)]
    extrapolated = fine + (fine - coarse) / 4.0
    tx, ty, _ = fastsim_force_3d(0.0, -0.000625, 0.625, 82000.0, 8e-3, 4e-3, 2 * 82e9 * 1.28,
                                 0.28, 0.3, n_strips=200, n_elements=200)
    assert abs(tx) < 1e-9
    assert ty / (0.3 * 82000.0) == pytest.approx(extrapolated, abs=0.015)


# Measured errors (% of mu N, |T - T_exact|) over the 21 cases, n = 40 x 40 defaults:
# FASTSIM max 7.09 (a/b = 1, pure spin), FaStrip max 4.32 (a/b = 0.2, longitudinal at Phi = 1).
# Tolerances: FASTSIM's error is known to be 5-15 % of mu N in the nonlinear range (Kalker 1982,
# Vollebregt & Wilders 2011); here 8 % (a regression margin above the measured 7.1 %); FaStrip
# 5 %.
@pytest.mark.parametrize("method, tol", [("fastsim", 0.08), ("fastrip", 0.05)])
def test_against_contact_exact(method, tol):
    errors = []
    for r in _exact_cases():
        tx, ty = _run(method, r)
        errors.append(np.hypot(tx - float(r["fx_over_mu_fn"]), ty - float(r["fy_over_mu_fn"])))
    errors = np.array(errors)
    print(method, f"max {errors.max() * 100:.2f} % rms {np.sqrt(np.mean(errors**2)) * 100:.2f} %")
    assert len(errors) == 21
    assert errors.max() < tol


#: FaStrip with spin against the exact solver: (xi_x, xi_y, phi [1/m], a0, b0 [m]) with
#: N = 82 kN, G = 82 GPa, nu = 0.28, mu = 0.3 (CONTACT's fastsim.inp material), the first case
#: CONTACT's published example (examples/fastsim.inp).
FASTRIP_SPIN_CASES = [(0.0, -6.25e-4, 0.625, 8e-3, 4e-3), (0.0, -6.25e-4, 0.625, 4e-3, 8e-3),
                      (1e-3, 0.0, 0.8, 6e-3, 6e-3), (5e-4, 5e-4, -0.5, 4e-3, 8e-3),
                      (0.0, 0.0, 2.0, 6e-3, 4e-3), (2e-3, 1e-3, 0.3, 8e-3, 4e-3)]


# Measured |T - T_exact| / (mu N) at 40 x 40 (defaults), in the order of FASTRIP_SPIN_CASES:
# 5.6, 1.9, 2.6, 2.0, 1.6, 1.8 %. The largest is CONTACT's example (a/b = 2, lateral creepage
# and spin): FaStrip -0.681 (-0.676 converged in n), exact -0.625, CONTACT's modified FaStrip
# -0.644. Tolerance 6.5 % of mu N (the exact reference's own error is below 0.4 %).
def test_fastrip_with_spin_against_exact_solver():
    import csv
    g_mod, nu, mu, n_load = 82e9, 0.28, 0.3, 82000.0
    e_mod = 2 * g_mod * (1 + nu)
    errors = []
    for xi_x, xi_y, phi, a0, b0 in FASTRIP_SPIN_CASES:
        args = (xi_x, xi_y, phi, n_load, a0, b0, e_mod, nu, mu)
        ref = creep_force_3d(*args, method="exact", grid=(40, 20), extrapolate=True)
        f = creep_force_3d(*args, method="fastrip")
        errors.append(np.hypot(f.tx - ref.tx, f.ty - ref.ty) / (mu * n_load))
    print("fastrip vs exact, % of mu N:", np.round(np.array(errors) * 100, 2))
    assert max(errors) < 0.065 and np.argmax(errors) == 0
    # CONTACT's published modified FaStrip on the first case (a different variant: a
    # plausibility bound, 4 % of mu N)
    with open(DATA / "contact_fastsim_example.csv") as fh:
        val = {(r["method"], int(r["grid"])): float(r["fy_over_mu_fn"])
               for r in csv.DictReader(line for line in fh if not line.startswith("#"))}
    f = creep_force_3d(*FASTRIP_SPIN_CASES[0][:3], n_load, *FASTRIP_SPIN_CASES[0][3:], e_mod,
                       nu, mu, method="fastrip")
    assert f.ty / (mu * n_load) == pytest.approx(val[("fastrip_modified", 220)], abs=0.04)


def test_fastrip_without_spin_is_the_modified_strip_theory():
    """FaStrip's stick zone without spin is Nielsen's modified strip theory (d = a0 z), and
    FASTSIM then gives the slip direction of the weighted creepage: the forces agree to the
    quadrature (0.2 % of mu N at 40 x 40)."""
    for th in (0.0, 0.7, np.pi / 2):
        for a0, b0 in ((2e-3, 8e-3), (6e-3, 6e-3), (8e-3, 2e-3)):
            s = np.geomspace(1e-5, 1e-2, 25)
            if th == 0.7:
                # near full sliding with combined creepage FaStrip turns the force towards the
                # rigid slip (one flexibility in sliding strips) while the modified strip
                # theory keeps the weighted direction: compare up to z = 0.5 there
                z = normalised_creepage_3d(s * np.cos(th), s * np.sin(th), 0.0, N, a0, b0,
                                           E, NU, MU)
                s = s[z <= 0.5]
            args = (s * np.cos(th), s * np.sin(th), 0.0, N, a0, b0, E, NU, MU)
            f = creep_force_3d(*args, method="fastrip")
            m = creep_force_3d(*args, method="modified_strip")
            np.testing.assert_allclose(f.tx / (MU * N), m.tx / (MU * N), atol=2e-3)
            np.testing.assert_allclose(f.ty / (MU * N), m.ty / (MU * N), atol=2e-3)


def test_discretisation_converges():
    """Doubling strips and elements changes FASTSIM by less than 0.3 % of mu N at 40 x 40."""
    args = (1e-3, 5e-4, 0.5, N, 4e-3, 6e-3, E, NU, MU)
    for fun in (fastsim_force_3d, fastrip_force_3d):
        coarse = np.array(fun(*args)[:2])
        fine = np.array(fun(*args, n_strips=160, n_elements=160)[:2])
        assert np.hypot(*(coarse - fine)) < 3e-3 * MU * N


def test_broadcasting_and_solution_fields():
    xi = np.linspace(-2e-3, 2e-3, 6)[:, None]
    n_load = np.array([5e4, 1e5])
    t = creep_force_3d(xi, 0.0, 0.2, n_load, 5e-3, 6e-3, E, NU, MU, method="fastsim")
    assert t.tx.shape == (6, 2)
    one = creep_force_3d(xi[3, 0], 0.0, 0.2, n_load[1], 5e-3, 6e-3, E, NU, MU, method="fastsim")
    assert t.tx[3, 1] == pytest.approx(one.tx, rel=1e-13)
    sol = creep_solution_3d(xi, 0.0, 0.0, n_load, 5e-3, 6e-3, E, NU, MU, method="fastrip")
    assert sol.stick_area_fraction.shape == (6, 2)
    # stick area of FaStrip without spin = modified strip's (2/pi)(arccos z - z sqrt(1 - z^2))
    ms = creep_solution_3d(xi, 0.0, 0.0, n_load, 5e-3, 6e-3, E, NU, MU)
    np.testing.assert_allclose(sol.stick_area_fraction, ms.stick_area_fraction, atol=5e-3)


def test_input_errors():
    args = (N, 5e-3, 6e-3, E, NU, MU)
    with pytest.raises(ValueError, match=r"n_strips must be an integer in \[2, 10000\]"):
        creep_force_3d(1e-3, 0, 0, *args, method="fastsim", n_strips=1)
    with pytest.raises(ValueError, match=r"n_elements must be an integer in \[2, 10000\]"):
        fastrip_force_3d(1e-3, 0, 0, *args, n_elements=2.5)
    with pytest.raises(ValueError, match=r"creepage_longitudinal must be .*got nan"):
        creep_force_3d(np.nan, 0, 0, *args, method="fastsim")
    with pytest.raises(ValueError, match=r"poisson_ratio must be in \[0, 0.5\] \[-\]; got 0.6"):
        creep_force_3d(1e-3, 0, 0, N, 5e-3, 6e-3, E, 0.6, MU, method="fastrip")
    with pytest.raises(ValueError, match=r"method 'fastsim' takes the options"):
        creep_force_3d(1e-3, 0, 0, *args, method="fastsim", reduction_slip=0.5)
    with pytest.raises(ValueError, match=r"method 'she' takes no options"):
        creep_force_3d(1e-3, 0, 0, *args, method="she", n_strips=4)


@pytest.mark.parametrize("method", ["fastsim", "fastrip", "polach"])
def test_extreme_magnitudes_by_similarity(method):
    """FASTSIM, FaStrip and Polach are evaluated on a similar reference contact (forces over
    mu N depend on a0/b0, nu and the creepages over mu p0 / G only), so extreme loads, sizes,
    moduli and creepages give the same T/(mu N) or a ValueError, never NaN (found by a seeded
    fuzz: xi = 1e308, a0 = 2e-308 gave NaN, a subnormal mu gave |T| > mu N)."""
    base = [1e-3, -5e-4, 0.1, 1e5, 6e-3, 5e-3, 210e9, 0.28, 0.3]
    ref = rc.creep_force_3d(*base, method=method)
    # N = 1e300 with E scaled by 1e295 (same mu p0 / G): the same T/(mu N)
    big = list(base)
    big[3], big[6] = 1e300, 210e9 * 1e295
    f = rc.creep_force_3d(*big, method=method)
    assert f.tx / (0.3 * 1e300) == pytest.approx(ref.tx / (0.3 * 1e5), rel=1e-9)
    assert f.ty / (0.3 * 1e300) == pytest.approx(ref.ty / (0.3 * 1e5), rel=1e-9)
    # creepage 1e308: full sliding, |T| = mu N (to the method's own sliding limit)
    slide = rc.creep_force_3d(1e308, 0.0, 0.0, *base[3:], method=method)
    assert np.hypot(slide.tx, slide.ty) == pytest.approx(0.3e5, rel=2e-3) and slide.tx < 0
    # subnormal friction: |T| <= mu N as rounded
    tiny = rc.creep_force_3d(*base[:8], 5e-324, method=method)
    assert np.hypot(tiny.tx, tiny.ty) <= 5e-324 * 1e5
    with pytest.raises(ValueError, match=r"a0/b0 must be in \[0.01, 100\]"):
        rc.creep_force_3d(*base[:4], 2.2e-308, 5e-3, *base[6:], method=method)
