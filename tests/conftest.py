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

import gc  # noqa: E402
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


def _cached_fmu(contacts=1):
    """Path of the FMU for the current sources, built once per source state and environment
    (:func:`railcontact.fmu_build.cached_build`), so that the forked test processes (below)
    do not rebuild it."""
    import build_fmu  # noqa: PLC0415

    return build_fmu.cached_build(contacts)


@pytest.fixture(scope="session")
def built_fmu():
    """WheelRailContact.fmu for the current sources (``build_fmu.py``), built once."""
    return _cached_fmu()


FMU_FIXTURES = {"built_fmu", "fmu_path"}


def pytest_collection_modifyitems(config, items):
    """Mark every test that loads the FMU into this process to run in a forked child process.

    PythonFMU's native library, loaded into a Python host (fmpy) and freed again, corrupts the
    host interpreter (upstream NTNU-IHB/PythonFMU#228, #229: invalid reads in
    ``finalizePythonInterpreter``, "free(): corrupted unsorted chunks"). Here that showed as
    segmentation faults later in the test run or at interpreter exit, never inside the FMU
    tests themselves. A forked child confines it: the child exits with ``os._exit`` and the
    pytest process never loads the library. Inside the child the cyclic garbage collector is
    off: a test that makes and frees many instances (the whole-float-range property, 40) left
    cycles of a freed instance's Python objects behind, and a collection that walked them
    during the next instantiation crashed the child (signal 11 in ``fmi2Instantiate``,
    "Garbage-collecting", once in the CI rehearsals of 2026-11-27; not keeping the library
    unloaded had already made it rarer, ``tests/test_properties._free_instance``). Users' own
    co-simulations load the FMU once and exit; the 1e6-step run
    (benchmarks/bench_long_run.py) checks that case.
    """
    for item in items:
        if FMU_FIXTURES & set(getattr(item, "fixturenames", ())):
            item.add_marker(pytest.mark.isolated)


def pytest_configure(config):
    config.addinivalue_line(
        "markers", "isolated: run the test in a forked child process (tests/conftest.py)")


# Why our own fork and not pytest-forked: pytest-forked (barely maintained) marshals its reports
# with the ``marshal`` module, and pytest 9.2's reports hold objects marshal refuses
# ("ValueError: unmarshallable object"), so every forked test failed with "EXITED with status
# 3". pytest-xdist runs many tests in one worker, which does not confine the corruption to one
# test, and a subprocess per test would re-import numpy/scipy/numba (1-2 s each). The fork
# below is what pytest-forked does, serialised with pytest's own public report hooks
# (``pytest_report_to_serializable`` / ``pytest_report_from_serializable``, the ones
# pytest-xdist relies on) and pickled (plain dicts, lists and tuples between two copies of the
# same interpreter), so it does not depend on the reports' internals.

@pytest.hookimpl(tryfirst=True)
def pytest_runtest_protocol(item, nextitem):
    """Run an ``isolated`` test in a forked child; report its phases in this process."""
    if item.get_closest_marker("isolated") is None or not hasattr(os, "fork"):
        return None
    import pickle  # noqa: PLC0415

    from _pytest.reports import TestReport  # noqa: PLC0415
    from _pytest.runner import runtestprotocol  # noqa: PLC0415

    hook, ihook = item.config.hook, item.ihook
    ihook.pytest_runtest_logstart(nodeid=item.nodeid, location=item.location)
    read_end, write_end = os.pipe()
    sys.stdout.flush()
    sys.stderr.flush()
    pid = os.fork()
    if pid == 0:  # the child: run setup, call and teardown, send the reports, exit at once
        os.close(read_end)
        gc.disable()    # (see pytest_collection_modifyitems; the child's memory goes at exit)
        code = 0
        try:
            reports = runtestprotocol(item, log=False, nextitem=None)
            payload = [hook.pytest_report_to_serializable(config=item.config, report=rep)
                       for rep in reports]
            data = pickle.dumps(payload)
        except BaseException as exc:  # noqa: BLE001 -- reported by the parent
            data = pickle.dumps({"error": f"{type(exc).__name__}: {exc}"})
            code = 1
        with os.fdopen(write_end, "wb") as stream:
            stream.write(data)
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(code)
    os.close(write_end)
    with os.fdopen(read_end, "rb") as stream:
        data = stream.read()
    _, status = os.waitpid(pid, 0)
    try:
        payload = pickle.loads(data) if data else None
    except (pickle.UnpicklingError, EOFError, ValueError):
        payload = None
    if isinstance(payload, list):
        reports = [hook.pytest_report_from_serializable(config=item.config, data=d)
                   for d in payload]
    else:
        why = (payload or {}).get("error") or (
            f"the forked child died: {_describe_status(status)}")
        reports = [TestReport(item.nodeid, item.location,
                              {k: 1 for k in item.keywords}, "failed", why, "???")]
    for rep in reports:
        ihook.pytest_runtest_logreport(report=rep)
    # The child tore its own copies down; here, tear down what earlier tests of this process
    # set up and the next test does not share (a module left on the stack for this item).
    item.session._setupstate.teardown_exact(nextitem)
    ihook.pytest_runtest_logfinish(nodeid=item.nodeid, location=item.location)
    return True


def _describe_status(status):
    if os.WIFSIGNALED(status):
        return f"signal {os.WTERMSIG(status)}"
    return f"exit status {os.WEXITSTATUS(status)}"
