"""The table ``corrugation_response`` as the corrugation and wear effects read it: one
harmonic's linearised response coefficients per call, the analytic closed forms outside its grid.
"""

from __future__ import annotations

import operator

import numpy as np

from .. import _compiled, corrugation
from ..wear import wear_coefficients
from .base import EffectUnavailable, load_table

__all__ = ["RESPONSE_VARIABLES", "ResponseTable", "pack_table", "pack_harmonics"]


#: Variables of the table ``corrugation_response`` the corrugation and wear effects read, in the
#: order :class:`ResponseTable` returns them.
RESPONSE_VARIABLES = ("half_width_real", "patch_shift_imag", "stick_half_width_real",
                       "stick_half_width_imag", "tangential_force_real",
                       "tangential_force_imag", "wear_real", "wear_imag")


def pack_table(spline, columns, bounds):
    """The flat buffers ``(fbuf, ibuf)`` of a 2-D table spline for ``superposed_response``.

    ``spline``: a :class:`railcontact.tables.TableSpline` with axes (a0/L, r_a0); ``columns``:
    the indices of its variables half_width_real, patch_shift_imag, tangential_force_real,
    tangential_force_imag, wear_real, wear_imag; ``bounds``: (a0/L lower, upper, r lower,
    upper), the range inside which the kernel evaluates the table.
    """
    coef, shape, knots, knot_start, strides, offset, work = spline.kernel_arrays()
    ibuf = np.concatenate([
        [shape.size, coef.shape[0], coef.shape[1], offset.size, knots.size],
        shape, knot_start, strides, offset, np.zeros(shape.size), columns,
    ]).astype(np.int64)
    fbuf = np.concatenate([coef.ravel(), knots, np.zeros(work.size), np.asarray(bounds, float)])
    return np.ascontiguousarray(fbuf), np.ascontiguousarray(ibuf)


def pack_harmonics(wavelengths, amplitudes_cos, amplitudes_sin, radius, n_var):
    """The harmonics' flat buffer for ``superposed_response``: wave numbers k [1/m], k R
    [-], Z_A, Z_B [m], wavelengths L [m], then the kernel's scratch (the points and the rows
    of the table, ``n (2 + n_var)``)."""
    lam = np.asarray(wavelengths, dtype=float)
    k = 2.0 * np.pi / lam
    n = lam.size
    return np.ascontiguousarray(np.concatenate([
        k, k * radius, np.asarray(amplitudes_cos, float), np.asarray(amplitudes_sin, float),
        lam, np.zeros(n * (2 + n_var))]))


#: The variables the compiled step (:meth:`ResponseTable.superpose`) reads, in its order.
_STEP_VARIABLES = ("half_width_real", "patch_shift_imag", "tangential_force_real",
                   "tangential_force_imag", "wear_real", "wear_imag")


class ResponseTable:
    """The linearised first-harmonic response coefficients of one harmonic, from the table
    ``corrugation_response`` (:func:`railcontact.wear.linear_response`, wear model
    "material_point"), with the analytic closed forms outside its grid.

    ``coefficients(a0/L, r_a0)`` returns the complex ``(c_a, c_Delta, c_a*, c_T, w)`` of
    :func:`railcontact.corrugation.normal_response`, :func:`~railcontact.corrugation.
    stick_zone_response`, :func:`~railcontact.corrugation.tangential_force_response` and
    :func:`railcontact.wear.wear_coefficients` (``w``; None unless ``wear``). The table's axes
    have ``out_of_range = "error"`` (a0/L in [0.01, 1], r_a0 in [0, 1]): outside them the
    reader raises, so this falls back to the analytic functions for that harmonic and calls
    ``warn("corrugation-table-range", message)`` (the FMU logs it once). Never NaN.
    """

    def __init__(self, tables_dir, effect, warn):
        self.table = load_table("corrugation_response", tables_dir, effect)
        names = self.table.variables
        missing = [v for v in RESPONSE_VARIABLES if v not in names]
        if missing:
            raise EffectUnavailable(f"effect {effect} (table) not available in this build: "
                                    f"{self.table.path.name} lacks {missing}")
        self._cols = [names.index(v) for v in RESPONSE_VARIABLES]
        # the eight values as Python floats from the spline's row in one call (per step)
        self._pick = operator.itemgetter(*self._cols)
        (self._lo, self._hi), (self._r_lo, self._r_hi) = [
            (float(a["nodes"][0]), float(a["nodes"][-1])) for a in self.table.axes]
        self._evaluate = self.table.spline.evaluate_unchecked
        self._points = np.empty((0, 2))     # the harmonics' (a0/L, r) of one step (rows)
        self._warn = warn if warn is not None else (lambda key, msg: None)
        # the step kernel's buffers: the table's spline and its range (pack_table)
        self._fbuf, self._ibuf = pack_table(
            self.table.spline, [names.index(v) for v in _STEP_VARIABLES],
            (self._lo, self._hi, self._r_lo, self._r_hi))
        # (loaded now, not in the first step: the ahead-of-time copy, or numba's)
        self._superpose = _compiled.superposed_response(
            self._fbuf, self._ibuf, self.harmonics([1.0], [0.0], [0.0], 1.0))
        acc = self.table.accuracy()
        #: Recorded max error of each variable read (name -> float), from the file.
        self.max_abs_error = {v: acc[v]["max_abs_error"] for v in RESPONSE_VARIABLES}

    def harmonics(self, wavelengths, amplitudes_cos, amplitudes_sin, radius):
        """The harmonics' buffer :meth:`superpose` takes (wavelengths [m], Z_A, Z_B [m], the
        wheel radius R [m]); make it again when the surface changes."""
        return pack_harmonics(wavelengths, amplitudes_cos, amplitudes_sin, radius,
                              len(self.table.variables))

    def superpose(self, harmonics, a0, x, r, out):
        """The harmonics' superposed response at one contact, from the table, in one compiled
        call (:func:`railcontact._response_kernels.superposed_response`): ``out`` (4,) gets
        ``sum hw k R z_r``, ``-sum ps k R z_i``, ``sum (tr z_r - ti z_i)`` and
        ``sum (wr z_r - wi z_i)``; ``a0`` [m], rail position ``x`` [m], ``r = a0*/a0`` [-].
        Returns False (``out`` untouched) where a harmonic's a0/L or r is outside the table's
        grid or NaN: then :meth:`rows` gives the closed forms."""
        return self._superpose(self._fbuf, self._ibuf, harmonics, a0, x, r, out)

    def coefficients_list(self, ratios, r, wear=True):
        """:meth:`coefficients` of every harmonic ``a0/L`` in ``ratios`` at one ``r``: one
        spline evaluation for all of them when all are inside the grid (see :meth:`rows`)."""
        return [self._complex(row, wear) for row in self.rows(ratios, r, wear)]

    def rows(self, ratios, r, wear=True):
        """The eight real coefficients of :data:`RESPONSE_VARIABLES` (floats) of every
        harmonic ``a0/L`` in ``ratios`` at one ``r``: one spline evaluation for all when all are
        inside the grid (the FMU's step, no complex objects); outside it, the closed forms of
        :meth:`coefficients` in the same order (c_a is real and c_Delta imaginary there too;
        the wear pair is 0 unless ``wear``)."""
        if (self._r_lo <= r <= self._r_hi
                and all(self._lo <= ratio <= self._hi for ratio in ratios)):
            pts = self._points
            if pts.shape[0] != len(ratios):
                pts = self._points = np.empty((len(ratios), 2))
            for i, ratio in enumerate(ratios):
                pts[i, 0] = ratio
                pts[i, 1] = r
            pick = self._pick
            return [pick(row) for row in self._evaluate(pts).tolist()]
        out = []
        for ratio in ratios:
            ca, cd, cs, ct, cw = self.coefficients(ratio, r, wear)
            cw = cw if wear else 0j
            out.append((ca.real, cd.imag, cs.real, cs.imag, ct.real, ct.imag, cw.real,
                        cw.imag))
        return out

    def coefficients(self, ratio, r, wear=True):
        if self._lo <= ratio <= self._hi and self._r_lo <= r <= self._r_hi:
            return self._complex(self._pick(self._evaluate(np.array([(ratio, r)]))[0].tolist()),
                                 wear)
        self._warn("corrugation-table-range",
                   f"corrugation table {self.table.path.name}: a0/L = {ratio:.4g} outside the "
                   f"table's grid [{self._lo:g}, {self._hi:g}] (the reader raises there); the "
                   "analytic closed forms of the linear theory are used for such harmonics")
        cd, ca = corrugation.normal_response(ratio)
        w = complex(wear_coefficients(ratio, r, "material_point")) if wear else None
        return (complex(ca), complex(cd), complex(corrugation.stick_zone_response(ratio, r)),
                complex(corrugation.tangential_force_response(ratio, r)), w)

    @staticmethod
    def _complex(row, wear):
        """The eight real coefficients (see :meth:`rows`) as ``(c_a, c_Delta, c_a*, c_T, w)``."""
        hw, ps, sr, si, tr, ti, wr, wi = row
        return (complex(hw, 0.0), complex(0.0, ps), complex(sr, si), complex(tr, ti),
                complex(wr, wi) if wear else None)
