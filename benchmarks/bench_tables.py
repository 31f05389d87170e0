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

from railcontact import creep_force_3d
from railcontact.exact_table import ExactCreepTable
from railcontact.strip_table import CreepTable
from railcontact.tables import Table, tables_directory


def per_call(fn, number):
    fn()
    best = min(timeit.repeat(fn, number=number, repeat=5))
    return best / number


#: Wall time over which the scalar calls are timed in turn [s].
SCALAR_WINDOW = 12.0


def _host_probe():
    """A fixed pure-Python loop: its time tracks the host's speed (no numba, no numpy)."""
    s = 0.0
    for i in range(10):
        s += i * 0.5
    return s


def interleaved(calls, seconds, number=2000):
    """Best and median time per call of each of ``calls`` (name -> callable), timed in rounds
    of ``number`` calls each, in turn, for ``seconds`` of wall time; and the fraction of the
    rounds in which the host was slow (the pure-Python probe, ``calls["python"]``, over 1.3
    times its best).

    This host (a virtual machine on 2 shared cores) switches between a fast and a slow state
    for seconds at a time, everything, a pure-Python loop included, taking 1.5-1.8 times as
    long in the slow one; a figure timed in one short burst then depends on which state it
    fell in. Timed in turn over a window, the calls share the host's states, the best of the
    rounds is each call's time on the host at its speed (timeit's advice: the minimum, as
    the higher values come from other load), and the median shows the rest."""
    times = {name: [] for name in calls}
    end = time.perf_counter() + seconds
    while time.perf_counter() < end:
        for name, fn in calls.items():
            times[name].append(timeit.timeit(fn, number=number) / number)
    best = {name: min(t) for name, t in times.items()}
    median = {name: float(np.median(t)) for name, t in times.items()}
    probe = np.array(times["python"])
    return best, median, float(np.mean(probe > 1.3 * probe.min()))


# (the peak from /proc's VmHWM, this process's own: ru_maxrss keeps the parent's across
# fork and exec, so started from this benchmark it showed the benchmark's peak)
_LOAD_MEMORY = """
import resource, time
from railcontact.exact_table import ExactCreepTable


def peak_mib():
    try:
        with open("/proc/self/status") as fh:
            return next(float(l.split()[1]) for l in fh if l.startswith("VmHWM:")) / 1024
    except (OSError, StopIteration):
        return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


before = peak_mib()
t = time.perf_counter()
table = ExactCreepTable.from_file()
t = time.perf_counter() - t
print(before, peak_mib(), table._coef.nbytes / 2**20, t)
"""


def load_memory():
    """Peak memory of loading the exact table in a fresh process (the file already in the
    user cache), against its coefficients' size."""
    import subprocess  # noqa: PLC0415
    import sys  # noqa: PLC0415

    out = subprocess.run([sys.executable, "-c", _LOAD_MEMORY], capture_output=True, text=True,
                         check=True).stdout.split()
    before, peak, coef, t = (float(v) for v in out)
    return (f"loading it (fresh process)                 : {t:7.2f} s, peak memory "
            f"{peak:.0f} MiB ({before:.0f} before; coefficients {coef:.0f} MiB float64: "
            f"{(peak - before) / coef:.2f}x)")


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
        exact_lookups(args)

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
    print("\n== sizes on disk ==")
    for path in sorted(tables_directory().glob("*.nc")):
        tab = Table.from_file(path)
        shape = "x".join(str(len(a["nodes"])) for a in tab.axes)
        print(f"{path.name:28s} {path.stat().st_size / 1024:8.1f} KiB  grid {shape}, "
              f"{len(tab.variables)} variables")


def exact_lookups(args):
    """The exact table: the public scalar call, the FMU step (forces, moment, stick area and
    Jacobian in one evaluation), batches, against the bare compiled spline kernel on
    precomputed coordinates (the limit: no input checks, no physics)."""
    from numba import njit

    from railcontact._exact_kernels import spline_point as _spline_point
    from railcontact.exact_table import SLAB_AFTER_POINTS, exact_table_coordinates
    from railcontact.kalker import kalker_coefficients

    ex = ExactCreepTable.from_file()
    print(f"\n== exact table {ex.path.name}: grid "
          + "x".join(str(len(a["nodes"])) for a in ex.table.axes) + " ==")
    print(load_memory())
    xi, eta, phi, n_load, a0, b0, e_mod, nu, mu = args
    c = kalker_coefficients(a0 / b0, nu)
    w_sat = np.pi * (1 + nu) * mu * 1.5 * n_load / (a0 * b0 * e_mod)
    coords = [float(v) for v in exact_table_coordinates(xi, eta, phi, a0, b0, nu, w_sat,
                                                        (c.c11, c.c22, c.c23))]
    slab = ex._slab_of(coords[0], coords[1])
    out, work = np.empty((4, 4)), np.empty(336)
    knots, poly = ex._knot_list, ex._poly_list
    _spline_point(ex._coef, slab, True, *knots, *poly, *coords, True, out, work)
    bare = _spline_point.overloads[_spline_point.signatures[0]].entry_point
    calls = {"bare": lambda: bare(ex._coef, slab, True, *knots, *poly, *coords, True, out,
                                  work),
             "step": lambda: ex.step(*args),
             "method": lambda: ex.creep_force_3d(*args),
             "api": lambda: creep_force_3d(*args, method="exact_table"),
             "python": _host_probe}
    for _ in range(SLAB_AFTER_POINTS):      # the contact's buffer, as in a co-simulation
        calls["api"]()
    best, median, slow = interleaved(calls, SCALAR_WINDOW)
    t_bare, t_step, t_ex, t_api = best["bare"], best["step"], best["method"], best["api"]
    print(f"(scalar calls: the best of {SCALAR_WINDOW:.0f} s of rounds in turn, median in "
          f"brackets; the host was slow in {slow:.0%} of the rounds, see interleaved)")
    print(f"bare compiled spline point (limit)         : {t_bare * 1e6:7.2f} us "
          f"({median['bare'] * 1e6:.2f}; 4 variables + 3 partials, contact's slab)")
    print(f"ExactCreepTable.step (FMU: all + Jacobian)  : {t_step * 1e6:7.2f} us "
          f"({median['step'] * 1e6:.2f})")
    print(f"ExactCreepTable.creep_force_3d (scalar)    : {t_ex * 1e6:7.2f} us "
          f"({median['method'] * 1e6:.2f})")
    print(f"creep_force_3d(method='exact_table')       : {t_api * 1e6:7.2f} us "
          f"({median['api'] * 1e6:.2f}; {t_api / t_bare:.1f}x the bare kernel)")
    print(f"  a pure-Python loop (the host's speed)    : {best['python'] * 1e6:7.2f} us "
          f"({median['python'] * 1e6:.2f})")
    # a contact whose a0/b0 changes at every call (a wheel profile's contact): the kernel of
    # any contact (the 5-D spline); a contact's buffer (the table summed over a0/b0 and nu)
    # is made only once the contact has been asked for SLAB_AFTER_POINTS points
    moving = ExactCreepTable.from_file()
    a0s = [float(v) for v in a0 * (1.0 + 0.01 * np.random.default_rng(3).standard_normal(
        50_000))]
    rest = list(args)

    def run_moving():
        for v in a0s:
            rest[4] = v
            moving.step_values(*rest)

    run_moving()
    t_mov = min(timeit.repeat(run_moving, number=1, repeat=3)) / len(a0s)
    print(f"ExactCreepTable.step, a0/b0 new each call  : {t_mov * 1e6:7.2f} us "
          f"({t_mov / t_step:.1f}x a kept contact; {len(moving._buffers)} buffers made)")
    t_slab = per_call(lambda: ex._slab_of(coords[0] + 1e-9, coords[1]), 3)
    print(f"  a contact's buffer (its slab), made once : {t_slab * 1e3:7.2f} ms = "
          f"{t_slab / max(t_mov - t_step, 1e-9):.0f} steps' extra cost "
          f"(made after {SLAB_AFTER_POINTS} points)")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        t_sol = per_call(lambda: creep_force_3d(*args, method="exact"), 3)
    print(f"creep_force_3d(method='exact') (default)   : {t_sol * 1e6:7.0f} us "
          f"-> the table is {t_sol / t_api:.0f}x faster")

    @njit(cache=False)
    def bare_batch(coef, slab, t0, t1, t2, t3, t4, p0, p1, p2, p3, p4, pts, res):
        out = np.empty((4, 4))
        work = np.empty(336)
        for i in range(pts.shape[0]):
            _spline_point(coef, slab, True, t0, t1, t2, t3, t4, p0, p1, p2, p3, p4, pts[i, 0],
                          pts[i, 1], pts[i, 2], pts[i, 3], pts[i, 4], False, out, work)
            for v in range(4):
                res[i, v] = out[0, v]

    rng = np.random.default_rng(0)
    n = 100_000
    xs, ys = rng.uniform(-3e-3, 3e-3, (2, n))
    ps = rng.uniform(-1.0, 1.0, n)
    cs = exact_table_coordinates(xs, ys, ps, a0, b0, nu, w_sat, (c.c11, c.c22, c.c23))
    pts = np.ascontiguousarray(np.column_stack(np.broadcast_arrays(*cs)))
    res = np.empty((n, 4))
    t_bb = per_call(lambda: bare_batch(ex._coef, slab, *knots, *poly, pts, res), 1)
    print(f"bare compiled spline batch (limit)         : {t_bb / n * 1e9:7.1f} ns/point "
          "(4 variables, no partials, on precomputed coordinates)")
    import numba

    from railcontact import _compiled

    t_b = per_call(lambda: ex.creep_force_3d(xs, ys, ps, n_load, a0, b0, e_mod, nu, mu), 1)
    print(f"creep_force_3d batch, one contact          : {t_b / n * 1e9:7.1f} ns/point "
          f"({t_b / t_bb:.2f}x the bare kernel; on {numba.get_num_threads()} numba threads)")
    entry = ex._buffers.get((a0 / b0, nu)) or ex._buffer(a0 / b0, nu)
    serial = _compiled.exact_kernels().creep_contact_batch
    r14, ok = np.empty((n, 14)), np.empty(n, dtype=bool)
    t_s = per_call(lambda: serial(entry[0], xs, ys, ps, n_load, a0, b0, e_mod, mu, False, r14,
                                  ok), 1)
    print(f"  its kernel on one thread                 : {t_s / n * 1e9:7.1f} ns/point "
          f"({t_s / t_bb:.2f}x the bare kernel: the physics and the coordinates)")
    t_bj = per_call(lambda: ex.creep_solution_3d(xs, ys, ps, n_load, a0, b0, e_mod, nu, mu), 1)
    print(f"creep_solution_3d batch + Jacobian         : {t_bj / n * 1e9:7.1f} ns/point")
    a0s = rng.uniform(3e-3, 8e-3, n)
    nus = rng.uniform(0.0, 0.5, n)
    t_bv = per_call(lambda: ex.creep_force_3d(xs, ys, ps, n_load, a0s, b0, e_mod, nus, mu), 1)
    print(f"creep_force_3d batch, every point its own  : {t_bv / n * 1e9:7.1f} ns/point "
          "contact (5-D evaluation)")


def builds(full):
    from tablegen.build import build_table
    from tablegen.registry import REGISTRY
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
