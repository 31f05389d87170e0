#!/usr/bin/env python
r"""Memory of the exact table as users meet it: sweeps, many FMU instances, one API process.

    python benchmarks/bench_memory.py [--fmu PATH] [--checkout DIR --checkout-fmu PATH]
                                      [--calls N] [--only PART ...]

Every figure is measured in a fresh child process and read from the kernel's own accounting of
that process (``/proc/self/status``: ``VmHWM``, the peak resident set, and ``VmRSS``), so it is
what the user's process pays, imports included:

``sweep``
    ``fmpy.simulate_fmu`` of the FMU's default scene (the exact table), 10 steps, called in a
    loop in one Python process, the way fmpy users script parameter studies: the resident set
    after 2 warm-up calls and after ``--calls`` more; the growth per call (target <= 4 MB,
    goal 0.5 MB, PythonFMU's own); ``sweep-trivial``: the same loop on a trivial PythonFMU
    slave of the same interface size (benchmarks/bench_fmu.py's), what PythonFMU costs.
``fmpy-K``, ``libcosim-K``
    K instances of the default scene in one process (K = 1, 8, 16; one per wheel/rail
    contact of a vehicle), each initialised and stepped 10 times: the peak (target for 8
    libcosim instances <= 800 MB, goal 400 MB).
``api``
    a Python process that imports railcontact and calls ``creep_force_3d(...,
    method="exact_table")`` on 20 contacts (scalars and a 10,001-point array): the peak
    (target <= 300 MB, goal 150 MB), once numba's cache holds the kernels (one process runs
    first to fill it: from a checkout, the very first run compiles, and LLVM's memory then
    counts too; a wheel ships its kernels compiled).
``load-warm``, ``load-cold``
    ``load_exact_table()`` in a fresh process, the user cache warm, and empty
    (``RAILCONTACT_CACHE_DIR`` a new directory: the table is decompressed and the cache
    entry written); best of 3 processes (target warm <= 0.3 s): the call alone, and the whole
    process (interpreter start, imports, load).

``--checkout DIR`` (with ``--checkout-fmu``, that checkout's FMU) measures another checkout
beside this one in the same run, e.g. the commit before a change: the two columns are then
comparable (same machine, same moment). Figures: docs/performance.md.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import textwrap
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

_STATUS = '''
def _status():
    out = {}
    for line in open("/proc/self/status"):
        key, _, value = line.partition(":")
        if key in ("VmHWM", "VmRSS"):
            out[key] = int(value.split()[0]) / 1024.0
    return out
'''

SWEEP = _STATUS + '''
import json, sys, warnings
from fmpy import simulate_fmu
warnings.simplefilter("ignore")
fmu, calls = sys.argv[1], int(sys.argv[2])
def run():
    simulate_fmu(fmu, stop_time=0.01, step_size=0.001, output_interval=0.001)
run(); run()
warm = _status()["VmRSS"]
for _ in range(calls):
    run()
end = _status()
print(json.dumps(dict(warm=warm, end=end["VmRSS"], peak=end["VmHWM"],
                      per_call=(end["VmRSS"] - warm) / calls)))
'''

FMPY_K = _STATUS + '''
import json, shutil, sys, tempfile, warnings
from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave
warnings.simplefilter("ignore")
fmu, k = sys.argv[1], int(sys.argv[2])
md = read_model_description(fmu)
refs = {v.name: v.valueReference for v in md.modelVariables}
slaves, dirs = [], []
for i in range(k):           # one extraction per instance, as importers do
    d = extract(fmu)
    dirs.append(d)
    s = FMU2Slave(guid=md.guid, unzipDirectory=d, modelIdentifier=md.coSimulation.modelIdentifier,
                  instanceName=f"contact{i}")
    s.instantiate()
    s.setupExperiment(startTime=0.0)
    s.enterInitializationMode()
    s.exitInitializationMode()
    slaves.append(s)
for step in range(10):
    for i, s in enumerate(slaves):
        s.setReal([refs["normal_force"], refs["creepage_longitudinal"], refs["spin"]],
                  [8e4 + 1e3 * i, 1e-3 * (step - 5), 0.1 * i])
        s.doStep(currentCommunicationPoint=step * 1e-3, communicationStepSize=1e-3)
        s.getReal([refs["Fx"], refs["Fy"]])
print(json.dumps(dict(peak=_status()["VmHWM"])))
import os
os._exit(0)     # (PythonFMU frees its interpreter guard twice at exit: docs/fmu_lifecycle.md)
'''

LIBCOSIM_K = _STATUS + '''
import json, sys
from libcosimpy.CosimExecution import CosimExecution
from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
from libcosimpy.CosimManipulator import CosimManipulator
from libcosimpy.CosimSlave import CosimLocalSlave
log_output_level(CosimLogLevel.ERROR)
fmu, k = sys.argv[1], int(sys.argv[2])
execution = CosimExecution.from_step_size(int(1e6))
manipulator = CosimManipulator.create_override()
execution.add_manipulator(manipulator)
slaves = []
for i in range(k):
    index = execution.add_local_slave(CosimLocalSlave(fmu_path=fmu, instance_name=f"contact{i}"))
    refs = {v.name.decode(): v.reference for v in execution.slave_variables(index)}
    slaves.append((index, refs))
for step in range(10):
    for i, (index, refs) in enumerate(slaves):
        manipulator.slave_real_values(index, [refs["normal_force"], refs["creepage_longitudinal"]],
                                      [8e4 + 1e3 * i, 1e-3 * (step - 5)])
    assert execution.step(), "step failed"
print(json.dumps(dict(peak=_status()["VmHWM"])))
import os
os._exit(0)
'''

API = _STATUS + '''
import json
import numpy as np
import railcontact as rc
rng = np.random.default_rng(0)
kw = dict(youngs_modulus=210e9, poisson_ratio=0.28, friction_coefficient=0.3,
          method="exact_table")
for k in range(20):         # 20 contacts (a0/b0 0.3-3), scalars
    g = float(np.exp(rng.uniform(np.log(0.3), np.log(3.0))))
    for _ in range(50):
        rc.creep_force_3d(creepage_longitudinal=float(rng.normal(0, 2e-3)),
                          creepage_lateral=float(rng.normal(0, 2e-3)),
                          spin=float(rng.normal(0, 0.5)), normal_load=8e4,
                          a0=6e-3 * g ** 0.5, b0=6e-3 / g ** 0.5, **kw)
xi = np.linspace(-5e-3, 5e-3, 10001)
rc.creep_force_3d(creepage_longitudinal=xi, creepage_lateral=0.0, spin=0.2, normal_load=8e4,
                  a0=6e-3, b0=5e-3, **kw)
print(json.dumps(dict(peak=_status()["VmHWM"])))
'''

LOAD = '''
import json, time
t0 = time.perf_counter()
from railcontact.creep3d import load_exact_table
import railcontact.exact_table, railcontact.tables     # (imports not counted)
t1 = time.perf_counter()
load_exact_table()
t2 = time.perf_counter()
print(json.dumps(dict(load=t2 - t1, imports=t1 - t0)))
'''


def child(code, *args, checkout=ROOT, env=None):
    """Run ``code`` in a fresh Python process with ``checkout``'s package first on the path;
    its last stdout line, parsed as JSON, with ``wall``: the whole process's wall time
    (interpreter start and imports included). [s]"""
    environ = dict(os.environ, **(env or {}))
    environ["PYTHONPATH"] = os.pathsep.join([str(Path(checkout) / "fmu_src"), str(checkout)])
    environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    start = time.perf_counter()
    done = subprocess.run([sys.executable, "-c", textwrap.dedent(code), *map(str, args)],
                          capture_output=True, text=True, env=environ, cwd=tempfile.gettempdir(),
                          timeout=1800)
    wall = time.perf_counter() - start
    lines = [ln for ln in done.stdout.splitlines() if ln.startswith("{")]
    if done.returncode != 0 or not lines:
        return {"error": (done.stderr.strip().splitlines() or ["?"])[-1][:200]}
    return dict(json.loads(lines[-1]), wall=wall)


def trivial_fmu(directory):
    """A trivial PythonFMU slave with the FMU's interface size (benchmarks/bench_fmu.py's):
    what PythonFMU itself costs."""
    import importlib.util  # noqa: PLC0415

    from pythonfmu.builder import FmuBuilder  # noqa: PLC0415

    spec = importlib.util.spec_from_file_location("bench_fmu", ROOT / "benchmarks" /
                                                  "bench_fmu.py")
    bench_fmu = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(bench_fmu)
    script = Path(directory) / "trivialcontact_bench.py"
    script.write_text(bench_fmu.TRIVIAL)
    return FmuBuilder.build_FMU(script, dest=Path(directory) / "TrivialContact.fmu")


def measure(checkout, fmu, parts, calls):
    out = {}
    if "sweep" in parts:
        out["sweep"] = child(SWEEP, fmu, calls, checkout=checkout)
        with tempfile.TemporaryDirectory() as work:
            out["sweep-trivial"] = child(SWEEP, trivial_fmu(work), calls, checkout=checkout)
    for k in (1, 8, 16):
        if "fmpy" in parts:
            out[f"fmpy-{k}"] = child(FMPY_K, fmu, k, checkout=checkout)
        if "libcosim" in parts:
            out[f"libcosim-{k}"] = child(LIBCOSIM_K, fmu, k, checkout=checkout)
    if "api" in parts:
        child(API, checkout=checkout)      # (numba's cache filled: a first run compiles)
        out["api"] = child(API, checkout=checkout)
    if "load" in parts:
        child(LOAD, checkout=checkout)         # (fills the user cache: the warm case)
        warm = [child(LOAD, checkout=checkout) for _ in range(3)]
        out["load-warm"] = min(warm, key=lambda r: r.get("load", 1e9))
        cold = []
        for _ in range(3):
            with tempfile.TemporaryDirectory() as cache:
                cold.append(child(LOAD, checkout=checkout,
                                  env={"RAILCONTACT_CACHE_DIR": cache}))
        out["load-cold"] = min(cold, key=lambda r: r.get("load", 1e9))
    return out


def figure(name, result):
    if "error" in result:
        return f"error: {result['error']}"
    if name.startswith("sweep"):
        return (f"{result['per_call']:7.2f} MB/call (RSS {result['warm']:.0f} -> "
                f"{result['end']:.0f} MB, peak {result['peak']:.0f} MB)")
    if name.startswith("load"):
        return f"{result['load']:6.3f} s (whole process {result['wall']:5.2f} s)"
    return f"{result['peak']:7.0f} MB peak"


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--fmu", default=str(ROOT / "WheelRailContact.fmu"))
    parser.add_argument("--checkout", help="another checkout, measured beside this one")
    parser.add_argument("--checkout-fmu", help="that checkout's FMU")
    parser.add_argument("--calls", type=int, default=10, help="sweep calls after the warm-up")
    parser.add_argument("--only", nargs="*", default=["sweep", "fmpy", "libcosim", "api", "load"])
    args = parser.parse_args(argv)
    columns = [("this checkout", ROOT, args.fmu)]
    if args.checkout:
        columns.insert(0, ("--checkout", Path(args.checkout), args.checkout_fmu or str(
            Path(args.checkout) / "WheelRailContact.fmu")))
    results = [(label, measure(path, fmu, set(args.only), args.calls))
               for label, path, fmu in columns]
    names = list(results[-1][1])
    print(f"{'':14s}" + "".join(f"{label:>44s}" for label, _ in results))
    for name in names:
        print(f"{name:14s}" + "".join(f"{figure(name, r.get(name, {'error': '-'})):>44s}"
                                      for _, r in results))
    return 0


if __name__ == "__main__":
    sys.exit(main())
