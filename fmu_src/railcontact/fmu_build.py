r"""Build ``WheelRailContact.fmu`` (FMI 2.0 co-simulation, PythonFMU) from a source checkout.

Usage (the command line is the thin script ``build_fmu.py`` at the top of the checkout)::

    python build_fmu.py [--dest DIR] [--no-validate] [--contacts K]

or from Python: ``from railcontact.fmu_build import build; build(dest)``

``--contacts K`` (1-32, default 1) builds a vehicle FMU, ``WheelRailContact_<K>contacts.fmu``:
one instance serves K contacts of one scene, its inputs and outputs are ``name[k]``, k = 1..K
(FMI 2.0 structured naming), its parameters those of the single-contact FMU, and every step
evaluates all K contacts together (:class:`railcontact.effects.Vehicle`). K = 1 is the
single-contact ``WheelRailContact.fmu`` with its plain names.
(:mod:`railcontact.run` builds the FMU this way when the sources changed).

Sources: the slave script ``fmu_src/WheelRailContact.py`` beside this package, the package
itself, ``tables/*.nc`` and ``examples/scenes/`` of the checkout (:data:`ROOT`, two levels
above this package; an installed copy of ``railcontact`` without the checkout cannot build,
:func:`build` says so: use a prebuilt FMU there).

What goes into the FMU (``resources/``):

* the slave script ``fmu_src/WheelRailContact.py``, saved as ``wheelrailcontact_<hash>.py``
  (its plain ``railcontact`` imports rewritten to the bundled name);
* a copy of the ``railcontact`` package renamed ``wheelrailcontact_<hash>_railcontact``
  (absolute ``railcontact`` imports inside it rewritten), so that two PythonFMU FMUs, or an
  FMU and the host's own ``railcontact``, never share a module in one Python process.
  PythonFMU puts ``resources/`` at the front of ``sys.path`` and imports the module named in
  ``resources/slavemodule.txt`` (the script's stem); Python caches modules by name, so a
  second FMU bundling a module of the same name would silently get the first one's copy.
  ``<hash>`` is a digest of everything bundled, so two different builds never collide and two
  identical builds share a module harmlessly;
* the tables ``tables/*.nc`` (inside the package copy, where
  :func:`railcontact.tables.default_table_path` finds them) and the scenes
  ``examples/scenes/*.toml`` (``resources/scenes/``, selectable by name via ``scene_file``)
  with the data files they name (``examples/scenes/*.csv``, e.g. a roughness profile; a scene's
  relative file names resolve against ``resources/scenes/``);
* the extension module ``_aot_kernels`` inside the package copy: the kernels the table scenes
  call per step compiled ahead of time from their numba source (:mod:`railcontact._compiled`;
  skipped with a message where no C compiler is found, and with ``--no-aot``);
* ``requirements.txt`` for the host interpreter (PythonFMU FMUs run in the host's Python,
  which needs numpy and scipy; numba and netCDF4 for the table source).

After building, the model description is checked with :func:`fmpy.validation.validate_fmu`
(the build fails on any problem) and the bundle is imported in a fresh interpreter in which
``import railcontact`` is blocked (the build fails if the copy still refers to the original).
"""

from __future__ import annotations

import argparse
import fnmatch
import hashlib
import os
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

__all__ = ["build", "source_hash", "bundle_names", "fmu_digest", "main", "MODEL_NAME", "ROOT",
           "MAX_CONTACTS", "check_contacts", "fmu_file_name", "up_to_date_fmu", "cached_build"]

#: The source checkout: the package lives in ``<ROOT>/fmu_src/railcontact``.
ROOT = Path(__file__).resolve().parents[2]
PACKAGE = Path(__file__).resolve().parent
SLAVE = PACKAGE.parent / "WheelRailContact.py"
TABLES = ROOT / "tables"
SCENES = ROOT / "examples" / "scenes"
MODEL_NAME = "WheelRailContact"
#: The range of ``--contacts`` (railcontact.effects.MAX_CONTACTS).
MAX_CONTACTS = 32
REQUIREMENTS = "numpy>=1.26\nscipy>=1.13\nnumba>=0.59\nnetCDF4>=1.6\n"

#: Files of the package not copied into the FMU: caches, the ahead-of-time module (built for
#: it), and the correction table of Polach's law, which no scene takes (its falling-friction
#: scene has the smooth law (5.16); the table is for the Python API).
NOT_IN_FMU = ("__pycache__", "*.pyc", "*.pyo", "_aot_kernels.*", "falling_correction_polach.nc")
_IGNORE = shutil.ignore_patterns(*NOT_IN_FMU)


def _check_sources():
    """The slave script and the checkout's tables and scenes must be there."""
    missing = [p for p in (SLAVE, TABLES, SCENES) if not p.exists()]
    if missing:
        raise FileNotFoundError(
            f"cannot build the FMU: {', '.join(str(p) for p in missing)} not found (the FMU is "
            "built from a source checkout of railcontact; use a prebuilt WheelRailContact.fmu, "
            "e.g. python -m railcontact.run --fmu PATH)")


def _bundled_files():
    _check_sources()
    files = [SLAVE]
    files += sorted(p for p in PACKAGE.rglob("*") if p.is_file() and not any(
        fnmatch.fnmatch(part, pattern) for part in p.relative_to(PACKAGE).parts
        for pattern in NOT_IN_FMU))
    files += sorted(TABLES.glob("*.nc")) + sorted(SCENES.glob("*.toml"))
    files += sorted(SCENES.glob("*.csv"))          # data files the scenes name (profiles)
    return files


def check_contacts(contacts):
    """``contacts`` as an int if it is an integer in [1, :data:`MAX_CONTACTS`], else a
    ValueError saying so (before any work)."""
    if isinstance(contacts, bool) or not isinstance(contacts, int) \
            or not 1 <= contacts <= MAX_CONTACTS:
        raise ValueError(f"contacts (the number of wheel/rail contacts one FMU instance "
                         f"serves) must be an integer in [1, {MAX_CONTACTS}]; got {contacts!r}")
    return contacts


def fmu_file_name(contacts=1):
    """``WheelRailContact.fmu`` (one contact) or ``WheelRailContact_<K>contacts.fmu``."""
    return f"{MODEL_NAME}.fmu" if contacts == 1 else f"{MODEL_NAME}_{contacts}contacts.fmu"


def source_hash(contacts=1):
    """Digest (12 hex digits) of everything the FMU bundles (and of the number of contacts,
    when not 1); names the bundled modules."""
    digest = hashlib.sha256()
    if contacts != 1:
        digest.update(f"contacts={contacts}\0".encode())
    for path in _bundled_files():
        digest.update(str(path.relative_to(ROOT)).encode())
        digest.update(b"\0")
        digest.update(path.read_bytes())
        digest.update(b"\0")
    digest.update(REQUIREMENTS.encode())
    return digest.hexdigest()[:12]


def bundle_names(digest=None):
    """(script module name, package name) used inside the FMU for this source state."""
    digest = digest or source_hash()
    return f"wheelrailcontact_{digest}", f"wheelrailcontact_{digest}_railcontact"


_IMPORT_RE = re.compile(r"^(\s*)(from|import)(\s+)railcontact(?=[\s.])", re.MULTILINE)


def _rewrite_imports(path, text, package_name):
    """``text`` with its absolute ``railcontact`` imports pointed at ``package_name``."""
    new = _IMPORT_RE.sub(lambda m: f"{m[1]}{m[2]}{m[3]}{package_name}", text)
    if re.search(r"^\s*import\s+" + package_name + r"\s*$", new, re.MULTILINE):
        raise RuntimeError(f"{path}: 'import railcontact' (bare) cannot be rewritten; use "
                           "'import railcontact as name', 'from railcontact import ...' or "
                           "relative imports inside the package")
    return new


def _rewrite_package(directory, package_name):
    """Point absolute ``railcontact`` imports in the copied package at its bundled name."""
    for path in directory.rglob("*.py"):
        text = path.read_text(encoding="utf-8")
        new = _rewrite_imports(path, text, package_name)
        if new != text:
            path.write_text(new, encoding="utf-8")


_CONTACTS_RE = re.compile(r"^CONTACTS = 1$", re.MULTILINE)


def _stage(stage, digest, aot=True, log=None, contacts=1):
    module_name, package_name = bundle_names(digest)
    script = stage / f"{module_name}.py"
    text = SLAVE.read_text(encoding="utf-8")
    new = _rewrite_imports(SLAVE, text, package_name)
    if new == text:
        raise RuntimeError(f"{SLAVE}: no 'railcontact' import for the build to rewrite")
    new, found = _CONTACTS_RE.subn(f"CONTACTS = {contacts}", new)
    if found != 1:
        raise RuntimeError(f"{SLAVE}: no line 'CONTACTS = 1' for the build to set")
    script.write_text(new, encoding="utf-8")
    shutil.copytree(PACKAGE, stage / package_name, ignore=_IGNORE)
    _rewrite_package(stage / package_name, package_name)
    if aot:
        # the kernels a table scene calls per step, compiled ahead of time from the same
        # source (railcontact._compiled): the scene then imports no numba
        from . import _compiled  # noqa: PLC0415

        # (a vehicle FMU's step is one batch call on the table summed over nu: that kernel too)
        message = _compiled.build_aot(stage / package_name, batches=(
            ("creep_table_batch_nu",) if contacts > 1 else ()))
        if log is not None:
            log(message)
    # tables inside the package copy: railcontact.tables.default_table_path looks there
    (stage / package_name / "tables").mkdir(exist_ok=True)
    for table in TABLES.glob("*.nc"):
        shutil.copy2(table, stage / package_name / "tables")
    (stage / "scenes").mkdir()
    for scene in SCENES.glob("*.toml"):
        shutil.copy2(scene, stage / "scenes")
    for data in SCENES.glob("*.csv"):       # files the scenes name, relative to themselves
        shutil.copy2(data, stage / "scenes")
    (stage / "requirements.txt").write_text(REQUIREMENTS)
    project_files = [stage / package_name, stage / "scenes",
                     stage / "requirements.txt"]
    return script, project_files


_ISOLATION_CHECK = r"""
import sys, importlib, importlib.abc
from pathlib import Path
class Block(importlib.abc.MetaPathFinder):
    def find_spec(self, name, path=None, target=None):
        if name == "railcontact" or name.startswith("railcontact."):
            raise ImportError("railcontact must not be imported by the bundled FMU code")
sys.meta_path.insert(0, Block())
sys.path.insert(0, sys.argv[1])
module = importlib.import_module(sys.argv[2])
slave = module.WheelRailContact(instance_name="check", resources=sys.argv[1])
# every bundled scene (and the parameters' default one) initialised and stepped once in
# contact: the data files and lazily imported modules come from the bundle too
# (a vehicle FMU: the default scene with its K contacts, the others with one -- what is
# checked here is where the code comes from, and K contacts would cost K times the time)
contacts = module.CONTACTS
for scene in [""] + sorted(p.stem for p in (Path(sys.argv[1]) / "scenes").glob("*.toml")):
    module.CONTACTS = contacts if scene == "" else 1
    slave = module.WheelRailContact(instance_name="check", resources=sys.argv[1])
    slave.scene_file = scene
    slave.enter_initialization_mode()
    slave.exit_initialization_mode()
    setters = {v.name: v.setter for v in slave.vars.values() if v.setter is not None}
    for name, value in (("normal_force", 8e4), ("creepage_longitudinal", 1e-3),
                        ("creepage_lateral", 1e-4), ("spin", 0.05), ("rolling_speed", 30.0),
                        ("rail_position", 0.01)):
        for var, setter in setters.items():     # (a vehicle: name[1] ... name[K])
            if var.split("[")[0] == name:
                setter(value)
    slave.do_step(0.0, 1e-3)
    slave.do_step(1e-3, 1e-3)
assert not any(m == "railcontact" or m.startswith("railcontact.") for m in sys.modules)
"""


def _check_isolation(stage, digest):
    module_name, _ = bundle_names(digest)
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    proc = subprocess.run([sys.executable, "-c", _ISOLATION_CHECK, str(stage), module_name],
                          capture_output=True, text=True, env=env, cwd=stage)
    if proc.returncode != 0:
        raise RuntimeError("the bundled copy of railcontact is not self-contained:\n"
                           + proc.stderr[-3000:])


def build(dest=ROOT, validate=True, aot=True, log=None, contacts=1):
    """Build ``WheelRailContact.fmu`` (or, for ``contacts`` > 1, the vehicle FMU
    ``WheelRailContact_<K>contacts.fmu``) into ``dest`` and return its path.

    Parameters
    ----------
    dest : path-like
        Output directory (created if needed).
    validate : bool
        Run :func:`fmpy.validation.validate_fmu` and the isolation check (default True).
    aot : bool
        Compile the kernels the table scenes call per step ahead of time into the bundled
        package (:func:`railcontact._compiled.build_aot`: about 20 s; needs a C compiler, else
        the FMU loads numba's kernels at run time). Default True.
    log : callable, optional
        Called with a line saying whether the kernels were compiled ahead of time.
    contacts : int
        Number of contacts one instance serves, 1-32 (checked first); default 1.

    Raises
    ------
    FileNotFoundError
        If the checkout's slave script, tables or scenes are missing (an installed copy).
    RuntimeError
        If the bundle is not self-contained or the model description has problems.
    """
    check_contacts(contacts)
    from pythonfmu.builder import FmuBuilder

    dest = Path(dest)
    dest.mkdir(parents=True, exist_ok=True)
    digest = source_hash(contacts)
    target = dest / fmu_file_name(contacts)
    with tempfile.TemporaryDirectory(prefix="wrc_build_") as tmp:
        stage = Path(tmp)
        script, project_files = _stage(stage, digest, aot, log, contacts)
        if validate:
            _check_isolation(stage, digest)
        # a private folder beside the target: pythonfmu < 0.7 takes ``dest`` as a folder only,
        # 0.7 also as a file name; both return the path of the FMU they wrote
        partial_dir = dest / f".{MODEL_NAME}.{os.getpid()}.build"
        try:
            try:
                partial = Path(FmuBuilder.build_FMU(
                    script, dest=partial_dir, project_files=project_files,
                    canGetAndSetFMUstate=True, canSerializeFMUstate=True))
            finally:
                module_name, package_name = bundle_names(digest)
                for name in [m for m in sys.modules
                             if m == module_name or m.split(".")[0] == package_name]:
                    del sys.modules[name]
                if str(stage) in sys.path:
                    sys.path.remove(str(stage))
            _add_bytecode(partial, stage)
            if validate:
                from fmpy.validation import validate_fmu
                problems = validate_fmu(str(partial))
                if problems:
                    raise RuntimeError("fmpy validate found problems in the model description:\n"
                                       + "\n".join(problems))
            os.replace(partial, target)
        finally:
            shutil.rmtree(partial_dir, ignore_errors=True)
    return target


def _add_bytecode(fmu, stage):
    """Add the bundled package's compiled modules (``__pycache__/*.pyc`` of this interpreter,
    checked against their source by hash, not by time) to the FMU's resources.

    An importer extracts the FMU into a new directory for each run and Python would compile
    every bundled module from source in each such process (about 0.2-0.3 s of a vehicle FMU's
    initialisation, 2026-11-28); pythonfmu's builder leaves ``__pycache__`` out. Python checks
    such a file against its source's hash (PEP 552), so it is used only while it matches,
    whatever the extraction's file times; another Python version ignores it."""
    import importlib.util  # noqa: PLC0415
    import py_compile  # noqa: PLC0415
    import zipfile  # noqa: PLC0415

    with tempfile.TemporaryDirectory(prefix="wrc_pyc_") as tmp, \
            zipfile.ZipFile(fmu, "a", compression=zipfile.ZIP_DEFLATED) as zf:
        names = set(zf.namelist())
        for source in sorted(stage.rglob("*.py")):
            relative = source.relative_to(stage)
            cached = Path(importlib.util.cache_from_source(str(relative)))
            arcname = (Path("resources") / cached).as_posix()
            if (Path("resources") / relative).as_posix() not in names or arcname in names:
                continue
            out = Path(tmp) / cached
            py_compile.compile(str(source), cfile=str(out), dfile=str(relative), doraise=True,
                               invalidation_mode=py_compile.PycInvalidationMode.CHECKED_HASH)
            zf.write(out, arcname)


def up_to_date_fmu(contacts=1, dest=ROOT, verbose=True):
    """Path of the FMU for ``contacts`` contacts in ``dest`` (:func:`fmu_file_name`), built
    first if it is missing or was built from other sources (:func:`fmu_digest`)."""
    check_contacts(contacts)
    target = Path(dest) / fmu_file_name(contacts)
    if not target.is_file() or fmu_digest(target) != source_hash(contacts):
        if verbose:
            print(f"building {target.name} (sources changed or FMU missing) ...", flush=True)
        build(dest, contacts=contacts)
    return target


def cached_build(contacts=1, verbose=False):
    """Path of the FMU for ``contacts`` contacts built from the current sources, built once per
    source state and environment (the tests' and benchmarks' cache).

    Built by ``build_fmu.py --dest`` into ``$TMPDIR/railcontact-test-fmu-<source hash>-<env>``
    and reused while the sources and the environment are unchanged. Keyed by the environment
    too: an FMU built with another pythonfmu carries that release's native library, which
    crashes (a segmentation fault in fmi2ExitInitializationMode) when it calls this
    environment's pythonfmu. Several processes may build at once: the first to finish wins."""
    from importlib.metadata import version  # noqa: PLC0415

    env_key = hashlib.sha256(f"{sys.prefix}|{sys.version}|{version('pythonfmu')}".encode())
    dest = Path(tempfile.gettempdir()) / (
        f"railcontact-test-fmu-{source_hash(contacts)}-{env_key.hexdigest()[:8]}")
    path = dest / fmu_file_name(contacts)
    if not path.is_file():
        work = Path(tempfile.mkdtemp(prefix="railcontact-test-fmu-build-"))
        if verbose:
            print(f"building {path.name} ...", flush=True)
        subprocess.run([sys.executable, str(ROOT / "build_fmu.py"), "--dest", str(work),
                        "--contacts", str(contacts)], check=True, capture_output=True,
                       text=True)
        try:
            os.rename(work, dest)
        except OSError:  # another process finished the same build first
            pass
    if not path.is_file():
        raise FileNotFoundError(f"the FMU build left no {path}")
    return path


def fmu_digest(path):
    """The source digest a built FMU was made from (None if it is not one of ours)."""
    import zipfile
    try:
        with zipfile.ZipFile(path) as zf:
            name = zf.read("resources/slavemodule.txt").decode().strip()
    except (OSError, KeyError, zipfile.BadZipFile):
        return None
    prefix = "wheelrailcontact_"
    return name[len(prefix):] if name.startswith(prefix) else None


def main(argv=None):
    parser = argparse.ArgumentParser(prog="build_fmu.py",
                                     description=__doc__.split("\n\n")[0])
    parser.add_argument("--dest", default=str(ROOT), help="output directory (default: repo)")
    parser.add_argument("--no-validate", action="store_true",
                        help="skip the fmpy validation and the isolation check")
    parser.add_argument("--no-aot", action="store_true",
                        help="do not compile the table kernels ahead of time (the FMU then "
                             "imports numba in its table scenes)")
    parser.add_argument("--contacts", default="1", metavar="K",
                        help=f"contacts one instance serves, 1-{MAX_CONTACTS} (default 1: "
                             "WheelRailContact.fmu; K > 1: WheelRailContact_<K>contacts.fmu "
                             "with variables name[k])")
    args = parser.parse_args(argv)
    try:
        contacts = check_contacts(int(args.contacts))
    except ValueError:
        parser.error(f"--contacts must be an integer in [1, {MAX_CONTACTS}]; got "
                     f"{args.contacts!r}")
    path = build(args.dest, validate=not args.no_validate, aot=not args.no_aot, log=print,
                 contacts=contacts)
    print(path)
    return 0

