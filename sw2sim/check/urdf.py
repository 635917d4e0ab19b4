"""Reading a URDF's values the way the URDF parsers do, for every check.

`number`/`vector` read a URDF number (or give None, which `number-invalid` reports once),
and `owner` names the link or joint an element belongs to. (The line of an attribute is
`sw2sim.xmlsafe.source_line`'s to find: lxml reports where a start tag ends.)
"""

from __future__ import annotations

import math
import re


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


def owner(element) -> str:
    """'joint "x"' or 'link "y"': the top-level element this one belongs to, for messages."""
    while element is not None and element.tag not in ("link", "joint", "material"):
        element = element.getparent()
    if element is None:
        return "the robot"
    return f'{element.tag} "{element.get("name", "")}"'
