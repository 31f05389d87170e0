"""Input signals of a 4-axle vehicle (8 wheel/rail contacts) entering a curve with a wet patch.

Shared by ``examples/vehicle_fmpy.py`` and ``examples/vehicle_libcosim.py``. In a real
co-simulation these come from the vehicle-dynamics model and the contact-geometry search
(rolling-radius difference, contact angle, profile curvatures at the contact point); here they
are smooth illustrative functions of time, one set per contact, all changing at every step.

Contact k = 1..8: axle (k + 1) // 2, left wheel for odd k, right wheel for even k. Every
quantity is SI; the curvatures are A' = 1/(2 R'_x), B' = 1/(2 R'_y) (half the relative
curvatures: ``curvature_longitudinal`` is NOT 1/R').
"""

import numpy as np

CONTACTS = 8
SPEED = 30.0                  # [m/s]
#: The FMU's inputs per contact, in the order of :func:`signals`' columns.
INPUTS = ("normal_force", "creepage_longitudinal", "creepage_lateral", "spin", "rolling_speed",
          "rail_position", "curvature_longitudinal", "curvature_lateral",
          "semi_axis_longitudinal", "semi_axis_lateral", "friction_coefficient")


def signals(t):
    """Input name -> array (len(t), 8) of its value at each contact.

    * ``normal_force``: 80 kN static wheel load, moved to the outer (right) wheels in the
      curve (cant deficiency), plus a 6 Hz bounce of each axle; wheel 3 (axle 2, left)
      unloads fully for a moment (a lifted wheel: its forces are 0 there).
    * creepages: a lateral wheelset displacement y(t) in the curve gives the longitudinal
      creepage (rolling-radius difference, opposite on the two wheels), a yaw angle the lateral
      creepage, the contact angle the spin.
    * ``curvature_longitudinal``, ``curvature_lateral``: A' = 1/(2 R_wheel) with the rolling
      radius moving with y, and B' of the profiles at the contact point moving with y.
    * ``friction_coefficient``: 0.35 dry, 0.12 on a wet patch 6-9 m along the track (smooth
      edges), reached by each axle at its own time (axles 2.5 m apart).
    """
    t = np.asarray(t, dtype=float)[:, None]
    k = np.arange(CONTACTS)[None, :]
    axle, side = k // 2, np.where(k % 2 == 0, 1.0, -1.0)   # side: +1 left, -1 right
    x = SPEED * t - 2.5 * axle                              # rail position of the axle [m]
    entry = 0.5 * (1.0 - np.cos(np.pi * np.clip(x / 12.0, 0.0, 1.0)))   # 0 -> 1 into the curve
    y = 4e-3 * entry + 0.6e-3 * np.sin(2 * np.pi * 1.3 * t - 0.8 * axle)  # lateral disp. [m]
    out = {}
    load = 80e3 * (1.0 - 0.25 * side * entry) * (1.0 + 0.08 * np.sin(2 * np.pi * 6.0 * t + axle))
    lift = (k == 2) & (np.abs(t - 0.3) < 0.02)
    out["normal_force"] = np.where(lift, 0.0, load)
    out["creepage_longitudinal"] = side * 0.05 * y / 0.46 + 2e-4 * np.sin(2 * np.pi * 2 * t)
    out["creepage_lateral"] = 1.5e-3 * entry * (1.0 - 0.5 * (axle % 2)) \
        + 2e-4 * np.cos(2 * np.pi * 1.3 * t - 0.8 * axle)
    out["spin"] = side * (0.05 + 8.0 * y)                   # [1/m]
    out["rolling_speed"] = SPEED + 0.0 * out["spin"]
    out["rail_position"] = x
    out["curvature_longitudinal"] = 1.0 / (2.0 * (0.46 + side * 0.04 * y))   # A' [1/m]
    out["curvature_lateral"] = 1.667 * (1.0 + 60.0 * np.abs(y))             # B' [1/m]
    out["semi_axis_longitudinal"] = np.full_like(load, 6e-3)  # (unused: geometry by curvatures)
    out["semi_axis_lateral"] = np.full_like(load, 5e-3)
    wet = 0.5 * (np.tanh((x - 6.0) / 0.3) - np.tanh((x - 9.0) / 0.3))
    out["friction_coefficient"] = 0.35 - 0.23 * wet
    return out
