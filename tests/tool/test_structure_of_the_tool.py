"""The tool's modules depend one way: no import cycle, rule modules never import each
other, and nothing in sw2sim/ imports the course build."""

import ast

from repository import ROOT

TOOL = ROOT / "sw2sim"
RULE_MODULES = {"structure", "package_xml", "meshes", "inertia", "joints", "collisions", "stability"}


def imports() -> dict[str, set[str]]:
    """sw2sim module -> the sw2sim modules it imports (anywhere in the file)."""
    graph = {}
    for path in TOOL.rglob("*.py"):
        parts = path.relative_to(ROOT).with_suffix("").parts
        name = ".".join(parts[:-1] if parts[-1] == "__init__" else parts)
        package = name if path.name == "__init__.py" else name.rpartition(".")[0]
        found = set()
        for node in ast.walk(ast.parse(path.read_bytes())):
            if isinstance(node, ast.ImportFrom):
                base = node.module or ""
                if node.level:
                    up = package.split(".")[: len(package.split(".")) - node.level + 1]
                    base = ".".join(up + ([node.module] if node.module else []))
                found.add(base)
                found.update(f"{base}.{a.name}" for a in node.names)
            elif isinstance(node, ast.Import):
                found.update(a.name for a in node.names)
        graph[name] = found
    modules = set(graph)
    return {m: {i for i in found if i in modules and i != m} | {i for i in found if i.split(".")[0] == "course"}
            for m, found in graph.items()}


def test_the_tool_never_imports_the_course():
    offenders = {m: sorted(i for i in found if i.split(".")[0] == "course") for m, found in imports().items()}
    assert not any(offenders.values()), offenders


def test_rule_modules_import_only_shared_modules():
    for module, found in imports().items():
        if module.rpartition(".")[2] in RULE_MODULES and module.startswith("sw2sim.check."):
            peers = {i for i in found if i.rpartition(".")[2] in RULE_MODULES and i.startswith("sw2sim.check.")}
            assert not peers, f"{module} imports other rule modules: {sorted(peers)}"


def test_no_import_cycle_among_the_checker_modules():
    graph = {m: {i for i in found if i.startswith("sw2sim.check.")}
             for m, found in imports().items() if m.startswith("sw2sim.check.")}
    state: dict[str, int] = {}

    def visit(node, path):
        state[node] = 1
        for nxt in graph.get(node, ()):
            if state.get(nxt) == 1:
                raise AssertionError("import cycle: " + " -> ".join(path + [nxt]))
            if nxt not in state:
                visit(nxt, path + [nxt])
        state[node] = 2

    for module in graph:
        if module not in state:
            visit(module, [module])
