"""The tool's modules depend one way: no import cycle, rule modules never import each
other, no module imports another's private names, only sw2sim.xmlsafe parses XML, nothing
in sw2sim/ imports the course build, and no module grows past LONG lines unsaid."""

import ast
from functools import cache
from pathlib import Path

from repository import ROOT

TOOL = ROOT / "sw2sim"
RULE_MODULES = {"structure", "package_xml", "meshes", "inertia", "joints", "collisions", "stability"}
# What a rule module may import from sw2sim.check (besides the tool's modules outside it).
SHARED = {"findings", "context", "urdf", "geometry"}
# lxml's and the standard library's ways to parse XML: only sw2sim.xmlsafe may use them.
PARSERS = {"parse", "fromstring", "XML", "XMLParser", "iterparse", "XMLPullParser", "HTML",
           "fromstringlist", "XMLID", "XMLDTDID"}
STDLIB_XML = ("xml.etree", "xml.dom", "xml.sax", "xml.parsers", "xmlrpc")
LONG = 500


@cache
def modules() -> dict[str, tuple[Path, ast.Module]]:
    """sw2sim module name -> (file, parsed source)."""
    found = {}
    for path in sorted(TOOL.rglob("*.py")):
        parts = path.relative_to(ROOT).with_suffix("").parts
        name = ".".join(parts[:-1] if parts[-1] == "__init__" else parts)
        found[name] = (path, ast.parse(path.read_bytes(), str(path)))
    return found


def _base(module: str, path: Path, node: ast.ImportFrom) -> str:
    """The absolute name an ImportFrom imports from."""
    if not node.level:
        return node.module or ""
    package = module if path.name == "__init__.py" else module.rpartition(".")[0]
    parts = package.split(".")
    up = parts[: len(parts) - node.level + 1]
    return ".".join(up + ([node.module] if node.module else []))


def imported(module: str) -> set[str]:
    """Every name `module` imports (anywhere in the file), absolute: modules and, for
    `from x import y`, both x and x.y."""
    path, tree = modules()[module]
    found = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            base = _base(module, path, node)
            found.add(base)
            found.update(f"{base}.{a.name}" for a in node.names)
        elif isinstance(node, ast.Import):
            found.update(a.name for a in node.names)
    return found


def imports() -> dict[str, set[str]]:
    """sw2sim module -> the sw2sim modules it imports, and any course module it imports."""
    names = set(modules())
    return {m: {i for i in imported(m) if (i in names and i != m) or i.split(".")[0] == "course"}
            for m in names}


def test_the_tool_never_imports_the_course():
    offenders = {m: sorted(i for i in found if i.split(".")[0] == "course")
                 for m, found in imports().items()}
    offenders = {m: found for m, found in offenders.items() if found}
    assert not offenders, offenders


def test_rule_modules_import_only_shared_modules():
    for module, found in imports().items():
        if module.rpartition(".")[2] in RULE_MODULES and module.startswith("sw2sim.check."):
            peers = {i for i in found if i.rpartition(".")[2] in RULE_MODULES and i.startswith("sw2sim.check.")}
            assert not peers, f"{module} imports other rule modules: {sorted(peers)}"
            inside = {i for i in found if i.startswith("sw2sim.check")}
            allowed = {f"sw2sim.check.{s}" for s in SHARED}
            assert inside <= allowed, f"{module} imports {sorted(inside - allowed)}"


def _cycle(graph: dict[str, set[str]]) -> list[str] | None:
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


def test_no_import_cycle_among_the_checker_modules():
    graph = {m: {i for i in found if i.startswith("sw2sim.check.")}
             for m, found in imports().items() if m.startswith("sw2sim.check.")}
    cycle = _cycle(graph)
    assert cycle is None, "import cycle: " + " -> ".join(cycle)


def test_no_import_cycle_among_all_the_tools_modules():
    # A package's __init__ runs before its modules, but it is not a dependency of theirs:
    # `from .findings import x` inside sw2sim.check depends on sw2sim.check.findings only.
    graph = {m: {i for i in found if not m.startswith(i + ".")} for m, found in imports().items()}
    cycle = _cycle(graph)
    assert cycle is None, "import cycle: " + " -> ".join(cycle)


def test_the_cycle_finder_finds_a_cycle():
    assert _cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}}) == ["a", "b", "c", "a"]
    assert _cycle({"a": {"b"}, "b": set()}) is None


def test_no_module_imports_another_modules_private_names():
    offenders = []
    for module, (path, tree) in modules().items():
        aliases = set()   # names bound to sw2sim modules: `from . import loader`, `import sw2sim.x as y`
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom):
                base = _base(module, path, node)
                for a in node.names:
                    if a.name.startswith("_") and not a.name.startswith("__"):
                        offenders.append(f"{module}: from {base} import {a.name}")
                    if f"{base}.{a.name}" in modules():
                        aliases.add(a.asname or a.name)
            elif isinstance(node, ast.Import):
                for a in node.names:
                    if any(part.startswith("_") and not part.startswith("__")
                           for part in a.name.split(".")):
                        offenders.append(f"{module}: import {a.name}")
                    if a.name in modules() and a.asname:
                        aliases.add(a.asname)
        for node in ast.walk(tree):
            if (isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name)
                    and node.value.id in aliases and node.attr.startswith("_")
                    and not node.attr.startswith("__")):
                offenders.append(f"{module}: {node.value.id}.{node.attr}")
    assert not offenders, offenders


def test_only_xmlsafe_parses_xml():
    offenders = []
    for module, (path, tree) in modules().items():
        if module == "sw2sim.xmlsafe":
            continue
        for node in ast.walk(tree):
            if isinstance(node, ast.Attribute) and node.attr in PARSERS and \
                    isinstance(node.value, ast.Name) and node.value.id == "etree":
                offenders.append(f"{path.name}:{node.lineno}: etree.{node.attr}")
            if isinstance(node, ast.ImportFrom) and (node.module or "").startswith("lxml"):
                offenders += [f"{path.name}:{node.lineno}: from {node.module} import {a.name}"
                              for a in node.names if a.name in PARSERS]
        offenders += [f"{path.name}: imports {name}" for name in imported(module)
                      if name.startswith(STDLIB_XML)]
    assert not offenders, offenders


def test_no_module_is_long_unless_it_says_why():
    for module, (path, tree) in modules().items():
        lines = len(path.read_text(encoding="utf-8").splitlines())
        if lines > LONG:
            doc = ast.get_docstring(tree) or ""
            assert f"over {LONG} lines" in doc, (
                f"{path.relative_to(ROOT)} has {lines} lines: split it, or say in its docstring "
                f"why it is over {LONG} lines")
