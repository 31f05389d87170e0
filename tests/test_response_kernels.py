"""The compiled step of the corrugation response table (railcontact._response_kernels),
against the superposition written in complex arithmetic from the table's per-harmonic
coefficients (ResponseTable.coefficients, the documented form ``Re(c Z e^{-ikx})`` of
Nielsen's Eqs. (4.36)-(4.71), (4.94)-(4.95))."""

from __future__ import annotations

import cmath
import math

import numpy as np
import pytest

from railcontact.effects.response_table import ResponseTable


@pytest.fixture(scope="module")
def table():
    return ResponseTable(None, "corrugation", None)


def _complex_sums(table, lam, za, zb, radius, a0, x, r):
    sums = np.zeros(4)
    for lm, a, b in zip(lam, za, zb):
        k = 2 * math.pi / lm
        c_a, c_d, _, c_t, w = table.coefficients(a0 / lm, r)
        z = complex(a, b) * cmath.exp(-1j * k * x)
        sums += [(k * radius * c_a * z).real, (k * radius * c_d * z).real, (c_t * z).real,
                 (w * z).real]
    return sums


def test_superposed_response_is_the_complex_superposition(table):
    rng = np.random.default_rng(3)
    for n in (1, 2, 5):
        for _ in range(40):
            lam = list(rng.uniform(0.02, 0.3, n))    # a0/L in the grid [0.01, 1]
            za, zb = list(rng.normal(0, 2e-6, n)), list(rng.normal(0, 2e-6, n))
            a0, x, r = rng.uniform(3e-3, 8e-3), rng.uniform(-5, 5), rng.uniform(0, 1)
            got = np.zeros(4)
            assert table.superpose(table.harmonics(lam, za, zb, 0.46), a0, x, r, got)
            want = _complex_sums(table, lam, za, zb, 0.46, a0, x, r)
            np.testing.assert_allclose(got, want, rtol=1e-12, atol=1e-14 * np.abs(want).max())


@pytest.mark.parametrize("a0, r", [(6e-3, math.nan), (math.nan, 0.5), (6e-3, -1e-9),
                                   (6e-3, 1.0 + 1e-9), (1e-5, 0.5), (1.0, 0.5)])
def test_superposed_response_declines_outside_the_grid_or_nan(table, a0, r):
    # a0/L outside [0.01, 1] for L = 0.05 m (a0 = 1e-5 m or 1 m), r outside [0, 1], NaN:
    # False and the sums untouched (the effect then uses the closed forms)
    out = np.full(4, 7.0)
    assert not table.superpose(table.harmonics([0.05], [1e-6], [0.0], 0.46), a0, 0.1, r, out)
    assert np.all(out == 7.0)
