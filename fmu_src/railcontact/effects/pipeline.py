"""The effect pipeline: build the effects a scene switches on, in the registry's order, and
evaluate them once per step (behind a cheap input check, for the FMU's ``do_step``)."""

from __future__ import annotations

import math
import sys

from ..scene import EFFECTS
from .base import EffectUnavailable
from .normal import NormalContact

__all__ = ["Pipeline", "build_pipeline", "checked_steps", "inputs_plausible",
           "MissingDependency"]


class MissingDependency(RuntimeError):
    """The host Python lacks a third-party module an effect needs (not a scene error)."""


#: pip names of the modules whose import name differs (none today; netCDF4, numba, scipy
#: install under their import names).
_PIP_NAMES = {}


class Pipeline:
    """The effects a scene switched on, in evaluation order.

    Attributes
    ----------
    effects : dict
        Name -> effect object, only those built, in evaluation order.
    replaced : dict
        Name of an effect the scene switched on that is not computed -> the effect that supplies
        its results in its place (registry field ``replaces`` of :data:`railcontact.scene.
        EFFECTS`).
    """

    def __init__(self, scene, effects, replaced=None):
        self.scene = scene
        self.effects = effects
        self.replaced = dict(replaced or {})
        # effects with a ``finish`` step (NonSteady: put the inputs back) end the step
        self._steps = (tuple(e.step for e in effects.values())
                       + tuple(e.finish for e in effects.values() if hasattr(e, "finish")))
        #: Every step function in evaluation order (what :meth:`step` calls).
        self.steps = self._steps
        self._auxiliary = tuple(e for e in effects.values() if hasattr(e, "auxiliary"))
        # effects that compute the Jacobian outputs only when read (Creep3D with falling
        # friction); without any, a read of them calls nothing (jacobian_on_demand False)
        self._jacobian = tuple(e for e in effects.values()
                               if getattr(e, "jacobian_on_demand", False))
        #: Whether :meth:`jacobian` has anything to compute.
        self.jacobian_on_demand = bool(self._jacobian)
        #: ``checked_step(contact) -> bool``: :meth:`step` behind a cheap validity check of the
        #: inputs (see :func:`checked_steps`).
        self.checked_step = checked_steps(self._steps)

    def step(self, contact):
        """Evaluate every built effect once on ``contact`` (in place)."""
        for step in self._steps:
            step(contact)

    def auxiliary(self, contact):
        """Evaluate the outputs effects compute only on demand (after a step)."""
        for e in self._auxiliary:
            e.auxiliary(contact)

    def jacobian(self, contact):
        """Evaluate the Jacobian outputs effects compute only on demand (after a step)."""
        for e in self._jacobian:
            e.jacobian(contact)

    def fmu_step(self, contact, otherwise, on_error):
        """The FMU's ``do_step(current_time, step_size)`` for this pipeline, in one Python frame.

        Returns a callable that makes the cheap input check of :func:`inputs_plausible` (and
        ``0 <= step_size < inf``), sets ``contact.step_size`` and evaluates every step on
        ``contact``, then returns True; if the check does not pass it returns
        ``otherwise(current_time, step_size)`` (the slave's full path: the range check that
        names the input, then the steps), changing nothing, and a ValueError raised by a model
        is passed to ``on_error(current_time, exc)`` and re-raised.
        """
        steps = self._steps

        def do_step(current_time, step_size, _isfinite=math.isfinite, _inf=math.inf):
            c = contact
            n, v, mu = c.normal_force, c.rolling_speed, c.friction_coefficient
            if not (_isfinite(n + c.creepage_longitudinal + c.creepage_lateral + c.spin + v
                              + c.rail_position + mu) and n >= 0.0 and v >= 0.0 and mu >= 0.0
                    and 0.0 <= step_size < _inf):
                return otherwise(current_time, step_size)
            c.step_size = step_size
            try:
                for step in steps:
                    step(c)
            except ValueError as exc:
                on_error(current_time, exc)
                raise
            return True
        return do_step

    def summary(self):
        """The effects in evaluation order, each with those it replaces: ``"normal, creep"``,
        ``"normal, roughness (in place of creep)"``."""
        def named(name):
            instead = [r for r, by in self.replaced.items() if by == name]
            return f"{name} (in place of {', '.join(instead)})" if instead else name
        return ", ".join(named(name) for name in self.effects)

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


# --------------------------------------------------------------------------------------------
# the FMU's per-step call: input pre-check + effects
# --------------------------------------------------------------------------------------------
# An FMU step is a few microseconds of Python, so the interpreter overhead (frames, attribute
# look-ups, float() calls) is a large part of it (the targets are in benchmarks/bench_fmu.py).
# The function below returns a closure with everything constant bound at build time.


def inputs_plausible(c, _isfinite=math.isfinite):
    """Cheap check: the six inputs and the friction coefficient finite (one isfinite on their
    sum), N >= 0, V >= 0 and mu >= 0. (The geometry inputs are checked by NormalContact when
    they change.)

    False does not mean invalid (a sum may overflow): the caller then makes the full range
    check, with messages naming the input."""
    n, v, mu = c.normal_force, c.rolling_speed, c.friction_coefficient
    return (_isfinite(n + c.creepage_longitudinal + c.creepage_lateral + c.spin + v
                      + c.rail_position + mu) and n >= 0.0 and v >= 0.0 and mu >= 0.0)


def checked_steps(steps):
    """``checked(c)``: if :func:`inputs_plausible`, evaluate ``steps`` on ``c`` and return
    True; else return False and change nothing."""
    def checked(c, _ok=inputs_plausible):
        if not _ok(c):
            return False
        for step in steps:
            step(c)
        return True
    return checked


def build_pipeline(scene, tables_dir=None, warn=None, creep_table=None, normal_unit=None):
    """Build the effects ``scene`` switches on (and only those), in the registry's order.

    The normal contact comes first, then the effects of :data:`railcontact.scene.EFFECTS` that
    the scene switches on, in that order; an effect that another one replaces (registry field
    ``replaces``: creep under velocity friction or roughness) is not built, the replacing
    effect supplies all of its outputs (:attr:`Pipeline.replaced`).

    Parameters
    ----------
    scene : Scene
        A validated scene.
    tables_dir : path-like, optional
        Directory holding the shipped ``<name>.nc`` tables (the FMU's resources); default:
        :func:`railcontact.tables.default_table_path`.
    warn : callable, optional
        ``warn(key, message)`` for warnings the effects log (the caller logs each key once).
    creep_table : optional
        A creep table reader already loaded for this scene (another contact's): the creep
        effect uses it instead of loading one (:class:`railcontact.effects.Vehicle`).
    normal_unit : tuple, optional
        The scene's Hertz ellipse at 1 N (a1, b1, p1) for a scene given by curvatures, if the
        caller made it (:class:`~.normal.NormalContact`'s ``unit``).

    Raises
    ------
    SceneError
        If an effect is not available in this build or its options are invalid.
    MissingDependency
        If the host Python lacks a third-party module an effect needs (netCDF4 to read a
        table, numba): named, with how to install it.
    """
    for name in scene.effects:
        if name not in EFFECTS:
            raise EffectUnavailable(f"effect {name} not available in this build")
    replaced = {victim: name for name in EFFECTS if name in scene.effects
                for victim in EFFECTS[name].replaces if victim in scene.effects}
    effects = {"normal": NormalContact(scene, warn=warn, unit=normal_unit)}
    wear = None
    for name in EFFECTS:
        if name not in scene.effects or name in replaced:
            continue
        try:
            if name == "corrugation" and "wear" in scene.effects:
                # the wear effect first: the corrugated contact sums its coefficients
                from .wear import Wear

                wear = Wear(scene, tables_dir=tables_dir, warn=warn)
            effect = (wear if name == "wear" and wear is not None
                      else _build_effect(name, scene, tables_dir, warn, wear, creep_table))
        except ImportError as exc:
            missing = (exc.name or "").split(".")[0]
            if missing and missing != __name__.split(".")[0]:
                # a module of the host's Python environment, not of this package
                raise MissingDependency(
                    f"effect {name} needs the Python module {missing!r}, which the host Python "
                    f"({sys.executable}) cannot import: {exc} (install it in that interpreter, "
                    f"e.g. `python -m pip install {_PIP_NAMES.get(missing, missing)}`)"
                ) from None
            # a model module missing from this build
            raise EffectUnavailable(f"effect {name} not available in this build ({exc})"
                                    ) from None
        effects[name] = effect
    if wear is not None:
        wear.corrugation = effects["corrugation"]
    return Pipeline(scene, effects, replaced)


def _build_effect(name, scene, tables_dir, warn, wear, creep_table=None):
    """The effect object ``name`` of the registry for ``scene`` (its module, and with it its
    model's, is imported here: a scene loads only the effects it switches on)."""
    if name == "nonsteady":
        from .nonsteady import NonSteady

        return NonSteady(scene)
    if name == "creep":
        from .creep import Creep2D, Creep3D

        if scene.effects["creep"]["method"] == "carter":
            return Creep2D(scene)
        return Creep3D(scene, tables_dir=tables_dir, warn=warn, table=creep_table)
    if name == "velocity_friction":
        from .velocity_friction import VelocityFriction

        return VelocityFriction(scene, tables_dir=tables_dir, warn=warn)
    if name == "roughness":
        from .roughness import Roughness

        return Roughness(scene)
    if name == "corrugation":
        from .corrugation import Corrugation

        return Corrugation(scene, wear=wear, tables_dir=tables_dir, warn=warn)
    if name == "wear":
        from .wear import Wear

        return Wear(scene, tables_dir=tables_dir, warn=warn)
    raise EffectUnavailable(f"effect {name} not available in this build")
