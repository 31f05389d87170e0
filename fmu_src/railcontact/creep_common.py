"""What the 3-D creep methods share: their result types and the spin coefficient.

:mod:`railcontact.creep3d` (the closed-form theories, FASTSIM/Polach/FaStrip dispatch and the
exact solver) and :mod:`railcontact.exact_table` (the exact theory from its table) both return
these types; this module sits below both, so neither imports the other for them.
"""

from __future__ import annotations

from collections import namedtuple

import numpy as np

from ._floats import _hypot_scaled, _value
from ._validation import check_range

__all__ = ["CreepForce3D", "CreepSolution3D", "ExactCreepSolution3D", "spin_coefficient"]

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
