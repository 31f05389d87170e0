"""The brute-force wear checks (:mod:`railcontact.reference.wear_direct`): the discretised
half-space solver's frictional work summed at material points against the exact wear integral
and the linearised coefficients of :mod:`railcontact.wear` (Nielsen Sec. 4.3, Eq. (4.74))."""

import pytest

from railcontact import corrugation as cg
from railcontact import wear
from railcontact.reference import wear_direct


# --------------------------------------------------------------------------------------------
# (c) brute force with the discretised half-space solver
# --------------------------------------------------------------------------------------------
def test_reference_solver_confirms_material_point_small():
    ratio, r, eps = 0.15, 0.5, 0.05
    ref = wear_direct.wear_first_harmonic_reference(ratio, r, eps, phase=0.4, n_positions=16,
                                                    n_elements=200)
    ex = wear.wear_first_harmonic_exact(ratio, r, eps, phase=0.4)
    gap = abs(ex["material_point"] - ex["patch_coordinate"])
    assert abs(ref["material_point"] - ex["material_point"]) < 0.15 * gap
    assert abs(ref["patch_coordinate"] - ex["patch_coordinate"]) < 0.15 * gap
    assert abs(ref["half_width"] - cg.normal_response(ratio)[1]) < 0.02


@pytest.mark.slow
@pytest.mark.parametrize("ratio, r", [(0.15, 0.5), (0.08, 0.3), (0.3, 0.7)])
def test_reference_solver_confirms_material_point_slow(ratio, r):
    eps = 0.05
    ref = wear_direct.wear_first_harmonic_reference(ratio, r, eps, phase=0.4, n_positions=32,
                                                    n_elements=400)
    ex = wear.wear_first_harmonic_exact(ratio, r, eps, phase=0.4)
    mp = ex["material_point"]
    # measured (32 positions, 400 elements): 1.19 %, 1.10 %, 3.14 % of |w|
    assert abs(ref["material_point"] - mp) < 0.05 * abs(mp)
    assert abs(ref["patch_coordinate"] - ex["patch_coordinate"]) < 0.05 * abs(mp)
    assert abs(mp - ex["patch_coordinate"]) > 5 * abs(ref["material_point"] - mp)


@pytest.mark.slow
def test_transient_rolling_also_levels():
    """Beyond the quasi-static model: time-stepped non-steady rolling (du/dt of (2.16)) summed
    at material points also gives W1 > 0 where the thesis' model amplifies (study values in
    docs/wear_finding.md; datum 5 a0, 80 elements)."""
    out = wear_direct.wear_first_harmonic_transient(0.1, 0.5, 0.05, phase=0.4, n_elements=80,
                                                    reference_length_over_a0=5.0)
    assert out["mean"] == pytest.approx(wear.wear_shape_function(0.5), rel=0.05)
    assert out["material_point"].real > 0
    assert wear.wear_coefficients(0.1, 0.5, "nielsen1998").real < 0
    assert out["material_point"].real == pytest.approx(
        wear.wear_coefficients(0.1, 0.5).real, rel=0.6)
