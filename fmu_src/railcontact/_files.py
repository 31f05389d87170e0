"""Where this package's data files are now (also inside the FMU, after a re-extraction)."""

from __future__ import annotations

import sys
from pathlib import Path

__all__ = ["package_directory"]


def package_directory():
    """This package's directory now: its ``__path__``, which the FMU slave points at each new
    instance's extraction, rather than ``__file__`` or :mod:`importlib.resources` (both keep
    the directory the module was first imported from): a second load of the same FMU in one
    process reuses the imported modules, whose first extraction an importer (fmpy) may have
    deleted. Falls back to the directory of this file."""
    package = sys.modules.get(__package__)
    paths = list(getattr(package, "__path__", None) or ())
    return Path(paths[0]) if paths else Path(__file__).resolve().parent
