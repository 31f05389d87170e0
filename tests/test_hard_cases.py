"""Hard cases of the catalogue ``docs/hard_cases.md`` not pinned by a module's own tests.

Each test names the catalogue row it pins. Cases that fail today are strict xfails with the
reproduction in the reason: they are bugs to route to the module's owner, and the xfail turns
into a failure (XPASS) as soon as the module is fixed, so the mark must then be removed.

Independent references used here: the exact linear-regime slope of Carter's solution,
``dT/dxi = -2 mu N / xi_c`` (Eq. (2.52)), which the closed form must reproduce to relative
rounding accuracy at any creepage below saturation (the form ``1 - (1 - f)^2`` is exactly
``2 f - f^2``); Hertz (2.40)-(2.42) and Carter as the a0/L -> 0 limit of the corrugated contact;
the analytic strip-theory function F(z) of Eq. (2.87) at the nodes of the shipped table.
"""

import math

import numpy as np
import pytest

from railcontact import (carter_creep_force, carter_critical_creepage, carter_stick_ratio,
                         creep_force_3d, creep_solution_3d, hertz_2d, hertz_3d,
                         kalker_coefficients)
from railcontact import corrugation as cg
from railcontact import friction as fr
from railcontact import polynomial as P
from railcontact.creep3d import saturation_creepage_3d, strip_force_function
from railcontact.strip_table import CreepTable

E, NU, R, MU = 210e9, 0.28, 0.5, 0.3
N_LINE = 1e6                                     # [N/m]
TINY = (1e-6, 1e-10, 1e-12, 1e-14, 1e-17, 1e-30)  # creepage over critical creepage


# --------------------------------------------------------------------------------------------
# Creepage -> 0: relative accuracy of the 2-D closed forms in the linear regime
# --------------------------------------------------------------------------------------------
def _carter_relative(f):
    xi_c = float(carter_critical_creepage(N_LINE, R, E, NU, MU))
    t = float(carter_creep_force(f * xi_c, N_LINE, R, E, NU, MU))
    return t / (-MU * N_LINE * (2.0 * f - f * f))


def test_carter_small_creepage_moderate_accuracy():
    """Down to xi/xi_c = 1e-10 Carter's closed form is within 1e-6 of its exact linear slope
    (the moderate range; the test below goes down to 1e-30)."""
    for f in (1e-2, 1e-6, 1e-10):
        assert _carter_relative(f) == pytest.approx(1.0, abs=1e-6)
    assert float(carter_creep_force(0.0, N_LINE, R, E, NU, MU)) == 0.0


def test_carter_tiny_creepage_relative_accuracy():
    """Found by this catalogue: 1 - r^2 cancelled (T = 0 below xi/xi_c = 1.1e-16); fixed in
    523c2a4 (f (2 - f)). Relative accuracy 1e-12 down to xi/xi_c = 1e-30."""
    for f in TINY:
        assert _carter_relative(f) == pytest.approx(1.0, rel=1e-12), f


def test_step_law_and_ohyama_tiny_creepage_relative_accuracy():
    """Found by this catalogue (same cancellation as Carter), fixed in 523c2a4. Leading order
    -2 chi (Carter's slope for mu_0); the next order is O(chi) for the step law and
    O((1 - m) chi^(3/2)) for Ohyama (slip zone of length chi at the edge, where p ~ sqrt(chi)),
    so the ratio to 2 chi - chi^2 tends to 1 like chi resp. sqrt(chi) -- and never to 0."""
    for f in TINY[2:]:
        step = float(fr.step_law_creep_force_normalised(f, 0.5)) / (-(2 * f - f * f))
        ohyama = float(fr.ohyama_creep_force_normalised(f, 0.5)) / (-(2 * f - f * f))
        assert abs(step - 1.0) <= f + 1e-15, f
        assert abs(ohyama - 1.0) <= 0.5 * math.sqrt(f) + 1e-15, f


def test_smooth_law_small_creepage_moderate_accuracy():
    """Smooth falling law (5.16): initial slope is Carter's for mu_0 (the stick zone covers the
    patch as chi -> 0); within 1e-6 at chi = 1e-8 for m = 0.5, kappa xi_c0 = 1."""
    f = float(fr.velocity_friction_creep_force_normalised(1e-8, 0.5, 1.0))
    assert f / (-2e-8) == pytest.approx(1.0, abs=1e-6)


# Was a strict xfail (the iteration lost the linear regime below chi ~ 1e-10); fixed: the
# linear regime uses Carter with mu_0, exact to ~kappa |1 - m| chi (friction.py).
def test_smooth_law_tiny_creepage_relative_accuracy():
    for m, kappa in ((0.5, 1.0), (0.8, 0.1)):
        for f in (1e-9, 1e-11, 1e-12, 1e-17):
            got = float(fr.velocity_friction_creep_force_normalised(f, m, kappa))
            assert got / (-2 * f) == pytest.approx(1.0, rel=1e-6), (m, kappa, f)


def test_polynomial_tiny_creepage_relative_accuracy():
    """Hertz pressure through the polynomial approach: Carter's curve at tiny creepage.
    Found by this catalogue (4e-3 relative error at xi/xi_c = 1e-14, T = 0 at 1e-20); fixed in
    dbc9928 (full-stick Taylor series). The critical creepage is |xi| at stick ratio 0."""
    nc = P.solve_normal_polynomial([0.0, 0.0, 1.0], 2e5, E, NU)
    xi_c = abs(float(P.tangential_state_polynomial(nc, MU, 0.0)[0]))
    for f in (1e-10, 1e-14, 1e-20, 1e-300):
        t = float(P.creep_curve_polynomial(nc, MU, f * xi_c))
        assert t / (-MU * 2e5 * (2 * f - f * f)) == pytest.approx(1.0, rel=1e-6), f


def test_3d_and_table_tiny_and_subnormal_creepage():
    """3-D solver and shipped table: relative accuracy at 1e-20 and 1e-300 (the series form of
    F(z) avoids the cancellation); a subnormal creepage still gives a finite force of the
    right sign (its own precision is only a few bits)."""
    table = CreepTable.from_file()
    a0, b0, load = 6e-3, 5e-3, 1e5
    c11 = float(kalker_coefficients(a0 / b0, NU).c11)
    lin = -E / (2 * (1 + NU)) * a0 * b0 * c11
    for xi in (1e-14, 1e-20, 1e-300):
        d = creep_force_3d(xi, 0.0, 0.0, load, a0, b0, E, NU, MU)
        t = table.creep_force_3d(xi, 0.0, 0.0, load, a0, b0, E, NU, MU)
        assert d.tx / (lin * xi) == pytest.approx(1.0, rel=1e-12)
        assert t.tx / (lin * xi) == pytest.approx(1.0, rel=1e-6)
    for xi in (5e-324, -5e-324):
        for t in (creep_force_3d(xi, 0.0, 0.0, load, a0, b0, E, NU, MU),
                  table.creep_force_3d(xi, 0.0, 0.0, load, a0, b0, E, NU, MU)):
            assert math.isfinite(t.tx) and np.sign(t.tx) == -np.sign(xi) and t.ty == 0.0


# Was a strict xfail (|T| up to 4 ulp above mu N in exact arithmetic); fixed: two-component
# forces are rescaled with a 4 eps margin (creep3d.py).
def test_coulomb_bound_holds_in_exact_arithmetic():
    from fractions import Fraction

    n_load = 198701.0592578831
    h = hertz_3d(1.0, 1.087, 1.667, E, NU)
    scale = n_load ** (1.0 / 3.0)
    sol = creep_solution_3d(-0.03931151716872166, 0.006119217761983133, -4.834565402750565,
                            n_load, float(h.a0) * scale, float(h.b0) * scale, E, NU, MU)
    mu_n = MU * n_load
    assert np.hypot(sol.tx, sol.ty) <= mu_n                   # what the module checks
    assert Fraction(float(sol.tx)) ** 2 + Fraction(float(sol.ty)) ** 2 <= Fraction(mu_n) ** 2


# --------------------------------------------------------------------------------------------
# Saturation, far beyond it, sign changes (2-D)
# --------------------------------------------------------------------------------------------
def test_carter_at_and_far_beyond_saturation_and_through_zero():
    xi_c = float(carter_critical_creepage(N_LINE, R, E, NU, MU))
    for f in (1.0, 1.0 + 1e-15, 2.0, 1e3, 1e12):
        for s in (1.0, -1.0):
            t = float(carter_creep_force(s * f * xi_c, N_LINE, R, E, NU, MU))
            assert t == -s * MU * N_LINE
            assert float(carter_stick_ratio(s * f * xi_c, N_LINE, R, E, NU, MU)) == 0.0
    # just below saturation: the stick ratio is small but positive, |T| < mu N
    r = float(carter_stick_ratio((1 - 1e-9) * xi_c, N_LINE, R, E, NU, MU))
    assert 0.0 < r < 2e-9
    # sign change: the curve passes through 0 continuously, odd in xi bit for bit
    xs = np.array([-1e-300, -0.0, 0.0, 1e-300]) * xi_c
    t = carter_creep_force(xs, N_LINE, R, E, NU, MU)
    assert np.all(np.abs(t) <= 1e-280) and t[0] == -t[3]


# --------------------------------------------------------------------------------------------
# Degenerate inputs: N -> 0
# --------------------------------------------------------------------------------------------
@pytest.mark.parametrize("load", [0.0, 5e-324, 1e-300, 1e-10])
def test_vanishing_load_gives_finite_zero_or_tiny_forces(load):
    """N -> 0 through Hertz into the 3-D solver (all methods), the table and Carter: finite,
    within mu N (so exactly 0 at N = 0), never NaN, even when a0 b0 underflows to 0."""
    h = hertz_3d(load, 1.087, 1.667, E, NU)
    assert all(math.isfinite(float(v)) for v in h)
    table = CreepTable.from_file()
    results = [creep_force_3d(1e-3, -2e-3, 0.5, load, h.a0, h.b0, E, NU, MU, method=m)
               for m in ("modified_strip", "strip", "she", "linear")]
    results.append(table.creep_force_3d(1e-3, -2e-3, 0.5, load, h.a0, h.b0, E, NU, MU))
    for t in results:
        assert math.isfinite(t.tx) and math.isfinite(t.ty)
    for t in results[:3] + results[4:]:
        assert math.hypot(t.tx, t.ty) <= MU * load
    sol = creep_solution_3d(1e-3, -2e-3, 0.5, load, h.a0, h.b0, E, NU, MU)
    assert all(math.isfinite(float(v)) for v in sol[:4])
    # documented diagnostics: z = inf when there is creepage but no friction force available
    assert not any(math.isnan(float(v)) for v in sol[4:6])
    t2 = float(carter_creep_force(1e-3, load, R, E, NU, MU))
    assert math.isfinite(t2) and abs(t2) <= MU * load
    assert all(math.isfinite(float(v)) for v in hertz_2d(load, R, E, NU))


def test_corrugated_contact_zero_and_tiny_creepage():
    """Found by this catalogue (T = mu N - ... cancelled: +-5.8e-11 N/m at zero creepage, 1-2 %
    error at xi/xi_c = 1e-14); fixed in 9af7cc7 (closed-form differences)."""
    xi_c = float(carter_critical_creepage(N_LINE, R, E, NU, MU))
    res = cg.corrugated_contact(0.01, N_LINE, R, E, NU, MU, 0.0, [1e-6], [0.0], [0.05])
    assert float(res.tangential_force) == 0.0
    for method in ("exact", "linear"):
        for f in (1e-10, 1e-14):
            res = cg.corrugated_contact(0.01, N_LINE, R, E, NU, MU, f * xi_c, [0.0], [0.0],
                                        [0.05], method=method)
            ref = MU * N_LINE * (2 * f - f * f)
            assert float(res.tangential_force) / ref == pytest.approx(1.0, rel=1e-6), (method, f)


# Was a strict xfail (cbrt(N ...) underflowed below ~1e-297 N); fixed: cbrt of each factor
# (hertz.py).
def test_hertz_3d_scaling_at_subnormal_loads():
    ref = hertz_3d(1.0, 1.0, 0.125, E, NU)
    for load in (1e-300, 1e-305, 1.1125369292536007e-308, 1e-315):
        h = hertz_3d(load, 1.0, 0.125, E, NU)
        scale = np.cbrt(load)
        assert float(h.a0) == pytest.approx(float(ref.a0) * scale, rel=1e-12, abs=0), load
        assert float(h.p0) == pytest.approx(float(ref.p0) * scale, rel=1e-12, abs=0), load


def test_corrugated_contact_rejects_zero_load_by_design():
    """The corrugated contact needs a contact (documented N > 0); the FMU short-circuits
    N <= 0 to zero forces before calling it (tests/test_effects.py)."""
    with pytest.raises(ValueError, match="normal_load"):
        cg.corrugated_contact(0.0, 0.0, R, E, NU, MU, 1e-4, [1e-6], [0.0], [0.05])


# --------------------------------------------------------------------------------------------
# Corrugation: a0/L -> 0 reduces to Hertz and Carter; a0/L > 1; edge of (4.2)
# --------------------------------------------------------------------------------------------
@pytest.mark.parametrize("method", ["exact", "linear"])
def test_corrugation_long_wave_limit_is_hertz_and_carter(method):
    """Fixed amplitude, a0/L -> 0: the surface curvature k^2 |Z| vanishes like (a0/L)^2 and the
    contact tends to Hertz (half-width) and Carter (force, stick zone); the deviation falls by
    ~100 per decade of a0/L."""
    a0 = float(hertz_2d(N_LINE, R, E, NU).a0)
    xi = 0.4 * MU * a0 / R
    t_carter = abs(float(carter_creep_force(xi, N_LINE, R, E, NU, MU)))
    r_carter = float(carter_stick_ratio(xi, N_LINE, R, E, NU, MU))
    devs = []
    for ratio in (1e-2, 1e-3, 1e-4):
        lam = a0 / ratio
        x = np.linspace(0.0, lam, 5)
        res = cg.corrugated_contact(x, N_LINE, R, E, NU, MU, xi, [1e-6], [0.0], [lam],
                                    method=method)
        dev = max(np.max(np.abs(res.half_width / a0 - 1)),
                  np.max(np.abs(res.tangential_force / t_carter - 1)),
                  np.max(np.abs(res.stick_half_width / (r_carter * a0) - 1)))
        devs.append(dev)
    assert devs[-1] < 1e-7
    assert devs[1] < 2e-2 * devs[0] and devs[2] < 2e-2 * devs[1]


@pytest.mark.parametrize("ratio", [3.0, 10.0])
def test_corrugation_short_waves_beyond_a0_over_l_one(ratio):
    """a0/L > 1 (many waves in the patch) at half the (4.2) limit: exact and linear both
    finite, within mu N, and the half-width oscillation shrinks as a0/L grows (the patch
    averages the waves)."""
    a0 = float(hertz_2d(N_LINE, R, E, NU).a0)
    lam = a0 / ratio
    k = 2 * np.pi / lam
    xi = 0.4 * MU * a0 / R
    out = {}
    for method in ("exact", "linear"):
        res = cg.corrugated_contact(np.linspace(0, lam, 9), N_LINE, R, E, NU, MU, xi,
                                    [0.5 / (k * k * R)], [0.0], [lam], method=method)
        assert np.all(np.isfinite(res.half_width)) and np.all(res.half_width > 0)
        assert np.all(res.tangential_force <= MU * N_LINE)
        out[method] = res.half_width / a0
    assert np.max(np.abs(out["exact"] - 1)) < 0.02 / ratio ** 0.5
    assert np.max(np.abs(out["exact"] - out["linear"])) < 1e-3


def test_corrugation_amplitude_at_edge_of_4_2():
    """k^2 R |Z| -> 1 from below: finite, positive patch; at and beyond 1: the documented
    ValueError naming the condition."""
    a0 = float(hertz_2d(N_LINE, R, E, NU).a0)
    lam = a0 / 0.2
    k = 2 * np.pi / lam
    x = np.linspace(0, lam, 9)
    for c in (0.999, 1 - 1e-6, 1 - 1e-12):
        res = cg.corrugated_contact(x, N_LINE, R, E, NU, MU, 1e-4, [c / (k * k * R)], [0.0],
                                    [lam])
        assert np.all(np.isfinite(res.half_width)) and res.half_width.min() > 0.5 * a0
        assert res.tangential_force.max() <= MU * N_LINE
    for c in (1.0, 1 + 1e-12, 2.0):
        with pytest.raises(ValueError, match=r"curvature_amplitude.*\(4\.2\)"):
            cg.corrugated_contact(x, N_LINE, R, E, NU, MU, 1e-4, [c / (k * k * R)], [0.0],
                                  [lam])


# Fixed (was a strict xfail): corrugation.solve_normal_exact raised "no single-patch solution"
# for long waves near the edge of (4.2) (a0/L = 0.05, k^2 R |Z| = 0.99 near a trough): its Newton
# step from (a0, 0) crossed a = 0 and converged to the mirror root (-a, Delta) of the equations,
# which are even in a; it now returns |a|. The second mode ("did not converge", a0/L = 1e-3,
# k^2 R |Z| = 0.858, |Delta| = 76 a0) was a step tolerance tol * a0 below the rounding of (4.31)
# (terms of size R k |Z| = 135 a0); the tolerance now scales with a0 + R sum k |Z|, and positions
# where Newton fails are re-solved by a bracketed 1-D reduction (Delta(a) from (4.31), then
# (4.33) in a).
def _reference_half_width_and_shift(x_axis, za, zb, lam, a, d, n_elements):
    from railcontact.reference.halfspace2d import solve_normal_2d
    k = 2 * np.pi / lam

    def gap(xb):
        return xb ** 2 / (2 * R) - (za * np.cos(k * (x_axis + xb)) + zb * np.sin(k * (x_axis + xb)))
    ref = solve_normal_2d(gap, N_LINE, E, NU, d - 1.3 * a, d + 1.3 * a, n_elements)
    return (0.5 * (ref.contact_end - ref.contact_start),
            0.5 * (ref.contact_end + ref.contact_start))


def test_corrugation_long_waves_near_edge_of_4_2_solve():
    """Long waves near the edge of (4.2): the exact solve succeeds at every position and agrees
    with the discretised 2-D half-space solver (independent: element log kernel, active set).
    Measured: |a - a_ref| = 2.9e-4 a0, |Delta - Delta_ref| = 3e-5 a0 (400 elements, X = 3L/8,
    Delta = -3.04 a0); 5.9e-4 a0 and 5e-6 a0 for the second repro (Delta = 76.4 a0); trough
    (a = 2.97 a0, 800 elements, dx = 0.0096 a0): 8.3e-4 a0 (the reference's edge estimate)."""
    a0 = float(hertz_2d(N_LINE, R, E, NU).a0)
    comp = 4 * (1 - NU ** 2) / (np.pi * E)
    for ratio, curv in ((0.05, 0.99), (np.exp(-4.0), 0.95)):
        lam = a0 / ratio
        k = 2 * np.pi / lam
        res = cg.corrugated_contact(np.linspace(0.0, lam, 33), N_LINE, R, E, NU, MU, 0.0,
                                    [curv / (k * k * R)], [0.0], [lam])
        assert np.all(np.isfinite(res.half_width)) and np.all(res.half_width > 0)
    res = cg.corrugated_contact(0.5009757221830826, N_LINE, R, E, NU, MU, 0.0,
                                [-0.08393828741367358], [-0.22802442202657747],
                                [2.3638322038063566])
    assert np.isfinite(float(res.half_width))
    lam = a0 / 0.05
    za = 0.99 / ((2 * np.pi / lam) ** 2 * R)
    cases = ((0.375 * lam, za, 0.0, lam, 400, 1e-3),
             (0.5 * lam, za, 0.0, lam, 800, 1.5e-3),
             (0.5009757221830826, -0.08393828741367358, -0.22802442202657747,
              2.3638322038063566, 400, 1e-3))
    for x_axis, c_a, c_b, wl, n_el, tol in cases:
        r = cg.corrugated_contact(x_axis, N_LINE, R, E, NU, MU, 0.0, [c_a], [c_b], [wl])
        a, d = float(r.half_width), float(r.patch_shift)
        a_ref, d_ref = _reference_half_width_and_shift(x_axis, c_a, c_b, wl, a, d, n_el)
        assert abs(a - a_ref) < tol * a0 and abs(d - d_ref) < tol * a0
        # the same root through the bracketed fallback (Newton limited to one step)
        a_b, d_b, _, _ = cg.solve_normal_exact(x_axis, N_LINE * comp, R, [2 * np.pi / wl],
                                               [c_a], [c_b], max_iter=1)
        assert abs(float(a_b) - a) < 1e-9 * a0 and abs(float(d_b) - d) < 1e-9 * a0
    # the sign of a: the mirror root is never returned
    a_m, _, _, _ = cg.solve_normal_exact(0.375 * lam, N_LINE * comp, R, [2 * np.pi / lam],
                                         [za], [0.0])
    assert float(a_m) > 0


# --------------------------------------------------------------------------------------------
# Tables: on knots, on the saturation knot, at the grid edges, just outside
# --------------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def creep_table():
    return CreepTable.from_file()


def _f_table(table, z):
    load, a0, b0 = 1e5, 6e-3, 5e-3
    xi_sat = float(np.asarray(saturation_creepage_3d(load, a0, b0, E, NU, MU)).ravel()[0])
    t = table.creep_force_3d(np.asarray(z, dtype=float) * xi_sat, 0.0, 0.0, load, a0, b0, E,
                             NU, MU)
    return -np.asarray(t.tx) / (MU * load)


def test_table_on_knots_equals_the_model(creep_table):
    """At every node the spline returns the tabulated value, i.e. F(z) of Eq. (2.87)."""
    nodes = np.asarray(creep_table.table.axes[0]["nodes"], dtype=float)
    raw = creep_table.table("force_ratio", nodes[:, None])
    exact = strip_force_function(np.minimum(nodes, 1.0))
    assert np.max(np.abs(raw - exact)) < 1e-13
    # through the physical interface (creepage -> z has one rounding)
    assert np.max(np.abs(_f_table(creep_table, nodes) - exact)) < 1e-9


def test_table_on_the_saturation_knot(creep_table):
    """z = 1 is a (double) knot: F(1) = 1 to rounding, never above, and one-sided slopes agree
    (C1; F'(1) = 0)."""
    nodes = np.asarray(creep_table.table.axes[0]["nodes"], dtype=float)
    assert np.any(nodes == 1.0)
    f1 = float(creep_table.table("force_ratio", np.array([[1.0]]))[0])
    assert abs(f1 - 1.0) <= 4 * np.finfo(float).eps and f1 <= 1.0
    h = 1e-6
    f = creep_table.table("force_ratio", np.array([[1 - h], [1.0], [1 + h]]))
    assert abs((f[2] - f[1]) / h) < 1e-6 and abs((f[1] - f[0]) / h) < 1e-3
    assert np.all(_f_table(creep_table, np.linspace(0.99, 1.01, 2001)) <= 1.0)


def test_table_grid_edges_and_just_outside(creep_table):
    """z = 0 (first node): exactly zero force. z = z_max (last node) and just beyond it: the
    held full-sliding value F = 1 (mu N), continuous across the edge; far outside the same."""
    nodes = np.asarray(creep_table.table.axes[0]["nodes"], dtype=float)
    z_max = nodes[-1]
    assert float(_f_table(creep_table, 0.0)) == 0.0
    edge = _f_table(creep_table, np.array([z_max * (1 - 1e-12), z_max,
                                           np.nextafter(z_max, 2 * z_max), 1.01 * z_max,
                                           1e6]))
    assert np.all(np.abs(edge - 1.0) <= 4 * np.finfo(float).eps) and np.all(edge <= 1.0)
    # the table is 1-D in z; other inputs have the solver's ranges: outside them a ValueError
    with pytest.raises(ValueError, match="poisson_ratio"):
        creep_table.creep_force_3d(1e-3, 0.0, 0.0, 1e5, 6e-3, 5e-3, E, 0.5, MU)


# --------------------------------------------------------------------------------------------
# FMU: the hard regions in one run (spin pole inside, N -> 0, sign changes, far saturation)
# --------------------------------------------------------------------------------------------
def test_fmu_hard_regions_finite_bounded_and_flagged(built_fmu, tmp_path):
    from fmpy import extract, read_model_description
    from fmpy.fmi2 import FMU2Slave

    from railcontact.scene import INPUTS

    root = __import__("pathlib").Path(__file__).resolve().parents[1]
    md = read_model_description(str(built_fmu))
    vr = {v.name: v.valueReference for v in md.modelVariables}
    fmu = FMU2Slave(guid=md.guid, unzipDirectory=extract(str(built_fmu), str(tmp_path / "x")),
                    modelIdentifier=md.coSimulation.modelIdentifier, instanceName="hard")
    fmu.instantiate()
    fmu.setupExperiment(startTime=0.0)
    fmu.setString([vr["scene_file"]], [str(root / "examples/scenes/creep_only_analytic.toml")])
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    names = ["Fx", "Fy", "a0", "b0", "p0", "stick_area_fraction", "stick_width_ratio", "r_a0"]
    outs = [vr[n] for n in names]
    rows = {   # normal_force, xi_x, xi_y, spin, speed, position
        "no contact": (0.0, 5e-3, -1e-3, 0.5, 30.0, 0.0),
        "tiny load": (1e-300, 5e-3, -1e-3, 0.5, 30.0, 0.0),
        "tiny creepage": (8e4, 1e-300, 0.0, 0.0, 30.0, 0.0),
        "zero creepage": (8e4, 0.0, 0.0, 0.0, 30.0, 0.0),
        "far beyond saturation": (8e4, -0.5, 0.3, 0.0, 30.0, 0.0),
        "spin pole inside": (8e4, 1e-5, 0.0, 8.0, 30.0, 0.0),
        "standstill": (8e4, 1e-3, 0.0, 0.0, 0.0, 0.0),
    }
    try:
        got = {}
        for k, (label, row) in enumerate(rows.items()):
            fmu.setReal([vr[n] for n in INPUTS], list(row))
            fmu.doStep(k * 1e-3, 1e-3)
            got[label] = np.array(fmu.getReal(outs))
            assert np.all(np.isfinite(got[label])), label
            assert math.hypot(*got[label][:2]) <= 0.3 * row[0], label
            valid = fmu.getBoolean([vr["creep_within_validity"]])[0]
            assert valid == (label != "spin pole inside"), label
    finally:
        fmu.terminate()
        fmu.freeInstance()
    assert np.all(got["no contact"][:2] == 0.0)
    assert np.all(got["zero creepage"][:2] == 0.0)
    assert got["tiny creepage"][0] < 0.0
    assert math.hypot(*got["far beyond saturation"][:2]) == pytest.approx(0.3 * 8e4, rel=1e-12)


# --------------------------------------------------------------------------------------------
# Non-steady (Ch. 7): stick ratio at the ends of its documented range (0, 1]
# --------------------------------------------------------------------------------------------
def test_nonsteady_stick_ratio_limits():
    """r -> 0+ and r = 1: finite transfer functions, continuous into both ends (r = 0 itself is
    outside the documented range and raises, see tests/test_nonsteady.py)."""
    from railcontact.nonsteady import nonsteady_transfer_function_normalised as tf

    waves = np.array([1e-6, 0.5, 3.0, 50.0])
    for variant in ("derived", "printed"):
        h = {r: tf(waves, r, variant=variant) for r in (1e-12, 1e-9, 1 - 1e-9, 1.0)}
        for r, v in h.items():
            assert np.all(np.isfinite(v)), (variant, r)
        # H - 1 = O(k a0 r) as r -> 0 (|H - 1| ~ 160 (a0/L) r measured): continuous into r = 0+
        assert np.max(np.abs(h[1e-12] - h[1e-9]) / (1 + waves)) < 1e-6
        assert np.max(np.abs(h[1.0] - h[1 - 1e-9])) < 1e-6


@pytest.mark.parametrize("m", [0.5, 1.5])
def test_ohyama_matches_high_precision_quadrature(m):
    """Ohyama's force (2/pi)[I(b, 1) + m I(-1, b)] - r^2, b = 1 - 2r, r = 1 - |chi|, evaluated
    independently by 40-digit mpmath quadrature of sqrt(1 - x^2): the cancellation-free form in
    friction.py (series for the circle segment at small chi) agrees to 1e-10 relative from
    chi = 1e-30 to full sliding."""
    import mpmath as mp

    mp.mp.dps = 40

    def reference(chi):
        chi = mp.mpf(chi)
        r = 1 - min(abs(chi), 1)
        b = 1 - 2 * r
        seg = lambda u, v: mp.quad(lambda x: mp.sqrt(1 - x * x), [u, v])  # noqa: E731
        return -((2 / mp.pi) * (seg(b, 1) + m * seg(-1, b)) - r * r)

    for chi in (1e-30, 1e-12, 1e-6, 1e-4, 2e-3, 0.3, 0.9, 1.0, 3.0):
        got = float(fr.ohyama_creep_force_normalised(chi, m))
        ref = float(reference(chi))
        assert got == pytest.approx(ref, rel=1e-10, abs=0), chi
