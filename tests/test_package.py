"""The package's front door: ``railcontact.__all__`` and the map in its docstring."""

import importlib
import pydoc
import re
import types

import railcontact as rc


def test_every_name_in_all_resolves_and_is_unique():
    assert len(rc.__all__) == len(set(rc.__all__))
    for name in rc.__all__:
        assert getattr(rc, name) is not None, name


def test_all_lists_every_public_function_and_class_of_the_top_level():
    public = {n for n in dir(rc) if not n.startswith("_") and n != "check_range"
              and not isinstance(getattr(rc, n), types.ModuleType) and callable(getattr(rc, n))}
    assert public <= set(rc.__all__), sorted(public - set(rc.__all__))


def test_all_is_the_documented_api():
    """The submodules the docs and examples use are public; the FMU's and the tests' tools
    are importable but not in ``__all__``."""
    documented = {"polynomial", "corrugation", "wear", "evolution", "filters", "friction",
                  "roughness", "nonsteady", "kalker", "creep3d", "fastsim", "polach", "tables",
                  "strip_table", "exact_table"}
    internal = {"run", "fmu_build", "fmu_parameters", "scene", "effects", "reference",
                "creep_common", "check_range"}
    assert documented <= set(rc.__all__), sorted(documented - set(rc.__all__))
    assert not internal & set(rc.__all__), sorted(internal & set(rc.__all__))
    for name in internal - {"check_range"}:        # still there for those who need them
        assert isinstance(getattr(rc, name), types.ModuleType), name


def test_submodules_in_all_are_the_package_modules():
    for name in rc.__all__:
        value = getattr(rc, name)
        if isinstance(value, types.ModuleType):
            assert value is importlib.import_module(f"railcontact.{name}")


def test_help_gives_a_map_naming_every_public_name():
    text = pydoc.render_doc(rc, renderer=pydoc.plaintext)
    assert "Map of the package" in text
    doc = rc.__doc__
    missing = [n for n in rc.__all__ if not re.search(rf"\b{n}\b", doc)]
    assert not missing, missing


HEAVY = ("scipy", "numba", "llvmlite", "netCDF4", "xarray", "matplotlib", "dask", "fmpy",
         "pythonfmu")


def _modules_after(code):
    """The top-level packages a fresh interpreter holds after running ``code``."""
    import subprocess
    import sys

    out = subprocess.run(
        [sys.executable, "-c", code + "\nimport sys; print(' '.join(sorted({m.split('.')[0] "
         "for m in sys.modules})))"], check=True, capture_output=True, text=True).stdout
    return set(out.split())


def test_import_railcontact_loads_no_heavy_dependency():
    """``import railcontact`` imports nothing but the package (not even numpy): its names and
    submodules load on first use."""
    loaded = _modules_after("import railcontact")
    assert not loaded & set(HEAVY + ("numpy",)), sorted(loaded & set(HEAVY + ("numpy",)))


def test_star_import_loads_neither_scipy_nor_numba():
    """``from railcontact import *`` binds every public name: the functions' modules load
    (numpy), the submodules are bound lazily and run on their first attribute access."""
    loaded = _modules_after("from railcontact import *")
    assert "numpy" in loaded
    assert not loaded & set(HEAVY), sorted(loaded & set(HEAVY))
    # the lazy submodule runs on its first attribute access; wear's closed forms need neither
    # scipy nor numba (a table scene's wear effect), its compiled series kernels load on
    # their first call
    loaded = _modules_after("from railcontact import *\n"
                            "assert wear.DEFAULT_WEAR_MODEL == 'material_point'")
    assert not loaded & set(HEAVY), sorted(loaded & set(HEAVY))
    loaded = _modules_after("from railcontact import *\nwear.wear_coefficients(0.3, 0.5)")
    assert "numba" in loaded and "scipy" in loaded


def _package_import_graph(package_dir):
    """Module -> the package's modules it imports (any ``import`` / ``from ... import``
    statement, at module level or inside a function), read with :mod:`ast`."""
    import ast
    from pathlib import Path

    root = Path(package_dir)
    modules = {}
    for path in root.rglob("*.py"):
        parts = list(path.relative_to(root.parent).with_suffix("").parts)
        is_package = parts[-1] == "__init__"
        if is_package:
            parts = parts[:-1]
        modules[".".join(parts)] = (path, is_package)
    graph = {}
    for name, (path, is_package) in modules.items():
        here = name.split(".") if is_package else name.split(".")[:-1]
        targets = set()
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Import):
                targets.update(alias.name for alias in node.names)
            elif isinstance(node, ast.ImportFrom):
                base = here[:len(here) - node.level + 1] if node.level else []
                stem = ".".join(base + ([node.module] if node.module else []))
                for alias in node.names:   # a submodule, else a name of module ``stem``
                    sub = f"{stem}.{alias.name}"
                    targets.add(sub if sub in modules else stem)
        graph[name] = {t for t in targets if t in modules and t != name}
    return graph


def _cycles(graph):
    """The import cycles of ``graph`` (each as a list of modules), by depth-first search."""
    found, state = [], {}

    def visit(node, stack):
        state[node] = "open"
        stack.append(node)
        for nxt in sorted(graph[node]):
            if state.get(nxt) == "open":
                found.append(stack[stack.index(nxt):] + [nxt])
            elif nxt not in state:
                visit(nxt, stack)
        stack.pop()
        state[node] = "done"

    for node in sorted(graph):
        if node not in state:
            visit(node, [])
    return found


def test_import_graph_of_the_package_has_no_cycles():
    """No module of railcontact imports, directly or through others, a module that imports it
    (statements anywhere in the file, lazy ones inside functions included; a package's import of
    its own submodules through ``railcontact.__getattr__`` is not a statement and not counted).
    The graph is read with ast, so it is what a reader or a structure tool sees."""
    from pathlib import Path

    graph = _package_import_graph(Path(rc.__file__).parent)
    assert "railcontact.wear" in graph and "railcontact.effects" in graph
    assert "railcontact.corrugation" in graph["railcontact.wear"]      # wear -> contact
    assert "railcontact.wear" not in graph["railcontact.corrugation"]  # ... not back
    assert _cycles(graph) == []
    import tablegen                                     # the table builder beside it, too
    assert _cycles(_package_import_graph(Path(tablegen.__file__).parent)) == []


def test_cycle_finder_finds_a_cycle():
    graph = {"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}
    assert _cycles(graph) == [["a", "b", "c", "a"]]
    assert _cycles({"a": {"b"}, "b": set()}) == []


def test_slave_and_runner_reach_the_package_by_plain_imports():
    """The FMU slave imports the package with import statements (the build points them at the
    bundled copy), the effects import their models the same way, and the runner imports the
    FMU builder from the package: no module loaded by a string name or a file path, so a reader
    and a structure tool can follow the FMU into the physics."""
    import ast
    from pathlib import Path

    import build_fmu
    from railcontact import fmu_build, run

    slave = Path(rc.__file__).parents[1] / "WheelRailContact.py"
    imported = set()
    for node in ast.walk(ast.parse(slave.read_text(encoding="utf-8"))):
        if isinstance(node, ast.ImportFrom) and node.module == "railcontact":
            imported.update(f"railcontact.{a.name}" for a in node.names)
    assert {"railcontact.effects", "railcontact.scene"} <= imported
    effects_dir = Path(rc.__file__).parent / "effects"
    for path in (slave, *sorted(effects_dir.glob("*.py")), Path(rc.__file__).parent / "run.py"):
        text = path.read_text(encoding="utf-8")
        assert "import_module" not in text and "spec_from_file_location" not in text, path
    assert run.fmu_build is fmu_build and build_fmu.build is fmu_build.build
    assert fmu_build.SLAVE == slave.resolve()


def _private_reads(path, package_dir):
    """(line, text) of every private name another module of the package is read for in
    ``path``: ``from .mod import _name`` (unless ``_name`` is itself a module) and
    ``alias._name`` where ``alias`` is an imported package module."""
    import ast

    tree = ast.parse(path.read_text())
    modules = {p.stem for p in package_dir.rglob("*.py")} | {
        p.name for p in package_dir.rglob("*") if p.is_dir()}
    aliases, found = set(), []
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and (node.level or (node.module or "").startswith(
                "railcontact")):
            for a in node.names:
                if a.name in modules:
                    aliases.add(a.asname or a.name)
                elif a.name.startswith("_") and not a.name.startswith("__"):
                    found.append((node.lineno, f"from {node.module} import {a.name}"))
        elif isinstance(node, ast.Import):
            for a in node.names:
                if a.name.startswith("railcontact") and a.asname:
                    aliases.add(a.asname)
    for node in ast.walk(tree):
        if (isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name)
                and node.value.id in aliases and node.attr.startswith("_")
                and not node.attr.startswith("__")):
            found.append((node.lineno, f"{node.value.id}.{node.attr}"))
    return found


def test_no_module_reads_another_modules_private_names():
    """One source per formula, read through public names: private names stay in their
    module (private *modules*, such as ``_floats``, offer public names to the package)."""
    from pathlib import Path

    package_dir = Path(rc.__file__).parent
    bad = {str(p.relative_to(package_dir)): _private_reads(p, package_dir)
           for p in package_dir.rglob("*.py")}
    assert {k: v for k, v in bad.items() if v} == {}


def test_private_read_finder_finds_one(tmp_path):
    (tmp_path / "a.py").write_text("from . import b\nfrom .b import _hidden\nx = b._other\n")
    (tmp_path / "b.py").write_text("_hidden = 1\n_other = 2\n")
    found = _private_reads(tmp_path / "a.py", tmp_path)
    assert [t for _, t in found] == ["from b import _hidden", "b._other"]
