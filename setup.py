"""Build hook of the wheel: the table kernels compiled ahead of time into the package.

The metadata is in pyproject.toml. A wheel (``pip install .``, ``pip wheel .``, ``python -m
build``) also gets the extension module ``railcontact/_aot_kernels`` that
:func:`railcontact._compiled.build_aot` makes from the numba source of the kernels (the FMU
build's helper, ``numba.pycc``, generic code for the architecture), so a user's first
exact-table or modified-strip call imports no numba and compiles nothing. Where that fails (no
C compiler or no Python headers on the building machine), the build goes on without it and
says so: the package then compiles the kernels just in time on first use, with numba, and
caches them (docs/performance.md). ``RAILCONTACT_NO_AOT=1`` skips the step (a pure wheel).
Editable installs never get it: their kernels follow the sources being edited.
"""

import os
import sys
import tempfile
from pathlib import Path

from setuptools import setup
from setuptools.command.build_py import build_py
from setuptools.dist import Distribution

ROOT = Path(__file__).resolve().parent
AOT = os.environ.get("RAILCONTACT_NO_AOT", "") in ("", "0")


class BuildPyWithKernels(build_py):
    """build_py, then the ahead-of-time kernels into the built package."""

    def run(self):
        super().run()
        target = Path(self.build_lib) / "railcontact"
        for stale in target.glob("_aot_kernels.*"):   # (an earlier build's, left in build/)
            stale.unlink()
        if not AOT or getattr(self, "editable_mode", False):
            return
        with tempfile.TemporaryDirectory(prefix="railcontact-aot-") as cache:
            # numba compiles the kernels' callees on the way: keep its cache out of the
            # builder's user cache
            os.environ["RAILCONTACT_CACHE_DIR"] = cache
            sys.path.insert(0, str(ROOT / "fmu_src"))
            try:
                from railcontact import _compiled
            finally:
                sys.path.pop(0)
            message = _compiled.build_aot(target, batches=True)
        print(f"railcontact: {message}", file=sys.stderr)


class PlatformDistribution(Distribution):
    """A platform wheel (cpXY-cpXY-<platform>): it holds a compiled module."""

    def has_ext_modules(self):
        return AOT


setup(cmdclass={"build_py": BuildPyWithKernels}, distclass=PlatformDistribution)
