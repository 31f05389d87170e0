"""Lazily bound submodules of the package: executed on their first attribute access
(:class:`importlib.util.LazyLoader`), so that a module can bind a heavy one (numba kernels,
scipy) that only some of its functions need."""

from __future__ import annotations

import importlib
import importlib.util
import sys

__all__ = ["lazy_submodule"]

_PACKAGE = __name__.rpartition(".")[0]


class _CurrentPathLoader:
    """Loader of a lazily bound submodule that finds its file when it runs, on the package's
    ``__path__`` *then*: inside an FMU the slave points that path at each new extraction and an
    importer may delete the one the submodule was bound from (fmpy does)."""

    def __init__(self, fullname):
        self.fullname = fullname

    def create_module(self, spec):
        return None

    def exec_module(self, module):
        from importlib.machinery import PathFinder  # noqa: PLC0415

        spec = PathFinder.find_spec(self.fullname, sys.modules[_PACKAGE].__path__)
        if spec is None:
            raise ModuleNotFoundError(f"No module named {self.fullname!r}", name=self.fullname)
        module.__spec__, module.__loader__ = spec, spec.loader
        module.__file__, module.__cached__ = spec.origin, spec.cached
        spec.loader.exec_module(module)


def lazy_submodule(name):
    """The submodule ``railcontact.<name>``, executed on its first attribute access
    (:class:`importlib.util.LazyLoader`, from the package's path at that moment): ``from
    railcontact import *`` binds every public submodule without importing scipy or numba for
    the ones a session never uses; a module binds the heavy ones it needs only in some of its
    functions the same way (the corrugation and wear modules their compiled kernels: a table
    scene's effects load no numba)."""
    full = f"{_PACKAGE}.{name}"
    if sys.modules.get(full) is not None:     # (imported already, or lazily bound already:
        return sys.modules[full]              # returned as it is, not executed by importlib)
    if full in sys.modules:                   # (blocked: None raises as import does)
        return importlib.import_module(full)
    spec = importlib.util.find_spec(full)
    if spec is None:
        raise ModuleNotFoundError(f"No module named {full!r}", name=full)
    loader = importlib.util.LazyLoader(_CurrentPathLoader(full))
    spec.loader = loader
    module = importlib.util.module_from_spec(spec)
    sys.modules[full] = module
    loader.exec_module(module)
    return module
