"""A 4-axle vehicle (8 wheel/rail contacts) in ONE FMU instance, from fmpy.

    python examples/vehicle_fmpy.py [FMU]

The FMU is ``WheelRailContact_8contacts.fmu`` (``python build_fmu.py --contacts 8``; built
here if missing or stale, or give its path): one instance serves 8 contacts of one scene, its
inputs and outputs are ``name[k]``, k = 1..8. Each contact has its own load, creepages,
curvatures and friction coefficient at every step (``examples/vehicle_track.py``); the scene
(Kalker's exact theory from the shipped table, by default) is one for all.
"""

import sys
from pathlib import Path

import numpy as np
from fmpy import simulate_fmu

from vehicle_track import CONTACTS, INPUTS, signals

if len(sys.argv) > 1:
    fmu = sys.argv[1]
else:   # the checkout's vehicle FMU, (re)built if the sources changed
    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "fmu_src"))
    from railcontact.fmu_build import up_to_date_fmu

    fmu = str(up_to_date_fmu(contacts=CONTACTS))

step = 1e-3                                        # [s]
t = np.arange(0.0, 0.5 + step / 2, step)
values = signals(t)                                # name -> (len(t), 8)

# fmpy's input: a structured array, time then one column per variable name[k]
names = [f"{n}[{k}]" for k in range(1, CONTACTS + 1) for n in INPUTS]
inputs = np.zeros(t.size, dtype=[("time", float)] + [(n, float) for n in names])
inputs["time"] = t
for k in range(1, CONTACTS + 1):
    for n in INPUTS:
        inputs[f"{n}[{k}]"] = values[n][:, k - 1]

outputs = [f"{n}[{k}]" for k in range(1, CONTACTS + 1) for n in ("Fx", "Fy", "Mz", "a0", "b0")]
result = simulate_fmu(fmu, stop_time=t[-1], step_size=step, output_interval=step,
                      input=inputs, start_values={"scene_file": "creep_exact_table"},
                      output=outputs)

# result row j holds the outputs of the step from t[j-1] with the inputs at t[j-1]
fx = np.column_stack([result[f"Fx[{k}]"] for k in range(1, CONTACTS + 1)])[1:]
fy = np.column_stack([result[f"Fy[{k}]"] for k in range(1, CONTACTS + 1)])[1:]
mu_n = (values["friction_coefficient"] * values["normal_force"])[:-1]
print(f"{len(result)} rows x {CONTACTS} contacts")
print(f"|T| <= mu N at every contact and step: {bool(np.all(np.hypot(fx, fy) <= mu_n * (1 + 1e-12)))}")
lifted = values["normal_force"][:-1, 2] == 0.0
print(f"contact 3 lifted for {lifted.sum()} steps, its forces there: "
      f"{np.abs(fx[lifted, 2]).max():.0f} N")
for k in range(1, CONTACTS + 1):
    print(f"contact {k}: final Fx = {result[f'Fx[{k}]'][-1]:.6e} N, "
          f"Fy = {result[f'Fy[{k}]'][-1]:.6e} N, Mz = {result[f'Mz[{k}]'][-1]:.6e} N.m")
