"""The creep-force effects: 3-D creep (analytic theories, the modified-strip and exact tables)
and Carter's 2-D force on a line contact."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from .. import creep3d
from .._scalar import (carter_scalar, creep_force_3d_scalar, creep_stick_3d_scalar,
                       spin_coefficient_scalar)
from ..exact_table import SLAB_AFTER_POINTS
from ..falling_table import (EFFECTIVE_MU_STEPS, falling_friction_table,
                             falling_friction_table_compiled, falling_friction_table_smooth)
from ..scene import POLACH_KEYS, SceneError
from .base import JACOBIAN_FIELDS, NOT_ESTIMATED, Effect, EffectUnavailable

__all__ = ["Creep3D", "Creep2D", "table_error_estimate", "FALLING_BUFFER_AFTER_STEPS",
           "SAME_SHAPE_RTOL"]


def table_error_estimate(table):
    r"""Recorded max error of a creep table's force, in units of mu N, from its file attributes.

    The table files record, per variable, the max ``|spline - direct computation|`` on seeded
    random off-grid check points (netCDF attribute ``<variable>:max_abs_error``, read by
    :meth:`railcontact.tables.Table.accuracy`); the direct computation is the theory the table
    holds, so this is the interpolation error only, not the theory's own error.

    * ``creep_modified_strip`` (:class:`railcontact.strip_table.CreepTable`): the force is
      ``-mu N F(z) w/|w|`` with the direction exact, so the error of the force over mu N is that
      of ``force_ratio``.
    * ``creep_exact`` (:class:`railcontact.exact_table.ExactCreepTable`): the force over mu N has the
      components ``force_ratio_parallel`` and ``force_ratio_perpendicular``; the returned bound on
      the error of the force vector is ``hypot`` of their two recorded maxima. It is against the
      solver the table was built with (file attribute ``solver_grid``: Richardson-extrapolated
      30 x 20 / 60 x 20 elements on two shifted grids), whose own error against the converged
      exact theory is in docs/tables.md.

    Parameters
    ----------
    table : railcontact.strip_table.CreepTable or railcontact.exact_table.ExactCreepTable
        A loaded creep table.

    Returns
    -------
    float
        Max error of |T| / (mu N) over the check points. [-] :data:`NOT_ESTIMATED` (-1) if the
        file records no accuracy.
    """
    acc = table.table.accuracy()
    names = (("force_ratio",) if "force_ratio" in acc
             else ("force_ratio_parallel", "force_ratio_perpendicular"))
    errors = [acc[n]["max_abs_error"] for n in names]
    if not all(math.isfinite(e) for e in errors):
        return NOT_ESTIMATED
    return float(math.hypot(*errors))


#: Slips beyond this over max(kappa, 1) are evaluated there by the smooth law (its value is
#: then mu_k to round-off): kappa s stays finite for any finite creepage. [-]
_SLIP_CAP = 1e300

#: Steps a contact's a0/b0 must hold (to :data:`SAME_SHAPE_RTOL`) before its falling-friction
#: step takes the exact table's contact buffer for that shape (some 20 ms and 4.7 MB to make,
#: a third of the step's kernel time after): the table's own ski rental
#: (:data:`railcontact.exact_table.SLAB_AFTER_POINTS` points, three a step), counted in the
#: effect's state. A contact whose a0/b0 changes at every step (a vehicle's on its track)
#: never pays it; one that holds its shape pays at most about twice the least. The scene's
#: own shape has its buffer from the start.
FALLING_BUFFER_AFTER_STEPS = SLAB_AFTER_POINTS // (EFFECTIVE_MU_STEPS + 1)

#: Relative change of a0/b0 within which a contact keeps its shape: a0 and b0 scale with the
#: cube root of the load, which leaves a0/b0 within an ulp or two of the unit ellipse's. [-]
SAME_SHAPE_RTOL = 1e-12


class Creep3D(Effect):
    r"""3-D creep forces: ``effects.creep`` (method, spin on/off, analytic or table).

    Analytic: :func:`railcontact.creep3d.creep_solution_3d` (Kalker's linear theory, Shen,
    Hedrick and Elkins, strip or modified strip theory, Nielsen Sec. 2.5-2.6), which also gives
    the stick area fraction, the stick width ratio b*/b0 and the validity flag (spin pole
    outside the ellipse). ``r_a0`` is the stick zone's length over the contact length on the
    centre line y = 0 of the strip theories, ``a*(0)/a0 = 1 - min(z, 1)`` (Eq. (2.83) with
    a(0) = a0, z the normalised creepage of :func:`~railcontact.creep3d.creep_solution_3d`);
    1 for the linear theory (full stick by assumption). With N = 0 (no contact) the forces are
    0 and the stick measures 1.

    Per step the effect calls the *scalar paths* (plain floats, ``math`` module; they repeat the
    public functions' arithmetic without numpy's per-call overhead and without their input
    check, which the slave has made: finite inputs, N >= 0; a0, b0 > 0 from Hertz; mu is
    checked here): ``railcontact._scalar.creep_force_3d_scalar`` for the analytic source's
    forces and normalised creepage in the step, and ``creep_stick_3d_scalar`` for its stick
    measures and validity flag from them, computed when first read after a step
    (:meth:`auxiliary`), so that an importer that reads only Fx and Fy does not pay for them
    (their table-driven test against :func:`~railcontact.creep3d.creep_force_3d` and
    :func:`~railcontact.creep3d.creep_solution_3d` is tests/test_scalar.py), and the
    modified-strip table reader's
    :meth:`~railcontact.strip_table.CreepTable.force_unchecked` and
    :meth:`~railcontact.strip_table.CreepTable.stick_unchecked` (tests/test_tables.py).

    Table (``method = "modified_strip"`` only, the theory the shipped table holds):
    :meth:`railcontact.strip_table.CreepTable.force_unchecked` gives the forces in the step (the
    table's one scalar implementation, without the input check the slave has already made);
    the stick measures and the
    validity flag are computed when first read after a step (:meth:`auxiliary`), as
    :meth:`~railcontact.strip_table.CreepTable.creep_solution_3d` gives them, on the inputs of that
    step, so an importer that reads only Fx and Fy does not pay for them. Out of the table's grid
    (normalised creepage z beyond its last node) the reader holds F = 1, which is exact (full
    sliding); the FMU logs a warning the first time this is seen (when the stick outputs are
    evaluated). ``creep_table_error_estimate`` is :func:`table_error_estimate` of the table.
    Kalker's exact theory (``method = "exact"``, table source only): the shipped table
    ``creep_exact`` (:class:`railcontact.exact_table.ExactCreepTable`, the extrapolated exact
    solver of :mod:`railcontact.reference.rolling3d` over a0/b0, nu and every creepage and
    spin), the only method that gives the spin moment ``Mz`` and the Jacobian outputs
    ``dFx_dxi_x`` ... ``dMz_dphi`` (0 for the others): one spline evaluation per step gives
    forces, moment, stick area fraction and Jacobian together (:meth:`ExactCreepTable.step`);
    ``stick_width_ratio`` and ``r_a0`` are the strip-theory estimates at the table's normalised
    creepage. Beyond the table's a0/b0 range (0.1-10) or spin coordinate (20) the reader calls
    the solver itself (milliseconds per step), so every input gets the exact theory.
    With ``spin = false`` the spin input is ignored (treated as 0).

    Falling friction (``friction_law = "smooth"``, method "exact" only): the smooth law (5.16)
    ``mu(s) = (mu_0 - mu_k) / (1 + kappa s) + mu_k`` with mu_0 the step's friction coefficient
    and ``kinetic_friction_coefficient``, ``kappa`` from the scene, through the Coulomb table
    (:mod:`railcontact.falling_table`: an effective coefficient and a spread correction, its
    compiled smooth-law path, one call per step; against the exact theory with the law 0.9 %
    of mu_0 N without spin or with spin coordinate |tau| <= 1, up to 5.5 % with larger spin;
    the numpy path where the table has no buffer for the contact). ``Mz``, the stick
    measures and z are the table's at the effective coefficient; the Jacobian outputs are
    the fast path's own slopes, by central differences when they are read (:meth:`jacobian`).

    FASTSIM, Polach, FaStrip (``method = "fastsim" | "polach" | "fastrip"``, analytic source
    only): the public :func:`~railcontact.creep3d.creep_solution_3d` each step (no scalar path;
    FASTSIM and FaStrip loop over their 40 elements per strip). Polach's 2005 parameters come
    from ``effects.creep.polach_*`` (:data:`railcontact.scene.POLACH_KEYS`) and his slip
    velocity from the ``rolling_speed`` input.
    """

    name = "creep"

    def __init__(self, scene, table_path=None, tables_dir=None, warn=None, table=None):
        super().__init__()
        opts = scene.effects["creep"]
        self.method = opts["method"]
        self.source = opts["source"]
        self.use_spin = opts["spin"]
        self._e, self._nu = scene.youngs_modulus, scene.poisson_ratio
        self._warn = warn if warn is not None else (lambda key, msg: None)
        self._aux_args = None
        self._jac_args = None     # falling friction: the step's arguments (jacobian, on demand)
        # falling friction: the contact's shape a0/b0 and the steps it has held it (state), the
        # scene's own shape, and the contact buffer held for a shape: (shape, entry) or None
        self._shape_run = (0.0, 0)
        self._scene_shape = None
        self._held = None
        self._table = None
        # the forces of the analytic theories and of the modified-strip table, (tx, ty) from
        # the step's arguments; their stick measures are set when read (auxiliary)
        self._force = None
        self._stick_measures = None
        self._solution = (0.0, 0.0, 0.0)    # the analytic step's (tx, ty, z)
        self._exact = self.method == "exact"
        # falling friction on the exact table (friction_law = "smooth"): (mu_k, kappa)
        self._smooth_law = ((float(opts["kinetic_friction_coefficient"]), float(opts["kappa"]))
                            if opts.get("friction_law", "coulomb") == "smooth" else None)
        #: Whether :meth:`jacobian` computes the Jacobian outputs when read (falling friction
        #: on the exact table; every other source sets them in its step).
        self.jacobian_on_demand = self._smooth_law is not None
        self._polach = {kw: float(opts.get(key, default)) for key, (kw, *_, default)
                        in POLACH_KEYS.items()}
        #: Output ``creep_table_error_estimate``: :func:`table_error_estimate` of the table in
        #: use (read once here), :data:`NOT_ESTIMATED` for the analytic source.
        self.table_error_estimate = NOT_ESTIMATED
        # the forces of one source, chosen here (``step`` calls it when there is contact)
        if self.source == "table":
            self._table_setup(opts, table_path, tables_dir, table, scene)
            self._forces = self._exact_table     # (modified strip: self._force, in step)
        elif self.method in creep3d.COMPARISON_METHODS:
            self._forces = self._comparison
        else:   # the forces now, the stick measures when read (auxiliary)
            self._force = self._analytic_force
            self._stick_measures = self._analytic_stick

    def _table_setup(self, opts, table_path, tables_dir, table=None, scene=None):
        if self.method not in ("modified_strip", "exact"):
            raise SceneError(f"effects.creep.method must be 'modified_strip' or 'exact' "
                             f"with source = 'table' (the shipped creep tables); got "
                             f"{self.method!r}")
        if table_path is None and tables_dir is not None:
            table_path = Path(tables_dir) / f"{opts['table']}.nc"
        try:
            if table is not None:       # (another contact's reader: Vehicle)
                self._table = table
            elif self._exact:
                self._table = creep3d.load_exact_table(table_path)
            else:
                from .. import strip_table      # (its spline: loaded only by a table scene)

                self._table = strip_table.CreepTable.from_file(table_path)
        except (OSError, ValueError, AttributeError) as exc:
            raise EffectUnavailable(f"effect creep (table {opts['table']}) not available "
                                    f"in this build: {exc}") from None
        self.table_error_estimate = table_error_estimate(self._table)
        if self._exact:
            # one evaluation at build (a round contact, moderate creepage; its result unused):
            # the reader's compiled kernels are loaded now, not in the first step
            try:
                self._table.step_values(1e-4, 1e-4, 0.1, 1e5, 6e-3, 6e-3, self._e, self._nu,
                                        0.3)
                if self._smooth_law is not None:    # (its compiled kernels loaded now too,
                    #                 the table summed over nu and the scene's shape made now)
                    falling_friction_table_smooth(self._table, 1e-4, 1e-4, 0.1, 1e5, 6e-3,
                                                  6e-3, self._e, self._nu, 0.3,
                                                  *self._smooth_law, path="table_point")
                    self._scene_shape = None if scene is None else scene_shape(scene)
                    if self._scene_shape is not None:
                        self._hold(self._scene_shape)
            except ValueError:
                pass            # (a scene outside the table's range: the step will say so)
        else:
            # The slave has range-checked every input (finite, N >= 0) and a0, b0 come from
            # Hertz: the reader's scalar path without its own input check
            self._force = self._table.force_unchecked
            self._stick = self._table.stick_unchecked
            self._stick_measures = self._table_stick
            self._z_max = float(self._table.table.axes[0]["nodes"][-1])

    def step(self, c):
        self.calls += 1
        c.creep_table_error_estimate = self.table_error_estimate
        if c.normal_force > 0.0:
            args = (c.creepage_longitudinal, c.creepage_lateral,
                    c.spin if self.use_spin else 0.0, c.normal_force, c.a0, c.b0, self._e,
                    self._nu, c.friction_coefficient)
            if self._force is None:
                self._forces(c, args)
            else:       # the forces now, the stick measures when read
                c.Fx, c.Fy = self._force(*args)
                self._aux_args = args
            return
        c.Fx = c.Fy = 0.0                              # no contact
        c.stick_area_fraction = c.stick_width_ratio = c.r_a0 = 1.0
        c.creep_within_validity = True
        c.Mz = 0.0
        self._jac_args = None
        for name in JACOBIAN_FIELDS:       # (no forces, none of their slopes: not the last
            setattr(c, name, 0.0)          # step's)
        self._aux_args = None

    def _comparison(self, c, args):
        # FASTSIM, Polach, FaStrip: the public function (no scalar path; it checks inputs)
        res = creep3d.creep_solution_3d(*args, self.method, **self._options(c))
        c.Fx, c.Fy = float(res.tx), float(res.ty)
        c.stick_area_fraction = float(res.stick_area_fraction)
        c.stick_width_ratio = float(res.stick_width_ratio)
        c.r_a0 = 1.0 - min(float(res.normalised_creepage), 1.0)
        c.creep_within_validity = bool(res.within_validity)

    def _analytic_force(self, *args):
        # scalar path; outside its assumptions the public function (it names the input); the
        # normalised creepage z is kept for the stick measures (auxiliary)
        if 0.0 <= args[8] < math.inf and args[4] > 0.0 and args[5] > 0.0:
            solution = self._solution = creep_force_3d_scalar(*args, self.method)
            return solution[0], solution[1]
        res = creep3d.creep_solution_3d(*args, self.method)
        self._solution = float(res.tx), float(res.ty), float(res.normalised_creepage)
        return self._solution[0], self._solution[1]

    def _analytic_stick(self, c, args):
        # the stick measures and the validity flag of the step's solution, from its forces
        # and z (a later effect may have replaced the contact's forces: not these)
        xi_x, xi_y, phi, n_load, a0, b0, _, _, mu = args
        tx, ty, z = self._solution
        stick, root, _, valid = creep_stick_3d_scalar(tx, ty, z, xi_x, xi_y, phi, mu * n_load,
                                                      a0, b0, self.method)
        c.stick_area_fraction = stick
        c.stick_width_ratio = root
        c.r_a0 = 1.0 if self.method == "linear" else 1.0 - min(z, 1.0)
        c.creep_within_validity = valid

    def _falling_values(self, args, mu):
        # the Coulomb table at mu: (tx, ty, mz, stick, z) (scalar path, else the array path)
        mu = float(mu)
        values = self._table.step_values(*args[:8], mu, False)
        if values is None:
            return self._table.step(*args[:8], mu, False)[:5]
        return values[:5]

    def _hold(self, shape):
        """The contact buffer of the table for a0/b0 = ``shape`` (made now if the table has
        none), held: ``(shape, entry)``, or None (beyond the table)."""
        if self._held is None or self._held[0] != shape:
            entry = self._table._buffer(shape, self._nu)
            self._held = None if entry is None else (shape, entry)
        return self._held

    def _count_shape(self, a0, b0):
        """Count the step's shape a0/b0 in the run of steps that held it (:meth:`step`)."""
        g = a0 / b0
        shape, n = self._shape_run
        self._shape_run = ((shape, n + 1) if abs(g - shape) <= SAME_SHAPE_RTOL * shape
                           else (g, 1))

    def _shape_buffer(self, g):
        """The held contact buffer for the step's a0/b0 = ``g``: the scene's shape, or a shape
        held for :data:`FALLING_BUFFER_AFTER_STEPS` steps; else None (the table's
        five-dimensional spline). A function of ``g`` and the effect's state alone."""
        scene = self._scene_shape
        if scene is not None and abs(g - scene) <= SAME_SHAPE_RTOL * scene:
            return self._hold(scene)
        shape, n = self._shape_run
        if n >= FALLING_BUFFER_AFTER_STEPS and abs(g - shape) <= SAME_SHAPE_RTOL * shape:
            return self._hold(shape)
        return None

    def _falling_forces(self, args):
        """``(tx, ty, mz, stick, z, mu_e)`` of the fast path with the scene's smooth law at
        the arguments ``args`` (mu_0 = ``args[8]``)."""
        mu0 = args[8]
        mu_k, kappa = self._smooth_law
        # the smooth law, compiled: on the contact buffer of a shape the contact holds (the
        # scene's, or one held FALLING_BUFFER_AFTER_STEPS steps), else on the table's
        # five-dimensional spline (a contact whose a0/b0 changes, a vehicle's). Its numbers
        # depend on the step's inputs and the effect's state alone: a restored state replays
        # bit for bit
        got = falling_friction_table_compiled(self._table, *args[:8], 0, mu0, mu_k, kappa,
                                              0.0, "table_point",
                                              buffer=self._shape_buffer(args[4] / args[5]))
        if got is None:     # a0/b0 beyond the table, or its array path
            cap = _SLIP_CAP / max(kappa, 1.0)    # kappa s stays finite (any creepage)

            def law(slip):
                return (mu0 - mu_k) / (1.0 + kappa * np.minimum(slip, cap)) + mu_k

            got = falling_friction_table(lambda mu: self._falling_values(args, mu), *args[:6],
                                         law, mu0, (args[6], args[7], mu_k / mu0, kappa))
        return got

    def _exact_table_falling(self, c, args):
        # falling friction (smooth law (5.16), mu_0 the step's friction coefficient) on the
        # Coulomb table: railcontact.falling_table, three table calls plus one; the Jacobian
        # outputs when read (jacobian)
        self._count_shape(args[4], args[5])
        self.set_falling(c, args, self._falling_forces(args))

    def set_falling(self, c, args, got):
        """The contact's outputs from the fast path's ``got = (tx, ty, mz, stick, z, mu_e)`` at
        the step's arguments ``args`` (the Jacobian then when read)."""
        tx, ty, mz, stick, z, _ = got
        c.Fx, c.Fy, c.Mz = float(tx), float(ty), float(mz)
        zc = z if z < 1.0 else 1.0
        c.stick_area_fraction = float(stick)
        c.stick_width_ratio = math.sqrt(1.0 - zc * zc)       # b*/b0, Eq. (2.84)
        c.r_a0 = 1.0 - zc                                    # a*(0)/a0, Eq. (2.83)
        c.creep_within_validity = True
        self._jac_args = args
        self._aux_args = None

    def _exact_table(self, c, args):
        if self._smooth_law is not None and args[8] > 0.0:
            self._exact_table_falling(c, args)
            return
        # one evaluation: forces, moment, stick area, normalised creepage, Jacobian
        values = self._table.step_values(*args)
        if values is None:        # the reader's array path (beyond its grid etc.)
            *values, jac = self._table.step(*args)
            values += jac.ravel().tolist()
        c.Fx, c.Fy, c.Mz, stick, z = values[:5]
        zc = z if z < 1.0 else 1.0
        c.stick_area_fraction = stick
        c.stick_width_ratio = math.sqrt(1.0 - zc * zc)       # b*/b0, Eq. (2.84)
        c.r_a0 = 1.0 - zc                                    # a*(0)/a0, Eq. (2.83)
        c.creep_within_validity = True
        (c.dFx_dxi_x, c.dFx_dxi_y, c.dFx_dphi, c.dFy_dxi_x, c.dFy_dxi_y, c.dFy_dphi,
         c.dMz_dxi_x, c.dMz_dxi_y, c.dMz_dphi) = values[5:]
        self._aux_args = None

    def _options(self, c):
        """Method options: Polach's 2005 parameters, the slip velocity from rolling_speed."""
        if self.method != "polach":
            return {}
        return dict(self._polach, rolling_speed=max(getattr(c, "rolling_speed", 0.0), 0.0))

    def auxiliary(self, c):
        """Fill the stick measures and the validity flag of the last step (lazily: analytic
        theories and the modified-strip table)."""
        # (nothing to do after the first read of a step: Mz and the stick measures of this step
        # are already set, by step (N = 0, exact table, comparison methods) or by the previous
        # call)
        args, self._aux_args = self._aux_args, None
        if args is None:
            return
        self._stick_measures(c, args)

    def jacobian(self, c):
        """The Jacobian outputs of the last step where they are computed only when read:
        falling friction, whose fast path (:mod:`railcontact.falling_table`) has no spline
        derivative. Central differences of the same fast path, the step ``h`` = 1e-5 of the
        creepage scale ``mu_0 p0 / G`` over which the creep curve bends (``h / sqrt(a0 b0)``
        in the spin): truncation ``(h / scale)^2`` and round-off ``eps scale / h``, both about
        1e-10 of the slope; six more calls of the fast path (some 50 us) on the steps whose
        Jacobian is read (tests/test_effects.py checks them against the spline's own
        derivatives in the Coulomb limit and against differences of the public API)."""
        args, self._jac_args = self._jac_args, None
        if args is None:
            return
        xi_x, xi_y, phi, n_load, a0, b0, e_mod, nu, mu0 = args
        p0 = 1.5 * n_load / (math.pi * a0 * b0)
        h = 1e-5 * mu0 * p0 * 2.0 * (1.0 + nu) / e_mod
        rows = []
        for k, step in enumerate((h, h, h / math.sqrt(a0 * b0))):
            plus, minus = list(args), list(args)
            plus[k] += step
            minus[k] -= step
            up, down = self._falling_forces(plus), self._falling_forces(minus)
            rows.append([(float(up[i]) - float(down[i])) / (2.0 * step) for i in range(3)])
        (c.dFx_dxi_x, c.dFy_dxi_x, c.dMz_dxi_x), (c.dFx_dxi_y, c.dFy_dxi_y, c.dMz_dxi_y), \
            (c.dFx_dphi, c.dFy_dphi, c.dMz_dphi) = rows

    def _table_stick(self, c, args):
        # the modified-strip table reader's scalar path (inputs as checked for the step)
        stick, z = self._stick(*args)
        zc = z if z < 1.0 else 1.0
        c.stick_area_fraction = stick
        c.stick_width_ratio = math.sqrt(1.0 - zc * zc)       # b*/b0, Eq. (2.84)
        c.r_a0 = 1.0 - zc                                    # a*(0)/a0, Eq. (2.83)
        c.creep_within_validity = spin_coefficient_scalar(
            args[0], args[1], args[2], args[4], args[5]) <= 1.0
        if z > self._z_max:
            self._warn("creep-table-range",
                       f"creep table {self._table.table.path.name}: normalised creepage "
                       f"z = {z:.4g} beyond the grid (last node {self._z_max:g}); the reader "
                       f"holds F = 1 there, which is exact (full sliding)")

    def get_state(self):
        return {"calls": self.calls,
                "aux_args": None if self._aux_args is None else list(self._aux_args),
                "jac_args": None if self._jac_args is None else list(self._jac_args),
                "solution": list(self._solution), "shape_run": list(self._shape_run)}

    def set_state(self, state):
        self.calls = int(state["calls"])
        args = state.get("aux_args")
        self._aux_args = None if args is None else tuple(args)
        args = state.get("jac_args")
        self._jac_args = None if args is None else tuple(args)
        self._solution = tuple(state.get("solution", (0.0, 0.0, 0.0)))
        shape, n = state.get("shape_run", (0.0, 0))
        self._shape_run = (float(shape), int(n))


class Creep2D(Effect):
    r"""Carter's 2-D creep force on a line contact (``effects.creep.method = "carter"``).

    :func:`railcontact.carter.carter_creep_force` for the load per unit length
    ``N / contact_width`` and the equivalent radius R, times the contact width;
    ``r_a0 = a*/a0`` from :func:`railcontact.carter.carter_stick_ratio` (Eq. (2.51)), which is
    also the stick fraction of the contact length. The 2-D theory has no lateral force: Fy = 0
    and ``creep_within_validity`` is False while the lateral creepage or the spin is not zero.
    """

    name = "creep"

    def __init__(self, scene, **_):
        super().__init__()
        if scene.effects["creep"]["source"] != "analytic":
            raise EffectUnavailable("effect creep (table) not available in this build for "
                                    "method 'carter' (no Carter table is shipped; the closed "
                                    "form is exact)")
        # (carter_creep_force, carter_stick_ratio) in one call on plain floats (their float
        # twin; its inputs are range-checked by the scene and the slave)
        self._scalar = carter_scalar
        geo = scene.geometry
        self._radius, self._width = geo["radius"], geo["contact_width"]
        self._e, self._nu = scene.youngs_modulus, scene.poisson_ratio

    def step(self, c):
        self.calls += 1
        c.Fy = 0.0
        c.creep_within_validity = c.creepage_lateral == 0.0 and c.spin == 0.0
        if c.normal_force <= 0.0:
            c.Fx = 0.0
            c.stick_area_fraction = c.stick_width_ratio = c.r_a0 = 1.0
            return
        n_line = c.normal_force / self._width
        force, c.r_a0 = self._scalar(c.creepage_longitudinal, n_line, self._radius, self._e,
                                     self._nu, c.friction_coefficient)
        fx = force * self._width
        mu_n = c.friction_coefficient * c.normal_force
        if abs(fx) > mu_n:       # (subnormal N: (mu N / w) w rounds a few ulp above mu N)
            fx = math.copysign(mu_n, fx)
        c.Fx = fx
        c.stick_area_fraction = c.r_a0
        c.stick_width_ratio = 1.0 if c.r_a0 > 0.0 else 0.0


def scene_shape(scene):
    """a0/b0 [-] of a 3-D scene's own geometry (its curvatures' Hertz ellipse, or its semi-axes),
    or None (a line contact)."""
    geo = scene.geometry
    if geo["kind"] == "curvatures":
        from .normal import unit_ellipse  # noqa: PLC0415

        a1, b1, _ = unit_ellipse(geo["curvature_longitudinal"], geo["curvature_lateral"],
                                 scene.youngs_modulus, scene.poisson_ratio)
        return float(a1) / float(b1)
    if geo["kind"] == "semi_axes":
        return float(geo["semi_axis_longitudinal"]) / float(geo["semi_axis_lateral"])
    return None
