"""Recipe 1: creep forces from the Python API.

    python examples/recipes/python_api.py

Hertz contact of a wheel on a rail, then the creep force by three of the 3-D methods. Every
function takes SI units, broadcasts over arrays and raises ValueError naming a bad argument.
"""

import numpy as np

import railcontact as rc

E, NU, MU, N = 210e9, 0.28, 0.3, 100e3          # Pa, -, -, N

# Hertz semi-axes from the curvatures of the gap h = A'x^2 + B'y^2 (Nielsen Eqs. 2.40-2.42)
a0, b0, p0 = rc.hertz_3d(normal_load=N, curvature_longitudinal=1.1, curvature_lateral=2.3,
                         youngs_modulus=E, poisson_ratio=NU)
print(f"a0 = {1e3 * a0:.3f} mm, b0 = {1e3 * b0:.3f} mm, p0 = {1e-6 * p0:.0f} MPa")

xi = np.array([1e-4, 1e-3, 3e-3])                # longitudinal creepage [-]
for method in ("linear", "she", "modified_strip"):
    tx, ty = rc.creep_force_3d(creepage_longitudinal=xi, creepage_lateral=0.0, spin=0.0,
                               normal_load=N, a0=a0, b0=b0, youngs_modulus=E,
                               poisson_ratio=NU, friction_coefficient=MU, method=method)
    print(f"{method:>15}: Tx/(mu N) = {np.round(tx / (MU * N), 4)}")

# the whole solution: stick area, validity flag, ...
sol = rc.creep_solution_3d(1e-3, 0.0, 0.0, N, a0, b0, E, NU, MU, method="modified_strip")
print(f"stick area fraction at xi = 1e-3: {float(sol.stick_area_fraction):.3f}")
