"""Rough rail surface (Nielsen Ch. 6): the single-asperity solution on the local gap, in place
of Carter's force."""

from __future__ import annotations

from .. import roughness
from ..scene import SceneError
from .base import Effect, EffectUnavailable

__all__ = ["Roughness"]


class Roughness(Effect):
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
        if opts.get("profile_file"):
            key = "effects.roughness.profile_file"
            try:
                self.surface = roughness.ProfileRoughness(opts["profile_positions"],
                                                       opts["profile_heights"],
                                                       opts["profile_extension"])
            except ValueError as exc:
                raise SceneError(f"{key}: {exc}") from None
        else:
            key = "effects.roughness.amplitudes_cos/amplitudes_sin"
            self.surface = roughness.HarmonicRoughness(
                opts["wavelengths"], opts["amplitudes_cos"], opts["amplitudes_sin"])
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
        solver = roughness.RoughRailSolver(self.surface, self._radius, self._e, self._nu)
        self._solve, self._local_gap = solver.contact, solver.local_gap
        # N~ per unit of normal_force (text after Nielsen (6.10))
        self._nt_per_newton = (float(roughness.normalised_load(1.0, self._e, self._nu))
                               / self._width)

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


