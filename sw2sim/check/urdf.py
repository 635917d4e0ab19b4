"""Reading a URDF's values the way the URDF parsers do, for every check.

`number`/`vector` read a URDF number (or give None, which `number-invalid` reports once),
`source_line` finds the line of an attribute (lxml reports where a start tag ends), and
`owner` names the link or joint an element belongs to.
"""

from __future__ import annotations

import math
import re
import weakref


# A decimal number as the URDF parsers read it: no "nan", "inf", "1_000" or non-ASCII digits.
_NUMBER = re.compile(r"[+-]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][+-]?[0-9]+)?")


def number(text: str | None) -> float | None:
    """The number an attribute holds, or None when it is absent or not a finite number."""
    if text is None or not _NUMBER.fullmatch(text.strip()):
        return None
    value = float(text)
    return value if math.isfinite(value) else None


def vector(text: str | None, size: int) -> tuple[float, ...] | None:
    """`size` numbers separated by spaces, or None when the text is anything else."""
    if text is None:
        return None
    values = [number(part) for part in text.split()]
    if len(values) != size or None in values:
        return None
    return tuple(values)


_source_lines: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def source_line(ctx, element, attribute: str | None = "name") -> int | None:
    """The URDF line holding `attribute` of `element`, else the line where its tag starts.

    lxml gives the line where a start tag ends; in the exporter's layout (one attribute
    per line) that is the last attribute's line, so the user would land on `type=` when
    the problem is the joint named two lines up.
    """
    end = element.sourceline
    if end is None:
        return None
    if ctx not in _source_lines:
        try:
            text = ctx.package.urdf.read_text(encoding="utf-8", errors="replace")
        except OSError:
            text = ""
        # lxml counts "\n" only; str.splitlines would also split at other characters.
        _source_lines[ctx] = text.split("\n")
    lines = _source_lines[ctx]
    start = re.compile(rf"<{re.escape(element.tag)}(\s|/|>|$)")
    wanted = (re.compile(rf"(^|\s){re.escape(attribute)}\s*=")
              if attribute and element.get(attribute) is not None else None)
    for number_ in range(min(end, len(lines)), 0, -1):
        line = lines[number_ - 1]
        if (wanted and wanted.search(line)) or start.search(line):
            return number_
    return end


def owner(element) -> str:
    """'joint "x"' or 'link "y"': the top-level element this one belongs to, for messages."""
    while element is not None and element.tag not in ("link", "joint", "material"):
        element = element.getparent()
    if element is None:
        return "the robot"
    return f'{element.tag} "{element.get("name", "")}"'
