"""Recipe 2: drive WheelRailContact.fmu from your own fmpy script (README, "Use the FMU").

Run: python examples/fmu_fmpy.py [WheelRailContact.fmu]
"""
import sys

import numpy as np
from fmpy import simulate_fmu

from railcontact.run import locate_fmu

# the FMU: the checkout's WheelRailContact.fmu (set-up command 1 built it; locate_fmu rebuilds
# it if the sources changed), or a path given on the command line
fmu = sys.argv[1] if len(sys.argv) > 1 else str(locate_fmu())

# Your inputs, as a structured array: time, then the six input variables (fmpy warns about any
# it is not given). Here a longitudinal creepage ramp at 80 kN and 30 m/s.
t = np.linspace(0.0, 1.0, 101)
names = ["normal_force", "creepage_longitudinal", "creepage_lateral", "spin", "rolling_speed",
         "rail_position"]
inputs = np.zeros(t.size, dtype=[("time", float)] + [(n, float) for n in names])
inputs["time"] = t
inputs["normal_force"] = 80e3                       # [N]
inputs["creepage_longitudinal"] = -4e-3 + 8e-3 * t  # [-], wheel faster than the rail for > 0
inputs["rolling_speed"] = 30.0                      # [m/s]
inputs["rail_position"] = 30.0 * t                  # [m]; creepage_lateral, spin stay 0

result = simulate_fmu(
    fmu, stop_time=1.0, output_interval=0.01, input=inputs,
    # a scene bundled in the FMU (or a path to your own TOML file), plus parameter overrides
    start_values={"scene_file": "creep_only_analytic", "friction_coefficient": 0.25},
    output=["Fx", "Fy", "a0", "b0", "creep_within_validity"])

print(f"{len(result)} rows; Fx from {result['Fx'][1]:.0f} N to {result['Fx'][-1]:.0f} N "
      f"(|Fx| <= mu N = {0.25 * 80e3:.0f} N)")
