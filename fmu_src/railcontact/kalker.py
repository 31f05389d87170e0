r"""Kalker's creep coefficients C11, C22, C23 of the linear theory, as a smooth (C2) function.

Data: Kalker (1967), Kalker (1990) Table E.3, for nu = 0, 0.25, 0.5 and a0/b0 = 0.1 ... 1 and
b0/a0 = 0.9 ... 0.1 (19 axis ratios), shipped in ``railcontact/data/kalker_coefficients.csv``.
Nielsen (1998) Appendix B lists the nu = 0.25 column; its first two rows are garbled by the OCR
(see the erratum in the CSV header).

Interpolation (exact at every one of the 57 nodes, C2 everywhere):

1. For each tabulated nu_j and each coefficient, a not-a-knot cubic spline of ``ln C`` in
   ``s = ln(a0/b0)`` through the 19 nodes (C2 in s).
2. In nu, the *reciprocal* is interpolated quadratically through the three nodes:
   ``1/C(nu) = sum_j L_j(nu) / C(nu_j)`` (Lagrange weights L_j). 1/C is very nearly linear in
   nu (e.g. 1/C11 at a0/b0 = 1: 0.294, 0.243, 0.192), and it is exactly linear in the limit
   a0/b0 -> 0, where C11 -> pi^2/(4 (1-nu)). This is also how Vollebregt's CONTACT (subroutine
   ``linrol``) interpolates in nu.
3. Outside the table (a0/b0 < 0.1 or > 10) the value is ``C = C_asym(g, nu) exp(P(t))`` with
   Kalker's asymptotic expressions C_asym (Kalker 1990, Table E.3, as coded in CONTACT's
   ``linrol``) and a cubic ``P(t) = c1 t + c2 t^2 + c3 t^3`` in ``t = min(a0/b0, b0/a0) / 0.1``
   whose value, first and second derivative (in s) match ``ln C - ln C_asym`` of the table
   interpolant at the table edge. Hence C is C2 across the edge, and ``P -> 0`` (C -> C_asym)
   as the ellipse degenerates (t -> 0). At the table edges the asymptotes differ from the table
   by 0.6-6 %, so over 0.05 <= a0/b0 < 0.1 and 10 < a0/b0 <= 20 the result is a smooth
   transition whose accuracy is of that order; beyond that it tends to the asymptote. The cubic
   may leave the band between the edge ratio C/C_asym and 1 by at most 2.0 % (measured: C11 for
   nu = 0.25-0.5 near a0/b0 = 0.035-0.05, i.e. C11 down to 0.973 C_asym) on the a0/b0 < 0.1
   side and 0.9 % on the a0/b0 > 10 side. (Clamping the spline's end curvature to the
   asymptote's instead of not-a-knot was tried: it trades the C11 dip for a 2.5 % one in C23.)

Asymptotes (g = a0/b0 -> 0, i.e. b0 >> a0)::

    C11 = pi^2 / (4 (1-nu)),   C22 = pi^2 / 4,
    C23 = pi sqrt(g) / (3 (1-nu)) [1 + nu (ln(16/g) - 5)]

and (g' = b0/a0 -> 0, a0 >> b0), with Lambda = ln(16 / g'^2)::

    C11 = 2 pi / ((Lambda - 2 nu) g') [1 + (3 - ln 4) / (Lambda - 2 nu)]
    C22 = 2 pi / g' [1 + (1-nu)(3 - ln 4) / ((1-nu) Lambda + 2 nu)] / ((1-nu) Lambda + 2 nu)
    C23 = 2 pi / (3 g'^(3/2) ((1-nu) Lambda - 2 + 4 nu))

References
----------
.. [1] J.J. Kalker, On the rolling contact of two elastic bodies in the presence of dry
   friction, PhD thesis, TH Delft, 1967.
.. [2] J.J. Kalker, Three-dimensional elastic bodies in rolling contact, Kluwer, 1990,
   Appendix E, Table E.3 (creepage coefficients and their asymptotes).
.. [3] E.A.H. Vollebregt, CONTACT (Apache-2.0, github.com/eve70a/CONTACT), src/m_hertz.f90,
   subroutine linrol: the same table and asymptotes, with linear interpolation in g and
   reciprocal-quadratic interpolation in nu.
.. [4] J.B. Nielsen, IMM-PHD-1998-51, DTU, 1998, Eqs. (2.61)-(2.62) and Appendix B.
"""

from __future__ import annotations

from collections import namedtuple
from functools import lru_cache

import numpy as np

from ._files import package_directory
from ._validation import check_range

__all__ = ["KalkerCoefficients", "kalker_coefficients", "kalker_interpolant", "kalker_table",
           "kalker_asymptotes", "A0_OVER_B0_MAX"]

KalkerCoefficients = namedtuple("KalkerCoefficients", ["c11", "c22", "c23"])
KalkerCoefficients.__doc__ = "Kalker's creep coefficients C11, C22, C23 of the linear theory. [-]"

_NU_NODES = np.array([0.0, 0.25, 0.5])
_G_LOW, _G_HIGH = 0.1, 10.0
#: Largest a0/b0 accepted: C23 grows as (a0/b0)^1.5 / ln(a0/b0) and overflows float64 beyond
#: ~1e205; 1e100 keeps every coefficient (and products such as sqrt(a0 b0) C23) far from it.
#: Small ratios have no such limit (C11, C22 tend to constants, C23 to 0).
A0_OVER_B0_MAX = 1e100
_FD_STEP = 1e-3


@lru_cache(maxsize=1)
def kalker_table():
    """The tabulated coefficients, read from the package data file.

    Returns
    -------
    g : ndarray, shape (19,)
        a0/b0, ascending; the b0/a0 rows are snapped to exactly ``1 / (b0/a0)``. [-]
    nu : ndarray, shape (3,)
        Poisson's ratios 0, 0.25, 0.5. [-]
    c : ndarray, shape (3, 3, 19)
        ``c[k, j, i]`` = coefficient k (C11, C22, C23) at nu[j], g[i]. [-]
    """
    # (this package's directory now: inside the FMU the bundled copy's current extraction)
    path = package_directory() / "data" / "kalker_coefficients.csv"
    text = path.read_text(encoding="utf-8")
    rows = [line.split(",") for line in text.splitlines()
            if line and not line.startswith("#") and not line.startswith("a0_over_b0")]
    # erratum: Nielsen (1998) Appendix B rows a0/b0 = 0.1 and 0.2 are garbled by the OCR
    # ("0.01 | 9 59", "3.31 9.97 | 2.32"); the file holds Kalker's values (3.31, 2.52, 0.473 and
    # 3.37, 2.63, 0.603 at nu = 0.25), checked against Kalker (1990) Table E.3 as coded in
    # CONTACT's linrol and against the smooth run of the neighbouring rows.
    data = np.array(rows, dtype=float)
    g_raw = data[:, 0]
    # snap 1.11111 -> 1/0.9 etc. (the table lists b0/a0 = 0.9 ... 0.1 with one decimal)
    g_snap = np.where(g_raw > 1.0, 1.0 / np.round(1.0 / g_raw, 1), g_raw)
    g = np.unique(g_snap)
    c = np.empty((3, 3, g.size))
    for row, gs in zip(data, g_snap):
        i = int(np.argmin(np.abs(g - gs)))
        j = int(np.argmin(np.abs(_NU_NODES - row[1])))
        c[:, j, i] = row[2:5]
    return g, _NU_NODES.copy(), c


def kalker_asymptotes(a0_over_b0, poisson_ratio):
    """Kalker's asymptotic creep coefficients (Kalker 1990, Table E.3), see module docstring.

    Uses the g -> 0 branch for a0/b0 <= 1 and the b0/a0 -> 0 branch for a0/b0 > 1. Only
    meaningful for a0/b0 << 1 or >> 1.

    Parameters
    ----------
    a0_over_b0 : array_like
        Semi-axis ratio a0/b0 > 0. [-]
    poisson_ratio : array_like
        Poisson's ratio, in [0, 0.5]. [-]

    Returns
    -------
    KalkerCoefficients
    """
    g = check_range("a0_over_b0", a0_over_b0, "-", 0.0, A0_OVER_B0_MAX, lower_closed=False)
    nu = check_range("poisson_ratio", poisson_ratio, "-", 0.0, 0.5)
    return KalkerCoefficients(*_asymptotes(*np.broadcast_arrays(g, nu)))


def _asymptotes(g, nu):
    low = g <= 1.0
    gl = np.where(low, g, 1.0)                       # a0/b0 -> 0 branch
    c11_l = np.pi**2 / (4.0 * (1.0 - nu))
    c22_l = np.full_like(gl, np.pi**2 / 4.0)
    # ln(16/g) and ln(16/g'^2) as differences of logarithms: 16/g overflows for g < ~1e-307
    c23_l = (np.pi * np.sqrt(gl) / (3.0 * (1.0 - nu))
             * (1.0 + nu * (np.log(16.0) - np.log(gl) - 5.0)))
    gh = 1.0 / np.where(low, 1.0, g)                 # b0/a0 -> 0 branch
    lam = np.log(16.0) - 2.0 * np.log(gh)
    c3 = 3.0 - np.log(4.0)
    d11 = lam - 2.0 * nu
    c11_h = 2.0 * np.pi / (d11 * gh) * (1.0 + c3 / d11)
    # C22 = 2 pi / g' [1 + (1-nu) c3 / ((1-nu) Lambda + 2 nu)] / ((1-nu) Lambda + 2 nu), written
    # with d22 = Lambda + 2 nu/(1-nu) so that C11 == C22 holds bit-for-bit at nu = 0
    d22 = lam + 2.0 * nu / (1.0 - nu)
    c22_h = 2.0 * np.pi / (d22 * gh) * (1.0 + c3 / d22) / (1.0 - nu)
    c23_h = 2.0 * np.pi / (3.0 * gh**1.5 * ((1.0 - nu) * lam - 2.0 + 4.0 * nu))
    # (finite for a0/b0 <= A0_OVER_B0_MAX: g'^1.5 >= 1e-150)
    return (np.where(low, c11_l, c11_h), np.where(low, c22_l, c22_h),
            np.where(low, c23_l, c23_h))


#: The spline of :func:`_spline` as scipy's ``CubicSpline`` fits it, kept beside the table
#: (``data/kalker_spline.npz``: breakpoints ``x``, coefficients ``c`` and the SHA-256 of the
#: table it was fitted to), so that evaluating Kalker's coefficients needs no scipy at run
#: time (0.4 s of a first call's import). Rewritten with :func:`write_spline_data` when
#: ``kalker_coefficients.csv`` changes; a test checks it is scipy's fit of the current table.
SPLINE_DATA = "kalker_spline.npz"


def _table_digest():
    import hashlib  # noqa: PLC0415

    path = package_directory() / "data" / "kalker_coefficients.csv"
    return hashlib.sha256(path.read_bytes()).hexdigest()


def fit_spline():
    """``(x, c)`` of the not-a-knot cubic spline of ln C[k, j] in s = ln(a0/b0) (scipy's
    ``CubicSpline``: breakpoints, and coefficients (4, m - 1, 3, 3) highest power first)."""
    from scipy.interpolate import CubicSpline  # noqa: PLC0415  (the fit: once, see SPLINE_DATA)

    g, _, c = kalker_table()
    spline = CubicSpline(np.log(g), np.log(np.moveaxis(c, -1, 0)), axis=0,
                         bc_type="not-a-knot")
    return np.array(spline.x, dtype=float), np.array(spline.c, dtype=float)


def write_spline_data(path=None):
    """Write :data:`SPLINE_DATA` (default: into the package's ``data/``) from
    :func:`fit_spline`."""
    x, c = fit_spline()
    path = package_directory() / "data" / SPLINE_DATA if path is None else path
    with open(path, "wb") as fh:
        np.savez(fh, x=x, c=c, table_sha256=np.array(_table_digest()))


class _PiecewiseCubic:
    """A piecewise cubic polynomial from breakpoints ``x`` and coefficients ``c`` (4, m - 1,
    ...), highest power first, evaluated as scipy's ``PPoly`` does (the interval with
    ``x[i] <= s < x[i+1]``, the end intervals continued), with derivatives up to 2."""

    def __init__(self, x, c):
        self.x, self.c = x, c

    def __call__(self, s, nu=0):
        s = np.asarray(s, dtype=float)
        i = np.clip(np.searchsorted(self.x, s, side="right") - 1, 0, self.x.size - 2)
        d = (s - self.x[i]).reshape(s.shape + (1,) * (self.c.ndim - 2))
        c3, c2, c1, c0 = self.c[:, i]
        if nu == 0:
            return ((c3 * d + c2) * d + c1) * d + c0
        if nu == 1:
            return (3.0 * c3 * d + 2.0 * c2) * d + c1
        return 6.0 * c3 * d + 2.0 * c2


@lru_cache(maxsize=1)
def _spline():
    """One vector-valued not-a-knot cubic spline of ln C[k, j] in s = ln(a0/b0): the fit of
    :data:`SPLINE_DATA`, or scipy's (:func:`fit_spline`) where that file is missing or was
    fitted to another table."""
    try:
        with np.load(package_directory() / "data" / SPLINE_DATA) as data:
            x, c, digest = data["x"], data["c"], str(data["table_sha256"])
        if digest != _table_digest():
            raise ValueError("fitted to another table")
    except (OSError, KeyError, ValueError):
        x, c = fit_spline()
    return _PiecewiseCubic(x, c)


def kalker_interpolant():
    """The data of :func:`kalker_coefficients` within Kalker's table (a0/b0 0.1-10), for
    compiled evaluators (the exact table's scalar kernel):
    ``1 / C_k = sum_j L_j(nu) exp(-S_kj(ln(a0/b0)))``, ``L_j`` the quadratic Lagrange weights
    on ``nu_nodes``, ``S_kj`` the not-a-knot cubic spline of ln C_kj as scipy's CubicSpline holds
    it.

    Returns
    -------
    breakpoints : ndarray, shape (m,)
        Its breakpoints in ln(a0/b0). [-]
    coefficients : ndarray, shape (4, m - 1, 3, 3)
        Its polynomial coefficients per interval, highest power first, in (k, j) = (C11,
        C22, C23) x nu node. [-]
    nu_nodes : ndarray, shape (3,)
        The Poisson ratios of Kalker's table, 0, 0.25, 0.5. [-]
    """
    spline = _spline()
    return (np.array(spline.x, dtype=float), np.array(spline.c, dtype=float),
            np.array(_NU_NODES, dtype=float))


def _lagrange(nu):
    n0, n1, n2 = _NU_NODES
    return np.stack([(nu - n1) * (nu - n2) / ((n0 - n1) * (n0 - n2)),
                     (nu - n0) * (nu - n2) / ((n1 - n0) * (n1 - n2)),
                     (nu - n0) * (nu - n1) / ((n2 - n0) * (n2 - n1))], axis=-1)


def _table_log(s, nu, derivatives=True):
    """ln C_k, k = 0..2 (last axis), and optionally its first two s-derivatives, from the table
    interpolant: 1/C = sum_j L_j(nu) exp(-S_kj(s))."""
    spline = _spline()
    w = _lagrange(nu)[..., None, :] * np.exp(-spline(s))     # (..., k, j): L_j / C_kj
    u = w.sum(axis=-1)
    if not derivatives:
        return -np.log(u)
    d1, d2 = spline(s, 1), spline(s, 2)
    u1 = -(d1 * w).sum(axis=-1)
    u2 = ((d1 * d1 - d2) * w).sum(axis=-1)
    return -np.log(u), -u1 / u, -u2 / u + (u1 / u) ** 2


def _asym_log(s, nu):
    """ln C_asym,k (last axis) and its first two s-derivatives (5-point central differences)."""
    h = _FD_STEP
    f = [np.log(np.stack(_asymptotes(np.exp(s + m * h) + 0.0 * nu, nu), axis=-1))
         for m in (-2, -1, 0, 1, 2)]
    d1 = (f[0] - 8.0 * f[1] + 8.0 * f[3] - f[4]) / (12.0 * h)
    d2 = (-f[0] + 16.0 * f[1] - 30.0 * f[2] + 16.0 * f[3] - f[4]) / (12.0 * h * h)
    return f[2], d1, d2


def _coefficients(g, nu):
    """C11, C22, C23 (last axis) for 1-D arrays g, nu of equal length."""
    s = np.log(g)
    s_lo, s_hi = np.log(_G_LOW), np.log(_G_HIGH)
    result = _table_log(np.clip(s, s_lo, s_hi), nu, derivatives=False)
    for edge, side in ((s_lo, -1.0), (s_hi, 1.0)):
        outside = (s - edge) * side > 0.0
        if not np.any(outside):
            continue
        nu_o, s_o = nu[outside], s[outside]
        t0, t1, t2 = _table_log(edge, nu_o)             # spline at the (scalar) edge
        a0_, a1, a2 = _asym_log(edge, nu_o)
        l0, l1, l2 = t0 - a0_, t1 - a1, t2 - a2
        # t = exp(-side (s - edge)): dt/ds = -side t; at t = 1: P' = -side l1, P'' = l2 - P'
        p1 = -side * l1
        p2 = l2 - p1
        # P = c1 t + c2 t^2 + c3 t^3 with P(1) = l0, P'(1) = p1, P''(1) = p2
        c3 = (p2 - 2.0 * (p1 - l0)) / 2.0
        c2 = p1 - l0 - 2.0 * c3
        c1 = l0 - c2 - c3
        t = np.exp(-side * (s_o - edge))[:, None]
        ln_asym = np.log(np.stack(_asymptotes(g[outside], nu_o), axis=-1))
        result[outside] = ln_asym + t * (c1 + t * (c2 + t * c3))
    return np.exp(result)


def kalker_coefficients(a0_over_b0, poisson_ratio):
    r"""Kalker's creep coefficients C11, C22, C23, smooth (C2) in a0/b0 and nu.

    Exact (to the table's 3 significant digits) at every tabulated node; a not-a-knot cubic
    spline in ln(a0/b0), reciprocal-quadratic in nu, and a C2 blend into Kalker's asymptotes
    beyond the table (see the module docstring). Used in the linear theory, Eqs. (2.61)-(2.62):
    ``T_x = -G a0 b0 C11 xi_x``, ``T_y = -G a0 b0 (C22 xi_y + sqrt(a0 b0) C23 phi)``.

    Parameters
    ----------
    a0_over_b0 : array_like
        Semi-axis ratio a0/b0 (rolling over lateral), in (0, 1e100]. [-] Table range
        0.1 ... 10; smooth blend into the asymptotes over 0.05 ... 0.1 and 10 ... 20 (the
        validated range is [0.05, 20]); beyond that the result tends to Kalker's asymptotes.
        The upper limit :data:`A0_OVER_B0_MAX` keeps C23 ~ (a0/b0)^1.5 finite.
    poisson_ratio : array_like
        Poisson's ratio nu, in [0, 0.5]. [-]

    Returns
    -------
    KalkerCoefficients
        ``c11``, ``c22``, ``c23`` [-], broadcast over the inputs. For nu = 0, C11 = C22.

    Raises
    ------
    ValueError
        If an input is outside the range stated above (NaN and inf included).

    References
    ----------
    .. [1] J.J. Kalker, Three-dimensional elastic bodies in rolling contact, 1990, Table E.3.
    .. [2] J.B. Nielsen, IMM-PHD-1998-51, DTU, 1998, Appendix B.
    """
    g = check_range("a0_over_b0", a0_over_b0, "-", 0.0, A0_OVER_B0_MAX, lower_closed=False)
    nu = check_range("poisson_ratio", poisson_ratio, "-", 0.0, 0.5)
    g, nu = np.broadcast_arrays(g, nu)
    shape = g.shape
    g = np.array(g, dtype=float).ravel()
    nu = np.array(nu, dtype=float).ravel()
    c = _coefficients(g, nu)
    return KalkerCoefficients(*(c[:, k].reshape(shape)[()] for k in range(3)))


@lru_cache(maxsize=1024)
def kalker_coefficients_cached(a0_over_b0, poisson_ratio):
    """(C11, C22, C23) as plain floats for scalar a0/b0 and nu, memoised (the scalar creep paths
    of the FMU: an FMU asks for the same ellipse shape step after step, and
    a0/b0 = (a1 s)/(b1 s) of Hertz's scaling takes only a few rounded values). Same values as
    :func:`kalker_coefficients`, which also makes the range check on a cache miss."""
    c = kalker_coefficients(a0_over_b0, poisson_ratio)
    return float(c.c11), float(c.c22), float(c.c23)
