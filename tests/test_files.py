"""The user cache directory (railcontact._files) under faults: one that cannot be written, and
processes that fill an empty one at the same moment."""

import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from railcontact import _files

ROOT = Path(__file__).resolve().parents[1]

# A table of more than _table_store.MAPPED_MIN_BYTES (kept decompressed in the cache) whose load
# checks its spline with numba's tensor_eval kernel (compiled into the cache): both caches.
USE_BOTH_CACHES = """
import sys, warnings
warnings.simplefilter("always")
import numpy as np
from railcontact import tables, _spline_kernels
path = tables.default_table_path("corrugation_exact")
table = tables.Table.from_file(path)
again = tables.Table.from_file(path)
point = [[np.mean(a["nodes"][[0, -1]]) for a in table.axes]]
value = table.spline.evaluate(np.array(point), check=False)
stats = _spline_kernels.tensor_eval.stats
mapped = isinstance(np.asarray(table.coefficients).base, np.memmap) or isinstance(
    getattr(table.coefficients, "base", None), np.memmap)
print(repr(float(value.ravel()[0])), mapped,
      sum(stats.cache_hits.values()), sum(stats.cache_misses.values()))
"""


def _env(cache):
    env = {k: v for k, v in os.environ.items() if k != "NUMBA_CACHE_DIR"}
    env.update(RAILCONTACT_CACHE_DIR=str(cache), OPENBLAS_NUM_THREADS="1",
               PYTHONPATH=os.pathsep.join([str(ROOT / "fmu_src"), str(ROOT)]))
    return env


def _expected():
    from railcontact import tables

    table = tables.Table.from_file(tables.default_table_path("corrugation_exact"))
    point = [[np.mean(a["nodes"][[0, -1]]) for a in table.axes]]
    return float(table.spline.evaluate(np.array(point), check=False).ravel()[0])


def test_writable_cache_dir_is_the_user_cache_when_it_can_be_written(tmp_path, monkeypatch):
    monkeypatch.setenv("RAILCONTACT_CACHE_DIR", str(tmp_path / "new" / "cache"))
    assert _files.writable_cache_dir() == tmp_path / "new" / "cache"
    assert (tmp_path / "new" / "cache").is_dir() and not list((tmp_path / "new" / "cache").iterdir())
    assert _files.numba_cache_root() == tmp_path / "new" / "cache" / "numba"


def test_an_unwritable_cache_gives_one_warning_and_a_temporary_numba_cache(tmp_path,
                                                                             monkeypatch):
    blocker = tmp_path / "a-file"
    blocker.write_text("")
    monkeypatch.setenv("RAILCONTACT_CACHE_DIR", str(blocker / "cache"))  # (even root fails)
    with pytest.warns(RuntimeWarning, match=r"cannot be written.*RAILCONTACT_CACHE_DIR"):
        assert _files.writable_cache_dir() is None
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error")          # the second time: silent
        assert _files.writable_cache_dir() is None
        temporary = _files.numba_cache_root()
    assert temporary.is_dir() and temporary == _files.numba_cache_root()


def test_an_unwritable_cache_in_a_process_warns_once_and_answers(tmp_path):
    """A whole process whose cache directory cannot be written: numba's kernels compile into a
    temporary directory, the table is read without its cache, both loads answer, and the user
    sees one warning."""
    blocker = tmp_path / "a-file"
    blocker.write_text("")
    run = subprocess.run([sys.executable, "-c", USE_BOTH_CACHES], env=_env(blocker / "cache"),
                         capture_output=True, text=True, timeout=600)
    assert run.returncode == 0, run.stderr[-2000:]
    assert run.stderr.count("cannot be written") == 1, run.stderr
    assert run.stderr.count("Warning") == 1, run.stderr
    value, from_cache, _, _ = run.stdout.split()
    assert float(value) == pytest.approx(_expected(), rel=1e-12)
    assert from_cache == "False"


def test_four_processes_on_an_empty_cache_at_once(tmp_path):
    """Four processes released at the same moment on an empty cache all answer correctly;
    the cache they leave is intact: a fifth process loads the table and the kernel from it
    (no compilation, no netCDF read) and gets the same value."""
    cache = tmp_path / "cache"
    go = tmp_path / "go"
    wait = (f"import os, time\nwhile not os.path.exists({str(go)!r}): time.sleep(0.005)\n")
    procs = [subprocess.Popen([sys.executable, "-c", wait + USE_BOTH_CACHES], env=_env(cache),
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
             for _ in range(4)]
    time.sleep(1.0)          # (all four started and waiting)
    go.write_text("")
    outs = [p.communicate(timeout=900) for p in procs]
    want = _expected()
    for p, (out, err) in zip(procs, outs):
        assert p.returncode == 0, err[-2000:]
        assert "Warning" not in err, err
        assert float(out.split()[0]) == pytest.approx(want, rel=1e-12)
    assert not list(cache.rglob("*.part")) and not list(cache.rglob("*.tmp"))
    fifth = subprocess.run([sys.executable, "-c", USE_BOTH_CACHES], env=_env(cache),
                           capture_output=True, text=True, timeout=600, check=True)
    value, from_cache, hits, misses = fifth.stdout.split()
    assert float(value) == pytest.approx(want, rel=1e-12)
    assert from_cache == "True"
    assert int(hits) >= 1 and int(misses) == 0
