"""The FMU's remaining float twins of public vectorised functions: one place, one suffix.

Internal module. Each function here repeats, on plain Python floats with the :mod:`math` and
:mod:`cmath` modules, the arithmetic of a public vectorised function, for the FMU's per-step
call: numpy's per-call overhead (array creation, ufunc dispatch, range checks) is tens of
microseconds on scalars against well under one of arithmetic, and these public functions
carry vectorised overflow-safe paths and broadcasting that the floats do not need. They are
kept as twins (rather than one compiled kernel, as the roughness and corrugation models) because
their modules are imported with ``import railcontact`` and stay free of numba, and the
formulas are a few lines each.

Every function is named ``<public function>_scalar`` and is compared with its public function
by one table-driven test, ``tests/test_scalar.py`` (its table lists every pair, the inputs over
all regimes and the bound). A change to a formula here or in its public function fails that
test until both agree.
"""

from __future__ import annotations

import cmath
import math

from . import creep3d
from ._floats import MODERATE_MAX, MODERATE_MIN, moderate as _moderate
from .creep_common import CreepSolution3D
from .kalker import kalker_coefficients_cached

__all__ = ["carter_scalar", "normalised_inputs_scalar",
           "step_law_creep_force_normalised_scalar", "evolve_harmonics_scalar",
           "creep_force_3d_scalar", "creep_stick_3d_scalar", "creep_solution_3d_scalar",
           "spin_coefficient_scalar"]


# ---------------------------------------------------------------------------------------------
# railcontact.carter
# ---------------------------------------------------------------------------------------------
# numpy's per-call overhead (array creation, ufunc dispatch, the input checks) is ~60 us per
# call of carter_creep_force on scalars, for well under 1 us of arithmetic. The function below
# repeats the array paths' arithmetic (hertz_2d's a0, carter_critical_creepage,
# _sliding_fraction, carter_creep_force's f (2 - f) form, carter_stick_ratio's 1 - f) operation
# for operation on floats with the math module, for callers that have already range-checked
# their inputs (the FMU slave: railcontact.effects.inputs_plausible, the scene's checks). It
# ASSUMES, and does not check: every input a finite float (or int, not bool), normal_load >= 0,
# radius > 0, youngs_modulus > 0, 0 <= poisson_ratio < 0.5, friction_coefficient >= 0. Outside
# that the result is undefined (possibly NaN or an exception); use the public functions there.
# Agreement with carter_creep_force and carter_stick_ratio to a few ulp (the operations are the
# same, in the same order; libm's sqrt and numpy's are both correctly rounded) is tested in
# tests/test_scalar.py.


def carter_scalar(creepage, normal_load, radius, youngs_modulus, poisson_ratio,
                   friction_coefficient, _sqrt=math.sqrt, _pi=math.pi, _inf=math.inf):
    """(:func:`railcontact.carter.carter_creep_force`, :func:`railcontact.carter.carter_stick_ratio`) for plain floats (inputs
    assumed in range, see above). [N/m], [-]"""
    xi, n_load, r, mu = creepage, normal_load, radius, friction_coefficient
    nu = poisson_ratio
    a0 = _sqrt(8.0 * (1.0 - nu * nu) * r * n_load / (_pi * youngs_modulus))
    xi_c = mu * a0 / r
    if xi_c > 0.0:
        frac = abs(xi) / xi_c
    else:                                  # no stick zone unless xi = 0 (see _sliding_fraction)
        frac = 0.0 if xi == 0.0 else _inf
    if not frac < 1.0:
        frac = 1.0
    sign = 1.0 if xi > 0.0 else (-1.0 if xi < 0.0 else 0.0)
    # f (2 - f) with f = 1 - r computed directly (no cancellation at tiny creepage)
    return -sign * mu * n_load * (frac * (2.0 - frac)), 1.0 - frac


# ---------------------------------------------------------------------------------------------
# railcontact.friction
# ---------------------------------------------------------------------------------------------
# numpy's per-call overhead (array creation, ufunc dispatch, the input checks) is tens of us per
# call of normalised_inputs or step_law_creep_force_normalised on scalars, for well under 1 us
# of arithmetic. The functions below repeat the array paths' arithmetic operation for operation
# on floats with the math module, for callers that have already range-checked their inputs (the
# FMU slave: railcontact.effects.inputs_plausible, the scene's checks). They ASSUME, and do not
# check: every input a finite float (or int, not bool), normal_load > 0, radius > 0,
# youngs_modulus > 0, 0 <= poisson_ratio < 0.5, mu_static > 0, mu_kinetic >= 0, kappa >= 0
# (normalised_inputs), friction_ratio >= 0 (the step law). Outside that the result is undefined
# (possibly NaN or an exception); use the public functions there. Agreement with the array paths
# to a few ulp (same operations, same order; libm's sqrt and numpy's are both correctly
# rounded) is tested in tests/test_scalar.py.


def normalised_inputs_scalar(creepage, normal_load, radius, youngs_modulus, poisson_ratio,
                              mu_static, mu_kinetic, kappa, _sqrt=math.sqrt, _pi=math.pi):
    """:func:`railcontact.friction.normalised_inputs` with ``mu_kinetic`` and ``kappa`` given, for plain floats
    (inputs assumed in range, see above).

    Returns
    -------
    tuple of float
        ``(creepage_ratio, critical_creepage, force_scale, friction_ratio, kappa_normalised)``.
    """
    nu = poisson_ratio
    # hertz_2d's a0 (nu**2 of a numpy scalar is nu * nu)
    a0 = _sqrt(8.0 * (1.0 - nu * nu) * radius * normal_load / (_pi * youngs_modulus))
    xi_c = mu_static * a0 / radius
    return (creepage / xi_c, xi_c, mu_static * normal_load, mu_kinetic / mu_static,
            kappa * xi_c)


def step_law_creep_force_normalised_scalar(creepage_ratio, friction_ratio, _inf=math.inf):
    """:func:`railcontact.friction.step_law_creep_force_normalised` for plain floats (inputs assumed in range, see
    above). [-]"""
    chi, m = creepage_ratio, friction_ratio
    c = abs(chi)
    # _carter_force_ratio(|chi|, m)
    if c == 0.0:
        frac = 0.0
    else:
        frac = c / m if m > 0.0 else _inf
        if not frac < 1.0:
            frac = 1.0
    sign = 1.0 if chi > 0.0 else (-1.0 if chi < 0.0 else 0.0)
    return -sign * (m * (frac * (2.0 - frac)))


# ---------------------------------------------------------------------------------------------
# railcontact.evolution
# ---------------------------------------------------------------------------------------------
# evolve_harmonics for one passage count on lists of floats (the FMU's wear effect, at every
# section crossing), with cmath in place of numpy: a twin of the vectorised function, kept for
# speed (numpy's per-call overhead) and tested against it in tests/test_scalar.py.


def evolve_harmonics_scalar(amplitudes_cos, amplitudes_sin, w1, w2, n_passages,
                             _log=cmath.log, _exp=cmath.exp, _isfinite=math.isfinite):
    """:func:`railcontact.evolution.evolve_harmonics` for one passage count and lists of floats, as lists of floats.

    The same operations in the same order per harmonic, with :mod:`cmath`'s log and exp in
    place of numpy's (they may round differently by an ulp; agreement to a few eps relative
    to |Z^n|, times ``1 + |n log(1 - W)|``, is tested in tests/test_scalar.py). Unlike the
    other scalar paths this one checks its inputs, since W1, W2 and the evolved amplitudes are
    computed, not range-checked by the caller: ``n_passages`` is assumed an int >= 0; if an
    amplitude is not finite, W1 or W2 is outside [-1, 1], or cmath fails (log of 0, overflow),
    the result is that of :func:`railcontact.evolution.evolve_harmonics` (its ValueError naming the input, or its
    numpy result).

    Returns
    -------
    amplitudes_cos, amplitudes_sin : list of float
        Z_A^n, Z_B^n per harmonic. [m]
    """
    n = float(n_passages)
    out_a, out_b = [], []
    try:
        for za, zb, wr, wi in zip(amplitudes_cos, amplitudes_sin, w1, w2):
            if not (_isfinite(za + zb) and -1.0 <= wr <= 1.0 and -1.0 <= wi <= 1.0):
                raise ValueError
            zn = _exp(n * _log(1.0 - wr - 1j * wi + 0j)) * (za + 1j * zb)
            out_a.append(zn.real)
            out_b.append(zn.imag)
    except (ValueError, OverflowError):
        from .evolution import evolve_harmonics

        za_n, zb_n = evolve_harmonics(amplitudes_cos, amplitudes_sin, w1, w2, [n_passages])
        return [float(v) for v in za_n[0]], [float(v) for v in zb_n[0]]
    return out_a, out_b


# ---------------------------------------------------------------------------------------------
# railcontact.creep3d
# ---------------------------------------------------------------------------------------------
# numpy's per-call overhead (array creation, ufunc dispatch, broadcasting, the input checks)
# is ~100 us per call of creep_solution_3d on scalars, for ~1 us of arithmetic. The helpers
# below repeat the array paths' arithmetic operation for operation on floats with the math
# module, for callers that have already range-checked their inputs (the FMU slave: see
# railcontact.effects.inputs_plausible, the scene's checks and Hertz's a0, b0). They ASSUME,
# and do not check: every input a finite float (or int, not bool), normal_load >= 0, a0 >= 0,
# b0 >= 0, youngs_modulus > 0, 0 <= poisson_ratio < 0.5, friction_coefficient >= 0, method in
# METHODS, and a0/b0 in the range kalker_coefficients accepts (> 0, any value; for a0 b0 = 0
# the array path's placeholder 1 is used). Outside that the result is undefined (possibly NaN
# or an exception); use the public functions there. Inputs of extreme magnitude (outside
# MODERATE_MIN..MODERATE_MAX, see _moderate) are passed on to the overflow-safe array path.
# Agreement with the array paths to a few ulp (libm's hypot, acos and pow may round
# differently from numpy's) is tested in tests/test_scalar.py.


# Magnitudes the scalar paths accept (railcontact._floats.MODERATE_MIN .. MODERATE_MAX): every
# non-zero input in [1e-50, 1e50] keeps all their intermediate products (at most five factors)
# in the normal float range, where they equal the array paths' (mantissa, exponent) arithmetic
# to a few ulp. Outside it they call the array path (overflow-safe; it also raises the
# ValueError of an input out of range).
def _f_over_z_scalar(z, _sqrt=math.sqrt, _acos=math.acos):
    """``railcontact.creep3d`` strip theory's F(z)/z for one float 0 <= z <= 1."""
    q = 1.0 - z * z
    r = _sqrt(q if q > 0.0 else 0.0)
    return z**3 * (2.0 + r) / (2.0 * (1.0 + r) ** 2) + 1.5 * _acos(z)


def spin_coefficient_scalar(xi_x, xi_y, phi, a0, b0):
    """:func:`railcontact.creep3d.spin_coefficient` for plain floats (inputs assumed in range,
    see above)."""
    if not _moderate(xi_x, xi_y, phi, a0, b0):
        return float(creep3d.spin_coefficient(xi_x, xi_y, phi, a0, b0))
    return _spin_coefficient_moderate(xi_x, xi_y, phi, a0, b0)


def _spin_coefficient_moderate(xi_x, xi_y, phi, a0, b0, _hypot=math.hypot, _inf=math.inf):
    """:func:`spin_coefficient_scalar` for inputs already known to be moderate."""
    num = _hypot(a0, b0) * abs(phi)
    den = _hypot(xi_x, xi_y)
    if den > 0.0:
        return num / den
    return _inf if num > 0.0 else 0.0


_EPS4 = 4.0 * 2.220446049250313e-16
_STRIP_C22 = math.pi**2 / 4.0


def _creep_forces(xi_x, xi_y, phi, n_load, a0, b0, e_mod, nu, mu, method,
                  _kalker=kalker_coefficients_cached, _sqrt=math.sqrt, _hypot=math.hypot,
                  _pi=math.pi, _inf=math.inf):
    """The forces of :func:`creep_solution_3d_scalar` (moderate inputs): ``(tx, ty, z, mu N)``,
    z the normalised creepage."""
    mu_n = mu * n_load
    has_area = a0 > 0.0 and b0 > 0.0
    c11, c22, c23 = _kalker(a0 / b0 if has_area else 1.0, nu)
    if method == "strip":
        c11 = _pi**2 / (4.0 * (1.0 - nu)) + 0.0 * c11
        c22 = _STRIP_C22 + 0.0 * c22
    w_x = c11 * xi_x
    w_y = c22 * xi_y + _sqrt(a0 * b0) * c23 * phi
    w_abs = _hypot(w_x, w_y)
    area = _pi * a0 * b0
    p0 = 1.5 * n_load / area if area > 0.0 else 0.0
    w_sat = _pi**2 * (1.0 + nu) * mu * p0 / e_mod
    has_force = mu_n > 0.0 and w_sat > 0.0
    if w_sat > 0.0:
        z = w_abs / w_sat                                   # (inf on overflow, as meant)
    else:
        z = _inf if w_abs > 0.0 else 0.0
    stiffness = e_mod / (2.0 * (1.0 + nu)) * a0 * b0        # G a0 b0 [N]
    if method == "linear":
        factor = stiffness
    elif method == "she":
        t_lin = stiffness * w_abs
        if mu_n > 0.0:
            u = t_lin / mu_n
        else:
            u = _inf if t_lin > 0.0 else 0.0
        if u <= 3.0:
            factor = stiffness * (1.0 - u / 3.0 + u * u / 27.0)
        else:
            factor = mu_n / w_abs if w_abs > 0.0 else 0.0
        if not (has_force or w_abs == 0.0):
            factor = 0.0
    elif has_force:
        if z <= 1.0:
            factor = (mu_n / w_sat) * _f_over_z_scalar(z)
        else:
            factor = mu_n / w_abs if w_abs > 0.0 else 0.0
    else:
        factor = 0.0
    tx = -factor * w_x
    ty = -factor * w_y
    if method != "linear":                  # never above mu N (see _solve)
        t_abs = _hypot(tx, ty)
        margin = 1.0 - _EPS4 if (tx != 0.0 and ty != 0.0) else 1.0
        if t_abs > mu_n * margin:
            scale = mu_n * (1.0 - _EPS4) / t_abs
            tx, ty = tx * scale, ty * scale
    tx, ty = tx + 0.0, ty + 0.0
    return tx, ty, z, mu_n


def _moderate_creep_inputs(xi_x, xi_y, phi, n_load, a0, b0, e_mod, mu, _lo=MODERATE_MIN,
                           _hi=MODERATE_MAX):
    """Whether the inputs of :func:`creep_force_3d_scalar` are all zero or moderate (above)."""
    return ((xi_x == 0.0 or _lo <= abs(xi_x) <= _hi) and (xi_y == 0.0 or _lo <= abs(xi_y) <= _hi)
            and (phi == 0.0 or _lo <= abs(phi) <= _hi) and (n_load == 0.0 or _lo <= n_load <= _hi)
            and _lo <= a0 <= _hi and _lo <= b0 <= _hi and _lo <= e_mod <= _hi
            and (mu == 0.0 or _lo <= mu <= _hi))


def creep_force_3d_scalar(xi_x, xi_y, phi, n_load, a0, b0, e_mod, nu, mu, method):
    """:func:`railcontact.creep3d.creep_force_3d` for plain floats (inputs assumed in range, see
    above; methods "linear", "she", "strip", "modified_strip"), with the normalised creepage:
    ``(tx, ty, z)`` (z as ``creep_solution_3d`` gives it).

    The FMU's creep step; :func:`creep_stick_3d_scalar` gives the stick measures from z when
    an importer reads them."""
    if not _moderate_creep_inputs(xi_x, xi_y, phi, n_load, a0, b0, e_mod, mu):
        res = creep3d.creep_solution_3d(xi_x, xi_y, phi, n_load, a0, b0, e_mod, nu, mu, method)
        return float(res.tx), float(res.ty), float(res.normalised_creepage)
    return _creep_forces(xi_x, xi_y, phi, n_load, a0, b0, e_mod, nu, mu, method)[:3]


def creep_stick_3d_scalar(tx, ty, z, xi_x, xi_y, phi, mu_n, a0, b0, method, _sqrt=math.sqrt,
                          _hypot=math.hypot, _acos=math.acos, _pi=math.pi):
    """The rest of :func:`railcontact.creep3d.creep_solution_3d` from the forces ``tx, ty`` [N]
    and the normalised creepage ``z`` of :func:`creep_force_3d_scalar`: ``(stick area
    fraction, stick width ratio, spin coefficient, within validity)``; ``mu_n`` = mu N [N]."""
    phi_coef = spin_coefficient_scalar(xi_x, xi_y, phi, a0, b0)
    if method == "linear":
        return 1.0, 1.0, phi_coef, phi_coef <= 1.0 and _hypot(tx, ty) <= mu_n
    zc = z if z < 1.0 else 1.0
    root = _sqrt(1.0 - zc * zc)
    return (2.0 / _pi) * (_acos(zc) - zc * root), root, phi_coef, phi_coef <= 1.0


def creep_solution_3d_scalar(xi_x, xi_y, phi, n_load, a0, b0, e_mod, nu, mu, method):
    """:func:`railcontact.creep3d.creep_solution_3d` for plain floats (inputs assumed in range,
    see above).

    The same operations in the same order as the array path of ``creep_solution_3d``;
    Kalker's coefficients from the cache :func:`railcontact.kalker.kalker_coefficients_cached` (per
    (a0/b0, nu); an FMU asks for the same ellipse shape step after step).

    Returns
    -------
    CreepSolution3D
        Fields as plain floats (``within_validity`` a bool).
    """
    if not _moderate_creep_inputs(xi_x, xi_y, phi, n_load, a0, b0, e_mod, mu):
        res = creep3d.creep_solution_3d(xi_x, xi_y, phi, n_load, a0, b0, e_mod, nu, mu, method)
        return CreepSolution3D(*(float(v) for v in res[:6]), bool(res[6]))
    tx, ty, z, mu_n = _creep_forces(xi_x, xi_y, phi, n_load, a0, b0, e_mod, nu, mu, method)
    stick, root, phi_coef, valid = creep_stick_3d_scalar(tx, ty, z, xi_x, xi_y, phi, mu_n, a0,
                                                         b0, method)
    return CreepSolution3D(tx, ty, stick, root, z, phi_coef, valid)
