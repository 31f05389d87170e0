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

The scene a vehicle model runs most, Kalker's exact theory from its table on contacts given
by their curvatures (effects normal and creep only), takes a path without per-effect Python
(:meth:`Vehicle.checked_step`): the inputs of all contacts are read into one array, checked,
the changed ellipses made in one compiled call (:func:`~.normal.unit_ellipses`' kernel), the
semi-axes scaled, the forces, moment, stick area and Jacobian of every contact evaluated in
one compiled call of the table's batch kernel on the table summed over Poisson's ratio (made
when the vehicle is built: :meth:`railcontact.exact_table.ExactCreepTable.prepare`), and the
outputs written back in one pass. A lifted wheel, a point beyond the table or another scene
takes the per-effect path above.

A contact gives what a single-contact instance with the same inputs gives: the same effect
code or the same kernels, and the batched table call evaluates the same spline (round-off
apart: tests/test_fmu_vehicle.py). Errors name the contact (1-based, as in the FMU's
``name[k]``).
"""

from __future__ import annotations

import math
from operator import attrgetter

import numpy as np

from .. import _compiled
from .._validation import check_range
from ..scene import INPUTS
from .normal import (NO_NORMAL_FORCE_MESSAGE, check_geometry_input, inverse_grid,
                     unit_ellipses)
from .pipeline import build_pipeline, inputs_plausible

_EMPTY = np.zeros(0)

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
        unit = None
        if scene.geometry["kind"] == "curvatures":
            # the scene's ellipse at 1 N once, by the kernel of the changing curvatures (no
            # scipy import; hertz_3d's values to a few ulp)
            unit = tuple(float(v[0]) for v in unit_ellipses(
                np.array([scene.geometry["curvature_longitudinal"]]),
                np.array([scene.geometry["curvature_lateral"]]), scene.youngs_modulus,
                scene.poisson_ratio))
        first = build_pipeline(scene, tables_dir=tables_dir, warn=warn, normal_unit=unit)
        creep = first.effects.get("creep")
        table = getattr(creep, "_table", None)
        # one reader object for every contact (the loader gives it; the others reuse it)
        self.pipelines = [first] + [build_pipeline(scene, tables_dir=tables_dir, warn=warn,
                                                   creep_table=table, normal_unit=unit)
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
            if getattr(creep, "_smooth_law", None) is not None:    # falling friction
                self._batch = self._falling_batch
                self._falling_setup(creep)
        self.summary = first.summary()
        self._pipeline_of = {id(c): p for c, p in zip(self.contacts, self.pipelines)}
        self._warn = warn if warn is not None else (lambda key, msg: None)
        self._lazy = True       # (outputs may be computed when read: auxiliary)
        # (falling friction keeps the per-effect path into its batch: through the array path
        # its step took 90 us against 84 us, 8 contacts, 2026-11-29)
        self._fast = (names == ["normal", "creep"] and self._batch == self._exact_batch
                      and self._curvatures)
        if self._fast:
            self._fast_setup(creep)

    # -- the array path (exact table, curvatures, normal and creep only) --------------------
    #: The inputs the array path reads, in the order of its rows: the three that must be
    #: >= 0 first, then the other four checked for being finite, then the curvatures.
    _FAST_INPUTS = ("normal_force", "rolling_speed", "friction_coefficient",
                    "creepage_longitudinal", "creepage_lateral", "spin", "rail_position",
                    "curvature_longitudinal", "curvature_lateral")

    def _fast_setup(self, creep):
        k = len(self.contacts)
        self._read = attrgetter(*self._FAST_INPUTS)
        # the curvatures (2, K) of the ellipses at 1 N in self._unit (3, K): a0, b0, p0
        # (the normal effects keep their own, the per-effect path's: both map curvatures to
        # the same ellipse, so neither needs the other's)
        self._cxy = np.array([[n._cx for n in self._normals], [n._cy for n in self._normals]])
        self._unit_rows = np.array([[n._a1, n._b1, n._p1] for n in self._normals])   # (K, 3)
        self._unit = self._unit_rows.T
        self._e_star = float(self._e / (2.0 * (1.0 - self._nu**2)))
        table = self._table
        table.prepare(self._nu)     # (deterministic: every step on the table summed over nu)
        self._coef = table._nu_slabs[float(self._nu)][0]
        self._tbuf = table._tbuf
        self._e_k, self._nu_k = np.full(k, float(self._e)), np.full(k, float(self._nu))
        self._zeros = np.zeros(k)
        self._r, self._ok = np.zeros((k, 14)), np.zeros(k, dtype=bool)
        self._out = np.zeros((k, 19))
        self._kernel = None         # the batch kernel, resolved with the first step
        self._estimate = creep.table_error_estimate
        self._rows = list(zip(self.contacts, self._normals, self._creeps))

    def _fast_geometry(self, cxy):
        """New ellipses at 1 N for the contacts whose curvatures ``cxy`` (2, K; checked)
        changed: one compiled call."""
        nodes, coefficients = inverse_grid()
        kernel = _compiled.unit_ellipses_kernel()
        changed = (cxy != self._cxy).any(axis=0)
        if changed.all():           # (a vehicle's contacts move together)
            if kernel(cxy[0], cxy[1], self._e_star, nodes, coefficients, self._unit_rows):
                self._unit_rows[:] = np.column_stack(unit_ellipses(cxy[0], cxy[1], self._e,
                                                                   self._nu))   # (rare)
            self._cxy[:] = cxy
            return
        changed = np.flatnonzero(changed)
        cx, cy = cxy[0, changed], cxy[1, changed]
        out = np.empty((changed.size, 3))
        if kernel(cx, cy, self._e_star, nodes, coefficients, out):
            out = np.column_stack(unit_ellipses(cx, cy, self._e, self._nu))   # (rare)
        self._unit_rows[changed] = out
        self._cxy[:, changed] = cxy[:, changed]

    def _fast_step(self, step_size):
        """The array path: True when stepped, False (nothing changed) if the cheap input check
        fails, None where it does not apply (a geometry input not set yet)."""
        contacts = self.contacts
        read = self._read
        try:
            x = np.array([read(c) for c in contacts], dtype=float).T.copy()
        except TypeError:           # (None: a geometry input not set yet)
            return None
        cxy = x[7:9]
        if not (math.isfinite(float(x[:7].sum())) and x[:3].min() >= 0.0):
            return False
        if (cxy != self._cxy).any():
            if not (cxy.min() > 0.0 and cxy.max() < math.inf):
                if any(c.curvature_longitudinal is None or c.curvature_lateral is None
                       for c in contacts):
                    return None     # (None reads as NaN: the scene's values, per effect)
                for k, c in enumerate(contacts):
                    try:
                        check_geometry_input("curvature_longitudinal", cxy[0, k], "1/m")
                        check_geometry_input("curvature_lateral", cxy[1, k], "1/m")
                    except ValueError as exc:
                        raise ValueError(f"contact {k + 1}: {exc}") from None
            self._fast_geometry(cxy)
        n_load = x[0]
        scale = n_load ** (1.0 / 3.0)
        unit = self._unit
        a0, b0, p0 = unit[0] * scale, unit[1] * scale, unit[2] * scale
        r, ok = self._r, self._ok
        live = n_load.min() > 0.0
        if live:
            args = (self._tbuf, self._coef, x[3], x[4], x[5] if self._use_spin else self._zeros,
                    n_load, a0, b0, self._e_k, self._nu_k, x[2], True, 4, r, ok)
            kernel = self._kernel
            if kernel is None:
                kernel = self._kernel = _compiled.batch_kernel("creep_table_batch_nu", args)
            kernel(*args)
            live = ok.all()
        self._lazy = False
        if not live:            # a lifted wheel, a point beyond the table: per contact
            for (c, normal, _), a0_, b0_, p0_ in zip(self._rows, a0.tolist(), b0.tolist(),
                                                      p0.tolist()):
                normal.calls += 1
                c.step_size = step_size
                c.a0, c.b0, c.p0 = a0_, b0_, p0_
                c.contact_half_width = a0_
                if c.normal_force <= 0.0 and (c.creepage_longitudinal or c.creepage_lateral
                                              or c.spin):
                    self._warn("no-normal-force", NO_NORMAL_FORCE_MESSAGE)
            self._exact_batch()
            return True
        out = self._out
        out[:, 0], out[:, 1], out[:, 2] = a0, b0, p0
        out[:, 3:17] = r
        zc = np.minimum(r[:, 4], 1.0)
        np.sqrt(1.0 - zc * zc, out=out[:, 17])          # b*/b0, Eq. (2.84)
        np.subtract(1.0, zc, out=out[:, 18])            # a*(0)/a0, Eq. (2.83)
        estimate = self._estimate
        for (c, normal, creep), row in zip(self._rows, out.tolist()):
            normal.calls += 1
            creep.calls += 1        # (its _aux_args stay None: the exact table's)
            c.step_size = step_size
            (c.a0, c.b0, c.p0, c.Fx, c.Fy, c.Mz, c.stick_area_fraction, _,
             c.dFx_dxi_x, c.dFx_dxi_y, c.dFx_dphi, c.dFy_dxi_x, c.dFy_dxi_y, c.dFy_dphi,
             c.dMz_dxi_x, c.dMz_dxi_y, c.dMz_dphi, c.stick_width_ratio, c.r_a0) = row
            c.contact_half_width = row[0]
            c.creep_within_validity = True
            c.creep_table_error_estimate = estimate
        return True

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

    def checked_step(self, step_size):
        """:meth:`step` behind the cheap input check of every contact
        (:func:`~.pipeline.inputs_plausible`): True when stepped, False (nothing changed)
        when the check does not pass (the caller then makes :meth:`check_inputs`, which names
        the input)."""
        if self._fast:
            done = self._fast_step(step_size)
            if done is not None:
                return done
        if not all(inputs_plausible(c) for c in self.contacts):
            return False
        self._plain_step(step_size)
        return True

    def fmu_step(self, otherwise, on_error):
        """The FMU's ``do_step(current_time, step_size)`` for this vehicle (as
        :meth:`~.pipeline.Pipeline.fmu_step` for one contact): :meth:`checked_step`, else
        ``otherwise(current_time, step_size)`` (the slave's full path: the range check that
        names the input, then :meth:`step`); a model's ValueError goes to
        ``on_error(current_time, exc)`` and is re-raised."""
        checked = self.checked_step

        def do_step(current_time, step_size, _inf=math.inf):
            if 0.0 <= step_size < _inf:
                try:
                    if checked(step_size):
                        return True
                except ValueError as exc:
                    on_error(current_time, exc)
                    raise
            return otherwise(current_time, step_size)
        return do_step

    def step(self, step_size):
        """Evaluate every contact (inputs checked by :meth:`check_inputs` first). A model's
        ValueError is re-raised naming the contact."""
        if self._fast and self._fast_step(step_size):
            return
        self._plain_step(step_size)

    def _plain_step(self, step_size):
        """The per-effect path of :meth:`step`."""
        self._lazy = True
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

    def _falling_setup(self, creep):
        """Falling friction (the scene's smooth law) on the exact table: what
        :meth:`_falling_batch` passes its kernel, made once (deterministic, as each contact's
        own path: the table summed over nu, the correction table summed over nu and, for the
        scene's shape, over a0/b0)."""
        from ..falling_table import correction_at, kernel_model_arguments  # noqa: PLC0415

        table = self._table
        table.prepare(self._nu)
        self._f_coef = table._nu_slabs[float(self._nu)][0]
        held = creep._held          # (the scene's shape, its buffer made at setup)
        self._f_shape = None if held is None else held[0]
        self._f_buf = table._tbuf if held is None else held[1][0]
        model, no_law_table = kernel_model_arguments()
        self._f_args = (
            correction_at(self._nu, 0.0, now=True),
            _EMPTY if held is None else correction_at(self._nu, 0.0, held[0], now=True),
            *model)
        self._f_law = (0, *creep._smooth_law, 0.0, no_law_table)
        self._f_kernel = _compiled.falling_contacts()

    def _falling_batch(self):
        """Falling friction for every contact in contact: each contact's shape counted and its
        path chosen as its own effect would (the scene's shape on its buffer, a changing one on
        the table's five-dimensional spline), then one compiled call for all; a contact the
        kernel hands back, one holding another shape for long, or one without friction takes
        its own effect's path."""
        live = self._live()
        if not live:
            return
        spin, e_mod, nu = self._use_spin, self._e, self._nu
        shape = self._f_shape
        rows, batch, own = [], [], []
        for k in live:
            c, creep = self.contacts[k], self._creeps[k]
            if not c.friction_coefficient > 0.0:
                creep.step(c)
                continue
            creep.calls += 1
            c.creep_table_error_estimate = creep.table_error_estimate
            creep._count_shape(c.a0, c.b0)
            held = creep._shape_buffer(c.a0 / c.b0)
            args = (c.creepage_longitudinal, c.creepage_lateral, c.spin if spin else 0.0,
                    c.normal_force, c.a0, c.b0, e_mod, nu, c.friction_coefficient)
            if held is None or held[0] == shape:
                rows.append(args)
                batch.append((k, held is not None))
            else:
                own.append((k, args))
        if rows:
            x = np.array(rows).T.copy()
            n = len(rows)
            on_buffer = np.array([b for _, b in batch], dtype=bool)
            out, ok = np.zeros((n, 6)), np.zeros(n, dtype=bool)
            kind, mu_k, kappa, p3, tab = self._f_law
            corr, corr_buf, gauss, steps, share, model = self._f_args
            self._f_kernel(self._table._tbuf, self._f_coef, self._f_buf, on_buffer, x[0], x[1],
                           x[2], x[3], x[4], x[5], e_mod, nu, kind, x[8], mu_k, kappa, p3, tab,
                           corr, corr_buf, gauss, steps, share, model, out, ok)
            values, ok = out.tolist(), ok.tolist()
            for j, (k, _) in enumerate(batch):
                if ok[j]:
                    self._creeps[k].set_falling(self.contacts[k], rows[j], values[j])
                else:
                    own.append((k, rows[j]))
        for k, args in own:
            creep = self._creeps[k]
            creep.set_falling(self.contacts[k], args, creep._falling_forces(args))

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
        self._on_demand("auxiliary", contact)

    def jacobian(self, contact=None):
        """The Jacobian outputs where an effect computes them only when read (falling
        friction), of ``contact`` or of every contact (None), as :meth:`auxiliary`."""
        self._on_demand("jacobian", contact)

    def _on_demand(self, what, contact):
        """The pipelines' ``what`` (auxiliary, jacobian) of ``contact`` or of every contact."""
        if not self._lazy:      # (the array path set every output)
            return
        if contact is not None:
            getattr(self._pipeline_of[id(contact)], what)(contact)
            return
        for p, c in zip(self.pipelines, self.contacts):
            getattr(p, what)(c)

    def get_state(self):
        return [p.get_state() for p in self.pipelines]

    def set_state(self, state):
        self._lazy = True
        for p, s in zip(self.pipelines, state):
            p.set_state(s)
