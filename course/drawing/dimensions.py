"""Dimensions (ISO 129) drafted on a view: linear, aligned and angular, with extension lines,
arrowheads and texts placed clear of each other; `check_dimensions` refuses dimensions a drawing
cannot show, and `dimension_text` and `angle_degrees` give what a dimension reads."""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
import shapely
from shapely.geometry import LineString

from ..parts import Angle, Dimension, Part
from .projection import VIEWS
from .svg import DIM_TEXT, Arc, Circle, Line, Poly, Text, bbox, fmt, mm_text, text_width

ARROW_LEN, ARROW_HALF = 3.0, 0.55  # filled arrowhead, about 20 degrees included angle
EXT_GAP, EXT_OVER, TEXT_GAP = 1.0, 2.0, 1.0  # extension line: gap at the part, overshoot


# --- dimensions (ISO 129) ----------------------------------------------------------------------


def check_dimensions(part: Part) -> None:
    """Every dimension names a view the drawing has and a direction it knows; every angle has
    two legs in that view."""
    for dim in part.dimensions:
        if dim.view not in VIEWS:
            raise ValueError(f"part {part.name!r}: dimension view {dim.view!r} is not one of "
                             f"{', '.join(VIEWS)}")
        if isinstance(dim, Angle):
            legs = _angle_legs(dim)
            if min(np.linalg.norm(legs, axis=1)) < 1e-9:
                raise ValueError(f"part {part.name!r}: an angle in view {dim.view!r} has a leg of "
                                 "zero length in that view")
        elif dim.direction not in ("h", "v", "a"):
            raise ValueError(f"part {part.name!r}: dimension direction {dim.direction!r} in view "
                             f"{dim.view!r} must be 'h' or 'v' (or 'a', aligned)")


def _in_view(dim: Dimension | Angle, p) -> np.ndarray:
    """A 3D point of the part in the view's plane (metres: horizontal, vertical)."""
    _, h, v = VIEWS[dim.view]
    return np.array([np.dot(p, h), np.dot(p, v)])


def _angle_legs(dim: Angle) -> np.ndarray:
    """The angle's two legs in the view, from its vertex (2 x 2, metres)."""
    vertex = _in_view(dim, dim.vertex)
    return np.stack([_in_view(dim, dim.a) - vertex, _in_view(dim, dim.b) - vertex])


def angle_degrees(dim: Angle) -> float:
    """The angle between the two legs in the view, 0 to 180 degrees."""
    a, b = _angle_legs(dim)
    return math.degrees(math.atan2(abs(a[0] * b[1] - a[1] * b[0]), float(a @ b)))


def dimension_text(dim: Dimension | Angle) -> str:
    """What the dimension shows: its label, the measured length in millimetres, or the angle in
    degrees (to a hundredth)."""
    if dim.label is not None:
        return dim.label
    if isinstance(dim, Angle):
        return f"{fmt(angle_degrees(dim))}°"
    if dim.direction == "a":
        return mm_text(float(np.linalg.norm(_in_view(dim, dim.b) - _in_view(dim, dim.a))))
    _, h, v = VIEWS[dim.view]
    axis = np.array(h if dim.direction == "h" else v)
    return mm_text(abs(float((np.array(dim.b) - np.array(dim.a)) @ axis)))


@dataclass
class _DimDraft:
    """A dimension laid out except for where its text goes: `options` are the possible texts,
    best first, each with the span the dimension line must then cover."""

    lines: list
    options: list  # (text, line start, line end) as sheet points
    segments: list  # the lines as ((x1, y1), (x2, y2)), for keeping texts off them


def _dimension_draft(dim: Dimension | Angle, k: float, centre: tuple[float, float]) -> _DimDraft:
    """A dimension in sheet mm about the view's origin: extension lines, arrowheads and the
    dimension line; its text goes above the line (vertical ones read from the right)."""
    if isinstance(dim, Angle):
        return _angle_draft(dim, k)
    _, h, v = (np.array(x) for x in VIEWS[dim.view])
    a2 = np.array([np.dot(dim.a, h), np.dot(dim.a, v)])
    b2 = np.array([np.dot(dim.b, h), np.dot(dim.b, v)])

    def to_sheet(p2):
        return np.array([k * p2[0], -k * p2[1]])

    if dim.direction == "a":
        U, W, angle, lam = _aligned_frame(to_sheet(a2), to_sheet(b2), k * dim.offset)
    else:
        if dim.direction == "h":
            U, W, angle, off = np.array([1.0, 0.0]), np.array([0.0, -1.0]), 0.0, 1
        else:  # reading upwards; "above" the line is its left side
            U, W, angle, off = np.array([0.0, -1.0]), np.array([-1.0, 0.0]), -90.0, 0
        # the dimension line's place in part coordinates, as the Dimension docstring defines it
        at = max(a2[off], b2[off]) + dim.offset if dim.offset > 0 else min(a2[off], b2[off]) + dim.offset
        line_pt = a2.copy()
        line_pt[off] = at
        lam = float(to_sheet(line_pt) @ W)  # the dimension line, across
    pa, pb = to_sheet(a2), to_sheet(b2)

    def pt(along, across):
        x, y = along * U + across * W
        return float(x), float(y)

    lines = []
    for p in (pa, pb):
        al, ac = float(p @ U), float(p @ W)
        sign = 1.0 if lam >= ac else -1.0
        if abs(lam - ac) > EXT_GAP + 0.5:
            lines.append(Line(*pt(al, ac + sign * EXT_GAP), *pt(al, lam + sign * EXT_OVER)))
    lo, hi = sorted((float(pa @ U), float(pb @ U)))
    text = dimension_text(dim)
    tw = text_width(text, DIM_TEXT)
    arrows_in = hi - lo >= 2 * ARROW_LEN + 1.5
    line_lo, line_hi = (lo, hi) if arrows_in else (lo - ARROW_LEN - 2.0, hi + ARROW_LEN + 2.0)
    lines += _arrow(pt(lo, lam), -U if arrows_in else U, W)
    lines += _arrow(pt(hi, lam), U if arrows_in else -U, W)
    segments = [((ln.x1, ln.y1), (ln.x2, ln.y2)) for ln in lines if isinstance(ln, Line)]
    segments.append((pt(line_lo, lam), pt(line_hi, lam)))
    if hi - lo >= tw + 2.0:
        options = [(Text(*pt((lo + hi) / 2, lam + TEXT_GAP), text, DIM_TEXT, "middle", angle),
                    pt(line_lo, lam), pt(line_hi, lam))]
    else:  # beside the dimension, the line running on under it; away from the view's middle first
        clear = 1.5 + (0.0 if arrows_in else ARROW_LEN)
        after = (Text(*pt(hi + clear, lam + TEXT_GAP), text, DIM_TEXT, "start", angle),
                 pt(line_lo, lam), pt(max(line_hi, hi + clear + tw), lam))
        before = (Text(*pt(lo - clear, lam + TEXT_GAP), text, DIM_TEXT, "end", angle),
                  pt(min(line_lo, lo - clear - tw), lam), pt(line_hi, lam))
        outward = (lo + hi) / 2 >= float(np.array(centre) @ U) - 1e-6
        options = [after, before] if outward else [before, after]
        # where both are taken (a drawing made small for a phone's column): the text over the
        # middle of the line, which runs on under it, or any of the three under the line
        middle = (lo + hi) / 2
        over = (Text(*pt(middle, lam + TEXT_GAP), text, DIM_TEXT, "middle", angle),
                pt(min(line_lo, middle - tw / 2), lam), pt(max(line_hi, middle + tw / 2), lam))
        under = lam - TEXT_GAP - 0.8 * DIM_TEXT
        options += [over] + [(replace(t, x=t.x + (under - lam - TEXT_GAP) * W[0],
                                      y=t.y + (under - lam - TEXT_GAP) * W[1]), p, q)
                             for t, p, q in (*options, over)]
    return _DimDraft(lines, options, segments)


def _aligned_frame(pa: np.ndarray, pb: np.ndarray, offset: float):
    """Along (U) and "above" (W) directions, text angle and line position (across, along W) of
    an aligned dimension between the sheet points pa and pb, `offset` sheet mm to the left of
    the direction from pa to pb as the part is seen (y up)."""
    d = (pb - pa) / np.linalg.norm(pb - pa)
    left = np.array([d[1], -d[0]])  # left of d, as seen on the sheet (y down)
    U = d if d[0] > 1e-9 or (abs(d[0]) <= 1e-9 and d[1] < 0) else -d  # text reads rightwards or up
    W = np.array([U[1], -U[0]])
    angle = math.degrees(math.atan2(U[1], U[0]))
    return U, W, angle, float((pa + offset * left) @ W)


def _angle_draft(dim: Angle, k: float) -> _DimDraft:
    """An angular dimension in sheet mm about the view's origin: an arc with an arrowhead on
    each leg, an extension line for a leg that is an edge produced past the vertex, and the
    text outside the arc's middle, upright."""
    vertex = _in_view(dim, dim.vertex) * [k, -k]
    legs = _angle_legs(dim)
    # angles as seen on the sheet, counter-clockwise (the part's view axes are right-handed)
    a0, a1 = (math.atan2(leg[1], leg[0]) for leg in legs)
    if (a1 - a0) % (2 * math.pi) > math.pi:
        a0, a1, legs = a1, a0, legs[::-1]
    a1 = a0 + (a1 - a0) % (2 * math.pi)
    r = k * dim.radius
    cx, cy = float(vertex[0]), float(vertex[1])

    def at(a, radius=r):
        return np.array([cx + radius * math.cos(a), cy - radius * math.sin(a)])

    lines: list = []
    for a, leg in ((a0, legs[0]), (a1, legs[1])):
        if k * float(np.linalg.norm(leg)) < r:  # a produced edge: an extension line from the vertex
            lines.append(Line(*at(a, EXT_GAP), *at(a, r + EXT_OVER)))
    lines.append(Arc(cx, cy, r, a0, a1, "thin"))
    for a, towards in ((a0, -1.0), (a1, 1.0)):
        tip = at(a)
        tangent = towards * np.array([-math.sin(a), -math.cos(a)])  # along the arc, outwards
        lines += _arrow(tip, tangent, np.array([tangent[1], -tangent[0]]))
    text = dimension_text(dim)
    w, size = text_width(text, DIM_TEXT), DIM_TEXT
    mid = (a0 + a1) / 2
    m = np.array([math.cos(mid), -math.sin(mid)])
    reach = r + TEXT_GAP + abs(m[0]) * w / 2 + abs(m[1]) * 0.51 * size
    x, y = np.array([cx, cy]) + reach * m
    label = Text(float(x), float(y + 0.29 * size), text, size, "middle")
    segments = [((ln.x1, ln.y1), (ln.x2, ln.y2)) for ln in lines if isinstance(ln, Line)]
    return _DimDraft(lines, [(label, None, None)], segments)


def view_dimensions(dims: list[Dimension | Angle], k: float, centre: tuple[float, float],
                    placed: list | None = None, drawn: list = ()) -> list:
    """All dimensions of one view, each text placed clear of the others' texts and lines,
    and of the part's own lines (`drawn`, the view's primitives) where it can be.

    Texts with one place (inside their dimension line) are placed first, then the others, each
    at the first of its places clear of what is placed already and of the part, else clear of
    what is placed already, or failing that (a drawing made small) the first clear of the
    texts placed already. When `placed` is a list, each dimension is appended to it with the
    text it was given, as (dimension, Text): what the sheet shows for it."""
    drafts = [_dimension_draft(d, k, centre) for d in dims]
    blockers = [LineString(seg) for dr in drafts for seg in dr.segments]
    part = [g for g in map(_outline, drawn) if g is not None]
    texts: list = []
    chosen: dict[int, tuple] = {}
    for i in sorted(range(len(drafts)), key=lambda i: len(drafts[i].options) > 1):
        boxes = [shapely.box(*bbox([option[0]])) for option in drafts[i].options]
        clear = [o for o, box in zip(drafts[i].options, boxes) if not any(box.intersects(b) for b in blockers)]
        off_part = [o for o, box in zip(drafts[i].options, boxes)
                    if o in clear and not any(box.intersects(g) for g in part)]
        apart = [o for o, box in zip(drafts[i].options, boxes) if not any(box.intersects(b) for b in texts)]
        chosen[i] = (off_part or clear or apart or drafts[i].options)[0]
        texts.append(shapely.box(*bbox([chosen[i][0]])).buffer(0.5))
        blockers.append(texts[-1])
    out = []
    for i, (dim, dr) in enumerate(zip(dims, drafts)):
        text, p, q = chosen[i]
        if placed is not None:
            placed.append((dim, text))
        out += [*dr.lines, *([] if p is None else [Line(*p, *q)]), text]
    return out


def _outline(prim):
    """A drawn line of the part as a shapely line (a circle's rim, a polyline), or None for
    what a text may cover (texts, arcs' insides, fills are not lines of the part)."""
    if isinstance(prim, Line):
        return LineString([(prim.x1, prim.y1), (prim.x2, prim.y2)])
    if isinstance(prim, Circle):
        return shapely.Point(prim.cx, prim.cy).buffer(prim.r).exterior
    if isinstance(prim, Poly) and not prim.closed:
        return LineString(prim.rings[0]) if len(prim.rings[0]) > 1 else None
    if isinstance(prim, Poly):
        return shapely.LinearRing(prim.rings[0]) if len(prim.rings[0]) > 2 else None
    return None


def _arrow(tip, direction, across) -> list:
    """A filled arrowhead with its tip at `tip`, pointing along `direction`."""
    tip = np.array(tip)
    base = tip - ARROW_LEN * np.asarray(direction)
    pts = (tip, base + ARROW_HALF * across, base - ARROW_HALF * across)
    return [Poly((tuple((float(x), float(y)) for x, y in pts),), True, "solid")]
