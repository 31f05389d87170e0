"""The speed figures the documentation quotes, measured in one run and written to one place.

    python benchmarks/figures.py              # measure (under a minute), record, render
    python benchmarks/figures.py --render     # render docs/figures.md from the recorded run

Measures, in one process, the calls a user makes through the public API (each scalar call
timed in turn with the others for a window of wall time, best and median of rounds of
calls: :func:`bench_tables.interleaved`), a batch, the exact solver, and the whole-process
times a user waits for (import; a first exact-table call, user cache warm). Records them in
``benchmarks/data/figures.json`` and renders ``docs/figures.md`` from that record, which
README and docs link to instead of restating numbers. Asserts nothing.
"""

from __future__ import annotations

import argparse
import datetime as _dt
import json
import os
import platform
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
RECORD = ROOT / "benchmarks" / "data" / "figures.json"
PAGE = ROOT / "docs" / "figures.md"

#: The contact every scalar call is timed on: 100 kN, A' = 1.087, B' = 1.667 1/m (README).
CONTACT = dict(normal_load=100e3, youngs_modulus=210e9, poisson_ratio=0.28,
               friction_coefficient=0.3)
CREEPAGES = (1e-3, 2e-4, 0.1)          # xi_x [-], xi_y [-], phi [1/m]

#: What each timed call is, in the order the page lists them: key -> (call, what it gives).
CALLS = {
    "exact_table": ('rc.creep_force_3d(..., method="exact_table")',
                    "Kalker's exact theory from the shipped table, scalar inputs"),
    "exact_table_curve": ('rc.creep_force_3d(xi, ..., method="exact_table")',
                          "the same, xi an array of 5 creepages (the README's creep curve); "
                          "per call"),
    "exact_table_changing": ('rc.creep_force_3d(..., method="exact_table")',
                             "the same, scalar, with a0/b0 new at every call"),
    "exact_step": ("ExactCreepTable.step(...)",
                   "forces, Mz, stick area and the Jacobian (what the FMU calls)"),
    "strip_table": ("CreepTable.creep_force_3d(...)", "modified strip theory from its table"),
    "modified_strip": ('rc.creep_force_3d(..., method="modified_strip")',
                       "modified strip theory, closed form (the API's default method)"),
    "linear": ('rc.creep_force_3d(..., method="linear")', "Kalker's linear theory"),
    "python": (None, "a 10-step pure-Python loop: the host's speed, for comparison"),
}


def _git_revision():
    try:
        return subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short=12", "HEAD"],
                              capture_output=True, text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def _process_seconds(code, repeat=3):
    """Wall time of ``python -c code`` in fresh processes: (first, best) [s]."""
    env = dict(os.environ)
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        subprocess.run([sys.executable, "-c", code], check=True, env=env,
                       capture_output=True)
        times.append(time.perf_counter() - t)
    return times[0], min(times)


def measure(window):
    """Run the measurements; returns the record (a JSON-able dict)."""
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    import numpy as np  # noqa: PLC0415
    from bench_tables import _host_probe, interleaved  # noqa: PLC0415

    import railcontact as rc  # noqa: PLC0415
    from railcontact.exact_table import ExactCreepTable  # noqa: PLC0415
    from railcontact.strip_table import CreepTable  # noqa: PLC0415

    a0, b0, _ = rc.hertz_3d(100e3, 1.087, 1.667, 210e9, 0.28)
    a0, b0 = float(a0), float(b0)
    xi_x, xi_y, phi = CREEPAGES
    exact = ExactCreepTable.from_file()
    strip = CreepTable.from_file()
    args = (xi_x, xi_y, phi, CONTACT["normal_load"], a0, b0, CONTACT["youngs_modulus"],
            CONTACT["poisson_ratio"], CONTACT["friction_coefficient"])
    ratios = iter(np.tile(np.linspace(0.6, 1.6, 97), 10_000_000 // 97))

    def changing():
        return rc.creep_force_3d(xi_x, xi_y, phi, CONTACT["normal_load"], a0 * next(ratios), b0,
                                 CONTACT["youngs_modulus"], CONTACT["poisson_ratio"],
                                 CONTACT["friction_coefficient"], method="exact_table")

    curve = np.linspace(-2e-3, 2e-3, 5)
    calls = {
        "exact_table": lambda: rc.creep_force_3d(*args, method="exact_table"),
        "exact_table_curve": lambda: rc.creep_force_3d(curve, *args[1:], method="exact_table"),
        "exact_table_changing": changing,
        "exact_step": lambda: exact.step(*args),
        "strip_table": lambda: strip.creep_force_3d(*args),
        "modified_strip": lambda: rc.creep_force_3d(*args, method="modified_strip"),
        "linear": lambda: rc.creep_force_3d(*args, method="linear"),
        "python": _host_probe,
    }
    for fn in calls.values():       # compile, load, warm
        fn()
    best, median, slow = interleaved(calls, window, number=200)
    # a batch on one contact
    n = 100_000
    rng = np.random.default_rng(0)
    batch = dict(creepage_longitudinal=rng.uniform(-5e-3, 5e-3, n),
                 creepage_lateral=rng.uniform(-5e-3, 5e-3, n), spin=rng.uniform(-1, 1, n),
                 a0=a0, b0=b0, **CONTACT)
    rc.creep_force_3d(method="exact_table", **batch)
    t_batch = min(_timed(lambda: rc.creep_force_3d(method="exact_table", **batch))
                  for _ in range(3)) / n
    t_batch_strip = min(_timed(lambda: rc.creep_force_3d(method="modified_strip", **batch))
                        for _ in range(3)) / n
    # the exact solver at its default setting (the shape's set-up cached after the first)
    rc.creep_force_3d(*args, method="exact")
    t_solver = min(_timed(lambda: rc.creep_force_3d(*args, method="exact")) for _ in range(3))
    # whole processes (the user cache warm: run once above)
    call = (f"import railcontact as rc; rc.creep_force_3d({', '.join(map(repr, args))}, "
            "method='exact_table')")
    first_import, best_import = _process_seconds("import railcontact")
    first_call, best_call = _process_seconds(call)
    import numba  # noqa: PLC0415
    import scipy  # noqa: PLC0415

    return {
        "date": _dt.datetime.now(_dt.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
        "git": _git_revision(),
        "machine": {"cpus": os.cpu_count(), "load_average": [round(v, 2) for v in
                                                             os.getloadavg()],
                    "processor": platform.processor() or platform.machine(),
                    "python": platform.python_version(), "numpy": np.__version__,
                    "scipy": scipy.__version__, "numba": numba.__version__},
        "contact": {"a0": a0, "b0": b0, **CONTACT, "creepage_longitudinal": xi_x,
                    "creepage_lateral": xi_y, "spin": phi},
        "window_seconds": window,
        "slow_fraction": slow,
        "per_call_us": {k: {"best": best[k] * 1e6, "median": median[k] * 1e6} for k in calls},
        "batch_ns_per_point": {"exact_table": t_batch * 1e9,
                               "modified_strip": t_batch_strip * 1e9, "points": n},
        "exact_solver_ms": t_solver * 1e3,
        "process_seconds": {"import railcontact": [first_import, best_import],
                            "one exact_table call": [first_call, best_call]},
    }


def _timed(fn):
    t = time.perf_counter()
    fn()
    return time.perf_counter() - t


def _fmt_us(value):
    return f"{value:.2f} us" if value < 10 else f"{value:.0f} us" if value < 1000 else \
        f"{value / 1000:.2f} ms"


def render(record):
    """The text of docs/figures.md from a record of :func:`measure`."""
    m = record["machine"]
    per = record["per_call_us"]
    batch = record["batch_ns_per_point"]
    proc = record["process_seconds"]
    solver_ms = record["exact_solver_ms"]
    lines = [
        "# Speed figures",
        "",
        "<!-- generated by `python benchmarks/figures.py` from benchmarks/data/figures.json; "
        "do not edit -->",
        "",
        "The one place the documentation's speed figures live; the other pages link here. "
        f"Measured {record['date']} (git {record['git']}) on {m['cpus']} cores "
        f"({m['processor']}, load average {', '.join(map(str, m['load_average']))}), Python "
        f"{m['python']}, numpy {m['numpy']}, scipy {m['scipy']}, numba {m['numba']}. "
        "Rerun: `python benchmarks/figures.py` (under a minute); it writes the record and this "
        "page.",
        "",
        "## One call through the public API",
        "",
        "The README's contact (100 kN, a0 = {:.2f} mm, b0 = {:.2f} mm, xi = ({:g}, {:g}), phi = "
        "{:g} 1/m), scalar inputs, the calls timed in turn for {:g} s of wall time. *Best*: "
        "the call at the host's speed; *median*: a typical call here (this host was slow in "
        "{:.0f} % of the rounds).".format(
            record["contact"]["a0"] * 1e3, record["contact"]["b0"] * 1e3,
            record["contact"]["creepage_longitudinal"], record["contact"]["creepage_lateral"],
            record["contact"]["spin"], record["window_seconds"],
            100 * record["slow_fraction"]),
        "",
        "| call | what | best | median |",
        "|---|---|---|---|",
    ]
    for key, (call, what) in CALLS.items():
        lines.append(f"| {f'`{call}`' if call else ''} | {what} | {_fmt_us(per[key]['best'])} "
                     f"| {_fmt_us(per[key]['median'])} |")
    lines += [
        f"| `rc.creep_force_3d(..., method=\"exact\")` | Kalker's exact theory solved at its "
        f"default setting (30x20 -> 60x20, two shifted grids; the shape's set-up cached) | "
        f"{solver_ms:.1f} ms | |",
        "",
        f"The exact table answers {solver_ms * 1e3 / per['exact_table']['best']:,.0f} times "
        "faster than the solver it tabulates (best against best); the closed-form modified "
        f"strip theory takes {per['modified_strip']['best'] / per['exact_table']['best']:.0f} "
        "times as long as the exact table.",
        "",
        "## A batch (one call, arrays)",
        "",
        f"{batch['points']:,} random creepages and spins on one contact: "
        f"`method=\"exact_table\"` {batch['exact_table']:.0f} ns per point, "
        f"`method=\"modified_strip\"` {batch['modified_strip']:.0f} ns per point.",
        "",
        "## What a user waits for (whole processes)",
        "",
        "Fresh `python -c` processes, the user cache (numba kernels, decompressed tables) warm; "
        "first of three / best of three:",
        "",
        f"- `import railcontact`: {proc['import railcontact'][0]:.2f} / "
        f"{proc['import railcontact'][1]:.2f} s;",
        f"- `import railcontact` and one `method=\"exact_table\"` call (loads the 19 MB table): "
        f"{proc['one exact_table call'][0]:.2f} / {proc['one exact_table call'][1]:.2f} s.",
        "",
        "The FMU's step costs are measured against a trivial FMU in "
        "`python benchmarks/bench_fmu.py` ([performance](performance.md)); accuracy against "
        "time for every model: [accuracy_vs_time.md](accuracy_vs_time.md).",
        "",
        "Back to the [README](../README.md).",
        "",
    ]
    return "\n".join(lines)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--render", action="store_true",
                        help="only render docs/figures.md from the recorded run")
    parser.add_argument("--window", type=float, default=20.0,
                        help="wall time over which the scalar calls are timed [s]")
    args = parser.parse_args(argv)
    if args.render:
        record = json.loads(RECORD.read_text(encoding="utf-8"))
    else:
        record = measure(args.window)
        RECORD.write_text(json.dumps(record, indent=1) + "\n", encoding="utf-8")
    PAGE.write_text(render(record), encoding="utf-8")
    print(render(record))
    return 0


if __name__ == "__main__":
    sys.exit(main())
