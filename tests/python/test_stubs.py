"""The type stubs and docstrings describe the whole module, so that help() and an editor's
completion explain every call."""

import ast
import inspect
from pathlib import Path

import omninav
from omninav import _omninav

STUBS = Path(omninav.__file__).with_name("__init__.pyi")


def public(namespace):
    return {name for name in dir(namespace) if not name.startswith("_")}


def test_the_package_exports_the_whole_module():
    assert public(_omninav) <= set(omninav.__all__)


def test_the_stubs_declare_every_class_function_and_member():
    tree = ast.parse(STUBS.read_text())
    declared = {}
    for node in tree.body:
        if isinstance(node, ast.ClassDef):
            members = set()
            for item in node.body:
                if isinstance(item, ast.FunctionDef):
                    members.add(item.name)
                elif isinstance(item, ast.AnnAssign):
                    members.add(item.target.id)
            declared[node.name] = members
        elif isinstance(node, ast.FunctionDef):
            declared[node.name] = set()
    assert public(_omninav) <= set(declared), "module names missing from the stubs"
    for name in public(_omninav):
        thing = getattr(_omninav, name)
        if inspect.isclass(thing) and not issubclass(thing, Exception):
            missing = public(thing) - declared[name]
            assert not missing, f"{name}: {sorted(missing)} missing from the stubs"


def test_every_class_and_function_has_a_docstring():
    for name in public(_omninav):
        thing = getattr(_omninav, name)
        assert (thing.__doc__ or "").strip(), f"{name} has no docstring"
