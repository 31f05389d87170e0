"""The table specs by name: the built-in ones of :mod:`tablegen.specs` and any registered later.

Kept apart from :mod:`tablegen.spec` (the dataclasses) and :mod:`tablegen.specs` (the
instances) so that the imports run one way: spec <- specs <- registry.
"""

from __future__ import annotations

from .spec import TableSpec
from .specs import SPECS

REGISTRY: dict[str, TableSpec] = {}


def register(spec):
    """Add a spec to :data:`REGISTRY` (name must be new) and return it."""
    if spec.name in REGISTRY:
        raise ValueError(f"table spec {spec.name!r} is already registered")
    REGISTRY[spec.name] = spec
    return spec


for _spec in SPECS:
    register(_spec)


def get_spec(name):
    """The registered spec ``name`` (ValueError listing the known names otherwise)."""
    if name not in REGISTRY:
        raise ValueError(f"table name must be one of {sorted(REGISTRY)}; got {name!r}")
    return REGISTRY[name]
