"""Where this package's files are: its data files now (also inside the FMU, after a
re-extraction), and its user cache directory (numba's compiled kernels, decompressed tables)."""

from __future__ import annotations

import os
import sys
from pathlib import Path

__all__ = ["package_directory", "user_cache_dir"]


def user_cache_dir() -> Path:
    """The package's user cache directory: ``$RAILCONTACT_CACHE_DIR`` or the platform's
    (``%LOCALAPPDATA%\\railcontact\\Cache``, ``~/Library/Caches/railcontact``,
    ``$XDG_CACHE_HOME/railcontact`` or ``~/.cache/railcontact``); created by its users on first
    write."""
    env = os.environ.get("RAILCONTACT_CACHE_DIR")
    if env:
        return Path(env)
    if sys.platform.startswith("win"):
        base = Path(os.environ.get("LOCALAPPDATA", Path.home() / "AppData" / "Local"))
        return base / "railcontact" / "Cache"
    if sys.platform == "darwin":
        return Path.home() / "Library" / "Caches" / "railcontact"
    return Path(os.environ.get("XDG_CACHE_HOME", Path.home() / ".cache")) / "railcontact"


def package_directory():
    """This package's directory now: its ``__path__``, which the FMU slave points at each new
    instance's extraction, rather than ``__file__`` or :mod:`importlib.resources` (both keep
    the directory the module was first imported from): a second load of the same FMU in one
    process reuses the imported modules, whose first extraction an importer (fmpy) may have
    deleted. Falls back to the directory of this file."""
    package = sys.modules.get(__package__)
    paths = list(getattr(package, "__path__", None) or ())
    return Path(paths[0]) if paths else Path(__file__).resolve().parent
