"""SVG primitives of a drawing sheet and the document they make.

Lines, circles, arcs, polylines, texts and fills in sheet millimetres (y down), each able to move,
report its points and write itself; the ISO 128 line styles and their dash patterns; estimated
text widths (DejaVu Sans); number formatting (`fmt`, `mm_text`) and escaping; one SVG group per
layer and style, and the whole A4 document.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

# --- sheet, lettering and line types ---------------------------------------------------------

SHEET_W, SHEET_H = 297.0, 210.0
FONT = "DejaVu Sans, Arial, sans-serif"

DIM_TEXT = 3.5  # mm, ISO 3098 lettering for dimensions

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
class Line:
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
class Circle:
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
class Arc:
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
class Poly(_Rings):
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
class Text:
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
class Fill(_Rings):
    """A filled region drawn before the lines of its layer (white for assembly occlusion)."""

    rings: tuple
    colour: str = "#fff"
    style: str = "fill"

    def svg(self):
        d = "".join("M" + "L".join(f"{fmt(x)} {fmt(y)}" for x, y in r) + "Z" for r in self.rings)
        return f'<path d="{d}" fill="{self.colour}" fill-rule="evenodd" stroke="none"/>'


STYLE_ORDER = ["fill", "hidden", "centre", "thin", "medium", "visible", "border", "solid",
               "jointleader", "joint", "jointfill", "grey", "text", "jointtext"]


def bbox(prims) -> tuple[float, float, float, float]:
    pts = np.array([p for pr in prims for p in pr.points()], dtype=float)
    return float(pts[:, 0].min()), float(pts[:, 1].min()), float(pts[:, 0].max()), float(pts[:, 1].max())


def moved(prims, dx, dy):
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


def document(layers: list[tuple[str, list]], title: str, box=None) -> str:
    """The SVG of the layers: the whole sheet, or only `box` (x0, y0, x1, y1 in sheet mm)."""
    x0, y0, x1, y1 = box or (0.0, 0.0, SHEET_W, SHEET_H)
    w, h = x1 - x0, y1 - y0
    lines = [
        '<?xml version="1.0" encoding="UTF-8" standalone="no"?>',
        f'<svg xmlns="http://www.w3.org/2000/svg" version="1.1" width="{fmt(w)}mm" '
        f'height="{fmt(h)}mm" viewBox="{fmt(x0)} {fmt(y0)} {fmt(w)} {fmt(h)}">',
        f"<title>{_esc(title)}</title>",
        f'<rect x="{fmt(x0)}" y="{fmt(y0)}" width="{fmt(w)}" height="{fmt(h)}" fill="#fff"/>',
    ]
    for name, prims in layers:
        lines.extend(_layer_svg(prims, name))
    lines.append("</svg>")
    return "\n".join(lines) + "\n"


VIEWS_MARGIN = 4.0  # mm of white around the views when a drawing shows only them


def views_box(layers: list[tuple[str, list]], margin: float = VIEWS_MARGIN):
    """The box (whole mm) around the layers' primitives, with `margin` all round."""
    x0, y0, x1, y1 = bbox([p for _, prims in layers for p in prims])
    return (float(np.floor(x0 - margin)), float(np.floor(y0 - margin)),
            float(np.ceil(x1 + margin)), float(np.ceil(y1 + margin)))
