r"""Evolution of a corrugated rail over many passages (Nielsen Sec. 4.4, Eqs. (4.99)-(4.112)).

Each passage removes the wear W(X) (4.99). One harmonic maps linearly (4.103):
``Z^{n+1} = (1 - W1 - i W2) Z^n`` with ``Z = Z_A + i Z_B``, so after ``n`` passages
``Z^n = (1 - W1 - i W2)^n Z^0`` -- a closed form, evaluated vectorised (no loop over passages).
Harmonics do not interact in the linear theory (superposition, Sec. 4.4).

* Growth per passage: ``|Z^{n+1}|/|Z^n| = sqrt((1 - W1)^2 + W2^2)``, which the thesis writes
  to first order as ``sqrt(1 - 2 W1)`` (4.104)-(4.105). ``W1 > 0`` levels, ``W1 < 0`` amplifies
  (4.106). :func:`growth_factor` returns ``1 - 2 W1`` (the quantity of Figs. 4.10-4.14).
* Phase: ``arg Z`` changes by ``-atan(W2/(1 - W1)) ~ -W2`` per passage (4.111): ``W2 > 0``
  decreases the phase (4.112). With ``Z2 = |Z| cos(kX - arg Z)`` the pattern then travels by
  ``-W2/k`` per passage, i.e. **against the rolling direction** (+X) for ``W2 > 0``.

``W1 + i W2 = wear_number * w``, ``wear_number = K mu^2 N / a0`` and ``w`` from
:func:`railcontact.wear.wear_coefficients`. The default wear model is ``"material_point"``,
which levels every wave length (see ``docs/wear_finding.md``); the thesis' amplifying band and
characteristic wave length appear only with ``wear_model="nielsen1998"`` or
``"patch_coordinate"``.

References
----------
.. [1] J.B. Nielsen, New Developments in the Theory of Wheel/Rail Contact Mechanics,
   IMM-PHD-1998-51, DTU, 1998, Sec. 4.4, Eqs. (4.99)-(4.112).
"""

from __future__ import annotations

import numpy as np

from ._validation import check_range
from .wear import DEFAULT_WEAR_MODEL, wear_coefficients

__all__ = ["wear_number", "growth_factor", "evolve_harmonics", "mixed_traffic_factor",
           "white_noise_surface", "stability_boundary", "characteristic_wavelength",
           "phase_change_boundary", "surface_profile"]


def wear_number(wear_coefficient, friction_coefficient, normal_load, a0):
    r"""Dimensionless wear number ``K mu^2 N / a0`` that scales W1 and W2.

    Parameters
    ----------
    wear_coefficient : array_like
        K of (4.74), >= 0 (steel ~ 7.58e-6 by the thesis' units). [m^2/N]
    friction_coefficient : array_like
        mu, >= 0. [-]
    normal_load : array_like
        N per unit length, >= 0. [N/m]
    a0 : array_like
        Hertz half-width, > 0. [m]

    Returns
    -------
    ndarray
        ``K mu^2 N / a0``. [-]
    """
    kw = check_range("wear_coefficient", wear_coefficient, "m^2/N", 0.0, None)
    mu = check_range("friction_coefficient", friction_coefficient, "-", 0.0, None)
    n = check_range("normal_load", normal_load, "N/m", 0.0, None)
    a0 = check_range("a0", a0, "m", 0.0, None, lower_closed=False)
    return wear_number_unchecked(kw, mu, n, a0)


def wear_number_unchecked(wear_coefficient, friction_coefficient, normal_load, a0):
    r""":func:`wear_number`'s formula ``K mu^2 N / a0`` without its range checks, for floats or
    arrays (:func:`wear_number` checks and calls it; the FMU's wear effect calls it on checked
    floats). [-]"""
    mu = friction_coefficient
    return wear_coefficient * mu * mu * normal_load / a0


def growth_factor(a0_over_wavelength, stick_ratio, wear_number, wear_model=DEFAULT_WEAR_MODEL):
    r"""Wear coefficient ``1 - 2 W1`` of (4.104)-(4.106): > 1 amplifies, < 1 levels.

    Parameters
    ----------
    a0_over_wavelength : array_like
        a0/L, > 0. [-]
    stick_ratio : array_like
        r_a0 in [0, 1]. [-]
    wear_number : array_like
        ``K mu^2 N / a0`` (:func:`wear_number`), >= 0. [-]
    wear_model : str
        See :func:`railcontact.wear.wear_coefficients`.

    Returns
    -------
    ndarray
        ``1 - 2 W1``. [-]
    """
    eps = check_range("wear_number", wear_number, "-", 0.0, None)
    return 1.0 - 2.0 * eps * np.real(wear_coefficients(a0_over_wavelength, stick_ratio,
                                                       wear_model))


def evolve_harmonics(amplitudes_cos, amplitudes_sin, w1, w2, n_passages):
    r"""Surface harmonics after ``n_passages`` passages, closed form of the map (4.103).

    ``Z_A^n + i Z_B^n = (1 - W1 - i W2)^n (Z_A^0 + i Z_B^0)``.

    Parameters
    ----------
    amplitudes_cos, amplitudes_sin : array_like, shape (M,)
        Initial Z_A, Z_B. [m]
    w1, w2 : array_like, shape (M,)
        W1, W2 per harmonic (dimensionless, ``|W1 + i W2| < 1``). [-]
    n_passages : array_like of int, shape (P,)
        Passage counts at which to return the surface, >= 0. [-]

    Returns
    -------
    amplitudes_cos, amplitudes_sin : ndarray, shape (P, M)
        Z_A^n, Z_B^n. [m]
    """
    za = check_range("amplitudes_cos", amplitudes_cos, "m")
    zb = check_range("amplitudes_sin", amplitudes_sin, "m")
    w1 = check_range("w1", w1, "-", -1.0, 1.0)
    w2 = check_range("w2", w2, "-", -1.0, 1.0)
    n = check_range("n_passages", n_passages, "-", 0.0, None)
    n = np.atleast_1d(n)
    factor = 1.0 - w1 - 1j * w2
    # (1 - W)^n through logs: exact, vectorised, no overflow of intermediate powers
    zn = np.exp(np.multiply.outer(n, np.log(factor + 0j))) * (za + 1j * zb)
    return zn.real, zn.imag


def mixed_traffic_factor(w1, w2, passages_per_vehicle):
    r"""Mixed traffic (4.110): complex factor ``prod_j (1 - W1_j - i W2_j)^{n_j}`` per harmonic.

    Parameters
    ----------
    w1, w2 : array_like, shape (J, M)
        W1, W2 of vehicle type j (its own a0, r_a0, N) for every harmonic m. [-]
    passages_per_vehicle : array_like, shape (J,)
        Number of passages of each vehicle type, >= 0. [-]

    Returns
    -------
    ndarray of complex, shape (M,)
        Multiply ``Z_A + i Z_B`` by it; its modulus is the amplitude ratio (4.110) (the thesis
        writes it to first order as ``prod (1 - 2 W1_j)^{1/2}``). The order of the passages does
        not matter in the linear theory. [-]
    """
    w1 = np.atleast_2d(check_range("w1", w1, "-", -1.0, 1.0))
    w2 = np.atleast_2d(check_range("w2", w2, "-", -1.0, 1.0))
    n = check_range("passages_per_vehicle", passages_per_vehicle, "-", 0.0, None)
    return np.exp(np.sum(np.asarray(n)[:, None] * np.log(1.0 - w1 - 1j * w2 + 0j), axis=0))


def white_noise_surface(n_harmonics, wavelength_min, wavelength_max, rms, seed=0):
    r"""A white-noise rail surface: ``n_harmonics`` equally spaced wave numbers, random phases.

    Parameters
    ----------
    n_harmonics : int
        Number of harmonics M, >= 1. [-]
    wavelength_min, wavelength_max : float
        Range of wave lengths, 0 < min < max. [m]
    rms : float
        Root-mean-square surface height, >= 0. [m]
    seed : int
        Seed of ``numpy.random.default_rng`` (reproducible). [-]

    Returns
    -------
    wavelengths, amplitudes_cos, amplitudes_sin : ndarray, shape (M,)
        Equal amplitudes (flat spectrum), uniformly random phases. [m]
    """
    m = int(check_range("n_harmonics", n_harmonics, "-", 1, None))
    lmin = float(check_range("wavelength_min", wavelength_min, "m", 0.0, None,
                             lower_closed=False))
    lmax = float(check_range("wavelength_max", wavelength_max, "m", lmin, None,
                             lower_closed=False, condition="wavelength_max > wavelength_min"))
    rms = float(check_range("rms", rms, "m", 0.0, None))
    k = np.linspace(2 * np.pi / lmax, 2 * np.pi / lmin, m)
    rng = np.random.default_rng(seed)
    phase = rng.uniform(0.0, 2 * np.pi, m)
    amp = rms * np.sqrt(2.0 / m)
    return 2 * np.pi / k, amp * np.cos(phase), amp * np.sin(phase)


def surface_profile(x, wavelengths, amplitudes_cos, amplitudes_sin):
    r"""Evaluate the surface (4.1) ``sum Z_A cos(2 pi x/L) + Z_B sin(2 pi x/L)``.

    Parameters
    ----------
    x : array_like
        Rail positions. [m]
    wavelengths, amplitudes_cos, amplitudes_sin : array_like, shape (..., M)
        Harmonics (leading axes broadcast, e.g. one row per passage count). [m]

    Returns
    -------
    ndarray, shape (..., len(x))
        Surface height. [m]
    """
    x = check_range("x", x, "m")
    lam = check_range("wavelengths", wavelengths, "m", 0.0, None, lower_closed=False)
    za = np.asarray(amplitudes_cos, float)
    zb = np.asarray(amplitudes_sin, float)
    arg = 2 * np.pi * x[:, None] / lam[..., None, :]
    return np.sum(za[..., None, :] * np.cos(arg) + zb[..., None, :] * np.sin(arg), -1)


def _scan(fun, r, l_min, l_max, n_scan):
    la = np.geomspace(l_min, l_max, n_scan)
    return la, fun(1.0 / la[None, :], np.asarray(r, float)[..., None])


def _last_sign_change(fun, r, l_min, l_max, n_scan):
    """L/a0 of the largest sign change of fun(a0/L, r) in [l_min, l_max]; inf if none."""
    la, vals = _scan(fun, r, l_min, l_max, n_scan)
    change = np.diff(np.sign(vals), axis=-1) != 0
    ok = change.any(-1)
    idx = np.where(ok, n_scan - 2 - np.argmax(change[..., ::-1], -1), 0)
    lo_s, hi_s = la[idx], la[idx + 1]
    f_lo = fun(1.0 / lo_s, r)
    for _ in range(50):
        mid = np.sqrt(lo_s * hi_s)
        f_mid = fun(1.0 / mid, r)
        left = np.sign(f_mid) == np.sign(f_lo)
        lo_s = np.where(left, mid, lo_s)
        f_lo = np.where(left, f_mid, f_lo)
        hi_s = np.where(left, hi_s, mid)
    return np.where(ok, np.sqrt(lo_s * hi_s), np.inf)


def stability_boundary(stick_ratio, wear_model=DEFAULT_WEAR_MODEL, *, wavelength_ratio_min=1.0,
                       wavelength_ratio_max=40.0, n_scan=400):
    r"""Limit between levelling and amplifying zones, W1 = 0 (Figs. 4.11 and 4.21).

    Parameters
    ----------
    stick_ratio : array_like
        r_a0 in (0, 1). [-]
    wear_model : str
        See :func:`railcontact.wear.wear_coefficients`.
    wavelength_ratio_min, wavelength_ratio_max : float
        Range of L/a0 searched. [-]
    n_scan : int
        Scan points (log-spaced) before refining each sign change by bisection. [-]

    Returns
    -------
    ndarray
        L/a0 of the **largest** sign change of W1 in the range (above it: amplification up to
        the longest waves for the thesis' models); ``+inf`` where W1 never changes sign in the
        range (e.g. ``"material_point"``: every wave length is levelled). [-]
    """
    r = check_range("stick_ratio", stick_ratio, "-", 0.0, 1.0, lower_closed=False,
                    upper_closed=False)

    def w1(q, rr):
        return np.real(wear_coefficients(q, rr, wear_model))

    return _last_sign_change(w1, r, wavelength_ratio_min, wavelength_ratio_max, n_scan)


def characteristic_wavelength(stick_ratio, wear_model=DEFAULT_WEAR_MODEL, *,
                              wavelength_ratio_min=2.0, wavelength_ratio_max=40.0, n_scan=800):
    r"""Characteristic wave length: L/a0 of the local maximum of ``1 - 2 W1`` (Fig. 4.14).

    The thesis' line marks the local maximum of ``1 - 2 W1`` (minimum of W1) in the long-wave
    amplifying band; where W1 has several local minima in the range (the thesis' model also
    amplifies very short waves, L/a0 < 2.3, for r_a0 >= 0.8) the one at the largest L/a0 is
    returned.

    Parameters
    ----------
    stick_ratio : array_like
        r_a0 in (0, 1). [-]
    wear_model : str
        See :func:`railcontact.wear.wear_coefficients`.
    wavelength_ratio_min, wavelength_ratio_max : float
        Range of L/a0 searched (default 2 to 40: below L/a0 = 2 the patch spans more than half a
        wave length, outside the range of the thesis' figures). [-]
    n_scan : int
        Log-spaced scan points, refined by a parabola through the best three. [-]

    Returns
    -------
    wavelength_ratio : ndarray
        L/a0 of that local minimum of W1 (of the global minimum if there is no interior one). [-]
    w1_normalised : ndarray
        ``W1 a0 / (K mu^2 N)`` there (negative: the wave length grows fastest; positive: every
        wave length is levelled and the "maximum" is only the slowest levelling). [-]
    interior : ndarray of bool
        True if W1 has a local minimum inside the range (a characteristic wave length); False
        if W1 is monotonic (no characteristic wave length, e.g. ``"material_point"``, whose
        W1 decreases towards 0+ for long waves). [-]
    """
    r = check_range("stick_ratio", stick_ratio, "-", 0.0, 1.0, lower_closed=False,
                    upper_closed=False)
    la, vals = _scan(lambda q, rr: np.real(wear_coefficients(q, rr, wear_model)), r,
                     wavelength_ratio_min, wavelength_ratio_max, n_scan)
    # local minima of W1 (local maxima of 1 - 2 W1); the thesis' line is the one of the
    # long-wave amplifying band, i.e. the local minimum at the largest L/a0
    local = (vals[..., 1:-1] < vals[..., :-2]) & (vals[..., 1:-1] <= vals[..., 2:])
    interior = local.any(-1)
    last = n_scan - 2 - np.argmax(local[..., ::-1], -1)
    i = np.where(interior, last, np.argmin(vals, -1))
    ic = np.clip(i, 1, n_scan - 2)
    y0 = np.take_along_axis(vals, (ic - 1)[..., None], -1)[..., 0]
    y1 = np.take_along_axis(vals, ic[..., None], -1)[..., 0]
    y2 = np.take_along_axis(vals, (ic + 1)[..., None], -1)[..., 0]
    den = y0 - 2 * y1 + y2
    off = np.where(interior & (den > 0), 0.5 * (y0 - y2) / np.where(den > 0, den, 1.0), 0.0)
    lg = np.log(la)
    step = lg[1] - lg[0]
    best = np.exp(lg[ic] + off * step)
    best = np.where(interior, best, la[i])
    wbest = np.where(interior, y1 - 0.25 * (y0 - y2) * off, np.take_along_axis(
        vals, i[..., None], -1)[..., 0])
    return best, wbest, interior


def phase_change_boundary(stick_ratio, wear_model=DEFAULT_WEAR_MODEL, *, wavelength_ratio_min=1.0,
                          wavelength_ratio_max=40.0, n_scan=400):
    r"""Limit between decreasing and increasing phase, W2 = 0 (Fig. 4.15), as L/a0.

    Same search as :func:`stability_boundary` applied to W2 (our orientation; the thesis' W2 is
    the negative, so its zero set is the same).

    Returns
    -------
    ndarray
        L/a0 of the largest sign change of W2 in the range, ``+inf`` if none. [-]
    """
    r = check_range("stick_ratio", stick_ratio, "-", 0.0, 1.0, lower_closed=False,
                    upper_closed=False)

    def w2(q, rr):
        return np.imag(wear_coefficients(q, rr, wear_model))

    return _last_sign_change(w2, r, wavelength_ratio_min, wavelength_ratio_max, n_scan)
