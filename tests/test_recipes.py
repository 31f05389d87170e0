"""The README's recipes (``examples/recipes/*.py``) run as a user runs them, and say the truth.

Each recipe runs in its own process (as from a shell). The FMU recipes get the session's FMU
(``conftest.built_fmu``) and must agree with each other and with the Python API at the same
inputs: the last step of both holds the creepage 3.96e-3 (sample and hold).
"""

import re
import subprocess
import sys
from pathlib import Path

import pytest

import railcontact as rc
from railcontact.scene import load_scene

ROOT = Path(__file__).resolve().parents[1]
RECIPES = ROOT / "examples" / "recipes"


def _run(name, *args):
    proc = subprocess.run([sys.executable, str(RECIPES / name), *map(str, args)],
                          capture_output=True, text=True, cwd=ROOT, timeout=600)
    assert proc.returncode == 0, proc.stderr[-3000:]
    return proc.stdout


def _fx(text):
    return float(re.search(r"Fx at the end: (-?[\d.]+) N", text).group(1))


def _direct_fx(xi):
    scene = load_scene(ROOT / "examples" / "scenes" / "creep_only_analytic.toml")
    geo = scene.geometry
    a0, b0, _ = rc.hertz_3d(100e3, geo["curvature_longitudinal"], geo["curvature_lateral"],
                            scene.youngs_modulus, scene.poisson_ratio)
    tx, _ = rc.creep_force_3d(xi, 0.0, 0.0, 100e3, a0, b0, scene.youngs_modulus,
                              scene.poisson_ratio, scene.friction_coefficient,
                              method=scene.effects["creep"]["method"])
    return float(tx)


def test_python_api_recipe():
    out = _run("python_api.py")
    assert "a0 = 7.503 mm, b0 = 4.594 mm" in out
    linear = re.search(r"linear: Tx/\(mu N\) = \[(.*)\]", out).group(1).split()
    a0, b0, _ = rc.hertz_3d(100e3, 1.1, 2.3, 210e9, 0.28)
    c11 = rc.kalker_coefficients(a0 / b0, 0.28).c11
    g = 210e9 / (2 * 1.28)
    assert float(linear[0]) == pytest.approx(-g * a0 * b0 * c11 * 1e-4 / (0.3 * 100e3),
                                             abs=1e-4)


def test_fmpy_and_libcosim_recipes_agree_with_the_api(built_fmu):
    fx_fmpy = _fx(_run("fmu_fmpy.py", built_fmu))
    fx_cosim = _fx(_run("fmu_libcosim.py", built_fmu))
    want = _direct_fx(3.96e-3)
    assert fx_fmpy == pytest.approx(want, abs=0.05)       # printed to 0.1 N
    assert fx_cosim == pytest.approx(want, abs=0.05)
    assert -0.3 * 100e3 < want < 0.0


def test_readme_api_snippet_runs():
    """The README's Python API block runs as printed and gives the recipe's Hertz contact."""
    text = (ROOT / "README.md").read_text()
    block = re.search(r"```python\n(import railcontact as rc\n.*?)```", text, re.S).group(1)
    scope = {}
    exec(compile(block, "README.md", "exec"), scope)      # noqa: S102 -- our own README
    assert 1e3 * scope["a0"] == pytest.approx(7.503, abs=5e-4)
    assert -0.3 * 100e3 < scope["tx"] < 0.0 and scope["ty"] == 0.0
