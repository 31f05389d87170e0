"""The compiled Hertz ellipse of changing curvatures (railcontact._hertz_kernels): Carlson's
R_D against scipy's (an independent implementation of the same integral) and the ellipse kernel
against the bisection of :func:`railcontact.hertz.hertz_3d` (tests/test_fmu_vehicle.py checks
:func:`railcontact.effects.normal.unit_ellipses` the same way)."""

import math

import numpy as np
import pytest
from scipy.special import elliprd

from railcontact import _compiled
from railcontact._hertz_kernels import carlson_rd
from railcontact.effects.normal import inverse_grid, unit_ellipses
from railcontact.hertz import hertz_3d

E, NU = 210e9, 0.28


def test_carlson_rd_equals_scipy():
    rng = np.random.default_rng(7)
    x, y, z = (10 ** rng.uniform(-6, 6, (3, 3000)))
    x[:1000] = 0.0                        # (the Hertz kernel's R_D(0, y, z))
    got = np.array([carlson_rd(*p) for p in zip(x, y, z)])
    np.testing.assert_allclose(got, elliprd(x, y, z), rtol=2e-15, atol=0)
    # closed forms: R_D(x, x, x) = x^(-3/2); R_D(0, 1, 1) = 3 pi / 4
    assert carlson_rd(4.0, 4.0, 4.0) == pytest.approx(0.125, rel=1e-15)
    assert carlson_rd(0.0, 1.0, 1.0) == pytest.approx(0.75 * math.pi, rel=1e-15)


def test_unit_ellipses_kernel_counts_pairs_beyond_its_grid():
    """a0/b0 beyond 1e6 either way: the kernel leaves NaN and counts them; unit_ellipses
    then gives hertz_3d's clipped answer there."""
    c_x = np.array([1.0, 1e-14, 1.0])
    c_y = np.array([2.0, 1.0, 1e-14])
    out = np.zeros((3, 3))
    nodes, coefficients = inverse_grid()
    e_star = E / (2.0 * (1.0 - NU**2))
    assert _compiled.unit_ellipses_kernel()(c_x, c_y, e_star, nodes, coefficients, out) == 2
    assert np.isnan(out[1:]).all() and np.isfinite(out[0]).all()
    a1, b1, p1 = unit_ellipses(c_x, c_y, E, NU)
    ref = hertz_3d(1.0, c_x, c_y, E, NU)
    np.testing.assert_allclose(a1, ref.a0, rtol=4e-15)
    np.testing.assert_allclose(b1, ref.b0, rtol=4e-15)
    np.testing.assert_allclose(p1, ref.p0, rtol=1e-14)


def test_the_shipped_inverse_grid_is_the_computed_one():
    """data/hertz_inverse_grid.npz (read at run time: a vehicle FMU imports no scipy) holds
    exactly what make_inverse_grid computes now (else: normal.write_inverse_grid())."""
    from railcontact._files import package_directory
    from railcontact.effects import normal

    nodes, coefficients = normal.make_inverse_grid()
    with np.load(package_directory() / "data" / normal.INVERSE_GRID_DATA) as data:
        np.testing.assert_array_equal(data["nodes"], nodes)
        np.testing.assert_array_equal(data["coefficients"], coefficients)
