r"""The polynomial approach to 2-D contact (Nielsen 1998, Ch. 3 and Appendix D).

Why one module of about 1,060 lines: it is Ch. 3 of the thesis, the polynomial approach (the
transform matrices, the series and the solutions built on them); its parts share the matrices
and their validation.

A stress that is a *polynomial form* on ``|x| < a``,

.. math::  p(x) = \frac{\sum_{n=0}^{N} B_n x^n}{\sqrt{a^2 - x^2}},

produces a surface displacement gradient that is a polynomial of degree ``N - 1`` inside the
strip (Eq. (3.4)):

.. math::  \mathrm{PV}\!\int_{-a}^{a} \frac{\sum B_n \zeta^n}{(x-\zeta)\sqrt{a^2-\zeta^2}}\,d\zeta
           = \sum_{m=0}^{N-1} \beta_m x^m + I_{-1}(x) \sum_{n=0}^{N} B_n x^n ,

with ``I_-1 = 0`` for ``|x| <= a`` and ``sign(x) pi / sqrt(x^2 - a^2)`` outside (3.5), and
``{beta} = [A]{B_1}`` (3.6)-(3.10). The matrices and vectors of Sec. 3.2 are exposed here, and on
top of them the non-Hertzian normal problem (Sec. 3.3.1) and the steady-rolling tangential
problem on a non-Hertzian pressure (Sec. 3.3.2).

Coefficient conventions used by every function here
--------------------------------------------------
* ``coefficients`` are always ascending: ``c[n]`` multiplies ``x**n``.
* Physical (local) pressure coefficients ``B_n`` [N/m^(n+1)] give ``p(x)`` in [Pa] with ``x`` in
  [m] measured from the patch centre.
* **Normalised** coefficients ``b_n = B_n a^n`` [N/m] use ``s = x / a``:
  ``p(x) = sum(b_n s^n) / (a sqrt(1 - s^2))``. The solvers work in ``s`` (``a = 1``), which keeps
  ``[A]``, ``[A]^-1`` and the force vector O(1) at any degree; ``(a/2)^(2k)`` in physical units
  under/overflows at high degree (see :func:`transform_coefficients`).
* Kernel factor (two identical bodies, plane strain): ``K = 4 (1 - nu^2) / (pi E)``; the surface
  slope in the contact is ``dZ/dx = K PV int p(z) / (x - z) dz`` (Eq. (3.28)).
* Tangential problem: package convention (see :mod:`railcontact`): leading edge ``x = +a``,
  stick zone ``[a - 2 a*, a]``, traction and force act on the wheel and oppose the creepage
  (``T > 0`` for ``xi < 0``). The thesis draws the stick zone at ``-a`` (mirrored picture).

Numerical limits (measured in ``benchmarks/bench_polynomial.py`` against 40-digit mpmath)
-----------------------------------------------------------------------------------------
* Normalised ``[A]``, ``[A]^-1``: exact to ~1e-16 at any degree (tested to N = 201; cond([A])
  is 9.4 at N = 128). In physical units ``(a/2)^(2k)`` underflows (a = 5 mm: from k = 71).
* (3.4) *outside* the strip as printed cancels like ``|x/a|^N`` (x = 1.5 a: 1.7e-12 at N = 32,
  1.8e-5 at N = 64); :func:`principal_value_integral` uses an equivalent Chebyshev form instead
  (error 1e-17 at N = 128).
* The base change ``[D(d)]`` with ``|d| = a`` loses about ``N log10 2`` digits on random O(1)
  coefficients (7.8e-13 at N = 32, 8e-8 at N = 64): the tangential solver, which shifts by
  ``a - a*``, is accurate to 1e-12 up to N ~ 30 for such coefficients; for smooth gaps whose
  coefficients decay (e.g. a truncated cosh) N = 48 still agrees with N = 24 to 1e-15.

Erratum (seed list no. 1, re-verified here): (3.10), (3.13) and (D.15) print ``(2k)!/k!``; the
factorial in the denominator is squared. Verified in ``tests/test_polynomial.py`` against an
mpmath quadrature of (3.4) (relative 1e-12) and by ``[A][A]^-1 = I``.

References
----------
.. [1] J.B. Nielsen, New Developments in the Theory of Wheel/Rail Contact Mechanics,
   IMM-PHD-1998-51, DTU, 1998, Ch. 3 and Appendix D.
.. [2] N.I. Muskhelishvili, Singular Integral Equations, Noordhoff, 1953 (finite Hilbert
   transform of Chebyshev-weighted polynomials).
.. [3] F.W. Carter, On the action of a locomotive driving wheel, Proc. R. Soc. A 112 (1926).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from scipy import optimize
from scipy.special import comb

from ._validation import check_range

__all__ = [
    "moment_ratios",
    "transform_coefficients",
    "inverse_transform_coefficients",
    "transform_matrix",
    "inverse_transform_matrix",
    "base_change_matrix",
    "force_vector",
    "polynomial_form",
    "polynomial_form_force",
    "principal_value_integral",
    "kernel_factor",
    "PolynomialNormalContact",
    "PolynomialTangentialContact",
    "normal_contact_from_coefficients",
    "solve_normal_polynomial",
    "solve_tangential_polynomial",
    "tangential_state_polynomial",
    "creep_curve_polynomial",
]

MAX_DEGREE = 400
"""Largest degree accepted. Normalised matrices stay exact to ~1e-15 far beyond this; the
limit only guards against accidental huge allocations."""


# ---------------------------------------------------------------------------------------------
# input checks
# ---------------------------------------------------------------------------------------------
def check_degree(degree, lower=1):
    d = check_range("degree", degree, "-", lower, MAX_DEGREE)
    if d.ndim != 0 or float(d) != int(d):
        raise ValueError(f"degree must be an integer in [{lower}, {MAX_DEGREE}] [-]; got {degree!r}")
    return int(d)


def _check_half_width(half_width):
    return float(check_range("half_width", half_width, "m", 0.0, None, lower_closed=False))


def check_coefficients(name, coefficients, unit, min_len=1):
    c = check_range(name, coefficients, unit)
    if c.ndim != 1 or c.size < min_len:
        raise ValueError(f"{name} must be a 1-D sequence of >= {min_len} coefficients [{unit}]; "
                         f"got shape {c.shape}")
    return c


def kernel_factor(youngs_modulus, poisson_ratio):
    r"""``K = 4 (1 - nu^2) / (pi E)`` of Eq. (3.1) (two identical bodies, plane strain). [1/Pa]

    Parameters
    ----------
    youngs_modulus : float
        Young's modulus of both bodies, > 0. [Pa]
    poisson_ratio : float
        Poisson's ratio of both bodies, in [0, 0.5). [-]
    """
    e = check_range("youngs_modulus", youngs_modulus, "Pa", 0.0, None, lower_closed=False)
    nu = check_range("poisson_ratio", poisson_ratio, "-", 0.0, 0.5, upper_closed=False)
    return 4.0 * (1.0 - nu**2) / (np.pi * e)


# ---------------------------------------------------------------------------------------------
# Sec. 3.2: transform coefficients and matrices
# ---------------------------------------------------------------------------------------------
@lru_cache(maxsize=64)
def _moment_ratios(count):
    k = np.arange(1, count, dtype=float)
    # c_k = (2k)! / ((k!)^2 4^k) by the stable recursion c_k = c_{k-1} (2k - 1) / (2k)
    c = np.concatenate(([1.0], np.cumprod((2.0 * k - 1.0) / (2.0 * k))))
    c.setflags(write=False)
    return c


def moment_ratios(count):
    r"""``c_k = (2k)! / ((k!)^2 4^k)``, k = 0..count-1, so ``int_-1^1 s^2k / sqrt(1-s^2) ds = pi c_k``.

    Computed by the recursion ``c_k = c_{k-1} (2k-1)/(2k)`` (no factorial overflow).

    Parameters
    ----------
    count : int
        Number of terms, >= 1. [-]

    Returns
    -------
    ndarray, shape (count,)
    """
    n = check_degree(count)
    return np.array(_moment_ratios(n))


def _scaled(c, half_width):
    k = np.arange(c.size)
    if half_width == 1.0:
        return c.copy()
    with np.errstate(under="ignore", over="ignore"):
        return c * np.exp(2.0 * k * np.log(half_width))


def transform_coefficients(count, half_width=1.0):
    r"""``A_k = -pi (2k)! / (k!)^2 (a/2)^(2k)``, k = 0..count-1, Eq. (3.10) (corrected).

    # erratum: (3.10) and (D.15) as printed have (2k)!/k!; the denominator is (k!)^2. Verified by
    # the mpmath quadrature of (3.4) in tests/test_polynomial.py (seed erratum 1).

    ``-A_k = int_-a^a z^2k / sqrt(a^2 - z^2) dz`` is the even moment of the Chebyshev weight.

    Parameters
    ----------
    count : int
        Number of coefficients, >= 1. [-]
    half_width : float, optional
        Half-width ``a`` of the strip, > 0 (default 1: normalised coordinate). [m]

    Returns
    -------
    ndarray, shape (count,)
        ``A_k`` [m^(2k)]. In physical units ``a^(2k)`` underflows (returns 0) or overflows for
        large ``k`` (e.g. a = 5 mm underflows past k ~ 140); use ``half_width=1`` and normalised
        coefficients for high degree.
    """
    n = check_degree(count)
    a = _check_half_width(half_width)
    return -np.pi * _scaled(np.asarray(_moment_ratios(n)), a)


def inverse_transform_coefficients(count, half_width=1.0):
    r"""``A_k^-1 = (1/pi) (2k)! / ((2k-1) (k!)^2) (a/2)^(2k)``, Eq. (3.13) (corrected).

    # erratum: (3.13) as printed has (2k)!/((2k-1) k!); the k! is squared. Verified by
    # [A][A]^-1 = I in tests/test_polynomial.py (seed erratum 1).

    These are the Taylor coefficients of ``-(1/pi) sqrt(1 - a^2 t)``, the reciprocal of the
    generating function ``-pi / sqrt(1 - a^2 t)`` of the ``A_k``.

    Parameters
    ----------
    count : int
        Number of coefficients, >= 1. [-]
    half_width : float, optional
        Half-width ``a``, > 0. [m]

    Returns
    -------
    ndarray, shape (count,)
    """
    n = check_degree(count)
    a = _check_half_width(half_width)
    k = np.arange(n, dtype=float)
    return _scaled(np.asarray(_moment_ratios(n)), a) / (np.pi * (2.0 * k - 1.0))


def _toeplitz_even(coef, size):
    """Upper-triangular matrix with ``coef[k]`` on the super-diagonal at offset 2k."""
    i, j = np.indices((size, size))
    off = j - i
    k = off // 2
    mask = (off >= 0) & (off % 2 == 0)
    out = np.zeros((size, size), dtype=np.result_type(coef, float))
    out[mask] = coef[k[mask]]
    return out


@lru_cache(maxsize=128)
def unit_matrices(n):
    """Normalised [A] and [A]^-1 (a = 1) of degree n, cached, read-only."""
    c = np.asarray(_moment_ratios((n + 1) // 2))
    k = np.arange(c.size, dtype=float)
    amat = _toeplitz_even(-np.pi * c, n)
    ainv = _toeplitz_even(c / (np.pi * (2.0 * k - 1.0)), n)
    amat.setflags(write=False)
    ainv.setflags(write=False)
    return amat, ainv


def _inverse_scaled(n, a):
    """[A]^-1 for half-width a (no validation; internal)."""
    c = np.asarray(_moment_ratios((n + 1) // 2))
    k = np.arange(c.size, dtype=float)
    return _toeplitz_even(c * a ** (2.0 * k) / (np.pi * (2.0 * k - 1.0)), n)


@lru_cache(maxsize=128)
def _binomials(n):
    i, j = np.indices((n + 1, n + 1))
    out = np.where(j >= i, comb(j, i), 0.0)
    out.setflags(write=False)
    return out, np.maximum(j - i, 0), j >= i


def _base_change(n, d):
    """[D(d)] without validation (internal)."""
    binom, power, upper = _binomials(n)
    return np.where(upper, binom * float(d) ** power, 0.0)


def transform_matrix(degree, half_width=1.0):
    r"""The matrix ``[A]`` of Eq. (3.9): ``{beta_0..beta_(N-1)} = [A] {B_1..B_N}``, Eq. (3.6).

    ``A[m, n-1] = A_k`` with ``k = (n - m - 1)/2`` when that is a non-negative integer, else 0.

    Parameters
    ----------
    degree : int
        Degree ``N`` of the polynomial form, >= 1. [-]
    half_width : float, optional
        Half-width ``a`` of the strip, > 0 (default 1: coordinates ``s = x / a``). [m]

    Returns
    -------
    ndarray, shape (N, N)
    """
    n = check_degree(degree)
    return _toeplitz_even(transform_coefficients((n + 1) // 2, half_width), n)


def inverse_transform_matrix(degree, half_width=1.0):
    r"""``[A]^-1`` of Eq. (3.12): ``{B_1..B_N} = [A]^-1 {beta}`` (3.11), entries ``A_k^-1`` (3.13).

    Parameters
    ----------
    degree : int
        Degree ``N``, >= 1. [-]
    half_width : float, optional
        Half-width ``a``, > 0. [m]

    Returns
    -------
    ndarray, shape (N, N)
    """
    n = check_degree(degree)
    return _toeplitz_even(inverse_transform_coefficients((n + 1) // 2, half_width), n)


def base_change_matrix(degree, shift):
    r"""Binomial base change ``[D]`` of Eqs. (3.17)-(3.21).

    If ``sum G_n (x + d)^n = sum gamma_n x^n`` then ``{gamma} = [D] {G}`` with
    ``D[i, j] = C(j, i) d^(j-i)`` for ``j >= i``; ``[D(d)]^-1 = [D(-d)]`` (3.22).

    Parameters
    ----------
    degree : int
        Polynomial degree ``N`` (matrix size N+1), >= 0. [-]
    shift : float
        Shift ``d`` (in the units of ``x``; use ``d/a`` with normalised coordinates). [m]

    Returns
    -------
    ndarray, shape (N+1, N+1)

    Notes
    -----
    The entries grow like ``(1 + |d|)^N``; with normalised coordinates and ``|d| <= 1`` the
    base change loses about ``N log10(2)`` digits in the worst case (measured in the tests).
    """
    n = check_degree(degree, lower=0)
    d = float(check_range("shift", shift, "m"))
    i, j = np.indices((n + 1, n + 1))
    with np.errstate(invalid="ignore"):
        powers = np.where(j >= i, float(d) ** np.maximum(j - i, 0), 0.0)
    return np.where(j >= i, comb(j, i) * powers, 0.0)


def force_vector(degree, half_width=1.0):
    r"""``{A_0} = {A_0, 0, A_1, 0, ...}`` of Eq. (3.25), length N+1: force ``= -{A_0}^T {B}``.

    Parameters
    ----------
    degree : int
        Degree ``N`` of the polynomial form, >= 0. [-]
    half_width : float, optional
        Half-width ``a``, > 0. [m]

    Returns
    -------
    ndarray, shape (N+1,)
    """
    n = check_degree(degree, lower=0)
    out = np.zeros(n + 1)
    out[0::2] = transform_coefficients(n // 2 + 1, half_width)
    return out


def polynomial_form(coefficients, x, half_width=1.0):
    r"""Evaluate ``sum B_n x^n / sqrt(a^2 - x^2)`` on ``|x| < a`` and 0 elsewhere, Eq. (3.2).

    Parameters
    ----------
    coefficients : array_like, shape (N+1,)
        ``B_n``, ascending.
    x : array_like
        Positions. [m]
    half_width : float, optional
        ``a``, > 0. [m]

    Returns
    -------
    ndarray
        Same shape as ``x``. At ``|x| = a`` the value is 0 when the boundary conditions (3.3)
        hold; it is returned as 0 (closed form of the limit for a vanishing numerator).
    """
    b = check_coefficients("coefficients", coefficients, "-")
    x = check_range("x", x, "m")
    a = _check_half_width(half_width)
    inside = np.abs(x) < a
    root = np.sqrt(np.where(inside, a * a - x * x, 1.0))
    return np.where(inside, np.polynomial.polynomial.polyval(x, b) / root, 0.0)


def polynomial_form_force(coefficients, half_width=1.0):
    r"""``int_-a^a sum B_n z^n / sqrt(a^2 - z^2) dz = -{A_0}^T {B}``, Eqs. (3.23)-(3.24).

    Parameters
    ----------
    coefficients : array_like, shape (N+1,)
        ``B_n``, ascending.
    half_width : float, optional
        ``a``, > 0. [m]

    Returns
    -------
    float
    """
    b = check_coefficients("coefficients", coefficients, "-")
    return float(-force_vector(b.size - 1, half_width) @ b)


def principal_value_integral(coefficients, x, half_width=1.0):
    r"""Full right-hand side of Eq. (3.4) at any ``x`` (inside: polynomial; outside: + I_-1 term).

    ``PV int_-a^a sum B_n z^n / ((x - z) sqrt(a^2 - z^2)) dz``.

    Parameters
    ----------
    coefficients : array_like, shape (N+1,)
        ``B_n``, ascending (N >= 0).
    x : array_like
        Positions. [m]
    half_width : float, optional
        ``a``, > 0. [m]

    Returns
    -------
    ndarray
        Same shape as ``x``; ``|x| <= a`` uses ``I_-1 = 0`` (3.5).

    Notes
    -----
    Inside the strip the polynomial ``[A]{B}`` is used. Outside, (3.4) as written suffers
    cancellation growing like ``|x/a|^N``; the value is computed in the equivalent, stable
    Chebyshev form (see the code comment), checked against quadrature in the tests.
    """
    b = check_coefficients("coefficients", coefficients, "-")
    x = check_range("x", x, "m")
    a = _check_half_width(half_width)
    bn = b * a ** np.arange(b.size)  # normalised: s = x / a
    s = x / a
    if bn.size == 1:
        beta = np.zeros(1)
    else:
        beta = unit_matrices(bn.size - 1)[0] @ bn[1:]
    inside = np.polynomial.polynomial.polyval(s, beta)
    outside = np.abs(s) > 1.0
    # Outside the strip, beta(s) + I_-1(s) b(s) cancels like |s|^N (the sum decays as 1/s while
    # each term grows): measured 4.5e-11 relative at s = -2.5, N = 12. Evaluate it instead in the
    # Chebyshev basis, where PV int_0^pi cos(k t) / (s - cos t) dt = pi sign(s) w^k / sqrt(s^2-1),
    # w = sign(s) / (|s| + sqrt(s^2 - 1)), |w| < 1: no cancellation.
    so = np.where(outside, s, 2.0)
    root = np.sqrt(so * so - 1.0)
    w = np.sign(so) / (np.abs(so) + root)
    cheb = np.polynomial.chebyshev.poly2cheb(bn)
    far = np.pi * np.sign(so) / root * np.polynomial.polynomial.polyval(w, cheb)
    return np.where(outside, far, inside) / a


# ---------------------------------------------------------------------------------------------
# Sec. 3.3.1: non-Hertzian normal contact
# ---------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class PolynomialNormalContact:
    r"""A normal pressure of polynomial form on one strip (result of :func:`solve_normal_polynomial`).

    Attributes
    ----------
    half_width : float
        Contact half-width ``a``. [m]
    centre : float
        Position ``d`` of the patch centre in the global coordinate ``X`` of the gap. [m]
    normalised_coefficients : ndarray
        ``b_n``: ``p = sum b_n s^n / (a sqrt(1 - s^2))``, ``s = (X - d)/a``. [N/m]
    normal_load : float
        Integral of the pressure. [N/m]
    youngs_modulus : float
        [Pa]
    poisson_ratio : float
        [-]
    """

    half_width: float
    centre: float
    normalised_coefficients: np.ndarray
    normal_load: float
    youngs_modulus: float
    poisson_ratio: float

    @property
    def degree(self):
        """Degree N of the polynomial form. [-]"""
        return self.normalised_coefficients.size - 1

    @property
    def coefficients(self):
        """Physical local coefficients ``B_n = b_n / a^n``: ``p = sum B_n x^n / sqrt(a^2-x^2)``.
        [N/m^(n+1)]"""
        n = np.arange(self.normalised_coefficients.size)
        return self.normalised_coefficients / self.half_width**n

    @property
    def geometric_coefficients(self):
        """Thesis form (3.30): ``p = (pi E / (4 (1-nu^2))) sum B_n x^n / sqrt(a^2 - x^2)``. [m^-n]"""
        return self.coefficients * kernel_factor(self.youngs_modulus, self.poisson_ratio)

    def pressure(self, x):
        """Pressure at global positions ``x`` (0 outside the strip). [Pa]

        Parameters
        ----------
        x : array_like
            Global coordinate ``X``. [m]
        """
        x = check_range("x", x, "m")
        s = (x - self.centre) / self.half_width
        inside = np.abs(s) < 1.0
        root = np.sqrt(np.where(inside, 1.0 - s * s, 1.0))
        val = np.polynomial.polynomial.polyval(s, self.normalised_coefficients)
        return np.where(inside, val / (self.half_width * root), 0.0)

    def surface_slope(self, x):
        """``K PV int p(z)/(x - z) dz`` at global ``x`` (equals ``dZ/dX`` inside the contact). [-]"""
        x = check_range("x", x, "m")
        s = (x - self.centre) / self.half_width
        k = kernel_factor(self.youngs_modulus, self.poisson_ratio)
        return k / self.half_width * principal_value_integral(self.normalised_coefficients, s)


def force_from_normalised(b):
    c = np.asarray(_moment_ratios(b.size // 2 + 1))
    return float(np.pi * (c[: (b.size + 1) // 2] @ b[0::2]))


def normal_contact_from_coefficients(pressure_coefficients, half_width, youngs_modulus,
                                     poisson_ratio, centre=0.0, *, normalised=False,
                                     rtol=1e-9):
    r"""Wrap a given polynomial-form pressure (Eq. (3.30)) for :func:`solve_tangential_polynomial`.

    Parameters
    ----------
    pressure_coefficients : array_like, shape (N+1,)
        ``B_n`` of ``p(x) = sum B_n x^n / sqrt(a^2 - x^2)`` with ``x`` from the patch centre
        [N/m^(n+1)]; or, with ``normalised=True``, ``b_n = B_n a^n`` [N/m].
    half_width : float
        ``a``, > 0. [m]
    youngs_modulus : float
        > 0. [Pa]
    poisson_ratio : float
        In [0, 0.5). [-]
    centre : float, optional
        Global position of the patch centre. [m]
    normalised : bool, optional
        Whether ``pressure_coefficients`` are already normalised.
    rtol : float, optional
        Tolerance for the boundary conditions (3.3): ``|sum b_n (+-1)^n| <= rtol sum |b_n|``.

    Returns
    -------
    PolynomialNormalContact

    Raises
    ------
    ValueError
        Bad input, boundary conditions (3.3) violated, or non-positive total load.
    """
    a = _check_half_width(half_width)
    kernel_factor(youngs_modulus, poisson_ratio)
    c = check_coefficients("pressure_coefficients", pressure_coefficients,
                            "N/m" if normalised else "N/m^(n+1)", 1)
    d = float(check_range("centre", centre, "m"))
    b = c.copy() if normalised else c * a ** np.arange(c.size)
    scale = np.abs(b).sum()
    sign = (-1.0) ** np.arange(b.size)
    if abs(b.sum()) > rtol * scale or abs((sign * b).sum()) > rtol * scale:
        raise ValueError("pressure_coefficients must satisfy the boundary conditions (3.3) "
                         f"sum B_n (+-a)^n = 0 [-]; got {b.sum():g} and {(sign * b).sum():g}")
    load = force_from_normalised(b)
    if not load > 0.0:
        raise ValueError(f"pressure_coefficients must give a positive normal load [N/m]; got {load:g}")
    return PolynomialNormalContact(a, d, b, load, float(youngs_modulus), float(poisson_ratio))


def _normalised_gap_slope(z, a, d):
    """Coefficients g_m of dZ/dX at X = d + a s, in powers of s (m = 0..N-1)."""
    n = z.size - 1
    zbar = _base_change(n, d) @ z
    m = np.arange(1, n + 1)
    return m * zbar[1:] * a ** (m - 1)


def _pressure_for(z, a, d, kern):
    """Normalised pressure coefficients b (length N+1) from the slope; b_0 from the even BC."""
    n = z.size - 1
    g = _normalised_gap_slope(z, a, d)
    b = np.empty(n + 1)
    b[1:] = (a / kern) * (unit_matrices(n)[1] @ g)
    b[0] = -b[2::2].sum()
    return b


def pressure_is_physical(b, tol=1e-8):
    s = np.cos(np.linspace(0.0, np.pi, 401))[1:-1]
    val = np.polynomial.polynomial.polyval(s, b) / np.sqrt(1.0 - s * s)
    return bool(val.min() >= -tol * max(val.max(), 0.0)) and val.max() > 0


def solve_normal_polynomial(gap_coefficients, normal_load, youngs_modulus, poisson_ratio, *,
                            centre_guess=None, half_width_guess=None, xtol=1e-13):
    r"""Non-Hertzian 2-D normal contact of a polynomial gap, Eqs. (3.27)-(3.29).

    The gap (separation) ``Z(X) = sum Z_n X^n`` is moved to the patch centre ``d`` with the base
    change (3.18)/(3.29); the slope condition (3.28) then fixes ``B_1..B_N`` through ``[A]^-1``
    (3.11), the even boundary condition (3.3) fixes ``B_0``, and the odd boundary condition and
    the load (3.24) are two nonlinear equations for ``(a, d)``, solved by Powell's hybrid method
    from a Hertz-like start (curvature at the lowest minimum of Z). All of it runs in the
    normalised coordinate ``s = (X - d)/a``.

    Parameters
    ----------
    gap_coefficients : array_like, shape (N+1,)
        ``Z_n`` of the undeformed separation, ascending, degree N >= 2. ``Z_0`` and ``Z_1``
        (rigid shift/tilt) are allowed. [m^(1-n)]
    normal_load : float
        Normal load per unit length, > 0. [N/m]
    youngs_modulus : float
        Young's modulus of both bodies, > 0. [Pa]
    poisson_ratio : float
        Poisson's ratio of both bodies, in [0, 0.5). [-]
    centre_guess : float, optional
        Start value for the centre ``d`` (default: the lowest real minimum of ``Z``). [m]
    half_width_guess : float, optional
        Start value for ``a`` (default: from the load equation at ``centre_guess``). [m]
    xtol : float, optional
        Relative tolerance of the nonlinear solve. [-]

    Returns
    -------
    PolynomialNormalContact
        ``a``, ``d`` and the pressure. The rigid approach is not returned: in 2-D it depends on
        the datum of the logarithmic kernel (thesis text after (2.35)).

    Raises
    ------
    ValueError
        Bad input; no minimum of the gap; no convergence; or a solution whose pressure is
        negative somewhere (contact not coherent: the thesis' "non-physical" roots).
    """
    z = check_coefficients("gap_coefficients", gap_coefficients, "m^(1-n)", 3)
    load = float(check_range("normal_load", normal_load, "N/m", 0.0, None, lower_closed=False))
    kern = float(kernel_factor(youngs_modulus, poisson_ratio))
    n = z.size - 1
    ztrim = np.trim_zeros(z, "b")
    if ztrim.size < 3:
        raise ValueError("gap_coefficients must have degree >= 2 (a curved gap) [m^(1-n)]; "
                         f"got {z!r}")
    # --- start value for the centre: lowest real minimum of Z
    if centre_guess is None:
        dz = np.polynomial.polynomial.polyder(ztrim)
        crit = np.polynomial.polynomial.polyroots(dz)
        scale = max(1.0, np.abs(crit).max()) if crit.size else 1.0
        real = crit[np.abs(crit.imag) <= 1e-7 * scale].real
        d2z = np.polynomial.polynomial.polyder(z, 2)
        real = real[np.polynomial.polynomial.polyval(real, d2z) >= 0.0]
        if real.size == 0:
            raise ValueError("gap_coefficients must describe a gap with a minimum [m^(1-n)]; "
                             "none found")
        d0 = float(real[np.argmin(np.polynomial.polynomial.polyval(real, z))])
    else:
        d0 = float(check_range("centre_guess", centre_guess, "m"))

    def load_residual(a, d, target=load):
        return (force_from_normalised(_pressure_for(z, a, d, kern)) - target) / target

    def start_width(d, target):
        curv = np.polynomial.polynomial.polyval(d, np.polynomial.polynomial.polyder(z, 2))
        hi = 1e-12 * max(1.0, abs(d))
        if curv > 0.0:  # start a decade below the Hertz estimate a^2 = 2 K N / Z''
            guess = 0.1 * np.sqrt(2.0 * kern * target / curv)
            with np.errstate(over="ignore", invalid="ignore"):
                if load_residual(guess, d, target) < 0.0:
                    hi = guess
        best, best_val = hi, -np.inf
        for _ in range(1000):
            hi *= 1.25
            with np.errstate(over="ignore", invalid="ignore"):
                val = load_residual(hi, d, target)
            if val > 0.0:
                break
            if val > best_val:
                best, best_val = hi, val
        else:
            # the load may peak between two samples (e.g. negative flatness near its limit)
            peak = optimize.minimize_scalar(lambda a: -load_residual(a, d, target),
                                            bounds=(best / 1.25, best * 1.25), method="bounded",
                                            options={"xatol": 1e-15 * best})
            if not -peak.fun > 0.0:
                raise ValueError("gap_coefficients: no half-width carries normal_load [N/m] "
                                 f"(gap not convex at the centre guess {d:g} m)")
            hi = peak.x
        return optimize.brentq(lambda a: load_residual(a, d, target), hi / 1.25, hi,
                               xtol=1e-16, rtol=1e-14)

    def solve(target, a_start, d_start):
        def residual(u):
            a = a_start * u[0]
            d = d_start + a_start * u[1]
            if a <= 0.0:
                return np.array([1e3 * (1.0 - u[0]), 1e3])
            b = _pressure_for(z, a, d, kern)
            scale = max(np.abs(b).sum(), 1e-300)
            return np.array([b[1::2].sum() / scale, load_residual(a, d, target)])

        sol = optimize.root(residual, np.array([1.0, 0.0]), method="hybr", tol=xtol)
        ok = sol.x[0] > 0 and np.all(np.abs(residual(sol.x)) < 1e-9)
        return ok, a_start * sol.x[0], d_start + a_start * sol.x[1], np.abs(residual(sol.x)).max()

    if half_width_guess is None:
        a0 = start_width(d0, load)
    else:
        a0 = float(check_range("half_width_guess", half_width_guess, "m", 0.0, None,
                               lower_closed=False))
    ok, a, d, res = solve(load, a0, d0)
    if not ok:
        # continuation in the load from 1e-3 N (robust when the patch moves far from the
        # minimum, e.g. on the flank of a double well)
        a, d = start_width(d0, 1e-3 * load), d0
        for target in load * np.geomspace(1e-3, 1.0, 40):
            ok, a, d, res = solve(target, a, d)
            if not ok:
                break
    if not ok:
        raise ValueError("gap_coefficients: the normal problem did not converge "
                         f"(residual {res:.3g}); give centre_guess/half_width_guess")
    b = _pressure_for(z, a, d, kern)
    if not pressure_is_physical(b):
        raise ValueError("gap_coefficients: the solution has negative pressure (contact not "
                         f"coherent) at a = {a:g} m, d = {d:g} m [m^(1-n)]")
    return PolynomialNormalContact(a, d, b, force_from_normalised(b), float(youngs_modulus),
                                   float(poisson_ratio))


# ---------------------------------------------------------------------------------------------
# Sec. 3.3.2: tangential problem on a non-Hertzian pressure
# ---------------------------------------------------------------------------------------------
def _stick_solution(b, r):
    """Stick-zone polynomial form for stick ratio r = a*/a (all normalised with a = 1).

    Returns (xi_factor, e, force2) where the creepage is ``K mu xi_factor / a``, ``e`` are the
    coefficients of ``q2`` in ``s* = s - (1 - r)`` over ``sqrt(r^2 - s*^2)`` (sign: same as the
    full-slip part, i.e. q = mu (P + Q2) before the -sign(xi) of the package convention), and
    ``force2 = int Q2 ds`` (negative).
    """
    n = b.size - 1
    beta = unit_matrices(n)[0] @ b[1:]                         # slope of q1 / mu, in s
    delta = 1.0 - r
    gamma = _base_change(n - 1, delta) @ beta                 # slope of q1 in powers of s*
    if r == 0.0:
        return float(gamma[0]), np.zeros(n + 1), 0.0
    rhs = np.concatenate(([0.0], -gamma[1:]))                 # beta*_0 = t unknown (first entry)
    u = _inverse_scaled(n, r) @ rhs                             # e_1..e_N for t = 0
    rn = r ** np.arange(1, n + 1)
    # odd boundary condition: (u_1 - t/pi) r + sum_{odd n >= 3} u_n r^n = 0
    t = np.pi * (u[0] + (u[2::2] * rn[2::2] / r).sum())
    e = np.empty(n + 1)
    e[1:] = u
    e[1] -= t / np.pi
    e[0] = -(e[2::2] * rn[1::2]).sum()                          # even boundary condition
    c = np.asarray(_moment_ratios(n // 2 + 1))
    force2 = np.pi * (c * r ** (2 * np.arange(c.size)) @ e[0::2])
    return float(gamma[0] + t), e, float(force2)


def _stick_scalars(b, r):
    """(xi_factor, force2) of :func:`_stick_solution` for real or complex r != 0 (polynomials
    in r; used for their Taylor series about full stick)."""
    n = b.size - 1
    beta = unit_matrices(n)[0] @ b[1:]
    delta = 1.0 - r
    binom, power, upper = _binomials(n - 1)
    gamma = np.where(upper, binom * delta ** power, 0.0) @ beta
    rhs = np.concatenate(([0.0], -gamma[1:]))
    c = np.asarray(_moment_ratios((n + 1) // 2))
    k = np.arange(c.size, dtype=float)
    u = _toeplitz_even(c * r ** (2.0 * k) / (np.pi * (2.0 * k - 1.0)), n) @ rhs
    rn = r ** np.arange(1, n + 1)
    t = np.pi * (u[0] + (u[2::2] * rn[2::2] / r).sum())
    e = np.concatenate(([0.0], u)).astype(u.dtype)
    e[1] -= t / np.pi
    e[0] = -(e[2::2] * rn[1::2]).sum()
    c2 = np.asarray(_moment_ratios(n // 2 + 1))
    force2 = np.pi * (c2 * r ** (2 * np.arange(c2.size)) @ e[0::2])
    return gamma[0] + t, force2


@lru_cache(maxsize=32)
def _full_stick_series_cached(key):
    b = np.frombuffer(key, dtype=float)
    n = b.size - 1
    m = 8 * n + 32
    rho = 0.25
    eps = rho * np.exp(2j * np.pi * np.arange(m) / m)
    vals = np.array([_stick_scalars(b, 1.0 - e) for e in eps])
    load = force_from_normalised(b)
    vals[:, 1] += load
    coef = (np.fft.fft(vals, axis=0) / m).real / rho ** np.arange(m)[:, None]
    coef[0] = 0.0  # xi and T vanish at full stick (exactly)
    out = coef[:16].copy()
    out.setflags(write=False)
    return out


def _full_stick_series(b):
    """Taylor coefficients in eps = 1 - a*/a of (xi_factor, N + force2) about full stick.

    Both are polynomials in a*/a, so the Cauchy integral (FFT on |eps| = 1/4) gives their
    coefficients without the cancellation of ``N + force2`` as eps -> 0."""
    return _full_stick_series_cached(np.ascontiguousarray(b, dtype=float).tobytes())


SERIES_LIMIT = 1e-4
"""Below this ``|xi|/xi_c`` (or ``|T|/(mu N)``) the creep state is taken from the full-stick
Taylor series (relative accuracy ~1e-14 down to subnormal creepages)."""


def _series_state(b, target, which):
    """eps with series_which(eps) = target (Newton), and both series at eps."""
    coef = _full_stick_series(b)
    col = coef[:, which]
    eps = target / col[1]
    for _ in range(30):
        val = np.polynomial.polynomial.polyval(eps, col) - target
        der = np.polynomial.polynomial.polyval(eps, np.polynomial.polynomial.polyder(col))
        step = val / der
        eps -= step
        if abs(step) <= 1e-16 * abs(eps):
            break
    return (eps, np.polynomial.polynomial.polyval(eps, coef[:, 0]),
            np.polynomial.polynomial.polyval(eps, coef[:, 1]))


@dataclass(frozen=True)
class PolynomialTangentialContact:
    r"""Steady-rolling traction on a polynomial-form pressure (result of
    :func:`solve_tangential_polynomial`).

    Attributes
    ----------
    normal : PolynomialNormalContact
        The normal problem.
    friction_coefficient : float
        [-]
    creepage : float
        Longitudinal creepage ``xi``. [-]
    tangential_force : float
        Force on the wheel, opposing the creepage. [N/m]
    stick_ratio : float
        ``a*/a`` (1 full stick, 0 full slip). [-]
    stick_coefficients : ndarray
        ``e_n`` of the stick-zone correction in ``s* = (x - c*)/a`` over ``sqrt(r^2 - s*^2)``. [N/m]
    """

    normal: PolynomialNormalContact
    friction_coefficient: float
    creepage: float
    tangential_force: float
    stick_ratio: float
    stick_coefficients: np.ndarray

    @property
    def stick_half_width(self):
        """``a*``. [m]"""
        return self.stick_ratio * self.normal.half_width

    @property
    def stick_centre(self):
        """Global position of the stick-zone centre, ``d + a - a*``. [m]"""
        return self.normal.centre + self.normal.half_width - self.stick_half_width

    @property
    def is_admissible(self):
        """Whether ``|q| <= mu p`` holds on the stick zone (sampled at 400 points).

        The Carter-like construction (3.31)-(3.33) does not enforce the friction bound in the
        stick zone; for strongly non-Hertzian pressures it can be violated, and the solution is
        then not the physical one (several stick zones; see the text after (3.45)).
        """
        if self.stick_ratio == 0.0 or self.creepage == 0.0:
            return True
        u = np.cos(np.linspace(0.0, np.pi, 402))[1:-1]
        x = self.stick_centre + self.stick_half_width * u
        bound = self.friction_coefficient * self.normal.pressure(x)
        return bool(np.all(np.abs(self.traction(x)) <= bound * (1 + 1e-9) + 1e-12 * bound.max()))

    def traction(self, x):
        """Traction on the wheel at global ``x`` (Eqs. (3.31)-(3.33)). [Pa]"""
        x = check_range("x", x, "m")
        a = self.normal.half_width
        r = self.stick_ratio
        sgn = -np.sign(self.creepage)
        sstar = (x - self.stick_centre) / a
        inside = np.abs(sstar) < r
        root = np.sqrt(np.where(inside, r * r - sstar**2, 1.0))
        q2 = np.where(inside, np.polynomial.polynomial.polyval(sstar, self.stick_coefficients)
                      / (a * root), 0.0)
        return sgn * self.friction_coefficient * (self.normal.pressure(x) + q2)


def _check_normal(normal_contact):
    if not isinstance(normal_contact, PolynomialNormalContact):
        raise ValueError("normal_contact must be a PolynomialNormalContact (from "
                         "solve_normal_polynomial or normal_contact_from_coefficients); got "
                         f"{type(normal_contact).__name__}")
    if normal_contact.degree < 1:
        raise ValueError("normal_contact must have degree >= 1 [-]")
    return normal_contact


def tangential_state_polynomial(normal_contact, friction_coefficient, stick_ratio):
    r"""Creepage and force for a prescribed stick ratio ``a*/a``, Eqs. (3.38)-(3.44).

    The stick zone ``[a - 2a*, a]`` sits at the leading edge. Returned for the branch
    ``xi <= 0``, force ``>= 0`` (as Carter (2.51)-(2.53) and
    :func:`railcontact.roughness.asperity_tangential_state`); flip both signs for ``xi > 0``.

    Parameters
    ----------
    normal_contact : PolynomialNormalContact
        Normal solution.
    friction_coefficient : float
        Coulomb coefficient, >= 0. [-]
    stick_ratio : array_like
        ``a*/a`` in [0, 1]. [-]

    Returns
    -------
    creepage : ndarray
        (<= 0). [-]
    tangential_force : ndarray
        (>= 0). [N/m]
    """
    nc = _check_normal(normal_contact)
    mu = float(check_range("friction_coefficient", friction_coefficient, "-", 0.0, None))
    r = check_range("stick_ratio", stick_ratio, "-", 0.0, 1.0)
    kern = float(kernel_factor(nc.youngs_modulus, nc.poisson_ratio))
    flat = r.ravel()
    xi = np.empty(flat.size)
    force = np.empty(flat.size)
    for i, ri in enumerate(flat):
        f, _, f2 = _stick_solution(nc.normalised_coefficients, float(ri))
        xi[i] = -kern * mu * f / nc.half_width
        force[i] = mu * (nc.normal_load + f2)
    return xi.reshape(r.shape), force.reshape(r.shape)


def _stick_ratio_for(b, target, func, n_scan=64):
    """Largest r in [0, 1] with func(r) = target, func(1) = 0 side; bracket by scanning."""
    grid = np.linspace(1.0, 0.0, n_scan + 1)
    prev_r, prev_f = 1.0, func(1.0) - target
    if prev_f == 0.0:
        return 1.0
    for r in grid[1:]:
        f = func(r) - target
        if np.sign(f) != np.sign(prev_f):
            return optimize.brentq(lambda x: func(x) - target, r, prev_r, xtol=1e-15, rtol=1e-14)
        prev_r, prev_f = r, f
    return 0.0


def solve_tangential_polynomial(normal_contact, friction_coefficient, creepage=None,
                                tangential_force=None):
    r"""Steady 2-D rolling on a non-Hertzian polynomial-form pressure, Eqs. (3.30)-(3.44).

    Carter-like split ``q = mu p + q2(x*)`` (3.31)-(3.33) with ``q2`` a polynomial form on the
    stick zone ``[a - 2a*, a]`` (leading edge, package convention). The stick condition gives
    ``[A_s]{B_2} + [D_s][A_s*]{B_2*} = 0`` (3.40)-(3.41); the two boundary conditions (3.42) fix
    the free constant term and ``B_0*``, so for each ``a*`` the creepage (3.43) and the force
    (3.44) are explicit; the ``a*`` belonging to the given creepage (or force) is found by
    bracketing from ``a* = a`` downwards (the largest root: smallest force) and Brent's method.

    Parameters
    ----------
    normal_contact : PolynomialNormalContact
        Normal solution (:func:`solve_normal_polynomial`, :func:`normal_contact_from_coefficients`).
    friction_coefficient : float
        Coulomb coefficient, >= 0. [-]
    creepage : float, optional
        Longitudinal creepage ``xi``. [-]
    tangential_force : float, optional
        Force on the wheel, ``|T| <= mu N``. [N/m]
        Exactly one of ``creepage`` and ``tangential_force``.

    Returns
    -------
    PolynomialTangentialContact
        ``|xi| >= xi_c`` (the value at ``a* = 0``) is full slip, ``T = -sign(xi) mu N``.

    Raises
    ------
    ValueError
        Bad input; both or neither of creepage/tangential_force; ``|T| > mu N``.
    """
    nc = _check_normal(normal_contact)
    mu = float(check_range("friction_coefficient", friction_coefficient, "-", 0.0, None))
    if (creepage is None) == (tangential_force is None):
        raise ValueError("creepage and tangential_force: give exactly one of them; got "
                         f"creepage={creepage!r}, tangential_force={tangential_force!r}")
    b = nc.normalised_coefficients
    kern = float(kernel_factor(nc.youngs_modulus, nc.poisson_ratio))

    def xi_of(r):
        return kern * mu * _stick_solution(b, r)[0] / nc.half_width

    def t_of(r):  # magnitude of the force
        return mu * (nc.normal_load + _stick_solution(b, r)[2])

    if creepage is not None:
        xi = float(check_range("creepage", creepage, "-"))
        sgn = np.sign(xi)
        target = abs(xi)
        xi_c = xi_of(0.0) if mu > 0.0 else 0.0
        if mu == 0.0 or target == 0.0:
            r = 1.0
            force = 0.0
        elif target < SERIES_LIMIT * xi_c:
            eps, _, f = _series_state(b, target * nc.half_width / (kern * mu), 0)
            r = 1.0 - eps
            force = -sgn * mu * f
        else:
            r = 0.0 if target >= xi_c else _stick_ratio_for(b, target, xi_of)
            force = -sgn * t_of(r)
    else:
        force = float(check_range("tangential_force", tangential_force, "N/m",
                                  -mu * nc.normal_load, mu * nc.normal_load,
                                  condition="|T| <= mu N"))
        sgn = -np.sign(force)
        target = abs(force)
        if target == 0.0:
            r, xi = 1.0, 0.0
        elif target < SERIES_LIMIT * mu * nc.normal_load:
            eps, x, _ = _series_state(b, target / mu, 1)
            r = 1.0 - eps
            xi = sgn * kern * mu * x / nc.half_width
        else:
            r = _stick_ratio_for(b, target, t_of)
            xi = sgn * xi_of(r)
    _, e, _ = _stick_solution(b, r)
    return PolynomialTangentialContact(nc, mu, float(xi), float(force), float(r), e)


def creep_curve_polynomial(normal_contact, friction_coefficient, creepage):
    r"""Tangential force for an array of creepages (loop over :func:`solve_tangential_polynomial`).

    Parameters
    ----------
    normal_contact : PolynomialNormalContact
        Normal solution.
    friction_coefficient : float
        >= 0. [-]
    creepage : array_like
        Creepages. [-]

    Returns
    -------
    ndarray
        Force on the wheel, same shape as ``creepage``. [N/m]
    """
    xi = check_range("creepage", creepage, "-")
    out = np.array([solve_tangential_polynomial(normal_contact, friction_coefficient,
                                                creepage=float(v)).tangential_force
                    for v in xi.ravel()])
    return out.reshape(xi.shape)
