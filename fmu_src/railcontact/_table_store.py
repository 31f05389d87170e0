"""One copy of each table per machine: a process-wide registry and a memory-mapped cache.

A table file's content is loaded once per process, whatever the number of places it is read
from: the installed package, each FMU extraction (a uniquely named copy of this package, so a
registry inside the package would be one per copy), each FMU instance. The registry is a small
module object kept in :data:`sys.modules` under :data:`REGISTRY_MODULE`, outside every copy of
the package, keyed by the file's content (BLAKE2b of its bytes), and it holds only plain
Python and numpy objects that any copy of the package can read.

A file of at least :data:`MAPPED_MIN_BYTES` is also kept decompressed in the user cache
(:func:`railcontact._files.user_cache_dir`, sub-folder ``tables``), as

``<key>.npy``
    the B-spline coefficients, every variable, in the file's precision (float32 for
    ``creep_exact``), variable axis last: the layout the readers' kernels take. It is mapped
    read-only (``numpy.memmap``), so that every process and every FMU instance on the machine
    shares the same pages of the operating system's page cache, and each pays only for the
    pages it touches;
``<key>.meta.pickle``
    everything else (attributes, axes, node values), with the coefficient file's size and its
    CRC-32.

Both are written under temporary names and renamed into place (atomic on POSIX and Windows),
so a reader never sees a partly written file, and a file replaced while mapped keeps its old
content for whoever maps it. A cache entry is checked on every open: the array header's
shape and type against the metadata, and the coefficient file's identity (size,
modification time in ns, inode) against the one recorded when it was written and its CRC-32
taken. A file that is not the one written (changed in place, replaced, swapped, copied) has
its CRC-32 checked in full (read with ``read``, not through the mapping, so the check adds
nothing to the process's resident memory; 0.07 s for the 165 MB of ``creep_exact`` on a
quiet machine, 0.25-0.4 s under load, which every process paid at every open before
2026-11-28). An entry that fails the check is never read as numbers: the table file is read
again and the entry rewritten. (What the identity cannot see is a change that keeps size,
inode and modification time, such as a disk's silent bit rot: as with Python's own
timestamp-checked ``.pyc`` files, the cache trusts its file system there.) Where the cache
directory cannot be written, the table is loaded into memory instead (in its file
precision), with one warning per process (:func:`railcontact._files.writable_cache_dir`'s, or
:class:`TableCacheWarning` where a write fails in a writable directory, e.g. a full disk).
"""

from __future__ import annotations

import hashlib
import mmap
import os
import pickle
import sys
import threading
import types
import warnings
import zlib
from pathlib import Path

import numpy as np

__all__ = ["REGISTRY_MODULE", "MAPPED_MIN_BYTES", "process_registry", "content_key", "load",
           "derived", "release_pages", "TableCacheWarning"]

#: Name, in :data:`sys.modules`, of the process-wide registry (shared by every copy of the
#: package that a process imports).
REGISTRY_MODULE = "_railcontact_process_registry"

#: Table files of at least this size [bytes] are kept decompressed and memory-mapped in the
#: user cache (``creep_exact.nc``, 19 MB zlib: 0.3 s to decompress, 165 MB of float32
#: coefficients); smaller ones are read into memory once per process.
MAPPED_MIN_BYTES = 1_000_000

_CHUNK = 1 << 22


class TableCacheWarning(UserWarning):
    """The user cache could not hold a table: it is loaded into this process's memory."""


def process_registry():
    """The process-wide registry: a module object with ``tables`` (content key -> loaded
    content), ``keys`` ((path, size, mtime, inode) -> content key), ``warned`` and ``lock``
    (a re-entrant lock around loads)."""
    registry = sys.modules.get(REGISTRY_MODULE)
    if registry is None:
        fresh = types.ModuleType(REGISTRY_MODULE, "railcontact: tables loaded in this process "
                                                  "(shared by every copy of the package)")
        fresh.tables, fresh.keys, fresh.warned = {}, {}, set()
        fresh.lock = threading.RLock()
        registry = sys.modules.setdefault(REGISTRY_MODULE, fresh)
    return registry


def content_key(path):
    """The content key of a file: the first 32 hex digits of the BLAKE2b of its bytes
    (memoised per process on its resolved path, size, modification time and inode)."""
    path = Path(path).resolve()
    st = path.stat()
    stamp = (str(path), st.st_size, st.st_mtime_ns, st.st_ino)
    registry = process_registry()
    key = registry.keys.get(stamp)
    if key is None:
        digest = hashlib.blake2b(digest_size=16)
        with open(path, "rb") as fh:
            while chunk := fh.read(_CHUNK):
                digest.update(chunk)
        if len(registry.keys) >= 4096:     # (one per FMU extraction of a long sweep)
            registry.keys.clear()
        key = registry.keys[stamp] = digest.hexdigest()
    return key


def load(path, read):
    """The content of the table file ``path``, loaded once per process (and, for a large
    file, decompressed once per machine).

    Parameters
    ----------
    path : path-like
        The table file.
    read : callable
        ``read(path) -> dict`` reads and checks the file (called only when neither the
        registry nor the cache has it); the dict holds plain objects and numpy arrays, its
        item ``"coefficients"`` the coefficient array that is mapped from the cache.

    Returns
    -------
    dict
        The content: shared, never to be modified.
    """
    path = Path(path)
    return _once(content_key(path), path, lambda: read(path),
                 mapped=path.stat().st_size >= MAPPED_MIN_BYTES, finish=_read_only)


def _once(key, source, make, mapped=True, mode="r", finish=None):
    """The content of ``key``, once per process (the registry) and, where ``mapped``, once
    per machine (the cache entry, opened with ``mode``); ``make()`` where neither has it;
    ``finish(content)`` before it is registered."""
    registry = process_registry()
    with registry.lock:
        content = registry.tables.get(key)
        if content is None:
            content = _open_entry(key, mode) if mapped else None
            if content is None:
                content = make()
                if mapped:
                    content = _write_entry(key, content, source, mode) or content
            registry.tables[key] = finish(content) if finish is not None else content
    return content


def release_pages(array):
    """Give the pages of ``array``, a view of a mapped cache entry, back to the operating
    system (``madvise(MADV_DONTNEED)``: they stay in the page cache, shared, and are mapped
    again when touched); nothing for an array in memory or where the platform has no
    ``madvise``. For a reader that streams through the file once."""
    root = array
    while isinstance(getattr(root, "base", None), np.ndarray):
        root = root.base               # the array made on the mapping (its base: the mmap)
    handle = getattr(root, "base", None)
    if not isinstance(root, np.memmap) or not isinstance(handle, mmap.mmap) \
            or not hasattr(handle, "madvise") or not hasattr(mmap, "MADV_DONTNEED"):
        return
    page = mmap.PAGESIZE
    start = array.__array_interface__["data"][0] - root.__array_interface__["data"][0] \
        + int(root.offset) % mmap.ALLOCATIONGRANULARITY
    first = (start // page) * page
    last = start + array.nbytes
    try:
        handle.madvise(mmap.MADV_DONTNEED, first, last - first)
    except (OSError, ValueError):
        pass


def _read_only(content):
    """``content`` with its arrays (coefficients, node values, axes) made read-only: every
    reader in the process shares them."""
    arrays = [content["coefficients"], *content["values"].values()]
    arrays += [v for axis in content["axes"] for v in axis.values() if isinstance(v, np.ndarray)]
    for array in arrays:
        array.flags.writeable = False
    return content


def derived(path, name, make):
    """An array derived from the table file ``path`` (e.g. its coefficients summed over one
    axis at one value), made once per machine like the table's own coefficients: kept in the
    user cache as ``<key>-<name>.npy`` beside the table's entry, mapped read-only, checked on
    open as that entry is, and held once per process.

    Parameters
    ----------
    path : path-like
        The table file it derives from (its content key names the entry).
    name : str
        What it is, unique per table (letters, digits, ``.``, ``_``, ``-``).
    make : callable
        ``make() -> numpy.ndarray``, called only where neither the process nor the cache
        has it.

    Returns
    -------
    numpy.ndarray
        Mapped copy-on-write where the cache can be written (``numpy.memmap`` mode ``"c"``:
        the pages are the machine's shared ones until a process writes to them, which the
        readers never do; writable, so that the compiled kernels take it with the types of an
        array made in memory), else in memory (with the cache's one warning per process).
    """
    content = _once(f"{content_key(path)}-{name}", path,
                    lambda: {"coefficients": np.ascontiguousarray(make())}, mode="c")
    return np.asarray(content["coefficients"])


def _entry_paths(key):
    from ._files import user_cache_dir  # noqa: PLC0415

    folder = user_cache_dir() / "tables"
    return folder, folder / f"{key}.npy", folder / f"{key}.meta.pickle"


def _crc32(fh):
    crc = 0
    while chunk := fh.read(_CHUNK):
        crc = zlib.crc32(chunk, crc)
    return crc


def _identity(st):
    """A file's identity as the cache records it: (size, modification time [ns], inode)."""
    return (st.st_size, st.st_mtime_ns, st.st_ino)


def _open_entry(key, mode="r"):
    """The cached content of ``key``, its coefficients mapped read-only (``mode="r"``) or
    copy-on-write (``"c"``), or None (no entry, or one that fails its check: never read as
    numbers)."""
    _, data_path, meta_path = _entry_paths(key)
    try:
        with open(meta_path, "rb") as fh:
            meta = pickle.load(fh)
        with open(data_path, "rb") as fh:
            header = (np.lib.format.read_array_header_1_0
                      if np.lib.format.read_magic(fh) == (1, 0)
                      else np.lib.format.read_array_header_2_0)
            shape, fortran, dtype = header(fh)
            offset = fh.tell()
            if (shape, fortran, dtype.str) != (meta["shape"], False, meta["dtype"]) \
                    or os.fstat(fh.fileno()).st_size != meta["file_bytes"]:
                return None
            if meta.get("identity") != _identity(os.fstat(fh.fileno())):
                fh.seek(0)                  # not the file written: its bytes are checked
                if _crc32(fh) != meta["crc32"]:
                    return None
            # the same open file: the inode checked is the inode mapped
            coefficients = np.memmap(fh, dtype=dtype, mode=mode, offset=offset, shape=shape)
    except Exception:  # noqa: BLE001  (missing, truncated, another format: read the file)
        return None
    content = dict(meta["content"])
    content["coefficients"] = coefficients
    return content


def _write_entry(key, content, source, mode="r"):
    """Write the cache entry of ``content`` and return it re-opened (mapped), or None where
    the cache cannot be written (one warning per process; the caller keeps ``content`` in
    memory)."""
    from ._files import writable_cache_dir  # noqa: PLC0415

    if writable_cache_dir() is None:     # (it warned, once per process: kept in memory)
        return None
    folder, data_path, meta_path = _entry_paths(key)
    coefficients = np.ascontiguousarray(content["coefficients"])
    tag = f".{os.getpid()}.{threading.get_ident()}.part"
    part = data_path.with_name(data_path.name + tag)
    meta_part = meta_path.with_name(meta_path.name + tag)
    try:
        folder.mkdir(parents=True, exist_ok=True)
        with open(part, "wb") as fh:
            np.lib.format.write_array(fh, coefficients, allow_pickle=False)
        with open(part, "rb") as fh:
            crc = _crc32(fh)
        st = part.stat()      # (a rename keeps the inode and the modification time)
        meta = dict(content={k: v for k, v in content.items() if k != "coefficients"},
                    shape=coefficients.shape, dtype=coefficients.dtype.str,
                    file_bytes=st.st_size, crc32=crc, identity=_identity(st))
        with open(meta_part, "wb") as fh:
            pickle.dump(meta, fh, protocol=pickle.HIGHEST_PROTOCOL)
        os.replace(part, data_path)       # (the data first: a meta file names only data
        os.replace(meta_part, meta_path)  # whose check it carries)
    except OSError as exc:
        registry = process_registry()
        if "cache" not in registry.warned:
            registry.warned.add("cache")
            warnings.warn(f"the table cache {str(folder)!r} cannot be written ({exc}); "
                          f"{Path(source).name} is loaded into this process's memory instead "
                          "(set RAILCONTACT_CACHE_DIR to a writable directory to share it "
                          "between processes)", TableCacheWarning, stacklevel=4)
        for leftover in (part, meta_part):
            try:
                leftover.unlink(missing_ok=True)
            except OSError:
                pass
        return None
    return _open_entry(key, mode)
