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

from railcontact import _scalar as S
from railcontact import evolution as ev
from railcontact.carter import carter_creep_force, carter_critical_creepage, carter_stick_ratio
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
        assert all(isinstance(v, float) for v in flat), (name, args)
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
