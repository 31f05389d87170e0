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
    public = {n for n, v in vars(rc).items()
              if not n.startswith("_") and not isinstance(v, types.ModuleType)
              and callable(v) and n != "check_range"}
    assert public <= set(rc.__all__), sorted(public - set(rc.__all__))


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
