"""The layout shows the layers: no import cycles between crankgen's modules, counting the imports
inside functions as well as those at module level; no hand-written module over 600 lines; a
package root that holds the public API and little else.

The import graph is built here from the source with `ast`: an edge from a module to every module
of the package it imports (`import crankgen.x`, `from .x import y`, `from . import x`, at any
depth of the code), a package's __init__ counting as a module; an import of one of a module's own
ancestor packages is no edge (Python imports those first, whatever the module does)."""

import ast
from pathlib import Path

import crankgen

ROOT = Path(crankgen.__file__).resolve().parent
MAX_LINES = 600
MAX_ROOT_MODULES = 12


def modules(root=ROOT, package="crankgen"):
    """{dotted name: (path, is a package's __init__)} of the package's hand-written modules (the
    generated kernels, installed as crankgen._generated, and the derivation are not its source)."""
    out = {}
    for path in sorted(root.rglob("*.py")):
        parts = path.relative_to(root).with_suffix("").parts
        if parts[0].startswith("_") and parts[0] != "__init__" and parts[0] != "__main__":
            continue                                    # _generated, _derive: not crankgen's hand-written runtime
        init = parts[-1] == "__init__"
        name = ".".join((package,) + (parts[:-1] if init else parts))
        out[name] = (path, init)
    return out


def _resolve(module, init, level, target):
    base = module.split(".") if init else module.split(".")[:-1]
    if level > 1:
        base = base[:len(base) - (level - 1)]
    return ".".join(base + ([target] if target else []))


def import_graph(mods):
    """{module: {modules it imports}} (module docstring)."""
    graph = {name: set() for name in mods}
    for name, (path, init) in mods.items():
        for node in ast.walk(ast.parse(path.read_text())):
            targets = []
            if isinstance(node, ast.Import):
                targets = [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom):
                base = _resolve(name, init, node.level, node.module) if node.level else (node.module or "")
                subs = [f"{base}.{a.name}" for a in node.names if f"{base}.{a.name}" in mods]
                ancestor = name.startswith(base + ".") or base == "crankgen"
                targets = subs + ([] if ancestor or len(subs) == len(node.names) else [base])
            for target in targets:
                parts = target.split(".")
                while parts and ".".join(parts) not in mods:
                    parts.pop()
                hit = ".".join(parts)
                if parts and hit != name and not name.startswith(hit + "."):
                    graph[name].add(hit)
    return graph


def cycles(graph):
    """The strongly connected components of more than one module (Tarjan), each sorted."""
    index, low, stack, on, out = {}, {}, [], set(), []
    counter = [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in sorted(graph[v]):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                out.append(sorted(component))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return out


def test_no_module_imports_one_that_imports_it_back():
    graph = import_graph(modules())
    assert cycles(graph) == []


def test_the_cycle_search_finds_a_cycle_through_a_deferred_import(tmp_path):
    """The scan can fail: two modules that import each other, one of them inside a function."""
    pkg = tmp_path / "crankgen"
    (pkg / "sub").mkdir(parents=True)
    (pkg / "__init__.py").write_text("")
    (pkg / "sub" / "__init__.py").write_text("")
    (pkg / "a.py").write_text("from .sub import b\n")
    (pkg / "sub" / "b.py").write_text("def f():\n    from ..a import g\n")
    (pkg / "c.py").write_text("import crankgen.a\n")
    found = cycles(import_graph(modules(pkg)))
    assert found == [["crankgen.a", "crankgen.sub.b"]]


def test_no_hand_written_module_is_over_600_lines():
    long = {name: n for name, (path, _) in modules().items() if (n := len(path.read_text().splitlines())) > MAX_LINES}
    assert long == {}


def test_the_package_root_holds_the_public_api_and_little_else():
    root = [p.name for p in ROOT.glob("*.py")]
    assert len(root) <= MAX_ROOT_MODULES, sorted(root)
    layers = {p.name for p in ROOT.iterdir() if p.is_dir() and (p / "__init__.py").exists()}
    assert {"declaration", "discrete", "engine", "analyses", "results", "plots", "cli", "experiments"} <= layers
