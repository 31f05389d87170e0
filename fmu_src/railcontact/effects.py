r"""Effect objects of the WheelRailContact FMU: one small object per physical effect.

The FMU slave (``fmu_src/WheelRailContact.py``) builds, at initialisation, only the effects a
:class:`~railcontact.scene.Scene` switches on (:func:`build_pipeline`), and each communication
step calls only those (:meth:`Pipeline.step`; the slave uses :attr:`Pipeline.checked_step`
or :meth:`Pipeline.fmu_step`, the same behind a cheap input check, with the creep-only table
scene fused into one function for speed). Every effect reads and writes the fields of one
:class:`ContactPoint` and keeps its own call counter (``calls``), which tests use to show that a
switched-off effect costs nothing.

Each effect takes its physics from :mod:`railcontact` (the analytic solvers) or from the shipped
tables (:mod:`railcontact.tables`); nothing here re-implements a model. An effect whose model
or table is not part of this build raises a :class:`~railcontact.scene.SceneError` at build
time ("effect X not available in this build"), never a placeholder result. Each effect
imports its model's module when it is built, so a scene loads only the models it uses.

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

import cmath
import functools
import math
import operator

from .scene import EFFECTS, POLACH_KEYS, SceneError

__all__ = ["ContactPoint", "NormalContact", "Creep3D", "Creep2D", "VelocityFriction",
           "Corrugation", "Wear", "NonSteady", "Roughness",
           "Pipeline", "build_pipeline", "EffectUnavailable", "NOT_ESTIMATED",
           "table_error_estimate", "wear_series_degree", "checked_steps"]

class EffectUnavailable(SceneError):
    """The scene asks for an effect whose model is not part of this build."""


_FLOAT_MAX = 1.7976931348623157e308

#: Sentinel of the accuracy outputs for "not estimated" (no table in use, no iteration run).
NOT_ESTIMATED = -1.0


def wear_series_degree(ka):
    """Series degree :func:`railcontact.wear.wear_coefficients` uses by default for ``k a0 = ka``:
    ``ceil(e ka) + 12`` (its documented default; ``tests/test_effects.py`` checks that they
    agree). [-]"""
    return int(math.ceil(math.e * ka)) + 12


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
      40 x 20 / 80 x 20 elements), whose own error against the converged exact theory is in
      docs/tables.md.

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


def _load_table(name, tables_dir, effect):
    """The shipped table ``<name>.nc`` (:class:`railcontact.tables.Table`) for ``effect``:
    from ``tables_dir`` (the FMU's resources) if given, else
    :func:`railcontact.tables.default_table_path`; a missing or unreadable file is
    :class:`EffectUnavailable`."""
    from . import tables

    try:
        path = tables.default_table_path(name, directory=tables_dir)
        return tables.Table.from_file(path, expected_name=name)
    except (OSError, ValueError) as exc:
        raise EffectUnavailable(f"effect {effect} (table {name}) not available in this build: "
                                f"{exc}") from None


#: Variables of the table ``corrugation_response`` the corrugation and wear effects read, in the
#: order :class:`_ResponseTable` returns them.
_RESPONSE_VARIABLES = ("half_width_real", "patch_shift_imag", "stick_half_width_real",
                       "stick_half_width_imag", "tangential_force_real",
                       "tangential_force_imag", "wear_real", "wear_imag")


class _ResponseTable:
    """The linearised first-harmonic response coefficients of one harmonic, from the table
    ``corrugation_response`` (:func:`railcontact.wear.linear_response`, wear model
    "material_point"), with the analytic closed forms outside its grid.

    ``coefficients(a0/L, r_a0)`` returns the complex ``(c_a, c_Delta, c_a*, c_T, w)`` of
    :func:`railcontact.corrugation.normal_response`, :func:`~railcontact.corrugation.
    stick_zone_response`, :func:`~railcontact.corrugation.tangential_force_response` and
    :func:`railcontact.wear.wear_coefficients` (``w``; None unless ``wear``). The table's axes
    have ``out_of_range = "error"`` (a0/L in [0.01, 1], r_a0 in [0, 1]): outside them the
    reader raises, so this falls back to the analytic functions for that harmonic and calls
    ``warn("corrugation-table-range", message)`` (the FMU logs it once). Never NaN.
    """

    def __init__(self, tables_dir, effect, warn):
        self.table = _load_table("corrugation_response", tables_dir, effect)
        names = self.table.variables
        missing = [v for v in _RESPONSE_VARIABLES if v not in names]
        if missing:
            raise EffectUnavailable(f"effect {effect} (table) not available in this build: "
                                    f"{self.table.path.name} lacks {missing}")
        self._cols = [names.index(v) for v in _RESPONSE_VARIABLES]
        # the eight values as Python floats from the spline's row in one call (per step)
        self._pick = operator.itemgetter(*self._cols)
        (self._lo, self._hi), (self._r_lo, self._r_hi) = [
            (float(a["nodes"][0]), float(a["nodes"][-1])) for a in self.table.axes]
        self._eval = self.table.spline.evaluate_point
        self._warn = warn if warn is not None else (lambda key, msg: None)
        from . import corrugation, wear

        self._corrugation = corrugation
        self._wear = wear
        acc = self.table.accuracy()
        #: Recorded max error of each variable read (name -> float), from the file.
        self.max_abs_error = {v: acc[v]["max_abs_error"] for v in _RESPONSE_VARIABLES}

    def coefficients(self, ratio, r, wear=True):
        if self._lo <= ratio <= self._hi and self._r_lo <= r <= self._r_hi:
            hw, ps, sr, si, tr, ti, wr, wi = self._pick(self._eval((ratio, r)).tolist())
            return (complex(hw, 0.0), complex(0.0, ps), complex(sr, si), complex(tr, ti),
                    complex(wr, wi) if wear else None)
        self._warn("corrugation-table-range",
                   f"corrugation table {self.table.path.name}: a0/L = {ratio:.4g} outside the "
                   f"table's grid [{self._lo:g}, {self._hi:g}] (the reader raises there); the "
                   "analytic closed forms of the linear theory are used for such harmonics")
        mod = self._corrugation
        cd, ca = mod.normal_response(ratio)
        w = (complex(self._wear.wear_coefficients(ratio, r, "material_point")) if wear
             else None)
        return (complex(ca), complex(cd), complex(mod.stick_zone_response(ratio, r)),
                complex(mod.tangential_force_response(ratio, r)), w)


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
                 "dMz_dxi_x", "dMz_dxi_y", "dMz_dphi")


    def __init__(self):
        for name in self.__slots__:
            setattr(self, name, 0.0)
        self.stick_area_fraction = self.stick_width_ratio = self.r_a0 = 1.0
        self.creep_within_validity = True
        self.creep_table_error_estimate = NOT_ESTIMATED
        self.friction_iteration_residual = NOT_ESTIMATED
        self.corrugation_series_error_estimate = NOT_ESTIMATED
        self.friction_table_error_estimate = NOT_ESTIMATED

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


#: Logged (once per FMU instance, category Warning) at the first evaluation with creepage but
#: without a normal force (e.g. the input normal_force left at its start value 0).
NO_NORMAL_FORCE_MESSAGE = (
    "normal_force = 0 N with non-zero creepage: no contact, so every force output is 0 (the "
    "input's start value is 0 N; set or connect normal_force)")


class NormalContact(_Effect):
    r"""Hertz contact ellipse from the normal force (always on).

    ``geometry.kind = "curvatures"``: :func:`railcontact.hertz.hertz_3d` once at build time for
    N = 1 N, then the exact Hertz scaling a0, b0, p0 proportional to N^(1/3) (Johnson (1985)
    Eqs. (4.17)-(4.19): the eccentricity depends on A'/B' only). ``"semi_axes"``: the ellipse
    is fixed and ``p0 = 3 N / (2 pi a0 b0)`` (Eq. (2.60)). ``"line"``: 2-D Hertz
    (:func:`railcontact.hertz.hertz_2d`, Eqs. (2.40)-(2.42)) for the load per unit length
    ``N / contact_width``, once for 1 N/m and then the exact scaling a0, p0 proportional to
    sqrt(N); ``b0`` is half the contact width. ``contact_half_width`` is a0 (the corrugation
    effect replaces it by the actual half-width).
    """

    name = "normal"

    def __init__(self, scene, mu_source=None, warn=None):
        super().__init__()
        self._warn = warn if warn is not None else (lambda key, msg: None)
        geo = scene.geometry
        self._line = geo["kind"] == "line"
        if self._line:
            from . import hertz

            a1, p1 = hertz.hertz_2d(1.0, geo["radius"], scene.youngs_modulus,
                                    scene.poisson_ratio)
            self._a1, self._p1 = float(a1), float(p1)
            self._width = geo["contact_width"]
            self._fixed = False
        elif geo["kind"] == "curvatures":
            from . import hertz

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
        # (a change here must be made in _normal_table_creep too: the fused FMU step)
        self.calls += 1
        n = c.normal_force
        if n <= 0.0 and (c.creepage_longitudinal or c.creepage_lateral or c.spin):
            self._warn("no-normal-force", NO_NORMAL_FORCE_MESSAGE)
        if self._line:
            n_line = n / self._width
            if n_line == math.inf:
                raise ValueError(f"normal_force / contact_width (load per unit length) must be "
                                 f"in [0, {_FLOAT_MAX:g}] [N/m]; got inf (normal_force = "
                                 f"{n:g} N, contact_width = {self._width:g} m)")
            scale = math.sqrt(n_line)
            c.a0, c.b0, c.p0 = self._a1 * scale, 0.5 * self._width, self._p1 * scale
            c.contact_half_width = c.a0
            return
        if self._fixed:
            c.a0, c.b0, c.p0 = self._a1, self._b1, self._p1 * n
        else:
            scale = n ** (1.0 / 3.0)
            c.a0, c.b0, c.p0 = self._a1 * scale, self._b1 * scale, self._p1 * scale
        c.contact_half_width = c.a0


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

    Per step the effect calls the *scalar paths* (plain floats, ``math`` module; they repeat the
    public functions' arithmetic without numpy's per-call overhead and without their input
    check, which the slave has made: finite inputs, N >= 0; a0, b0 > 0 from Hertz; mu is
    checked here): ``railcontact.creep3d._creep_solution_scalar`` for the analytic source,
    and the table readers' ``_scalar`` / ``_scalar_stick`` / ``_scalar_solution``. They agree
    with the public array paths to 4 eps (tests/test_creep3d.py, tests/test_tables.py).

    Table (``method = "modified_strip"`` only, the theory the shipped table holds):
    :meth:`railcontact.strip_table.CreepTable.creep_force_3d` gives the forces in the step (its
    scalar fast path, whose input check the slave has already made); the stick measures and the
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

    FASTSIM, Polach, FaStrip (``method = "fastsim" | "polach" | "fastrip"``, analytic source
    only): the public :func:`~railcontact.creep3d.creep_solution_3d` each step (no scalar path;
    FASTSIM and FaStrip loop over their 40 elements per strip). Polach's 2005 parameters come
    from ``effects.creep.polach_*`` (:data:`railcontact.scene.POLACH_KEYS`) and his slip
    velocity from the ``rolling_speed`` input.
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
        from . import creep3d

        self._solve = creep3d.creep_solution_3d
        self._spin_coefficient = creep3d.spin_coefficient
        # scalar paths (plain floats, no numpy per call): the inputs are range-checked by the
        # slave (finite, N >= 0), E and nu by the scene, a0, b0 > 0 come from Hertz; mu is
        # checked in step (it may come from another effect)
        self._solve_scalar = creep3d._creep_solution_scalar
        self._spin_scalar = creep3d._spin_coefficient_scalar
        self._force_analytic = creep3d.creep_force_3d
        self._table = None
        self._exact = self.method == "exact"
        self._comparison = self.method in creep3d.COMPARISON_METHODS
        polach_keys = POLACH_KEYS
        self._polach = {kw: float(opts.get(key, default)) for key, (kw, *_, default)
                        in polach_keys.items()}
        #: Output ``creep_table_error_estimate``: :func:`table_error_estimate` of the table in
        #: use (read once here), :data:`NOT_ESTIMATED` for the analytic source.
        self.table_error_estimate = NOT_ESTIMATED
        if self.source == "table":
            from . import strip_table, tables

            if self.method not in ("modified_strip", "exact"):
                raise SceneError(f"effects.creep.method must be 'modified_strip' or 'exact' "
                                 f"with source = 'table' (the shipped creep tables); got "
                                 f"{self.method!r}")
            reader = (creep3d.load_exact_table if self._exact
                      else strip_table.CreepTable.from_file)
            try:
                path = table_path or tables.default_table_path(opts["table"])
                self._table = reader(path)
            except (OSError, ValueError, AttributeError) as exc:
                raise EffectUnavailable(f"effect creep (table {opts['table']}) not available "
                                        f"in this build: {exc}") from None
            # The slave has range-checked every input (finite, N >= 0) and a0, b0 come from
            # Hertz, so the reader's scalar fast path without its own input check is used
            # ("inputs already range-checked"); the public method otherwise.
            self._force = getattr(self._table, "_scalar", self._table.creep_force_3d)
            self.table_error_estimate = table_error_estimate(self._table)
            if not self._exact:
                self._z_max = float(self._table.table.axes[0]["nodes"][-1])

    def step(self, c):
        # (a change here must be made in _normal_table_creep too: the fused FMU step)
        self.calls += 1
        c.creep_table_error_estimate = self.table_error_estimate
        if c.normal_force <= 0.0:
            c.Fx = c.Fy = 0.0
            c.stick_area_fraction = c.stick_width_ratio = c.r_a0 = 1.0
            c.creep_within_validity = True
            c.Mz = 0.0
            self._aux_args = None
            return
        spin = c.spin if self.use_spin else 0.0
        if self._comparison:
            # FASTSIM, Polach, FaStrip: the public function (no scalar path; it checks inputs)
            res = self._solve(c.creepage_longitudinal, c.creepage_lateral, spin,
                              c.normal_force, c.a0, c.b0, self._e, self._nu,
                              c.friction_coefficient, self.method, **self._options(c))
            c.Fx, c.Fy = float(res.tx), float(res.ty)
            c.stick_area_fraction = float(res.stick_area_fraction)
            c.stick_width_ratio = float(res.stick_width_ratio)
            c.r_a0 = 1.0 - min(float(res.normalised_creepage), 1.0)
            c.creep_within_validity = bool(res.within_validity)
        elif self._table is None:
            mu = c.friction_coefficient
            # scalar path; outside its assumptions the public function (it names the input)
            solve = (self._solve_scalar if 0.0 <= mu < math.inf and c.a0 > 0.0
                     and c.b0 > 0.0 else self._solve)
            res = solve(c.creepage_longitudinal, c.creepage_lateral, spin, c.normal_force,
                        c.a0, c.b0, self._e, self._nu, mu, self.method)
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
            if self._exact:
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
                return
            out = self._force(*args)
            c.Fx, c.Fy = float(out[0]), float(out[1])
            self._aux_args = args

    def _options(self, c):
        """Method options: Polach's 2005 parameters, the slip velocity from rolling_speed."""
        if self.method != "polach":
            return {}
        return dict(self._polach, rolling_speed=max(getattr(c, "rolling_speed", 0.0), 0.0))

    def auxiliary(self, c):
        """Fill the stick measures and the validity flag of the last table step (lazily)."""
        # (nothing to do after the first read of a step: Mz and the stick measures of this step
        # are already set, by step (N = 0, analytic source) or by the previous call)
        args, self._aux_args = self._aux_args, None
        if args is None:
            return
        # scalar path of the reader (inputs as checked for the step; see step)
        stick, z = self._table._scalar_stick(*args)
        zc = z if z < 1.0 else 1.0
        c.stick_area_fraction = stick
        c.stick_width_ratio = math.sqrt(1.0 - zc * zc)       # b*/b0, Eq. (2.84)
        c.r_a0 = 1.0 - zc                                    # a*(0)/a0, Eq. (2.83)
        c.creep_within_validity = self._spin_scalar(
            args[0], args[1], args[2], args[4], args[5]) <= 1.0
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


class Creep2D(_Effect):
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
        from . import _scalar, carter

        if scene.effects["creep"]["source"] != "analytic":
            raise EffectUnavailable("effect creep (table) not available in this build for "
                                    "method 'carter' (no Carter table is shipped; the closed "
                                    "form is exact)")
        self._force = carter.carter_creep_force
        self._stick = carter.carter_stick_ratio
        # (force, stick ratio) of the two public functions above in one call on plain floats
        # (their float twin; its inputs are range-checked by the scene and the slave)
        self._scalar = _scalar.carter_scalar
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


class VelocityFriction(_Effect):
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
        from . import _scalar, carter, friction

        self._friction = friction
        self._carter = carter
        # plain-float paths of normalised_inputs, step_law_creep_force_normalised and
        # carter_stick_ratio (the same operations; inputs range-checked by the scene and the
        # slave, as they assume)
        self._normalised = _scalar.normalised_inputs_scalar
        self._step_law = _scalar.step_law_creep_force_normalised_scalar
        self._carter_scalar = _scalar.carter_scalar
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
        table = _load_table("velocity_friction", tables_dir, "velocity_friction")
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
            sol = self._friction.solve_velocity_friction_normalised(
                chi, m, kap, degree=self.series_degree, tol=self.tolerance)
            ratio = float(sol.force_ratio)          # T/(mu_0 N), opposes the creepage
            if math.isfinite(sol.residual):
                c.friction_iteration_residual = float(sol.residual)
            c.r_a0 = float(sol.stick_ratio)
        c.Fx = ratio * scale
        c.stick_area_fraction = c.r_a0
        c.stick_width_ratio = 1.0 if c.r_a0 > 0.0 else 0.0


class Corrugation(_Effect):
    r"""Corrugated rail surface (Nielsen Ch. 4.2): rail position in; a, Delta, a*, T out.

    :func:`railcontact.corrugation.corrugated_contact` at the contact's rail position with the
    current surface harmonics (Eq. (4.1)), the load per unit length ``N / contact_width``, the
    radius R, mu and the longitudinal creepage; ``method`` "exact" (nonlinear) or "linear"
    (closed forms). It replaces ``contact_half_width`` (a), sets ``patch_shift`` (Delta) and the
    longitudinal force ``Fx = -sign(xi) |T| contact_width`` (T opposes the creepage). With the
    wear effect on it also gives the wear per passage at the material point under the contact
    (linearised, Eq. (4.94): :func:`railcontact.wear.corrugated_wear_depth`).
    ``corrugation_amplitude`` is |Z| of the first listed harmonic. Condition (4.2) (no loss of
    contact) is checked at build time for the initial surface. The surface harmonics are
    internal state (the wear effect may evolve them).

    Accuracy: the contact itself (both methods) is computed from closed forms (the Chebyshev
    series of the contact distributions summed through Bessel functions, Newton to 1e-13): no
    truncated series, no knob. The linearised wear coefficients
    (:func:`railcontact.wear.wear_coefficients`, models "material_point" and
    "patch_coordinate"; used for the wear depth, the growth rate and the evolution) do truncate
    that series, at the automatic degree ``ceil(e k a0) + 12`` of the largest ``k a0``; its
    truncation error (:func:`railcontact.corrugation.series_truncation_error`, the neglected
    Bessel coefficients relative to the largest, the size (4.27) whose term ratio is (4.28)) is
    the output ``corrugation_series_error_estimate``, evaluated when read (:meth:`auxiliary`);
    :data:`NOT_ESTIMATED` when no truncated series is in use (wear off, or the time-domain wear
    models, or no contact). The degree is not a scene knob: ``corrugated_contact`` takes none.

    Table source (``source = "table"``, ``method = "linear"`` only: the table holds the
    linearised theory; ``method = "exact"`` with the table is a SceneError): the table
    ``corrugation_response`` (:func:`railcontact.wear.linear_response` over a0/L and r_a0) gives
    each harmonic's normalised response coefficients ``c_a, c_Delta, c_T`` and, with wear on,
    the wear coefficient ``w`` (model "material_point" only; another ``effects.wear.wear_model``
    is a SceneError), superposed as ``corrugated_contact(method="linear")`` does:
    ``a = a0 + sum Re(k R c_a Z e^{-ikX})`` etc., ``T = mu N (1 - r)(1 + r) + sum Re(mu/C c_T
    Z e^{-ikX})``, the wear depth ``W0 + sum Re(K mu^2 N/a0 w Z e^{-ikX})`` with ``W0`` the
    closed form (4.96). Agreement with the analytic linear theory is the table's recorded
    accuracy (max 3.6e-5 of the normalised coefficients; ``tests/test_effects.py``). A harmonic
    with a0/L outside the grid [0.01, 1] (the reader raises there, its documented behaviour)
    uses the analytic closed forms instead and a warning is logged once
    (``corrugation-table-range``). ``corrugation_series_error_estimate`` is -1 unless the wear
    effect's own coefficients are analytic (then their series is estimated as above).
    """

    name = "corrugation"

    def __init__(self, scene, wear=None, tables_dir=None, warn=None, **_):
        super().__init__()
        from . import _corrugation_kernels
        from . import corrugation as module

        opts = scene.effects["corrugation"]
        self.source = opts["source"]
        geo = scene.geometry
        self._solve = module.corrugated_contact
        self.method = opts["method"]
        # corrugated_contact at one position as floats (the same compiled kernels; it calls
        # corrugated_contact itself where that raises) and the series estimate's kernel
        solver = module.CorrugatedContactSolver(geo["radius"], scene.youngs_modulus,
                                                scene.poisson_ratio, self.method)
        self._solve_scalar = solver.contact
        self._load_underflows = solver.load_underflows
        self._truncation_error_scalar = _corrugation_kernels.series_relative_error
        self.wavelengths = list(opts["wavelengths"])
        self.amplitudes_cos = list(opts["amplitudes_cos"])
        self.amplitudes_sin = list(opts["amplitudes_sin"])
        self._radius, self._width = geo["radius"], geo["contact_width"]
        self._e, self._nu = scene.youngs_modulus, scene.poisson_ratio
        self._wear = wear
        if wear is not None:
            from .wear import _corrugated_wear_depth_scalar

            # wear per passage at the material point under the contact (wear.corrugated_wear_depth
            # on floats; the wear module depends on the contact module, not the other way round)
            self._wear_depth_scalar = _corrugated_wear_depth_scalar
        self._series = wear is not None and wear.wear_model in ("material_point",
                                                                 "patch_coordinate")
        self._table = None
        if self.source == "table":
            self._table_setup(scene, wear, tables_dir, warn)
        self._truncation_error = module.series_truncation_error
        self._pending_ka = None
        k = [2.0 * math.pi / lam for lam in self.wavelengths]
        try:
            module.check_no_contact_loss([km * km * self._radius * math.hypot(za, zb) for
                                          km, za, zb in zip(k, self.amplitudes_cos,
                                                            self.amplitudes_sin)])
        except ValueError as exc:
            raise SceneError(f"effects.corrugation.amplitudes_cos/amplitudes_sin: {exc}") from None

    # -- table source (linear theory): the block below is the table path ------------------
    def _table_setup(self, scene, wear, tables_dir, warn):
        if self.method != "linear":    # (scene_from_dict rejects this; a direct caller too)
            raise SceneError("effects.corrugation.method must be 'linear' with source = "
                             "'table' (the table corrugation_response holds the linearised "
                             f"theory); got {self.method!r}")
        if wear is not None and wear.wear_model != "material_point":
            raise SceneError("effects.wear.wear_model must be 'material_point' with "
                             "effects.corrugation.source = 'table' (the table "
                             "corrugation_response holds that wear model only); got "
                             f"{wear.wear_model!r}")
        self._table = _ResponseTable(tables_dir, "corrugation", warn)
        self._comp = 4.0 * (1.0 - self._nu ** 2) / (math.pi * self._e)
        self._k = [2.0 * math.pi / lam for lam in self.wavelengths]
        from .corrugation import check_no_contact_loss

        self._check_no_contact_loss = check_no_contact_loss
        # no series is summed at run time unless the wear effect's own coefficients are
        # analytic (growth rate, evolution)
        self._series = self._series and wear.source == "analytic"

    def _step_table(self, c):
        """:func:`railcontact.corrugation.corrugated_contact` (method "linear") with the
        response coefficients from the table: the same superposition over the harmonics."""
        big_r, n_line, mu = self._radius, c.normal_force / self._width, c.friction_coefficient
        za, zb, k = self.amplitudes_cos, self.amplitudes_sin, self._k
        if any(km * km * big_r * math.hypot(a, b) >= 1.0 for km, a, b in zip(k, za, zb)):
            self._check_no_contact_loss([km * km * big_r * math.hypot(a, b)
                                         for km, a, b in zip(k, za, zb)])   # raises (4.2)
        a0, x = c.a0, c.rail_position
        xi = abs(c.creepage_longitudinal)
        a0s = max(a0 - xi * big_r / mu, 0.0)
        r = a0s / a0
        one_minus_r = min(xi * big_r / (mu * a0), 1.0)          # 1 - r without cancellation
        a, d, t = a0, 0.0, mu * n_line * one_minus_r * (2.0 - one_minus_r)
        wear = self._wear
        if wear is not None:
            kw = wear.wear_coefficient
            depth = kw * mu * mu * n_line * a0 / big_r * (1 - r) ** 2 * (1 + r)
            w_scale = kw * mu * mu * n_line / a0
        scale_t = mu / self._comp
        coefficients = self._table.coefficients
        for lam, km, zam, zbm in zip(self.wavelengths, k, za, zb):
            ca, cd, _, ct, cw = coefficients(a0 / lam, r, wear is not None)
            zc = complex(zam, zbm) * cmath.exp(-1j * km * x)
            krz = km * big_r * zc
            a += (ca * krz).real
            d += (cd * krz).real
            t += scale_t * (ct * zc).real
            if wear is not None:
                depth += w_scale * (cw * zc).real
        c.contact_half_width = a
        c.patch_shift = d
        xi_signed = c.creepage_longitudinal
        c.Fx = -math.copysign(t, xi_signed) * self._width if xi_signed else 0.0
        if wear is not None:
            c.wear_depth_per_passage = depth

    def step(self, c):
        self.calls += 1
        c.corrugation_amplitude = math.hypot(self.amplitudes_cos[0], self.amplitudes_sin[0])
        c.patch_shift = 0.0
        c.corrugation_series_error_estimate = NOT_ESTIMATED
        self._pending_ka = None
        if (c.normal_force <= 0.0 or c.friction_coefficient <= 0.0
                or self._load_underflows(c.normal_force / self._width)):
            # no contact; also a load whose normalised value 8 (1 - nu^2) N / (pi E) underflows
            # (N below about 1e-295 N), which corrugated_contact rejects (a0 would underflow)
            c.wear_depth_per_passage = 0.0
            return
        if self._series:
            self._pending_ka = 2.0 * math.pi * c.a0 / min(self.wavelengths)
        if self._table is not None:
            self._step_table(c)
            return
        wear = self._wear
        x, n_line, mu, xi = (c.rail_position, c.normal_force / self._width,
                             c.friction_coefficient, c.creepage_longitudinal)
        za, zb, lam = self.amplitudes_cos, self.amplitudes_sin, self.wavelengths
        a, d, _, t = self._solve_scalar(x, n_line, mu, xi, za, zb, lam)
        c.contact_half_width = a
        c.patch_shift = d
        c.Fx = -math.copysign(t, xi) * self._width if xi else 0.0
        if wear is not None:
            c.wear_depth_per_passage = self._wear_depth_scalar(
                x, n_line, self._radius, self._e, self._nu, mu, xi, za, zb, lam,
                wear.wear_coefficient, wear.wear_model)

    def auxiliary(self, c):
        """``corrugation_series_error_estimate`` of the last step (on demand)."""
        ka, self._pending_ka = self._pending_ka, None
        if ka is not None:
            c.corrugation_series_error_estimate = self._truncation_error_scalar(
                ka, wear_series_degree(ka))

    def get_state(self):
        return {"calls": self.calls, "amplitudes_cos": list(self.amplitudes_cos),
                "amplitudes_sin": list(self.amplitudes_sin), "pending_ka": self._pending_ka}

    def set_state(self, state):
        self.calls = int(state["calls"])
        self.amplitudes_cos = [float(v) for v in state["amplitudes_cos"]]
        self.amplitudes_sin = [float(v) for v in state["amplitudes_sin"]]
        self._pending_ka = state.get("pending_ka")


class Wear(_Effect):
    r"""Frictional wear per passage (Nielsen Sec. 4.3) and, optionally, surface evolution (4.4).

    Smooth rail: ``wear_depth_per_passage`` = :func:`railcontact.wear.mean_wear`
    (``W0 = K mu^2 N a0/R (1 - r)^2 (1 + r)``, Eq. (4.96), N per unit length). Corrugated rail:
    the linearised wear at the material point under the contact, from the corrugation effect.
    ``corrugation_growth_rate`` (corrugation on): ``|1 - W1 - i W2| - 1``, the relative change
    of the first harmonic's amplitude per passage under the current contact (Eq. (4.103)-
    (4.104); ``W1 + i W2`` = :func:`railcontact.evolution.wear_number` x
    :func:`railcontact.wear.wear_coefficients`), evaluated when read. With ``evolve = true``,
    every time ``rail_position`` completes a further ``section_length`` the surface harmonics
    are advanced by that many passages with :func:`railcontact.evolution.evolve_harmonics`
    under the contact conditions of that step (the thesis' mixed-traffic superposition (4.110)
    over the passages of a run).

    Table source (``source = "table"``, ``wear_model = "material_point"`` only, else a
    SceneError naming ``effects.wear.wear_model``): ``W1 + i W2`` = wear number x the table
    ``corrugation_response``'s ``wear_real + i wear_imag`` at (a0/L, r_a0) (analytic
    :func:`railcontact.wear.wear_coefficients` for a harmonic outside the grid, with a warning
    once). The smooth-rail mean wear is the closed form (4.96) in both sources; the wear depth
    on a corrugated rail comes from the corrugation effect (its own source).
    """

    name = "wear"

    def __init__(self, scene, tables_dir=None, warn=None, **_):
        super().__init__()
        from . import _corrugation_kernels, _scalar, evolution, wear

        self._wear = wear
        self._evolution = evolution
        # the formulas of mean_wear and wear_number without their checks (inputs checked by
        # the scene and the slave, r_a0 clipped to [0, 1])
        self._mean_wear = self._wear.mean_wear_unchecked
        self._wear_number = self._evolution.wear_number_unchecked
        # evolve_harmonics for one passage count on lists (cmath; checks W, falls back to it)
        self._evolve = _scalar.evolve_harmonics_scalar
        # wear_coefficients on a list at one r: the series models' compiled kernel directly
        self._wear_coefficients = (
            _corrugation_kernels.wear_coefficients_list
            if scene.effects["wear"]["wear_model"] in ("material_point", "patch_coordinate")
            else self._wear.wear_coefficients)
        opts = scene.effects["wear"]
        self.wear_coefficient = opts["wear_coefficient"]
        self.wear_model = opts["wear_model"]
        self.evolve = opts["evolve"]
        self.section_length = opts.get("section_length")
        self._radius, self._width = scene.geometry["radius"], scene.geometry["contact_width"]
        self.corrugation = None          # set by build_pipeline when corrugation is on
        self.passages = 0
        self._section = None
        self._pending = None
        self.source = opts["source"]
        self._table = None
        if self.source == "table":
            if self.wear_model != "material_point":  # (scene_from_dict rejects this too)
                raise SceneError("effects.wear.wear_model must be 'material_point' with "
                                 "effects.wear.source = 'table' (the table "
                                 "corrugation_response holds that wear model only); got "
                                 f"{self.wear_model!r}")
            self._table = _ResponseTable(tables_dir, "wear", warn)

    def _w(self, c, wavelengths):
        """W1 + i W2 per harmonic for the contact state c (complex list)."""
        n_line = c.normal_force / self._width
        number = self._wear_number(self.wear_coefficient, c.friction_coefficient, n_line, c.a0)
        r = min(max(c.r_a0, 0.0), 1.0)
        if self._table is not None:        # table source: w from corrugation_response
            coefficients = self._table.coefficients
            return [number * coefficients(c.a0 / lam, r)[4] for lam in wavelengths]
        w = self._wear_coefficients([c.a0 / lam for lam in wavelengths], r, self.wear_model)
        return [number * v for v in w]

    def step(self, c):
        self.calls += 1
        if c.normal_force <= 0.0:
            c.wear_depth_per_passage = 0.0
            c.corrugation_growth_rate = 0.0
            self._pending = None
        elif self.corrugation is None:
            c.wear_depth_per_passage = self._mean_wear(
                self.wear_coefficient, c.friction_coefficient, c.normal_force / self._width,
                self._radius, c.a0, min(max(c.r_a0, 0.0), 1.0))
        else:
            self._pending = (c.normal_force, c.friction_coefficient, c.a0, c.r_a0)
        if self.evolve:
            section = math.floor(c.rail_position / self.section_length)
            if self._section is None:
                self._section = section
            elif section > self._section and c.normal_force > 0.0:
                n = section - self._section
                corr = self.corrugation
                w = self._w(c, corr.wavelengths)
                corr.amplitudes_cos, corr.amplitudes_sin = self._evolve(
                    corr.amplitudes_cos, corr.amplitudes_sin, [v.real for v in w],
                    [v.imag for v in w], n)
                self.passages += n
                self._section = section
                c.corrugation_amplitude = math.hypot(corr.amplitudes_cos[0],
                                                     corr.amplitudes_sin[0])
            else:
                self._section = max(self._section, section)

    def auxiliary(self, c):
        """Growth rate of the first harmonic under the last step's contact (on demand)."""
        pending, self._pending = self._pending, None
        if pending is None or self.corrugation is None:
            return
        probe = ContactPoint()
        probe.normal_force, probe.friction_coefficient, probe.a0, probe.r_a0 = pending
        w = self._w(probe, self.corrugation.wavelengths[:1])[0]
        c.corrugation_growth_rate = abs(1.0 - w) - 1.0

    def get_state(self):
        return {"calls": self.calls, "passages": self.passages, "section": self._section,
                "pending": None if self._pending is None else list(self._pending)}

    def set_state(self, state):
        self.calls = int(state["calls"])
        self.passages = int(state["passages"])
        self._section = state["section"]
        self._pending = None if state["pending"] is None else tuple(state["pending"])


class NonSteady(_Effect):
    r"""Non-steady rolling (Nielsen Ch. 7) as a relaxation-length law with state.

    The creep forces are the steady ones at *relaxed creepages* ``xi_e`` that follow the input
    creepages through ``(sigma / V) d xi_e / dt + xi_e = xi`` with the relaxation length
    ``sigma = a0* (Lambda(r_a0) - 1)`` (:func:`railcontact.nonsteady.relaxation_length`: the
    first-order term of the thesis' transfer function (7.53)-(7.54), Carter (7.20) or Johnson
    (7.15) displacement model, ``pseudo_width_ratio`` b/a0). Since the force is a steady force
    at some creepage, ``|F| <= mu N`` holds by construction.

    In a step the relaxed creepages are advanced over the rolled distance ``V h`` (``h`` =
    :attr:`ContactPoint.step_size`, set by the slave; inputs held, sample and hold) with the
    exact exponential and the predictor-corrector for the state-dependent sigma,
    :func:`railcontact.nonsteady.relaxation_step` (unconditionally stable, no overshoot, second
    order, sub-steps where sigma changes fast; error bound
    :func:`railcontact.nonsteady.relaxation_step_error_bound`). sigma is
    evaluated at the relaxed state, from the stick ratio the creep effect reports for it:

    * line contact (Carter, the thesis' 2-D setting): ``r_a0 = max(0, 1 - |xi_e| / xi_c)``,
      ``xi_c = mu a0 / R`` (Eqs. (2.51), (2.54)); only the longitudinal creepage is relaxed
      (the 2-D theory has no lateral force; lateral creepage and spin pass through);
    * elliptic contact (Creep3D): the strip-theory extension of the 2-D result. The centre
      strip y = 0 has half-length a0 and ``r_a0 = 1 - min(z, 1)`` (Eq. (2.83), z the
      normalised creepage of the strip or modified strip theory, Kalker's coefficients for
      "she", "modified_strip" and "exact"; 1 for the linear theory); xi_x, xi_y and spin are
      relaxed with that one sigma (the same relaxed state feeds the strip theory, whose strips
      then all lag by the centre strip's sigma -- an approximation: the thesis treats 2-D only).

    Initialisation (the first evaluation, ``exit_initialization_mode``) is the steady state,
    ``xi_e = xi``. Without contact (N = 0) the contact is stress free, ``xi_e = 0`` (a contact
    that closes again builds its force up over sigma). ``V = 0`` holds the state; full sliding
    (``r_a0 = 0``, sigma = 0) has no memory, ``xi_e = xi``. Outputs: ``relaxation_length``
    (sigma at the relaxed state after the step), ``relaxed_creepage_longitudinal``,
    ``relaxed_creepage_lateral``, ``relaxed_spin``. The relaxed creepages are internal state
    (:meth:`get_state`).

    Velocity-dependent friction reads the relaxed creepage like any creep effect; sigma is then
    still that of Coulomb friction with mu = ``friction.friction_coefficient`` (Ch. 7 assumes
    Coulomb friction). The scene rejects nonsteady with corrugation or wear (their Ch. 4
    models are quasi-static).
    """

    name = "nonsteady"

    def __init__(self, scene, **_):
        super().__init__()
        opts = scene.effects["nonsteady"]
        if opts["source"] != "analytic":       # (scene_from_dict rejects it already)
            raise EffectUnavailable("effect nonsteady (table) not available in this build (the "
                                    "relaxation length is a closed form)")
        from . import nonsteady as module

        self.model = opts["model"]
        self.pseudo_width_ratio = opts["pseudo_width_ratio"]
        self._sigma = module.relaxation_length_function(scene.poisson_ratio,
                                                        self.pseudo_width_ratio, self.model)
        self._relaxation_step = module.relaxation_step
        self._line = scene.geometry["kind"] == "line"
        method = scene.effects["creep"]["method"]
        self._full_stick = method == "linear"
        if self._line:
            self._inv_radius = 1.0 / scene.geometry["radius"]
        else:
            from . import creep3d

            self._coefficients = creep3d._coefficients
            self._method = "strip" if method == "strip" else "modified_strip"
            self._nu = scene.poisson_ratio
            self._w_sat_per_mu_p0 = math.pi ** 2 * (1.0 + self._nu) / scene.youngs_modulus
            self._shape = (None, None)             # (a0/b0, (C11, C22, C23)) of the last step
        #: Relaxed (xi_x, xi_y, phi) after the last step; None before the first evaluation.
        self.relaxed = None
        self._inputs = None

    def _relaxation_length_function(self, c):
        """``sigma(state)`` [m] for the contact of this step: :func:`relaxation_length_function`
        at the r_a0 the creep theory gives for the relaxed creepages ``state``."""
        mu, a0, sig = c.friction_coefficient, c.a0, self._sigma
        if self._line:
            xi_c = mu * a0 * self._inv_radius                       # Eq. (2.54)

            def sigma_of(state):
                if xi_c > 0.0:
                    f = abs(state[0]) / xi_c
                    return sig(a0, 1.0 - f) if f < 1.0 else 0.0     # Eq. (2.51)
                return sig(a0, 1.0) if state[0] == 0.0 else 0.0
            return sigma_of
        if self._full_stick:
            full = sig(a0, 1.0)
            return lambda state: full
        b0 = c.b0
        g = a0 / b0 if b0 > 0.0 else 1.0
        last = self._shape[0]
        # (the Hertz scaling keeps a0/b0 up to rounding: Kalker's coefficients are computed
        # again only when the shape really changes; their change over 1e-12 is far below it)
        if last is None or abs(g - last) > 1e-12 * last:
            coefs = self._coefficients(a0, b0, self._nu, self._method)
            self._shape = (g, tuple(float(v) for v in coefs))
        c11, c22, c23 = self._shape[1]
        c23 *= math.sqrt(a0 * b0)
        w_sat = self._w_sat_per_mu_p0 * mu * c.p0            # Eqs. (2.93)-(2.96), (2.99)

        def sigma_of(state, _hypot=math.hypot):
            w = _hypot(c11 * state[0], c22 * state[1] + c23 * state[2])
            if w_sat > 0.0:
                z = w / w_sat
                return sig(a0, 1.0 - z) if z < 1.0 else 0.0     # Eq. (2.83), y = 0
            return sig(a0, 1.0) if w == 0.0 else 0.0
        return sigma_of

    def step(self, c):
        self.calls += 1
        xi = (c.creepage_longitudinal, c.creepage_lateral, c.spin)
        self._inputs = xi
        if c.normal_force <= 0.0:                  # no contact: stress free, no length
            new = (0.0, xi[1], xi[2]) if self._line else (0.0, 0.0, 0.0)
            sigma = 0.0
        else:
            sigma_of = self._relaxation_length_function(c)
            old = self.relaxed
            if old is None:                        # initialisation: the steady state
                new = xi
            else:
                if self._line:
                    old = (old[0], xi[1], xi[2])
                new = self._relaxation_step(old, xi, c.rolling_speed * c.step_size, sigma_of)
            sigma = sigma_of(new)
        self.relaxed = new
        c.relaxation_length = sigma
        (c.relaxed_creepage_longitudinal, c.relaxed_creepage_lateral,
         c.relaxed_spin) = new
        c.creepage_longitudinal, c.creepage_lateral, c.spin = new

    def finish(self, c):
        """After the last effect: the creepage fields are the importer's inputs again.

        (If an effect in between raises, the fields keep the relaxed creepages; the FMU then
        reports the error and the instance is not stepped further.)"""
        if self._inputs is not None:
            c.creepage_longitudinal, c.creepage_lateral, c.spin = self._inputs

    def get_state(self):
        return {"calls": self.calls,
                "relaxed": None if self.relaxed is None else list(self.relaxed),
                "inputs": None if self._inputs is None else list(self._inputs)}

    def set_state(self, state):
        self.calls = int(state["calls"])
        self.relaxed = None if state["relaxed"] is None else tuple(state["relaxed"])
        self._inputs = None if state["inputs"] is None else tuple(state["inputs"])
class Roughness(_Effect):
    r"""Rough rail surface (Nielsen Ch. 6): the single-asperity solution on the local gap.

    At each step :func:`railcontact.roughness.rough_rail_contact` at ``rail_position``: the gap
    between the wheel's parabola (equivalent radius R) and the rail roughness ``r(X)`` is
    expanded to 4th order about its minimum (:func:`railcontact.roughness.local_gap`: curvature
    ``1/R - r''(X)``, skewness ``-r'''(X)``, flatness ``-r''''(X)`` at the gap minimum; ``r`` is
    the rail height, up positive, the convention of Eq. (4.1)), and Ch. 6's asperity solution
    gives the contact (Table 6.1: half-width a, shift Delta) and the steady creep force
    ((6.38)-(6.39), opposing the creepage) for the load per unit length
    ``N / contact_width``. It replaces Carter's force (``Fx`` = force per length x
    contact_width), ``contact_half_width`` (a), ``patch_shift`` (patch centre relative to the
    wheel axis: the gap minimum's shift + Delta) and the stick measures
    (``r_a0 = stick_area_fraction = a*/a``); it sets ``gap_curvature``, ``gap_skewness``,
    ``gap_flatness`` (the lambdas of (6.1)) and ``critical_creepage`` (the full-slip creepage
    (6.40)). ``a0``, ``p0`` stay the smooth-rail Hertz values.

    Roughness: the harmonics ``wavelengths, amplitudes_cos, amplitudes_sin`` (exactly the
    surface the corrugation effect describes with the same lists) or a sampled profile
    (``profile_file``, quintic spline, ``profile_extension`` "periodic" or "hold"; see
    :class:`railcontact.roughness.ProfileRoughness`). The roughness is constant (no state but
    the call counter).

    Hard cases: the gap must be convex everywhere, ``R max r'' < 1`` (condition (4.2)
    generalised; for harmonics the bound ``R sum k^2 |Z| < 1``): checked at build time, a
    :class:`~railcontact.scene.SceneError` naming the key. A restriction of Table 6.1 failing at
    some position (the local quartic has no single coherent patch for the load, e.g. a strongly
    negative flatness on a crest when the half-width is not small against the wave length)
    raises a ValueError naming ``rail_position`` and the restriction (the FMU logs it and
    returns an error status); there is no silent fallback. No contact (N = 0, or a load so
    small that the normalised load ``N~ = 8 (1 - nu^2) N / (pi E contact_width)`` is below the
    smallest normal double, 2.2e-308 m, i.e. N below about 1e-295 N): zero force,
    zero half-width and critical creepage, stick measures 1, ``patch_shift`` the gap minimum's
    shift and the gap coefficients still reported; mu = 0: zero force.
    """

    name = "roughness"

    def __init__(self, scene, **_):
        super().__init__()
        opts = scene.effects["roughness"]
        if opts["source"] != "analytic":
            raise EffectUnavailable("effect roughness (table) not available in this build (no "
                                    "roughness table is shipped; the Ch. 6 asperity solution "
                                    "is closed-form or a 1-D root per step)")
        from . import roughness as module

        if opts.get("profile_file"):
            key = "effects.roughness.profile_file"
            try:
                self.surface = module.ProfileRoughness(opts["profile_positions"],
                                                       opts["profile_heights"],
                                                       opts["profile_extension"])
            except ValueError as exc:
                raise SceneError(f"{key}: {exc}") from None
        else:
            key = "effects.roughness.amplitudes_cos/amplitudes_sin"
            self.surface = module.HarmonicRoughness(opts["wavelengths"], opts["amplitudes_cos"],
                                                    opts["amplitudes_sin"])
        geo = scene.geometry
        self._radius, self._width = geo["radius"], geo["contact_width"]
        self._e, self._nu = scene.youngs_modulus, scene.poisson_ratio
        curvature = self.surface.max_height_curvature()
        if not curvature * self._radius < 1.0:
            raise SceneError(f"{key}: the gap between wheel and rail must be convex everywhere, "
                             f"R max r'' < 1 (condition (4.2) generalised; a rail more curved "
                             f"than the wheel gives multiple contact / impact, out of scope); "
                             f"got R max r'' = {curvature * self._radius:.6g} with "
                             f"geometry.radius = {self._radius:g} m")
        # rough_rail_contact as floats from one compiled kernel (it calls rough_rail_contact
        # itself for errors and the full-stick series)
        solver = module.RoughRailSolver(self.surface, self._radius, self._e, self._nu)
        self._solve, self._local_gap = solver.contact, solver.local_gap
        # N~ per unit of normal_force (text after Nielsen (6.10))
        self._nt_per_newton = float(module.normalised_load(1.0, self._e, self._nu)) / self._width

    def step(self, c):
        # (in place of Creep2D, which the pipeline does not build: its outputs are set here)
        self.calls += 1
        c.Fy = 0.0
        c.creep_within_validity = c.creepage_lateral == 0.0 and c.spin == 0.0
        if not c.normal_force * self._nt_per_newton >= 2.2250738585072014e-308:
            (c.patch_shift, c.gap_curvature, c.gap_skewness,
             c.gap_flatness) = self._local_gap(c.rail_position)
            c.Fx = 0.0
            c.stick_area_fraction = c.stick_width_ratio = c.r_a0 = 1.0
            c.contact_half_width = 0.0
            c.critical_creepage = 0.0
            return
        (shift, c.gap_curvature, c.gap_skewness, c.gap_flatness, c.contact_half_width, delta,
         force, ratio, c.critical_creepage) = self._solve(
            c.rail_position, c.normal_force / self._width, c.friction_coefficient,
            c.creepage_longitudinal)
        c.patch_shift = shift + delta
        c.Fx = force * self._width
        c.r_a0 = c.stick_area_fraction = ratio
        c.stick_width_ratio = 1.0 if ratio > 0.0 else 0.0


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
        self._fused = _fusable(effects)
        #: ``checked_step(contact) -> bool``: :meth:`step` behind a cheap validity check of the
        #: inputs (see :func:`checked_steps`); fused into one function for the creep-only
        #: table scene (:func:`_normal_table_creep`).
        self.checked_step = (_normal_table_creep(effects["normal"], effects["creep"],
                                                 _declined, _no_log)
                             if self._fused else checked_steps(self._steps))

    def step(self, contact):
        """Evaluate every built effect once on ``contact`` (in place)."""
        for step in self._steps:
            step(contact)

    def auxiliary(self, contact):
        """Evaluate the outputs effects compute only on demand (after a step)."""
        for e in self._auxiliary:
            e.auxiliary(contact)

    def fmu_step(self, contact, otherwise, on_error):
        """The whole FMU ``do_step(current_time, step_size)`` in one Python frame, if fused.

        For the scene whose effects are exactly the normal contact and the modified-strip creep
        table (the creep-only table scene): a callable ``(current_time, step_size) -> True``
        that makes the cheap input check and evaluates both effects on ``contact`` (as
        :attr:`checked_step`); if the check does not pass it returns
        ``otherwise(current_time, step_size)`` (the slave's full path: the range check that
        names the input, then the effects), and a ValueError raised by a model is passed to
        ``on_error(current_time, exc)`` and re-raised. None for every other scene.
        """
        if not self._fused:
            return None
        step = _normal_table_creep(self.effects["normal"], self.effects["creep"], otherwise,
                                   on_error)
        return functools.partial(step, contact)

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
# the FMU's per-step call: input pre-check + effects, one Python frame where possible
# --------------------------------------------------------------------------------------------
# An FMU step is a few microseconds of Python, so the interpreter overhead (frames, attribute
# look-ups, float() calls) is a large part of it (the target: the creep-only table scene at
# <= 2x a trivial PythonFMU slave's doStep, measured by benchmarks/bench_fmu.py). The
# functions below return closures with everything constant bound at build time.


def _inputs_plausible(c, _isfinite=math.isfinite):
    """Cheap check: all six inputs finite (one isfinite on their sum), N >= 0 and V >= 0.

    False does not mean invalid (a sum may overflow): the caller then makes the full range
    check, with messages naming the input."""
    n, v = c.normal_force, c.rolling_speed
    return (_isfinite(n + c.creepage_longitudinal + c.creepage_lateral + c.spin + v
                      + c.rail_position) and n >= 0.0 and v >= 0.0)


def checked_steps(steps):
    """``checked(c)``: if :func:`_inputs_plausible`, evaluate ``steps`` on ``c`` and return
    True; else return False and change nothing."""
    def checked(c, _ok=_inputs_plausible):
        if not _ok(c):
            return False
        for step in steps:
            step(c)
        return True
    return checked


def _fusable(effects):
    """True for exactly {normal (ellipse), creep (modified-strip table)}: the fused step."""
    normal, creep = effects.get("normal"), effects.get("creep")
    return (list(effects) == ["normal", "creep"] and type(normal) is NormalContact
            and not normal._line and type(creep) is Creep3D and creep._table is not None
            and not creep._exact and creep._force == getattr(creep._table, "_scalar", None))


def _declined(current_time, step_size):
    return False


def _no_log(current_time, exc):
    pass


def _normal_table_creep(normal, creep, otherwise, on_error):
    """:func:`checked_steps` for ``NormalContact.step`` then ``Creep3D.step`` (table,
    modified strip), fused into one function: the same statements in the same order, with
    the effects' constants bound here and the table's scalar path (``CreepTable._scalar``)
    inlined, so the results are the same bit for bit (tests/test_effects.py); both call
    counters still count.

    Returns ``step(c, current_time=0.0, step_size=0.0)``: True after evaluating, or
    ``otherwise(current_time, step_size)`` if the cheap input check does not pass (nothing
    changed); a ValueError of a model goes to ``on_error(current_time, exc)``, then up.
    """
    a1, b1, p1, fixed = normal._a1, normal._b1, normal._p1, normal._fixed
    table, e_mod, nu, use_spin = creep._table, creep._e, creep._nu, creep.use_spin
    estimate = creep.table_error_estimate
    third = 1.0 / 3.0
    # CreepTable._scalar (creep._force, see _fusable), inlined below with its constants bound
    # here: the same operations in the same order; nu is fixed by the scene, so the factor
    # pi^2 (1 + nu) of w_sat is computed once (it is the first product of _scalar's
    # left-to-right expression, so the result is the same bit for bit), and the Kalker
    # coefficients are memoised per a0/b0 in a small dict: with Hertz's scaling a0/b0 =
    # (a1 s)/(b1 s) takes a few rounded values (3 seen), which a one-slot memo would miss
    kalker, sqrt, hypot, bisect = _table_kalker(), math.sqrt, math.hypot, table._bisect
    pi, pi2_nu = math.pi, math.pi**2 * (1.0 + nu)
    slope0, half_curv0, z_max = table._slope0, 0.5 * table._curv0, table._z_max
    breaks, coefs = table._pp_breaks, table._pp_coefs
    guard = 1.0 - 2.0**-51
    from . import creep3d

    lo, hi = creep3d.MODERATE_MIN, creep3d.MODERATE_MAX
    e_ok = lo <= e_mod <= hi
    memo = {}
    memo_get = memo.get

    def step(c, current_time=0.0, step_size=0.0, _isfinite=math.isfinite, _inf=math.inf):
        n, v = c.normal_force, c.rolling_speed
        xi_x, xi_y, phi = c.creepage_longitudinal, c.creepage_lateral, c.spin
        if not (_isfinite(n + xi_x + xi_y + phi + v + c.rail_position) and n >= 0.0
                and v >= 0.0 and 0.0 <= step_size < _inf):
            return otherwise(current_time, step_size)
        # NormalContact.step
        normal.calls += 1
        if fixed:
            a0, b0, p0 = a1, b1, p1 * n
        else:
            scale = n ** third
            a0, b0, p0 = a1 * scale, b1 * scale, p1 * scale
        c.a0, c.b0, c.p0 = a0, b0, p0
        c.contact_half_width = a0
        # Creep3D.step, table path
        creep.calls += 1
        c.creep_table_error_estimate = estimate
        if n <= 0.0:
            if xi_x or xi_y or phi:                  # (NormalContact.step)
                normal._warn("no-normal-force", NO_NORMAL_FORCE_MESSAGE)
            c.Fx = c.Fy = 0.0
            c.stick_area_fraction = c.stick_width_ratio = c.r_a0 = 1.0
            c.creep_within_validity = True
            c.Mz = 0.0
            creep._aux_args = None
            return True
        if not use_spin:
            phi = 0.0
        mu = c.friction_coefficient
        # CreepTable._scalar(table, xi_x, xi_y, phi, n, a0, b0, e_mod, nu, mu), n > 0 here
        if a0 <= 0.0 or b0 <= 0.0 or mu <= 0.0:
            c.Fx, c.Fy = 0.0, 0.0
            creep._aux_args = (xi_x, xi_y, phi, n, a0, b0, e_mod, nu, mu)
            return True
        if not (e_ok and lo <= n <= hi and lo <= mu <= hi and lo <= a0 <= hi
                and lo <= b0 <= hi and (xi_x == 0.0 or lo <= abs(xi_x) <= hi)
                and (xi_y == 0.0 or lo <= abs(xi_y) <= hi)
                and (phi == 0.0 or lo <= abs(phi) <= hi)):
            # extreme magnitudes (railcontact.creep3d._moderate): as CreepTable._scalar, the
            # overflow-safe array path, which raises a ValueError naming a bad input
            try:
                c.Fx, c.Fy = table._scalar(xi_x, xi_y, phi, n, a0, b0, e_mod, nu, mu)
            except ValueError as exc:
                on_error(current_time, exc)
                raise
            creep._aux_args = (xi_x, xi_y, phi, n, a0, b0, e_mod, nu, mu)
            return True
        g = a0 / b0
        coefs_k = memo_get(g)
        if coefs_k is None:
            try:
                coefs_k = kalker(g, nu)
            except ValueError as exc:  # (Kalker coefficients' range; shape fixed by the scene)
                on_error(current_time, exc)
                raise
            if len(memo) >= 64:
                memo.clear()
            memo[g] = coefs_k
        c11, c22, c23 = coefs_k
        w_x = c11 * xi_x
        w_y = c22 * xi_y + sqrt(a0 * b0) * c23 * phi
        w_sat = pi2_nu * mu * (1.5 * n / (pi * a0 * b0)) / e_mod
        if w_sat <= 0.0:
            c.Fx, c.Fy = -0.0, -0.0
            creep._aux_args = (xi_x, xi_y, phi, n, a0, b0, e_mod, nu, mu)
            return True
        mu_n = mu * n
        z = hypot(w_x, w_y) / w_sat
        if z < 1e-6:
            f_over_z = slope0 + half_curv0 * z
        else:
            zz = z if z < z_max else z_max
            i = bisect(breaks, zz) - 1
            if i < 0:
                i = 0
            k3, k2, k1, k0 = coefs[i]
            dz = zz - breaks[i]
            f = ((k3 * dz + k2) * dz + k1) * dz + k0
            if f > 1.0:
                f = 1.0
            f_over_z = f / z
        k = mu_n / w_sat * f_over_z
        tx, ty = -k * w_x, -k * w_y
        t_abs = hypot(tx, ty)
        if t_abs > mu_n:
            r = mu_n * guard / t_abs
            tx, ty = tx * r, ty * r
        c.Fx, c.Fy = tx, ty
        creep._aux_args = (xi_x, xi_y, phi, n, a0, b0, e_mod, nu, mu)
        return True
    return step


def _table_kalker():
    """The scalar Kalker lookup the creep table's scalar path uses (cached per (a0/b0, nu))."""
    from .strip_table import _kalker_cached  # noqa: PLC0415

    return _kalker_cached


def build_pipeline(scene, tables_dir=None, warn=None):
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

    Raises
    ------
    SceneError
        If an effect is not available in this build or its options are invalid.
    """
    for name in scene.effects:
        if name not in EFFECTS:
            raise EffectUnavailable(f"effect {name} not available in this build")
    replaced = {victim: name for name in EFFECTS if name in scene.effects
                for victim in EFFECTS[name].replaces if victim in scene.effects}
    effects = {"normal": NormalContact(scene, warn=warn)}
    wear = None
    for name in EFFECTS:
        if name not in scene.effects or name in replaced:
            continue
        try:
            if name == "corrugation" and "wear" in scene.effects:
                # the wear effect first: the corrugated contact sums its coefficients
                wear = Wear(scene, tables_dir=tables_dir, warn=warn)
            effect = (wear if name == "wear" and wear is not None
                      else _build_effect(name, scene, tables_dir, warn, wear))
        except ImportError as exc:          # a model module missing from this build
            raise EffectUnavailable(f"effect {name} not available in this build ({exc})"
                                    ) from None
        effects[name] = effect
    if wear is not None:
        wear.corrugation = effects["corrugation"]
    return Pipeline(scene, effects, replaced)


def _build_effect(name, scene, tables_dir, warn, wear):
    """The effect object ``name`` of the registry for ``scene``."""
    if name == "nonsteady":
        return NonSteady(scene)
    if name == "creep":
        if scene.effects["creep"]["method"] == "carter":
            return Creep2D(scene)
        table_path = None
        if scene.effects["creep"]["source"] == "table" and tables_dir is not None:
            from pathlib import Path

            table_path = Path(tables_dir) / f"{scene.effects['creep']['table']}.nc"
        return Creep3D(scene, table_path=table_path, warn=warn)
    if name == "velocity_friction":
        return VelocityFriction(scene, tables_dir=tables_dir, warn=warn)
    if name == "roughness":
        return Roughness(scene)
    if name == "corrugation":
        return Corrugation(scene, wear=wear, tables_dir=tables_dir, warn=warn)
    if name == "wear":
        return Wear(scene, tables_dir=tables_dir, warn=warn)
    raise EffectUnavailable(f"effect {name} not available in this build")
