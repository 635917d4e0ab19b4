"""The sheet of a drawing and the part drawing on it.

The A4 frame with its centring marks, the title block with the first-angle projection symbol, the
standard scales, placing views on the sheet clear of the title block (first-angle arrangement),
and `part_drawing_svg`: a part in three views with dimensions.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..parts import Part
from .dimensions import check_dimensions, view_dimensions
from .projection import CENTRE_EXT, VIEWS, Projector, ViewLines, trace_view, view_prims
from .solids import Solid, shape_corners
from .svg import (SHEET_H, SHEET_W, Circle, Line, Poly, Text, bbox, document, fmt, moved, text_width,
                  views_box)

FRAME = (20.0, 10.0, 287.0, 200.0)  # ISO 5457: 20 mm filing margin on the left, 10 mm elsewhere
TITLE_W, TITLE_H = 180.0, 28.0
TITLE_BLOCK = (FRAME[2] - TITLE_W, FRAME[3] - TITLE_H, FRAME[2], FRAME[3])
LABEL_TEXT = 3.5  # mm, the views' names
VIEW_GAP = 10.0  # clear space between neighbouring views (with their dimensions)

# Standard scales (ISO 5455, plus 1:2.5), largest first: the largest that fits is used.
SCALES = [("5:1", 5.0), ("2:1", 2.0), ("1:1", 1.0), ("1:2", 0.5), ("1:2.5", 0.4), ("1:5", 0.2),
          ("1:10", 0.1), ("1:20", 0.05), ("1:50", 0.02), ("1:100", 0.01)]


# --- title block, frame, projection symbol -------------------------------------------------------


def fit(text: str, width: float, size: float) -> float:
    """The largest lettering size up to `size` at which `text` fits in `width` mm."""
    return min(size, width / max(text_width(text, 1.0), 1e-9))


def _cell(x, y, w, h, label, value, size=3.5, bold=False) -> list:
    out = [Text(x + 1.2, y + 2.4, label, 1.8, "start", style="grey")]
    if value:
        s = fit(value, w - 2.4, size)
        out.append(Text(x + 1.2, y + h - 1.6, value, s, "start", bold=bold))
    return out


def frame() -> list:
    """The border frame with ISO 5457 centring marks."""
    x0, y0, x1, y1 = FRAME
    out = [Poly((((x0, y0), (x1, y0), (x1, y1), (x0, y1)),), True, "border")]
    cx, cy = (x0 + x1) / 2, (y0 + y1) / 2
    out += [Line(cx, 5.0, cx, y0, "border"), Line(cx, y1, cx, SHEET_H - 5.0, "border"),
            Line(5.0, cy, x0, cy, "border"), Line(x1, cy, SHEET_W - 5.0, cy, "border")]
    return out


def _projection_symbol(x: float, y: float) -> list:
    """ISO 5456-2 first-angle symbol at (x, y) (top left): the truncated cone's front view with
    its end view (seen from the small end, on the left) drawn to the right of it."""
    h = 2.2  # half the large diameter
    cy = y + h
    cone = ((x, cy - h / 2), (x + 6.0, cy - h), (x + 6.0, cy + h), (x, cy + h / 2))
    cx = x + 6.0 + 3.0 + h
    return [Poly((cone,), True, "medium"), Circle(cx, cy, h, "medium"), Circle(cx, cy, h / 2, "medium"),
            Line(x - 1.0, cy, cx + h + 1.0, cy, "centre"), Line(cx, cy - h - 1.0, cx, cy + h + 1.0, "centre")]


def title_block(title: str, file_name: str, material: str, density: str, mass: str, scale: str) -> list:
    """An ISO 7200-like title block in the frame's bottom right corner."""
    x0, y0, x1, y1 = TITLE_BLOCK
    r1, r2 = y0 + 8.0, y0 + 16.0
    out = [Poly((((x0, y0), (x1, y0), (x1, y1), (x0, y1)),), True, "visible"),
           Line(x0, r1, x1, r1), Line(x0, r2, x1, r2)]
    out += [Line(x0 + 70, y0, x0 + 70, r2), Line(x0 + 105, y0, x0 + 105, y1),
            Line(x0 + 140, y0, x0 + 140, r1), Line(x0 + 150, r2, x0 + 150, y1)]
    out += _cell(x0, y0, 70, 8, "Material", material)
    out += _cell(x0 + 70, y0, 35, 8, "Density", density)
    out += _cell(x0 + 105, y0, 35, 8, "Mass", mass)
    out += _cell(x0 + 140, y0, 40, 8, "Scale", scale)
    out += _cell(x0, r1, 70, 8, "General tolerance", "ISO 2768-m")
    out += _cell(x0 + 70, r1, 35, 8, "Units", "Dimensions in mm", 3.0)
    out += _cell(x0 + 105, r1, 75, 8, "Projection", "")
    out += _projection_symbol(x0 + 108.0, r1 + 2.5)
    out.append(Text(x0 + 126.0, r2 - 2.0, "First angle projection", 3.0, "start"))
    out += _cell(x0, r2, 105, 12, "Title", title, 6.0, bold=True)
    out += _cell(x0 + 105, r2, 45, 12, "File name", file_name, 3.5)
    out += _cell(x0 + 150, r2, 30, 12, "Sheet", "1/1", 3.5)
    return out


# --- placing views on the sheet ------------------------------------------------------------------


def boxes_fit(boxes, reserved, margin: float = 3.0):
    """Front-view origins (x, y) at which every box lies in the frame clear of `reserved`.

    `boxes` are (x0, y0, x1, y1) relative to the front view's origin. Returns the feasible origin
    nearest the middle of the space above the reserved block, or None.
    """
    fx0, fy0, fx1, fy1 = FRAME[0] + margin, FRAME[1] + margin, FRAME[2] - margin, FRAME[3] - margin
    b = np.array(boxes)
    xs = np.arange(fx0 - b[:, 0].min(), fx1 - b[:, 2].max() + 1e-9, 0.5)
    ys = np.arange(fy0 - b[:, 1].min(), fy1 - b[:, 3].max() + 1e-9, 0.5)
    if not len(xs) or not len(ys):
        return None
    X, Y = np.meshgrid(xs, ys)
    ok = np.ones(X.shape, dtype=bool)
    for rx0, ry0, rx1, ry1 in reserved:
        for x0, y0, x1, y1 in b:  # clear of the reserved rectangle, with a margin
            ok &= ((X + x1 <= rx0 - margin) | (X + x0 >= rx1 + margin)
                   | (Y + y1 <= ry0 - margin) | (Y + y0 >= ry1 + margin))
    if not ok.any():
        return None
    top = min(r[1] for r in reserved)
    tx, ty = (FRAME[0] + FRAME[2]) / 2, (FRAME[1] + top) / 2
    cx = X + (b[:, 0].min() + b[:, 2].max()) / 2
    cy = Y + (b[:, 1].min() + b[:, 3].max()) / 2
    score = np.where(ok, (cx - tx) ** 2 + (cy - ty) ** 2, np.inf)
    i = np.unravel_index(int(np.argmin(score)), score.shape)
    return float(X[i]), float(Y[i])


def view_label(prims, text: str, centre_x: float) -> list:
    """The view's name, centred under everything drawn for it."""
    _, _, _, y1 = bbox(prims)
    return [Text(centre_x, y1 + 6.0, text, LABEL_TEXT, "middle", bold=True)]


# --- the part drawing ----------------------------------------------------------------------------


def _part_view(part: Part, solid: Solid, view: str, k: float, traced: ViewLines | None,
               placed: list | None = None) -> list:
    """Everything of one view, in sheet mm about the part's origin: lines, dimensions, name.

    With `traced` None only the extents are needed (the outline box stands in for the lines).
    `placed`, when given, receives each dimension of the view with its text (see
    `view_dimensions`)."""
    proj = Projector(solid, view)
    pts = proj.project(np.concatenate([shape_corners(s) for s in solid.added]))
    h0, v0 = pts.min(0)
    h1, v1 = pts.max(0)
    outline = Poly((((k * h0, -k * v0), (k * h1, -k * v0), (k * h1, -k * v1), (k * h0, -k * v1)),), True)
    centre = (k * (h0 + h1) / 2, -k * (v0 + v1) / 2)
    if traced is None:  # centre lines reach past the outline; allow for them
        c = CENTRE_EXT
        prims = [outline, Line(k * h0 - c, -k * v0 + c, k * h1 + c, -k * v1 - c)]
    else:
        prims = view_prims(traced, proj, k)
    prims += view_dimensions([d for d in part.dimensions if d.view == view], k, centre, placed,
                             drawn=prims if traced is not None else ())
    return prims + view_label(prims, view.upper(), centre[0])


def _first_angle(boxes: dict) -> dict:
    """Offsets of the views from the front view's origin, in first-angle projection.

    First angle: the part sits between the viewer and the drawing plane, and each view is
    projected through the part onto the plane behind it. So the view from above (top, looking
    down -z) lands BELOW the front view, and the view from the right (side, looking along -x
    from +x) lands to the LEFT of the front view. Front and top share the x columns; front and
    side share the z rows.
    """
    f, t, s = boxes["front"], boxes["top"], boxes["side"]
    dy = f[3] - t[1] + VIEW_GAP  # top view under the front view
    dx = s[2] - f[0] + VIEW_GAP  # side view left of the front view
    if s[3] + VIEW_GAP > t[1] + dy + 1e-6 and s[2] - dx + VIEW_GAP > t[0] + 1e-6:
        dx = s[2] - t[0] + VIEW_GAP  # the side view reaches down beside the top view: clear it
    return {"front": (0.0, 0.0), "side": (-dx, 0.0), "top": (0.0, dy)}


@dataclass
class PartSheet:
    """A part's drawing before it is written out: its layers (name, primitives) in sheet mm,
    and every dimension with the text the sheet shows for it, as (view, dimension, Text)."""

    title: str
    layers: list
    dimensions: list

    def svg(self) -> str:
        """The whole A4 sheet: frame and title block included."""
        return document(self.layers, self.title)

    def views_svg(self) -> str:
        """Only the views with their dimensions, cropped close: what a page shows, so that
        the lettering is large enough at the page's width (the sheet is linked beside it)."""
        views = [(name, prims) for name, prims in self.layers if name != "sheet"]
        return document(views, self.title, views_box(views))


def part_drawing_svg(part: Part, views_only: bool = False) -> str:
    """The part's drawing: three first-angle views with dimensions, frame and title block
    (or, `views_only`, the views and their dimensions alone)."""
    sheet = part_sheet(part)
    return sheet.views_svg() if views_only else sheet.svg()


def _sheet_layout(part: Part, solid: Solid):
    """The largest standard scale at which the part's views fit the sheet: its label, k (sheet
    mm per metre), the views' offsets from the front view and the front view's origin."""
    for label, factor in SCALES:
        k = 1000.0 * factor
        boxes = {v: bbox(_part_view(part, solid, v, k, None)) for v in VIEWS}
        offsets = _first_angle(boxes)
        placed = [(b[0] + offsets[v][0], b[1] + offsets[v][1], b[2] + offsets[v][0], b[3] + offsets[v][1])
                  for v, b in boxes.items()]
        origin = boxes_fit(placed, [TITLE_BLOCK])
        if origin is not None:
            return label, k, offsets, origin
    raise ValueError(f"part {part.name!r} does not fit an A4 sheet at 1:100")


def part_sheet(part: Part) -> PartSheet:
    """The part's drawing sheet as primitives, with the dimensions placed on it."""
    check_dimensions(part)
    solid = Solid(part.features)
    label, k, offsets, origin = _sheet_layout(part, solid)
    layers, dims = [], []
    for view in VIEWS:
        traced = trace_view(solid, view, k)
        placed: list = []
        prims = _part_view(part, solid, view, k, traced, placed)
        dx, dy = origin[0] + offsets[view][0], origin[1] + offsets[view][1]
        layers.append((f"view-{view}", moved(prims, dx, dy)))
        dims += [(view, dim, text.moved(dx, dy)) for dim, text in placed]
    m = part.material
    block = title_block(part.title or part.name, f"{part.name}.SLDPRT", m.name,
                         f"{fmt(m.density)} kg/m³", f"{part.mass:.3f} kg", label)
    layers.append(("sheet", frame() + block))
    return PartSheet(f"{part.title or part.name} ({part.name}.SLDPRT)", layers, dims)


# --- the views for a narrow column ---------------------------------------------------------------


def largest_fitting(wide, k: float, width: float) -> float:
    """The largest scale up to `k` (sheet mm per metre) at which what is drawn, `wide(k)` mm
    wide, is at most `width` mm wide: `k` itself when it fits. The lettering keeps its size
    at every scale, so the width is not proportional to the scale: the scale is found by
    halving an interval, then rounded down to a tenth of a sheet mm per metre."""
    if wide(k) <= width:
        return k
    low, high = k / 64, k
    if wide(low) > width:
        raise ValueError(f"the views cannot be drawn {width:g} mm wide even at 1/64 of the sheet's "
                         "scale: their lettering alone is wider")
    for _ in range(24):
        middle = (low + high) / 2
        low, high = (middle, high) if wide(middle) <= width else (low, middle)
    return math.floor(low * 10) / 10


def _stacked(views: dict) -> list:
    """The views one above the other: the top view under the front view, sharing its columns
    as in first-angle projection, and the side view under the top view, centred under both.
    `views` are each view's primitives about its own origin; returns the layers."""
    f, t, s = (bbox(views[v]) for v in ("front", "top", "side"))
    top_dy = f[3] - t[1] + VIEW_GAP
    middle = (min(f[0], t[0]) + max(f[2], t[2])) / 2
    side = (middle - (s[0] + s[2]) / 2, t[3] + top_dy - s[1] + VIEW_GAP)
    offsets = {"front": (0.0, 0.0), "top": (0.0, top_dy), "side": side}
    return [(f"view-{v}", moved(views[v], *offsets[v])) for v in VIEWS]


def part_views_narrow_svg(part: Part, width: float) -> str:
    """The part's views for a narrow column (a phone's: course/drawing/narrow.py): one above
    the other (`_stacked`), each named, with its dimensions, at the sheet's scale or, if that
    makes them wider than `width` mm, the largest that does not: the front and top views,
    which share their columns, at one scale, the side view, centred under them, at its own
    (never smaller), so that a part's short side is not drawn as small as its long top. The
    lettering is as large as on the sheet."""
    check_dimensions(part)
    solid = Solid(part.features)
    _, sheet_k, _, _ = _sheet_layout(part, solid)

    def wide(views: tuple[str, ...], k: float) -> float:
        x0, _, x1, _ = bbox([p for v in views for p in _part_view(part, solid, v, k, None)])
        return x1 - x0

    k = largest_fitting(lambda k: wide(("front", "top"), k), sheet_k, width)
    scales = {"front": k, "top": k, "side": max(k, largest_fitting(lambda k: wide(("side",), k), sheet_k, width))}
    layers = _stacked({v: _part_view(part, solid, v, scales[v], trace_view(solid, v, scales[v])) for v in VIEWS})
    return document(layers, f"{part.title or part.name} ({part.name}.SLDPRT)", views_box(layers))
