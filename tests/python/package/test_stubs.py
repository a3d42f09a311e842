"""The committed type stub python/graspmix/_core.pyi (scripts/make_stubs.sh) declares everything the built module
has: every public class and function, and every field of every settings class. A stale stub fails here."""

import ast
import inspect
from pathlib import Path

import graspmix
import pytest
from graspmix import _core

STUB = Path(graspmix.__file__).resolve().parent / "_core.pyi"


def _stub_tree():
    if not STUB.is_file():
        pytest.fail(f"{STUB.name} is missing: run scripts/make_stubs.sh and commit it")
    return ast.parse(STUB.read_text(), filename=str(STUB))


def _top_level(tree):
    classes, functions, others = {}, set(), set()
    for node in tree.body:
        if isinstance(node, ast.ClassDef):
            classes[node.name] = node
        elif isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            functions.add(node.name)
        elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
            others.add(node.target.id)
        elif isinstance(node, ast.Assign):
            others.update(t.id for t in node.targets if isinstance(t, ast.Name))
    return classes, functions, others


def _members(cls_node):
    names = set()
    for node in cls_node.body:
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            names.add(node.name)
        elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
            names.add(node.target.id)
        elif isinstance(node, ast.Assign):
            names.update(t.id for t in node.targets if isinstance(t, ast.Name))
    return names


def test_py_typed_marker_ships_with_the_stub():
    assert (STUB.parent / "py.typed").is_file()


def test_every_public_class_and_function_is_declared():
    classes, functions, others = _top_level(_stub_tree())
    public = [n for n in dir(_core) if not n.startswith("_")]
    missing = []
    for name in public:
        obj = getattr(_core, name)
        if inspect.isclass(obj):
            if name not in classes:
                missing.append(name)
        elif callable(obj):
            if name not in functions:
                missing.append(name)
    assert not missing, f"not in {STUB.name} (run scripts/make_stubs.sh): {missing}"
    extra = (set(classes) | functions) - set(public)
    assert not extra, f"{STUB.name} declares names the module lacks (run scripts/make_stubs.sh): {sorted(extra)}"


def test_every_public_member_of_every_class_is_declared():
    classes, _, _ = _top_level(_stub_tree())
    missing = []
    for name, node in classes.items():
        cls = getattr(_core, name, None)
        if cls is None:
            continue
        declared = _members(node)
        for member in vars(cls):
            if not member.startswith("_") and member not in declared:
                missing.append(f"{name}.{member}")
    assert not missing, f"not in {STUB.name} (run scripts/make_stubs.sh): {missing}"


def test_every_settings_field_is_declared():
    classes, _, _ = _top_level(_stub_tree())
    settings = [n for n in dir(_core) if inspect.isclass(getattr(_core, n)) and hasattr(getattr(_core, n), "_fields")]
    assert len(settings) >= 14
    missing = [
        f"{n}.{f}"
        for n in settings
        for f in getattr(_core, n)._fields
        if n not in classes or f not in _members(classes[n])
    ]
    assert not missing, f"settings fields not in {STUB.name} (run scripts/make_stubs.sh): {missing}"
