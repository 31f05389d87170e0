"""Shared test configuration: single-threaded BLAS, hypothesis profiles, a session-built FMU.

Threads first, before anything imports numpy: the discretised reference solvers make many
small dense solves, which threaded OpenBLAS slows down 10-50x on a loaded 2-core machine.

Hypothesis profiles (select with the environment variable ``HYPOTHESIS_PROFILE``):

``ci`` (default)
    Few examples, derandomized (the same examples on every run, no example database), no
    deadline. Keeps the property tests of ``tests/test_properties.py`` well under a minute.
``thorough``
    10^3 examples, random: a few minutes, for checking a change locally.
``long``
    10^5 examples per property test (the expensive ones -- iterative solvers, FMU steps --
    take a fixed fraction of it, see ``tests/test_properties.py``), random and not
    derandomized, for a fuzzing run::

        HYPOTHESIS_PROFILE=long python -m pytest tests/test_properties.py -p no:cacheprovider

    (hours on a loaded 2-core machine: 10-50 ms per example). ``HYPOTHESIS_MAX_EXAMPLES=N``
    overrides the profile's number of examples.
"""

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("MKL_NUM_THREADS", "1")

import subprocess  # noqa: E402
import sys  # noqa: E402
from pathlib import Path  # noqa: E402

import pytest  # noqa: E402
from hypothesis import HealthCheck, settings  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]

settings.register_profile(
    "ci", max_examples=40, derandomize=True, deadline=None, database=None, print_blob=True,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
settings.register_profile(
    "thorough", max_examples=1000, derandomize=False, deadline=None, database=None,
    print_blob=True, suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
settings.register_profile(
    "long", max_examples=100_000, derandomize=False, deadline=None, database=None,
    print_blob=True, suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))
if os.environ.get("HYPOTHESIS_MAX_EXAMPLES"):   # e.g. a shorter "long" run: 10^4 examples
    settings.register_profile("_override", settings.default,
                              max_examples=int(float(os.environ["HYPOTHESIS_MAX_EXAMPLES"])))
    settings.load_profile("_override")


@pytest.fixture(scope="session")
def built_fmu(tmp_path_factory):
    """WheelRailContact.fmu built once per session (``build_fmu.py --dest``) into a temporary
    directory. The same build as ``tests/test_fmu.py``'s ``fmu_path`` fixture; new tests
    should use this one."""
    dest = tmp_path_factory.mktemp("fmu_built")
    subprocess.run([sys.executable, str(ROOT / "build_fmu.py"), "--dest", str(dest)],
                   check=True, capture_output=True, text=True)
    path = dest / "WheelRailContact.fmu"
    assert path.is_file()
    return path
