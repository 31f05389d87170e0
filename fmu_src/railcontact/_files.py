"""Where this package's files are: its data files now (also inside the FMU, after a
re-extraction), and its user cache directory (numba's compiled kernels, decompressed tables)."""

from __future__ import annotations

import os
import sys
import threading
from pathlib import Path

__all__ = ["package_directory", "user_cache_dir", "writable_cache_dir", "numba_cache_root"]


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


_LOCK = threading.Lock()
_WRITABLE = {}        # user cache directory -> whether it could be written (once per process)
_TEMPORARY = []       # [the per-process numba cache, made when the user cache is not writable]


def writable_cache_dir():
    """:func:`user_cache_dir` if this process can write to it (created if missing), else None,
    after ONE ``RuntimeWarning`` per process saying what is lost: compiled kernels and
    decompressed tables are then not kept for the next process. Nothing fails because of it
    (a read-only home, a full disk, a cache directory owned by another user)."""
    path = user_cache_dir()
    with _LOCK:
        if path not in _WRITABLE:
            try:
                path.mkdir(parents=True, exist_ok=True)
                probe = path / f".write-test-{os.getpid()}-{threading.get_ident()}"
                probe.write_bytes(b"")
                probe.unlink()
            except OSError as exc:
                _WRITABLE[path] = False
                import warnings  # noqa: PLC0415

                warnings.warn(
                    f"railcontact: the user cache directory {str(path)!r} cannot be written "
                    f"({type(exc).__name__}: {exc.strerror or exc}); compiled kernels and "
                    "decompressed tables are kept for this process only (set "
                    "RAILCONTACT_CACHE_DIR to a writable directory to keep them)",
                    RuntimeWarning, stacklevel=3)
            else:
                _WRITABLE[path] = True
        return path if _WRITABLE[path] else None


def numba_cache_root():
    """Where numba keeps this package's compiled kernels: ``<user cache>/numba``, or, where
    the user cache cannot be written (:func:`writable_cache_dir` warned), a temporary
    directory of this process, removed at its exit."""
    base = writable_cache_dir()
    if base is not None:
        return base / "numba"
    with _LOCK:
        if not _TEMPORARY:
            import atexit  # noqa: PLC0415
            import shutil  # noqa: PLC0415
            import tempfile  # noqa: PLC0415

            _TEMPORARY.append(Path(tempfile.mkdtemp(prefix="railcontact-numba-")))
            atexit.register(shutil.rmtree, _TEMPORARY[0], True)
        return _TEMPORARY[0]
