r"""Effects of the WheelRailContact FMU: one small object per physical effect, and the pipeline.

The FMU slave (``fmu_src/WheelRailContact.py``) builds, at initialisation, only the effects a
:class:`~railcontact.scene.Scene` switches on (:func:`build_pipeline`), and each communication
step calls only those (:meth:`Pipeline.step`; the slave uses :attr:`Pipeline.checked_step`, the
same behind a cheap input check). Every effect reads and writes the fields of one
:class:`ContactPoint` and keeps its own call counter (``calls``), which tests use to show that a
switched-off effect costs nothing.

One module per effect, plus what they share and the pipeline:

============================  ===============================================================
``base``                      :class:`ContactPoint`, the base class :class:`Effect`,
                              :class:`EffectUnavailable`, :data:`NOT_ESTIMATED`, the table loader
``normal``                    :class:`NormalContact`: Hertz (Ch. 2), always on
``nonsteady``                 :class:`NonSteady`: relaxed creepages (Ch. 7)
``creep``                     :class:`Creep3D` (analytic, modified-strip and exact tables),
                              :class:`Creep2D` (Carter)
``velocity_friction``         :class:`VelocityFriction` (Ch. 5)
``roughness``                 :class:`Roughness`: rough rail (Ch. 6)
``corrugation``               :class:`Corrugation`: corrugated rail (Ch. 4.2)
``wear``                      :class:`Wear`: wear per passage, surface evolution (Ch. 4.3-4.4)
``response_table``            the table ``corrugation_response`` the last two read
``pipeline``                  :class:`Pipeline`, :func:`build_pipeline`, :func:`checked_steps`
============================  ===============================================================

Each effect takes its physics from :mod:`railcontact` (the analytic solvers) or from the shipped
tables (:mod:`railcontact.tables`); nothing here re-implements a model. An effect whose model
or table is not part of this build raises a :class:`~railcontact.scene.SceneError` at build
time ("effect X not available in this build"), never a placeholder result. The pipeline
imports an effect's module (and with it its model's) when the scene switches the effect on, so
a scene loads only the models it uses; the names below are imported on first access.

Order of evaluation in a step: the normal contact (Hertz, always), then the effects the scene
switches on in the order of the registry :data:`railcontact.scene.EFFECTS`, which scene
validation reads too: non-steady correction, creep forces, velocity-dependent friction,
roughness, corrugation, wear (then the non-steady correction's ``finish`` step). An effect that
*replaces* another (registry field ``replaces``) is evaluated in its place: with velocity
friction or roughness on, Carter's force is not computed (:attr:`Pipeline.replaced`).

The non-steady correction (:class:`NonSteady`) runs just before the creep effects: it replaces
the creepage fields of the :class:`ContactPoint` by its relaxed creepages, so every creep-force
effect (Creep3D, Creep2D, VelocityFriction, ...) reads them unchanged, and puts the inputs back
after the last effect (its ``finish`` step, :attr:`Pipeline.steps`), so the FMU's input
variables stay as the importer set them.

Sign convention: the forces are those acting on the wheel, opposing the creepage (see
:mod:`railcontact`).
"""

from __future__ import annotations

from ..scene import EFFECTS
from .base import JACOBIAN_FIELDS, NOT_ESTIMATED, ContactPoint, Effect, EffectUnavailable
from .normal import NO_NORMAL_FORCE_MESSAGE, NormalContact
from .pipeline import (MissingDependency, Pipeline, build_pipeline, checked_steps,
                       inputs_plausible)
from .vehicle import MAX_CONTACTS, Vehicle

__all__ = ["ContactPoint", "Vehicle", "MAX_CONTACTS", "MissingDependency", "Effect", "NormalContact", "Creep3D", "Creep2D", "VelocityFriction",
           "Corrugation", "Wear", "NonSteady", "Roughness",
           "Pipeline", "build_pipeline", "EffectUnavailable", "NOT_ESTIMATED",
           "JACOBIAN_FIELDS", "NO_NORMAL_FORCE_MESSAGE", "EFFECTS",
           "table_error_estimate", "wear_series_degree", "checked_steps", "inputs_plausible"]

#: Names imported on first access (``effects.Creep3D``), so that ``import railcontact.effects``
#: loads no model a scene does not use: name -> its module.
_LAZY = {"Creep3D": "creep", "Creep2D": "creep", "table_error_estimate": "creep",
         "VelocityFriction": "velocity_friction", "Corrugation": "corrugation",
         "wear_series_degree": "corrugation", "Wear": "wear", "NonSteady": "nonsteady",
         "Roughness": "roughness"}


def __getattr__(name):
    module = _LAZY.get(name)
    if module == "creep":
        from . import creep as module
    elif module == "velocity_friction":
        from . import velocity_friction as module
    elif module == "corrugation":
        from . import corrugation as module
    elif module == "wear":
        from . import wear as module
    elif module == "nonsteady":
        from . import nonsteady as module
    elif module == "roughness":
        from . import roughness as module
    else:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = globals()[name] = getattr(module, name)
    return value


def __dir__():
    return sorted(set(globals()) | set(_LAZY))
