"""Small pieces the practices share: millimetres to metres, the wheel, the drawing figures."""

from pathlib import Path

from ..parts import Cylinder, Dimension, Material, Part
from ..phone import phone_path


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


def part_drawing(part_factory, views_only: bool = False):
    """A figure maker: the drawing sheet of the part that `part_factory()` returns, or only
    its views (what the pages show; the sheet is linked beside them), with their phone
    variant beside them when they are too wide for a phone (course/drawing/narrow.py)."""
    def make(path: Path) -> None:
        from ..drawing import narrow, part_drawing_svg
        part = part_factory()
        svg = part_drawing_svg(part, views_only)
        path.write_text(svg)
        if views_only and narrow.too_wide(svg):
            phone_path(path).write_text(narrow.part_views_narrow(part, svg))
    make.__qualname__ = f"drawing_{part_factory.__name__}" + ("_views" if views_only else "")
    return make


def assembly_drawing(robot_factory, views_only: bool = False):
    """A figure maker: the assembly drawing of the robot that `robot_factory()` returns, or
    only its views with a key to the balloons, and their phone variant as `part_drawing`'s."""
    def make(path: Path) -> None:
        from ..drawing import assembly_drawing_svg, narrow
        robot = robot_factory()
        svg = assembly_drawing_svg(robot, views_only)
        path.write_text(svg)
        if views_only and narrow.too_wide(svg):
            phone_path(path).write_text(narrow.assembly_views_narrow(robot, svg))
    make.__qualname__ = "assembly" + ("_views" if views_only else "")
    return make


def drawing_figures(media: str, name: str, maker, factory, inputs: list[str], title: str,
                    phone: bool = False) -> list:
    """A drawing's two figures: `name.svg`, the views the page shows, and `name-sheet.svg`,
    the whole A4 sheet with its title block, which the page links to. `maker` is
    part_drawing or assembly_drawing; `phone`: the views are too wide for a phone's column,
    and their maker writes a phone variant too (`name-phone.svg`)."""
    from ..media import Figure
    return [Figure(f"{media}/{name}.svg", maker(factory, views_only=True), inputs, title, phone=phone),
            Figure(f"{media}/{name}-sheet.svg", maker(factory), inputs, f"{title}: the whole sheet")]
