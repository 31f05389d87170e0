"""The FMU's float twins (``railcontact._scalar``) against their public vectorised functions.

One table (:data:`PAIRS`) lists every pair: the twin, the public function it repeats, seeded
inputs over all regimes, and the bound. Bounds: 4 eps relative to each value (zeros equal with
their sign; the stick ratio in [0, 1] absolutely) for the closed forms on the same operations
(measured: bit-identical); for ``evolve_harmonics_scalar`` (cmath's log and exp against
numpy's) 4 eps relative to |Z^n| times the conditioning ``1 + |n log(1 - W)|`` of
``exp(n log(.))``.
"""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from railcontact import _scalar as S
from railcontact import evolution as ev
from railcontact.carter import carter_creep_force, carter_critical_creepage, carter_stick_ratio
from railcontact.creep3d import (METHODS, creep_force_3d, creep_solution_3d, saturation_creepage_3d,
                                 spin_coefficient)
from railcontact.friction import normalised_inputs, step_law_creep_force_normalised
from railcontact.hertz import hertz_2d

EPS = float(np.finfo(float).eps)
ULPS = 4.0


def _close(one, ref):
    """4 eps relative to ``ref``; zeros equal with their sign."""
    return (one == ref and np.signbit(one) == np.signbit(ref)) or (
        abs(one - ref) <= ULPS * EPS * abs(ref))


# ---------------------------------------------------------------------------------------------
# carter_scalar: (carter_creep_force, carter_stick_ratio)
# ---------------------------------------------------------------------------------------------
def _carter_cases():
    """(xi, N, R, E, nu, mu) covering: zero creepage, tiny creepage (1e-300 .. 1e-8 xi_c),
    partial slip, the sliding limit |xi| = xi_c, full sliding (up to 1e6 xi_c), N = 0, mu = 0
    (with and without creepage), both signs of the creepage."""
    rng = np.random.default_rng(71)
    for regime in ("zero", "tiny", "partial", "limit", "sliding", "no_load", "no_friction"):
        for _ in range(30):
            n_load = float(10 ** rng.uniform(1.0, 7.5))
            radius, e_mod = float(rng.uniform(0.05, 1.0)), float(rng.uniform(7e10, 2.2e11))
            nu, mu = float(rng.uniform(0.0, 0.49)), float(rng.uniform(0.01, 1.0))
            xi_c = float(carter_critical_creepage(n_load, radius, e_mod, nu, mu))
            sign = float(rng.choice([-1.0, 1.0]))
            xi = sign * xi_c * {
                "zero": 0.0, "tiny": 10 ** rng.uniform(-300, -8),
                "partial": rng.uniform(1e-6, 1.0), "limit": 1.0,
                "sliding": 10 ** rng.uniform(0.0, 6.0),
                "no_load": rng.uniform(0.0, 2.0), "no_friction": rng.uniform(0.0, 2.0)}[regime]
            if regime == "no_load":
                n_load = 0.0
            elif regime == "no_friction":
                mu = 0.0
                xi = 0.0 if rng.uniform() < 0.2 else sign * 10 ** rng.uniform(-8, -1)
            yield (float(xi), n_load, radius, e_mod, nu, mu)


def _carter_public(*args):
    return float(carter_creep_force(*args)), float(carter_stick_ratio(*args))


def _carter_agree(got, want):
    (force, stick), (ref_force, ref_stick) = got, want
    return _close(force, ref_force) and abs(stick - ref_stick) <= ULPS * EPS


# ---------------------------------------------------------------------------------------------
# normalised_inputs_scalar and step_law_creep_force_normalised_scalar (railcontact.friction)
# ---------------------------------------------------------------------------------------------
_NORMALISED_NAMES = ("creepage_ratio", "critical_creepage", "force_scale", "friction_ratio",
                     "kappa_normalised")


def _normalised_cases():
    rng = np.random.default_rng(81)
    for regime in ("zero", "tiny", "partial", "sliding", "no_kinetic", "no_kappa"):
        for _ in range(30):
            n_load = float(10 ** rng.uniform(-2.0, 7.5))
            radius, e_mod = float(rng.uniform(0.05, 1.0)), float(rng.uniform(7e10, 2.2e11))
            nu, mu0 = float(rng.uniform(0.0, 0.49)), float(rng.uniform(0.01, 1.0))
            mu_k, kappa = float(rng.uniform(0.0, 1.5)), float(10 ** rng.uniform(-1, 4))
            xi_c0 = float(mu0 * hertz_2d(n_load, radius, e_mod, nu).a0 / radius)
            xi = float(rng.choice([-1.0, 1.0])) * xi_c0 * {
                "zero": 0.0, "tiny": 10 ** rng.uniform(-300, -8),
                "partial": rng.uniform(0.0, 1.0), "sliding": 10 ** rng.uniform(0.0, 4.0),
                "no_kinetic": rng.uniform(0.0, 2.0), "no_kappa": rng.uniform(0.0, 2.0)}[regime]
            if regime == "no_kinetic":
                mu_k = 0.0
            elif regime == "no_kappa":
                kappa = 0.0
            yield (xi, n_load, radius, e_mod, nu, mu0, mu_k, kappa)


def _normalised_public(*args):
    ref = normalised_inputs(*args)
    return tuple(float(ref[name]) for name in _NORMALISED_NAMES)


def _step_law_cases():
    rng = np.random.default_rng(82)
    yield from [(0.0, 0.5), (-0.0, 0.5), (0.0, 0.0), (1.0, 0.0), (-1.0, 0.0), (0.3, 0.3),
                (-0.3, 0.3), (1e-300, 0.7), (-1e-300, 1.3)]
    for regime in ("tiny", "partial", "sliding", "rising", "no_kinetic"):
        for _ in range(40):
            m = float(rng.uniform(0.0, 1.0))
            chi = float(rng.choice([-1.0, 1.0])) * m * {
                "tiny": 10 ** rng.uniform(-300, -8), "partial": rng.uniform(0.0, 1.0),
                "sliding": 10 ** rng.uniform(0.0, 6.0), "rising": rng.uniform(0.0, 2.0),
                "no_kinetic": 1.0}[regime]
            if regime == "rising":
                m = float(rng.uniform(1.0, 3.0))
            elif regime == "no_kinetic":
                chi, m = float(rng.uniform(-2.0, 2.0)), 0.0
            yield (chi, m)


def _all_close(got, want):
    got = got if isinstance(got, tuple) else (got,)
    want = want if isinstance(want, tuple) else (want,)
    return all(_close(g, w) for g, w in zip(got, want, strict=True))


# ---------------------------------------------------------------------------------------------
# evolve_harmonics_scalar (railcontact.evolution)
# ---------------------------------------------------------------------------------------------
def _evolve_cases():
    rng = np.random.default_rng(93)
    for i in range(300):
        m = int(rng.integers(1, 5))
        za = list(rng.normal(size=m) * 1e-5)
        zb = list(rng.normal(size=m) * 1e-5)
        mag = 10 ** rng.uniform(-12, -0.05, size=m)      # |W| from tiny to ~0.9
        phase = rng.uniform(-np.pi, np.pi, size=m)
        w1, w2 = list(mag * np.cos(phase)), list(mag * np.sin(phase))
        n = int(rng.choice([0, 1, 2, int(rng.integers(3, 2000))]))
        if i % 25 == 0:
            w2 = [0.0] * m                                  # real factor
        yield (za, zb, w1, w2, n)


def _evolve_public(za, zb, w1, w2, n):
    ref_a, ref_b = ev.evolve_harmonics(za, zb, w1, w2, [n])
    return list(ref_a[0]), list(ref_b[0]), w1, w2, n


def _evolve_agree(got, want):
    (one_a, one_b), (ref_a, ref_b, w1, w2, n) = got, want
    for k in range(len(ref_a)):
        size = abs(complex(ref_a[k], ref_b[k]))
        cond = 1.0 + abs(n * np.log(complex(1.0 - w1[k], -w2[k])))
        if abs(complex(one_a[k] - ref_a[k], one_b[k] - ref_b[k])) > 4 * EPS * size * cond:
            return False
    return True


# ---------------------------------------------------------------------------------------------
# creep_force_3d_scalar, creep_solution_3d_scalar and spin_coefficient_scalar
# (railcontact.creep3d)
# ---------------------------------------------------------------------------------------------
# Bound: 4 eps, relative to mu N (and to |T| for the unbounded linear theory) for the forces,
# absolute for the [0, 1] stick measures, relative for z and Phi; the validity flag equal.
# Measured on these inputs: <= 1.5 eps (libm's hypot and acos against numpy's; the arithmetic
# is otherwise the same operations in the same order).
def _regime_cases(seed, n_per=40):
    """Inputs (tuples) covering every regime: full stick (tiny creepage), partial slip, full
    sliding (z > 1), zero creepage, spin-dominated, pure spin, N = 0, mu = 0, a0/b0 from 0.05
    to 20, nu from 0 to 0.49."""
    rng = np.random.default_rng(seed)
    cases = []
    for regime in ("stick", "partial", "sliding", "zero", "spin_dominated", "pure_spin",
                   "no_load", "no_friction", "huge"):
        for _ in range(n_per):
            g = float(np.exp(rng.uniform(np.log(0.05), np.log(20.0))))
            a0, b0 = 5e-3 * np.sqrt(g), 5e-3 / np.sqrt(g)
            n_load, nu, mu = rng.uniform(1.0, 2e5), rng.uniform(0.0, 0.49), rng.uniform(0.01, 1)
            e_mod = rng.uniform(7e10, 2.2e11)
            s_sat = float(saturation_creepage_3d(n_load, a0, b0, e_mod, nu, mu))
            xi = rng.normal(size=2) * s_sat
            phi = rng.normal() * s_sat / np.sqrt(a0 * b0)
            if regime == "stick":
                xi, phi = xi * 1e-9, phi * 1e-9
            elif regime == "sliding":
                xi, phi = xi * rng.uniform(2.0, 50.0), phi * rng.uniform(2.0, 50.0)
            elif regime == "zero":
                xi, phi = xi * 0.0, 0.0
            elif regime == "spin_dominated":
                xi, phi = xi * 1e-3, phi * rng.uniform(1.0, 30.0)
            elif regime == "pure_spin":
                xi = xi * 0.0
            elif regime == "no_load":
                n_load = 0.0
            elif regime == "no_friction":
                mu = 0.0
            elif regime == "huge":
                xi, phi = xi * 1e6, phi * 1e6
            cases.append((float(xi[0]), float(xi[1]), float(phi), float(n_load), float(a0),
                          float(b0), float(e_mod), float(nu), float(mu)))
    return cases


def _creep_cases():
    for method in METHODS:
        for args in _regime_cases(seed=61):
            yield (*args, method)


def _creep_public(*args):
    return creep_solution_3d(*args), args[3] * args[8]          # (solution, mu N)


def _creep_agree(one, want):
    ref, mu_n = want
    scale = max(mu_n, abs(float(ref.tx)), abs(float(ref.ty)))
    ok = [abs(one[k] - float(ref[k])) <= ULPS * EPS * scale for k in (0, 1)]      # [N]
    ok += [abs(one[k] - float(ref[k])) <= ULPS * EPS for k in (2, 3)]             # in [0, 1]
    ok += [one[k] == float(ref[k]) if np.isinf(ref[k]) or ref[k] == 0.0           # z, Phi
           else abs(one[k] - float(ref[k])) <= ULPS * EPS * float(ref[k]) for k in (4, 5)]
    return all(ok) and isinstance(one[6], bool) and one[6] == bool(ref.within_validity)


def _force_public(*args):
    # (force, its z, mu N)
    return creep_force_3d(*args), creep_solution_3d(*args).normalised_creepage, args[3] * args[8]


def _force_agree(one, want):
    ref, z, mu_n = want
    scale = max(mu_n, abs(float(ref.tx)), abs(float(ref.ty)))
    return (len(one) == 3 and all(abs(one[k] - float(ref[k])) <= ULPS * EPS * scale
                                  for k in (0, 1))
            and (one[2] == float(z) if np.isinf(z) or z == 0.0
                 else abs(one[2] - float(z)) <= ULPS * EPS * float(z)))


_STICK_CONTACTS = {}      # the stick twin's inputs -> the contact they came from


def _stick_cases():
    for args in _creep_cases():
        tx, ty, z = S.creep_force_3d_scalar(*args)
        xi_x, xi_y, phi, n_load, a0, b0, _, _, mu, method = args
        case = (tx, ty, z, xi_x, xi_y, phi, mu * n_load, a0, b0, method)
        _STICK_CONTACTS[case] = args
        yield case


def _stick_public(*case):
    # creep_solution_3d of the contact the case came from
    return creep_solution_3d(*_STICK_CONTACTS[case])


def _stick_agree(one, ref):
    # (stick area fraction, b*/b0, Phi, validity) against the public solution's fields
    return (abs(one[0] - float(ref.stick_area_fraction)) <= ULPS * EPS
            and abs(one[1] - float(ref.stick_width_ratio)) <= ULPS * EPS
            and _spin_agree(one[2], float(ref.spin_coefficient))
            and one[3] == bool(ref.within_validity))


def _spin_cases():
    for args in _regime_cases(seed=62, n_per=20):
        xi_x, xi_y, phi, _, a0, b0 = args[:6]
        yield (xi_x, xi_y, phi, a0, b0)


def _spin_agree(one, ref):
    return one == ref or abs(one - ref) <= ULPS * EPS * ref


#: Every float twin: (twin, its public function, seeded inputs, agreement test).
PAIRS = {
    "carter_scalar": (S.carter_scalar, _carter_public, _carter_cases, _carter_agree),
    "normalised_inputs_scalar": (S.normalised_inputs_scalar, _normalised_public,
                                 _normalised_cases, _all_close),
    "step_law_creep_force_normalised_scalar": (
        S.step_law_creep_force_normalised_scalar,
        lambda chi, m: float(step_law_creep_force_normalised(chi, m)), _step_law_cases,
        _all_close),
    "evolve_harmonics_scalar": (S.evolve_harmonics_scalar, _evolve_public, _evolve_cases,
                                _evolve_agree),
    "creep_force_3d_scalar": (S.creep_force_3d_scalar, _force_public, _creep_cases,
                              _force_agree),
    "creep_stick_3d_scalar": (S.creep_stick_3d_scalar, _stick_public, _stick_cases,
                              _stick_agree),
    "creep_solution_3d_scalar": (S.creep_solution_3d_scalar, _creep_public, _creep_cases,
                                 _creep_agree),
    "spin_coefficient_scalar": (S.spin_coefficient_scalar,
                                lambda *args: float(spin_coefficient(*args)), _spin_cases,
                                _spin_agree),
}


def test_the_table_lists_every_twin():
    assert set(PAIRS) == set(S.__all__)


@pytest.mark.parametrize("name", sorted(PAIRS))
def test_float_twin_equals_its_public_function(name):
    twin, public, cases, agree = PAIRS[name]
    count = 0
    for args in cases():
        got = twin(*args)
        values = got if isinstance(got, tuple) else (got,)
        flat = [v for item in values for v in (item if isinstance(item, list) else [item])]
        # (plain floats; a flag, as CreepSolution3D.within_validity, a bool)
        assert all(isinstance(v, (float, bool)) for v in flat), (name, args)
        assert agree(got, public(*args)), (name, args)
        count += 1
    assert count >= 100


# ---------------------------------------------------------------------------------------------
# the limits the twins must keep (the public functions' tests cover the same for themselves)
# ---------------------------------------------------------------------------------------------
def test_carter_scalar_keeps_tiny_creepage_digits_and_limits():
    nu, mu, r = 0.28, 0.3, 0.5
    e = 2 * 82e9 * (1 + nu)
    n = 1e-3**2 * np.pi * e / (8 * (1 - nu**2) * r)      # a0 = 1 mm
    args = (n, r, e, nu, mu)
    xi_c = float(carter_critical_creepage(*args))
    # initial slope dT/dxi = -2 mu N / xi_c (Carter; the printed 1 - r^2 would give 0 here)
    for ratio in (1e-20, 1e-12, 1e-300):
        force, stick = S.carter_scalar(ratio * xi_c, *args)
        assert force == pytest.approx(-2.0 * mu * n * ratio, rel=4 * EPS)
        assert stick == 1.0 - ratio
    assert S.carter_scalar(-2.0 * xi_c, *args) == (mu * n, 0.0)      # full sliding, sign
    assert S.carter_scalar(0.0, *args)[1] == 1.0
    n0 = (0.0, *args[1:])
    assert S.carter_scalar(1e-3, *n0) == (-0.0, 0.0) and S.carter_scalar(0.0, *n0)[1] == 1.0


def test_spin_coefficient_scalar_limits_and_a_worked_value():
    """No spin -> 0 (also without creepage), pure spin -> inf; sqrt(3^2 + 4^2) mm * 2 /m /
    hypot(3e-3, 4e-3) = 2."""
    assert S.spin_coefficient_scalar(0.0, 0.0, 0.0, 3e-3, 4e-3) == 0.0
    assert S.spin_coefficient_scalar(0.0, 0.0, 0.5, 3e-3, 4e-3) == np.inf
    assert S.spin_coefficient_scalar(3e-3, -4e-3, -2.0, 3e-3, 4e-3) == pytest.approx(
        2.0, rel=4 * EPS)


@settings(max_examples=60, derandomize=True)
@given(xi_x=st.floats(-0.05, 0.05), xi_y=st.floats(-0.05, 0.05), phi=st.floats(-20.0, 20.0),
       n_load=st.one_of(st.just(0.0), st.floats(1e-3, 3e5)),
       log_ratio=st.floats(np.log(0.05), np.log(20.0)), nu=st.floats(0.0, 0.49),
       mu=st.one_of(st.just(0.0), st.floats(1e-3, 1.0)), method=st.sampled_from(METHODS))
def test_creep_solution_3d_scalar_property(xi_x, xi_y, phi, n_load, log_ratio, nu, mu, method):
    """creep_solution_3d_scalar against creep_solution_3d on hypothesis' inputs (the bound of
    the table above)."""
    a0, b0 = 5e-3 * np.exp(0.5 * log_ratio), 5e-3 * np.exp(-0.5 * log_ratio)
    args = (xi_x, xi_y, phi, n_load, a0, b0, 210e9, nu, mu, method)
    assert _creep_agree(S.creep_solution_3d_scalar(*args), _creep_public(*args))


def test_step_law_scalar_initial_slope():
    # the initial slope -2 (Carter with mu_k, force over mu_0 N) at tiny creepage
    assert S.step_law_creep_force_normalised_scalar(1e-20, 0.6) == pytest.approx(
        -2e-20, rel=4 * EPS)


def test_evolve_harmonics_scalar_falls_back_to_the_checked_function():
    # W outside [-1, 1] and a non-finite amplitude: the public function's ValueError
    with pytest.raises(ValueError, match="w1"):
        S.evolve_harmonics_scalar([1e-5], [0.0], [1.5], [0.0], 1)
    with pytest.raises(ValueError, match="amplitudes_cos"):
        S.evolve_harmonics_scalar([np.inf], [0.0], [0.1], [0.0], 1)
    # W = 1 (factor 0, cmath.log fails): numpy's result, the surface worn flat
    with np.errstate(divide="ignore", invalid="ignore"):
        a, b = S.evolve_harmonics_scalar([1e-5, 2e-5], [0.0, 1e-6], [1.0, 0.1], [0.0, 0.0], 3)
        ref_a, ref_b = ev.evolve_harmonics([1e-5, 2e-5], [0.0, 1e-6], [1.0, 0.1], [0.0, 0.0],
                                           [3])
    assert a == list(ref_a[0]) and b == list(ref_b[0]) and a[0] == 0.0
