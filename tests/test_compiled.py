"""railcontact._compiled: the lists of kernels compiled ahead of time and the argument check
that guards the exported functions (which check nothing themselves)."""

import numpy as np
import pytest

from railcontact import _compiled


def _signatures():
    return {name: sig for name, _, sig in _compiled._all_exports()}


def test_every_export_names_a_numba_kernel_of_its_module():
    import importlib

    for name, module, _ in _compiled._all_exports():
        kernel = getattr(importlib.import_module(f"railcontact.{module}"), name)
        assert hasattr(kernel, "py_func"), name


def test_the_batch_kernels_take_the_coefficients_of_creep_table_point():
    sig = _signatures()
    coef = _compiled._split_args(sig["creep_table_point"])[0][1]
    assert _compiled._split_args(sig["creep_batch"])[0][0] == coef
    assert "{" not in sig["creep_batch"]


def test_the_signatures_are_numba_signatures_of_the_kernels_arguments():
    """Each string parses as numba's, with as many arguments as the Python function."""
    import inspect
    import importlib

    from numba.core import sigutils

    for name, module, sig in _compiled._all_exports():
        args, ret = sigutils.normalize_signature(sig)
        assert len(args) == len(_compiled._split_args(sig)[0]), name
        kernel = getattr(importlib.import_module(f"railcontact.{module}"), name)
        assert len(args) == len(inspect.signature(kernel.py_func).parameters), name


@pytest.mark.parametrize("args, ok", [
    ((np.zeros((2, 3, 4)), 1.0), True),
    ((np.zeros((2, 3, 8))[:, :, ::2], 1.0), False),            # not C-contiguous
    ((np.zeros((2, 3, 4), dtype=np.float32), 1.0), False),     # another dtype
    ((np.zeros((2, 3)), 1.0), False),                          # another dimension
    ((np.zeros((2, 3, 4)), np.zeros(1)), False),               # an array for a scalar
    ((np.zeros((2, 3, 4)),), False),                           # too few
])
def test_matches_checks_dtype_dimension_and_layout(args, ok):
    assert _compiled.matches("b1(f8[:, :, ::1], f8)", args) is ok


def test_matches_reads_tuple_return_types_and_strided_arrays():
    assert _compiled.matches("UniTuple(f8, 2)(f8[::1], i8[:], b1)",
                             (np.zeros(3), np.zeros(4, dtype=np.int64)[::2], True))
    assert not _compiled.matches("void(f8[::1])", ([0.0, 1.0],))   # a list is no array


def test_without_the_compiled_module_no_batch_kernel_is_offered(monkeypatch):
    monkeypatch.setattr(_compiled, "_AOT", [None])
    assert _compiled.aot_batch("creep_contact_batch", ()) is None


def test_the_reference_solver_takes_the_wheels_sweep_where_it_loads(monkeypatch):
    """Where a wheel's compiled module has the sweep (:data:`SOLVER_EXPORTS`), the rolling
    solver calls it with arguments of exactly its signature on every sweep (here numba's copy
    stands in for the compiled one, so the answer is the checkout's)."""
    from types import SimpleNamespace

    import railcontact as rc
    from railcontact.reference import rolling3d

    calls = []

    def sweep(*args):
        calls.append(_compiled.matches(_signatures()["_sweep"], args))
        return rolling3d._sweep(*args)

    kw = dict(normal_load=100e3, a0=6e-3, b0=4e-3, youngs_modulus=210e9, poisson_ratio=0.28,
              friction_coefficient=0.3)
    plain = rc.creep_solution_3d(3e-4, 5e-4, 0.5, method="exact", **kw)
    aot = SimpleNamespace(**{name: None for name, _, _ in _compiled.EXPORTS}, _sweep=sweep)
    monkeypatch.setattr(_compiled, "_AOT", [aot])
    rolling3d.clear_setup_cache()
    via = rc.creep_solution_3d(3e-4, 5e-4, 0.5, method="exact", **kw)
    assert calls and all(calls)
    assert (via.tx, via.ty, via.spin_moment, via.stick_area_fraction) == (
        plain.tx, plain.ty, plain.spin_moment, plain.stick_area_fraction)
