"""The import graph of one of this repository's Python packages, read from the source
(nothing is imported), for the structure tests of the tool and of the course build."""

from __future__ import annotations

import ast
from functools import cache
from pathlib import Path

from repository import ROOT

# A module longer than this says in its docstring why it is ("over 500 lines").
LONG = 500


@cache
def modules(package: str) -> dict[str, tuple[Path, ast.Module]]:
    """Module name -> (file, parsed source), for every module of the package folder."""
    found = {}
    for path in sorted((ROOT / package).rglob("*.py")):
        if "__pycache__" in path.parts:
            continue
        parts = path.relative_to(ROOT).with_suffix("").parts
        name = ".".join(parts[:-1] if parts[-1] == "__init__" else parts)
        found[name] = (path, ast.parse(path.read_bytes(), str(path)))
    return found


def base_of(module: str, path: Path, node: ast.ImportFrom) -> str:
    """The absolute name an ImportFrom imports from."""
    if not node.level:
        return node.module or ""
    package = module if path.name == "__init__.py" else module.rpartition(".")[0]
    parts = package.split(".")
    up = parts[: len(parts) - node.level + 1]
    return ".".join(up + ([node.module] if node.module else []))


def imported(package: str, module: str) -> set[str]:
    """Every name `module` imports (anywhere in the file), absolute: modules and, for
    `from x import y`, both x and x.y."""
    path, tree = modules(package)[module]
    found = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            base = base_of(module, path, node)
            found.add(base)
            found.update(f"{base}.{a.name}" for a in node.names)
        elif isinstance(node, ast.Import):
            found.update(a.name for a in node.names)
    return found


def imports(package: str, also: tuple[str, ...] = ()) -> dict[str, set[str]]:
    """Module -> the package's modules it imports, and any module under the top-level
    names in `also`."""
    names = set(modules(package))
    return {m: {i for i in imported(package, m)
                if (i in names and i != m) or i.split(".")[0] in also}
            for m in names}


def dependency_graph(package: str) -> dict[str, set[str]]:
    """Module -> the package's modules it depends on. A package's __init__ runs before its
    modules, but is not a dependency of theirs: `from .findings import x` inside
    sw2sim.check depends on sw2sim.check.findings only."""
    return {m: {i for i in found if not m.startswith(i + ".")}
            for m, found in imports(package).items()}


def find_cycle(graph: dict[str, set[str]]) -> list[str] | None:
    """One import cycle of the graph, as the path that closes it, or None."""
    state: dict[str, int] = {}

    def visit(node, path):
        state[node] = 1
        for nxt in sorted(graph.get(node, ())):
            if state.get(nxt) == 1:
                return path + [nxt]
            if nxt not in state:
                found = visit(nxt, path + [nxt])
                if found:
                    return found
        state[node] = 2
        return None

    for module in sorted(graph):
        if module not in state:
            found = visit(module, [module])
            if found:
                return found
    return None


def private_imports(package: str) -> list[str]:
    """Where a module of the package uses a private name of another module."""
    known = modules(package)
    offenders = []
    for module, (path, tree) in known.items():
        aliases = set()   # names bound to the package's modules: `from . import x`, `import a.x as y`
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom):
                base = base_of(module, path, node)
                for a in node.names:
                    if a.name.startswith("_") and not a.name.startswith("__"):
                        offenders.append(f"{module}: from {base} import {a.name}")
                    if f"{base}.{a.name}" in known:
                        aliases.add(a.asname or a.name)
            elif isinstance(node, ast.Import):
                for a in node.names:
                    if any(part.startswith("_") and not part.startswith("__")
                           for part in a.name.split(".")):
                        offenders.append(f"{module}: import {a.name}")
                    if a.name in known and a.asname:
                        aliases.add(a.asname)
        for node in ast.walk(tree):
            if (isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name)
                    and node.value.id in aliases and node.attr.startswith("_")
                    and not node.attr.startswith("__")):
                offenders.append(f"{module}: {node.value.id}.{node.attr}")
    return offenders


def long_modules_unsaid(package: str) -> list[str]:
    """Modules over LONG lines whose docstring does not say why."""
    found = []
    for path, tree in modules(package).values():
        lines = len(path.read_text(encoding="utf-8").splitlines())
        if lines > LONG and f"over {LONG} lines" not in (ast.get_docstring(tree) or ""):
            found.append(f"{path.relative_to(ROOT)} has {lines} lines: split it, or say in "
                         f"its docstring why it is over {LONG} lines")
    return found
