"""Run a scene through the WheelRailContact FMU with libcosimpy (OSP libcosim).

Run in its own process (two FMI importers in one process can abort at exit)::

    python tests/_cosim_runner.py FMU SCENE OUT_CSV

It feeds the scene's input signals (:meth:`railcontact.scene.Scene.input_signals`) through an
override manipulator before every step and reads the outputs with a last-value observer after
it, so row k (time t_k, k >= 1) holds the outputs of the step from t_(k-1) with the inputs at
t_(k-1): the same sample-and-hold convention as fmpy's co-simulation loop. The CSV has a header
line ``time,<outputs>``.
"""

import sys
from pathlib import Path

import numpy as np

_OUTPUT = 2   # libcosimpy.CosimEnums.CosimVariableCausality.OUTPUT
_REAL = 0     # libcosimpy.CosimEnums.CosimVariableType.REAL


def run(fmu, scene_path, out_csv):
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
    from libcosimpy.CosimManipulator import CosimManipulator
    from libcosimpy.CosimObserver import CosimObserver
    from libcosimpy.CosimSlave import CosimLocalSlave

    from railcontact.scene import INPUTS, load_scene

    log_output_level(CosimLogLevel.WARNING)
    scene = load_scene(scene_path)
    inputs = scene.input_signals()
    step_ns = int(round(scene.simulation["step_size"] * 1e9))
    if scene.simulation["start_time"] != 0.0:
        raise SystemExit("the libcosim runner supports start_time = 0 only")

    execution = CosimExecution.from_step_size(step_ns)
    slave = CosimLocalSlave(fmu_path=str(fmu), instance_name="wrc")
    index = execution.add_local_slave(slave)
    variables = {v.name.decode(): v for v in execution.slave_variables(index)}
    outputs = [n for n, v in variables.items() if v.causality == _OUTPUT and v.type == _REAL]
    in_refs = [variables[n].reference for n in INPUTS]
    out_refs = [variables[n].reference for n in outputs]

    if not execution.string_initial_value(index, variables["scene_file"].reference,
                                          str(Path(scene_path).resolve())):
        raise SystemExit("libcosim: cannot set scene_file")
    for name, ref in zip(INPUTS, in_refs):
        execution.real_initial_value(index, ref, float(inputs[name][0]))
    manipulator = CosimManipulator.create_override()
    execution.add_manipulator(manipulator)
    observer = CosimObserver.create_last_value()
    execution.add_observer(observer)

    rows = []
    for k in range(1, len(inputs)):
        values = [float(inputs[name][k - 1]) for name in INPUTS]
        manipulator.slave_real_values(index, in_refs, values)
        if not execution.step():
            raise SystemExit(f"libcosim: step {k} failed")
        rows.append([inputs["time"][k]] + list(observer.last_real_values(index, out_refs)))
    np.savetxt(out_csv, np.array(rows), delimiter=",", header=",".join(["time"] + outputs),
               comments="", fmt="%.17g")


if __name__ == "__main__":
    run(*sys.argv[1:4])
