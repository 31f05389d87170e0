r"""Contact filters and the filter solution of the corrugation problem (Nielsen Sec. 4.5).

The Remington filter (4.113) and Hempelmann's modified filter (4.114) reduce the surface to an
equivalent curvature, ``R_eqv = R - (R k)^2 (Z_A cos kX + Z_B sin kX)`` (4.116), filtered, and
insert it in Hertz and Carter. This gives ``a_F``, ``a_F*``, ``T_F`` (4.117)-(4.119) and, with the
wear "concentrated in the centre of the slip zone", ``W_F`` (4.123)-(4.126); the stability limit
``W_F1 = 0`` is ``a0/L = 1/(4 r_a0)`` (4.127).

Same conventions as :mod:`railcontact.corrugation` (rolling +X, ``Q_A + i Q_B = c (Z_A + i Z_B)``,
the thesis' quadrature coefficients are the negatives of ours).

Errata:

* (4.119) prints ``+ k^2 R r(1 - r) [...] F_R``; Carter (2.53) with (4.117)-(4.118) gives
  ``T_F = mu N [1 - r^2 - k^2 R r (1 - r) (Z_A cos kX + Z_B sin kX) F_R]`` (on a crest the
  patch shrinks, r grows, T falls). The printed (4.125)-(4.126) follow from the corrected sign.
  Verified in the tests by finite differences of Carter's T with the equivalent radius.

References
----------
.. [1] J.B. Nielsen, New Developments in the Theory of Wheel/Rail Contact Mechanics,
   IMM-PHD-1998-51, DTU, 1998, Sec. 4.5, Eqs. (4.113)-(4.127).
.. [2] P.J. Remington, Wheel/rail rolling noise: theoretical analysis, J. Acoust. Soc. Am. 81
   (1987) (thesis ref. [60]).
.. [3] K. Hempelmann, Short pitch corrugation on railway rails -- a linear model for prediction,
   VDI Fortschritt-Berichte 12/231, 1994 (thesis ref. [26]).
"""

from __future__ import annotations

import numpy as np

from ._validation import check_choice, check_range

__all__ = ["remington_filter", "hempelmann_filter", "filter_solution",
           "filter_wear_coefficients", "filter_stability_limit", "filter_half_width_error"]

_TWO_PI = 2.0 * np.pi


def _ratio(a0_over_wavelength):
    return check_range("a0_over_wavelength", a0_over_wavelength, "-", 0.0, None)


def remington_filter(a0_over_wavelength):
    r"""Remington's contact filter ``F_R = sin(2 pi a0/L) / (2 pi a0/L)``, Eq. (4.113).

    Parameters
    ----------
    a0_over_wavelength : array_like
        a0/L, >= 0. [-]

    Returns
    -------
    ndarray
        F_R (1 at a0/L = 0; negative for 1/2 < a0/L < 1, ...). [-]
    """
    beta = _TWO_PI * _ratio(a0_over_wavelength)
    return np.sinc(beta / np.pi)


def hempelmann_filter(a0_over_wavelength):
    r"""Hempelmann's modified Remington filter, Eq. (4.114).

    ``F_RM = 1 / (1 + 5.32 q^2 + 6 q^4 - 1.984 q^6)``, ``q = a0/L``.

    Parameters
    ----------
    a0_over_wavelength : array_like
        a0/L in [0, 1.2] (the polynomial's denominator vanishes near q = 1.34). [-]

    Returns
    -------
    ndarray
        F_RM in (0, 1]. [-]
    """
    q = check_range("a0_over_wavelength", a0_over_wavelength, "-", 0.0, 1.2,
                    condition="Eq. (4.114) is a fit; its denominator vanishes near 1.34")
    return 1.0 / (1.0 + 5.32 * q ** 2 + 6.0 * q ** 4 - 1.984 * q ** 6)


def _filter(a0_over_wavelength, contact_filter):
    check_choice("contact_filter", contact_filter, ("remington", "hempelmann"))
    if contact_filter == "remington":
        return remington_filter(a0_over_wavelength)
    return hempelmann_filter(a0_over_wavelength)


def filter_solution(a0_over_wavelength, stick_ratio, contact_filter="remington"):
    r"""Filter solution: linear coefficients of a_F, a_F*, T_F, Eqs. (4.117)-(4.119).

    Parameters
    ----------
    a0_over_wavelength : array_like
        a0/L, >= 0. [-]
    stick_ratio : array_like
        r_a0 in [0, 1]. [-]
    contact_filter : {"remington", "hempelmann"}
        Filter applied to the curvature.

    Returns
    -------
    half_width, stick_half_width : ndarray
        ``c_aF/(k R) = -(k a0/2) F`` and ``c_aF*/(k R) = (k a0/2)(1 - 2 r) F`` (real: no phase
        shift, Delta = 0). [-]
    tangential_force : ndarray
        ``c_TF`` in units of ``mu pi E/(4(1-nu^2))`` (as :func:`railcontact.corrugation.
        tangential_force_response`): ``-(k a0)^2 r (1 - r) F / 2`` (corrected sign, see module
        docstring). [-]
    """
    beta = _TWO_PI * _ratio(a0_over_wavelength)
    r = check_range("stick_ratio", stick_ratio, "-", 0.0, 1.0)
    f = _filter(a0_over_wavelength, contact_filter)
    # erratum: (4.119) as printed has "+ k^2 R r(1-r)"; the minus sign follows from (2.53) with
    # (4.117)-(4.118), verified by finite differences of Carter's force in test_filters.py.
    return -0.5 * beta * f, 0.5 * beta * (1 - 2 * r) * f, -0.5 * beta ** 2 * r * (1 - r) * f


def filter_wear_coefficients(a0_over_wavelength, stick_ratio, contact_filter="remington"):
    r"""Filter wear coefficients ``w_F = (W_F1 + i W_F2) a0/(K mu^2 N)``, Eqs. (4.123)-(4.126).

    Wear ``K |T_F xi|`` laid at the centre of the slip zone (a* behind the axis):
    ``W_F1 = -K mu^2 N k^2 a0 r (1-r)^2 cos(k a0*) F``, and ``W_F2 = +K mu^2 N k^2 a0 r (1-r)^2
    sin(k a0*) F`` in our orientation (the thesis' (4.126) has the minus sign of its mirrored
    orientation).

    Parameters
    ----------
    a0_over_wavelength : array_like
        a0/L, >= 0. [-]
    stick_ratio : array_like
        r_a0 in [0, 1]. [-]
    contact_filter : {"remington", "hempelmann"}

    Returns
    -------
    ndarray of complex
        ``w_F``. [-]
    """
    beta = _TWO_PI * _ratio(a0_over_wavelength)
    r = check_range("stick_ratio", stick_ratio, "-", 0.0, 1.0)
    f = _filter(a0_over_wavelength, contact_filter)
    return -beta ** 2 * r * (1 - r) ** 2 * f * np.exp(-1j * beta * r)


def filter_stability_limit(stick_ratio):
    r"""Stability limit of the filter solution, ``a0/L = 1/(4 r_a0)`` (4.127).

    Parameters
    ----------
    stick_ratio : array_like
        r_a0 in (0, 1]. [-]

    Returns
    -------
    ndarray
        a0/L at which ``cos(k a0*) = 0`` (first zero): amplifying for smaller a0/L (longer
        waves, while ``F_R > 0``), levelling above. [-]
    """
    r = check_range("stick_ratio", stick_ratio, "-", 0.0, 1.0, lower_closed=False)
    return 0.25 / r


def filter_half_width_error(a0_over_wavelength):
    r"""Relative error of the filtered half-width amplitude, ``1 - a^_F / a^``, exact and (4.120).

    ``a^_F / a^ = sin(k a0) / (2 J1(k a0))``; (4.120) is its expansion
    ``(pi^2/6)(a0/L)^2 + O((a0/L)^4)``.

    Parameters
    ----------
    a0_over_wavelength : array_like
        a0/L, > 0. [-]

    Returns
    -------
    exact, series : ndarray
        ``1 - sin(k a0)/(2 J1(k a0))`` and ``pi^2/6 (a0/L)^2``. [-]
    """
    from scipy.special import j1

    q = check_range("a0_over_wavelength", a0_over_wavelength, "-", 0.0, None,
                    lower_closed=False)
    beta = _TWO_PI * q
    return 1.0 - np.sin(beta) / (2.0 * j1(beta)), np.pi ** 2 / 6.0 * q * q
