#!/usr/bin/env python
r"""What accuracy costs in time: every way railcontact computes the same quantity, measured in one run.

Why one script of about 1,340 lines: it measures every model family in one run and writes one
report, so the families' timings share one machine load.

    python benchmarks/accuracy_vs_time.py            # default run (< 10 min on 2 cores)
    python benchmarks/accuracy_vs_time.py --quick    # < 1 min, a few points per family (CI)
    python benchmarks/accuracy_vs_time.py --out DIR  # write DIR/accuracy_vs_time.md, DIR/figures/

Writes ``docs/accuracy_vs_time.md`` (Markdown tables: how accurate is each model for its time) and
``docs/figures/accuracy_vs_time.png`` (log-log error against time per evaluation, one Pareto
frontier per model family, the peers' published figures as reference marks). Nothing is
asserted: the script measures and reports.

Families, quantities and error normalisations (each error is the maximum over a fixed set of
cases, stated in the output):

* **2-D Hertz / Carter** -- tangential force ``T/(mu N)`` at four creepages; reference: Carter's
  closed form (2.53), exact for this problem. Methods: the discretised half-space solver
  (``railcontact.reference.halfspace2d``) at increasing element counts, the polynomial approach
  (Ch. 3), Carter.
* **2-D corrugated rail** (non-Hertzian gap, one rail position) -- ``T/(mu N)``; reference: the
  exact nonlinear solution of Ch. 4.2 (``corrugation.corrugated_contact(method="exact")``,
  the polynomial approach with the full Bessel series). Methods: half-space solver at increasing
  element counts, polynomial approach with the gap's Taylor series truncated at degree N,
  linearised closed forms, Carter ignoring the corrugation.
* **3-D creep forces** -- ``|T - T_ref| / (mu N)`` (vector difference) over the CONTACT cases
  (tractcurv series 1, a/b = 0.5, and the 7 cases at a/b = 1 of CONTACT's grid-convergence
  study). Two references: CONTACT's published values (tractcurv at 48x44; the grid-convergence
  cases at 240x60), and the project's most accurate method, the 3-D exact theory
  (``reference.rolling3d``) Richardson-extrapolated from the finest grid pair. Methods: linear,
  SHE, strip, modified strip, the methods users compare against (FASTSIM, Kalker 1982, at
  several strip/element counts; Polach 1999; FaStrip, Sichani et al. 2016), the modified-strip
  table at three resolutions, the exact-theory table (if built), the exact theory at increasing
  grids, with and without Richardson. Plus a table of where each closed-form method is within
  1 %, 5 %, 10 % of mu N by a/b and spin class (21 CONTACT cases, converged exact values).
* **Corrugation and wear** (Ch. 4) -- normalised wear coefficient ``w`` (first harmonic),
  ``|w - w_ref| / |w_ref|``; reference: the exact nonlinear wear integral extrapolated to zero
  amplitude (Richardson in amplitude^2); the direct wear integral with the half-space solver
  (the issue's reference) is measured too and its own convergence reported. Plus the series
  degree study ((4.28) estimate against the true error) and the amplitude / a0/L study of the
  linearised closed forms.
* **Friction** (Ch. 5) -- ``T/(mu_0 N)`` of a velocity-dependent law; reference: the iteration
  at degree 512, tol 1e-10. Methods: the iteration at several degrees and tolerances; the
  half-space solver with the same law.
* **Non-steady** (Ch. 7) and **roughness** (Ch. 6) -- closed forms, timed (no independent
  reference in this run; see the document).
* **FMU** -- microseconds per ``doStep`` for each bundled scene (fmpy, same run), analytic
  against tables; error of the table scene against the analytic scene on the same inputs,
  ``max |F_table - F_analytic| / (mu N)``.

Absolute times depend on the machine load (printed); ratios measured in the same run hold.
"""

from __future__ import annotations

import argparse
import csv
import math
import os
import shutil
import sys
import tempfile
import time
import warnings
from dataclasses import dataclass, field
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")    # many small dense solves: 1 thread is faster

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT / "fmu_src"), str(ROOT / "benchmarks"), str(ROOT)]

import _timing  # noqa: E402
from _timing import median_time  # noqa: E402

#: per-call timing settings (the quick mode shortens them)
TIMING = dict(target=0.05, repeat=5)


def per_call(func, target=None, repeat=None, budget=2.0):
    """Median time of one call (see :func:`_timing.per_call`), with this run's settings."""
    return _timing.per_call(func, target=target or TIMING["target"],
                            repeat=min(repeat or TIMING["repeat"], TIMING["repeat"]),
                            budget=budget)

E, NU = 2.1e11, 0.28


@dataclass
class Row:
    family: str
    method: str
    knob: str
    error: float                      # against the family's project reference
    t_single: float                   # s per evaluation, one call
    t_batch: float = math.nan         # s per evaluation, in a batch
    error_peer: float = math.nan      # against CONTACT's creep curve (tractcurv, 48x44)
    error_peer2: float = math.nan     # against CONTACT's converged values (hertz3d, 240x60)
    note: str = ""


@dataclass
class Family:
    name: str
    quantity: str
    reference: str
    rows: list = field(default_factory=list)
    peer_reference: str = ""
    notes: list = field(default_factory=list)
    extra: dict = field(default_factory=dict)


def _log(msg):
    print(msg, flush=True)


def _vec_err(tx, ty, rx, ry, scale):
    return float(np.max(np.hypot(np.asarray(tx) - rx, np.asarray(ty) - ry) / scale))


# =============================================================================================
# 2-D Hertz / Carter
# =============================================================================================
def family_2d_hertz(quick):
    from railcontact import carter_creep_force, hertz_2d
    from railcontact import polynomial as poly
    from railcontact.reference.halfspace2d import solve_normal_2d, solve_rolling_2d

    fam = Family("2-D Hertz/Carter", "T/(mu N) at xi/xi_c = 0.1, 0.37, 0.7, 0.95",
                 "Carter's closed form (2.53), exact for this problem; error max |T - T_C|/(mu N)")
    big_r, n_load, mu = 0.5, 1.0e6, 0.3
    a0 = float(hertz_2d(n_load, big_r, E, NU).a0)
    chis = np.array([0.1, 0.37, 0.7, 0.95])
    xis = -chis * mu * a0 / big_r
    t_exact = mu * n_load * (1 - (1 - chis) ** 2)          # force on the wheel, xi < 0 -> T > 0

    def carter_all():
        return carter_creep_force(xis, n_load, big_r, E, NU, mu)

    err = np.max(np.abs(carter_all() - t_exact)) / (mu * n_load)
    t1 = per_call(lambda: carter_creep_force(xis[1], n_load, big_r, E, NU, mu))
    tb = per_call(carter_all) / chis.size
    fam.rows.append(Row(fam.name, "Carter closed form", "-", err, t1, tb))

    gap = [0.0, 0.0, 1.0 / (2 * big_r)]

    def poly_one(xi):
        nc = poly.solve_normal_polynomial(gap, n_load, E, NU)
        return poly.solve_tangential_polynomial(nc, mu, creepage=xi).tangential_force

    vals = np.array([poly_one(x) for x in xis])
    err = np.max(np.abs(vals - t_exact)) / (mu * n_load)
    t1 = per_call(lambda: poly_one(xis[1]), repeat=3)
    fam.rows.append(Row(fam.name, "polynomial approach (Ch. 3)", "degree 2 (exact gap)",
                        err, t1, math.nan))

    sizes = [25, 50, 100] if quick else [25, 50, 100, 200, 400, 800, 1600]
    for n in sizes:
        def solve_all(n=n):
            r = solve_normal_2d(lambda x: x * x / (2 * big_r), n_load, E, NU,
                                -1.23 * a0, 1.31 * a0, n)
            return [solve_rolling_2d(r.x, r.pressure, E, NU, creepage=x, friction=mu)
                    .tangential_force for x in xis]

        def solve_one(n=n):
            r = solve_normal_2d(lambda x: x * x / (2 * big_r), n_load, E, NU,
                                -1.23 * a0, 1.31 * a0, n)
            return solve_rolling_2d(r.x, r.pressure, E, NU, creepage=xis[1], friction=mu)

        t0 = time.perf_counter()
        vals = np.array(solve_all())
        tb = (time.perf_counter() - t0) / chis.size
        err = np.max(np.abs(vals - t_exact)) / (mu * n_load)
        t1 = median_time(solve_one, repeat=3, warmup=0, budget=3.0)
        fam.rows.append(Row(fam.name, "half-space solver (reference 2-D)", f"{n} elements",
                            err, t1, tb, note="normal + rolling solve per evaluation"))
    return fam


# =============================================================================================
# 2-D non-Hertzian: a cylinder on a corrugated rail at one position
# =============================================================================================
def family_2d_corrugated(quick):
    from math import factorial

    from railcontact import carter_creep_force, hertz_2d
    from railcontact import polynomial as poly
    from railcontact.corrugation import corrugated_contact
    from railcontact.reference.halfspace2d import solve_normal_2d, solve_rolling_2d

    big_r, n_load, mu = 0.5, 1.0e6, 0.3
    a0 = float(hertz_2d(n_load, big_r, E, NU).a0)
    lam = 0.02
    k = 2 * np.pi / lam
    amp = 0.3 / (k * k * big_r)                 # k^2 R |Z| = 0.3 (condition (4.2): < 1)
    za, zb = amp, 0.0
    xpos = lam / 8
    chi = 0.5
    xi = chi * mu * a0 / big_r
    fam = Family("2-D corrugated rail", f"T/(mu N), one rail position (a0/L = {a0 / lam:.3f}, "
                 f"k^2 R Z = 0.3, xi/xi_c = {chi})",
                 "exact nonlinear solution of Ch. 4.2 (corrugated_contact, method='exact'); "
                 "error |T - T_exact|/(mu N)")
    scale = mu * n_load

    def exact():
        return corrugated_contact(xpos, n_load, big_r, E, NU, mu, xi, [za], [zb], [lam],
                                  method="exact").tangential_force

    t_ref = float(exact())
    t1 = per_call(exact, repeat=3)
    fam.rows.append(Row(fam.name, "exact nonlinear (Ch. 4.2)", "-", 0.0, t1,
                        note="reference"))

    def linear():
        return corrugated_contact(xpos, n_load, big_r, E, NU, mu, xi, [za], [zb], [lam],
                                  method="linear").tangential_force

    err = abs(float(linear()) - t_ref) / scale
    fam.rows.append(Row(fam.name, "linearised closed forms (Ch. 4.2)", "-", err,
                        per_call(linear, repeat=3)))

    def carter():
        return abs(carter_creep_force(xi, n_load, big_r, E, NU, mu))

    fam.rows.append(Row(fam.name, "Carter (corrugation ignored)", "-",
                        abs(float(carter()) - t_ref) / scale, per_call(carter, repeat=3)))

    zeta = (za - 1j * zb) * np.exp(1j * k * xpos)
    degrees = [2, 4, 6] if quick else [2, 3, 4, 5, 6, 8, 10, 12]
    for deg in degrees:
        coeffs = np.array([-np.real(zeta * (1j * k) ** n) / factorial(n) for n in range(deg + 1)])
        coeffs[2] += 1.0 / (2 * big_r)
        coeffs[0] += za                      # rigid shift only (the datum); keeps Z(0) ~ 0

        def poly_one(coeffs=coeffs):
            nc = poly.solve_normal_polynomial(coeffs, n_load, E, NU)
            return abs(poly.solve_tangential_polynomial(nc, mu, creepage=xi).tangential_force)

        try:
            val = poly_one()
            fam.rows.append(Row(fam.name, "polynomial approach, Taylor gap (Ch. 3)",
                                f"degree {deg}", abs(val - t_ref) / scale,
                                per_call(poly_one, repeat=3)))
        except ValueError as exc:            # e.g. a truncated gap without a physical solution
            fam.notes.append(f"polynomial approach at degree {deg}: {exc}")

    hw = 1.6 * a0
    sizes = [50, 100, 200] if quick else [50, 100, 200, 400, 800, 1600]
    for n in sizes:
        def solve_one(n=n):
            def gap(xb):
                return xb * xb / (2 * big_r) - (za * np.cos(k * (xpos + xb))
                                                 + zb * np.sin(k * (xpos + xb)))
            r = solve_normal_2d(gap, n_load, E, NU, -hw, hw, n)
            return abs(solve_rolling_2d(r.x, r.pressure, E, NU, creepage=-xi,
                                        friction=mu).tangential_force)

        t0 = time.perf_counter()
        val = solve_one()
        t_first = time.perf_counter() - t0
        t1 = min(t_first, median_time(solve_one, repeat=2, warmup=0, budget=2.0))
        fam.rows.append(Row(fam.name, "half-space solver (reference 2-D)", f"{n} elements",
                            abs(val - t_ref) / scale, t1))
    return fam


# =============================================================================================
# 3-D creep forces
# =============================================================================================
def _contact_cases(quick):
    """CONTACT cases: dicts of the inputs of creep_force_3d plus CONTACT's (fx, fy)/(mu N)."""
    data = ROOT / "tests" / "data"
    cases = []
    g, nu = 82e9, 0.28
    e_mod = 2 * g * (1 + nu)
    rows = list(csv.reader(line for line in open(data / "contact_tractcurv_series1_coulomb.csv")
                           if not line.startswith("#")))[1:]
    pick = (0.0008, 0.0016) if quick else (0.0004, 0.0008, 0.0012, 0.0016, 0.002, 0.0024,
                                            0.0028, 0.0036)
    for cksi, fx in rows:
        if any(abs(float(cksi) - p) < 1e-12 for p in pick):
            cases.append(dict(xi=float(cksi), eta=0.0, phi=0.0, n=106.7e3, a=6.304e-3,
                              b=12.61e-3, e=e_mod, nu=nu, mu=0.33, fx=float(fx), fy=0.0,
                              label=f"tractcurv cksi={cksi}"))
    path = data / "contact_hertz3d_grid_convergence.csv"
    if path.exists():
        reader = csv.DictReader(line for line in open(path) if not line.startswith("#"))
        labels = ("long k1", "comb k1") if quick else None
        for r in reader:
            if r["a_over_b"] != "1" or (r["mx"], r["my"]) != ("30", "30"):
                continue
            if labels and r["case"] not in labels:
                continue
            gm, nuc = float(r["G_Pa"]), float(r["nu"])
            cases.append(dict(xi=float(r["cksi"]), eta=float(r["ceta"]),
                              phi=float(r["cphi_per_m"]), n=float(r["Fn_N"]),
                              a=float(r["a_m"]), b=float(r["b_m"]), e=2 * gm * (1 + nuc),
                              nu=nuc, mu=float(r["mu"]),
                              fx=float(r["fx_over_mu_fn"]) - float(r["dfx_vs_240x60"]),
                              fy=float(r["fy_over_mu_fn"]) - float(r["dfy_vs_240x60"]),
                              label=f"hertz3d a/b=1 {r['case']}"))
    return cases


SPIN_CLASSES = (("no spin", lambda case: case in ("long k0.3", "long k1", "lat k1", "comb k1")),
                ("Phi = 1", lambda case: "Phi1" in case),
                ("pure spin", lambda case: case.startswith("spin")))


def method_regions():
    """Max |T - T_exact|/(mu N) of every 3-D method per (a/b, spin class) over the 21 cases of
    CONTACT's grid-convergence study, reference its converged 240x60 exact values."""
    from railcontact import creep_force_3d
    from railcontact.creep3d import COMPARISON_METHODS, METHODS
    path = ROOT / "tests" / "data" / "contact_hertz3d_grid_convergence.csv"
    rows = [r for r in csv.DictReader(line for line in open(path) if not line.startswith("#"))
            if (r["mx"], r["my"]) == ("240", "60")]
    ratios = sorted({float(r["a_over_b"]) for r in rows})
    out = {}
    for method in METHODS + COMPARISON_METHODS:
        for r in rows:
            e_mod = 2 * float(r["G_Pa"]) * (1 + float(r["nu"]))
            mu_n = float(r["mu"]) * float(r["Fn_N"])
            f = creep_force_3d(float(r["cksi"]), float(r["ceta"]), float(r["cphi_per_m"]),
                               float(r["Fn_N"]), float(r["a_m"]), float(r["b_m"]), e_mod,
                               float(r["nu"]), float(r["mu"]), method=method)
            err = math.hypot(f.tx / mu_n - float(r["fx_over_mu_fn"]),
                             f.ty / mu_n - float(r["fy_over_mu_fn"]))
            cls = next(name for name, test in SPIN_CLASSES if test(r["case"]))
            key = (method, float(r["a_over_b"]), cls)
            out[key] = max(out.get(key, 0.0), err)
    return ratios, out


def regions_markdown(ratios, errors):
    """The 'where within 1 %, 5 %, 10 % of mu N' table."""
    classes = [c for c, _ in SPIN_CLASSES]
    methods = list(dict.fromkeys(k[0] for k in errors))
    lines = ["## Where each 3-D method is within 1 %, 5 %, 10 % of mu N", "",
             "Max |T - T_exact| / (mu N) per ellipse shape a/b and spin class over the 21 cases "
             "of CONTACT's grid-convergence study (reference: CONTACT's exact theory at 240x60; "
             "'no spin': longitudinal, lateral and combined creepage at 0.3 and 1 of the "
             "linear-force scale (4 cases), 'Phi = 1': lateral or longitudinal creepage with "
             "spin coefficient 1 (2 cases), 'pure spin': one case, spin at 1.2 of its scale). "
             "Cell: the class it falls in (<= 1 %, <= 5 %, <= 10 %, > 10 %) and the measured "
             "error in %. FASTSIM and FaStrip at their defaults (40 strips x 40 elements), "
             "Polach 1999 (k_A = k_S = 1, constant friction).", "",
             "| method | " + " | ".join(f"a/b = {g:g}, {c}" for g in ratios for c in classes)
             + " |", "|---|" + "---|" * (len(ratios) * len(classes))]
    for m in methods:
        cells = []
        for g in ratios:
            for c in classes:
                e = errors.get((m, g, c), math.nan) * 100
                band = ("<= 1 %" if e <= 1 else "<= 5 %" if e <= 5 else "<= 10 %" if e <= 10
                        else "> 10 %")
                cells.append(f"{band} ({e:.1f})")
        lines.append(f"| {m} | " + " | ".join(cells) + " |")
    lines.append("")
    return lines


def contact_grid_errors():
    """CONTACT's own discretisation error per grid: max |F(mx,my) - F(240x60)|/(mu N), a/b = 1."""
    path = ROOT / "tests" / "data" / "contact_hertz3d_grid_convergence.csv"
    if not path.exists():
        return {}
    out = {}
    for r in csv.DictReader(line for line in open(path) if not line.startswith("#")):
        if r["a_over_b"] != "1":
            continue
        key = (int(r["mx"]), int(r["my"]))
        e = math.hypot(float(r["dfx_vs_240x60"]), float(r["dfy_vs_240x60"]))
        out[key] = max(out.get(key, 0.0), e)
    return out


#: FASTSIM, Polach, FaStrip runs of the 3-D family: (method, knob label, options, note); the
#: first three are the defaults (the --quick run measures only those).
COMPARISON_RUNS = (
    ("fastsim", "40x40", {}, "Kalker 1982, 3 flexibilities, parabolic bound"),
    ("polach", "1999 (kA = kS = 1)", {}, "Polach 1999 with spin"),
    ("fastrip", "40x40", {}, "Sichani et al. 2016"),
    ("fastsim", "10x10", dict(n_strips=10, n_elements=10), ""),
    ("fastsim", "20x20", dict(n_strips=20, n_elements=20), ""),
    ("fastsim", "100x100", dict(n_strips=100, n_elements=100), ""),
    ("fastrip", "10x10", dict(n_strips=10, n_elements=10), ""),
    ("fastrip", "100x100", dict(n_strips=100, n_elements=100), ""),
)


def family_3d(quick, workdir):
    from railcontact import creep_force_3d
    from railcontact.creep3d import METHODS
    from railcontact.reference.rolling3d import solve_rolling_3d
    from railcontact.exact_table import ExactCreepTable
    from railcontact.strip_table import CreepTable
    from railcontact.tables import tables_directory

    cases = _contact_cases(quick)
    arr = {k: np.array([c[k] for c in cases]) for k in ("xi", "eta", "phi", "n", "a", "b", "e",
                                                         "nu", "mu", "fx", "fy")}
    args = tuple(arr[k] for k in ("xi", "eta", "phi", "n", "a", "b", "e", "nu", "mu"))
    one = next(i for i, c in enumerate(cases) if c["xi"] > 0.001 and c["eta"] == 0
               and c["phi"] == 0)
    args1 = tuple(float(v[one]) for v in args)
    scale = arr["mu"] * arr["n"]
    cfx, cfy = arr["fx"] * scale, arr["fy"] * scale
    n_ref = 16 if quick else 32
    fam = Family("3-D creep forces", f"(Tx, Ty) on {len(cases)} CONTACT cases "
                 f"(tractcurv a/b = 0.5 and hertz3d a/b = 1, incl. spin)",
                 f"exact theory (reference.rolling3d) at {n_ref}x{n_ref} with Richardson "
                 f"({2 * n_ref}x{2 * n_ref}); error max |T - T_ref|/(mu N)",
                 peer_reference="CONTACT: its creep curve (tractcurv series 1, 48x44 grid, "
                                "itself ~7e-3 from the converged value) and its converged "
                                "values (the a/b = 1 cases at 240x60); error max "
                                "|T - T_CONTACT|/(mu N)")

    def rolling(n, richardson, i, tolerance=1e-6):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            return solve_rolling_3d(*(float(v[i]) for v in args), mx=n, my=n,
                                    richardson=richardson, tolerance=tolerance)

    rolling(8, False, one)                     # numba dispatch, first influence matrices
    _log(f"  3-D reference: rolling3d {n_ref}x{n_ref} + Richardson on {len(cases)} cases ...")
    t0 = time.perf_counter()
    ref = [rolling(n_ref, True, i) for i in range(len(cases))]
    t_ref_batch = (time.perf_counter() - t0) / len(cases)
    rfx = np.array([r.tx for r in ref])
    rfy = np.array([r.ty for r in ref])

    # the closed forms' small-spin substitution holds for Phi <= 1 (spin pole outside the
    # ellipse); pure spin (Phi = inf) is reported separately, not in the max
    creep = np.hypot(arr["xi"], arr["eta"])
    phi_coef = np.where(creep > 0, np.hypot(arr["a"], arr["b"]) * np.abs(arr["phi"])
                        / np.where(creep > 0, creep, 1.0), np.where(arr["phi"] != 0, np.inf, 0))
    valid = phi_coef <= 1.0 + 1e-9
    if not valid.all():
        fam.quantity += (f"; errors over the {int(valid.sum())} cases with spin coefficient "
                         "Phi <= 1 (the closed forms' validity, (2.98)); the pure-spin case is "
                         "in the note column")

    curve = np.array([c["label"].startswith("tractcurv") for c in cases])

    def add(method, knob, tx, ty, t1, tb, note=""):
        tx, ty = np.asarray(tx, float), np.asarray(ty, float)
        if np.isnan(tx[valid]).any():
            note = (note + "; " if note else "") + \
                f"{int(np.isnan(tx[valid]).sum())} case(s) out of the table's range, not counted"
        ok = valid & np.isfinite(tx)
        err = _vec_err(tx[ok], ty[ok], rfx[ok], rfy[ok], scale[ok])
        m1, m2 = ok & curve, ok & ~curve
        e1 = _vec_err(tx[m1], ty[m1], cfx[m1], cfy[m1], scale[m1]) if m1.any() else math.nan
        e2 = _vec_err(tx[m2], ty[m2], cfx[m2], cfy[m2], scale[m2]) if m2.any() else math.nan
        bad = ~valid & np.isfinite(tx)
        if bad.any():
            eb = _vec_err(tx[bad], ty[bad], cfx[bad], cfy[bad], scale[bad])
            note = (note + "; " if note else "") + f"pure spin vs CONTACT: {eb:.1e}"
        fam.rows.append(Row(fam.name, method, knob, err, t1, tb, e1, e2, note))

    add("exact theory (rolling3d) + Richardson", f"{n_ref}x{n_ref} -> {2 * n_ref}x{2 * n_ref}",
        rfx, rfy, t_ref_batch, t_ref_batch, note="project reference (time: mean over the cases)")
    for method in METHODS:
        f = creep_force_3d(*args, method=method)
        t1 = per_call(lambda: creep_force_3d(*args1, method=method))
        tb = per_call(lambda: creep_force_3d(*args, method=method)) / len(cases)
        add(f"closed form: {method}", "-", f.tx, f.ty, t1, tb)

    # the methods users compare against (FASTSIM, Polach, FaStrip), same cases and timing
    for method, knob, opts, note in COMPARISON_RUNS if not quick else COMPARISON_RUNS[:3]:
        f = creep_force_3d(*args, method=method, **opts)
        t1 = per_call(lambda: creep_force_3d(*args1, method=method, **opts))
        tb = per_call(lambda: creep_force_3d(*args, method=method, **opts)) / len(cases)
        add(f"comparison: {method}", knob, f.tx, f.ty, t1, tb, note)

    # tables: the shipped modified-strip table built at three resolutions (same run)
    try:
        from tablegen import specs  # noqa: F401
        from tablegen.build import build_table
        for res in ("coarse", "default", "fine"):
            out = Path(workdir) / f"tab_{res}"
            build_table("creep_modified_strip", res, output_dir=out, scheduler="synchronous",
                        progress=False, workdir=Path(workdir) / f"w_{res}")
            tab = CreepTable.from_file(out / "creep_modified_strip.nc")
            f = tab.creep_force_3d(*args)
            t1 = per_call(lambda: tab.creep_force_3d(*args1))
            tb = per_call(lambda: tab.creep_force_3d(*args)) / len(cases)
            nodes = len(tab.table.axes[0]["nodes"])
            direct = creep_force_3d(*args, method="modified_strip")
            own = _vec_err(f.tx, f.ty, direct.tx, direct.ty, scale)
            fam.extra[f"table_own_{res}"] = own
            add("table: modified strip (C2 spline)", f"{res} ({nodes} nodes)", f.tx, f.ty, t1,
                tb, note=f"vs the closed form: {own:.1e}")
    except Exception as exc:                      # report, do not hide
        fam.notes.append(f"modified-strip table build/evaluation failed: {exc!r}")
    exact_tables = []
    if (tables_directory() / "creep_exact.nc").exists():
        exact_tables.append(("shipped", tables_directory() / "creep_exact.nc"))
    else:
        fam.notes.append("exact-theory table (tables/creep_exact.nc) not shipped in this "
                         "checkout; `python -m tablegen build --only creep_exact` adds it")
    for label, path in exact_tables:
        try:
            tab = ExactCreepTable.from_file(path)
            tx = np.full(len(cases), np.nan)
            ty = np.full(len(cases), np.nan)
            for i in range(len(cases)):
                try:
                    f = tab.creep_force_3d(*(float(v[i]) for v in args))
                    tx[i], ty[i] = f.tx, f.ty
                except ValueError:
                    pass
            ok = np.isfinite(tx)
            sub = tuple(v[ok] for v in args)
            t1 = per_call(lambda: tab.creep_force_3d(*args1))
            tb = per_call(lambda: tab.creep_force_3d(*sub)) / int(ok.sum())
            shape = "x".join(str(len(a["nodes"])) for a in tab.table.axes)
            from railcontact.creep_common import (  # noqa: PLC0415
                EXACT_TABLE_NARROW_ASPECT_MAX as g_max, EXACT_TABLE_NARROW_SPIN_MIN as t_min)
            note = ("solver 30x20 -> 60x20 extrapolated on two shifted grids at the nodes "
                    f"(30x36 -> 60x36 at a/b < {g_max:g} with spin coordinate > {t_min:g}), "
                    "anchored to Kalker's linear theory near zero; every a/b, nu, sign")
            add("table: exact theory (C2 spline)", f"{label} ({shape})", tx, ty, t1, tb, note)
        except Exception as exc:
            fam.notes.append(f"exact-theory table ({label}): {exc!r}")

    grids = [8, 12] if quick else [8, 12, 16, 24, 32, 48]
    for n in grids:
        t0 = time.perf_counter()
        res = [rolling(n, False, i) for i in range(len(cases))]
        tb = (time.perf_counter() - t0) / len(cases)
        t1 = median_time(lambda: rolling(n, False, one), repeat=3, warmup=0, budget=3.0)
        add("exact theory (rolling3d)", f"{n}x{n}", [r.tx for r in res], [r.ty for r in res],
            t1, tb, note="influence matrices cached per grid")
    n_tol = 12 if quick else 24
    for tol in ([1e-2] if quick else [1e-2, 1e-3, 1e-4]):
        t0 = time.perf_counter()
        res = [rolling(n_tol, False, i, tol) for i in range(len(cases))]
        tb = (time.perf_counter() - t0) / len(cases)
        t1 = median_time(lambda: rolling(n_tol, False, one, tol), repeat=3, warmup=0,
                         budget=3.0)
        add("exact theory (rolling3d)", f"{n_tol}x{n_tol}, tolerance {tol:g}",
            [r.tx for r in res], [r.ty for r in res], t1, tb,
            note="iteration tolerance knob (grid rows: 1e-6)")
    rich = [8] if quick else [8, 12, 16, 24]
    for n in rich:
        t0 = time.perf_counter()
        res = [rolling(n, True, i) for i in range(len(cases))]
        tb = (time.perf_counter() - t0) / len(cases)
        add("exact theory (rolling3d) + Richardson", f"{n}x{n} -> {2 * n}x{2 * n}",
            [r.tx for r in res], [r.ty for r in res], tb, tb)
        fam.extra["reference_self_error"] = fam.rows[-1].error    # finest pair below the ref
    return fam


# =============================================================================================
# Ch. 4: corrugation and wear
# =============================================================================================
def family_wear(quick):
    from railcontact import wear
    from railcontact.reference import wear_direct

    ratio, r = 0.1, 0.5
    fam = Family("Corrugation & wear", f"wear coefficient w (first harmonic), a0/L = {ratio}, "
                 f"r_a0 = {r}",
                 "exact nonlinear wear integral (wear_first_harmonic_exact, 128 positions x 128 "
                 "nodes) extrapolated to zero amplitude (eps = 0.02, 0.01; Richardson in "
                 "eps^2); error |w - w_ref|/|w_ref|")

    def exact(eps, npos=128):
        return wear.wear_first_harmonic_exact(ratio, r, eps, n_positions=npos,
                                              n_nodes=npos)["material_point"]

    w_ref = (4 * exact(0.01) - exact(0.02)) / 3
    scale = abs(w_ref)
    for nn in ([4, 24] if quick else [4, 6, 8, 12, 24, 64]):
        w = wear.wear_coefficients(ratio, r, n_nodes=nn)
        t1 = per_call(lambda: wear.wear_coefficients(ratio, r, n_nodes=nn))
        rg = np.linspace(0.05, 0.95, 100)
        tb = per_call(lambda: wear.wear_coefficients(ratio, rg, n_nodes=nn)) / rg.size
        fam.rows.append(Row(fam.name, "linearised closed form (material point, (4.94))",
                            f"{nn} quadrature nodes", abs(w - w_ref) / scale, t1, tb))
    for model in ("patch_coordinate", "time_domain_carter", "nielsen1998"):
        w = wear.wear_coefficients(ratio, r, model)
        t1 = per_call(lambda: wear.wear_coefficients(ratio, r, model))
        fam.rows.append(Row(fam.name, f"closed form, wear model '{model}'", "-",
                            abs(w - w_ref) / scale, t1,
                            note="a different model: the error is the model's"))
    for npos in ([8, 16] if quick else [4, 8, 16, 32, 64]):
        w = wear.wear_first_harmonic_exact(ratio, r, 0.01, n_positions=npos, n_nodes=npos)
        t1 = per_call(lambda: wear.wear_first_harmonic_exact(ratio, r, 0.01, n_positions=npos,
                                                              n_nodes=npos), repeat=3)
        fam.rows.append(Row(fam.name, "exact nonlinear solve (eps = 0.01)",
                            f"{npos} positions x {npos} nodes",
                            abs(w["material_point"] - w_ref) / scale, t1))
    for ne in ([50] if quick else [50, 100, 200, 400, 800]):
        t0 = time.perf_counter()
        w = wear_direct.wear_first_harmonic_reference(ratio, r, 0.01, n_elements=ne)
        t1 = time.perf_counter() - t0
        fam.rows.append(Row(fam.name, "direct wear integral, half-space solver (4.74)",
                            f"{ne} elements x 16 positions",
                            abs(w["material_point"] - w_ref) / scale, t1,
                            note="the issue's reference; first order in the element size"))
    fam.notes.append("no Ch. 4 tables exist (tablegen registers creep tables only), so the "
                     "issue's 'and the tables' has no row here")
    fam.notes.append("the direct wear integral (the issue's reference) converges slowly: "
                     "first order in the element size and sensitive to where the stick/slip "
                     "limit falls in an element; 5-10 % at 200-800 elements, consistent with "
                     "the 5 % tolerance of tests/test_wear.py. The exact nonlinear integral "
                     "extrapolated to zero amplitude and the independent linearised closed form "
                     "agree to ~1e-10, so that pair is used as the reference")
    return fam


def series_study(quick):
    """(4.28) estimate against the true truncation error of the pressure series."""
    from railcontact import hertz_2d
    from railcontact.corrugation import contact_distributions

    big_r, n_load, mu = 0.5, 1.0e6, 0.3
    a0 = float(hertz_2d(n_load, big_r, E, NU).a0)
    out = []
    for ka in ([4.0] if quick else [1.0, 4.0, 10.0]):
        lam = 2 * np.pi * a0 / ka
        k = 2 * np.pi / lam
        amp = 0.3 / (k * k * big_r)
        xs = np.linspace(-a0, a0, 201)
        xi = 0.5 * mu * a0 / big_r
        args = (xs, lam / 8, n_load, big_r, E, NU, mu, xi, [amp], [0.0], [lam])
        ref = contact_distributions(*args, degree=int(3 * ka) + 60)
        pmax = np.max(ref.pressure)
        for deg in sorted({1, 2, 4, 8, int(ka) + 2, int(2 * ka) + 4, int(3 * ka) + 10}):
            d = contact_distributions(*args, degree=deg)
            true = np.max(np.abs(d.pressure - ref.pressure)) / pmax
            t1 = per_call(lambda: contact_distributions(*args, degree=deg), repeat=3,
                          budget=1.0)
            out.append(dict(ka=ka, degree=deg,
                            ratio=d.truncation_ratio, estimate=d.truncation_error,
                            true=true, t=t1))
    return out


def amplitude_study(quick):
    """Linearised closed forms against the exact nonlinear solution vs amplitude and a0/L."""
    from railcontact import hertz_2d, wear
    from railcontact.corrugation import corrugated_contact

    ratios = [0.1] if quick else [0.02, 0.05, 0.1, 0.2, 0.5]
    epss = [0.03, 0.3] if quick else [0.01, 0.03, 0.1, 0.3]
    big_r, n_load, mu = 0.5, 1.0e6, 0.3
    a0 = float(hertz_2d(n_load, big_r, E, NU).a0)
    out = []
    for ratio in ratios:
        w_lin = wear.wear_coefficients(ratio, 0.5)
        for eps in epss:
            if eps * 2 * np.pi * ratio >= 1:
                continue
            w_ex = wear.wear_first_harmonic_exact(ratio, 0.5, eps, n_positions=64)
            lam = a0 / ratio
            k = 2 * np.pi / lam
            amp = eps * a0 / (k * big_r)
            xs = np.linspace(0, lam, 64, endpoint=False)
            xi = 0.5 * mu * a0 / big_r
            te = corrugated_contact(xs, n_load, big_r, E, NU, mu, xi, [amp], [0.0], [lam],
                                    method="exact").tangential_force
            tl = corrugated_contact(xs, n_load, big_r, E, NU, mu, xi, [amp], [0.0], [lam],
                                    method="linear").tangential_force
            out.append(dict(ratio=ratio, eps=eps, kkrz=eps * 2 * np.pi * ratio,
                            wear=abs(w_lin - w_ex["material_point"])
                            / abs(w_ex["material_point"]),
                            force=float(np.max(np.abs(te - tl)) / (mu * n_load)),
                            force_var=float(np.max(np.abs(te - np.mean(te))) / (mu * n_load))))
    return out


# =============================================================================================
# Ch. 5-7: friction, roughness, non-steady
# =============================================================================================
def family_friction(quick):
    from railcontact import hertz_2d
    from railcontact.friction import SmoothFriction, velocity_friction_creep_force_normalised
    from railcontact.reference.halfspace2d import solve_rolling_2d

    m, kap = 1.4, 10.0
    chis = np.array([0.1, 0.5, 1.2])
    fam = Family("Friction (Ch. 5)", f"T/(mu_0 N), smooth law (5.16) mu_k/mu_0 = {m}, "
                 f"kappa xi_c0 = {kap}, xi/xi_c0 = 0.1, 0.5, 1.2",
                 "the iteration of Sec. 5.3 at degree 512, tol 1e-10; error max |dT|/(mu_0 N)")
    ref_deg = 128 if quick else 512
    ref = velocity_friction_creep_force_normalised(chis, m, kap, degree=ref_deg, tol=1e-10)
    fam.reference = fam.reference.replace("512", str(ref_deg))
    knobs = [(16, 1e-4), (32, 1e-10)] if quick else [
        (16, 1e-3), (16, 1e-10), (32, 1e-10), (64, 1e-3), (64, 1e-6), (64, 1e-10),
        (128, 1e-10), (256, 1e-10)]
    for deg, tol in knobs:
        t0 = time.perf_counter()
        f = velocity_friction_creep_force_normalised(chis, m, kap, degree=deg, tol=tol)
        tb = (time.perf_counter() - t0) / chis.size
        t1 = median_time(lambda: velocity_friction_creep_force_normalised(
            0.5, m, kap, degree=deg, tol=tol), repeat=3, warmup=0, budget=2.0)
        fam.rows.append(Row(fam.name, "iteration (Sec. 5.3)", f"degree {deg}, tol {tol:g}",
                            float(np.max(np.abs(f - ref))), t1, tb))
    mu0, big_r, n_load = 0.3, 0.5, 1.0e6
    hz = hertz_2d(n_load, big_r, E, NU)
    a0, p0 = float(hz.a0), float(hz.p0)
    xic = mu0 * a0 / big_r
    law = SmoothFriction(mu0, m * mu0, kap / xic)
    for n in ([100] if quick else [100, 200, 400, 800]):
        dx = 2 * a0 / n
        x = np.arange(-a0 + dx / 2, a0, dx)
        p = p0 * np.sqrt(np.clip(1 - (x / a0) ** 2, 0, None))

        def one(chi, x=x, p=p):
            r = solve_rolling_2d(x, p, E, NU, creepage=chi * xic, friction=law)
            return r.tangential_force / (mu0 * r.normal_load)

        t0 = time.perf_counter()
        f = np.array([one(c) for c in chis])
        tb = (time.perf_counter() - t0) / chis.size
        t1 = min(tb * 3, median_time(lambda: one(0.5), repeat=2, warmup=0, budget=2.0))
        fam.rows.append(Row(fam.name, "half-space solver, same law", f"{n} elements",
                            float(np.max(np.abs(f - ref))), t1, tb))
    by_deg = {}
    for r in fam.rows:
        if r.method.startswith("iteration"):
            by_deg.setdefault(r.knob.split(",")[0], []).append(r.error)
    spread = max((max(v) - min(v) for v in by_deg.values() if len(v) > 1), default=math.nan)
    fam.notes.append(f"the tolerance knob changes the error by at most {spread:.1e} at a fixed "
                     "degree: the error is set by the degree (square-root kink of mu(s(x)) at "
                     "the stick/slip limit); no friction table exists")
    return fam


def family_falling_3d(quick):
    """Kalker's exact theory with Polach's falling law, element by element (method "exact"
    with a friction law), against its own fine grids; the cheaper stand-ins: Polach 2005 (the
    law at the contact's slip velocity V |xi|), FASTSIM with the law (the local bound per
    element), the exact table's fast path with the law (railcontact.falling_table), the Coulomb
    exact table at mu_0 and at mu of the RMS rigid slip (benchmarks/bench_falling_friction_3d.py
    has more)."""
    from railcontact import creep_force_3d
    from railcontact.creep3d import load_exact_table
    from railcontact.friction import PolachFriction

    speed, mu0, n_load, a0, b0 = 30.0, 0.3, 1.0e5, 6e-3, 9e-3
    law = PolachFriction(mu0, 0.4, 6.93)       # B as CONTACT's veldep_fric example: strong fall
    cases = [(1e-3, 0.0, 0.0), (1e-2, 0.0, 0.0), (2e-3, 1e-3, 0.5)]
    if not quick:
        cases += [(3e-3, 0.0, 0.0), (0.0, 0.0, 2.0)]
    xi, eta, phi = (np.array(v) for v in zip(*cases))
    contact = (n_load, a0, b0, E, NU)
    fam = Family("Falling friction (3-D)",
                 f"T/(mu_0 N), a0 = 6 mm, b0 = 9 mm, Polach's law mu0 = {mu0}, A = 0.4, "
                 f"B = 6.93 s/m at V = {speed:g} m/s; {len(cases)} cases (creepage 1e-3 to "
                 "1e-2, lateral creepage with spin" + (", pure spin)" if not quick else ")"),
                 "method='exact' with the law on 60x40 -> 120x40, two grid shifts, tolerance "
                 "1e-4; error max |dT|/(mu_0 N)")
    scale = mu0 * n_load
    ref = creep_force_3d(xi, eta, phi, *contact, law, method="exact", rolling_speed=speed,
                         grid=(60, 40), tolerance=1e-4)
    table = load_exact_table()

    def exact(grid_kw):
        return lambda x, y, p: creep_force_3d(x, y, p, *contact, law, method="exact",
                                              rolling_speed=speed, **grid_kw)

    def rigid(x, y, p):
        s_r = np.sqrt(np.asarray(x) ** 2 + np.asarray(y) ** 2
                      + np.asarray(p) ** 2 * (a0 * a0 + b0 * b0) / 5.0)
        return table.creep_force_3d(x, y, p, *contact, law(s_r * speed))

    runs = [("exact, friction law", "default (30x20 -> 60x20, two shifts)", exact({}), True),
            ("exact, friction law", "40x20, one grid", exact(
                dict(grid=(40, 20), extrapolate=False, grid_shifts=1)), True),
            ("polach 2005, its law at V s_C", "k_A = k_S = 1",
             lambda x, y, p: creep_force_3d(x, y, p, *contact, law, method="polach",
                                            rolling_speed=speed), False),
            ("fastsim, friction law", "40 x 40 (default)",
             lambda x, y, p: creep_force_3d(x, y, p, *contact, law, method="fastsim",
                                            rolling_speed=speed), False),
            ("fastsim, friction law", "20 x 20",
             lambda x, y, p: creep_force_3d(x, y, p, *contact, law, method="fastsim",
                                            rolling_speed=speed, n_strips=20,
                                            n_elements=20), False),
            ("exact table, friction law", "falling_table (3 table calls + correction)",
             lambda x, y, p: creep_force_3d(x, y, p, *contact, law, method="exact_table",
                                            rolling_speed=speed), False),
            ("exact table, Coulomb mu_0", "the law ignored",
             lambda x, y, p: table.creep_force_3d(x, y, p, *contact, mu0), False),
            ("exact table, mu(RMS rigid slip)", "one table call", rigid, False)]
    for method, knob, fun, slow in runs:
        t0 = time.perf_counter()
        f = fun(xi, eta, phi)
        tb = (time.perf_counter() - t0) / xi.size
        if slow:
            t1 = median_time(lambda: fun(2e-3, 1e-3, 0.5), repeat=2, warmup=0, budget=2.0)
        else:
            t1 = per_call(lambda: fun(2e-3, 1e-3, 0.5))
        fam.rows.append(Row(fam.name, method, knob, _vec_err(f.tx, f.ty, ref.tx, ref.ty, scale),
                            t1, tb))
    fam.notes.append("exact table with a friction law: railcontact.falling_table, an "
                     "effective coefficient and a spread correction on the Coulomb table, "
                     "blended with spin into the Coulomb solution at mu_0, plus "
                     "its correction table (the exact theory minus that model over the law's "
                     "normalised parameters); over 30 x 150 random cases with the smooth law "
                     "0.96 % of mu_0 N without spin, 1.00 % at |tau| <= 1, 1.02 % beyond "
                     "(4,489 of the 4,491 within 1 %; 0.91 % where a strong law's stick zone "
                     "collapses with spin); with Polach's law, on its own table, 50 x 150 "
                     "cases: all 7,478 within 1 %, max 0.93 % (2.31 % on the smooth "
                     "law's table) (docs/reference_solvers.md; "
                     "SmoothFriction and PolachFriction take a compiled path, 8-9 us a "
                     "scalar call on a contact whose a0/b0 stays, 12-18 us where it changes "
                     "at every call; benchmarks/bench_falling_friction_3d.py); FASTSIM with "
                     "the law: the local bound mu(q) p per element, a crude theory")
    return fam


def family_other(quick):
    """Non-steady and roughness closed forms: timed; error only where a limit is exact."""
    fam = Family("Non-steady & one asperity", "closed forms of Ch. 6-7",
                 "exact limits where available (see rows); otherwise timing only")
    try:
        from railcontact.nonsteady import nonsteady_transfer_function_normalised as h
        # Carter's quasi-static limit: H -> 1 as a0/L -> 0 (exact)
        for model in ("carter", "johnson"):
            err = abs(complex(h(1e-6, 0.5, model=model)) - 1.0)
            t1 = per_call(lambda: h(0.1, 0.5, model=model))
            grid = np.linspace(0.001, 1.0, 1000)
            tb = per_call(lambda: h(grid, 0.5, model=model)) / grid.size
            fam.rows.append(Row(fam.name, f"non-steady transfer function ({model})",
                                "-", err, t1, tb,
                                note="error: abs(H - 1) at a0/L = 1e-6 (Carter's limit)"))
    except Exception as exc:
        fam.notes.append(f"non-steady: {exc!r}")
    try:
        from railcontact import roughness as rg
        from railcontact import polynomial as poly
        n_load, curv = 1.0e6, 2.0       # Hertz limit: skewness = flatness = 0
        c = rg.asperity_normal_contact(n_load, curv, 0.0, 0.0, E, NU)
        ref = poly.solve_normal_polynomial([0, 0, curv / 2], n_load, E, NU)
        err = abs(c.half_width / ref.half_width - 1)
        t1 = per_call(lambda: rg.asperity_normal_contact(n_load, curv, 0.0, 0.0, E, NU))
        fam.rows.append(Row(fam.name, "one asperity, normal (Table 6.1)", "-", err, t1,
                            note="error: relative half-width vs Hertz at zero skew/flatness"))
    except Exception as exc:
        fam.notes.append(f"roughness: {exc!r}")
    fam.notes.append("no independent reference is run for these closed forms here (the transient "
                     "half-space solver, reference.halfspace2d.solve_transient_rolling_2d, and the "
                     "two-patch reference comparison are in the modules' tests); no tables exist")
    return fam


def family_two_patch(quick):
    """Two contact patches of a double asperity (Ch. 6.4): the polynomial degree knob."""
    from railcontact import roughness as rg
    from railcontact.reference.halfspace2d import solve_normal_2d

    l2 = -20.0                                   # asperity A of Fig. 6.5
    z = rg.double_asperity_coefficients(l2)
    d = 1 / (16 * abs(l2))
    n_load = 4.0e6
    ref_deg = 12 if quick else 24
    fam = Family("Roughness, two patches (Ch. 6)",
                 f"half-width and centre of the leading patch, double asperity A of Fig. 6.5 "
                 f"(lambda2 = {l2} 1/m), N = {n_load:g} N/m",
                 f"two_patch_normal_contact at degree {ref_deg} (Chebyshev cross field); "
                 "error max(|a - a_ref|, |c - c_ref|)/a_ref")

    def solve(**kw):
        return rg.two_patch_normal_contact(z, n_load, E, NU, (-d, d), **kw).patches[1]

    ref = solve(degree=ref_deg)
    a_ref, c_ref = ref.half_width, ref.centre
    knobs = ([dict(degree=4), dict(degree=8), dict(cross_influence=False)] if quick else
             [dict(degree=4), dict(degree=6), dict(degree=8), dict(degree=12), dict(degree=16),
              dict(degree=8, expansion="taylor"), dict(degree=16, expansion="taylor"),
              dict(cross_influence=False)])
    for kw in knobs:
        p = solve(**kw)
        err = max(abs(p.half_width - a_ref), abs(p.centre - c_ref)) / a_ref
        t1 = median_time(lambda: solve(**kw), repeat=3, warmup=0, budget=2.0)
        label = ("no cross influence" if kw.get("cross_influence") is False else
                 f"degree {kw['degree']}, {kw.get('expansion', 'chebyshev')}")
        fam.rows.append(Row(fam.name, "polynomial approach, two patches (6.12)-(6.25)", label,
                            err, t1))
    for n in ([300] if quick else [300, 600, 1200, 2400]):
        def one(n=n):
            return solve_normal_2d(lambda x: np.polynomial.polynomial.polyval(x, z), n_load,
                                   E, NU, -1.4 * d, 1.4 * d, n)
        t0 = time.perf_counter()
        r = one()
        t1 = time.perf_counter() - t0
        s_, e_ = r.zones[1]
        err = max(abs(0.5 * (e_ - s_) - a_ref), abs(0.5 * (e_ + s_) - c_ref)) / a_ref
        fam.rows.append(Row(fam.name, "half-space solver (reference 2-D)", f"{n} elements",
                            err, t1))
    return fam


# =============================================================================================
# FMU
# =============================================================================================
def family_fmu(quick, workdir):
    import bench_fmu

    fam = Family("FMU (per step)", "microseconds per fmi2DoStep, inputs changing every step",
                 "creep_only_table against creep_only_analytic on the same inputs; "
                 "error max |F_table - F_analytic|/(mu N)")
    import build_fmu
    fmu = ROOT / f"{build_fmu.MODEL_NAME}.fmu"       # the checkout's FMU, if current
    if not (fmu.is_file() and build_fmu.fmu_digest(fmu) == build_fmu.source_hash()):
        fmu = build_fmu.build(Path(workdir) / "fmu")
    scenes = sorted((ROOT / "examples" / "scenes").glob("*.toml"))
    if quick:
        scenes = [s for s in scenes if s.stem in ("creep_only_table", "creep_only_analytic")]
    n_fast = 2000 if quick else 20000
    n_slow = 200 if quick else 2000
    forces = {}
    for i, scene in enumerate(scenes):
        inst = bench_fmu.Instance(fmu, Path(workdir) / f"x{i}", scene_file=scene)
        n = n_fast if "table" in scene.stem else n_slow
        bench_fmu.time_steps(inst, min(n, 200))
        step, io = bench_fmu.time_steps(inst, n)
        if scene.stem in ("creep_only_table", "creep_only_analytic"):
            from fmpy import read_model_description
            md = read_model_description(str(fmu))
            vr = {v.name: v.valueReference for v in md.modelVariables}
            rows = bench_fmu._signals(500 if quick else 2000)
            out = []
            t = 0.0
            fxy = [vr["Fx"], vr["Fy"]]
            t0 = time.perf_counter()
            for row in rows:
                inst.fmu.setReal(inst.inputs, row)
                inst.fmu.doStep(t, 1e-3)
                t += 1e-3
                out.append(inst.fmu.getReal(fxy))
            t_fxy = (time.perf_counter() - t0) / len(rows)
            forces[scene.stem] = (np.array(out), np.array(rows)[:, 0])
        inst.close()
        fam.rows.append(Row(fam.name, f"scene {scene.stem}", f"{n} steps", math.nan,
                            step * 1e-6, io * 1e-6,
                            note="batch column: setReal + doStep + getReal of all outputs"))
        if scene.stem in ("creep_only_table", "creep_only_analytic"):
            fam.rows[-1].note += (f"; setReal + doStep + getReal(Fx, Fy) only: "
                                  f"{_fmt_t(t_fxy)}")
    fam.notes.append("doStep = the single-call column; a master reading every Real output "
                     "each step pays the batch column (the stick measures and other lazily "
                     "computed outputs are evaluated when first read after a step, from the "
                     "same table or solver as the forces)")
    if len(forces) == 2:
        (fa, n_a), (ft, _) = forces["creep_only_analytic"], forces["creep_only_table"]
        err = float(np.max(np.hypot(*(ft - fa).T) / (0.3 * np.maximum(n_a, 1.0))))
        for row in fam.rows:
            if row.method == "scene creep_only_table":
                row.error = err
            if row.method == "scene creep_only_analytic":
                row.error = 0.0
                row.note += "; reference"
    return fam


# =============================================================================================
# output
# =============================================================================================
PEERS = dict(
    contact_11=(1.3e-3, 1.7e-3, 11), contact_25=(10e-3, 10e-3, 25), contact_48=(84e-3, 116e-3, 48),
)


def pareto(points):
    """Indices of the points not dominated in (time, error) (both to be minimised)."""
    order = sorted(range(len(points)), key=lambda i: (points[i][0], points[i][1]))
    best, out = math.inf, []
    for i in order:
        if points[i][1] < best:
            out.append(i)
            best = points[i][1]
    return out


def _fmt(v, unit=""):
    if v is None or not np.isfinite(v):
        return "n/a"
    return f"{v:.2e}{unit}"


def _fmt_t(s):
    if s is None or not np.isfinite(s):
        return "n/a"
    us = s * 1e6
    if us < 1000:
        return f"{us:.3g} us"
    if us < 1e6:
        return f"{us / 1e3:.3g} ms"
    return f"{s:.3g} s"


def peer_marks(contact_errors):
    """CONTACT's published figures, with errors from CONTACT's own grid convergence."""
    e30 = contact_errors.get((30, 30), math.nan)
    marks = []
    for key, (t_lo, t_hi, mx) in PEERS.items():
        marks.append(dict(label=f"CONTACT {mx}x{mx if mx != 48 else 44}", t_lo=t_lo, t_hi=t_hi,
                          err=e30 * 30 / mx))
    return marks


def plot(families, contact_errors, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.ticker import NullFormatter

    # one small panel per family (left), the 3-D family against CONTACT (right); the points of
    # each Pareto frontier are named in the panel's legend, not by text on the points (which
    # overlapped when several methods have similar times)
    fig = plt.figure(figsize=(22, 10))
    grid = fig.add_gridspec(2, 6)
    fam_axes = [fig.add_subplot(grid[i // 4, i % 4]) for i in range(8)]
    axes = [None, fig.add_subplot(grid[:, 4:])]
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    markers = "os^vD<>pXP*h"
    floor = 1e-16
    for fi, fam in enumerate(families[:len(fam_axes)]):
        ax = fam_axes[fi]
        pts = [(r.t_single, max(r.error, floor), r) for r in fam.rows
               if np.isfinite(r.t_single) and np.isfinite(r.error)
               and not (r.error == 0.0 and "reference" in r.note)]
        ax.set_title(fam.name, fontsize=9)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.grid(True, which="both", alpha=0.3)
        ax.tick_params(labelsize=7)
        ax.xaxis.set_minor_formatter(NullFormatter())     # (minor labels overlap on short
        ax.yaxis.set_minor_formatter(NullFormatter())     # decades)
        if not pts:
            continue
        ax.scatter([p[0] for p in pts], [p[1] for p in pts], color="0.6", s=12)
        front = [pts[i] for i in pareto([(p[0], p[1]) for p in pts])]
        ax.step([p[0] for p in front], [p[1] for p in front], where="post", color="k", lw=1)
        for k, p in enumerate(front):
            knob = "" if p[2].knob == "-" else ", " + p[2].knob.split(" (")[0][:18]
            ax.scatter([p[0]], [p[1]], color=colors[k % len(colors)],
                       marker=markers[k % len(markers)], s=36, edgecolor="k", zorder=3,
                       label=f"{p[2].method.split(' (')[0][:34]}{knob}")
        ax.legend(fontsize=5.5, loc="best", framealpha=0.8)
    for ax in fam_axes[len(families):]:
        ax.set_visible(False)
    for ax in fam_axes[4:]:
        ax.set_xlabel("time per single call [s]", fontsize=8)
    for ax in fam_axes[::4]:
        ax.set_ylabel("max error vs the family's reference", fontsize=8)

    ax = axes[1]
    fam3 = next((f for f in families if f.name == "3-D creep forces"), None)
    if fam3 is not None:
        groups = {}
        for r in fam3.rows:
            if np.isfinite(r.error_peer2):
                name = r.method.split(":")[0].split(" (")[0]
                if name == "table":      # the exact-theory table apart from the strip tables
                    name = ("exact-theory table (ours)" if "exact theory" in r.method
                            else "modified-strip table")
                groups.setdefault(name, []).append(r)
        k = 0
        for gi, (name, rows) in enumerate(groups.items()):
            if name in ("closed form", "comparison"):
                # one legend entry per method (their times are close: text would overlap)
                for r in rows:
                    lab = r.method.split(": ", 1)[1] + ("" if r.knob in ("-", "40x40")
                                                        else f" {r.knob.split(' (')[0]}")
                    ax.scatter([r.t_single], [max(r.error_peer2, floor)], s=46,
                               marker=markers[k % len(markers)], edgecolor="k", zorder=4,
                               color=colors[k % len(colors)], label=lab)
                    k += 1
                continue
            ours = name.startswith("exact-theory table")
            ax.scatter([r.t_single for r in rows], [max(r.error_peer2, floor) for r in rows],
                       color="0.5" if name.startswith("exact theory") else colors[(gi + 5) % 10],
                       marker="." if name.startswith("exact theory") else ("*" if ours else "d"),
                       s=140 if ours else 30, edgecolor="k" if ours else None, zorder=5,
                       label=name)
            for r in rows:
                if ours:
                    ax.annotate("exact-theory table", (r.t_single, max(r.error_peer2, floor)),
                                fontsize=7, xytext=(6, -3), textcoords="offset points")
                if name.startswith("exact theory"):
                    ax.annotate(r.knob.split(",")[0].split(" ->")[0][:10],
                                (r.t_single, max(r.error_peer2, floor)), fontsize=5.5,
                                xytext=(3, 2), textcoords="offset points", color="0.3")
        pts = [(r.t_single, r.error_peer2) for r in fam3.rows if np.isfinite(r.error_peer2)]
        front = [pts[i] for i in pareto(pts)]
        ax.step([p[0] for p in front], [p[1] for p in front], where="post", color="k", lw=1.5,
                label="Pareto frontier (ours)")
        she = next((r for r in fam3.rows if r.method == "closed form: she"), None)
        if she is not None and np.isfinite(she.error_peer):
            ax.axhline(she.error_peer, color="tab:red", ls=":", lw=1)
            ax.text(2e-7, she.error_peer * 1.1, "SHE's error vs CONTACT's creep curve "
                    "(tractcurv)", fontsize=7, color="tab:red")
    for m in peer_marks(contact_errors):
        if not np.isfinite(m["err"]):
            continue
        ax.plot([m["t_lo"], m["t_hi"]], [m["err"]] * 2, color="tab:purple", lw=4, alpha=0.7)
        ax.scatter([math.sqrt(m["t_lo"] * m["t_hi"])], [m["err"]], marker="s",
                   color="tab:purple", zorder=4)
        ax.annotate(m["label"], (m["t_hi"], m["err"]), fontsize=7, color="tab:purple",
                    xytext=(4, 0), textcoords="offset points")
    e30 = contact_errors.get((30, 30), math.nan)
    if np.isfinite(e30):
        ax.plot([1.9e-3, 134e-3], [e30 * 30 / 11, e30 * 30 / 35], color="tab:purple", ls="--",
                lw=1)
        ax.annotate("CONTACT 2016 test, 11^2..35^2", (134e-3, e30 * 30 / 35), fontsize=7,
                    color="tab:purple", xytext=(4, -8), textcoords="offset points")
    ax.axvline(1e-3, color="tab:brown", ls="--", lw=1)
    ax.text(1e-3, 2e-1, " FASTSIM (peers) < 1 ms;\n ours measured: legend", fontsize=7,
            color="tab:brown")
    t_usetab = 10e-3 / 15000
    ax.axvline(t_usetab, color="tab:olive", ls="--", lw=1)
    ax.text(t_usetab, 5e-2, " USETAB: CONTACT 25x25 / 15000", fontsize=7, color="tab:olive")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("time per evaluation, single call [s]")
    ax.set_ylabel("max |T - T_CONTACT(240x60)| / (mu N) [-]")
    ax.set_title("3-D creep forces against CONTACT's converged values (a/b = 1, 240x60),\n"
                 "FASTSIM, Polach, FaStrip measured; the peers' published times")
    ax.grid(True, which="both", alpha=0.3)
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=6.5, loc="upper left", ncol=2, framealpha=0.85)
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)


def _find(fam, method_start, knob_start=""):
    for r in fam.rows if fam else []:
        if r.method.startswith(method_start) and r.knob.startswith(knob_start):
            return r
    return None


def answers(fams, series, amp, contact_errors):
    """The four accuracy-for-time questions, answered with this run's numbers."""
    f = {fam.name: fam for fam in fams}
    f3, f2 = f.get("3-D creep forces"), f.get("2-D Hertz/Carter")
    fc, ff = f.get("2-D corrugated rail"), f.get("FMU (per step)")
    lines = ["## Answers (this run)", ""]
    # 1. error budget
    lines.append("**1. Which method for a given error budget**: the cheapest method (single "
                 "call) whose measured error against the family's project reference is within "
                 "the budget (normalisations as in each family's table; reference rows "
                 "excluded, '-' = no method measured within the budget except the reference):")
    lines.append("")
    budgets = (3e-2, 1e-2, 1e-3, 1e-4, 1e-6)
    lines.append("| family | " + " | ".join(f"error <= {b:g}" for b in budgets) + " |")
    lines.append("|---|" + "---|" * len(budgets))
    for fam in fams:
        cand = [r for r in fam.rows if np.isfinite(r.error) and np.isfinite(r.t_single)
                and "reference" not in r.note]
        if not cand:
            continue
        cells = []
        for b in budgets:
            ok = [r for r in cand if r.error <= b]
            if ok:
                r = min(ok, key=lambda r: r.t_single)
                knob = "" if r.knob == "-" else f", {r.knob}"
                cells.append(f"{r.method}{knob} ({_fmt_t(r.t_single)})")
            else:
                cells.append("-")
        lines.append(f"| {fam.name} | " + " | ".join(cells) + " |")
    lines.append("")
    if f3:
        self_err = f3.extra.get("reference_self_error")
        if self_err is not None:
            lines.append(f"3-D: the reference itself (exact theory with Richardson) differs by "
                         f"{self_err:.1e} of mu N from the Richardson value of the next coarser "
                         "grid pair, an estimate of its own error; budgets below the "
                         "strip theories' error (~1e-2 of mu N) need the exact theory (or its "
                         "table).")
    lines.append("")
    # 2. tables vs direct
    lines.append("**2. How fast the tables are** (single call, same run):")
    lines.append("")
    tab = _find(f3, "table: modified strip", "default")
    direct = _find(f3, "closed form: modified_strip")
    r3 = [r for r in (f3.rows if f3 else []) if r.method == "exact theory (rolling3d)"
          and "tolerance" not in r.knob]
    if tab and direct:
        lines.append(f"* modified-strip table (default resolution) {_fmt_t(tab.t_single)} vs the "
                     f"direct closed form {_fmt_t(direct.t_single)}: "
                     f"{direct.t_single / tab.t_single:.1f}x; in a batch "
                     f"{_fmt_t(tab.t_batch)} vs {_fmt_t(direct.t_batch)} per point "
                     f"({direct.t_batch / tab.t_batch:.2f}x).")
        for r in (next((r for r in r3 if r.knob == k), None) for k in ("12x12", "24x24",
                                                                         "48x48")):
            if r is not None:
                lines.append(f"* vs the 3-D exact theory at {r.knob} ({_fmt_t(r.t_single)}): "
                             f"{r.t_single / tab.t_single:,.0f}x faster, at an error of "
                             f"{tab.error:.2e} (table, vs exact theory) against {r.error:.2e} "
                             f"(that grid).")
    ex = _find(f3, "table: exact theory")
    if ex and r3:
        fin = r3[-1]
        lines.append(f"* exact-theory table ({ex.knob}): {_fmt_t(ex.t_single)} per call, error "
                     f"{ex.error:.2e} vs the project reference ({_fmt(ex.error_peer2)} vs "
                     f"CONTACT 240x60); the exact theory at {fin.knob} takes "
                     f"{_fmt_t(fin.t_single)} for {fin.error:.2e}: the table is "
                     f"{fin.t_single / ex.t_single:,.0f}x faster (USETAB's claim against "
                     "CONTACT: 15,000x).")
    hs = [r for r in (f2.rows if f2 else []) if r.method.startswith("half-space")]
    if tab and hs:
        lines.append(f"* vs the 2-D reference solver: {hs[0].knob} {_fmt_t(hs[0].t_single)} "
                     f"... {hs[-1].knob} {_fmt_t(hs[-1].t_single)}, i.e. "
                     f"{hs[0].t_single / tab.t_single:,.0f}x to "
                     f"{hs[-1].t_single / tab.t_single:,.0f}x the table's time.")
    if ff:
        st = _find(ff, "scene creep_only_table")
        an = _find(ff, "scene creep_only_analytic")
        if st and an:
            lines.append(f"* in the FMU: {st.t_single * 1e6:.1f} us per doStep from the table vs "
                         f"{an.t_single * 1e6:.1f} us analytic ({an.t_single / st.t_single:.1f}x);"
                         f" table error vs analytic {_fmt(st.error)} of mu N.")
    lines.append("")
    # 3. linearised closed forms
    lines.append("**3. What the linearised closed forms give up** (Ch. 4, against the exact "
                 "nonlinear solution; relative wear-coefficient error and tangential-force "
                 "error in mu N over one wave, r_a0 = 0.5):")
    lines.append("")
    lines.append("| a0/L | eps = k R Z / a0 | k^2 R Z | wear error (rel.) | force error [mu N] | "
                 "force variation [mu N] |")
    lines.append("|---|---|---|---|---|---|")
    for a in amp:
        lines.append(f"| {a['ratio']:g} | {a['eps']:g} | {a['kkrz']:.3f} | {a['wear']:.2e} | "
                     f"{a['force']:.2e} | {a['force_var']:.2e} |")
    lines.append("")
    if amp:
        cw = max(a["wear"] / a["kkrz"] ** 2 for a in amp)
        ct = max(a["force"] / a["kkrz"] ** 2 for a in amp)
        lines.append(f"Rule of thumb from this table: relative wear-coefficient error <= "
                     f"{cw:.2g} (k^2 R |Z|)^2 and force error <= {ct:.2g} (k^2 R |Z|)^2 mu N "
                     "(k^2 R |Z| < 1 is the no-contact-loss condition (4.2)); e.g. a 1 % wear "
                     f"error needs k^2 R |Z| ~ {math.sqrt(0.01 / cw):.2f}.")
        lines.append("")
    lines.append("The error grows like the square of the amplitude (the first harmonic has no "
                 "O(eps) correction) and with k^2 R |Z| = eps * 2 pi a0/L, the distance to "
                 "contact loss (4.2). Error of the linear corrugated-rail force at one position "
                 + (f"(2-D corrugated family): {_find(fc, 'linearised').error:.2e} mu N at "
                    "k^2 R |Z| = 0.3." if fc and _find(fc, "linearised") else "."))
    lines.append("")
    # 4. where tables win
    lines.append("**4. Where the tables are the best choice and where not:**")
    lines.append("")
    if tab and direct:
        own = f3.extra.get("table_own_default", math.nan)
        lines.append(f"* The modified-strip table is a C2 spline of a closed form: its own error "
                     f"(vs the closed form) is {own:.1e} of mu N at default resolution, "
                     f"negligible against the theory's error vs the exact theory "
                     f"({direct.error:.2e}). It pays off for single (scalar) calls, "
                     f"as in an FMU step ({direct.t_single / tab.t_single:.1f}x); in "
                     "large numpy batches the closed form is as fast or faster.")
    if ex:
        lines.append(f"* The exact-theory table ({ex.knob}) gives {ex.error:.2e} of mu N "
                     f"(vs the project reference) at {_fmt_t(ex.t_single)}: the best choice "
                     "for budgets between the strip theories' error (~1e-2) and the table's own "
                     "(its node spacing, and with large spin the kink where the adhesion area "
                     "vanishes, and its node solutions, the solver's default setting); below "
                     "that only the "
                     "exact theory itself is accurate enough: creep_force_3d(method='exact') "
                     "at its default (Richardson on two shifted grids, about 0.2 % of mu N) "
                     "costs about 25 ms per call. Beyond its axes (a0/b0 outside 0.1-10, "
                     "spin coordinate above 20) the solver answers (load_exact_table).")
    else:
        lines.append("* The exact-theory table (not built here) is where tables matter most: "
                     "the exact theory costs milliseconds to seconds per call.")
    lines.append("* Not for Ch. 4 wear and corrugation: no tables exist, and the closed forms "
                 "cost microseconds already; not for non-Hertzian 2-D contact, where the "
                 "polynomial approach is both exact and fast.")
    lines.append("")
    return lines


def write_markdown(fams, series, amp, contact_errors, path, meta, regions=None):
    lines = ["# Accuracy versus time", "",
             "Generated by `python benchmarks/accuracy_vs_time.py` "
             f"({meta['mode']} run, {meta['date']}, {meta['seconds']:.0f} s, load average "
             f"{meta['load']}). Regenerate with the same command; `--quick` for a fast check, "
             "`--out DIR` to write elsewhere.", "",
             "**Timings**: median of repeats, wall clock, on a shared 2-core machine under "
             "load from other processes: absolute times are noisy (easily 2-5x); the *ratios* "
             "between rows, measured in the same run, are what counts. `single` = one scalar "
             "call (as an FMU step makes it), `batch` = per point of a vectorised call "
             "(or a loop over the cases for the iterative solvers). The speed figures the "
             "documentation quotes are in [figures.md](figures.md) "
             "(`benchmarks/figures.py`); the times here are this run's.", "",
             "![error vs time](figures/accuracy_vs_time.png)", ""]
    lines += answers(fams, series, amp, contact_errors)
    if regions is not None:
        lines += regions_markdown(*regions)
    for fam in fams:
        lines += [f"## {fam.name}", "", f"* quantity: {fam.quantity}",
                  f"* reference: {fam.reference}"]
        if fam.peer_reference:
            lines.append(f"* peer reference: {fam.peer_reference}")
        lines += [""]
        peer = bool(fam.peer_reference)
        head = "| method | knob | error | " + \
            ("vs CONTACT curve | vs CONTACT 240x60 | " if peer else "") + \
            "single call | batch / point | note |"
        lines += [head, "|" + "---|" * (6 + 2 * peer)]
        front = set(pareto([(r.t_single if np.isfinite(r.t_single) else math.inf,
                             r.error if np.isfinite(r.error) else math.inf)
                            for r in fam.rows]))
        for i, r in enumerate(fam.rows):
            star = " **(P)**" if i in front and np.isfinite(r.error) else ""
            lines.append(f"| {r.method}{star} | {r.knob} | {_fmt(r.error)} | "
                         + (f"{_fmt(r.error_peer)} | {_fmt(r.error_peer2)} | " if peer else "")
                         + f"{_fmt_t(r.t_single)} | {_fmt_t(r.t_batch)} | {r.note} |")
        for n in fam.notes:
            lines.append(f"\n* note: {n}")
        lines.append("")
    lines.append("(P) = on the family's Pareto frontier (no other row is both faster and more "
                 "accurate).")
    lines.append("")
    lines += ["## Series degree: the estimate (4.28) against the true error", "",
              "Pressure of the corrugated contact (`corrugation.contact_distributions`), "
              "truncated at `degree`, against degree 3 ka + 60; true error max |dp| / p_max. "
              "`ratio` is the thesis' (4.28) ka/(degree+1), `estimate` the neglected-Bessel "
              "bound returned as `truncation_error`.", "",
              "| k a | degree | (4.28) ratio | estimate | true error | time per call |",
              "|---|---|---|---|---|---|"]
    for s in series:
        lines.append(f"| {s['ka']:g} | {s['degree']} | {s['ratio']:.3g} | {s['estimate']:.2e} | "
                     f"{s['true']:.2e} | {_fmt_t(s['t'])} |")
    lines.append("")
    lines += ["## Peers' figures (reference marks in the plot)", "",
              "| peer | time per evaluation | error [mu N] |", "|---|---|---|"]
    for m in peer_marks(contact_errors):
        lines.append(f"| {m['label']} (Python interface, Hertzian case) | "
                     f"{_fmt_t(m['t_lo'])} - {_fmt_t(m['t_hi'])} | {_fmt(m['err'])} "
                     "(first-order estimate from CONTACT's own 30x30 vs 240x60 difference) |")
    lines.append("| CONTACT 2016 performance test, 11^2 .. 35^2 | 1.9 ms - 134 ms | as above |")
    lines.append("| FASTSIM | < 1 ms | not stated |")
    lines.append("| USETAB | '15,000 x faster than CONTACT' (~0.7 us vs 10 ms) | not stated |")
    f3 = next((f for f in fams if f.name == "3-D creep forces"), None)
    she = _find(f3, "closed form: she")
    if she:
        lines.append(f"| SHE (ours, same formula) | {_fmt_t(she.t_single)} | "
                     f"{_fmt(she.error_peer)} vs CONTACT's curve (tractcurv); "
                     f"{_fmt(she.error_peer2)} vs CONTACT 240x60 |")
    for method in ("fastsim", "polach", "fastrip"):
        r = _find(f3, f"comparison: {method}")
        if r:
            lines.append(f"| {method} (ours, {r.knob}) | {_fmt_t(r.t_single)} single, "
                         f"{_fmt_t(r.t_batch)} per batch point | {_fmt(r.error)} vs the "
                         f"project reference; {_fmt(r.error_peer)} vs CONTACT's curve; "
                         f"{_fmt(r.error_peer2)} vs CONTACT 240x60 |")
    if contact_errors:
        lines += ["", "CONTACT's own discretisation error, max |F(grid) - F(240x60)| / (mu N) "
                  "over the 7 cases at a/b = 1: " + ", ".join(
                      f"{k[0]}x{k[1]}: {v:.1e}" for k, v in sorted(contact_errors.items())
                      if k != (240, 60)) + "."]
    lines.append("")
    lines += ["## Accuracy knobs and error estimates (for the lead)", "",
              "* exposed in the Python API: `solve_rolling_3d(mx, my, tolerance, richardson)`, "
              "`solve_normal_2d(..., n)`, `contact_distributions(degree, tolerance)` with the "
              "(4.28) estimate as output, `series_degree`, `wear_coefficients(n_nodes, degree)`, "
              "`wear_first_harmonic_exact(n_positions, n_nodes, degree)`, friction "
              "`degree`, `tol`, tables via `python -m tablegen build --resolution`.",
              "* not (yet) exposed: `corrugated_contact` has no `degree` knob (exact Bessel "
              "closed forms: none needed for a, Delta, a*, T); the polynomial approach's "
              "truncation is the user's (degree of the gap coefficients).", ""]
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text("\n".join(lines))


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--quick", action="store_true", help="a few points per family (< 1 min)")
    parser.add_argument("--out", default=str(ROOT / "docs"),
                        help="output directory (default: the checkout's docs/)")
    parser.add_argument("--skip", nargs="*", default=[],
                        help="families to skip: 2d corrugated 3d wear friction falling3d "
                             "other roughness fmu")
    args = parser.parse_args(argv)
    out = Path(args.out)
    if args.quick:
        TIMING.update(target=0.01, repeat=3)
    t_start = time.perf_counter()
    load = os.getloadavg()
    _log(f"load average {load[0]:.1f} {load[1]:.1f} {load[2]:.1f}; "
         f"{'quick' if args.quick else 'default'} run")
    work = Path(tempfile.mkdtemp(prefix="accuracy_vs_time_"))
    fams, series, amp = [], [], []
    steps = [("2d", family_2d_hertz), ("corrugated", family_2d_corrugated),
             ("3d", lambda q: family_3d(q, work)), ("wear", family_wear),
             ("friction", family_friction), ("falling3d", family_falling_3d),
             ("other", family_other),
             ("roughness", family_two_patch),
             ("fmu", lambda q: family_fmu(q, work))]
    try:
        for key, fn in steps:
            if key in args.skip:
                continue
            t0 = time.perf_counter()
            _log(f"{key} ...")
            fam = fn(args.quick)
            fams.append(fam)
            _log(f"{key}: {len(fam.rows)} rows in {time.perf_counter() - t0:.1f} s")
            for r in fam.rows:
                _log(f"   {r.method:48s} {r.knob:26s} err {_fmt(r.error):>9s} "
                     f"peer {_fmt(r.error_peer):>9s} {_fmt(r.error_peer2):>9s} single {_fmt_t(r.t_single):>10s} "
                     f"batch {_fmt_t(r.t_batch):>10s}")
            for n in fam.notes:
                _log(f"   note: {n}")
            if key == "wear":
                t0 = time.perf_counter()
                series = series_study(args.quick)
                amp = amplitude_study(args.quick)
                _log(f"series and amplitude studies in {time.perf_counter() - t0:.1f} s")
    finally:
        shutil.rmtree(work, ignore_errors=True)
    contact_errors = contact_grid_errors()
    meta = dict(mode="quick" if args.quick else "default",
                date=time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()),
                seconds=time.perf_counter() - t_start,
                load=f"{load[0]:.1f}")
    regions = method_regions()
    write_markdown(fams, series, amp, contact_errors, out / "accuracy_vs_time.md", meta,
                   regions)
    plot(fams, contact_errors, out / "figures" / "accuracy_vs_time.png")
    _log(f"wrote {out / 'accuracy_vs_time.md'} and {out / 'figures' / 'accuracy_vs_time.png'} "
         f"in {time.perf_counter() - t_start:.0f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
