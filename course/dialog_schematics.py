"""Schematics of the exporter's three windows, drawn as SVG from course/exporter_dialogs.py.

They are drawings, not screenshots: boxes where the exporter has boxes, and its own words
where it has words. Three kinds of text are told apart by their class, so that a test can
check them: "label" is a text of the exporter (from its source, see exporter_dialogs),
"value" an example entry in a field (Practice 1's names), "note" the course's own remarks
beside the window. The assembly window keeps the Designer's positions and sizes, except
that its tree, 450 px wide and nearly empty, is drawn narrower and everything to its right
moved left by as much; the windows are drawn 1:1 on a 736 px wide page. Their phone
variants, the same windows cut into parts one above the other, are drawn with these
functions by course/dialog_schematics_phone.py, which also writes both.
"""

from __future__ import annotations

from dataclasses import dataclass

from .exporter_dialogs import (ASSEMBLY_FORM, FORM_TITLE, PROPERTY_MANAGER, PROPERTY_MANAGER_TITLE,
                               Control)

FONT = "Liberation Sans, Arial, Helvetica, sans-serif"
SIZE = 11.5          # px: the Designer's 8.25 pt, a little over 10 px on a 736 px page
WIDTH = 736
FACE = "#f0f0f0"     # window background
EDGE = "#7a7a7a"
BOX = "#ffffff"
NOTE = "#1f5fa8"     # the course's remarks
TREE_W = 150         # the trees' drawn width
TITLE_H = 24
PAD = 8

STYLE = f"""<style>
text {{ font-family: {FONT}; font-size: {SIZE}px; fill: #000; }}
text.value {{ fill: #303030; }}
text.note {{ fill: {NOTE}; font-style: italic; }}
text.hidden {{ fill: #8a8a8a; }}
text.tip {{ fill: #555; font-style: italic; }}
text.title {{ fill: #fff; font-size: 12px; }}
.frame {{ fill: {FACE}; stroke: #505050; stroke-width: 1; }}
.box {{ fill: {BOX}; stroke: {EDGE}; stroke-width: 1; }}
.ghost {{ fill: none; stroke: #9a9a9a; stroke-width: 1; stroke-dasharray: 4 3; }}
.button {{ fill: #e1e1e1; stroke: #adadad; stroke-width: 1; }}
.group {{ fill: none; stroke: #c8c8c8; stroke-width: 1; }}
.leader {{ fill: none; stroke: {NOTE}; stroke-width: 0.8; }}
.pick {{ fill: #cce4f7; stroke: none; }}
</style>"""


def _esc(text: str) -> str:
    return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;").replace('"', "&quot;")


def _f(v: float) -> str:
    return f"{v:.1f}".rstrip("0").rstrip(".")


def text(x, y, s, cls="label", anchor="start", bold=False, size=None) -> str:
    attrs = f'x="{_f(x)}" y="{_f(y)}" class="{cls}"'
    if anchor != "start":
        attrs += f' text-anchor="{anchor}"'
    if bold:
        attrs += ' font-weight="bold"'
    if size:
        attrs += f' style="font-size:{_f(size)}px"'
    return f"<text {attrs}>{_esc(s)}</text>"


def rect(x, y, w, h, cls, rx=0) -> str:
    r = f' rx="{_f(rx)}"' if rx else ""
    return f'<rect x="{_f(x)}" y="{_f(y)}" width="{_f(w)}" height="{_f(h)}" class="{cls}"{r}/>'


def path(d: str, cls="", style="") -> str:
    c = f' class="{cls}"' if cls else ""
    s = f' style="{style}"' if style else ""
    return f'<path d="{d}"{c}{s}/>'


def document(height: float, body: list[str], title: str, width: float = WIDTH) -> str:
    return (f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 {_f(width)} {_f(height)}" '
            f'width="{_f(width)}" height="{_f(height)}" role="img">\n<title>{_esc(title)}</title>\n{STYLE}\n'
            + "\n".join(body) + "\n</svg>\n")


def _arrow(x, y, down=True, colour="#404040") -> str:
    d = f"M{_f(x - 4)},{_f(y - 2)} L{_f(x + 4)},{_f(y - 2)} L{_f(x)},{_f(y + 3)} Z" if down else \
        f"M{_f(x - 4)},{_f(y + 2)} L{_f(x + 4)},{_f(y + 2)} L{_f(x)},{_f(y - 3)} Z"
    return path(d, style=f"fill:{colour}")


def combo(x, y, w, h, value="", cls="box") -> list[str]:
    out = [rect(x, y, w, h, cls), _arrow(x + w - 9, y + h / 2)]
    if value:
        out.append(text(x + 4, y + h / 2 + 4, value, "value"))
    return out


# --- steps 2 and 3: the assembly export window -----------------------------------------------

BOXES = ("TextBox", "ComboBox", "DomainUpDown")


def placed_controls(parent: str) -> list[tuple[Control, float, float]]:
    """The controls under `parent` (and its group boxes), each with its position in the
    window, the tree drawn narrower and what lies right of it moved left."""
    tree = next(c for c in ASSEMBLY_FORM if c.kind == "TreeView" and c.parent == parent)
    shift = tree.w - TREE_W
    out = []

    def walk(p: str, ox: float, oy: float) -> None:
        for c in ASSEMBLY_FORM:
            if c.parent != p or c.kind == "Panel":
                continue
            x, y = ox + c.x, oy + c.y
            if p == parent and x > tree.x + tree.w:
                x -= shift
            out.append((c, x, y))
            if c.kind == "GroupBox":
                walk(c.name, x, y)

    walk(parent, 0, 0)
    return out


def _label_anchor(c: Control, x: float, y: float, placed) -> tuple[float, str]:
    """A label just left of a box on its row ends at the box, as the dialog shows it;
    any other starts where the Designer puts it."""
    for other, ox, oy in placed:
        if other.kind in BOXES and abs((oy + other.h / 2) - (y + c.h / 2)) <= 7 and x < ox <= x + c.w + 14:
            return ox - 4, "end"
    return x, "start"


def window_frame(width: float, height: float) -> list[str]:
    """The window's face and its title bar, `height` the face's below the bar."""
    return [rect(0.5, 0.5, width - 1, height + TITLE_H - 1, "frame"),
            f'<rect x="0.5" y="0.5" width="{_f(width - 1)}" height="{TITLE_H}" style="fill:#2b579a"/>',
            text(PAD, 16.5, FORM_TITLE[0], "label title")]


def draws_nothing(c: Control, values: dict[str, str]) -> bool:
    """An empty label the example leaves empty: the Designer's placeholder for a text."""
    return c.kind == "Label" and not c.text and c.name not in values


def draw_controls(chosen, placed, values: dict[str, str], tree: list[tuple[int, str]]) -> list[str]:
    """The controls `chosen` (control, x, y), drawn where `placed` (every control of the
    window, as `placed_controls` gives them) puts them, the title bar above."""
    out = []
    for c, x, y in chosen:
        y += TITLE_H
        ghost = c.hidden
        if c.kind == "TreeView":
            out.append(rect(x, y, TREE_W, c.h, "box"))
            for i, (depth, name) in enumerate(tree):
                ty = y + 16 + 18 * i
                if name.startswith("*"):
                    name = name[1:]
                    out.append(rect(x + 8 + 14 * depth, ty - 12, 7 * len(name) + 6, 16, "pick"))
                out.append(text(x + 11 + 14 * depth, ty, name, "value"))
        elif c.kind == "GroupBox":
            out.append(rect(x, y + 6, c.w, c.h - 6, "group", rx=3))
            if c.text:
                out.append(f'<rect x="{_f(x + 5)}" y="{_f(y)}" width="{_f(6.2 * len(c.text))}" height="13" '
                           f'style="fill:{FACE}"/>')
                out.append(text(x + 7, y + 10, c.text))
        elif c.kind == "Label":
            if not c.text:
                if c.name in values:
                    out.append(text(x + 6, y + 10, values[c.name], "value"))
                continue
            ax, anchor = _label_anchor(c, x, y - TITLE_H, placed)
            size = 14 if c.bold and c.h >= 17 else None
            cls = "label hidden" if ghost else "label"
            if c.text == "*":
                out.append(text(ax, y + 10, c.text, cls, anchor, bold=True).replace(
                    'class="label"', 'class="label" style="fill:#c00000"'))
                continue
            out.append(text(ax, y + (14 if size else 10), c.text, cls, anchor, bold=c.bold, size=size))
        elif c.kind in ("TextBox", "DomainUpDown"):
            out.append(rect(x, y, c.w, c.h, "ghost" if ghost else "box"))
            if c.kind == "DomainUpDown":
                out += [_arrow(x + c.w - 8, y + c.h / 2 - 3, down=False), _arrow(x + c.w - 8, y + c.h / 2 + 4)]
                out.append(text(x + 4, y + c.h / 2 + 4, values.get(c.name, c.text),
                                "value" if c.name in values else "label"))
            elif c.name in values:
                out.append(text(x + 4, y + c.h / 2 + 4, values[c.name], "value"))
        elif c.kind == "ComboBox":
            out += combo(x, y, c.w, c.h, values.get(c.name, ""), "ghost" if ghost else "box")
        elif c.kind == "Button":
            out.append(rect(x, y, c.w, c.h + 2, "button", rx=2))
            out.append(text(x + c.w / 2, y + c.h / 2 + 5, c.text, "label", "middle"))
        elif c.kind == "RadioButton":
            out.append(f'<circle cx="{_f(x + 7)}" cy="{_f(y + 8)}" r="6" class="box"/>')
            if c.checked:
                out.append(f'<circle cx="{_f(x + 7)}" cy="{_f(y + 8)}" r="3" style="fill:#202020"/>')
            out.append(text(x + 17, y + 12, c.text))
        elif c.kind == "CheckBox":
            out.append(rect(x + 1, y + 2, 12, 12, "box"))
            out.append(text(x + 18, y + 12, c.text))
    return out


def window_width(parent: str) -> float:
    """The window's client width, less what the tree gave up."""
    view = next(c for c in ASSEMBLY_FORM if c.kind == "TreeView" and c.parent == parent)
    return 1073 - (view.w - TREE_W)


def _assembly_body(parent: str, values: dict[str, str], tree: list[tuple[int, str]],
                   notes: list[str]) -> tuple[list[str], float, float]:
    placed = placed_controls(parent)
    width = window_width(parent)
    height = 634
    body = window_frame(width, height) + draw_controls(placed, placed, values, tree)
    y = height + TITLE_H + 20
    for line in notes:
        body.append(text(4, y, line, "note"))
        y += 17
    return body, y - 6, width


JOINT_VALUES = {
    "labelParent": "base_link", "labelChild": "front_left_wheel", "textBoxJointName": "front_left_joint",
    "comboBoxJointType": "continuous", "comboBoxOrigin": "Origin_front_left_joint",
    "comboBoxAxis": "Axis_front", "textBoxJointX": "0.13", "textBoxJointY": "0.18", "textBoxJointZ": "0",
    "textBoxJointRoll": "1.5708", "textBoxJointPitch": "0", "textBoxJointYaw": "0",
    "textBoxAxisX": "0", "textBoxAxisY": "1", "textBoxAxisZ": "0",
}
JOINT_TREE = [(0, "base_link"), (1, "*front_left_joint"), (1, "front_right_joint"),
              (1, "rear_left_joint"), (1, "rear_right_joint")]
LINK_TREE = [(0, "*base_link"), (1, "front_left_wheel"), (1, "front_right_wheel"),
             (1, "rear_left_wheel"), (1, "rear_right_wheel")]
LINK_VALUES = {"textBoxMass": "2.6535", "textBoxInertialOriginX": "0", "textBoxInertialOriginY": "0",
               "textBoxInertialOriginZ": "0", "textBoxIxx": "0.016024", "textBoxIyy": "0.029823",
               "textBoxIzz": "0.045673", "textBoxIxy": "0", "textBoxIxz": "0", "textBoxIyz": "0",
               "textBoxInertialOriginRoll": "0", "textBoxInertialOriginPitch": "0", "textBoxInertialOriginYaw": "0",
               "textBoxVisualOriginX": "0", "textBoxVisualOriginY": "0", "textBoxVisualOriginZ": "0",
               "textBoxVisualOriginRoll": "0", "textBoxVisualOriginPitch": "0", "textBoxVisualOriginYaw": "0",
               "domainUpDownRed": "0.792", "domainUpDownGreen": "0.82", "domainUpDownBlue": "0.933",
               "domainUpDownAlpha": "1"}


JOINT_NOTES = ["Dashed: the mimic fields, shown once Mimic Other Joint is ticked.",
               "The joint tree is drawn narrower than the window has it; example entries from Practice 1."]
LINK_NOTES = ["The link tree is drawn narrower than the window has it; example entries: Practice 1's base, rounded.",
              "Mesh Format is in the source after release 1.6.1 only."]


def joint_window() -> str:
    body, height, width = _assembly_body("form", JOINT_VALUES, JOINT_TREE, JOINT_NOTES)
    return document(height, body, "Configure Joint Properties, schematic", width)


def link_window() -> str:
    body, height, width = _assembly_body("panelLinkProperties", LINK_VALUES, LINK_TREE, LINK_NOTES)
    return document(height, body, "Configure Link Properties, schematic", width)


# --- step 1: the panel beside the feature tree -----------------------------------------------

PANEL_X, PANEL_W = 8, 300
ROW = 19
NOTE_X = 350


def _pm(caption: str, shown: str = "child"):
    return next(c for c in PROPERTY_MANAGER if c.caption == caption and c.shown in (shown, "always"))


@dataclass
class Panel:
    """The panel drawn `w` wide at `x0`, and where its unlabelled controls are."""

    body: list[str]
    callouts: list[tuple[float, str, str]]   # (y of the control, caption, tooltip)
    joint_top: float        # the four joint rows, top and bottom
    joint_bottom: float
    height: float


def panel(x0: float = PANEL_X, w: float = PANEL_W) -> Panel:
    """The panel of step 1 with front_left_wheel selected, its controls in the source's order."""
    ix = x0 + 22                 # the indented boxes
    bw = w - 36
    body: list[str] = []
    callouts: list[tuple[float, str, str]] = []     # (y of the control, caption, tooltip)
    y = 0.5
    body.append(rect(x0, y, w, 600, "frame"))
    body.append(text(x0 + 10, y + 20, PROPERTY_MANAGER_TITLE[0], "label", bold=True, size=14))
    # OK and Cancel, drawn as the panel's green tick and red cross
    body.append(path(f"M{x0 + 12},{y + 36} l5,5 l9,-11", style="fill:none;stroke:#2e9b3a;stroke-width:2.4"))
    body.append(path(f"M{x0 + 40},{y + 28} l10,10 M{x0 + 50},{y + 28} l-10,10",
                     style="fill:none;stroke:#c0392b;stroke-width:2.4"))
    y = 56
    group = _pm("Configure and Organize Links")
    body.append(rect(x0 + 6, y, w - 12, 22, "button", rx=2))
    body.append(text(x0 + 14, y + 15, group.caption, bold=True))
    body.append(_arrow(x0 + w - 20, y + 11, down=False))
    y += 34
    # the parent's name: a label the panel fills in
    body.append(text(ix, y + 10, "base_link", "value"))
    callouts.append((y + 6, "Parent Link", ""))
    y += ROW
    name = _pm("base_link")
    body.append(rect(ix, y, bw, 20, "box"))
    body.append(text(ix + 4, y + 14, "front_left_wheel", "value"))
    callouts.append((y + 10, "Link Name", name.tip))
    y += 30
    rows = [("Joint Name", "front_left_joint", "Textbox"),
            ("Reference Coordinate System", "Origin_front_left_joint", "Combobox"),
            ("Reference Axis", "Axis_front", "Combobox"),
            ("Joint Type", "continuous", "Combobox")]
    joint_top = y
    for caption, value, kind in rows:
        body.append(text(x0 + 12, y + 10, _pm(caption).caption))
        y += 15
        if kind == "Textbox":
            body.append(rect(ix, y, bw, 20, "box"))
            body.append(text(ix + 4, y + 14, value, "value"))
        else:
            body += combo(ix, y, bw, 20, value)
        y += 29
    joint_bottom = y - 8
    comps = _pm("Link Components")
    body.append(rect(ix, y, bw, 50, "box"))
    body.append(rect(ix + 2, y + 2, bw - 4, 16, "pick"))
    body.append(text(ix + 6, y + 14, "wheel-1@Example_1", "value"))
    callouts.append((y + 22, comps.caption, comps.tip))
    y += 60
    count = _pm("Number of child links")
    body.append(rect(ix, y, 80, 20, "box"))
    body.append(text(ix + 4, y + 14, "0", "value"))
    body += [_arrow(ix + 72, y + 6, down=False), _arrow(ix + 72, y + 14)]
    callouts.append((y + 10, count.caption, next(c.tip for c in PROPERTY_MANAGER if c.kind == "Numberbox")))
    y += 32
    for caption in ("Load Configuration...", "Preview and Export..."):
        body.append(rect(x0 + (w - 200) / 2, y, 200, 22, "button", rx=2))
        body.append(text(x0 + w / 2, y + 15, _pm(caption).caption, anchor="middle"))
        y += 30
    y += 4
    tree_top = y
    body.append(rect(x0 + 6, y, w - 12, 163, "box"))
    for i, (depth, item) in enumerate([(0, "base_link"), (1, "*front_left_wheel"), (1, "front_right_wheel"),
                                       (1, "rear_left_wheel"), (1, "rear_right_wheel")]):
        ty = y + 17 + 18 * i
        if item.startswith("*"):
            item = item[1:]
            body.append(rect(x0 + 14 + 16 * depth, ty - 12, 7 * len(item) + 8, 16, "pick"))
        body.append(text(x0 + 18 + 16 * depth, ty, item, "value"))
    callouts.append((tree_top + 40, "Link Tree", ""))
    y += 163 + 10
    height = y + 2
    body[0] = rect(x0, 0.5, w, height - 1, "frame")
    return Panel(body, callouts, joint_top, joint_bottom, height)


def root_rows(x: float, y: float) -> list[str]:
    """What the panel shows instead of the four joint rows with the root link selected,
    in a frame 300 wide whose top left corner is (x, y)."""
    root = _pm("Global Origin Coordinate System", "root")
    return [rect(x, y, 300, 52, "frame"), text(x + 10, y + 16, root.caption),
            *combo(x + 24, y + 24, 264, 20, "Origin_global")]


def property_manager() -> str:
    x0, w = PANEL_X, PANEL_W
    drawn = panel(x0, w)
    body = drawn.body
    # the callouts: what the source calls the controls that have no label in the panel
    body.append(text(NOTE_X, 66, "No label in the panel; the source calls them:", "note"))
    for cy, caption, tip in drawn.callouts:
        ty = max(cy, 0)
        body.append(path(f"M{x0 + w - 6},{_f(cy)} H{NOTE_X - 6}", "leader"))
        body.append(text(NOTE_X, ty + 4, caption, "label", bold=True))
        if tip:
            body.append(text(NOTE_X + 8, ty + 19, tip if len(tip) < 52 else tip[:tip.rfind(" ", 0, 52)], "label tip"))
            if len(tip) >= 52:
                body.append(text(NOTE_X + 8, ty + 33, tip[tip.rfind(" ", 0, 52) + 1:], "label tip"))
    # the root link's rows
    body.append(path(f"M{x0 + w - 2},{drawn.joint_top - 2} h6 V{drawn.joint_bottom} h-6", "leader"))
    rx, ry = NOTE_X, drawn.joint_top + 40
    body.append(text(rx, ry, "With the root link selected, the panel shows", "note"))
    body.append(text(rx, ry + 16, "this instead of the four joint rows:", "note"))
    body += root_rows(rx, ry + 26)
    return document(drawn.height, body, "The exporter's property manager panel, schematic")

