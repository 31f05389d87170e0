"""Slip-velocity dependent friction on a line contact (Nielsen Ch. 5), in place of Carter's
force: the step law (closed form), the smooth law (the Sec. 5.3 iteration) or its table."""

from __future__ import annotations

import math

from .. import friction
from .._scalar import (carter_scalar, normalised_inputs_scalar,
                       step_law_creep_force_normalised_scalar)
from ..scene import SceneError
from .base import NOT_ESTIMATED, Effect, EffectUnavailable, load_table

__all__ = ["VelocityFriction"]


class VelocityFriction(Effect):
    r"""Slip-velocity dependent friction on a line contact (Nielsen Ch. 5), replacing Carter.

    ``mu(0)`` is ``friction.friction_coefficient``; ``law = "step"``: Ohyama's step law (5.3)
    with the thesis' corrected (minimum) solution, force from
    :func:`railcontact.friction.step_law_creep_force_normalised` (closed form) and the stick
    ratio of Carter's solution for mu_k (:func:`railcontact.carter.carter_stick_ratio`), which is
    that minimum solution (module docstring of :mod:`railcontact.friction`). ``law = "smooth"``:
    the law (5.16) solved by :func:`railcontact.friction.solve_velocity_friction_normalised`
    (the iteration of Sec. 5.3; accurate to about 1e-3 mu N at the default degree, and slow:
    0.01-0.1 s per step). Normalisation by :func:`railcontact.friction.normalised_inputs`.

    Accuracy knobs of the smooth law (scene keys ``series_degree``, ``tolerance``; FMU
    parameters ``friction_series_degree``, ``friction_tolerance``): the number of Chebyshev nodes
    of the friction polynomial (5.7) and the iteration's tolerance, passed as ``degree`` and
    ``tol``. ``friction_iteration_residual`` is the solution's final residual
    (:data:`NOT_ESTIMATED` for the step law, a closed form, and without contact).

    Table source (``source = "table"``, smooth law only; the step law is a closed form and
    ``source = "table"`` with it is a SceneError): the table ``velocity_friction`` over
    (m = mu_k/mu_0, kappa xi_c0, z = |xi|/xi_sat), inputs converted by
    :func:`railcontact.friction.normalised_inputs`; ``xi_sat/xi_c0`` from the table's
    ``saturation_creepage_ratio`` (at z = 0), then ``force_ratio`` and ``stick_ratio`` at z
    (``r_a0 = 0`` for z >= 1, exact; clipped to [0, 1] below). No iteration runs:
    ``friction_iteration_residual`` is -1 and ``friction_table_error_estimate`` is the table's
    recorded max error of ``force_ratio`` (|Fx| / (mu_0 N), 1.7e-4). The knobs
    ``series_degree``/``tolerance`` do not apply (the table was built with 128 and 1e-10). m
    outside the table's range is a SceneError at build time (it is fixed by the scene); kappa
    xi_c0 or z beyond the grid (the reader raises there, its documented behaviour) use the
    analytic iteration for that step (residual reported, table error -1) and log a warning
    once (``velocity-friction-table-range``). About 7 us per step (two spline lookups; the
    inputs converted on the float path of normalised_inputs) against 3-15 ms for the
    iteration (``benchmarks/bench_table_sources.py``).
    """

    name = "velocity_friction"

    def __init__(self, scene, tables_dir=None, warn=None, **_):
        super().__init__()
        # plain-float paths of normalised_inputs, step_law_creep_force_normalised and
        # carter_stick_ratio (the same operations; inputs range-checked by the scene and the
        # slave, as they assume)
        self._normalised = normalised_inputs_scalar
        self._step_law = step_law_creep_force_normalised_scalar
        self._carter_scalar = carter_scalar
        opts = scene.effects["velocity_friction"]
        self.law = opts["law"]
        self.mu_kinetic = opts["kinetic_friction_coefficient"]
        self.kappa = opts.get("kappa", 0.0)
        self.series_degree = int(opts.get("series_degree", 128))
        self.tolerance = float(opts.get("tolerance", 1e-10))
        geo = scene.geometry
        self._radius, self._width = geo["radius"], geo["contact_width"]
        self._e, self._nu = scene.youngs_modulus, scene.poisson_ratio
        self._warn = warn if warn is not None else (lambda key, msg: None)
        self.source = opts["source"]
        self._table = None
        #: Output ``friction_table_error_estimate``: recorded max error of the table's
        #: force_ratio (|T| / (mu_0 N)); :data:`NOT_ESTIMATED` for the analytic source.
        self.table_error_estimate = NOT_ESTIMATED
        if self.source == "table":
            self._table_setup(scene, tables_dir)

    # -- table source (smooth law): the block below is the table path ----------------------
    def _table_setup(self, scene, tables_dir):
        if self.law != "smooth":       # (scene_from_dict rejects this; a direct caller too)
            raise SceneError("effects.velocity_friction.source must be 'analytic' with law = "
                             "'step' (the step law is a closed form; the table velocity_friction"
                             " holds the smooth law (5.16))")
        table = load_table("velocity_friction", tables_dir, "velocity_friction")
        self._table = table
        spline = table.spline
        names = table.variables
        if "stick_ratio" not in names:
            raise EffectUnavailable(f"effect velocity_friction (table) not available in this "
                                    f"build: {table.path.name} has no variable 'stick_ratio' "
                                    "(rebuild it: python -m tablegen build --only "
                                    "velocity_friction)")
        self._i_force = names.index("force_ratio")
        self._i_sat = names.index("saturation_creepage_ratio")
        self._i_stick = names.index("stick_ratio")
        self._eval = spline.evaluate_point
        self._box = [(float(a["nodes"][0]), float(a["nodes"][-1])) for a in table.axes]
        m = self.mu_kinetic / scene.friction_coefficient if scene.friction_coefficient > 0 \
            else math.inf
        lo, hi = self._box[0]
        if not lo <= m <= hi:
            raise SceneError(
                f"effects.velocity_friction.kinetic_friction_coefficient over "
                f"friction.friction_coefficient, mu_k/mu_0, must be in [{lo:g}, {hi:g}] with "
                f"source = 'table' (range of the table "
                f"{table.path.name}) [-]; got mu_k = {self.mu_kinetic:g}, mu_0 = "
                f"{scene.friction_coefficient:g} (ratio {m:g}); use source = 'analytic'")
        err = table.accuracy()["force_ratio"]["max_abs_error"]
        self.table_error_estimate = float(err) if math.isfinite(err) else NOT_ESTIMATED

    def _table_force(self, chi, m, kap):
        """(|T| / (mu_0 N), r) from the table, or None outside its grid (kappa xi_c0, z)."""
        (_, _), (k_lo, k_hi), (_, z_hi) = self._box
        if not k_lo <= kap <= k_hi:
            return None
        sat = self._eval((m, kap, 0.0)).item(self._i_sat)     # (.item: a Python float)
        z = chi / sat
        if z > z_hi:
            return None
        vals = self._eval((m, kap, z))
        stick = 0.0 if z >= 1.0 else min(max(vals.item(self._i_stick), 0.0), 1.0)
        return vals.item(self._i_force), stick

    def step(self, c):
        # (in place of Creep2D, which the pipeline does not build: its outputs are set here)
        self.calls += 1
        mu0 = c.friction_coefficient
        c.friction_iteration_residual = NOT_ESTIMATED
        c.friction_table_error_estimate = self.table_error_estimate
        c.Fy = 0.0
        c.creep_within_validity = c.creepage_lateral == 0.0 and c.spin == 0.0
        if c.normal_force <= 0.0 or mu0 <= 0.0:
            # no contact, or no friction: no force; full stick without contact or creepage,
            # else full slip (Carter's answer, Creep2D)
            c.Fx = 0.0
            stick = 1.0 if c.normal_force <= 0.0 or c.creepage_longitudinal == 0.0 else 0.0
            c.r_a0 = c.stick_area_fraction = c.stick_width_ratio = stick
            return
        n_line = c.normal_force / self._width
        chi, _, force_scale, m, kap = self._normalised(
            c.creepage_longitudinal, n_line, self._radius, self._e, self._nu, mu0,
            self.mu_kinetic, self.kappa)
        scale = force_scale * self._width
        if self.law == "step":
            ratio = self._step_law(chi, m)
            c.r_a0 = self._carter_scalar(c.creepage_longitudinal, n_line, self._radius,
                                         self._e, self._nu, self.mu_kinetic)[1]
        else:
            if self._table is not None:
                got = self._table_force(abs(chi), m, kap)
                if got is not None:
                    c.Fx = -math.copysign(got[0], chi) * scale if chi else 0.0
                    c.r_a0 = got[1]
                    c.stick_area_fraction = c.r_a0
                    c.stick_width_ratio = 1.0 if c.r_a0 > 0.0 else 0.0
                    return
                c.friction_table_error_estimate = NOT_ESTIMATED
                self._warn("velocity-friction-table-range",
                           f"velocity friction table {self._table.path.name}: input outside "
                           f"the table (kappa xi_c0 = {kap:.4g}, |xi|/xi_c0 = {abs(chi):.4g}; "
                           f"grid kappa xi_c0 in [{self._box[1][0]:g}, {self._box[1][1]:g}], "
                           f"|xi|/xi_sat <= {self._box[2][1]:g}; the reader raises there); the "
                           "analytic Sec. 5.3 iteration is used for such steps")
            sol = friction.solve_velocity_friction_normalised(
                chi, m, kap, degree=self.series_degree, tol=self.tolerance)
            ratio = float(sol.force_ratio)          # T/(mu_0 N), opposes the creepage
            if math.isfinite(sol.residual):
                c.friction_iteration_residual = float(sol.residual)
            c.r_a0 = float(sol.stick_ratio)
        c.Fx = ratio * scale
        c.stick_area_fraction = c.r_a0
        c.stick_width_ratio = 1.0 if c.r_a0 > 0.0 else 0.0


