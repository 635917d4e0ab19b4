"""The drawings: well-formed SVG, the dimensions the design asks for, the sheet, the title block."""

import math
import re
import xml.etree.ElementTree as ET
from dataclasses import replace

import pytest
from assembly_drawings import assembly as assembly_of

from course.drawing import assembly_drawing_svg, part_drawing_svg
from course.parts import Box, Dimension, Material, Part
from course.practices import PRACTICES
from course.practices.practice_1 import design

NS = {"s": "http://www.w3.org/2000/svg"}
SHEET = (297.0, 210.0)
FRAME = (20.0, 10.0, 287.0, 200.0)
STANDARD_SCALES = {"5:1": 5, "2:1": 2, "1:1": 1, "1:2": 0.5, "1:2.5": 0.4, "1:5": 0.2,
                   "1:10": 0.1, "1:20": 0.05, "1:50": 0.02, "1:100": 0.01}
# The view axes as the Dimension docstring fixes them: (horizontal, vertical) indices of x, y, z.
AXES = {"front": (0, 2), "top": (0, 1), "side": (1, 2)}

PARTS = {p.name: p for p in design.parts()}


@pytest.fixture(scope="module")
def drawings():
    return {name: part_drawing_svg(part) for name, part in PARTS.items()}


@pytest.fixture(scope="module")
def assembly():
    return assembly_of("practice_1")[1]


def tag(el) -> str:
    return el.tag.split("}")[-1]


def texts(svg: str, group: str | None = None) -> list[ET.Element]:
    root = ET.fromstring(svg)
    scope = root if group is None else root.find(f".//s:g[@id='{group}']", NS)
    assert scope is not None, f"no group {group!r}"
    return [el for el in scope.iter() if tag(el) == "text"]


def text_values(svg: str, group: str | None = None) -> list[str]:
    return [el.text for el in texts(svg, group)]


def element_points(el) -> list[tuple[float, float]]:
    """The sheet points an element reaches (circles by their bounding box, paths by every
    end point and arc radius), parsed from the SVG alone."""
    a = el.attrib
    name = tag(el)
    if name == "line":
        return [(float(a["x1"]), float(a["y1"])), (float(a["x2"]), float(a["y2"]))]
    if name == "circle":
        cx, cy, r = float(a["cx"]), float(a["cy"]), float(a["r"])
        return [(cx - r, cy - r), (cx + r, cy + r)]
    if name == "text":
        return [(float(a["x"]), float(a["y"]))]
    if name == "rect":
        x, y = float(a["x"]), float(a["y"])
        return [(x, y), (x + float(a["width"]), y + float(a["height"]))]
    if name == "path":
        tokens = re.findall(r"[MLAZ]|-?\d+(?:\.\d+)?", a["d"])
        pts, i = [], 0
        while i < len(tokens):
            cmd = tokens[i]
            if cmd in "ML":
                pts.append((float(tokens[i + 1]), float(tokens[i + 2])))
                i += 3
            elif cmd == "A":  # rx ry rotation large-arc sweep x y
                r, large, sweep = float(tokens[i + 1]), tokens[i + 4] == "1", tokens[i + 5] == "1"
                end = (float(tokens[i + 6]), float(tokens[i + 7]))
                pts += arc_points(pts[-1], end, r, large, sweep)
                i += 8
            else:
                i += 1
        return pts
    return []


def arc_points(start, end, r, large, sweep, n=24):
    """Points along an SVG circular arc (y down; sweep 1 turns clockwise on the sheet)."""
    (x0, y0), (x1, y1) = start, end
    mx, my, dx, dy = (x0 + x1) / 2, (y0 + y1) / 2, x1 - x0, y1 - y0
    half = math.hypot(dx, dy) / 2
    h = math.sqrt(max(r * r - half * half, 0.0))
    for sign in (1, -1):
        cx, cy = mx - sign * h * dy / (2 * half), my + sign * h * dx / (2 * half)
        a0, a1 = math.atan2(y0 - cy, x0 - cx), math.atan2(y1 - cy, x1 - cx)
        span = (a1 - a0) % (2 * math.pi) if sweep else -((a0 - a1) % (2 * math.pi))
        if (abs(span) > math.pi) == large:
            return [(cx + r * math.cos(a0 + span * i / n), cy + r * math.sin(a0 + span * i / n))
                    for i in range(n + 1)]
    raise AssertionError("no arc through these points")


def group_box(svg: str, group: str) -> tuple[float, float, float, float]:
    root = ET.fromstring(svg)
    g = root.find(f".//s:g[@id='{group}']", NS)
    pts = [p for el in g.iter() for p in element_points(el) if tag(el) != "text"]
    xs, ys = [p[0] for p in pts], [p[1] for p in pts]
    return min(xs), min(ys), max(xs), max(ys)


def scale_of(svg: str) -> str:
    """The scale written in the title block (the one text of the form a:b)."""
    found = [t for t in text_values(svg, "sheet") if re.fullmatch(r"\d+(\.\d+)?:\d+(\.\d+)?", t)]
    assert len(found) == 1, found
    return found[0]


def expected_text(part: Part, dim: Dimension) -> str:
    """The text a dimension must show, worked out here from its two points."""
    if dim.label is not None:
        return dim.label
    h, v = AXES[dim.view]
    axis = h if dim.direction == "h" else v
    value = round(abs(dim.b[axis] - dim.a[axis]) * 1000, 2)
    return f"{value:g}"


# --- the SVG itself --------------------------------------------------------------------------------


@pytest.mark.parametrize("name", sorted(PARTS))
def test_part_drawing_is_an_a4_svg(drawings, name):
    root = ET.fromstring(drawings[name])
    assert tag(root) == "svg"
    assert root.attrib["viewBox"] == "0 0 297 210"
    assert root.attrib["width"] == "297mm" and root.attrib["height"] == "210mm"
    # self-contained: no links, images, external fonts or style sheets
    assert "href" not in drawings[name] and "@import" not in drawings[name] and "<style" not in drawings[name]


def test_assembly_drawing_parses(assembly):
    root = ET.fromstring(assembly)
    assert tag(root) == "svg"


@pytest.mark.parametrize("name", sorted(PARTS))
def test_coordinates_are_rounded_to_a_hundredth(drawings, name):
    numbers = re.findall(r'"(-?\d+\.\d+)"', drawings[name])
    assert numbers and all(len(n.split(".")[1]) <= 2 for n in numbers)


def test_output_is_deterministic(drawings, assembly):
    assert part_drawing_svg(design.base()) == drawings["base_link"]
    assert part_drawing_svg(design.wheel()) == drawings["wheel"]
    assert assembly_drawing_svg(design.robot()) == assembly


# --- dimensions ------------------------------------------------------------------------------------


@pytest.mark.parametrize("name", sorted(PARTS))
def test_every_dimension_is_shown_with_its_value(drawings, name):
    part = PARTS[name]
    assert part.dimensions
    for view in AXES:
        wanted = sorted(expected_text(part, d) for d in part.dimensions if d.view == view)
        shown = [t for t in text_values(drawings[name], f"view-{view}") if t != view.upper()]
        assert sorted(shown) == wanted, view


def test_base_dimension_values(drawings):
    shown = set(text_values(drawings["base_link"]))
    assert {"300", "260", "40", "100", "50", "400", "20", "Ø20"} <= shown


def test_wheel_dimension_labels(drawings):
    shown = set(text_values(drawings["wheel"]))
    assert {"Ø200", "Ø110 PCD", "4 × Ø30 THRU", "Ø20 THRU", "40"} <= shown


def test_dimension_texts_do_not_overlap(drawings):
    """Estimated text boxes (DejaVu widths) of each view's texts stay apart."""
    from course.drawing import text_width
    for svg in drawings.values():
        for view in AXES:
            boxes = []
            for el in texts(svg, f"view-{view}"):
                x, y, size = float(el.attrib["x"]), float(el.attrib["y"]), float(el.attrib["font-size"])
                w = text_width(el.text, size)
                anchor = el.attrib.get("text-anchor", "start")
                start = {"start": 0, "middle": -w / 2, "end": -w}[anchor]
                if "rotate(-90" in el.attrib.get("transform", ""):
                    boxes.append((x - 0.8 * size, y - start - w, x + 0.2 * size, y - start))
                else:
                    boxes.append((x + start, y - 0.8 * size, x + start + w, y + 0.2 * size))
            for i, a in enumerate(boxes):
                for b in boxes[i + 1:]:
                    assert a[2] <= b[0] or b[2] <= a[0] or a[3] <= b[1] or b[3] <= a[1], (view, a, b)


def test_bad_view_name_is_refused():
    part = replace(design.base(), dimensions=[Dimension("iso", (0, 0, 0), (0.1, 0, 0))])
    with pytest.raises(ValueError, match=r"base_link.*'iso'"):
        part_drawing_svg(part)


def test_bad_direction_is_refused():
    part = replace(design.base(), dimensions=[Dimension("top", (0, 0, 0), (0.1, 0, 0), "x")])
    with pytest.raises(ValueError, match=r"base_link.*'x'"):
        part_drawing_svg(part)


# --- sheet, scale, views ----------------------------------------------------------------------------


@pytest.mark.parametrize("name", sorted(PARTS))
def test_scale_is_standard_and_everything_is_on_the_sheet(drawings, name):
    svg = drawings[name]
    assert scale_of(svg) in STANDARD_SCALES
    root = ET.fromstring(svg)
    for el in root.iter():
        for x, y in element_points(el):
            assert -0.01 <= x <= SHEET[0] + 0.01 and -0.01 <= y <= SHEET[1] + 0.01, (tag(el), x, y)
    for view in AXES:  # the views stay inside the frame
        x0, y0, x1, y1 = group_box(svg, f"view-{view}")
        assert FRAME[0] < x0 and x1 < FRAME[2] and FRAME[1] < y0 and y1 < FRAME[3], view


@pytest.mark.parametrize("name", sorted(PARTS))
def test_views_in_first_angle_arrangement(drawings, name):
    """Top view below the front view, the view from +x (side) to the left of it."""
    svg = drawings[name]
    front, top, side = (group_box(svg, f"view-{v}") for v in ("front", "top", "side"))
    assert top[1] > front[3]
    assert side[2] < front[0]


def test_wheel_circles_at_scale(drawings):
    """The front view of the wheel shows the rim, the bore and four holes as visible circles."""
    svg = drawings["wheel"]
    k = STANDARD_SCALES[scale_of(svg)]
    root = ET.fromstring(svg)
    front = root.find(".//s:g[@id='view-front']", NS)
    radii = sorted(float(c.attrib["r"]) for g in front.iter() if tag(g) == "g"
                   and g.attrib.get("stroke-width") == "0.5" for c in g if tag(c) == "circle")
    want = sorted([design.WHEEL_DIAMETER / 2 * k, design.BORE_DIAMETER / 2 * k]
                  + [design.HOLE_DIAMETER / 2 * k] * 4)
    assert radii == pytest.approx(want, abs=0.01)


def test_wheel_side_view_has_hidden_holes(drawings):
    """Seen from the side, the bore and holes are hidden: dashed lines across the wheel's width."""
    root = ET.fromstring(drawings["wheel"])
    side = root.find(".//s:g[@id='view-side']", NS)
    dashed = [el for el in side.iter() if tag(el) == "line" and "stroke-dasharray" in el.attrib
              and float(el.attrib["y1"]) == float(el.attrib["y2"])]
    k = STANDARD_SCALES[scale_of(drawings["wheel"])]
    hidden = [el for el in dashed if math.isclose(abs(float(el.attrib["x2"]) - float(el.attrib["x1"])),
                                                  design.WHEEL_WIDTH * k, abs_tol=0.02)]
    # bore (2 lines), side holes (2, on one line each side), top and bottom holes (4)
    assert len(hidden) == 8


# --- title block ------------------------------------------------------------------------------------


@pytest.mark.parametrize("name", sorted(PARTS))
def test_title_block(drawings, name):
    part = PARTS[name]
    values = text_values(drawings[name], "sheet")
    assert f"{part.mass:.3f} kg" in values
    assert f"{part.name}.SLDPRT" in values
    assert part.title in values
    assert part.material.name in values
    assert "2700 kg/m³" in values
    for fixed in ("Dimensions in mm", "ISO 2768-m", "First angle projection", "1/1"):
        assert fixed in values


# --- the assembly ------------------------------------------------------------------------------------


def parts_list_rows(svg: str) -> dict[str, list[str]]:
    """Rows of the parts list, keyed by the part's cell text, by the texts' common baseline."""
    rows: dict[float, list[tuple[float, str]]] = {}
    for el in texts(svg, "sheet"):
        rows.setdefault(round(float(el.attrib["y"]), 1), []).append((float(el.attrib["x"]), el.text))
    out = {}
    for cells in rows.values():
        cells.sort()
        for _, text in cells:
            if text.endswith(".SLDPRT)"):
                out[text] = [t for _, t in cells]
    return out


def test_parts_list_counts_the_wheels(assembly):
    rows = parts_list_rows(assembly)
    wheel = rows["Wheel (wheel.SLDPRT)"]
    base = rows["Base (base_link.SLDPRT)"]
    assert wheel[0] == "2" and wheel[3] == "4" and wheel[4] == design.ALUMINIUM.name
    assert base[0] == "1" and base[3] == "1"


def test_assembly_balloons_joints_and_title(assembly):
    robot = design.robot()
    values = text_values(assembly)
    for j in robot.joints:
        assert j.name in values
    notes = text_values(assembly, "front-notes") + text_values(assembly, "top-notes")
    assert sorted(v for v in notes if v.isdigit()) == ["1", "2"]  # one balloon per item
    total = sum(lk.part.mass for lk in robot.links if lk.part is not None)
    assert f"{total:.3f} kg" in values
    assert f"{robot.name}.SLDASM" in values
    assert scale_of(assembly) in STANDARD_SCALES


def test_assembly_elements_on_the_sheet(assembly):
    root = ET.fromstring(assembly)
    for el in root.iter():
        for x, y in element_points(el):
            assert -0.01 <= x <= SHEET[0] + 0.01 and -0.01 <= y <= SHEET[1] + 0.01, (tag(el), x, y)


def test_yawed_box_is_drawn_turned_in_the_top_view():
    """A box turned 90° about z is drawn with its x and y sizes swapped in the top view and
    projected extents in the front view."""
    steel = Material("Steel", 7850.0)
    part = Part("block", steel, [Box((0.1, 0.04, 0.02), yaw=90)],
                [Dimension("top", (-0.02, 0, 0), (0.02, 0, 0), "h", -0.06),
                 Dimension("front", (-0.02, 0, -0.01), (0.02, 0, -0.01), "h", -0.02)])
    svg = part_drawing_svg(part)
    k = STANDARD_SCALES[scale_of(svg)]
    root = ET.fromstring(svg)
    for view, (w, h) in {"top": (40, 100), "front": (40, 20), "side": (100, 20)}.items():
        g = root.find(f".//s:g[@id='view-{view}']", NS)
        wide = [p for sub in g.iter() if tag(sub) == "g" and sub.attrib.get("stroke-width") == "0.5"
                for el in sub for p in element_points(el)]
        xs, ys = [p[0] for p in wide], [p[1] for p in wide]
        assert (max(xs) - min(xs), max(ys) - min(ys)) == pytest.approx((w * k, h * k), abs=0.02), view


@pytest.mark.parametrize("practice", PRACTICES)
def test_balloons_keep_clear_of_the_joint_names(practice):
    """A balloon level with a joint name would put its leader through the name."""
    from course.drawing import BALLOON_R
    robot, svg = assembly_of(practice)
    notes = texts(svg, "top-notes")
    names = {j.name for j in robot.joints}
    balloons = [float(t.attrib["y"]) for t in notes if t.text.isdigit()]
    labels = [float(t.attrib["y"]) for t in notes if t.text in names]
    assert balloons and labels
    for b in balloons:
        assert all(abs(b - y) > BALLOON_R for y in labels), (practice, b, labels)


@pytest.mark.parametrize("practice", PRACTICES)
def test_every_joint_is_named_once_and_names_do_not_overlap(practice):
    robot, svg = assembly_of(practice)
    notes = texts(svg, "top-notes")
    names = {j.name for j in robot.joints}
    labels = [t for t in notes if set(t.text.split(", ")) <= names]
    shown = [n for t in labels for n in t.text.split(", ")]
    assert sorted(shown) == sorted(names)
    spots = [(t.attrib.get("text-anchor"), float(t.attrib["y"])) for t in labels]
    for i, (side, y) in enumerate(spots):
        assert all(s != side or abs(y - y2) > 2.0 for s, y2 in spots[i + 1:]), (practice, spots)


def test_a_dimension_text_with_room_beside_the_part_keeps_off_its_lines():
    """A text that could go on either side of its dimension line goes where no line of the
    part runs (the chassis's "Ø10 pin" sat across a fork's wall); with no such place it
    keeps the place it had, clear of the other dimensions."""
    import shapely

    from course.drawing.dimensions import view_dimensions
    from course.drawing.svg import Line, Text, bbox

    short = Dimension("front", (0.0, 0.0, 0.0), (0.0, 0.0, 0.002), "v", 0.01, "Ø2 pin")

    def text_of(drawn):
        return next(p for p in view_dimensions([short], 1000.0, (0.0, 0.0), drawn=drawn)
                    if isinstance(p, Text))

    alone = text_of([])
    box = shapely.box(*bbox([alone]))
    x0, y0, x1, y1 = box.bounds
    wall = Line((x0 + x1) / 2, y0 - 5, (x0 + x1) / 2, y1 + 5, "visible")   # through the text
    moved = text_of([wall])
    assert (moved.x, moved.y) != (alone.x, alone.y)
    assert not shapely.box(*bbox([moved])).intersects(
        shapely.LineString([(wall.x1, wall.y1), (wall.x2, wall.y2)]))
    everywhere = [Line(-100, y, 100, y, "visible") for y in range(-100, 101, 1)]
    assert text_of(everywhere) == alone
