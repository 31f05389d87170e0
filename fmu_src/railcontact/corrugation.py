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

import cmath
import math
from collections import namedtuple

import numpy as np
from scipy.special import j0, j1, jv

from ._validation import (check_corrugated_contact_inputs, check_load_not_underflowing,
                          check_range, load_underflows)

__all__ = [
    "normal_response", "stick_zone_response", "tangential_force_response",
    "contact_point_shift_coefficient", "series_truncation_error", "series_degree",
    "solve_normal_exact", "solve_stick_zone_exact", "corrugated_contact",
    "contact_distributions", "CorrugatedContact", "ContactDistributions",
    "check_no_contact_loss", "half_width_load_term",
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
    beta = _TWO_PI * _ratio(a0_over_wavelength)
    return -1j * j0(beta), -j1(beta) + 0j


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
    beta = _TWO_PI * _ratio(a0_over_wavelength)
    r = _stick(stick_ratio)
    kd = beta * (1.0 - r)
    js = j0(beta * r)
    return (-j1(beta) + js * np.sin(kd)) - 1j * (j0(beta) - js * np.cos(kd))


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
    beta = _TWO_PI * _ratio(a0_over_wavelength)
    r = _stick(stick_ratio)
    kd = beta * (1.0 - r)
    return -beta * r * (stick_zone_response(a0_over_wavelength, r)
                        + j1(beta * r) * np.exp(-1j * kd))


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
    nmax = int(np.max(n)) + 60 + int(np.max(ka)) * 2
    j = np.arange(1, nmax + 1)
    shape = np.broadcast(ka, n).shape
    kab = np.broadcast_to(ka, shape)[..., None]
    nb = np.broadcast_to(n, shape)[..., None]
    terms = np.abs(jv(j, kab))
    biggest = np.maximum(terms.max(axis=-1), 1e-300)
    tail = np.where(j > nb, terms, 0.0).sum(axis=-1)
    return ka / (n + 1.0), np.where(np.squeeze(kab, -1) > 0, tail / biggest, 0.0)


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
def _surface_terms(y, k, za, zb):
    """S = Z_A sin ky - Z_B cos ky and Zc = Z_A cos ky + Z_B sin ky (last axis = harmonics)."""
    s, c = np.sin(k * y), np.cos(k * y)
    return za * s - zb * c, za * c + zb * s


def _shift_for_half_width(x, a, big_r, k, za, zb, atol, max_iter, d=None):
    """Delta(a) from (4.31) at fixed half-width, bracketed (vectorised over positions).

    ``h(Delta) = Delta + R sum k J0(k a) S(X + Delta)`` satisfies ``h(-B) <= 0 <= h(B)`` with
    ``B = R sum k |J0(k a)| |Z|`` and ``h' = 1 + R sum k^2 J0(k a) Zc >= 1 - sum k^2 R |Z| > 0``
    under (4.2): one root, found by Newton safeguarded by bisection."""
    ka = k * a[:, None]
    jz = j0(ka)
    bound = big_r * np.sum(k * np.abs(jz) * np.hypot(za, zb), -1)
    lo, hi = -bound, bound.copy()
    d = np.zeros_like(a) if d is None else np.clip(d, lo, hi)
    for _ in range(max_iter):
        s, c = _surface_terms(x[:, None] + d[:, None], k, za, zb)
        h = d + big_r * np.sum(k * jz * s, -1)
        dh = 1.0 + big_r * np.sum(k * k * jz * c, -1)
        lo = np.where(h <= 0, d, lo)
        hi = np.where(h >= 0, d, hi)
        with np.errstate(divide="ignore", invalid="ignore"):
            new = d - h / dh
        new = np.where((new > lo) & (new < hi), new, 0.5 * (lo + hi))
        done = (np.abs(new - d) <= atol) | (hi - lo <= atol) | (h == 0)
        d = np.where(h == 0, d, new)
        if np.all(done):
            break
    return d


def _solve_normal_bracketed(x, nc, big_r, k, za, zb, atol, max_iter):
    """(4.31), (4.33) as a bracketed 1-D problem in a (globally convergent Newton fallback).

    For each a, Delta(a) is the unique root of (4.31) (:func:`_shift_for_half_width`); then
    ``P(a) = a^2/(2R) + sum k a J1(k a) Zc(X + Delta(a)) - N C`` has ``P(0) = -N C < 0`` and
    ``P(a_hi) > 0`` for ``a_hi = R s + sqrt((R s)^2 + 2 R N C)``, ``s = 0.582 sum k |Z|``
    (``max |J1| = 0.5819``). Under (4.2) (convex gap) the root is unique: every root gives the
    bounded Muskhelishvili pressure ``p ~ sqrt(a^2 - x^2) int (g'(t) - g'(x))/(t - x) ...``,
    positive for a convex gap, i.e. a solution of the (uniquely solvable) contact problem.
    Newton on ``P`` with ``dP/da = det / j11`` (total derivative), safeguarded by bisection.
    """
    x = np.asarray(x, float)
    s_j1 = 0.582 * np.sum(k * np.hypot(za, zb))
    lo = np.zeros_like(x)
    hi = np.full_like(x, big_r * s_j1 + np.sqrt((big_r * s_j1) ** 2 + 2.0 * big_r * nc))
    a = np.minimum(np.sqrt(2.0 * big_r * nc), 0.5 * hi)
    d = None
    for _ in range(max_iter):
        d = _shift_for_half_width(x, a, big_r, k, za, zb, atol, max_iter, d)
        s, c = _surface_terms(x[:, None] + d[:, None], k, za, zb)
        ka = k * a[:, None]
        jz, jo = j0(ka), j1(ka)
        p = a * a / (2 * big_r) + np.sum(k * a[:, None] * jo * c, -1) - nc
        j11 = 1.0 + big_r * np.sum(k * k * jz * c, -1)
        j12 = -big_r * np.sum(k * k * jo * s, -1)
        j21 = -np.sum(k * k * a[:, None] * jo * s, -1)
        j22 = a / big_r + np.sum(k * k * a[:, None] * jz * c, -1)
        lo = np.where(p <= 0, a, lo)
        hi = np.where(p >= 0, a, hi)
        with np.errstate(divide="ignore", invalid="ignore"):
            new = a - p * j11 / (j11 * j22 - j12 * j21)
        new = np.where((new > lo) & (new < hi), new, 0.5 * (lo + hi))
        done = (np.abs(new - a) <= atol) | (hi - lo <= atol) | (p == 0)
        a = np.where(p == 0, a, new)
        if np.all(done):
            break
    else:
        raise ValueError("amplitudes_cos, amplitudes_sin must satisfy Eq. (4.2) k^2 R |Z| < 1 "
                         "[m]: the bracketed normal problem (4.31), (4.33) did not converge "
                         f"in {max_iter} steps at rail_position = {x[~done]} m")
    d = _shift_for_half_width(x, a, big_r, k, za, zb, atol, max_iter, d)
    return a, d


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
    x = np.asarray(rail_position, dtype=float)[..., None]
    k = np.asarray(wavenumbers, float)
    za = np.asarray(amplitudes_cos, float)
    zb = np.asarray(amplitudes_sin, float)
    big_r = float(radius)
    nc = float(normal_load_compliance)
    a0 = np.sqrt(2.0 * big_r * nc)
    a = np.full(x.shape[:-1], a0 if a_start is None else 0.0) + (0.0 if a_start is None
                                                                else np.asarray(a_start))
    d = np.zeros(x.shape[:-1])
    step = np.full(x.shape[:-1], np.inf)
    # Steps are compared with tol * (a0 + R sum k |Z|): the residual of (4.31) is a sum of terms
    # of size |Delta| <= R sum k |Z|, so its rounding (eps R k |Z| / j11) exceeds tol * a0 for long
    # waves (a0/L = 1e-3, k^2 R |Z| = 0.858: |Delta| = 76 a0; with tol * a0 alone Newton had
    # converged but never met the criterion and reported "did not converge").
    atol = tol * (a0 + big_r * float(np.sum(k * np.hypot(za, zb))))
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        for _ in range(max_iter):
            s, c = _surface_terms(x + d[..., None], k, za, zb)
            ka = k * a[..., None]
            jz, jo = j0(ka), j1(ka)
            f1 = d + big_r * np.sum(k * jz * s, -1)
            f2 = a * a / (2 * big_r) + np.sum(k * a[..., None] * jo * c, -1) - nc
            j11 = 1.0 + big_r * np.sum(k * k * jz * c, -1)
            j12 = -big_r * np.sum(k * k * jo * s, -1)
            j21 = -np.sum(k * k * a[..., None] * jo * s, -1)
            j22 = a / big_r + np.sum(k * k * a[..., None] * jz * c, -1)
            det = j11 * j22 - j12 * j21
            dd = (f1 * j22 - f2 * j12) / det
            da = (j11 * f2 - j21 * f1) / det
            d = d - dd
            a = a - da
            step = np.abs(dd) + np.abs(da)
            if np.all(step < atol):
                break
    # (4.31) and (4.33) are even in a (J0 even, a J1(k a) even): a Newton step through a = 0
    # (tiny det far from the solution, e.g. long waves near the edge of (4.2) where the patch
    # moves by ~L/7 from the axis) lands on the mirror root (-a, Delta), the same physical
    # solution. Positions where plain Newton did not converge (it can cycle when the patch
    # shift is a sizeable part of the wave length) are re-solved by the bracketed reduction.
    a = np.abs(a)
    bad = (~(step < atol) | ~np.isfinite(a) | ~np.isfinite(d)).reshape(-1)
    if np.any(bad):
        a_f, d_f = a.reshape(-1).copy(), d.reshape(-1).copy()
        a_f[bad], d_f[bad] = _solve_normal_bracketed(x.reshape(-1)[bad], nc, big_r, k, za, zb,
                                                     atol, max(4 * max_iter, 200))
        a, d = a_f.reshape(a.shape), d_f.reshape(d.shape)
    curv_sum = float(np.sum(k * k * big_r * np.hypot(za, zb)))
    s, c = _surface_terms(x + d[..., None], k, za, zb)
    ka = k * a[..., None]
    jz, jo = j0(ka), j1(ka)
    j11 = 1.0 + big_r * np.sum(k * k * jz * c, -1)
    j12 = -big_r * np.sum(k * k * jo * s, -1)
    j21 = -np.sum(k * k * a[..., None] * jo * s, -1)
    j22 = a / big_r + np.sum(k * k * a[..., None] * jz * c, -1)
    det = j11 * j22 - j12 * j21
    if np.any(a <= 0) or np.any(~(det > 0)) or np.any(~(j11 > 0)):
        raise ValueError("amplitudes_cos, amplitudes_sin must satisfy sum k^2 R |Z| < 1 (Eq. "
                         f"(4.2) for the sum of the harmonics; got {curv_sum:g}) [m]: no "
                         "single-patch solution")
    g1 = big_r * np.sum(k * k * jz * c, -1)              # dF1/dX
    g2 = -np.sum(k * k * a[..., None] * jo * s, -1)      # dF2/dX
    dd_dx = -(g1 * j22 - g2 * j12) / det
    da_dx = -(j11 * g2 - j21 * g1) / det
    return a, d, da_dx, dd_dx


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
    x = np.asarray(rail_position, dtype=float)
    a = np.asarray(a, float)
    d = np.asarray(delta, float)
    offset = _stick_offset(x, a, d, float(creepage_over_friction), float(radius),
                           np.asarray(wavenumbers, float), np.asarray(amplitudes_cos, float),
                           np.asarray(amplitudes_sin, float), tol, max_iter)
    return a - offset


# Small offsets delta = a - a* (tiny creepage) are handled by second-order Taylor expansions in
# delta of the *differences* below, so that neither delta nor T is the difference of two
# nearly equal O(1) numbers (xi -> 0 gives delta = 0 and T = 0 exactly).
_TAYLOR_LIMIT = 1e-4          # k delta below which the Taylor forms are used


def _j1_over_z(z):
    return np.where(z > 1e-8, j1(z) / np.where(z > 1e-8, z, 1.0), 0.5)


def _stick_bracket(y, a, delta, k, za, zb):
    """G(delta) - G(0), G = sum k J0(k (a - delta)) S(y + delta), and dG/d delta."""
    kd = k * delta[..., None]
    small = np.max(kd, -1, initial=0.0) < _TAYLOR_LIMIT
    s0, c0 = _surface_terms(y[..., None], k, za, zb)
    z = k * a[..., None]
    jz, jo = j0(z), j1(z)
    g1 = np.sum(k * k * (jo * s0 + jz * c0), -1)
    g2 = np.sum(k ** 3 * (-(2 * jz - _j1_over_z(z)) * s0 + 2 * jo * c0), -1)
    taylor = delta * g1 + 0.5 * delta * delta * g2
    s1, c1 = _surface_terms(y[..., None] + delta[..., None], k, za, zb)
    zs = k * (a - delta)[..., None]
    direct = np.sum(k * (j0(zs) * s1 - jz * s0), -1)
    deriv = np.sum(k * k * (j1(zs) * s1 + j0(zs) * c1), -1)
    return np.where(small, taylor, direct), deriv


def _stick_offset(x, a, d, xi, big_r, k, za, zb, tol=1e-13, max_iter=60):
    """Solve delta = a - a* from delta/R + [G(delta) - G(0)] = xi/mu, delta in [0, a].

    (The creepage condition minus the normal condition (4.31), which holds at delta = 0.)"""
    y = x + d
    delta = np.clip(np.full(np.shape(y), xi * big_r), 0.0, a)
    for _ in range(max_iter):
        bracket, deriv = _stick_bracket(y, a, delta, k, za, zb)
        f = delta / big_r + bracket - xi
        df = 1.0 / big_r + deriv
        new = np.clip(delta - f / df, 0.0, a)
        done = np.all(np.abs(new - delta) <= tol * np.maximum(np.abs(new), 1e-300)
                      + 1e-15 * tol * a)
        delta = new
        if done:
            break
    return delta


def _tangential_force_exact(x, a, d, delta, mu, comp, big_r, k, za, zb):
    """|T| = (mu/C) [delta (2a - delta)/(2R) + H(0) - H(delta)] (4.67) minus (4.33),
    H(delta) = sum k (a - delta) J1(k (a - delta)) Zc(y + delta), y = X + Delta."""
    y = (x + d)[..., None]
    kd = k * delta[..., None]
    small = np.max(kd, -1, initial=0.0) < _TAYLOR_LIMIT
    s0, c0 = _surface_terms(y, k, za, zb)
    z = k * a[..., None]
    jz, jo = j0(z), j1(z)
    av = a[..., None]
    h1 = -np.sum(k * k * av * (jz * c0 + jo * s0), -1)
    h2 = np.sum(k * k * (jz * c0 + jo * s0)
                - k ** 3 * av * (2 * jo * c0 - (2 * jz - _j1_over_z(z)) * s0), -1)
    taylor = -(delta * h1 + 0.5 * delta * delta * h2)
    s1, c1 = _surface_terms(y + delta[..., None], k, za, zb)
    ast = (a - delta)[..., None]
    direct = np.sum(k * (av * jo * c0 - ast * j1(k * ast) * c1), -1)
    diff = np.where(small, taylor, direct)
    return mu / comp * (delta * (2 * a - delta) / (2 * big_r) + diff)


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


_TINY = 2.2250738585072014e-308   # smallest normal double
_load_underflows = load_underflows       # (the FMU's corrugation effect reads this name)


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
        offset = _stick_offset(x, a, d, xi / mu, big_r, k, za, zb)
        ast = a - offset
        t = _tangential_force_exact(x, a, d, offset, mu, comp, big_r, k, za, zb)
    else:
        ratio = a0 / lam
        r = a0s / a0
        zc = (za + 1j * zb)[None, :] * np.exp(-1j * k * x[..., None])     # Z_A + i Z_B rotated
        cd, ca = normal_response(ratio)
        cs = stick_zone_response(ratio, r)
        ct = tangential_force_response(ratio, r)
        # Q(X) = Re[conj(c) zeta e^{ikX}] = Re[c (Z_A + i Z_B) e^{-ikX}]
        a = a0 + np.sum(np.real(k * big_r * ca * zc), -1)
        d = np.sum(np.real(k * big_r * cd * zc), -1)
        ast = a0s + np.sum(np.real(k * big_r * cs * zc), -1)
        one_minus_r = min(xi * big_r / (mu * a0), 1.0)          # 1 - r without cancellation
        t = (mu * n_load * one_minus_r * (2.0 - one_minus_r)
             + np.sum(np.real(mu / comp * ct * zc), -1))
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
# Scalar path (plain Python floats): the FMU's per-step call
# ---------------------------------------------------------------------------------------------
# corrugated_contact at one rail position costs ~1 ms, nearly all of it numpy's per-call
# overhead on arrays of M harmonics (range checks, ~40 small operations per Newton step). The
# functions below repeat its arithmetic on floats (math.sin/cos, scipy's j0/j1 on floats, the
# same cephes routines the array path uses): the same Newton iterations from the same start,
# the same convergence tests and tolerances, the same Taylor switch of the stick-zone
# differences. They differ from the array path by rounding only (libm's sin/cos against
# numpy's, the order of the sums over harmonics), so the iterates agree to a few ulp and the
# converged roots to the solver tolerance 1e-13 (tests/test_corrugation.py asserts it on seeded
# inputs over amplitudes, harmonics, k a0, r_a0, creepage and both methods).
# Every branch that is not the plain Newton solution -- condition (4.2) violated, Newton not
# converged within max_iter or not finite (the bracketed fallback), a root failing the
# single-patch check -- is handed to corrugated_contact itself, which raises or solves it.
# It ASSUMES, and does not check: normal_load > 0, radius > 0, youngs_modulus > 0,
# 0 <= poisson_ratio < 0.5, friction_coefficient > 0, every other input finite,
# amplitudes_cos, amplitudes_sin, wavelengths sequences of equal length >= 1 with wavelengths
# > 0, method "exact" or "linear" (the scene and the FMU slave check all of these first).
def _corrugated_contact_scalar(rail_position, normal_load, radius, youngs_modulus,
                               poisson_ratio, friction_coefficient, creepage, amplitudes_cos,
                               amplitudes_sin, wavelengths, method="exact"):
    """:func:`corrugated_contact` at one rail position for plain floats (inputs assumed in
    range, see above): ``(a, Delta, a*, |T|)``. [m, m, m, N/m]"""
    x, n_load, big_r, nu, mu = rail_position, normal_load, radius, poisson_ratio, \
        friction_coefficient
    xi = abs(creepage)
    harm = [(_TWO_PI / lam, za, zb) for za, zb, lam in zip(amplitudes_cos, amplitudes_sin,
                                                           wavelengths)]
    if not (all(k * k * big_r * math.hypot(za, zb) < 1.0 for k, za, zb in harm)
            and 8.0 * (1.0 - nu * nu) * n_load / (math.pi * youngs_modulus) >= _TINY):
        return _public_contact(rail_position, normal_load, radius, youngs_modulus, poisson_ratio,
                               friction_coefficient, creepage, amplitudes_cos, amplitudes_sin,
                               wavelengths, method)
    a0 = math.sqrt(8.0 * (1.0 - nu * nu) * big_r * n_load / (math.pi * youngs_modulus))
    comp = 4.0 * (1.0 - nu * nu) / (math.pi * youngs_modulus)
    a0s = max(a0 - xi * big_r / mu, 0.0)
    if method == "exact":
        solved = _solve_normal_scalar(x, n_load * comp, big_r, harm)
        if solved is None:                    # bracketed fallback or no single-patch solution
            return _public_contact(rail_position, normal_load, radius, youngs_modulus,
                                   poisson_ratio, friction_coefficient, creepage,
                                   amplitudes_cos, amplitudes_sin, wavelengths, method)
        a, d = solved
        offset = _stick_offset_scalar(x, a, d, xi / mu, big_r, harm)
        ast = a - offset
        t = _tangential_force_scalar(x, a, d, offset, mu, comp, big_r, harm)
    else:
        r = a0s / a0
        a, d, ast = a0, 0.0, a0s
        one_minus_r = min(xi * big_r / (mu * a0), 1.0)
        t = mu * n_load * one_minus_r * (2.0 - one_minus_r)
        scale_t = mu / comp
        for (k, za, zb), lam in zip(harm, wavelengths):
            beta = _TWO_PI * (a0 / lam)
            zc = complex(za, zb) * cmath.exp(-1j * k * x)
            jb0, jb1 = float(j0(beta)), float(j1(beta))
            kd = beta * (1.0 - r)
            js = float(j0(beta * r))
            cs = (-jb1 + js * math.sin(kd)) - 1j * (jb0 - js * math.cos(kd))
            ct = -beta * r * (cs + float(j1(beta * r)) * cmath.exp(-1j * kd))
            kr = k * big_r
            a += (kr * -jb1 * zc).real
            d += (kr * (-1j * jb0) * zc).real
            ast += (kr * cs * zc).real
            t += (scale_t * ct * zc).real
    return a, d, ast, t


def _series_truncation_error_scalar(ka, degree):
    """The ``relative_error`` of :func:`series_truncation_error` for one float ``ka >= 0`` and
    int ``degree >= 1`` (not checked): the same numpy operations on the same 1-D arrays, so the
    same float, bit for bit (the public function's broadcasting and range checks dropped). [-]"""
    j = np.arange(1, degree + 60 + int(ka) * 2 + 1)
    terms = np.abs(jv(j, ka))
    biggest = max(float(terms.max()), 1e-300)
    tail = float(np.where(j > degree, terms, 0.0).sum())
    return tail / biggest if ka > 0 else 0.0


def _public_contact(*args):
    """corrugated_contact (the array path) for the scalar path's arguments, as floats."""
    *args, method = args
    res = corrugated_contact(*args, method=method)
    return (float(res.half_width), float(res.patch_shift), float(res.stick_half_width),
            float(res.tangential_force))


def _solve_normal_scalar(x, nc, big_r, harm, tol=1e-13, max_iter=60, _sin=math.sin,
                         _cos=math.cos):
    """solve_normal_exact's Newton iteration for one position: (a, Delta), or None where the
    array path takes its bracketed fallback or raises (not converged, not finite, or the
    single-patch check fails)."""
    a = math.sqrt(2.0 * big_r * nc)
    atol = tol * (a + big_r * sum(k * math.hypot(za, zb) for k, za, zb in harm))
    d = 0.0
    step = math.inf
    for _ in range(max_iter):
        y = x + d
        f1 = f2 = j11 = j12 = j21 = j22 = 0.0
        for k, za, zb in harm:
            sn, cs = _sin(k * y), _cos(k * y)
            s, c = za * sn - zb * cs, za * cs + zb * sn
            ka = k * a
            jz, jo = float(j0(ka)), float(j1(ka))
            kjz, kkjo = k * jz, k * k * jo
            f1 += kjz * s
            f2 += k * a * jo * c
            j11 += k * k * jz * c
            j12 += kkjo * s
            j21 += k * k * a * jo * s
            j22 += k * k * a * jz * c
        f1 = d + big_r * f1
        f2 = a * a / (2 * big_r) + f2 - nc
        j11 = 1.0 + big_r * j11
        j12 = -big_r * j12
        j21 = -j21
        j22 = a / big_r + j22
        det = j11 * j22 - j12 * j21
        if det == 0.0:
            return None
        dd = (f1 * j22 - f2 * j12) / det
        da = (j11 * f2 - j21 * f1) / det
        d = d - dd
        a = a - da
        step = abs(dd) + abs(da)
        if not math.isfinite(step):
            return None
        if step < atol:
            break
    if not step < atol:
        return None
    a = abs(a)
    # the single-patch check of solve_normal_exact at the root
    y = x + d
    j11 = j12 = j21 = j22 = 0.0
    for k, za, zb in harm:
        sn, cs = _sin(k * y), _cos(k * y)
        s, c = za * sn - zb * cs, za * cs + zb * sn
        ka = k * a
        jz, jo = float(j0(ka)), float(j1(ka))
        j11 += k * k * jz * c
        j12 += k * k * jo * s
        j21 += k * k * a * jo * s
        j22 += k * k * a * jz * c
    j11 = 1.0 + big_r * j11
    det = j11 * (a / big_r + j22) - big_r * j12 * j21
    if not (a > 0 and det > 0 and j11 > 0):
        return None
    return a, d


def _stick_offset_scalar(x, a, d, xi, big_r, harm, tol=1e-13, max_iter=60, _sin=math.sin,
                         _cos=math.cos):
    """_stick_offset for one position (the same Newton iteration, floats)."""
    y = x + d
    base = []
    g1 = g2 = 0.0
    for k, za, zb in harm:
        sn, cs = _sin(k * y), _cos(k * y)
        s0, c0 = za * sn - zb * cs, za * cs + zb * sn
        z = k * a
        jz, jo = float(j0(z)), float(j1(z))
        j1oz = jo / z if z > 1e-8 else 0.5
        g1 += k * k * (jo * s0 + jz * c0)
        g2 += k ** 3 * (-(2 * jz - j1oz) * s0 + 2 * jo * c0)
        base.append((k, za, zb, jz * s0))
    delta = min(max(xi * big_r, 0.0), a)
    for _ in range(max_iter):
        small = max(0.0, max(k * delta for k, _, _, _ in base)) < _TAYLOR_LIMIT
        direct = deriv = 0.0
        yd = y + delta
        for k, za, zb, jzs0 in base:
            sn, cs = _sin(k * yd), _cos(k * yd)
            s1, c1 = za * sn - zb * cs, za * cs + zb * sn
            zs = k * (a - delta)
            js0, js1 = float(j0(zs)), float(j1(zs))
            direct += k * (js0 * s1 - jzs0)
            deriv += k * k * (js1 * s1 + js0 * c1)
        bracket = delta * g1 + 0.5 * delta * delta * g2 if small else direct
        f = delta / big_r + bracket - xi
        df = 1.0 / big_r + deriv
        new = min(max(delta - f / df, 0.0), a)
        done = abs(new - delta) <= tol * max(abs(new), 1e-300) + 1e-15 * tol * a
        delta = new
        if done:
            break
    return delta


def _tangential_force_scalar(x, a, d, delta, mu, comp, big_r, harm, _sin=math.sin,
                             _cos=math.cos):
    """_tangential_force_exact for one position (floats)."""
    y = x + d
    small = max(0.0, max(k * delta for k, _, _ in harm)) < _TAYLOR_LIMIT
    h1 = h2 = direct = 0.0
    ast = a - delta
    for k, za, zb in harm:
        sn, cs = _sin(k * y), _cos(k * y)
        s0, c0 = za * sn - zb * cs, za * cs + zb * sn
        z = k * a
        jz, jo = float(j0(z)), float(j1(z))
        if small:
            j1oz = jo / z if z > 1e-8 else 0.5
            h1 += k * k * a * (jz * c0 + jo * s0)
            h2 += (k * k * (jz * c0 + jo * s0)
                   - k ** 3 * a * (2 * jo * c0 - (2 * jz - j1oz) * s0))
        else:
            sn, cs = _sin(k * (y + delta)), _cos(k * (y + delta))
            c1 = za * cs + zb * sn
            direct += k * (a * jo * c0 - ast * float(j1(k * ast)) * c1)
    diff = -(delta * -h1 + 0.5 * delta * delta * h2) if small else direct
    return mu / comp * (delta * (2 * a - delta) / (2 * big_r) + diff)
