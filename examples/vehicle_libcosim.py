"""A 4-axle vehicle (8 wheel/rail contacts) in ONE FMU instance, from OSP libcosim.

    python examples/vehicle_libcosim.py [FMU]

Same FMU and signals as ``examples/vehicle_fmpy.py``: ``WheelRailContact_8contacts.fmu``
(``python build_fmu.py --contacts 8``), variables ``name[k]``, k = 1..8; every input of
every contact set before each step through an override manipulator, the forces read after it
through a last-value observer.
"""

import sys
from pathlib import Path

import numpy as np
from libcosimpy.CosimExecution import CosimExecution
from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
from libcosimpy.CosimManipulator import CosimManipulator
from libcosimpy.CosimObserver import CosimObserver
from libcosimpy.CosimSlave import CosimLocalSlave

from vehicle_track import CONTACTS, INPUTS, signals

if len(sys.argv) > 1:
    fmu = sys.argv[1]
else:   # the checkout's vehicle FMU, (re)built if the sources changed
    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "fmu_src"))
    from railcontact.fmu_build import up_to_date_fmu

    fmu = str(up_to_date_fmu(contacts=CONTACTS))

log_output_level(CosimLogLevel.WARNING)                      # libcosim logs debug by default
step = 1e-3                                                  # [s]
t = np.arange(0.0, 0.5 + step / 2, step)
values = signals(t)                                          # name -> (len(t), 8)

execution = CosimExecution.from_step_size(int(round(step * 1e9)))   # nanoseconds
vehicle = execution.add_local_slave(CosimLocalSlave(fmu_path=fmu, instance_name="vehicle"))
ref = {v.name.decode(): v.reference for v in execution.slave_variables(vehicle)}
execution.string_initial_value(vehicle, ref["scene_file"], "creep_exact_table")

in_refs = [ref[f"{n}[{k}]"] for k in range(1, CONTACTS + 1) for n in INPUTS]
out_names = [f"{n}[{k}]" for k in range(1, CONTACTS + 1) for n in ("Fx", "Fy", "Mz")]
out_refs = [ref[n] for n in out_names]
manipulator = CosimManipulator.create_override()
execution.add_manipulator(manipulator)
observer = CosimObserver.create_last_value()
execution.add_observer(observer)

# row j: the inputs at t[j], all contacts, in the order of in_refs
rows = np.stack([values[n] for n in INPUTS], axis=-1).reshape(t.size, -1).tolist()
forces = []
for j in range(t.size - 1):
    manipulator.slave_real_values(vehicle, in_refs, rows[j])
    assert execution.step(), f"step {j} failed"
    forces.append(observer.last_real_values(vehicle, out_refs))
forces = np.array(forces).reshape(-1, CONTACTS, 3)
fx, fy = forces[..., 0], forces[..., 1]
mu_n = (values["friction_coefficient"] * values["normal_force"])[:-1]
print(f"{len(forces)} steps x {CONTACTS} contacts")
print(f"|T| <= mu N at every contact and step: {bool(np.all(np.hypot(fx, fy) <= mu_n * (1 + 1e-12)))}")
for k in range(1, CONTACTS + 1):
    fx_k, fy_k, mz_k = forces[-1, k - 1]
    print(f"contact {k}: final Fx = {fx_k:.6e} N, Fy = {fy_k:.6e} N, Mz = {mz_k:.6e} N.m")
