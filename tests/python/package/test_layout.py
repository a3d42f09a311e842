"""The package's shape: subpackages import only from lower layers, no module imports another's private
names, no import cycle, and the tests mirror the layout. Read from the source with ast (nothing imported for
the structural checks)."""

import ast
from pathlib import Path

import graspmix

ROOT = Path(graspmix.__file__).resolve().parent
# Lower number = lower layer. A subpackage imports from itself, from lower layers and from the C++ core;
# sim and viz are peers that do not import each other. The package's __init__ (the facade) may import
# anything, and nothing in a subpackage imports it.
LAYERS = {"io": 0, "perception": 1, "model": 2, "sim": 3, "viz": 3, "experiment": 4, "clutter": 5, "cli": 6}
FACADE = {"graspmix"}


def _modules():
    """module name -> (path, is package __init__)"""
    out = {}
    for p in sorted(ROOT.rglob("*.py")):
        parts = list(p.relative_to(ROOT.parent).with_suffix("").parts)
        is_pkg = parts[-1] == "__init__"
        if is_pkg:
            parts = parts[:-1]
        out[".".join(parts)] = (p, is_pkg)
    return out


MODULES = _modules()


def _imports(name):
    """(target module, imported name or None, line) of every import in a module, relative ones resolved."""
    path, is_pkg = MODULES[name]
    package = name if is_pkg else name.rpartition(".")[0]
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            for a in node.names:
                yield a.name, None, node.lineno
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")
                base = base[: len(base) - (node.level - 1)]
                module = ".".join(base + ([node.module] if node.module else []))
            else:
                module = node.module
            for a in node.names:
                sub = f"{module}.{a.name}"
                # `from pkg import submodule` imports the submodule.
                is_module = sub in MODULES or sub == "graspmix._core"
                yield (sub, None, node.lineno) if is_module else (module, a.name, node.lineno)


def _layer(module):
    parts = module.split(".")
    return parts[1] if len(parts) > 1 and parts[1] in LAYERS else None


def test_every_subpackage_is_in_the_layer_table():
    found = {m.split(".")[1] for m in MODULES if m.count(".") >= 1 and MODULES[m][1]}
    assert found == set(LAYERS)


def test_no_import_runs_from_a_lower_layer_to_a_higher_one():
    bad = []
    for name in MODULES:
        own = _layer(name)
        if own is None:
            continue
        for target, _, line in _imports(name):
            if not target.startswith("graspmix") or target == "graspmix._core":
                continue
            if target in FACADE:
                bad.append(f"{name}:{line} imports the facade {target}")
                continue
            other = _layer(target)
            if other is not None and other != own and not LAYERS[other] < LAYERS[own]:
                bad.append(f"{name}:{line} ({own}) imports {target} ({other})")
    assert not bad, "\n".join(bad)


def test_no_module_imports_a_private_name_of_another():
    bad = [
        f"{name}:{line} imports {n} from {target}"
        for name in MODULES
        for target, n, line in _imports(name)
        if target.startswith("graspmix") and n is not None and n.startswith("_") and n != "_core"
    ]
    assert not bad, "\n".join(bad)


def test_no_import_cycle():
    graph = {name: set() for name in MODULES}
    for name in MODULES:
        for target, _, _ in _imports(name):
            if target in MODULES and target != name:
                graph[name].add(target)
    # A package's __init__ gathers its submodules: edges from a submodule to its own package's __init__
    # would be a cycle, and are reported like any other.
    state, stack = {}, []

    def visit(n):
        state[n] = "open"
        stack.append(n)
        for m in sorted(graph[n]):
            if state.get(m) == "open":
                raise AssertionError("import cycle: " + " -> ".join(stack[stack.index(m) :] + [m]))
            if m not in state:
                visit(m)
        stack.pop()
        state[n] = "done"

    for n in sorted(graph):
        if n not in state:
            visit(n)


def test_the_python_tests_mirror_the_package_and_the_cpp_layers():
    """tests/python has a folder per subpackage of graspmix and per C++ layer (src/<layer>), and nothing else."""
    tests = Path(__file__).resolve().parents[1]
    repo = tests.parents[1]
    folders = {p.name for p in tests.iterdir() if p.is_dir() and not p.name.startswith((".", "_"))}
    cpp = {p.name for p in (repo / "src").iterdir() if p.is_dir()}
    expected = set(LAYERS) | cpp | {"package", "fuzz"}  # the package as a whole; the bad-input corpus
    assert folders == expected


def test_files_and_functions_stay_short():
    long_files = [
        f"{n}: {len(p.read_text().splitlines())} lines"
        for n, (p, _) in MODULES.items()
        if len(p.read_text().splitlines()) > 500
    ]
    long_functions = [
        f"{n}.{f.name}: {f.end_lineno - f.lineno + 1} lines"
        for n, (p, _) in MODULES.items()
        for f in ast.walk(ast.parse(p.read_text()))
        if isinstance(f, ast.FunctionDef) and f.end_lineno - f.lineno + 1 > 80
    ]
    assert not long_files and not long_functions, long_files + long_functions
