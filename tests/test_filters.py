"""Tests of railcontact.filters (Nielsen Sec. 4.5): the filter solution against finite
differences of Hertz/Carter with the equivalent radius (4.116), (4.120) against its exact form,
(4.121)-(4.122) symmetry and the stability limit (4.127)."""

import numpy as np
import pytest

from railcontact import corrugation as cg
from railcontact import filters as fl
from railcontact.carter import carter_creep_force, carter_stick_ratio
from railcontact.hertz import hertz_2d

E, NU, R, MU = 2.1e11, 0.28, 0.5, 0.3


def test_filter_values():
    assert fl.remington_filter(0.0) == 1.0
    assert abs(fl.remington_filter(0.5)) < 1e-15
    assert fl.remington_filter(0.75) < 0
    q = np.linspace(0, 1.2, 50)
    assert np.all(fl.hempelmann_filter(q) > 0)
    assert fl.hempelmann_filter(0.2) == pytest.approx(1 / (1 + 5.32 * 0.04 + 6 * 0.0016
                                                           - 1.984 * 0.000064))
    with pytest.raises(ValueError, match="a0_over_wavelength"):
        fl.hempelmann_filter(1.5)


def test_filter_solution_by_finite_differences_of_carter():
    """(4.117)-(4.119) unfiltered (F = 1 in the long-wave limit): Hertz and Carter with
    1/R_eqv = 1/R + k^2 Z (4.116), at constant load and creepage, differentiated numerically."""
    n_load = 1e6
    a0 = float(hertz_2d(n_load, R, E, NU).a0)
    r0 = 0.35
    xi = -MU * a0 * (1 - r0) / R
    ratio = 1e-4                                   # F_R = 1 - O(ratio^2)
    k = 2 * np.pi * ratio / a0
    dz = 1e-3 / (k * k * R)                       # k^2 R Z = 1e-3
    r_eqv = 1 / (1 / R + k * k * dz)
    a_p = float(hertz_2d(n_load, r_eqv, E, NU).a0)
    r_p = float(carter_stick_ratio(xi, n_load, r_eqv, E, NU, MU))
    t_p = abs(float(carter_creep_force(xi, n_load, r_eqv, E, NU, MU)))
    ca, cs, ct = fl.filter_solution(ratio, r0)
    scale_a = k * R * dz
    assert (a_p - a0) / scale_a == pytest.approx(ca, rel=2e-3)
    assert (r_p * a_p - r0 * a0) / scale_a == pytest.approx(cs, rel=2e-3)
    t0 = MU * n_load * (1 - r0 ** 2)
    comp = 4 * (1 - NU ** 2) / (np.pi * E)
    assert (t_p - t0) / (MU / comp * dz) == pytest.approx(ct, rel=2e-3)   # sign erratum (4.119)


def test_4_120_half_width_error():
    exact, series = fl.filter_half_width_error(np.array([0.01, 0.05]))
    assert np.allclose(exact, series, rtol=2e-2)
    # against the closed forms of the two theories: 1 - |a_F| / |a|
    q = 0.05
    ca_f = fl.filter_solution(q, 0.5)[0]
    ca = cg.normal_response(q)[1]
    assert 1 - abs(ca_f) / abs(ca) == pytest.approx(fl.filter_half_width_error(q)[0], rel=1e-12)
    # thesis text: a0/L = 0.25 -> about 10 %
    assert fl.filter_half_width_error(0.25)[1] == pytest.approx(0.103, abs=1e-3)


def test_symmetry_4_121_4_122():
    q = np.linspace(0.01, 0.4, 20)
    for r in (0.1, 0.3, 0.45):
        assert np.allclose(np.abs(fl.filter_solution(q, r)[1]),
                           np.abs(fl.filter_solution(q, 1 - r)[1]))
    assert np.allclose(fl.filter_solution(q, 0.5)[1], 0)


def test_stability_limit_4_127():
    r = np.array([0.55, 0.7, 0.9])        # a0/L = 1/(4r) < 1/2, where F_R > 0
    q = fl.filter_stability_limit(r)
    assert np.allclose(q, 1 / (4 * r))
    assert np.allclose(fl.filter_wear_coefficients(q, r).real, 0, atol=1e-12)
    assert np.all(fl.filter_wear_coefficients(0.9 * q, r).real < 0)   # amplifying below
    assert np.all(fl.filter_wear_coefficients(1.1 * q, r).real > 0)


def test_filter_wear_is_shifted_force():
    """(4.123): W_F(X) = K |T_F(X + a*)| |xi| in our orientation -> rotation by e^{-i k a0*}."""
    q, r = 0.2, 0.3
    beta = 2 * np.pi * q
    ct = fl.filter_solution(q, r)[2]
    # normalisation: T in mu/C units, xi = mu a0 (1-r)/R, N = a0^2/(2RC) -> factor 2 (1-r)
    w = fl.filter_wear_coefficients(q, r)
    assert w == pytest.approx(2 * (1 - r) * ct * np.exp(-1j * beta * r), rel=1e-12)


def test_errors():
    with pytest.raises(ValueError, match="contact_filter"):
        fl.filter_solution(0.1, 0.5, "gauss")
    with pytest.raises(ValueError, match="stick_ratio"):
        fl.filter_stability_limit(0.0)
