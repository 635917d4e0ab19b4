"""Every part can be modelled from its drawing alone, and the drawings can be read.

What a part is built from is its features (course/parts.py): boxes and cylinders, added or cut.
The numbers a student types into SolidWorks are those features' parameters:

- a box: its three sizes, each along the box's own (possibly turned) axes;
- a cylinder: its diameter, and its length along its axis;
- a hole (a cut cylinder): also where its axis is, along each of the part's axes across it.

The test reads what the sheet dimensions from the drawing model (`course.drawing.part_sheet`):
every dimension placed on the sheet, with the text it shows. A dimension gives a length along
one direction: a view's horizontal or vertical axis, or for an aligned one the direction between
its two points. Its value is the number its text shows (checked against what it measures).

The rules:

- A size is shown when a dimension along the size's direction shows its value. One dimension
  shows that value for every feature that has it along that direction: equal values are
  dimensioned once (a plate and a beam of the same thickness, the four arms of a base).
- A diameter is shown by a dimension whose text starts with Ø (after a count such as "4 ×"),
  measured across the cylinder's axis, or with R and half the value (a round end). Holes that
  share a diameter are dimensioned once, with their count: "4 × Ø30 THRU" for four holes. A
  hole marked THRU needs no length.
- The parts are symmetric about their x = 0 or y = 0 planes where their features are: a
  direction and its mirror image in those planes count as the same (Practice 2's arms are
  dimensioned on whichever arm has room).
- A hole's position along an axis is shown when the hole lies on the part's origin along that
  axis (the centre lines mark it), when a dimension along that axis ends on the hole's axis, or
  when the hole lies on a pitch circle about the origin whose diameter ("PCD") is dimensioned.
"""

import math
import re
import xml.etree.ElementTree as ET
from functools import cache

import numpy as np
import pytest
import shapely
from assembly_drawings import assembly as assembly_of

from course.drawing import dimension_text, part_sheet
from course.parts import Angle, Box, Cylinder
from course.practices import practices

PAGE_PX = 736  # the width the site shows a drawing at
READABLE_PX = 10.0
TOL = 0.005  # mm: dimension values are written to a hundredth
AXES3 = {"x": (1.0, 0.0, 0.0), "y": (0.0, 1.0, 0.0), "z": (0.0, 0.0, 1.0)}
VIEW_AXES = {"front": ("x", "z"), "top": ("x", "y"), "side": ("y", "z")}
NS = {"s": "http://www.w3.org/2000/svg"}

PARTS = [(p.name, part.name) for p in practices() for part in p.design.parts()]
IDS = [f"{practice}-{part}" for practice, part in PARTS]


@cache
def part_of(practice: str, name: str):
    part = {p.name: p for p in next(p for p in practices() if p.name == practice).design.parts()}[name]
    return part, part_sheet(part)


def yaw_matrix(degrees: float) -> np.ndarray:
    c, s = math.cos(math.radians(degrees)), math.sin(math.radians(degrees))
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def feature_parameters(part) -> list[tuple]:
    """What each feature is built from: (kind, direction, value mm, feature index); kind is
    'size' or 'diameter' (direction: the cylinder's axis) or 'position' (value: the hole's
    axis coordinate along the direction, one of the part's axes)."""
    out = []
    for i, f in enumerate(part.features):
        R = yaw_matrix(f.yaw)
        if isinstance(f, Box):
            for axis, size in zip("xyz", f.size):
                out.append(("size", R @ AXES3[axis], size * 1000, i))
        else:
            axis = R @ AXES3[f.axis]
            out.append(("diameter", axis, 2000 * f.radius, i))
            out.append(("size", axis, f.length * 1000, i))
            if f.cut:
                for name, e in AXES3.items():
                    if abs(np.dot(e, axis)) < 1e-9:
                        out.append(("position", np.array(e), float(np.dot(f.center, e)) * 1000, i))
    return out


def measured(dim) -> tuple[np.ndarray, float]:
    """The direction (unit, part frame) a dimension measures along and its length, mm."""
    a, b = np.array(dim.a), np.array(dim.b)
    h, v = (np.array(AXES3[n]) for n in VIEW_AXES[dim.view])
    if dim.direction == "a":
        d = (b - a) @ h * h + (b - a) @ v * v
        return d / np.linalg.norm(d), float(np.linalg.norm(d)) * 1000
    u = h if dim.direction == "h" else v
    return u, abs(float((b - a) @ u)) * 1000


LABEL = re.compile(r"^(?:(?P<count>\d+) ?× ?)?(?P<dia>[ØR])?(?P<value>\d+(?:\.\d+)?)")
MIRRORS = [np.diag([sx, sy, 1.0]) for sx in (1, -1) for sy in (1, -1)]


def reading(text: str) -> dict:
    """What a dimension's text says: its value (a diameter for Ø and R), whether it is a
    diameter, the count, PCD, THRU; `length` is what its line spans, to check against."""
    m = LABEL.match(text)
    assert m, f"a dimension text that gives no number: {text!r}"
    radius = m["dia"] == "R"
    return {"value": float(m["value"]) * (2 if radius else 1), "diameter": bool(m["dia"]),
            "radius": radius, "count": int(m["count"] or 1), "pcd": "PCD" in text, "thru": "THRU" in text}


def along(m: dict, d) -> bool:
    """The dimension measures along d (or its mirror image)."""
    return any(abs(abs((M @ m["direction"]) @ d) - 1) < 1e-6 for M in MIRRORS)


def across(m: dict, axis) -> bool:
    """The dimension measures across the axis (or its mirror image)."""
    return any(abs((M @ m["direction"]) @ axis) < 1e-6 for M in MIRRORS)


def shown(practice: str, name: str) -> list[dict]:
    """Every linear dimension on the part's sheet, as read off it."""
    part, sheet = part_of(practice, name)
    out = []
    for view, dim, text in sheet.dimensions:
        if isinstance(dim, Angle):
            continue
        direction, length = measured(dim)
        r = reading(text.text)
        out.append({**r, "direction": direction, "length": length, "dim": dim, "text": text.text})
    return out


def missing_parameters(practice: str, name: str) -> list[str]:
    part, _ = part_of(practice, name)
    dims = shown(practice, name)
    holes: dict[float, int] = {}
    for f in part.features:
        if isinstance(f, Cylinder) and f.cut:
            key = round(2000 * f.radius, 2)
            holes[key] = holes.get(key, 0) + 1
    missing = []
    for kind, d, value, i in feature_parameters(part):
        f = part.features[i]
        what = f"feature {i} ({type(f).__name__}{', cut' if f.cut else ''})"
        diameter = isinstance(f, Cylinder) and [m for m in dims if m["diameter"] and across(m, d)
                                                and abs(m["value"] - 2000 * f.radius) < TOL]
        if kind == "size":
            ok = any(not m["diameter"] and along(m, d) and abs(m["value"] - value) < TOL for m in dims)
            ok = ok or (f.cut and any(m["thru"] for m in diameter))
            if not ok:
                missing.append(f"{what}: {value:g} along {np.round(d, 3).tolist()}")
        elif kind == "diameter":
            count = holes.get(round(value, 2), 1) if f.cut else 1
            ok = any(not f.cut or m["count"] == count for m in diameter)
            if not ok:
                missing.append(f"{what}: Ø{value:g}" + (f" ({count} ×)" if count > 1 else ""))
        else:  # the position of a hole's axis along d
            centre = np.array(f.center) * 1000
            axis = yaw_matrix(f.yaw) @ AXES3[f.axis]
            radial = centre - (centre @ axis) * axis
            ok = abs(value) < TOL or any(
                along(m, d) and min(abs(np.dot(m["dim"].a, d) * 1000 - value), abs(np.dot(m["dim"].b, d) * 1000 - value)) < TOL
                for m in dims) or any(
                m["pcd"] and abs(m["value"] - 2 * np.linalg.norm(radial)) < TOL for m in dims)
            if not ok:
                missing.append(f"{what}: the hole's axis at {value:g} along {np.round(d, 3).tolist()}")
    return missing


@pytest.mark.parametrize("practice, name", PARTS, ids=IDS)
def test_every_feature_parameter_is_dimensioned_on_the_parts_sheet(practice, name):
    assert missing_parameters(practice, name) == []


@pytest.mark.parametrize("practice, name", PARTS, ids=IDS)
def test_every_dimension_reads_what_it_measures_and_is_on_the_sheet(practice, name):
    """A label such as "225 (axis to fingertips)" starts with the length its line spans, and
    every dimension's text is written in the SVG."""
    part, sheet = part_of(practice, name)
    svg = sheet.svg()
    assert len(sheet.dimensions) == len(part.dimensions)
    for m in shown(practice, name):
        assert abs(m["value"] / (2 if m["radius"] else 1) - m["length"]) < TOL, m["text"]
    for view, dim, text in sheet.dimensions:
        assert text.text == dimension_text(dim)
        assert text.svg() in svg, text.text


def text_box(text):
    return shapely.Polygon(np.array(text.points())[[0, 1, 3, 2]])


@pytest.mark.parametrize("practice, name", PARTS, ids=IDS)
def test_no_two_texts_of_a_parts_sheet_overlap(practice, name):
    """The dimensions' texts and the views' names, boxes estimated from the font size and the
    text's length (DejaVu Sans widths), turned with the text, stay clear of each other."""
    _, sheet = part_of(practice, name)
    from course.drawing.svg import Text
    texts = [p for layer, prims in sheet.layers if layer.startswith("view-") for p in prims
             if isinstance(p, Text)]
    assert {t.text for _, _, t in sheet.dimensions} <= {t.text for t in texts}
    boxes = [text_box(t) for t in texts]
    clashes = [(texts[i].text, texts[j].text) for i in range(len(texts)) for j in range(i + 1, len(texts))
               if boxes[i].intersection(boxes[j]).area > 1e-6]
    assert clashes == []


def joint_texts(svg: str) -> tuple[float, list[tuple[str, float]]]:
    """(viewBox width, [(text, font size)]) of the joint notes (the red texts) of a sheet."""
    root = ET.fromstring(svg)
    width = float(root.attrib["viewBox"].split()[2])
    found = []
    for g in root.iter(f"{{{NS['s']}}}g"):
        if g.attrib.get("fill") == "#b03020":
            found += [(t.text, float(t.attrib["font-size"])) for t in g.iter(f"{{{NS['s']}}}text")]
    return width, found


@pytest.mark.parametrize("practice", [p.name for p in practices()])
def test_joint_names_are_readable_at_the_page_width(practice):
    """Shown 736 px wide, a joint's name and the key to the joint marks are at least 10 px
    high: px = font size × 736 / viewBox width."""
    robot, svg = assembly_of(practice)
    width, found = joint_texts(svg)
    names = {j.name for j in robot.joints}
    assert names <= {n for text, _ in found for n in text.split(", ")}
    small = [(text, round(size * PAGE_PX / width, 2)) for text, size in found
             if size * PAGE_PX / width < READABLE_PX]
    assert small == []
