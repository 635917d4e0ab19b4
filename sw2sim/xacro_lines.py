"""Lines of a .xacro for what is found in the URDF it expands to.

xacro's output carries no line numbers, so a finding in it is mapped back by structure:
the expanded URDF is laid out one attribute per line (`laid_out`), so that a finding's line
names one element and one attribute there, and `xacro_line` looks for the same element in
the .xacro as written: a <link>, <joint> or other top-level element whose name is written
there literally and once, then the same child, by tag and place, down to the element. An
element a macro writes (a name built from `${...}`, a tag of xacro's own) has no place in
the .xacro to point at; the finding then names the line of the expanded URDF and says so.
"""

from __future__ import annotations

import re
from pathlib import Path

from lxml import etree

from . import xmlsafe

XACRO = "http://www.ros.org/wiki/xacro"
_ATTRIBUTE = re.compile(r"^\s*([\w:.-]+)\s*=")


def escape(text: str) -> str:
    return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")


def quoteattr(value: str) -> str:
    """A quoted attribute value that reads back as `value` (newlines and tabs included)."""
    return '"' + escape(value).replace('"', "&quot;").replace("\n", "&#10;") \
        .replace("\r", "&#13;").replace("\t", "&#9;") + '"'


def laid_out(root: etree._Element) -> bytes:
    """The document as XML text with every attribute on a line of its own, as the exporter
    writes URDFs (the same elements, attributes and text)."""
    out: list[str] = ['<?xml version="1.0" encoding="utf-8"?>\n']

    def write(element, depth: int) -> None:
        pad = "  " * depth
        if not isinstance(element.tag, str):   # a comment or a processing instruction
            out.append(pad + etree.tostring(element, encoding="unicode", with_tail=False) + "\n")
            return
        out.append(f"{pad}<{element.tag}")
        for name, value in element.attrib.items():
            out.append(f"\n{pad}    {name}={quoteattr(value)}")
        children = list(element)
        text = (element.text or "").strip()
        if not children and not text:
            out.append(" />\n")
            return
        out.append(">" + escape(text) + ("\n" if children else ""))
        for child in children:
            write(child, depth + 1)
        out.append((pad if children else "") + f"</{element.tag}>\n")

    write(root, 0)
    return "".join(out).encode("utf-8")


def element_at(robot: etree._Element, line: int) -> tuple[etree._Element, str | None] | None:
    """The element of the laid-out URDF whose start tag holds `line`, and the attribute
    written on it (None on the tag's own line)."""
    lines = xmlsafe.source_lines(robot)
    for element in robot.iter(etree.Element):
        end = element.sourceline
        if end is None or end < line:
            continue
        start = xmlsafe.source_line(element, None)
        if start is not None and start <= line:
            found = _ATTRIBUTE.match(lines[line - 1]) if 0 < line <= len(lines) else None
            name = found.group(1) if found and element.get(found.group(1)) is not None else None
            return element, name
    return None


def xacro_line(xacro: etree._Element, element: etree._Element, attribute: str | None
               ) -> int | None:
    """The line of the .xacro (parsed as `xacro`) that writes `element` of the expanded URDF
    (its `attribute`, or its tag); None when a macro writes it."""
    path = []
    while element.getparent() is not None:
        path.append(element)
        element = element.getparent()
    if not path:
        return None
    top = path.pop()
    name = top.get("name")
    if not name or "${" in name:
        return None
    # at the top of the robot, or inside <xacro:if> / <xacro:unless> there
    found = [e for e in xacro.iter(top.tag) if e.get("name") == name
             and all(a.tag in (f"{{{XACRO}}}if", f"{{{XACRO}}}unless")
                     for a in list(e.iterancestors())[:-1])]
    if len(found) != 1:
        return None
    here, there = top, found[0]
    for step in reversed(path):
        ours = [c for c in here if c.tag == step.tag]
        theirs = [c for c in there if c.tag == step.tag]
        if len(ours) != len(theirs) or any(_is_xacro(c) for c in there):
            return None
        here, there = step, theirs[ours.index(step)]
    if attribute and there.get(attribute) is None:
        attribute = None
    return xmlsafe.source_line(there, attribute)


def _is_xacro(element) -> bool:
    return isinstance(element.tag, str) and element.tag.startswith(f"{{{XACRO}}}")


def parsed_xacro(path: Path) -> etree._Element | None:
    """The .xacro as written, or None when it cannot be read again."""
    try:
        return xmlsafe.parse_file(path)
    except (OSError, ValueError, etree.XMLSyntaxError):
        return None
