#!/usr/bin/env python
r"""A vehicle in one FMU: speed of the K-contact WheelRailContact FMU, every input changing.

    python benchmarks/bench_vehicle.py [--contacts 8] [--seconds 10] [--rounds 3]
                                       [--scene creep_exact_table] [--skip-libcosim]

All figures from one run, on one machine, under the same load:

1. **Step ratio** (this process, fmpy's ``FMU2Slave``): per step, ``fmi2SetReal`` of all
   K x 11 inputs (load, creepages, spin, speed, position, A', B', a0, b0, mu; every one changes
   at every step) + ``fmi2DoStep`` + ``fmi2GetReal`` of all forces (Fx, Fy, Mz of every
   contact), the K-contact FMU against the same loop on a trivial PythonFMU slave with the same
   variables (``do_step`` copies numbers), rounds interleaved, best round each. Target
   <= 4x, goal 2x.
2. **10 s of a vehicle at 1 ms** (10^4 steps), each in a fresh process, whole-process wall
   time (imports, FMU extraction, table load, the loop; what a user waits for) and the loop
   alone: the K-contact FMU in fmpy (``FMU2Slave`` loop, and ``fmpy.simulate_fmu`` with the
   signals as its input array) and in libcosim, against K single-contact instances in each,
   and the trivial slave in each (the host's own cost). Targets: <= 2 s in fmpy, <= 3 s in
   libcosim. libcosim two ways:

   * ``libcosim``: the inputs set from Python before every step through the override
     manipulator, the forces read through a last-value observer (the old recipe). libcosim
     itself spends about 9 us per variable set this way (``cosim_manipulator_slave_set_real``,
     measured without stepping: 1 variable 9 us, 88 variables 0.8 ms a call), and its
     last-value observer reads every variable of every slave after every step: this is
     the floor of that way, whatever the FMU does (the trivial slave's figure);
   * ``libcosim connected``: the inputs come from a second FMU (:func:`driver_fmu`, a
     PythonFMU playing the same signals: what the vehicle-dynamics model is in a real run),
     connected to the contact FMU's inputs, the forces connected back to it and recorded by
     a time-series observer, the run one ``step(n)`` call (``examples/vehicle_libcosim.py``).

The FMUs are built for the current sources (``build_fmu.py [--contacts K]``) into a cache
directory keyed by the source digest (as the tests do), so a second run builds nothing.
"""

from __future__ import annotations

import argparse
import gc
import json
import math
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT / "fmu_src"), str(ROOT)]

#: Per contact, in this order.
INPUTS = ("normal_force", "creepage_longitudinal", "creepage_lateral", "spin", "rolling_speed",
          "rail_position", "curvature_longitudinal", "curvature_lateral",
          "semi_axis_longitudinal", "semi_axis_lateral", "friction_coefficient")
FORCES = ("Fx", "Fy", "Mz")

TRIVIAL = '''
from pythonfmu import Fmi2Slave, Fmi2Causality, Real

CONTACTS = {contacts}
INPUTS = {inputs!r}
FORCES = {forces!r}


class TrivialVehicle(Fmi2Slave):
    """The vehicle FMU's inputs and forces; do_step copies numbers."""

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        for k in range(1, CONTACTS + 1):
            for name in INPUTS:
                self.register_variable(Real(f"{{name}}[{{k}}]", causality=Fmi2Causality.input,
                                            getter=lambda: 0.0, setter=lambda v: None))
        self.values = [0.0] * (3 * CONTACTS)
        for k in range(CONTACTS):
            for j, name in enumerate(FORCES):
                self.register_variable(Real(f"{{name}}[{{k + 1}}]",
                                            causality=Fmi2Causality.output,
                                            getter=lambda i=3 * k + j: self.values[i]))

    def do_step(self, current_time, step_size):
        self.values[0] = current_time
        return True
'''


DRIVER = '''
from pathlib import Path

import numpy as np
from pythonfmu import Fmi2Causality, Fmi2Slave, Real

CONTACTS = {contacts}
INPUTS = {inputs!r}
FORCES = {forces!r}


class VehicleSignals(Fmi2Slave):
    """The vehicle model's side of the vehicle FMU: its outputs are the contacts' inputs
    (name_k), played from resources/signals.npy (row j at t = j ms), its inputs the forces."""

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self.table = (np.load(Path(self.resources) / "signals.npy") if self.resources
                      else np.zeros((1, CONTACTS * len(INPUTS))))
        self.row = self.table[0].tolist()
        self.forces = [0.0] * (CONTACTS * len(FORCES))
        self.index = {{}}
        for k in range(CONTACTS):
            for j, name in enumerate(INPUTS):
                i = k * len(INPUTS) + j
                var = Real(f"{{name}}_{{k + 1}}", causality=Fmi2Causality.output,
                           getter=lambda i=i: self.row[i])
                self.register_variable(var)
                self.index[var.value_reference] = i
            for j, name in enumerate(FORCES):
                i = k * len(FORCES) + j
                self.register_variable(Real(f"{{name}}_{{k + 1}}", causality=Fmi2Causality.input,
                                            getter=lambda i=i: self.forces[i],
                                            setter=lambda v, i=i: self.forces.__setitem__(i, v)))

    def get_real(self, vrs):       # (a native model's cost: one list per call)
        index, row = self.index, self.row
        try:
            return [row[index[vr]] for vr in vrs]
        except KeyError:
            return super().get_real(vrs)

    def do_step(self, current_time, step_size):
        j = min(int(round((current_time + step_size) * 1e3)), len(self.table) - 1)
        self.row = self.table[j].tolist()
        return True
'''


def _name(name, k, contacts):
    return name if contacts == 1 else f"{name}[{k}]"


def signals(n, contacts, h=1e-3):
    """``(n, contacts, 11)``: every input of every contact changes at every step (a vehicle
    on a curving, undulating track: load, creepages, spin, curvatures and friction oscillate
    at contact-dependent frequencies)."""
    t = np.arange(n)[:, None] * h
    k = np.arange(contacts)[None, :]
    w = 2.0 * np.pi * (1.0 + 0.13 * k) * t
    out = np.empty((n, contacts, len(INPUTS)))
    out[..., 0] = 8e4 + 2e4 * np.sin(w)                       # N [N]
    out[..., 1] = 3e-3 * np.sin(3.0 * w)                      # through saturation
    out[..., 2] = 1.5e-3 * np.cos(2.0 * w)
    out[..., 3] = 0.2 * np.sin(w + k)                         # spin [1/m]
    out[..., 4] = 30.0 + 0.1 * np.sin(w)                      # V [m/s]
    out[..., 5] = 30.0 * t + 0.0 * k                          # rail position [m]
    out[..., 6] = 1.0 + 0.3 * np.sin(0.5 * w)                 # A' [1/m]
    out[..., 7] = 1.8 + 0.5 * np.cos(0.5 * w)                 # B' [1/m]
    out[..., 8] = 6e-3 + 1e-4 * np.sin(w)                     # a0, b0 (unused: curvatures)
    out[..., 9] = 5e-3 + 1e-4 * np.cos(w)
    out[..., 10] = 0.3 + 0.05 * np.sin(0.2 * w)               # mu
    return out


# --------------------------------------------------------------------------------------------
# building
# --------------------------------------------------------------------------------------------
def cached_fmu(contacts):
    """The WheelRailContact FMU for the current sources, built once per source state."""
    import build_fmu

    return build_fmu.cached_build(contacts, verbose=True)


def trivial_fmu(contacts, work):
    from pythonfmu.builder import FmuBuilder

    script = Path(work) / "trivialvehicle_bench.py"
    script.write_text(TRIVIAL.format(contacts=contacts, inputs=INPUTS, forces=FORCES))
    return Path(FmuBuilder.build_FMU(script, dest=Path(work) / "TrivialVehicle.fmu"))


def driver_fmu(contacts, n, work):
    """A PythonFMU playing :func:`signals` (``n`` rows) as outputs ``name_k`` and taking the
    forces ``Fx_k``, ``Fy_k``, ``Mz_k`` as inputs: what a vehicle-dynamics FMU connected to
    the contact FMU does (libcosim moves the values between them natively)."""
    from pythonfmu.builder import FmuBuilder

    work = Path(work)
    script = work / "vehiclesignals.py"
    script.write_text(DRIVER.format(contacts=contacts, inputs=INPUTS, forces=FORCES))
    np.save(work / "signals.npy", signals(n, contacts).reshape(n, -1))
    return Path(FmuBuilder.build_FMU(script, dest=work / "VehicleSignals.fmu",
                                     project_files=[work / "signals.npy"]))


# --------------------------------------------------------------------------------------------
# 1. the step ratio (this process)
# --------------------------------------------------------------------------------------------
class Instance:
    """An initialised FMU2Slave and the value references of the benchmark's variables."""

    def __init__(self, fmu, contacts, scene=None, name="bench"):
        from fmpy import extract, read_model_description
        from fmpy.fmi2 import FMU2Slave

        md = read_model_description(str(fmu))
        self.unzip = extract(str(fmu))
        self.fmu = FMU2Slave(guid=md.guid, unzipDirectory=self.unzip,
                             modelIdentifier=md.coSimulation.modelIdentifier,
                             instanceName=name)
        vr = {v.name: v.valueReference for v in md.modelVariables}
        self.inputs = [vr[_name(n, k, contacts)] for k in range(1, contacts + 1)
                       for n in INPUTS]
        self.forces = [vr[_name(n, k, contacts)] for k in range(1, contacts + 1)
                       for n in FORCES]
        f = self.fmu
        f.instantiate()
        f.setupExperiment(startTime=0.0)
        f.enterInitializationMode()
        if scene is not None and "scene_file" in vr:
            f.setString([vr["scene_file"]], [scene])
        f.exitInitializationMode()


def time_loop(instances, rows, h=1e-3):
    """CPU seconds of the loop: for each step, every instance gets its inputs
    (``fmi2SetReal``), steps and gives its forces; ``rows``: (n, instances, values)."""
    gc.collect()
    gc.disable()
    try:
        calls = [(i.fmu.setReal, i.inputs, i.fmu.doStep, i.fmu.getReal, i.forces)
                 for i in instances]
        t = 0.0
        t0 = time.process_time()
        for row in rows:
            for (set_real, ins, do_step, get_real, forces), values in zip(calls, row):
                set_real(ins, values)
                do_step(t, h)
                get_real(forces)
            t += h
        return time.process_time() - t0
    finally:
        gc.enable()


def step_ratio(vehicle, trivial, contacts, scene, rounds, n=1000):
    sig = signals(n, contacts)
    rows = [[row.ravel().tolist()] for row in sig]
    veh = Instance(vehicle, contacts, scene)
    triv = Instance(trivial, contacts)
    best_v = best_t = math.inf
    for _ in range(rounds):
        best_t = min(best_t, time_loop([triv], rows))
        best_v = min(best_v, time_loop([veh], rows))
    return 1e6 * best_v / n, 1e6 * best_t / n


# --------------------------------------------------------------------------------------------
# 2. 10 s of a vehicle (a fresh process each)
# --------------------------------------------------------------------------------------------
def _libcosim_connected(fmu, driver, contacts, n, scene):
    """libcosim with the inputs connected from the driver FMU (:func:`driver_fmu`) and the
    forces connected back to it and recorded by a time-series observer: one ``step(n)`` call,
    no Python of the host per step. Returns the loop's wall time."""
    from libcosimpy.CosimEnums import CosimVariableType
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
    from libcosimpy.CosimObserver import CosimObserver
    from libcosimpy.CosimSlave import CosimLocalSlave

    log_output_level(CosimLogLevel.ERROR)
    ex = CosimExecution.from_step_size(10**6)
    s = ex.add_local_slave(CosimLocalSlave(fmu_path=str(fmu), instance_name="contacts"))
    d = ex.add_local_slave(CosimLocalSlave(fmu_path=str(driver), instance_name="vehicle"))
    r = {v.name.decode(): v.reference for v in ex.slave_variables(s)}
    rd = {v.name.decode(): v.reference for v in ex.slave_variables(d)}
    if "scene_file" in r:
        ex.string_initial_value(s, r["scene_file"], scene)
    for k in range(1, contacts + 1):
        for nm in INPUTS:
            if ex.connect_real_variables(d, rd[f"{nm}_{k}"], s, r[_name(nm, k, contacts)]):
                raise SystemExit(f"libcosim: cannot connect {nm}_{k}")
        for nm in FORCES:
            if ex.connect_real_variables(s, r[_name(nm, k, contacts)], d, rd[f"{nm}_{k}"]):
                raise SystemExit(f"libcosim: cannot connect {nm}[{k}]")
    obs = CosimObserver.create_time_series(n + 10)
    ex.add_observer(obs)
    forces = [r[_name(nm, k, contacts)] for k in range(1, contacts + 1) for nm in FORCES]
    for ref in forces:
        obs.start_time_series(s, ref, CosimVariableType.REAL)
    t1 = time.perf_counter()
    if not ex.step(n):
        raise SystemExit("libcosim: a step failed")
    loop = time.perf_counter() - t1
    obs.time_series_real_samples(s, forces[0], 1, n)   # (the record is there)
    return loop


def child(mode, fmu, contacts, seconds, scene, driver=None):
    """One run in this (fresh) process; prints a JSON line with the loop's wall time."""
    n = int(round(seconds / 1e-3))
    sig = signals(n, contacts)
    single = mode.endswith("singles")
    t0 = time.perf_counter()
    if mode.startswith("fmpy-simulate"):
        import fmpy

        names = [_name(nm, k, contacts) for k in range(1, contacts + 1) for nm in INPUTS]
        data = np.zeros(n, dtype=[("time", float)] + [(nm, float) for nm in names])
        data["time"] = np.arange(n) * 1e-3
        flat = sig.reshape(n, -1)
        for j, nm in enumerate(names):
            data[nm] = flat[:, j]
        fmpy.simulate_fmu(str(fmu), stop_time=(n - 1) * 1e-3, step_size=1e-3,
                          output_interval=1e-3, input=data, start_values={"scene_file": scene},
                          output=[_name(nm, k, contacts) for k in range(1, contacts + 1)
                                  for nm in FORCES])
    elif mode.startswith("fmpy"):
        m = contacts if single else 1
        instances = [Instance(fmu, 1 if single else contacts, scene, name=f"c{i}")
                     for i in range(m)]
        rows = sig.reshape(n, m, -1).tolist()
        t1 = time.perf_counter()
        time_loop(instances, rows)
        loop = time.perf_counter() - t1
    elif mode.startswith("libcosim-connected"):
        loop = _libcosim_connected(fmu, driver, contacts, n, scene)
    else:   # libcosim, inputs through the override manipulator
        from libcosimpy.CosimExecution import CosimExecution
        from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
        from libcosimpy.CosimManipulator import CosimManipulator
        from libcosimpy.CosimObserver import CosimObserver
        from libcosimpy.CosimSlave import CosimLocalSlave

        log_output_level(CosimLogLevel.ERROR)
        ex = CosimExecution.from_step_size(10**6)
        m = contacts if single else 1
        k_in = 1 if single else contacts
        slaves = [ex.add_local_slave(CosimLocalSlave(fmu_path=str(fmu), instance_name=f"c{i}"))
                  for i in range(m)]
        refs = [{v.name.decode(): v.reference for v in ex.slave_variables(s)} for s in slaves]
        for s, r in zip(slaves, refs):
            if "scene_file" in r:
                ex.string_initial_value(s, r["scene_file"], scene)
        ins = [[r[_name(nm, k, k_in)] for k in range(1, k_in + 1) for nm in INPUTS]
               for r in refs]
        outs = [[r[_name(nm, k, k_in)] for k in range(1, k_in + 1) for nm in FORCES]
                for r in refs]
        manip = CosimManipulator.create_override()
        ex.add_manipulator(manip)
        obs = CosimObserver.create_last_value()
        ex.add_observer(obs)
        rows = sig.reshape(n, m, -1).tolist()
        t1 = time.perf_counter()
        for row in rows:
            for s, i, values in zip(slaves, ins, row):
                manip.slave_real_values(s, i, values)
            if not ex.step():
                raise SystemExit("libcosim: a step failed")
            for s, o in zip(slaves, outs):
                obs.last_real_values(s, o)
        loop = time.perf_counter() - t1
    if mode.startswith("fmpy-simulate"):
        loop = time.perf_counter() - t0
    print(json.dumps({"loop": loop}), flush=True)
    os._exit(0)     # (PythonFMU's exit handlers: docs/fmu_lifecycle.md; nothing left to do)


def whole_process(mode, fmu, contacts, seconds, scene, driver=None):
    t0 = time.perf_counter()
    extra = ["--driver", str(driver)] if driver is not None else []
    proc = subprocess.run([sys.executable, __file__, "--child", mode, "--fmu", str(fmu),
                           "--contacts", str(contacts), "--seconds", str(seconds),
                           "--scene", scene] + extra, capture_output=True, text=True,
                          env=dict(os.environ, OPENBLAS_NUM_THREADS="1"))
    wall = time.perf_counter() - t0
    lines = [ln for ln in proc.stdout.splitlines() if ln.startswith("{")]
    if proc.returncode != 0 or not lines:
        return wall, None, proc.stderr[-2000:]
    return wall, json.loads(lines[-1])["loop"], ""


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--contacts", type=int, default=8)
    p.add_argument("--seconds", type=float, default=10.0, help="simulated time at 1 ms")
    p.add_argument("--rounds", type=int, default=3)
    p.add_argument("--scene", default="creep_exact_table",
                   help="bundled scene (default: Kalker's exact theory from its table)")
    p.add_argument("--skip-libcosim", action="store_true")
    p.add_argument("--child", help=argparse.SUPPRESS)
    p.add_argument("--fmu", help=argparse.SUPPRESS)
    p.add_argument("--driver", help=argparse.SUPPRESS)
    args = p.parse_args(argv)
    if args.child:
        return child(args.child, args.fmu, args.contacts, args.seconds, args.scene,
                     args.driver)

    vehicle, single = cached_fmu(args.contacts), cached_fmu(1)
    with tempfile.TemporaryDirectory(prefix="bench_vehicle_") as work:
        trivial = trivial_fmu(args.contacts, work)
        driver = None if args.skip_libcosim else driver_fmu(
            args.contacts, int(round(args.seconds / 1e-3)) + 1, work)
        t_v, t_t = step_ratio(vehicle, trivial, args.contacts, args.scene, args.rounds)
        _report(args, vehicle, single, trivial, t_v, t_t, driver)
    return 0


def _report(args, vehicle, single, trivial, t_v, t_t, driver=None):
    print(f"scene {args.scene}, {args.contacts} contacts, every input changing at every step")
    print(f"\n1. one step (fmi2SetReal of {args.contacts * len(INPUTS)} inputs + fmi2DoStep + "
          f"fmi2GetReal of {args.contacts * len(FORCES)} forces), best of {args.rounds} "
          "rounds of 1000 steps, CPU time:")
    print(f"   {args.contacts}-contact FMU      {t_v:8.1f} us")
    print(f"   trivial PythonFMU slave {t_t:8.1f} us   (same variables, do_step copies numbers)")
    print(f"   ratio                   {t_v / t_t:8.2f} x   (target <= 4, goal 2)")

    print(f"\n2. {args.seconds:g} s at 1 ms ({int(round(args.seconds / 1e-3))} steps), a fresh "
          "process each: whole-process wall time (imports, extraction, table load, loop) "
          "and the loop alone")
    modes = [("fmpy-trivial", trivial, args.contacts, "fmpy FMU2Slave, trivial slave"),
             ("fmpy-vehicle", vehicle, args.contacts, "fmpy FMU2Slave, 1 vehicle FMU"),
             ("fmpy-simulate-vehicle", vehicle, args.contacts,
              "fmpy.simulate_fmu, 1 vehicle FMU"),
             ("fmpy-singles", single, args.contacts,
              f"fmpy FMU2Slave, {args.contacts} single-contact instances")]
    if not args.skip_libcosim:
        modes += [("libcosim-trivial", trivial, args.contacts, "libcosim, trivial slave"),
                  ("libcosim-vehicle", vehicle, args.contacts, "libcosim, 1 vehicle FMU"),
                  ("libcosim-singles", single, args.contacts,
                   f"libcosim, {args.contacts} single-contact instances"),
                  ("libcosim-connected-trivial", trivial, args.contacts,
                   "libcosim connected, driver + trivial slave"),
                  ("libcosim-connected-vehicle", vehicle, args.contacts,
                   "libcosim connected, driver + 1 vehicle FMU")]
    for mode, fmu, contacts, label in modes:
        wall, loop, err = whole_process(mode, fmu, contacts, args.seconds, args.scene,
                                        driver if "connected" in mode else None)
        if loop is None:
            print(f"   {label:45s} failed: {err.strip().splitlines()[-1] if err else '?'}")
            continue
        target = " (target <= 2 s)" if mode == "fmpy-vehicle" else (
            " (target <= 3 s)" if mode.startswith("libcosim") and mode.endswith("-vehicle")
            else "")
        print(f"   {label:45s} {wall:6.2f} s whole process, {loop:6.2f} s loop{target}")


if __name__ == "__main__":
    sys.exit(main())
