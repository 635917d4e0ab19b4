"""The tool's modules depend one way: no import cycle, rule modules never import each
other, no module imports another's private names, only sw2sim.xmlsafe parses XML, nothing
in sw2sim/ imports the course build, and no module grows past LONG lines unsaid."""

import ast
import re

from module_graph import (dependency_graph, find_cycle, imported, imports, long_modules_unsaid,
                          modules, private_imports)

TOOL = "sw2sim"
RULE_MODULES = {"structure", "package_xml", "meshes", "inertia", "joints", "collisions", "stability"}
# What a rule module may import from sw2sim.check (besides the tool's modules outside it).
SHARED = {"findings", "context", "urdf", "geometry", "repairs", "trimeshes", "density_command",
          "collision_hulls"}
# lxml's and the standard library's ways to parse XML: only sw2sim.xmlsafe may use them.
PARSERS = {"parse", "fromstring", "XML", "XMLParser", "iterparse", "XMLPullParser", "HTML",
           "fromstringlist", "XMLID", "XMLDTDID"}
STDLIB_XML = ("xml.etree", "xml.dom", "xml.sax", "xml.parsers", "xmlrpc")
# XML-RPC is ROS 1's own protocol: the stand-in's nodes speak it with the ROS master and
# its nodes, never with a file of the user's.
XMLRPC_SPEAKERS = {"sw2sim.ros.wire"}


def test_the_tool_never_imports_the_course():
    offenders = {m: sorted(i for i in found if i.split(".")[0] == "course")
                 for m, found in imports(TOOL, also=("course",)).items()}
    offenders = {m: found for m, found in offenders.items() if found}
    assert not offenders, offenders


def test_rule_modules_import_only_shared_modules():
    for module, found in imports(TOOL).items():
        if module.rpartition(".")[2] in RULE_MODULES and module.startswith("sw2sim.check."):
            peers = {i for i in found if i.rpartition(".")[2] in RULE_MODULES and i.startswith("sw2sim.check.")}
            assert not peers, f"{module} imports other rule modules: {sorted(peers)}"
            inside = {i for i in found if i.startswith("sw2sim.check")}
            allowed = {f"sw2sim.check.{s}" for s in SHARED}
            assert inside <= allowed, f"{module} imports {sorted(inside - allowed)}"


def test_no_import_cycle_among_the_checker_modules():
    graph = {m: {i for i in found if i.startswith("sw2sim.check.")}
             for m, found in imports(TOOL).items() if m.startswith("sw2sim.check.")}
    cycle = find_cycle(graph)
    assert cycle is None, "import cycle: " + " -> ".join(cycle)


def test_no_import_cycle_among_all_the_tools_modules():
    cycle = find_cycle(dependency_graph(TOOL))
    assert cycle is None, "import cycle: " + " -> ".join(cycle)


def test_the_cycle_finder_finds_a_cycle():
    assert find_cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}}) == ["a", "b", "c", "a"]
    assert find_cycle({"a": {"b"}, "b": set()}) is None


def test_no_module_imports_another_modules_private_names():
    offenders = private_imports(TOOL)
    assert not offenders, offenders


def test_only_xmlsafe_parses_xml():
    offenders = []
    for module, (path, tree) in modules(TOOL).items():
        if module == "sw2sim.xmlsafe":
            continue
        for node in ast.walk(tree):
            if isinstance(node, ast.Attribute) and node.attr in PARSERS and \
                    isinstance(node.value, ast.Name) and node.value.id == "etree":
                offenders.append(f"{path.name}:{node.lineno}: etree.{node.attr}")
            if isinstance(node, ast.ImportFrom) and (node.module or "").startswith("lxml"):
                offenders += [f"{path.name}:{node.lineno}: from {node.module} import {a.name}"
                              for a in node.names if a.name in PARSERS]
        offenders += [f"{path.name}: imports {name}" for name in imported(TOOL, module)
                      if name.startswith(STDLIB_XML) and not (
                          module in XMLRPC_SPEAKERS and name.startswith("xmlrpc"))]
    assert not offenders, offenders


def test_no_module_is_long_unless_it_says_why():
    assert not long_modules_unsaid(TOOL), "\n".join(long_modules_unsaid(TOOL))


# The modules below the check: reading packages and meshes. They serve the check, convert
# and the loader alike, so nothing in them may reach up into sw2sim.check.
BELOW_THE_CHECK = ("sw2sim.mesh_formats", "sw2sim.collada_reader", "sw2sim.mesh_paths",
                   "sw2sim.package", "sw2sim.loader", "sw2sim.xmlsafe", "sw2sim.xacro_lines")


def test_the_mesh_and_package_readers_import_nothing_from_the_check():
    offenders = {module: sorted(n for n in imported(TOOL, module)
                                if n.startswith("sw2sim.check"))
                 for module in BELOW_THE_CHECK}
    assert not any(offenders.values()), offenders


def test_the_tool_tests_find_the_practices_as_the_course_does():
    """A practice added to course/practices/ is tested without editing a list of numbers."""
    from repository import ROOT
    listed = re.compile(r"\[1, 2, 3, 4, 5\]|range\(1, 6\)")
    found = [f"{path.relative_to(ROOT)}:{n}" for path in sorted((ROOT / "tests" / "tool").rglob("*.py"))
             for n, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1)
             if listed.search(line)]
    assert not found, found


def test_no_module_is_over_600_lines_whatever_it_says():
    over = {str(path): n for path, _ in modules(TOOL).values()
            if (n := len(path.read_text(encoding="utf-8").splitlines())) > 600}
    assert not over, over
