"""The built-in table specifications (registered on import).

Why one module of about 880 lines: it holds every registered table specification (axes, point
function, check points and attributes of each shipped table), one block per table.

Each spec's point function maps table coordinates to the tabulated variables by calling the
direct model in :mod:`railcontact`; the coordinate conversions live in
:mod:`railcontact.tables` next to the readers that invert them.
"""

from __future__ import annotations

import numpy as np
from railcontact.creep_common import CREEPAGE_COORDINATE_FORM
from railcontact.creep_common import (
    EXACT_TABLE_LATERAL_ELEMENTS_NARROW as EXACT_LATERAL_ELEMENTS_NARROW,
    EXACT_TABLE_NARROW_ASPECT_MAX as EXACT_NARROW_ASPECT_MAX,
    EXACT_TABLE_NARROW_SPIN_MIN as EXACT_NARROW_SPIN_MIN,
    EXACT_TABLE_LATERAL_ELEMENTS_VERY_NARROW as EXACT_LATERAL_ELEMENTS_VERY_NARROW,
    EXACT_TABLE_VERY_NARROW_ASPECT_MAX as EXACT_VERY_NARROW_ASPECT_MAX)

from .spec import Axis, TableSpec, Variable

#: The built-in specs, in registration order (``tablegen.registry`` looks them up by name).
SPECS: list[TableSpec] = []


def register(spec):
    """Add a built-in spec to :data:`SPECS` and return it."""
    SPECS.append(spec)
    return spec

THESIS = ("J.B. Nielsen, New Developments in the Theory of Wheel/Rail Contact Mechanics, "
          "IMM-PHD-1998-51, DTU, 1998")

_COUNTS = {"coarse": 16, "default": 32, "fine": 64}


# --------------------------------------------------------------------------------------------
# Self-test (hidden): a synthetic saturating function with a C1 kink, NOT physics
# --------------------------------------------------------------------------------------------

def _selftest_axes(resolution):
    n = {"coarse": 8, "default": 12, "fine": 24}[resolution]
    z = np.r_[np.linspace(0.0, 1.0, n + 1), 1.25, 1.5, 2.0]
    return [Axis("x", z, "1", "synthetic coordinate, kink at 1", double_knots=(1.0,),
                 out_of_range="hold"),
            Axis("s", np.linspace(0.5, 2.0, 5), "1", "synthetic parameter")]


def selftest_function(points):
    """Synthetic test function f = 1 - (1 - min(x,1))^2 (1 + s x / 2) (C1 kink at x = 1),
    g = s sin(x). Used only by the tests of the build machinery."""
    x, s = points[:, 0], points[:, 1]
    xc = np.minimum(x, 1.0)
    return np.stack([1.0 - (1.0 - xc) ** 2 * (1.0 + 0.5 * s * xc), s * np.sin(x)], axis=1)


register(TableSpec(
    name="selftest",
    title="synthetic self-test table of tablegen (not physics)",
    axes=_selftest_axes,
    function=selftest_function,
    variables=[Variable("f", "1", "synthetic saturating function", error_target=1e-2),
               Variable("g", "1", "synthetic smooth function", error_target=1e-2)],
    references="none (synthetic)",
    method="tablegen.specs.selftest_function",
    n_check={"coarse": 50, "default": 100, "fine": 200},
    chunk_size=8,
    hidden=True,
))


# --------------------------------------------------------------------------------------------
# Creep forces, modified strip theory (Nielsen Sec. 2.6)
# --------------------------------------------------------------------------------------------

def _modified_strip_axes(resolution):
    n = _COUNTS[resolution]
    u = np.linspace(0.0, 1.0, n + 1)
    z = np.r_[1.0 - (0.5 * (1.0 + np.cos(np.pi * u))) ** 2, 1.05, 1.15, 1.3, 1.5]
    return [Axis(
        "normalised_creepage", z, "1",
        "modified creepage magnitude |w|/w_sat, w = (C11 xi_x, C22 xi_y + sqrt(a0 b0) C23 phi), "
        "w_sat = pi^2 (1 + nu) mu p0 / E (1 = onset of full sliding)",
        double_knots=(1.0,), out_of_range="hold",
        comment="nodes z = 1 - ((1 + cos(pi u))/2)^2 (u uniform) crowd towards z = 0 (initial "
                "slope = linear theory to ~1e-7 relative) and towards the saturation z = 1, "
                "where the third derivative of the force (second of the stick area) has a "
                "square-root singularity; z >= 1 is full "
                "sliding (force ratio 1, no stick zone), so values are held beyond the last "
                "node (exact)")]


def modified_strip_function(points):
    """|T|/(mu N) and the stick area fraction of the modified strip theory at z = points[:, 0].

    Evaluated with :func:`railcontact.creep_solution_3d` on a reference contact (longitudinal
    creepage only), which is exact for every direction and spin because the theory depends on
    the creepages only through z (see :mod:`railcontact.creep3d`).
    """
    from railcontact.creep3d import creep_solution_3d, saturation_creepage_3d  # noqa: PLC0415

    z = points[:, 0]
    args = (1.0e5, 6.0e-3, 5.0e-3, 210e9, 0.28, 0.3)  # N, a0, b0, E, nu, mu (any contact)
    xi_sat = saturation_creepage_3d(*args)
    sol = creep_solution_3d(-z * xi_sat, 0.0, 0.0, *args, method="modified_strip")
    mu_n = args[0] * args[-1]
    return np.stack([np.hypot(sol.tx, sol.ty) / mu_n, sol.stick_area_fraction], axis=1)


def _modified_strip_check(axes, n, rng):
    return np.sort(rng.uniform(0.0, 1.6, n))[:, None]


register(TableSpec(
    name="creep_modified_strip",
    title="Creep force and stick area of the modified strip theory (Nielsen 1998, Sec. 2.6)",
    axes=_modified_strip_axes,
    function=modified_strip_function,
    variables=[
        Variable("force_ratio", "1",
                 "magnitude of the tangential force over the Coulomb limit, |T|/(mu N)",
                 comment="T = -mu N force_ratio(z) w/|w| (on the wheel, opposing the "
                         "Kalker-weighted creepage w); <= 1"),
        Variable("stick_area_fraction", "1",
                 "stick area over the contact area pi a0 b0 (strip-theory estimate)"),
    ],
    references=(f"{THESIS}, Sec. 2.6, Eqs. (2.85)-(2.99) (modified strip theory with the "
                "small-spin substitution (2.99)); J.J. Kalker, Three-dimensional elastic bodies "
                "in rolling contact, Kluwer, 1990 (creep coefficients)"),
    method="railcontact.creep3d.creep_solution_3d(method='modified_strip')",
    check_points=_modified_strip_check,
    n_check={"coarse": 2000, "default": 5000, "fine": 20000},
    chunk_size=512,
    requires=("railcontact.creep3d",),
    attributes={"normalisation": (
        "the modified strip theory depends on the creepages only through z = |w|/w_sat and "
        "the direction of w, so one 1-D table serves every load, material, a0/b0, creepage "
        "direction and (small) spin; the reader converts with railcontact.kalker_coefficients")},
))


# --------------------------------------------------------------------------------------------
# Creep forces, exact theory (discretised, railcontact.reference.rolling3d)
# --------------------------------------------------------------------------------------------

#: The solver setting the table is built with: the exact method's default
#: (``creep_force_3d(method="exact")``): one Richardson step in the rolling-direction element
#: size, 30 x 20 and 60 x 20 elements, on two grids moved -1/4 and +1/4 of an element, the
#: results averaged (0.17 % of mu N max against the converged exact theory on CONTACT's 21
#: grid-convergence cases, against 0.33 % for one grid at 40 x 20 and 80 x 20: the setting of
#: the tables before 2026-11-26, whose slope at zero creepage was 1-5 % above Kalker's),
#: tolerance 1e-4 (the forces within 0.0004 % of mu N of a converged iteration).
EXACT_SOLVER = dict(mx=30, my=20, tolerance=1e-4, max_iterations=4000)
EXACT_RICHARDSON = True
EXACT_GRID_SHIFTS = (-0.25, 0.25)
#: Lateral elements where the contact is narrow in the rolling direction and the spin large
#: (since 2026-11-27): there the spin's slip varies fastest across the wide lateral extent,
#: and 20 elements across 2.16 b0 leave the discrete solution depending on where the spin
#: pole falls between element rows. Measured along creepage scans (rho / w 0.03-1.2, four
#: cases with tau 4.4-20 per a0/b0) against 30 (60) x 80 elements, % of mu N max:
#: a0/b0 = 0.1: my = 20 1.29, 27 0.63, 36 0.17; 0.18: 1.51, 0.68, 0.20; 0.32: 0.69, 0.29,
#: 0.15; 0.56: 0.37, 0.20, 0.12; 1: 0.20, 0.10, 0.05; 1.8: 0.10 with 20 (the forces along
#: such a scan at a0/b0 = 0.18, tau = 9.5 alternate by up to 1 % of mu N with 20 elements,
#: smooth with 40). With tau <= 1 20 elements are within 0.13 %. So where a0/b0 < 0.87 and
#: |tau| > 2.75 (between the nodes 0.75 and 1 of a0/b0 and 2.5 and 3 of tau; rebuilt in
#: steps: a0/b0 < 0.45, 62,370 solver points of the computed quarter, then the node 0.56,
#: 20,790 (threshold 0.75 until the node 0.75 came, 2026-11-27); from tau = 1.3 it would
#: have been 1.7 times as many) the table's solver
#: uses 36 lateral elements: EXACT_LATERAL_ELEMENTS_NARROW, EXACT_NARROW_ASPECT_MAX,
#: EXACT_NARROW_SPIN_MIN (imported from railcontact.creep_common, which the table's solver
#: beyond its axes shares).


def exact_solver_lateral_elements(log_aspect_ratio, spin_coordinate, aspect_max=None,
                                  spin_min=None, very_narrow_max=None):
    """Lateral elements ``my`` of the table's solver at table points: 48 where a0/b0 <
    ``very_narrow_max`` and 36 where a0/b0 < ``aspect_max``, both where |tau| > ``spin_min``
    (defaults :data:`EXACT_VERY_NARROW_ASPECT_MAX` = 0.115 (the node 0.1; 0.2 once the
    nodes 0.133 and 0.178 are rebuilt), :data:`EXACT_NARROW_ASPECT_MAX` =
    0.87, :data:`EXACT_NARROW_SPIN_MIN` = 2.75; :data:`EXACT_LATERAL_ELEMENTS_VERY_NARROW`,
    :data:`EXACT_LATERAL_ELEMENTS_NARROW`), else 20. ``very_narrow_max = 0``: no 48 tier
    (the rules before 2026-11-28). [-]"""
    aspect_max = EXACT_NARROW_ASPECT_MAX if aspect_max is None else aspect_max
    spin_min = EXACT_NARROW_SPIN_MIN if spin_min is None else spin_min
    very_narrow_max = (EXACT_VERY_NARROW_ASPECT_MAX if very_narrow_max is None
                       else very_narrow_max)
    log_g = np.asarray(log_aspect_ratio)
    spin = np.abs(np.asarray(spin_coordinate)) > spin_min
    very = spin & (log_g < (np.log(very_narrow_max) if very_narrow_max > 0.0 else -np.inf))
    narrow = spin & (log_g < np.log(aspect_max))
    return np.where(very, EXACT_LATERAL_ELEMENTS_VERY_NARROW,
                    np.where(narrow, EXACT_LATERAL_ELEMENTS_NARROW, EXACT_SOLVER["my"]))

_EXACT_COUNTS = {  # nodes: ln(a0/b0), nu, rho (incl. 0 and inf), theta in [-pi/2, pi/2], tau
    "coarse": (4, 4, 7, 5, 5),
    "default": (14, 5, 29, 23, 28),  # theta every 15 degrees (30 until 2026-11-26: with
    # large spin up to 7.4 % of mu N midway between its nodes, exact_table_accuracy --axes),
    # and +-3.75, +-7.5, +-67.5, +-82.5, +-86.25 since 2026-11-27 (below); rho and tau with 5 and 7
    # more nodes and a0/b0 with 3 since 2026-11-27 (below); rho with 0.25 and 0.32 and tau
    # with 1.7 since 2026-11-27 (seventh session, below); rho with 0.30 and tau with 1.375
    # since 2026-11-27 (eighth session, below), and a0/b0 with 0.133 (eighth session, below)
    "fine": (13, 6, 25, 13, 25),
}
EXACT_TAU_MAX = 20.0
EXACT_ASPECT_RANGE = (0.1, 10.0)
#: ln(a0/b0) nodes where they are not uniform over EXACT_ASPECT_RANGE: the uniform 9 (a0/b0
#: 0.1, 0.18, 0.32, 0.56, 1, 1.8, 3.2, 5.6, 10) and, since 2026-11-27, the midpoints 0.42 and
#: 0.75 of the two intervals where large spin changes the force fastest with a0/b0 (the stick
#: area shrinks from ~0.1 to ~0.03 of the ellipse between a0/b0 0.7 and 0.8 at tau 2.5-3):
#: one-axis cubic fits through the solver's values along ln(a0/b0) at the worst random cases
#: erred by 0.75 % of mu N (a0/b0 0.43, tau 4.1) and 0.55 % (0.79, tau 6.8) on the uniform
#: nodes, 0.23 % and 0.10 % with the intervals halved; and (fifth session of 2026-11-27)
#: 7.5, the midpoint of 5.6-10, where the worst random cases against the converged theory lay;
#: and (sixth session) 2.37, the midpoint of 1.8-3.2: one-axis errors along ln(a0/b0) of 0.50
#: and 0.51 % of mu N at a0/b0 2.49 (tau 19.9) and 2.16 (tau 7.1), the worst random cases left;
#: and (eighth session) 0.133, the midpoint of the end interval 0.1-0.18: the worst random
#: cases left lay there with large spin (a0/b0 0.133, tau 10.3: 0.51 % of mu N against the
#: solver, 0.52 % against the converged theory; one axis at a time, along ln(a0/b0) 0.53 %,
#: every other axis 0.04 % or less)
_EXACT_ASPECT_EXTRA = {"default": (0.5, 2.5, 3.5, 5.5, 7.5)}   # in steps of the uniform grid
# from 0.1
# (the uniform grid has the count of _EXACT_COUNTS less these)
_EXACT_RHO = {  # the creepage magnitudes r = |v| / w of the computed quarter (inf: full
    # sliding), w = sqrt(1 + tau^2). Graded towards 0: without spin the force's curvature jumps
    # there (Carter's 2 r - r |r|), and the spline's slope at 0 errs in proportion to the first
    # interval (0.08 put it 4.5 % below Kalker's coefficients; 0.006 up to 0.8 % at a0/b0 =
    # 10, where the lateral force bends within rho ~ 0.01: 0.0007 and 0.002 added, which
    # leaves 0.05 % in a 1-D fit of the solver's values); crowded near r = 1, the onset of
    # full sliding without spin; 0.13, 0.22 and 0.36 added (fifth session of 2026-11-27)
    # where moderate spin makes the adhesion area collapse below saturation (a/b 10, tau 1.3:
    # from 0.70 to 0.05 of the ellipse between rho / w 0.22 and 0.27; a 1-D fit through the
    # solver's values along rho erred 3.7 and 3.1 % of mu N on the old nodes, 0.7 and 1.2 %);
    # 0.25 and 0.32 added (seventh session of 2026-11-27), the midpoints in s of 0.22-0.28 and
    # 0.28-0.36, where that collapse still erred most: a build check point at a0/b0 4.3, tau
    # 1.31 (0.86 % of mu N; one axis at a time, along s 1.1 %) and the known kink line a0/b0
    # 10, tau 1.3, theta 135 deg (0.93 %, at rho / w 0.29, all other coordinates on nodes);
    # 0.30 added (eighth session of 2026-11-27), the midpoint in s of 0.28-0.32, where that
    # kink line still erred 0.52 % of mu N (at rho / w 0.29)
    "coarse": [0.0, 0.5, 0.9, 1.1, 1.6, 3.0, np.inf],
    "default": [0.0, 0.0007, 0.002, 0.006, 0.02, 0.045, 0.09, 0.13, 0.17, 0.22, 0.25, 0.28,
                0.30, 0.32, 0.36, 0.45, 0.62, 0.77, 0.88, 0.96, 1.03, 1.1, 1.22, 1.45, 1.85,
                2.5, 3.6, 6.0, np.inf],
    "fine": [0.0, 0.004, 0.012, 0.03, 0.06, 0.1, 0.15, 0.3, 0.45, 0.58, 0.7, 0.8, 0.88, 0.94,
             0.99, 1.03, 1.07, 1.12, 1.2, 1.32, 1.5, 1.8, 2.5, 4.0, np.inf],
}
_EXACT_TAU = {  # spin coordinates of the computed quarter: graded towards 0 (the spin's force
    # at zero combined creepage starts at second order), about uniform where the adhesion
    # area vanishes with growing spin (tau ~ 1.5-3, a kink in the slope), geometric beyond;
    # 0.875, 1.45, 2.25 and 16.5 added 2026-11-27 (midway errors up to 0.5-0.8 % of mu N in
    # those intervals, at most 0.1 % in the others but 13.5-20: 0.2 %); 0.003 and 0.01 too:
    # along pure spin the force leaves the linear theory by 0.8 % within tau = 0.03 at a0/b0
    # = 10, and with the first node there the slope d Ty / d phi at zero (C23) erred 0.85 %;
    # 1.8 added 2026-11-27 (a one-axis fit along tau through the solver's values erred by
    # 0.72 % of mu N at a0/b0 4.3, tau 1.88 and 0.37 % at a0/b0 2.8, tau 1.77 with the
    # interval 1.6-2; 0.20 and 0.09 % with the intervals halved); 1.7 added (seventh session
    # of 2026-11-27), the midpoint of 1.6-1.8: the build's worst check point left (a0/b0 1.63,
    # tau 1.71, rho / w 0.10, 0.66 % of mu N; one axis at a time, along tau 0.87 %), where
    # the adhesion area vanishes with growing spin; 1.375 added (eighth session of
    # 2026-11-27), the midpoint of 1.3-1.45: the build's worst check point left (a0/b0 4.33,
    # tau 1.37, rho / w 0.24, 0.57 % of mu N in f_par; one axis at a time, along tau 0.65 %,
    # along ln(a0/b0) 0.16 %, along s 0.13 %)
    "coarse": [0.0, 1.0, 2.5, 6.0, 20.0],
    "default": [0.0, 0.003, 0.01, 0.03, 0.1, 0.25, 0.5, 0.75, 0.875, 1.0, 1.3, 1.375, 1.45,
                1.6, 1.7, 1.8, 2.0, 2.25, 2.5, 3.0, 3.6, 4.4, 5.5, 7.0, 9.5, 13.5, 16.5, 20.0],
    "fine": [0.0, 0.03, 0.1, 0.2, 0.4, 0.6, 0.8, 1.0, 1.2, 1.4, 1.6, 1.8, 2.0, 2.25, 2.5, 2.8,
             3.2, 3.6, 4.1, 4.7, 5.5, 7.0, 10.0, 14.0, 20.0],
}


#: creepage angles of the computed quarter [deg] where they are not uniform (symmetric about
#: 0; the full circle adds 180 - theta and the seam)
_EXACT_THETA = {
    # +-3.75, +-7.5, +-67.5 and +-82.5 added 2026-11-27: large spin turns the force within
    # ~15 degrees of theta = 0 (a0/b0 < 1) and +-90 degrees (a0/b0 > 1); on the 15-degree grid
    # a periodic cubic through the solver's values along theta erred by up to 3.6 % of mu N
    # there (a0/b0 0.1 and 10, tau 3-16.5, at nodes of the other axes), with +-7.5 and +-82.5
    # by up to 0.64 % (a0/b0 0.1, near theta = 0) and 0.60 % (a0/b0 10, near 68 degrees), with
    # all four pairs by up to 0.33 % (10 such profiles); +-86.25 added 2026-11-27 (sixth
    # session): the worst random case left (a0/b0 8.8, tau 12.9, theta 87 deg, 0.79 % of mu N)
    # was this axis; a periodic cubic through the solver's values (a0/b0 10, rho/w 0.88,
    # tau 13.5, theta 60-120 deg) erred 1.25 % without the pair, 0.12 % with it
    "default": [-90.0, -86.25, -82.5, -75.0, -67.5, -60.0, -45.0, -30.0, -15.0, -7.5, -3.75,
                0.0, 3.75, 7.5, 15.0, 30.0, 45.0, 60.0, 67.5, 75.0, 82.5, 86.25, 90.0],
}


def _full_circle(theta):
    """The periodic angle nodes over [-pi, pi] of the quarter nodes ``theta`` in [-pi/2,
    pi/2] (symmetric about 0): theta, pi - theta, wrapped, with both ends of the seam."""
    both = np.r_[theta, np.pi - theta]
    wrapped = (both + np.pi) % (2.0 * np.pi) - np.pi
    nodes = np.unique(np.round(wrapped, 12))
    return np.r_[nodes, nodes[0] + 2.0 * np.pi]


def _exact_quarter(resolution):
    """Nodes of the computed quarter: ln g, nu, s >= 0, theta in [-pi/2, pi/2], tau >= 0."""
    from railcontact.exact_table import creepage_coordinate  # noqa: PLC0415

    n_g, n_nu, n_r, n_t, n_s = _EXACT_COUNTS[resolution]
    lo, hi = np.log(EXACT_ASPECT_RANGE)
    extra = np.asarray(_EXACT_ASPECT_EXTRA.get(resolution, ()), dtype=float)
    n_u = n_g - len(extra)
    g = np.sort(np.r_[np.linspace(lo, hi, n_u), lo + extra * (hi - lo) / (n_u - 1)])
    rho = np.asarray(_EXACT_RHO[resolution])
    tau = np.asarray(_EXACT_TAU[resolution])
    assert len(rho) == n_r and len(tau) == n_s and tau[-1] == EXACT_TAU_MAX
    theta = (np.radians(_EXACT_THETA[resolution]) if resolution in _EXACT_THETA
             else np.linspace(-0.5 * np.pi, 0.5 * np.pi, n_t))
    assert len(theta) == n_t and np.allclose(theta, -theta[::-1])
    return (g, np.linspace(0.0, 0.5, n_nu),
            creepage_coordinate(rho), theta, tau)


def _exact_axes(resolution):
    g, nu, s, theta, tau = _exact_quarter(resolution)
    full_theta = _full_circle(theta)
    return [
        Axis("log_aspect_ratio", g, "1",
             "natural logarithm of the semi-axis ratio a0/b0 (rolling over lateral)",
             comment=f"a0/b0 from {EXACT_ASPECT_RANGE[0]} to {EXACT_ASPECT_RANGE[1]}"),
        Axis("poisson_ratio", nu, "1", "Poisson's ratio nu of both bodies"),
        Axis("creepage_coordinate", np.r_[-s[:0:-1], s], "1",
             "s = (2 / pi) atan(rho / sqrt(1 + tau^2)), rho = |v|, v = (C11 xi_x, C22 xi_y + "
             "sqrt(a0 b0) C23 phi) / w_sat, w_sat = pi^2 (1 + nu) mu p0 / E, p0 = 3 N / (2 pi "
             "a0 b0), C_ij Kalker's coefficients, tau the spin coordinate; signed: (-s, theta "
             "+ pi) is the point (s, theta)",
             comment="s = 1 is rho = infinity (full sliding, spin negligible); nodes graded "
                     "towards s = 0 and crowded near rho / sqrt(1 + tau^2) = 1 (onset of full "
                     "sliding without spin); the negative half mirrors the positive (double "
                     "cover, smooth through v = 0)"),
        Axis("creepage_angle", full_theta, "rad",
             "theta = atan2(v_y, v_x), the direction of the combined creepage v",
             periodic=True, comment="periodic over [-pi, pi]"),
        Axis("spin_coordinate", np.r_[-tau[:0:-1], tau], "1",
             "tau = phi sqrt((b0 C11)^2 + (a0 C22)^2) / w_sat (rigid slip of the spin at the "
             "ellipse edges over the saturation creepages), signed with phi",
             comment="about uniform up to tau ~ 3, geometric beyond; beyond |tau| = "
                     f"{EXACT_TAU_MAX:g} the reader falls back to the solver"),
    ]


#: The exact table's forces and moment are stored to multiples of this (over mu N, resp. mu N
#: sqrt(a0 b0)): the spline within 2.4e-4 of them, 20 times below the 0.5 % target. 2^-15
#: until the sixth session of 2026-11-27; 2^-13 broke T(-v, -phi) = -T(v, phi) (1.7e-5 of
#: mu N) until the coefficients were made exactly symmetric (_exact_coefficient_symmetry):
#: 15.8 MB against 18.5 at 2^-15 with the angle nodes +-86.25; 2^-12 in the eighth
#: session of 2026-11-27, to make room for two node planes under 20 MB (the quarter
#: 13 x 5 x 28 x 23 x 27 took 19.7 MB at 2^-13; re-rounded to 2^-12 its coefficients
#: compressed 1.7 MB smaller), 2^-11 later in that session for the a0/b0 node 0.133 (the
#: quarter 13 x 5 x 29 x 23 x 28 took 19.9 MB at 2^-12; re-rounded to 2^-11, 2.2 MB less)
EXACT_ABSOLUTE_PRECISION = 2.0**-11
#: ... and its stick area fraction to multiples of this (within 0.008, against its target
#: 0.05; its many small coefficients had taken 3.1 of 17.3 MB at 2 significant digits, 1.9
#: of 18.4 at 2^-7, 1.5 at 2^-6)
EXACT_STICK_AREA_ABSOLUTE_PRECISION = 2.0**-6


#: |s| below which the exact table's coefficients keep their significant digits (the nodes
#: rho / w = 0 to 0.006)
EXACT_RELATIVE_PRECISION_S_MAX = 0.005


def _near_zero_creepage(axes):
    """Coefficients next to zero creepage (|s| < :data:`EXACT_RELATIVE_PRECISION_S_MAX`),
    kept to significant digits, as a mask broadcastable to the exact table's coefficient
    grid."""
    names = [a.name for a in axes]
    k = names.index("creepage_coordinate")
    s = np.asarray(axes[k].nodes)
    shape = [1] * len(axes)
    shape[k] = len(s)
    return (np.abs(s) < EXACT_RELATIVE_PRECISION_S_MAX).reshape(shape)


#: Multipliers of (f_par, f_perp, moment, stick area) under the exact table's three
#: symmetries (:func:`_exact_symmetry_image`): the double cover D (e(theta + pi) = -e(theta),
#: so both components change sign), the mirror in y S1 and the reversal of x at fixed spin S3
_EXACT_SYMMETRY_SIGNS = {"D": np.array([-1.0, -1.0, 1.0, 1.0]),
                         "S1": np.array([1.0, -1.0, -1.0, 1.0]),
                         "S3": np.array([1.0, -1.0, 1.0, 1.0])}


def _exact_symmetry_image(s, theta, tau, signs, op):
    """The grid point (s, theta, tau) and the multipliers ``signs`` under one of the exact
    table's symmetries: D, the double cover (-s, theta + pi); S1, the mirror in y (s, -theta,
    -tau); S3, the reversal of x at fixed spin (s, pi - theta, tau). Theta is not wrapped."""
    signs = signs * _EXACT_SYMMETRY_SIGNS[op]
    if op == "D":
        return -s, theta + np.pi, tau, signs
    if op == "S1":
        return s, -theta, -tau, signs
    return s, np.pi - theta, tau, signs


def _wrapped(theta):
    """theta in [-pi, pi)."""
    return (theta + np.pi) % (2.0 * np.pi) - np.pi


def _exact_reduce(axes):
    """Quarter points for the solver, and the assembly of the full grid by symmetry (see
    :mod:`railcontact.exact_table`).

    The three symmetries (the double cover D, the mirror in y S1, the reversal of x at fixed
    spin S3) generate a group of eight maps of the grid onto itself. A quarter node on one of
    its mirror planes (tau = 0, theta = +-pi/2, s = 0) has mirror images inside the quarter,
    and the solver computes each of them on its own (its grid, shifted by a quarter element,
    is not symmetric): they agree only to its tolerance, about 5e-6 of mu N. ``assemble``
    therefore averages every quarter value over its images (the group average, a projection),
    so the full grid, and with it the fitted spline, has every symmetry exactly: T(-v, -phi)
    = -T(v, phi) to rounding, and f_perp = 0 on theta = +-pi/2 where S3 demands it.
    """
    g, nu, s, theta, tau = (a.nodes for a in axes)
    s_q, th_q, tau_q = s[s >= 0.0], theta[np.abs(theta) <= 0.5 * np.pi + 1e-12], tau[tau >= 0.0]
    mesh = np.meshgrid(g, nu, s_q, th_q, tau_q, indexing="ij")
    points = np.stack([m.ravel() for m in mesh], axis=1)
    shape_q = (len(g), len(nu), len(s_q), len(th_q), len(tau_q))

    def reduced(ss, tt, uu):
        """Quarter node indices of the full node (ss, tt, uu) and the multipliers of f_par,
        f_perp, moment (the stick area is even)."""
        f = np.ones(4)
        if ss < 0.0:
            ss, tt, uu, f = _exact_symmetry_image(ss, tt, uu, f, "D")
        tt = _wrapped(tt)
        if uu < 0.0:
            ss, tt, uu, f = _exact_symmetry_image(ss, tt, uu, f, "S1")
        if abs(tt) > 0.5 * np.pi + 1e-9:
            ss, tt, uu, f = _exact_symmetry_image(ss, tt, uu, f, "S3")
            tt = _wrapped(tt)
        jj = int(np.argmin(np.abs(th_q - tt)))
        ii = int(np.argmin(np.abs(s_q - ss)))
        kk = int(np.argmin(np.abs(tau_q - uu)))
        assert abs(th_q[jj] - tt) < 1e-9 and abs(s_q[ii] - ss) < 1e-12 \
            and abs(tau_q[kk] - uu) < 1e-12
        return (ii, jj, kk), f

    # index maps: every full node (s, theta, tau) to a quarter node and sign pattern
    n_s, n_t, n_u = len(s), len(theta), len(tau)
    src = np.zeros((n_s, n_t, n_u, 3), dtype=int)
    sgn = np.zeros((n_s, n_t, n_u, 4))        # multipliers of f_par, f_perp, moment, stick
    for i, s_i in enumerate(s):
        for j, t_j in enumerate(theta):
            for k, u_k in enumerate(tau):
                src[i, j, k], sgn[i, j, k] = reduced(s_i, t_j, u_k)

    # the group average on the quarter: each quarter node x and each of the eight maps h
    # (h(x) a full node, h's own multipliers), reduced back to the quarter
    n_q = (len(s_q), len(th_q), len(tau_q))
    img = np.zeros((8,) + n_q + (3,), dtype=int)
    img_sgn = np.zeros((8,) + n_q + (4,))
    for i, s_i in enumerate(s_q):
        for j, t_j in enumerate(th_q):
            for k, u_k in enumerate(tau_q):
                for h in range(8):
                    ss, tt, uu, f = s_i, t_j, u_k, np.ones(4)
                    for bit, op in ((4, "S3"), (2, "S1"), (1, "D")):
                        if h & bit:
                            ss, tt, uu, f = _exact_symmetry_image(ss, tt, uu, f, op)
                    img[h, i, j, k], back = reduced(ss, _wrapped(tt), uu)
                    # value(h x) = f value(x) and value(h x) = back q[img]
                    img_sgn[h, i, j, k] = f * np.asarray(back)

    def assemble(values):
        q = np.asarray(values, dtype=float).reshape(shape_q + (4,))
        q = np.mean(q[:, :, img[..., 0], img[..., 1], img[..., 2], :] * img_sgn, axis=2)
        full = q[:, :, src[..., 0], src[..., 1], src[..., 2], :]   # (g, nu, s, t, u, 4)
        full *= sgn
        # the periodic seam: theta = -pi and theta = pi are the same node
        full[:, :, :, -1] = full[:, :, :, 0]
        return np.moveaxis(full, -1, 0)

    return points, assemble


#: The exact table's symmetries as maps of its coefficient grid, with the symmetries of
#: :data:`_EXACT_SYMMETRY_SIGNS` whose multipliers they carry: the point reflection T(-v,
#: -phi) = -T(v, phi) as the reader evaluates it (-v at the same s and at theta + pi, -phi at
#: -tau: S1 then S3), the double cover D and the mirror in y S1
_EXACT_COEFFICIENT_SYMMETRIES = (
    (("half_turn", "flip_tau"), ("S1", "S3")),
    (("flip_s", "half_turn"), ("D",)),
    (("flip_theta", "flip_tau"), ("S1",)),
)


def _exact_coefficient_symmetry(axes, knots, coefs):
    """The coefficients made exactly symmetric, bit for bit, under the table's symmetries
    (:data:`_EXACT_COEFFICIENT_SYMMETRIES`) as maps of the coefficient grid: s and tau
    reversed (symmetric knots), theta reversed or turned by half a period (the periodic
    axis's coefficient index + n / 2 modulo its n distinct ones).

    Each map P in turn: ``(c + sign c[P]) / 2``, exact for both signs (a + b = b + a and a - b
    = -(b - a) in floating point) and keeping the earlier maps' symmetry (the maps commute,
    and negation is exact), so the rounding that follows, odd itself, keeps them all.
    Without this the fit's round-off put coefficients that sit on a rounding tie (a
    rebuild's reused node values put many there) on both sides of it: T(-v, -phi) + T(v,
    phi) reached 1.7e-5 of mu N with the forces at 2^-13 (3.6e-8 at 2^-15; 1e-13 with this,
    the evaluation's round-off).
    """
    names = [a.name for a in axes]
    i_s, i_t, i_u = (1 + names.index(n) for n in ("creepage_coordinate", "creepage_angle",
                                                    "spin_coordinate"))
    t = np.asarray(knots[i_t - 1])
    c = np.array(coefs, dtype=float)
    n_c = c.shape[i_t]
    n_per = n_c - 3                    # distinct coefficients of the periodic axis
    half = n_per // 2
    if n_per % 2 or not np.allclose(t[half:half + n_c + 4 - half] - t[:n_c + 4 - half], np.pi,
                                    rtol=0.0, atol=1e-9) \
            or not np.allclose(t, -t[::-1], rtol=0.0, atol=1e-9):
        raise ValueError("creepage_angle: the knots are not invariant under theta -> theta "
                         "+ pi and theta -> -theta")
    maps = {"half_turn": lambda a: np.take(a, (np.arange(n_c) + half) % n_per, axis=i_t),
            "flip_theta": lambda a: np.flip(a, axis=i_t),
            "flip_s": lambda a: np.flip(a, axis=i_s),
            "flip_tau": lambda a: np.flip(a, axis=i_u)}
    for steps, ops in _EXACT_COEFFICIENT_SYMMETRIES:
        image = c
        for step in steps:
            image = maps[step](image)
        sign = np.prod([_EXACT_SYMMETRY_SIGNS[op] for op in ops], axis=0)
        c = (c + sign.reshape((-1,) + (1,) * (c.ndim - 1)) * image) / 2.0
    return c


def exact_full_sliding_limit(points):
    """Table values at s = +-1 (infinite creepage): the force is mu N against the *physical*
    creepage (xi_x, xi_y), the moment and the stick area vanish.

    The spin's rigid slip is negligible beside an infinite creepage, so every element slides
    along (xi_x, xi_y) = w_sat (v_x / C11, v_y / C22) (the spin part of v_y is finite): the
    direction of v turned by Kalker's weights, not v itself (the two agree only when C11 =
    C22 or v is along an axis; at a0/b0 = 0.1 they differ by up to 17 degrees). The earlier
    table set (f_par, f_perp) = (1, 0) there and erred by up to 1.4 % of mu N near full
    sliding. Checked against the solver at large creepage in tests/test_exact_table.py.

    Parameters
    ----------
    points : array_like, shape (n, 5)
        Table points (ln(a0/b0), nu, s, theta, tau) with s = +-1.

    Returns
    -------
    ndarray, shape (n, 4)
        (f_par, f_perp, moment ratio, stick fraction).
    """
    from railcontact.kalker import kalker_coefficients  # noqa: PLC0415

    points = np.asarray(points, dtype=float)
    c = kalker_coefficients(np.exp(points[:, 0]), points[:, 1])
    theta = points[:, 3]
    ux = np.sign(points[:, 2]) * np.cos(theta) / c.c11
    uy = np.sign(points[:, 2]) * np.sin(theta) / c.c22
    norm = np.hypot(ux, uy)
    ux, uy = ux / norm, uy / norm
    zero = np.zeros(len(points))
    # T / (mu N) = -(ux, uy) = -(f_par e + f_perp e_perp)
    return np.column_stack([ux * np.cos(theta) + uy * np.sin(theta),
                            -ux * np.sin(theta) + uy * np.cos(theta), zero, zero])


#: Width R0 of the linear-limit anchoring, in the table's units (R = sqrt(rho^2 + tau^2), both
#: rigid slips over the saturation creepage): the correction (J_Kalker - J_solver) x carries the
#: weight exp(-(R / R0)^2), so it is whole at zero creepage (the slope there is Kalker's), below
#: 0.1 % of mu N everywhere and below 1e-13 of mu N beyond R = 0.55.
EXACT_LINEAR_LIMIT_WIDTH = 0.1
#: rho of the solver's linear-response probes (full stick; relative nonlinearity ~ 1e-4)
_EXACT_LINEAR_PROBE = 1e-4


def _exact_solver_point(kw, key, previous, my=None):
    """(tx, ty, mz, fine solution) at the table's solver setting: 30 x my and 60 x my
    (``my`` default 20), extrapolated once, averaged over the grids moved by
    :data:`EXACT_GRID_SHIFTS`; ``previous`` holds the last solution per (contact, grid) as
    the next start."""
    import warnings  # noqa: PLC0415

    from railcontact.reference.rolling3d import (  # noqa: PLC0415
        RollingConvergenceError, solve_rolling_3d)

    my = int(EXACT_SOLVER["my"] if my is None else my)

    def solve(mx, shift, start=None):
        start = previous.get((key, mx, my, shift), start)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            try:
                r = solve_rolling_3d(**kw, **dict(EXACT_SOLVER, mx=mx, my=my),
                                     initial_guess=start, grid_shift=shift)
            except RollingConvergenceError:
                # one retry from zero, looser and longer; a second failure fails the chunk
                # (finished chunks are kept, the build resumes)
                r = solve_rolling_3d(**kw, **dict(EXACT_SOLVER, mx=mx, my=my, tolerance=1e-3,
                                                  max_iterations=20000), grid_shift=shift)
        previous[(key, mx, my, shift)] = r
        return r

    mx = EXACT_SOLVER["mx"]
    tx = ty = mz = 0.0
    for shift in EXACT_GRID_SHIFTS:
        coarse = solve(mx, shift)
        fine = solve(2 * mx, shift, coarse) if EXACT_RICHARDSON else coarse
        w_f, w_c = (2.0, -1.0) if EXACT_RICHARDSON else (1.0, 0.0)
        tx += (w_f * fine.tx + w_c * coarse.tx) / len(EXACT_GRID_SHIFTS)
        ty += (w_f * fine.ty + w_c * coarse.ty) / len(EXACT_GRID_SHIFTS)
        mz += (w_f * fine.mz + w_c * coarse.mz) / len(EXACT_GRID_SHIFTS)
    return tx, ty, mz, fine


_LINEAR_RESPONSE_CACHE = {}


def exact_solver_linear_response(log_aspect_ratio, poisson_ratio):
    """The solver's linear response at zero creepage on the reference contact, at the table's
    setting, and Kalker's.

    Probes ``xi_x``, ``xi_y`` and ``phi`` one at a time at ``rho = 1e-4`` saturation creepages
    (full stick) and divides by the probe: the 3 x 3 matrix ``d(Tx, Ty, Mz) / d(xi_x, xi_y,
    phi)``. Kalker's matrix has the force rows of the package's linear theory
    (``creep_force_3d(..., method="linear")``, Eqs. (2.61)-(2.62), J.J. Kalker, 1990, Table
    E.3) at the same probes, Mz(xi_y) = -Ty(phi) by Betti's reciprocity, and the solver's
    Mz(phi) (C33 is not in the shared coefficient table).

    Returns
    -------
    tuple of ndarray, shape (3, 3)
        ``(solver, kalker)`` in [N, N m] per unit creepage [-] and spin [1/m].
    """
    from railcontact.creep3d import REFERENCE_CONTACT, creep_force_3d  # noqa: PLC0415
    from railcontact.exact_table import (  # noqa: PLC0415
        creepage_coordinate, exact_table_inverse)

    key = (float(log_aspect_ratio), float(poisson_ratio))
    if key in _LINEAR_RESPONSE_CACHE:
        return _LINEAR_RESPONSE_CACHE[key]
    s0 = float(creepage_coordinate(_EXACT_LINEAR_PROBE))
    base = exact_table_inverse(*np.array([[key[0], key[1], s0, 0.0, 0.0],
                                          [key[0], key[1], s0, 0.5 * np.pi, 0.0],
                                          [key[0], key[1], 0.0, 0.0, _EXACT_LINEAR_PROBE]]).T,
                               contact=REFERENCE_CONTACT)
    probes = (float(base["creepage_longitudinal"][0]), float(base["creepage_lateral"][1]),
              float(base["spin"][2]))
    solver, kalker = np.zeros((3, 3)), np.zeros((3, 3))
    previous = {}
    names = ("creepage_longitudinal", "creepage_lateral", "spin")
    for j, size in enumerate(probes):
        kw = {k: float(v[0]) for k, v in base.items()}
        kw.update(dict.fromkeys(names, 0.0))
        kw[names[j]] = size
        tx, ty, mz, _ = _exact_solver_point(kw, key, previous)
        solver[:, j] = np.array([tx, ty, mz]) / size
        linear = creep_force_3d(**kw, method="linear")
        kalker[:2, j] = np.array([float(linear.tx), float(linear.ty)]) / size
    kalker[2, 1] = -kalker[1, 2]             # Betti: Mz(xi_y) = -Ty(phi)
    kalker[2, 2] = solver[2, 2]
    if not (np.sign(solver[0, 0]) == np.sign(solver[1, 1]) == np.sign(solver[1, 2]) == -1.0):
        raise RuntimeError(f"the solver's linear response has unexpected signs: {solver}")
    _LINEAR_RESPONSE_CACHE[key] = (solver, kalker)
    return solver, kalker


def exact_linear_limit_correction(points):
    """Anchoring of the table to the exact theory's linear limit, Kalker's creep coefficients:
    ``(J_Kalker - J_solver) x exp(-(R / R0)^2)`` in table units, added to the solver's values.

    The exact theory's slope at zero creepage *is* Kalker's linear theory (his coefficients are
    its solution, Kalker 1990, Table E.3). The discretised solver approaches it only slowly:
    the stick traction has an inverse-square-root edge singularity, so C11 at a0/b0 = 1, nu = 0
    reads 3.3715 at the table's setting (30 x 20 -> 60 x 20), 3.3845, 3.3926, 3.3946 on grids
    of 60 x 40, 120 x 80, 200 x 100 (error of order about h^0.7; extrapolated 3.406 against
    Kalker's 3.40). The correction replaces the solver's linear part by Kalker's near zero and
    fades with R = sqrt(rho^2 + tau^2) (``R0`` = :data:`EXACT_LINEAR_LIMIT_WIDTH`): it is
    linear times an even Gaussian, so it keeps every symmetry of the table, and it is at most
    0.43 R0 |J_K - J_s| / (mu N) (about 0.1 % of mu N) in the middle of the fade.

    Parameters
    ----------
    points : array_like, shape (n, 5)
        Table points (ln(a0/b0), nu, s, theta, tau), any signs, ``|s| < 1``.

    Returns
    -------
    ndarray, shape (n, 3)
        Corrections of (f_par, f_perp, spin moment ratio). [-]
    """
    from railcontact.creep3d import REFERENCE_CONTACT  # noqa: PLC0415
    from railcontact.exact_table import creepage_magnitude, exact_table_inverse  # noqa: PLC0415

    points = np.asarray(points, dtype=float)
    out = np.zeros((len(points), 3))
    rho = creepage_magnitude(points[:, 2], points[:, 4])
    weight = np.exp(-(rho**2 + points[:, 4] ** 2) / EXACT_LINEAR_LIMIT_WIDTH**2)
    near = np.nonzero(weight > 1e-16)[0]
    if near.size == 0:
        return out
    phys = exact_table_inverse(*points[near, :5].T, contact=REFERENCE_CONTACT)
    x = np.column_stack([phys["creepage_longitudinal"], phys["creepage_lateral"], phys["spin"]])
    d = np.empty((near.size, 3))
    for i in range(near.size):
        solver, kalker = exact_solver_linear_response(points[near[i], 0], points[near[i], 1])
        d[i] = (kalker - solver) @ x[i] * weight[near[i]]
    mu_n = REFERENCE_CONTACT["friction_coefficient"] * REFERENCE_CONTACT["normal_load"]
    c, s = np.cos(points[near, 3]), np.sin(points[near, 3])
    fx, fy = -d[:, 0] / mu_n, -d[:, 1] / mu_n
    out[near, 0] = fx * c + fy * s
    out[near, 1] = -fx * s + fy * c
    out[near, 2] = d[:, 2] / (mu_n * np.sqrt(phys["a0"] * phys["b0"]))
    return out


def exact_creep_function(points, lateral_elements=None):
    """Exact-theory values at table points (n, 5) in the quarter s >= 0, |theta| <= pi/2,
    tau >= 0: (f_par, f_perp, spin moment ratio, stick area fraction); see
    :mod:`railcontact.exact_table`.

    Calls :func:`railcontact.reference.rolling3d.solve_rolling_3d` on the reference contact
    (:data:`railcontact.creep3d.REFERENCE_CONTACT`) at 30 x my and 60 x my elements (my =
    20, or 36 where a0/b0 < 0.87 and |tau| > 2.75: :func:`exact_solver_lateral_elements`),
    extrapolates once (Richardson, first order in the rolling-direction element size) and
    averages the grids moved by :data:`EXACT_GRID_SHIFTS` (what ``creep_solution_3d(...,
    method="exact")`` does by default, but for my); each grid starts from the previous point's
    solution on it when the contact is the same (only the number of sweeps changes). Near zero
    creepage and spin the forces and moment are anchored to Kalker's linear theory
    (:func:`exact_linear_limit_correction`). The stick area fraction is the last fine grid's
    element count. At s = 1 (infinite creepage) the values are the full-sliding limit,
    :func:`exact_full_sliding_limit` (no solver). ``lateral_elements`` (optional) sets my at
    every point instead (a reference on finer grids, ``exact_table_accuracy --converged``).
    """
    from railcontact.creep3d import REFERENCE_CONTACT  # noqa: PLC0415
    from railcontact.exact_table import exact_table_inverse  # noqa: PLC0415

    points = np.asarray(points, dtype=float)
    out = np.empty((len(points), 4))
    finite = ~_exact_analytic_points(points)
    out[~finite] = exact_full_sliding_limit(points[~finite])
    phys = exact_table_inverse(*np.where(finite[:, None], points[:, :5], 0.0).T,
                               contact=REFERENCE_CONTACT)
    # the discrete problem is exactly similar in (mu, creepages, spin) -> lambda (mu,
    # creepages, spin) with tractions scaled by lambda: where large spin makes the reference
    # contact's creepages exceed the solver's |creepage| <= 1, lower mu for that point
    big = np.maximum(np.abs(phys["creepage_longitudinal"]), np.abs(phys["creepage_lateral"]))
    lam = 0.5 / np.maximum(big, 0.5)
    for name in ("creepage_longitudinal", "creepage_lateral", "spin", "friction_coefficient"):
        phys[name] = phys[name] * lam
    previous = {}
    lateral = (exact_solver_lateral_elements(points[:, 0], points[:, 4])
               if lateral_elements is None else np.full(len(points), int(lateral_elements)))

    for i in np.nonzero(finite)[0]:
        kw = {k: float(v[i]) for k, v in phys.items()}
        key = (points[i, 0], points[i, 1])               # same contact: same grid, pressure
        tx, ty, mz, fine = _exact_solver_point(kw, key, previous,
                                               my=lateral[i])
        mu_n = kw["friction_coefficient"] * kw["normal_load"]
        n_contact = np.count_nonzero(fine.pn > 0.0)
        c, s = np.cos(points[i, 3]), np.sin(points[i, 3])
        fx, fy = -tx / mu_n, -ty / mu_n          # T/(mu N) = -(f_par e + f_perp e_perp)
        out[i] = (fx * c + fy * s, -fx * s + fy * c,
                  mz / (mu_n * np.sqrt(kw["a0"] * kw["b0"])),
                  np.count_nonzero(fine.adhesion) / max(n_contact, 1))
    out[finite, :3] += exact_linear_limit_correction(points[finite])
    return out


def _exact_provenance():
    import hashlib  # noqa: PLC0415

    import railcontact.reference.rolling3d as mod  # noqa: PLC0415

    with open(mod.__file__, "rb") as fh:
        digest = hashlib.sha1(fh.read()).hexdigest()
    return {"solver_source_sha1": f"railcontact/reference/rolling3d.py sha1 {digest} (at the "
                                  "end of the build)"}


def _exact_analytic_points(points):
    """The points answered without the solver: s = +-1 (:func:`exact_full_sliding_limit`)."""
    return np.abs(np.asarray(points, dtype=float)[:, 2]) >= 1.0


def _exact_check(axes, n, rng):
    """Off-node points spread over the computed quarter (the rest follows by symmetry):
    uniform in ln g, nu, theta; r / sqrt(1 + r^2) uniform up to r = 5 for three quarters of
    the points (r = rho / sqrt(1 + tau^2)) and
    rho log-uniform in 5-100 for the rest (far past saturation, where the force turns to the
    physical creepage); tau uniform in the node index."""
    from railcontact.exact_table import creepage_coordinate  # noqa: PLC0415

    g, nu, s, theta, tau = (a.nodes for a in axes)
    tau_q = tau[tau >= 0.0]
    far = rng.random(n) < 0.25
    # (uniform in u = r / sqrt(1 + r^2), the creepage coordinate of the tables before
    # 2026-11-27: the same physical points as their checks)
    r_far = np.exp(rng.uniform(np.log(5.0), np.log(100.0), n))
    u = rng.uniform(0.0, 5.0 / np.sqrt(26.0), n)
    s_pts = np.where(far, creepage_coordinate(r_far),
                     creepage_coordinate(_algebraic_creepage_magnitude(u)))
    pts = np.column_stack([
        rng.uniform(g[0], g[-1], n), rng.uniform(nu[0], nu[-1], n),
        s_pts,                                   # |v| / sqrt(1 + tau^2) <= 100
        rng.uniform(-0.5 * np.pi, 0.5 * np.pi, n),
        np.interp(rng.uniform(0.0, len(tau_q) - 1.0, n), np.arange(len(tau_q)), tau_q)])
    return pts[np.lexsort((pts[:, 1], pts[:, 0]))]   # contact by contact (solver caches)


def _algebraic_creepage_magnitude(u):
    """r = u / sqrt(1 - u^2): the creepage r = rho / w of the coordinate u = r / sqrt(1 + r^2)
    the exact tables used before 2026-11-27 (infinite at |u| = 1)."""
    u = np.asarray(u, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(np.abs(u) >= 1.0, np.sign(u) * np.inf, u / np.sqrt(1.0 - u * u))


def _exact_reuse_coordinates(attrs, name, nodes):
    """An earlier file's node coordinates in today's: files without ``creepage_coordinate_form
    = "arctan"`` (before 2026-11-27) measured the creepage as s = r / sqrt(1 + r^2), r = rho /
    w; the same nodes r are s = (2 / pi) atan(r) now (no new solves for the change)."""
    from railcontact.exact_table import creepage_coordinate  # noqa: PLC0415

    nodes = np.asarray(nodes, dtype=float)
    if not name.startswith("creepage_coordinate") or attrs.get(
            "creepage_coordinate_form") == CREEPAGE_COORDINATE_FORM:
        return nodes
    return creepage_coordinate(_algebraic_creepage_magnitude(nodes))


#: The exact table's method before 2026-11-27 (20 lateral elements everywhere).
_EXACT_METHOD_MY20 = (
    "railcontact.reference.rolling3d.solve_rolling_3d at mx = 30 and 60, my = 20, "
    "scale 1.08, tolerance 1e-4, extrapolated 2 F(60 x 20) - F(30 x 20) on the grids "
    "moved -1/4 and +1/4 of an element and averaged (creep_force_3d(method='exact')'s "
    "default), on a0 b0 = 36 mm^2, N = 100 kN, E = 210 GPa, mu = 0.3; forces and "
    "moment anchored near zero creepage and spin to Kalker's linear theory "
    "(tablegen.specs.exact_linear_limit_correction, width R0 = 0.1)")


def _exact_method(aspect_max, spin_min, very_narrow_max=None):
    """The exact spec's method string with the narrow-contact rule (a0/b0 < aspect_max,
    |tau| > spin_min: 36 lateral elements; a0/b0 < very_narrow_max too: 48; None: the
    strings of the rules before 2026-11-28, which had no 48 tier)."""
    rule = (f"36 where a0/b0 < {aspect_max:g} and |tau| > {spin_min:g}" if very_narrow_max is None
            else f"48 where a0/b0 < {very_narrow_max:g} and 36 where a0/b0 < {aspect_max:g}, "
                 f"both where |tau| > {spin_min:g}")
    return (
        f"railcontact.reference.rolling3d.solve_rolling_3d at mx = 30 and 60, my = 20 ({rule}: "
        "tablegen.specs.exact_solver_lateral_elements), scale 1.08, tolerance 1e-4, "
        "extrapolated 2 F(60 x my) - F(30 x my) on the grids moved -1/4 and +1/4 of an element "
        "and averaged (creep_force_3d(method='exact')'s default but for my), on a0 b0 = 36 "
        "mm^2, N = 100 kN, E = 210 GPa, mu = 0.3; forces and moment anchored near zero "
        "creepage and spin to Kalker's linear theory (tablegen.specs."
        "exact_linear_limit_correction, width R0 = 0.1)")


_EXACT_METHOD = _exact_method(EXACT_NARROW_ASPECT_MAX, EXACT_NARROW_SPIN_MIN,
                              EXACT_VERY_NARROW_ASPECT_MAX)
#: Earlier methods of the exact table and their narrow-contact rule ((a0/b0 max, |tau| min)
#: of the 36 lateral elements, no 48 tier; None: 20 everywhere), for --reuse-nodes across a
#: change.
_EXACT_EARLIER_METHODS = {_EXACT_METHOD_MY20: None,
                          _exact_method(0.45, 2.75): (0.45, 2.75),   # 2026-11-27, 70ae614
                          _exact_method(0.75, 2.75): (0.75, 2.75),   # 2026-11-27, 4b9f815
                          _exact_method(0.87, 2.75): (0.87, 2.75)}   # 2026-11-27 - 11-28


def _exact_reusable_points(attrs, points):
    """A file of an earlier method (:data:`_EXACT_EARLIER_METHODS`): its values stand where
    its lateral elements equal today's :func:`exact_solver_lateral_elements`."""
    if attrs.get("method") not in _EXACT_EARLIER_METHODS:
        return None
    rule = _EXACT_EARLIER_METHODS[attrs["method"]]
    points = np.asarray(points, dtype=float)
    now = exact_solver_lateral_elements(points[:, 0], points[:, 4])
    then = (np.full(len(points), EXACT_SOLVER["my"]) if rule is None
            else exact_solver_lateral_elements(points[:, 0], points[:, 4], *rule,
                                               very_narrow_max=0.0))
    return now == then


register(TableSpec(
    name="creep_exact",
    title="Creep forces of Kalker's exact theory (discretised, Richardson-extrapolated) with "
          "spin, every a0/b0 in 0.1-10 and Poisson's ratio in 0-0.5",
    axes=_exact_axes,
    function=exact_creep_function,
    reduce=_exact_reduce,
    node_values_float32=True,      # 4,266,675 coefficients x 4 variables: with the node values
    coefficients_float32=True,     # in float32 too, and to 5 significant digits (stick area: 3)
    significant_digits=5,          # the file stays under 20 MB. (4 digits made the spline 3e-8
    # off zero near v = 0: combinations of coefficients that cancel there keep their rounding,
    # and the slope taken at |v| = 1e-6 of the saturation creepage was 1 % off)
    node_values_stored=False,      # since 2026-11-27 (format 3): the node values took 3.5 of
    # the 19.7 MB; without them, and with the stick area to 2 digits (3.1 -> 2.2 MB), the
    # finer grid fits (the spline at the nodes gives them back, to the coefficients' rounding)
    # Since 2026-11-27 (fifth session) the forces and moment to multiples of 2^-15 (2^-13
    # since the sixth) and the stick area to 2^-7 (2^-6 since the sixth), but next to zero
    # creepage (|s| < 0.005: the nodes rho / w = 0 to 0.006), where they keep their digits:
    # on the 11-node grid 16.3 -> 12.7 MB for the three (the perpendicular force's many
    # small coefficients cost 7.3 MB at 5 relative digits), the stick area 3.1 -> 1.4 MB on
    # 12 a0/b0 nodes
    relative_precision_region=_near_zero_creepage,
    coefficient_symmetry=_exact_coefficient_symmetry,
    relative_precision_comment=(
        f"where |creepage_coordinate| < {EXACT_RELATIVE_PRECISION_S_MAX:g} (the nodes rho / w "
        "= 0 to 0.006), which keep significant_digits: there the force is the small "
        "difference of coefficients and its slope is Kalker's"),
    variables=[
        Variable("force_ratio_parallel", "1", "force on the wheel over the Coulomb limit, "
                 "component opposing the combined creepage v: f_par = -T.e/(mu N), e = "
                 "(cos theta, sin theta)", error_target=5e-3,
                 absolute_precision=EXACT_ABSOLUTE_PRECISION,
                 comment="T/(mu N) = -(f_par e + f_perp e_perp); see railcontact.exact_table"),
        Variable("force_ratio_perpendicular", "1", "force on the wheel over the Coulomb limit, "
                 "component along -e_perp, e_perp = (-sin theta, cos theta)",
                 error_target=5e-3, absolute_precision=EXACT_ABSOLUTE_PRECISION),
        Variable("spin_moment_ratio", "1", "spin moment on the wheel about the ellipse "
                 "centre over mu N sqrt(a0 b0)", error_target=5e-3,
                 absolute_precision=EXACT_ABSOLUTE_PRECISION),
        Variable("stick_area_fraction", "1", "adhesion area over contact area (element counts of "
                 "the 60 x my solution on the grid moved +1/4 of an element)",
                 error_target=5e-2, significant_digits=2,
                 absolute_precision=EXACT_STICK_AREA_ABSOLUTE_PRECISION,
                 comment="piecewise constant in the solver (element count), so only "
                         "approximately smooth"),
    ],
    references=("J.J. Kalker, Three-dimensional elastic bodies in rolling contact, Kluwer, "
                "1990 (exact theory, steady rolling, creep coefficients); E.A.H. Vollebregt, "
                "J. Optim. Theory Appl. 157 (2013) (block Gauss-Seidel); "
                f"{THESIS}, Sec. 2.5.3-2.5.4 (discretisation, tables)"),
    method=_EXACT_METHOD,
    check_points=_exact_check,
    analytic_points=_exact_analytic_points,
    reuse_coordinates=_exact_reuse_coordinates,
    reusable_points=_exact_reusable_points,
    n_check={"coarse": 100, "default": 1000, "fine": 4000},
    chunk_size=24,
    requires=("railcontact.reference.rolling3d",),
    build_attributes=_exact_provenance,
    attributes={
        "solver_grid": "30 x my and 60 x my elements over [-1.08 a0, 1.08 a0] x [-1.08 b0, "
                       f"1.08 b0], my = 20 (48 where a0/b0 < {EXACT_VERY_NARROW_ASPECT_MAX:g} and 36 "
                       f"where a0/b0 < {EXACT_NARROW_ASPECT_MAX:g}, both where |tau| > "
                       f"{EXACT_NARROW_SPIN_MIN:g}), one "
                       "Richardson step, on the grids moved -1/4 and +1/4 of an element, "
                       "averaged",
        "spin_coordinate_max": EXACT_TAU_MAX,
        "linear_limit": (
            "slope at zero creepage and spin anchored to Kalker's linear theory (C11, C22, "
            "C23; the solver's own Mz(phi)): (J_Kalker - J_solver) x exp(-(R / 0.1)^2) added "
            "to the solver's forces and moment, R = sqrt(rho^2 + tau^2); at most about 0.1 % "
            "of mu N; see tablegen.specs.exact_linear_limit_correction"),
        "creepage_coordinate_spin_weight": 1.0,
        # s = (2 / pi) atan(rho / w); the tables before 2026-11-27: rho / sqrt(rho^2 + w^2)
        "creepage_coordinate_form": CREEPAGE_COORDINATE_FORM,
        "normalisation": (
            "forces over mu N depend only on a0/b0, nu and the Kalker-weighted creepages "
            "(C11 xi_x, C22 xi_y, sqrt(a0 b0) C23 phi)/w_sat; the solver computes the quarter "
            "v_x >= 0, phi >= 0 and the file holds every sign (filled by symmetry) so that the "
            "spline is C2 across xi_x = 0 and phi = 0; see railcontact.exact_table"),
        "symmetry": (
            "(f_par, f_perp, moment, stick) at (s, theta, tau) equals: (-f_par, -f_perp, "
            "moment, stick) at (-s, theta + pi, tau) (one point, two coordinates); (f_par, "
            "-f_perp, -moment, stick) at (s, -theta, -tau) (mirror in y); (f_par, -f_perp, "
            "moment, stick) at (s, pi - theta, tau) (reversed x at fixed spin); the node "
            "values are stored for s >= 0, |theta| <= pi/2, tau >= 0"),
    },
))


# --------------------------------------------------------------------------------------------
# Corrugation and wear: linearised response coefficients (Nielsen Ch. 4), railcontact.wear
# --------------------------------------------------------------------------------------------

_CW_COUNTS = {"coarse": (8, 31, 16), "default": (15, 61, 41), "fine": (30, 121, 81)}
_CW_ZERO = ("patch_shift_real", "half_width_imag", "tau_imag")  # identically 0: not stored
_CW_FIELDS = ("patch_shift", "half_width", "stick_half_width", "tangential_force", "tau",
              "tau_star", "wear")
_CW_NAMES = {
    "patch_shift": "patch shift Delta",
    "half_width": "contact half-width a",
    "stick_half_width": "stick-zone half-width a*",
    "tangential_force": "tangential force T",
    "tau": "passage time tau",
    "tau_star": "passage time through the stick zone tau*",
    "wear": "wear w = (W1 + i W2) a0 / (K mu^2 N), model material_point",
}


def _cw_axes(resolution):
    n_log, n_lin, n_r = _CW_COUNTS[resolution]
    s = np.linspace(0.0, 1.0, n_r)
    ratio = np.r_[np.geomspace(0.01, 0.1, n_log)[:-1], np.linspace(0.1, 1.0, n_lin)]
    return [
        Axis("a0_over_wavelength", ratio, "1",
             "a0/L, contact half-length over corrugation wavelength",
             comment="a0/L from 0.01 to 1 (L/a0 from 1 to 100): log-spaced below 0.1, "
                     "uniform above (the Bessel functions of k a0 = 2 pi a0/L oscillate)"),
        Axis("stick_ratio", 0.5 - 0.5 * np.cos(np.pi * s), "1",
             "r_a0 = a0*/a0, stick-zone half-width over contact half-width (1 = full stick)",
             comment="nodes crowd towards 0 and 1 (0.5 - 0.5 cos(pi s), s uniform)"),
    ]


def corrugation_wear_function(points):
    """Real and imaginary parts of :func:`railcontact.wear.linear_response` at (a0/L, r_a0)."""
    from railcontact.wear import linear_response  # noqa: PLC0415

    ratio = points[:, 0]
    r = np.clip(points[:, 1], 0.0, 1.0)
    res = linear_response(ratio, r)
    cols = []
    for f in _CW_FIELDS:
        v = np.asarray(getattr(res, f), dtype=complex)
        for part, val in (("real", v.real), ("imag", v.imag)):
            if f"{f}_{part}" not in _CW_ZERO:
                cols.append(val)
    return np.stack(cols, axis=1)


_CW_VARIABLES = []
for _f in _CW_FIELDS:
    for _part, _label in (("real", "real part"), ("imag", "imaginary part")):
        if f"{_f}_{_part}" in _CW_ZERO:
            continue
        _CW_VARIABLES.append(Variable(
            f"{_f}_{_part}", "1", f"{_label} of the normalised first-harmonic response of the "
            f"{_CW_NAMES[_f]} (railcontact.wear.linear_response)", error_target=1e-4))

register(TableSpec(
    name="corrugation_response",
    title="Linearised corrugation and wear response of the 2-D rolling contact "
          "(Nielsen 1998, Ch. 4)",
    axes=_cw_axes,
    function=corrugation_wear_function,
    variables=_CW_VARIABLES,
    references=(f"{THESIS}, Sec. 4.1-4.3, Eqs. (4.1)-(4.98) with the errata recorded in "
                "railcontact.corrugation and railcontact.wear"),
    method="railcontact.wear.linear_response(a0/L, r_a0) (wear_model='material_point')",
    n_check={"coarse": 300, "default": 2000, "fine": 5000},
    chunk_size=256,
    requires=("railcontact.wear",),
    attributes={"normalisation": (
        "coefficients of one harmonic per unit relative corrugation amplitude, normalised as "
        "in railcontact.wear.linear_response; complex values stored as _real/_imag pairs "
        "(patch_shift_real, half_width_imag and tau_imag are identically 0 and not stored); the "
        "growth factor per passage is 1 - 2 wear_number * wear_real "
        "(railcontact.evolution.growth_factor)")},
))


# --------------------------------------------------------------------------------------------
# Non-steady (oscillating-creepage) transfer function, Carter model (Nielsen Ch. 7)
# --------------------------------------------------------------------------------------------

_NS_COUNTS = {"coarse": (8, 13, 6, 9), "default": (19, 31, 13, 21), "fine": (29, 49, 21, 33)}
NONSTEADY_STICK_MIN = 0.02


def _nonsteady_axes(resolution):
    n_log, n_lin, n_rlog, n_rlin = _NS_COUNTS[resolution]
    ratio = np.r_[0.0, np.geomspace(0.001, 0.1, n_log)[:-1], np.linspace(0.1, 1.0, n_lin)]
    stick = np.r_[np.geomspace(NONSTEADY_STICK_MIN, 0.2, n_rlog)[:-1],
                  np.linspace(0.2, 1.0, n_rlin)]
    return [
        Axis("a0_over_wavelength", ratio, "1",
             "a0/L, contact half-width over the wavelength of the creepage oscillation",
             comment="a0/L from 0 (quasi-static: H = 1 exactly) to 1 (L/a0 = 1); nodes 0, then "
                     "log-spaced from 0.001 to 0.1, uniform above (H is analytic in k a0, "
                     "varying on the scale 1/(k a0* Lambda) at low frequency)"),
        Axis("stick_ratio", stick, "1",
             "r_a0 = a0*/a0, steady stick-zone half-width over contact half-width "
             "(1 = full stick)",
             comment=f"r_a0 from {NONSTEADY_STICK_MIN} to 1: log-spaced below 0.2 (the "
                     "k a0* ln(4 b/a0*) term has a logarithmic derivative singularity at "
                     "r_a0 = 0, so the axis stops short of it), uniform above; below the "
                     "first node the reader raises"),
    ]


def nonsteady_transfer_function(points):
    """|H| and angle(H) of :func:`railcontact.nonsteady.nonsteady_amplitude_phase_normalised`
    (model="carter", variant="derived", nu = 0.28, b/a0 = 20) at (a0/L, r_a0)."""
    from railcontact.nonsteady import nonsteady_amplitude_phase_normalised  # noqa: PLC0415

    amp, phase = nonsteady_amplitude_phase_normalised(
        points[:, 0], points[:, 1], **NONSTEADY_SETTINGS)
    return np.stack([np.asarray(amp, dtype=float), np.asarray(phase, dtype=float)], axis=1)


NONSTEADY_SETTINGS = dict(poisson_ratio=0.28, pseudo_width_ratio=20.0, model="carter",
                          variant="derived")

register(TableSpec(
    name="nonsteady_transfer",
    title="Amplitude ratio and phase of the non-steady creep force for an oscillating "
          "creepage, Carter model (Nielsen 1998, Ch. 7)",
    axes=_nonsteady_axes,
    function=nonsteady_transfer_function,
    variables=[
        Variable("amplitude_ratio", "1",
                 "|T_hat/xi_hat| over Carter's quasi-static slope pi E a0* / (4 (1 - nu^2)), "
                 "Eq. (7.53)", error_target=1e-4,
                 comment="1 at a0/L = 0; decays like 1/(k a0* Lambda) at high frequency"),
        Variable("phase", "rad",
                 "phase of the force relative to the creepage, phi_T - phi_xi, Eq. (7.54) "
                 "(negative: the force lags)", error_target=1e-4,
                 comment="stays in (-pi/2 - 0.05, 0] on the grid: no 2 pi wrap"),
    ],
    references=(f"{THESIS}, Ch. 7, Eqs. (7.16)-(7.20), (7.53)-(7.54), with the errata "
                "recorded in railcontact.nonsteady; F.W. Carter, Proc. R. Soc. Lond. A 112 "
                "(1926) 151-157 (steady traction)"),
    method=("railcontact.nonsteady.nonsteady_amplitude_phase_normalised(a0/L, r_a0, "
            "poisson_ratio=0.28, pseudo_width_ratio=20, model='carter', variant='derived')"),
    n_check={"coarse": 1000, "default": 4000, "fine": 10000},
    chunk_size=1024,
    requires=("railcontact.nonsteady",),
    attributes={
        "poisson_ratio": 0.28,
        "pseudo_width_ratio": 20.0,
        "model": "carter",
        "normalisation": (
            "H = (T_hat/xi_hat) / (pi E a0* / (4 (1 - nu^2))) of the 2-D linearised "
            "non-steady Carter contact (magnitude-frame force; the force on the wheel is -T); "
            "amplitude_ratio = |H|, phase = angle(H). Valid while k^2 R |U| << 1 (see "
            "railcontact.nonsteady). The table holds nu = 0.28 and b/a0 = 20 fixed; other "
            "values need the direct function"),
    },
))


# --------------------------------------------------------------------------------------------
# Velocity-dependent friction: creep curves of the smooth law (5.16) (Nielsen Sec. 5.3)
# --------------------------------------------------------------------------------------------

VELOCITY_FRICTION_SOLVER = dict(degree=128, tol=1e-10)
VELOCITY_FRICTION_RATIO_RANGE = (0.2, 1.8)
VELOCITY_FRICTION_KAPPA_MAX = 6.0
VELOCITY_FRICTION_SLIDING_NODES = (1.05, 1.15, 1.3, 1.5, 1.75, 2.0, 2.5, 3.0, 3.5, 4.0, 4.5, 5.0,
                                   5.5, 6.0)

_VF_COUNTS = {"coarse": (5, 7, 8), "default": (13, 17, 16), "fine": (17, 25, 32)}


def _velocity_friction_axes(resolution):
    n_m, n_k, n_c = _VF_COUNTS[resolution]
    u = np.linspace(0.0, 1.0, n_c + 1)
    z = np.r_[1.0 - (0.5 * (1.0 + np.cos(np.pi * u))) ** 2, VELOCITY_FRICTION_SLIDING_NODES]
    s = np.linspace(0.0, 1.0, n_k)
    c = 6.0                                   # nodes uniform in log(1 + 6 kappa xi_c0)
    kappa = ((1.0 + c * VELOCITY_FRICTION_KAPPA_MAX) ** s - 1.0) / c
    return [
        Axis("friction_ratio", np.linspace(*VELOCITY_FRICTION_RATIO_RANGE, n_m), "1",
             "m = mu_k/mu_0, kinetic over static friction coefficient of the law (5.16)",
             comment="m from 0.2 (falling law) to 1.8 (rising law); m = 1 (Carter) is a node"),
        Axis("kappa_normalised", kappa, "1",
             "kappa xi_c0: decay rate of the law (5.16) in slip velocity over rolling speed, "
             "times Carter's critical creepage xi_c0 = mu_0 a0/R",
             comment="kappa xi_c0 from 0 (Carter) to 6, nodes uniform in log(1 + 6 kappa "
                     "xi_c0) (the sliding branch ~ 1/(1 + kappa |xi|), |xi|/xi_c0 up to 5, "
                     "varies fastest in kappa at small kappa); steeper laws (kappa xi_c0 >> 6) put the peak of the curve at a "
                     "few percent of xi_c0, which this grid does not resolve, and need many "
                     "more polynomial terms (the iteration fails for kappa xi_c0 >> degree)"),
        Axis("normalised_creepage", z, "1",
             "z = |xi|/xi_sat(m, kappa), creepage magnitude over the saturation creepage (the "
             "creepage at which the stick zone vanishes; z = 1 is the onset of full sliding; "
             "xi_sat/xi_c0 is the variable saturation_creepage_ratio; the table is odd in xi: "
             "T(-xi) = -T(xi))",
             double_knots=(1.0,),
             comment="nodes z = 1 - ((1 + cos(pi u))/2)^2 (u uniform) on [0, 1] crowd towards "
                     "the saturation z = 1, where the curve has a jump of its second "
                     "derivative (double knot: the spline is C1 there, C2 elsewhere, and does "
                     "not ring past the Coulomb limit); z > 1 is the sliding branch up to z = 6 "
                     "(|xi|/xi_c0 >= 3.2 everywhere in the box, xi_sat/xi_c0 >= 0.538); beyond "
                     "the last node the reader raises"),
    ]


def velocity_friction_function(points):
    """|T|/(mu_0 N), xi_sat/xi_c0 and the stick ratio a*/a0 at (m, kappa xi_c0, z = |xi|/xi_sat)
    for the law (5.16).

    :func:`railcontact.friction.velocity_friction_saturation_curve` (the Sec. 5.3 solver behind
    :func:`railcontact.friction.velocity_friction_creep_force_normalised`, degree 128,
    tol 1e-10; one solver per (m, kappa), reused over z): xi_sat is the creepage of the solution
    at stick ratio r = 0; below it the partial-slip solution at creepage z xi_sat (root search
    on r), above it the full-sliding solution. m = 1 or kappa = 0 is Carter (xi_sat = xi_c0,
    force 1 - (1 - z)^2, stick ratio 1 - z, then 1 and 0).
    """
    from railcontact.friction import velocity_friction_saturation_curve  # noqa: PLC0415

    pts = np.asarray(points, dtype=float)
    res = velocity_friction_saturation_curve(pts[:, 2], pts[:, 0], pts[:, 1],
                                             **VELOCITY_FRICTION_SOLVER)
    return np.stack([np.atleast_1d(res.force_ratio), np.atleast_1d(res.saturation_creepage_ratio),
                     np.atleast_1d(res.stick_ratio)], axis=1)


def _velocity_friction_check(axes, n, rng):
    lo = np.array([a.nodes[0] for a in axes])
    hi = np.array([a.nodes[-1] for a in axes])
    pts = lo + (hi - lo) * rng.random((n, len(axes)))
    near = rng.random(n) < 0.6          # most points on the curved part z <= 1.5
    pts[near, 2] = rng.uniform(0.0, 1.5, near.sum())
    return pts[np.lexsort((pts[:, 1], pts[:, 0]))]


register(TableSpec(
    name="velocity_friction",
    title="Creep curves of the 2-D rolling contact with slip-velocity-dependent friction "
          "(Nielsen 1998, Sec. 5.3, law (5.16))",
    axes=_velocity_friction_axes,
    function=velocity_friction_function,
    variables=[
        Variable("force_ratio", "1",
                 "magnitude of the tangential force over the static Coulomb limit, "
                 "|T|/(mu_0 N)", error_target=1e-3,
                 comment="T = -force_ratio sign(xi) mu_0 N (on the wheel, opposing the "
                         "creepage); 0 <= force_ratio <= max(1, m). The curve's kink at the "
                         "onset of full sliding (jump of the second derivative) lies on the "
                         "grid line z = 1, which has a double knot: the spline is C1 there, C2 "
                         "elsewhere, and does not overshoot the Coulomb limit. The direct "
                         "solver itself is accurate to about 1e-3 (railcontact.friction, "
                         "degree 128)"),
        Variable("saturation_creepage_ratio", "1",
                 "xi_sat/xi_c0, saturation creepage (stick zone vanishes) over Carter's "
                 "critical creepage xi_c0 = mu_0 a0/R, a function of (m, kappa xi_c0) only",
                 error_target=1e-4,
                 comment="constant along normalised_creepage (stored on the full grid so that "
                         "the same reader evaluates it; evaluate at any z, e.g. 0): converts "
                         "|xi|/xi_c0 to the table coordinate z = (|xi|/xi_c0) / "
                         "saturation_creepage_ratio; 1 for m = 1 or kappa = 0 (Carter)"),
        Variable("stick_ratio", "1",
                 "r_a0 = a*/a0, stick-zone half-width over the Hertz half-width (1 = full "
                 "stick, 0 from the saturation creepage on)", error_target=1e-2,
                 comment="the stick ratio of the same Sec. 5.3 solution (the root of the "
                         "creepage condition for z < 1, 0 for z >= 1); 1 - min(z, 1) for "
                         "m = 1 or kappa = 0 (Carter). The direct solution's stick ratio is "
                         "itself only accurate to about 1e-2 for steep falling laws (m < 0.4, "
                         "kappa xi_c0 > 4): its discrete creepage(r) is slightly non-monotone "
                         "there and r jumps by up to ~1e-2 between neighbouring inputs (e.g. "
                         "m = 0.32, z = 0.38 at kappa xi_c0 = 5.15), which the spline smooths; "
                         "hence the target 1e-2, not 1e-3. A reader should take 0 for z >= 1 "
                         "(exact) and clip to [0, 1] below"),
    ],
    references=(f"{THESIS}, Sec. 5.3, Eq. (5.16) and Fig. 5.4 (polynomial approach); "
                "F.W. Carter, Proc. R. Soc. Lond. A 112 (1926) 151-157 (m = 1 or kappa = 0)"),
    method=("railcontact.friction.velocity_friction_saturation_curve(z, m, kappa xi_c0, "
            "degree=128, tol=1e-10) (the Sec. 5.3 solver behind "
            "velocity_friction_creep_force_normalised): xi_sat = creepage at stick ratio 0, "
            "force and stick ratio at z xi_sat (partial slip, z < 1) or full sliding (z > 1)"),
    check_points=_velocity_friction_check,
    n_check={"coarse": 100, "default": 500, "fine": 1500},
    chunk_size=31,
    requires=("railcontact.friction",),
    attributes={
        "smoothness": (
            "cubic B-spline interpolant, C2 on every axis except C1 at the double knot "
            "normalised_creepage = 1 (onset of full sliding, where the creep curve's second "
            "derivative jumps); the spline does not overshoot the Coulomb limit "
            "max(1, m) (checked on dense random points in tests/test_tablegen_specs.py)"),
        "solver_settings": "degree = 128, tol = 1e-10 (railcontact.friction)",
        "normalisation": (
            "law (5.16) mu(s) = mu_0 [(1 - m)/(1 + kappa s) + m], s the slip velocity over the "
            "rolling speed; kappa times xi_c0 = mu_0 a0/R; creepage over the saturation "
            "creepage xi_sat(m, kappa) (stick zone vanishes; variable "
            "saturation_creepage_ratio = xi_sat/xi_c0); force over mu_0 N: one 3-D table "
            "serves every load, radius and mu_0 of the 2-D (Carter) contact. Grid box: "
            "0.2 <= m <= 1.8, 0 <= kappa xi_c0 <= 6, 0 <= |xi|/xi_sat <= 6 (covers "
            "|xi|/xi_c0 <= 3.2 everywhere), inside the region where the Sec. 5.3 iteration "
            "converges at degree 128"),
    },
))


# --------------------------------------------------------------------------------------------
# Corrugation and wear: exact nonlinear first harmonics next to the linearised ones (Ch. 4)
# --------------------------------------------------------------------------------------------

_CX_COUNTS = {"coarse": (5, 13, 5, 7, 5), "default": (10, 37, 9, 15, 9),
              "fine": (19, 73, 17, 29, 17)}
CORRUGATION_EXACT_STICK_RANGE = (0.02, 0.98)
CORRUGATION_EXACT_AMPLITUDE_MAX = 0.8
CORRUGATION_EXACT_SETTINGS = dict(n_positions=64, n_nodes=64)
_CX_FIELDS = (("half_width", "half_width", ("real",)),
              ("patch_shift", "patch_shift", ("imag",)),
              ("stick_half_width", "stick_half_width", ("real", "imag")),
              ("tangential_force", "tangential_force", ("real", "imag")),
              ("wear", "material_point", ("real", "imag")))
_CX_SMALL = 1e-4        # amplitude used for the (amplitude-independent) mean wear at A = 0


def _cx_axes(resolution):
    n_log, n_lin, n_rlog, n_r, n_a = _CX_COUNTS[resolution]
    lo, hi = CORRUGATION_EXACT_STICK_RANGE
    s = np.linspace(0.0, 1.0, n_r)
    stick = np.r_[np.geomspace(lo, 0.2, n_rlog)[:-1], 0.2 + (hi - 0.2) * np.sin(0.5 * np.pi * s)]
    ratio = np.r_[np.geomspace(0.01, 0.1, n_log)[:-1], np.linspace(0.1, 1.0, n_lin)]
    return [
        Axis("a0_over_wavelength", ratio, "1",
             "a0/L, contact half-length over corrugation wavelength",
             comment="a0/L from 0.01 to 1: log-spaced below 0.1, uniform above (as the "
                     "linearised table corrugation_response, with fewer nodes)"),
        Axis("stick_ratio", stick, "1",
             "r_a0 = a0*/a0, mean stick-zone half-width over contact half-width",
             comment=f"r_a0 from {lo} to {hi} (the exact solver needs 0 < r_a0 < 1): "
                     "log-spaced below 0.2 (the stick-zone response varies on the scale r_a0 "
                     "there), 0.2 + 0.78 sin(pi s/2) above (s uniform; crowding towards full "
                     "stick); beyond the first/last node the reader raises"),
        Axis("relative_amplitude", np.linspace(0.0, CORRUGATION_EXACT_AMPLITUDE_MAX, n_a),
             "1",
             "k^2 R |Z|: corrugation amplitude |Z| times k^2 R (k = 2 pi/L, R the wheel "
             "radius); condition (4.2) of the exact solution is k^2 R |Z| < 1",
             comment="0 (the linearised limit, exactly railcontact.wear.linear_response) to "
                     f"{CORRUGATION_EXACT_AMPLITUDE_MAX}, uniform; the coefficients are even "
                     "in the amplitude to leading order (O(amplitude^2) corrections)"),
    ]


def corrugation_exact_function(points):
    """Exact nonlinear first harmonics over the amplitude at (a0/L, r_a0, k^2 R |Z|).

    :func:`railcontact.wear.wear_first_harmonic_exact` with ``relative_amplitude = k^2 R |Z| /
    (2 pi a0/L)`` (its amplitude is k R |Z| / a0) and phase 0; at zero amplitude the limit,
    :func:`railcontact.wear.linear_response` (the mean wear from a tiny amplitude, 1e-4).
    """
    import warnings  # noqa: PLC0415

    from railcontact.wear import linear_response, wear_first_harmonic_exact  # noqa: PLC0415

    n_var = sum(len(p) for _, _, p in _CX_FIELDS) + 1
    out = np.empty((len(points), n_var))
    for i, (ratio, r, amp) in enumerate(np.asarray(points, dtype=float)):
        kz = 2.0 * np.pi * ratio
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            res = wear_first_harmonic_exact(ratio, r, max(amp, _CX_SMALL) / kz,
                                            **CORRUGATION_EXACT_SETTINGS)
        vals = {k: complex(res[key]) for k, key, _ in _CX_FIELDS}
        if amp == 0.0:
            lin = linear_response(ratio, r)
            vals = {k: complex(getattr(lin, k)) for k, _, _ in _CX_FIELDS}
        row = [getattr(vals[k], part) for k, _, parts in _CX_FIELDS for part in parts]
        out[i] = row + [float(np.real(res["mean"]))]
    return out


_CX_VARIABLES = []
for _f, _key, _parts in _CX_FIELDS:
    for _part in _parts:
        _CX_VARIABLES.append(Variable(
            f"{_f}_{_part}", "1",
            f"{_part} part of the exact first harmonic of the {_CW_NAMES[_f]} divided by the "
            "amplitude, normalised as in railcontact.wear.linear_response "
            "(railcontact.wear.wear_first_harmonic_exact)", error_target=1e-3,
            comment="equals the linearised coefficient (table corrugation_response) at "
                    "relative_amplitude = 0"))
_CX_VARIABLES.append(Variable(
    "mean_wear", "1", "mean wear per passage W0 R / (K mu^2 N a0) of the exact contact "
    "(railcontact.wear.wear_first_harmonic_exact, 'mean')", error_target=1e-3))

register(TableSpec(
    name="corrugation_exact",
    title="Exact nonlinear corrugation and wear response of the 2-D rolling contact, first "
          "harmonics per unit amplitude (Nielsen 1998, Ch. 4)",
    axes=_cx_axes,
    function=corrugation_exact_function,
    variables=_CX_VARIABLES,
    references=(f"{THESIS}, Sec. 4.1-4.3, Eqs. (4.1)-(4.98) (exact normal and stick-zone "
                "solutions, wear (4.74)) with the errata recorded in railcontact.corrugation "
                "and railcontact.wear"),
    method=("railcontact.wear.wear_first_harmonic_exact(a0/L, r_a0, k^2 R |Z| / (2 pi a0/L), "
            "phase=0, n_positions=64, n_nodes=64); relative_amplitude = 0: "
            "railcontact.wear.linear_response(a0/L, r_a0)"),
    n_check={"coarse": 200, "default": 1000, "fine": 3000},
    chunk_size=207,
    requires=("railcontact.wear",),
    attributes={"smoothness": (
        "cubic B-spline interpolant, C2 on every axis. The exact response has a kink surface "
        "that is not a grid line: where the amplitude is large enough for the stick zone to "
        "vanish during part of each wave (k^2 R |Z| of order r_a0 times a factor of order 1, "
        "e.g. k^2 R |Z| = 0.052 at a0/L = 0.2, r_a0 = 0.024), a* is clipped at 0 and the "
        "first harmonics of a* (and, weaker, of T and the wear) have a slope jump in the "
        "amplitude. The spline rounds it off: the stick_half_width errors (max ~2.6e-2, RMS "
        "~1e-3 at the build of 2026-11-22) come from there and miss the target 1e-3 (the file "
        "says so); half_width and patch_shift do not depend on the stick zone (errors ~4e-6)"),
        "normalisation": (
        "exact nonlinear first harmonics (a, Delta, a*, |T|, wear w at a material point) divided "
        "by the complex surface amplitude, normalised as in railcontact.wear.linear_response, "
        "so that they equal the linearised table corrugation_response at relative_amplitude "
        "= 0 (patch_shift_real and half_width_imag vanish and are not stored); the mean wear "
        "is not divided by the amplitude. The growth factor per passage with the exact wear "
        "is 1 - 2 wear_number * wear_real")},
))
