"""Recipe 3: run WheelRailContact.fmu in OSP libcosim through libcosimpy (README, "Use the FMU").

Run: python examples/fmu_libcosim.py [WheelRailContact.fmu]
(pip install libcosimpy; it comes with the ".[test]" extra). Use one FMI importer per process:
see docs/fmu_lifecycle.md.
"""
import sys

from libcosimpy.CosimExecution import CosimExecution
from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
from libcosimpy.CosimManipulator import CosimManipulator
from libcosimpy.CosimObserver import CosimObserver
from libcosimpy.CosimSlave import CosimLocalSlave

from railcontact.run import locate_fmu

# the FMU: the checkout's WheelRailContact.fmu (set-up command 1 built it; locate_fmu rebuilds
# it if the sources changed), or a path given on the command line
fmu = sys.argv[1] if len(sys.argv) > 1 else str(locate_fmu())

log_output_level(CosimLogLevel.WARNING)                      # libcosim logs debug by default
step = 0.01                                                  # [s]
execution = CosimExecution.from_step_size(int(step * 1e9))   # libcosim counts nanoseconds
wheel = execution.add_local_slave(CosimLocalSlave(fmu_path=fmu, instance_name="wheel"))
ref = {v.name.decode(): v.reference for v in execution.slave_variables(wheel)}

# parameters before initialisation: a scene bundled in the FMU, one override
execution.string_initial_value(wheel, ref["scene_file"], "creep_only_analytic")
execution.real_initial_value(wheel, ref["friction_coefficient"], 0.25)

# inputs each step through an override manipulator, outputs through a last-value observer
manipulator = CosimManipulator.create_override()
execution.add_manipulator(manipulator)
observer = CosimObserver.create_last_value()
execution.add_observer(observer)

inputs = ["normal_force", "creepage_longitudinal", "rolling_speed"]
for k in range(100):
    t = k * step
    manipulator.slave_real_values(wheel, [ref[n] for n in inputs],
                                  [80e3, -4e-3 + 8e-3 * t, 30.0])   # [N], [-], [m/s]
    assert execution.step(), f"step {k} failed"
    fx, fy = observer.last_real_values(wheel, [ref["Fx"], ref["Fy"]])

print(f"after {k + 1} steps: Fx = {fx:.0f} N, Fy = {fy:.0f} N")
