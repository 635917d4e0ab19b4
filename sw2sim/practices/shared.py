"""Small pieces every practice uses: millimetres to metres, and the drawing figures."""

from pathlib import Path


def mm(*values: float):
    """Millimetres, as on the drawings, to metres: one value, or a tuple of several."""
    return tuple(v / 1000 for v in values) if len(values) > 1 else values[0] / 1000


def part_drawing(part_factory):
    """A figure maker: the drawing sheet of the part that `part_factory()` returns."""
    def make(path: Path) -> None:
        from ..drawing import part_drawing_svg
        path.write_text(part_drawing_svg(part_factory()))
    make.__qualname__ = f"drawing_{part_factory.__name__}"
    return make


def assembly_drawing(robot_factory):
    """A figure maker: the assembly drawing of the robot that `robot_factory()` returns."""
    def make(path: Path) -> None:
        from ..drawing import assembly_drawing_svg
        path.write_text(assembly_drawing_svg(robot_factory()))
    make.__qualname__ = "assembly"
    return make
