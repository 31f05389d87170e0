r"""Polach's creep-force method (1999, with spin) and its 2005 extension (falling friction).

Package convention (see :mod:`railcontact`): forces act on the wheel and oppose the creepage;
Polach writes the force in the direction of the creepage, so every force below is used with a
minus sign. Symbols: Q = N the normal load, a = a0 the semi-axis in the rolling direction,
b = b0 the lateral one ([1]'s listing: "A - semiaxis a of the contact ellipse (in longitudinal
direction)"), C_ij Kalker's coefficients (:func:`railcontact.kalker_coefficients`),
G = E / (2 (1 + nu)), phi the spin [1/m], mu the friction coefficient.

Resultant creepage with spin ([1], [2]; [1]'s listing)

    s = sqrt(xi_x^2 + xi_y^2),
    s_yC = xi_y + phi a   if |xi_y + phi a| > |xi_y|,  else xi_y,
    s_C = sqrt(xi_x^2 + s_yC^2).

Creep part ([2] Eqs. (2), (3); C from Kalker's coefficients as in [1]; s_C in place of s and
in the components as in [1]'s listing)

    C = (3/8) (G / a) c_jj,   c_jj = sqrt((C11 xi_x / s)^2 + (C22 xi_y / s)^2),
    eps = (2/3) C pi a^2 b s_C / (Q mu) = (1/4) G pi a b c_jj s_C / (Q mu),
    F = (2 Q mu / pi) (k_A eps / (1 + (k_A eps)^2) + arctan(k_S eps)),
    F_x = F xi_x / s_C,   F_y = F xi_y / s_C.

With k_A = k_S = 1 this is the 1999 formula; without spin (s_C = s) its initial slope
``dF/ds = G a b c_jj`` is the linear theory's for pure longitudinal or pure lateral creepage
(for combined creepage Polach's force stays parallel to (xi_x, xi_y)) and F -> mu Q as
s -> inf.

Spin part ([1]; [1]'s listing)

    eps_M = (8/3) (G b sqrt(a b) / (Q mu)) C23 |s_yC| / (1 + 6.3 (1 - exp(-a/b))),
    delta = (eps_M^2 - 1) / (eps_M^2 + 1),
    K_M = |eps_M| (delta^3/3 - delta^2/2 + 1/6) - (1/3) sqrt((1 - delta^2)^3),
    F_yS = -(9/16) a Q mu K_M (1 + 6.3 (1 - exp(-a/b))) phi / s_C,
    F_y,total = F_y + F_yS.

At small spin K_M -> -(2/3) eps_M and F_yS -> G a b sqrt(a b) C23 phi |s_yC| / s_C: the linear
theory for pure spin and spin with lateral creepage (xi_x = 0); longitudinal creepage reduces
the spin part (|s_yC| < s_C). At large eps_M, K_M -> 0: pure spin's lateral force rises and
then decays, as in the exact theory.

2005 extension ([2]): friction falling with the magnitude of the slip velocity w [m/s],

    mu = mu0 ((1 - A) exp(-B w) + A),

A = mu_inf / mu0 the ratio of the friction at infinite slip velocity to the maximum, B [s/m]
the rate of the exponential decrease ([2]; the same law in CONTACT, [3] Eq. "polach_law", which
notes [2]'s B in s/m); here w = V s_C (V the rolling speed): our reading, the slip velocity of
the resultant creepage that enters eps (Open Rails, which has no spin, uses V xi_x); and the
reduction factors k_A (initial slope in the area of adhesion) and k_S (slope in the area of
slip), 0 < k_S <= k_A <= 1 ([2]: they model the reduced initial slope measured on real,
contaminated rails). k_A and k_S reduce the creep part only (the 1999 Eq. (2) of [2]); the spin
part keeps its 1999 form with the falling mu (whether [2] reduces it too could not be checked:
no source we could read has both). The 1999 method is the default
here (k_A = k_S = 1, A = 1): the exact theory it is measured against has neither. Polach's
recommended parameter sets ([2]; tests/data/polach2005_parameters.csv): dry rail k_A = 1.00,
k_S = 0.40, mu0 = 0.55, A = 0.40, B = 0.60 s/m; wet rail k_A = 0.30, k_S = 0.10, mu0 = 0.30,
A = 0.40, B = 0.20 s/m (:data:`POLACH_DRY`, :data:`POLACH_WET`).

Coulomb bound: F_y + F_yS can exceed mu Q slightly when lateral creepage and spin act together
(the two parts are superposed); the result is scaled back onto |T| = mu Q there (this package's
guarantee for every bounded method, not part of [1]).

Sources. The published papers themselves were not available to us. The equations above were
checked against (i) the text of [2] as quoted in a public copy of its first pages (Eq. (2), F
without k_A, k_S; Eq. (3), eps with s; the friction law), (ii) a public transcription of the
FORTRAN subroutine printed in [1] (github.com/leo-bart/mbs-flex-rail, ``polachContactForces.pyx``,
2024: c_jj from s, s_C in eps and in the components, |s_yC| in eps_M, the factor
1 + 6.3 (1 - exp(-a/b)), K_M, delta and F_yS as above, a "in longitudinal direction"; its spin
test reads ``|s_y + phi a| <= |s_y|``, which gives pure spin no force at all, so we keep ">",
the only reading under which Polach's spin part acts for pure spin) and (iii) Open Rails'
implementation of [2] (github.com/openrails/openrails, ``Axle.cs``, class PolachCalculator,
longitudinal only: c_jj from s, eps with s_C, F_x = F s_x / s_C, the k_A, k_S form of F (its
denominator is 1 + k_A eps^2 instead of 1 + (k_A eps)^2), the friction law; its k_A, k_S, A, B
are straight lines in mu0 through exactly the dry and wet sets above). (ii) and (iii) agree on
everything they share. No code was taken from either. The formulas as first written here (eps
with s, components xi / s, eps_M with s_C) were closer to the exact theory with spin (max
11.7 % against 15.6 % of mu N on CONTACT's 21 cases) but were not Polach's.

References
----------
.. [1] O. Polach, A fast wheel-rail forces calculation computer code, Vehicle System Dynamics
   33 Suppl. (1999) 728-739 (with the FORTRAN listing).
.. [2] O. Polach, Creep forces in simulations of traction vehicles running on adhesion limit,
   Wear 258 (2005) 992-1000.
.. [3] E.A.H. Vollebregt, CONTACT user guide (github.com/eve70a/CONTACT, doc/user-guide.tex),
   Polach's exponential friction law.
"""

from __future__ import annotations

import numpy as np

from ._validation import check_creep_inputs, check_range
from .kalker import kalker_coefficients

__all__ = ["polach_force_3d", "polach_friction", "POLACH_DRY", "POLACH_WET"]

POLACH_DRY = {"reduction_adhesion": 1.0, "reduction_slip": 0.4, "friction_ratio_limit": 0.4,
              "friction_decay": 0.6}
"""Polach 2005, dry rail (with friction_coefficient = 0.55)."""
POLACH_WET = {"reduction_adhesion": 0.3, "reduction_slip": 0.1, "friction_ratio_limit": 0.4,
              "friction_decay": 0.2}
"""Polach 2005, wet rail (with friction_coefficient = 0.30)."""


def _check_polach(reduction_adhesion, reduction_slip, friction_ratio_limit, friction_decay,
                  rolling_speed):
    k_a = check_range("reduction_adhesion", reduction_adhesion, "-", 0.0, 1.0,
                      lower_closed=False)
    k_s = check_range("reduction_slip", reduction_slip, "-", 0.0, 1.0, lower_closed=False)
    a_ratio = check_range("friction_ratio_limit", friction_ratio_limit, "-", 0.0, 1.0)
    b_decay = check_range("friction_decay", friction_decay, "s/m", 0.0, None)
    speed = check_range("rolling_speed", rolling_speed, "m/s", 0.0, None)
    return k_a, k_s, a_ratio, b_decay, speed


def polach_friction(friction_coefficient, slip_velocity, friction_ratio_limit=1.0,
                    friction_decay=0.0):
    r"""Polach's falling friction ``mu = mu0 ((1 - A) exp(-B w) + A)`` (Polach 2005).

    Parameters
    ----------
    friction_coefficient : array_like
        Maximum friction coefficient mu0 (at zero slip velocity), >= 0. [-]
    slip_velocity : array_like
        Magnitude of the slip velocity w, >= 0. [m/s]
    friction_ratio_limit : array_like, optional
        A = mu_inf / mu0, in [0, 1]; 1 = constant friction. [-]
    friction_decay : array_like, optional
        Exponential decrease rate B, >= 0. [s/m]

    Returns
    -------
    ndarray
        mu in [A mu0, mu0]. [-]
    """
    mu0 = check_range("friction_coefficient", friction_coefficient, "-", 0.0, None)
    w = check_range("slip_velocity", slip_velocity, "m/s", 0.0, None)
    a_ratio = check_range("friction_ratio_limit", friction_ratio_limit, "-", 0.0, 1.0)
    b_decay = check_range("friction_decay", friction_decay, "s/m", 0.0, None)
    return (mu0 * ((1.0 - a_ratio) * np.exp(-b_decay * w) + a_ratio))[()]


def polach_force_3d(creepage_longitudinal, creepage_lateral, spin, normal_load, a0, b0,
                    youngs_modulus, poisson_ratio, friction_coefficient,
                    reduction_adhesion=1.0, reduction_slip=1.0, friction_ratio_limit=1.0,
                    friction_decay=0.0, rolling_speed=0.0):
    r"""Creep force by Polach's method [1] with the 2005 extension [2].

    See the module docstring for the equations. Inputs broadcast.

    Parameters
    ----------
    creepage_longitudinal, creepage_lateral, spin, normal_load, a0, b0, youngs_modulus,
    poisson_ratio
        As in :func:`railcontact.creep_force_3d` ([-], [-], [1/m], [N], [m], [m], [Pa], [-]).
    friction_coefficient : array_like
        Maximum friction coefficient mu0, >= 0. [-]
    reduction_adhesion : array_like, optional
        k_A, reduction of the initial slope (area of adhesion), in (0, 1]. [-]
    reduction_slip : array_like, optional
        k_S, reduction of the slope in the area of slip, in (0, 1]; Polach: k_S <= k_A. [-]
    friction_ratio_limit : array_like, optional
        A = mu_inf / mu0, in [0, 1]; 1 (default) = constant friction. [-]
    friction_decay : array_like, optional
        B, rate of the exponential friction decrease with slip velocity, >= 0. [s/m]
    rolling_speed : array_like, optional
        V, >= 0; the slip velocity is V s_C. Needed only with A < 1 and B > 0. [m/s]

    Returns
    -------
    CreepForce3D-like tuple
        ``(tx, ty)`` force on the wheel [N]; |T| <= mu N with mu from the falling law; zero
        creepage and spin, N = 0, mu = 0 or a0 b0 = 0 give zeros.

    Raises
    ------
    ValueError
        If an input is outside its range (NaN and inf included).

    References
    ----------
    .. [1] O. Polach, Vehicle System Dynamics 33 Suppl. (1999) 728-739.
    .. [2] O. Polach, Wear 258 (2005) 992-1000.
    """
    xi_x, xi_y, phi, n_load, a0, b0, e_mod, nu, mu0 = check_creep_inputs(
        creepage_longitudinal, creepage_lateral, spin, normal_load, a0, b0, youngs_modulus,
        poisson_ratio, friction_coefficient)
    k_a, k_s, a_ratio, b_decay, speed = _check_polach(
        reduction_adhesion, reduction_slip, friction_ratio_limit, friction_decay, rolling_speed)
    shape = np.broadcast(xi_x, xi_y, phi, n_load, a0, b0, e_mod, nu, mu0, k_a, k_s, a_ratio,
                         b_decay, speed).shape
    has_area = (a0 > 0.0) & (b0 > 0.0)
    a = np.where(has_area, a0, 1.0)
    b = np.where(has_area, b0, 1.0)
    c11, c22, c23 = kalker_coefficients(a / b, nu)
    g_mod = e_mod / (2.0 * (1.0 + nu))

    s = np.hypot(xi_x, xi_y)
    s_y_spin = xi_y + phi * a
    s_yc = np.where(np.abs(s_y_spin) > np.abs(xi_y), s_y_spin, xi_y)
    s_c = np.hypot(xi_x, s_yc)
    mu = mu0 * ((1.0 - a_ratio) * np.exp(-b_decay * speed * s_c) + a_ratio)
    q_mu = np.broadcast_to(n_load * mu, shape)
    ok = np.broadcast_to(has_area & (q_mu > 0.0), shape)
    q_mu_s = np.where(ok, q_mu, 1.0)
    has_s = np.broadcast_to(s > 0.0, shape)
    has_sc = np.broadcast_to(s_c > 0.0, shape)

    # creepage part: c_jj = |(C11 xi_x, C22 xi_y)| / s (the direction of the creepage without
    # spin), eps with s_C, components xi / s_C ([1]'s listing)
    c_jj = np.divide(np.hypot(c11 * xi_x, c22 * xi_y), s, out=np.zeros(shape), where=has_s)
    eps = 0.25 * np.pi * g_mod * a * b * c_jj * s_c / q_mu_s
    with np.errstate(over="ignore"):         # eps = inf (N mu -> 0): arctan -> pi/2, meant
        ka_eps = k_a * eps
        first = np.where(ka_eps < 1e150, ka_eps / (1.0 + np.minimum(ka_eps, 1e150) ** 2), 0.0)
        f_mag = 2.0 * q_mu / np.pi * (first + np.arctan(k_s * eps))
    fx = f_mag * np.divide(xi_x, s_c, out=np.zeros(shape), where=has_sc)
    fy = f_mag * np.divide(xi_y, s_c, out=np.zeros(shape), where=has_sc)

    # spin part, eps_M with |s_yC| ([1]'s listing)
    shape_factor = 1.0 + 6.3 * (1.0 - np.exp(-a / b))
    eps_m = (8.0 / 3.0) * g_mod * b * np.sqrt(a * b) / q_mu_s * c23 * np.abs(s_yc) / shape_factor
    with np.errstate(over="ignore"):
        em2 = np.minimum(eps_m, 1e150) ** 2
        delta = (em2 - 1.0) / (em2 + 1.0)
        one_m_d2 = np.divide(4.0 * em2, (em2 + 1.0) ** 2, out=np.zeros(shape),
                             where=np.broadcast_to(em2 < 1e300, shape))   # 1 - delta^2
    # K_M = |eps_M| (delta^3/3 - delta^2/2 + 1/6) - (1/3)(1 - delta^2)^(3/2); the polynomial
    # is (delta - 1)^2 (2 delta + 1)/6, which with 1 - delta = 2/(eps_M^2 + 1) avoids the
    # cancellation at large eps_M
    poly = (2.0 / (em2 + 1.0)) ** 2 * (2.0 * delta + 1.0) / 6.0
    k_m = np.abs(eps_m) * poly - one_m_d2 ** 1.5 / 3.0
    f_ys = np.divide(-(9.0 / 16.0) * a * q_mu * k_m * shape_factor * phi, s_c,
                     out=np.zeros(shape), where=has_sc)
    fy = fy + f_ys

    tx = np.where(ok, -fx, 0.0)
    ty = np.where(ok, -fy, 0.0)
    t_abs = np.hypot(tx, ty)
    # (1 - 4 eps): np.hypot of the rescaled components must not round above mu N (creep3d)
    cap = q_mu * (1.0 - 4.0 * np.finfo(float).eps)
    scale = np.divide(cap, t_abs, out=np.ones(shape), where=t_abs > cap)
    return (tx * scale + 0.0)[()], (ty * scale + 0.0)[()]
