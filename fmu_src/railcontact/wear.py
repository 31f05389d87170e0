r"""Frictional wear of a corrugated rail under a rolling cylinder (Nielsen Sec. 4.3), and the
choice of wear model.

The wear per passage at a rail point ``X0`` is the frictional work (Frederick's hypothesis),
Eq. (4.74) of [1]_:

.. math:: W(X_0) = K V \int q(X_0, t)\, s(X_0, t)\, dt ,

a **time integral at a material point**. With the patch quasi-static at every axis position
``X_c = V t`` and the material point at patch coordinate ``x = X0 - X_c - Delta(X_c)``,
``V dt = dX_c = dx / (1 + dDelta/dX)``: over a crest the patch centre moves more slowly along the
rail (``Delta' < 0``), so every point dwells longer in the slip zone.

Wear models (``wear_model=``)
-----------------------------
``"material_point"`` (default)
    (4.74) evaluated exactly as written: ``W = K int q s dX_c``, dwell factor ``1/(1 + Delta')``
    included. Verified against a direct evaluation of (4.74) with the discretised half-space
    solver (quasi-static rolling at every rail position, see ``docs/wear_finding.md``).
``"patch_coordinate"``
    ``W = K int q s dx`` along the path of the material point, i.e. the dwell factor dropped.
``"nielsen1998"``
    The thesis' closed form (4.92) ``W = |K V N R/a0^2 (mu pi B0/a)^2 tau (1 - r - r^2 + r^3)|``,
    ``r = tau*/tau``, with the passage times tau, tau* of (4.81)-(4.87) (tau*_1 with the sign
    erratum below corrected, i.e. as derived from (4.76)-(4.77)). Reproduces what the
    thesis states about its Figs. 4.10, 4.11 and 4.14 (one critical L/a0, 1 - 2 W1 -> 1+ for long
    waves, characteristic L/a0 5.6-8.9 for r_a0 = 0.1-0.9, inside the stated 5-10).
    The thesis' tau (4.83) follows from (4.76)-(4.78) only if
    the patch shift enters with the sign of the *opposite* rolling direction (``Delta -> -Delta``;
    checked in the tests), so its passage time carries the factor ``(1 + Delta')`` instead of
    ``1/(1 + Delta')``: the dwell acts the wrong way round. See ``docs/wear_finding.md``.
``"time_domain_carter"``
    (4.92) with tau, tau* from the consistent kinematics (our orientation, Delta with its sign):
    the thesis' heuristic with the sign error removed; an approximation of ``"material_point"``.

Linearised result (one harmonic): ``W = W0 + W_A cos kX + W_B sin kX``,
``W_A + i W_B = (W1 + i W2)(Z_A + i Z_B)`` (4.94)-(4.95), ``W0 = K mu^2 N a0/R (1-r)^2 (1+r)``
(4.96). :func:`wear_coefficients` returns ``w = (W1 + i W2) a0 / (K mu^2 N)``, a function of
``(a0/L, r_a0)`` only; the growth factor per passage is ``1 - 2 W1`` ((4.104),
:func:`railcontact.evolution.growth_factor`).

Errata of (4.96)-(4.98), found while deriving the linearisation:

* (4.97) is dimensionally inconsistent: the first term carries ``k_m V/R`` where ``V/R`` is
  right (W1 must be dimensionless; tau_1 already contains k R / V), the second term lacks a
  factor ``k_m``. ``B^_0`` (never defined) is ``int_0^{k a0} J0(t) dt`` and the bracket is
  ``[int_0^{k a0} J0 - J1(k a0)]`` with a plus sign in front (from B0 = a p(0) C, the pressure
  at the patch centre; checked against (4.92) evaluated with the exact B0 and the passage
  times solved from (4.76)-(4.78), tests/test_wear.py).
* (4.98) prints ``3 r^3``; the linearisation gives ``(1 + 2 r - 3 r^2)`` as in (4.97).
* (4.86) prints ``J0(k a0)[3 sin k(2a0* - a0) - sin k a0]``; (4.76)-(4.77) give ``+ sin k a0``.

References
----------
.. [1] J.B. Nielsen, New Developments in the Theory of Wheel/Rail Contact Mechanics,
   IMM-PHD-1998-51, DTU, 1998, Sec. 4.3, Eqs. (4.74)-(4.98).
.. [2] T.F.J. Quinn / Frederick: wear proportional to frictional work (thesis ref. [17]).
"""

from __future__ import annotations

import math
from collections import namedtuple

import numpy as np
from ._lazy import lazy_submodule
from ._validation import (check_choice, check_corrugated_contact_inputs,
                          check_load_not_underflowing, check_range)
from .corrugation import (check_no_contact_loss, normal_response, solve_normal_exact,
                          solve_stick_zone_exact, stick_zone_response, tangential_force_response)

_TWO_PI = 2.0 * np.pi
# the compiled kernels (numba) and scipy.special load on the first call that needs them: the
# closed forms (mean_wear) and a table scene's wear effect need neither
_kernels = lazy_submodule("_corrugation_kernels")

__all__ = ["WEAR_MODELS", "DEFAULT_WEAR_MODEL", "wear_coefficients", "mean_wear",
           "corrugated_wear_depth",
           "linear_response", "LinearResponse",
           "passage_time_response", "wear_first_harmonic_exact", "wear_shape_function"]

WEAR_MODELS = ("material_point", "patch_coordinate", "nielsen1998", "time_domain_carter")
DEFAULT_WEAR_MODEL = "material_point"


def wear_shape_function(stick_ratio):
    r"""Carter's slip-zone wear shape ``(1 - r)^2 (1 + r) = 1 - r - r^2 + r^3`` of (4.92), (4.96).

    Parameters
    ----------
    stick_ratio : array_like
        ``r_a0`` in [0, 1]. [-]

    Returns
    -------
    ndarray
        ``(1 - r)^2 (1 + r)``; ``int_slip q s dx = mu^2 (E/(4(1-nu^2) R)) (pi/2) a^3`` times it
        for Carter (checked by quadrature in the tests). [-]
    """
    r = check_range("stick_ratio", stick_ratio, "-", 0.0, 1.0)
    return (1.0 - r) ** 2 * (1.0 + r)


def mean_wear(wear_coefficient, friction_coefficient, normal_load, radius, a0, stick_ratio):
    r"""Mean wear per passage W0 = K mu^2 N a0/R (1 - r)^2 (1 + r), Eq. (4.96).

    Parameters
    ----------
    wear_coefficient : array_like
        K of (4.74), >= 0. [m^2/N]
    friction_coefficient : array_like
        mu, >= 0. [-]
    normal_load : array_like
        N per unit length, >= 0. [N/m]
    radius : array_like
        R, > 0. [m]
    a0 : array_like
        Hertz half-width, > 0. [m]
    stick_ratio : array_like
        r_a0 in [0, 1]. [-]

    Returns
    -------
    ndarray
        W0 (equal to the wear of a smooth rail, Carter). [m]
    """
    kw = check_range("wear_coefficient", wear_coefficient, "m^2/N", 0.0, None)
    mu = check_range("friction_coefficient", friction_coefficient, "-", 0.0, None)
    n = check_range("normal_load", normal_load, "N/m", 0.0, None)
    big_r = check_range("radius", radius, "m", 0.0, None, lower_closed=False)
    a0 = check_range("a0", a0, "m", 0.0, None, lower_closed=False)
    r = check_range("stick_ratio", stick_ratio, "-", 0.0, 1.0)
    return mean_wear_unchecked(kw, mu, n, big_r, a0, r)


def mean_wear_unchecked(wear_coefficient, friction_coefficient, normal_load, radius, a0,
                        stick_ratio):
    r""":func:`mean_wear`'s formula (4.96) without its range checks, for floats or arrays.

    :func:`mean_wear` checks its inputs and calls this; the FMU's wear effect calls it per step
    on floats whose ranges the scene and the slave have checked (a few float products instead
    of six range checks). The inputs must satisfy :func:`mean_wear`'s ranges. [m]
    """
    mu, slip = friction_coefficient, 1.0 - stick_ratio
    return (wear_coefficient * mu * mu * normal_load * a0 / radius
            * (slip * slip * (1.0 + stick_ratio)))


# ---------------------------------------------------------------------------------------------
# linear response, normalised units a0 = R = C = mu = K = V = 1 (so N = 1/2)
# ---------------------------------------------------------------------------------------------
def _h_basic(beta, r):
    """Coefficients h (Q = Re[h zeta e^{ikX}]) of Delta, a, a*, our orientation (R = a0 = 1)."""
    from scipy.special import j0, j1  # noqa: PLC0415  (see _kernels)
    k = beta
    e_kd = np.exp(1j * k * (1.0 - r))
    h_d = 1j * k * j0(beta)
    h_a = -k * j1(beta) + 0j
    h_as = h_d + h_a - 1j * k * j0(beta * r) * e_kd
    return h_d, h_a, h_as, e_kd


def passage_time_response(a0_over_wavelength, stick_ratio, *, convention="consistent"):
    r"""Linear response of the half passage times |tau| and |tau*| to one harmonic, (4.81)-(4.87).

    ``|tau|(X0) = a0/V + Re[...]``: ``c_tau``, ``c_tau*`` in units of ``k R / V`` with
    ``(tau_A + i tau_B) = c (Z_A + i Z_B)`` for the *magnitudes* (the thesis' tau is negative).

    Parameters
    ----------
    a0_over_wavelength : array_like
        a0/L, > 0. [-]
    stick_ratio : array_like
        r_a0 in [0, 1]. [-]
    convention : {"consistent", "nielsen1998", "printed"}
        "consistent": from (4.76)-(4.78) written for our orientation (rolling +X, the patch at
        ``X + Delta``, stick zone at the leading edge) -- the times a material point really spends
        in the patch and the stick zone. "nielsen1998": (4.76)-(4.78) with the thesis' a*
        (4.59)-(4.62) and the patch at ``X - Delta`` (the only reading that reproduces (4.83) and
        the tau*_2 of (4.86)), in the thesis' orientation. "printed": (4.83), (4.86) as printed
        (including the sign erratum of (4.86) noted in the module docstring).

    Returns
    -------
    tau, tau_star : ndarray of complex
        ``c_|tau| / (k R / V)``, ``c_|tau*| / (k R / V)``. [-]
    """
    from scipy.special import j0, j1  # noqa: PLC0415  (see _kernels)
    beta = _TWO_PI * check_range("a0_over_wavelength", a0_over_wavelength, "-", 0.0, None,
                                 lower_closed=False)
    r = check_range("stick_ratio", stick_ratio, "-", 0.0, 1.0)
    check_choice("convention", convention, ("consistent", "nielsen1998", "printed"))
    k = beta
    if convention == "printed":
        b, bs, bm = beta, beta * r, beta * (2 * r - 1)
        t1 = j0(b) * np.sin(b) + j1(b) * np.cos(b)
        ts1 = 0.5 * (j0(b) * (3 * np.sin(bm) - np.sin(b)) + j1(b) * (np.cos(bm) + np.cos(b))
                     - 2 * j0(bs) * np.sin(bs))
        ts2 = -0.5 * (j0(b) * (3 * np.cos(bm) - np.cos(b)) - j1(b) * (np.sin(bm) - np.sin(b))
                      - 2 * j0(bs) * np.cos(bs))
        # thesis tau < 0: magnitudes are minus the printed coefficients
        return -(t1 + 0j), -(ts1 + 1j * ts2)
    h_d, h_a, h_as, _ = _h_basic(beta, r)

    def at(h, s):  # coefficient of Q(X0 + s) in terms of zeta e^{ikX0}
        return h * np.exp(1j * k * s)

    if convention == "consistent":
        s = -1.0 + 2.0 * r
        tau = 0.5 * (at(h_a, 1) - at(h_d, 1) + at(h_a, -1) + at(h_d, -1))
        taus = 0.5 * (-at(h_a, s) + 2 * at(h_as, s) - at(h_d, s) + at(h_a, -1) + at(h_d, -1))
        return np.conj(tau) / k, np.conj(taus) / k
    # nielsen1998: thesis orientation, its a* = conj of ours, Delta -> -Delta in (4.76)-(4.78)
    a1 = k * (-j1(beta) - j0(beta * r) * np.sin(k * (r - 1)))
    a2 = k * (j0(beta) - j0(beta * r) * np.cos(k * (r - 1)))
    h_as_th = a1 - 1j * a2
    s1 = 1.0 - 2.0 * r
    sig = -1.0
    tau = 0.5 * (-at(h_a, -1) - at(h_a, 1) - sig * at(h_d, -1) + sig * at(h_d, 1))
    taus = 0.5 * (-sig * at(h_d, s1) - 2 * at(h_as_th, s1) + at(h_a, s1) + sig * at(h_d, 1)
                  - at(h_a, 1))
    return -np.conj(tau) / k, -np.conj(taus) / k


def wear_coefficients(a0_over_wavelength, stick_ratio, wear_model=DEFAULT_WEAR_MODEL, *,
                      n_nodes=24, degree=None):
    r"""Linearised wear coefficients ``w = (W1 + i W2) a0 / (K mu^2 N)`` of one harmonic.

    ``W_A + i W_B = (W1 + i W2)(Z_A + i Z_B)`` (4.95) with ``W1 + i W2 = K mu^2 N / a0 * w``.
    ``W1 > 0`` levels the corrugation, ``W1 < 0`` amplifies it (4.106); ``W2`` shifts its phase
    (4.111)-(4.112). Package orientation (rolling +X); the thesis' W2 is ``-Im(w)`` times the
    scale.

    Parameters
    ----------
    a0_over_wavelength : array_like
        a0/L, > 0 (hard cases tested from 1e-3 to 2). [-]
    stick_ratio : array_like
        r_a0 = a0*/a0 in [0, 1] (0: full slip, 1: full stick; the limits are the one-sided limits
        of the linear theory, W -> 0 at r = 1). [-]
    wear_model : str
        One of :data:`WEAR_MODELS` (module docstring); default ``"material_point"``.
    n_nodes : int
        Gauss-Chebyshev nodes across the slip zone (the integrand times the weight is smooth,
        so the quadrature converges spectrally; 24 gives a relative error below 1e-9 for a0/L
        up to 2 and r_a0 in [0.01, 0.99], checked against 256 nodes). [-]
    degree : int, optional
        Series degree (Chebyshev-Bessel terms); default ``ceil(e k a0) + 12``. [-]

    Returns
    -------
    ndarray of complex
        ``w``, broadcast over the inputs. [-]
    """
    from scipy.special import itj0y0, j1  # noqa: PLC0415  (see _kernels)
    ratio = check_range("a0_over_wavelength", a0_over_wavelength, "-", 0.0, None,
                        lower_closed=False)
    r_in = check_range("stick_ratio", stick_ratio, "-", 0.0, 1.0)
    check_choice("wear_model", wear_model, WEAR_MODELS)
    nq = int(check_range("n_nodes", n_nodes, "-", 4, 100000))
    ratio, r_in = np.broadcast_arrays(ratio, r_in)
    beta = _TWO_PI * ratio
    r = np.clip(r_in, 1e-9, 1.0 - 1e-9)
    f = (1 - r) ** 2 * (1 + r)
    if wear_model in ("material_point", "patch_coordinate"):
        if degree is None:
            degree = int(np.ceil(np.e * np.max(beta, initial=0.0))) + 12
        deg = int(check_range("degree", degree, "-", 1, 100000))
        # normalised units: K mu^2 N / a0 = 1/2
        w = _kernels.wear_coefficients_array(
            np.ravel(beta).astype(float), np.ravel(r_in).astype(float), nq, deg,
            wear_model == "material_point").reshape(beta.shape)
    else:
        conv = "nielsen1998" if wear_model == "nielsen1998" else "consistent"
        c_tau, c_taus = passage_time_response(ratio, r, convention=conv)
        c_tau, c_taus = beta * c_tau, beta * c_taus          # units a0/V per unit Z (R = 1)
        big_j0 = itj0y0(beta)[0]
        c_b = beta * (big_j0 - j1(beta))                     # (delta B0/B0 - delta a/a)
        fprime = -(1 - r) * (1 + 3 * r)
        w = f * (2 * c_b + c_tau) + fprime * (c_taus - r * c_tau)
        if wear_model == "nielsen1998":
            w = np.conj(w)                                   # thesis orientation -> ours
    return np.where(r_in >= 1.0, 0.0, w)


# ---------------------------------------------------------------------------------------------
# exact (nonlinear) evaluation of the wear integral
# ---------------------------------------------------------------------------------------------
def wear_first_harmonic_exact(a0_over_wavelength, stick_ratio, relative_amplitude, *,
                              phase=0.0, n_positions=64, n_nodes=64, degree=None):
    r"""Exact wear per passage, first harmonic, from the exact contact at every rail position.

    The exact nonlinear a, Delta, a* (:func:`railcontact.corrugation.solve_normal_exact`,
    :func:`railcontact.corrugation.solve_stick_zone_exact`) and the exact pressure and slip
    series are evaluated at ``n_positions`` axis positions per wave length; the frictional work
    ``P = q |s|`` is integrated over the slip zone (Gauss-Chebyshev) and over the rail positions
    (periodic trapezoid, spectrally accurate):

    ``int W(X0) e^{-ikX0} dX0 = K int dX_c w(X_c) int_slip P(x; X_c) e^{-ik(X_c + Delta + x)} dx``

    with ``w = 1`` for (4.74) at a material point and ``w = 1 + Delta'(X_c)`` for the
    patch-coordinate integral.

    Parameters
    ----------
    a0_over_wavelength : float
        a0/L, > 0. [-]
    stick_ratio : float
        r_a0 in (0, 1). [-]
    relative_amplitude : float
        ``k R sqrt(Z_A^2 + Z_B^2) / a0``, > 0; condition (4.2) requires
        ``relative_amplitude * 2 pi a0/L < 1``. [-]
    phase : float
        ``arg(Z_A + i Z_B)``. [rad]
    n_positions, n_nodes : int
        Rail positions per wave length, quadrature nodes across the slip zone. [-]
    degree : int, optional
        Series degree. [-]

    Returns
    -------
    dict
        ``"material_point"``, ``"patch_coordinate"``: ``w`` normalised as in
        :func:`wear_coefficients` (first harmonic of the exact wear divided by the surface
        amplitude; equals the linear coefficient up to O(amplitude^2)); ``"mean"``:
        ``W0 R / (K mu^2 N a0)``; ``"half_width"``, ``"patch_shift"``, ``"stick_half_width"``:
        first harmonics of the exact a, Delta, a* over ``k R`` (compare
        :func:`railcontact.corrugation.normal_response`,
        :func:`railcontact.corrugation.stick_zone_response`); ``"tangential_force"``: of the
        exact |T| (4.67) in units of ``mu pi E/(4(1-nu^2))`` (compare
        :func:`railcontact.corrugation.tangential_force_response`). [-]
    """
    from scipy.special import j1, jv  # noqa: PLC0415  (see _kernels)
    ratio = float(check_range("a0_over_wavelength", a0_over_wavelength, "-", 0.0, None,
                              lower_closed=False))
    r = float(check_range("stick_ratio", stick_ratio, "-", 0.0, 1.0, lower_closed=False,
                          upper_closed=False))
    eps = float(check_range("relative_amplitude", relative_amplitude, "-", 0.0, None,
                            lower_closed=False))
    k = _TWO_PI * ratio
    check_no_contact_loss(eps * k)
    npos = int(n_positions)
    lam = 1.0 / ratio
    xc = np.arange(npos) * lam / npos
    amp = eps / k                                     # |Z| with R = a0 = 1
    za, zb = amp * np.cos(phase), amp * np.sin(phase)
    a, d, _, dd = solve_normal_exact(xc, 0.5, 1.0, [k], [za], [zb])
    ast = solve_stick_zone_exact(xc, a, d, 1.0 - r, 1.0, [k], [za], [zb])
    if degree is None:
        degree = int(np.ceil(np.e * k)) + 14
    n = np.arange(1, degree + 1)
    zeta = za - 1j * zb
    jn_a = jv(n[None, :], k * a[:, None])
    jn_s = jv(n[None, :], k * ast[:, None])
    ipow = (1j) ** ((n + 1) % 4)
    cn = -2 * k * jn_a * np.real(ipow[None, :] * zeta * np.exp(1j * k * (xc + d))[:, None])
    cn[:, 0] += a
    xs_c = a - ast                                    # stick centre, patch coordinate
    dn = -2 * k * jn_s * np.real(ipow[None, :] * zeta
                                 * np.exp(1j * k * (xc + d + xs_c))[:, None])
    dn[:, 0] += ast
    jq = np.arange(1, n_nodes + 1)
    t = np.cos((2 * jq - 1) * np.pi / (2 * n_nodes))
    wq = np.pi / n_nodes * np.sqrt(1 - t * t)
    half = (a - ast)[:, None]
    x = -ast[:, None] + half * t[None, :]
    theta = np.arccos(np.clip(x / a[:, None], -1, 1))
    p = np.einsum("pjn,pn->pj", np.sin(theta[..., None] * n), cn) / np.pi
    v = (x - xs_c[:, None]) / np.maximum(ast[:, None], 1e-300)
    v = np.minimum(v, -1.0)
    w = 1.0 / (v - np.sqrt(v * v - 1.0))
    g2 = ((d[:, None] + x) + k * np.real(-1j * zeta * np.exp(1j * k * (xc[:, None] + d[:, None]
                                                                        + x)))
          - (1.0 - r))
    s = np.abs(np.einsum("pjn,pn->pj", w[..., None] ** n, dn) - g2)
    dens = np.sum(p * s * np.exp(-1j * k * x) * wq, -1) * half[:, 0]
    base = np.exp(-1j * k * (xc + d)) * lam / npos
    out = {}
    zc_ab = za + 1j * zb

    def harmonic(vals):          # c with Q_A + i Q_B = c (Z_A + i Z_B), per unit k R (R = 1)
        return 2 * np.mean(vals * np.exp(1j * k * xc)) / zc_ab / k

    xs_axis = d + a - ast
    t_exact = -(ast ** 2 / 2 + k * ast * j1(k * ast) * (za * np.cos(k * (xc + xs_axis))
                                                        + zb * np.sin(k * (xc + xs_axis))))
    out["half_width"] = harmonic(a)
    out["patch_shift"] = harmonic(d)
    out["stick_half_width"] = harmonic(ast)
    out["tangential_force"] = harmonic(t_exact) * k      # units mu pi E/(4(1-nu^2)), C = 1
    for name, weight in (("material_point", 1.0), ("patch_coordinate", 1.0 + dd)):
        first = np.sum(weight * dens * base) / lam      # (1/L) int W e^{-ikX0} dX0, K = 1
        # W = W0 + Re[H zeta e^{ikX0}] -> first = H zeta / 2 ; c = conj(H); w = c / (1/2)
        h = 2 * first / zeta
        out[name] = 2 * np.conj(h)
    out["mean"] = 2.0 * float(np.sum(np.sum(p * s * wq, -1) * half[:, 0])) / npos
    return out


LinearResponse = namedtuple("LinearResponse", [
    "patch_shift", "half_width", "stick_half_width", "tangential_force", "tau", "tau_star",
    "wear", "w1", "w2", "growth_factor"])
LinearResponse.__doc__ = """Result of :func:`linear_response` (arrays broadcast over the inputs).

Complex coefficients ``c`` with ``Q_A + i Q_B = c (Z_A + i Z_B)`` (amplitude ``|c| |Z|``, phase
``arg c`` in the package orientation, rolling +X; the thesis' phase is ``-arg c``):

patch_shift, half_width, stick_half_width : complex
    Delta, a, a* over ``k R`` ((4.36), (4.37), (4.59)-(4.62)).
tangential_force : complex
    |T| in units of ``mu pi E / (4 (1 - nu^2))`` ((4.68)-(4.71)); ``T0 = mu N (1 - r^2)``.
tau, tau_star : complex
    Half passage times |tau|, |tau*| over ``k R / V`` (consistent kinematics; see
    :func:`passage_time_response`).
wear : complex
    ``w = (W1 + i W2) a0 / (K mu^2 N)`` of the chosen wear model.
w1, w2 : float
    ``W1 = wear_number Re(w)``, ``W2 = wear_number Im(w)`` (0 when ``wear_number = 0``).
growth_factor : float
    ``1 - 2 W1`` (4.104); 1 if no wear number was given.
"""


def linear_response(a0_over_wavelength, stick_ratio, wear_model=DEFAULT_WEAR_MODEL,
                    wear_number=0.0):
    r"""All linearised response coefficients of one harmonic, normalised (tables, FMU).

    One call for the table builder: Delta, a, a*, T, tau, tau*, wear ``w`` and, with the wear
    number ``K mu^2 N / a0``, ``W1``, ``W2`` and the growth factor ``1 - 2 W1``.

    Parameters
    ----------
    a0_over_wavelength : array_like
        a0/L, > 0. [-]
    stick_ratio : array_like
        r_a0 in [0, 1]. [-]
    wear_model : str
        One of :data:`WEAR_MODELS`; default ``"material_point"`` (see module docstring and
        ``docs/wear_finding.md``).
    wear_number : array_like
        ``K mu^2 N / a0`` (:func:`railcontact.evolution.wear_number`), >= 0; 0 gives
        ``w1 = w2 = 0`` and ``growth_factor = 1``. [-]

    Returns
    -------
    LinearResponse
    """
    eps = check_range("wear_number", wear_number, "-", 0.0, None)
    cd, ca = normal_response(a0_over_wavelength)
    cs = stick_zone_response(a0_over_wavelength, stick_ratio)
    ct = tangential_force_response(a0_over_wavelength, stick_ratio)
    tau, taus = passage_time_response(a0_over_wavelength, stick_ratio)
    w = wear_coefficients(a0_over_wavelength, stick_ratio, wear_model)
    w1, w2 = eps * w.real, eps * w.imag
    return LinearResponse(cd, ca, cs, ct, tau, taus, w, w1, w2, 1.0 - 2.0 * w1)


def corrugated_wear_depth(rail_position, normal_load, radius, youngs_modulus, poisson_ratio,
                          friction_coefficient, creepage, amplitudes_cos, amplitudes_sin,
                          wavelengths, wear_coefficient, wear_model=DEFAULT_WEAR_MODEL):
    r"""Wear per passage at rail points of a corrugated rail, linearised (Eqs. (4.94)-(4.96)).

    ``W(X) = W0 + sum_m Re[(K mu^2 N / a0) w_m (Z_A,m + i Z_B,m) e^{-i k_m X}]`` with
    ``W0 = K mu^2 N a0/R (1 - r)^2 (1 + r)`` (4.96, :func:`mean_wear`), ``w_m`` =
    :func:`wear_coefficients` at ``(a0/L_m, r_a0)`` and ``r_a0 = max(a0 - |xi| R/mu, 0)/a0``
    (Carter's stick ratio of the smooth contact, about which the wear is linearised), at the
    *material points* X (the wear one passage leaves at that rail point). The contact on the
    corrugated rail itself is :func:`railcontact.corrugation.corrugated_contact`, which takes the
    same first ten arguments.

    Parameters
    ----------
    rail_position : array_like
        Rail point(s) X. [m]
    normal_load, radius, youngs_modulus, poisson_ratio, friction_coefficient, creepage
        As in :func:`railcontact.corrugation.corrugated_contact`: N per unit length > 0 [N/m],
        R > 0 [m], E > 0 [Pa], nu in [0, 0.5) [-], mu > 0 [-], longitudinal creepage [-].
    amplitudes_cos, amplitudes_sin, wavelengths : array_like, shape (M,)
        Surface harmonics Z_A,m, Z_B,m of (4.1) [m] and their wavelengths L_m > 0 [m];
        condition (4.2) must hold.
    wear_coefficient : float
        K of (4.74), >= 0. [m^2/N]
    wear_model : str
        One of :data:`WEAR_MODELS` (default "material_point").

    Returns
    -------
    ndarray
        W(X), shape of ``rail_position``. [m]

    Raises
    ------
    ValueError
        Bad input (naming it), or condition (4.2) violated.
    """
    n_load, big_r, e_mod, nu, mu, xi, za, zb, lam = check_corrugated_contact_inputs(
        normal_load, radius, youngs_modulus, poisson_ratio, friction_coefficient, creepage,
        amplitudes_cos, amplitudes_sin, wavelengths)
    kw = float(check_range("wear_coefficient", wear_coefficient, "m^2/N", 0.0, None))
    check_choice("wear_model", wear_model, WEAR_MODELS)
    x = check_range("rail_position", rail_position, "m")
    k = _TWO_PI / lam
    check_no_contact_loss(k * k * big_r * np.hypot(za, zb))
    check_load_not_underflowing(n_load, e_mod, nu)
    wear = corrugated_wear_depth_unchecked(np.ravel(x), float(n_load), float(big_r),
                                           float(e_mod), float(nu), float(mu), float(xi), za,
                                           zb, lam, kw, wear_model)
    return np.reshape(wear, np.shape(x))


def corrugated_wear_depth_unchecked(rail_position, normal_load, radius, youngs_modulus,
                                   poisson_ratio, friction_coefficient, creepage, amplitudes_cos,
                                   amplitudes_sin, wavelengths, wear_coefficient,
                                   wear_model=DEFAULT_WEAR_MODEL):
    """:func:`corrugated_wear_depth` without its range checks: its one implementation, which it
    calls after checking, and the FMU's corrugation effect calls once per step.

    Takes the arguments of :func:`corrugated_wear_depth` with the loads, moduli, mu and the
    creepage as plain floats and the harmonics as sequences or float arrays; assumes what that
    function checks (N, mu > 0, condition (4.2), a normalised load that does not underflow, a
    known wear model) and checks nothing. The series models' coefficients come from the compiled
    kernel's entry point for one r (the nodes and degree of :func:`wear_coefficients`, which
    raises its ValueError for a degree beyond its limit), the time-domain models' from
    :func:`wear_coefficients`; the superposition is one compiled kernel.

    Returns
    -------
    float or ndarray
        W at ``rail_position``: a float for a scalar position, else a 1-D array. [m]
    """
    x, n_load, big_r, nu, mu = (rail_position, normal_load, radius, poisson_ratio,
                                friction_coefficient)
    a0 = math.sqrt(8.0 * (1.0 - nu * nu) * big_r * n_load / (math.pi * youngs_modulus))
    r = max(a0 - abs(creepage) * big_r / mu, 0.0) / a0
    kw = wear_coefficient
    w0 = kw * mu * mu * n_load * a0 / big_r * (1 - r) ** 2 * (1 + r)
    lam = np.asarray(wavelengths, dtype=float)
    if wear_model in ("material_point", "patch_coordinate"):
        cw = _kernels.wear_coefficients_series(a0 / lam, r, wear_model)
    else:
        cw = np.ravel(wear_coefficients(a0 / lam, r, wear_model)).astype(complex)
    wear = _kernels.wear_depth_array(
        np.array(x, dtype=float, ndmin=1), w0, kw * mu * mu * n_load / a0, _TWO_PI / lam,
        np.asarray(amplitudes_cos, dtype=float), np.asarray(amplitudes_sin, dtype=float), cw)
    return float(wear[0]) if np.ndim(x) == 0 else wear
