"""Recipe 3: run the WheelRailContact FMU in libcosim (OSP, through libcosimpy).

    python examples/recipes/fmu_libcosim.py [WheelRailContact.fmu]

libcosim is a C++ co-simulation library (a non-Python FMI host). The scene goes in as the
string parameter ``scene_file``; the inputs are set before each step with an override
manipulator and the outputs read after it with a last-value observer.
"""

import sys
from pathlib import Path

from libcosimpy.CosimExecution import CosimExecution
from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
from libcosimpy.CosimManipulator import CosimManipulator
from libcosimpy.CosimObserver import CosimObserver
from libcosimpy.CosimSlave import CosimLocalSlave

from railcontact.run import locate_fmu

ROOT = Path(__file__).resolve().parents[2]
fmu = sys.argv[1] if len(sys.argv) > 1 else str(locate_fmu())
scene = ROOT / "examples" / "scenes" / "creep_only_analytic.toml"

log_output_level(CosimLogLevel.WARNING)
execution = CosimExecution.from_step_size(int(1e6))           # 1 ms, in nanoseconds
index = execution.add_local_slave(CosimLocalSlave(fmu_path=fmu, instance_name="contact"))
ref = {v.name.decode(): v.reference for v in execution.slave_variables(index)}
execution.string_initial_value(index, ref["scene_file"], str(scene))
manipulator = CosimManipulator.create_override()
execution.add_manipulator(manipulator)
observer = CosimObserver.create_last_value()
execution.add_observer(observer)

inputs = ["normal_force", "creepage_longitudinal", "rolling_speed"]
for k in range(100):
    manipulator.slave_real_values(index, [ref[n] for n in inputs],
                                  [100e3, 4e-5 * k, 30.0])
    if not execution.step():
        raise SystemExit(f"step {k} failed")
fx, fy = observer.last_real_values(index, [ref["Fx"], ref["Fy"]])
print(f"100 steps in libcosim; Fx at the end: {fx:.1f} N, Fy: {fy:.1f} N")
