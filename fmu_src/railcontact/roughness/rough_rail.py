"""A rough rail under a rolling wheel (the thesis' use of the asperity model, Ch. 6): rail
surfaces (harmonics, Eq. (4.1), or a sampled profile), the local 4th-order gap about the gap
minimum, and the single-asperity contact there; :class:`RoughRailSolver` is the FMU step.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .. import polynomial as _poly
from .._validation import check_choice, check_range
from . import _kernels
from .asperity import (AsperityContact, AsperityTangentialContact, asperity_critical_creepage,
                       asperity_normal_contact, asperity_tangential_contact, normalised_load)


# ---------------------------------------------------------------------------------------------
# a rough rail under a rolling wheel: local 4th-order gap at a wheel position
# ---------------------------------------------------------------------------------------------
def _surface_derivatives(roughness, rail_position):
    """``r .. r''''`` of a HarmonicRoughness or ProfileRoughness at ``rail_position``."""
    x = np.asarray(rail_position, dtype=float)
    out = _kernels.surface_derivatives_array(*roughness._kernel_surface,
                                             np.ravel(x).astype(float))
    return out.reshape((5,) + x.shape)


class HarmonicRoughness:
    r"""Rail roughness as a sum of harmonics, the rail surface height of Eq. (4.1).

    ``r(X) = sum_m Z_A,m cos(k_m X) + Z_B,m sin(k_m X)``, ``k_m = 2 pi / L_m``: the same surface
    (height up, towards the wheel) as :mod:`railcontact.corrugation` describes with the same
    three lists. Derivatives are exact: ``r^(n)(X) = Re[(Z_A - i Z_B) (i k)^n e^(i k X)]``.

    Parameters
    ----------
    wavelengths : array_like, shape (M,)
        ``L_m``, > 0. [m]
    amplitudes_cos, amplitudes_sin : array_like, shape (M,)
        ``Z_A,m``, ``Z_B,m``. [m]
    """

    def __init__(self, wavelengths, amplitudes_cos, amplitudes_sin):
        lam = np.atleast_1d(check_range("wavelengths", wavelengths, "m", 0.0, None,
                                        lower_closed=False))
        za = np.atleast_1d(check_range("amplitudes_cos", amplitudes_cos, "m"))
        zb = np.atleast_1d(check_range("amplitudes_sin", amplitudes_sin, "m"))
        if not (lam.shape == za.shape == zb.shape) or lam.ndim != 1 or lam.size == 0:
            raise ValueError("wavelengths, amplitudes_cos, amplitudes_sin must be non-empty 1-D "
                             f"of equal length [m]; got shapes {lam.shape}, {za.shape}, "
                             f"{zb.shape}")
        self.wavelengths, self.amplitudes_cos, self.amplitudes_sin = lam, za, zb
        self._k = 2.0 * np.pi / lam
        self._zeta = za - 1j * zb
        # (i k)^n (Z_A - i Z_B) for n = 0..4, shape (5, M)
        coef = (1j * self._k) ** np.arange(5)[:, None] * self._zeta
        self._kernel_surface = (_kernels.HARMONIC, self._k, np.stack((coef.real, coef.imag)),
                                np.zeros(2))

    def derivatives(self, rail_position):
        r"""``r, r', r'', r''', r''''`` at ``rail_position``. [m, -, 1/m, 1/m^2, 1/m^3]

        ``r^(n)(X) = sum_m Re[(i k_m)^n (Z_A,m - i Z_B,m) e^(i k_m X)]``.

        Returns
        -------
        ndarray, shape (5,) + shape of rail_position
        """
        return _surface_derivatives(self, rail_position)

    def max_height_curvature(self):
        r"""``sum_m k_m^2 |Z_m|``, an upper bound of ``r''(X)``. [1/m]

        Exact (the supremum over X) for one harmonic and for rationally independent wave
        numbers (Kronecker); for commensurate wave lengths it may overestimate.
        """
        return float(np.sum(self._k**2 * np.abs(self._zeta)))

    def max_slope(self):
        """``sum_m k_m |Z_m|``, an upper bound of ``|r'(X)|``. [-]"""
        return float(np.sum(self._k * np.abs(self._zeta)))


class ProfileRoughness:
    r"""Rail roughness from a sampled height profile, interpolated by a quintic (C4) spline.

    :func:`scipy.interpolate.make_interp_spline` with ``k = 5`` through the samples; the
    derivatives up to 4th order are continuous inside the profile.

    Outside the sampled range (``extension``):

    * ``"periodic"``: the profile repeats with period ``positions[-1] - positions[0]``; the
      spline has periodic end conditions, so the surface is C4 everywhere. Needs
      ``heights[-1] == heights[0]`` (within 1e-12 of the largest height).
    * ``"hold"``: the spline has zero 1st and 2nd derivatives at both ends and the end heights
      are held outside (a flat rail): the surface is C2 at the ends (``r'''`` and ``r''''`` jump
      there, so the 4th-order gap coefficients do).

    Parameters
    ----------
    positions : array_like, shape (n,)
        Rail positions of the samples, strictly increasing, n >= 6. [m]
    heights : array_like, shape (n,)
        Rail surface height at them (up, towards the wheel, as in Eq. (4.1)). [m]
    extension : {"periodic", "hold"}
        See above.
    """

    def __init__(self, positions, heights, extension="periodic"):
        from scipy.interpolate import PPoly, make_interp_spline

        x = check_range("positions", positions, "m")
        y = check_range("heights", heights, "m")
        check_choice("extension", extension, {"periodic", "hold"})
        if x.ndim != 1 or x.shape != y.shape or x.size < 6:
            raise ValueError("positions and heights must be 1-D of equal length >= 6 (quintic "
                             f"spline) [m]; got shapes {x.shape}, {y.shape}")
        if np.any(np.diff(x) <= 0.0):
            raise ValueError("positions must be strictly increasing [m]")
        if extension == "periodic":
            tol = 1e-12 * max(np.abs(y).max(), np.finfo(float).tiny)
            if abs(y[-1] - y[0]) > tol:
                raise ValueError("heights: a periodic profile needs heights[-1] == heights[0] "
                                 f"[m]; got {y[0]:g} and {y[-1]:g} (use extension = 'hold')")
            y = y.copy()
            y[-1] = y[0]
            spline = make_interp_spline(x, y, k=5, bc_type="periodic")
        else:
            ends = [(1, 0.0), (2, 0.0)]
            spline = make_interp_spline(x, y, k=5, bc_type=(ends, ends))
        self.positions, self.heights, self.extension = x, y, extension
        self.spline = spline
        self._start, self._period = float(x[0]), float(x[-1] - x[0])
        self._ppoly = PPoly.from_spline(spline)
        # piecewise-polynomial coefficients of r, r', ..., r^(4) (highest power first, padded
        # with leading zeros to the quintic's 6) for a direct Horner evaluation of all five
        c = self._ppoly.c
        coef = np.zeros((5,) + c.shape)
        for n in range(5):
            cn = self._ppoly.derivative(n).c if n else c
            coef[n, c.shape[0] - cn.shape[0]:] = cn
        kind = _kernels.PERIODIC_PROFILE if extension == "periodic" else _kernels.HELD_PROFILE
        self._kernel_surface = (kind, np.ascontiguousarray(self._ppoly.x), coef,
                                np.array([self._start, self._period]))
        self._max_curvature = self._max_of_derivative(2)
        self._max_slope = self._max_of_derivative(1, absolute=True)

    def derivatives(self, rail_position):
        r"""``r, r', r'', r''', r''''`` at ``rail_position``. [m, -, 1/m, 1/m^2, 1/m^3]

        Returns
        -------
        ndarray, shape (5,) + shape of rail_position
        """
        return _surface_derivatives(self, rail_position)

    def _max_of_derivative(self, order, absolute=False):
        """Exact max of ``r^(order)`` (or of its magnitude) over the profile (critical points
        of the piecewise polynomial and the knots)."""
        p = self._ppoly.derivative(order)
        crit = self._ppoly.derivative(order + 1).roots(extrapolate=False)
        pts = np.concatenate((self._ppoly.x, crit[np.isfinite(crit)]))
        pts = pts[(pts >= self._start) & (pts <= self._start + self._period)]
        v = p(pts)
        if absolute:
            v = np.abs(v)
        best = float(v.max())
        return max(best, 0.0) if self.extension == "hold" else best

    def max_height_curvature(self):
        """``max_X r''(X)`` (exact, over the profile and its extension). [1/m]"""
        return self._max_curvature

    def max_slope(self):
        """``max_X |r'(X)|`` (exact). [-]"""
        return self._max_slope


@dataclass(frozen=True)
class LocalGap:
    r"""The gap between wheel and rough rail expanded about its minimum (:func:`local_gap`).

    ``Z(x) = l0 + l2 x^2/2 + l3 x^3/6 + l4 x^4/24`` with ``x`` from the contact point, which
    lies ``contact_point_shift`` ahead (+X) of the wheel axis.

    Attributes
    ----------
    contact_point_shift : ndarray
        ``x_c``: gap minimum relative to the wheel axis. [m]
    curvature : ndarray
        ``lambda2 = 1/R - r''(X + x_c)``. [1/m]
    skewness : ndarray
        ``lambda3 = -r'''(X + x_c)``. [1/m^2]
    flatness : ndarray
        ``lambda4 = -r''''(X + x_c)``. [1/m^3]
    rail_height : ndarray
        ``r(X + x_c)``. [m]
    """

    contact_point_shift: np.ndarray
    curvature: np.ndarray
    skewness: np.ndarray
    flatness: np.ndarray
    rail_height: np.ndarray


def _check_gap(roughness, radius):
    """The surface type, ``radius > 0`` and the convexity ``R max r'' < 1``: the radius."""
    if not isinstance(roughness, (HarmonicRoughness, ProfileRoughness)):
        raise ValueError("roughness must be a HarmonicRoughness or ProfileRoughness; got "
                         f"{type(roughness).__name__}")
    big_r = float(check_range("radius", radius, "m", 0.0, None, lower_closed=False))
    check_range("radius * max_height_curvature", big_r * roughness.max_height_curvature(), "-",
                None, 1.0, upper_closed=False,
                condition="the gap x^2/(2R) - r(X + x) must be convex: R max r'' < 1, "
                          "Eq. (4.2) generalised")
    return big_r


def local_gap(roughness, rail_position, radius, *, max_iter=60):
    r"""Local 4th-order gap of a wheel (equivalent radius R) on a rough rail, about its minimum.

    In the frame of the wheel axis at rail position ``X`` the undeformed gap is
    ``h(x) = x^2/(2R) - r(X + x)`` (the wheel's parabola (4.3) and the rail height ``r``, up
    positive, as in :func:`railcontact.reference.halfspace2d.solve_quasistatic_corrugated_2d`).
    Its minimum ``x_c`` (``h'(x_c) = x_c/R - r'(X + x_c) = 0``, unique because ``h`` is convex)
    is found by a safeguarded Newton iteration (bisection inside the bracket
    ``|x_c| <= R max|r'|``), and ``h`` is expanded there to 4th order: the lambdas of Nielsen's
    asperity (6.1) with no linear term, ``lambda2 = 1/R - r''``, ``lambda3 = -r'''``,
    ``lambda4 = -r''''`` at ``X + x_c``. The patch of the asperity solution is centred at
    ``x_c + Delta`` from the wheel axis.

    Parameters
    ----------
    roughness : HarmonicRoughness or ProfileRoughness
        Rail surface height.
    rail_position : array_like
        Wheel axis position(s) ``X``. [m]
    radius : float
        Equivalent radius ``R``, > 0. [m]
    max_iter : int, optional
        Newton/bisection iterations at most. [-]

    Returns
    -------
    LocalGap

    Raises
    ------
    ValueError
        Bad input, or the gap is not convex everywhere: ``R max r'' >= 1`` (the generalisation of
        condition (4.2); the rail is then more curved than the wheel somewhere and a second
        contact can appear).
    """
    big_r = _check_gap(roughness, radius)
    x_axis = check_range("rail_position", rail_position, "m")
    bound = big_r * roughness.max_slope()
    out, converged = _kernels.local_gap_array(*roughness._kernel_surface,
                                              np.ravel(x_axis).astype(float), big_r,
                                              bound, int(max_iter))
    if not converged:
        raise ValueError("rail_position: the gap minimum did not converge in max_iter = "
                         f"{max_iter} iterations [m]")
    out = out.reshape((5,) + x_axis.shape)
    return LocalGap(contact_point_shift=out[0], curvature=out[1], skewness=out[2],
                    flatness=out[3], rail_height=out[4])


@dataclass(frozen=True)
class RoughRailContact:
    r"""Contact of a wheel on a rough rail at one position (:func:`rough_rail_contact`).

    Attributes
    ----------
    gap : LocalGap
        The local 4th-order gap (its lambdas and the contact point ``x_c``).
    normal : AsperityContact
        Ch. 6 normal solution of that gap (half-width ``a``, shift ``Delta``).
    tangential : AsperityTangentialContact
        Ch. 6 steady rolling solution (stick ratio ``a*/a``, force).
    critical_creepage : float
        Full-slip creepage magnitude, Eq. (6.40) (with its factor mu). [-]
    """

    gap: LocalGap
    normal: AsperityContact
    tangential: AsperityTangentialContact
    critical_creepage: float

    @property
    def half_width(self):
        """``a``. [m]"""
        return self.normal.half_width

    @property
    def patch_shift(self):
        """Patch centre relative to the wheel axis, ``x_c + Delta``. [m]"""
        return float(self.gap.contact_point_shift) + self.normal.shift

    @property
    def stick_ratio(self):
        """``a*/a``. [-]"""
        return self.tangential.stick_ratio

    @property
    def tangential_force(self):
        """Force on the wheel, opposing the creepage. [N/m]"""
        return self.tangential.tangential_force


def rough_rail_contact(roughness, rail_position, normal_load, radius, youngs_modulus,
                       poisson_ratio, friction_coefficient, creepage):
    r"""Normal and steady tangential contact of a wheel on a rough rail at one position.

    :func:`local_gap` gives the 4th-order gap about the gap minimum; Nielsen's single-asperity
    solution (:func:`asperity_normal_contact`, Table 6.1, and
    :func:`asperity_tangential_contact`, (6.38)-(6.40)) gives the contact and the creep force.
    Quasi-static: the rail surface is frozen at each position (as in Ch. 4's quasi-static
    corrugated contact). The 4th-order gap is the Taylor expansion of the true gap, so the
    result converges to the exact contact as the half-width becomes small against the
    roughness wave lengths (measured in ``tests/test_roughness.py``: errors of order
    ``(k a)^2`` relative).

    Parameters
    ----------
    roughness : HarmonicRoughness or ProfileRoughness
    rail_position : float
        Wheel axis position ``X``. [m]
    normal_load : float
        Normal load per unit length, > 0. [N/m]
    radius : float
        Equivalent radius ``R``, > 0. [m]
    youngs_modulus : float
        > 0. [Pa]
    poisson_ratio : float
        In [0, 0.5). [-]
    friction_coefficient : float
        >= 0. [-]
    creepage : float
        Longitudinal creepage. [-]

    Returns
    -------
    RoughRailContact

    Raises
    ------
    ValueError
        Bad input (a load whose normalised value underflows counts as no contact and is
        rejected); the gap not convex (see :func:`local_gap`); or a restriction of Table 6.1
        fails at this position (the local quartic gap has no single coherent patch for this
        load, typically a strongly negative flatness on a crest when the half-width is not
        small against the roughness wave length): the message names ``rail_position`` and the
        restriction.
    """
    x = float(check_range("rail_position", rail_position, "m"))
    if float(normalised_load(normal_load, youngs_modulus, poisson_ratio)) < np.finfo(float).tiny:
        raise ValueError("normal_load must be > 0 with a normalised load 8 (1 - nu^2) N / (pi E) "
                         "of at least 2.2e-308 m (no contact below) [N/m]; got "
                         f"{float(normal_load):g}")
    gap = local_gap(roughness, x, radius)
    l2, l3, l4 = float(gap.curvature), float(gap.skewness), float(gap.flatness)
    try:
        normal = asperity_normal_contact(normal_load, l2, l3, l4, youngs_modulus, poisson_ratio)
    except ValueError as exc:
        raise ValueError(f"rail_position = {x:g} m: the local 4th-order gap (curvature {l2:.6g} "
                         f"1/m, skewness {l3:.6g} 1/m^2, flatness {l4:.6g} 1/m^3) has no "
                         f"single-patch solution of Table 6.1: {exc}") from None
    tangential = asperity_tangential_contact(normal, friction_coefficient, creepage=creepage)
    return RoughRailContact(gap, normal, tangential,
                            float(asperity_critical_creepage(normal, friction_coefficient)))


class RoughRailSolver:
    r""":func:`rough_rail_contact` at many positions, for a fixed surface, radius and material.

    The FMU's Roughness effect calls it once per step. The surface, radius and material are
    checked once here; :meth:`contact` returns plain floats from one compiled kernel (the same
    kernels as :func:`local_gap`, :func:`asperity_normal_contact` and
    :func:`asperity_tangential_contact`) and calls :func:`rough_rail_contact` itself where
    that raises (a non-finite position or creepage, an underflowing normalised load, a
    restriction of Table 6.1) or uses the full-stick series of Ch. 3 (``0 < |creepage| <
    1e-4 critical creepage``), so the errors and results are the public function's.

    Parameters
    ----------
    roughness : HarmonicRoughness or ProfileRoughness
    radius : float
        Equivalent radius ``R``, > 0, with ``R max r'' < 1``. [m]
    youngs_modulus : float
        > 0. [Pa]
    poisson_ratio : float
        In [0, 0.5). [-]
    """

    def __init__(self, roughness, radius, youngs_modulus, poisson_ratio):
        self.radius = _check_gap(roughness, radius)
        self.roughness = roughness
        self.youngs_modulus, self.poisson_ratio = float(youngs_modulus), float(poisson_ratio)
        kfac = float(_poly.kernel_factor(youngs_modulus, poisson_ratio))
        e, nu = self.youngs_modulus, self.poisson_ratio
        self._constants = (self.radius * roughness.max_slope(), kfac,
                           np.pi * e / (8.0 * (1.0 - nu**2)))
        self._surface = roughness._kernel_surface
        self._nt_per_load = 2.0 * kfac              # normalised_load: n * 2.0 * K

    def contact(self, rail_position, normal_load, friction_coefficient, creepage):
        """:func:`rough_rail_contact` as floats.

        Returns
        -------
        tuple of float
            ``(x_c, lambda2, lambda3, lambda4, a, Delta, force, stick_ratio,
            critical_creepage)``: the gap minimum's shift [m], the lambdas, the half-width
            and shift [m], the tangential force [N/m], ``a*/a`` and Eq. (6.40)'s critical
            creepage.
        """
        nt = normal_load * self._nt_per_load
        if (2.2250738585072014e-308 <= nt < math.inf and math.isfinite(rail_position)
                and math.isfinite(creepage) and 0.0 <= friction_coefficient < math.inf):
            bound, kfac, ref = self._constants
            *values, status = _kernels.rough_rail_contact(
                *self._surface, rail_position, normal_load, nt, self.radius, bound, kfac, ref,
                friction_coefficient, creepage, _poly.SERIES_LIMIT)
            if status == 0:
                return tuple(values)
        res = rough_rail_contact(self.roughness, rail_position, normal_load, self.radius,
                                 self.youngs_modulus, self.poisson_ratio, friction_coefficient,
                                 creepage)
        gap = res.gap
        return (float(gap.contact_point_shift), float(gap.curvature), float(gap.skewness),
                float(gap.flatness), float(res.half_width), float(res.normal.shift),
                float(res.tangential_force), float(res.stick_ratio),
                float(res.critical_creepage))

    def local_gap(self, rail_position):
        """:func:`local_gap` at one position as floats: ``(x_c, lambda2, lambda3, lambda4)``."""
        if math.isfinite(rail_position):
            xc, l2, l3, l4, _, converged = _kernels.local_gap(
                *self._surface, rail_position, self.radius, self._constants[0], 60)
            if converged:
                return xc, l2, l3, l4
        gap = local_gap(self.roughness, rail_position, self.radius)
        return (float(gap.contact_point_shift), float(gap.curvature), float(gap.skewness),
                float(gap.flatness))
