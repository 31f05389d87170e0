"""Recipe 2: drive the WheelRailContact FMU from your own fmpy script.

    python examples/recipes/fmu_fmpy.py [WheelRailContact.fmu]

The FMU takes a scene (TOML: which effects, which methods, geometry, material) as the string
parameter ``scene_file`` (or the scene's text as ``scene_toml``), and the contact's state as
real inputs at every step: ``normal_force`` [N], ``creepage_longitudinal``,
``creepage_lateral`` [-], ``spin`` [1/m], ``rolling_speed`` [m/s], ``rail_position`` [m].
Without an FMU path it builds one from the checkout (``railcontact.run.locate_fmu``).
"""

import sys
from pathlib import Path

import numpy as np
from fmpy import simulate_fmu

from railcontact.run import locate_fmu

ROOT = Path(__file__).resolve().parents[2]
fmu = sys.argv[1] if len(sys.argv) > 1 else str(locate_fmu())
scene = ROOT / "examples" / "scenes" / "creep_only_analytic.toml"

# your own input signals: a creepage ramp at constant load and speed
time = np.linspace(0.0, 0.1, 101)
signals = np.zeros(time.size, dtype=[("time", float), ("normal_force", float),
                                     ("creepage_longitudinal", float),
                                     ("creepage_lateral", float), ("spin", float),
                                     ("rolling_speed", float), ("rail_position", float)])
signals["time"] = time
signals["normal_force"] = 100e3
signals["creepage_longitudinal"] = np.linspace(0.0, 4e-3, time.size)
signals["rolling_speed"] = 30.0
signals["rail_position"] = 30.0 * time

result = simulate_fmu(fmu, start_time=0.0, stop_time=0.1, output_interval=1e-3,
                      start_values={"scene_file": str(scene)}, input=signals,
                      output=["Fx", "Fy", "stick_area_fraction"])
print(f"{len(result)} steps; Fx at the end: {result['Fx'][-1]:.1f} N; "
      f"stick area fraction: {result['stick_area_fraction'][-1]:.3f}")
