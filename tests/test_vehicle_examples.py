"""The vehicle recipes (``examples/vehicle_fmpy.py``, ``examples/vehicle_libcosim.py``) run as
written on the 8-contact FMU, keep |T| <= mu N at every contact, and agree with each other (the
same inputs at the same communication points, sample and hold in both importers)."""

import re

import pytest

from test_examples import _run_example
from test_fmu_vehicle import _vehicle_fmu

pytestmark = pytest.mark.isolated


@pytest.fixture(scope="module")
def vehicle8():
    return _vehicle_fmu(8)


def _finals(out):
    return {int(k): tuple(float(v) for v in vals) for k, *vals in re.findall(
        r"contact (\d): final Fx = (\S+) N, Fy = (\S+) N, Mz = (\S+) N\.m", out)}


def test_vehicle_recipes_run_and_agree(vehicle8, tmp_path):
    out_fmpy = _run_example("vehicle_fmpy.py", vehicle8, cwd=tmp_path)
    assert "501 rows x 8 contacts" in out_fmpy, out_fmpy
    assert "|T| <= mu N at every contact and step: True" in out_fmpy
    assert "contact 3 lifted for 40 steps, its forces there: 0 N" in out_fmpy
    pytest.importorskip("libcosimpy")
    out_cosim = _run_example("vehicle_libcosim.py", vehicle8, cwd=tmp_path)
    assert "500 steps x 8 contacts" in out_cosim, out_cosim
    assert "|T| <= mu N at every contact and step: True" in out_cosim
    a, b = _finals(out_fmpy), _finals(out_cosim)
    assert sorted(a) == list(range(1, 9)) and sorted(b) == list(range(1, 9))
    for k in a:
        assert a[k] == pytest.approx(b[k], rel=1e-6, abs=1e-3), k   # (printed to 7 digits)
    # the contacts differ: each has its own load, creepages, curvatures and friction
    assert len({round(v[0]) for v in a.values()}) == 8
