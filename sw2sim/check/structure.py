"""Checks of the URDF's structure: names, joint types, the link tree, and numbers that parse.

The tree rules follow what ROS's URDF parser demands and what MuJoCo's import needs: every
joint joins two links that exist, every link but one (the root) is the child of exactly
one joint, and following parents never comes back to where it started.

Two helpers live here because every check uses them: `number`/`vector` read a URDF number
the way the URDF parsers do (or give None, reported once by `number-invalid`), and
`source_line` finds the line of an attribute, since lxml reports where a start tag ends.
"""

from __future__ import annotations

from collections import defaultdict
from difflib import get_close_matches

from ..xmlsafe import source_line
from .findings import ERROR, PACKAGING, WARNING, rule
from .urdf import number, owner, urdfdom_version_error

JOINT_TYPES = ("revolute", "continuous", "prismatic", "fixed", "floating", "planar")

rule("name-missing", ERROR, "structure", "A link or joint has no name",
     symptom="ROS refuses a link or joint without a name attribute (\"No name given for the "
             "link\", \"unnamed joint found\"); check_urdf accepts a joint whose name is "
             "empty or spaces, but ROS's tools and controllers address joints by name, so "
             "nothing can command it. MuJoCo names the body or joint after nothing, and "
             "joints cannot refer to the link.",
     cause="A hand edit that dropped or emptied the name attribute; the exporter always "
           "writes one.",
     fix="Give the element a name that is unique among links (or joints), such as the "
         "name the exporter dialog shows for it.")
rule("name-duplicate", ERROR, "structure", "Two links, or two joints, share a name",
     symptom="ROS refuses the URDF (\"link ... is not unique\"); MuJoCo stops with a "
             "repeated name error.",
     cause="Copying a link or joint block by hand without renaming it, or two SolidWorks "
           "components given the same link name in the exporter dialog.",
     fix="Rename one of them, and update the <parent>/<child> elements that refer to it.")
rule("joint-type-unknown", ERROR, "structure", "A joint's type is missing or not a URDF type",
     symptom="ROS refuses the URDF (\"Joint ... has no known type\"); MuJoCo stops with an "
             "invalid keyword error.",
     cause="A typo or a type from another format (\"hinge\", \"slider\", \"ball\"). URDF knows "
           "revolute, continuous, prismatic, fixed, floating and planar.",
     fix="Pick the joint type in the exporter dialog again, or write one of revolute, "
         "continuous, prismatic, fixed, floating or planar in the URDF.")
rule("joint-parent-missing", ERROR, "structure", "A joint has no parent link, or names one "
     "that does not exist",
     symptom="ROS refuses the URDF (\"parent link ... not found\"); MuJoCo stops with an "
             "error about the joint or leaves part of the robot out.",
     cause="The <parent link=...> element is missing, or the link was renamed or removed "
           "after the export while the joint still names the old link.",
     fix="Write <parent link=\"...\"/> with the name of an existing link, or export again "
         "so the joint and link names agree.")
rule("joint-child-missing", ERROR, "structure", "A joint has no child link, or names one "
     "that does not exist",
     symptom="ROS refuses the URDF (\"child link ... not found\"); MuJoCo stops with an "
             "error about the joint or leaves part of the robot out.",
     cause="The <child link=...> element is missing, or the link was renamed or removed "
           "after the export while the joint still names the old link.",
     fix="Write <child link=\"...\"/> with the name of an existing link, or export again "
         "so the joint and link names agree.")
rule("link-two-parents", ERROR, "structure", "A link is the child of two joints",
     symptom="check_urdf accepts the URDF and lists the link under both parents, but ROS "
             "keeps one joint as its parent (urdfdom the one whose name sorts last, and "
             "robot_state_publisher with it); MuJoCo also keeps one and silently drops the "
             "other. Either way the mechanism does not move as designed.",
     cause="An attempt to close a loop, such as a four-bar or a steering trapezoid, in the "
           "URDF. URDF describes trees only: each link has one parent.",
     fix="Keep one joint as the link's parent and remove the other; close the loop in "
         "MuJoCo with an equality constraint (<connect> or <weld>) instead.",
     seen_in=("onshape-to-robot#94",))
rule("kinematic-cycle", ERROR, "structure", "Following the joints from parent to child "
     "comes back to the start",
     symptom="MuJoCo cannot build the body tree (\"URDF body not found\"). check_urdf "
             "refuses the URDF when the loop leaves no link without a parent (\"No root link "
             "found\"); when another link is the root it accepts the file, and the loop's "
             "links are missing from the tree RViz and robot_state_publisher use.",
     cause="A joint whose child is one of its own ancestors, often from a hand-closed "
           "linkage or a parent and child swapped by mistake.",
     fix="Break the cycle: swap parent and child where they were reversed, or remove the "
         "closing joint and close the loop with a MuJoCo equality constraint.",
     seen_in=("onshape-to-robot#94",))
rule("roots-several", ERROR, "structure", "More than one link has no parent joint",
     symptom="ROS refuses the URDF (\"two root links found\"); MuJoCo places each root "
             "separately in the world, so the parts fall apart.",
     cause="A link that no joint connects, usually one left out of the exporter's link "
           "tree or a joint deleted by hand.",
     fix="Connect every link to the tree in the exporter dialog (add it as a child of the "
         "link it is attached to), or add the missing <joint> to the URDF.")
rule("urdf-no-links", ERROR, "structure", "The URDF has no links",
     symptom="ROS and MuJoCo have nothing to load; MuJoCo reports an empty model.",
     cause="An export that stopped before writing the links, or the wrong file.",
     fix="Export the assembly again and check the exporter's log for the failure.")
rule("number-invalid", ERROR, "structure", "A number in the URDF does not parse",
     symptom="MuJoCo stops with \"bad format in attribute\". check_urdf refuses it in a "
             "joint; in a link's <inertial>, <visual> or <collision> it prints the parse error "
             "and accepts the file, keeping the link without that element and those after it "
             "(without its mass, or its shapes), which is how RViz and robot_state_publisher "
             "then read it.",
     cause="A hand edit with a typo (\"1.0.0\", \"0,5\" with a decimal comma, a unit such as "
           "\"90deg\"), a value that is not finite (\"nan\", \"inf\"), or a vector with too "
           "few or too many entries.",
     fix="Write plain decimal numbers in SI units (metres, radians, kilograms), with a "
         "decimal point, and exactly as many as the attribute takes (three for xyz and rpy).")

rule("urdf-version", ERROR, "structure", "The <robot> names a URDF version ROS does not read",
     symptom="ROS's URDF parser (urdfdom: check_urdf, RViz, robot_state_publisher) refuses the "
             "file: \"Invalid 'version' specified; only version 1.0 is currently supported\", "
             "or a word on the attribute's form (\"The version attribute should be in the "
             "form 'x.y'\", \"Extra characters after the version number\"). MuJoCo ignores "
             "the attribute.",
     cause="urdfdom reads version 1.0 only (Debian 12's 3.0.1, every release from 3.0 to "
           "5.0, and 1.0.4, ROS Noetic's; the 2.x releases ignore the attribute): two whole "
           "numbers joined by one dot, each read as C's strtol reads it. So \"1.00\", "
           "\"01.0\" and \" 1.0\" pass, and \"1\", \"1.1\", \"2.0\", \"1.0.0\" and "
           "\"1.0 \" (a space after it) do not. No urdfdom release reads the proposed URDF 1.1; "
           "the attribute comes from a hand edit or a tool written for that proposal.",
     fix="Delete version=\"...\" from <robot>, or write version=\"1.0\".",
     blocks=PACKAGING)
rule("geometry-unknown", ERROR, "structure", "A <geometry> holds no shape URDF knows",
     symptom="MuJoCo stops with \"geometry specification not found\". check_urdf prints "
             "\"Unknown geometry type\" and accepts the file, keeping the link without that "
             "shape and those after it.",
     cause="A shape URDF does not have (a <cone>, a <plane>), a misspelt one, or an empty "
           "<geometry>: URDF knows <box>, <cylinder>, <sphere> and <mesh>.",
     fix="Use one of <box size>, <cylinder radius length>, <sphere radius> or <mesh "
         "filename>; for any other shape, export it as a mesh.")
rule("geometry-capsule", ERROR, "structure", "A <geometry> is a <capsule>, which ROS "
     "does not read",
     symptom="MuJoCo reads it as a capsule. ROS's URDF parser (urdfdom: check_urdf, RViz, "
             "robot_state_publisher) prints \"Unknown geometry type 'capsule'\" and accepts "
             "the file, keeping the link without the capsule and the shapes after it: RViz and "
             "robot_state_publisher work on a robot without it.",
     cause="Capsules belong to a proposed URDF 1.1 that no urdfdom release reads (up to "
           "5.0); MuJoCo's URDF import reads them. The SolidWorks exporter never writes them.",
     fix="For ROS 1, replace the capsule by a <cylinder> (and two <sphere> ends, in "
         "collisions of their own) or by a mesh.",
     blocks=PACKAGING)

rule("geom-name-duplicate", WARNING, "structure", "Two <visual> or <collision> elements share "
     "a name",
     symptom="MuJoCo prints \"Geom with duplicate name ... encountered in URDF, creating an "
             "unnamed geom\" and the second shape loses its name, so code that looks it up "
             "by name finds the first.",
     cause="A copied <visual> or <collision> block whose name attribute was not changed. "
           "The exporter writes no names there.",
     fix="Give each <visual> and <collision> a name of its own, or delete the name "
         "attributes.")

SHAPES = ("box", "cylinder", "sphere", "mesh")

# The numeric attributes of URDF elements, and how many numbers each one holds.
NUMERIC = {
    "origin": {"xyz": 3, "rpy": 3},
    "axis": {"xyz": 3},
    "limit": dict.fromkeys(("lower", "upper", "effort", "velocity"), 1),
    "safety_controller": dict.fromkeys(
        ("soft_lower_limit", "soft_upper_limit", "k_position", "k_velocity"), 1),
    "dynamics": {"damping": 1, "friction": 1},
    "calibration": {"rising": 1, "falling": 1},
    "mimic": {"multiplier": 1, "offset": 1},
    "mass": {"value": 1},
    "inertia": dict.fromkeys(("ixx", "ixy", "ixz", "iyy", "iyz", "izz"), 1),
    "box": {"size": 3},
    "cylinder": {"radius": 1, "length": 1},
    "sphere": {"radius": 1},
    "mesh": {"scale": 3},
    "color": {"rgba": 4},
}


def check(ctx) -> None:
    """Add a finding to ctx for every problem of this group."""
    links = ctx.robot.findall("link")
    joints = ctx.robot.findall("joint")
    _names(ctx, links, "link")
    _names(ctx, joints, "joint")
    if not links:
        ctx.add("urdf-no-links", f'robot "{ctx.robot.get("name", "")}" has no <link> elements',
                line=source_line(ctx.robot))
    _version(ctx)
    _joint_types(ctx, joints)
    edges = _joint_ends(ctx, joints, {link.get("name") for link in links})
    _tree(ctx, links, edges)
    _numbers(ctx)
    _geometries(ctx, links)
    _geom_names(ctx, links)


def _geom_names(ctx, links) -> None:
    first: dict[str, object] = {}
    for link in links:
        for element in link:
            name = element.get("name") if element.tag in ("visual", "collision") else None
            if not name:
                continue
            if name in first:
                ctx.add("geom-name-duplicate", f'the {element.tag} of {owner(element)} is named '
                        f'"{name}", as is the one at line {source_line(first[name])}',
                        line=source_line(element))
            else:
                first[name] = element


def _version(ctx) -> None:
    version = ctx.robot.get("version")
    if version is None:
        return
    said = urdfdom_version_error(version)
    if said is not None:
        ctx.add("urdf-version", f'<robot version="{_short(version)}">: urdfdom refuses it '
                f'("{said}")', line=source_line(ctx.robot, "version"))


def _geometries(ctx, links) -> None:
    for link in links:
        for element in link:
            if element.tag not in ("visual", "collision"):
                continue
            geometry = element.find("geometry")
            if geometry is None:
                continue
            shapes = [s for s in geometry if isinstance(s.tag, str)]
            known = [s for s in shapes if s.tag in SHAPES]
            if known:
                continue
            where = f"{element.tag} of {owner(geometry)}"
            if any(s.tag == "capsule" for s in shapes):
                capsule = next(s for s in shapes if s.tag == "capsule")
                ctx.add("geometry-capsule", f"the {where} is a <capsule>",
                        line=source_line(capsule, None))
            elif shapes:
                ctx.add("geometry-unknown", f"the {where} is a <{shapes[0].tag}>, not a "
                        "shape URDF knows", line=source_line(shapes[0], None),
                        fix=f"replace <{shapes[0].tag}> by a <box>, <cylinder>, <sphere> or "
                            "<mesh filename=...>")
            else:
                ctx.add("geometry-unknown", f"the {where} has an empty <geometry>",
                        line=source_line(geometry, None))

def _names(ctx, elements, kind: str) -> None:
    first: dict[str, object] = {}
    for element in elements:
        name = element.get("name")
        if name is None or not name.strip():
            ctx.add("name-missing", f"a <{kind}> has no name", line=source_line(element),
                    fix=f"add name=\"...\" to this <{kind}>, unique among the {kind}s")
        elif name in first:
            earlier = source_line(first[name])
            ctx.add("name-duplicate", f'{kind} "{name}" is defined again (first at line '
                    f"{earlier})", line=source_line(element),
                    fix=f'rename one of the two {kind}s called "{name}"')
        else:
            first[name] = element


def _joint_types(ctx, joints) -> None:
    for joint in joints:
        kind = joint.get("type")
        if kind in JOINT_TYPES:
            continue
        name = joint.get("name", "")
        if kind is None:
            message = f'joint "{name}" has no type'
        else:
            message = f'joint "{name}" has type "{_short(kind)}", which URDF does not know'
        guess = get_close_matches((kind or "").lower(), JOINT_TYPES, n=1)
        fix = (f'write type="{guess[0]}"' if guess else None)
        ctx.add("joint-type-unknown", message, line=source_line(joint, "type"), fix=fix)


def _joint_ends(ctx, joints, link_names: set) -> list[tuple[str, str, object]]:
    """Report joints whose parent or child is missing; return (parent, child, joint) edges
    for the joints whose ends both exist."""
    edges = []
    for joint in joints:
        ends = {}
        for end in ("parent", "child"):
            ends[end] = _joint_end(ctx, joint, end, link_names)
        if ends["parent"] is not None and ends["child"] is not None:
            edges.append((ends["parent"], ends["child"], joint))
    return edges


def _joint_end(ctx, joint, end: str, link_names: set) -> str | None:
    name = joint.get("name", "")
    rule_id = f"joint-{end}-missing"
    element = joint.find(end)
    link = None if element is None else element.get("link")
    if link is None or not link.strip():
        ctx.add(rule_id, f'joint "{name}" has no <{end} link="..."/>',
                line=source_line(joint),
                fix=f'add <{end} link="..."/> naming the {end} link of "{name}"')
        return None
    if link not in link_names:
        guess = _closest(link, link_names)
        fix = (f'did you mean "{guess}"? Write <{end} link="{guess}"/>' if guess
               else f"name an existing link, or add a <link name=\"{_short(link)}\">")
        ctx.add(rule_id, f'joint "{name}" names {end} link "{_short(link)}", which does not '
                "exist", line=source_line(element, "link"), fix=fix)
        return None
    return link


def _tree(ctx, links, edges) -> None:
    parent_joint: dict[str, object] = {}
    for parent, child, joint in edges:
        if child in parent_joint:
            first = parent_joint[child].get("name", "")
            ctx.add("link-two-parents", f'link "{child}" is the child of joint "{first}" and '
                    f'of joint "{joint.get("name", "")}"',
                    line=source_line(joint.find("child"), "link"),
                    fix=f'keep one parent joint for "{child}"; close the loop in MuJoCo with '
                        "an equality constraint")
        else:
            parent_joint[child] = joint
    _cycles(ctx, edges)
    # A link named as any joint's child is not a root, even when that joint is broken, and
    # neither is the link a misspelt child name was surely meant to be: those joints are
    # reported already.
    names = {link.get("name") for link in links}
    children = set()
    for joint in ctx.robot.findall("joint"):
        child = joint.find("child")
        if child is not None and child.get("link"):
            name = child.get("link")
            children.add(name if name in names else _closest(name, names))
    roots, seen = [], set()
    for link in links:
        name = link.get("name")
        if name and name.strip() and name not in children and name not in seen:
            roots.append(link)
        seen.add(name)
    if len(roots) > 1:
        listed = _listed([f'"{r.get("name")}"' for r in roots])
        ctx.add("roots-several", f"{len(roots)} links have no parent joint: {listed}",
                line=source_line(roots[1]),
                fix=f'join each of them to the tree with a joint; "{roots[0].get("name")}" '
                    "can stay the root")


def _closest(name: str, link_names: set) -> str | None:
    """The existing link name a misspelt one most likely means, if any is close.

    Not searched for in robots far larger than any export, to keep the check fast."""
    if len(link_names) > 500 or len(name) > 200:
        return None
    guess = get_close_matches(name, [n for n in link_names if n], n=1)
    return guess[0] if guess else None


def _cycles(ctx, edges) -> None:
    """Report one cycle in each knot of joints that loops back on itself, at its first
    joint in the file."""
    successors: dict[str, list[str]] = defaultdict(list)
    for parent, child, _ in edges:
        successors[parent].append(child)
    component = {}
    for number_, members in enumerate(_strong_components(list(successors), successors)):
        for link in members:
            component[link] = number_
    # Inside a knot every link has a parent in the same knot; walking up those parents
    # must come back to a link already met, and the walk from there on is a cycle.
    parent_of = {}
    for edge in edges:
        parent, child, _ = edge
        if component.get(parent) == component.get(child):
            parent_of.setdefault(child, edge)
    cycles, done = [], set()
    for start in sorted(parent_of):
        if component[start] in done:
            continue
        done.add(component[start])
        order: dict[str, int] = {}
        walk, link = [], start
        while link not in order:
            order[link] = len(walk)
            walk.append(parent_of[link])
            link = parent_of[link][0]
        cycles.append(walk[order[link]:][::-1])
    for cycle in sorted(cycles, key=lambda c: min(j.sourceline or 0 for _, _, j in c)):
        joints = [joint for _, _, joint in cycle]
        first = min(joints, key=lambda j: j.sourceline or 0)
        path = _listed([f'"{parent}"' for parent, _, _ in cycle], " -> ")
        ctx.add("kinematic-cycle", f"the joints {_listed(_quoted(joints))} form a cycle: "
                f'{path} -> "{cycle[0][0]}"', line=source_line(first),
                fix="remove one joint of the cycle, or swap parent and child where they "
                    "were reversed")


def _strong_components(nodes: list[str], successors) -> list[list[str]]:
    """Tarjan's strongly connected components, without recursion (a chain of links may be
    thousands deep)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found = []
    for root in nodes:
        if root in index:
            continue
        work = [(root, iter(successors.get(root, ())))]
        index[root] = low[root] = len(index)
        stack.append(root)
        on_stack.add(root)
        while work:
            node, children = work[-1]
            for child in children:
                if child not in index:
                    index[child] = low[child] = len(index)
                    stack.append(child)
                    on_stack.add(child)
                    work.append((child, iter(successors.get(child, ()))))
                    break
                if child in on_stack:
                    low[node] = min(low[node], index[child])
            else:
                work.pop()
                if work:
                    above = work[-1][0]
                    low[above] = min(low[above], low[node])
                if low[node] == index[node]:
                    members = []
                    while True:
                        member = stack.pop()
                        on_stack.discard(member)
                        members.append(member)
                        if member == node:
                            break
                    found.append(members)
    return found


def _numbers(ctx) -> None:
    for top in ctx.robot:
        if top.tag not in ("link", "joint", "material"):
            continue
        for element in top.iter():
            for attribute, size in NUMERIC.get(element.tag, {}).items():
                text = element.get(attribute)
                if text is None:
                    continue
                problem = _number_problem(text, size)
                if problem:
                    ctx.add("number-invalid", f'{owner(element)}: <{element.tag} {attribute}='
                            f'"{_short(text)}">: {problem}',
                            line=source_line(element, attribute),
                            fix=_number_fix(attribute, size))


def _number_problem(text: str, size: int) -> str | None:
    parts = text.split()
    bad = [p for p in parts if number(p) is None]
    if bad:
        return f'"{_short(bad[0])}" is not a number'
    if len(parts) != size:
        want = "one number" if size == 1 else f"{size} numbers"
        return f"expected {want}, found {len(parts)}"
    return None


def _number_fix(attribute: str, size: int) -> str:
    if size == 1:
        return f"write {attribute} as one decimal number in SI units, e.g. {attribute}=\"0.5\""
    example = " ".join(["0"] * size)
    return f'write {attribute} as {size} decimal numbers separated by spaces, e.g. "{example}"'


def _quoted(joints) -> list[str]:
    return [f'"{j.get("name", "")}"' for j in joints]


def _listed(items: list[str], separator: str = ", ", limit: int = 10) -> str:
    """Items joined for a message; a long list is cut after `limit` items."""
    if len(items) <= limit:
        return separator.join(items)
    return separator.join(items[:limit]) + f"{separator}... ({len(items) - limit} more)"


def _short(text: str, limit: int = 40) -> str:
    """A value as it may appear in a message: long or multi-line values are cut."""
    text = " ".join(text.split()) if "\n" in text else text
    return text if len(text) <= limit else text[:limit - 3] + "..."
