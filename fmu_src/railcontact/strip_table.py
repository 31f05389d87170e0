"""The modified strip theory's creep table (``tables/creep_modified_strip.nc``): the reader.

:class:`CreepTable` gives the forces of :func:`railcontact.creep_force_3d` with
``method="modified_strip"`` from the shipped C2 spline of ``F(z)`` (Nielsen Sec. 2.5.4, Eqs.
(2.87), (2.93)-(2.99)); the spline machinery and the file format are in
:mod:`railcontact.tables`, the exact theory's table in :mod:`railcontact.exact_table`.
"""

from __future__ import annotations

import math

import numpy as np

from ._floats import MODERATE_MAX, MODERATE_MIN, moderate as _moderate, scaled as _scaled
from ._floats import value as _value
from ._validation import check_range
from .creep_common import (axis_ratio, coulomb_limit, saturation_creepage_scaled,
                           weighted_creepage_scaled)
from .kalker import kalker_coefficients_cached
from .tables import Table, TableFileError, default_table_path

__all__ = ["CreepTable"]


# --------------------------------------------------------------------------------------------
# Creep tables
# --------------------------------------------------------------------------------------------

def _kalker(g, nu):
    """C11, C22, C23 (cached for scalars: an FMU calls with the same a0/b0 step after step)."""
    if np.ndim(g) == 0 and np.ndim(nu) == 0:
        return kalker_coefficients_cached(float(g), float(nu))
    from .kalker import kalker_coefficients  # noqa: PLC0415

    c = kalker_coefficients(g, nu)
    return c.c11, c.c22, c.c23


_CREEP_ARGS = ("creepage_longitudinal", "creepage_lateral", "spin", "normal_load", "a0", "b0",
               "youngs_modulus", "poisson_ratio", "friction_coefficient")


def _check_creep_inputs(xi_x, xi_y, phi, n_load, a0, b0, e_mod, nu, mu):
    return (check_range("creepage_longitudinal", xi_x, "-"),
            check_range("creepage_lateral", xi_y, "-"),
            check_range("spin", phi, "1/m"),
            check_range("normal_load", n_load, "N", 0.0, None),
            check_range("a0", a0, "m", 0.0, None),
            check_range("b0", b0, "m", 0.0, None),
            check_range("youngs_modulus", e_mod, "Pa", 0.0, None, lower_closed=False),
            check_range("poisson_ratio", nu, "-", 0.0, 0.5, upper_closed=False),
            check_range("friction_coefficient", mu, "-", 0.0, None))


_SCALAR_TYPES = (float, int, np.floating, np.integer)


def _fast_scalars_ok(xi_x, xi_y, phi, n_load, a0, b0, e_mod, nu, mu):
    """True if all inputs are real scalars within range (then no message is needed)."""
    for v in (xi_x, xi_y, phi, n_load, a0, b0, e_mod, nu, mu):
        if not isinstance(v, _SCALAR_TYPES) or isinstance(v, bool):
            return False
    return (math.isfinite(xi_x) and math.isfinite(xi_y) and math.isfinite(phi)
            and 0.0 <= n_load < math.inf and 0.0 <= a0 < math.inf and 0.0 <= b0 < math.inf
            and 0.0 < e_mod < math.inf and 0.0 <= nu < 0.5 and 0.0 <= mu < math.inf)


def _variable_indices(table, names):
    """Positions of ``names`` in the table's variables (attribute ``table_variables``)."""
    missing = [n for n in names if n not in table.variables]
    if missing:
        raise TableFileError(f"table file {str(table.path)!r}: attribute table_variables "
                             f"({' '.join(table.variables)!r}) lacks {missing}")
    return [table.variables.index(n) for n in names]


def _creep_force_type():
    global _CreepForce3D
    if _CreepForce3D is None:
        from .creep3d import CreepForce3D  # noqa: PLC0415

        _CreepForce3D = CreepForce3D
    return _CreepForce3D


_CreepForce3D = None


class CreepTable:
    """Creep forces from a shipped table, with the conventions of :func:`railcontact.creep_force_3d`.

    Load with :meth:`from_file` (``CreepTable.from_file()`` loads the shipped modified-strip
    table). Forces act on the wheel and oppose the creepage; ``|T| <= mu N`` always.

    Modified strip table (``creep_modified_strip``): the theory depends on the creepages only
    through the Kalker-weighted vector ``w = (C11 xi_x, C22 xi_y + sqrt(a0 b0) C23 phi)``,
    ``T = -mu N F(z) w/|w|`` with ``z = |w| / w_sat``, ``w_sat = pi^2 (1 + nu) mu p0 / E`` and
    ``p0 = 3 N / (2 pi a0 b0)`` (see :mod:`railcontact.creep3d`). The table holds ``F(z)`` and
    the stick area fraction on 0 <= z <= 1.5, C1 with a double knot at the saturation z = 1,
    C2 elsewhere. **Out of grid:** z > 1.5 is full sliding, where F = 1 exactly (held); every
    other input range is that of :func:`railcontact.creep_force_3d` (ValueError outside).
    C11, C22, C23 come from :func:`railcontact.kalker_coefficients` (cached per (a0/b0, nu)).
    """

    def __init__(self, table):
        self.table = table
        kind = str(table.attrs.get("creep_table_kind", "modified_strip" if
                                   table.name == "creep_modified_strip" else ""))
        if kind != "modified_strip":
            raise TableFileError(f"table file {str(table.path)!r} is not a creep table "
                                 f"(table_name {table.name!r})")
        self.kind = kind
        self._spline = table.spline
        self._z_max = float(table.axes[0]["nodes"][-1])
        self._i_f, self._i_s = _variable_indices(table, ("force_ratio", "stick_area_fraction"))
        # The same cubic spline of F(z) in piecewise-polynomial form, as plain Python floats, for
        # the scalar path (force_unchecked): one bisect and one Horner step cost far less than a
        # compiled call with array arguments (an FMU calls this once per step). Per knot span
        # [x0, x0 + h] (the zero-length double-knot span dropped) the coefficients of
        # c0 + c1 d + c2 d^2 + c3 d^3 come from the table's own evaluator: F, F', F''/2 at x0 and
        # c3 = (F''(x0 + h/2) - F''(x0)) / (3 h), exact for a cubic to round-off (what
        # scipy's PPoly.from_spline gives, tests/test_strip_table.py), without importing
        # scipy.interpolate: about 0.5 s of a fresh process, an FMU's start included
        # (docs/performance.md).
        from bisect import bisect_right  # noqa: PLC0415

        knots = np.asarray(table.axes[0]["knots"], dtype=float)
        keep = np.diff(knots) > 0.0
        x0, h = knots[:-1][keep], np.diff(knots)[keep]
        ev = self._spline.evaluate
        d0 = ev(x0[:, None], [0], check=False)
        d1 = ev(x0[:, None], [1], check=False)
        d2 = ev(np.concatenate([x0, x0 + 0.5 * h])[:, None], [2], check=False)
        n = len(x0)
        c3 = (d2[n:] - d2[:n]) / (3.0 * h[:, None])
        self._pp_breaks = [float(v) for v in x0]
        for i, name in ((self._i_f, "_pp_coefs"), (self._i_s, "_pp_coefs_stick")):
            setattr(self, name, [(float(c3[j, i]), float(0.5 * d2[j, i]), float(d1[j, i]),
                                  float(d0[j, i])) for j in range(n)])
        self._bisect = bisect_right
        # F'(0) (3 pi / 4 in theory) and F''(0) of the table: its first piece at z = 0
        if self._pp_breaks[0] != 0.0:
            raise TableFileError(f"table file {str(table.path)!r}: the creep table's first node "
                                 f"must be z = 0; got {self._pp_breaks[0]!r}")
        _, curv_half, self._slope0, _ = self._pp_coefs[0]
        self._curv0 = 2.0 * curv_half

    @classmethod
    def from_file(cls, path=None, directory=None):
        """Load a creep table; ``path=None`` finds ``creep_modified_strip.nc`` with
        :func:`default_table_path` (``directory`` searched first)."""
        if path is None:
            path = default_table_path("creep_modified_strip", directory)
        return cls(Table.from_file(path))

    # -- the 1-D function and its derivatives ---------------------------------------------
    def _f(self, z, derivative=0):
        """F(z) (or derivative) and stick fraction for z >= 0 (arrays), held beyond z_max."""
        zc = np.minimum(z, self._z_max)
        out = self._spline.evaluate(zc.reshape(-1, 1), [derivative], check=False)
        if derivative:
            out = np.where((z > self._z_max)[..., None] if z.ndim else z > self._z_max,
                           0.0, out.reshape(z.shape + (-1,)))
        return out.reshape(z.shape + (-1,))

    def _solve(self, args, jacobian=False):
        xi_x, xi_y, phi, n_load, a0, b0, e_mod, nu, mu = _check_creep_inputs(*args)
        shape = np.broadcast(xi_x, xi_y, phi, n_load, a0, b0, e_mod, nu, mu).shape
        xi_x, xi_y, phi, n_load, a0, b0, e_mod, nu, mu = (np.broadcast_to(v, shape) for v in (
            xi_x, xi_y, phi, n_load, a0, b0, e_mod, nu, mu))
        mu_n = coulomb_limit(mu, n_load)
        c11, c22, c23 = _kalker(axis_ratio(a0, b0), nu)
        # w, w_sat and mu N / w_sat in (mantissa, exponent) form (railcontact._floats.scaled):
        # no intermediate overflows or underflows for any finite input
        d_x, d_y, w_m, w_e, u_x, u_y, top = weighted_creepage_scaled(xi_x, xi_y, phi, a0, b0, c11,
                                                                 c22, c23, parts=True)
        s_m, s_e = saturation_creepage_scaled(n_load, a0, b0, e_mod, nu, mu)
        has_force = (mu_n > 0.0) & (s_m > 0.0)
        s_safe = np.where(has_force, s_m, 1.0)
        z = np.where(has_force, _value(w_m / s_safe, w_e - s_e), 0.0)
        vals = self._f(z)
        f = np.minimum(vals[..., self._i_f], 1.0)   # rounding guard: the spline is <= 1 + 1e-15
        stick = np.clip(vals[..., self._i_s], 0.0, 1.0)
        small = z < 1e-6
        f_over_z = np.where(small, self._slope0 + 0.5 * self._curv0 * z,
                            f / np.where(small, 1.0, z))
        k_m, k_e = _scaled((np.where(has_force, mu_n, 0.0),), ((s_safe, s_e),))  # mu N/w_sat
        held = z > self._z_max                       # full sliding: -mu N w/|w| (F = 1)
        tx = np.where(held, -mu_n * d_x, -_value(k_m * f_over_z * u_x, k_e + top))
        ty = np.where(held, -mu_n * d_y, -_value(k_m * f_over_z * u_y, k_e + top))
        tx, ty = np.where(has_force, tx, -0.0), np.where(has_force, ty, -0.0)
        # rounding guard (|T| = mu N f with f <= 1, but w/|w| is rounded): never above mu N
        t_abs = np.hypot(tx, ty)
        over = t_abs > mu_n
        scale = np.divide(mu_n * (1.0 - 2.0**-51), t_abs, out=np.ones(shape), where=over)
        tx, ty = tx * scale, ty * scale
        if not jacobian:
            return tx, ty, stick, z
        fp = self._f(z, 1)[..., self._i_f]
        n_x, n_y = d_x, d_y
        n_x = np.where(w_m > 0.0, n_x, 1.0)
        # dT/dw = -(mu_n / w_sat) [F'(z) n n^T + (F/z)(I - n n^T)]
        k = _value(k_m, k_e)
        with np.errstate(over="ignore", invalid="ignore"):
            a_ = -k * fp
            b_ = -k * f_over_z
            dxx = a_ * n_x * n_x + b_ * (1.0 - n_x * n_x)
            dxy = (a_ - b_) * n_x * n_y
            dyy = a_ * n_y * n_y + b_ * (1.0 - n_y * n_y)
            root = np.sqrt(a0) * np.sqrt(b0)
            jac = np.empty(shape + (2, 3))
            jac[..., 0, 0] = dxx * c11
            jac[..., 0, 1] = dxy * c22
            jac[..., 0, 2] = dxy * (root * c23)
            jac[..., 1, 0] = dxy * c11
            jac[..., 1, 1] = dyy * c22
            jac[..., 1, 2] = dyy * (root * c23)
        if not np.all(np.isfinite(jac)):
            i = np.flatnonzero(~np.all(np.isfinite(jac), axis=(-2, -1)))[0]
            raise ValueError(
                f"the creep force's derivative G a0 b0 C (and sqrt(a0 b0) C23) must be in "
                f"[0, {np.finfo(float).max:g}] [N]; got inf (overflow at a0 = "
                f"{a0.flat[i]:g}, b0 = {b0.flat[i]:g}, youngs_modulus = {e_mod.flat[i]:g})")
        return tx, ty, stick, z, jac

    def creep_force_3d(self, creepage_longitudinal, creepage_lateral, spin, normal_load, a0, b0,
                       youngs_modulus, poisson_ratio, friction_coefficient):
        """Creep force on the wheel from the table; same inputs and conventions as
        :func:`railcontact.creep_force_3d` (``method="modified_strip"``).

        Returns
        -------
        CreepForce3D
            ``tx``, ``ty`` [N]; ``|T| <= mu N``.
        """
        args = (creepage_longitudinal, creepage_lateral, spin, normal_load, a0, b0,
                youngs_modulus, poisson_ratio, friction_coefficient)
        result = _CreepForce3D or _creep_force_type()
        if _fast_scalars_ok(*args):
            return result(*self.force_unchecked(*args))
        tx, ty = self._solve(args)[:2]
        return result(tx[()], ty[()])

    def force_unchecked(self, xi_x, xi_y, phi, n_load, a0, b0, e_mod, nu, mu,
                        _kalker=kalker_coefficients_cached, _sqrt=math.sqrt, _hypot=math.hypot,
                        _pi=math.pi, _pi2=math.pi**2, _lo=MODERATE_MIN, _hi=MODERATE_MAX):
        """:meth:`creep_force_3d` for plain floats whose range the caller has checked, as
        ``(tx, ty)`` [N]: the table's one scalar implementation (the FMU's creep effect calls
        it once per step; :meth:`creep_force_3d` calls it for scalar inputs after its check).

        Assumes every input a finite float in the ranges of :meth:`creep_force_3d` (the FMU
        slave checks them; a0, b0 come from Hertz) and checks nothing. Written for the
        interpreter: the math functions and constants are bound as default arguments, no
        builtin min/max calls, and Kalker's coefficients come from the cache
        :func:`railcontact.kalker.kalker_coefficients_cached` (an FMU asks for the same ellipse
        shape step after step). Inputs of extreme magnitude go to the overflow-safe array
        path, which also names a bad input. Agrees with the array path to a few ulp
        (tests/test_tables.py).
        """
        if a0 <= 0.0 or b0 <= 0.0 or n_load <= 0.0 or mu <= 0.0:
            return 0.0, 0.0
        # railcontact._floats.moderate, inlined (one call per FMU step; N, a0, b0, mu > 0 here)
        if not (_lo <= n_load <= _hi and _lo <= a0 <= _hi and _lo <= b0 <= _hi
                and _lo <= e_mod <= _hi and _lo <= mu <= _hi
                and (xi_x == 0.0 or _lo <= abs(xi_x) <= _hi)
                and (xi_y == 0.0 or _lo <= abs(xi_y) <= _hi)
                and (phi == 0.0 or _lo <= abs(phi) <= _hi)):
            # extreme magnitudes: the overflow-safe array path (it also names a bad input)
            tx, ty = self._solve((xi_x, xi_y, phi, n_load, a0, b0, e_mod, nu, mu))[:2]
            return float(tx), float(ty)
        c11, c22, c23 = _kalker(a0 / b0, nu)
        w_x = c11 * xi_x
        w_y = c22 * xi_y + _sqrt(a0 * b0) * c23 * phi
        p0 = 1.5 * n_load / (_pi * a0 * b0)
        w_sat = _pi2 * (1.0 + nu) * mu * p0 / e_mod
        if w_sat <= 0.0:    # mu so small (~1e-320) that w_sat underflows: |T| <= mu N ~ 0
            return -0.0, -0.0
        mu_n = mu * n_load
        z = _hypot(w_x, w_y) / w_sat
        if z < 1e-6:
            f_over_z = self._slope0 + 0.5 * self._curv0 * z
        else:
            zz = z if z < self._z_max else self._z_max          # min(z, z_max)
            breaks = self._pp_breaks
            i = self._bisect(breaks, zz) - 1
            if i < 0:
                i = 0
            c3, c2, c1, c0 = self._pp_coefs[i]
            dz = zz - breaks[i]
            f = ((c3 * dz + c2) * dz + c1) * dz + c0
            if f > 1.0:                                         # min(f, 1)
                f = 1.0
            f_over_z = f / z
        k = mu_n / w_sat * f_over_z
        tx, ty = -k * w_x, -k * w_y
        t_abs = _hypot(tx, ty)
        if t_abs > mu_n:  # rounding guard, see _solve
            r = mu_n * (1.0 - 2.0**-51) / t_abs
            tx, ty = tx * r, ty * r
        return tx, ty

    def stick_unchecked(self, xi_x, xi_y, phi, n_load, a0, b0, e_mod, nu, mu,
                        _kalker=kalker_coefficients_cached, _sqrt=math.sqrt, _hypot=math.hypot,
                        _pi=math.pi, _pi2=math.pi**2):
        """Scalar path of the stick outputs: ``(stick_area_fraction, normalised_creepage)``,
        the last two items of :meth:`creep_solution_3d`, for plain floats.

        Assumes what :meth:`force_unchecked` assumes (inputs finite and in the ranges of
        :meth:`creep_force_3d`, as the FMU slave has checked; no check is made here). z is
        computed with the same operations as the array path; the stick fraction comes from
        the piecewise-polynomial copy of the table's spline (as the force in
        :meth:`force_unchecked`), which agrees with the B-spline evaluation to a few ulp
        (tests/test_tables.py).
        """
        if a0 <= 0.0 or b0 <= 0.0 or n_load <= 0.0 or mu <= 0.0:
            z = 0.0
        elif not _moderate(xi_x, xi_y, phi, n_load, a0, b0, e_mod, mu):
            _, _, stick, z = self._solve((xi_x, xi_y, phi, n_load, a0, b0, e_mod, nu, mu))
            return float(stick), float(z)
        else:
            c11, c22, c23 = _kalker(a0 / b0, nu)
            w_x = c11 * xi_x
            w_y = c22 * xi_y + _sqrt(a0 * b0) * c23 * phi
            w_sat = _pi2 * (1.0 + nu) * mu * (1.5 * n_load / (_pi * a0 * b0)) / e_mod
            z = _hypot(w_x, w_y) / w_sat if w_sat > 0.0 else 0.0
        zz = z if z < self._z_max else self._z_max               # held beyond the grid
        breaks = self._pp_breaks
        i = self._bisect(breaks, zz) - 1
        if i < 0:
            i = 0
        c3, c2, c1, c0 = self._pp_coefs_stick[i]
        dz = zz - breaks[i]
        stick = ((c3 * dz + c2) * dz + c1) * dz + c0
        return (0.0 if stick < 0.0 else 1.0 if stick > 1.0 else stick), z

    def creep_solution_3d(self, creepage_longitudinal, creepage_lateral, spin, normal_load,
                          a0, b0, youngs_modulus, poisson_ratio, friction_coefficient):
        """Force, stick area fraction and normalised creepage z from the table.

        Returns
        -------
        tuple of ndarray
            ``(tx, ty, stick_area_fraction, normalised_creepage)`` [N, N, -, -].
        """
        out = self._solve((creepage_longitudinal, creepage_lateral, spin, normal_load, a0, b0,
                           youngs_modulus, poisson_ratio, friction_coefficient))
        return tuple(v[()] for v in out)

    def creep_force_jacobian_3d(self, creepage_longitudinal, creepage_lateral, spin,
                                normal_load, a0, b0, youngs_modulus, poisson_ratio,
                                friction_coefficient):
        """Derivatives of (tx, ty) with respect to (xi_x, xi_y, phi), for implicit integrators.

        Returns
        -------
        ndarray, shape (..., 2, 3)
            ``J[..., i, j] = d T_i / d q_j`` with T = (tx, ty) [N] and q = (xi_x [-], xi_y [-],
            phi [1/m]); continuous everywhere (the table is C1 at saturation, C2 elsewhere).
        """
        return self._solve((creepage_longitudinal, creepage_lateral, spin, normal_load, a0, b0,
                            youngs_modulus, poisson_ratio, friction_coefficient),
                           jacobian=True)[4]

