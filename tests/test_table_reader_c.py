"""The shipped tables read from C: ``examples/c/read_table.c`` against the Python evaluator.

The design promises table files that other codes can read. The C program opens a table with the
netCDF C library, finds knots and coefficients only through the attributes the file documents
(``table_axes``, ``spline_degree``, ``spline_knots``, ``bspline_coefficients``) and evaluates
the spline and its first partial derivatives. It must agree with
:meth:`railcontact.tables.Table.__call__` to 1e-12 (relative to the largest value or slope of the
variable, or absolute below 1) at seeded random points inside every table's grid: both sum the
same 4^D products, in another order.

Needs gcc and the netCDF C headers (Debian: ``libnetcdf-dev``; ``.ci/run`` installs them);
skipped, saying which is missing, where they are not installed.
"""

import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

from railcontact.tables import Table, tables_directory

ROOT = Path(__file__).resolve().parents[1]
SOURCE = ROOT / "examples" / "c" / "read_table.c"
TABLES = sorted(Path(tables_directory()).glob("*.nc"))


def _flags():
    """Compiler and linker flags for netCDF-C (nc-config where present)."""
    if shutil.which("nc-config"):
        cflags = subprocess.run(["nc-config", "--cflags"], capture_output=True, text=True)
        libs = subprocess.run(["nc-config", "--libs"], capture_output=True, text=True)
        if cflags.returncode == 0 and libs.returncode == 0:
            return cflags.stdout.split(), libs.stdout.split()
    return [], ["-lnetcdf"]


@pytest.fixture(scope="module")
def reader(tmp_path_factory):
    if shutil.which("gcc") is None:
        pytest.skip("gcc is not installed (Debian: apt-get install gcc)")
    cflags, libs = _flags()
    exe = tmp_path_factory.mktemp("c_reader") / "read_table"
    proc = subprocess.run(["gcc", "-O2", "-Wall", "-Wextra", "-Werror", *cflags, "-o", str(exe),
                           str(SOURCE), *libs, "-lm"], capture_output=True, text=True)
    if proc.returncode != 0 and "netcdf.h" in proc.stderr:
        pytest.skip("the netCDF C headers are not installed (Debian: apt-get install "
                    "libnetcdf-dev)")
    assert proc.returncode == 0, proc.stderr
    return exe


def _axes_range(table):
    lo = np.array([ax["nodes"][0] for ax in table.spline.axes])
    hi = np.array([ax["nodes"][-1] for ax in table.spline.axes])
    return lo, hi


@pytest.mark.parametrize("path", TABLES, ids=[p.stem for p in TABLES])
def test_c_reader_equals_python_evaluator(reader, path):
    table = Table.from_file(path)
    rng = np.random.default_rng(20261125)
    lo, hi = _axes_range(table)
    pts = lo + (hi - lo) * rng.random((100, len(lo)))
    text = "\n".join(" ".join(repr(float(x)) for x in p) for p in pts)
    for variable in table.variables:
        out = subprocess.run([str(reader), str(path), variable], input=text,
                             capture_output=True, text=True, check=True).stdout
        got = np.array([[float(v) for v in line.split()] for line in out.splitlines()])
        want = np.column_stack(
            [table(variable, pts)]
            + [table(variable, pts, derivative=[int(d == k) for d in range(len(lo))])
               for k in range(len(lo))])
        assert got.shape == want.shape
        scale = max(1.0, float(np.abs(want).max()))
        np.testing.assert_allclose(got, want, rtol=0, atol=1e-12 * scale,
                                   err_msg=f"{path.name}: {variable}")


def test_c_reader_rejects_unknown_variable(reader):
    proc = subprocess.run([str(reader), str(TABLES[0]), "no_such_variable"], input="",
                          capture_output=True, text=True)
    assert proc.returncode == 2 and "no_such_variable" in proc.stderr
