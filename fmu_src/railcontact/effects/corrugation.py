"""Corrugated rail surface (Nielsen Ch. 4.2): the contact, its force and the wear per passage
at the rail position, from the closed forms or the table ``corrugation_response``."""

from __future__ import annotations

import math

import numpy as np

from .. import corrugation
from .._lazy import lazy_submodule
from ..scene import SceneError
from ..wear import corrugated_wear_depth_unchecked
from .base import NOT_ESTIMATED, Effect
from .response_table import ResponseTable

__all__ = ["Corrugation", "wear_series_degree"]


def wear_series_degree(ka):
    """Series degree :func:`railcontact.wear.wear_coefficients` uses by default for ``k a0 = ka``:
    ``ceil(e ka) + 12`` (its documented default; ``tests/test_effects.py`` checks that they
    agree). [-]"""
    return int(math.ceil(math.e * ka)) + 12


class Corrugation(Effect):
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
        opts = scene.effects["corrugation"]
        self.source = opts["source"]
        geo = scene.geometry
        self.method = opts["method"]
        # corrugated_contact at one position as floats (the same compiled kernels; it calls
        # corrugated_contact itself where that raises) and the series estimate's kernel
        solver = corrugation.CorrugatedContactSolver(geo["radius"], scene.youngs_modulus,
                                                     scene.poisson_ratio, self.method)
        self._solve_scalar = solver.contact
        self._surface = solver.surface
        self._load_underflows = solver.load_underflows
        self._truncation_error_scalar = None   # (its compiled kernel, on the first estimate)
        self.wavelengths = list(opts["wavelengths"])
        self.amplitudes_cos = list(opts["amplitudes_cos"])
        self.amplitudes_sin = list(opts["amplitudes_sin"])
        self._radius, self._width = geo["radius"], geo["contact_width"]
        self._e, self._nu = scene.youngs_modulus, scene.poisson_ratio
        self._wear = wear
        if wear is not None:
            # wear per passage at the material point under the contact (the wear module's
            # corrugated_wear_depth without its checks; the wear module depends on the contact
            # module, not the other way round)
            self._wear_depth_unchecked = corrugated_wear_depth_unchecked
        self._series = wear is not None and wear.wear_model in ("material_point",
                                                                 "patch_coordinate")
        self._table = None
        if self.source == "table":
            self._table_setup(scene, wear, tables_dir, warn)
        self._pending_ka = None
        k = [2.0 * math.pi / lam for lam in self.wavelengths]
        try:
            corrugation.check_no_contact_loss([
                km * km * self._radius * math.hypot(za, zb)
                for km, za, zb in zip(k, self.amplitudes_cos, self.amplitudes_sin)])
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
        self._table = ResponseTable(tables_dir, "corrugation", warn)
        self._comp = 4.0 * (1.0 - self._nu ** 2) / (math.pi * self._e)
        self._k = [2.0 * math.pi / lam for lam in self.wavelengths]
        self._kr = [km * self._radius for km in self._k]      # k R of each harmonic
        # the amplitude lists (4.2) was checked for, and the table's buffer of them
        self._checked_surface = None, None
        self._harmonics = None
        self._sums = np.zeros(4)
        # no series is summed at run time unless the wear effect's own coefficients are
        # analytic (growth rate, evolution)
        self._series = self._series and wear.source == "analytic"

    def _step_table(self, c):
        """:func:`railcontact.corrugation.corrugated_contact` (method "linear") with the
        response coefficients from the table: the same superposition over the harmonics."""
        big_r, n_line, mu = self._radius, c.normal_force / self._width, c.friction_coefficient
        za, zb, k = self.amplitudes_cos, self.amplitudes_sin, self._k
        if za is not self._checked_surface[0] or zb is not self._checked_surface[1]:
            # (once per surface: the wear effect evolves it into new lists)
            curvatures = [km * km * big_r * math.hypot(a, b) for km, a, b in zip(k, za, zb)]
            if any(v >= 1.0 for v in curvatures):
                corrugation.check_no_contact_loss(curvatures)               # raises (4.2)
            self._checked_surface = za, zb
            self._harmonics = self._table.harmonics(self.wavelengths, za, zb, big_r)
        a0, x = c.a0, c.rail_position
        xi = abs(c.creepage_longitudinal)
        a0s = max(a0 - xi * big_r / mu, 0.0)
        r = a0s / a0
        one_minus_r = min(xi * big_r / (mu * a0), 1.0)          # 1 - r without cancellation
        t = mu * n_line * one_minus_r * (2.0 - one_minus_r)
        wear = self._wear
        if wear is not None:
            kw = wear.wear_coefficient
            depth = kw * mu * mu * n_line * a0 / big_r * (1 - r) ** 2 * (1 + r)
            w_scale = kw * mu * mu * n_line / a0
        scale_t = mu / self._comp
        sums = self._sums
        if self._table.superpose(self._harmonics, a0, x, r, sums):
            # one compiled call: the table's rows and the sums over the harmonics
            s_a, s_d, s_t, s_w = sums.tolist()
            a, d = a0 + s_a, s_d
            t += scale_t * s_t
            if wear is not None:
                depth += w_scale * s_w
        else:
            a, d = a0, 0.0
            # outside the table's grid: the closed forms per harmonic, the same sums; in
            # real arithmetic: z = (Z_A + i Z_B) e^{-i k x} = z_r + i z_i; the response
            # coefficients are c_a = hw, c_Delta = i ps, c_T = tr + i ti, w = wr + i wi, and
            # each term is Re(c z) (Eqs. (4.36)-(4.71), (4.94)-(4.95))
            rows = self._table.rows([a0 / lam for lam in self.wavelengths], r, wear is not None)
            for (hw, ps, _, _, tr, ti, wr, wi), km, kr, zam, zbm in zip(rows, k, self._kr, za,
                                                                      zb):
                ckx = math.cos(km * x)
                skx = math.sin(km * x)
                z_r = zam * ckx + zbm * skx
                z_i = zbm * ckx - zam * skx
                a += hw * kr * z_r
                d -= ps * kr * z_i
                t += scale_t * (tr * z_r - ti * z_i)
                if wear is not None:
                    depth += w_scale * (wr * z_r - wi * z_i)
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
            # (the surface as the solver holds it: float arrays, made once per surface)
            za_a, zb_a, lam_a, _, _ = self._surface(za, zb, lam)
            c.wear_depth_per_passage = self._wear_depth_unchecked(
                x, n_line, self._radius, self._e, self._nu, mu, xi, za_a, zb_a, lam_a,
                wear.wear_coefficient, wear.wear_model)

    def auxiliary(self, c):
        """``corrugation_series_error_estimate`` of the last step (on demand)."""
        ka, self._pending_ka = self._pending_ka, None
        if ka is not None:
            if self._truncation_error_scalar is None:
                self._truncation_error_scalar = lazy_submodule(
                    "_corrugation_kernels").series_relative_error
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


