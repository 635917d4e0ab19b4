"""Carry the hand edits of a saved URDF into the URDF a re-export wrote.

The exporter writes, for each link, one <inertial>, <visual> and <collision>, and for each
joint its <origin>, <parent>, <child>, <axis> and <limit>: the numbers come from the
assembly and from what was typed in the exporter, and the new file's are kept. What the
exporter never writes, and a re-export therefore drops, is carried over from the saved copy:

- every top-level element other than <link> and <joint>: <transmission>, <gazebo>, and
  anything else (a top-level <material>, <ros2_control>), in the saved order, at the end;
- a link the new URDF lacks that has no <inertial>, <visual> or <collision> of its own (a
  frame such as `world`), and the joints the new URDF lacks that join such a link;
- a joint's children beyond the exporter's numbers (<dynamics>, <calibration>,
  <safety_controller>, <mimic>), where the new joint has none of that kind;
- a link's visual <material> (its colour), where the saved one differs from the new one.

Everything else that differs is left as the re-export wrote it and named as not carried,
so that nothing changes silently. The carried elements are copied as whole lines of the
saved text, so they keep the layout they were written in; the rest of the file is the
exporter's own, untouched (`sw2sim.edits.spans`).
"""

from __future__ import annotations

from dataclasses import dataclass, field

from .. import xmlsafe
from .spans import Span, block, line_start, spans_by_element

BODY = ("inertial", "visual", "collision")
# A joint's children in the order the exporter writes them (and URDF's own documentation
# lists them); a carried child goes before the first later one the new joint has.
JOINT_ORDER = ("origin", "parent", "child", "axis", "limit", "calibration", "dynamics",
               "safety_controller", "mimic")
EXPORTER_NUMBERS = {"origin", "parent", "child", "axis", "limit"}


@dataclass
class Carried:
    """The new URDF's text with the hand edits put back, and what was and was not carried."""

    text: str
    carried: list[str] = field(default_factory=list)
    not_carried: list[str] = field(default_factory=list)


class _Document:
    """One URDF's text, its parsed tree and each element's span in the text."""

    def __init__(self, text: str, name: str):
        root = xmlsafe.parse_bytes(text.encode("utf-8"))
        if root is None or root.tag != "robot":
            raise ValueError(f"{name} is not a URDF (its top element is not <robot>)")
        self.text, self.root = text, root
        self.spans = spans_by_element(root, text)
        self.links = _named(root, "link")
        self.joints = _named(root, "joint")

    def span(self, element) -> Span:
        return self.spans[element]

    def lines(self, element) -> str:
        """The element's text as whole lines, ending with a newline."""
        start, end = block(self.text, self.span(element))
        piece = self.text[start:end]
        if start == self.span(element).start:   # not alone on its lines: give it its own
            piece = "  " * _depth(element) + piece + "\n"
        return piece if piece.endswith("\n") else piece + "\n"


def carry(saved_text: str, new_text: str) -> Carried:
    """The new URDF with what only the saved one has (see the module's docstring)."""
    saved, new = _Document(saved_text, "the saved URDF"), _Document(new_text, "the new URDF")
    result = Carried(new_text)
    edits: list[tuple[int, int, str]] = []   # (start, end, text): replace text[start:end]

    def insert(at: int, element) -> None:
        edits.append((at, at, saved.lines(element)))

    frames = [link for name, link in saved.links.items()
              if name not in new.links and not any(link.find(t) is not None for t in BODY)]
    frame_names = {link.get("name") for link in frames}
    first_link = next(iter(new.links.values()), None)
    top = line_start(new.text, new.span(first_link).start) if first_link is not None else \
        _before_close(new, new.root)
    for link in frames:
        insert(top, link)
        result.carried.append(f"link {link.get('name')}")
    for name, link in saved.links.items():
        if name not in new.links and name not in frame_names:
            result.not_carried.append(f"link {name} (the new export has no such link; the "
                                      "assembly changed)")
    for name, joint in saved.joints.items():
        if name in new.joints:
            _joint_children(saved, new, joint, new.joints[name], edits, result)
            continue
        ends = {_end(joint, "parent"), _end(joint, "child")}
        if ends & frame_names:
            anchor = new.links.get(_end(joint, "child"))
            anchor = anchor if anchor is not None else new.links.get(_end(joint, "parent"))
            at = block(new.text, new.span(anchor))[1] if anchor is not None else top
            insert(at, joint)
            result.carried.append(f"joint {name}")
        else:
            result.not_carried.append(f"joint {name} (the new export has no such joint; the "
                                      "assembly changed)")
    for name, link in saved.links.items():
        if name in new.links:
            _colour(saved, new, name, link, new.links[name], edits, result)
    end = _before_close(new, new.root)
    present = [_canonical(e) for e in new.root if isinstance(e.tag, str)
               and e.tag not in ("link", "joint")]
    for element in saved.root:
        if not isinstance(element.tag, str) or element.tag in ("link", "joint"):
            continue
        if _canonical(element) in present:
            continue
        insert(end, element)
        result.carried.append(_describe(element))
    result.text = _applied(new.text, edits, "\r\n" if "\r\n" in new.text else "\n")
    return result


def _joint_children(saved, new, old, joint, edits, result) -> None:
    name = joint.get("name")
    for child in old:
        if not isinstance(child.tag, str) or child.tag in EXPORTER_NUMBERS:
            continue
        there = joint.find(child.tag)
        if there is None:
            at = _slot(new, joint, child.tag)
            edits.append((at, at, saved.lines(child)))
            result.carried.append(f"<{child.tag}> of joint {name}")
        elif dict(there.attrib) != dict(child.attrib):
            result.not_carried.append(
                f"<{child.tag}> of joint {name} (the new export writes its own: "
                f"{_attributes(there)}; the saved one had {_attributes(child)})")


def _colour(saved, new, name, old, link, edits, result) -> None:
    was, now = old.find("visual/material"), link.find("visual/material")
    if was is None or (now is not None and _canonical(was) == _canonical(now)):
        return
    if now is None:
        visual = link.find("visual")
        if visual is None:
            result.not_carried.append(f"colour of link {name} (the new link has no <visual>)")
            return
        at = _before_close(new, visual)
        edits.append((at, at, saved.lines(was)))
    else:
        start, end = block(new.text, new.span(now))
        edits.append((start, end, saved.lines(was) if start != new.span(now).start
                      else saved.text[saved.span(was).start:saved.span(was).end]))
    colour = was.find("color")
    shown = f" (rgba {colour.get('rgba')})" if colour is not None else ""
    result.carried.append(f"colour of link {name}{shown}")


def _slot(new, joint, tag: str) -> int:
    """Where a child `tag` goes in the new joint: before the first later child it has."""
    rank = JOINT_ORDER.index(tag) if tag in JOINT_ORDER else len(JOINT_ORDER)
    for child in joint:
        if isinstance(child.tag, str) and child.tag in JOINT_ORDER and \
                JOINT_ORDER.index(child.tag) > rank:
            return line_start(new.text, new.span(child).start)
    return _before_close(new, joint)


def _before_close(doc, element) -> int:
    """The start of the line holding the element's closing tag."""
    span = doc.span(element)
    return line_start(doc.text, doc.text.rfind("</", span.start, span.end))


def _applied(text: str, edits: list[tuple[int, int, str]], newline: str) -> str:
    """The text with each edit made; edits at one place keep their order."""
    out, at = [], 0
    for start, end, piece in sorted(edits, key=lambda e: e[0]):
        if start < at:
            raise ValueError("two carried edits overlap")
        out += [text[at:start], piece.replace("\r\n", "\n").replace("\n", newline)]
        at = max(start, end)
    return "".join(out) + text[at:]


def _named(root, tag: str) -> dict:
    found = {}
    for element in root.findall(tag):
        found.setdefault(element.get("name", ""), element)
    return found


def _end(joint, which: str) -> str | None:
    found = joint.find(which)
    return None if found is None else found.get("link")


def _depth(element) -> int:
    return sum(1 for _ in element.iterancestors())


def _canonical(element) -> str:
    """An element's content without its layout: equal for the same edit written twice."""
    parts = [element.tag, *sorted(f"{k}={v}" for k, v in element.attrib.items()),
             (element.text or "").strip()]
    parts += [_canonical(child) for child in element if isinstance(child.tag, str)]
    return "(" + "|".join(parts) + ")"


def _attributes(element) -> str:
    return " ".join(f'{k}="{v}"' for k, v in element.attrib.items()) or "no attributes"


def _describe(element) -> str:
    """A carried top-level element, as a reader finds it in the file."""
    name = element.get("name") or element.get("reference")
    plugins = [p.get("filename") or p.get("name") for p in element.iter("plugin")]
    what = f"<{element.tag}"
    if name:
        what += f' {"name" if element.get("name") else "reference"}="{name}"'
    what += ">"
    return what + (f" (plugin {', '.join(plugins)})" if plugins else "")
