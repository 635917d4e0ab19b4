"""Package names that ROS 2 accepts, and the legal name made from one it refuses.

ROS 2 follows REP 144: a package name starts with a lower-case letter and holds only
lower-case letters, digits and single underscores. catkin_pkg, which colcon uses to read
package.xml, still accepts capitals and dashes with a warning (its pattern is
`^[a-zA-Z0-9][a-zA-Z0-9_-]*$`), but CMake targets, Python modules and `ros2 launch` do not
all cope with them, so the ported package always gets a REP 144 name. Exporter packages
are named after the assembly: `Arm_Assembly`, `robot.SLDASM`, `2wd_car`.
"""

from __future__ import annotations

import re

LEGAL = re.compile(r"^[a-z][a-z0-9]*(_[a-z0-9]+)*$")
LEADING_LETTER = "r"   # put before a name that starts with a digit: 2wd_car -> r2wd_car


def is_legal(name: str) -> bool:
    """Whether `name` is a package name ROS 2 accepts as it is (REP 144)."""
    return bool(LEGAL.match(name))


def legal_name(name: str) -> str:
    """`name` made legal: lower case, every run of other characters one `_`, no `_` at
    either end, and a letter before a leading digit. An empty result is "robot"."""
    text = re.sub(r"[^a-z0-9]+", "_", name.lower()).strip("_")
    if not text:
        return "robot"
    if text[0].isdigit():
        text = LEADING_LETTER + text
    return text


def why_illegal(name: str) -> str:
    """What is wrong with a name `is_legal` refuses, in a few words."""
    reasons = []
    if name != name.lower():
        reasons.append("capitals")
    if re.search(r"[^A-Za-z0-9_]", name):
        odd = sorted({c for c in name if not (c.isascii() and (c.isalnum() or c == "_"))})
        reasons.append("the character(s) " + " ".join(repr(c) for c in odd))
    if name[:1].isdigit():
        reasons.append("a leading digit")
    if "__" in name or name.startswith("_") or name.endswith("_"):
        reasons.append("a doubled, leading or trailing underscore")
    return ", ".join(reasons) or "an empty name"
