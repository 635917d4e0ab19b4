"""The assembly drawing of a robot.

Each link's pose composed down the joint tree (`link_poses`); the links in a front and a top view,
nearest last, each filled white over those behind it and drawn with its part's own lines (or its
silhouette when turned); balloons with leaders, the joints' origins and axes, the parts list above
the title block, and `assembly_drawing_svg`.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

import numpy as np
import shapely
from shapely import affinity
from shapely.geometry import MultiPolygon, Polygon
from shapely.ops import polylabel

from ..parts import Part
from .projection import VIEWS, Projector, trace_view, view_prims
from .sheet import (SCALES, TITLE_BLOCK, VIEW_GAP, boxes_fit, fit, frame, largest_fitting, title_block,
                    view_label)
from .solids import Solid
from .svg import Circle, Fill, Line, Poly, Text, bbox, document, moved, text_width, views_box

# --- the assembly drawing ------------------------------------------------------------------------

BALLOON_R = 4.0
JOINT_CROSS, JOINT_ARROW = 1.8, 10.0  # sheet mm
# The joints' names: 4.1 mm reads 10 px high when the sheet (297 mm) is shown 736 px wide.
JOINT_TEXT = 4.1
JOINT_PITCH = 1.3 * JOINT_TEXT  # between the baselines of two names on the same side


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
        prims = [Fill(rings)]
        if p.square:
            key = (id(p.item.part), view)
            if key not in lines_cache:
                solid = Solid(p.item.part.features)
                traced = trace_view(solid, view, k)
                traced.hidden, traced.centre = [], []
                lines_cache[key] = view_prims(traced, Projector(solid, view), k)
            prims += moved(lines_cache[key], k * p.offset[0], -k * p.offset[1])
        else:
            prims.append(Poly(rings, True, "visible"))
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
        out += [Circle(float(at[0]), float(at[1]), 0.5, "solid"),
                Line(float(at[0]), float(at[1]), float(edge[0]), float(edge[1])),
                Circle(float(spot[0]), float(spot[1]), BALLOON_R, "thin"),
                Text(float(spot[0]), float(spot[1]) + 1.75, str(number), 5.0)]
    return out


def _joint_marks(robot, poses, k: float, box, listed: list | None = None) -> list:
    """Each joint's origin (a cross) and axis (an arrow, or a circled dot when the axis points
    at the viewer, a circle alone when away) in the top view; its name beside the view, on a
    leader, on the side of the view the joint is on. Joints that share an origin have their
    names one under the other; names that would touch are spread apart, the leader bending to
    reach them. With `listed` (a list), the names are not drawn beside the view, whose width
    they would double on a phone: each origin gets a letter beside its cross instead, and
    `listed` receives (letter, name) for a key under the views."""
    d, h, v = (np.array(x) for x in VIEWS["top"])
    middle = (box[0] + box[2]) / 2
    out = []
    names: dict[tuple[float, float], list[str]] = {}  # joints that share an origin share a label
    for j in robot.joints:
        T = poses[j.child]
        o = T[:3, 3]
        x, y = float(k * (o @ h)), float(-k * (o @ v))
        names.setdefault((round(x, 2), round(y, 2)), []).append(j.name)
        out += [Line(x - JOINT_CROSS, y, x + JOINT_CROSS, y, "joint"),
                Line(x, y - JOINT_CROSS, x, y + JOINT_CROSS, "joint")]
        if j.axis is None:
            continue
        axis = T[:3, :3] @ np.asarray(j.axis, dtype=float)
        axis /= np.linalg.norm(axis)
        flat = np.array([axis @ h, -(axis @ v)])
        if np.linalg.norm(flat) > 0.3:
            end = np.array([x, y]) + JOINT_ARROW * flat
            u = flat / np.linalg.norm(flat)
            tip = end
            out.append(Line(x, y, *(tip - 1.5 * u), "joint"))
            base = tip - 2.5 * u
            across = np.array([-u[1], u[0]])
            pts = (tip, base + 0.8 * across, base - 0.8 * across)
            out.append(Poly((tuple((float(a), float(b)) for a, b in pts),), True, "jointfill"))
        else:
            out.append(Circle(x, y, 2.5, "joint"))
            if axis @ d < 0:  # pointing at the viewer: a dot
                out.append(Circle(x, y, 0.6, "jointfill"))
    if listed is not None:
        return out + _joint_letters(names, out, listed)
    for right in (False, True):
        side = sorted(((y, x, n) for (x, y), n in names.items() if (x >= middle) == right))
        # each origin's names as a block of lines centred on it, blocks pushed apart downwards
        # where they would touch, then the whole side moved back up to stay centred
        heights = [(len(n) - 1) * JOINT_PITCH for _, _, n in side]
        tops = [y - h / 2 for (y, _, _), h in zip(side, heights)]
        for i in range(1, len(tops)):
            tops[i] = max(tops[i], tops[i - 1] + heights[i - 1] + JOINT_PITCH)
        if tops:
            wanted = [y - h / 2 for (y, _, _), h in zip(side, heights)]
            shift = min(0.0, float(np.mean(np.array(wanted) - np.array(tops))))
            tops = [t + shift for t in tops]
            for i in range(1, len(tops)):  # the shift keeps the gaps
                tops[i] = max(tops[i], tops[i - 1] + heights[i - 1] + JOINT_PITCH)
        end = box[2] + 3.0 if right else box[0] - 3.0
        knee = end - 2.0 if right else end + 2.0
        for (y, x, joint_names), top, h in zip(side, tops, heights):
            at = top + h / 2
            if abs(at - y) < 0.01:
                out.append(Line(x, y, end, y, "jointleader"))
            else:
                out += [Line(x, y, knee, y, "jointleader"), Line(knee, y, end, at, "jointleader")]
            for i, name in enumerate(joint_names):
                out.append(Text(end + (1.0 if right else -1.0), top + i * JOINT_PITCH + 0.36 * JOINT_TEXT,
                                name, JOINT_TEXT, "start" if right else "end", style="jointtext"))
    return out


def _joint_letters(names: dict, marks: list, listed: list) -> list:
    """A letter beside each joint origin of `names` ((x, y) -> joint names), top to bottom
    and left to right, in the first corner round its cross clear of the `marks` and of the
    letters placed before; (letter, name) of each joint appended to `listed`."""
    taken = [shapely.box(*bbox([m])) if isinstance(m, Text) else shapely.LineString(m.points()).buffer(0.3)
             for m in marks if isinstance(m, (Line, Poly, Text))]
    taken += [shapely.Point(m.cx, m.cy).buffer(m.r) for m in marks if isinstance(m, Circle)]
    out = []
    for i, ((x, y), joint_names) in enumerate(sorted(names.items(), key=lambda o: (o[0][1], o[0][0]))):
        letter = chr(ord("a") + i)
        gap = JOINT_CROSS + 0.8
        corners = [(x + gap, y - gap, "start"), (x - gap, y - gap, "end"),
                   (x + gap, y + gap + 0.75 * JOINT_TEXT, "start"), (x - gap, y + gap + 0.75 * JOINT_TEXT, "end")]
        texts = [Text(cx, cy, letter, JOINT_TEXT, anchor, style="jointtext") for cx, cy, anchor in corners]
        text = next((t for t in texts if not any(shapely.box(*bbox([t])).intersects(o) for o in taken)),
                    texts[0])
        taken.append(shapely.box(*bbox([text])))
        out.append(text)
        listed += [(letter, name) for name in joint_names]
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
    out = [Poly((((x0, top), (x1, top), (x1, y_base), (x0, y_base)),), True, "visible"),
           Line(x0, y_base - head_h, x1, y_base - head_h, "visible")]
    x = x0
    for name, w in PARTS_COLUMNS:
        out.append(Text(x + 1.2, y_base - 1.8, name, 2.5, "start", bold=True))
        if x > x0:
            out.append(Line(x, top, x, y_base))
        x += w
    y = y_base - head_h
    for cells, h in rows:  # item 1 just above the headings
        out.append(Line(x0, y - h, x1, y - h))
        x = x0
        for (name, w), value in zip(PARTS_COLUMNS, cells):
            values = value if isinstance(value, list) else [value]
            for n, text in enumerate(values):
                size = fit(text, w - 2.4, 2.5 if isinstance(value, list) else 3.0)
                out.append(Text(x + 1.2, y - h + 4.2 + 3.2 * n, text, size, "start"))
            x += w
        y -= h
    return out, height


def assembly_drawing_svg(robot, views_only: bool = False, width: float | None = None) -> str:
    """The robot's assembly drawing: front and top views with balloons, the joints' origins and
    axes, a parts list and the title block. `views_only`: the views with their balloons and
    joint marks alone, cropped close, and under them a key to the balloons (what a page
    shows, so that the lettering is large enough at the page's width). `width` (with
    `views_only`): the views drawn smaller, if they must, so that they are at most `width`
    mm wide with their names and marks, the lettering as large as ever (for a phone's
    column: course/drawing/narrow.py)."""
    joints: list = []
    layers, items = _assembly_layers(robot, width if views_only else None, joints)
    title = f"{robot.name} ({robot.name}.SLDASM)"
    if not views_only:
        return document(layers, title)
    views = [(name, prims) for name, prims in layers if name != "sheet"]
    x0, _, x1, y1 = bbox([p for _, prims in views for p in prims])
    # the key's lines as wide as the views at most where they must fit a width (a phone's)
    room = None if width is None else max(width, x1 - x0)
    rows = [(str(item.number), f"{item.part.title or item.part.name} ({item.part.name}.SLDPRT)"
             f" × {len(item.links)}", "text") for item in items]
    # the joints' names, when the narrow views mark each origin with a letter instead
    rows += [(letter, name, "jointtext") for letter, name in joints]
    key = []
    for mark, entry, style in rows:
        for indent, line in _key_lines(mark, entry, room):
            key.append(Text(x0 + indent, y1 + 6.0 + len(key) * 1.4 * KEY_TEXT, line, KEY_TEXT, "start",
                            style=style))
    views.append(("key", key))
    return document(views, title, views_box(views))


KEY_TEXT = 4.1  # mm: the key to the balloons under the views, as large as the joints' names


def _key_lines(mark: str, entry: str, width: float | None) -> list[tuple[float, str]]:
    """One line of the key, (its indent in mm, its text): `mark` (a balloon's number or a
    joint's letter) then `entry`; or, where that is wider than `width` mm, the entry broken
    between words onto lines set under its first word (a word wider than the room keeps a
    line of its own, and a count, "× 2", the word before it)."""
    lead = f"{mark}  "
    if width is None or text_width(lead + entry, KEY_TEXT) <= width:
        return [(0.0, lead + entry)]
    indent = text_width(lead, KEY_TEXT)
    lines, line = [], ""
    for word in re.split(r"(?<!×) (?!×)", entry):   # "× 2" stays with the word before it
        trial = f"{line} {word}".strip()
        if line and indent + text_width(trial, KEY_TEXT) > width:
            lines.append(line)
            line = word
        else:
            line = trial
    lines.append(line)
    return [(0.0, lead + lines[0])] + [(indent, text) for text in lines[1:]]


def _assembly_layers(robot, width: float | None = None, joints: list | None = None) -> tuple[list, list]:
    """The sheet's layers and the parts list's items; or, `width` given, the views alone at
    the sheet's scale or, if that makes them wider than `width` mm, the largest that does not,
    the joints marked with letters and their names appended to `joints` (`_joint_marks`)."""
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

    def view_layers(v: str, k: float, full: bool, listed: list | None = None) -> list[tuple[str, list]]:
        if full:
            layers = _assembly_links(views[v], v, k, lines_cache)
        else:  # extents only: the outlines' boxes stand in for the lines
            layers = [("", [Poly(_rings(p.outline.envelope, k), True) for p in views[v]])]
        box = bbox([q for _, prims in layers for q in prims])
        notes = _joint_marks(robot, poses, k, box, listed) if v == "top" else []
        leaders = [y for n in notes if isinstance(n, Line) and n.style == "jointleader" for y in (n.y1, n.y2)]
        notes += _balloons(anchors[v], bbox([Poly((((box[0], box[1]), (box[2], box[3])),))] + notes), k,
                           leaders)
        notes += view_label([q for _, prims in layers for q in prims] + notes, v.upper(), (box[0] + box[2]) / 2)
        if v == "top":  # a key to the joint marks, under the view's name
            y = notes[-1].y + 4.5
            notes.append(Text((box[0] + box[2]) / 2, y + JOINT_TEXT - 2.5, "Joints: + origin, → axis",
                               JOINT_TEXT, "middle", style="jointtext"))
        return layers + [(f"{v}-notes", notes)]

    def extent(layers):
        return bbox([q for _, prims in layers for q in prims])

    for label, factor in SCALES:
        k = 1000.0 * factor
        front, top = extent(view_layers("front", k, False)), extent(view_layers("top", k, False))
        dy = front[3] - top[1] + VIEW_GAP
        origin = boxes_fit([front, (top[0], top[1] + dy, top[2], top[3] + dy)], reserved)
        if origin is not None:
            break
    else:
        raise ValueError(f"robot {robot.name!r} does not fit an A4 sheet at 1:100")
    if width is not None:
        def wide(k: float) -> float:
            front, top = extent(view_layers("front", k, False)), extent(view_layers("top", k, False, []))
            return max(front[2], top[2]) - min(front[0], top[0])

        k = largest_fitting(wide, k, width)
        front, top = extent(view_layers("front", k, False)), extent(view_layers("top", k, False, []))
        dy = front[3] - top[1] + VIEW_GAP
        listed = [] if joints is None else joints
        layers = view_layers("front", k, True) + [(name, moved(prims, 0.0, dy))
                                                   for name, prims in view_layers("top", k, True, listed)]
        return layers, items
    layers = [(name, moved(prims, *origin)) for name, prims in view_layers("front", k, True)]
    layers += [(name, moved(prims, origin[0], origin[1] + dy)) for name, prims in view_layers("top", k, True)]
    mass = sum(lk.part.mass for item in items for lk in item.links)
    block = title_block(robot.name, f"{robot.name}.SLDASM", "See parts list", "–", f"{mass:.3f} kg", label)
    layers.append(("sheet", frame() + plist + block))
    return layers, items
