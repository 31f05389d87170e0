"""One copy of each table per machine (railcontact._table_store): the process-wide registry,
the memory-mapped user cache, and what happens when the cache is damaged, raced for or not
writable. The values are always checked against the netCDF file read directly."""

import multiprocessing
import os
import shutil
import sys
import warnings

import numpy as np
import pytest

from railcontact import _table_store, tables

SMALL = "velocity_friction"     # 0.2 MB: mapped here by lowering the size threshold
_READ_NETCDF = tables._read_netcdf_file     # (the tests count the loader's calls to it)


def _file_coefficients(path):
    """The file's coefficients, variable axis last, read with netCDF4 (not the loader)."""
    attrs, variables = _READ_NETCDF(path)
    names = str(attrs["table_variables"]).split()
    return np.stack([variables[f"{v}_bspline_coefficients"][1] for v in names], axis=-1)


@pytest.fixture()
def fresh(tmp_path, monkeypatch):
    """An empty user cache and an empty process registry (restored afterwards); every file
    mapped; a copy of a small table in two 'FMU extractions'."""
    monkeypatch.setenv("RAILCONTACT_CACHE_DIR", str(tmp_path / "cache"))
    monkeypatch.delitem(sys.modules, _table_store.REGISTRY_MODULE, raising=False)
    monkeypatch.setattr(_table_store, "MAPPED_MIN_BYTES", 0)
    return tmp_path / "cache" / "tables", _two_extractions(tables.default_table_path(SMALL),
                                                           tmp_path)


def _two_extractions(source, root):
    """Copies of the file ``source`` in two 'FMU extractions' under ``root``."""
    copies = []
    for k in (1, 2):
        copy = root / f"extraction{k}" / source.name
        copy.parent.mkdir()
        shutil.copy(source, copy)
        copies.append(copy)
    return copies


def _reads(monkeypatch):
    calls = []
    monkeypatch.setattr(tables, "_read_netcdf_file",
                        lambda path: calls.append(path) or _READ_NETCDF(path))
    return calls


def test_two_extractions_share_one_mapped_copy(fresh, monkeypatch):
    entries, (first, second) = fresh
    calls = _reads(monkeypatch)
    a = tables.Table.from_file(first, expected_name=SMALL)
    b = tables.Table.from_file(second, expected_name=SMALL)   # another path, same content
    assert calls == [first]                                   # read once in this process
    assert np.shares_memory(a.coefficients, b.coefficients)
    assert isinstance(np.asarray(a.coefficients).base, np.memmap) or isinstance(
        a.coefficients.base, np.memmap)
    assert not a.coefficients.flags.writeable
    assert len(_table_store.process_registry().tables) == 1
    assert len(list(entries.glob("*.npy"))) == 1 and len(list(entries.glob("*.meta.pickle"))) == 1
    assert not list(entries.glob("*.part"))
    np.testing.assert_array_equal(np.moveaxis(a.coefficients, 0, -1),
                                  _file_coefficients(first))
    # a new process (an empty registry) maps the entry: no netCDF read, the same numbers
    monkeypatch.delitem(sys.modules, _table_store.REGISTRY_MODULE)
    c = tables.Table.from_file(second)
    assert calls == [first]
    np.testing.assert_array_equal(c.coefficients, a.coefficients)
    point = [float(np.mean(ax["nodes"][:2])) for ax in a.axes]
    np.testing.assert_array_equal(c.spline.evaluate(point), a.spline.evaluate(point))


def test_a_changed_file_is_not_served_the_old_entry(fresh, monkeypatch):
    _, (first, _) = fresh
    old = tables.Table.from_file(first)
    calls = _reads(monkeypatch)
    with open(first, "ab") as fh:        # another content: another key
        fh.write(b"\0")
    os.utime(first, ns=(1, 1))
    tables.Table.from_file(first)
    assert calls == [first]
    assert len(_table_store.process_registry().tables) == 2
    assert old.coefficients.shape[0] == 3


@pytest.mark.parametrize("damage", ["truncate", "flip", "garbage_meta", "swap_data"])
def test_a_damaged_cache_entry_is_never_read_as_numbers(fresh, monkeypatch, damage):
    entries, (first, _) = fresh
    tables.Table.from_file(first)
    data = next(entries.glob("*.npy"))
    meta = next(entries.glob("*.meta.pickle"))
    raw = bytearray(data.read_bytes())
    if damage == "truncate":
        data.write_bytes(raw[:len(raw) // 2])
    elif damage == "flip":       # one bit of one coefficient: same size, same header
        raw[-9] ^= 0x10
        data.write_bytes(raw)
    elif damage == "garbage_meta":
        meta.write_bytes(b"not a pickle")
    else:                        # another array of the same shape and type in its place
        np.save(data, np.zeros_like(_file_coefficients(first)))
    monkeypatch.delitem(sys.modules, _table_store.REGISTRY_MODULE)   # a new process
    calls = _reads(monkeypatch)
    table = tables.Table.from_file(first)
    assert calls == [first]                          # detected: the file was read again
    np.testing.assert_array_equal(np.moveaxis(table.coefficients, 0, -1),
                                  _file_coefficients(first))
    # ... and the entry was rewritten: the next new process maps it without reading
    monkeypatch.delitem(sys.modules, _table_store.REGISTRY_MODULE)
    tables.Table.from_file(first)
    assert calls == [first]


def test_an_unchanged_entry_is_opened_without_reading_its_bytes(fresh, monkeypatch):
    """The CRC-32 of the coefficients is taken when the entry is written and again only when
    the file is not the one written (here: its modification time changed, its bytes not):
    then the entry passes its check and is kept."""
    entries, (first, _) = fresh
    tables.Table.from_file(first)
    data = next(entries.glob("*.npy"))
    crcs = []
    real = _table_store._crc32
    monkeypatch.setattr(_table_store, "_crc32", lambda fh: crcs.append(1) or real(fh))
    monkeypatch.delitem(sys.modules, _table_store.REGISTRY_MODULE)   # a new process
    calls = _reads(monkeypatch)
    tables.Table.from_file(first)
    assert (calls, crcs) == ([], [])
    os.utime(data, ns=(1, 1))                        # touched, not changed
    monkeypatch.delitem(sys.modules, _table_store.REGISTRY_MODULE)
    table = tables.Table.from_file(first)
    assert (calls, crcs) == ([], [1])                # checked in full, and it passed
    np.testing.assert_array_equal(np.moveaxis(table.coefficients, 0, -1),
                                  _file_coefficients(first))


def test_an_entry_replaced_while_mapped_keeps_the_mapped_numbers(fresh, monkeypatch):
    entries, (first, _) = fresh
    table = tables.Table.from_file(first)
    before = np.array(table.coefficients)
    data = next(entries.glob("*.npy"))
    part = data.with_name("replacement.npy.part")
    with open(part, "wb") as fh:
        np.save(fh, np.full_like(_file_coefficients(first), 7.0))
    os.replace(part, data)
    np.testing.assert_array_equal(table.coefficients, before)   # the old inode, still mapped
    monkeypatch.delitem(sys.modules, _table_store.REGISTRY_MODULE)
    calls = _reads(monkeypatch)
    again = tables.Table.from_file(first)        # the replacement fails the CRC: re-read
    assert calls == [first]
    np.testing.assert_array_equal(again.coefficients, before)


def test_an_unwritable_cache_loads_into_memory_with_one_warning(tmp_path, monkeypatch):
    blocker = tmp_path / "a_file"
    blocker.write_text("not a directory")
    monkeypatch.setenv("RAILCONTACT_CACHE_DIR", str(blocker / "cache"))
    monkeypatch.delitem(sys.modules, _table_store.REGISTRY_MODULE, raising=False)
    monkeypatch.setattr(_table_store, "MAPPED_MIN_BYTES", 0)
    with pytest.warns(RuntimeWarning, match=r"cache directory .* cannot be written.*decompressed "
                                            r"tables are kept for this process only"):
        first = tables.Table.from_file(tables.default_table_path(SMALL))
    with warnings.catch_warnings():
        warnings.simplefilter("error")           # one warning per process, not per table
        second = tables.Table.from_file(tables.default_table_path("nonsteady_transfer"))
    assert not isinstance(first.coefficients.base, np.memmap)
    np.testing.assert_array_equal(np.moveaxis(first.coefficients, 0, -1),
                                  _file_coefficients(tables.default_table_path(SMALL)))
    assert second.coefficients.shape[0] == 2


def _load_in_child(args):
    cache, path, barrier = args
    os.environ["RAILCONTACT_CACHE_DIR"] = cache
    _table_store.MAPPED_MIN_BYTES = 0
    barrier.wait()                               # all four at the same moment
    table = tables.Table.from_file(path)
    mapped = isinstance(table.coefficients.base, np.memmap)
    return np.moveaxis(np.asarray(table.coefficients), 0, -1).tobytes(), mapped


def test_four_processes_creating_the_cache_at_once_all_get_the_right_numbers(
        tmp_path, monkeypatch):
    path = tables.default_table_path(SMALL)
    context = multiprocessing.get_context("spawn")
    with context.Manager() as manager:
        barrier = manager.Barrier(4)
        with context.Pool(4) as pool:
            got = pool.map(_load_in_child, [(str(tmp_path), str(path), barrier)] * 4)
    want = _file_coefficients(path).tobytes()
    assert all(values == want and mapped for values, mapped in got)
    entries = tmp_path / "tables"
    assert len(list(entries.glob("*.npy"))) == 1 and not list(entries.glob("*.part"))
    # the entry left behind is intact: it passes its check and holds the file's numbers
    monkeypatch.setenv("RAILCONTACT_CACHE_DIR", str(tmp_path))
    content = _table_store._open_entry(_table_store.content_key(path))
    assert content is not None and content["coefficients"].tobytes() == want


def test_the_exact_table_is_mapped_float32_and_loaded_once_per_process():
    from railcontact import creep3d

    path = tables.default_table_path("creep_exact")
    first = creep3d.load_exact_table(path)
    assert first._coef.dtype == np.float32 and not first._coef.flags.writeable
    # a second extraction of the same file (another path, same content) in this process
    # gets the same table object: nothing is loaded twice
    import tempfile

    with tempfile.TemporaryDirectory() as extraction:
        copy = shutil.copy(path, extraction)
        assert creep3d.load_exact_table(copy) is first


def test_the_falling_correction_is_one_mapped_copy_for_two_extractions(tmp_path, monkeypatch):
    """The falling-friction correction (package data, its packed spline in float64): two
    copies of its file (two FMU extractions) share one mapped cache entry, written once and
    equal to the file read directly; a second process would read nothing (the entry is
    there)."""
    from pathlib import Path

    from railcontact import falling_table

    monkeypatch.setenv("RAILCONTACT_CACHE_DIR", str(tmp_path / "cache"))
    monkeypatch.delitem(sys.modules, _table_store.REGISTRY_MODULE, raising=False)
    source = Path(falling_table.__file__).parent / "data" / f"{falling_table.CORRECTION_TABLE}.nc"
    copies = _two_extractions(source, tmp_path)
    reads = []
    monkeypatch.setattr(falling_table, "_read_packed",
                        lambda path, read=falling_table._read_packed: reads.append(path)
                        or read(path))
    a = falling_table.load_falling_correction(copies[0])
    b = falling_table.load_falling_correction(copies[1])
    assert reads == [copies[0]]
    assert np.shares_memory(a, b)
    root = a
    while isinstance(getattr(root, "base", None), np.ndarray):
        root = root.base
    assert isinstance(root, np.memmap)
    assert len(list((tmp_path / "cache" / "tables").glob("*-falling-packed.npy"))) == 1
    np.testing.assert_array_equal(a, falling_table._read_packed(source))
