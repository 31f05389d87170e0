"""A vehicle: K contacts of one scene in one FMU instance, stepped together.

Each contact keeps its own state in its own effect objects (one :class:`~.pipeline.Pipeline` per
contact: the non-steady relaxed creepages, the wear and corrugation state are per contact);
the costly parts are evaluated for all K contacts at once:

* the Hertz ellipses of every contact whose curvatures changed, in one
  :func:`~.normal.unit_ellipses` call;
* the creep forces of a table scene (``source = "table"``: Kalker's exact theory from
  ``creep_exact``, the modified strip theory from ``creep_modified_strip``) in ONE vectorised
  call of the table reader with length-K arrays (:meth:`railcontact.exact_table.ExactCreepTable.
  evaluate_contacts`: one compiled loop, Kalker's coefficients inside it;
  :meth:`railcontact.strip_table.CreepTable._solve`), not K calls. The analytic
  theories keep their per-contact scalar paths (a loop over the contacts).

A contact gives what a single-contact instance with the same inputs gives: the same effect
code, and the batched table call evaluates the same spline (round-off apart:
tests/test_fmu_vehicle.py). Errors name the contact (1-based, as in the FMU's ``name[k]``).
"""

from __future__ import annotations

import math

import numpy as np

from .._validation import check_range
from ..scene import INPUTS
from .normal import check_geometry_input, unit_ellipses
from .pipeline import build_pipeline

__all__ = ["Vehicle", "MAX_CONTACTS"]

#: The most contacts one instance serves (``build_fmu.py --contacts K``).
MAX_CONTACTS = 32


class Vehicle:
    """K contacts of one scene: per-contact effects, batched Hertz and creep-table calls.

    Parameters
    ----------
    scene : Scene
        The validated scene (one for all contacts).
    contacts : list of ContactPoint
        One per contact; their geometry and friction fields are set by the caller.
    tables_dir, warn
        As for :func:`~.pipeline.build_pipeline`.
    """

    def __init__(self, scene, contacts, tables_dir=None, warn=None):
        self.scene = scene
        self.contacts = list(contacts)
        first = build_pipeline(scene, tables_dir=tables_dir, warn=warn)
        creep = first.effects.get("creep")
        table = getattr(creep, "_table", None)
        # one reader object for every contact (the loader gives it; the others reuse it)
        self.pipelines = [first] + [build_pipeline(scene, tables_dir=tables_dir, warn=warn,
                                                   creep_table=table)
                                    for _ in self.contacts[1:]]
        names = list(first.effects)
        i = names.index("creep") if "creep" in names else len(names)
        self._normals = [p.effects["normal"] for p in self.pipelines]
        self._curvatures = scene.geometry["kind"] == "curvatures"
        self._e, self._nu = scene.youngs_modulus, scene.poisson_ratio
        self._before = [tuple(list(p.effects.values())[k].step for k in range(i))
                        for p in self.pipelines]
        self._after = [tuple(e.step for e in list(p.effects.values())[i + 1:])
                       + tuple(e.finish for e in p.effects.values() if hasattr(e, "finish"))
                       for p in self.pipelines]
        self._creeps = [p.effects[names[i]] for p in self.pipelines] if i < len(names) else []
        self._batch = None
        if self._creeps and getattr(creep, "source", None) == "table":
            self._batch = self._exact_batch if creep._exact else self._strip_batch
            self._table = table
            self._use_spin = creep.use_spin
        self.summary = first.summary()
        self._pipeline_of = {id(c): p for c, p in zip(self.contacts, self.pipelines)}

    # -- the step ------------------------------------------------------------------------------
    def check_inputs(self):
        """ValueError naming the contact and the input if one is invalid (NaN, inf, N < 0,
        V < 0, mu < 0); cheap when all are valid."""
        isfinite = math.isfinite
        for k, c in enumerate(self.contacts):
            n, v, mu = c.normal_force, c.rolling_speed, c.friction_coefficient
            if isfinite(n + c.creepage_longitudinal + c.creepage_lateral + c.spin + v
                        + c.rail_position + mu) and n >= 0.0 and v >= 0.0 and mu >= 0.0:
                continue
            for name, lower in (("normal_force", 0.0), ("creepage_longitudinal", None),
                                ("creepage_lateral", None), ("spin", None),
                                ("rolling_speed", 0.0), ("rail_position", None),
                                ("friction_coefficient", 0.0)):
                unit = INPUTS[name][0] if name in INPUTS else "1"
                try:
                    check_range(name, getattr(c, name), unit, lower, None)
                except ValueError as exc:
                    raise ValueError(f"contact {k + 1}: {name}[{k + 1}]: {exc}") from None

    def step(self, step_size):
        """Evaluate every contact (inputs checked by :meth:`check_inputs` first). A model's
        ValueError is re-raised naming the contact."""
        contacts = self.contacts
        for c in contacts:
            c.step_size = step_size
        self._geometry()
        k = 0
        try:
            for k, c in enumerate(contacts):
                for step in self._before[k]:
                    step(c)
            if self._batch is not None:
                self._batch()
            else:
                for k, c in enumerate(contacts):
                    if self._creeps:
                        self._creeps[k].step(c)
            for k, c in enumerate(contacts):
                for step in self._after[k]:
                    step(c)
        except ValueError as exc:
            raise ValueError(f"contact {k + 1}: {exc}") from None

    def _geometry(self):
        """New Hertz ellipses at 1 N for every contact whose geometry inputs changed: one
        :func:`unit_ellipses` call for all changed curvatures."""
        changed = [k for k, (normal, c) in enumerate(zip(self._normals, self.contacts))
                   if normal.geometry_changed(c)]
        if not changed:
            return
        if not self._curvatures:        # semi-axes: no solve, per contact
            for k in changed:
                try:
                    self._normals[k].set_geometry(self.contacts[k])
                except ValueError as exc:
                    raise ValueError(f"contact {k + 1}: {exc}") from None
            return
        cx, cy = np.empty(len(changed)), np.empty(len(changed))
        for j, k in enumerate(changed):
            c = self.contacts[k]
            try:
                cx[j] = check_geometry_input("curvature_longitudinal",
                                             c.curvature_longitudinal, "1/m")
                cy[j] = check_geometry_input("curvature_lateral", c.curvature_lateral, "1/m")
            except ValueError as exc:
                raise ValueError(f"contact {k + 1}: {exc}") from None
        a1, b1, p1 = (v.tolist() for v in unit_ellipses(cx, cy, self._e, self._nu))
        for j, k in enumerate(changed):
            self._normals[k].set_geometry(self.contacts[k], (a1[j], b1[j], p1[j]))

    def _live(self):
        """Contacts in contact (N > 0); the others take their creep effect's no-contact step."""
        live = []
        for k, c in enumerate(self.contacts):
            if c.normal_force > 0.0:
                live.append(k)
            else:
                self._creeps[k].step(c)
        return live

    def _arguments(self, live):
        cs = [self.contacts[k] for k in live]
        spin = self._use_spin
        return (np.array([c.creepage_longitudinal for c in cs]),
                np.array([c.creepage_lateral for c in cs]),
                np.array([c.spin if spin else 0.0 for c in cs]),
                np.array([c.normal_force for c in cs]), np.array([c.a0 for c in cs]),
                np.array([c.b0 for c in cs]), self._e, self._nu,
                np.array([c.friction_coefficient for c in cs]))

    def _exact_batch(self):
        """Kalker's exact theory for every contact in contact: one table call."""
        live = self._live()
        if not live:
            return
        # the inputs are checked (finite, N > 0, mu >= 0: fmu_step): one compiled call
        res, jac = self._table.evaluate_contacts(*self._arguments(live), jacobian=True)
        res, jac = res.tolist(), jac.reshape(len(live), 9).tolist()
        sqrt = math.sqrt
        for j, k in enumerate(live):
            c, creep = self.contacts[k], self._creeps[k]
            creep.calls += 1
            c.creep_table_error_estimate = creep.table_error_estimate
            c.Fx, c.Fy, c.Mz, stick, z = res[j]
            zc = z if z < 1.0 else 1.0
            c.stick_area_fraction = stick
            c.stick_width_ratio = sqrt(1.0 - zc * zc)       # b*/b0, Eq. (2.84)
            c.r_a0 = 1.0 - zc                               # a*(0)/a0, Eq. (2.83)
            c.creep_within_validity = True
            (c.dFx_dxi_x, c.dFx_dxi_y, c.dFx_dphi, c.dFy_dxi_x, c.dFy_dxi_y, c.dFy_dphi,
             c.dMz_dxi_x, c.dMz_dxi_y, c.dMz_dphi) = jac[j]
            creep._aux_args = None

    def _strip_batch(self):
        """The modified strip theory's table for every contact in contact: one table call for
        the forces; the stick measures per contact when read (as a single contact)."""
        live = self._live()
        if not live:
            return
        args = self._arguments(live)
        tx, ty = (v.tolist() for v in self._table._solve(args)[:2])
        columns = [v.tolist() if isinstance(v, np.ndarray) else [v] * len(live) for v in args]
        for j, k in enumerate(live):
            c, creep = self.contacts[k], self._creeps[k]
            creep.calls += 1
            c.creep_table_error_estimate = creep.table_error_estimate
            c.Fx, c.Fy = tx[j], ty[j]
            creep._aux_args = tuple(col[j] for col in columns)

    # -- the rest --------------------------------------------------------------------------------
    def auxiliary(self, contact=None):
        """The outputs computed only when read: of ``contact`` (one of :attr:`contacts`), or of
        every contact (None)."""
        if contact is not None:
            self._pipeline_of[id(contact)].auxiliary(contact)
            return
        for p, c in zip(self.pipelines, self.contacts):
            p.auxiliary(c)

    def get_state(self):
        return [p.get_state() for p in self.pipelines]

    def set_state(self, state):
        for p, s in zip(self.pipelines, state):
            p.set_state(s)
