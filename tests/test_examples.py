"""The README's recipes (scripts in ``examples/``) run as written, and the table readers
``examples/table_reader.c`` and ``examples/table_reader.f90`` agree with the Python evaluator.

The C program is compiled with gcc and the netCDF C library (Debian: ``gcc libnetcdf-dev``),
the Fortran one with gfortran and netCDF-Fortran (``gfortran libnetcdff-dev``), both installed
by ``.ci/run``; where a compiler or library is missing its tests are skipped and say which.
"""

import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from railcontact.tables import Table

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "examples"
TABLES = sorted((ROOT / "tables").glob("*.nc"))


def _run_example(script, *args, cwd, timeout=600):
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1", PYTHONPATH=os.pathsep.join(
        [str(ROOT / "fmu_src"), str(ROOT), os.environ.get("PYTHONPATH", "")]))
    proc = subprocess.run([sys.executable, str(EXAMPLES / script), *map(str, args)], cwd=cwd,
                          capture_output=True, text=True, timeout=timeout, env=env)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    return proc.stdout


# --------------------------------------------------------------------------------------------
# Tables from C
# --------------------------------------------------------------------------------------------

def _compile(tmp_path_factory, compiler, config, source, flags_option, package, libs=()):
    if shutil.which(compiler) is None:
        pytest.skip(f"{compiler} not found (Debian: apt-get install {package}); "
                    f"{source} is not compiled")
    if shutil.which(config) is None:
        pytest.skip(f"{config} not found: the netCDF development files are not installed "
                    f"(Debian: apt-get install {package})")
    flags = subprocess.run([config, *flags_option], capture_output=True,
                           text=True).stdout.split()
    exe = tmp_path_factory.mktemp("table_reader") / Path(source).stem
    proc = subprocess.run([compiler, "-O2", "-Wall", "-Werror", "-o", str(exe),
                           str(EXAMPLES / source), *flags, *libs], capture_output=True,
                          text=True,
                          cwd=exe.parent)
    assert proc.returncode == 0, proc.stderr
    return exe


@pytest.fixture(scope="module", params=["c", "fortran"])
def table_reader(request, tmp_path_factory):
    """examples/table_reader.c (gcc, netCDF C) or examples/table_reader.f90 (gfortran,
    netCDF-Fortran), compiled against the system libraries."""
    if request.param == "c":
        return _compile(tmp_path_factory, "gcc", "nc-config", "table_reader.c",
                        ["--cflags", "--libs"], "gcc libnetcdf-dev", libs=["-lm"])
    return _compile(tmp_path_factory, "gfortran", "nf-config", "table_reader.f90",
                    ["--fflags", "--flibs"], "gfortran libnetcdff-dev")


@pytest.mark.parametrize("path", TABLES, ids=[p.stem for p in TABLES])
def test_table_reader_agrees_with_python_evaluator(table_reader, path):
    """Value and every first derivative, every variable, at 200 seeded random points inside
    the grid (and the corner nodes), to 1e-12 relative to max(1, |value|) and to the
    derivative's scale (max |dV/dx| over the points, times the axis length) plus the rounding
    a derivative carries on fine knot intervals (below)."""
    table = Table.from_file(path)
    rng = np.random.default_rng(20261125)
    lower = np.array([a["nodes"][0] for a in table.axes])
    upper = np.array([a["nodes"][-1] for a in table.axes])
    points = np.vstack([lower, upper, lower + (upper - lower) * rng.random((200, len(lower)))])
    text = "\n".join(" ".join(f"{v:.17g}" for v in p) for p in points) + "\n"
    ndim = len(table.axes)
    for k, name in enumerate(table.variables):
        proc = subprocess.run([str(table_reader), str(path), name], input=text,
                              capture_output=True, text=True, timeout=120)
        assert proc.returncode == 0, proc.stderr
        got = np.loadtxt(proc.stdout.splitlines(), ndmin=2)
        assert got.shape == (len(points), 1 + ndim)
        want = table.spline.evaluate(points)[:, k]
        np.testing.assert_allclose(got[:, 0], want, rtol=0,
                                   atol=1e-12 * max(1.0, np.abs(want).max()),
                                   err_msg=f"{path.name}: {name}")
        for d in range(ndim):
            order = np.zeros(ndim, dtype=int)
            order[d] = 1
            dwant = table.spline.evaluate(points, derivative=order)[:, k]
            scale = max(1.0, np.abs(dwant).max() * (upper[d] - lower[d]))
            # a derivative's rounding grows with the largest basis derivative, 3 / h over the
            # narrowest knot interval (the exact table's creepage axis: h = 0.0007 of 2), times
            # the coefficients' size: the two evaluators sum in different orders
            knots = np.asarray(table.axes[d]["knots"])
            h_min = np.diff(knots)[np.diff(knots) > 0].min()
            rounding = (16 * np.finfo(float).eps * np.abs(table.coefficients[k]).max()
                        * 3.0 / h_min * (upper[d] - lower[d]))
            np.testing.assert_allclose(got[:, 1 + d] * (upper[d] - lower[d]),
                                       dwant * (upper[d] - lower[d]), rtol=0,
                                       atol=1e-12 * scale + rounding,
                                       err_msg=f"{path.name}: d{name}/d{table.axes[d]['name']}")


def test_table_reader_refuses_a_file_without_the_format_attribute(table_reader, tmp_path):
    netCDF4 = pytest.importorskip("netCDF4")
    path = tmp_path / "not_a_table.nc"
    with netCDF4.Dataset(path, "w") as ds:
        ds.title = "no railcontact_table_format attribute"
    proc = subprocess.run([str(table_reader), str(path), "x"], input="", capture_output=True,
                          text=True, timeout=60)
    assert proc.returncode != 0
    assert "Attribute not found" in proc.stderr, proc.stderr


@pytest.fixture(scope="module")
def c_table_reader(tmp_path_factory):
    """examples/table_reader.c alone (its --exact-coordinates mode)."""
    return _compile(tmp_path_factory, "gcc", "nc-config", "table_reader.c",
                    ["--cflags", "--libs"], "gcc libnetcdf-dev", libs=["-lm"])


def test_c_exact_table_coordinates_agree_with_python(c_table_reader):
    """exact_table_coordinates in examples/table_reader.c (Kalker's coefficients interpolated
    in C) against railcontact: kalker_coefficients, the saturation creepage and
    exact_table.exact_table_coordinates, on 400 seeded random contacts over the table's
    a0/b0 and nu (the ends included) and every sign of the creepages and the spin."""
    from railcontact import kalker_coefficients
    from railcontact.exact_table import exact_table_coordinates

    rng = np.random.default_rng(39)
    n = 400
    ratio = np.exp(rng.uniform(np.log(0.1), np.log(10.0), n))
    ratio[:4] = [0.1, 10.0, 1.0, 1.0 / 0.7]             # the ends and two of Kalker's nodes
    nu = rng.uniform(0.0, 0.5, n)
    nu[:3] = [0.0, 0.5, 0.25]
    b0 = rng.uniform(2e-3, 8e-3, n)
    a0 = ratio * b0
    xi_x, xi_y = rng.uniform(-5e-3, 5e-3, (2, n))
    phi = rng.uniform(-2.0, 2.0, n)
    xi_x[5], xi_y[5], phi[5] = 0.0, 0.0, 0.0           # no creepage at all
    n_load = rng.uniform(1e3, 2e5, n)
    e_mod = rng.uniform(70e9, 230e9, n)
    mu = rng.uniform(0.05, 0.6, n)
    rows = np.column_stack([xi_x, xi_y, phi, a0, b0, nu, n_load, e_mod, mu])
    proc = subprocess.run([str(c_table_reader), "--exact-coordinates"], capture_output=True,
                          text=True, timeout=60,
                          input="\n".join(" ".join(f"{v:.17g}" for v in r) for r in rows))
    assert proc.returncode == 0, proc.stderr
    got = np.loadtxt(proc.stdout.splitlines(), ndmin=2)
    c = kalker_coefficients(ratio, nu)
    p0 = 3.0 * n_load / (2.0 * np.pi * a0 * b0)
    w_sat = np.pi**2 * (1.0 + nu) * mu * p0 / e_mod
    want = np.column_stack(exact_table_coordinates(xi_x, xi_y, phi, a0, b0, nu, w_sat,
                                                   (c.c11, c.c22, c.c23)))
    assert got.shape == want.shape == (n, 5)
    np.testing.assert_allclose(got, want, rtol=1e-12, atol=1e-13)
    assert got[:, 4].min() < -10 < 10 < got[:, 4].max() and np.ptp(got[:, 2]) > 0.5   # spans
    # outside the table's axes: refused, naming the range
    for bad, message in (([1e-3, 0, 0, 5e-4, 6e-3, 0.3, 1e5, 210e9, 0.3], "a0/b0 must be in"),
                         ([1e-3, 0, 0, 5e-3, 6e-3, 0.6, 1e5, 210e9, 0.3], "nu in [0, 0.5]"),
                         ([1e-3, 0, 0, 5e-3, 6e-3, 0.3, 0.0, 210e9, 0.3], "must be > 0")):
        proc = subprocess.run([str(c_table_reader), "--exact-coordinates"], text=True,
                              input=" ".join(map(str, bad)), capture_output=True, timeout=60)
        assert proc.returncode == 1 and message in proc.stderr, proc.stderr


# --------------------------------------------------------------------------------------------
# The README's Python recipes
# --------------------------------------------------------------------------------------------

def test_api_recipe_runs(tmp_path):
    out = _run_example("quickstart_api.py", cwd=tmp_path)
    # the table and the closed form print the same creep curve (table error 2e-7 of mu N)
    lines = dict(line.split(":", 1) for line in out.splitlines() if ":" in line)
    closed = np.array(lines["Tx [kN]       "].strip(" []").split(), float)
    table = np.array(lines["Tx table [kN] "].strip(" []").split(), float)
    np.testing.assert_allclose(table, closed, atol=1e-3)
    assert np.all(np.abs(closed) <= 0.3 * 100.0)          # |Tx| <= mu N [kN]
    assert "valid: [ True False]" in out


def test_fmpy_recipe_runs(built_fmu, tmp_path):
    out = _run_example("fmu_fmpy.py", built_fmu, cwd=tmp_path)
    assert "101 rows; Fx from 20000 N to -20000 N" in out, out


def test_libcosim_recipe_runs(built_fmu, tmp_path):
    pytest.importorskip("libcosimpy")
    out = _run_example("fmu_libcosim.py", built_fmu, cwd=tmp_path)
    assert "after 100 steps: Fx = -20000 N, Fy = 0 N" in out, out


# --------------------------------------------------------------------------------------------
# The README shows the recipes as they are in examples/, and its links resolve
# --------------------------------------------------------------------------------------------

README = ROOT / "README.md"
# written by another change; remove from this set once docs/fmu_lifecycle.md is in the tree
_PENDING_DOCS = set()


def _readme_recipe_blocks():
    import re  # noqa: PLC0415
    blocks = re.findall(r"```python\n(.*?)```", README.read_text(encoding="utf-8"), re.S)
    return [b for b in blocks if b.startswith("# examples/")]


def test_readme_python_blocks_are_the_example_scripts():
    """Each ```python block headed ``# examples/NAME.py`` is a contiguous run of lines of that
    script (which the tests above run), so the README cannot drift from a tested recipe."""
    blocks = _readme_recipe_blocks()
    assert {b.splitlines()[0] for b in blocks} == {
        "# examples/quickstart_api.py", "# examples/fmu_fmpy.py", "# examples/fmu_libcosim.py"}
    for block in blocks:
        header, *lines = block.rstrip("\n").splitlines()
        script = (ROOT / header[2:].strip()).read_text(encoding="utf-8")
        assert "\n".join(lines) in script, f"README block {header!r} differs from the script"


def test_readme_and_docs_links_resolve():
    import re  # noqa: PLC0415
    for page in [README, *sorted((ROOT / "docs").glob("*.md"))]:
        for target in re.findall(r"\]\(([^)#\s]+)(?:#[^)]*)?\)", page.read_text(encoding="utf-8")):
            if "://" in target:
                continue
            path = (page.parent / target).resolve()
            rel = path.relative_to(ROOT).as_posix() if path.is_relative_to(ROOT) else target
            if rel in _PENDING_DOCS:
                continue
            assert path.exists(), f"{page.name}: broken link {target}"


def test_readme_is_short():
    """A newcomer reads it in about five minutes: under 1400 words, about half of them the recipes."""
    words = len(README.read_text(encoding="utf-8").split())
    assert words < 1400, words


def test_api_guide_tour_runs(tmp_path):
    """The first code block of docs/api_guide.md (the tour) runs as written."""
    import re  # noqa: PLC0415
    text = (ROOT / "docs" / "api_guide.md").read_text(encoding="utf-8")
    tour = re.findall(r"```python\n(.*?)```", text, re.S)[0]
    assert "(...)" not in tour
    script = tmp_path / "tour.py"
    script.write_text(tour + "\nprint('tour ok', sol.within_validity)\n", encoding="utf-8")
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1", PYTHONPATH=os.pathsep.join(
        [str(ROOT / "fmu_src"), str(ROOT), os.environ.get("PYTHONPATH", "")]))
    proc = subprocess.run([sys.executable, str(script)], cwd=tmp_path, capture_output=True,
                          text=True, timeout=300, env=env)
    assert proc.returncode == 0, proc.stderr
    assert "tour ok True" in proc.stdout


def test_the_speed_figures_page_is_generated_from_the_recorded_run():
    """docs/figures.md, the one page of speed figures, is what benchmarks/figures.py renders
    from its record (benchmarks/data/figures.json); README and performance.md link to it and
    restate no time per call."""
    import importlib.util  # noqa: PLC0415
    import json  # noqa: PLC0415
    import re  # noqa: PLC0415

    spec = importlib.util.spec_from_file_location("figures", ROOT / "benchmarks" / "figures.py")
    figures = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(figures)
    record = json.loads(figures.RECORD.read_text(encoding="utf-8"))
    page = (ROOT / "docs" / "figures.md").read_text(encoding="utf-8")
    assert page == figures.render(record)
    best = record["per_call_us"]["exact_table"]["best"]
    assert f"| {figures._fmt_us(best)} |" in page
    for doc in (README, ROOT / "docs" / "performance.md"):
        text = doc.read_text(encoding="utf-8")
        assert "figures.md" in text, doc.name
        assert not re.findall(r"\d (?:us|ms) per (?:call|case)|\d us\b", text), doc.name
