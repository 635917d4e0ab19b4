"""The course build's modules depend one way: no import cycle (the drawing package's
modules included), no module uses another's private names, and none grows past LONG lines
without saying why. The course may use the tool; the tool never uses the course
(tests/tool/test_structure_of_the_tool.py)."""

from module_graph import dependency_graph, find_cycle, imports, long_modules_unsaid, private_imports

COURSE = "course"


def test_no_import_cycle_among_the_course_modules():
    cycle = find_cycle(dependency_graph(COURSE))
    assert cycle is None, "import cycle: " + " -> ".join(cycle)


def test_the_drawing_modules_are_found_and_import_each_other():
    graph = imports(COURSE)
    assert "course.drawing.assembly" in graph and "course.drawing.svg" in graph
    assert any(i.startswith("course.drawing.") for i in graph["course.drawing.assembly"])


def test_no_module_imports_another_modules_private_names():
    offenders = private_imports(COURSE)
    assert not offenders, offenders


def test_no_module_is_long_unless_it_says_why():
    assert not long_modules_unsaid(COURSE), "\n".join(long_modules_unsaid(COURSE))
