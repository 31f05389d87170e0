"""Recipe 1: the Python API (README, "Use it from Python"). Run: python examples/quickstart_api.py"""
import numpy as np

import railcontact as rc
from railcontact.strip_table import CreepTable
from railcontact.tables import default_table_path

# Hertz contact of a wheel on a rail, 100 kN: gap coefficients A' = 1/(2 R'_x) (wheel radius
# 0.46 m), B' = 1/(2 R'_y) (rail head 0.3 m) [1/m], half of 1/R' (not 1/R') -> a0, b0, p0
a0, b0, p0 = rc.hertz_3d(normal_load=100e3, curvature_longitudinal=1.087, curvature_lateral=1.667,
                         youngs_modulus=210e9, poisson_ratio=0.28)

# Creep forces on the wheel [N] over a creep curve (vectorised: creepage is an array)
xi = np.linspace(-0.002, 0.002, 5)
contact = dict(normal_load=100e3, a0=a0, b0=b0, youngs_modulus=210e9, poisson_ratio=0.28,
               friction_coefficient=0.3)
tx, ty = rc.creep_force_3d(creepage_longitudinal=xi, creepage_lateral=0.0, spin=0.0,
                           method="modified_strip", **contact)

# ... with the stick zone and the validity flag (spin pole inside the patch: not valid)
sol = rc.creep_solution_3d(creepage_longitudinal=1e-3, creepage_lateral=0.0, spin=[0.1, 5.0],
                           **contact)

# The same forces from the shipped C2 table (faster per call: docs/figures.md)
table = CreepTable.from_file(default_table_path("creep_modified_strip"))
tx_table, _ = table.creep_force_3d(xi, 0.0, 0.0, **contact)

print(f"a0 = {a0 * 1e3:.3f} mm, b0 = {b0 * 1e3:.3f} mm, p0 = {p0 / 1e6:.0f} MPa")
print("Tx [kN]       :", np.round(tx / 1e3, 3))
print("Tx table [kN] :", np.round(tx_table / 1e3, 3))
print("stick area    :", np.round(sol.stick_area_fraction, 3), " valid:", sol.within_validity)
