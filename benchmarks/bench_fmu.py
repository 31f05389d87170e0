#!/usr/bin/env python
r"""Speed and memory of the WheelRailContact FMU, measured through fmpy's FMI 2.0 API.

    python benchmarks/bench_fmu.py [--long N] [--fmu PATH]

For every bundled scene (``examples/scenes/*.toml``), plus a normal-contact-only scene and a
trivial PythonFMU slave with the same interface (6 Real inputs, 9 Real outputs, ``do_step``
copies numbers), all in the same run:

* ``doStep``: microseconds per ``fmi2DoStep`` with the inputs changing every step (the inputs
  are set before the timed call, outside the timing);
* ``step+Fx,Fy``: microseconds per ``fmi2SetReal`` (6 inputs) + ``fmi2DoStep`` +
  ``fmi2GetReal`` of Fx and Fy only, what a master pays per step when it uses only the forces;
* ``step+all``: the same with ``fmi2GetReal`` of all Real outputs each step (the stick-zone
  outputs, which the creep effect computes only when read, included);
* the non-steady correction's cost: ``creep_only_analytic`` and ``creep_only_table`` also with
  ``[effects.nonsteady]`` on, ``nonsteady_creep`` also with it off (printed as pairs).

Each scene is timed in ``--rounds`` rounds interleaved with rounds of the trivial slave (kept
loaded), and each figure is the best round: the ratio to the trivial slave compares times taken
under the same machine load. The target is <= 2 for the creep-only scene from the tables.
``--long N`` runs the table scene for N steps (default 1e6) with inputs sweeping
the hard regions (N through 0, creepage past saturation, large spin) and reports the resident
set size at 1e5 steps and at the end, and the peak.

``--cold-start`` measures instead, for every scene that reads a table, what a fresh process
pays from a fresh extraction (what ``fmpy.simulate_fmu`` does in a new interpreter) with the
user's numba cache warm (one run first fills it): ``fmi2Instantiate`` (Python imports the
slave and the package), setup + initialisation (the scene, the effects, the tables), the
first ``doStep``, best of ``--rounds`` processes (at most 5); and which numba functions of
the package were loaded from the cache or compiled during initialisation (the target:
setup plus initialisation <= 0.3 s).
"""

from __future__ import annotations

import argparse
import gc
import math
import resource
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT / "fmu_src")]

TRIVIAL = '''
from pythonfmu import Fmi2Slave, Fmi2Causality, Real

INPUTS = ["normal_force", "creepage_longitudinal", "creepage_lateral", "spin",
          "rolling_speed", "rail_position"]
OUTPUTS = ["Fx", "Fy", "a0", "b0", "p0", "stick_area_fraction", "stick_width_ratio", "r_a0",
           "extra"]


class TrivialContact(Fmi2Slave):
    """Same interface size as WheelRailContact; do_step only copies numbers."""

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        for name in INPUTS:
            setattr(self, name, 0.0)
            self.register_variable(Real(name, causality=Fmi2Causality.input))
        for name in OUTPUTS:
            setattr(self, name, 0.0)
            self.register_variable(Real(name, causality=Fmi2Causality.output))

    def do_step(self, current_time, step_size):
        self.Fx = -self.creepage_longitudinal
        self.Fy = -self.creepage_lateral
        return True
'''

INPUT_NAMES = ["normal_force", "creepage_longitudinal", "creepage_lateral", "spin",
               "rolling_speed", "rail_position"]


def _rss_mb():
    with open("/proc/self/statm") as f:
        pages = int(f.read().split()[1])
    return pages * resource.getpagesize() / 2**20


def _peak_mb():
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


class Instance:
    def __init__(self, fmu, workdir, scene_file=None, scene_toml=None):
        from fmpy import extract, read_model_description
        from fmpy.fmi2 import FMU2Slave

        md = read_model_description(str(fmu))
        self.unzip = extract(str(fmu), str(workdir))
        self.fmu = FMU2Slave(guid=md.guid, unzipDirectory=self.unzip,
                             modelIdentifier=md.coSimulation.modelIdentifier,
                             instanceName="bench")
        vr = {v.name: v.valueReference for v in md.modelVariables}
        self.inputs = [vr[n] for n in INPUT_NAMES]
        self.outputs = [v.valueReference for v in md.modelVariables
                        if v.causality == "output" and v.type == "Real"]
        self.forces = [vr["Fx"], vr["Fy"]]
        f = self.fmu
        f.instantiate()
        f.setupExperiment(startTime=0.0)
        if scene_file is not None:
            f.setString([vr["scene_file"]], [str(scene_file)])
        if scene_toml is not None:
            f.setString([vr["scene_toml"]], [scene_toml])
        f.enterInitializationMode()
        f.exitInitializationMode()

    def close(self):
        self.fmu.terminate()
        self.fmu.freeInstance()


def _signals(n):
    k = np.arange(n)
    return np.column_stack([
        8e4 + 2e4 * np.sin(0.01 * k),                 # normal force [N]
        0.008 * np.sin(0.003 * k),                    # through saturation both ways
        0.002 * np.cos(0.007 * k),
        0.05 + 0.0 * k,
        30.0 + 0.0 * k,
        30.0 * 1e-3 * k]).tolist()


def time_steps(inst, n, h=1e-3, reads=None):
    """Microseconds per step, inputs changing every step: ``(doStep, step + I/O ...)``.

    The first item times ``fmi2DoStep`` alone (inputs set outside the timing; wall clock per
    call); then, for each list of value references in ``reads`` (default: all Real outputs),
    the whole ``fmi2SetReal`` (6 inputs) + ``fmi2DoStep`` + ``fmi2GetReal(reads)`` per step,
    timed over the loop in CPU time of this process (``time.process_time``: on a loaded
    machine the loop is often preempted, which CPU time does not count). The garbage
    collector is off during the timing, as ``timeit`` does it: its passes cost in proportion to
    everything the process holds (every scene loaded before), not to the step timed."""
    gc.collect()
    enabled = gc.isenabled()
    gc.disable()
    try:
        return _time_steps(inst, n, h, reads)
    finally:
        if enabled:
            gc.enable()


def _time_steps(inst, n, h, reads):
    f, ins = inst.fmu, inst.inputs
    reads = [inst.outputs] if reads is None else reads
    rows = _signals(n)
    do_step, set_real, get_real = f.doStep, f.setReal, f.getReal
    clock = time.perf_counter
    total = 0.0
    t = 0.0
    for row in rows:
        set_real(ins, row)
        t0 = clock()
        do_step(t, h)
        total += clock() - t0
        t += h
    timed = []
    cpu = time.process_time
    for read in reads:
        t0 = cpu()
        for row in rows:
            set_real(ins, row)
            do_step(t, h)
            get_real(read)
            t += h
        timed.append(1e6 * (cpu() - t0) / n)
    return (1e6 * total / n, *timed)


def long_run(fmu, workdir, scene, n_steps):
    inst = Instance(fmu, workdir, scene_file=scene)
    f, ins, outs = inst.fmu, inst.inputs, inst.outputs
    h, t = 1e-4, 0.0
    cycle = 10007
    k = np.arange(cycle)
    sweep = np.column_stack([
        np.maximum(0.0, 1e5 * np.sin(2 * math.pi * k / cycle)),      # includes N = 0
        0.05 * np.sin(2 * math.pi * 3 * k / cycle),                  # far beyond saturation
        0.01 * np.cos(2 * math.pi * 5 * k / cycle),
        5.0 * np.sin(2 * math.pi * 7 * k / cycle),                   # spin pole inside
        30.0 + 0.0 * k, 0.0 * k]).tolist()
    report = {}
    gc.collect()
    rss0 = _rss_mb()
    t_start = time.perf_counter()
    bad = 0
    for i in range(n_steps):
        f.setReal(ins, sweep[i % cycle])
        f.doStep(t, h)
        t += h
        if i % 1000 == 0:
            values = f.getReal(outs)
            bad += sum(not math.isfinite(v) for v in values)
        if i + 1 in (10**5, n_steps):
            report[i + 1] = _rss_mb()
    elapsed = time.perf_counter() - t_start
    inst.close()
    return rss0, report, _peak_mb(), elapsed, bad


# non-steady correction: per-step cost of the effect, the same scene with it on and off
_NONSTEADY_PAIRS = (("creep_only_analytic", "on"), ("creep_only_table", "on"),
                    ("nonsteady_creep", "off"))


def _nonsteady_label(stem, switch):
    return f"{stem} (nonsteady {switch})"


def _nonsteady_cases(fmu):
    """The bundled scenes of _NONSTEADY_PAIRS with the non-steady correction switched."""
    cases = []
    for stem, switch in _NONSTEADY_PAIRS:
        path = ROOT / "examples" / "scenes" / f"{stem}.toml"
        if not path.exists():
            continue
        text = path.read_text()
        text = (text + "\n[effects.nonsteady]\n" if switch == "on" else
                text.replace("[effects.nonsteady]\n", "[effects.nonsteady]\nenabled = false\n"))
        cases.append((_nonsteady_label(stem, switch), fmu,
                      {"scene_toml": text}))
    return cases


def _print_nonsteady_cost(results):
    step = {label: times[0] for label, _, times, _ in results}      # best doStep [us]
    lines = []
    for stem, switch in _NONSTEADY_PAIRS:
        other = step.get(_nonsteady_label(stem, switch))
        if other is None or stem not in step:
            continue
        on, off = (other, step[stem]) if switch == "on" else (step[stem], other)
        lines.append(f"  {stem:22s} off {off:9.2f} us  on {on:9.2f} us  (+{on - off:.2f} us, "
                     f"x {on / off:.2f})")
    if lines:
        print("\nnon-steady correction, doStep (best round) with it off / on (same run):")
        print("\n".join(lines))


_COLD_START = r"""
import sys, time
from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave

fmu, scene, where = sys.argv[1:4]
md = read_model_description(fmu)
vr = {v.name: v.valueReference for v in md.modelVariables}
unzip = extract(fmu, where)
t0 = time.perf_counter()
f = FMU2Slave(guid=md.guid, unzipDirectory=unzip, instanceName="cold",
              modelIdentifier=md.coSimulation.modelIdentifier)
f.instantiate()
t1 = time.perf_counter()
f.setupExperiment(startTime=0.0)
f.setString([vr["scene_file"]], [scene])
f.enterInitializationMode()
f.exitInitializationMode()
t2 = time.perf_counter()
f.setReal([vr["normal_force"], vr["creepage_longitudinal"], vr["rail_position"]],
          [8e4, 1e-3, 0.01])
f.doStep(0.0, 1e-3)
t3 = time.perf_counter()
loaded, compiled = [], []
numba = "numba" in sys.modules
CPUDispatcher = None
if numba:
    from numba.core.registry import CPUDispatcher
package = open(f"{unzip}/resources/slavemodule.txt").read().strip() + "_railcontact"
for name, module in list(sys.modules.items()):
    if CPUDispatcher is None or not name.startswith(package):
        continue
    for attr, value in vars(module).items():
        if isinstance(value, CPUDispatcher):
            where_from = (loaded if sum(value._cache_hits.values()) else
                          compiled if value.signatures else None)
            if where_from is not None:
                where_from.append(name.rpartition(".")[2] + "." + attr)
print("COLD", t1 - t0, t2 - t1, t3 - t2, ",".join(sorted(loaded)) or "-",
      ",".join(sorted(compiled)) or "-", numba)
f.terminate()
f.freeInstance()
"""


def cold_start(fmu, work, scenes, rounds):
    """Fresh process and extraction per run, warm user cache: best times and numba use."""
    print(f"{'scene':26s} {'instantiate':>11s} {'setup+init':>10s} {'1st step':>9s}   [s, best "
          f"of {rounds} processes]; numba functions loaded from the cache / compiled")
    for scene in scenes:
        best, info = [math.inf] * 3, None
        for k in range(rounds + 1):               # the first run warms the user cache
            proc = subprocess.run([sys.executable, "-c", _COLD_START, str(fmu), scene.stem,
                                   str(work / f"cold_{scene.stem}_{k}")],
                                  capture_output=True, text=True)
            if proc.returncode:
                raise RuntimeError(f"{scene.stem}: {proc.stderr[-2000:]}")
            line = [ln for ln in proc.stdout.splitlines() if ln.startswith("COLD ")][-1]
            fields = line.split()
            if k:
                best = list(map(min, best, map(float, fields[1:4])))
                info = fields[4:]
        loaded, compiled, numba = info
        print(f"{scene.stem:26s} {best[0]:11.3f} {best[1]:10.3f} {best[2]:9.4f}   "
              f"numba imported: {numba}; loaded: {loaded}; compiled: {compiled}")
    print("(target: setup+init <= 0.3 s from a fresh extraction with the user cache warm)")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--fmu", default=None, help="WheelRailContact.fmu (default: build)")
    parser.add_argument("--steps", type=int, default=20000,
                        help="steps per measurement (scenes slower than 100 us per step + all "
                             "outputs: steps/10)")
    parser.add_argument("--rounds", type=int, default=20,
                        help="timed rounds per scene, interleaved with the trivial slave's; "
                             "the best round counts")
    parser.add_argument("--only", default=None, metavar="SUBSTRING",
                        help="only the scenes whose name contains SUBSTRING (and the trivial "
                             "slave)")
    parser.add_argument("--long", type=float, default=0, metavar="N",
                        help="also run N steps of the table scene and report memory")
    parser.add_argument("--cold-start", action="store_true",
                        help="only measure instantiation and initialisation of the table "
                             "scenes in fresh processes (see above)")
    args = parser.parse_args(argv)

    from pythonfmu.builder import FmuBuilder

    work = Path(tempfile.mkdtemp(prefix="bench_fmu_"))
    try:
        if args.fmu:
            fmu = Path(args.fmu)
        else:
            sys.path.insert(0, str(ROOT))
            import build_fmu
            fmu = build_fmu.build(work)
        if args.cold_start:
            scenes = [p for p in sorted((ROOT / "examples" / "scenes").glob("*.toml"))
                      if "source = \"table\"" in p.read_text()
                      and (not args.only or args.only in p.stem)]
            cold_start(fmu, work, scenes, min(args.rounds, 5))
            return 0
        script = work / "trivialcontact_bench.py"
        script.write_text(TRIVIAL)
        trivial = FmuBuilder.build_FMU(script, dest=work / "TrivialContact.fmu")

        cases = [("trivial PythonFMU slave", trivial, {})]
        cases.append(("normal contact only", fmu,
                      {"scene_toml": "[effects.creep]\nenabled = false\n"}))
        from railcontact.scene import load_scene
        from railcontact.tables import tables_directory
        for scene in sorted((ROOT / "examples" / "scenes").glob("*.toml")):
            creep = load_scene(scene).effects.get("creep", {})
            if creep.get("source") == "table" and not (
                    tables_directory() / f"{creep['table']}.nc").exists():
                print(f"skipping {scene.stem}: tables/{creep['table']}.nc is not built")
                continue
            cases.append((scene.stem, fmu, {"scene_file": scene}))
        cases += _nonsteady_cases(fmu)
        if args.only:
            cases = [c for c in cases if c[0] == "trivial PythonFMU slave" or args.only in c[0]]

        # The trivial slave stays loaded and is timed in rounds interleaved with each scene's,
        # so that each ratio compares times measured under the same machine load; each figure
        # is the best (minimum) of the rounds, the usual estimate of the undisturbed time.
        triv = Instance(trivial, work / "trivial")
        triv_reads = [triv.forces, triv.outputs]
        time_steps(triv, 500, reads=triv_reads)
        results = []
        for i, (label, path, kw) in enumerate(cases[1:]):
            inst = Instance(path, work / f"x{i}", **kw)
            reads = [inst.forces, inst.outputs]
            warm = time_steps(inst, 200, reads=reads)   # warm-up (numba dispatch, caches)
            n = args.steps if warm[2] < 100.0 else max(200, args.steps // 10)
            per_round = max(100, n // args.rounds)
            best, best_triv = [math.inf] * 3, [math.inf] * 3
            for _ in range(args.rounds):
                best_triv = list(map(min, best_triv, time_steps(triv, per_round,
                                                                reads=triv_reads)))
                best = list(map(min, best, time_steps(inst, per_round, reads=reads)))
            results.append((label, per_round * args.rounds, best, best_triv))
            inst.close()
        triv.close()

        overall = list(map(min, *(r[3] for r in results))) if len(results) > 1 else (
            results[0][3] if results else [math.nan] * 3)
        print(f"{'case':34s} {'steps':>6s} {'doStep':>8s} {'x triv':>7s} {'step+Fx,Fy':>11s} "
              f"{'x triv':>7s} {'step+all':>9s} {'x triv':>7s}   [us per step]")
        print(f"{'trivial PythonFMU slave (best)':34s} {'':6s} " + " ".join(
            f"{t:{w}.2f} {1.0:7.2f}" for t, w in zip(overall, (8, 11, 9))))
        for label, n, times, base in results:
            cols = " ".join(f"{t:{w}.2f} {t / b:7.2f}" for t, b, w in zip(times, base,
                                                                       (8, 11, 9)))
            print(f"{label:34s} {n:6d} {cols}")
        print("(x triv: against the trivial slave's rounds interleaved with that scene's)")
        table = [r for r in results if r[0] == "creep_only_table"]
        if table:
            ratio = table[0][2][0] / table[0][3][0]
            print(f"\ncreep-only scene from the tables: {ratio:.2f} x the trivial doStep "
                  f"(target <= 2): {'met' if ratio <= 2 else 'NOT met'}")

        coulomb = [r for r in results if r[0] == "creep_exact_table"]
        falling = [r for r in results if r[0] == "creep_exact_table_falling"]
        if coulomb and falling:
            # the two scenes' own times (each measured under its own rounds' load), and the
            # ratio of their ratios to the trivial slave (load-corrected)
            raw = falling[0][2][0] / coulomb[0][2][0]
            corr = (falling[0][2][0] / falling[0][3][0]) / (coulomb[0][2][0] / coulomb[0][3][0])
            print(f"falling friction on the exact table: {raw:.2f} x the Coulomb exact-table "
                  f"scene's doStep ({corr:.2f} x against the trivial slave's rounds; target "
                  f"<= 2): {'met' if max(raw, corr) <= 2 else 'NOT met'}")

        _print_nonsteady_cost(results)

        if args.long:
            n_long = int(args.long)
            rss0, rss, peak, elapsed, bad = long_run(
                fmu, work / "long", ROOT / "examples" / "scenes" / "creep_only_table.toml",
                n_long)
            print(f"\nlong run, creep_only_table, {n_long} steps in {elapsed:.1f} s "
                  f"({1e6 * elapsed / n_long:.1f} us/step incl. setReal), non-finite outputs "
                  f"sampled: {bad}")
            print(f"RSS before {rss0:.1f} MB; " + "; ".join(
                f"after {k} steps {v:.1f} MB" for k, v in sorted(rss.items()))
                + f"; peak {peak:.1f} MB")
    finally:
        shutil.rmtree(work, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
