"""The normal contact (Hertz), always on: the contact ellipse or strip from the normal force."""

from __future__ import annotations

import math

import numpy as np

from .. import _compiled, hertz
from .._validation import check_range
from ..scene import DEFAULT_SCENE
from .base import Effect

__all__ = ["NormalContact", "NO_NORMAL_FORCE_MESSAGE", "unit_ellipse", "unit_ellipses",
           "inverse_grid", "make_inverse_grid", "write_inverse_grid", "INVERSE_GRID_DATA"]

_FLOAT_MAX = 1.7976931348623157e308


#: Logged (once per FMU instance, category Warning) at the first evaluation with creepage but
#: without a normal force (e.g. the input normal_force left at its start value 0).
NO_NORMAL_FORCE_MESSAGE = (
    "normal_force = 0 N with non-zero creepage: no contact, so every force output is 0 (the "
    "input's start value is 0 N; set or connect normal_force)")


#: The inverse of log f(e^u) (f of :func:`railcontact.hertz.hertz_3d`, decreasing in k = e^u):
#: nodes (log f increasing), u and du/dlog f there, made on first use. Module level because it
#: is data, the same for every instance (no per-instance object is kept here).
_INVERSE_GRID = []
#: Complex-step size of the node slopes d log f / du (exact to round-off for any small step).
_COMPLEX_STEP = 1e-30


def make_inverse_grid():
    """``(nodes, coefficients)`` of :func:`inverse_grid`, computed (scipy's ``elliprd`` with a
    complex argument: the slopes by complex step)."""
    from scipy.special import elliprd  # noqa: PLC0415  (the grid's data: see INVERSE_GRID_DATA)

    u = np.linspace(math.log(hertz.AXIS_RATIO_MIN), 0.0, 4001)
    k2 = np.exp(2.0 * u)
    z = k2 + 1j * (2.0 * _COMPLEX_STEP) * k2               # d(k^2)/du = 2 k^2
    f = elliprd(0.0, 1.0, z) / elliprd(0.0, z, 1.0)
    nodes, y, slope = (np.ascontiguousarray(v[::-1]) for v in (
        np.log(f.real), u, f.real / (f.imag / _COMPLEX_STEP)))     # du / dlog f
    nodes[0] = 0.0                  # (the circle, k = 1: exactly log 1)
    h = np.diff(nodes)
    m0, m1 = slope[:-1] * h, slope[1:] * h
    y0, y1 = y[:-1], y[1:]
    coefficients = np.column_stack([
        nodes[:-1], 1.0 / h, y0, m0, 3.0 * (y1 - y0) - 2.0 * m0 - m1,
        2.0 * (y0 - y1) + m0 + m1, slope[:-1], slope[1:] - slope[:-1]])
    return nodes, np.ascontiguousarray(coefficients)


#: :func:`make_inverse_grid`'s result kept in the package (``data/hertz_inverse_grid.npz``),
#: so that a vehicle FMU's initialisation imports no scipy (``scipy.special``: 0.3-0.6 s of
#: a fresh process); rewritten with :func:`write_inverse_grid`, checked by a test.
INVERSE_GRID_DATA = "hertz_inverse_grid.npz"


def write_inverse_grid(path=None):
    """Write :data:`INVERSE_GRID_DATA` (default: into the package's ``data/``)."""
    from .._files import package_directory  # noqa: PLC0415

    nodes, coefficients = make_inverse_grid()
    path = package_directory() / "data" / INVERSE_GRID_DATA if path is None else path
    with open(path, "wb") as fh:
        np.savez(fh, nodes=nodes, coefficients=coefficients)


def inverse_grid():
    """The inverse of log f(e^u) (f of :func:`railcontact.hertz.hertz_3d`, decreasing in
    k = e^u): ``(nodes, coefficients)``, the nodes of log f (increasing from 0) and, per
    interval, (node, 1/width, c0, c1, c2, c3, s0, s1 - s0): the cubic Hermite interpolant of
    u(log f) as c0 + t (c1 + t (c2 + t c3)), t in [0, 1] across the interval, and its slope
    du/dlog f linear between the nodes' s0, s1. Read from :data:`INVERSE_GRID_DATA` (else
    computed) on first use."""
    if not _INVERSE_GRID:
        from .._files import package_directory  # noqa: PLC0415

        try:
            with np.load(package_directory() / "data" / INVERSE_GRID_DATA) as data:
                grid = (np.ascontiguousarray(data["nodes"], dtype=float),
                        np.ascontiguousarray(data["coefficients"], dtype=float))
        except (OSError, KeyError, ValueError):
            grid = make_inverse_grid()
        _INVERSE_GRID.append(grid)
    return _INVERSE_GRID[0]


def unit_ellipse(curvature_longitudinal, curvature_lateral, youngs_modulus, poisson_ratio):
    """``hertz_3d(1.0, ...)`` as three floats (a1, b1, p1 at N = 1 N): :func:`unit_ellipses`
    for one pair.

    A scene's fixed curvatures give its ellipse once per process. ``hertz_3d`` itself imports
    ``scipy.special`` (Carlson's R_D), which costs a fresh process 0.3-1 s, most of what an FMU
    of a table scene with curvatures would add to its user's start (docs/performance.md);
    :func:`unit_ellipses` gives the same values to a few ulp (4e-15 relative, against
    ``hertz_3d`` in tests/test_fmu_vehicle.py) in a few microseconds, the same with an empty
    user cache as with a warm one, and the same as a vehicle's contacts get."""
    a1, b1, p1 = unit_ellipses(np.array([float(curvature_longitudinal)]),
                               np.array([float(curvature_lateral)]), float(youngs_modulus),
                               float(poisson_ratio))
    return float(a1[0]), float(b1[0]), float(p1[0])


def unit_ellipses(curvature_longitudinal, curvature_lateral, youngs_modulus, poisson_ratio):
    r"""Hertz ellipses at N = 1 N for many curvature pairs: what
    :func:`railcontact.hertz.hertz_3d` gives, in one compiled loop.

    ``hertz_3d`` finds the eccentricity k = c_min/c_max of ``f(k) = B'/A'`` (or its inverse)
    by 64 bisection steps (about 0.5 ms a call); a contact whose curvatures change at every
    step (the contact point moves over the wheel and rail profiles) cannot pay that. Here the
    same equation, ``log f(e^u) = log(c_minor/c_major)`` with ``f(k) = R_D(0, 1, k^2) /
    R_D(0, k^2, 1)`` (Johnson (1985) Eq. (4.17), the module docstring of
    :mod:`railcontact.hertz`), starts from the cubic Hermite interpolant of its inverse on a
    grid of 4001 values of u (slopes by complex step; error ~1e-13) and takes one Newton step
    (error: round-off). The semi-axes and the pressure then follow by ``hertz_3d``'s own
    formulas. Same values as ``hertz_3d`` to a few ulp (tests/test_fmu_vehicle.py: 4e-15
    relative on 10^3 random pairs). One compiled loop over the pairs
    (:func:`railcontact._hertz_kernels.unit_ellipses_kernel`, Carlson's R_D in it; its
    ahead-of-time copy in an FMU): a few microseconds for 1-8 pairs, against about 40 with
    numpy and ``scipy.special.elliprd``.

    Parameters
    ----------
    curvature_longitudinal, curvature_lateral : ndarray
        A', B' > 0 and finite (checked by the caller), 1-D. [1/m]
    youngs_modulus : float
        E. [Pa]
    poisson_ratio : float
        nu in [0, 0.5). [-]

    Returns
    -------
    a1, b1, p1 : ndarray
        Semi-axes [m] and maximum pressure [Pa] at N = 1 N (a0 = a1 N^(1/3), b0 = b1 N^(1/3),
        p0 = p1 N^(1/3)).
    """
    c_x = np.ascontiguousarray(curvature_longitudinal, dtype=float)
    c_y = np.ascontiguousarray(curvature_lateral, dtype=float)
    out = np.empty((c_x.size, 3))
    e_star = youngs_modulus / (2.0 * (1.0 - poisson_ratio**2))
    nodes, coefficients = inverse_grid()
    if _compiled.unit_ellipses_kernel()(c_x, c_y, float(e_star), nodes, coefficients, out):
        # beyond a0/b0 = 1e6 either way: hertz_3d's clipped answer there
        for k in np.flatnonzero(np.isnan(out[:, 0])):
            out[k] = [float(v) for v in hertz.hertz_3d(1.0, c_x[k], c_y[k], youngs_modulus,
                                                       poisson_ratio)]
    return out[:, 0], out[:, 1], out[:, 2]


def check_geometry_input(name, value, unit):
    """``value`` as a float if it is in (0, inf), else a ValueError naming the input."""
    if 0.0 < value < math.inf:
        return float(value)
    check_range(name, value, unit, 0.0, None, lower_closed=False)
    return float(value)     # (not reached)


class NormalContact(Effect):
    r"""Hertz contact ellipse from the normal force (always on).

    ``geometry.kind = "curvatures"``: :func:`railcontact.hertz.hertz_3d` (as :func:`unit_ellipse`,
    the same values to a few ulp without importing scipy) once at build time for N = 1 N, then the exact Hertz scaling a0, b0, p0 proportional to N^(1/3) (Johnson (1985)
    Eqs. (4.17)-(4.19): the eccentricity depends on A'/B' only). ``"semi_axes"``: the ellipse
    is fixed and ``p0 = 3 N / (2 pi a0 b0)`` (Eq. (2.60)). ``"line"``: 2-D Hertz
    (:func:`railcontact.hertz.hertz_2d`, Eqs. (2.40)-(2.42)) for the load per unit length
    ``N / contact_width``, once for 1 N/m and then the exact scaling a0, p0 proportional to
    sqrt(N); ``b0`` is half the contact width. ``contact_half_width`` is a0 (the corrugation
    effect replaces it by the actual half-width).

    Geometry as inputs (the FMU's ``curvature_longitudinal``, ``curvature_lateral``,
    ``semi_axis_longitudinal``, ``semi_axis_lateral``): the contact's fields of those names,
    when not None, override the scene's. A changed pair of curvatures gives a new ellipse at
    1 N by :func:`unit_ellipses` (the same values as ``hertz_3d`` to a few ulp); unchanged
    ones reuse the last (at the scene's own values, :func:`unit_ellipse`'s result, or ``unit``,
    the scene's ellipse at 1 N (a1, b1, p1) when the caller made it: a vehicle, by
    :func:`unit_ellipses` for all its contacts at once). A value that
    is not in (0, inf) is a ValueError naming the input.
    """

    name = "normal"

    def __init__(self, scene, mu_source=None, warn=None, unit=None):
        super().__init__()
        self._warn = warn if warn is not None else (lambda key, msg: None)
        geo = scene.geometry
        self._line = geo["kind"] == "line"
        if self._line:
            a1, p1 = hertz.hertz_2d(1.0, geo["radius"], scene.youngs_modulus,
                                    scene.poisson_ratio)
            self._a1, self._p1 = float(a1), float(p1)
            self._width = geo["contact_width"]
            self._fixed = False
        elif geo["kind"] == "curvatures":
            self._cx, self._cy = geo["curvature_longitudinal"], geo["curvature_lateral"]
            a1, b1, p1 = unit if unit is not None else unit_ellipse(
                self._cx, self._cy, scene.youngs_modulus, scene.poisson_ratio)
            self._a1, self._b1, self._p1 = float(a1), float(b1), float(p1)
            self._fixed = False
        else:
            self._a1 = geo["semi_axis_longitudinal"]
            self._b1 = geo["semi_axis_lateral"]
            self._p1 = 1.5 / (math.pi * self._a1 * self._b1)
            self._fixed = True
        self._e, self._nu = scene.youngs_modulus, scene.poisson_ratio
        # (a line scene holds none of them: the defaults, unused there)
        self._scene_geometry = tuple(
            float(geo.get(name, DEFAULT_SCENE["geometry"][name]))
            for name in ("curvature_longitudinal", "curvature_lateral",
                         "semi_axis_longitudinal", "semi_axis_lateral"))

    def geometry_changed(self, c):
        """True if the contact's geometry inputs differ from those of the current ellipse
        (curvatures, or semi-axes; never for a line contact). Inputs not set yet (None) take
        the scene's values."""
        if c.curvature_longitudinal is None:
            (c.curvature_longitudinal, c.curvature_lateral, c.semi_axis_longitudinal,
             c.semi_axis_lateral) = self._scene_geometry
        if self._line:
            return False
        if self._fixed:
            return (c.semi_axis_longitudinal != self._a1
                    or c.semi_axis_lateral != self._b1)
        return c.curvature_longitudinal != self._cx or c.curvature_lateral != self._cy

    def set_geometry(self, c, unit=None):
        """Take the contact's geometry inputs (checked: a ValueError names a bad one); ``unit``:
        the ellipse at 1 N for them, if the caller computed it (:func:`unit_ellipses`)."""
        if self._fixed:
            a = check_geometry_input("semi_axis_longitudinal", c.semi_axis_longitudinal, "m")
            b = check_geometry_input("semi_axis_lateral", c.semi_axis_lateral, "m")
            self._a1, self._b1 = a, b
            self._p1 = 1.5 / (math.pi * a * b)
            return
        cx = check_geometry_input("curvature_longitudinal", c.curvature_longitudinal, "1/m")
        cy = check_geometry_input("curvature_lateral", c.curvature_lateral, "1/m")
        if unit is None:
            unit = [float(v[0]) for v in unit_ellipses(np.array([cx]), np.array([cy]),
                                                       self._e, self._nu)]
        self._a1, self._b1, self._p1 = unit
        self._cx, self._cy = cx, cy

    def step(self, c):
        self.calls += 1
        n = c.normal_force
        if n <= 0.0 and (c.creepage_longitudinal or c.creepage_lateral or c.spin):
            self._warn("no-normal-force", NO_NORMAL_FORCE_MESSAGE)
        if self.geometry_changed(c):
            self.set_geometry(c)
        if self._line:
            n_line = n / self._width
            if n_line == math.inf:
                raise ValueError(f"normal_force / contact_width (load per unit length) must be "
                                 f"in [0, {_FLOAT_MAX:g}] [N/m]; got inf (normal_force = "
                                 f"{n:g} N, contact_width = {self._width:g} m)")
            scale = math.sqrt(n_line)
            c.a0, c.b0, c.p0 = self._a1 * scale, 0.5 * self._width, self._p1 * scale
            c.contact_half_width = c.a0
            return
        if self._fixed:
            c.a0, c.b0, c.p0 = self._a1, self._b1, self._p1 * n
        else:
            scale = n ** (1.0 / 3.0)
            c.a0, c.b0, c.p0 = self._a1 * scale, self._b1 * scale, self._p1 * scale
        c.contact_half_width = c.a0


