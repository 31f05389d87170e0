r"""Effect objects of the WheelRailContact FMU: one small object per physical effect.

The FMU slave (``fmu_src/WheelRailContact.py``) builds, at initialisation, only the effects a
:class:`~railcontact.scene.Scene` switches on (:func:`build_pipeline`), and each communication
step calls only those (:meth:`Pipeline.step`). Every effect reads and writes the fields of one
:class:`ContactPoint` and keeps its own call counter (``calls``), which tests use to show that a
switched-off effect costs nothing.

Each effect takes its physics from :mod:`railcontact` (the analytic solvers) or from the shipped
tables (:mod:`railcontact.tables`); nothing here re-implements a model. An effect whose model
is not part of this build raises a :class:`~railcontact.scene.SceneError` at build time
("effect X not available in this build"), never a placeholder result.

Order of evaluation in a step (:data:`railcontact.scene.EFFECTS`): the friction coefficient
(velocity-dependent friction), the normal contact (Hertz, always), the creep forces, then the
effects that act on them.

Sign convention: the forces are those acting on the wheel, opposing the creepage (see
:mod:`railcontact`).
"""

from __future__ import annotations

import importlib
import math

from .scene import SceneError

__all__ = ["ContactPoint", "NormalContact", "Creep3D", "Pipeline", "build_pipeline",
           "EffectUnavailable"]

_PACKAGE = __name__.rpartition(".")[0]     # "railcontact", or the FMU's bundled copy's name


class EffectUnavailable(SceneError):
    """The scene asks for an effect whose model is not part of this build."""


def _import(module, effect):
    try:
        return importlib.import_module(f"{_PACKAGE}.{module}")
    except ImportError as exc:
        raise EffectUnavailable(f"effect {effect} not available in this build (module "
                                f"railcontact.{module} is missing: {exc})") from None


class ContactPoint:
    """Inputs and outputs of one wheel/rail contact at the current communication point.

    All SI: forces [N], lengths [m], creepages [-], spin [1/m], speed [m/s], pressure [Pa].
    """

    __slots__ = ("normal_force", "creepage_longitudinal", "creepage_lateral", "spin",
                 "rolling_speed", "rail_position", "friction_coefficient", "a0", "b0", "p0",
                 "Fx", "Fy", "stick_area_fraction", "stick_width_ratio", "r_a0",
                 "creep_within_validity")

    def __init__(self):
        for name in self.__slots__:
            setattr(self, name, 0.0)
        self.stick_area_fraction = self.stick_width_ratio = self.r_a0 = 1.0
        self.creep_within_validity = True

    def as_dict(self):
        """Field name -> value (plain floats)."""
        return {name: getattr(self, name) for name in self.__slots__}


class _Effect:
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


class NormalContact(_Effect):
    r"""Hertz contact ellipse from the normal force (always on).

    ``geometry.kind = "curvatures"``: :func:`railcontact.hertz.hertz_3d` once at build time for
    N = 1 N, then the exact Hertz scaling a0, b0, p0 proportional to N^(1/3) (Johnson (1985)
    Eqs. (4.17)-(4.19): the eccentricity depends on A'/B' only). ``"semi_axes"``: the ellipse
    is fixed and ``p0 = 3 N / (2 pi a0 b0)`` (Eq. (2.60)).
    """

    name = "normal"

    def __init__(self, scene, mu_source=None):
        super().__init__()
        geo = scene.geometry
        if geo["kind"] == "curvatures":
            hertz = _import("hertz", "normal contact (Hertz)")
            a1, b1, p1 = hertz.hertz_3d(1.0, geo["curvature_longitudinal"],
                                        geo["curvature_lateral"], scene.youngs_modulus,
                                        scene.poisson_ratio)
            self._a1, self._b1, self._p1 = float(a1), float(b1), float(p1)
            self._fixed = False
        else:
            self._a1 = geo["semi_axis_longitudinal"]
            self._b1 = geo["semi_axis_lateral"]
            self._p1 = 1.5 / (math.pi * self._a1 * self._b1)
            self._fixed = True

    def step(self, c):
        self.calls += 1
        n = c.normal_force
        if self._fixed:
            c.a0, c.b0, c.p0 = self._a1, self._b1, self._p1 * n
        else:
            scale = n ** (1.0 / 3.0)
            c.a0, c.b0, c.p0 = self._a1 * scale, self._b1 * scale, self._p1 * scale


class Creep3D(_Effect):
    r"""3-D creep forces: ``effects.creep`` (method, spin on/off, analytic or table).

    Analytic: :func:`railcontact.creep3d.creep_solution_3d` (Kalker's linear theory, Shen,
    Hedrick and Elkins, strip or modified strip theory, Nielsen Sec. 2.5-2.6), which also gives
    the stick area fraction, the stick width ratio b*/b0 and the validity flag (spin pole
    outside the ellipse). ``r_a0`` is the stick zone's length over the contact length on the
    centre line y = 0 of the strip theories, ``a*(0)/a0 = 1 - min(z, 1)`` (Eq. (2.83) with
    a(0) = a0, z the normalised creepage of :func:`~railcontact.creep3d.creep_solution_3d`);
    1 for the linear theory (full stick by assumption). With N = 0 (no contact) the forces are
    0 and the stick measures 1.

    Table (``method = "modified_strip"`` only, the theory the shipped table holds):
    :meth:`railcontact.tables.CreepTable.creep_force_3d` gives the forces in the step (its
    scalar fast path); the stick measures and the validity flag are computed when first read
    after a step (:meth:`auxiliary`) with :meth:`~railcontact.tables.CreepTable.
    creep_solution_3d` on the inputs of that step, so an importer that reads only Fx and Fy
    does not pay for them. Out of the table's grid (normalised creepage z beyond its last
    node) the reader holds F = 1, which is exact (full sliding); the FMU logs a warning the
    first time this is seen (when the stick outputs are evaluated).
    With ``spin = false`` the spin input is ignored (treated as 0).
    """

    name = "creep"

    def __init__(self, scene, table_path=None, warn=None):
        super().__init__()
        opts = scene.effects["creep"]
        self.method = opts["method"]
        self.source = opts["source"]
        self.use_spin = opts["spin"]
        self._e, self._nu = scene.youngs_modulus, scene.poisson_ratio
        self._warn = warn if warn is not None else (lambda key, msg: None)
        self._aux_args = None
        creep3d = _import("creep3d", f"creep ({self.source})")
        self._solve = creep3d.creep_solution_3d
        self._spin_coefficient = creep3d.spin_coefficient
        self._table = None
        if self.source == "table":
            tables = _import("tables", "creep (table)")
            if self.method != "modified_strip":
                raise SceneError(f"effects.creep.method must be 'modified_strip' with source = "
                                 f"'table' (the shipped creep table holds the modified strip "
                                 f"theory); got {self.method!r}")
            try:
                path = table_path or tables.default_table_path(opts["table"])
                self._table = tables.CreepTable.from_file(path)
            except (OSError, ValueError) as exc:
                raise EffectUnavailable(f"effect creep (table) not available in this build: "
                                        f"{exc}") from None
            self._force = self._table.creep_force_3d
            self._z_max = float(self._table.table.axes[0]["nodes"][-1])

    def step(self, c):
        self.calls += 1
        if c.normal_force <= 0.0:
            c.Fx = c.Fy = 0.0
            c.stick_area_fraction = c.stick_width_ratio = c.r_a0 = 1.0
            c.creep_within_validity = True
            self._aux_args = None
            return
        spin = c.spin if self.use_spin else 0.0
        if self._table is None:
            res = self._solve(c.creepage_longitudinal, c.creepage_lateral, spin,
                              c.normal_force, c.a0, c.b0, self._e, self._nu,
                              c.friction_coefficient, self.method)
            c.Fx = float(res.tx)
            c.Fy = float(res.ty)
            c.stick_area_fraction = float(res.stick_area_fraction)
            c.stick_width_ratio = float(res.stick_width_ratio)
            c.r_a0 = 1.0 if self.method == "linear" else 1.0 - min(float(
                res.normalised_creepage), 1.0)
            c.creep_within_validity = bool(res.within_validity)
        else:
            args = (c.creepage_longitudinal, c.creepage_lateral, spin, c.normal_force, c.a0,
                    c.b0, self._e, self._nu, c.friction_coefficient)
            fx, fy = self._force(*args)
            c.Fx, c.Fy = float(fx), float(fy)
            self._aux_args = args

    def auxiliary(self, c):
        """Fill the stick measures and the validity flag of the last table step (lazily)."""
        args, self._aux_args = self._aux_args, None
        if args is None:
            return
        _, _, stick, z = self._table.creep_solution_3d(*args)
        z = float(z)
        zc = min(z, 1.0)
        c.stick_area_fraction = float(stick)
        c.stick_width_ratio = math.sqrt(1.0 - zc * zc)       # b*/b0, Eq. (2.84)
        c.r_a0 = 1.0 - zc                                    # a*(0)/a0, Eq. (2.83)
        c.creep_within_validity = bool(float(self._spin_coefficient(
            args[0], args[1], args[2], args[4], args[5])) <= 1.0)
        if z > self._z_max:
            self._warn("creep-table-range",
                       f"creep table {self._table.table.path.name}: normalised creepage "
                       f"z = {z:.4g} beyond the grid (last node {self._z_max:g}); the reader "
                       f"holds F = 1 there, which is exact (full sliding)")

    def get_state(self):
        return {"calls": self.calls,
                "aux_args": None if self._aux_args is None else list(self._aux_args)}

    def set_state(self, state):
        self.calls = int(state["calls"])
        args = state.get("aux_args")
        self._aux_args = None if args is None else tuple(args)


class Pipeline:
    """The effects a scene switched on, in evaluation order.

    Attributes
    ----------
    effects : dict
        Name -> effect object, only those built.
    """

    def __init__(self, scene, effects):
        self.scene = scene
        self.effects = effects
        self._steps = tuple(e.step for e in effects.values())
        self._auxiliary = tuple(e for e in effects.values() if hasattr(e, "auxiliary"))

    def step(self, contact):
        """Evaluate every built effect once on ``contact`` (in place)."""
        for step in self._steps:
            step(contact)

    def auxiliary(self, contact):
        """Evaluate the outputs effects compute only on demand (after a step)."""
        for e in self._auxiliary:
            e.auxiliary(contact)

    def calls(self):
        """Effect name -> number of evaluations so far."""
        return {name: e.calls for name, e in self.effects.items()}

    def get_state(self):
        """JSON-able internal state of every effect."""
        return {name: e.get_state() for name, e in self.effects.items()}

    def set_state(self, state):
        """Restore :meth:`get_state` (the scene must be the same)."""
        for name, e in self.effects.items():
            e.set_state(state[name])


def build_pipeline(scene, tables_dir=None, warn=None):
    """Build the effects ``scene`` switches on (and only those).

    Parameters
    ----------
    scene : Scene
        A validated scene.
    tables_dir : path-like, optional
        Directory holding the shipped ``<name>.nc`` tables (the FMU's resources); default:
        :func:`railcontact.tables.default_table_path`.
    warn : callable, optional
        ``warn(key, message)`` for warnings the effects log (the caller logs each key once).

    Raises
    ------
    SceneError
        If an effect is not available in this build or its options are invalid.
    """
    from pathlib import Path

    effects = {"normal": NormalContact(scene)}
    for name in scene.effects:
        if name != "creep":
            raise EffectUnavailable(f"effect {name} not available in this build")
    if "creep" in scene.effects:
        table_path = None
        if scene.effects["creep"]["source"] == "table" and tables_dir is not None:
            table_path = Path(tables_dir) / f"{scene.effects['creep']['table']}.nc"
        effects["creep"] = Creep3D(scene, table_path=table_path, warn=warn)
    return Pipeline(scene, effects)
