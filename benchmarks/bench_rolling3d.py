"""Speed and accuracy of the 3-D exact steady rolling solver (railcontact.reference.rolling3d).

Single thread, one case per call. For each grid the CPU time (``time.process_time``; the shared
machine's wall time is inflated by other processes, it is printed too) of one solve (best of
``--repeat``,
after a warm-up call that fills the influence-matrix and normal-solution caches and the numba
cache) and the error of Fx, Fy against the finest-grid CONTACT value (240x60, the continuum
proxy of tests/data/contact_hertz3d_grid_convergence.csv; that value has its own first-order
error, about 1e-3 of mu N) are printed, in units of mu N.

Run:  python benchmarks/bench_rolling3d.py [--repeat 3] [--cases all] [--tolerance 1e-6]

Reference figures (issue 9): a scratch implementation 40x20 15 ms (0.9 % max error against the
continuum), 40x40 67 ms, Richardson 40x20 -> 80x40 0.23-0.38 s (0.4-0.5 %); CONTACT 38 ms at
35x35 and 478 ms at 64x64.
"""

from __future__ import annotations

import argparse
import csv
import os
import time
from pathlib import Path

os.environ.setdefault("NUMBA_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("MKL_NUM_THREADS", "1")

from railcontact.reference.rolling3d import solve_rolling_3d  # noqa: E402

DATA = Path(__file__).resolve().parent.parent / "tests" / "data"
GRIDS = [(40, 20, False), (35, 35, False), (40, 40, False), (64, 64, False), (40, 20, True)]


def _cases(which):
    with open(DATA / "contact_hertz3d_grid_convergence.csv") as fh:
        rows = list(csv.DictReader(line for line in fh if not line.startswith("#")))
    fine = [r for r in rows if r["mx"] == "240"]
    if which == "all":
        return fine
    return [r for r in fine if r["a_over_b"] == "1" and r["case"] in ("comb k1", "long k1 Phi1")]


def _args(row):
    g = float(row["G_Pa"])
    nu = float(row["nu"])
    return dict(creepage_longitudinal=float(row["cksi"]), creepage_lateral=float(row["ceta"]),
                spin=float(row["cphi_per_m"]), normal_load=float(row["Fn_N"]),
                a0=float(row["a_m"]), b0=float(row["b_m"]), youngs_modulus=2 * g * (1 + nu),
                poisson_ratio=nu, friction_coefficient=float(row["mu"]))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--cases", choices=["default", "all"], default="default")
    parser.add_argument("--tolerance", type=float, default=1e-6,
                        help="relative traction change per sweep at which to stop")
    opts = parser.parse_args()
    print(f"{'a/b':>4} {'case':<13} {'grid':<14} {'cpu [ms]':>9} {'wall [ms]':>9} {'sweeps':>6} "
          f"{'err Fx':>8} {'err Fy':>8}   (errors vs CONTACT 240x60, units of mu N)")
    for row in _cases(opts.cases):
        args = _args(row)
        mu_n = args["friction_coefficient"] * args["normal_load"]
        fx_ref, fy_ref = float(row["fx_over_mu_fn"]), float(row["fy_over_mu_fn"])
        for mx, my, rich in GRIDS:
            kw = dict(mx=mx, my=my, richardson=rich, tolerance=opts.tolerance)
            solve_rolling_3d(**args, **kw)  # warm caches
            best = wall = float("inf")
            for _ in range(opts.repeat):
                t0, w0 = time.process_time(), time.perf_counter()
                res = solve_rolling_3d(**args, **kw)
                best = min(best, time.process_time() - t0)
                wall = min(wall, time.perf_counter() - w0)
            label = f"{mx}x{my}" + (f"->{2 * mx}x{2 * my}" if rich else "")
            print(f"{row['a_over_b']:>4} {row['case']:<13} {label:<14} {best * 1e3:9.1f} "
                  f"{wall * 1e3:9.1f} "
                  f"{res.iterations:6d} {res.tx / mu_n - fx_ref:+8.4f} "
                  f"{res.ty / mu_n - fy_ref:+8.4f}")
    # the cold cost: influence matrices + normal problem, once per grid and contact
    from railcontact.reference import rolling3d

    rolling3d._normal_solution.cache_clear()
    rolling3d._kernels.cache_clear()
    row = _cases("default")[0]
    for mx, my, _ in GRIDS[:4]:
        t0 = time.process_time()
        rolling3d._normal_solution(mx, my, 1.08, float(row["a_m"]), float(row["b_m"]),
                                   float(row["Fn_N"]), 2 * float(row["G_Pa"]) * 1.28, 0.28)
        print(f"set-up (influence coefficients + normal problem) {mx}x{my}: "
              f"{(time.process_time() - t0) * 1e3:.1f} ms CPU (once per grid and contact, cached)")


if __name__ == "__main__":
    main()
