"""Where numba keeps the compiled code of this package: a user cache directory.

numba's default (``cache=True``) writes next to the source file (``__pycache__``), keyed by
the source directory when ``NUMBA_CACHE_DIR`` is set. Inside an FMU the package runs from a
temporary extraction directory, new for every instantiation: both places are lost, and each
fresh process pays the full compilation (about 6 s for the exact 3-D solver). This module
registers a cache locator (numba's extension point, ``CacheImpl._locator_classes`` (``_CacheImpl`` before 0.61),
also selectable with ``NUMBA_CACHE_LOCATOR_CLASSES``) that, for this package's files only,
stores the cache in

    ``$RAILCONTACT_CACHE_DIR`` or the platform's user cache directory
    (``%LOCALAPPDATA%\\railcontact\\Cache``, ``~/Library/Caches/railcontact``,
    ``$XDG_CACHE_HOME/railcontact`` or ``~/.cache/railcontact``), sub-folder ``numba``,

one folder per module import name and source content (the first 16 hex digits of its
SHA-256), so the
cache survives re-extraction and two versions of the package do not overwrite each other's
entries. numba still checks the source stamp (a content hash in numba >= 0.61) and the
target machine before it loads an entry. A user's ``NUMBA_CACHE_DIR`` keeps precedence. If the
directory cannot be written, one warning says so and the kernels are cached in a temporary
directory of the process (numba's own fallbacks, the package's ``__pycache__`` or its user-wide
cache, may be unwritable too, and with no writable place numba refuses to import the module).
numba writes each entry to a temporary file and renames it into place, so processes that start
together on an empty cache each compile and the last rename wins; none reads a half-written
entry (tests/test_numba_cache.py).

Import this module before any ``@njit(cache=True)`` of the package is decorated.
"""

from __future__ import annotations

import hashlib
from pathlib import Path

from numba.core import caching

from ._files import numba_cache_root, user_cache_dir  # noqa: F401  (user_cache_dir: tests)

_PACKAGE_DIR = Path(__file__).resolve().parent


class RailcontactCacheLocator(caching._SourceFileBackedLocatorMixin, caching._CacheLocator):
    """numba cache locator: this package's modules cache in the user cache directory (a
    temporary one of the process where that cannot be written:
    :func:`railcontact._files.numba_cache_root`)."""

    def __init__(self, py_func, py_file):
        self._py_file = py_file
        self._lineno = py_func.__code__.co_firstlineno
        with open(py_file, "rb") as fh:
            digest = hashlib.sha256(fh.read()).hexdigest()[:16]
        # keyed by the module's import name too: the FMU bundles the same file under another
        # package name, and numba's cached environment re-imports the module by that name
        module = getattr(py_func, "__module__", None) or Path(py_file).stem
        self._cache_path = str(numba_cache_root() / f"{module}-{digest}")

    def get_cache_path(self):
        return self._cache_path

    @classmethod
    def from_function(cls, py_func, py_file):
        try:
            inside = Path(py_file).resolve().is_relative_to(_PACKAGE_DIR)
        except (OSError, ValueError):
            inside = False
        if not inside:
            return None
        return super().from_function(py_func, py_file)


_IMPL = getattr(caching, "CacheImpl", None) or getattr(caching, "_CacheImpl")
if RailcontactCacheLocator not in _IMPL._locator_classes:
    # after numba's UserProvidedCacheLocator: an explicit NUMBA_CACHE_DIR wins
    _IMPL._locator_classes.insert(1, RailcontactCacheLocator)
