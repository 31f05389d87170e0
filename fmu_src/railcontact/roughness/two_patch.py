"""Two adjacent contact patches with cross influence (Nielsen 1998, Sec. 6.4 and 6.5.2),
(6.12)-(6.28) and (6.42)-(6.54); see :mod:`railcontact.roughness` for the method and limits.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import optimize

from .. import polynomial as _poly
from .._validation import check_choice, check_range
from .asperity import asperity_gap_coefficients


# ---------------------------------------------------------------------------------------------
# two patches with cross influence (6.12)-(6.28), (6.42)-(6.54)
# ---------------------------------------------------------------------------------------------
def double_asperity_coefficients(curvature):
    r"""The asperity ``A`` of Fig. 6.5: ``lambda3 = 0``, ``lambda4 = -1536 lambda2^3``, (6.26)-(6.28).

    Parameters
    ----------
    curvature : float
        ``lambda2 < 0`` (a trough between two minima at ``+-1/(16 |lambda2|)``). [1/m]

    Returns
    -------
    ndarray
        Gap coefficients ``[0, 0, l2/2, 0, l4/24]``. [m^(1-n)]
    """
    l2 = float(check_range("curvature", curvature, "1/m", None, 0.0, upper_closed=False))
    return asperity_gap_coefficients(l2, 0.0, -1536.0 * l2**3)


def _pv_basis(degree, s):
    """Matrix F[j, n] = PV int_-1^1 s'^n / ((s_j - s') sqrt(1 - s'^2)) ds' (stable outside)."""
    s = np.asarray(s, dtype=float)
    n = degree
    inside_vals = np.zeros((s.size, n + 1))
    if n >= 1:
        amat = _poly.unit_matrices(n)[0]
        vand = np.vander(s, n, increasing=True)
        inside_vals[:, 1:] = vand @ amat
    outside = np.abs(s) > 1.0
    so = np.where(outside, s, 2.0)
    root = np.sqrt(so * so - 1.0)
    w = np.sign(so) / (np.abs(so) + root)
    p2c = np.zeros((n + 1, n + 1))  # column k: Chebyshev coefficients of s^k
    for k in range(n + 1):
        p2c[: k + 1, k] = np.polynomial.chebyshev.poly2cheb(np.eye(n + 1)[k])[: k + 1]
    far = (np.pi * np.sign(so) / root)[:, None] * (np.vander(w, n + 1, increasing=True) @ p2c)
    return np.where(outside[:, None], far, inside_vals)


def _pv_basis_complex(degree, z):
    """Analytic continuation of the field of s^n off the cut [-1, 1] (for Taylor expansion)."""
    n = degree
    vals = np.zeros((z.size, n + 1), dtype=complex)
    if n >= 1:
        vals[:, 1:] = np.vander(z, n, increasing=True) @ _poly.unit_matrices(n)[0]
    factor = np.pi / (np.sqrt(z - 1.0) * np.sqrt(z + 1.0))
    return vals + factor[:, None] * np.vander(z, n + 1, increasing=True)


@dataclass(frozen=True)
class _Form:
    centre: float
    half_width: float


def _cross_matrix(target, source, degree, nodes, expansion):
    """Field of each normalised basis form of ``source`` at the ``nodes`` (target-normalised),
    as seen by the target patch: exact values ("chebyshev" = collocation) or the values of its
    Taylor polynomial of degree ``len(nodes)-1`` about the target centre ("taylor", thesis)."""
    m = nodes.size
    if expansion == "chebyshev":
        s = (target.centre + target.half_width * nodes - source.centre) / source.half_width
        return _pv_basis(degree, s) / source.half_width
    # Taylor coefficients by the Cauchy integral on a circle inside the convergence radius
    dist = (abs(target.centre - source.centre) - source.half_width) / target.half_width
    rho = 0.5 * dist
    nfft = max(64, 4 * m)
    theta = 2.0 * np.pi * np.arange(nfft) / nfft
    z = rho * np.exp(1j * theta)
    s = (target.centre + target.half_width * z - source.centre) / source.half_width
    vals = _pv_basis_complex(degree, s) / source.half_width
    coef = np.fft.fft(vals, axis=0)[:m] / nfft / rho ** np.arange(m)[:, None]
    return np.real(np.vander(nodes, m, increasing=True) @ coef)


def _nodes(m):
    return np.cos(np.pi * (np.arange(m) + 0.5) / m)


@dataclass(frozen=True)
class TwoPatchContact:
    r"""Normal contact with two separate patches (result of :func:`two_patch_normal_contact`).

    Attributes
    ----------
    patches : tuple of railcontact.polynomial.PolynomialNormalContact
        The two patches, ordered by position (``patches[1]`` is the leading one, the thesis'
        "first" patch). Each carries its own polynomial form; the pressure of the contact is
        their sum.
    normal_load : float
        Total load. [N/m]
    cross_influence : bool
        Whether the field of each patch acts on the other.
    expansion : str
        ``"chebyshev"`` or ``"taylor"``.
    degree : int
        Degree of the polynomial forms. [-]
    """

    patches: tuple
    normal_load: float
    cross_influence: bool
    expansion: str
    degree: int

    @property
    def loads(self):
        """Load on each patch. [N/m]"""
        return tuple(p.normal_load for p in self.patches)

    def pressure(self, x):
        """Total pressure at ``x``. [Pa]"""
        return self.patches[0].pressure(x) + self.patches[1].pressure(x)


def _slope_at(z, x):
    return np.polynomial.polynomial.polyval(x, np.polynomial.polynomial.polyder(z))


def _two_patch_linear(z, geo, loads, kern, degree, cross, expansion):
    """Solve the collocation + force equations for the two coefficient vectors."""
    m = degree
    nodes = _nodes(m)
    forms = [_Form(c, a) for a, c in geo]
    c_k = np.asarray(_poly.moment_ratios(m // 2 + 1))
    size = 2 * (m + 1)
    mat = np.zeros((size, size))
    rhs = np.zeros(size)
    for i in range(2):
        rows = slice(i * m, (i + 1) * m)
        own = _pv_basis(m, nodes) / forms[i].half_width
        mat[rows, i * (m + 1):(i + 1) * (m + 1)] = own
        if cross:
            j = 1 - i
            mat[rows, j * (m + 1):(j + 1) * (m + 1)] = _cross_matrix(forms[i], forms[j], m,
                                                                      nodes, expansion)
        rhs[rows] = _slope_at(z, forms[i].centre + forms[i].half_width * nodes) / kern
        row = 2 * m + i
        mat[row, i * (m + 1) + np.arange(0, m + 1, 2)] = np.pi * c_k[: m // 2 + 1]
        rhs[row] = loads[i]
    sol = np.linalg.solve(mat, rhs)
    return sol[: m + 1], sol[m + 1:]


def _outside_field_antiderivative(b, s):
    """Antiderivative in s of the normalised field PV int b(s')/((s - s') sqrt(1-s'^2)) ds' for
    |s| >= 1 (one side). With the Chebyshev coefficients c_k of b and w = 1/(t + sqrt(t^2-1)),
    t = |s|: pi w^k / sqrt(t^2-1) = -(pi/k) d(w^k)/dt and pi / sqrt(t^2-1) = -pi d(ln w)/dt."""
    cheb = np.polynomial.chebyshev.poly2cheb(b)
    t = abs(float(s))
    if s < 0:
        cheb = cheb * (-1.0) ** np.arange(cheb.size)
    w = 1.0 / (t + np.sqrt(max(t * t - 1.0, 0.0)))
    k = np.arange(1, cheb.size)
    return -np.pi * (cheb[0] * np.log(w) + (cheb[1:] * w**k / k).sum())


def _deformed_gap_jump(z, patches, kern):
    """h(inner edge of right patch) - h(inner edge of left patch) = int (Z' - K field) dX,
    with the field integrated in closed form (it is the outside field of both patches)."""
    lo = patches[0].centre + patches[0].half_width
    hi = patches[1].centre - patches[1].half_width
    jump = float(np.polynomial.polynomial.polyval(hi, z) - np.polynomial.polynomial.polyval(lo, z))
    for p in patches:
        s_lo = (lo - p.centre) / p.half_width
        s_hi = (hi - p.centre) / p.half_width
        b = p.normalised_coefficients
        jump -= kern * (_outside_field_antiderivative(b, s_hi)
                        - _outside_field_antiderivative(b, s_lo))
    return jump


def two_patch_normal_contact(gap_coefficients, normal_load, youngs_modulus, poisson_ratio,
                             centre_guesses, *, load_split=0.5, cross_influence=True, degree=8,
                             expansion="chebyshev"):
    r"""Normal contact of a gap with two minima and two separate patches, (6.12)-(6.25).

    Unknowns: the two polynomial forms (degree ``M = degree``), half-widths ``a1, a2`` and
    centres. For given geometry the forms follow linearly from the slope condition (6.20)-(6.21)
    at ``M`` Chebyshev nodes of each patch plus the load of each patch (6.24)-(6.25); the four
    boundary conditions (6.22)-(6.23) are then solved for the geometry by Powell's hybrid method,
    started from the solution without cross influence.

    Parameters
    ----------
    gap_coefficients : array_like
        Global gap ``Z(X)`` ascending, degree <= ``degree``. [m^(1-n)]
    normal_load : float
        Total load, > 0. [N/m]
    youngs_modulus : float
        > 0. [Pa]
    poisson_ratio : float
        In [0, 0.5). [-]
    centre_guesses : sequence of 2 floats
        Positions of the two minima of ``Z`` (start values). [m]
    load_split : float or "compatible", optional
        Fraction of the load carried by the patch at the smaller ``X`` (the thesis leaves this
        open and uses equal shares for its symmetric example: 0.5). ``"compatible"``: the share
        that makes the deformed gap close at both patches (one more equation, the relative
        displacement between the patches integrated from the exact fields).
    cross_influence : bool, optional
        Include the field of each patch on the other (default) or not (independent patches).
    degree : int, optional
        Degree ``M`` of the polynomial forms, >= degree of the gap (thesis: 4). With cross
        influence a higher ``M`` represents the other patch's field better. [-]
    expansion : {"chebyshev", "taylor"}, optional
        How the other patch's field is made polynomial: interpolation at the Chebyshev nodes
        (default) or Taylor expansion about the patch centre (thesis, text after (6.21)).

    Returns
    -------
    TwoPatchContact

    Raises
    ------
    ValueError
        Bad input; patches overlapping or merged; no convergence; negative pressure.
    """
    z = _poly.check_coefficients("gap_coefficients", gap_coefficients, "m^(1-n)", 3)
    load = float(check_range("normal_load", normal_load, "N/m", 0.0, None, lower_closed=False))
    kern = float(_poly.kernel_factor(youngs_modulus, poisson_ratio))
    m = _poly.check_degree(degree, lower=max(2, z.size - 1))
    check_choice("expansion", expansion, {"chebyshev", "taylor"})
    guesses = np.sort(check_range("centre_guesses", centre_guesses, "m"))
    if guesses.shape != (2,) or guesses[0] == guesses[1]:
        raise ValueError(f"centre_guesses must be two distinct positions [m]; got {centre_guesses!r}")
    compatible = isinstance(load_split, str)
    if compatible:
        check_choice("load_split", load_split, {"compatible"})
        if not cross_influence:
            raise ValueError("load_split='compatible' needs cross_influence=True")
        frac0 = 0.5
    else:
        frac0 = float(check_range("load_split", load_split, "-", 0.0, 1.0, lower_closed=False,
                                  upper_closed=False))
    zp = np.zeros(m + 1)
    zp[: z.size] = z

    def independent(frac, total):
        out = []
        for g, share in zip(guesses, (frac, 1.0 - frac)):
            nc = _poly.solve_normal_polynomial(z, share * total, youngs_modulus, poisson_ratio,
                                               centre_guess=g)
            out.append((nc.half_width, nc.centre))
        return np.array([out[0][0], out[1][0], out[0][1], out[1][1], frac])

    def build(v, total):
        geo = [(v[0], v[2]), (v[1], v[3])]
        frac = v[4]
        b, g = _two_patch_linear(zp, geo, (frac * total, (1 - frac) * total), kern, m,
                                 cross_influence, expansion)
        return geo, frac, b, g

    def coupled(total, v0):
        """Powell hybrid solve for (a1, a2, c1, c2[, frac]) at the load ``total`` from v0."""
        scale = np.array([v0[0], v0[1], v0[0], v0[1], 1.0])
        nvar = 5 if compatible else 4

        def unpack(u):
            v = v0.copy()
            v[:nvar] = v0[:nvar] + scale[:nvar] * u
            return v

        def residual(u):
            v = unpack(u)
            if v[0] <= 0 or v[1] <= 0 or not 0 < v[4] < 1 or v[2] + v[0] >= v[3] - v[1]:
                return np.full(nvar, 1e3)
            geo, frac, b, g = build(v, total)
            sign = (-1.0) ** np.arange(m + 1)
            res = [b.sum() / total, (sign * b).sum() / total, g.sum() / total,
                   (sign * g).sum() / total]
            if compatible:
                patches = _patches(geo, b, g, youngs_modulus, poisson_ratio)
                res.append(_deformed_gap_jump(z, patches, kern) / (kern * total))
            return np.array(res)

        sol = optimize.root(residual, np.zeros(nvar), method="hybr", tol=1e-13)
        res = np.abs(residual(sol.x)).max()
        return res < 1e-9, unpack(sol.x), res

    ok = False
    res = np.inf
    try:
        v = independent(frac0, load)
    except ValueError:
        v = None
    if v is not None:
        if v[2] + v[0] >= v[3] - v[1]:
            raise ValueError("normal_load: the patches overlap already without cross influence "
                             "(one coherent patch: use railcontact.polynomial."
                             f"solve_normal_polynomial) [N/m]; got {load:g}")
        ok, v, res = coupled(load, v)
    if not ok:
        # continuation in the load, starting where the independent patches are small and far
        # apart (needed when a patch reaches the concave flank between the minima, where the
        # independent single-patch problem has no solution)
        for first in (0.5, 0.2, 0.05, 1e-2, 1e-3, 1e-4):
            try:
                v = independent(frac0, first * load)
            except ValueError:
                continue
            for total in load * np.geomspace(first, 1.0, 10)[1:]:
                ok, v, res = coupled(total, v)
                if not ok:
                    break
            break
    if not ok:
        raise ValueError("normal_load: the two-patch problem did not converge (residual "
                         f"{res:.3g}); the patches may have merged [N/m]; got {load:g}")
    geo, frac, b, g = build(v, load)
    patches = _patches(geo, b, g, youngs_modulus, poisson_ratio)
    if patches[0].centre + patches[0].half_width >= patches[1].centre - patches[1].half_width:
        raise ValueError(f"normal_load: the two patches merge [N/m]; got {load:g}")
    for p in patches:
        if not _poly.pressure_is_physical(p.normalised_coefficients, tol=1e-7):
            raise ValueError(f"normal_load: negative pressure in a patch [N/m]; got {load:g}")
    return TwoPatchContact(tuple(patches), load, bool(cross_influence), expansion, m)


def _patches(geo, b, g, e, nu):
    out = []
    for (a, c), coef in zip(geo, (b, g)):
        out.append(_poly.PolynomialNormalContact(float(a), float(c), coef,
                                                 _poly.force_from_normalised(coef),
                                                 float(e), float(nu)))
    return out


@dataclass(frozen=True)
class TwoPatchTangentialContact:
    r"""Steady rolling on two patches (result of :func:`two_patch_tangential_contact`).

    Attributes
    ----------
    normal : TwoPatchContact
    friction_coefficient : float
        [-]
    creepage : float
        Common creepage of both patches (stationary contact). [-]
    forces : tuple of float
        Force on the wheel per patch (ordered like ``normal.patches``). [N/m]
    stick_ratios : tuple of float
        ``a_i*/a_i``. [-]
    stick_coefficients : tuple of ndarray
        Normalised coefficients of each stick-zone form in ``(x - c_i*)/a_i*``. [N/m]
    cross_influence : bool
    """

    normal: TwoPatchContact
    friction_coefficient: float
    creepage: float
    forces: tuple
    stick_ratios: tuple
    stick_coefficients: tuple
    cross_influence: bool

    @property
    def tangential_force(self):
        """Total force. [N/m]"""
        return float(sum(self.forces))

    def traction(self, x):
        """Traction on the wheel at ``x``. [Pa]"""
        x = check_range("x", x, "m")
        total = self.normal.pressure(x)
        for p, r, e in zip(self.normal.patches, self.stick_ratios, self.stick_coefficients):
            if r > 0:
                a_s = r * p.half_width
                c_s = p.centre + p.half_width - a_s
                total = total + _poly.polynomial_form(e / a_s ** np.arange(e.size), x - c_s, a_s)
        return -np.sign(self.creepage) * self.friction_coefficient * total


def two_patch_tangential_contact(normal, friction_coefficient, creepage, *, cross_influence=None):
    r"""Steady rolling with a common creepage on two patches, (6.42)-(6.51).

    Each patch gets ``q_i = mu p_i + q_i*`` with a stick zone at its leading edge (6.46)-(6.47).
    The stick conditions (6.48)-(6.49) include the fields of all four forms; the other patch's
    fields are made polynomial as in the normal problem (``normal.expansion``). For given stick
    ratios the two stick forms are linear (collocation at ``M`` Chebyshev nodes per stick zone +
    even boundary conditions); the odd boundary conditions are solved for the two stick ratios by
    Powell's hybrid method from the solution without cross influence.

    Parameters
    ----------
    normal : TwoPatchContact
        Normal solution (the thesis uses the one *with* cross influence for both variants).
    friction_coefficient : float
        > 0. [-]
    creepage : float
        Common creepage ``xi != 0``; both patches must be in partial slip. [-]
    cross_influence : bool, optional
        Default: ``normal.cross_influence``.

    Returns
    -------
    TwoPatchTangentialContact

    Raises
    ------
    ValueError
        Bad input, a patch in full slip (stick zone vanishing) or no convergence.
    """
    if not isinstance(normal, TwoPatchContact):
        raise ValueError("normal must be a TwoPatchContact (from two_patch_normal_contact); got "
                         f"{type(normal).__name__}")
    mu = float(check_range("friction_coefficient", friction_coefficient, "-", 0.0, None,
                           lower_closed=False))
    xi = float(check_range("creepage", creepage, "-"))
    if xi == 0.0:
        raise ValueError("creepage must be non-zero [-]; got 0")
    cross = normal.cross_influence if cross_influence is None else bool(cross_influence)
    patches = normal.patches
    m = normal.degree
    e_mod, nu = patches[0].youngs_modulus, patches[0].poisson_ratio
    kern = float(_poly.kernel_factor(e_mod, nu))
    target = abs(xi) / (kern * mu)
    nodes = _nodes(m)
    # independent solutions: start values, and the answer without cross influence
    indep = [_poly.solve_tangential_polynomial(p, mu, creepage=xi) for p in patches]
    r0 = np.array([t.stick_ratio for t in indep])
    if np.any(r0 <= 0.0):
        raise ValueError("creepage: a patch is in full slip; the two-patch tangential problem "
                         f"needs partial slip on both [-]; got {xi:g}")
    c_k = np.asarray(_poly.moment_ratios(m // 2 + 1))
    pforms = [_Form(p.centre, p.half_width) for p in patches]

    def stick_forms(r):
        return [_Form(p.centre + p.half_width * (1 - ri), p.half_width * ri)
                for p, ri in zip(patches, r)]

    def linear(r):
        sforms = stick_forms(r)
        size = 2 * (m + 1)
        mat = np.zeros((size, size))
        rhs = np.zeros(size)
        for i in range(2):
            rows = slice(i * m, (i + 1) * m)
            x = sforms[i].centre + sforms[i].half_width * nodes
            known = np.zeros(m)
            for j in range(2):
                if j == i or cross:
                    sj = (x - pforms[j].centre) / pforms[j].half_width
                    if j != i and normal.expansion == "taylor":
                        known += _cross_matrix(sforms[i], pforms[j], m, nodes, "taylor") @ \
                            patches[j].normalised_coefficients
                    else:
                        known += (_pv_basis(m, sj) / pforms[j].half_width) @ \
                            patches[j].normalised_coefficients
            mat[rows, i * (m + 1):(i + 1) * (m + 1)] = _pv_basis(m, nodes) / sforms[i].half_width
            if cross:
                j = 1 - i
                mat[rows, j * (m + 1):(j + 1) * (m + 1)] = _cross_matrix(
                    sforms[i], sforms[j], m, nodes, normal.expansion)
            rhs[rows] = target - known
            row = 2 * m + i
            mat[row, i * (m + 1) + np.arange(0, m + 1, 2)] = 1.0  # even boundary condition
        sol = np.linalg.solve(mat, rhs)
        return sol[: m + 1], sol[m + 1:]

    def residual(r):
        if np.any(r <= 0) or np.any(r > 1):
            return np.array([1e3, 1e3])
        e1, e2 = linear(r)
        return np.array([e1[1::2].sum(), e2[1::2].sum()]) / (
            patches[0].normal_load + patches[1].normal_load)

    if cross:
        sol = optimize.root(residual, r0, method="hybr", tol=1e-13)
        r = sol.x
        res = residual(r)
        if not (np.all(np.abs(res) < 1e-9) and np.all((r > 0) & (r <= 1))):
            raise ValueError("creepage: the two-patch tangential problem did not converge "
                             f"(residual {np.abs(res).max():.3g}) [-]; got {xi:g}")
        e1, e2 = linear(r)
        coefs = (e1, e2)
    else:
        r = r0
        coefs = tuple(t.stick_coefficients * ri ** np.arange(m + 1) for t, ri in zip(indep, r0))
    forces = tuple(float(-np.sign(xi) * mu * (p.normal_load + np.pi * (c_k @ e[0::2])))
                   for p, e in zip(patches, coefs))
    return TwoPatchTangentialContact(normal, mu, xi, forces, tuple(float(v) for v in r),
                                     tuple(coefs), cross)
