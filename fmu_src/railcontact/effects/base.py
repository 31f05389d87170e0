"""What every effect shares: the contact point they read and write, their base class, the
"not available in this build" error and the table loader.

:class:`ContactPoint` holds the inputs and outputs of one contact at the current communication
point; each effect (:class:`Effect`) reads and writes its fields and counts its calls.
"""

from __future__ import annotations

from ..scene import SceneError

__all__ = ["EffectUnavailable", "NOT_ESTIMATED", "JACOBIAN_FIELDS", "ContactPoint", "Effect",
           "load_table"]


class EffectUnavailable(SceneError):
    """The scene asks for an effect whose model is not part of this build."""


#: Sentinel of the accuracy outputs for "not estimated" (no table in use, no iteration run).
NOT_ESTIMATED = -1.0


def load_table(name, tables_dir, effect):
    """The shipped table ``<name>.nc`` (:class:`railcontact.tables.Table`) for ``effect``:
    from ``tables_dir`` (the FMU's resources) if given, else
    :func:`railcontact.tables.default_table_path`; a missing or unreadable file is
    :class:`EffectUnavailable`."""
    from .. import tables     # (numba: loaded only by a scene that reads a table)

    try:
        path = tables.default_table_path(name, directory=tables_dir)
        table = tables.Table.from_file(path, expected_name=name)
    except (OSError, ValueError) as exc:
        raise EffectUnavailable(f"effect {effect} (table {name}) not available in this build: "
                                f"{exc}") from None
    table.spline.warm_up()         # (the compiled evaluator loaded at build, not in a step)
    return table


#: The Jacobian fields of :class:`ContactPoint`, row by row (Fx, Fy, Mz) and column by column
#: (xi_x, xi_y, phi), as :meth:`railcontact.exact_table.ExactCreepTable.step` returns them.
JACOBIAN_FIELDS = ("dFx_dxi_x", "dFx_dxi_y", "dFx_dphi", "dFy_dxi_x", "dFy_dxi_y", "dFy_dphi",
                   "dMz_dxi_x", "dMz_dxi_y", "dMz_dphi")


class ContactPoint:
    """Inputs and outputs of one wheel/rail contact at the current communication point.

    All SI: forces [N], lengths [m], creepages [-], spin [1/m], speed [m/s], pressure [Pa].
    """

    __slots__ = ("normal_force", "creepage_longitudinal", "creepage_lateral", "spin",
                 "rolling_speed", "rail_position", "friction_coefficient", "a0", "b0", "p0",
                 "Fx", "Fy", "stick_area_fraction", "stick_width_ratio", "r_a0",
                 "creep_within_validity", "Mz", "contact_half_width", "patch_shift",
                 "wear_depth_per_passage", "corrugation_amplitude", "corrugation_growth_rate",
                 "creep_table_error_estimate", "friction_iteration_residual",
                 "corrugation_series_error_estimate", "friction_table_error_estimate",
                 # non-steady correction (NonSteady): the communication step size [s] the slave
                 # sets before each step, and the effect's outputs
                 "step_size", "relaxation_length", "relaxed_creepage_longitudinal",
                 "relaxed_creepage_lateral", "relaxed_spin",
                 # rough rail (Roughness effect)
                 "gap_curvature", "gap_skewness", "gap_flatness", "critical_creepage",
                 # creep-force Jacobian d(Fx, Fy, Mz)/d(xi_x, xi_y, phi) (exact table)
                 "dFx_dxi_x", "dFx_dxi_y", "dFx_dphi", "dFy_dxi_x", "dFy_dxi_y", "dFy_dphi",
                 "dMz_dxi_x", "dMz_dxi_y", "dMz_dphi",
                 # geometry inputs (NormalContact; None = the scene's)
                 "curvature_longitudinal", "curvature_lateral", "semi_axis_longitudinal",
                 "semi_axis_lateral")

    #: The geometry inputs: None (the scene's values) until set.
    GEOMETRY_FIELDS = ("curvature_longitudinal", "curvature_lateral", "semi_axis_longitudinal",
                       "semi_axis_lateral")

    def __init__(self):
        for name in self.__slots__:
            setattr(self, name, 0.0)
        self.stick_area_fraction = self.stick_width_ratio = self.r_a0 = 1.0
        self.creep_within_validity = True
        self.creep_table_error_estimate = NOT_ESTIMATED
        self.friction_iteration_residual = NOT_ESTIMATED
        self.corrugation_series_error_estimate = NOT_ESTIMATED
        self.friction_table_error_estimate = NOT_ESTIMATED
        for name in self.GEOMETRY_FIELDS:
            setattr(self, name, None)

    def as_dict(self):
        """Field name -> value (plain floats)."""
        return {name: getattr(self, name) for name in self.__slots__}


class Effect:
    """Base: a name, a call counter and a JSON-able internal state (none by default)."""

    name = "effect"

    def __init__(self):
        self.calls = 0

    def get_state(self):
        """Internal state as JSON-able values (for FMU state save/restore)."""
        return {"calls": self.calls}

    def set_state(self, state):
        """Restore :meth:`get_state`."""
        self.calls = int(state["calls"])

