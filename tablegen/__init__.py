"""tablegen: build the smooth (C2) railcontact lookup tables in parallel (dask) as CF netCDF.

``python -m tablegen build [--only NAME] [--resolution R] [--scheduler ADDRESS]`` writes
``./tables-build/`` (never the shipped ``tables/`` unless ``--replace-shipped``); a dask
cluster's workers must be able to import tablegen and railcontact. The readers are in
:mod:`railcontact.tables` (the FMU ships only railcontact).
"""

from .registry import REGISTRY, get_spec, register  # noqa: F401
from .spec import Axis, TableSpec, Variable  # noqa: F401
from .build import build_table  # noqa: F401
