"""Accuracy of the exact-theory table: off-node random cases of every sign against the solver
at the table's setting (interpolation error), and CONTACT's 21 converged cases (the table's
whole error against the exact theory). Prints figures by a/b and spin class; asserts nothing.

    python benchmarks/exact_table_accuracy.py [--n 1000] [--seed 7] [--theta-scans] [--axes N]
        [--converged N] [--creepage-scans N] [--classes N]

Random cases: a0/b0 log-uniform in [0.1, 10], nu uniform in [0, 0.5], creepage direction
uniform on the circle, |v| / sqrt(1 + tau^2) (|v| the Kalker-weighted creepage over the
saturation creepage; the table's creepage coordinate measures |v| against sqrt(1 + tau^2), so
large spin meets creepages as large as its own slip) log-uniform in [0.01, 5] (three
quarters of the cases) or in [5, 100] (far past saturation: the rest), spin
coordinate tau log-uniform in [0.01, 20] with a random sign (a third of the
cases without spin). The reference is the build's point function,
tablegen.specs.exact_creep_function (the solver at the table's setting, the exact method's
default: 30x20 -> 60x20 Richardson on two shifted grids, on the reference contact; 36 lateral
elements at a0/b0 < 0.87 with |tau| > 2.75), at the same table coordinates. ``--converged N``
adds N such cases (rho / w <= 5) against the exact theory converged in the element size (80
lateral elements everywhere): the table's whole error, and its build solver's, over the
domain rather than at CONTACT's 21 cases. ``--creepage-scans N`` scans N random lines along
the creepage magnitude: random points rarely meet the creepage where the adhesion area
vanishes, and where it collapses between two creepage nodes the table errs most (3.7 % of
mu N at a0/b0 = 10, tau = 1.3, theta = 90 deg on the grid of 2026-11-27; 1,000 random points
found 1.1 % at most). ``--classes N`` prints only the error by a/b class (< 0.2, 0.2-5, > 5) x
spin class (none, moderate, large, pure) of the solver's public default, the previous
default and the table against a converged reference (Richardson in both directions, lateral
elements following a/b), with the default's time per case.
"""

from __future__ import annotations

import argparse
import csv
import math
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT / "fmu_src")]

from railcontact import creep_force_3d  # noqa: E402
from railcontact.creep3d import REFERENCE_CONTACT, load_exact_table  # noqa: E402
from railcontact._floats import value as _value  # noqa: E402
from railcontact.creep_common import saturation_creepage_scaled  # noqa: E402
from railcontact.exact_table import (  # noqa: E402
    creepage_coordinate, exact_table_coordinates, exact_table_inverse)
from railcontact.kalker import kalker_coefficients  # noqa: E402

sys.path[:0] = [str(ROOT)]
from tablegen.specs import exact_creep_function, exact_solver_lateral_elements  # noqa: E402

#: the solver setting the shipped table was built with (tablegen/specs.py: the exact method's
#: default grids, 30x20 -> 60x20 on the grids moved -1/4 and +1/4, scale 1.08; the lateral
#: elements per case from tablegen.specs.exact_solver_lateral_elements)
TABLE_SETTING = dict(tolerance=1e-4)


def table_grid(args):
    """The table solver's grid (30, my) for physical inputs ``args`` of creep_force_3d."""
    xi, eta, phi, n_load, a0, b0, e_mod, nu, mu = args
    w_sat = _value(*saturation_creepage_scaled(n_load, a0, b0, e_mod, nu, mu))
    c = kalker_coefficients(a0 / b0, nu)
    coords = exact_table_coordinates(xi, eta, phi, a0, b0, nu, w_sat, (c.c11, c.c22, c.c23))
    return (30, int(exact_solver_lateral_elements(coords[0], coords[4])))


def random_cases(n, rng):
    g = np.exp(rng.uniform(np.log(0.1), np.log(10.0), n))
    nu = rng.uniform(0.0, 0.5, n)
    theta = rng.uniform(-np.pi, np.pi, n)
    tau = np.exp(rng.uniform(np.log(0.01), np.log(20.0), n)) * rng.choice([-1.0, 1.0], n)
    tau[rng.random(n) < 1.0 / 3.0] = 0.0
    rho = np.where(rng.random(n) < 0.25, np.exp(rng.uniform(np.log(5.0), np.log(100.0), n)),
                   np.exp(rng.uniform(np.log(0.01), np.log(5.0), n)))
    points = np.column_stack([np.log(g), nu, creepage_coordinate(rho), theta, tau])  # rho/w
    # (the table takes any creepage; the reference, exact_creep_function, scales its own
    # inputs into the solver's domain)
    phys = exact_table_inverse(*points.T, contact=REFERENCE_CONTACT)
    return phys, g, tau, points


def contact_converged():
    path = ROOT / "tests" / "data" / "contact_hertz3d_grid_convergence.csv"
    rows = list(csv.DictReader(l for l in open(path) if not l.startswith("#")))
    by = {}
    for r in rows:
        by.setdefault((r["a_over_b"], r["case"]), {})[(int(r["mx"]), int(r["my"]))] = r
    out = []
    for (g, case), grids in by.items():
        r1, r2 = grids[(120, 60)], grids[(240, 60)]
        fx = 2 * float(r2["fx_over_mu_fn"]) - float(r1["fx_over_mu_fn"])
        fy = 2 * float(r2["fy_over_mu_fn"]) - float(r1["fy_over_mu_fn"])
        nu = float(r2["nu"])
        args = (float(r2["cksi"]), float(r2["ceta"]), float(r2["cphi_per_m"]),
                float(r2["Fn_N"]), float(r2["a_m"]), float(r2["b_m"]),
                2 * float(r2["G_Pa"]) * (1 + nu), nu, float(r2["mu"]))
        out.append((g, case, args, fx, fy))
    return out


#: (a0/b0, nu, s, tau) of the 1-D scans over the creepage angle: the worst random cases and
#: their neighbours (large spin with very long or very wide ellipses)
THETA_SCANS = [(9.21, 0.29, 0.423, -3.08), (0.23, 0.22, 0.612, -3.53), (7.43, 0.04, 0.624, 5.07),
               (8.25, 0.49, 0.617, 12.0), (0.15, 0.47, 0.945, 0.60), (0.40, 0.10, 0.679, 11.27),
               (1.0, 0.28, 0.6, 3.0), (0.5, 0.28, 0.5, 5.0), (1.0, 0.28, 0.6, 0.0)]


def theta_scans(table):
    """Max error of (f_par, f_perp) along the creepage angle (every 2.5 degrees) at fixed
    (a0/b0, nu, s, tau): random cases rarely land on the narrow turns of the force's direction
    that large spin makes near theta = 0 (a0/b0 < 1) or +-90 degrees (a0/b0 > 1)."""
    print("\n== 1-D scans over the creepage angle (every 2.5 deg), against the solver ==")
    theta = np.radians(np.arange(-180.0, 180.0, 2.5))
    for g, nu, s, tau in THETA_SCANS:
        pts = np.column_stack([np.full_like(theta, math.log(g)), np.full_like(theta, nu),
                               np.full_like(theta, s), theta, np.full_like(theta, tau)])
        ref = exact_creep_function(pts)
        got = table.table.spline.evaluate(np.ascontiguousarray(pts), check=False)
        err = np.hypot(got[:, 0] - ref[:, 0], got[:, 1] - ref[:, 1])
        i = int(np.argmax(err))
        print(f"  a/b {g:5.2f} nu {nu:4.2f} s {s:5.3f} tau {tau:6.2f}: max {err.max() * 100:6.2f} % "
              f"of mu N at theta = {math.degrees(theta[i]):6.1f} deg")


#: lateral elements of the converged reference (--converged): against 80, the table's 36
#: lateral elements at narrow contacts err by up to 0.2 % of mu N and 20 elements at a0/b0 >=
#: 1 by up to 0.2 %; 60 x 80 -> 120 x 80 differs from 30 x 80 -> 60 x 80 by at most 0.04 %
CONVERGED_LATERAL_ELEMENTS = 80


def _by_class(err, g, tau):
    for name, sel in (("a/b < 0.3", g < 0.3), ("0.3 <= a/b <= 3", (g >= 0.3) & (g <= 3)),
                      ("a/b > 3", g > 3), ("no spin", tau == 0),
                      ("|tau| <= 1", (tau != 0) & (np.abs(tau) <= 1)),
                      ("1 < |tau| <= 5", (np.abs(tau) > 1) & (np.abs(tau) <= 5)),
                      ("|tau| > 5", np.abs(tau) > 5)):
        if np.any(sel):
            print(f"  {name:18s} n = {int(sel.sum()):4d}: max {err[sel].max() * 100:.3f} %, "
                  f"RMS {math.sqrt(np.mean(err[sel]**2)) * 100:.3f} %")


def converged_cases(table, n, rng):
    """The table and its build solver against the exact theory converged in the element
    size (Richardson 30 x 80 -> 60 x 80 on the two moved grids: 80 lateral elements
    everywhere) at ``n`` random cases of :func:`random_cases` (those at rho / w <= 5: the
    solver's own error is where the traction has structure)."""
    phys, g, tau, points = random_cases(n, rng)
    keep = np.abs(np.tan(0.5 * np.pi * points[:, 2])) <= 5.0
    phys = {k: v[keep] for k, v in phys.items()}
    g, tau, points = g[keep], tau[keep], points[keep]
    print(f"\n== {len(points)} random cases against the converged exact theory (30 x "
          f"{CONVERGED_LATERAL_ELEMENTS} -> 60 x {CONVERGED_LATERAL_ELEMENTS}) ==")
    build = exact_creep_function(points)
    ref = exact_creep_function(points, lateral_elements=CONVERGED_LATERAL_ELEMENTS)
    got = table.table.spline.evaluate(np.ascontiguousarray(points), check=False)
    for label, vals in (("table", got), ("its build solver", build)):
        err = np.hypot(vals[:, 0] - ref[:, 0], vals[:, 1] - ref[:, 1])
        i = int(np.argmax(err))
        print(f"  {label}: max {err.max() * 100:.3f} %, RMS "
              f"{math.sqrt(np.mean(err**2)) * 100:.3f} % of mu N (worst: a/b {g[i]:.3g}, "
              f"nu {points[i, 1]:.2f}, rho/w {np.tan(0.5 * np.pi * points[i, 2]):.3g}, "
              f"theta {math.degrees(points[i, 3]):.1f} deg, tau {tau[i]:.3g})")
        _by_class(err, g, tau)


def axis_errors(table, n_per, rng):
    """Interpolation error of one axis at a time: points on nodes in every axis but one and
    midway between two nodes in that one (the spline's error along that axis alone; on the
    nodes it interpolates the solver's values), by spin class (tau = 0, 0 < |tau| <= 1,
    |tau| > 1), ``n_per`` random points per axis and class, against the build's point
    function. Says which axis a finer grid needs."""
    axes = table.table.axes
    nodes = [np.asarray(a["nodes"]) for a in axes]
    names = [a["name"] for a in axes]
    s_nodes, tau_nodes = nodes[2], nodes[4]
    # the computed quarter (the point function's domain; the rest is its mirror image):
    # 0 < s < 1 (s = 0 and 1 are exact forms), |theta| <= pi/2, tau >= 0
    s_pos = np.nonzero((s_nodes > 0.0) & (s_nodes < 1.0))[0]
    th_q = np.nonzero(np.abs(nodes[3]) <= 0.5 * np.pi + 1e-12)[0]
    spin = {"tau = 0": np.nonzero(tau_nodes == 0.0)[0],
            "0 < tau <= 1": np.nonzero((tau_nodes > 0.0) & (tau_nodes <= 1.0))[0],
            "tau > 1": np.nonzero(tau_nodes > 1.0)[0]}
    quarter = {2: s_pos, 3: th_q}
    print(f"\n== one axis at a time: midway between nodes there, on nodes elsewhere ({n_per} "
          "points per axis and spin class), |error| of (f_par, f_perp) in % of mu N ==")
    for label, tau_idx in spin.items():
        line = []
        for d, name in enumerate(names):
            idx = np.column_stack([rng.integers(0, len(n), n_per) for n in nodes])
            idx[:, 2] = rng.choice(s_pos, n_per)
            idx[:, 3] = rng.choice(th_q, n_per)
            idx[:, 4] = rng.choice(tau_idx, n_per)
            pts = np.column_stack([nodes[k][idx[:, k]] for k in range(5)])
            lo = np.minimum(idx[:, d], len(nodes[d]) - 2)
            if d in quarter:     # midway inside the quarter
                lo = np.clip(lo, quarter[d][0], quarter[d][-1] - 1)
            if d == 4:           # tau >= 0; between 0 and the next node without spin
                lo = np.clip(lo, int(tau_idx[0]), len(nodes[4]) - 2)
            pts[:, d] = 0.5 * (nodes[d][lo] + nodes[d][lo + 1])
            ref = exact_creep_function(pts)
            got = table.table.spline.evaluate(np.ascontiguousarray(pts), check=False)
            err = np.hypot(got[:, 0] - ref[:, 0], got[:, 1] - ref[:, 1]) * 100
            line.append(f"{name} {err.max():.2f} / {math.sqrt(np.mean(err**2)):.2f}")
        print(f"  {label:15s} max / RMS: " + "; ".join(line), flush=True)


#: creepage scans known to cross a sharp kink between the creepage nodes: at a0/b0 = 10 with
#: moderate spin the adhesion area collapses (0.70 -> 0.05 of the ellipse between rho / w =
#: 0.22 and 0.27 at theta = 90 deg, tau = 1.3), between the creepage nodes rho / w = 0.22 and
#: 0.28 (0.17 and 0.28 until the nodes 0.13, 0.22, 0.36 came, fifth session of 2026-11-27)
#: (a0/b0, nu, theta [deg], tau)
KINK_SCANS = [(10.0, 0.25, 90.0, 1.3), (10.0, 0.25, 135.0, 1.3), (10.0, 0.375, 123.0, 2.0)]


def creepage_scans(table, n, rng):
    """Error of (f_par, f_perp) along the creepage magnitude (24 points, rho / w 0.05-2,
    log-spaced) on ``n`` random lines (a0/b0 log-uniform in [0.1, 10], nu uniform, theta
    uniform, tau log-uniform in [0.3, 20], a quarter without spin) and on
    :data:`KINK_SCANS`, against the build's point function. Every line crosses the creepage
    where the adhesion area vanishes, which random points rarely meet: where it collapses
    between two creepage nodes the spline rounds the kink off."""
    r = np.geomspace(0.05, 2.0, 24)
    g = np.exp(rng.uniform(np.log(0.1), np.log(10.0), n))
    nu = rng.uniform(0.0, 0.5, n)
    theta = rng.uniform(-180.0, 180.0, n)
    tau = np.exp(rng.uniform(np.log(0.3), np.log(20.0), n))
    tau[rng.random(n) < 0.25] = 0.0
    lines = [(g[i], nu[i], theta[i], tau[i]) for i in range(n)] + list(KINK_SCANS)
    print(f"\n== creepage scans (24 points, rho/w 0.05-2) on {n} random lines and "
          f"{len(KINK_SCANS)} known kinks, against the solver, % of mu N ==")
    worst, all_err, line_g, line_tau = [], [], [], []
    for k, (g_k, nu_k, th_k, tau_k) in enumerate(lines):
        pts = np.column_stack([np.full_like(r, math.log(g_k)), np.full_like(r, nu_k),
                               creepage_coordinate(r * math.hypot(1.0, tau_k), tau_k),
                               np.full_like(r, math.radians(th_k)), np.full_like(r, tau_k)])
        ref = exact_creep_function(pts)
        got = table.table.spline.evaluate(np.ascontiguousarray(pts), check=False)
        err = np.hypot(got[:, 0] - ref[:, 0], got[:, 1] - ref[:, 1])
        i = int(np.argmax(err))
        worst.append((err[i], g_k, nu_k, th_k, tau_k, r[i], ref[i, 3]))
        if k >= n:
            print(f"  known: a/b {g_k:5.2f} nu {nu_k:4.2f} theta {th_k:6.1f} tau {tau_k:5.2f}: "
                  f"max {err[i] * 100:.2f} % at rho/w {r[i]:.3f}")
        else:
            all_err.append(err)
            line_g.append(np.full_like(err, g_k))
            line_tau.append(np.full_like(err, tau_k))
    e = np.concatenate(all_err)
    w = max(worst[:n], key=lambda x: x[0])
    print(f"  random lines: max {e.max() * 100:.3f} %, RMS {math.sqrt(np.mean(e**2)) * 100:.3f} %"
          f", lines above 0.5 %: {sum(x[0] > 5e-3 for x in worst[:n])} of {n} (worst: a/b "
          f"{w[1]:.3g}, nu {w[2]:.2f}, theta {w[3]:.0f} deg, tau {w[4]:.3g}, rho/w {w[5]:.3f}, "
          f"stick area {w[6]:.2f})")
    _by_class(e, np.concatenate(line_g), np.concatenate(line_tau))


#: a/b classes and spin classes of the class table (--classes), as in issue 40
ASPECT_CLASSES = (("a/b < 0.2", 0.1, 0.2), ("0.2 <= a/b <= 5", 0.2, 5.0), ("a/b > 5", 5.0, 10.0))
SPIN_CLASSES = ("none", "moderate", "large", "pure")
#: an extra spin class (``--classes N --near-saturation``, its own random cases): large spin
#: near saturation, |tau| in [3, 20] and rho / w log-uniform in [0.5, 2] sqrt(1 + tau^2),
#: where the force turns from the spin's direction to the creepage's
NEAR_SATURATION = "large, near saturation"


def _class_case(rng, g_lo, g_hi, spin_class):
    """Table coordinates (ln g, nu, s, theta, tau) of one random case of a class: a0/b0
    log-uniform in the class, nu uniform, theta uniform, rho / w log-uniform in [0.05, 3]
    (partial slip to well past saturation); tau 0 (none), |tau| log-uniform in [0.3, 3]
    (moderate) or [3, 20] (large), or no creepage and |tau| log-uniform in [0.5, 20] (pure)."""
    g = math.exp(rng.uniform(math.log(g_lo), math.log(g_hi)))
    tau = {"none": 0.0,
           "moderate": math.exp(rng.uniform(math.log(0.3), math.log(3.0))),
           "large": math.exp(rng.uniform(math.log(3.0), math.log(20.0))),
           "pure": math.exp(rng.uniform(math.log(0.5), math.log(20.0))),
           NEAR_SATURATION: None}[spin_class]        # (every class draws the same numbers)
    if spin_class == NEAR_SATURATION:
        tau = math.exp(rng.uniform(math.log(3.0), math.log(20.0)))
    tau *= rng.choice([-1.0, 1.0])
    lo, hi = (0.5, 2.0) if spin_class == NEAR_SATURATION else (0.05, 3.0)
    rho = 0.0 if spin_class == "pure" else (
        math.exp(rng.uniform(math.log(lo), math.log(hi))) * math.hypot(1.0, tau))
    return (math.log(g), rng.uniform(0.0, 0.5), float(creepage_coordinate(rho, tau)),
            rng.uniform(-math.pi, math.pi), tau)


def reference_grids(g):
    """(mx, my_coarse, my_fine) of the converged reference at a0/b0 = g: the lateral element
    follows the ellipse (160 lateral elements below a0/b0 = 0.5, 120 up to 2, and 80 with 60
    along x beyond), each grid the default x-setting (Richardson mx -> 2 mx on the two moved
    grids) and one more Richardson step in the lateral element size (second order) between
    my_coarse and my_fine."""
    if g < 0.5:
        return 30, 80, 160
    if g <= 2.0:
        return 30, 60, 120
    return 60, 40, 80


#: the class table's converged references, computed once per case (the reference costs
#: seconds to a minute per case; the table and the default are re-measured every run)
CLASS_REFERENCE_FILE = ROOT / "benchmarks" / "data" / "exact_class_reference.csv"
_CLASS_FIELDS = ("log_aspect_ratio", "poisson_ratio", "creepage_coordinate", "creepage_angle",
                 "spin_coordinate", "tx", "ty", "lateral_correction_percent")


def _read_class_reference(path):
    """{case coordinates (repr of 5 floats): (tx, ty, lateral correction)} from
    :data:`CLASS_REFERENCE_FILE` (empty when there is none)."""
    if not Path(path).exists():
        return {}
    with open(path, newline="") as f:
        rows = list(csv.DictReader(row for row in f if not row.startswith("#")))
    return {tuple(float(r[k]) for k in _CLASS_FIELDS[:5]):
            tuple(float(r[k]) for k in _CLASS_FIELDS[5:]) for r in rows}


def _append_class_reference(path, pt, values):
    new = not Path(path).exists()
    with open(path, "a", newline="") as f:
        if new:
            f.write("# converged exact theory at the class table's cases "
                    "(benchmarks/exact_table_accuracy.py --classes; reference_grids: Richardson "
                    "in x on two moved grids and one step in the lateral element size); tx, ty "
                    "[N] on the reference contact railcontact.creep3d.REFERENCE_CONTACT, "
                    "lateral_correction_percent = |R - F(my_fine)| / (mu N) [%]\n")
        w = csv.writer(f)
        if new:
            w.writerow(_CLASS_FIELDS)
        w.writerow([repr(float(x)) for x in pt] + [repr(float(x)) for x in values])


def class_table(table, n, rng, reference_file=CLASS_REFERENCE_FILE, table_only=False,
                near_saturation=False):
    """Error by a/b class x spin class against a converged reference (:func:`reference_grids`,
    Richardson in both directions): the solver's public default (``creep_force_3d(...,
    method="exact")``: :func:`railcontact.creep3d.exact_default_grid`), the previous default
    (30 x 20 everywhere) and the table, max / RMS in % of mu N, and the default's time per
    case (set-ups cached). The reference's own error is estimated by the size of its lateral
    Richardson correction, ``|R - F(my_fine)|``. References are kept in ``reference_file``
    (computed for cases not yet there); ``table_only`` skips the two solver columns;
    ``near_saturation`` adds :data:`NEAR_SATURATION` per a/b class (drawn after the others,
    so the other classes keep their cases)."""
    from railcontact.creep3d import exact_default_grid  # noqa: PLC0415

    keys = ("creepage_longitudinal", "creepage_lateral", "spin", "normal_load", "a0", "b0",
            "youngs_modulus", "poisson_ratio", "friction_coefficient")
    cached = _read_class_reference(reference_file)
    print(f"\n== class table: {n} random cases per a/b x spin class against the converged "
          "exact theory (Richardson in x and y), % of mu N ==")
    print(f"  {'class':40s} {'default max / RMS':>18s} {'(ms)':>6s} {'30x20 max / RMS':>16s} "
          f"{'table max / RMS':>16s} {'ref. corr.':>10s}  my")
    result = []
    rows = [(a, s) for a in ASPECT_CLASSES for s in SPIN_CLASSES]
    rows += [(a, NEAR_SATURATION) for a in ASPECT_CLASSES] if near_saturation else []
    for (a_name, g_lo, g_hi), spin_class in rows:
        e_new, e_old, e_tab, corr, t_new, mys = [], [], [], [], [], set()
        for _ in range(n):
            pt = _class_case(rng, g_lo, g_hi, spin_class)
            phys = exact_table_inverse(*pt, contact=REFERENCE_CONTACT)
            args = [float(phys[k]) for k in keys]
            mu_n = args[3] * args[8]
            key = tuple(float(x) for x in pt)
            if key not in cached:
                mx, my_c, my_f = reference_grids(math.exp(pt[0]))
                f_c = creep_force_3d(*args, method="exact", grid=(mx, my_c),
                                     tolerance=1e-4)
                f_f = creep_force_3d(*args, method="exact", grid=(mx, my_f),
                                     tolerance=1e-4)
                rx = (4.0 * f_f.tx - f_c.tx) / 3.0
                ry = (4.0 * f_f.ty - f_c.ty) / 3.0
                cached[key] = (rx, ry, math.hypot(f_f.tx - rx, f_f.ty - ry) / mu_n * 100)
                _append_class_reference(reference_file, key, cached[key])
            rx, ry, c = cached[key]
            corr.append(c)
            tab = table.creep_force_3d(*args)
            e_tab.append(math.hypot(tab.tx - rx, tab.ty - ry) / mu_n * 100)
            if table_only:
                continue
            creep_force_3d(*args, method="exact")           # set-up cached
            t0 = time.perf_counter()
            new = creep_force_3d(*args, method="exact")
            t_new.append(time.perf_counter() - t0)
            old = creep_force_3d(*args, method="exact", grid=(30, 20))
            mys.add(exact_default_grid(args[4], args[5], pt[4])[1])
            for store, f in ((e_new, new), (e_old, old)):
                store.append(math.hypot(f.tx - rx, f.ty - ry) / mu_n * 100)

        def mr(e):
            e = np.asarray(e)
            return f"{e.max():.2f} / {math.sqrt(np.mean(e**2)):.2f}" if e.size else "-"
        t_ms = f"{np.mean(t_new) * 1e3:6.0f}" if t_new else "     -"
        my_used = f"{min(mys)}-{max(mys)}" if mys else "-"
        print(f"  {a_name + ', ' + spin_class:40s} {mr(e_new):>18s} "
              f"{t_ms} {mr(e_old):>16s} {mr(e_tab):>16s} "
              f"{max(corr):10.3f}  {my_used}", flush=True)
        result.append((f"{a_name}, {spin_class}", n, mr(e_tab), max(corr)))
    return result


def record_class_table(path, result, n, seed):
    """Write the class table's table column into the file's ``accuracy_by_class`` attribute
    (and a ``history`` line): the edge figures a reader of the file sees."""
    import datetime  # noqa: PLC0415

    import netCDF4  # noqa: PLC0415

    now = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ")
    text = ("max / RMS of |T - T_ref| in % of mu N against the exact theory converged in both "
            "element sizes (Richardson in x on two moved grids and one step in the lateral "
            f"element size; its lateral correction at most {max(r[3] for r in result):.3f} %), "
            f"{n} random cases per a/b class x spin class (benchmarks/exact_table_accuracy.py "
            f"--classes {n} --near-saturation --seed {seed}): "
            + "; ".join(f"{name} {mr}" for name, _, mr, _ in result))
    with netCDF4.Dataset(str(path), "a") as nc:
        nc.setncattr("accuracy_by_class", text)
        nc.setncattr("history", f"{nc.getncattr('history')}\n{now} accuracy_by_class "
                                f"recorded by benchmarks/exact_table_accuracy.py --classes {n}")
    print(f"recorded in {path}: accuracy_by_class")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=1000)
    ap.add_argument("--seed", type=int, default=7)
    ap.add_argument("--theta-scans", action="store_true",
                    help="also scan the creepage angle at the worst-known cases (~1 min)")
    ap.add_argument("--axes", type=int, default=0, metavar="N",
                    help="also the error of one axis at a time, N points per axis and spin "
                         "class (N = 60: about 2 min)")
    ap.add_argument("--converged", type=int, default=0, metavar="N",
                    help="also N random cases against the exact theory converged in the "
                         "element size (80 lateral elements; N = 200: about 10 min)")
    ap.add_argument("--creepage-scans", type=int, default=0, metavar="N",
                    help="also N random lines along the creepage magnitude (24 points each) "
                         "and the known kinks (N = 100: about 3 min)")
    ap.add_argument("--classes", type=int, default=0, metavar="N",
                    help="only the class table: N random cases per a/b x spin class against "
                         "the converged exact theory (N = 6: about 6 min; references kept in "
                         "benchmarks/data/exact_class_reference.csv)")
    ap.add_argument("--near-saturation", action="store_true",
                    help="with --classes: add large spin near saturation per a/b class")
    ap.add_argument("--record", action="store_true",
                    help="with --classes: write the table's column into the file's "
                         "accuracy_by_class attribute (the file of --table)")
    ap.add_argument("--table-only", action="store_true",
                    help="with --classes: the table's column only (the solver columns skipped)")
    ap.add_argument("--table", default=None, metavar="FILE",
                    help="an exact table file to measure instead of the shipped one")
    opts = ap.parse_args(argv)
    table = load_exact_table(opts.table) if opts.table else load_exact_table()
    if opts.classes:
        result = class_table(table, opts.classes, np.random.default_rng(opts.seed + 4),
                             table_only=opts.table_only, near_saturation=opts.near_saturation)
        if opts.record:
            record_class_table(opts.table or table.path, result, opts.classes, opts.seed)
        return
    print(f"table {table.path} ({table.table.attrs.get('source', '?')})")

    print("\n== against CONTACT's 21 cases, converged (Richardson of 120x60 and 240x60) ==")
    errs = []
    for g, case, args, fx, fy in contact_converged():
        f = table.creep_force_3d(*args)
        s = creep_force_3d(*args, method="exact", grid=table_grid(args), **TABLE_SETTING)
        mu_n = args[3] * args[8]
        e_tab = math.hypot(f.tx / mu_n - fx, f.ty / mu_n - fy)
        e_sol = math.hypot(s.tx / mu_n - fx, s.ty / mu_n - fy)
        errs.append((g, case, e_tab, e_sol))
        print(f"  a/b {g:>4s} {case:14s} table {e_tab * 100:6.3f} %  solver {e_sol * 100:6.3f} % "
              "of mu N")
    e = np.array([x[2] for x in errs])
    s_ = np.array([x[3] for x in errs])
    print(f"  table: max {e.max() * 100:.3f} %, RMS {math.sqrt(np.mean(e**2)) * 100:.3f} %;"
          f" its solver: max {s_.max() * 100:.3f} %, RMS {math.sqrt(np.mean(s_**2)) * 100:.3f} %")

    print(f"\n== {opts.n} random off-node cases of every sign, against the solver ==")
    rng = np.random.default_rng(opts.seed)
    phys, g, tau, points = random_cases(opts.n, rng)
    keys = ("creepage_longitudinal", "creepage_lateral", "spin", "normal_load", "a0", "b0",
            "youngs_modulus", "poisson_ratio", "friction_coefficient")
    args = [phys[k] for k in keys]
    t0 = time.perf_counter()
    tab = table.creep_solution_3d(*args, sensitivities=False)
    t_tab = time.perf_counter() - t0
    t0 = time.perf_counter()
    # the build's own point function (solve_rolling_3d on the reference contact at the
    # table's setting; reaches past the public solver's |v| ~ 200 domain limit)
    ref = exact_creep_function(points)
    t_ref = time.perf_counter() - t0
    c, sn = np.cos(points[:, 3]), np.sin(points[:, 3])
    ref_x = -(ref[:, 0] * c - ref[:, 1] * sn)
    ref_y = -(ref[:, 0] * sn + ref[:, 1] * c)
    mu_n = phys["normal_load"] * phys["friction_coefficient"]
    err = np.hypot(tab.tx / mu_n - ref_x, tab.ty / mu_n - ref_y)
    print(f"  all: max {err.max() * 100:.3f} %, RMS {math.sqrt(np.mean(err**2)) * 100:.3f} % of "
          f"mu N; table {t_tab / opts.n * 1e6:.1f} us/case, solver {t_ref / opts.n * 1e3:.1f} "
          "ms/case")
    worst = int(np.argmax(err))
    print("  worst: " + ", ".join(f"{k} = {float(phys[k][worst]):.4g}" for k in keys))
    _by_class(err, g, tau)
    if opts.theta_scans:
        theta_scans(table)
    if opts.axes:
        axis_errors(table, opts.axes, np.random.default_rng(opts.seed + 1))
    if opts.converged:
        converged_cases(table, opts.converged, np.random.default_rng(opts.seed + 2))
    if opts.creepage_scans:
        creepage_scans(table, opts.creepage_scans, np.random.default_rng(opts.seed + 3))


if __name__ == "__main__":
    main()
