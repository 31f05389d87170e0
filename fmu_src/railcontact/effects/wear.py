"""Frictional wear per passage (Nielsen Sec. 4.3) and the evolution of the surface (Sec. 4.4)."""

from __future__ import annotations

import math

from .. import wear
from .._lazy import lazy_submodule
from .._scalar import evolve_harmonics_scalar
from ..evolution import wear_number_unchecked
from ..scene import SceneError
from .base import ContactPoint, Effect
from .response_table import ResponseTable

__all__ = ["Wear"]


class Wear(Effect):
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
        # the formulas of mean_wear and wear_number without their checks (inputs checked by
        # the scene and the slave, r_a0 clipped to [0, 1])
        self._mean_wear = wear.mean_wear_unchecked
        self._wear_number = wear_number_unchecked
        # evolve_harmonics for one passage count on lists (cmath; checks W, falls back to it)
        self._evolve = evolve_harmonics_scalar
        # wear_coefficients on a list at one r: the series models' compiled kernel directly
        # (the analytic source only: a table scene loads no numba or scipy.special for it)
        self._wear_coefficients = (
            None if scene.effects["wear"]["source"] == "table"
            else lazy_submodule("_corrugation_kernels").wear_coefficients_list
            if scene.effects["wear"]["wear_model"] in ("material_point", "patch_coordinate")
            else wear.wear_coefficients)
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
            self._table = ResponseTable(tables_dir, "wear", warn)

    def _w(self, c, wavelengths):
        """W1 + i W2 per harmonic for the contact state c (complex list)."""
        n_line = c.normal_force / self._width
        number = self._wear_number(self.wear_coefficient, c.friction_coefficient, n_line, c.a0)
        r = min(max(c.r_a0, 0.0), 1.0)
        if self._table is not None:        # table source: w from corrugation_response
            return [number * v[4] for v in self._table.coefficients_list(
                [c.a0 / lam for lam in wavelengths], r)]
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


