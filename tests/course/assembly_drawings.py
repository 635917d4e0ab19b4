"""Each practice's assembly drawing, drawn once per test session: drawing one takes seconds,
and several test modules read the same one."""

from functools import cache

from course.drawing import assembly_drawing_svg
from course.practices import design


@cache
def assembly(practice: str):
    """(robot, SVG text of its assembly drawing) for a practice, e.g. assembly("practice_2")."""
    robot = design(practice).robot()
    return robot, assembly_drawing_svg(robot)
