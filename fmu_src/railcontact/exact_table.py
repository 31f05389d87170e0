"""Coordinates of the exact-theory creep table (``tables/creep_exact.nc``).

The steady rolling problem of Kalker's exact theory with Hertzian pressure depends on the
inputs only through a0/b0, Poisson's ratio and three normalised creepages (scale invariance of
the half-space equations; J.J. Kalker, *Three-dimensional elastic bodies in rolling contact*,
Kluwer, 1990, Ch. 2). With Kalker's coefficients C_ij(a0/b0, nu), the saturation creepage
``w_sat = pi^2 (1 + nu) mu p0 / E`` and ``p0 = 3 N / (2 pi a0 b0)``:

    u_x = C11 xi_x / w_sat,   u_y = C22 xi_y / w_sat,   sigma = sqrt(a0 b0) C23 phi / w_sat,
    v = (u_x, u_y + sigma),   tau = sign(phi) |phi| sqrt((b0 C11)^2 + (a0 C22)^2) / w_sat.

In these units Kalker's linear theory reads ``T / (mu N) = -(3 pi / 4) v``. The table's five
axes are

    log_aspect_ratio  ln(a0/b0)
    poisson_ratio     nu
    creepage_coordinate  s = rho / sqrt(1 + rho^2), rho = |v|, *signed* (see below)
    creepage_angle    theta = atan2(v_y, v_x), periodic over [-pi, pi]
    spin_coordinate   tau (signed with phi)

and the variables are the force in the frame of v, ``T / (mu N) = -(f_par e + f_perp e_perp)``
with ``e = (cos theta, sin theta)``, ``e_perp = (-sin theta, cos theta)``, the spin moment
``M_z / (mu N sqrt(a0 b0))`` and the stick area fraction.

**Why these coordinates (smoothness).** A table that evaluates only a symmetry-reduced part
through absolute values has kinks on the symmetry planes (xi_x = 0, phi = 0). This table
instead covers every sign, and computes only a quarter with the solver:

* ``theta`` runs over the full circle with a periodic spline (C2 across xi_x = 0 and the seam
  at theta = +-pi);
* ``tau`` is signed and the table symmetric data on both sides of 0 (C2 across phi = 0);
* ``s`` is signed: the point (-s, theta + pi) is the same creepage as (s, theta), with the frame
  components negated. Fitting that double cover makes every straight line through v = 0 a
  C2 curve of the spline (the polar origin is not an end of the grid);
* ``s`` reaches 1 (|v| = infinity), where the force is mu N along -v and the moment and the
  stick area vanish (full sliding with the spin negligible against the creepage), so every
  finite creepage is inside the grid; the saturation near rho = 1 has crowded nodes.

Symmetries used to fill the grid from the computed quarter (v_x >= 0, tau >= 0, s >= 0):
S1, mirroring y: (v_x, v_y, tau) -> (v_x, -v_y, -tau), (f_par, f_perp, M) -> (f_par, -f_perp,
-M); S3, reversing x at fixed spin: (v_x, v_y, tau) -> (-v_x, v_y, tau), (f_par, f_perp, M) ->
(f_par, -f_perp, M); the double cover (s, theta) -> (-s, theta + pi), (f_par, f_perp) -> -(f_par,
f_perp). The stick fraction is unchanged by all three.
"""

from __future__ import annotations

import numpy as np

__all__ = ["exact_table_coordinates", "exact_table_inverse", "creepage_coordinate",
           "creepage_magnitude"]


def creepage_coordinate(rho):
    """Compactified creepage magnitude ``s = rho / sqrt(1 + rho^2)`` (1 at rho = inf). [-]"""
    rho = np.asarray(rho, dtype=float)
    with np.errstate(over="ignore", invalid="ignore"):
        big = np.abs(rho) > 1e150
        return np.where(big, np.sign(rho), rho / np.sqrt(1.0 + np.where(big, 0.0, rho) ** 2))


def creepage_magnitude(s):
    """Inverse of :func:`creepage_coordinate`: ``rho = s / sqrt(1 - s^2)`` (inf at |s| = 1)."""
    s = np.asarray(s, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(np.abs(s) >= 1.0, np.sign(s) * np.inf, s / np.sqrt(1.0 - s * s))


def exact_table_inverse(log_aspect_ratio, poisson_ratio, creepage_coordinate_, creepage_angle,
                        spin_coordinate, contact):
    """Physical inputs on a reference contact for table coordinates.

    Parameters
    ----------
    log_aspect_ratio, poisson_ratio, creepage_coordinate_, creepage_angle, spin_coordinate :
        array_like
        Table coordinates (see the module docstring); ``|s| < 1``.
    contact : dict
        ``area_radius`` sqrt(a0 b0) [m], ``normal_load`` [N], ``youngs_modulus`` [Pa],
        ``friction_coefficient`` [-] of the reference contact.

    Returns
    -------
    dict
        ``creepage_longitudinal``, ``creepage_lateral``, ``spin``, ``normal_load``, ``a0``,
        ``b0``, ``youngs_modulus``, ``poisson_ratio``, ``friction_coefficient`` (arrays).
    """
    from .kalker import kalker_coefficients  # noqa: PLC0415

    g = np.exp(np.asarray(log_aspect_ratio, dtype=float))
    nu = np.broadcast_to(np.asarray(poisson_ratio, dtype=float), g.shape)
    a0 = contact["area_radius"] * np.sqrt(g)
    b0 = contact["area_radius"] / np.sqrt(g)
    c = kalker_coefficients(g, nu)
    c11, c22, c23 = (np.asarray(getattr(c, k), dtype=float) for k in ("c11", "c22", "c23"))
    n_load, e_mod = contact["normal_load"], contact["youngs_modulus"]
    mu = contact["friction_coefficient"]
    p0 = 1.5 * n_load / (np.pi * a0 * b0)
    w_sat = np.pi**2 * (1.0 + nu) * mu * p0 / e_mod
    rho = creepage_magnitude(creepage_coordinate_)
    v_x = rho * np.cos(creepage_angle)
    v_y = rho * np.sin(creepage_angle)
    phi = np.asarray(spin_coordinate, dtype=float) * w_sat / np.hypot(b0 * c11, a0 * c22)
    sigma = np.sqrt(a0 * b0) * c23 * phi / w_sat
    return dict(creepage_longitudinal=v_x * w_sat / c11,
                creepage_lateral=(v_y - sigma) * w_sat / c22,
                spin=phi,
                normal_load=np.full(g.shape, n_load), a0=a0, b0=b0,
                youngs_modulus=np.full(g.shape, e_mod), poisson_ratio=nu,
                friction_coefficient=np.full(g.shape, mu))


def exact_table_coordinates(creepage_longitudinal, creepage_lateral, spin, a0, b0,
                            poisson_ratio, saturation_creepage, coefficients):
    """Table coordinates ``(ln(a0/b0), nu, s, theta, tau)`` of physical inputs.

    Parameters
    ----------
    creepage_longitudinal, creepage_lateral : array_like
        xi_x, xi_y. [-]
    spin : array_like
        phi. [1/m]
    a0, b0 : array_like
        Semi-axes. [m]
    poisson_ratio : array_like
        nu. [-]
    saturation_creepage : array_like
        ``w_sat = pi^2 (1 + nu) mu p0 / E``, > 0. [-]
    coefficients : tuple of array_like
        Kalker's (C11, C22, C23) at (a0/b0, nu). [-]

    Returns
    -------
    tuple of ndarray
    """
    xi_x, xi_y, phi, a0, b0, nu, w_sat = (np.asarray(v, dtype=float) for v in (
        creepage_longitudinal, creepage_lateral, spin, a0, b0, poisson_ratio,
        saturation_creepage))
    c11, c22, c23 = coefficients
    v_x = c11 * xi_x / w_sat
    v_y = (c22 * xi_y + np.sqrt(a0 * b0) * c23 * phi) / w_sat
    tau = phi * np.hypot(b0 * c11, a0 * c22) / w_sat
    rho = np.hypot(v_x, v_y)
    return (np.log(a0 / b0), nu, creepage_coordinate(rho), np.arctan2(v_y, v_x), tau)
