"""The exporter's three windows laid out for a phone, and the figures that write both layouts.

A schematic of course/dialog_schematics.py is 736 to 772 px wide; in a phone's column
(course/phone.py) its 11.5 px lettering would read under 6 px. Its phone variant is the
same window cut into its parts, each drawn 1:1 by the same code from the same controls,
the parts one above the other in a window WIDTH px wide, so that the lettering reads
SIZE × SHOWN_PX / WIDTH px (9.4) in the column.

A part of an assembly window is a `Cut`: a rectangle of the window as the desktop figure
draws it, holding every control whose top left corner lies in it. A `Row` puts cuts side
by side; a `Group` draws a group box around rows, with the box's heading. Where the parts
are too wide even so, a box is drawn narrower (the coordinate and axis boxes, the texture
box) and a tree shorter (`SIZES`); the figure's notes say so. Every control the desktop
figure draws falls in exactly one cut, or the layout is refused. The panel of step 1 is
narrow already: it is drawn narrower still, its callouts in a column beside it, wrapped,
and the rows it shows for the root link below it.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from pathlib import Path

from . import dialog_schematics as d
from .phone import MIN_TEXT_PX, SHOWN_PX, phone_path

WIDTH = 400
MARGIN = 6          # between the window's edge and its parts
GAP = 10            # between parts
GROUP_PAD = 6       # between a group box's edge and its parts
LINE = 15           # between the lines of a note
NOTE_CHARS = 66     # a note's line across the whole width, in characters


@dataclass(frozen=True)
class Cut:
    """A rectangle of the window as the desktop figure draws it (x after the tree is drawn
    narrower, y under the title bar)."""

    x0: float
    y0: float
    x1: float
    y1: float

    @property
    def width(self) -> float:
        return self.x1 - self.x0

    def holds(self, c, x: float, y: float) -> bool:
        inside = self.x0 <= x < self.x1 and self.y0 <= y < self.y1
        if c.kind == "GroupBox":     # a group box goes only whole
            return inside and x + c.w <= self.x1 and y + c.h <= self.y1
        return inside


@dataclass(frozen=True)
class Row:
    cuts: tuple[Cut, ...]
    right: bool = False      # against the right edge


@dataclass(frozen=True)
class Group:
    """The group box `box`, drawn as wide as there is room, around `rows`."""

    box: str
    rows: tuple


def _n(v: float) -> str:
    """A coordinate as the schematics write them: a tenth of a pixel at most."""
    return f"{v:.1f}".rstrip("0").rstrip(".")


def row(*cuts: Cut, right: bool = False) -> Row:
    return Row(cuts, right)


# Tree heights: as many rows as the example has, and a little room.
TREE_H = 18 * 5 + 12
SIZES = {"treeViewJointTree": {"h": TREE_H}, "treeViewLinkProperties": {"h": TREE_H},
         "comboBoxOrigin": {"w": 300}, "comboBoxAxis": {"w": 300}, "textBoxTexture": {"w": 225}}
TREE = Cut(4, 70, 170, 600)

JOINT_PARTS = (
    row(Cut(4, 0, 330, 30)),                                     # the page's heading
    row(TREE, Cut(195, 70, 365, 112)),                            # the tree; parent and child
    row(Cut(195, 115, 525, 160)),                                 # Joint Name
    row(Cut(535, 115, 705, 162)),                                 # Joint Type
    row(Cut(183, 170, 562, 232)),                                 # Coordinates, Axis
    row(Cut(195, 244, 525, 350)),                                 # Origin, Axis
    row(Cut(555, 244, 715, 372)),                                 # Limit
    row(Cut(172, 390, 525, 470)),                                 # Calibration, Dynamics
    row(Cut(530, 394, 745, 520)),                                 # Safety Controller
    row(Cut(205, 530, 525, 595)),                                 # Mimic Other Joint
    row(Cut(530, 570, 712, 590)),                                 # its equation
    row(Cut(8, 600, 92, 627), Cut(205, 600, 480, 632)),           # Cancel, the two remarks
    row(Cut(670, 600, 753, 627), right=True),                     # Next
)
LINK_PARTS = (
    row(Cut(4, 0, 340, 48)),                                      # the page's heading
    row(TREE),
    Group("groupBox5", (row(Cut(196, 97, 415, 205)),              # Inertial: Origin
                        row(Cut(420, 97, 735, 205)),              # Moment of Inertia
                        row(Cut(196, 225, 330, 252)))),           # Mass
    Group("groupBox4", (row(Cut(196, 305, 412, 403), Cut(545, 305, 670, 430)),   # Origin, Color
                        row(Cut(196, 422, 505, 527)),             # Mesh Detail, Format, Material
                        row(Cut(196, 530, 438, 578), Cut(587, 530, 670, 578)))),  # Texture
    row(Cut(8, 600, 92, 627), Cut(204, 600, 288, 627)),           # Cancel, Previous
    row(Cut(454, 600, 767, 627), right=True),                     # the two Export buttons
)
PHONE_NOTE = "Laid out for a phone: the window's parts one above the other, the tree shorter{}."


def wrap(words: str, chars: int) -> list[str]:
    """`words` in lines of at most `chars` characters, broken at spaces."""
    lines: list[str] = []
    for word in words.split():
        if lines and len(lines[-1]) + 1 + len(word) <= chars:
            lines[-1] += " " + word
        else:
            lines.append(word)
    return lines


def _document(height: float, body: list[str], title: str) -> str:
    if d.SIZE * SHOWN_PX / WIDTH < MIN_TEXT_PX:
        raise ValueError(f"a phone variant {WIDTH} px wide shows {d.SIZE} px lettering under "
                         f"{MIN_TEXT_PX} px in a {SHOWN_PX} px column")
    return d.document(height, body, f"{title}, laid out for a phone", width=WIDTH)


def _notes(lines: list[str], y: float) -> tuple[list[str], float]:
    """The course's notes under the window, wrapped; and the y under them."""
    out = []
    for line in (part for note in lines for part in wrap(note, NOTE_CHARS)):
        out.append(d.text(4, y, line, "note"))
        y += LINE + 2
    return out, y - 8


class _Window:
    """One assembly window's controls as the desktop figure places them, and the phone
    variant's parts drawn from them."""

    def __init__(self, parent: str, values: dict[str, str], tree: list[tuple[int, str]]):
        self.values, self.tree = values, tree
        self.placed = [(dataclasses.replace(c, **SIZES.get(c.name, {})), x, y)
                       for c, x, y in d.placed_controls(parent)]
        self.boxes = {c.name: (c, x, y) for c, x, y in self.placed if c.kind == "GroupBox"}
        self.drawn: dict[str, int] = {}

    def chosen(self, cut: Cut):
        found = [(c, x, y) for c, x, y in self.placed
                 if cut.holds(c, x, y) and not d.draws_nothing(c, self.values)]
        for c, _, _ in found:
            self.drawn[c.name] = self.drawn.get(c.name, 0) + 1
        return found

    def cut(self, cut: Cut, at_x: float, at_y: float) -> tuple[list[str], float]:
        """The cut's controls drawn with the cut's top left corner at (at_x, at_y); and
        the height they take."""
        chosen = self.chosen(cut)
        if not chosen:
            raise ValueError(f"{cut} holds no control")
        bottom = max(y + c.h + (2 if c.kind == "Button" else 0) for c, x, y in chosen)
        shift = f"translate({_n(at_x - cut.x0)},{_n(at_y - cut.y0 - d.TITLE_H)})"
        drawn = d.draw_controls(chosen, self.placed, self.values, self.tree)
        return [f'<g transform="{shift}">', *drawn, "</g>"], bottom - cut.y0

    def stack(self, parts, x: float, y: float, width: float) -> tuple[list[str], float]:
        """The parts one above the other from (x, y), `width` wide; and the y under them."""
        out: list[str] = []
        for part in parts:
            if isinstance(part, Group):
                box, bx, by = self.boxes[part.box]
                self.drawn[box.name] = self.drawn.get(box.name, 0) + 1
                heading = [(c, cx, cy) for c, cx, cy in self.placed
                           if c.parent == box.name and cy - by < 6]
                for c, _, _ in heading:
                    self.drawn[c.name] = self.drawn.get(c.name, 0) + 1
                shift = f"translate({_n(x - bx)},{_n(y - by - d.TITLE_H)})"
                inner, bottom = self.stack(part.rows, x + GROUP_PAD, y + 17, width - 2 * GROUP_PAD)
                out.append(d.rect(x, y + 6, width, bottom - y - 6 + GROUP_PAD - GAP, "group", rx=3))
                out += [f'<g transform="{shift}">', *d.draw_controls(heading, self.placed, self.values,
                                                                       self.tree), "</g>", *inner]
                y = bottom + GROUP_PAD
                continue
            wide = sum(c.width for c in part.cuts) + GAP * (len(part.cuts) - 1)
            if wide > width:
                raise ValueError(f"{part} is {wide} px wide, more than the {width} px there is")
            cx, height = x + (width - wide if part.right else 0), 0.0
            for cut in part.cuts:
                drawn, h = self.cut(cut, cx, y)
                out += drawn
                cx += cut.width + GAP
                height = max(height, h)
            y += height + GAP
        return out, y

    def check(self) -> None:
        """Every control the desktop figure draws is drawn once."""
        wrong = sorted(f"{c.name} ({self.drawn.get(c.name, 0)} times)" for c, _, _ in self.placed
                       if not d.draws_nothing(c, self.values) and self.drawn.get(c.name, 0) != 1)
        if wrong:
            raise ValueError(f"controls not drawn exactly once in the phone variant: {', '.join(wrong)}")


def assembly_phone(parent: str, values, tree, parts, notes: list[str], title: str) -> str:
    window = _Window(parent, values, tree)
    body, y = window.stack(parts, MARGIN, d.TITLE_H, WIDTH - 2 * MARGIN)
    window.check()
    height = y - GAP + MARGIN - d.TITLE_H
    lines, bottom = _notes(notes, height + d.TITLE_H + 20)
    return _document(bottom, d.window_frame(WIDTH, height) + body + lines, title)


def joint_window_phone() -> str:
    return assembly_phone(
        "form", d.JOINT_VALUES, d.JOINT_TREE, JOINT_PARTS,
        [*d.JOINT_NOTES, PHONE_NOTE.format(", the Coordinates and Axis boxes narrower")],
        "Configure Joint Properties, schematic")


def link_window_phone() -> str:
    return assembly_phone(
        "panelLinkProperties", d.LINK_VALUES, d.LINK_TREE, LINK_PARTS,
        [*d.LINK_NOTES, PHONE_NOTE.format(", the Texture box narrower")],
        "Configure Link Properties, schematic")


# --- the panel of step 1 ------------------------------------------------------------------

PANEL_W = 250
NOTE_X = PANEL_W + d.PANEL_X + 14      # the callouts' column, right of the panel
COLUMN_CHARS = 22                      # a line of that column, in characters


def property_manager_phone() -> str:
    """The panel 250 px wide, the names the source gives its unlabelled controls in a column
    beside it, each moved down as far as the one above needs; the root link's rows under it."""
    x0, w = d.PANEL_X, PANEL_W
    drawn = d.panel(x0, w)
    body = drawn.body
    y = 58
    for line in wrap("No label in the panel; the source calls them:", COLUMN_CHARS):
        body.append(d.text(NOTE_X, y, line, "note"))
        y += LINE
    free = y                                  # the column is free from here down
    for cy, caption, tip in drawn.callouts:
        ty = max(cy, free + 4)
        bend = f" H{NOTE_X - 14} L{NOTE_X - 4},{_n(ty)}" if ty > cy else f" H{NOTE_X - 4}"
        body.append(d.path(f"M{x0 + w - 6},{_n(cy)}{bend}", "leader"))
        body.append(d.text(NOTE_X, ty + 4, caption, "label", bold=True))
        ly = ty + 4
        for line in wrap(tip, COLUMN_CHARS):
            ly += LINE - 1
            body.append(d.text(NOTE_X, ly, line, "label tip"))
        free = ly + 8
        if caption == "Link Name":           # the four joint rows come next
            body.append(d.path(f"M{x0 + w - 2},{drawn.joint_top - 2} h6 V{drawn.joint_bottom} h-6",
                               "leader"))
            ny = max(free + 10, drawn.joint_top + 40)
            for line in wrap("With the root link selected, the panel shows the box below instead "
                             "of these four rows.", COLUMN_CHARS):
                body.append(d.text(NOTE_X, ny, line, "note"))
                ny += LINE
            free = ny
    y = drawn.height + 20
    body.append(d.text(4, y, "With the root link selected, instead of the four joint rows:", "note"))
    body += d.root_rows(x0, y + 10)
    return _document(y + 10 + 52 + 2, body, "The exporter's property manager panel, schematic")


# --- the figures ---------------------------------------------------------------------------

def write(svg: str, path: Path) -> None:
    Path(path).write_text(svg, encoding="utf-8")


def property_manager_figure(path: Path) -> None:
    write(d.property_manager(), path)
    write(property_manager_phone(), phone_path(path))


def joint_window_figure(path: Path) -> None:
    write(d.joint_window(), path)
    write(joint_window_phone(), phone_path(path))


def link_window_figure(path: Path) -> None:
    write(d.link_window(), path)
    write(link_window_phone(), phone_path(path))
