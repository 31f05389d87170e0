r"""Velocity-dependent friction in 2-D steady rolling (Nielsen 1998, Ch. 5, Eqs. (5.2)-(5.17)).

Why one module of about 1,150 lines: it is Ch. 5 of the thesis (the friction laws, Ohyama's
step law in closed form, the smooth law's iteration, its peak and saturation creepage), whose
parts share one set of normalised variables.

Friction laws
-------------
A friction law is any vectorised callable ``mu(s)`` of the dimensionless slip magnitude
``s = |slip velocity| / V_m >= 0`` (Eq. (5.2)). Three are provided as small objects:

* :class:`CoulombFriction` -- constant ``mu`` (Eq. (5.1));
* :class:`StepFriction` -- Ohyama's step law, ``mu_static`` at ``s = 0``, ``mu_kinetic`` else (5.3);
* :class:`SmoothFriction` -- ``mu(s) = (mu_0 - mu_k) / (1 + |kappa s|) + mu_k`` (5.16).

A law in the slip *velocity* ``w = s V`` [m/s] needs the rolling speed V: :class:`PolachFriction`
(Polach 2005, ``mu = mu0 ((1 - A) exp(-B w) + A)``) says so with ``needs_rolling_speed = True``
and becomes a law in ``s`` with :meth:`PolachFriction.at_rolling_speed`. The 3-D creep methods
(:func:`railcontact.creep3d.creep_force_3d`, ``friction_coefficient`` and ``rolling_speed``) do
this themselves.

Users may pass their own callable (e.g. ``lambda s: 0.3 - 0.1 * np.tanh(50 * s)``); the static
value is ``mu(0)``.

Convention
----------
Package convention (see :mod:`railcontact`): the traction and force act on the wheel and oppose
the creepage; the leading edge is ``x = +a0`` and the stick zone ``[a0 - 2 a*, a0]`` touches it
(the thesis draws the mirror image). The slip is ``s(x) = xi + (4(1-nu^2)/(pi E)) PV int q(z) /
(x - z) dz`` (as in :mod:`railcontact.carter` and :mod:`railcontact.reference.halfspace2d`).

Normalisation (the table coordinates)
-------------------------------------
With the Hertz half-width ``a0`` and ``xi_c0 = mu_0 a0 / R`` (Carter's critical creepage for the
*static* coefficient, Eq. (2.54)) every smooth-law result depends only on

* ``creepage_ratio = xi / xi_c0``,
* ``friction_ratio = mu_k / mu_0``,
* ``kappa_normalised = kappa xi_c0`` (the slope of (5.16) per unit of normalised slip),

and the force is returned as ``T / (mu_0 N)``. :func:`normalised_inputs` converts physical
inputs to these coordinates.

The iteration of Sec. 5.3 ((5.7)-(5.15))
----------------------------------------
For a given stick-zone half-width ``a* = r a0`` the traction is split as in (5.8),
``q = q1(x) + q2(x*)``:

* ``q1 = mu(x) p(x)`` on the whole patch with ``mu(x)`` a polynomial (5.7): the Chebyshev
  interpolant, at ``degree`` first-kind nodes of ``[-a0, a0]``, of ``mu(s(x))`` in the slip zone
  (continued by ``mu(0)`` in the stick zone, where ``q2`` absorbs whatever ``q1`` is). In the
  Chebyshev-U basis ``mu = sum c_n U_n(x/a0)`` the half-space relation is exact:
  ``(1/pi) PV int sqrt(1 - z^2) U_n(z) / (x - z) dz = T_{n+1}(x)`` inside and
  ``(x - sign(x) sqrt(x^2 - 1))^{n+1}`` outside the patch (this replaces the monomial
  coefficients (5.10)-(5.15) by an equivalent, better conditioned basis).
* ``q2`` is the polynomial form on the stick zone that is bounded at both of its ends (the
  polynomial approach of Ch. 3); its existence condition gives the creepage for the given ``a*``
  (for constant ``mu`` this is Carter's (2.52)).
* The slip in the slip zone follows in closed form, ``mu(s)`` is updated and the fixed point is
  found to the tolerance ``tol`` (max change of ``mu/mu_0`` at the nodes). The map from the nodal
  ``mu`` values to the slip is affine, so the fixed point is solved by Newton's method (the plain
  substitution of Sec. 5.3 oscillates for rising laws, ``mu_k > mu_0``, at large ``kappa``).

Accuracy: ``mu(s(x))`` has a square-root kink at the stick/slip limit, so the polynomial converges
slowly with ``degree``: about 1e-3 ``mu_0 N`` in the force for ``degree = 128`` (checked against
the discretised reference solver, ``tests/test_friction.py``; measured in
``benchmarks/bench_friction_nonsteady.py``). A very steep law (``kappa_normalised >> degree``) is
resolved only in the integral sense (the creep curve), not the boundary layer of the traction.

References
----------
.. [1] J.B. Nielsen, New Developments in the Theory of Wheel/Rail Contact Mechanics,
   IMM-PHD-1998-51, DTU, 1998, Ch. 5.
.. [2] T. Ohyama, Some basic studies on the influence of surface contamination on adhesion
   force between wheel and rail at higher speeds, Quarterly Report RTRI 30(3) (1989) 127-135
   (ref. [53] of [1]; the step-law model of [1], Sec. 5.2).
.. [3] F.W. Carter, On the action of a locomotive driving wheel, Proc. R. Soc. A 112 (1926).
"""

from __future__ import annotations

from collections import namedtuple
from dataclasses import dataclass

import numpy as np
from numpy.polynomial import chebyshev as _cheb

from ._validation import check_range
from .hertz import hertz_2d

__all__ = [
    "CoulombFriction", "StepFriction", "SmoothFriction", "PolachFriction",
    "normalised_inputs",
    "ohyama_creep_force_normalised", "ohyama_traction_normalised",
    "step_law_creep_force_normalised", "step_law_traction_normalised",
    "VelocityFrictionSolution", "solve_velocity_friction_normalised",
    "velocity_friction_creep_force_normalised", "velocity_friction_peak_normalised",
    "velocity_friction_creep_force", "velocity_friction_traction",
    "velocity_friction_peak_creepage",
    "velocity_friction_saturation_creepage", "velocity_friction_saturation_curve",
    "SaturationCurve",
]


# ---------------------------------------------------------------------------------------------
# friction laws
# ---------------------------------------------------------------------------------------------
class CoulombFriction:
    """Constant friction coefficient, Eq. (5.1).

    Parameters
    ----------
    mu : float
        Friction coefficient, >= 0. [-]
    """

    def __init__(self, mu):
        self.mu = float(check_range("mu", mu, "-", 0.0, None))

    @property
    def mu_static(self):
        return self.mu

    def __call__(self, slip):
        return np.full(np.shape(slip), self.mu)

    def derivative(self, slip):
        """d mu / d s. [-]"""
        return np.zeros(np.shape(slip))

    def __repr__(self):
        return f"CoulombFriction(mu={self.mu:g})"


class StepFriction:
    """Ohyama's step law, Eq. (5.3): ``mu_static`` for ``s = 0``, ``mu_kinetic`` for ``s != 0``.

    Parameters
    ----------
    mu_static : float
        Static coefficient mu_0, >= 0. [-]
    mu_kinetic : float
        Kinetic coefficient mu_k, >= 0. [-]
    """

    def __init__(self, mu_static, mu_kinetic):
        self.mu_static = float(check_range("mu_static", mu_static, "-", 0.0, None))
        self.mu_kinetic = float(check_range("mu_kinetic", mu_kinetic, "-", 0.0, None))

    def __call__(self, slip):
        s = np.abs(np.asarray(slip, dtype=float))
        return np.where(s == 0.0, self.mu_static, self.mu_kinetic)

    def __repr__(self):
        return f"StepFriction(mu_static={self.mu_static:g}, mu_kinetic={self.mu_kinetic:g})"


class SmoothFriction:
    r"""Smooth velocity-dependent law, Eq. (5.16): ``mu = (mu_0 - mu_k) / (1 + |kappa s|) + mu_k``.

    ``mu(0) = mu_0``, ``mu(inf) = mu_k`` (5.17), initial slope ``-(mu_0 - mu_k) kappa``.

    Parameters
    ----------
    mu_static : float
        mu_0 = mu(0), >= 0. [-]
    mu_kinetic : float
        mu_k = lim mu(s), s -> inf, >= 0. [-]
    kappa : float
        Slope parameter kappa, >= 0 (0 gives Coulomb with mu_0). [-]
    """

    def __init__(self, mu_static, mu_kinetic, kappa):
        self.mu_static = float(check_range("mu_static", mu_static, "-", 0.0, None))
        self.mu_kinetic = float(check_range("mu_kinetic", mu_kinetic, "-", 0.0, None))
        self.kappa = float(check_range("kappa", kappa, "-", 0.0, None))

    def __call__(self, slip):
        s = np.abs(np.asarray(slip, dtype=float))
        return (self.mu_static - self.mu_kinetic) / (1.0 + self.kappa * s) + self.mu_kinetic

    def derivative(self, slip):
        """d mu / d|s|. [-]"""
        s = np.abs(np.asarray(slip, dtype=float))
        return -(self.mu_static - self.mu_kinetic) * self.kappa / (1.0 + self.kappa * s) ** 2

    def __repr__(self):
        return (f"SmoothFriction(mu_static={self.mu_static:g}, mu_kinetic={self.mu_kinetic:g}, "
                f"kappa={self.kappa:g})")


class PolachFriction:
    r"""Polach's falling friction in the slip velocity (Polach 2005 [4]):
    ``mu(w) = mu0 ((1 - A) exp(-B w) + A)``, ``w`` the slip velocity magnitude [m/s].

    The same formula as :func:`railcontact.polach.polach_friction`, as a law object. Polach's
    own creep-force method evaluates it at the slip velocity of the whole contact, ``V |xi|``;
    the exact theory (``creep_force_3d(..., method="exact", friction_coefficient=law,
    rolling_speed=V)``) evaluates it element by element at the local slip velocity ``V |s|``.

    Parameters
    ----------
    mu_static : float
        mu0 = mu(0), > 0. [-]
    friction_ratio_limit : float
        A = mu(inf) / mu0, in [0, 1]; 1 = Coulomb. [-]
    friction_decay : float
        Exponential decrease rate B, >= 0 (0 = Coulomb). [s/m]

    Attributes
    ----------
    needs_rolling_speed : bool
        True: the argument is the slip velocity, not the slip ``s = w / V``. The 3-D creep
        methods then need ``rolling_speed``; :meth:`at_rolling_speed` gives the law in ``s``.

    References
    ----------
    .. [4] O. Polach, Creep forces in simulations of traction vehicles running on adhesion
       limit, Wear 258 (2005) 992-1000.
    """

    needs_rolling_speed = True

    def __init__(self, mu_static, friction_ratio_limit, friction_decay):
        self.mu_static = float(check_range("mu_static", mu_static, "-", 0.0, None,
                                           lower_closed=False))
        self.friction_ratio_limit = float(check_range(
            "friction_ratio_limit", friction_ratio_limit, "-", 0.0, 1.0))
        self.friction_decay = float(check_range("friction_decay", friction_decay, "s/m", 0.0,
                                                None))

    @property
    def mu_kinetic(self):
        """mu(inf) = A mu0. [-]"""
        return self.friction_ratio_limit * self.mu_static

    def __call__(self, slip_velocity):
        from .polach import polach_friction  # noqa: PLC0415  (one formula, polach.py's)

        return polach_friction(self.mu_static, np.abs(np.asarray(slip_velocity, dtype=float)),
                               self.friction_ratio_limit, self.friction_decay)

    def at_rolling_speed(self, rolling_speed):
        """The law in the slip ``s = w / V`` at rolling speed V > 0 [m/s]: ``s -> mu(s V)``."""
        speed = float(check_range("rolling_speed", rolling_speed, "m/s", 0.0, None,
                                  lower_closed=False))
        return LawAtRollingSpeed(self, speed)

    def __repr__(self):
        return (f"PolachFriction(mu_static={self.mu_static:g}, friction_ratio_limit="
                f"{self.friction_ratio_limit:g}, friction_decay={self.friction_decay:g})")


class LawAtRollingSpeed:
    """A law in slip velocity seen as a law in the slip s at a rolling speed: ``mu(s V)``.

    Parameters
    ----------
    law : callable
        mu(w) of the slip velocity w. [m/s] -> [-]
    rolling_speed : float
        V > 0. [m/s]
    """

    def __init__(self, law, rolling_speed):
        self.law = law
        self.rolling_speed = float(rolling_speed)

    @property
    def mu_static(self):
        return float(np.asarray(self.law(np.zeros(1)), dtype=float).ravel()[0])

    def __call__(self, slip):
        return self.law(np.abs(np.asarray(slip, dtype=float)) * self.rolling_speed)

    def __repr__(self):
        return f"{self.law!r} at rolling_speed={self.rolling_speed:g} m/s"


def _mu_static(law):
    if getattr(law, "needs_rolling_speed", False):
        raise ValueError(f"friction_law {law!r} is a law in the slip velocity [m/s]; pass "
                         f"law.at_rolling_speed(V), a law in the slip s = w / V [-]")
    if not callable(law):
        raise ValueError(f"friction_law must be a callable mu(s) [-]; got {law!r}")
    mu0 = np.asarray(law(np.zeros(1)), dtype=float).ravel()
    return float(check_range("friction_law(0)", mu0[0], "-", 0.0, None))


# ---------------------------------------------------------------------------------------------
# normalisation
# ---------------------------------------------------------------------------------------------
def normalised_inputs(creepage, normal_load, radius, youngs_modulus, poisson_ratio,
                      mu_static, mu_kinetic=None, kappa=None):
    r"""Convert physical inputs to the normalised coordinates of this module.

    Parameters
    ----------
    creepage : array_like
        Longitudinal creepage xi. [-]
    normal_load : array_like
        Normal load per unit length N, > 0. [N/m]
    radius : array_like
        Equivalent radius R, > 0. [m]
    youngs_modulus : array_like
        Young's modulus E, > 0. [Pa]
    poisson_ratio : array_like
        Poisson's ratio, in [0, 0.5). [-]
    mu_static : array_like
        mu_0, > 0. [-]
    mu_kinetic, kappa : array_like, optional
        mu_k >= 0 and kappa >= 0 of (5.16). [-]

    Returns
    -------
    dict
        ``creepage_ratio = xi / xi_c0``, ``critical_creepage = xi_c0 = mu_0 a0 / R``,
        ``friction_ratio = mu_k / mu_0`` and ``kappa_normalised = kappa xi_c0`` (if given),
        ``force_scale = mu_0 N`` [N/m].
    """
    xi = check_range("creepage", creepage, "-")
    n_load = check_range("normal_load", normal_load, "N/m", 0.0, None, lower_closed=False)
    mu0 = check_range("mu_static", mu_static, "-", 0.0, None, lower_closed=False)
    h = hertz_2d(n_load, radius, youngs_modulus, poisson_ratio)
    r = np.asarray(radius, dtype=float)
    xi_c = mu0 * h.a0 / r
    out = {"creepage_ratio": xi / xi_c, "critical_creepage": xi_c, "force_scale": mu0 * n_load}
    if mu_kinetic is not None:
        out["friction_ratio"] = check_range("mu_kinetic", mu_kinetic, "-", 0.0, None) / mu0
    if kappa is not None:
        out["kappa_normalised"] = check_range("kappa", kappa, "-", 0.0, None) * xi_c
    return out


def _sqrt_pos(v):
    return np.sqrt(np.clip(v, 0.0, None))


def _carter_force_ratio(chi, mu_ratio):
    """|T| / (mu_0 N) of Carter with coefficient mu_ratio * mu_0 at |xi| / xi_c0 = chi."""
    with np.errstate(over="ignore"):             # tiny mu_ratio: frac = inf, clipped to 1
        frac = np.divide(chi, mu_ratio, out=np.full(np.broadcast(chi, mu_ratio).shape, np.inf),
                         where=mu_ratio > 0)
    frac = np.minimum(np.where((chi == 0), 0.0, frac), 1.0)
    # 1 - r^2 = f (2 - f) with f = 1 - r: no cancellation at tiny creepage
    return mu_ratio * (frac * (2.0 - frac))


def _circle_segment_area(h):
    """``int_{-1}^{-1+h} sqrt(1 - x^2) dx`` for ``h`` in [0, 2], without cancellation at small h.

    Small h: the series ``sqrt(2) [2/3 h^1.5 - 1/10 h^2.5 - 1/112 h^3.5 - 1/576 h^4.5]`` of
    ``int_0^h sqrt(t (2 - t)) dt`` (relative truncation error < h^4 ~ 1e-12 for h < 1e-3);
    otherwise the primitive.
    """
    h = np.clip(h, 0.0, 2.0)
    series = np.sqrt(2.0) * h * np.sqrt(h) * (2.0 / 3.0 - h * (0.1 + h * (1.0 / 112.0
                                                                          + h / 576.0)))
    u = h - 1.0
    prim = 0.5 * (u * _sqrt_pos(1.0 - u * u) + np.arcsin(np.clip(u, -1.0, 1.0))) + np.pi / 4.0
    return np.where(h < 1e-3, series, prim)


# ---------------------------------------------------------------------------------------------
# step law: Ohyama and the corrected (minimum) solution, Sec. 5.2
# ---------------------------------------------------------------------------------------------
def ohyama_creep_force_normalised(creepage_ratio, friction_ratio):
    r"""Creep curve of Ohyama's step-law solution as described in Sec. 5.2 (Fig. 5.2, solid).

    Ohyama's stress is Carter's with ``mu_0`` in the stick zone and ``mu_k p`` in the slip zone
    (Fig. 5.1), with the stick zone ``r = a*/a0 = 1 - |xi|/xi_c0`` of the ``mu_0`` Carter solution
    (Carter's creepage relation (2.52) for ``mu_0``). Integrated:
    ``|T|/(mu_0 N) = (2/pi)[I(b, 1) + m I(-1, b)] - r^2`` with ``b = 1 - 2 r``,
    ``I(u, v) = int_u^v sqrt(1 - x^2) dx``. This is a reading of the thesis' description (Ohyama's
    paper was not available); it reproduces the features the thesis states: zero at ``xi = 0``,
    ``mu_k N`` at ``|xi| >= xi_c0``, a maximum above ``mu_k N`` for ``m < 1``, and a curve that
    leaves the band between the two Carter curves (which the thesis shows to be wrong).

    Parameters
    ----------
    creepage_ratio : array_like
        xi / xi_c0, xi_c0 = mu_0 a0 / R. [-]
    friction_ratio : array_like
        m = mu_k / mu_0, >= 0. [-]

    Returns
    -------
    ndarray
        T / (mu_0 N), opposite in sign to the creepage. [-]
    """
    chi = check_range("creepage_ratio", creepage_ratio, "-")
    m = check_range("friction_ratio", friction_ratio, "-", 0.0, None)
    # With r = 1 - f, f = min(|chi|, 1), b = 1 - 2r = -1 + 2f and I(-1, 1) = pi/2:
    # (2/pi)[I(b, 1) + m I(-1, b)] - r^2 = f (2 - f) - (2/pi)(1 - m) I(-1, -1 + 2f),
    # written so that tiny creepage loses no digits (the printed form cancels).
    f = np.minimum(np.abs(chi), 1.0)
    force = f * (2.0 - f) - (2.0 / np.pi) * (1.0 - m) * _circle_segment_area(2.0 * f)
    return (-np.sign(chi) * force)[()]


def ohyama_traction_normalised(x_ratio, creepage_ratio, friction_ratio):
    r"""Ohyama's step-law traction (Fig. 5.1), ``q / (mu_0 p0)`` at ``x / a0``.

    Stick zone ``[1 - 2r, 1]``: Carter with ``mu_0``; slip zone: ``mu_k p``. See
    :func:`ohyama_creep_force_normalised`.

    Parameters
    ----------
    x_ratio : array_like
        x / a0 (leading edge +1). [-]
    creepage_ratio : array_like
        xi / xi_c0. [-]
    friction_ratio : array_like
        mu_k / mu_0, >= 0. [-]

    Returns
    -------
    ndarray
        q / (mu_0 p0) on the wheel. [-]
    """
    x = check_range("x_ratio", x_ratio, "-")
    chi = check_range("creepage_ratio", creepage_ratio, "-")
    m = check_range("friction_ratio", friction_ratio, "-", 0.0, None)
    r = np.clip(1.0 - np.abs(chi), 0.0, 1.0)
    b = 1.0 - 2.0 * r
    p = _sqrt_pos(1.0 - x * x)
    stick = p - _sqrt_pos(r * r - (x - 1.0 + r) ** 2)
    q = np.where(x >= b, stick, m * p)
    return (-np.sign(chi) * q)[()]


def step_law_creep_force_normalised(creepage_ratio, friction_ratio):
    r"""Creep curve of the step law (5.3), the thesis' corrected (minimum) solution (5.4)-(5.6).

    For ``mu_k < mu_0`` the minimum solution is Carter's with ``mu_k`` plus a peak of zero
    integral at the stick/slip limit (Fig. 5.3); the thesis states the same creep curve (the upper
    Carter curve) for ``mu_k > mu_0``. Both are confirmed here as the limit ``kappa -> inf`` of
    the smooth law (``tests/test_friction.py``). So ``|T| / (mu_0 N) = m [1 - (1 - chi/m)^2]``
    for ``chi < m``, else ``m``; no falling branch: a step law gives no negative damping.

    Parameters
    ----------
    creepage_ratio : array_like
        xi / xi_c0, xi_c0 = mu_0 a0 / R. [-]
    friction_ratio : array_like
        m = mu_k / mu_0, >= 0. [-]

    Returns
    -------
    ndarray
        T / (mu_0 N), opposite in sign to the creepage. [-]
    """
    chi = check_range("creepage_ratio", creepage_ratio, "-")
    m = check_range("friction_ratio", friction_ratio, "-", 0.0, None)
    return (-np.sign(chi) * _carter_force_ratio(np.abs(chi), m))[()]


def step_law_traction_normalised(x_ratio, creepage_ratio, friction_ratio):
    r"""Traction of the corrected step-law solution, ``q / (mu_0 p0)`` (Fig. 5.3).

    Carter with ``mu_k`` (stick zone ``r_k = 1 - |chi| / m``); for ``m < 1`` the solution also
    has the value ``mu_0 p`` at the single point ``x = 1 - 2 r_k`` (the thesis' "Kronecker peak",
    zero integral), which is returned when ``x_ratio`` hits that point exactly.

    Parameters
    ----------
    x_ratio : array_like
        x / a0 (leading edge +1). [-]
    creepage_ratio : array_like
        xi / xi_c0. [-]
    friction_ratio : array_like
        mu_k / mu_0, >= 0. [-]

    Returns
    -------
    ndarray
        q / (mu_0 p0) on the wheel. [-]
    """
    x = check_range("x_ratio", x_ratio, "-")
    chi = check_range("creepage_ratio", creepage_ratio, "-")
    m = check_range("friction_ratio", friction_ratio, "-", 0.0, None)
    frac = np.divide(np.abs(chi), m, out=np.full(np.broadcast(chi, m).shape, np.inf),
                     where=m > 0)
    frac = np.where(chi == 0, 0.0, frac)
    r = np.clip(1.0 - frac, 0.0, 1.0)
    p = _sqrt_pos(1.0 - x * x)
    q = m * (p - _sqrt_pos(r * r - (x - 1.0 + r) ** 2))
    peak = (x == 1.0 - 2.0 * r) & (m < 1.0) & (r > 0) & (r < 1)
    q = np.where(peak, p, q)
    return (-np.sign(chi) * q)[()]


# ---------------------------------------------------------------------------------------------
# smooth law: the iteration of Sec. 5.3
# ---------------------------------------------------------------------------------------------
def _cheb_nodes(n):
    return np.cos(np.pi * (np.arange(n) + 0.5) / n)


def _cheb_coef_matrix(n):
    """Matrix mapping values at the n first-kind nodes to T coefficients of the interpolant."""
    theta = np.pi * (np.arange(n) + 0.5) / n
    mat = (2.0 / n) * np.cos(np.arange(n)[:, None] * theta[None, :])
    mat[0] *= 0.5
    return mat


def _t_to_u_matrix(n):
    """c = M a with sum a_k T_k = sum c_k U_k (T_0 = U_0, T_1 = U_1/2, T_k = (U_k - U_{k-2})/2)."""
    mat = np.zeros((n, n))
    mat[0, 0] = 1.0
    for k in range(1, n):
        mat[k, k] += 0.5
        if k >= 2:
            mat[k - 2, k] -= 0.5 if k > 2 else 0.5
    return mat


class _NormalisedSolver:
    """Polynomial-approach solver of Sec. 5.3 for a normalised law g(sigma) = mu(s)/mu_0.

    sigma = s / xi_c0, traction t = q / (mu_0 p0) in the magnitude frame (t >= 0 for creepage > 0),
    x in units of a0, leading edge +1, stick zone [1 - 2r, 1]. Carter: t = sqrt(1-x^2) -
    sqrt(r^2 - (x - 1 + r)^2), sigma = chi - (1/pi) PV int t(z)/(x - z) dz.
    """

    def __init__(self, g, dg, degree, tol, max_iter, label):
        self.g, self.dg = g, dg
        self.n = int(degree)
        self.tol, self.max_iter, self.label = float(tol), int(max_iter), label
        n = self.n
        self.x = _cheb_nodes(n)
        self.coef = _cheb_coef_matrix(n)
        self.t2u = _t_to_u_matrix(n)
        self.cmat = self.t2u @ self.coef                   # nodal mu -> U coefficients c
        self.tx = _cheb.chebvander(self.x, n)[:, 1:]       # T_{k+1}(x_j)
        self.ny = n + 4
        self.yn = _cheb_nodes(self.ny)
        self.coef_y = _cheb_coef_matrix(self.ny)
        self._maps = {}

    # affine maps (linear, no constant term) for a given stick ratio r
    def maps(self, r):
        key = float(r)
        hit = self._maps.get(key)
        if hit is not None:
            return hit
        n, x = self.n, self.x
        h1 = self.tx @ self.cmat                            # H[t1] at nodes
        if r > 0.0:
            xc = 1.0 - r
            ty = _cheb.chebvander(xc + r * self.yn, n)[:, 1:]
            e = self.coef_y @ (ty @ self.cmat)              # (ny, n): T coefficients of H[t1]
            chi_row = e[0]
            dmat = -e[1:n + 1]                              # stick-zone U coefficients d
            y = (x - xc) / r
            slip = x < 1.0 - 2.0 * r
            w = np.where(slip, y + _sqrt_pos(y * y - 1.0), 0.0)
            wv = w[:, None] ** np.arange(1, n + 1)[None, :]
            sig = chi_row[None, :] - h1 - wv @ dmat
            force_row = self.cmat[0] + r * dmat[0]
        else:
            slip = x < 1.0
            chi_row = np.ones(n) @ self.cmat
            dmat = np.zeros((n, n))
            sig = chi_row[None, :] - h1
            force_row = self.cmat[0].copy()
        out = (sig, chi_row, dmat, force_row, slip)
        if len(self._maps) > 64:
            self._maps.clear()
        self._maps[key] = out
        return out

    def _newton(self, sig_map, sig0, free, mu, lam_law=1.0):
        """Solve mu_f = g(lam sigma^+), sigma = sig_map @ mu + sig0, on the free nodes (Newton).

        ``sigma^+ = max(sigma, 0)``: a node whose slip comes out negative (possible only through
        the polynomial approximation next to the stick/slip limit) gets mu_0, like the stick zone.
        Returns (mu, sigma, steps, residual) or raises ``_NoConvergence``.
        """
        g, dg = self.g, self.dg
        a = sig_map[np.ix_(free, free)]
        eye = np.eye(int(free.sum()))

        def resid(m_):
            sf_ = (sig_map @ m_ + sig0)[free]
            return sf_, g(lam_law * np.maximum(sf_, 0.0)) - m_[free]

        sf, f = resid(mu)
        norm = float(np.max(np.abs(f))) if f.size else 0.0
        for it in range(1, self.max_iter + 1):
            if norm < self.tol:
                return mu, sig_map @ mu + sig0, it - 1, norm
            slope = lam_law * dg(lam_law * np.maximum(sf, 0.0)) * (sf > 0.0)
            step = np.linalg.solve(slope[:, None] * a - eye, -f)
            lam = 1.0
            while True:   # backtracking on the max-norm of the residual
                trial = mu.copy()
                trial[free] += lam * step
                sf_t, f_t = resid(trial)
                norm_t = float(np.max(np.abs(f_t)))
                if norm_t < norm or lam < 1e-4:
                    break
                lam *= 0.5
            if not norm_t < norm:
                break
            mu, sf, f, norm = trial, sf_t, f_t, norm_t
        if norm < self.tol:
            return mu, sig_map @ mu + sig0, self.max_iter, norm
        raise _NoConvergence(norm)

    def _solve(self, sig_map, sig0, free, mu):
        """Newton from the warm start; if that fails, continuation g(lam s), lam: 0 -> 1."""
        try:
            return self._newton(sig_map, sig0, free, mu)
        except _NoConvergence:
            pass
        lam, step, total = 0.0, 1.0 / 16.0, 0
        mu = np.ones(self.n)
        res = np.nan
        while lam < 1.0:
            trial = min(1.0, lam + step)
            try:
                mu_t, sig, it, res = self._newton(sig_map, sig0, free, mu.copy(), trial)
            except _NoConvergence as exc:
                res = exc.args[0]
                step *= 0.5
                if step < 1e-4:
                    break
                continue
            total += it
            lam, mu = trial, mu_t
            step *= 2.0
        if lam >= 1.0:
            return mu, sig, total, res
        raise ValueError(f"{self.label}: the friction iteration of Sec. 5.3 did not converge to "
                         f"tol = {self.tol:g} in max_iter = {self.max_iter} Newton steps, also "
                         f"not by continuation in the law (stopped at {lam:.3g} of the slip "
                         f"scale; residual {res:.3g}, degree = {self.n}). A discontinuous law "
                         "has no polynomial solution: use StepFriction (solved in closed form) "
                         "or a smooth law")

    def at_stick_ratio(self, r):
        """Converged solution for stick ratio r in [0, 1] (always started from mu = mu_0, so
        that the result is a function of r)."""
        sig_map, chi_row, dmat, force_row, slip = self.maps(r)
        mu = np.ones(self.n)
        if slip.any() and r < 1.0:
            mu, sig, it, res = self._solve(sig_map, np.zeros(self.n), slip, mu)
        else:
            it, res = 0, 0.0
        return _Raw(r=float(r), chi=float(chi_row @ mu), force=float(force_row @ mu),
                    c=self.cmat @ mu, d=dmat @ mu, mu=mu, iterations=it, residual=res)

    def full_sliding(self, chi):
        """Converged full-sliding solution at creepage ratio chi >= saturation."""
        h1 = self.tx @ self.cmat
        free = np.ones(self.n, bool)
        mu, sig, it, res = self._solve(-h1, np.full(self.n, chi), free, np.ones(self.n))
        c = self.cmat @ mu
        return _Raw(r=0.0, chi=float(chi), force=float(c[0]), c=c, d=np.zeros(1), mu=mu,
                    iterations=it, residual=res)

    def at_creepage(self, chi):
        """Solution at creepage ratio chi >= 0 (root search on the stick ratio)."""
        if chi == 0.0:
            return self.at_stick_ratio(1.0)
        sat = self.at_stick_ratio(0.0)
        if chi >= sat.chi:
            return self.full_sliding(chi)
        # chi(r) falls from sat.chi (r = 0) to 0 (r = 1)
        from scipy.optimize import brentq  # noqa: PLC0415  (scipy: only where needed)

        r = brentq(lambda r_: self.at_stick_ratio(r_).chi - chi, 0.0, 1.0, xtol=1e-11,
                   rtol=1e-11, maxiter=200)
        raw = self.at_stick_ratio(r)
        if abs(raw.chi - chi) > 1e-7:
            # chi(r) jumps here (a law far too steep for the polynomial degree makes the
            # discrete chi(r) slightly non-monotone): interpolate the creep curve across the jump
            lo = self.at_stick_ratio(min(1.0, r + 1e-9))
            hi = self.at_stick_ratio(max(0.0, r - 1e-9))
            w = (chi - lo.chi) / (hi.chi - lo.chi) if hi.chi != lo.chi else 0.5
            force = lo.force + w * (hi.force - lo.force)
            raw = _Raw(r=r, chi=chi, force=force, c=raw.c, d=raw.d, mu=raw.mu,
                       iterations=raw.iterations, residual=raw.residual)
        return raw

    def peak(self):
        """Solution at the maximum of the force over the partial-slip branch (scan + refine)."""
        rs = np.linspace(0.0, 1.0, 41)
        forces = np.array([self.at_stick_ratio(r).force for r in rs])
        k = int(np.argmax(forces))
        if k == 0:
            return self.at_stick_ratio(0.0)
        lo, hi = rs[max(k - 1, 0)], rs[min(k + 1, rs.size - 1)]
        from scipy.optimize import minimize_scalar  # noqa: PLC0415

        res = minimize_scalar(lambda r: -self.at_stick_ratio(r).force, bounds=(lo, hi),
                              method="bounded", options={"xatol": 1e-8})
        top = self.at_stick_ratio(float(res.x))
        return top if top.force >= forces[k] else self.at_stick_ratio(rs[k])


class _NoConvergence(Exception):
    pass


@dataclass
class _Raw:
    r: float
    chi: float
    force: float
    c: np.ndarray
    d: np.ndarray
    mu: np.ndarray
    iterations: int
    residual: float


@dataclass
class VelocityFrictionSolution:
    """Normalised solution of the 2-D rolling problem with velocity-dependent friction.

    Attributes
    ----------
    stick_ratio : float
        r = a*/a0 (1 full stick, 0 full sliding). [-]
    creepage_ratio : float
        xi / xi_c0 (signed as given). [-]
    force_ratio : float
        T / (mu_0 N), opposing the creepage. [-]
    iterations : int
        Newton steps of the friction iteration. [-]
    residual : float
        Final max |mu(s)/mu_0 - mu(x)/mu_0| at the slip-zone nodes. [-]
    """

    stick_ratio: float
    creepage_ratio: float
    force_ratio: float
    iterations: int
    residual: float
    _raw: _Raw
    _law: object = None

    def slip(self, x_ratio):
        """Slip magnitude over the critical creepage, s / xi_c0, at x / a0 (0 in the stick zone,
        closed form from the polynomial forms; outside the patch the far-field slip). [-]"""
        x = np.asarray(x_ratio, dtype=float)
        raw = self._raw
        r = raw.r
        xin = np.clip(x, -1.0, 1.0)
        h1 = _cheb.chebval(xin, np.concatenate([[0.0], raw.c]))   # U_n -> T_{n+1}
        # outside |x| < 1 the transform of t1 is (x - sign(x) sqrt(x^2 - 1))^(n+1)
        wout = x - np.sign(x) * _sqrt_pos(x * x - 1.0)
        h1_out = np.polynomial.polynomial.polyval(wout, np.concatenate([[0.0], raw.c]))
        h1 = np.where(np.abs(x) <= 1.0, h1, h1_out)
        if r > 0.0:
            y = (x - 1.0 + r) / r
            w = y - np.sign(y) * _sqrt_pos(y * y - 1.0)
            h2_out = np.polynomial.polynomial.polyval(w, np.concatenate([[0.0], raw.d]))
            h2_in = _cheb.chebval(np.clip(y, -1, 1), np.concatenate([[0.0], raw.d]))
            h2 = np.where(np.abs(y) < 1.0, h2_in, h2_out)
            stick = np.abs(y) < 1.0
        else:
            h2, stick = 0.0, np.zeros(x.shape, bool)
        sig = abs(self.creepage_ratio) - h1 - h2
        return np.where(stick, 0.0, sig)

    def traction(self, x_ratio):
        """Traction q / (mu_0 p0) on the wheel at x / a0 (leading edge +1). [-]

        Stick zone: the polynomial forms q1 + q2 of (5.8). Slip zone: ``mu(s(x)) p(x)`` with the
        slip of the converged solution (equal to q1 at the interpolation nodes, free of the
        polynomial's oscillation next to the square-root kink at the stick/slip limit).
        """
        x = np.asarray(x_ratio, dtype=float)
        raw = self._raw
        p = _sqrt_pos(1.0 - x * x)
        t = _cheb.chebval(np.clip(x, -1, 1), _u_to_t(raw.c)) * p
        r = raw.r
        if r > 0.0:
            y = (x - 1.0 + r) / r
            inside = np.abs(y) < 1.0
            t2 = _cheb.chebval(np.clip(y, -1, 1), _u_to_t(raw.d)) * _sqrt_pos(1.0 - y * y)
            t = t + np.where(inside, t2, 0.0)
            slip_zone = x < 1.0 - 2.0 * r
        else:
            slip_zone = np.ones(x.shape, bool)
        if self._law is not None:
            t_slip = self._law(np.maximum(self.slip(x), 0.0)) * p
            t = np.where(slip_zone & (np.abs(x) < 1.0), t_slip, t)
        t = np.where(np.abs(x) < 1.0, t, 0.0)
        return -np.sign(self.creepage_ratio) * t

    def friction_coefficient_ratio(self, x_ratio):
        """The polynomial mu(x) / mu_0 of (5.7) (meaningful in the slip zone). [-]"""
        return _cheb.chebval(np.asarray(x_ratio, dtype=float), _u_to_t(self._raw.c))


def _u_to_t(c):
    """T coefficients of sum c_k U_k."""
    n = c.size
    a = np.zeros(n)
    for k in range(n):   # U_k = 2 sum_{j odd/even <= k} T_j - [k even] T_0
        j = np.arange(k % 2, k + 1, 2)
        a[j] += 2.0 * c[k]
        if k % 2 == 0:
            a[0] -= c[k]
    return a


def _normalised_law(friction_ratio, kappa_normalised):
    m, kap = float(friction_ratio), float(kappa_normalised)

    def g(sig):
        return (1.0 - m) / (1.0 + kap * sig) + m

    def dg(sig):
        return -(1.0 - m) * kap / (1.0 + kap * sig) ** 2
    return g, dg


def _check_knobs(degree, tol, max_iter):
    deg = check_range("degree", degree, "-", 8, 2048)
    if deg != int(deg):
        raise ValueError(f"degree must be an integer in [8, 2048] [-]; got {degree}")
    check_range("tol", tol, "-", 0.0, 1e-2, lower_closed=False)
    check_range("max_iter", max_iter, "-", 1, None)
    return int(deg)


def solve_velocity_friction_normalised(creepage_ratio, friction_ratio, kappa_normalised, *,
                                       degree=128, tol=1e-10, max_iter=50):
    r"""Solve the smooth law (5.16) at one normalised creepage by the iteration of Sec. 5.3.

    Parameters
    ----------
    creepage_ratio : float
        xi / xi_c0, xi_c0 = mu_0 a0 / R. [-]
    friction_ratio : float
        m = mu_k / mu_0, >= 0. [-]
    kappa_normalised : float
        kappa xi_c0, >= 0. [-]
    degree : int, optional
        Number of Chebyshev nodes of the polynomial mu(x) (5.7), in [8, 2048]. [-]
    tol : float, optional
        Convergence tolerance on max |mu(s)/mu_0 - mu(x)/mu_0| at the nodes, in (0, 1e-2]. [-]
    max_iter : int, optional
        Maximum Newton steps per friction iteration. [-]

    Returns
    -------
    VelocityFrictionSolution

    Raises
    ------
    ValueError
        Bad input, or no convergence (naming the law parameters and the creepage).
    """
    chi = float(check_range("creepage_ratio", creepage_ratio, "-"))
    m = float(check_range("friction_ratio", friction_ratio, "-", 0.0, None))
    kap = float(check_range("kappa_normalised", kappa_normalised, "-", 0.0, None))
    deg = _check_knobs(degree, tol, max_iter)
    g, dg = _normalised_law(m, kap)
    label = (f"friction_ratio = {m:g}, kappa_normalised = {kap:g}, "
             f"creepage_ratio = {chi:g}")
    solver = _NormalisedSolver(g, dg, deg, tol, max_iter, label)
    raw = solver.at_creepage(abs(chi))
    return VelocityFrictionSolution(raw.r, chi, -np.sign(chi) * raw.force, raw.iterations,
                                    raw.residual, raw, g)


def velocity_friction_creep_force_normalised(creepage_ratio, friction_ratio, kappa_normalised,
                                             *, degree=128, tol=1e-10, max_iter=50):
    r"""Creep curve ``T / (mu_0 N)`` of the smooth law (5.16), vectorised (Sec. 5.3, Fig. 5.4).

    Inputs broadcast (the table builder uses the same solver through
    :func:`velocity_friction_saturation_curve`, in the coordinate |xi|/xi_sat). ``friction_ratio = 1`` or ``kappa_normalised = 0``
    give Carter exactly, ``1 - (1 - |chi|)^2``.

    Parameters
    ----------
    creepage_ratio : array_like
        xi / xi_c0, xi_c0 = mu_0 a0 / R (Carter's critical creepage for mu_0). [-]
    friction_ratio : array_like
        m = mu_k / mu_0, >= 0. [-]
    kappa_normalised : array_like
        kappa xi_c0, >= 0. [-]
    degree, tol, max_iter
        See :func:`solve_velocity_friction_normalised`.

    Returns
    -------
    ndarray
        T / (mu_0 N), opposite in sign to the creepage. [-]
    """
    chi = check_range("creepage_ratio", creepage_ratio, "-")
    m = check_range("friction_ratio", friction_ratio, "-", 0.0, None)
    kap = check_range("kappa_normalised", kappa_normalised, "-", 0.0, None)
    deg = _check_knobs(degree, tol, max_iter)
    chi, m, kap = np.broadcast_arrays(chi, m, kap)
    out = np.empty(chi.shape)
    solvers = {}
    for idx in np.ndindex(chi.shape):
        c, mm, kk = float(chi[idx]), float(m[idx]), float(kap[idx])
        # Linear regime: the slip zone has length ~2|chi| a0 and mu departs from mu_0 there by
        # ~(1 - m) kappa |chi| mu_0, so Carter with mu_0 is exact to a relative
        # ~kappa |1 - m| |chi| (<= 1e-9 here), while the iteration loses digits below chi ~ 1e-9
        # (its force sticks at a rounding floor ~5e-18).
        if mm == 1.0 or kk == 0.0 or (abs(c) <= 1e-8 and abs(c) * kk * abs(1.0 - mm) <= 1e-9):
            out[idx] = -np.sign(c) * _carter_force_ratio(abs(c), 1.0)
            continue
        key = (mm, kk)
        if key not in solvers:
            g, dg = _normalised_law(mm, kk)
            solvers[key] = _NormalisedSolver(
                g, dg, deg, tol, max_iter,
                f"friction_ratio = {mm:g}, kappa_normalised = {kk:g}")
        solver = solvers[key]
        try:
            out[idx] = -np.sign(c) * solver.at_creepage(abs(c)).force
        except ValueError as exc:
            raise ValueError(f"{exc} at creepage_ratio = {c:g}") from None
    return out[()]


def velocity_friction_peak_normalised(friction_ratio, kappa_normalised, *, degree=128,
                                      tol=1e-10, max_iter=50):
    r"""Creepage at the maximum of the creep curve: the onset of negative damping (Sec. 5.3).

    Parameters
    ----------
    friction_ratio : array_like
        m = mu_k / mu_0, >= 0. [-]
    kappa_normalised : array_like
        kappa xi_c0, >= 0. [-]
    degree, tol, max_iter
        See :func:`solve_velocity_friction_normalised`.

    Returns
    -------
    creepage_ratio : ndarray
        |xi| / xi_c0 at the maximum of |T|. For a falling law (m < 1, kappa > 0) an interior
        maximum before full sliding (as the thesis states). For ``m = 1`` or ``kappa = 0``
        (Carter) the force first reaches its maximum ``mu_0 N`` at 1. For a rising law (m > 1)
        the force increases towards ``mu_k N`` without a maximum: ``inf``. [-]
    force_ratio : ndarray
        max |T| / (mu_0 N) (``m`` for a rising law, the supremum). [-]
    """
    m = check_range("friction_ratio", friction_ratio, "-", 0.0, None)
    kap = check_range("kappa_normalised", kappa_normalised, "-", 0.0, None)
    deg = _check_knobs(degree, tol, max_iter)
    m, kap = np.broadcast_arrays(m, kap)
    chi_out = np.empty(m.shape)
    f_out = np.empty(m.shape)
    for idx in np.ndindex(m.shape):
        mm, kk = float(m[idx]), float(kap[idx])
        if mm == 1.0 or kk == 0.0:
            chi_out[idx], f_out[idx] = 1.0, 1.0
        elif mm > 1.0:
            chi_out[idx], f_out[idx] = np.inf, mm
        else:
            g, dg = _normalised_law(mm, kk)
            top = _NormalisedSolver(g, dg, deg, tol, max_iter,
                                    f"friction_ratio = {mm:g}, kappa_normalised = {kk:g}"
                                    ).peak()
            chi_out[idx], f_out[idx] = top.chi, top.force
    return chi_out[()], f_out[()]


# ---------------------------------------------------------------------------------------------
# the creep curve over the saturation creepage (the coordinates of the table velocity_friction)
# ---------------------------------------------------------------------------------------------
SaturationCurve = namedtuple("SaturationCurve", ["force_ratio", "stick_ratio",
                                                 "saturation_creepage_ratio"])
SaturationCurve.__doc__ = """Result of :func:`velocity_friction_saturation_curve`.

force_ratio : ndarray
    |T| / (mu_0 N), magnitude of the tangential force (it opposes the creepage). [-]
stick_ratio : ndarray
    r = a*/a0 (1 full stick, 0 from the saturation creepage on). [-]
saturation_creepage_ratio : ndarray
    xi_sat / xi_c0, the creepage at which the stick zone vanishes over Carter's critical
    creepage xi_c0 = mu_0 a0 / R. [-]
"""


def _saturation_solvers(friction_ratio, kappa_normalised, degree, tol, max_iter):
    """Broadcast (m, kappa) and a cache key -> (solver, solution at r = 0) for the law (5.16)."""
    m = check_range("friction_ratio", friction_ratio, "-", 0.0, None)
    kap = check_range("kappa_normalised", kappa_normalised, "-", 0.0, None)
    deg = _check_knobs(degree, tol, max_iter)
    cache = {}

    def get(mm, kk):
        key = (mm, kk)
        if key not in cache:
            g, dg = _normalised_law(mm, kk)
            solver = _NormalisedSolver(g, dg, deg, tol, max_iter,
                                       f"friction_ratio = {mm:g}, kappa_normalised = {kk:g}")
            cache[key] = (solver, solver.at_stick_ratio(0.0))
        return cache[key]
    return m, kap, get


def velocity_friction_saturation_creepage(friction_ratio, kappa_normalised, *, degree=128,
                                          tol=1e-10, max_iter=50):
    r"""Saturation creepage of the smooth law (5.16): the creepage at which the stick zone
    vanishes, over Carter's critical creepage (Sec. 5.3).

    It is the creepage of the Sec. 5.3 solution at stick ratio ``r = 0`` (the polynomial
    approach with the stick zone shrunk to the leading edge). For ``m = 1`` or ``kappa = 0``
    (Coulomb friction) it is Carter's ``xi_c0 = mu_0 a0 / R`` (Eq. (2.54)), i.e. 1 exactly. It is
    the normalisation of the table ``velocity_friction`` (axis ``normalised_creepage =
    |xi| / xi_sat``).

    Parameters
    ----------
    friction_ratio : array_like
        m = mu_k / mu_0, >= 0. [-]
    kappa_normalised : array_like
        kappa xi_c0, >= 0. [-]
    degree, tol, max_iter
        See :func:`solve_velocity_friction_normalised`.

    Returns
    -------
    ndarray
        xi_sat / xi_c0, broadcast over the inputs. [-]

    Raises
    ------
    ValueError
        Bad input, or the iteration does not converge.
    """
    m, kap, get = _saturation_solvers(friction_ratio, kappa_normalised, degree, tol, max_iter)
    m, kap = np.broadcast_arrays(m, kap)
    out = np.empty(m.shape)
    for idx in np.ndindex(m.shape):
        mm, kk = float(m[idx]), float(kap[idx])
        out[idx] = 1.0 if (mm == 1.0 or kk == 0.0) else get(mm, kk)[1].chi
    return out[()]


def velocity_friction_saturation_curve(normalised_creepage, friction_ratio, kappa_normalised, *,
                                       degree=128, tol=1e-10, max_iter=50):
    r"""Creep curve of the smooth law (5.16) against the creepage over the saturation creepage.

    At ``z = |xi| / xi_sat`` (:func:`velocity_friction_saturation_creepage`): below 1 the
    partial-slip solution of Sec. 5.3 at creepage ``z xi_sat`` (root search on the stick
    ratio), at 1 the solution with stick ratio 0, above 1 the full-sliding solution; ``z = 0``
    gives force 0 and stick ratio 1. ``m = 1`` or ``kappa = 0`` is Carter in closed form
    (force ``1 - (1 - min(z, 1))^2``, stick ratio ``1 - min(z, 1)``, Eqs. (2.51)-(2.53)). The
    table ``velocity_friction`` holds this function (one solver per (m, kappa), reused over z).

    Parameters
    ----------
    normalised_creepage : array_like
        z = |xi| / xi_sat, >= 0. [-]
    friction_ratio : array_like
        m = mu_k / mu_0, >= 0. [-]
    kappa_normalised : array_like
        kappa xi_c0, >= 0. [-]
    degree, tol, max_iter
        See :func:`solve_velocity_friction_normalised`.

    Returns
    -------
    SaturationCurve
        Arrays broadcast over the inputs.

    Raises
    ------
    ValueError
        Bad input, or the iteration does not converge.
    """
    z = check_range("normalised_creepage", normalised_creepage, "-", 0.0, None)
    m, kap, get = _saturation_solvers(friction_ratio, kappa_normalised, degree, tol, max_iter)
    z, m, kap = np.broadcast_arrays(z, m, kap)
    force, stick, sat_ratio = np.empty(z.shape), np.empty(z.shape), np.empty(z.shape)
    for idx in np.ndindex(z.shape):
        zz, mm, kk = float(z[idx]), float(m[idx]), float(kap[idx])
        if mm == 1.0 or kk == 0.0:
            zc = min(zz, 1.0)
            force[idx], stick[idx], sat_ratio[idx] = 1.0 - (1.0 - zc) ** 2, 1.0 - zc, 1.0
            continue
        solver, sat = get(mm, kk)
        sat_ratio[idx] = sat.chi
        if zz == 0.0:
            force[idx], stick[idx] = 0.0, 1.0
        elif zz == 1.0:
            force[idx], stick[idx] = sat.force, 0.0
        elif zz > 1.0:
            force[idx], stick[idx] = solver.full_sliding(zz * sat.chi).force, 0.0
        else:
            raw = solver.at_creepage(zz * sat.chi)
            force[idx], stick[idx] = raw.force, raw.r
    return SaturationCurve(force[()], stick[()], sat_ratio[()])


# ---------------------------------------------------------------------------------------------
# physical inputs, any law
# ---------------------------------------------------------------------------------------------
def _law_solver(friction_law, xi_c, degree, tol, max_iter, label):
    mu0 = _mu_static(friction_law)
    deriv = getattr(friction_law, "derivative", None)

    def g(sig):
        return np.asarray(friction_law(sig * xi_c), dtype=float) / mu0

    if deriv is not None:
        def dg(sig):
            return np.asarray(deriv(sig * xi_c), dtype=float) * xi_c / mu0
    else:
        def dg(sig):   # one-sided difference (s >= 0), step relative to the slip scale
            h = 1e-6 * np.maximum(sig, 1e-3)
            return (g(sig + h) - g(sig)) / h
    return _NormalisedSolver(g, dg, degree, tol, max_iter, label)


def _physical(creepage, normal_load, radius, youngs_modulus, poisson_ratio, friction_law):
    xi = check_range("creepage", creepage, "-")
    n_load = check_range("normal_load", normal_load, "N/m", 0.0, None)
    rad = check_range("radius", radius, "m", 0.0, None, lower_closed=False)
    h = hertz_2d(n_load, rad, youngs_modulus, poisson_ratio)
    mu0 = _mu_static(friction_law)
    return xi, n_load, rad, h, mu0


def velocity_friction_creep_force(creepage, normal_load, radius, youngs_modulus, poisson_ratio,
                                  friction_law, *, degree=128, tol=1e-10, max_iter=50):
    r"""Creep force of two rolling cylinders with a slip-dependent friction law (Sec. 5.3).

    Parameters
    ----------
    creepage : array_like
        Longitudinal creepage xi. [-]
    normal_load : float
        Normal load per unit length N, >= 0. [N/m]
    radius : float
        Equivalent radius R, > 0. [m]
    youngs_modulus : float
        Young's modulus E, > 0. [Pa]
    poisson_ratio : float
        Poisson's ratio, in [0, 0.5). [-]
    friction_law : callable
        mu(s) of the slip magnitude s >= 0 (e.g. :class:`SmoothFriction`); mu(0) >= 0. A law
        with a ``derivative`` method uses it in the Newton iteration. A :class:`StepFriction`
        is solved by the closed-form minimum solution (:func:`step_law_creep_force_normalised`);
        other discontinuous laws raise ``ValueError``. [-]
    degree, tol, max_iter
        See :func:`solve_velocity_friction_normalised`.

    Returns
    -------
    ndarray
        Tangential force per unit length on the wheel, opposite in sign to xi. [N/m]
        ``mu(0) = 0`` or ``N = 0`` gives 0.
    """
    xi, n_load, rad, h, mu0 = _physical(creepage, normal_load, radius, youngs_modulus,
                                        poisson_ratio, friction_law)
    deg = _check_knobs(degree, tol, max_iter)
    xi_c = float(mu0 * h.a0 / rad)
    scale = float(mu0 * n_load)
    if scale == 0.0:
        return np.zeros(xi.shape)[()]
    if isinstance(friction_law, StepFriction):   # discontinuous: the minimum solution (5.4)-(5.6)
        return (scale * step_law_creep_force_normalised(
            xi / xi_c, friction_law.mu_kinetic / mu0))[()]
    solver = _law_solver(friction_law, xi_c, deg, tol, max_iter, f"friction_law = {friction_law!r}")
    out = np.empty(xi.shape)
    for idx in np.ndindex(xi.shape):
        c = float(xi[idx])
        try:
            out[idx] = -np.sign(c) * scale * solver.at_creepage(abs(c) / xi_c).force
        except ValueError as exc:
            raise ValueError(f"{exc} at creepage = {c:g}") from None
    return out[()]


def velocity_friction_traction(x, creepage, normal_load, radius, youngs_modulus, poisson_ratio,
                               friction_law, *, degree=128, tol=1e-10, max_iter=50):
    r"""Traction q(x) on the wheel with a slip-dependent friction law (Sec. 5.3, Fig. 5.5).

    Parameters
    ----------
    x : array_like
        Positions (leading edge +a0). [m]
    creepage : float
        Longitudinal creepage xi. [-]
    normal_load, radius, youngs_modulus, poisson_ratio, friction_law, degree, tol, max_iter
        As in :func:`velocity_friction_creep_force`.

    Returns
    -------
    ndarray
        Traction on the wheel, zero outside the contact. [Pa]
    """
    xq = check_range("x", x, "m")
    xi, n_load, rad, h, mu0 = _physical(creepage, normal_load, radius, youngs_modulus,
                                        poisson_ratio, friction_law)
    if xi.ndim:
        raise ValueError(f"creepage must be a scalar [-]; got shape {xi.shape}")
    deg = _check_knobs(degree, tol, max_iter)
    a0, p0 = float(h.a0), float(h.p0)
    if mu0 * n_load == 0.0:
        return np.zeros(xq.shape)[()]
    xi_c = mu0 * a0 / float(rad)
    if isinstance(friction_law, StepFriction):
        q = mu0 * p0 * step_law_traction_normalised(xq / a0, float(xi) / xi_c,
                                                    friction_law.mu_kinetic / mu0)
        return np.where(np.abs(xq) < a0, q, 0.0)[()]
    solver = _law_solver(friction_law, xi_c, deg, tol, max_iter, f"friction_law = {friction_law!r}")
    raw = solver.at_creepage(abs(float(xi)) / xi_c)
    sol = VelocityFrictionSolution(raw.r, float(xi) / xi_c, 0.0, raw.iterations, raw.residual,
                                   raw, solver.g)
    q = mu0 * p0 * sol.traction(xq / a0)
    return np.where(np.abs(xq) < a0, q, 0.0)[()]


def velocity_friction_peak_creepage(normal_load, radius, youngs_modulus, poisson_ratio,
                                    friction_law, *, degree=128, tol=1e-10, max_iter=50):
    r"""Creepage and force at the maximum of the creep curve for any law (Sec. 5.3).

    The maximum is searched over the partial-slip branch (stick ratio in [0, 1]); if it lies at
    full sliding onset the saturation creepage is returned. For a law that does not fall the
    result is the saturation creepage (the force may keep rising beyond it).

    Parameters
    ----------
    normal_load, radius, youngs_modulus, poisson_ratio, friction_law, degree, tol, max_iter
        As in :func:`velocity_friction_creep_force`.

    Returns
    -------
    creepage : float
        |xi| at the maximum. [-]
    force : float
        max |T|. [N/m]
    """
    _, n_load, rad, h, mu0 = _physical(0.0, normal_load, radius, youngs_modulus,
                                       poisson_ratio, friction_law)
    deg = _check_knobs(degree, tol, max_iter)
    if mu0 * float(n_load) == 0.0:
        return 0.0, 0.0
    xi_c = mu0 * float(h.a0) / float(rad)
    if isinstance(friction_law, StepFriction):   # Carter with mu_k: saturates at mu_k N
        m = friction_law.mu_kinetic / mu0
        return m * xi_c, m * mu0 * float(n_load)
    solver = _law_solver(friction_law, xi_c, deg, tol, max_iter, f"friction_law = {friction_law!r}")
    top = solver.peak()
    return top.chi * xi_c, top.force * mu0 * float(n_load)
