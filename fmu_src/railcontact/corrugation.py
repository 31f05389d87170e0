r"""A cylinder rolling on a corrugated surface: normal and tangential problem (Nielsen Ch. 4.2).

The 2-D contact of a cylinder (equivalent radius ``R``) rolling over a rail surface

.. math:: Z_2(X) = \sum_{m=1}^{M} Z_{A,m}\cos(k_m X) + Z_{B,m}\sin(k_m X),
          \qquad k_m = 2\pi/L_m,                                                   \quad (4.1)

solved exactly within the polynomial approach (Eqs. (4.11)-(4.73) of [1]_), quasi-statically at
every rail position ``X`` of the cylinder axis.

Conventions
-----------
* ``X`` is the rail position of the cylinder axis; the cylinder rolls towards **+X**; the patch is
  ``|x| <= a`` in the patch coordinate ``x`` (origin at the patch centre, which lies at
  ``X + Delta`` on the rail); the **leading edge is x = +a** (package convention, as in
  :mod:`railcontact.reference.halfspace2d`). Carter's stick zone is ``[a - 2 a*, a]``.
* The thesis solves the tangential problem with the stick zone at ``x = -a`` (its (2.55)-(2.56),
  (4.47)), i.e. for rolling towards -X. All in-phase ("1") coefficients are the same in both
  orientations; the quadrature ("2") coefficients and every phase change sign:
  ``c_ours = conj(c_thesis)``. The figure script plots in the thesis' orientation.
* One harmonic, linear response: a quantity ``Q(X) = Q0 + Q_A cos kX + Q_B sin kX`` responds to
  the surface through ``Q_A + i Q_B = c (Z_A + i Z_B)``; ``c = Q1 + i Q2`` carries the thesis'
  matrix ``[[Q1, -Q2], [Q2, Q1]]`` (e.g. (4.60)), amplitude ``|c| sqrt(Z_A^2 + Z_B^2)`` and phase
  ``arg c`` ((4.63)-(4.64): the response peaks ``arg(c)/k`` after the surface crest in +X).
* Magnitudes: creepage enters through Carter's stick ratio ``r_a0 = a0*/a0`` (Eq. (4.65));
  ``T`` is the magnitude of the tangential force, ``T0 = mu N (1 - r_a0^2)`` (Carter (2.53)).

Method (what is exact and what is linearised)
---------------------------------------------
With ``g'(xb) = xb/R - dZ2/dX`` the slope of the undeformed separation and the Chebyshev expansion
(Jacobi-Anger) ``exp(i b u) = J0(b) + 2 sum_n i^n J_n(b) T_n(u)``, the polynomial approach (3.16)
gives the pressure as the Chebyshev series

.. math:: p(x) = \frac{1}{\pi C}\sum_{n\ge1} c_n \sin(n\theta), \quad x = a\cos\theta,\quad
          C = \frac{4(1-\nu^2)}{\pi E},

``c_1 = a/R + 2 sum_m k_m J_1(k_m a) Re[zeta_m e^{i phi_m}]``,
``c_n = -2 sum_m k_m J_n(k_m a) Re[i^(n+1) zeta_m e^{i phi_m}]`` (n >= 2), ``zeta = Z_A - i Z_B``,
``phi_m = k_m (X + Delta)``. This is the thesis' series (4.18)-(4.26) re-expanded in Chebyshev
polynomials, which is what makes the Bessel functions of (4.31)-(4.37) appear (they only appear
with the (k!)^2 form of (3.10)/(3.13), see the seed errata). The two conditions (bounded at both
edges, given load) are exactly (4.31) and (4.33); the stick zone obeys the same equations on
``[a - 2a*, a]`` (the creepage condition, mirrored (4.57); the force, mirrored (4.67)), and the
slip in the slip zone is the analytic continuation ``s = mu (sum d_n w^n - g2'(x))``,
``w = v + sqrt(v^2 - 1)`` (v < -1), so no power series with cancellation is ever summed.
``degree`` truncates the series (the user knob of (4.18)-(4.28)); the estimate (4.28) is returned
by :func:`series_truncation_error`.

References
----------
.. [1] J.B. Nielsen, New Developments in the Theory of Wheel/Rail Contact Mechanics,
   IMM-PHD-1998-51, DTU, 1998, Secs. 4.2.1-4.2.3, Eqs. (4.1)-(4.73).
.. [2] F.W. Carter, On the action of a locomotive driving wheel, Proc. R. Soc. A 112 (1926).
.. [3] N.I. Muskhelishvili, Singular Integral Equations, Noordhoff, 1953 (finite Hilbert
   transform of Chebyshev polynomials).
"""

from __future__ import annotations

import math
from collections import namedtuple

import numpy as np
from ._lazy import lazy_submodule

# the compiled kernels (numba) and scipy.special load on the first call that needs them: a
# table scene's corrugation effect imports this module for its checks only
_kernels = lazy_submodule("_corrugation_kernels")
from ._validation import (check_corrugated_contact_inputs, check_load_not_underflowing,
                          check_range, load_underflows)

__all__ = [
    "normal_response", "stick_zone_response", "tangential_force_response",
    "contact_point_shift_coefficient", "series_truncation_error", "series_degree",
    "solve_normal_exact", "solve_stick_zone_exact", "corrugated_contact",
    "contact_distributions", "CorrugatedContact", "ContactDistributions",
    "check_no_contact_loss", "half_width_load_term", "CorrugatedContactSolver",
]

_TWO_PI = 2.0 * np.pi


# ---------------------------------------------------------------------------------------------
# input helpers
# ---------------------------------------------------------------------------------------------
def _ratio(a0_over_wavelength):
    return check_range("a0_over_wavelength", a0_over_wavelength, "-", 0.0, None,
                       lower_closed=False)


def _stick(stick_ratio):
    return check_range("stick_ratio", stick_ratio, "-", 0.0, 1.0)


def check_no_contact_loss(curvature_amplitude):
    r"""Check condition (4.2), ``k^2 R sqrt(Z_A^2 + Z_B^2) < 1`` for every harmonic.

    Parameters
    ----------
    curvature_amplitude : array_like
        ``k_m^2 R sqrt(Z_A,m^2 + Z_B,m^2)``, the surface curvature amplitude relative to the
        cylinder curvature. [-]

    Returns
    -------
    ndarray
        The input as a float array.

    Raises
    ------
    ValueError
        If any value reaches 1: the surface is more curved than the cylinder somewhere, a
        second contact (impact, multiple contact) appears and the model is out of scope.
    """
    return check_range("curvature_amplitude", curvature_amplitude, "-", 0.0, 1.0,
                       upper_closed=False,
                       condition="Eq. (4.2) k^2 R |Z| < 1: multiple contact / impact is out of "
                                 "scope")


# ---------------------------------------------------------------------------------------------
# linear closed forms, one harmonic, normalised (vectorised over grids)
# ---------------------------------------------------------------------------------------------
def normal_response(a0_over_wavelength):
    r"""Linear response of the patch shift and half-width to one harmonic, (4.34)-(4.37).

    ``Delta(X) = -k R J0(k a0) [Z_A sin kX - Z_B cos kX]`` (4.36) and
    ``a(X) = a0 - k R J1(k a0) [Z_A cos kX + Z_B sin kX]`` (4.37), at constant normal load.

    Parameters
    ----------
    a0_over_wavelength : array_like
        Hertz half-width over wave length ``a0/L``, > 0. [-]

    Returns
    -------
    delta : ndarray of complex
        ``c_Delta / (k R) = -i J0(2 pi a0/L)``; ``|c|`` is Fig. 4.3. [-]
    half_width : ndarray of complex
        ``c_a / (k R) = -J1(2 pi a0/L)``; ``|c|`` is Fig. 4.4 (maximum 0.5819 at a0/L = 0.2930). [-]

    Notes
    -----
    Verified in the tests against the exact nonlinear solution of (4.31), (4.33)
    (:func:`solve_normal_exact`) at small amplitude, and against the discretised half-space
    solver :func:`railcontact.reference.halfspace2d.solve_normal_2d`.
    """
    cd, ca, _, _ = _linear_responses(a0_over_wavelength, 1.0)
    return cd, ca


def _linear_responses(a0_over_wavelength, stick_ratio):
    """The kernel's ``(c_Delta, c_a, c_a*, c_T)`` (normalised) at checked ``a0/L`` and
    ``r_a0``, broadcast (numpy scalars for scalar inputs)."""
    beta, r = np.broadcast_arrays(_TWO_PI * _ratio(a0_over_wavelength), _stick(stick_ratio))
    out = _kernels.linear_response_array(_flat(beta), _flat(r))
    return tuple(v.reshape(beta.shape)[()] for v in out)


def contact_point_shift_coefficient():
    r"""Linear coefficient of the contact-point shift Delta_c (4.41), normalised by ``k R``.

    ``Delta_c(X) = -k R [Z_A sin kX - Z_B cos kX]``, i.e. ``c = -i``; compare ``Delta`` = ``J0(k
    a0) Delta_c`` (4.42).

    # erratum: (4.40) as printed has cos/sin swapped on the right-hand side; the tangency
    # condition is Delta_c/sqrt(R^2 - Delta_c^2) = dZ2/dX
    #   = -k sum [Z_A sin - Z_B cos](k(X + Delta_c)),
    # whose first-order solution is the printed (4.41); verified by finite differences in the tests.

    Returns
    -------
    complex
        ``-1j``. [-]
    """
    return -1j


def stick_zone_response(a0_over_wavelength, stick_ratio):
    r"""Linear response of the stick-zone half-width a* to one harmonic, (4.58)-(4.64).

    In the package orientation (rolling towards +X, stick zone at the leading edge ``+a``):

    ``c_a* / (k R) = -J1(k a0) + J0(k a0*) sin(k d) - i [J0(k a0) - J0(k a0*) cos(k d)]``,
    ``d = a0 - a0*``. The thesis' (4.61)-(4.62) are the complex conjugate (its orientation).

    Parameters
    ----------
    a0_over_wavelength : array_like
        ``a0/L``, > 0. [-]
    stick_ratio : array_like
        Carter stick ratio ``r_a0 = a0*/a0`` in [0, 1]. [-]

    Returns
    -------
    ndarray of complex
        ``c_a* / (k R)``; amplitude is Fig. 4.6 (top), ``-arg`` its phase (bottom). [-]
    """
    return _linear_responses(a0_over_wavelength, stick_ratio)[2]


def tangential_force_response(a0_over_wavelength, stick_ratio):
    r"""Linear response of the tangential force magnitude T to one harmonic, (4.68)-(4.73).

    ``c_T = -k a0* [c_a*/(k R) + J1(k a0*) exp(-i k d)]`` in units of
    ``mu pi E / (4 (1 - nu^2))`` per unit surface amplitude (the normalisation of Fig. 4.8);
    conjugate of (4.70)-(4.71) (orientation, see module docstring). ``T0 = mu N (1 - r_a0^2)``.

    Parameters
    ----------
    a0_over_wavelength : array_like
        ``a0/L``, > 0. [-]
    stick_ratio : array_like
        ``r_a0`` in [0, 1]. [-]

    Returns
    -------
    ndarray of complex
        ``c_T / (mu pi E / (4 (1 - nu^2)))``. [-]
    """
    return _linear_responses(a0_over_wavelength, stick_ratio)[3]


def half_width_load_term(rail_position, a0, mean_normal_load, load_amplitudes_cos,
                         load_amplitudes_sin, load_wavelengths):
    r"""Half-width change from an oscillating normal load, the middle term of (4.39).

    ``a = a0 + a0/(2 N0) sum [N_A cos(k_N X) + N_B sin(k_N X)] - (surface term of (4.37))``;
    Delta is unchanged to first order.

    Parameters
    ----------
    rail_position : array_like
        Axis position X. [m]
    a0 : float
        Hertz half-width at the mean load N0, > 0. [m]
    mean_normal_load : float
        N0, > 0. [N/m]
    load_amplitudes_cos, load_amplitudes_sin : array_like, shape (M_N,)
        N_A,m and N_B,m of (4.38). [N/m]
    load_wavelengths : array_like, shape (M_N,)
        2 pi / k_N,m, > 0. [m]

    Returns
    -------
    ndarray
        ``a0/(2 N0) sum [...]``, to be added to a(X). [m]
    """
    x = check_range("rail_position", rail_position, "m")
    a0 = float(check_range("a0", a0, "m", 0.0, None, lower_closed=False))
    n0 = float(check_range("mean_normal_load", mean_normal_load, "N/m", 0.0, None,
                           lower_closed=False))
    na = np.atleast_1d(check_range("load_amplitudes_cos", load_amplitudes_cos, "N/m"))
    nb = np.atleast_1d(check_range("load_amplitudes_sin", load_amplitudes_sin, "N/m"))
    lam = np.atleast_1d(check_range("load_wavelengths", load_wavelengths, "m", 0.0, None,
                                    lower_closed=False))
    arg = _TWO_PI * x[..., None] / lam
    return a0 / (2.0 * n0) * np.sum(na * np.cos(arg) + nb * np.sin(arg), -1)


# ---------------------------------------------------------------------------------------------
# series truncation (4.27)-(4.28)
# ---------------------------------------------------------------------------------------------
def series_truncation_error(ka, degree):
    r"""Truncation-error estimates of the polynomial series (4.18) of degree ``degree``.

    Parameters
    ----------
    ka : array_like
        ``k a`` (wave number times half-width), >= 0. [-]
    degree : array_like of int
        Highest power of x kept in ``sum B_n x^n`` (= highest Chebyshev index), >= 1. [-]

    Returns
    -------
    ratio : ndarray
        The thesis' estimate (4.28), ``k a / (degree + 1)``: ratio of the errors of the degree-n
        and degree-(n+1) truncations near the edge (< 1 once the series converges). [-]
    relative_error : ndarray
        ``sum_{j > degree} |J_j(k a)| / max_j |J_j(k a)|``: the neglected Chebyshev-Bessel
        coefficients relative to the largest one, i.e. the relative error of the corrugation part
        of the pressure and slope (the size (4.27) ``(k a)^n / n!`` with the exact constants). [-]
    """
    ka = check_range("ka", ka, "-", 0.0, None)
    n = check_range("degree", degree, "-", 1, None)
    kab, nb = np.broadcast_arrays(ka, n)
    rel = [_kernels.series_relative_error(float(v), m) for v, m in zip(kab.ravel().tolist(),
                                                                     nb.ravel().tolist())]
    return ka / (n + 1.0), np.reshape(rel, kab.shape)


def series_degree(ka, tolerance=1e-10, max_degree=400):
    r"""Smallest series degree whose truncation error (:func:`series_truncation_error`) is below
    ``tolerance``.

    Parameters
    ----------
    ka : array_like
        ``k a``, >= 0. [-]
    tolerance : float
        Relative tolerance, in (0, 1). [-]
    max_degree : int
        Largest degree allowed. [-]

    Returns
    -------
    int
        The degree (maximum over the array).

    Raises
    ------
    ValueError
        If the tolerance cannot be met with ``max_degree`` (the series does converge for every
        ``k a``, like ``(k a/2)^n/n!``, but needs about ``e k a / 2`` terms before it does).
    """
    ka = check_range("ka", ka, "-", 0.0, None)
    tol = float(check_range("tolerance", tolerance, "-", 0.0, 1.0, lower_closed=False,
                            upper_closed=False))
    kamax = float(np.max(ka)) if ka.size else 0.0
    for n in range(1, int(max_degree) + 1):
        if n > kamax and series_truncation_error(kamax, n)[1] < tol:
            return n
    raise ValueError(f"degree must be <= max_degree = {max_degree} [-]; the series for "
                     f"k a = {kamax:g} needs more terms to reach tolerance {tol:g} "
                     "(increase max_degree)")


# ---------------------------------------------------------------------------------------------
# exact nonlinear solution at given rail positions (any number of harmonics)
# ---------------------------------------------------------------------------------------------
def solve_normal_exact(rail_position, normal_load_compliance, radius, wavenumbers, amplitudes_cos,
                       amplitudes_sin, *, a_start=None, tol=1e-13, max_iter=60):
    r"""Solve the exact normal equations (4.31) and (4.33) for ``a`` and ``Delta``.

    ``0 = Delta + R sum k J0(k a) [Z_A sin k(X+Delta) - Z_B cos k(X+Delta)]`` (4.31),
    ``N C = a^2/(2R) + sum k a J1(k a) [Z_A cos k(X+Delta) + Z_B sin k(X+Delta)]`` (4.33).

    Parameters
    ----------
    rail_position : array_like
        Axis position(s) X. [m]
    normal_load_compliance : float
        ``N C = N 4 (1 - nu^2)/(pi E)``, i.e. ``a0^2 / (2 R)``. [m]
    radius : float
        Equivalent radius R. [m]
    wavenumbers, amplitudes_cos, amplitudes_sin : array_like, shape (M,)
        ``k_m`` [1/m], ``Z_A,m`` [m], ``Z_B,m`` [m].

    Returns
    -------
    a, delta, d_a_dx, d_delta_dx : ndarray
        Half-width [m], patch-centre shift relative to the axis [m], and their derivatives with
        respect to X (implicit differentiation) [-].

    Raises
    ------
    ValueError
        If no single-patch solution exists (``a <= 0`` or a singular / negative Jacobian at the
        root: several harmonics whose curvatures add up beyond (4.2), ``sum k^2 R |Z| >= 1``),
        or if even the bracketed fallback does not converge.

    Notes
    -----
    Newton from ``(a0, 0)``; the equations are even in ``a``, so a root with ``a < 0`` is the
    mirror of the physical one and is returned as ``|a|`` (Newton reaches it when the first step
    crosses ``a = 0``: long waves near the edge of (4.2), e.g. ``a0/L = 0.05``,
    ``k^2 R |Z| = 0.99`` at ``X = 3L/8``, where the patch sits 3 a0 from the axis). Positions
    where Newton does not converge in ``max_iter`` steps are re-solved by a bracketed
    reduction: ``Delta(a)`` from (4.31), monotone in ``Delta`` under (4.2), then (4.33) in ``a``
    on ``[0, a_hi]`` (Newton safeguarded by bisection in both). For a convex gap (4.2) the root
    is unique. Verified against the 2-D half-space solver up to ``k^2 R |Z| = 0.99`` and down to
    ``a0/L = 1e-3`` (tests/test_hard_cases.py) and on a random sweep (``a0/L`` in
    ``[5e-4, 1]``, ``k^2 R |Z| < 0.999``, 400 surfaces x 37 positions: no failure, Newton and
    the bracketed fallback agree within 1.5e-11 a0).
    """
    x = np.asarray(rail_position, dtype=float)
    k, za, zb = _harmonics(wavenumbers, amplitudes_cos, amplitudes_sin)
    big_r = float(radius)
    nc = float(normal_load_compliance)
    a_start = np.sqrt(2.0 * big_r * nc) if a_start is None else np.asarray(a_start, float)
    x, a_start = np.broadcast_arrays(x, a_start)
    out, status = _kernels.solve_normal_array(_flat(x), nc, big_r, k, za, zb, _flat(a_start),
                                              float(tol), int(max_iter))
    if np.any(status == _kernels.NOT_CONVERGED):
        raise ValueError("amplitudes_cos, amplitudes_sin must satisfy Eq. (4.2) k^2 R |Z| < 1 "
                         "[m]: the bracketed normal problem (4.31), (4.33) did not converge "
                         f"in {max(4 * int(max_iter), 200)} steps at rail_position = "
                         f"{x.ravel()[status == _kernels.NOT_CONVERGED]} m")
    if np.any(status != _kernels.OK):
        curv_sum = float(np.sum(k * k * big_r * np.hypot(za, zb)))
        raise ValueError("amplitudes_cos, amplitudes_sin must satisfy sum k^2 R |Z| < 1 (Eq. "
                         f"(4.2) for the sum of the harmonics; got {curv_sum:g}) [m]: no "
                         "single-patch solution")
    a, d, da_dx, dd_dx = (v.reshape(x.shape) for v in out)
    return a, d, da_dx, dd_dx


def _flat(values):
    """``values`` as a new 1-D float array (the kernels' argument; a fresh, writeable copy,
    also of a broadcast view)."""
    return np.ravel(values).astype(float)


def _harmonics(wavenumbers, amplitudes_cos, amplitudes_sin):
    """The harmonics as the kernels' contiguous float arrays ``(k, Z_A, Z_B)``."""
    return tuple(_flat(v) for v in (wavenumbers, amplitudes_cos, amplitudes_sin))


def solve_stick_zone_exact(rail_position, a, delta, creepage_over_friction, radius, wavenumbers,
                           amplitudes_cos, amplitudes_sin, *, tol=1e-13, max_iter=60):
    r"""Solve the exact creepage condition for the stick half-width ``a*`` (mirrored (4.57)).

    ``xi/mu = xs/R + sum k J0(k a*) [Z_A sin k(X+xs) - Z_B cos k(X+xs)]``, with the stick-zone
    centre ``xs = Delta + a - a*`` (relative to the axis; leading edge at +a). ``a*`` is limited
    to ``[0, a]`` (0: full slip, a: no slip anywhere at this position).

    Parameters
    ----------
    rail_position, a, delta : array_like
        Axis position, half-width and patch shift from :func:`solve_normal_exact`. [m]
    creepage_over_friction : float
        ``|xi| / mu = (a0 - a0*)/R`` (Carter (2.52)). [-]
    radius : float
        R. [m]
    wavenumbers, amplitudes_cos, amplitudes_sin : array_like, shape (M,)
        Surface harmonics. [1/m], [m], [m]

    Returns
    -------
    ndarray
        ``a*``. [m]
    """
    x, a, d = np.broadcast_arrays(np.asarray(rail_position, dtype=float),
                                  np.asarray(a, float), np.asarray(delta, float))
    k, za, zb = _harmonics(wavenumbers, amplitudes_cos, amplitudes_sin)
    offset = _kernels.stick_offset_array(
        *(_flat(v) for v in (x, a, d)), float(creepage_over_friction),
        float(radius), k, za, zb, float(tol), int(max_iter))
    return a - offset.reshape(x.shape)


CorrugatedContact = namedtuple("CorrugatedContact", [
    "half_width", "patch_shift", "stick_half_width", "tangential_force", "normal_load"])
CorrugatedContact.__doc__ = """Result of :func:`corrugated_contact`.

half_width : ndarray
    Contact half-width a at the rail position. [m]
patch_shift : ndarray
    Delta: patch centre relative to the axis (rail coordinate of the centre is X + Delta). [m]
stick_half_width : ndarray
    a*: stick-zone half-width; the stick zone is [a - 2a*, a] in the patch coordinate. [m]
tangential_force : ndarray
    |T|: magnitude of the tangential force per unit length (opposes the creepage). [N/m]
normal_load : ndarray
    Normal load per unit length (constant here). [N/m]

The wear per passage on the corrugated rail is :func:`railcontact.wear.corrugated_wear_depth`
(same arguments plus the wear coefficient): wear depends on the contact, not the other way
round.
"""


def corrugated_contact(rail_position, normal_load, radius, youngs_modulus, poisson_ratio,
                       friction_coefficient, creepage, amplitudes_cos, amplitudes_sin,
                       wavelengths, *, method="exact", wear_coefficient=None,
                       wear_model=None):
    r"""One contact on a corrugated rail at given axis positions, physical units (Ch. 4.2).

    Parameters
    ----------
    rail_position : array_like
        Axis position(s) X along the rail. [m]
    normal_load : float
        Normal load per unit length N, > 0. [N/m]
    radius : float
        Equivalent radius R, > 0. [m]
    youngs_modulus : float
        E of both bodies, > 0. [Pa]
    poisson_ratio : float
        nu, in [0, 0.5). [-]
    friction_coefficient : float
        Coulomb mu, > 0. [-]
    creepage : float
        Longitudinal creepage; only ``|creepage|`` matters here (T is returned as a magnitude),
        ``|creepage| <= mu a0 / R`` (beyond: full slip, a* = 0). [-]
    amplitudes_cos, amplitudes_sin : array_like, shape (M,)
        Surface harmonics Z_A,m, Z_B,m of (4.1) (rail surface height, up positive). [m]
    wavelengths : array_like, shape (M,)
        L_m, > 0. [m]
    method : {"exact", "linear"}
        "exact": the nonlinear equations (4.31), (4.33), (4.57), (4.67) solved by Newton;
        "linear": the closed forms (4.36)-(4.37), (4.59)-(4.62), (4.68)-(4.71).
    wear_coefficient, wear_model
        No longer taken here: the wear per passage is
        :func:`railcontact.wear.corrugated_wear_depth` (the same arguments, then
        ``wear_coefficient`` and ``wear_model``). Passing either raises a TypeError saying so.

    Returns
    -------
    CorrugatedContact

    Raises
    ------
    ValueError
        Bad input, or condition (4.2) violated (multiple contact / impact: out of scope).
    TypeError
        ``wear_coefficient`` or ``wear_model`` given (see above).
    """
    from .hertz import hertz_2d

    if wear_coefficient is not None or wear_model is not None:
        raise TypeError("corrugated_contact no longer computes wear (the contact module does not "
                        "depend on the wear models): call railcontact.wear.corrugated_wear_depth"
                        "(rail_position, normal_load, radius, youngs_modulus, poisson_ratio, "
                        "friction_coefficient, creepage, amplitudes_cos, amplitudes_sin, "
                        "wavelengths, wear_coefficient, wear_model) for the wear per passage "
                        "W(X) of Eq. (4.94)")
    n_load, big_r, e_mod, nu, mu, xi, za, zb, lam = check_corrugated_contact_inputs(
        normal_load, radius, youngs_modulus, poisson_ratio, friction_coefficient, creepage,
        amplitudes_cos, amplitudes_sin, wavelengths)
    if method not in ("exact", "linear"):
        raise ValueError(f"method must be one of ['exact', 'linear']; got {method!r}")
    x = check_range("rail_position", rail_position, "m")
    k = _TWO_PI / lam
    check_no_contact_loss(k * k * big_r * np.hypot(za, zb))
    check_load_not_underflowing(n_load, e_mod, nu)
    a0 = float(hertz_2d(n_load, big_r, e_mod, nu).a0)
    comp = 4.0 * (1.0 - nu * nu) / (np.pi * e_mod)
    a0s = max(a0 - xi * big_r / mu, 0.0)
    if method == "exact":
        a, d, _, _ = solve_normal_exact(x, n_load * comp, big_r, k, za, zb)
        xs, a, d = (_flat(v) for v in np.broadcast_arrays(x, a, d))
        harmonics = _harmonics(k, za, zb)
        offset = _kernels.stick_offset_array(xs, a, d, xi / mu, big_r, *harmonics, 1e-13, 60)
        ast = a - offset
        t = _kernels.tangential_force_array(xs, a, d, offset, mu, comp, big_r, *harmonics)
    else:
        one_minus_r = min(xi * big_r / (mu * a0), 1.0)          # 1 - r without cancellation
        # Q(X) = Re[conj(c) zeta e^{ikX}] = Re[c (Z_A + i Z_B) e^{-ikX}] per harmonic
        a, d, ast, t = _kernels.contact_linear_array(
            _flat(x), a0, a0s,
            mu * n_load * one_minus_r * (2.0 - one_minus_r), big_r, mu / comp,
            *_harmonics(k, za, zb), _flat(_TWO_PI * (a0 / lam)))
    shape = np.shape(x)
    return CorrugatedContact(np.reshape(a, shape), np.reshape(d, shape), np.reshape(ast, shape),
                             np.reshape(t, shape), np.full(shape, n_load))


# ---------------------------------------------------------------------------------------------
# distributions (pressure, traction, slip) from the Chebyshev-Bessel series
# ---------------------------------------------------------------------------------------------
ContactDistributions = namedtuple("ContactDistributions", [
    "pressure", "traction", "slip", "degree", "truncation_ratio", "truncation_error"])
ContactDistributions.__doc__ = """Result of :func:`contact_distributions`.

pressure : ndarray
    p(x) (4.18). [Pa]
traction : ndarray
    |q(x)|, tangential stress magnitude (mu p in the slip zone). [Pa]
slip : ndarray
    |s(x)|, slip magnitude (relative sliding velocity over the rolling speed), 0 in the stick
    zone. [-]
degree : int
    Series degree used.
truncation_ratio, truncation_error : float
    Estimates of :func:`series_truncation_error` for that degree (worst harmonic). [-]
"""


def _cheb_coeffs(n_max, ka, phase_term, k, half_width, radius):
    """Chebyshev coefficients c_1..c_n of g' over an interval of half-width ``half_width``.

    ``phase_term`` = zeta e^{i k centre} per harmonic (complex, last axis M)."""
    from scipy.special import jv  # noqa: PLC0415  (see _kernels)

    n = np.arange(1, n_max + 1)
    jn = jv(n[:, None], ka[None, :])                                   # (n, M)
    ipow = (1j) ** ((n + 1) % 4)
    coeff = -2.0 * np.sum(k[None, :] * jn * np.real(ipow[:, None] * phase_term[None, :]), -1)
    coeff[0] += half_width / radius
    return coeff


def contact_distributions(x, rail_position, normal_load, radius, youngs_modulus, poisson_ratio,
                          friction_coefficient, creepage, amplitudes_cos, amplitudes_sin,
                          wavelengths, *, degree=None, tolerance=1e-10):
    r"""Pressure, traction and slip along the patch at one rail position (Figs. 4.5, 4.7).

    Uses the exact a, Delta, a* (:func:`solve_normal_exact`, :func:`solve_stick_zone_exact`) and
    the series of the module docstring truncated at ``degree``.

    Parameters
    ----------
    x : array_like
        Patch coordinates (origin at the patch centre, leading edge +a). [m]
    rail_position : float
        Axis position X. [m]
    normal_load, radius, youngs_modulus, poisson_ratio, friction_coefficient, creepage
        As in :func:`corrugated_contact`.
    amplitudes_cos, amplitudes_sin, wavelengths : array_like, shape (M,)
        Surface harmonics. [m]
    degree : int, optional
        Series degree (user knob of (4.18)-(4.28)); default: :func:`series_degree` for
        ``tolerance``.
    tolerance : float
        Requested relative truncation error when ``degree`` is None. [-]

    Returns
    -------
    ContactDistributions
    """
    n_load, big_r, e_mod, nu, mu, xi, za, zb, lam = check_corrugated_contact_inputs(
        normal_load, radius, youngs_modulus, poisson_ratio, friction_coefficient, creepage,
        amplitudes_cos, amplitudes_sin, wavelengths)
    xs_in = check_range("x", x, "m")
    xpos = float(check_range("rail_position", rail_position, "m"))
    k = _TWO_PI / lam
    check_no_contact_loss(k * k * big_r * np.hypot(za, zb))
    comp = 4.0 * (1.0 - nu * nu) / (np.pi * e_mod)
    a, d, _, _ = solve_normal_exact(xpos, n_load * comp, big_r, k, za, zb)
    ast = solve_stick_zone_exact(xpos, a, d, xi / mu, big_r, k, za, zb)
    a, d, ast = float(a), float(d), float(ast)
    if degree is None:
        degree = series_degree(k * a, tolerance)
    degree = int(check_range("degree", degree, "-", 1, 10000))
    ratio, err = series_truncation_error(k * a, degree)
    zeta = za - 1j * zb
    cn = _cheb_coeffs(degree, k * a, zeta * np.exp(1j * k * (xpos + d)), k, a, big_r)
    n = np.arange(1, degree + 1)
    u = np.clip(xs_in / a, -1.0, 1.0)
    theta = np.arccos(u)
    inside = np.abs(xs_in) < a
    p = np.where(inside, np.sin(np.multiply.outer(theta, n)) @ cn / (np.pi * comp), 0.0)
    q = mu * p
    s = np.zeros_like(p)
    if ast > 0:
        xc = a - ast                                   # stick-zone centre (patch coordinate)
        dn = _cheb_coeffs(degree, k * ast, zeta * np.exp(1j * k * (xpos + d + xc)), k, ast,
                          big_r)
        v = (xs_in - xc) / ast
        in_stick = inside & (np.abs(v) < 1)
        phi = np.arccos(np.clip(v, -1, 1))
        p2 = np.sin(np.multiply.outer(phi, n)) @ dn / (np.pi * comp)
        q = np.where(in_stick, mu * (p - p2), q)
        in_slip = inside & (v <= -1)
        vv = np.minimum(v, -1.0)
        w = vv + np.sqrt(vv * vv - 1.0)
        g2 = ((d + xs_in) / big_r
              + np.sum(k * np.real(-1j * zeta * np.exp(1j * k * (xpos + d + xs_in[..., None]))),
                       -1)
              - xi / mu)
        s = np.where(in_slip, mu * np.abs(np.power.outer(w, n) @ dn - g2), 0.0)
    else:
        g2 = ((d + xs_in) / big_r
              + np.sum(k * np.real(-1j * zeta * np.exp(1j * k * (xpos + d + xs_in[..., None]))),
                       -1)
              - xi / mu)
        s = np.where(inside, mu * np.abs(g2), 0.0)
    return ContactDistributions(p, np.abs(q), s, degree, float(np.max(ratio)),
                                float(np.max(err)))


# ---------------------------------------------------------------------------------------------
# one rail position per call, as floats: the FMU's corrugation effect
# ---------------------------------------------------------------------------------------------
class CorrugatedContactSolver:
    r""":func:`corrugated_contact` at one rail position per call, as plain floats.

    The FMU's corrugation effect calls it once per step (a call of
    :func:`corrugated_contact` costs tens of microseconds of numpy overhead and range checks
    at one position). Radius, material and method are checked once here;
    :meth:`contact` evaluates the same compiled kernels as :func:`corrugated_contact` and
    calls that function itself where it would raise (a load or friction coefficient <= 0, a
    non-finite input, condition (4.2) violated, an underflowing normalised load, no
    single-patch solution), so the errors are the public function's. The wear per passage
    is not computed here: :func:`railcontact.wear.corrugated_wear_depth` (the contact module
    does not depend on the wear models).

    Parameters
    ----------
    radius : float
        Equivalent radius R, > 0. [m]
    youngs_modulus : float
        > 0. [Pa]
    poisson_ratio : float
        In [0, 0.5). [-]
    method : {"exact", "linear"}
        As in :func:`corrugated_contact`.
    """

    def __init__(self, radius, youngs_modulus, poisson_ratio, method="exact"):
        self.radius = float(check_range("radius", radius, "m", 0.0, None, lower_closed=False))
        self.youngs_modulus = float(check_range("youngs_modulus", youngs_modulus, "Pa", 0.0,
                                                None, lower_closed=False))
        self.poisson_ratio = float(check_range("poisson_ratio", poisson_ratio, "-", 0.0, 0.5,
                                               upper_closed=False))
        if method not in ("exact", "linear"):
            raise ValueError(f"method must be one of ['exact', 'linear']; got {method!r}")
        self.method = method
        nu, e_mod = self.poisson_ratio, self.youngs_modulus
        self._comp = 4.0 * (1.0 - nu * nu) / (math.pi * e_mod)       # C
        self._surface_key = (None, None, None)       # the lists self._surface was made from
        self._surface = None

    def surface(self, amplitudes_cos, amplitudes_sin, wavelengths):
        """The harmonics as float arrays ``(Z_A, Z_B, L, k)`` and whether they are a valid
        surface (equal 1-D non-empty shapes, finite, L > 0, condition (4.2)); converted and
        checked once per surface (the lists the caller passes: a new surface is new lists)."""
        key = self._surface_key
        if (amplitudes_cos is key[0] and amplitudes_sin is key[1] and wavelengths is key[2]):
            return self._surface
        za = np.array(amplitudes_cos, dtype=float)
        zb = np.array(amplitudes_sin, dtype=float)
        lam = np.array(wavelengths, dtype=float)
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            k = _TWO_PI / lam
            ok = bool(za.shape == zb.shape == lam.shape and za.ndim == 1 and za.size
                      and np.all(np.isfinite(za)) and np.all(np.isfinite(zb))
                      and np.all(lam > 0.0)
                      and np.all(k * k * self.radius * np.hypot(za, zb) < 1.0))
        self._surface_key = (amplitudes_cos, amplitudes_sin, wavelengths)
        self._surface = (za, zb, lam, k, ok)
        return self._surface

    def load_underflows(self, normal_load):
        """True if the normalised load ``8 (1 - nu^2) N / (pi E)`` is below the smallest
        normal double (or not a number): no contact (:func:`corrugated_contact` raises)."""
        return load_underflows(normal_load, self.youngs_modulus, self.poisson_ratio)

    def contact(self, rail_position, normal_load, friction_coefficient, creepage,
                amplitudes_cos, amplitudes_sin, wavelengths):
        """:func:`corrugated_contact` at one rail position: ``(a, Delta, a*, |T|)``.
        [m, m, m, N/m]

        ``amplitudes_cos``, ``amplitudes_sin``, ``wavelengths``: sequences of floats (the
        harmonics may change between calls, e.g. by surface evolution)."""
        x, n_load, big_r, mu = rail_position, normal_load, self.radius, friction_coefficient
        za, zb, lam, k, surface_ok = self.surface(amplitudes_cos, amplitudes_sin, wavelengths)
        if not (surface_ok and math.isfinite(x) and math.isfinite(creepage)
                and 0.0 < mu < math.inf and not self.load_underflows(n_load)
                and n_load < math.inf):
            return self._public(rail_position, normal_load, friction_coefficient, creepage,
                                amplitudes_cos, amplitudes_sin, wavelengths)
        xi = abs(creepage)
        nu, e_mod = self.poisson_ratio, self.youngs_modulus
        a0 = math.sqrt(8.0 * (1.0 - nu * nu) * big_r * n_load / (math.pi * e_mod))  # Hertz
        comp = self._comp
        a0s = max(a0 - xi * big_r / mu, 0.0)
        if self.method == "exact":
            a, d, ast, t, status = _kernels.contact_exact(x, n_load * comp, big_r, k, za, zb,
                                                          xi / mu, mu, comp)
            if status != _kernels.OK:             # no single-patch solution: the public error
                return self._public(rail_position, normal_load, friction_coefficient, creepage,
                                    amplitudes_cos, amplitudes_sin, wavelengths)
        else:
            one_minus_r = min(xi * big_r / (mu * a0), 1.0)      # 1 - r without cancellation
            a, d, ast, t = _kernels.contact_linear(
                x, a0, a0s, mu * n_load * one_minus_r * (2.0 - one_minus_r), big_r, mu / comp,
                k, za, zb, _TWO_PI * (a0 / lam))
        return a, d, ast, t

    def _public(self, rail_position, normal_load, friction_coefficient, creepage,
                amplitudes_cos, amplitudes_sin, wavelengths):
        """:func:`corrugated_contact` (which raises or solves the case) as floats."""
        res = corrugated_contact(rail_position, normal_load, self.radius, self.youngs_modulus,
                                 self.poisson_ratio, friction_coefficient, creepage,
                                 amplitudes_cos, amplitudes_sin, wavelengths,
                                 method=self.method)
        return (float(res.half_width), float(res.patch_shift), float(res.stick_half_width),
                float(res.tangential_force))
