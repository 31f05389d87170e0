r"""Non-steady 2-D rolling with an oscillating tangential force (Nielsen 1998, Ch. 7).

Why one module of about 800 lines: it is Ch. 7 of the thesis (the transfer functions, their
closed forms and the time-domain relaxation the FMU uses), which share one normalisation.

A cylinder rolls at constant speed ``V`` and normal load ``N`` while the tangential force
oscillates. The stick zone carries a displacement field frozen in the material,
``U_x(x + V t)`` (7.5), (7.24), whose gradient is

    F'(x + V t) = mu k [U_A cos(k (x + V t)) + U_B sin(k (x + V t))],   (7.26)

with wave number ``k = 2 pi / L`` and frequency ``omega = k V``. The stick/slip problem is then
solved exactly with the polynomial approach (7.27)-(7.36): the stick half-width ``a*(t)`` and the
force ``T(t)``; linearised in the small amplitudes ``(U_A, U_B)`` they give (7.37)-(7.43). Only the
creepage needs the displacement ``u_x(x0, t)`` of a reference point ``x0`` (the stick-zone centre),
which the 2-D half-space cannot give (its datum is undefined); it is approximated by the 3-D
displacement of a long rectangle ``2a x 2b`` (``b >> a``, Appendix C) loaded by

* ``model="johnson"``: the modified Johnson stress, two uniform blocks (7.11)-(7.15);
* ``model="carter"``: Carter's two ellipses (7.16)-(7.20);

and the creepage follows from the non-steady kinematic constraint (7.10),
``xi(t) = -du/dx0 + (1/V) du(x0, t)/dt``, with ``-du/dx0`` the stick-zone creepage
``mu (a0 - a*(t)) / R`` (the gradient ``F'`` enters as its stick-zone average, as in (7.35);
this is the choice that reproduces Gross-Thebing's (7.57) at ``J0(k a0*) = 0``).

Package frame and conventions
-----------------------------
Leading edge ``x = +a0``, stick zone ``[a0 - 2a*, a0]``, material moving in ``-x`` (as in
:mod:`railcontact.carter`; the thesis draws the mirror image, which conjugates every phase). The
oscillating quantities are written ``X(t) = X_A cos(omega t) + X_B sin(omega t)`` with
``{X_A, X_B} = [[X_1, -X_2], [X_2, X_1]] {U_A, U_B}`` (7.39), (7.45), i.e. the complex amplitude is
``X_hat = (X_1 - i X_2)(U_A - i U_B)`` for ``X(t) = Re(X_hat exp(i omega t))`` -- the convention of
Gross-Thebing's (7.55)-(7.56). Forces in this module are the *magnitude-frame* force ``T`` of the
thesis (positive for positive creepage, ``T = mu N (1 - (a*/a0)^2)`` steady); the force on the
wheel in the package convention is ``-T`` (it opposes the creepage), so the transfer function of
the wheel force is ``-H``.

Derivation used (and checked in ``tests/test_nonsteady.py``)
-----------------------------------------------------------
With ``theta = k (a0 - a0*)``, ``C = mu pi E / (4 (1 - nu^2))``, ``Z = U_A - i U_B`` and Bessel
functions of ``k a0*``:

* ``a*_hat = k R J0 Z e^{i theta}`` -> ``a_1 = k R J0 cos(theta)``, ``a_2 = -k R J0 sin(theta)``;
* ``T_hat = -C k a0* (J0 + i J1) Z e^{i theta}``;
* ``xi_hat = k Z e^{i theta} [-mu J0 + i k R J0 D_a - i k D_T C a0* (J0 + i J1)]`` with
  ``D_a = du/da* = mu a0* / (2 R)`` and ``D_T = du/dT = (4 (1 - nu^2) / (pi E)) Lambda``,
  ``Lambda_johnson = 1/(1 - nu) + ln(2 b / a0*)`` (7.15), ``Lambda_carter = (1 + nu)/(2 (1 - nu))
  + ln(4 b / a0*)`` (7.20); so

      H = T_hat / xi_hat / (a0* pi E / (4 (1 - nu^2)))
        = 1 / [J0 (1 - i k a0*/2) / (J0 + i J1) + i k a0* Lambda],

  which equals Gross-Thebing's (7.57) (with ``a0 -> a0*``) exactly when ``J0(k a0*) = 0`` and
  as ``k a0* -> 0`` (both -> 1, Carter's quasi-static slope), as the thesis states.

Errata of the printed equations (the structure (7.37)-(7.45) is confirmed):

* (7.47)-(7.48) are dimensionally inconsistent: ``mu (k a0)^2`` must be ``mu k^2 a0`` (a creepage
  per metre of U). With that fix the printed coefficients have the a*-term ``-J0`` where the
  derivation above gives ``-J0/2`` (the factor ``4(1-nu^2)N/(pi E) = a0^2/(2R)``), and their phase
  is that of the mirrored frame with the thesis' sign of the force, ``pi - phase``. Both variants
  are available (``variant="printed"``) and agree with (7.57) at ``J0 = 0`` and ``k a0 -> 0`` in
  amplitude.
* (7.35) as printed has ``sin``/``cos`` and the sign of ``Delta*`` of the corrugation case (4.57);
  the solvability of (7.27) gives ``xi0 = mu (a0 - a*)/R + mu k J0(k a*) [U_A cos(k x_c + omega t)
  + U_B sin(k x_c + omega t)]`` in the package frame (``x_c = a0 - a*``), checked by quadrature.
* (7.52) is the gradient ``U_x'``, not ``U_x`` (compare (7.24) and (7.26)).

Large ``a0/L``: the linear theory holds for any ``k a0*`` as long as ``k^2 R |U| << 1`` (the
amplitude of ``a*`` is ``k R J0 |U|`` and must stay below ``a0*`` and ``a0 - a0*``); ``H`` decays
like ``1 / (k a0* Lambda)``. The 3-D displacement approximation needs ``b >> a0*``:
``pseudo_width_ratio = b / a0 >= 2`` is required and a value below 5 is poor.

Time-domain relaxation model (for co-simulation)
------------------------------------------------
The theory above is in the frequency domain; a co-simulation step needs a law with state. Its
low-frequency expansion (``x = k a0*``, ``J0 = 1 - x^2/4 + ...``, ``J1 = x/2 - x^3/16 + ...``,
``J0/(J0 + i J1) = 1 - i x/2 - x^2/4 + ...``) is

    1/H = J0 (1 - i x/2) / (J0 + i J1) + i x Lambda = 1 + i k sigma - x^2/2 + O(x^3),
    sigma = a0* (Lambda(r_a0) - 1),

(``tests/test_nonsteady.py`` checks sigma and the ``-x^2/2`` by a complex polynomial fit of
:func:`nonsteady_transfer_function_normalised` at a0/L = 1e-5 ... 1e-4, to 1e-7; note
``Lambda - 1``, not ``Lambda + 1``: the two ``-i x/2`` of the stick-zone factor and of
``1 - i x/2`` against the ``+i x Lambda`` of the reference-point displacement). The
first-order model with the same expansion to O(k) is the classic relaxation-length law (as for
tyres, Pacejka, *Tyre and Vehicle Dynamics*, Ch. 7): the force is the steady (Carter) force at a *relaxed creepage* ``xi_e``,

    (sigma / V) d xi_e / dt + xi_e = xi,      H_model = 1 / (1 + i k sigma)

(:func:`relaxation_length`, :func:`relaxation_transfer_function_normalised`). Because the force
is a steady force at some creepage, ``|T| <= mu N`` holds by construction, also when N and mu
change. ``sigma -> 0`` as ``r_a0 -> 0`` (full sliding has no memory) and ``sigma > 0``
otherwise (``Lambda > 1`` for every admissible nu and b/a0 >= 2).

Accuracy of the first-order model against the thesis' H (``tests/test_nonsteady.py``,
nu = 0.28, b/a0 = 20, Carter; Johnson within 3 %): ``|H_model / H - 1|`` stays below

======= ======================== ======================== ========================
r_a0     1 % for a0/L below       5 % for a0/L below       10 % for a0/L below
======= ======================== ======================== ========================
1.0      0.0246                   0.0756                   0.140
0.7      0.0357                   0.114                    0.215
0.5      0.0508                   0.169                    0.320
0.3      0.0869                   0.304                    0.585
0.1      0.277                    1.07                     2.09
======= ======================== ======================== ========================

i.e. about 1 % up to ``k a0* = 0.155``, 5 % up to ``k a0* = 0.47`` and 10 % up to
``k a0* = 0.85`` (the limit in ``k a0*`` rises slowly as r_a0 falls); the error is bounded
(below 27 % at any frequency: both decay like 1/(i k ...)). The leading error is the
``-(k a0*)^2 / 2`` that the first-order law lacks.

Time integration (:func:`relaxation_factor`, :func:`relax_creepage`,
:func:`relaxation_step`): over a communication step of length ``h`` the
input is held (sample and hold) and the step rolls ``d = V h``. For constant sigma the exact
solution is ``xi_e <- xi + (xi_e - xi) exp(-d / sigma)``: unconditionally stable, monotone (no
overshoot) for any ``d / sigma`` in [0, inf]; ``V = 0`` holds the state and ``sigma = 0`` gives
``xi_e = xi``. sigma depends on the state through ``r_a0(xi_e)``; with ``u = xi - xi_e`` the
exact solution is ``u_end = u_start exp(-integral_0^d dx / sigma(xi_e(x)))``. The step uses
the trapezoidal rule for that integral in a predictor-corrector (Heun) form: sigma at the start
state, a predictor with it, sigma at the predicted end state, then the exponential with
``d (1/sigma_start + 1/sigma_end) / 2``. This is second order in the step (against first order
for sigma frozen at the start) and keeps every property above, because the exponent is still
``-d / sigma_eff`` with sigma_eff (the harmonic mean of two values taken on the path) between
the smallest and largest sigma met on the path, as is the exact one. Hence the error of one
step is bounded for *any* step size (:func:`relaxation_step_error_bound`):
``|xi_e - xi_e,exact| <= |xi - xi_e,start| (rho^(rho/(1-rho)) - rho^(1/(1-rho)))`` with
``rho = sigma_min / sigma_max`` on the path (0.25 |...| at rho = 1/2). Where sigma changes by
more than 25 % on one step (a large creepage jump in a step of the order sigma/V) the step is
split into sub-steps (:func:`relaxation_step`); measured against ``solve_ivp`` (rtol 1e-12)
for jumps across most of the creep curve (0 -> 0.8, 0.2 -> 0.95, 0.9 -> 0.1 and -0.5 -> 0.6 of
the saturation creepage), the error of one step of any length is then 0.4-1.5 % of the jump
(up to 19 % without sub-steps), far below the bound; with steps short against sigma/V the
error falls like h^2.

References
----------
.. [1] J.B. Nielsen, New Developments in the Theory of Wheel/Rail Contact Mechanics,
   IMM-PHD-1998-51, DTU, 1998, Ch. 7 and Sec. 4.2.3.
.. [2] G. Gross-Thebing, Frequency-dependent creep coefficients for three-dimensional rolling
   contact problems, Vehicle System Dynamics 18 (1989) 359-374 (ref. [23] of [1]).
.. [3] K.L. Johnson, Contact Mechanics, 1985, Sec. 8.4 (transient rolling).
.. [4] H.B. Pacejka, Tyre and Vehicle Dynamics, 2nd ed., Butterworth-Heinemann, 2006, Ch. 7
   (relaxation length, first-order transient model).
"""

from __future__ import annotations

from dataclasses import dataclass

import math

import numpy as np
from scipy.special import j0, j1, xlogy

from ._validation import check_choice, check_range
from .hertz import hertz_2d

__all__ = [
    "NonSteadyCoefficients", "nonsteady_coefficients", "nonsteady_time_response",
    "nonsteady_transfer_function_normalised", "nonsteady_amplitude_phase_normalised",
    "gross_thebing_transfer_function_normalised", "displacement_factor",
    "relaxation_length", "relaxation_length_function", "relaxation_transfer_function_normalised",
    "relaxation_factor", "relax_creepage", "relaxation_step", "relaxation_step_error_bound",
]

_MODELS = ("carter", "johnson")
_LN2 = math.log(2.0)
_VARIANTS = ("derived", "printed")


def displacement_factor(model, poisson_ratio, pseudo_width_ratio, stick_ratio=1.0):
    r"""``Lambda = g(0, a0*)`` of (7.15) (Johnson) or (7.20) (Carter), with ``b, a`` over ``a0``.

    ``u(x0) = (4 (1 - nu^2) / (pi E)) F g`` is the displacement at the centre of a ``2a x 2b``
    rectangle (``b >> a``) loaded by a force per unit length ``F`` distributed uniformly
    (Johnson) or elliptically (Carter) over ``|x| < a``; with ``a -> a0*``:
    ``Lambda_johnson = 1/(1 - nu) + ln(2 b / a0*)``,
    ``Lambda_carter = (1 + nu) / (2 (1 - nu)) + ln(4 b / a0*)`` (length unit of the log: a0).

    Parameters
    ----------
    model : {"carter", "johnson"}
    poisson_ratio : array_like
        Poisson's ratio, in [0, 0.5). [-]
    pseudo_width_ratio : array_like
        b / a0, >= 2. [-]
    stick_ratio : array_like
        r_a0 = a0*/a0, in (0, 1]. [-]

    Returns
    -------
    ndarray
        Lambda. [-]
    """
    check_choice("model", model, _MODELS)
    nu = check_range("poisson_ratio", poisson_ratio, "-", 0.0, 0.5, upper_closed=False)
    bq = check_range("pseudo_width_ratio", pseudo_width_ratio, "-", 2.0, None,
                     condition="Eq. (7.14)-(7.20) assume b >> a0")
    r = check_range("stick_ratio", stick_ratio, "-", 0.0, 1.0, lower_closed=False)
    if model == "johnson":
        return (1.0 / (1.0 - nu) + np.log(2.0 * bq / r))[()]
    return ((1.0 + nu) / (2.0 * (1.0 - nu)) + np.log(4.0 * bq / r))[()]


def _check_common(wave_ratio, stick_ratio, poisson_ratio, pseudo_width_ratio, model, variant):
    ka = 2.0 * np.pi * check_range("wave_ratio", wave_ratio, "-", 0.0, None)
    r = check_range("stick_ratio", stick_ratio, "-", 0.0, 1.0, lower_closed=False)
    check_choice("model", model, _MODELS)
    check_choice("variant", variant, _VARIANTS)
    lam = displacement_factor(model, poisson_ratio, pseudo_width_ratio, r)
    return ka, r, lam


def nonsteady_transfer_function_normalised(wave_ratio, stick_ratio, *, poisson_ratio=0.28,
                                           pseudo_width_ratio=20.0, model="carter",
                                           variant="derived"):
    r"""Complex ratio of force to creepage amplitudes, normalised (Sec. 7.2, Figs. 7.2-7.3).

    ``H = (T_hat / xi_hat) / (a0* pi E / (4 (1 - nu^2)))`` for ``T(t) = Re(T_hat e^{i omega t})``,
    ``xi(t) = Re(xi_hat e^{i omega t})`` (magnitude-frame force; the wheel force is ``-T``).
    ``|H|`` is the amplitude ratio (7.53) and ``angle(H)`` the phase difference (7.54).
    ``H -> 1`` as ``a0/L -> 0`` (Carter's quasi-static slope ``pi E a0* / (4 (1 - nu^2))``).
    Vectorised over (wave_ratio, stick_ratio) for table building.

    Parameters
    ----------
    wave_ratio : array_like
        a0 / L, contact half-width over the wave length of the oscillation, >= 0. [-]
    stick_ratio : array_like
        r_a0 = a0*/a0 of the steady state, in (0, 1]. [-]
    poisson_ratio : float, optional
        Poisson's ratio, in [0, 0.5). [-]
    pseudo_width_ratio : float, optional
        b / a0 of the 3-D rectangle used for u_x(x0, t), >= 2 (thesis: 20). [-]
    model : {"carter", "johnson"}, optional
        Stress used for u_x(x0, t): Carter's ellipses (7.16)-(7.20) or the modified Johnson blocks
        (7.11)-(7.15). [-]
    variant : {"derived", "printed"}, optional
        ``"derived"``: the derivation in the module docstring. ``"printed"``: the thesis'
        (7.47)-(7.48) (Johnson, dimension fixed) or (7.50)-(7.51) (Carter) with (7.40)-(7.43), in
        the thesis' own frame and sign (its phase is ``pi - phase`` of the derived one at low
        frequency). [-]

    Returns
    -------
    ndarray of complex
        H. [-]
    """
    ka, r, lam = _check_common(wave_ratio, stick_ratio, poisson_ratio, pseudo_width_ratio,
                               model, variant)
    ks = ka * r                                   # k a0*
    b0, b1 = j0(ks), j1(ks)
    if variant == "derived":
        den = b0 * (1.0 - 0.5j * ks) / (b0 + 1j * b1) + 1j * ks * lam
        return (1.0 / den)[()]
    # printed: a0 = R = 1, mu = C = 1 (so 4(1-nu^2)/(pi E) = 1); per unit U_A
    if model == "johnson":
        # erratum: (7.47)-(7.48) print mu (k a0)^2; dimensionally mu k^2 a0 (a0* = a0 assumed)
        t1, t2 = -ks * b1, ks * b0
        x1 = ka * ks * (b0 * lam - b0)
        x2 = ka * ks * (b1 * lam - np.divide(b0, ks, out=np.zeros_like(ks), where=ks > 0))
        x2 = np.where(ks > 0, x2, -ka)            # limit k -> 0 of k^2 a0 J0 / (k a0*)
    else:
        th = ka * (r - 1.0)                       # k (a0* - a0), thesis frame
        a1 = -ka * b0 * np.sin(th)                # (7.40) / R
        a2 = -ka * b0 * np.cos(th)                # (7.41) / R
        kk = np.where(ka > 0, ka, 1.0)
        t1 = ka * r * (-a1 / kk - b1 * np.cos(th))     # (7.42) / C
        t2 = ka * r * (-a2 / kk + b1 * np.sin(th))     # (7.43) / C
        x1 = (a1 + ka * r * a2) + ka * t2 * lam        # (7.50)
        x2 = (a2 - ka * r * a1) - ka * t1 * lam        # (7.51)
    # ratio of (T1 - i T2) / (xi1 - i xi2), normalised by a0* (C/mu = 1)
    with np.errstate(invalid="ignore", divide="ignore"):
        h = (t1 - 1j * t2) / ((x1 - 1j * x2) * r)
    # k -> 0: both vanish linearly; the limit is the quasi-static slope with the thesis' sign
    return np.where(ka > 0, h, -1.0 + 0j)[()]


def nonsteady_amplitude_phase_normalised(wave_ratio, stick_ratio, **kwargs):
    r"""Amplitude ratio (7.53) and phase difference (7.54), normalised, vectorised.

    Parameters
    ----------
    wave_ratio, stick_ratio, **kwargs
        As in :func:`nonsteady_transfer_function_normalised`.

    Returns
    -------
    amplitude_ratio : ndarray
        ``|T_hat / xi_hat| / (a0* pi E / (4 (1 - nu^2)))``. [-]
    phase : ndarray
        ``phi_T - phi_xi`` in (-pi, pi]; negative: the force lags the creepage. [rad]
    """
    h = np.asarray(nonsteady_transfer_function_normalised(wave_ratio, stick_ratio, **kwargs))
    return np.abs(h)[()], np.angle(h)[()]


def gross_thebing_transfer_function_normalised(wave_ratio, *, poisson_ratio=0.28,
                                               pseudo_width_ratio=20.0, stick_ratio=1.0):
    r"""Gross-Thebing's full-stick transfer function (7.57), normalised by ``pi E a / (4(1-nu^2))``.

    ``H_GT = 1 / [J0(ka) / (J0(ka) + i J1(ka)) + i k a (1/(1 - nu) + ln(2b/a))]`` with ``a = a0``,
    or ``a = a0*`` (``stick_ratio < 1``) as in the thesis' Fig. 7.3.

    Parameters
    ----------
    wave_ratio : array_like
        a0 / L, >= 0. [-]
    poisson_ratio : float, optional
        In [0, 0.5). [-]
    pseudo_width_ratio : float, optional
        b / a0, >= 2. [-]
    stick_ratio : array_like, optional
        a / a0 used in place of a0, in (0, 1]. [-]

    Returns
    -------
    ndarray of complex
        H_GT. [-]
    """
    ka, r, lam = _check_common(wave_ratio, stick_ratio, poisson_ratio, pseudo_width_ratio,
                               "johnson", "derived")
    ks = ka * r
    b0, b1 = j0(ks), j1(ks)
    return (1.0 / (b0 / (b0 + 1j * b1) + 1j * ks * lam))[()]


@dataclass
class NonSteadyCoefficients:
    """Linearised non-steady coefficients (7.37)-(7.45) in the package frame, per metre of U.

    Attributes
    ----------
    contact_half_width : float
        a0. [m]
    stick_half_width : float
        a0* of the steady state. [m]
    creepage_steady : float
        xi0 = mu (a0 - a0*) / R (magnitude frame, >= 0), (7.49). [-]
    force_steady : float
        T0 = mu N (1 - r_a0^2) (magnitude frame). [N/m]
    stick_1, stick_2 : float
        a*_1, a*_2 of (7.39)-(7.41): a*(t) - a0* = Re((a_1 - i a_2)(U_A - i U_B) e^{i w t}). [-]
    force_1, force_2 : float
        T_1, T_2 of (7.39), (7.42)-(7.43). [N/m per m]
    creepage_1, creepage_2 : float
        xi_1, xi_2 of (7.45). [1/m]
    wavenumber : float
        k = 2 pi / L. [1/m]
    """

    contact_half_width: float
    stick_half_width: float
    creepage_steady: float
    force_steady: float
    stick_1: float
    stick_2: float
    force_1: float
    force_2: float
    creepage_1: float
    creepage_2: float
    wavenumber: float


def nonsteady_coefficients(wavenumber, normal_load, radius, youngs_modulus, poisson_ratio,
                           friction_coefficient, stick_ratio, *, pseudo_width_ratio=20.0,
                           model="carter"):
    r"""Coefficients of a*(t), T(t) and xi(t), (7.37)-(7.45), derived variant, package frame.

    Parameters
    ----------
    wavenumber : float
        k = 2 pi / L of the oscillation (omega = k V), >= 0. [1/m]
    normal_load : float
        Normal load per unit length N, > 0. [N/m]
    radius : float
        Equivalent radius R, > 0. [m]
    youngs_modulus : float
        Young's modulus E, > 0. [Pa]
    poisson_ratio : float
        Poisson's ratio, in [0, 0.5). [-]
    friction_coefficient : float
        mu, > 0. [-]
    stick_ratio : float
        Steady r_a0 = a0*/a0, in (0, 1]. [-]
    pseudo_width_ratio : float, optional
        b / a0, >= 2. [-]
    model : {"carter", "johnson"}, optional
        Approximation of u_x(x0, t). [-]

    Returns
    -------
    NonSteadyCoefficients
    """
    k = float(check_range("wavenumber", wavenumber, "1/m", 0.0, None))
    mu = float(check_range("friction_coefficient", friction_coefficient, "-", 0.0, None,
                           lower_closed=False))
    n_load = float(check_range("normal_load", normal_load, "N/m", 0.0, None,
                               lower_closed=False))
    rad = float(check_range("radius", radius, "m", 0.0, None, lower_closed=False))
    r = float(check_range("stick_ratio", stick_ratio, "-", 0.0, 1.0, lower_closed=False))
    e_mod = float(youngs_modulus)
    nu = float(check_range("poisson_ratio", poisson_ratio, "-", 0.0, 0.5, upper_closed=False))
    h = hertz_2d(n_load, rad, e_mod, nu)
    a0 = float(h.a0)
    a_s = r * a0
    lam = float(displacement_factor(model, nu, pseudo_width_ratio, r))
    c = mu * np.pi * e_mod / (4.0 * (1.0 - nu ** 2))
    ks = k * a_s
    b0, b1 = float(j0(ks)), float(j1(ks))
    ph = np.exp(1j * k * (a0 - a_s))
    a_hat = k * rad * b0 * ph                                   # per unit Z
    t_hat = -c * ks * (b0 + 1j * b1) * ph
    gam = 4.0 * (1.0 - nu ** 2) / (np.pi * e_mod)
    d_a = mu * a_s / (2.0 * rad)
    d_t = gam * lam
    xi_hat = k * ph * (-mu * b0 + 1j * k * rad * b0 * d_a
                       - 1j * k * d_t * c * a_s * (b0 + 1j * b1))
    return NonSteadyCoefficients(
        contact_half_width=a0, stick_half_width=a_s, creepage_steady=mu * (a0 - a_s) / rad,
        force_steady=mu * n_load * (1.0 - r * r),
        stick_1=a_hat.real, stick_2=-a_hat.imag, force_1=t_hat.real, force_2=-t_hat.imag,
        creepage_1=xi_hat.real, creepage_2=-xi_hat.imag, wavenumber=k)


def nonsteady_time_response(time, velocity, amplitude_a, amplitude_b, coefficients):
    r"""a*(t), T(t) and xi(t) from the coefficients, (7.37), (7.38), (7.44).

    Parameters
    ----------
    time : array_like
        Time t. [s]
    velocity : float
        Rolling speed V_m, > 0 (omega = k V). [m/s]
    amplitude_a, amplitude_b : float
        U_A, U_B of (7.24)/(7.26), small: ``k^2 R sqrt(U_A^2 + U_B^2) << 1``. [m]
    coefficients : NonSteadyCoefficients

    Returns
    -------
    stick_half_width : ndarray
        a*(t). [m]
    force : ndarray
        T(t), magnitude frame (the force on the wheel is -T for positive creepage). [N/m]
    creepage : ndarray
        xi(t). [-]

    Raises
    ------
    ValueError
        If the amplitude drives a* out of (0, a0] (linearisation invalid).
    """
    t = check_range("time", time, "s")
    v = float(check_range("velocity", velocity, "m/s", 0.0, None, lower_closed=False))
    ua = float(check_range("amplitude_a", amplitude_a, "m"))
    ub = float(check_range("amplitude_b", amplitude_b, "m"))
    co = coefficients
    w = co.wavenumber * v
    cs, sn = np.cos(w * t), np.sin(w * t)

    def comb(x1, x2):
        return (x1 * ua - x2 * ub) * cs + (x2 * ua + x1 * ub) * sn

    a_t = co.stick_half_width + comb(co.stick_1, co.stick_2)
    amp = np.hypot(co.stick_1, co.stick_2) * np.hypot(ua, ub)
    if amp >= co.stick_half_width or (amp > co.contact_half_width - co.stick_half_width
                                      and co.stick_half_width < co.contact_half_width):
        raise ValueError(
            f"amplitude_a, amplitude_b: the stick half-width amplitude {amp:g} m exceeds "
            f"a0* = {co.stick_half_width:g} m or a0 - a0* (linearisation of (7.37) invalid; "
            f"need k^2 R |U| << 1)")
    force = co.force_steady + comb(co.force_1, co.force_2)
    xi = co.creepage_steady + comb(co.creepage_1, co.creepage_2)
    return a_t, force, xi


# --------------------------------------------------------------------------------------------
# time-domain relaxation model (module docstring, "Time-domain relaxation model")
# --------------------------------------------------------------------------------------------

def _displacement_factor_full_stick(model, poisson_ratio, pseudo_width_ratio):
    """Lambda at r_a0 = 1 (validates model, nu and b/a0); Lambda(r) = this - ln(r)."""
    return float(displacement_factor(model, poisson_ratio, pseudo_width_ratio, 1.0))


def relaxation_length(contact_half_width, stick_ratio, *, poisson_ratio,
                      pseudo_width_ratio=20.0, model="carter"):
    r"""Relaxation length ``sigma = a0* (Lambda(r_a0) - 1)`` of the non-steady 2-D contact.

    The first-order term of the thesis' transfer function (Sec. 7.2, derived variant):
    ``1/H = 1 + i k sigma + O((k a0*)^2)`` with ``Lambda`` of (7.15) (Johnson) or (7.20)
    (Carter), see the module docstring. ``Lambda(r) = Lambda(1) - ln(r)``, so
    ``sigma = a0 (r (Lambda(1) - 1) - r ln r)``, which is 0 at r = 0 (full sliding: no memory)
    and positive otherwise. Vectorised.

    Parameters
    ----------
    contact_half_width : array_like
        Contact half-width a0, >= 0. [m]
    stick_ratio : array_like
        r_a0 = a0*/a0 of the current state, in [0, 1]. [-]
    poisson_ratio : float
        Poisson's ratio, in [0, 0.5). [-]
    pseudo_width_ratio : float, optional
        b / a0 of the 3-D rectangle of the displacement approximation, >= 2 (thesis: 20). [-]
    model : {"carter", "johnson"}, optional
        Stress used for u_x(x0, t), (7.16)-(7.20) or (7.11)-(7.15). [-]

    Returns
    -------
    ndarray
        sigma >= 0. [m]

    Raises
    ------
    ValueError
        If an input is outside the range stated above.

    References
    ----------
    .. [1] J.B. Nielsen (1998), Eqs. (7.15), (7.20), (7.53)-(7.54) (low-frequency expansion).
    """
    a0 = check_range("contact_half_width", contact_half_width, "m", 0.0, None)
    r = check_range("stick_ratio", stick_ratio, "-", 0.0, 1.0)
    lam1 = _displacement_factor_full_stick(model, poisson_ratio, pseudo_width_ratio)
    return (a0 * (r * (lam1 - 1.0) - xlogy(r, r)))[()]


def relaxation_length_function(poisson_ratio, pseudo_width_ratio=20.0, model="carter"):
    r"""Scalar :func:`relaxation_length` with the constants bound, for a per-step call.

    Parameters
    ----------
    poisson_ratio, pseudo_width_ratio, model
        As in :func:`relaxation_length` (validated here, once).

    Returns
    -------
    callable
        ``sigma(contact_half_width, stick_ratio) -> float`` [m] for plain floats with
        ``a0 >= 0`` and ``0 <= r_a0 <= 1`` (not checked again); equal to
        :func:`relaxation_length` to rounding.
    """
    c1 = _displacement_factor_full_stick(model, poisson_ratio, pseudo_width_ratio) - 1.0

    def sigma(contact_half_width, stick_ratio, _log=math.log):
        if stick_ratio <= 0.0:
            return 0.0
        return contact_half_width * stick_ratio * (c1 - _log(stick_ratio))
    return sigma


def relaxation_transfer_function_normalised(wave_ratio, stick_ratio, *, poisson_ratio=0.28,
                                            pseudo_width_ratio=20.0, model="carter"):
    r"""Transfer function of the first-order relaxation model, ``1 / (1 + i k sigma)``.

    Normalised as :func:`nonsteady_transfer_function_normalised` (linearised force amplitude
    over Carter's quasi-static slope ``pi E a0* / (4 (1 - nu^2))``, which is the steady slope
    ``dT/dxi`` of Carter's curve at r_a0, so the steady force at the relaxed creepage has this
    transfer function); ``k sigma = 2 pi (a0/L) r_a0 (Lambda(r_a0) - 1)``. Its accuracy against
    the thesis' H is tabulated in the module docstring.

    Parameters
    ----------
    wave_ratio : array_like
        a0 / L, >= 0. [-]
    stick_ratio : array_like
        r_a0 of the steady state, in [0, 1]. [-]
    poisson_ratio, pseudo_width_ratio, model
        As in :func:`relaxation_length`.

    Returns
    -------
    ndarray of complex
        H_model. [-]
    """
    ratio = check_range("wave_ratio", wave_ratio, "-", 0.0, None)
    k_sigma = 2.0 * np.pi * ratio * relaxation_length(
        1.0, stick_ratio, poisson_ratio=poisson_ratio, pseudo_width_ratio=pseudo_width_ratio,
        model=model)
    return (1.0 / (1.0 + 1j * np.asarray(k_sigma)))[()]


def relaxation_factor(rolled_distance, relaxation_length_start, relaxation_length_end=None):
    r"""Factor ``q`` of one step of the relaxation law: ``xi_e <- xi + (xi_e - xi) q``.

    ``q = exp(-d (1/sigma_start + 1/sigma_end) / 2)``, the exact solution of
    ``d xi_e / dx = (xi - xi_e) / sigma`` over a rolled distance ``d = V h`` with the input
    held, for constant sigma (``relaxation_length_end`` omitted), and the trapezoidal rule for
    the integral of ``1/sigma`` along the step otherwise (the corrector of the scheme in the
    module docstring). ``q`` is in [0, 1] for every input: 1 for d = 0 (V = 0: the state is
    held), 0 if either sigma is 0 (full sliding: no memory, also for d = 0) or the step is
    long (``d / sigma`` up to inf). Vectorised.

    Parameters
    ----------
    rolled_distance : array_like
        d = V h, >= 0 (inf allowed). [m]
    relaxation_length_start : array_like
        sigma at the start state, >= 0. [m]
    relaxation_length_end : array_like, optional
        sigma at the (predicted) end state, >= 0. [m]

    Returns
    -------
    ndarray
        q in [0, 1]. [-]
    """
    return np.exp(-_exponent(rolled_distance, relaxation_length_start,
                             relaxation_length_end))[()]


def _exponent(rolled_distance, relaxation_length_start, relaxation_length_end):
    """``x = -ln q`` of :func:`relaxation_factor`, in [0, inf], checked and broadcast."""
    d = check_range("rolled_distance", np.nan_to_num(np.asarray(rolled_distance, float),
                                                     nan=np.nan, posinf=np.finfo(float).max),
                    "m", 0.0, None)
    s0 = check_range("relaxation_length_start", relaxation_length_start, "m", 0.0, None)
    s1 = s0 if relaxation_length_end is None else check_range(
        "relaxation_length_end", relaxation_length_end, "m", 0.0, None)
    d, s0, s1 = np.broadcast_arrays(d, s0, s1)
    no_memory = (s0 <= 0.0) | (s1 <= 0.0)
    with np.errstate(over="ignore", divide="ignore", invalid="ignore"):  # 1/sigma = inf
        inv = 0.5 / np.where(no_memory, 1.0, s0) + 0.5 / np.where(no_memory, 1.0, s1)
        x = np.where(d > 0.0, d * inv, 0.0)
    return np.where(no_memory, np.inf, x)


def relax_creepage(relaxed_creepage, creepage, rolled_distance, relaxation_length_start,
                   relaxation_length_end=None):
    r"""One step of the relaxation law: the relaxed creepage after rolling ``d`` with ``xi`` held.

    ``xi_e + (xi - xi_e) (1 - q)`` with ``q`` of :func:`relaxation_factor`, evaluated without
    cancellation: as ``xi_e - (xi - xi_e) expm1(-x)`` while ``q > 1/2`` (short steps, the
    change is small) and as ``xi + (xi_e - xi) q`` otherwise, ``x = -ln q``. Either form
    combines the two end points with a weight in [0, 1/2], so the result lies between
    ``xi_e`` and ``xi`` also after rounding (no overshoot); it is ``xi_e`` for d = 0 and ``xi``
    for sigma = 0 or a long step, exactly. Vectorised.

    Parameters
    ----------
    relaxed_creepage : array_like
        xi_e at the start of the step (any real). [-] (or [1/m] for spin)
    creepage : array_like
        Input xi held over the step. [-] (or [1/m])
    rolled_distance, relaxation_length_start, relaxation_length_end
        As in :func:`relaxation_factor`. [m]

    Returns
    -------
    ndarray
        xi_e at the end of the step. [-] (or [1/m])
    """
    old = check_range("relaxed_creepage", relaxed_creepage, "-")
    xi = check_range("creepage", creepage, "-")
    x = _exponent(rolled_distance, relaxation_length_start, relaxation_length_end)
    short = x < _LN2
    with np.errstate(invalid="ignore", over="ignore"):
        em = np.expm1(-np.where(short, x, 0.0))
        q = np.exp(-x)
        out = np.where(short, old - (xi - old) * em, xi + (old - xi) * q)
        # xi - xi_e beyond the float range (|xi|, |xi_e| ~ 1e308, opposite signs): the same
        # weights on the halved difference (the result lies between xi_e and xi: finite)
        halved = np.where(short, old - ((0.5 * xi - 0.5 * old) * em) * 2.0,
                          xi + ((0.5 * old - 0.5 * xi) * q) * 2.0)
        return np.where(np.isfinite(out), out, halved)[()]


def _relaxation_exponent(d, s0, s1):
    """Scalar ``-ln q`` of :func:`relaxation_factor` (plain floats d >= 0, sigma >= 0)."""
    if s0 <= 0.0 or s1 <= 0.0:
        return math.inf
    if d <= 0.0:
        return 0.0
    return d * (0.5 / s0 + 0.5 / s1)


def _relax(old, xi, x, _expm1=math.expm1, _exp=math.exp, _ln2=_LN2):
    """Scalar :func:`relax_creepage` for the exponent ``x = -ln q`` (plain floats)."""
    if x < _ln2:
        em = _expm1(-x)
        out = old - (xi - old) * em
        return out if out - out == 0.0 else old - ((0.5 * xi - 0.5 * old) * em) * 2.0
    q = _exp(-x)
    out = xi + (old - xi) * q
    # (xi - xi_e beyond the float range: the halved difference, see relax_creepage)
    return out if out - out == 0.0 else xi + ((0.5 * old - 0.5 * xi) * q) * 2.0


def relaxation_step(relaxed_creepages, creepages, rolled_distance, relaxation_length_of, *,
                    max_ratio=1.25, max_substeps=64):
    r"""One communication step of the relaxation law with a state-dependent sigma.

    The scheme of the module docstring: sigma at the start state, a predictor
    (:func:`relax_creepage` with it), sigma at the predicted end state, the corrector with
    the trapezoidal exponent ``d (1/sigma_start + 1/sigma_end) / 2``. If sigma changes on the
    step by more than the factor ``max_ratio`` (largest over smallest of its values at the
    start, the middle and the predicted end; a large creepage jump in a step of the order
    sigma / V) the step is split into ``n = ceil(ln(ratio) / ln(max_ratio))`` equal sub-steps
    (at most ``max_substeps``), each done the same way. Every (sub-)step keeps the properties
    of the exact exponential (between the start state and the input, exact for constant
    sigma, ``xi`` once sigma is 0) and the error bound of
    :func:`relaxation_step_error_bound` holds for the whole step. Several creepages
    (xi_x, xi_y, phi) relax with one common sigma.

    Parameters
    ----------
    relaxed_creepages : sequence of float
        xi_e at the start of the step. [-] ([1/m] for spin)
    creepages : sequence of float
        The inputs, held over the step, same length. [-] ([1/m])
    rolled_distance : float
        d = V h, >= 0. [m]
    relaxation_length_of : callable
        ``relaxation_length_of(state) -> sigma`` [m], >= 0, for a state (tuple of floats) on
        the segment between the two arguments above.
    max_ratio : float, optional
        Largest change of sigma in one sub-step, > 1. [-]
    max_substeps : int, optional
        Cap on the number of sub-steps, >= 1. [-]

    Returns
    -------
    tuple of float
        xi_e at the end of the step. [-] ([1/m])
    """
    old, xi = tuple(relaxed_creepages), tuple(creepages)
    d = rolled_distance
    s0 = relaxation_length_of(old)
    x = _relaxation_exponent(d, s0, s0)
    pred = _relax_all(old, xi, x)
    s1 = relaxation_length_of(pred)
    n = 1
    if 0.0 < x < math.inf:
        # sigma may peak inside the segment (xi_e crossing 0: full stick): also its middle
        s_mid = relaxation_length_of(tuple([0.5 * (o + p) for o, p in zip(old, pred)]))
        hi, lo = max(s0, s1, s_mid), min(s0, s1, s_mid)
        if hi > max_ratio * lo:
            n = max_substeps if lo <= 0.0 else min(
                max_substeps, math.ceil(math.log(hi / lo) / math.log(max_ratio)))
    if n == 1:
        return _relax_all(old, xi, _relaxation_exponent(d, s0, s1))
    d = d / n
    state = old
    for _ in range(n):
        s0 = relaxation_length_of(state)
        pred = _relax_all(state, xi, _relaxation_exponent(d, s0, s0))
        state = _relax_all(state, xi, _relaxation_exponent(d, s0, relaxation_length_of(pred)))
    return state


def _relax_all(old, xi, x, _expm1=math.expm1, _exp=math.exp, _ln2=_LN2,
               _isfinite=math.isfinite):
    """:func:`_relax` of every component for one exponent (the same arithmetic)."""
    if x < _ln2:
        em = _expm1(-x)
        out = tuple([o - (v - o) * em for o, v in zip(old, xi)])
    else:
        q = _exp(-x)
        out = tuple([v + (o - v) * q for o, v in zip(old, xi)])
    if _isfinite(sum(out)):
        return out
    # a difference xi - xi_e beyond the float range (or only the sum overflowed): per component
    return tuple([_relax(o, v, x) for o, v in zip(old, xi)])


def _relaxation_factor(d, s0, s1):
    """Scalar :func:`relaxation_factor` (plain floats, d >= 0, sigma >= 0; not checked)."""
    return math.exp(-_relaxation_exponent(d, s0, s1))


def relaxation_step_error_bound(relaxation_length_min, relaxation_length_max):
    r"""Bound on the error of one step of the relaxation scheme, per unit ``|xi - xi_e|``.

    If sigma varies on the path of the step between ``sigma_min`` and ``sigma_max``, both the
    exact solution and the scheme (module docstring) are ``xi + (xi_e - xi) exp(-d/s)`` with
    some s in that interval, so their difference is at most
    ``max_d [exp(-d/sigma_max) - exp(-d/sigma_min)] = rho^(rho/(1-rho)) - rho^(1/(1-rho))``,
    ``rho = sigma_min / sigma_max``, for any rolled distance d. 0 for rho = 1 (constant sigma:
    the step is exact), 1 for rho = 0.

    Parameters
    ----------
    relaxation_length_min, relaxation_length_max : array_like
        Smallest and largest sigma on the path, ``0 <= min <= max``, ``max > 0``. [m]

    Returns
    -------
    ndarray
        Bound on ``|xi_e,scheme - xi_e,exact| / |xi - xi_e,start|``, in [0, 1]. [-]
    """
    lo = check_range("relaxation_length_min", relaxation_length_min, "m", 0.0, None)
    hi = check_range("relaxation_length_max", relaxation_length_max, "m", 0.0, None,
                     lower_closed=False)
    if np.any(lo > hi):
        raise ValueError(f"relaxation_length_min must be <= relaxation_length_max [m]; got "
                         f"{np.max(lo - hi):g} m more")
    rho = lo / hi
    inner = (rho > 0.0) & (rho < 1.0)
    rr = np.where(inner, rho, 0.5)
    val = rr ** (rr / (1.0 - rr)) - rr ** (1.0 / (1.0 - rr))
    return np.where(inner, val, np.where(rho <= 0.0, 1.0, 0.0))[()]
