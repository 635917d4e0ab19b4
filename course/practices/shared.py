"""Small pieces the practices share: millimetres to metres, the wheel, the drawing figures."""

from pathlib import Path

from ..parts import Cylinder, Dimension, Material, Part


def mm(*values: float):
    """Millimetres, as on the drawings, to metres: one value, or a tuple of several."""
    return tuple(v / 1000 for v in values) if len(values) > 1 else values[0] / 1000


def holed_wheel(material: Material, diameter: float, width: float, bore: float, hole: float,
                pitch: float, offsets: tuple[float, ...], name: str = "wheel") -> Part:
    """A wheel as the lessons draw it: a disc on the y axis with a bore and four holes on a
    pitch circle (sizes in mm). `offsets` place its five dimension lines on the drawing, in
    metres from the part: diameter, pitch circle, hole, bore, width."""
    r, w, p = diameter / 2, width, pitch / 2
    holes = [Cylinder(mm(hole / 2), mm(w + 2), "y", mm(x, 0, z), cut=True)
             for x, z in ((p, 0), (-p, 0), (0, p), (0, -p))]
    outside, pcd, at_hole, at_bore, side = offsets
    return Part(
        name=name,
        title="Wheel",
        material=material,
        features=[
            Cylinder(mm(r), mm(w), "y"),
            Cylinder(mm(bore / 2), mm(w + 2), "y", cut=True),
            *holes,
        ],
        dimensions=[
            Dimension("front", mm(0, 0, -r), mm(0, 0, r), "v", outside, f"Ø{diameter}"),
            Dimension("front", mm(-p, 0, 0), mm(p, 0, 0), "h", pcd, f"Ø{pitch} PCD"),
            Dimension("front", mm(p - hole / 2, 0, 0), mm(p + hole / 2, 0, 0), "h",
                      at_hole, f"4 × Ø{hole} THRU"),
            Dimension("front", mm(-bore / 2, 0, 0), mm(bore / 2, 0, 0), "h", at_bore, f"Ø{bore} THRU"),
            Dimension("side", mm(0, -w / 2, 0), mm(0, w / 2, 0), "h", side),
        ],
    )


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
