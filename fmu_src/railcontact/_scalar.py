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

__all__ = ["carter_scalar", "normalised_inputs_scalar",
           "step_law_creep_force_normalised_scalar", "evolve_harmonics_scalar"]


# ---------------------------------------------------------------------------------------------
# railcontact.carter
# ---------------------------------------------------------------------------------------------
# numpy's per-call overhead (array creation, ufunc dispatch, the input checks) is ~60 us per
# call of carter_creep_force on scalars, for well under 1 us of arithmetic. The function below
# repeats the array paths' arithmetic (hertz_2d's a0, carter_critical_creepage,
# _sliding_fraction, carter_creep_force's f (2 - f) form, carter_stick_ratio's 1 - f) operation
# for operation on floats with the math module, for callers that have already range-checked
# their inputs (the FMU slave: railcontact.effects._inputs_plausible, the scene's checks). It
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
# FMU slave: railcontact.effects._inputs_plausible, the scene's checks). They ASSUME, and do not
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
