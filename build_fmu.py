#!/usr/bin/env python
"""Build ``WheelRailContact.fmu``: ``python build_fmu.py [--dest DIR] [--no-validate]
[--contacts K]`` (K = 1-32 contacts per instance; K > 1 builds
``WheelRailContact_<K>contacts.fmu``, variables ``name[k]``).

The command line of :mod:`railcontact.fmu_build` (the builder lives in the package, so that
``railcontact.run`` imports it normally); the names below are re-exported for scripts that
``import build_fmu``.
"""

import sys
from pathlib import Path

_PACKAGE_PARENT = str(Path(__file__).resolve().parent / "fmu_src")
if _PACKAGE_PARENT not in sys.path:     # the checkout's package, also when not installed
    sys.path.insert(0, _PACKAGE_PARENT)

from railcontact.fmu_build import (MAX_CONTACTS, MODEL_NAME, ROOT,  # noqa: E402,F401
                                   build, bundle_names, cached_build, check_contacts, fmu_digest,
                                   fmu_file_name, main, source_hash)

if __name__ == "__main__":
    sys.exit(main())
