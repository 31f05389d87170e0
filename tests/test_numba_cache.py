"""numba's cache of the package lives in a user cache directory (railcontact._numba_cache)."""

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from railcontact import _numba_cache
from railcontact.reference import rolling3d

PACKAGE = Path(rolling3d.__file__).resolve().parent.parent


def test_package_functions_cache_in_the_user_directory(tmp_path, monkeypatch):
    monkeypatch.setenv("RAILCONTACT_CACHE_DIR", str(tmp_path))
    py_func = rolling3d._sweep.py_func
    locator = _numba_cache.RailcontactCacheLocator.from_function(py_func, rolling3d.__file__)
    path = Path(locator.get_cache_path())
    assert path.parent == tmp_path / "numba" and path.name.startswith("railcontact.reference.rolling3d-")
    assert path.is_dir()  # created (and checked writable) by numba's locator protocol
    # not for code outside the package
    assert _numba_cache.RailcontactCacheLocator.from_function(py_func, __file__) is None


def test_user_cache_dir_follows_xdg(monkeypatch, tmp_path):
    monkeypatch.delenv("RAILCONTACT_CACHE_DIR", raising=False)
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    if sys.platform.startswith("linux"):
        assert _numba_cache.user_cache_dir() == tmp_path / "railcontact"


@pytest.mark.slow
def test_fresh_extraction_loads_the_cache(tmp_path):
    # the FMU case: the package is unpacked to a new directory for every process; the second
    # process must load the compiled solver instead of compiling it (measured: 0.75 s from
    # process start to the first exact solve with a warm cache, 6-9 s cold)
    script = ("import railcontact as rc\n"
              "from railcontact.reference import rolling3d as r\n"
              "rc.creep_force_3d(1e-3, 0, 0.5, 1e5, 6e-3, 5e-3, 210e9, 0.28, 0.3, "
              "method='exact')\n"
              "print(sum(r._sweep.stats.cache_hits.values()))\n")
    env = dict(os.environ, RAILCONTACT_CACHE_DIR=str(tmp_path / "cache"),
               OPENBLAS_NUM_THREADS="1")
    env.pop("NUMBA_CACHE_DIR", None)
    hits = []
    for run in range(2):
        root = tmp_path / f"extract{run}"
        shutil.copytree(PACKAGE, root / "railcontact",
                        ignore=shutil.ignore_patterns("__pycache__"))
        out = subprocess.run([sys.executable, "-c", script], cwd=root, env=dict(
            env, PYTHONPATH=str(root)), capture_output=True, text=True, check=True)
        hits.append(int(out.stdout.split()[-1]))
    assert hits[1] >= 1
