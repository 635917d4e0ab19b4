"""Engineering drawings (SVG) made from the same features as the part meshes.

`part_drawing_svg` draws one part in three orthographic views (first-angle
projection), with ISO-style dimensions and a title block. `assembly_drawing_svg`
draws a robot's links in a front and a top view, with balloons, a parts list and
the joints' origins and axes. Both are A4 landscape sheets (297 x 210 mm) drawn in
millimetres at a standard scale, and both are deterministic: the same input gives
the same bytes.

A part's lines are computed from its features exactly, not from its mesh: every
edge, face seen edge-on and cylinder silhouette of every feature is a candidate
line; a candidate is drawn where it is really on the solid's boundary, as a visible
line where nothing lies between it and the viewer, dashed where something does.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Callable

import numpy as np
import shapely
from shapely import affinity
from shapely.geometry import LineString, MultiPolygon, Polygon
from shapely.ops import polylabel

from .parts import Angle, Box, Cylinder, Dimension, Part

# --- sheet, lettering and line types ---------------------------------------------------------

SHEET_W, SHEET_H = 297.0, 210.0
FRAME = (20.0, 10.0, 287.0, 200.0)  # ISO 5457: 20 mm filing margin on the left, 10 mm elsewhere
TITLE_W, TITLE_H = 180.0, 28.0
TITLE_BLOCK = (FRAME[2] - TITLE_W, FRAME[3] - TITLE_H, FRAME[2], FRAME[3])
FONT = "DejaVu Sans, Arial, sans-serif"

DIM_TEXT = 3.5  # mm, ISO 3098 lettering for dimensions
LABEL_TEXT = 3.5
ARROW_LEN, ARROW_HALF = 3.0, 0.55  # filled arrowhead, about 20 degrees included angle
EXT_GAP, EXT_OVER, TEXT_GAP = 1.0, 2.0, 1.0  # extension line: gap at the part, overshoot
CENTRE_EXT = 3.0  # centre lines run this far past the feature
VIEW_GAP = 10.0  # clear space between neighbouring views (with their dimensions)
SAMPLE_STEP = 0.4  # sheet mm between samples when tracing a candidate line
MIN_RUN = 0.2  # sheet mm: shorter line pieces and gaps are numerical noise

# Standard scales (ISO 5455, plus 1:2.5), largest first: the largest that fits is used.
SCALES = [("5:1", 5.0), ("2:1", 2.0), ("1:1", 1.0), ("1:2", 0.5), ("1:2.5", 0.4), ("1:5", 0.2),
          ("1:10", 0.1), ("1:20", 0.05), ("1:50", 0.02), ("1:100", 0.01)]

# ISO 128 line widths (0.5 mm group): every visible edge is a wide line, the rest are narrow.
STYLES = {
    "visible": 'stroke="#000" stroke-width="0.5" stroke-linecap="round" stroke-linejoin="round" fill="none"',
    "hidden": 'stroke="#000" stroke-width="0.25" fill="none"',
    "centre": 'stroke="#000" stroke-width="0.25" fill="none"',
    "thin": 'stroke="#000" stroke-width="0.25" fill="none"',
    "medium": 'stroke="#000" stroke-width="0.35" fill="none"',
    "border": 'stroke="#000" stroke-width="0.7" fill="none"',
    "solid": 'fill="#000" stroke="none"',
    "joint": 'stroke="#b03020" stroke-width="0.35" fill="none"',
    "jointfill": 'fill="#b03020" stroke="none"',
    "jointleader": 'stroke="#b03020" stroke-width="0.18" fill="none"',
    "text": f'fill="#000" font-family="{FONT}"',
    "grey": f'fill="#555" font-family="{FONT}"',
    "jointtext": f'fill="#b03020" font-family="{FONT}"',
}
CENTRE_DASH = (8.0, 1.5, 0.5, 1.5)  # long dash, gap, dot, gap (ISO 128 type 04)
HIDDEN_DASH = (2.5, 1.2)  # dash, gap (ISO 128 type 02)

# Views as the Dimension docstring fixes them: (viewing direction, horizontal, vertical).
# Each is right-handed: horizontal x vertical points back at the viewer.
VIEWS = {
    "front": ((0.0, 1.0, 0.0), (1.0, 0.0, 0.0), (0.0, 0.0, 1.0)),
    "top": ((0.0, 0.0, -1.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)),
    "side": ((-1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)),
}

# DejaVu Sans advance widths (per em) to estimate text lengths without a font at run time.
_GLYPHS = (" !\"#$%&'()*+,-./0123456789:;<=>?@ABCDEFGHIJKLMNOPQRSTUVWXYZ[\\]^_`"
           "abcdefghijklmnopqrstuvwxyz{|}~Øø×°±ρ³²µ–·")
_ADVANCES = (
    "318 401 460 838 636 950 780 275 390 390 500 838 318 361 318 337 636 636 636 636 636 636 636 "
    "636 636 636 337 337 838 838 838 531 1000 684 686 698 770 632 575 775 752 295 295 656 557 863 "
    "748 787 603 787 695 635 611 732 684 989 685 611 685 390 337 390 838 500 500 613 635 550 635 "
    "615 352 635 634 278 278 579 278 974 634 612 635 635 411 521 392 634 592 818 592 592 525 636 "
    "337 636 838 787 612 838 500 838 635 401 401 636 500 318")
ADVANCE = dict(zip(_GLYPHS, (int(w) / 1000 for w in _ADVANCES.split())))


def text_width(text: str, size: float) -> float:
    """Estimated width in mm of `text` set at `size` mm (DejaVu Sans; narrower fonts fit too)."""
    return size * sum(ADVANCE.get(ch, 0.65) for ch in text)


def fmt(v: float) -> str:
    """A coordinate rounded to 0.01 mm, without trailing zeros (deterministic and compact)."""
    s = f"{v:.2f}".rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


def mm_text(length_m: float) -> str:
    """A length in metres as the millimetre figure a drawing shows: 0.3 -> '300', 0.0125 -> '12.5'."""
    return fmt(length_m * 1000.0)


def _esc(text: str) -> str:
    return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")


# --- sheet primitives --------------------------------------------------------------------------
# Everything on the sheet is one of these, in sheet millimetres (y down). Each can be moved (views
# are drawn about their own origin, then placed), report its points (for extents) and write SVG.


@dataclass(frozen=True)
class _Line:
    x1: float
    y1: float
    x2: float
    y2: float
    style: str = "thin"

    def moved(self, dx, dy):
        return replace(self, x1=self.x1 + dx, y1=self.y1 + dy, x2=self.x2 + dx, y2=self.y2 + dy)

    def points(self):
        return [(self.x1, self.y1), (self.x2, self.y2)]

    def svg(self):
        extra = _dashes(self.style, math.hypot(self.x2 - self.x1, self.y2 - self.y1), closed=False)
        return (f'<line x1="{fmt(self.x1)}" y1="{fmt(self.y1)}" x2="{fmt(self.x2)}" '
                f'y2="{fmt(self.y2)}"{extra}/>')


def _dashes(style: str, length: float, closed: bool) -> str:
    """A dash pattern stretched to the element's length, so that an open line starts and ends
    with a dash (ISO 128): centre lines with an odd number of long dashes, so that two centre
    lines cross at long dashes; hidden lines with whole dashes at both ends."""
    if style == "hidden":
        dash, gap = HIDDEN_DASH
    elif style == "centre":
        long_, gap1, dot, gap2 = CENTRE_DASH
        link = gap1 + dot + gap2
        if closed:
            n = max(2, round(length / (long_ + link)))
            return f' stroke-dasharray="{fmt(length / n - link)} {fmt(gap1)} {fmt(dot)} {fmt(gap2)}"'
        n = max(1, 2 * round(((length + link) / (long_ + link) - 1) / 2) + 1)
        if n == 1:
            return ""
        return f' stroke-dasharray="{fmt((length - (n - 1) * link) / n)} {fmt(gap1)} {fmt(dot)} {fmt(gap2)}"'
    else:
        return ""
    if closed:
        n = max(2, round(length / (dash + gap)))
        return f' stroke-dasharray="{fmt(length / n - gap)} {fmt(gap)}"'
    # at least two dashes, or a short hidden line would look like a visible one
    n = max(2 if length > 2 * gap else 1, round((length + gap) / (dash + gap)))
    return "" if n == 1 else f' stroke-dasharray="{fmt((length - (n - 1) * gap) / n)} {fmt(gap)}"'


@dataclass(frozen=True)
class _Circle:
    cx: float
    cy: float
    r: float
    style: str = "visible"

    def moved(self, dx, dy):
        return replace(self, cx=self.cx + dx, cy=self.cy + dy)

    def points(self):
        return [(self.cx - self.r, self.cy - self.r), (self.cx + self.r, self.cy + self.r)]

    def svg(self):
        extra = _dashes(self.style, 2 * math.pi * self.r, closed=True)
        return f'<circle cx="{fmt(self.cx)}" cy="{fmt(self.cy)}" r="{fmt(self.r)}"{extra}/>'


@dataclass(frozen=True)
class _Arc:
    """A circular arc from angle a0 to a1 (radians, counter-clockwise as seen on the sheet)."""

    cx: float
    cy: float
    r: float
    a0: float
    a1: float
    style: str = "visible"

    def moved(self, dx, dy):
        return replace(self, cx=self.cx + dx, cy=self.cy + dy)

    def _at(self, a):
        return self.cx + self.r * math.cos(a), self.cy - self.r * math.sin(a)

    def points(self):
        n = max(2, int(abs(self.a1 - self.a0) / 0.1) + 1)
        return [self._at(self.a0 + (self.a1 - self.a0) * i / (n - 1)) for i in range(n)]

    def svg(self):
        (x0, y0), (x1, y1) = self._at(self.a0), self._at(self.a1)
        large = 1 if self.a1 - self.a0 > math.pi else 0
        extra = _dashes(self.style, self.r * (self.a1 - self.a0), closed=False)
        # Counter-clockwise on the sheet is sweep-flag 0 in SVG's y-down coordinates.
        return (f'<path d="M{fmt(x0)} {fmt(y0)}A{fmt(self.r)} {fmt(self.r)} 0 {large} 0 '
                f'{fmt(x1)} {fmt(y1)}"{extra}/>')


class _Rings:
    """Shared by shapes made of point rings: shift them, list their points."""

    def moved(self, dx, dy):
        return replace(self, rings=tuple(tuple((x + dx, y + dy) for x, y in r) for r in self.rings))

    def points(self):
        return [p for r in self.rings for p in r]


@dataclass(frozen=True)
class _Poly(_Rings):
    """A polyline or closed polygon (rings: the first outer, the rest holes when filled)."""

    rings: tuple
    closed: bool = False
    style: str = "visible"

    def svg(self):
        parts = []
        for ring in self.rings:
            pts = [f"{fmt(x)} {fmt(y)}" for x, y in ring]
            parts.append("M" + "L".join(pts) + ("Z" if self.closed else ""))
        fill = ' fill-rule="evenodd"' if self.closed and len(self.rings) > 1 else ""
        if self.style in ("hidden", "centre") and len(self.rings) == 1:
            ring = np.array(self.rings[0])
            fill += _dashes(self.style, float(np.linalg.norm(np.diff(ring, axis=0), axis=1).sum()), False)
        return f'<path d="{"".join(parts)}"{fill}/>'


@dataclass(frozen=True)
class _Text:
    x: float
    y: float
    text: str
    size: float = DIM_TEXT
    anchor: str = "middle"  # start / middle / end
    angle: float = 0.0  # degrees, SVG sense (-90: reads upwards)
    bold: bool = False
    style: str = "text"

    def moved(self, dx, dy):
        return replace(self, x=self.x + dx, y=self.y + dy)

    def points(self):
        """Corners of the text's box (estimated), turned with the text."""
        w = text_width(self.text, self.size)
        start = {"start": 0.0, "middle": -w / 2, "end": -w}[self.anchor]
        a = math.radians(self.angle)
        ux, uy = math.cos(a), math.sin(a)  # reading direction
        nx, ny = -uy, ux  # down the glyphs (y down)
        out = []
        for along in (start, start + w):
            for down in (-0.8 * self.size, 0.22 * self.size):
                out.append((self.x + along * ux + down * nx, self.y + along * uy + down * ny))
        return out

    def svg(self):
        attrs = f'x="{fmt(self.x)}" y="{fmt(self.y)}" font-size="{fmt(self.size)}"'
        if self.anchor != "start":
            attrs += f' text-anchor="{self.anchor}"'
        if self.bold:
            attrs += ' font-weight="bold"'
        if self.angle:
            attrs += f' transform="rotate({fmt(self.angle)} {fmt(self.x)} {fmt(self.y)})"'
        return f"<text {attrs}>{_esc(self.text)}</text>"


@dataclass(frozen=True)
class _Fill(_Rings):
    """A filled region drawn before the lines of its layer (white for assembly occlusion)."""

    rings: tuple
    colour: str = "#fff"
    style: str = "fill"

    def svg(self):
        d = "".join("M" + "L".join(f"{fmt(x)} {fmt(y)}" for x, y in r) + "Z" for r in self.rings)
        return f'<path d="{d}" fill="{self.colour}" fill-rule="evenodd" stroke="none"/>'


STYLE_ORDER = ["fill", "hidden", "centre", "thin", "medium", "visible", "border", "solid",
               "jointleader", "joint", "jointfill", "grey", "text", "jointtext"]


def _bbox(prims) -> tuple[float, float, float, float]:
    pts = np.array([p for pr in prims for p in pr.points()], dtype=float)
    return float(pts[:, 0].min()), float(pts[:, 1].min()), float(pts[:, 0].max()), float(pts[:, 1].max())


def _moved(prims, dx, dy):
    return [p.moved(dx, dy) for p in prims]


def _layer_svg(prims, name: str = "") -> list[str]:
    """One <g> per style, in a fixed order, so wide lines lie over thin ones."""
    out = [f'<g id="{name}">' if name else "<g>"]
    for style in STYLE_ORDER:
        chosen = [p for p in prims if p.style == style]
        if not chosen:
            continue
        attrs = f" {STYLES[style]}" if style in STYLES else ""
        out.append(f"<g{attrs}>")
        out.extend(p.svg() for p in chosen)
        out.append("</g>")
    out.append("</g>")
    return out


def _document(layers: list[tuple[str, list]], title: str) -> str:
    lines = [
        '<?xml version="1.0" encoding="UTF-8" standalone="no"?>',
        f'<svg xmlns="http://www.w3.org/2000/svg" version="1.1" width="{fmt(SHEET_W)}mm" '
        f'height="{fmt(SHEET_H)}mm" viewBox="0 0 {fmt(SHEET_W)} {fmt(SHEET_H)}">',
        f"<title>{_esc(title)}</title>",
        f'<rect x="0" y="0" width="{fmt(SHEET_W)}" height="{fmt(SHEET_H)}" fill="#fff"/>',
    ]
    for name, prims in layers:
        lines.extend(_layer_svg(prims, name))
    lines.append("</svg>")
    return "\n".join(lines) + "\n"


# --- exact point and line queries on a part's features ----------------------------------------


def _yaw_matrix(deg: float) -> np.ndarray:
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


class _Shape:
    """One feature as a solid the queries understand: a turned box or a cylinder."""

    def __init__(self, f: Box | Cylinder):
        rot = _yaw_matrix(f.yaw)
        self.feature = f
        self.c = np.asarray(f.center, dtype=float)
        if isinstance(f, Box):
            self.kind = "box"
            self.E = rot.T.copy()  # rows: the box's own x, y, z in the part frame
            self.h = np.asarray(f.size, dtype=float) / 2
        else:
            if f.axis not in ("x", "y", "z"):
                raise ValueError(f"cylinder axis must be 'x', 'y' or 'z', not {f.axis!r}")
            self.kind = "cyl"
            self.a = rot @ np.eye(3)[{"x": 0, "y": 1, "z": 2}[f.axis]]
            self.r = float(f.radius)
            self.hl = float(f.length) / 2

    def contains(self, P: np.ndarray) -> np.ndarray:
        rel = P - self.c
        if self.kind == "box":
            return np.all(np.abs(rel @ self.E.T) <= self.h + 1e-12, axis=1)
        s = rel @ self.a
        radial2 = np.einsum("ij,ij->i", rel, rel) - s * s
        return (np.abs(s) <= self.hl + 1e-12) & (radial2 <= self.r * self.r + 1e-15)

    def span(self, O: np.ndarray, u: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Where the lines O + t u are inside: (t_in, t_out), empty when t_in >= t_out."""
        n = len(O)
        t0, t1 = np.full(n, -np.inf), np.full(n, np.inf)
        rel = O - self.c
        if self.kind == "box":
            slabs = [(rel @ e, float(u @ e), h) for e, h in zip(self.E, self.h)]
        else:
            slabs = [(rel @ self.a, float(u @ self.a), self.hl)]
        for o, w, h in slabs:
            if abs(w) < 1e-12:
                out = np.abs(o) > h
                t0[out], t1[out] = np.inf, -np.inf
            else:
                a, b = (-h - o) / w, (h - o) / w
                t0, t1 = np.maximum(t0, np.minimum(a, b)), np.minimum(t1, np.maximum(a, b))
        if self.kind == "cyl":
            sa, ua = rel @ self.a, float(u @ self.a)
            w0 = rel - sa[:, None] * self.a
            wu = u - ua * self.a
            A, B = float(wu @ wu), 2 * (w0 @ wu)
            C = np.einsum("ij,ij->i", w0, w0) - self.r ** 2
            if A < 1e-18:  # a line along the axis: inside the whole way or not at all
                out = C > 0
                t0[out], t1[out] = np.inf, -np.inf
            else:
                disc = B * B - 4 * A * C
                sq = np.sqrt(np.maximum(disc, 0.0))
                r0, r1 = (-B - sq) / (2 * A), (-B + sq) / (2 * A)
                r0[disc < 0], r1[disc < 0] = np.inf, -np.inf
                t0, t1 = np.maximum(t0, r0), np.minimum(t1, r1)
        return t0, t1


class _Solid:
    """The part as added and cut features, queried exactly (no mesh, no sampling in depth)."""

    def __init__(self, features):
        self.shapes = [_Shape(f) for f in features]
        self.added = [s for s in self.shapes if not s.feature.cut]
        self.cuts = [s for s in self.shapes if s.feature.cut]
        corners = np.concatenate([_shape_corners(s) for s in self.added])
        self.lo, self.hi = corners.min(0), corners.max(0)
        self.reach = float(np.linalg.norm(self.hi - self.lo)) + 1e-3
        self.eps = 1e-6 * max(1.0, self.reach)

    def contains(self, P: np.ndarray) -> np.ndarray:
        inside = np.zeros(len(P), dtype=bool)
        for s in self.added:
            inside |= s.contains(P)
        for s in self.cuts:
            inside &= ~s.contains(P)
        return inside

    def pieces(self, origins: list[np.ndarray], u: np.ndarray, lo, hi):
        """Cut the lines O + t u, t in [lo, hi], at every feature boundary (all origin sets alike).

        Returns the sorted cut points (N, K) and, for each origin set, whether each of the K-1
        pieces is material (M, N, K-1). A piece of zero length is reported empty.
        """
        n = len(origins[0])
        lo, hi = np.broadcast_to(lo, (n,)).astype(float), np.broadcast_to(hi, (n,)).astype(float)
        cols = [lo, hi]
        for O in origins:
            for s in self.shapes:
                t0, t1 = s.span(O, u)
                ok = t0 < t1
                cols += [np.where(ok, t0, lo), np.where(ok, t1, lo)]
        cuts = np.sort(np.clip(np.stack(cols, axis=1), lo[:, None], hi[:, None]), axis=1)
        mid = (cuts[:, 1:] + cuts[:, :-1]) / 2
        real = (cuts[:, 1:] - cuts[:, :-1]) > 1e-10
        occ = np.stack([
            self.contains((O[:, None, :] + mid[..., None] * u).reshape(-1, 3)).reshape(mid.shape) & real
            for O in origins])
        return cuts, occ

    def blocked(self, O: np.ndarray, u: np.ndarray) -> np.ndarray:
        """Whether material lies on the rays O + t u, t > 0 (the part is hidden there)."""
        if not len(O):
            return np.zeros(0, dtype=bool)
        cuts, occ = self.pieces([O], u, 0.0, 2 * self.reach)
        return (((cuts[:, 1:] - cuts[:, :-1]) > 1e-9 * self.reach) & occ[0]).any(axis=1)


def _shape_corners(s: _Shape) -> np.ndarray:
    """Points whose hull contains the shape (exact extents along any of the part's axes)."""
    if s.kind == "box":
        signs = np.array([[i, j, k] for i in (-1, 1) for j in (-1, 1) for k in (-1, 1)], dtype=float)
        return s.c + (signs * s.h) @ s.E
    pts = []
    for end in (-1, 1):
        ce = s.c + end * s.hl * s.a
        for axis in np.eye(3):
            perp = axis - (axis @ s.a) * s.a
            norm = np.linalg.norm(perp)
            if norm > 1e-12:
                pts += [ce + s.r * perp / norm, ce - s.r * perp / norm]
        pts.append(ce)
    return np.array(pts)


# --- the lines of one view ---------------------------------------------------------------------


@dataclass
class _Curve:
    """A candidate line of a view, traced by a parameter t in [0, period).

    kind 'seg' is a straight segment (t in [0, 1]), 'arc' a circle about `centre` (t an angle),
    'poly' any other closed curve. `state(t)` is 0 where the candidate is not on the solid's
    boundary, 1 where it is hidden and 2 where it is visible.
    """

    kind: str
    shape: int
    role: str
    where: Callable[[np.ndarray], np.ndarray]  # t -> (N, 3) points of the part
    state: Callable[[np.ndarray], np.ndarray]
    period: float = 1.0
    centre: tuple = (0.0, 0.0)
    radius: float = 0.0


@dataclass
class _ViewLines:
    """The traced lines of one view, in metres of the part, view plane (h right, v up)."""

    visible: list = field(default_factory=list)  # (curve, t0, t1)
    hidden: list = field(default_factory=list)
    centre: list = field(default_factory=list)  # ('line', p, q) or ('circle', centre, radius)


class _Projector:
    """One of the three views of a solid: projection, candidate lines and their visibility."""

    def __init__(self, solid: _Solid, view: str):
        d, h, v = (np.array(x) for x in VIEWS[view])
        self.solid, self.name, self.d, self.h, self.v = solid, view, d, h, v
        self.P = np.stack([h, v])

    def project(self, X: np.ndarray) -> np.ndarray:
        return np.asarray(X, dtype=float) @ self.P.T

    # candidate states ---------------------------------------------------------------------------

    def _sweep_state(self, B, n, s0, s1):
        """A surface containing the viewing direction: drawn where it bounds the solid somewhere
        along the sight line, visible when its nearest such point can be seen."""
        eps, d, solid = self.solid.eps, self.d, self.solid
        cuts, occ = solid.pieces([B + eps * n, B - eps * n], d, s0, s1)
        exists = occ[0] != occ[1]
        has = exists.any(axis=1)
        state = np.zeros(len(B), dtype=int)
        if not has.any():
            return state
        rows = np.nonzero(has)[0]
        i = exists[rows].argmax(axis=1)
        start, end = cuts[rows, i], cuts[rows, i + 1]
        q = B[rows] + (start + np.minimum((end - start) / 2, 10 * eps))[:, None] * d
        side = np.where(occ[0][rows, i], -eps, eps)  # step off the surface on its empty side
        seen = ~solid.blocked(q + side[:, None] * n[rows], -d)
        state[rows] = np.where(seen, 2, 1)
        return state

    def _probe_state(self, B, offsets, exists_fn):
        """An edge or silhouette at B: exists by the material pattern around it, visible when
        one of its empty sides can see the viewer."""
        solid = self.solid
        occ = [solid.contains(B + o) for o in offsets]
        exists = exists_fn(occ)
        seen = np.zeros(len(B), dtype=bool)
        for o, oc in zip(offsets, occ):
            ask = exists & ~oc & ~seen
            if ask.any():
                seen[ask] = ~solid.blocked((B + o)[ask], -self.d)
        return np.where(exists, np.where(seen, 2, 1), 0)

    # candidates of each feature -------------------------------------------------------------------

    def curves(self) -> list[_Curve]:
        out = []
        for i, s in enumerate(self.solid.shapes):
            out += self._box_curves(i, s) if s.kind == "box" else self._cylinder_curves(i, s)
        return out

    def _box_curves(self, i: int, s: _Shape) -> list[_Curve]:
        d, out = self.d, []
        for ax in range(3):
            for sign in (-1.0, 1.0):
                n = sign * s.E[ax]
                if abs(n @ d) < 1e-9:  # a face seen edge-on: it draws as a segment
                    out.append(self._box_face(i, s, ax, n))
        for ax in range(3):
            e = s.E[ax]
            if abs(abs(e @ d) - 1) < 1e-9:
                continue  # an edge along the sight line draws as a point
            j, k = [x for x in range(3) if x != ax]
            for sj in (-1.0, 1.0):
                for sk in (-1.0, 1.0):
                    n1, n2 = sj * s.E[j], sk * s.E[k]
                    if abs(n1 @ d) < 1e-9 or abs(n2 @ d) < 1e-9:
                        continue  # drawn by the face seen edge-on
                    mid = s.c + sj * s.h[j] * s.E[j] + sk * s.h[k] * s.E[k]
                    out.append(self._edge(i, mid - s.h[ax] * e, mid + s.h[ax] * e, n1, n2))
        return out

    def _box_face(self, i, s, ax, n) -> _Curve:
        d = self.d
        cf = s.c + (n @ s.E[ax]) * s.h[ax] * s.E[ax]
        w = np.cross(n, d)
        w /= np.linalg.norm(w)
        inplane = [(s.E[x], s.h[x]) for x in range(3) if x != ax]
        ext = sum(h * abs(e @ w) for e, h in inplane)

        def where(t):
            return cf + ((2 * np.asarray(t) - 1) * ext)[:, None] * w

        def state(t):
            B = where(t)
            s0, s1 = np.full(len(B), -np.inf), np.full(len(B), np.inf)
            for e, h in inplane:
                o, we = (B - cf) @ e, float(d @ e)
                if abs(we) > 1e-12:
                    a, b = (-h - o) / we, (h - o) / we
                    s0, s1 = np.maximum(s0, np.minimum(a, b)), np.minimum(s1, np.maximum(a, b))
            s0, s1 = np.maximum(s0, -self.solid.reach), np.minimum(s1, self.solid.reach)
            return self._sweep_state(B, np.broadcast_to(n, B.shape), s0, np.maximum(s1, s0))

        return _Curve("seg", i, "face", where, state)

    def _edge(self, i, p0, p1, n1, n2) -> _Curve:
        eps = self.solid.eps
        offs = [eps * (a * n1 + b * n2) for a in (1, -1) for b in (1, -1)]

        def where(t):
            return p0 + np.asarray(t)[:, None] * (p1 - p0)

        def state(t):
            B = where(t)
            return self._probe_state(B, [np.broadcast_to(o, B.shape) for o in offs], _is_edge)

        return _Curve("seg", i, "edge", where, state)

    def _cylinder_curves(self, i: int, s: _Shape) -> list[_Curve]:
        d, eps = self.d, self.solid.eps
        along = abs(s.a @ d)
        if along > 1 - 1e-9:  # seen end-on: the round surface draws as a circle
            h, v = self.h, self.v

            def where(t):
                t = np.asarray(t)
                return s.c + s.r * (np.cos(t)[:, None] * h + np.sin(t)[:, None] * v)

            def state(t):
                t = np.asarray(t)
                n = np.cos(t)[:, None] * h + np.sin(t)[:, None] * v
                full = np.full(len(t), s.hl)
                return self._sweep_state(where(t), n, -full, full)

            c2 = self.project(s.c)
            return [_Curve("arc", i, "lateral", where, state, 2 * math.pi, (c2[0], c2[1]), s.r)]
        out = []
        m = np.cross(s.a, d)
        m /= np.linalg.norm(m)
        for sign in (-1.0, 1.0):  # the two silhouette lines, where the surface turns away
            n = sign * m
            p0, p1 = s.c + s.r * n - s.hl * s.a, s.c + s.r * n + s.hl * s.a

            def where(t, p0=p0, p1=p1):
                return p0 + np.asarray(t)[:, None] * (p1 - p0)

            def state(t, n=n, where=where):
                B = where(t)
                offs = [np.broadcast_to(eps * n, B.shape), np.broadcast_to(-eps * n, B.shape)]
                return self._probe_state(B, offs, lambda occ: occ[0] != occ[1])

            out.append(_Curve("seg", i, "silhouette", where, state))
        for end in (-1.0, 1.0):
            out.append(self._disc(i, s, end) if along < 1e-9 else self._rim(i, s, end))
        return out

    def _disc(self, i, s, end) -> _Curve:
        """An end face of a cylinder seen edge-on: a segment across it."""
        d = self.d
        n = end * s.a
        cf = s.c + end * s.hl * s.a
        w = np.cross(n, d)
        w /= np.linalg.norm(w)

        def where(t):
            return cf + (s.r * (2 * np.asarray(t) - 1))[:, None] * w

        def state(t):
            B = where(t)
            half = np.sqrt(np.maximum(s.r ** 2 - np.sum((B - cf) ** 2, axis=1), 0.0))
            return self._sweep_state(B, np.broadcast_to(n, B.shape), -half, half)

        return _Curve("seg", i, "face", where, state)

    def _rim(self, i, s, end) -> _Curve:
        """An end circle of a cylinder seen at a slant: an ellipse, treated as an edge."""
        eps = self.solid.eps
        e1 = np.cross(s.a, [0.0, 0.0, 1.0] if abs(s.a[2]) < 0.9 else [1.0, 0.0, 0.0])
        e1 /= np.linalg.norm(e1)
        e2 = np.cross(s.a, e1)
        ce = s.c + end * s.hl * s.a

        def where(t):
            t = np.asarray(t)
            return ce + s.r * (np.cos(t)[:, None] * e1 + np.sin(t)[:, None] * e2)

        def state(t):
            t = np.asarray(t)
            radial = np.cos(t)[:, None] * e1 + np.sin(t)[:, None] * e2
            offs = [eps * (a * end * s.a + b * radial) for a in (1, -1) for b in (1, -1)]
            return self._probe_state(where(t), offs, _is_edge)

        return _Curve("poly", i, "edge", where, state, 2 * math.pi)


def _is_edge(occ: list[np.ndarray]) -> np.ndarray:
    """From the material in the four quadrants around a line (++, +-, -+, --): an edge unless
    all four agree or the material fills exactly one half (a flat face through the line)."""
    pp, pm, mp, mm_ = occ
    same = (pp == pm) & (pm == mp) & (mp == mm_)
    half = ((pp == pm) & (mp == mm_) & (pp != mp)) | ((pp == mp) & (pm == mm_) & (pp != pm))
    return ~same & ~half


def _runs(f, lo: float, hi: float, n: int, periodic: bool = False) -> list[tuple[float, float, int]]:
    """Split [lo, hi] into runs where the integer function f is constant; run ends are bisected."""
    t = lo + (hi - lo) * (np.arange(n) + 0.5) / n
    s = np.asarray(f(t))
    cut = np.nonzero(s[1:] != s[:-1])[0]
    a, b, sa = t[cut], t[cut + 1], s[cut]
    for _ in range(16 if len(cut) else 0):
        m = (a + b) / 2
        same = np.asarray(f(m)) == sa
        a, b = np.where(same, m, a), np.where(same, b, m)
    edges = [lo, *((a + b) / 2).tolist(), hi]
    states = [int(s[0]), *(int(x) for x in s[cut + 1])]
    runs = [(edges[i], edges[i + 1], states[i]) for i in range(len(states))]
    if periodic and len(runs) > 1 and runs[0][2] == runs[-1][2]:
        first, last = runs.pop(0), runs.pop()
        runs.append((last[0], first[1] + (hi - lo), first[2]))
    return runs


def _tidy(runs, length) -> list[tuple[float, float, int]]:
    """Give runs shorter than MIN_RUN their neighbours' state (or none), then merge equal runs."""
    runs = list(runs)
    for i, (t0, t1, s) in enumerate(runs):
        if length(t0, t1) >= MIN_RUN:
            continue
        prev = runs[i - 1][2] if i > 0 else None
        nxt = runs[i + 1][2] if i + 1 < len(runs) else None
        if prev is None and nxt is None:
            continue
        if prev is not None and nxt is not None:
            new = prev if prev == nxt else 0  # a blip inside a line takes the line's state
        elif s == 0:
            new = prev if nxt is None else nxt  # a sliver of gap at an end: the line runs on
        else:
            new = 0  # a sliver of line at an end
        runs[i] = (t0, t1, new)
    merged = []
    for r in runs:
        if merged and merged[-1][2] == r[2]:
            merged[-1] = (merged[-1][0], r[1], r[2])
        else:
            merged.append(r)
    return merged


def _curve_points(curve: _Curve, proj: _Projector, t0: float, t1: float, step: float) -> np.ndarray:
    """The run's 2D points (metres), enough to follow it within a fraction of `step`."""
    if curve.kind == "seg":
        return proj.project(curve.where(np.array([t0, t1])))
    if curve.kind == "arc":
        n = max(3, int(math.ceil(curve.radius * (t1 - t0) / step)) + 1)
    else:
        rough = proj.project(curve.where(np.linspace(t0, t1, 17)))
        n = max(3, int(math.ceil(np.linalg.norm(np.diff(rough, axis=0), axis=1).sum() / step)) + 1)
    return proj.project(curve.where(np.linspace(t0, t1, n)))


def _length_fn(curve: _Curve, proj: _Projector, k: float):
    """Sheet length (mm) of a piece [t0, t1] of the curve."""
    def length(t0, t1):
        pts = _curve_points(curve, proj, t0, t1, 1.0 / k)
        return k * float(np.linalg.norm(np.diff(pts, axis=0), axis=1).sum())
    return length


def _cover_test(geoms: list, tol: float):
    """A function telling which 2D points lie within `tol` of lines already drawn."""
    if not geoms:
        return lambda P: np.zeros(len(P), dtype=bool)
    tree = shapely.STRtree(geoms)

    def covered(P):
        hits = tree.query(shapely.points(P), predicate="dwithin", distance=tol)
        out = np.zeros(len(P), dtype=bool)
        out[hits[0]] = True
        return out

    return covered


def _trace_view(solid: _Solid, view: str, k: float) -> _ViewLines:
    """All lines of one view at k sheet-mm per metre: visible and hidden runs, centre lines."""
    proj = _Projector(solid, view)
    traced = []  # (curve, runs, sheet length)
    for curve in proj.curves():
        length = _length_fn(curve, proj, k)
        span = length(0.0, curve.period)
        if span < MIN_RUN:
            continue
        n = max(8, int(math.ceil(span / SAMPLE_STEP)))
        runs = _runs(curve.state, 0.0, curve.period, n, periodic=curve.period != 1.0)
        traced.append((curve, _tidy(runs, length), span))
    lines = _ViewLines()
    drawn: list = []
    lines.visible = _undrawn(traced, 2, proj, k, drawn)
    lines.hidden = _undrawn(traced, 1, proj, k, drawn)  # a visible line hides a hidden one
    lines.centre = _centre_lines(proj, traced, k)
    return lines


def _undrawn(traced, state: int, proj: _Projector, k: float, drawn: list) -> list:
    """The runs in `state` minus whatever lies on a line already drawn (which `drawn` collects),
    longest candidates first, so that a short line lying on a long one is the one dropped."""
    out = []
    for curve, runs, _ in sorted(traced, key=lambda c: -c[2]):
        length = _length_fn(curve, proj, k)
        for t0, t1, s in runs:
            if s != state:
                continue
            covered = _cover_test(drawn, 0.1 / k)

            def on_drawn(t, curve=curve, covered=covered):
                return covered(proj.project(curve.where(t))).astype(int)

            n = max(4, int(math.ceil(length(t0, t1) / SAMPLE_STEP)))
            for a, b, c in _tidy(_runs(on_drawn, t0, t1, n), length):
                if c == 0:
                    out.append((curve, a, b))
                    drawn.append(LineString(_curve_points(curve, proj, a, b, SAMPLE_STEP / k)))
    return out


def _centre_lines(proj: _Projector, traced, k: float) -> list:
    """Centre lines of every cylinder that is part of the solid: a cross where it is seen end-on,
    its axis over its drawn length otherwise; a pitch circle through equal holes on a circle."""
    ext = CENTRE_EXT / k
    lines, ends = [], []  # ends: (centre, radius) of the cylinders seen end-on
    for i, s in enumerate(proj.solid.shapes):
        if s.kind != "cyl":
            continue
        mine = [(c, [r for r in runs if r[2]]) for c, runs, _ in traced if c.shape == i]
        mine = [(c, runs) for c, runs in mine if runs and c.role in ("lateral", "silhouette")]
        if not mine:
            continue
        if mine[0][0].role == "lateral":
            c2 = proj.project(s.c)
            reach = s.r + ext
            lines.append((c2 - [reach, 0], c2 + [reach, 0]))
            lines.append((c2 - [0, reach], c2 + [0, reach]))
            ends.append((c2, s.r))
            continue
        ts = [t for _, runs in mine for r in runs for t in r[:2]]
        a0, a1 = s.c + (2 * min(ts) - 1) * s.hl * s.a, s.c + (2 * max(ts) - 1) * s.hl * s.a
        p, q = proj.project(a0), proj.project(a1)
        u = (q - p) / max(np.linalg.norm(q - p), 1e-12)
        lines.append((p - ext * u, q + ext * u))
    out = [("line", p, q) for p, q in _merge_collinear(lines)]
    out += [("circle", c, r) for c, r in _pitch_circles(ends)]
    return out


def _merge_collinear(lines) -> list:
    """Join centre lines that lie on one line and overlap (a hole's cross on the wheel's axis)."""
    groups: dict = {}
    for p, q in lines:
        u = (q - p) / np.linalg.norm(q - p)
        if u[0] < -1e-9 or (abs(u[0]) <= 1e-9 and u[1] < 0):
            u = -u
        key = (round(float(u[0]), 6), round(float(u[1]), 6), round(float(u[0] * p[1] - u[1] * p[0]), 7))
        groups.setdefault(key, []).append(sorted((float(p @ u), float(q @ u))))
    out = []
    for (ux, uy, off), spans in groups.items():
        u, nrm = np.array([ux, uy]), np.array([-uy, ux])
        spans.sort()
        merged = [spans[0]]
        for a, b in spans[1:]:
            if a <= merged[-1][1] + 1e-9:
                merged[-1][1] = max(merged[-1][1], b)
            else:
                merged.append([a, b])
        out += [(a * u + off * nrm, b * u + off * nrm) for a, b in merged]
    return out


def _pitch_circles(ends) -> list:
    """Three or more equal circles whose centres lie on one circle: that circle (a PCD)."""
    groups: dict = {}
    for c, r in ends:
        groups.setdefault(round(r, 7), []).append(c)
    out = []
    for centres in groups.values():
        pts = np.unique(np.round(np.array(centres), 9), axis=0)  # a hole seen twice is one hole
        if len(pts) < 3:
            continue
        mid = pts.mean(axis=0)
        dist = np.linalg.norm(pts - mid, axis=1)
        if dist.min() > 1e-6 and dist.max() - dist.min() < 1e-6:
            out.append((mid, float(dist.mean())))
    return out


def _view_prims(lines: _ViewLines, proj: _Projector, k: float) -> list:
    """Sheet primitives (mm, about the part's origin, y down) of a traced view."""
    def sheet(p):
        return float(k * p[0]), float(-k * p[1])

    out = []
    for style, runs in (("visible", lines.visible), ("hidden", lines.hidden)):
        for curve, t0, t1 in runs:
            if curve.kind == "seg":
                (x1, y1), (x2, y2) = (sheet(p) for p in proj.project(curve.where(np.array([t0, t1]))))
                out.append(_Line(x1, y1, x2, y2, style))
            elif curve.kind == "arc":
                cx, cy = sheet(curve.centre)
                if t1 - t0 >= 2 * math.pi - 1e-9:
                    out.append(_Circle(cx, cy, k * curve.radius, style))
                else:
                    out.append(_Arc(cx, cy, k * curve.radius, t0, t1, style))
            else:
                line = LineString(k * _curve_points(curve, proj, t0, t1, 0.2 / k) * [1, -1]).simplify(0.05)
                out.append(_Poly((tuple(map(tuple, np.asarray(line.coords))),), False, style))
    for kind, a, b in lines.centre:
        if kind == "line":
            (x1, y1), (x2, y2) = sheet(a), sheet(b)
            out.append(_Line(x1, y1, x2, y2, "centre"))
        else:
            cx, cy = sheet(a)
            out.append(_Circle(cx, cy, k * b, "centre"))
    return out


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
            lines.append(_Line(*pt(al, ac + sign * EXT_GAP), *pt(al, lam + sign * EXT_OVER)))
    lo, hi = sorted((float(pa @ U), float(pb @ U)))
    text = dimension_text(dim)
    tw = text_width(text, DIM_TEXT)
    arrows_in = hi - lo >= 2 * ARROW_LEN + 1.5
    line_lo, line_hi = (lo, hi) if arrows_in else (lo - ARROW_LEN - 2.0, hi + ARROW_LEN + 2.0)
    lines += _arrow(pt(lo, lam), -U if arrows_in else U, W)
    lines += _arrow(pt(hi, lam), U if arrows_in else -U, W)
    segments = [((ln.x1, ln.y1), (ln.x2, ln.y2)) for ln in lines if isinstance(ln, _Line)]
    segments.append((pt(line_lo, lam), pt(line_hi, lam)))
    if hi - lo >= tw + 2.0:
        options = [(_Text(*pt((lo + hi) / 2, lam + TEXT_GAP), text, DIM_TEXT, "middle", angle),
                    pt(line_lo, lam), pt(line_hi, lam))]
    else:  # beside the dimension, the line running on under it; away from the view's middle first
        clear = 1.5 + (0.0 if arrows_in else ARROW_LEN)
        after = (_Text(*pt(hi + clear, lam + TEXT_GAP), text, DIM_TEXT, "start", angle),
                 pt(line_lo, lam), pt(max(line_hi, hi + clear + tw), lam))
        before = (_Text(*pt(lo - clear, lam + TEXT_GAP), text, DIM_TEXT, "end", angle),
                  pt(min(line_lo, lo - clear - tw), lam), pt(line_hi, lam))
        outward = (lo + hi) / 2 >= float(np.array(centre) @ U) - 1e-6
        options = [after, before] if outward else [before, after]
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
            lines.append(_Line(*at(a, EXT_GAP), *at(a, r + EXT_OVER)))
    lines.append(_Arc(cx, cy, r, a0, a1, "thin"))
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
    label = _Text(float(x), float(y + 0.29 * size), text, size, "middle")
    segments = [((ln.x1, ln.y1), (ln.x2, ln.y2)) for ln in lines if isinstance(ln, _Line)]
    return _DimDraft(lines, [(label, None, None)], segments)


def _dimensions(dims: list[Dimension | Angle], k: float, centre: tuple[float, float]) -> list:
    """All dimensions of one view, each text placed clear of the others' texts and lines."""
    drafts = [_dimension_draft(d, k, centre) for d in dims]
    blockers = [LineString(seg) for dr in drafts for seg in dr.segments]
    out = []
    for dr in drafts:
        chosen = dr.options[0]
        for option in dr.options:
            box = shapely.box(*_bbox([option[0]]))
            if not any(box.intersects(b) for b in blockers):
                chosen = option
                break
        text, p, q = chosen
        blockers.append(shapely.box(*_bbox([text])).buffer(0.5))
        out += [*dr.lines, *([] if p is None else [_Line(*p, *q)]), text]
    return out


def _arrow(tip, direction, across) -> list:
    """A filled arrowhead with its tip at `tip`, pointing along `direction`."""
    tip = np.array(tip)
    base = tip - ARROW_LEN * np.asarray(direction)
    pts = (tip, base + ARROW_HALF * across, base - ARROW_HALF * across)
    return [_Poly((tuple((float(x), float(y)) for x, y in pts),), True, "solid")]


# --- title block, frame, projection symbol -------------------------------------------------------


def _fit(text: str, width: float, size: float) -> float:
    """The largest lettering size up to `size` at which `text` fits in `width` mm."""
    return min(size, width / max(text_width(text, 1.0), 1e-9))


def _cell(x, y, w, h, label, value, size=3.5, bold=False) -> list:
    out = [_Text(x + 1.2, y + 2.4, label, 1.8, "start", style="grey")]
    if value:
        s = _fit(value, w - 2.4, size)
        out.append(_Text(x + 1.2, y + h - 1.6, value, s, "start", bold=bold))
    return out


def _frame() -> list:
    """The border frame with ISO 5457 centring marks."""
    x0, y0, x1, y1 = FRAME
    out = [_Poly((((x0, y0), (x1, y0), (x1, y1), (x0, y1)),), True, "border")]
    cx, cy = (x0 + x1) / 2, (y0 + y1) / 2
    out += [_Line(cx, 5.0, cx, y0, "border"), _Line(cx, y1, cx, SHEET_H - 5.0, "border"),
            _Line(5.0, cy, x0, cy, "border"), _Line(x1, cy, SHEET_W - 5.0, cy, "border")]
    return out


def _projection_symbol(x: float, y: float) -> list:
    """ISO 5456-2 first-angle symbol at (x, y) (top left): the truncated cone's front view with
    its end view (seen from the small end, on the left) drawn to the right of it."""
    h = 2.2  # half the large diameter
    cy = y + h
    cone = ((x, cy - h / 2), (x + 6.0, cy - h), (x + 6.0, cy + h), (x, cy + h / 2))
    cx = x + 6.0 + 3.0 + h
    return [_Poly((cone,), True, "medium"), _Circle(cx, cy, h, "medium"), _Circle(cx, cy, h / 2, "medium"),
            _Line(x - 1.0, cy, cx + h + 1.0, cy, "centre"), _Line(cx, cy - h - 1.0, cx, cy + h + 1.0, "centre")]


def _title_block(title: str, file_name: str, material: str, density: str, mass: str, scale: str) -> list:
    """An ISO 7200-like title block in the frame's bottom right corner."""
    x0, y0, x1, y1 = TITLE_BLOCK
    r1, r2 = y0 + 8.0, y0 + 16.0
    out = [_Poly((((x0, y0), (x1, y0), (x1, y1), (x0, y1)),), True, "visible"),
           _Line(x0, r1, x1, r1), _Line(x0, r2, x1, r2)]
    out += [_Line(x0 + 70, y0, x0 + 70, r2), _Line(x0 + 105, y0, x0 + 105, y1),
            _Line(x0 + 140, y0, x0 + 140, r1), _Line(x0 + 150, r2, x0 + 150, y1)]
    out += _cell(x0, y0, 70, 8, "Material", material)
    out += _cell(x0 + 70, y0, 35, 8, "Density", density)
    out += _cell(x0 + 105, y0, 35, 8, "Mass", mass)
    out += _cell(x0 + 140, y0, 40, 8, "Scale", scale)
    out += _cell(x0, r1, 70, 8, "General tolerance", "ISO 2768-m")
    out += _cell(x0 + 70, r1, 35, 8, "Units", "Dimensions in mm", 3.0)
    out += _cell(x0 + 105, r1, 75, 8, "Projection", "")
    out += _projection_symbol(x0 + 108.0, r1 + 2.5)
    out.append(_Text(x0 + 126.0, r2 - 2.0, "First angle projection", 3.0, "start"))
    out += _cell(x0, r2, 105, 12, "Title", title, 6.0, bold=True)
    out += _cell(x0 + 105, r2, 45, 12, "File name", file_name, 3.5)
    out += _cell(x0 + 150, r2, 30, 12, "Sheet", "1/1", 3.5)
    return out


# --- placing views on the sheet ------------------------------------------------------------------


def _boxes_fit(boxes, reserved, margin: float = 3.0):
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


def _label(prims, text: str, centre_x: float) -> list:
    """The view's name, centred under everything drawn for it."""
    _, _, _, y1 = _bbox(prims)
    return [_Text(centre_x, y1 + 6.0, text, LABEL_TEXT, "middle", bold=True)]


# --- the part drawing ----------------------------------------------------------------------------


def _part_view(part: Part, solid: _Solid, view: str, k: float, traced: _ViewLines | None) -> list:
    """Everything of one view, in sheet mm about the part's origin: lines, dimensions, name.

    With `traced` None only the extents are needed (the outline box stands in for the lines)."""
    proj = _Projector(solid, view)
    pts = proj.project(np.concatenate([_shape_corners(s) for s in solid.added]))
    h0, v0 = pts.min(0)
    h1, v1 = pts.max(0)
    outline = _Poly((((k * h0, -k * v0), (k * h1, -k * v0), (k * h1, -k * v1), (k * h0, -k * v1)),), True)
    centre = (k * (h0 + h1) / 2, -k * (v0 + v1) / 2)
    if traced is None:  # centre lines reach past the outline; allow for them
        c = CENTRE_EXT
        prims = [outline, _Line(k * h0 - c, -k * v0 + c, k * h1 + c, -k * v1 - c)]
    else:
        prims = _view_prims(traced, proj, k)
    prims += _dimensions([d for d in part.dimensions if d.view == view], k, centre)
    return prims + _label(prims, view.upper(), centre[0])


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


def part_drawing_svg(part: Part) -> str:
    """The part's drawing: three first-angle views with dimensions, frame and title block."""
    check_dimensions(part)
    solid = _Solid(part.features)
    for label, factor in SCALES:
        k = 1000.0 * factor
        boxes = {v: _bbox(_part_view(part, solid, v, k, None)) for v in VIEWS}
        offsets = _first_angle(boxes)
        placed = [(b[0] + offsets[v][0], b[1] + offsets[v][1], b[2] + offsets[v][0], b[3] + offsets[v][1])
                  for v, b in boxes.items()]
        origin = _boxes_fit(placed, [TITLE_BLOCK])
        if origin is not None:
            break
    else:
        raise ValueError(f"part {part.name!r} does not fit an A4 sheet at 1:100")
    layers = []
    for view in VIEWS:
        traced = _trace_view(solid, view, k)
        prims = _part_view(part, solid, view, k, traced)
        dx, dy = origin[0] + offsets[view][0], origin[1] + offsets[view][1]
        layers.append((f"view-{view}", _moved(prims, dx, dy)))
    m = part.material
    block = _title_block(part.title or part.name, f"{part.name}.SLDPRT", m.name,
                         f"{fmt(m.density)} kg/m³", f"{part.mass:.3f} kg", label)
    layers.append(("sheet", _frame() + block))
    return _document(layers, f"{part.title or part.name} ({part.name}.SLDPRT)")


# --- the assembly drawing ------------------------------------------------------------------------

BALLOON_R = 4.0
JOINT_CROSS, JOINT_ARROW = 1.8, 10.0  # sheet mm


def _rpy_matrix(rpy) -> np.ndarray:
    """URDF roll-pitch-yaw: R = Rz(yaw) Ry(pitch) Rx(roll)."""
    r, p, y = rpy
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    rx = np.array([[1, 0, 0], [0, cr, -sr], [0, sr, cr]])
    ry = np.array([[cp, 0, sp], [0, 1, 0], [-sp, 0, cp]])
    rz = np.array([[cy, -sy, 0], [sy, cy, 0], [0, 0, 1]])
    return rz @ ry @ rx


def link_poses(robot) -> dict[str, np.ndarray]:
    """Each link's pose (4 x 4) in the root link's frame, composed down the joint tree."""
    by_child = {j.child: j for j in robot.joints}
    poses: dict[str, np.ndarray] = {}

    def pose(name: str, depth: int = 0) -> np.ndarray:
        if name not in poses:
            if depth > len(robot.joints):
                raise ValueError(f"robot {robot.name!r}: the joints form a loop at link {name!r}")
            joint = by_child.get(name)
            T = np.eye(4)
            if joint is not None:
                local = np.eye(4)
                local[:3, :3] = _rpy_matrix(joint.rpy)
                local[:3, 3] = joint.xyz
                T = pose(joint.parent, depth + 1) @ local
            poses[name] = T
        return poses[name]

    for link in robot.links:
        pose(link.name)
    return poses


@dataclass
class _Item:
    """One row of the parts list: a part and the links made of it."""

    number: int
    part: Part
    links: list


def _items(robot) -> list[_Item]:
    items: dict[int, _Item] = {}
    for link in robot.links:
        if link.part is None:
            continue
        key = id(link.part)
        if key not in items:
            items[key] = _Item(len(items) + 1, link.part, [])
        items[key].links.append(link)
    return list(items.values())


def _silhouette(part: Part, R: np.ndarray, view: str):
    """The outline of the part's mesh, turned by R, projected in a view (metres): the union of
    its projected triangles, through-holes left open."""
    _, h, v = (np.array(x) for x in VIEWS[view])
    P2 = (part.mesh.vertices @ R.T) @ np.stack([h, v]).T
    tri = P2[part.mesh.faces]
    e1, e2 = tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]
    area = np.abs(e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0])
    tri = tri[area > 1e-12]
    polys = shapely.polygons(np.concatenate([tri, tri[:, :1]], axis=1))
    return shapely.union_all(polys).buffer(0)


def _rings(geom, k: float, tol: float = 0.05, min_hole: float = 0.0) -> tuple:
    """Sheet rings (mm, y down) of a polygon or multipolygon in metres, simplified to `tol` mm;
    holes smaller than `min_hole` mm² are left out."""
    geom = affinity.scale(geom, k, -k, origin=(0, 0)).simplify(tol)
    polys = list(geom.geoms) if isinstance(geom, MultiPolygon) else [geom] if isinstance(geom, Polygon) else []
    out = []
    for poly in polys:
        holes = [r for r in poly.interiors if not min_hole or Polygon(r).area >= min_hole]
        for ring in (poly.exterior, *holes):
            out.append(tuple((float(x), float(y)) for x, y in np.asarray(ring.coords)[:-1]))
    return tuple(out)


@dataclass
class _Placed:
    """A link drawn in one view: its outline (metres, placed), depth key and lines."""

    link: object
    item: _Item
    outline: object
    near: tuple  # sort key: smaller is nearer the viewer
    offset: np.ndarray  # the link origin in the view (metres)
    square: bool  # not turned: the part drawing's own lines of this view apply


def _assembly_view(items, poses, view: str):
    """The links of one view, farthest first."""
    d = np.array(VIEWS[view][0])
    P = np.stack([np.array(VIEWS[view][1]), np.array(VIEWS[view][2])])
    cache: dict = {}
    placed = []
    for item in items:
        for link in item.links:
            T = poses[link.name]
            R, t = T[:3, :3], T[:3, 3]
            key = (id(item.part), np.round(R, 9).tobytes())
            if key not in cache:
                cache[key] = _silhouette(item.part, R, view)
            off = P @ t
            outline = affinity.translate(cache[key], *off)
            world = item.part.mesh.vertices @ R.T + t
            depth = world @ d
            # nearest point first (to 1 µm, so that touching faces tie), then the mass centre
            near = (round(float(depth.min()), 6), float(item.part.mesh.center_mass @ R.T @ d + t @ d))
            placed.append(_Placed(link, item, outline, near, off, bool(np.allclose(R, np.eye(3), atol=1e-9))))
    placed.sort(key=lambda p: (-p.near[0], -p.near[1]))
    return placed


def _assembly_links(placed, view: str, k: float, lines_cache: dict) -> list[tuple[str, list]]:
    """One layer per link of an assembly view (sheet mm about the root link's origin), farthest
    first: the link filled white over the ones behind it, then its edges (the part's own view
    lines when the link is not turned, else its outline)."""
    layers = []
    for p in placed:
        # a turned link is drawn by its outline: slivers where its projected triangles fail to
        # meet would show as specks
        rings = _rings(p.outline, k, min_hole=0.0 if p.square else 0.01)
        if not rings:
            continue
        prims = [_Fill(rings)]
        if p.square:
            key = (id(p.item.part), view)
            if key not in lines_cache:
                solid = _Solid(p.item.part.features)
                traced = _trace_view(solid, view, k)
                traced.hidden, traced.centre = [], []
                lines_cache[key] = _view_prims(traced, _Projector(solid, view), k)
            prims += _moved(lines_cache[key], k * p.offset[0], -k * p.offset[1])
        else:
            prims.append(_Poly(rings, True, "visible"))
        layers.append((f"{view}-{p.link.name}", prims))
    return layers


def _visible_parts(placed) -> list:
    """For each placed link, the part of its outline no nearer link covers."""
    out = []
    for i, p in enumerate(placed):
        nearer = [q.outline for q in placed[i + 1:]]
        cover = shapely.union_all(nearer) if nearer else None
        out.append(p.outline if cover is None else p.outline.difference(cover))
    return out


def _anchor(region, tol: float):
    """A point well inside a region (its largest piece), for a balloon's leader."""
    polys = list(region.geoms) if hasattr(region, "geoms") else [region]
    polys = [g for g in polys if isinstance(g, Polygon) and not g.is_empty]
    if not polys:
        return None
    biggest = max(polys, key=lambda g: g.area)
    pt = polylabel(biggest, tolerance=tol)
    return np.array([pt.x, pt.y])


def _balloons(anchors: list, box, k: float, avoid_y=()) -> list:
    """Balloons (numbered circles) outside the view's box, each with a leader to its anchor.

    `anchors` are (number, point in metres) of this view; box is the view geometry's sheet box;
    `avoid_y` are heights of the joint names' leaders, which a balloon must not sit on.
    """
    x0, y0, x1, y1 = box
    centre = np.array([(x0 + x1) / 2, (y0 + y1) / 2])
    pad = 7.0 + BALLOON_R
    out, used = [], []
    for number, a in anchors:
        at = np.array([k * a[0], -k * a[1]])
        base = at - centre
        base = base / np.linalg.norm(base) if np.linalg.norm(base) > 1.0 else np.array([-0.6, -0.8])
        for turn in (0, 15, -15, 30, -30, 45, -45, 60, -60):
            c, s = math.cos(math.radians(turn)), math.sin(math.radians(turn))
            u = np.array([c * base[0] - s * base[1], s * base[0] + c * base[1]])
            # leave the box (grown by pad) along u
            ts = [((x0 - pad) - at[0]) / u[0] if u[0] < -1e-9 else ((x1 + pad) - at[0]) / u[0] if u[0] > 1e-9 else np.inf,
                  ((y0 - pad) - at[1]) / u[1] if u[1] < -1e-9 else ((y1 + pad) - at[1]) / u[1] if u[1] > 1e-9 else np.inf]
            spot = at + min(ts) * u
            if all(np.linalg.norm(spot - o) > 2 * BALLOON_R + 2.0 for o in used) and \
                    all(abs(spot[1] - y) > BALLOON_R + 3.0 for y in avoid_y):
                break
        used.append(spot)
        edge = spot - BALLOON_R * u
        out += [_Circle(float(at[0]), float(at[1]), 0.5, "solid"),
                _Line(float(at[0]), float(at[1]), float(edge[0]), float(edge[1])),
                _Circle(float(spot[0]), float(spot[1]), BALLOON_R, "thin"),
                _Text(float(spot[0]), float(spot[1]) + 1.75, str(number), 5.0)]
    return out


def _joint_marks(robot, poses, k: float, box) -> list:
    """Each joint's origin (a cross) and axis (an arrow, or a circled dot when the axis points
    at the viewer, a circle alone when away) in the top view; its name beside the view, on a
    leader, on the side of the view the joint is on."""
    d, h, v = (np.array(x) for x in VIEWS["top"])
    middle = (box[0] + box[2]) / 2
    out = []
    names: dict[tuple[float, float], list[str]] = {}  # joints that share an origin share a label
    for j in robot.joints:
        T = poses[j.child]
        o = T[:3, 3]
        x, y = float(k * (o @ h)), float(-k * (o @ v))
        names.setdefault((round(x, 2), round(y, 2)), []).append(j.name)
        out += [_Line(x - JOINT_CROSS, y, x + JOINT_CROSS, y, "joint"),
                _Line(x, y - JOINT_CROSS, x, y + JOINT_CROSS, "joint")]
        if j.axis is None:
            continue
        axis = T[:3, :3] @ np.asarray(j.axis, dtype=float)
        axis /= np.linalg.norm(axis)
        flat = np.array([axis @ h, -(axis @ v)])
        if np.linalg.norm(flat) > 0.3:
            end = np.array([x, y]) + JOINT_ARROW * flat
            u = flat / np.linalg.norm(flat)
            tip = end
            out.append(_Line(x, y, *(tip - 1.5 * u), "joint"))
            base = tip - 2.5 * u
            across = np.array([-u[1], u[0]])
            pts = (tip, base + 0.8 * across, base - 0.8 * across)
            out.append(_Poly((tuple((float(a), float(b)) for a, b in pts),), True, "jointfill"))
        else:
            out.append(_Circle(x, y, 2.5, "joint"))
            if axis @ d < 0:  # pointing at the viewer: a dot
                out.append(_Circle(x, y, 0.6, "jointfill"))
    for (x, y), joint_names in names.items():
        right = x >= middle
        end = box[2] + 3.0 if right else box[0] - 3.0
        out.append(_Line(x, y, end, y, "jointleader"))
        out.append(_Text(end + (1.0 if right else -1.0), y + 0.7, ", ".join(joint_names), 2.0,
                         "start" if right else "end", style="jointtext"))
    return out


def _wrap(text_items: list[str], width: float, size: float) -> list[str]:
    """Comma-separated names broken into lines that fit `width` mm."""
    lines, line = [], ""
    for i, name in enumerate(text_items):
        piece = name + ("," if i < len(text_items) - 1 else "")
        trial = f"{line} {piece}".strip()
        if line and text_width(trial, size) > width:
            lines.append(line)
            line = piece
        else:
            line = trial
    return lines + ([line] if line else [])


PARTS_COLUMNS = (("Item", 12.0), ("Part", 48.0), ("Links", 62.0), ("Qty", 12.0), ("Material", 46.0))


def _parts_list(items: list[_Item]) -> tuple[list, float]:
    """The parts list just above the title block (ISO 7573: headings at the bottom, item 1 next
    to them, numbering upwards). Returns its primitives and height."""
    x0, y_base, x1, _ = TITLE_BLOCK
    rows = []
    for item in items:
        link_lines = _wrap([lk.name for lk in item.links], PARTS_COLUMNS[2][1] - 2.4, 2.5)
        title = item.part.title or item.part.name
        rows.append(([str(item.number), f"{title} ({item.part.name}.SLDPRT)", link_lines,
                      str(len(item.links)), item.part.material.name], max(6.0, 2.0 + 3.2 * len(link_lines))))
    head_h = 6.0
    height = head_h + sum(h for _, h in rows)
    top = y_base - height
    out = [_Poly((((x0, top), (x1, top), (x1, y_base), (x0, y_base)),), True, "visible"),
           _Line(x0, y_base - head_h, x1, y_base - head_h, "visible")]
    x = x0
    for name, w in PARTS_COLUMNS:
        out.append(_Text(x + 1.2, y_base - 1.8, name, 2.5, "start", bold=True))
        if x > x0:
            out.append(_Line(x, top, x, y_base))
        x += w
    y = y_base - head_h
    for cells, h in rows:  # item 1 just above the headings
        out.append(_Line(x0, y - h, x1, y - h))
        x = x0
        for (name, w), value in zip(PARTS_COLUMNS, cells):
            values = value if isinstance(value, list) else [value]
            for n, text in enumerate(values):
                size = _fit(text, w - 2.4, 2.5 if isinstance(value, list) else 3.0)
                out.append(_Text(x + 1.2, y - h + 4.2 + 3.2 * n, text, size, "start"))
            x += w
        y -= h
    return out, height


def assembly_drawing_svg(robot) -> str:
    """The robot's assembly drawing: front and top views with balloons, the joints' origins and
    axes, a parts list and the title block."""
    items = _items(robot)
    if not items:
        raise ValueError(f"robot {robot.name!r} has no link with a part to draw")
    poses = link_poses(robot)
    views = {v: _assembly_view(items, poses, v) for v in ("front", "top")}
    visible = {v: _visible_parts(views[v]) for v in views}
    # each item's balloon goes where the item shows most
    anchors: dict = {"front": [], "top": []}
    for item in items:
        best = max(((float(g.area), v, i) for v in views for i, (p, g) in enumerate(zip(views[v], visible[v]))
                    if p.item is item), key=lambda b: (b[0], b[1] == "top"))
        area, v, i = best
        scale_ref = math.sqrt(max(views[v][i].outline.area, 1e-12))
        point = _anchor(visible[v][i], scale_ref / 200)
        if point is not None:
            anchors[v].append((item.number, point))
    plist, plist_h = _parts_list(items)
    reserved = [TITLE_BLOCK, (TITLE_BLOCK[0], TITLE_BLOCK[1] - plist_h, TITLE_BLOCK[2], TITLE_BLOCK[1])]
    lines_cache: dict = {}

    def view_layers(v: str, k: float, full: bool) -> list[tuple[str, list]]:
        if full:
            layers = _assembly_links(views[v], v, k, lines_cache)
        else:  # extents only: the outlines' boxes stand in for the lines
            layers = [("", [_Poly(_rings(p.outline.envelope, k), True) for p in views[v]])]
        box = _bbox([q for _, prims in layers for q in prims])
        notes = _joint_marks(robot, poses, k, box) if v == "top" else []
        leaders = [n.y1 for n in notes if isinstance(n, _Line) and n.style == "jointleader"]
        notes += _balloons(anchors[v], _bbox([_Poly((((box[0], box[1]), (box[2], box[3])),))] + notes), k,
                           leaders)
        notes += _label([q for _, prims in layers for q in prims] + notes, v.upper(), (box[0] + box[2]) / 2)
        if v == "top":  # a key to the joint marks, under the view's name
            y = notes[-1].y + 4.5
            notes.append(_Text((box[0] + box[2]) / 2, y, "Joints: + origin, → axis (the URDF joint frames)",
                               2.5, "middle", style="jointtext"))
        return layers + [(f"{v}-notes", notes)]

    def extent(layers):
        return _bbox([q for _, prims in layers for q in prims])

    for label, factor in SCALES:
        k = 1000.0 * factor
        front, top = extent(view_layers("front", k, False)), extent(view_layers("top", k, False))
        dy = front[3] - top[1] + VIEW_GAP
        origin = _boxes_fit([front, (top[0], top[1] + dy, top[2], top[3] + dy)], reserved)
        if origin is not None:
            break
    else:
        raise ValueError(f"robot {robot.name!r} does not fit an A4 sheet at 1:100")
    layers = [(name, _moved(prims, *origin)) for name, prims in view_layers("front", k, True)]
    layers += [(name, _moved(prims, origin[0], origin[1] + dy)) for name, prims in view_layers("top", k, True)]
    mass = sum(lk.part.mass for item in items for lk in item.links)
    block = _title_block(robot.name, f"{robot.name}.SLDASM", "See parts list", "–", f"{mass:.3f} kg", label)
    layers.append(("sheet", _frame() + plist + block))
    return _document(layers, f"{robot.name} ({robot.name}.SLDASM)")
