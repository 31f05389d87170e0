"""What a user waits for: whole processes (interpreter start and imports included), with an
empty and with a warm user cache.

Each figure is the wall time of a fresh ``python -c ...`` process, measured from outside
(``time.perf_counter`` around ``subprocess.run``), the median of ``--runs`` processes (min and
max printed too). "cold" gives every process a new empty ``RAILCONTACT_CACHE_DIR`` (a new
machine, user, CI runner or container: numba's kernels and the decompressed tables are not
there yet); "warm" runs them on one cache that a first, untimed process filled. The
interpreter's own start (``python -c pass``) is printed for reference, and each process's
own peak resident memory (the median of the runs; ``--only TEXT`` times the processes whose
label contains TEXT).

Usage (the figures of docs/performance.md: a wheel built from a fresh clone, installed in a
fresh virtual environment, run from another directory)::

    python -m pip wheel --no-deps -w dist .
    python -m venv /tmp/fresh && /tmp/fresh/bin/pip install dist/railcontact-*.whl
    cd /tmp && /tmp/fresh/bin/python /path/to/benchmarks/bench_first_call.py --runs 5

``--python`` times another interpreter than the one running this script (default: this
one). With an editable install (a checkout) the table kernels are numba's, compiled on first
use, so "cold" then includes their compilation: minutes (``--skip-cold`` leaves it out).

``--fmu [PATH]`` times instead the FMU's cold start as a co-simulation user waits for it: a
fresh process running ``fmpy.simulate_fmu`` for 10 steps of each table scene
(``examples/scenes``), against the same run of a trivial PythonFMU slave with the same
interface (``bench_fmu.TRIVIAL``), the two in turn (A B A B ...), so each difference compares
processes run under the same machine load; with an empty user cache per process ("cold") and
with a warm one. The figure is the median of the pairwise differences (targets: <= 0.5 s warm,
<= 2 s cold); the CPU seconds (user + system) of each process are printed too, the median of
the pairwise CPU differences for the FMU: on a loaded machine they stretch much less than wall
times. PATH defaults to the FMU built from this checkout
(``railcontact.fmu_build.cached_build``).
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time

CONTACT = ("kw = dict(normal_load=100e3, a0=6e-3, b0=4e-3, youngs_modulus=210e9, "
           "poisson_ratio=0.28, friction_coefficient=0.3)\n")

#: (label, code) of each timed process.
CASES = (
    ("python -c pass (interpreter start)", "pass"),
    ("import railcontact", "import railcontact"),
    ("from railcontact import *", "from railcontact import *"),
    ("import + exact table: scalar", "import railcontact as rc\n" + CONTACT
     + "rc.creep_force_3d(1e-3, 0.0, 0.0, method='exact_table', **kw)"),
    ("import + exact table: scalar, 10 and 10,001 points",
     "import numpy as np, railcontact as rc\n" + CONTACT
     + "rc.creep_force_3d(1e-3, 0.0, 0.0, method='exact_table', **kw)\n"
       "rc.creep_force_3d(np.linspace(-2e-3, 2e-3, 10), 0.0, 0.0, method='exact_table', **kw)\n"
       "rc.creep_force_3d(np.linspace(-2e-3, 2e-3, 10_001), 0.0, 0.0, method='exact_table', "
       "**kw)"),
    ("import + modified strip (default method): 10 points",
     "import numpy as np, railcontact as rc\n" + CONTACT
     + "rc.creep_force_3d(np.linspace(-2e-3, 2e-3, 10), 0.0, 0.0, **kw)"),
    ("import + first method='exact' call", "import railcontact as rc\n" + CONTACT
     + "rc.creep_solution_3d(1e-3, 0.0, 0.0, method='exact', **kw)"),
    ("import + exact table with Polach's law: scalar",
     "import railcontact as rc\nfrom railcontact.friction import PolachFriction\n" + CONTACT
     + "kw['friction_coefficient'] = PolachFriction(0.3, 0.4, 0.6)\n"
       "rc.creep_force_3d(1e-3, 0.0, 0.0, method='exact_table', rolling_speed=30.0, **kw)"),
    ("import + exact table with the smooth law (5.16): scalar",
     "import railcontact as rc\nfrom railcontact.friction import SmoothFriction\n" + CONTACT
     + "kw['friction_coefficient'] = SmoothFriction(0.3, 0.15, 300.0)\n"
       "rc.creep_force_3d(1e-3, 0.0, 0.0, method='exact_table', **kw)"),
)


#: A co-simulation user's whole process: 10 steps of 1 ms through fmpy (argv: the FMU, and
#: the scene's name or nothing for the trivial slave).
SIMULATE = """
import sys
from fmpy import simulate_fmu
simulate_fmu(sys.argv[1], start_time=0.0, stop_time=0.01, step_size=1e-3,
             output_interval=1e-3, start_values={"scene_file": sys.argv[2]} if sys.argv[2:] else {})
"""


def _run(python, code, cache, timeout, args=()):
    env = {k: v for k, v in os.environ.items() if k not in ("NUMBA_CACHE_DIR",)}
    env["RAILCONTACT_CACHE_DIR"] = cache
    env.setdefault("OPENBLAS_NUM_THREADS", "1")
    t0 = time.perf_counter()
    cpu0 = _children_cpu()
    out = subprocess.run([python, "-c", code + PEAK, *args], env=env, check=True,
                         capture_output=True, text=True, timeout=timeout).stdout
    wall = time.perf_counter() - t0
    _CPU.append(_children_cpu() - cpu0)
    _PEAK.append(float(out.rsplit("peak-rss-kib ", 1)[-1]) / 1024.0)
    return wall


#: Appended to each process's code: its own peak resident memory (Linux: KiB), the last line
#: of its output (the timed process includes this line: microseconds).
PEAK = ("\nimport resource as _r\nprint('peak-rss-kib', "
        "_r.getrusage(_r.RUSAGE_SELF).ru_maxrss)\n")
#: Peak resident memory of each process run, in order. [MiB]
_PEAK = []


#: CPU seconds (user + system) of each process run, in order: on a loaded machine the wall
#: time of a single-threaded process stretches with the load, its CPU time much less.
_CPU = []


def _children_cpu():
    import resource  # noqa: PLC0415

    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def fmu_cold_start(python, fmu, runs, timeout, tmp):
    """The FMU's table scenes against the trivial slave, whole processes, cold and warm."""
    from pathlib import Path  # noqa: PLC0415

    from pythonfmu.builder import FmuBuilder  # noqa: PLC0415

    from bench_fmu import TRIVIAL  # noqa: PLC0415

    root = Path(__file__).resolve().parents[1]
    if fmu is None:
        sys.path[:0] = [str(root / "fmu_src")]
        from railcontact.fmu_build import cached_build  # noqa: PLC0415

        fmu = cached_build()
    script = Path(tmp) / "trivialcontact_bench.py"
    script.write_text(TRIVIAL)
    trivial = FmuBuilder.build_FMU(script, dest=Path(tmp) / "TrivialContact.fmu")
    scenes = [p.stem for p in sorted((root / "examples" / "scenes").glob("*.toml"))
              if 'source = "table"' in p.read_text()]
    print(f"FMU {fmu}\nfmpy.simulate_fmu of 10 steps in a fresh process: each table scene "
          "against a trivial PythonFMU slave, in turn; the difference is the median of the "
          "pairs")
    for kind in ("warm", "cold"):
        warm = os.path.join(tmp, "fmu-warm")
        for scene in scenes:
            if kind == "warm":     # the untimed first process fills the cache
                _run(python, SIMULATE, warm, timeout, (str(fmu), scene))
            own, base, cpu = [], [], []
            for k in range(runs):
                cache = warm if kind == "warm" else os.path.join(tmp, f"fmu-{scene}-{k}")
                base.append(_run(python, SIMULATE, cache + "-trivial" * (kind == "cold"),
                                 timeout, (str(trivial),)))
                own.append(_run(python, SIMULATE, cache, timeout, (str(fmu), scene)))
                cpu.append(_CPU[-1] - _CPU[-2])
            diff = [a - b for a, b in zip(own, base)]
            print(f"{kind} {scene:<24s} {statistics.median(own):6.2f} s, trivial "
                  f"{statistics.median(base):5.2f} s: +{statistics.median(diff):.2f} s "
                  f"(min {min(diff):+.2f}, max {max(diff):+.2f}, {runs} pairs; CPU "
                  f"+{statistics.median(cpu):.2f} s; target {0.5 if kind == 'warm' else 2.0} "
                  "s)", flush=True)


def _row(label, times):
    cpu, peak = _CPU[-len(times):], _PEAK[-len(times):]
    return (f"{label:<56s} {statistics.median(times):8.2f} s  (min {min(times):.2f}, "
            f"max {max(times):.2f}, {len(times)} runs; CPU {statistics.median(cpu):.2f} s; "
            f"peak memory {statistics.median(peak):.0f} MiB)")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--python", default=sys.executable,
                        help="interpreter to time (default: this one)")
    parser.add_argument("--runs", type=int, default=5, help="processes per figure")
    parser.add_argument("--cold-runs", type=int, default=None,
                        help="processes per cold figure (default: --runs)")
    parser.add_argument("--skip-cold", action="store_true",
                        help="warm cache only (cold: minutes without the compiled kernels)")
    parser.add_argument("--timeout", type=float, default=900.0, help="per process [s]")
    parser.add_argument("--only", default="", metavar="TEXT",
                        help="time only the processes whose label contains TEXT")
    parser.add_argument("--fmu", nargs="?", const="", default=None, metavar="PATH",
                        help="time the FMU's table scenes against a trivial slave instead "
                             "(default PATH: the FMU built from this checkout)")
    args = parser.parse_args(argv)
    if args.fmu is not None:
        with tempfile.TemporaryDirectory(prefix="railcontact-bench-") as tmp:
            fmu_cold_start(args.python, args.fmu or None, args.runs, args.timeout, tmp)
        return
    where = subprocess.run([args.python, "-c", "import railcontact, railcontact._compiled as c;"
                            "print(railcontact.__file__, c.aot_module() is not None)"],
                           check=True, capture_output=True, text=True).stdout.split()
    print(f"python {args.python}\nrailcontact {where[0]}\ncompiled kernels (wheel) "
          f"{where[1]}\n")
    cases = [(label, code) for label, code in CASES if args.only in label]
    with tempfile.TemporaryDirectory(prefix="railcontact-bench-") as tmp:
        if not args.skip_cold:
            print("cold: a new empty user cache for every process")
            for i, (label, code) in enumerate(cases):
                times = []
                for k in range(args.cold_runs or args.runs):
                    cache = os.path.join(tmp, f"cold-{i}-{k}")
                    times.append(_run(args.python, code, cache, args.timeout))
                print(_row(label, times), flush=True)
        print("warm: one user cache, filled by an untimed first process")
        warm = os.path.join(tmp, "warm")
        for label, code in cases:
            _run(args.python, code, warm, args.timeout)
            times = [_run(args.python, code, warm, args.timeout) for _ in range(args.runs)]
            print(_row(label, times), flush=True)


if __name__ == "__main__":
    main()
