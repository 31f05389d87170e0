"""railcontact.strip_table: the modified strip theory's creep table."""

import numpy as np
import pytest

from railcontact.strip_table import CreepTable


def test_the_scalar_paths_piecewise_polynomial_is_scipys_conversion_of_the_spline():
    """The per-span cubic coefficients (from the table's own evaluator, without importing
    scipy.interpolate) are those of scipy's PPoly.from_spline of the same B-spline, to
    round-off, for F and the stick area fraction."""
    from scipy.interpolate import BSpline, PPoly

    table = CreepTable.from_file()
    knots = np.asarray(table.table.axes[0]["knots"], dtype=float)
    for i, mine in ((table._i_f, table._pp_coefs), (table._i_s, table._pp_coefs_stick)):
        pp = PPoly.from_spline(BSpline(knots, np.asarray(table._spline._coef[i], float), 3,
                                       extrapolate=False))
        keep = np.diff(pp.x) > 0.0
        np.testing.assert_array_equal(table._pp_breaks, pp.x[:-1][keep])
        want = pp.c[:, keep].T
        # each term's contribution across its span (c_m h^m; the values are of order 1): the
        # spans near the saturation are 1e-5 wide, where both conversions lose digits of c3
        h = np.diff(pp.x)[keep][:, None] ** np.array([3, 2, 1, 0])
        np.testing.assert_allclose(np.array(mine) * h, want * h, rtol=0, atol=2e-15)


@pytest.mark.parametrize("z", [0.0, 1e-6, 0.3, 0.999999, 1.0, 1.2, 1.5])
def test_the_scalar_path_agrees_with_the_array_path(z):
    table = CreepTable.from_file()
    i = max(table._bisect(table._pp_breaks, z) - 1, 0)
    c3, c2, c1, c0 = table._pp_coefs[i]
    d = z - table._pp_breaks[i]
    scalar = c0 + d * (c1 + d * (c2 + d * c3))
    assert scalar == pytest.approx(float(table._f(np.array(z))[table._i_f]), rel=0, abs=1e-14)
