"""Reading a URDF's values the way the URDF parsers do, for every check.

`number`/`vector` read a URDF number (or give None, which `number-invalid` reports once),
`owner` names the link or joint an element belongs to, and `urdfdom_version_error` says
what urdfdom says of a <robot version>. (The line of an attribute is
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


# urdfdom's URDFVersion reads each part with C's strtol: white space, a sign, digits.
_STRTOL = re.compile(r"[ \t\n\v\f\r]*[+-]?[0-9]+")
_LONG = 2 ** 63


def urdfdom_version_error(text: str) -> str | None:
    """urdfdom's message about <robot version=text>, or None when it reads version 1.0.

    As urdf_export_helpers::URDFVersion does it (urdfdom 1.0.4, 3.0 to 5.0): the text is
    split at dots, an empty last part dropped; there must be two parts, each a base-10
    strtol number (leading white space and a sign allowed, nothing after the digits, not
    negative) kept as a 32-bit unsigned number; and only (1, 0) is accepted."""
    parts = text.split(".")
    if parts[-1] == "":
        parts.pop()
    if len(parts) != 2:
        return "The version attribute should be in the form 'x.y'"
    numbers = []
    for part in parts:
        if part == "":
            return "One of the fields of the version attribute is blank"
        read = _STRTOL.match(part)
        if read is None:
            return "Version attribute is not an integer"
        if read.end() != len(part):
            return "Extra characters after the version number"
        value = max(min(int(read.group().lstrip(" \t\n\v\f\r")), _LONG - 1), -_LONG)
        if value < 0:
            return "Version number must be positive"
        numbers.append(value % 2 ** 32)
    if numbers != [1, 0]:
        return "Invalid 'version' specified; only version 1.0 is currently supported"
    return None
