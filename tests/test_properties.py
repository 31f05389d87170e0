"""Property tests (hypothesis) over the documented input domains: solvers, tables and the FMU.

For every model the same questions, asked of randomly drawn valid inputs:

* the outputs are finite;
* the tangential force obeys the Coulomb bound ``|T| <= mu N``;
* creep curves are odd in the creepage and monotone where the theory says so (|T| grows with
  the creepage along a ray for the strip theories, SHE, Carter, the tables; the stick ratio
  falls);
* the forces are continuous in every input (a relative perturbation of 1e-7 of one input moves
  the force by a bounded multiple of it);
* vectorised calls equal scalar calls;
* for the shipped creep table: second differences across every knot stay bounded as the
  spacing shrinks (C2; C1 at the saturation double knot, where they stay bounded too) and the
  force never overshoots the saturation value;
* for the FMU: the outputs equal the direct ``railcontact`` call, and getting/setting and
  serialising the FMU state reproduces a continued run bit for bit;
* invalid inputs raise ``ValueError`` naming the parameter (solver) or make the FMI call fail
  with an error message naming the input (FMU) -- never NaN, a crash or a hang.

The hypothesis profile (``tests/conftest.py``) sets the number of examples: ``ci`` (default,
derandomized) or ``long`` (``HYPOTHESIS_PROFILE=long``, 10^5 per cheap test). Tests that run an
iterative solver or an FMU step take a fixed fraction of it (:func:`budget`).
"""

import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from railcontact import (carter_creep_force, carter_stick_ratio, creep_force_3d,
                         creep_solution_3d, hertz_2d, hertz_3d, kalker_coefficients)
from railcontact import corrugation as cg
from railcontact import friction as fr
from railcontact import polynomial as P
from railcontact.creep3d import METHODS, strip_force_function
from railcontact.evolution import growth_factor
from railcontact.filters import filter_solution
from railcontact.strip_table import CreepTable
from railcontact.wear import wear_coefficients

E, NU = 210e9, 0.28
_BASE = settings.default.max_examples
EPS = float(np.finfo(float).eps)


def within_coulomb(tx, ty, mu_n):
    """|T| <= mu N by the correctly rounded hypot, allowing 4 ulp (the exact-arithmetic bound
    is pinned by tests/test_hard_cases.py::test_coulomb_bound_holds_in_exact_arithmetic)."""
    return math.hypot(tx, ty) <= mu_n * (1.0 + 4.0 * EPS)


def budget(fraction, minimum=5):
    """Examples for an expensive property test: a fraction of the active profile's."""
    return max(minimum, int(_BASE * fraction))


# --------------------------------------------------------------------------------------------
# strategies
# --------------------------------------------------------------------------------------------
def signed_log(lo_exp, hi_exp, zero=True):
    """Signed values with log-uniform magnitude in [10^lo_exp, 10^hi_exp] (and 0)."""
    mag = st.floats(lo_exp, hi_exp).map(lambda e: 10.0 ** e)
    val = st.tuples(st.sampled_from([-1.0, 1.0]), mag).map(lambda t: t[0] * t[1])
    return st.one_of(st.just(0.0), val) if zero else val


creepages = signed_log(-12, -0.5)                   # |xi| from 1e-12 to 0.3
spins = signed_log(-8, 1)                           # |phi| up to 10 1/m (spin pole inside)
axis_ratios = st.floats(np.log(0.05), np.log(20.0)).map(np.exp)
loads = st.one_of(st.just(0.0), st.floats(1.0, 3e5))
frictions = st.one_of(st.just(0.0), st.floats(1e-3, 1.0))
poissons = st.floats(0.0, 0.49)
rel_steps = st.floats(1.0 + 1e-6, 4.0)              # a creepage ray is scaled by this factor


def _ellipse(ratio, size=5e-3):
    return size * math.sqrt(ratio), size / math.sqrt(ratio)


# --------------------------------------------------------------------------------------------
# 3-D creep forces (linear, SHE, strip, modified strip)
# --------------------------------------------------------------------------------------------
@given(xi_x=creepages, xi_y=creepages, phi=spins, ratio=axis_ratios, load=loads, mu=frictions,
       nu=poissons, method=st.sampled_from(METHODS), scale=rel_steps)
def test_creep3d_finite_bounded_odd_monotone_vectorised(xi_x, xi_y, phi, ratio, load, mu, nu,
                                                       method, scale):
    a0, b0 = _ellipse(ratio)
    rest = (load, a0, b0, E, nu, mu)
    t = creep_force_3d(xi_x, xi_y, phi, *rest, method=method)
    mag = math.hypot(t.tx, t.ty)
    assert math.isfinite(t.tx) and math.isfinite(t.ty)
    if method != "linear":
        assert within_coulomb(t.tx, t.ty, mu * load)
    neg = creep_force_3d(-xi_x, -xi_y, -phi, *rest, method=method)
    assert neg.tx == -t.tx and neg.ty == -t.ty
    # monotone along the ray (xi_x, xi_y, phi) -> s (xi_x, xi_y, phi), s > 1
    far = creep_force_3d(scale * xi_x, scale * xi_y, scale * phi, *rest, method=method)
    assert math.hypot(far.tx, far.ty) >= mag * (1.0 - 1e-12)
    # vectorised == scalar, bit for bit, in any position of a broadcast array
    vec = creep_force_3d(np.array([0.5 * xi_x, xi_x]), np.array([xi_y, xi_y]),
                         np.array([[phi], [phi]]), *rest, method=method)
    assert vec.tx.shape == (2, 2)
    assert vec.tx[1, 1] == t.tx and vec.ty[1, 1] == t.ty
    sol = creep_solution_3d(xi_x, xi_y, phi, *rest, method=method)
    assert sol.tx == t.tx and sol.ty == t.ty
    assert 0.0 <= sol.stick_area_fraction <= 1.0 and 0.0 <= sol.stick_width_ratio <= 1.0


@given(xi_x=creepages, xi_y=creepages, phi=spins, ratio=axis_ratios,
       load=st.floats(1.0, 3e5), mu=st.floats(1e-3, 1.0), nu=poissons,
       method=st.sampled_from(METHODS), which=st.integers(0, 8))
def test_creep3d_continuous_in_every_input(xi_x, xi_y, phi, ratio, load, mu, nu, method,
                                           which):
    """A relative change of 1e-7 of any one input changes T by at most ~1e-6 of its scale."""
    a0, b0 = _ellipse(ratio)
    args = [xi_x, xi_y, phi, load, a0, b0, E, nu, mu]
    t0 = creep_force_3d(*args, method=method)
    args[which] *= 1.0 + 1e-7
    t1 = creep_force_3d(*args, method=method)
    scale = (math.hypot(t0.tx, t0.ty) if method == "linear" else mu * load)
    assert math.hypot(t1.tx - t0.tx, t1.ty - t0.ty) <= 2e-6 * scale + 1e-300


# --------------------------------------------------------------------------------------------
# 2-D: Carter, Hertz, Kalker coefficients
# --------------------------------------------------------------------------------------------
@given(xi=signed_log(-12, -0.5), load=st.one_of(st.just(0.0), st.floats(1.0, 3e6)),
       radius=st.floats(0.05, 2.0), mu=frictions, nu=poissons, scale=rel_steps)
def test_carter_finite_bounded_odd_monotone_vectorised(xi, load, radius, mu, nu, scale):
    rest = (load, radius, E, nu, mu)
    t = float(carter_creep_force(xi, *rest))
    r = float(carter_stick_ratio(xi, *rest))
    assert math.isfinite(t) and abs(t) <= mu * load
    assert 0.0 <= r <= 1.0
    assert float(carter_creep_force(-xi, *rest)) == -t
    assert t * xi <= 0.0                                        # opposes the creepage
    far_t = float(carter_creep_force(scale * xi, *rest))
    far_r = float(carter_stick_ratio(scale * xi, *rest))
    assert abs(far_t) >= abs(t) * (1 - 1e-12) and far_r <= r + 1e-15
    vec = carter_creep_force(np.array([xi, 0.3 * xi, -xi]), *rest)
    assert vec[0] == t and vec[2] == -t
    if load > 0 and mu > 0:
        moved = float(carter_creep_force(xi * (1 + 1e-7), load * (1 + 1e-7), radius, E, nu, mu))
        assert abs(moved - t) <= 2e-6 * mu * load


@given(load=st.floats(0.0, 3e5), cx=st.floats(0.05, 50.0), cy=st.floats(0.05, 50.0),
       nu=poissons, scale=rel_steps)
def test_hertz_finite_monotone_in_load_and_vectorised(load, cx, cy, nu, scale):
    h = hertz_3d(load, cx, cy, E, nu)
    assert all(math.isfinite(float(v)) and float(v) >= 0.0 for v in h)
    more = hertz_3d(scale * load, cx, cy, E, nu)
    # subnormal loads included (tests/test_hard_cases.py::test_hertz_3d_scaling_at_subnormal_loads)
    assert all(float(m) >= float(v) for m, v in zip(more, h))
    vec = hertz_3d(np.array([load, scale * load]), cx, cy, E, nu)
    assert all(float(v[0]) == float(s) for v, s in zip(vec, h))
    if float(h[0] * h[1]) > 0:   # Hertz: p0 = 3 N / (2 pi a0 b0) (a0 b0 underflows near 1e-300 N)
        assert float(h[2]) == pytest.approx(1.5 * load / (math.pi * float(h[0] * h[1])),
                                            rel=1e-12)
    h2 = hertz_2d(load, 1.0 / cx, E, nu)
    assert all(math.isfinite(float(v)) for v in h2)


@given(ratio=st.floats(np.log(0.02), np.log(50.0)).map(np.exp), nu=st.floats(0.0, 0.5))
def test_kalker_positive_continuous_vectorised(ratio, nu):
    c = kalker_coefficients(ratio, nu)
    vals = np.array(c, dtype=float)
    assert np.all(np.isfinite(vals)) and np.all(vals > 0)
    moved = np.array(kalker_coefficients(ratio * (1 + 1e-7), min(nu * (1 + 1e-7), 0.5)))
    assert np.all(np.abs(moved - vals) <= 1e-6 * vals)
    vec = kalker_coefficients(np.array([ratio, 1.0, ratio]), nu)
    assert all(v[0] == s and v[2] == s for v, s in zip(vec, c))


# --------------------------------------------------------------------------------------------
# velocity-dependent friction (Ch. 5), polynomial approach (Ch. 3), corrugation, wear
# --------------------------------------------------------------------------------------------
@given(chi=signed_log(-10, 1), m=st.floats(0.0, 3.0))
def test_step_law_and_ohyama_bounded_odd_continuous(chi, m):
    for func in (fr.step_law_creep_force_normalised, fr.ohyama_creep_force_normalised):
        f = float(func(chi, m))
        assert math.isfinite(f) and abs(f) <= max(1.0, m) * (1 + 1e-12)
        assert float(func(-chi, m)) == -f
        moved = float(func(chi * (1 + 1e-7), m * (1 + 1e-7)))
        assert abs(moved - f) <= 1e-5
        vec = func(np.array([chi, -chi]), m)
        assert vec[0] == f and vec[1] == -f


@settings(max_examples=budget(0.2))
@given(chi=signed_log(-6, 0.7), m=st.floats(0.3, 1.0), kappa=st.floats(0.0, 3.0))
def test_smooth_law_finite_bounded_or_documented_error(chi, m, kappa):
    """Falling smooth law (5.16): a bounded creep force, or the documented non-convergence
    ValueError naming the law parameters -- never NaN."""
    try:
        f = float(fr.velocity_friction_creep_force_normalised(chi, m, kappa, degree=64))
    except ValueError as exc:
        assert "kappa_normalised" in str(exc) and "friction_ratio" in str(exc)
        return
    assert math.isfinite(f) and abs(f) <= 1.0 + 1e-9
    assert f * chi <= 0.0


@pytest.fixture(scope="module")
def hertz_polynomial():
    return P.solve_normal_polynomial([0.0, 0.0, 1.0], 2e5, E, NU)


@settings(max_examples=budget(0.5))
@given(frac=signed_log(-8, 0.5), mu=st.floats(0.01, 1.0), scale=rel_steps)
def test_polynomial_creep_curve_bounded_odd_monotone(hertz_polynomial, frac, mu, scale):
    nc = hertz_polynomial
    xi_c = float(P.tangential_state_polynomial(nc, mu, 0.0)[0])
    t = P.creep_curve_polynomial(nc, mu, np.array([frac * xi_c, -frac * xi_c,
                                                   scale * frac * xi_c]))
    assert np.all(np.isfinite(t)) and np.all(np.abs(t) <= mu * 2e5 * (1 + 1e-12))
    assert t[1] == pytest.approx(-t[0], rel=1e-12, abs=1e-9 * mu * 2e5)
    assert abs(t[2]) >= abs(t[0]) * (1 - 1e-9)


@settings(max_examples=budget(0.5))
@given(ratio=st.floats(np.log(1e-3), np.log(2.5)).map(np.exp), curv=st.floats(0.0, 0.999),
       phase=st.floats(0.0, 2 * np.pi), frac=st.floats(0.0, 1.5), position=st.floats(0, 1))
def test_corrugated_contact_finite_bounded(ratio, curv, phase, frac, position):
    """Within (4.2) (curvature amplitude <= 0.999) for a0/L from 1e-3 to 2.5: a finite patch, a
    stick zone inside the patch and |T| <= mu N (long waves near the edge of (4.2): see
    tests/test_hard_cases.py::test_corrugation_long_waves_near_edge_of_4_2_solve)."""
    radius, mu, load = 0.5, 0.3, 1e6
    a0 = float(hertz_2d(load, radius, E, NU).a0)
    lam = a0 / ratio
    k = 2 * np.pi / lam
    amp = curv / (k * k * radius)
    xi = frac * mu * a0 / radius
    res = cg.corrugated_contact(position * lam, load, radius, E, NU, mu, xi,
                                [amp * np.cos(phase)], [amp * np.sin(phase)], [lam])
    a = float(res.half_width)
    assert math.isfinite(a) and a > 0.0 and math.isfinite(float(res.patch_shift))
    assert 0.0 <= float(res.stick_half_width) <= a * (1 + 1e-12)
    assert 0.0 <= float(res.tangential_force) <= mu * load * (1 + 1e-12)


@given(ratio=st.floats(np.log(1e-4), np.log(5.0)).map(np.exp), r=st.floats(0.0, 1.0),
       model=st.sampled_from(["material_point", "nielsen1998", "time_domain_carter"]))
def test_wear_filter_coefficients_finite_and_vectorised(ratio, r, model):
    try:
        w = complex(wear_coefficients(ratio, r, model))
    except ValueError as exc:     # a model not available for this argument is documented
        pytest.skip(str(exc))
    assert math.isfinite(w.real) and math.isfinite(w.imag)
    vec = np.asarray(wear_coefficients(np.array([ratio, 2 * ratio]), r, model))
    # the quadrature degree may follow the largest ratio of the array: equal to rounding of the
    # O(1) terms (abs) where W itself vanishes (r -> 1)
    assert vec[0] == pytest.approx(w, rel=1e-12, abs=1e-14)
    g = complex(growth_factor(ratio, r, 1e-3, model))
    assert math.isfinite(abs(g))
    f = np.asarray(filter_solution(ratio, r), dtype=complex)
    assert np.all(np.isfinite(f))


# --------------------------------------------------------------------------------------------
# invalid inputs: ValueError naming the parameter, for every numeric input of the solvers
# --------------------------------------------------------------------------------------------
_CREEP = dict(creepage_longitudinal=1e-3, creepage_lateral=1e-3, spin=0.1, normal_load=1e5,
              a0=6e-3, b0=5e-3, youngs_modulus=E, poisson_ratio=NU, friction_coefficient=0.3)
_CARTER = dict(creepage=1e-3, normal_load=1e6, radius=0.5, youngs_modulus=E, poisson_ratio=NU,
               friction_coefficient=0.3)
#: function -> (valid keyword arguments, {parameter: a value below its lower bound or None})
INVALID = {
    creep_force_3d: (_CREEP, dict(normal_load=-1.0, a0=-1e-3, b0=-1e-3, youngs_modulus=0.0,
                                  poisson_ratio=0.5, friction_coefficient=-0.1,
                                  creepage_longitudinal=None, creepage_lateral=None,
                                  spin=None)),
    carter_creep_force: (_CARTER, dict(creepage=None, normal_load=-1.0, radius=0.0,
                                       youngs_modulus=-1.0, poisson_ratio=-0.1,
                                       friction_coefficient=-1.0)),
    carter_stick_ratio: (_CARTER, dict(creepage=None, normal_load=-1.0, radius=0.0,
                                       youngs_modulus=-1.0, poisson_ratio=0.6,
                                       friction_coefficient=-1.0)),
    hertz_3d: (dict(normal_load=1e5, curvature_longitudinal=1.0, curvature_lateral=1.6,
                    youngs_modulus=E, poisson_ratio=NU),
               dict(normal_load=-1.0, curvature_longitudinal=0.0, curvature_lateral=-1.0,
                    youngs_modulus=0.0, poisson_ratio=0.5)),
    hertz_2d: (dict(normal_load=1e6, radius=0.5, youngs_modulus=E, poisson_ratio=NU),
               dict(normal_load=-1.0, radius=0.0, youngs_modulus=0.0, poisson_ratio=0.5)),
    kalker_coefficients: (dict(a0_over_b0=1.0, poisson_ratio=NU),
                          dict(a0_over_b0=0.0, poisson_ratio=0.51)),
    cg.stick_zone_response: (dict(a0_over_wavelength=0.1, stick_ratio=0.5),
                             dict(a0_over_wavelength=-1.0, stick_ratio=1.5)),
    wear_coefficients: (dict(a0_over_wavelength=0.1, stick_ratio=0.5),
                        dict(a0_over_wavelength=-1.0, stick_ratio=-0.5)),
    fr.step_law_creep_force_normalised: (dict(creepage_ratio=0.5, friction_ratio=0.5),
                                         dict(creepage_ratio=None, friction_ratio=-1.0)),
    fr.velocity_friction_creep_force_normalised: (
        dict(creepage_ratio=0.5, friction_ratio=0.5, kappa_normalised=1.0),
        dict(creepage_ratio=None, friction_ratio=-1.0, kappa_normalised=-1.0)),
}
_INVALID_CASES = [(f, p, low) for f, (_, bad) in INVALID.items() for p, low in bad.items()]


@given(case=st.sampled_from(_INVALID_CASES),
       kind=st.sampled_from(["nan", "inf", "-inf", "below", "string"]))
def test_invalid_input_raises_value_error_naming_it(case, kind):
    func, name, low = case
    valid, _ = INVALID[func]
    value = {"nan": math.nan, "inf": math.inf, "-inf": -math.inf, "below": low,
             "string": "abc"}[kind]
    assume(value is not None)
    with pytest.raises(ValueError, match=name):
        func(**{**valid, name: value})
    # also inside an otherwise valid array
    if kind != "string":
        arr = np.array([valid[name], value], dtype=float)
        with pytest.raises(ValueError, match=name):
            func(**{**valid, name: arr})


# --------------------------------------------------------------------------------------------
# the whole float range: finite results with |T| <= mu N, or a ValueError naming the parameter
# --------------------------------------------------------------------------------------------
_EDGES = [0.0, 5e-324, 2.2250738585072014e-308, 1e-300, 1e300, float(np.finfo(float).max)]
#: Any finite float: the edges of the range (both signs) or any value hypothesis draws
#: (unbounded st.floats covers subnormals to 1.8e308, both signs).
any_magnitude = st.one_of(
    st.tuples(st.sampled_from(_EDGES), st.sampled_from([-1.0, 1.0])).map(lambda t: t[0] * t[1]),
    st.floats(allow_nan=False, allow_infinity=False))
_CREEP_NAMES = list(_CREEP)


def _extreme_creep_kwargs(values, where, as_array):
    """The valid creep inputs with the parameters ``where`` set to ``values`` (the first one
    as an array [value, valid value] if ``as_array``: the array paths)."""
    kwargs = dict(_CREEP)
    for k, (value, i) in enumerate(zip(values, where)):
        name = _CREEP_NAMES[i]
        kwargs[name] = np.array([value, _CREEP[name]]) if as_array and k == 0 else value
    return kwargs


def _finite_bounded_or_named_error(call, kwargs, coulomb=True):
    """``call(**kwargs)`` gives finite forces within mu N, or a ValueError whose message names
    a parameter (in the house style "... must be ...")."""
    try:
        tx, ty = call(**kwargs)[:2]
    except ValueError as exc:
        message = str(exc)
        assert " must " in message and any(n in message for n in _CREEP_NAMES), message
        return
    assert np.all(np.isfinite(tx)) and np.all(np.isfinite(ty)), kwargs
    if coulomb:
        mu_n = np.asarray(kwargs["friction_coefficient"]) * np.asarray(kwargs["normal_load"])
        assert np.all(np.hypot(tx, ty) <= mu_n * (1.0 + 4.0 * EPS)), kwargs


_extreme_args = dict(values=st.lists(any_magnitude, min_size=1, max_size=3),
                     where=st.lists(st.integers(0, 8), min_size=3, max_size=3, unique=True),
                     as_array=st.booleans())


@settings(max_examples=budget(2.0))
@given(method=st.sampled_from(METHODS), solution=st.booleans(), **_extreme_args)
def test_creep3d_whole_float_range_finite_bounded_or_named_error(values, where, as_array,
                                                                 method, solution):
    call = creep_solution_3d if solution else creep_force_3d
    _finite_bounded_or_named_error(lambda **kw: call(**kw, method=method),
                                   _extreme_creep_kwargs(values, where, as_array),
                                   coulomb=method != "linear")


@settings(max_examples=budget(1.0))
@given(a0_over_b0=any_magnitude, nu=st.one_of(any_magnitude, st.floats(0.0, 0.5)))
def test_kalker_whole_float_range_finite_or_named_error(a0_over_b0, nu):
    try:
        c = kalker_coefficients(a0_over_b0, nu)
    except ValueError as exc:
        assert "a0_over_b0 must" in str(exc) or "poisson_ratio must" in str(exc)
        return
    assert all(math.isfinite(float(v)) and float(v) >= 0.0 for v in c)


@settings(max_examples=budget(1.0))
@given(values=st.lists(any_magnitude, min_size=5, max_size=5), keep=st.integers(0, 4))
def test_hertz_3d_whole_float_range_finite_or_named_error(values, keep):
    names = ["normal_load", "curvature_longitudinal", "curvature_lateral", "youngs_modulus",
             "poisson_ratio"]
    kwargs = dict(zip(names, [8e4, 1.087, 1.667, E, NU]))
    for i, v in enumerate(values):
        if i != keep:
            kwargs[names[i]] = abs(v) if i < 4 else kwargs[names[i]]
    try:
        out = hertz_3d(**kwargs)
    except ValueError as exc:
        assert " must " in str(exc) and any(n in str(exc) for n in names), str(exc)
        return
    assert all(np.all(np.isfinite(v)) for v in out), kwargs


# --------------------------------------------------------------------------------------------
# the shipped creep table
# --------------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def creep_table():
    return CreepTable.from_file()


@given(xi_x=creepages, xi_y=creepages, phi=spins, ratio=axis_ratios, load=loads, mu=frictions,
       nu=st.floats(0.0, 0.49), scale=rel_steps)
def test_table_finite_bounded_odd_monotone_vectorised(creep_table, xi_x, xi_y, phi, ratio,
                                                      load, mu, nu, scale):
    a0, b0 = _ellipse(ratio)
    rest = (load, a0, b0, E, nu, mu)
    t = creep_table.creep_force_3d(xi_x, xi_y, phi, *rest)
    mag = math.hypot(t.tx, t.ty)
    assert math.isfinite(t.tx) and math.isfinite(t.ty) and within_coulomb(t.tx, t.ty, mu * load)
    neg = creep_table.creep_force_3d(-xi_x, -xi_y, -phi, *rest)
    assert neg.tx == -t.tx and neg.ty == -t.ty
    far = creep_table.creep_force_3d(scale * xi_x, scale * xi_y, scale * phi, *rest)
    # the spline of F(z) is monotone up to its fit error (recorded accuracy ~1e-6 of mu N)
    assert math.hypot(far.tx, far.ty) >= mag - 1e-6 * mu * load
    vec = creep_table.creep_force_3d(np.array([xi_x, 0.5 * xi_x]), xi_y, phi, *rest)
    assert vec.tx[0] == pytest.approx(t.tx, rel=1e-12, abs=1e-9)
    assert vec.ty[0] == pytest.approx(t.ty, rel=1e-12, abs=1e-9)
    direct = creep_force_3d(xi_x, xi_y, phi, *rest)
    assert math.hypot(t.tx - direct.tx, t.ty - direct.ty) <= 1e-4 * mu * load + 1e-300


@given(xi_x=creepages, xi_y=creepages, phi=spins, ratio=axis_ratios, load=loads, mu=frictions,
       nu=st.floats(0.0, 0.49), method=st.sampled_from(METHODS))
def test_scalar_paths_equal_array_paths(creep_table, xi_x, xi_y, phi, ratio, load, mu, nu,
                                        method):
    """The FMU's per-step scalar paths (plain floats, no numpy) against the public array
    paths: within 4 eps (forces relative to mu N, or |T| for the linear theory; stick
    measures absolute; z and Phi relative)."""
    from railcontact._scalar import creep_solution_3d_scalar
    a0, b0 = _ellipse(ratio)
    args = (xi_x, xi_y, phi, load, a0, b0, E, nu, mu)
    one, ref = creep_solution_3d_scalar(*args, method), creep_solution_3d(*args, method)
    scale = max(mu * load, abs(float(ref.tx)), abs(float(ref.ty)))
    assert abs(one.tx - ref.tx) <= 4 * EPS * scale and abs(one.ty - ref.ty) <= 4 * EPS * scale
    for k in (2, 3):
        assert abs(one[k] - ref[k]) <= 4 * EPS
    for k in (4, 5):
        assert one[k] == ref[k] or abs(one[k] - ref[k]) <= 4 * EPS * ref[k]
    assert one.within_validity == ref.within_validity
    stick, z = creep_table.stick_unchecked(*args)
    _, _, ref_stick, ref_z = creep_table.creep_solution_3d(*args)
    assert abs(stick - ref_stick) <= 4 * EPS and abs(z - ref_z) <= 4 * EPS * ref_z


def _force_ratio_along_z(table, z):
    """F(z) = |T|/(mu N) of the table through its physical interface: a pure longitudinal
    creepage chosen so that the normalised creepage is exactly z."""
    from railcontact.creep3d import saturation_creepage_3d
    load, a0, b0, mu = 1e5, 6e-3, 5e-3, 0.3
    xi_sat = float(np.asarray(saturation_creepage_3d(load, a0, b0, E, NU, mu)).ravel()[0])
    t = table.creep_force_3d(np.asarray(z) * xi_sat, 0.0, 0.0, load, a0, b0, E, NU, mu)
    return -np.asarray(t.tx) / (mu * load)


@given(knot=st.integers(0, 10**6), h0=st.floats(1e-3, 2e-2))
def test_table_second_differences_bounded_across_knots(creep_table, knot, h0):
    """C2 across interior knots (C1 at the double knot z = 1): (F(t+h) - 2F(t) + F(t-h))/h^2
    does not grow as h shrinks; a C0 kink would make it grow like 1/h."""
    nodes = np.asarray(creep_table.table.axes[0]["nodes"], dtype=float)
    t = float(nodes[1:-1][knot % (len(nodes) - 2)])
    h0 = min(h0, 0.45 * float(np.min(np.diff(nodes))))
    second = []
    for h in (h0, h0 / 10, h0 / 100):
        f = _force_ratio_along_z(creep_table, np.array([t - h, t, t + h]))
        second.append(abs(f[2] - 2 * f[1] + f[0]) / h**2)
    # the exact F has |F''| <= 3 (F'' = -3 sqrt(1 - z^2)); rounding adds ~eps/h^2
    assert second[-1] <= 2.0 * second[0] + 1.0 + 1e-15 / (h0 / 100) ** 2, (t, second)
    assert max(second) <= 3.5 + 1e-15 / (h0 / 100) ** 2


@given(z=st.floats(0.8, 4.0))
def test_table_no_overshoot_past_saturation(creep_table, z):
    f = float(_force_ratio_along_z(creep_table, z))
    assert f <= 1.0
    assert f == pytest.approx(float(strip_force_function(min(z, 1.0))), abs=1e-5)


@pytest.fixture(scope="module")
def exact_table():
    from railcontact.exact_table import ExactCreepTable

    return ExactCreepTable.from_file()


@settings(max_examples=budget(2.0))
@given(kind=st.sampled_from(["force", "solution", "jacobian", "exact"]), **_extreme_args)
def test_tables_whole_float_range_finite_bounded_or_named_error(creep_table, exact_table,
                                                                values, where, as_array, kind):
    """The table readers over the whole float range (the array b0 = 1e-300 raised
    ZeroDivisionError, xi = 1e308 gave NaN); the scalar fast path is taken unless as_array."""
    kwargs = _extreme_creep_kwargs(values, where, as_array)
    args = [kwargs[n] for n in _CREEP_NAMES]
    if kind == "jacobian":
        try:
            jac = creep_table.creep_force_jacobian_3d(*args)
        except ValueError as exc:
            assert " must " in str(exc) and any(n in str(exc) for n in _CREEP_NAMES)
            return
        assert np.all(np.isfinite(jac))
        return
    call = {"force": creep_table.creep_force_3d, "solution": creep_table.creep_solution_3d,
            "exact": exact_table.creep_force_3d}[kind]
    _finite_bounded_or_named_error(lambda **kw: call(*[kw[n] for n in _CREEP_NAMES]), kwargs)


# --------------------------------------------------------------------------------------------
# the FMU, driven through fmpy's FMI 2.0 API
# --------------------------------------------------------------------------------------------
FMU_INPUTS = ["normal_force", "creepage_longitudinal", "creepage_lateral", "spin",
              "rolling_speed", "rail_position"]
FMU_OUTPUTS = ["Fx", "Fy", "a0", "b0", "p0", "stick_area_fraction", "stick_width_ratio", "r_a0"]


def _free_instance(fmu):
    """Free the FMU instance but keep PythonFMU's native library loaded (fmpy's freeInstance
    also unloads it): unloading it while Python objects it created are still alive crashed
    the forked test process during a later garbage collection (signal 11 inside the next
    FMU2Slave(), about one run in ten of the whole-float-range property; upstream
    NTNU-IHB/PythonFMU#228). The library stays mapped until the forked child exits."""
    fmu.fmi2FreeInstance(fmu.component)


class _Instance:
    """One FMU2Slave with a message-collecting logger."""

    def __init__(self, unzipdir, md, scene_file, name="prop"):
        from fmpy import calloc, free
        from fmpy.fmi2 import (FMU2Slave, fmi2CallbackAllocateMemoryTYPE,
                               fmi2CallbackFreeMemoryTYPE, fmi2CallbackFunctions,
                               fmi2CallbackLoggerTYPE)
        from fmpy.logging import addLoggerProxy
        from ctypes import byref

        self.messages = []

        def logger(_env, _instance, status, _category, message):
            self.messages.append((int(status), message.decode(errors="replace")))

        cb = fmi2CallbackFunctions()
        cb.logger = fmi2CallbackLoggerTYPE(logger)
        cb.allocateMemory = fmi2CallbackAllocateMemoryTYPE(calloc)
        cb.freeMemory = fmi2CallbackFreeMemoryTYPE(free)
        addLoggerProxy(byref(cb))
        self._cb = cb
        self.vr = {v.name: v.valueReference for v in md.modelVariables}
        self.fmu = FMU2Slave(guid=md.guid, unzipDirectory=unzipdir,
                             modelIdentifier=md.coSimulation.modelIdentifier,
                             instanceName=name)
        self.fmu.instantiate(callbacks=cb, loggingOn=True)
        self.fmu.setupExperiment(startTime=0.0)
        self.fmu.setString([self.vr["scene_file"]], [str(scene_file)])
        self.fmu.enterInitializationMode()
        self.fmu.exitInitializationMode()
        self.inputs = [self.vr[n] for n in FMU_INPUTS]
        self.outputs = [self.vr[n] for n in FMU_OUTPUTS]
        self.t = 0.0

    def step(self, row, h=1e-3):
        self.fmu.setReal(self.inputs, [float(v) for v in row])
        self.fmu.doStep(self.t, h)
        self.t += h
        return np.array(self.fmu.getReal(self.outputs))

    def close(self):
        try:
            self.fmu.terminate()
        finally:
            _free_instance(self.fmu)


@pytest.fixture(scope="module")
def fmu_setup(built_fmu, tmp_path_factory):
    from fmpy import extract, read_model_description
    from railcontact.scene import load_scene

    unzipdir = extract(str(built_fmu), str(tmp_path_factory.mktemp("prop_fmu")))
    md = read_model_description(str(built_fmu))
    scenes = {}
    from pathlib import Path
    root = Path(__file__).resolve().parents[1] / "examples" / "scenes"
    for stem in ("creep_only_analytic", "creep_only_table"):
        path = root / f"{stem}.toml"
        scenes[stem] = (path, load_scene(str(path)), _Instance(unzipdir, md, path, stem))
    yield unzipdir, md, scenes
    for _, _, inst in scenes.values():
        inst.close()


fmu_rows = st.tuples(
    st.one_of(st.just(0.0), st.floats(1.0, 2e5)),     # normal force [N]
    signed_log(-12, -1), signed_log(-12, -1),          # creepages
    signed_log(-6, 0.7),                               # spin up to 5 1/m [1/m]
    st.floats(0.0, 100.0), st.floats(-1e3, 1e3))


def _direct(scene, row, source):
    n, xi_x, xi_y, phi = row[:4]
    geo = scene.geometry
    a0, b0, p0 = (float(v) for v in hertz_3d(n, geo["curvature_longitudinal"],
                                             geo["curvature_lateral"], scene.youngs_modulus,
                                             scene.poisson_ratio))
    args = (xi_x, xi_y, phi, n, a0, b0, scene.youngs_modulus, scene.poisson_ratio,
            scene.friction_coefficient)
    if source == "table":
        t = CreepTable.from_file().creep_force_3d(*args)
    else:
        t = creep_force_3d(*args, method=scene.effects["creep"]["method"])
    return float(t.tx), float(t.ty), a0, b0


@settings(max_examples=budget(1.0))
@given(row=fmu_rows, stem=st.sampled_from(["creep_only_analytic", "creep_only_table"]))
def test_fmu_outputs_finite_bounded_odd_and_equal_to_solver(fmu_setup, row, stem):
    _, _, scenes = fmu_setup
    _, scene, inst = scenes[stem]
    out = inst.step(row)
    assert np.all(np.isfinite(out))
    fx, fy = out[0], out[1]
    mu_n = scene.friction_coefficient * row[0]
    assert within_coulomb(fx, fy, mu_n)
    tx, ty, a0, b0 = _direct(scene, row, scene.effects["creep"]["source"])
    assert fx == pytest.approx(tx, rel=1e-12, abs=1e-12 * mu_n + 1e-300)
    assert fy == pytest.approx(ty, rel=1e-12, abs=1e-12 * mu_n + 1e-300)
    assert out[2] == pytest.approx(a0, rel=1e-12) and out[3] == pytest.approx(b0, rel=1e-12)
    assert np.all((out[5:] >= 0.0) & (out[5:] <= 1.0))
    mirrored = inst.step((row[0], -row[1], -row[2], -row[3]) + tuple(row[4:]))
    assert mirrored[0] == -fx and mirrored[1] == -fy


@settings(max_examples=budget(0.25))
@given(rows=st.lists(fmu_rows, min_size=2, max_size=8), split=st.integers(1, 7),
       stem=st.sampled_from(["creep_only_analytic", "creep_only_table"]))
def test_fmu_state_save_restore_bit_identical(fmu_setup, rows, split, stem):
    _, _, scenes = fmu_setup
    inst = scenes[stem][2]
    fmu = inst.fmu
    split = min(split, len(rows) - 1)
    for row in rows[:split]:
        inst.step(row)
    t_saved = inst.t
    state = fmu.getFMUState()
    before = np.array(fmu.getReal(inst.outputs))
    first = np.array([inst.step(r) for r in rows[split:]])
    fmu.setFMUState(state)
    inst.t = t_saved
    assert np.array(fmu.getReal(inst.outputs)).tobytes() == before.tobytes()
    second = np.array([inst.step(r) for r in rows[split:]])
    blob = fmu.serializeFMUstate(state)
    fmu.freeFMUState(state)
    state2 = fmu.deSerializeFMUstate(blob)
    fmu.setFMUState(state2)
    fmu.freeFMUState(state2)
    inst.t = t_saved
    third = np.array([inst.step(r) for r in rows[split:]])
    assert first.tobytes() == second.tobytes() == third.tobytes()


@settings(max_examples=budget(0.25))
@given(name=st.sampled_from(FMU_INPUTS),
       value=st.sampled_from([math.nan, math.inf, -math.inf, -1.0]))
def test_fmu_invalid_input_is_an_fmi_error_naming_it(fmu_setup, name, value):
    """NaN or inf in any input, or a negative normal force or speed: fmi2DoStep fails (error
    or fatal status) after logging an error naming the input; no NaN output, no crash."""
    from fmpy.fmi1 import FMICallException

    if value == -1.0:
        assume(name in ("normal_force", "rolling_speed"))
    unzipdir, md, scenes = fmu_setup
    path = scenes["creep_only_analytic"][0]
    inst = _Instance(unzipdir, md, path, "bad")
    try:
        good = inst.step((8e4, 1e-3, 0.0, 0.01, 30.0, 0.0))
        assert np.all(np.isfinite(good))
        row = dict(zip(FMU_INPUTS, (8e4, 1e-3, 0.0, 0.01, 30.0, 0.0)))
        row[name] = value
        with pytest.raises(FMICallException, match="fmi2DoStep") as info:
            inst.step([row[n] for n in FMU_INPUTS])
        assert info.value.status >= 3       # fmi2Error or fmi2Fatal
        errors = [m for s, m in inst.messages if s >= 3]
        assert errors and name in errors[0], inst.messages
    finally:
        _free_instance(inst.fmu)


@settings(max_examples=budget(0.5))
@given(values=st.lists(any_magnitude, min_size=1, max_size=3),
       where=st.lists(st.integers(0, 5), min_size=3, max_size=3, unique=True),
       step_size=st.one_of(st.just(1e-3), any_magnitude),
       stem=st.sampled_from(["creep_only_analytic", "creep_only_table"]))
def test_fmu_whole_float_range_finite_bounded_or_fmi_error(fmu_setup, values, where, step_size,
                                                           stem):
    """Inputs and step sizes over the whole float range: finite outputs within mu N and status
    OK, or fmi2DoStep fails with an error logged that names the input or the step size (with
    creepage 1e308 the table scenes gave Fx = NaN with status OK; a negative, NaN or infinite
    step size returned OK)."""
    from fmpy.fmi1 import FMICallException

    unzipdir, md, scenes = fmu_setup
    path, scene, _ = scenes[stem]
    inst = _Instance(unzipdir, md, path, "extreme")
    try:
        row = dict(zip(FMU_INPUTS, (8e4, 1e-3, -5e-4, 0.1, 20.0, 0.0)))
        for value, i in zip(values, where):
            row[FMU_INPUTS[i]] = value
        try:
            out = inst.step([row[n] for n in FMU_INPUTS], h=step_size)
        except FMICallException as exc:
            assert "fmi2DoStep" in str(exc) and exc.status >= 3
            errors = [m for s, m in inst.messages if s >= 3]
            assert errors and any(n in errors[0] for n in FMU_INPUTS + ["step_size"]), \
                inst.messages
            return
        assert np.all(np.isfinite(out)), (row, step_size, out)
        assert within_coulomb(out[0], out[1], scene.friction_coefficient * row["normal_force"])
    finally:
        _free_instance(inst.fmu)
        # keep the freed instance (its ctypes callbacks) alive for the rest of this process:
        # PythonFMU's native library may still hold the logger callback of a freed instance,
        # and collecting it while later instances are created crashed the process (a
        # segmentation fault during garbage collection, once in a CI run)
        _FREED_INSTANCES.append(inst)


#: Freed FMU instances of this process, kept alive (see above).
_FREED_INSTANCES = []
