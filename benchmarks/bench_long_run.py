#!/usr/bin/env python
r"""Long FMU run through the hard regions: no NaN, no error, no memory growth.

    python benchmarks/bench_long_run.py [--steps 1e6] [--scene creep_only_analytic ...]
                                        [--fmu PATH]

Builds WheelRailContact.fmu (or uses ``--fmu``) and drives one instance per scene through
fmpy's FMI 2.0 API for ``--steps`` communication steps (default 10^6) with inputs that sweep
the hard regions of ``docs/hard_cases.md`` over and over (a cycle of 10007 steps, a prime, so
the phases of the signals drift against each other):

* normal force through 0 (a quarter of the cycle without contact, N = 0 exactly), up to
  150 kN, with 1e-300 N and 1e-10 N spikes;
* longitudinal creepage sweeping through zero in sign changes, far beyond saturation
  (|xi| up to 0.05, ~20 x the saturation creepage) and down to 1e-12 (log sweep);
* lateral creepage with its own sign changes; spin up to +-8 1/m (spin pole inside the patch,
  Phi >> 1) and exactly 0;
* rolling speed 0 ... 40 m/s (standstill included), rail position advancing.

Every step: ``fmi2SetReal`` (6 inputs), ``fmi2DoStep``, ``fmi2GetReal`` of Fx, Fy; checked
finite and ``math.hypot(Fx, Fy) <= mu N`` (correctly rounded hypot; excesses of less than
4 ulp are counted separately, see the Coulomb-bound row of the catalogue). Every 100 steps all Real outputs are read and checked
finite. Memory: resident set size after a 10^4-step warm-up, at 10^5 steps and at the end,
and the process peak (``ru_maxrss``). Exit status 1 if any NaN, FMI error or bound violation beyond rounding.

This takes minutes (about 1e6 x the per-step cost printed by ``bench_fmu.py``), so it is a
benchmark, not a test; ``tests/test_properties.py`` and ``tests/test_hard_cases.py`` check the
same regions with few steps.
"""

from __future__ import annotations

import argparse
import math
import os
import resource
import shutil
import sys
import tempfile
import time
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

import numpy as np  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT / "fmu_src"), str(ROOT)]

INPUTS = ["normal_force", "creepage_longitudinal", "creepage_lateral", "spin",
          "rolling_speed", "rail_position"]
CYCLE = 10007
EPS = float(np.finfo(float).eps)


def _rss_mb():
    with open("/proc/self/statm") as f:
        pages = int(f.read().split()[1])
    return pages * resource.getpagesize() / 2**20


def _peak_mb():
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def sweep(cycle=CYCLE):
    """One cycle of the hard-region inputs, shape (cycle, 6)."""
    k = np.arange(cycle)
    u = k / cycle
    two_pi = 2 * math.pi
    load = np.maximum(0.0, 1.5e5 * np.sin(two_pi * u) + 0.5e5)      # ~1/4 of the cycle N = 0
    load[::997] = 1e-300
    load[5::1009] = 1e-10
    # longitudinal creepage: far beyond saturation, through zero, and a log sweep to 1e-12
    xi_x = 0.05 * np.sin(two_pi * 3 * u) ** 3
    tiny = (u > 0.6) & (u < 0.8)
    xi_x[tiny] = np.sign(np.sin(two_pi * 50 * u[tiny])) * 10.0 ** (-12 + 9 * (u[tiny] - 0.6)
                                                                  / 0.2)
    xi_x[::503] = 0.0
    xi_y = 0.01 * np.cos(two_pi * 5 * u)
    spin = 8.0 * np.sin(two_pi * 7 * u)
    spin[::7] = 0.0
    speed = 20.0 + 20.0 * np.cos(two_pi * 2 * u)                      # 0 ... 40 m/s
    position = 0.03 * k
    return np.column_stack([load, xi_x, xi_y, spin, speed, position])


class Instance:
    def __init__(self, fmu, workdir, scene_file):
        from ctypes import byref

        from fmpy import calloc, extract, free, read_model_description
        from fmpy.fmi2 import (FMU2Slave, fmi2CallbackAllocateMemoryTYPE,
                               fmi2CallbackFreeMemoryTYPE, fmi2CallbackFunctions,
                               fmi2CallbackLoggerTYPE)
        from fmpy.logging import addLoggerProxy

        self.messages = []

        def logger(_env, _instance, status, _category, message):
            if len(self.messages) < 1000:
                self.messages.append((int(status), message.decode(errors="replace")))

        cb = fmi2CallbackFunctions()
        cb.logger = fmi2CallbackLoggerTYPE(logger)
        cb.allocateMemory = fmi2CallbackAllocateMemoryTYPE(calloc)
        cb.freeMemory = fmi2CallbackFreeMemoryTYPE(free)
        addLoggerProxy(byref(cb))
        self._cb = cb
        md = read_model_description(str(fmu))
        vr = {v.name: v.valueReference for v in md.modelVariables}
        self.unzip = extract(str(fmu), str(workdir))
        self.fmu = FMU2Slave(guid=md.guid, unzipDirectory=self.unzip,
                             modelIdentifier=md.coSimulation.modelIdentifier,
                             instanceName="long")
        self.inputs = [vr[n] for n in INPUTS]
        self.forces = [vr["Fx"], vr["Fy"]]
        self.outputs = [v.valueReference for v in md.modelVariables
                        if v.causality == "output" and v.type == "Real"]
        f = self.fmu
        f.instantiate(callbacks=cb, loggingOn=True)
        f.setupExperiment(startTime=0.0)
        f.setString([vr["scene_file"]], [str(scene_file)])
        f.enterInitializationMode()
        f.exitInitializationMode()

    def close(self):
        self.fmu.terminate()
        self.fmu.freeInstance()


def long_run(fmu, workdir, scene_file, n_steps, friction_coefficient, h=1e-4):
    from fmpy.fmi1 import FMICallException

    inst = Instance(fmu, workdir, scene_file)
    f = inst.fmu
    set_real, do_step, get_real = f.setReal, f.doStep, f.getReal
    ins, forces, outs = inst.inputs, inst.forces, inst.outputs
    rows = sweep().tolist()
    report = {"nonfinite": 0, "over_bound": 0, "over_by_rounding": 0, "errors": 0,
              "worst_ratio": 0.0}
    rss = {}
    t = 0.0
    warm = min(10_000, n_steps)
    t_start = time.perf_counter()
    for i in range(n_steps):
        row = rows[i % CYCLE]
        set_real(ins, row)
        try:
            do_step(t, h)
        except FMICallException as exc:
            report["errors"] += 1
            if report["errors"] == 1:
                report["first_error"] = (i, row, str(exc), inst.messages[-3:])
            break
        t += h
        fx, fy = get_real(forces)
        mag = math.hypot(fx, fy)
        if not math.isfinite(mag):
            report["nonfinite"] += 1
            report.setdefault("first_nonfinite", (i, row, fx, fy))
        limit = friction_coefficient * row[0]
        if mag > limit * (1.0 + 4.0 * EPS):
            report["over_bound"] += 1
            report.setdefault("first_over_bound", (i, row, fx, fy, limit))
        elif mag > limit:        # by < 4 ulp: the rounding-level case of docs/hard_cases.md
            report["over_by_rounding"] += 1
            report.setdefault("first_over_by_rounding", (i, row, fx, fy, limit))
        if limit > 0:
            report["worst_ratio"] = max(report["worst_ratio"], mag / limit)
        if i % 100 == 0:
            values = get_real(outs)
            bad = sum(not math.isfinite(v) for v in values)
            if bad:
                report["nonfinite"] += bad
                report.setdefault("first_nonfinite", (i, row, values))
        done = i + 1
        if done == warm:
            rss["warm-up 1e4"] = _rss_mb()
        if done in (10**5, n_steps):
            rss[f"{done:.0e}"] = _rss_mb()
    report["elapsed"] = time.perf_counter() - t_start
    report["steps"] = i + 1
    report["warnings"] = [m for s, m in inst.messages if s == 1]
    inst.close()
    return report, rss


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--fmu", default=None, help="WheelRailContact.fmu (default: build)")
    parser.add_argument("--steps", type=float, default=1e6, help="steps per scene")
    parser.add_argument("--scene", action="append", default=None,
                        help="bundled scene stem (repeatable); default: creep_only_analytic "
                             "and creep_only_table")
    args = parser.parse_args(argv)
    n_steps = int(args.steps)
    scenes = args.scene or ["creep_only_analytic", "creep_only_table"]

    from railcontact.scene import load_scene

    work = Path(tempfile.mkdtemp(prefix="bench_long_"))
    failed = False
    try:
        if args.fmu:
            fmu = Path(args.fmu)
        else:
            import build_fmu
            fmu = build_fmu.build(work)
        print(f"{n_steps} steps per scene, input cycle {CYCLE} steps; RSS in MB")
        for stem in scenes:
            scene_file = ROOT / "examples" / "scenes" / f"{stem}.toml"
            mu = load_scene(str(scene_file)).friction_coefficient
            report, rss = long_run(fmu, work / stem, scene_file, n_steps, mu)
            ok = not (report["nonfinite"] or report["over_bound"] or report["errors"])
            failed |= not ok
            growth = (rss.get(f"{n_steps:.0e}", float("nan")) - rss.get("1e+05", float("nan")))
            print(f"\n{stem}: {report['steps']} steps in {report['elapsed']:.1f} s "
                  f"({1e6 * report['elapsed'] / report['steps']:.1f} us/step incl. I/O)")
            print(f"  non-finite outputs: {report['nonfinite']}, |F| > mu N (1 + 4 eps): "
                  f"{report['over_bound']}, mu N < |F| <= mu N (1 + 4 eps): "
                  f"{report['over_by_rounding']}, FMI errors: {report['errors']}, "
                  f"max |F|/(mu N) - 1: {report['worst_ratio'] - 1:.3e}")
            print("  RSS: " + ", ".join(f"{k}: {v:.1f}" for k, v in rss.items())
                  + f"; growth 1e5 -> end: {growth:+.1f}; process peak {_peak_mb():.1f}")
            if report["warnings"]:
                print(f"  FMU warnings ({len(report['warnings'])}): {report['warnings'][:3]}")
            for key in ("first_error", "first_nonfinite", "first_over_bound",
                        "first_over_by_rounding"):
                if key in report:
                    print(f"  {key}: {report[key]}")
            print(f"  result: {'OK' if ok else 'FAILED'}")
    finally:
        shutil.rmtree(work, ignore_errors=True)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
