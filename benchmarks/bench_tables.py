"""Speed and size of the smooth tables. Prints figures; asserts nothing.

    python benchmarks/bench_tables.py            # lookups, sizes, direct-model ratios
    python benchmarks/bench_tables.py --build    # also: 1 -> 2 workers (coarse creep_exact)
    python benchmarks/bench_tables.py --full-build   # also: full default build, 2 workers

Measured in one run, so the ratios are meaningful even on a loaded machine; the absolute
times depend on the load (the load average is printed).
"""

from __future__ import annotations

import argparse
import os
import tempfile
import time
import timeit
import warnings

import numpy as np
from scipy.interpolate import NdBSpline, RegularGridInterpolator

from railcontact import creep_force_3d
from railcontact.tables import (CreepTable, ExactCreepTable, Table, default_table_path,
                                tables_directory)


def per_call(fn, number):
    fn()
    best = min(timeit.repeat(fn, number=number, repeat=5))
    return best / number


def lookups():
    print(f"load average: {os.getloadavg()}")
    ms = CreepTable.from_file()
    args = (1e-3, 2e-4, 0.3, 5e4, 5e-3, 4e-3, 210e9, 0.28, 0.3)
    print("\n== one point, from Python ==")
    t_raw1 = per_call(lambda: ms.table.spline.evaluate_point((0.5,)), 20000)
    print(f"modified strip (1-D) raw spline point      : {t_raw1 * 1e6:7.2f} us")
    t_ms = per_call(lambda: ms.creep_force_3d(*args), 20000)
    print(f"CreepTable.creep_force_3d (checked, scalar): {t_ms * 1e6:7.2f} us")
    t_dir = per_call(lambda: creep_force_3d(*args), 500)
    print(f"creep_force_3d direct (modified strip)     : {t_dir * 1e6:7.2f} us "
          f"-> table is {t_dir / t_ms:.0f}x faster")
    have_exact = (tables_directory() / "creep_exact.nc").exists()
    if have_exact:
        ex = ExactCreepTable.from_file()
        sp = ex.table.spline
        p = np.array([0.1, 0.7, 0.4, 0.3])
        t_raw4 = per_call(lambda: sp.evaluate_point(p), 20000)
        print(f"exact (4-D, 4 variables) raw spline point  : {t_raw4 * 1e6:7.2f} us")
        t_ex = per_call(lambda: ex.creep_force_3d(*args), 2000)
        print(f"ExactCreepTable.creep_force_3d (checked)   : {t_ex * 1e6:7.2f} us")
        knots = tuple(a["knots"] for a in ex.table.axes)
        coef = ex.table.spline._coef[0].reshape(tuple(sp._shape))
        nd = NdBSpline(knots, coef, 3)
        t_nd = per_call(lambda: nd(p), 2000)
        print(f"scipy NdBSpline point (1 variable)         : {t_nd * 1e6:7.2f} us")
        grid = tuple(a["nodes"] for a in ex.table.axes)
        rgi = RegularGridInterpolator(grid, ex.table.values["force_ratio_parallel"],
                                      method="cubic")
        t_rgi = per_call(lambda: rgi(p), 200)
        print(f"scipy RegularGridInterpolator cubic point  : {t_rgi * 1e6:7.2f} us")
        from railcontact.reference.rolling3d import solve_rolling_3d
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            t_sol = per_call(lambda: solve_rolling_3d(*args, mx=40, my=20), 3)
        print(f"solve_rolling_3d 40x20 (direct exact)      : {t_sol * 1e6:7.0f} us "
              f"-> table is {t_sol / t_ex:.0f}x faster")

    print("\n== batch of 1e5 points ==")
    rng = np.random.default_rng(0)
    n = 100_000
    z = rng.uniform(0.0, 1.5, (n, 1))
    t = per_call(lambda: ms.table.spline.evaluate(z, check=False), 1)
    print(f"modified strip raw spline batch            : {t / n * 1e9:7.1f} ns/point")
    case = dict(creepage_longitudinal=rng.uniform(-5e-3, 5e-3, n),
                creepage_lateral=rng.uniform(-5e-3, 5e-3, n), spin=rng.uniform(-1, 1, n),
                normal_load=rng.uniform(1e4, 1e5, n), a0=rng.uniform(3e-3, 8e-3, n),
                b0=rng.uniform(3e-3, 8e-3, n), youngs_modulus=210e9, poisson_ratio=0.28,
                friction_coefficient=0.3)
    t_tab = per_call(lambda: ms.creep_force_3d(**case), 1)
    print(f"CreepTable.creep_force_3d batch            : {t_tab / n * 1e9:7.1f} ns/point")
    t_dirb = per_call(lambda: creep_force_3d(**case), 1)
    print(f"creep_force_3d direct batch                : {t_dirb / n * 1e9:7.1f} ns/point "
          f"(ratio direct/table {t_dirb / t_tab:.2f})")
    if have_exact:
        pts = np.column_stack([rng.uniform(lo, hi, n) for lo, hi in
                               zip(sp._lower, sp._upper)])
        t4 = per_call(lambda: sp.evaluate(pts, check=False), 1)
        print(f"exact raw spline batch (4-D, 4 variables)  : {t4 / n * 1e9:7.1f} ns/point")
        t2 = per_call(lambda: ex._force_spline.evaluate(pts, check=False), 1)
        print(f"exact raw spline batch (2 force variables) : {t2 / n * 1e9:7.1f} ns/point")
        srt = pts[np.lexsort(pts.T[::-1])]
        t4s = per_call(lambda: sp.evaluate(srt, check=False), 1)
        print(f"  same, points sorted (coherent access)    : {t4s / n * 1e9:7.1f} ns/point")
        t_nd = per_call(lambda: nd(pts), 1)
        print(f"scipy NdBSpline batch (1 variable)         : {t_nd / n * 1e9:7.1f} ns/point")
        small = {k: (v[:20000] if np.ndim(v) else v) for k, v in case.items()}
        for key, lim in (("creepage_longitudinal", 1e-3), ("creepage_lateral", 1e-3),
                         ("spin", 0.3)):
            small[key] = rng.uniform(-lim, lim, 20000)   # inside the exact table's range
        small["normal_load"] = rng.uniform(6e4, 1e5, 20000)
        t_exb = per_call(lambda: ex.creep_force_3d(**small), 1)
        print(f"ExactCreepTable.creep_force_3d batch       : {t_exb / 20000 * 1e9:7.1f} "
              "ns/point")

    print("\n== sizes on disk ==")
    for path in sorted(tables_directory().glob("*.nc")):
        tab = Table.from_file(path)
        shape = "x".join(str(len(a["nodes"])) for a in tab.axes)
        print(f"{path.name:28s} {path.stat().st_size / 1024:8.1f} KiB  grid {shape}, "
              f"{len(tab.variables)} variables")


def builds(full):
    from tablegen.build import build_table
    from tablegen.spec import REGISTRY
    from tablegen import specs  # noqa: F401

    print("\n== builds ==")
    print(f"load average: {os.getloadavg()}")
    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        for name, spec in (sorted(REGISTRY.items()) if full else []):
            if spec.hidden or spec.available():
                continue
            res = build_table(name, "default", output_dir=tmp, workers=2, progress=False,
                              workdir=os.path.join(tmp, "w"))
            print(f"default build {name:24s}: {res['seconds']:7.1f} s "
                  f"({res['n_points']} points + {res['n_check']} checks, 2 workers)")
        if full:
            print(f"full default build (all tables, 2 workers) : "
                  f"{time.perf_counter() - t0:7.1f} s wall incl. cluster start-up")
        times = {}
        for workers in (1, 2):
            t0 = time.perf_counter()
            build_table("creep_exact", "coarse", output_dir=tmp, workers=workers,
                        progress=False, workdir=os.path.join(tmp, f"w{workers}"))
            times[workers] = time.perf_counter() - t0
            print(f"creep_exact coarse, {workers} worker(s)         : {times[workers]:7.1f} s")
        print(f"speedup 1 -> 2 workers                     : {times[1] / times[2]:7.2f}")


if __name__ == "__main__":
    parser = argparse.ArgumentParser()
    parser.add_argument("--build", action="store_true",
                        help="also time a coarse creep_exact build with 1 and 2 workers")
    parser.add_argument("--full-build", action="store_true",
                        help="also time the full default build of all tables (minutes)")
    parser.add_argument("--no-lookups", action="store_true")
    a = parser.parse_args()
    if not a.no_lookups:
        lookups()
    if a.build or a.full_build:
        builds(a.full_build)
