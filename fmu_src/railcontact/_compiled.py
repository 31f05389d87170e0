"""The compiled kernels a table evaluation calls: ahead of time where a wheel's or an FMU's
build made them, else numba's just-in-time copies of the same source.

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
the numba kernels: the same source and, as the tests check, the same results. A wheel's
build (``setup.py``) compiles the same module into the installed package, with the serial
batch kernels of :data:`BATCH_EXPORTS` too, so that a user's first call neither imports numba
nor compiles (docs/performance.md), and the reference rolling solver's sweep
(:data:`SOLVER_EXPORTS`), so that a first ``method="exact"`` call does not compile it.
"""

from __future__ import annotations

import warnings
from functools import lru_cache
from pathlib import Path
from types import SimpleNamespace

import numpy as np

__all__ = ["EXPORTS", "BATCH_EXPORTS", "SOLVER_EXPORTS", "matches", "aot_kernel", "aot_batch",
           "AOT_MODULE", "aot_module", "tensor_eval", "find_span", "cubic_basis",
           "creep_contact", "creep_contact_force", "creep_table_point", "creep_table_force",
           "superposed_response", "exact_kernels", "unit_ellipses_kernel", "batch_kernel",
           "falling_contact", "falling_table_point", "falling_contacts",
           "falling_correction_batch", "build_aot"]

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
    ("creep_table_force", "_exact_kernels",
     "UniTuple(f8, 2)(f8[::1], f4[:, :, :, :, :, ::1], f8, f8, f8, f8, f8, f8, f8, f8, f8)"),
    # the same two kernels on the table summed over nu (float64: ExactCreepTable.prepare)
    ("creep_table_point_nu", "_exact_kernels",
     "b1(f8[::1], f8[:, :, :, :, :, ::1], f8, f8, f8, f8, f8, f8, f8, f8, f8, b1)"),
    ("creep_table_force_nu", "_exact_kernels",
     "UniTuple(f8, 2)(f8[::1], f8[:, :, :, :, :, ::1], f8, f8, f8, f8, f8, f8, f8, f8, f8)"),
    ("superposed_response", "_response_kernels",
     "b1(f8[::1], i8[::1], f8[::1], f8, f8, f8, f8[::1])"),
    # falling friction on one exact-table contact (railcontact.falling_table: the FMU's step
    # and the public scalar call with SmoothFriction, PolachFriction or a tabulated law)
    ("falling_contact", "_falling_kernels",
     "b1(f8[::1], f8, f8, f8, f8, f8, f8, f8, i8, f8, f8, f8, f8, f8[:, ::1], f8[::1], "
     "f8[:, ::1], i8, f8, f8[::1], f8[::1])"),
    # the same for any contact, without a contact buffer: the exact table's 5-D spline at
    # each point (a contact whose a0/b0 changes at every call; a vehicle FMU's contacts), on
    # the file's coefficients and on those summed over nu
    ("falling_table_point", "_falling_kernels",
     "b1(f8[::1], f4[:, :, :, :, :, ::1], f8, f8, f8, f8, f8, f8, f8, f8, i8, f8, f8, f8, f8, "
     "f8[:, ::1], f8[::1], f8[:, ::1], i8, f8, f8[::1], f8[::1])"),
    ("falling_table_point_nu", "_falling_kernels",
     "b1(f8[::1], f8[:, :, :, :, :, ::1], f8, f8, f8, f8, f8, f8, f8, f8, i8, f8, f8, f8, f8, "
     "f8[:, ::1], f8[::1], f8[:, ::1], i8, f8, f8[::1], f8[::1])"),
    # a vehicle's contacts in one call (railcontact.effects.Vehicle: the table summed over nu)
    ("falling_contacts", "_falling_kernels",
     "void(f8[::1], f8[:, :, :, :, :, ::1], f8[::1], b1[::1], f8[::1], f8[::1], f8[::1], "
     "f8[::1], f8[::1], f8[::1], f8, f8, i8, f8[::1], f8, f8, f8, f8[:, ::1], f8[::1], "
     "f8[::1], f8[:, ::1], i8, f8, f8[::1], f8[:, ::1], b1[::1])"),
    # its correction table at many points (the array path of railcontact.falling_table)
    ("falling_correction_batch", "_falling_kernels",
     "void(f8[::1], f8[::1], f8[::1], f8[::1], f8[::1], f8[::1], f8[::1], f8[::1], "
     "f8[:, ::1])"),
    # the Hertz ellipses of changing curvatures (railcontact.effects.normal.unit_ellipses)
    ("unit_ellipses_kernel", "_hertz_kernels",
     "i8(f8[::1], f8[::1], f8, f8[::1], f8[:, ::1], f8[:, ::1])"),
)

# --- kernels compiled ahead of time for a wheel: the serial batches -----------------------
#: The batch kernels compiled ahead of time beside :data:`EXPORTS` (same format): the serial
#: copies of :mod:`railcontact._exact_kernels`' batch loops. ``numba.pycc`` cannot compile
#: ``parallel=True`` (numba issue #3336: prange runs as range), so where these load the reader
#: runs its batches on them, serially, and imports no numba; the threaded ``<name>_parallel``
#: kernels remain the just-in-time path. The coefficients' type is creep_table_point's
#: (:data:`EXPORTS`), so that the two lists cannot disagree.
BATCH_EXPORTS = (
    ("creep_table_batch", "_exact_kernels",
     "void(f8[::1], {coef}, f8[::1], f8[::1], f8[::1], f8[::1], f8[::1], f8[::1], f8[::1], "
     "f8[::1], f8[::1], b1, i8, f8[:, ::1], b1[::1])"),
    ("creep_table_batch_nu", "_exact_kernels",
     "void(f8[::1], f8[:, :, :, :, :, ::1], f8[::1], f8[::1], f8[::1], f8[::1], f8[::1], "
     "f8[::1], f8[::1], f8[::1], f8[::1], b1, i8, f8[:, ::1], b1[::1])"),
    ("creep_contact_batch", "_exact_kernels",
     "void(f8[::1], f8[::1], f8[::1], f8[::1], f8, f8, f8, f8, f8, b1, f8[:, ::1], b1[::1])"),
    ("creep_batch", "_exact_kernels",
     "void({coef}, f8[:, :, :, ::1], b1, f8[::1], i8[::1], f8[:, :, ::1], f8, f8[::1], "
     "f8[::1], f8[::1], f8[::1], f8[::1], f8[::1], f8[::1], f8[::1], f8[::1], f8[::1], "
     "f8[::1], f8[::1], b1, f8[:, ::1], b1[::1])"),
)


# --- kernels compiled ahead of time for a wheel: the reference solver --------------------
#: The reference rolling solver's kernel compiled ahead of time for a wheel beside
#: :data:`BATCH_EXPORTS` (same format; the module is relative to the package): the block
#: Gauss-Seidel sweep of :mod:`railcontact.reference.rolling3d` and its callees (the line
#: Newton solver, the friction table). numba compiles it in 10-30 s on a first
#: ``method="exact"`` call with an empty user cache, nearly all of that call's time; the
#: solver takes the compiled copy where it loads and its arguments match (:func:`aot_kernel`).
#: The FMU's build leaves it out: a table scene never calls the reference solver.
SOLVER_EXPORTS = (
    ("_sweep", "reference.rolling3d",
     "f8(i8[::1], i8[::1], i8[::1], f8[::1], f8[::1], f8[::1], f8[:, ::1], f8[:, ::1], "
     "f8[:, ::1], f8[:, :, ::1], f8[:, :, ::1], i8[::1], i8, i8, f8[::1], f8[::1], f8[::1], "
     "f8[::1], f8, i8, f8)"),
)


@lru_cache(maxsize=None)
def _split_args(signature):
    """The argument types of a numba signature string such as ``"b1(f8[::1], f8)"``, split at
    the top-level commas, and the return type."""
    close = signature.rindex(")")
    depth = 0
    for open_ in range(close, -1, -1):
        depth += {")": 1, "(": -1}.get(signature[open_], 0)
        if depth == 0:
            break
    parts, depth, current = [], 0, ""
    for ch in signature[open_ + 1:close]:
        depth += {"[": 1, "(": 1, "]": -1, ")": -1}.get(ch, 0)
        if ch == "," and depth == 0:
            parts.append(current.strip())
            current = ""
        else:
            current += ch
    return tuple(parts + ([current.strip()] if current.strip() else [])), signature[:open_]


def _coefficient_type():
    """The exact table's coefficient array type, from creep_table_point's entry of EXPORTS."""
    sig = next(s for name, _, s in EXPORTS if name == "creep_table_point")
    return _split_args(sig)[0][1]


@lru_cache(maxsize=1)
def _all_exports():
    """:data:`EXPORTS`, :data:`BATCH_EXPORTS` (their ``{coef}`` filled in) and
    :data:`SOLVER_EXPORTS`: what a wheel's build compiles."""
    coef = _coefficient_type()
    return EXPORTS + tuple((name, module, sig.format(coef=coef))
                           for name, module, sig in BATCH_EXPORTS) + SOLVER_EXPORTS


_DTYPES = {"f8": np.float64, "f4": np.float32, "i8": np.int64, "b1": np.bool_}


@lru_cache(maxsize=None)
def _argument_specs(signature):
    """Per argument of ``signature``: None for a scalar, else (dtype, ndim, C-contiguous)."""
    specs = []
    for t in _split_args(signature)[0]:
        if "[" not in t:
            specs.append(None)
        else:
            code, dims = t.split("[", 1)
            specs.append((np.dtype(_DTYPES[code.strip()]), dims.count(",") + 1, "::1" in dims))
    return tuple(specs)


def matches(signature, args):
    """Whether ``args`` have exactly the types of the numba ``signature`` string: arrays of
    its dtype, dimension and (``::1``) C layout, no array where it takes a scalar. Exported
    ahead-of-time functions check nothing themselves (numba's pycc documentation), so a
    caller checks arrays before it calls one."""
    specs = _argument_specs(signature)
    if len(specs) != len(args):
        return False
    for spec, a in zip(specs, args):
        if spec is None:
            if isinstance(a, np.ndarray):
                return False
        elif not isinstance(a, np.ndarray) or a.dtype != spec[0] or a.ndim != spec[1] \
                or (spec[2] and not a.flags.c_contiguous):
            return False
    return True


_BATCH_SIGNATURES = {}


def aot_kernel(name, args):
    """The ahead-of-time kernel ``name`` of a wheel (:data:`BATCH_EXPORTS`,
    :data:`SOLVER_EXPORTS`) if there is one and ``args`` match its signature, else None (then
    the numba kernels)."""
    aot = aot_module()
    kernel = getattr(aot, name, None) if aot is not None else None
    if kernel is None:
        return None
    if not _BATCH_SIGNATURES:
        _BATCH_SIGNATURES.update((n, sig) for n, _, sig in _all_exports())
    return kernel if matches(_BATCH_SIGNATURES[name], args) else None


#: The serial batch kernels (:data:`BATCH_EXPORTS`) are looked up as every wheel kernel.
aot_batch = aot_kernel


_AOT = []      # [module or None] once looked up


def aot_module():
    """The ahead-of-time compiled kernels (the extension module ``_aot_kernels`` beside this
    file: made by a wheel's or an FMU's build), or None where there is none, it does not load,
    or it lacks one of :data:`EXPORTS` (an older build: the numba kernels then). Its
    attributes are the exported kernels (of :data:`BATCH_EXPORTS` and :data:`SOLVER_EXPORTS`
    those it has)."""
    if not _AOT:
        import importlib  # noqa: PLC0415

        try:
            module = importlib.import_module(f"{__package__}.{AOT_MODULE}")
            kernels = {name: getattr(module, name) for name, _, _ in EXPORTS}
        except (ImportError, AttributeError):
            _AOT.append(None)
        else:
            kernels.update({name: getattr(module, name)
                            for name, _, _ in BATCH_EXPORTS + SOLVER_EXPORTS
                            if hasattr(module, name)})
            _AOT.append(SimpleNamespace(**kernels))
    return _AOT[0]
# --- end of the wheel's kernels --------------------------------------------------------------


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


def _table_kernel(name, args):
    """The kernel ``name`` of the exact table for any contact, or its copy ``<name>_nu`` for
    the coefficients summed over nu (float64), as a plain callable: the ahead-of-time copy
    where it loads and ``args`` match its signature, else numba's entry point for ``args``."""
    if args[1].dtype != np.float32:
        name += "_nu"
    aot = aot_module()
    if aot is not None and matches(dict((n, s) for n, _, s in EXPORTS)[name], args):
        return getattr(aot, name)
    return _entry_point(getattr(exact_kernels(), name), *args)


def creep_table_point(tbuf, coef):
    """The exact table's scalar kernel for any contact (``_exact_kernels.creep_table_point``:
    the five-dimensional spline) as a plain callable (:func:`_table_kernel`), for the table
    buffer ``tbuf`` and the coefficients ``coef``: the file's (float32) or those summed over
    nu (float64, n1 = 1)."""
    return _table_kernel("creep_table_point",
                         (tbuf, coef, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0, 0.25, 1.0, False))


def creep_table_force(tbuf, coef):
    """The exact table's forces-only scalar kernel for any contact
    (``_exact_kernels.creep_table_force``: returns ``(tx, ty)``, raises ArithmeticError for
    the array path) as a plain callable (see :func:`creep_table_point`)."""
    return _table_kernel("creep_table_force",
                         (tbuf, coef, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0, 0.25, 1.0))


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


def falling_contact():
    """Falling friction on one exact-table contact (``_falling_kernels.falling_contact``): the
    ahead-of-time copy, or numba's dispatcher (its caller passes arrays of the exported
    types: the table's contact buffer, ``falling_table``'s Gauss rows and result array)."""
    aot = aot_module()
    if aot is not None:
        return aot.falling_contact
    from ._falling_kernels import falling_contact as kernel  # noqa: PLC0415  (numba)

    return kernel


def falling_table_point(coef):
    """Falling friction on any contact, on the exact table's five-dimensional spline
    (``_falling_kernels.falling_table_point``) for the coefficients ``coef``: the file's
    (float32) or those summed over nu (float64, its copy ``falling_table_point_nu``). The
    ahead-of-time copy, or numba's dispatcher (as :func:`falling_contact`)."""
    name = "falling_table_point" + ("" if coef.dtype == np.float32 else "_nu")
    aot = aot_module()
    if aot is not None:
        return getattr(aot, name)
    from . import _falling_kernels  # noqa: PLC0415  (numba)

    return getattr(_falling_kernels, name)


def falling_contacts():
    """Falling friction on a vehicle's contacts in one call
    (``_falling_kernels.falling_contacts``): the ahead-of-time copy, or numba's dispatcher."""
    aot = aot_module()
    if aot is not None:
        return aot.falling_contacts
    from ._falling_kernels import falling_contacts as kernel  # noqa: PLC0415  (numba)

    return kernel


def falling_correction_batch():
    """The falling-friction correction table at many points
    (``_falling_kernels.falling_correction_batch``): the ahead-of-time copy, or numba's."""
    aot = aot_module()
    if aot is not None:
        return aot.falling_correction_batch
    from ._falling_kernels import falling_correction_batch as kernel  # noqa: PLC0415

    return kernel


@lru_cache(maxsize=1)
def unit_ellipses_kernel():
    """The Hertz ellipses of changing curvatures (``_hertz_kernels.unit_ellipses_kernel``) as a
    plain callable: the ahead-of-time copy, or the entry point of numba's signature."""
    aot = aot_module()
    if aot is not None:
        return aot.unit_ellipses_kernel
    from . import _hertz_kernels  # noqa: PLC0415  (numba: only when needed)

    # (no pairs: the kernel returns at once)
    return _entry_point(_hertz_kernels.unit_ellipses_kernel, np.zeros(0), np.zeros(0), 1.0,
                        np.zeros(2), np.zeros((1, 8)), np.zeros((0, 3)))


def batch_kernel(name, args):
    """The serial batch kernel ``name`` of :mod:`railcontact._exact_kernels` as a plain callable
    for arguments of the types of ``args``: the ahead-of-time copy where there is one
    (:func:`aot_batch`), else numba's entry point for those types (compiled or loaded from
    the cache by calling it once with ``args``, which it overwrites the outputs of). For a
    caller that makes many small batch calls with arrays of fixed types (the vehicle FMU's
    step): no type dispatch, no lock, no threads."""
    aot = aot_batch(name, args)
    if aot is not None:
        return aot
    return _entry_point(getattr(exact_kernels(), name), *args)


def build_aot(directory, batches=False):
    """Compile :data:`EXPORTS` (and with ``batches=True`` :data:`BATCH_EXPORTS` and
    :data:`SOLVER_EXPORTS`, or with a list the :data:`BATCH_EXPORTS` it names) ahead of time
    into ``directory`` as the extension module ``_aot_kernels`` (``numba.pycc``: needs a C
    compiler and the Python headers; generic code for the architecture, e.g. x86-64, so the
    module runs on any CPU of it). Used by the FMU build (the per-step kernels, and for a
    vehicle FMU the one batch kernel its step calls: each export adds to the build time) and
    by the wheel's (``setup.py``, with all the batches).

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

            import importlib  # noqa: PLC0415

            cc = CC(AOT_MODULE)
            cc.output_dir = str(directory)
            cc.verbose = False
            solver = batches is True          # (the wheel's build; FMUs leave the solver out)
            if batches is True:
                batches = [name for name, _, _ in BATCH_EXPORTS]
            batch_names = {n for n, _, _ in BATCH_EXPORTS}
            solver_names = {n for n, _, _ in SOLVER_EXPORTS}
            skipped = []
            for name, module, signature in _all_exports():
                if (name in batch_names and name not in (batches or ())) \
                        or (name in solver_names and not solver):
                    continue
                try:
                    kernel = getattr(importlib.import_module(f"{__package__}.{module}"), name)
                except ImportError as exc:
                    if name not in solver_names:
                        raise
                    # a build environment without scipy: the table kernels all the same
                    skipped.append(f"{name} ({exc})")
                    continue
                cc.export(name, signature)(kernel.py_func)
            cc.compile()
    except Exception as exc:  # noqa: BLE001  (no compiler, no headers, a numba without pycc)
        return (f"ahead-of-time kernels not compiled ({type(exc).__name__}: "
                f"{str(exc).strip().splitlines()[-1] if str(exc).strip() else ''}); the FMU's "
                "table scenes load numba's kernels at run time")
    made = sorted(directory.glob(f"{AOT_MODULE}.*"))
    return (f"ahead-of-time kernels compiled: {made[0].name if made else '?'}"
            + (f"; not compiled (numba's at run time): {', '.join(skipped)}" if skipped else ""))
