"""What the 3-D creep methods share: their result types and the spin coefficient.

:mod:`railcontact.creep3d` (the closed-form theories, FASTSIM/Polach/FaStrip dispatch and the
exact solver) and :mod:`railcontact.exact_table` (the exact theory from its table) both return
these types; this module sits below both, so neither imports the other for them.
"""

from __future__ import annotations

from collections import namedtuple

import numpy as np

from ._floats import NO_EXP as _NO_EXP, TINY_SUBNORMAL as _TINY_SUBNORMAL
from ._floats import hypot_scaled as _hypot_scaled, root_ab as _root_ab
from ._floats import scaled as _scaled, value as _value
from ._validation import check_range
from .kalker import A0_OVER_B0_MAX

__all__ = ["CreepForce3D", "CreepSolution3D", "ExactCreepSolution3D", "spin_coefficient"]

#: Weight of the spin in the exact table's creepage coordinate:
#: ``w^2 = 1 + (SPIN_WEIGHT tau)^2`` (:mod:`railcontact.exact_table`; here so that its reader
#: and its compiled kernels share it without either importing the other). [-]
SPIN_WEIGHT = 1.0
#: Form of that coordinate, ``s = (2 / pi) atan(rho / w)`` (global attribute
#: ``creepage_coordinate_form`` of the table file; files before 2026-11-27 used
#: ``rho / sqrt(rho^2 + w^2)``, whose approach to s = 1 goes like the square root of the
#: force's 1/rho tail and cost up to 1.6 % of mu N far past saturation with spin).
CREEPAGE_COORDINATE_FORM = "arctan"
#: Below this combined creepage |v| the exact table's Jacobian is taken in Cartesian form
#: from the radial derivatives along v_x and v_y at |v| = JACOBIAN_RHO_MIN (the polar
#: coordinates divide by |v|; the Jacobian is continuous there). [-]
JACOBIAN_RHO_MIN = 1e-6

#: The exact table's solver uses EXACT_TABLE_LATERAL_ELEMENTS_NARROW lateral elements (20
#: elsewhere) where a0/b0 < EXACT_TABLE_NARROW_ASPECT_MAX and |tau| >
#: EXACT_TABLE_NARROW_SPIN_MIN (narrow contacts with large spin: with 20 elements across
#: 2.16 b0 the discrete solution depends on where the spin pole falls between element rows,
#: up to 1.5 % of mu N at a0/b0 = 0.18; with 36 up to 0.2 %; tablegen.specs and
#: railcontact.creep3d.load_exact_table's solver beyond the table both follow it; 0.87, between
#: the table's nodes 0.75 and 1 of a0/b0, since 2026-11-27, was 0.75). [-]
EXACT_TABLE_LATERAL_ELEMENTS_NARROW = 36
EXACT_TABLE_NARROW_ASPECT_MAX = 0.87
EXACT_TABLE_NARROW_SPIN_MIN = 2.75
#: ... and EXACT_TABLE_LATERAL_ELEMENTS_VERY_NARROW where a0/b0 <
#: EXACT_TABLE_VERY_NARROW_ASPECT_MAX and |tau| > EXACT_TABLE_NARROW_SPIN_MIN (since
#: 2026-11-28, issue 40: narrow contacts with large spin, where the public default,
#: railcontact.creep3d.exact_default_grid, uses 48 too). Rebuilt in steps with --reuse-nodes:
#: 0.115, between the table's nodes 0.1 and 0.133, takes the node 0.1 (28,980 solver points of
#: the computed quarter); 0.2, between 0.178 and 0.316, the nodes 0.133 and 0.178 next
#: (57,960 more). [-]
EXACT_TABLE_LATERAL_ELEMENTS_VERY_NARROW = 48
EXACT_TABLE_VERY_NARROW_ASPECT_MAX = 0.115

CreepForce3D = namedtuple("CreepForce3D", ["tx", "ty"])
CreepForce3D.__doc__ = "Tangential creep force on the wheel, components tx, ty. [N]"

CreepSolution3D = namedtuple("CreepSolution3D", [
    "tx", "ty", "stick_area_fraction", "stick_width_ratio", "normalised_creepage",
    "spin_coefficient", "within_validity"])
CreepSolution3D.__doc__ = """Full result of :func:`creep_solution_3d`.

tx, ty : force on the wheel [N].
stick_area_fraction : stick area / (pi a0 b0) [-], strip-theory estimate (see module docstring);
    1 for "linear" (full stick by assumption); for "she", which has no stick zone, the
    modified-strip estimate at the same creepages.
stick_width_ratio : b*/b0 = sqrt(1 - z^2) [-], lateral extent of the stick zone (Eq. (2.84)).
normalised_creepage : z = |w| / w_sat [-] of the method ("strip" uses its own coefficients; the
    modified-strip value for the others); 1 = onset of full sliding.
spin_coefficient : Phi, Eq. (2.98) [-] (inf for pure spin, 0 without spin).
within_validity : bool, Phi <= 1 (spin pole outside the ellipse) and, for "linear",
    |T| <= mu N.
"""


ExactCreepSolution3D = namedtuple("ExactCreepSolution3D", [
    "tx", "ty", "stick_area_fraction", "stick_width_ratio", "normalised_creepage",
    "spin_coefficient", "within_validity", "spin_moment", "sensitivity", "fields",
    "iterations"])
ExactCreepSolution3D.__doc__ = """Result of :func:`creep_solution_3d` with ``method="exact"``.

The first seven fields are those of :class:`CreepSolution3D`, so code reading them works for
every method.

tx, ty : force on the wheel [N].
stick_area_fraction : area of the sticking elements / (pi a0 b0) [-] (of the finer grid with
    ``extrapolate=True``).
stick_width_ratio : lateral extent of the stick zone / (2 b0) [-] (rows holding a sticking
    element times the element width); 0 without stick.
normalised_creepage : the modified-strip z = |w| / w_sat [-] (see
    :func:`normalised_creepage_3d`), for comparison with the other methods.
spin_coefficient : Phi, Eq. (2.98) [-].
within_validity : bool, always True (the exact theory holds for any spin; the solver raises
    instead of returning an unconverged answer).
spin_moment : M_z about the ellipse centre on the wheel, sum (x p_y - y p_x) dA [N m].
sensitivity : with ``sensitivities=True`` an array of shape ``(..., 3, 3)``:
    d(tx, ty, M_z)/d(xi_x, xi_y, phi), rows tx [N], ty [N], M_z [N m], columns per unit
    xi_x [-], xi_y [-], phi [1/m]; else None.
fields : with ``fields=True`` the solver's :class:`railcontact.reference.rolling3d.Rolling3DResult`
    (element centres, pressure, tractions px, py [Pa], slip, adhesion masks; an object array
    for array input); else None.
iterations : Gauss-Seidel sweeps used (summed over both grids with ``extrapolate``) [-].
"""



def spin_coefficient(creepage_longitudinal, creepage_lateral, spin, a0, b0):
    r"""Spin coefficient Phi, Eq. (2.98): ``sqrt(a0^2 + b0^2) |phi| / sqrt(xi_x^2 + xi_y^2)``.

    Parameters
    ----------
    creepage_longitudinal, creepage_lateral : array_like
        Creepages xi_x, xi_y. [-]
    spin : array_like
        Spin creepage phi. [1/m]
    a0, b0 : array_like
        Semi-axes of the contact ellipse, >= 0. [m]

    Returns
    -------
    ndarray
        Phi >= 0 [-]; 0 when phi = 0 (also with zero creepage), inf for pure spin. The spin pole
        (-xi_y/phi, xi_x/phi), Eq. (2.97), lies outside the ellipse when Phi <= 1.
    """
    xi_x = check_range("creepage_longitudinal", creepage_longitudinal, "-")
    xi_y = check_range("creepage_lateral", creepage_lateral, "-")
    phi = check_range("spin", spin, "1/m")
    a0 = check_range("a0", a0, "m", 0.0, None)
    b0 = check_range("b0", b0, "m", 0.0, None)
    # hypot(a0, b0) |phi| / hypot(xi_x, xi_y) in (mantissa, exponent) form: no overflow
    n_m, n_e = _hypot_scaled(a0, b0)
    d_m, d_e = _hypot_scaled(xi_x, xi_y)
    p_m, p_e = np.frexp(np.abs(phi))
    n_m, d_m, p_m, n_e, d_e, p_e = np.broadcast_arrays(n_m, d_m, p_m, n_e, d_e, p_e)
    num_m = n_m * p_m
    den = d_m > 0.0
    ratio = _value(num_m / np.where(den, d_m, 1.0), n_e + p_e.astype(np.int64) - d_e)
    return np.where(den, ratio, np.where(num_m > 0.0, np.inf, 0.0))[()]


# --------------------------------------------------------------------------------------------
# The overflow-safe creepage arithmetic the closed-form theories and the strip table share
# --------------------------------------------------------------------------------------------

def axis_ratio(a0, b0):
    """a0/b0 where both are > 0 (else the placeholder 1), checked against the range of
    :func:`railcontact.kalker_coefficients`; an underflow to 0 is held at the smallest
    subnormal (the coefficients have reached their a0/b0 -> 0 limits long before)."""
    has_area = (a0 > 0.0) & (b0 > 0.0)
    with np.errstate(over="ignore", under="ignore"):
        g = np.where(has_area, a0 / np.where(has_area, b0, 1.0), 1.0)
    return check_range("a0/b0", np.maximum(g, _TINY_SUBNORMAL), "-", 0.0, A0_OVER_B0_MAX,
                       lower_closed=False,
                       condition="semi-axis ratio; Kalker's C23 ~ (a0/b0)^1.5 overflows beyond")


def weighted_creepage_scaled(xi_x, xi_y, phi, a0, b0, c11, c22, c23, parts=False):
    """The Kalker-weighted creepage w = (C11 xi_x, C22 xi_y + sqrt(a0 b0) C23 phi) without
    overflow: its direction (unit vector, (0, 0) for w = 0) and |w| as (m, e); with
    ``parts`` also (ux, uy, top), w = (ux, uy) 2^top."""
    t1 = _scaled((c11, xi_x))
    t2 = _scaled((c22, xi_y))
    t3 = _scaled((_root_ab(a0, b0), c23, phi))
    ey = np.maximum(t2[1], t3[1])
    wy_m = _value(t2[0], t2[1] - ey) + _value(t3[0], t3[1] - ey)    # |.| <= 2
    wy_m, wy_e = np.frexp(wy_m)
    wy_e = np.where(wy_m == 0.0, _NO_EXP, ey + wy_e.astype(np.int64))
    top = np.maximum(t1[1], wy_e)
    ux = _value(t1[0], t1[1] - top)                 # w / 2^top: |.| <= 1, one of them >= 1/2
    uy = _value(wy_m, wy_e - top)
    u_abs = np.hypot(ux, uy)
    nonzero = u_abs > 0.0
    safe = np.where(nonzero, u_abs, 1.0)
    dx = np.where(nonzero, ux / safe, 0.0)
    dy = np.where(nonzero, uy / safe, 0.0)
    m, e = np.frexp(u_abs)
    out = dx, dy, m, np.where(nonzero, top + e.astype(np.int64), _NO_EXP)
    return out + (ux, uy, top) if parts else out


def saturation_creepage_scaled(n_load, a0, b0, e_mod, nu, mu):
    """w_sat = 1.5 pi (1 + nu) mu N / (a0 b0 E) (= pi^2 (1 + nu) mu p0 / E with Hertz's p0)
    as (m, e); m = 0 without contact (N, mu, a0 or b0 zero)."""
    has_area = (a0 > 0.0) & (b0 > 0.0)
    # the operations (and roundings) of pi^2 (1 + nu) mu (1.5 N / (pi a0 b0)) / E
    area = _scaled((np.pi, np.where(has_area, a0, 1.0), np.where(has_area, b0, 1.0)))
    p0 = _scaled((1.5, n_load), (area,))
    m, e = _scaled((np.pi**2 * (1.0 + nu), mu, p0), (e_mod,))
    m = np.where(has_area, m, 0.0)
    return m, np.where(m == 0.0, _NO_EXP, e)


def coulomb_limit(mu, n_load):
    """mu N, which must be a finite float (it bounds the force)."""
    with np.errstate(over="ignore"):
        mu_n = mu * n_load
    if not np.all(np.isfinite(mu_n)):
        bad = np.broadcast_arrays(mu, n_load, mu_n)
        i = np.flatnonzero(~np.isfinite(bad[2]))[0]
        raise ValueError(
            f"friction_coefficient * normal_load (the Coulomb limit mu N) must be in "
            f"[0, {np.finfo(float).max:g}] [N]; got inf (friction_coefficient = "
            f"{bad[0].flat[i]:g}, normal_load = {bad[1].flat[i]:g})")
    return mu_n
