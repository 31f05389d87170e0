"""The built distribution: the wheel and the sdist carry the shipped tables, the wheel the
table kernels compiled ahead of time (setup.py), and a wheel installed (not editable) in a
fresh environment answers from another directory with an empty user cache, without numba.

The wheels are built with ``pip wheel --no-deps`` (pip's build isolation: the build
requirements of pyproject.toml from the package index), as a user's ``pip install .`` builds
them: a pure one (``RAILCONTACT_NO_AOT=1``, seconds) for the package data, the full one
(compiling the kernels, about 1-3 min) in the slow tests.
"""

import os
import subprocess
import sys
import sysconfig
import tarfile
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
SHIPPED_TABLES = sorted(p.name for p in (ROOT / "tables").glob("*.nc"))


def _pip(*args, cwd=None, env=None):
    return subprocess.run([sys.executable, "-m", "pip", *args], cwd=cwd, check=True,
                          capture_output=True, text=True, env=env)


def _build_wheel(out, aot):
    env = dict(os.environ, RAILCONTACT_NO_AOT="0" if aot else "1")
    _pip("wheel", "--no-deps", "-q", "-w", str(out), str(ROOT), env=env)
    (path,) = out.glob("railcontact-*.whl")
    return path


@pytest.fixture(scope="module")
def wheel(tmp_path_factory):
    """The pure wheel of the checkout (without the compiled kernels)."""
    return _build_wheel(tmp_path_factory.mktemp("wheel"), aot=False)


@pytest.fixture(scope="module")
def aot_wheel(tmp_path_factory):
    """The wheel as a user's build makes it: with the compiled kernels."""
    return _build_wheel(tmp_path_factory.mktemp("aot-wheel"), aot=True)


def test_the_checkout_ships_tables():
    assert "creep_exact.nc" in SHIPPED_TABLES and "creep_modified_strip.nc" in SHIPPED_TABLES


def test_the_wheel_holds_every_shipped_table_as_package_data(wheel):
    with zipfile.ZipFile(wheel) as zf:
        sizes = {Path(i.filename).name: i.file_size for i in zf.infolist()
                 if i.filename.startswith("railcontact/tables/")}
        names = zf.namelist()
    assert sorted(sizes) == SHIPPED_TABLES
    for name in SHIPPED_TABLES:     # whole files, not pointers or stubs
        assert sizes[name] == (ROOT / "tables" / name).stat().st_size, name
    assert "railcontact/tables.py" in names          # the reader beside its data
    assert "railcontact/data/kalker_spline.npz" in names   # Kalker's spline, fitted
    assert "railcontact/data/falling_correction.nc" in names   # the falling fast path's table
    assert "railcontact/data/falling_correction_polach.nc" in names     # and Polach's
    for package in ("effects", "roughness", "reference", "data"):
        assert any(n.startswith(f"railcontact/{package}/") for n in names), package


def test_the_sdist_holds_every_shipped_table(tmp_path):
    """The sdist (PyPA's ``build``, in its isolated environment) carries the tables too, so
    a wheel built from it does."""
    subprocess.run([sys.executable, "-m", "build", "--sdist", "-o", str(tmp_path), str(ROOT)],
                   check=True, capture_output=True, text=True)
    (sdist,) = tmp_path.glob("railcontact-*.tar.gz")
    with tarfile.open(sdist) as tf:
        sizes = {Path(m.name).name: m.size for m in tf.getmembers()
                 if "/tables/" in m.name and m.name.endswith(".nc")}
    assert sorted(sizes) == SHIPPED_TABLES
    assert all(sizes[n] == (ROOT / "tables" / n).stat().st_size for n in SHIPPED_TABLES)


SMOKE = """
import sys
import numpy as np, railcontact as rc, railcontact.tables as t
assert 'site-packages' in rc.__file__, rc.__file__
kw = dict(normal_load=100e3, a0=6e-3, b0=4e-3, youngs_modulus=210e9, poisson_ratio=0.28,
          friction_coefficient=0.3)
tx, ty = rc.creep_force_3d(1e-3, 0.0, 0.0, method="exact_table", **kw)
x = np.linspace(-2e-3, 2e-3, 11)
tx_a, _ = rc.creep_force_3d(x, 0.0, 0.0, method="exact_table", **kw)
tx_b, _ = rc.creep_force_3d(np.linspace(-2e-3, 2e-3, 10_001), 0.0, 0.0, method="exact_table",
                            **kw)
tx_s, _ = rc.creep_force_3d(x, 0.0, 0.0, method="modified_strip", **kw)
print(repr(float(tx)), repr(float(tx_a[8])), repr(float(tx_b[8000])), repr(float(tx_s[8])),
      t.default_table_path("creep_exact"), "numba" in sys.modules)
"""


def test_the_wheel_compiles_the_kernels_unless_told_not_to(wheel):
    assert wheel.name.endswith("-py3-none-any.whl"), wheel.name      # RAILCONTACT_NO_AOT=1
    with zipfile.ZipFile(wheel) as zf:
        assert not [n for n in zf.namelist() if "_aot_kernels" in n]


@pytest.mark.slow
def test_the_wheel_carries_the_compiled_kernels(aot_wheel):
    tag = sysconfig.get_config_var("SOABI")
    assert "-none-any" not in aot_wheel.name, aot_wheel.name    # a platform wheel
    with zipfile.ZipFile(aot_wheel) as zf:
        assert f"railcontact/_aot_kernels.{tag}{sysconfig.get_config_var('SHLIB_SUFFIX')}" \
            in zf.namelist()


@pytest.mark.slow
def test_the_wheel_installed_in_a_fresh_venv_answers_from_elsewhere(aot_wheel, tmp_path):
    """Installed (not editable) into a new virtual environment whose only railcontact is the
    wheel's (its dependencies: this environment's site-packages, appended through a .pth
    file), run from an empty directory with an empty user cache: the exact table's scalar and
    array calls and the modified strip theory agree with this checkout's (numba's kernels),
    the table comes from the installed package, and numba is never imported (the wheel's
    kernels were compiled when it was built). A first ``method="exact"`` call runs the
    wheel's compiled sweep of the reference solver and agrees with the checkout's."""
    wheel = aot_wheel
    venv = tmp_path / "venv"
    subprocess.run([sys.executable, "-m", "venv", "--without-pip", str(venv)], check=True)
    python = venv / "bin" / "python"
    site = Path(subprocess.run([str(python), "-c", "import sysconfig; print(sysconfig."
                                "get_paths()['purelib'])"], check=True, capture_output=True,
                               text=True).stdout.strip())
    _pip("install", "--no-deps", "-q", "--target", str(site), str(wheel))
    (site / "zz_dependencies.pth").write_text(sysconfig.get_paths()["purelib"] + "\n")
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "RAILCONTACT_TABLES_DIR")}
    env["RAILCONTACT_CACHE_DIR"] = str(tmp_path / "empty-cache")
    out = subprocess.run([str(python), "-c", SMOKE], cwd=elsewhere, env=env, check=True,
                         capture_output=True, text=True, timeout=900).stdout.split()
    import numpy as np

    import railcontact as rc

    kw = dict(normal_load=100e3, a0=6e-3, b0=4e-3, youngs_modulus=210e9, poisson_ratio=0.28,
              friction_coefficient=0.3)
    x = np.linspace(-2e-3, 2e-3, 11)
    assert float(out[0]) == pytest.approx(
        float(rc.creep_force_3d(1e-3, 0.0, 0.0, method="exact_table", **kw)[0]), rel=1e-12)
    assert float(out[1]) == pytest.approx(
        float(rc.creep_force_3d(x, 0.0, 0.0, method="exact_table", **kw)[0][8]), rel=1e-12)
    assert float(out[2]) == pytest.approx(float(rc.creep_force_3d(
        np.linspace(-2e-3, 2e-3, 10_001), 0.0, 0.0, method="exact_table", **kw)[0][8000]),
        rel=1e-12)
    assert float(out[3]) == pytest.approx(
        float(rc.creep_force_3d(x, 0.0, 0.0, method="modified_strip", **kw)[0][8]), rel=1e-12)
    assert Path(out[4]).is_relative_to(site / "railcontact" / "tables"), out[4]
    assert out[5] == "False"        # no numba: the compiled kernels answered
    # the reference solver (method="exact") runs the wheel's compiled sweep, nothing compiled
    out = subprocess.run([str(python), "-c", EXACT], cwd=elsewhere, env=env, check=True,
                         capture_output=True, text=True, timeout=900).stdout.split()
    want = rc.creep_solution_3d(3e-4, 5e-4, 0.5, method="exact", **kw)
    assert float(out[0]) == pytest.approx(float(want.tx), rel=1e-12)
    assert float(out[1]) == pytest.approx(float(want.ty), rel=1e-12)
    assert out[2] == "True"


EXACT = """
import railcontact as rc
from railcontact import _compiled
used = []
aot_kernel = _compiled.aot_kernel
def spy(name, args):
    kernel = aot_kernel(name, args)
    used.append(kernel is not None)
    return kernel
_compiled.aot_kernel = spy
kw = dict(normal_load=100e3, a0=6e-3, b0=4e-3, youngs_modulus=210e9, poisson_ratio=0.28,
          friction_coefficient=0.3)
s = rc.creep_solution_3d(3e-4, 5e-4, 0.5, method="exact", **kw)
print(repr(float(s.tx)), repr(float(s.ty)), bool(used) and all(used))
"""
