"""A raw export to practise `sw2sim check` on (the "Your own model" page).

It is Practice 3's arm as the exporter writes it when the joint dialog is left empty
and one part's mesh comes out empty: no hand edits (no world link, no transmissions),
the package named after the assembly file, and three faults its users often meet:

- both revolute joints keep the exporter's default limit, everything 0;
- meshes/end_arm_link.STL is the 80-byte header and nothing else;
- the package name has capital letters.

`python -m course.practices` writes it to examples/Arm_Assembly/.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

from ..exporter_format import Limit, Robot, write_package
from .practice_3 import design as arm

PACKAGE = "Arm_Assembly"
EMPTY_MESH = "end_arm_link"
# What the exporter writes for a part it could not mesh: the 80-byte header, no triangles.
EMPTY_STL = bytes(80)


def robot() -> Robot:
    """The arm's links and joints as exported, with the joint dialog's default limits."""
    original = arm.robot()
    joints = [replace(j, limit=Limit(0.0, 0.0, 0.0, 0.0), safety=None) for j in original.joints]
    return Robot(PACKAGE, original.links, joints)


def write(root: Path | None = None) -> list[Path]:
    from .. import ROOT
    folder = (root or ROOT / "examples") / PACKAGE
    written = write_package(robot(), folder, rviz=False)   # as exported: no urdf.rviz
    (folder / "meshes" / f"{EMPTY_MESH}.STL").write_bytes(EMPTY_STL)
    return written
