"""The normal contact (Hertz), always on: the contact ellipse or strip from the normal force."""

from __future__ import annotations

import math

from .. import hertz
from .base import Effect

__all__ = ["NormalContact", "NO_NORMAL_FORCE_MESSAGE"]

_FLOAT_MAX = 1.7976931348623157e308


#: Logged (once per FMU instance, category Warning) at the first evaluation with creepage but
#: without a normal force (e.g. the input normal_force left at its start value 0).
NO_NORMAL_FORCE_MESSAGE = (
    "normal_force = 0 N with non-zero creepage: no contact, so every force output is 0 (the "
    "input's start value is 0 N; set or connect normal_force)")


class NormalContact(Effect):
    r"""Hertz contact ellipse from the normal force (always on).

    ``geometry.kind = "curvatures"``: :func:`railcontact.hertz.hertz_3d` once at build time for
    N = 1 N, then the exact Hertz scaling a0, b0, p0 proportional to N^(1/3) (Johnson (1985)
    Eqs. (4.17)-(4.19): the eccentricity depends on A'/B' only). ``"semi_axes"``: the ellipse
    is fixed and ``p0 = 3 N / (2 pi a0 b0)`` (Eq. (2.60)). ``"line"``: 2-D Hertz
    (:func:`railcontact.hertz.hertz_2d`, Eqs. (2.40)-(2.42)) for the load per unit length
    ``N / contact_width``, once for 1 N/m and then the exact scaling a0, p0 proportional to
    sqrt(N); ``b0`` is half the contact width. ``contact_half_width`` is a0 (the corrugation
    effect replaces it by the actual half-width).
    """

    name = "normal"

    def __init__(self, scene, mu_source=None, warn=None):
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
            a1, b1, p1 = hertz.hertz_3d(1.0, geo["curvature_longitudinal"],
                                        geo["curvature_lateral"], scene.youngs_modulus,
                                        scene.poisson_ratio)
            self._a1, self._b1, self._p1 = float(a1), float(b1), float(p1)
            self._fixed = False
        else:
            self._a1 = geo["semi_axis_longitudinal"]
            self._b1 = geo["semi_axis_lateral"]
            self._p1 = 1.5 / (math.pi * self._a1 * self._b1)
            self._fixed = True

    def step(self, c):
        self.calls += 1
        n = c.normal_force
        if n <= 0.0 and (c.creepage_longitudinal or c.creepage_lateral or c.spin):
            self._warn("no-normal-force", NO_NORMAL_FORCE_MESSAGE)
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


