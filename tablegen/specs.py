"""The built-in table specifications (registered on import).

Each spec's point function maps table coordinates to the tabulated variables by calling the
direct model in :mod:`railcontact`; the coordinate conversions live in
:mod:`railcontact.tables` next to the readers that invert them.
"""

from __future__ import annotations

import numpy as np

from .spec import Axis, TableSpec, Variable, register

THESIS = ("J.B. Nielsen, New Developments in the Theory of Wheel/Rail Contact Mechanics, "
          "IMM-PHD-1998-51, DTU, 1998")

_COUNTS = {"coarse": 16, "default": 32, "fine": 64}


# --------------------------------------------------------------------------------------------
# Self-test (hidden): a synthetic saturating function with a C1 kink, NOT physics
# --------------------------------------------------------------------------------------------

def _selftest_axes(resolution):
    n = {"coarse": 8, "default": 12, "fine": 24}[resolution]
    z = np.r_[np.linspace(0.0, 1.0, n + 1), 1.25, 1.5, 2.0]
    return [Axis("x", z, "1", "synthetic coordinate, kink at 1", double_knots=(1.0,),
                 out_of_range="hold"),
            Axis("s", np.linspace(0.5, 2.0, 5), "1", "synthetic parameter")]


def selftest_function(points):
    """Synthetic test function f = 1 - (1 - min(x,1))^2 (1 + s x / 2) (C1 kink at x = 1),
    g = s sin(x). Used only by the tests of the build machinery."""
    x, s = points[:, 0], points[:, 1]
    xc = np.minimum(x, 1.0)
    return np.stack([1.0 - (1.0 - xc) ** 2 * (1.0 + 0.5 * s * xc), s * np.sin(x)], axis=1)


register(TableSpec(
    name="selftest",
    title="synthetic self-test table of tablegen (not physics)",
    axes=_selftest_axes,
    function=selftest_function,
    variables=[Variable("f", "1", "synthetic saturating function", error_target=1e-2),
               Variable("g", "1", "synthetic smooth function", error_target=1e-2)],
    references="none (synthetic)",
    method="tablegen.specs.selftest_function",
    n_check={"coarse": 50, "default": 100, "fine": 200},
    chunk_size=8,
    hidden=True,
))


# --------------------------------------------------------------------------------------------
# Creep forces, modified strip theory (Nielsen Sec. 2.6)
# --------------------------------------------------------------------------------------------

def _modified_strip_axes(resolution):
    n = _COUNTS[resolution]
    u = np.linspace(0.0, 1.0, n + 1)
    z = np.r_[1.0 - (0.5 * (1.0 + np.cos(np.pi * u))) ** 2, 1.05, 1.15, 1.3, 1.5]
    return [Axis(
        "normalised_creepage", z, "1",
        "modified creepage magnitude |w|/w_sat, w = (C11 xi_x, C22 xi_y + sqrt(a0 b0) C23 phi), "
        "w_sat = pi^2 (1 + nu) mu p0 / E (1 = onset of full sliding)",
        double_knots=(1.0,), out_of_range="hold",
        comment="nodes z = 1 - ((1 + cos(pi u))/2)^2 (u uniform) crowd towards z = 0 (initial "
                "slope = linear theory to ~1e-7 relative) and towards the saturation z = 1, "
                "where the third derivative of the force (second of the stick area) has a "
                "square-root singularity; z >= 1 is full "
                "sliding (force ratio 1, no stick zone), so values are held beyond the last "
                "node (exact)")]


def modified_strip_function(points):
    """|T|/(mu N) and the stick area fraction of the modified strip theory at z = points[:, 0].

    Evaluated with :func:`railcontact.creep_solution_3d` on a reference contact (longitudinal
    creepage only), which is exact for every direction and spin because the theory depends on
    the creepages only through z (see :mod:`railcontact.creep3d`).
    """
    from railcontact.creep3d import creep_solution_3d, saturation_creepage_3d  # noqa: PLC0415

    z = points[:, 0]
    args = (1.0e5, 6.0e-3, 5.0e-3, 210e9, 0.28, 0.3)  # N, a0, b0, E, nu, mu (any contact)
    xi_sat = saturation_creepage_3d(*args)
    sol = creep_solution_3d(-z * xi_sat, 0.0, 0.0, *args, method="modified_strip")
    mu_n = args[0] * args[-1]
    return np.stack([np.hypot(sol.tx, sol.ty) / mu_n, sol.stick_area_fraction], axis=1)


def _modified_strip_check(axes, n, rng):
    return np.sort(rng.uniform(0.0, 1.6, n))[:, None]


register(TableSpec(
    name="creep_modified_strip",
    title="Creep force and stick area of the modified strip theory (Nielsen 1998, Sec. 2.6)",
    axes=_modified_strip_axes,
    function=modified_strip_function,
    variables=[
        Variable("force_ratio", "1",
                 "magnitude of the tangential force over the Coulomb limit, |T|/(mu N)",
                 comment="T = -mu N force_ratio(z) w/|w| (on the wheel, opposing the "
                         "Kalker-weighted creepage w); <= 1"),
        Variable("stick_area_fraction", "1",
                 "stick area over the contact area pi a0 b0 (strip-theory estimate)"),
    ],
    references=(f"{THESIS}, Sec. 2.6, Eqs. (2.85)-(2.99) (modified strip theory with the "
                "small-spin substitution (2.99)); J.J. Kalker, Three-dimensional elastic bodies "
                "in rolling contact, Kluwer, 1990 (creep coefficients)"),
    method="railcontact.creep3d.creep_solution_3d(method='modified_strip')",
    check_points=_modified_strip_check,
    n_check={"coarse": 2000, "default": 5000, "fine": 20000},
    chunk_size=512,
    requires=("railcontact.creep3d",),
    attributes={"normalisation": (
        "the modified strip theory depends on the creepages only through z = |w|/w_sat and "
        "the direction of w, so one 1-D table serves every load, material, a0/b0, creepage "
        "direction and (small) spin; the reader converts with railcontact.kalker_coefficients")},
))
