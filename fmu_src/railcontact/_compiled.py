"""The compiled kernels a table evaluation calls: ahead of time where an FMU build made them,
else numba's just-in-time copies of the same source.

The kernels have one source, the numba functions of :mod:`railcontact._spline_kernels` (the
tables' tensor-product spline) and :mod:`railcontact._exact_kernels` (the exact-theory creep
table). Loaded just in time they cost a fresh process about 0.3 s to import numba and 0.2 s
for numba to set up its compiler before the first cached kernel loads: more than a
co-simulation master should wait for a table scene to initialise. So the FMU build
(:mod:`railcontact.fmu_build`) also compiles the kernels that a table scene calls per step
ahead of time (``numba.pycc``, from the same Python functions, :data:`EXPORTS`) into the
extension module ``_aot_kernels`` inside the bundled package, and the functions here return
those where they load. Where that module is missing (a checkout or an installed package, a
build machine without a C compiler) or does not load (another Python version), they return
the numba kernels: the same source and, as the tests check, the same results.
"""

from __future__ import annotations

import warnings
from pathlib import Path
from types import SimpleNamespace

import numpy as np

__all__ = ["EXPORTS", "AOT_MODULE", "aot_module", "tensor_eval", "find_span", "cubic_basis",
           "creep_contact", "creep_contact_force", "creep_table_point", "creep_table_force",
           "superposed_response",
           "exact_kernels", "build_aot"]

#: Name of the ahead-of-time compiled extension module inside the package.
AOT_MODULE = "_aot_kernels"

#: What the FMU build compiles ahead of time: (exported name, kernel module, numba
#: signature). The exported name is the kernel's name in its module.
EXPORTS = (
    ("tensor_eval", "_spline_kernels",
     "void(f8[:, ::1], i8[::1], f8[::1], i8[::1], i8[::1], i8[::1], f8[:, ::1], i8[::1], "
     "f8[:, ::1], f8[::1])"),
    ("find_span", "_spline_kernels", "i8(f8[::1], i8, f8)"),
    ("cubic_basis", "_exact_kernels", "void(f8[::1], i8, f8, f8[::1], f8[::1], f8[::1])"),
    ("creep_contact", "_exact_kernels", "b1(f8[::1], f8, f8, f8, f8, f8, f8, f8, f8, b1)"),
    ("creep_contact_force", "_exact_kernels",
     "UniTuple(f8, 2)(f8[::1], f8, f8, f8, f8, f8, f8, f8, f8)"),
    ("creep_table_point", "_exact_kernels",
     "b1(f8[::1], f4[:, :, :, :, :, ::1], f8, f8, f8, f8, f8, f8, f8, f8, f8, b1)"),
    ("superposed_response", "_response_kernels",
     "b1(f8[::1], i8[::1], f8[::1], f8, f8, f8, f8[::1])"),
)

_AOT = []      # [module or None] once looked up


def aot_module():
    """The ahead-of-time compiled kernels (the extension module ``_aot_kernels`` beside this
    file), or None where there is none or it does not load."""
    if not _AOT:
        try:   # made by the FMU build only
            from ._aot_kernels import (  # noqa: PLC0415
                creep_contact, creep_contact_force, creep_table_force, creep_table_point,
                cubic_basis, find_span, superposed_response, tensor_eval)
        except ImportError:
            _AOT.append(None)
        else:
            _AOT.append(SimpleNamespace(creep_contact=creep_contact,
                                        creep_contact_force=creep_contact_force,
                                        creep_table_point=creep_table_point,
                                        creep_table_force=creep_table_force,
                                        cubic_basis=cubic_basis,
                                        find_span=find_span, tensor_eval=tensor_eval,
                                        superposed_response=superposed_response))
    return _AOT[0]


def _spline_kernels():
    from . import _spline_kernels as kernels  # noqa: PLC0415  (numba: only when needed)

    return kernels


def exact_kernels():
    """The numba kernels of the exact table (:mod:`railcontact._exact_kernels`; its batch
    kernels have no ahead-of-time copy)."""
    from . import _exact_kernels as kernels  # noqa: PLC0415  (numba: only when needed)

    return kernels


def tensor_eval():
    """The tables' tensor-product spline evaluator (``_spline_kernels.tensor_eval``)."""
    aot = aot_module()
    return aot.tensor_eval if aot is not None else _spline_kernels().tensor_eval


def find_span():
    """The knot span search (``_spline_kernels.find_span``)."""
    aot = aot_module()
    return aot.find_span if aot is not None else _spline_kernels().find_span


def cubic_basis():
    """The cubic B-spline basis and its derivative (``_exact_kernels.cubic_basis``)."""
    aot = aot_module()
    return aot.cubic_basis if aot is not None else exact_kernels().cubic_basis


def _entry_point(kernel, *args):
    """The entry point of numba's ``kernel`` for the types of ``args``, compiled (or loaded
    from the cache) by calling it with them: a plain callable without numba's type dispatch,
    which costs about 1 us a call."""
    import numba  # noqa: PLC0415

    kernel(*args)
    return kernel.overloads[tuple(numba.typeof(a) for a in args)].entry_point


def creep_contact(buf):
    """The exact table's scalar kernel (``_exact_kernels.creep_contact``) as a plain callable:
    the ahead-of-time copy, or the entry point of numba's float signature, compiled (or loaded
    from the cache) with ``buf``, one contact's buffer."""
    aot = aot_module()
    if aot is not None:
        return aot.creep_contact
    return _entry_point(exact_kernels().creep_contact, buf, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0,
                        1.0, False)


def creep_contact_force(buf):
    """The exact table's forces-only scalar kernel (``_exact_kernels.creep_contact_force``:
    returns ``(tx, ty)``, raises ArithmeticError for the array path) as a plain callable, as
    :func:`creep_contact`."""
    aot = aot_module()
    if aot is not None:
        return aot.creep_contact_force
    return _entry_point(exact_kernels().creep_contact_force, buf, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0,
                        1.0, 1.0)


def creep_table_point(tbuf, coef):
    """The exact table's scalar kernel for any contact (``_exact_kernels.creep_table_point``:
    the five-dimensional spline) as a plain callable: the ahead-of-time copy, or the entry
    point of numba's signature for the table buffer ``tbuf`` and coefficients ``coef`` (see
    :func:`creep_contact`): the file's or those summed over nu (both float32)."""
    aot = aot_module()
    if aot is not None:
        return aot.creep_table_point
    return _entry_point(exact_kernels().creep_table_point, tbuf, coef, 0.0, 0.0, 0.0, 1.0,
                        1.0, 1.0, 1.0, 0.25, 1.0, False)


def creep_table_force(tbuf, coef):
    """The exact table's forces-only scalar kernel for any contact
    (``_exact_kernels.creep_table_force``: returns ``(tx, ty)``, raises ArithmeticError for
    the array path) as a plain callable (see :func:`creep_table_point`)."""
    aot = aot_module()
    if aot is not None:
        return aot.creep_table_force
    return _entry_point(exact_kernels().creep_table_force, tbuf, coef, 0.0, 0.0, 0.0, 1.0,
                        1.0, 1.0, 1.0, 0.25, 1.0)


def superposed_response(fbuf, ibuf, harm):
    """The corrugation response table's step kernel
    (``_response_kernels.superposed_response``) as a plain callable: the ahead-of-time copy, or
    the entry point of numba's signature for these buffers (see :func:`creep_contact`)."""
    aot = aot_module()
    if aot is not None:
        return aot.superposed_response
    from . import _response_kernels  # noqa: PLC0415  (numba: only when needed)

    # (r < 0: the kernel returns at once)
    return _entry_point(_response_kernels.superposed_response, fbuf, ibuf, harm, 0.0, 0.0,
                        -1.0, np.zeros(4))


def build_aot(directory):
    """Compile :data:`EXPORTS` ahead of time into ``directory`` as the extension module
    ``_aot_kernels`` (``numba.pycc``: needs a C compiler and the Python headers).

    Returns
    -------
    str
        What happened, for the build's log: the file written, or why nothing was (then the
        package uses the numba kernels at run time).
    """
    directory = Path(directory)
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")         # numba.pycc: pending deprecation
            from numba.pycc import CC  # noqa: PLC0415

            from . import _response_kernels  # noqa: PLC0415

            modules = {"_spline_kernels": _spline_kernels(), "_exact_kernels": exact_kernels(),
                       "_response_kernels": _response_kernels}
            cc = CC(AOT_MODULE)
            cc.output_dir = str(directory)
            cc.verbose = False
            for name, module, signature in EXPORTS:
                cc.export(name, signature)(getattr(modules[module], name).py_func)
            cc.compile()
    except Exception as exc:  # noqa: BLE001  (no compiler, no headers, a numba without pycc)
        return (f"ahead-of-time kernels not compiled ({type(exc).__name__}: "
                f"{str(exc).strip().splitlines()[-1] if str(exc).strip() else ''}); the FMU's "
                "table scenes load numba's kernels at run time")
    made = sorted(directory.glob(f"{AOT_MODULE}.*"))
    return f"ahead-of-time kernels compiled: {made[0].name if made else '?'}"
