"""Repairs: the changes `sw2sim convert` makes to its own copy of a URDF when a problem has
exactly one right answer.

A rule that finds such a problem hands `Context.add` a `Repair`: a sentence saying what
convert does and what it assumes, and the edit, a change to one element of the URDF.
Nothing here touches the user's files: `repaired` applies the edits to a copy of the
package's tree and returns a new Package around it, which the stability run and convert
use. With `Options(strict=True)` no repair is offered, and every problem that stops the
simulation stops convert, as a package must be fixed at its source in the end.
"""

from __future__ import annotations

import copy
import dataclasses
from dataclasses import dataclass
from typing import Callable

import numpy as np
from lxml import etree

from ..package import Package


@dataclass(frozen=True)
class Options:
    """What the user chose for the repairs (`sw2sim convert`'s flags)."""

    strict: bool = False               # repair nothing (--strict)
    lock_default_limits: bool = False  # exporter-default limits: lock the joint (fixed)
    density: float | None = None       # kg/m^3: recompute wrong masses from the meshes
    # The user's own `sw2sim convert ...` words when convert runs the check: a fix that
    # suggests a flag adds it to these, so that -o and the other choices stay the user's.
    command: tuple[str, ...] | None = None


DEFAULT = Options()


Change = Callable[[etree._Element], None]


@dataclass(frozen=True)
class Repair:
    """What convert does about one finding: a sentence, and the edits that do it, each a
    change to one element of the URDF (none when only how convert reads the package
    changes)."""

    says: str                                          # what is done, and what is assumed
    edits: tuple[tuple[etree._Element, Change], ...] = ()
    unactuated: str | None = None    # a joint convert gives no actuator, whatever drives it


def repair(says: str, *edits: tuple[etree._Element, Change], unactuated: str | None = None
           ) -> Repair:
    return Repair(says, tuple(edits), unactuated)


def repaired(package: Package, repairs: list[Repair]) -> Package:
    """The package with every repair's edits made in a copy of its tree (the package
    itself when there is nothing to change)."""
    edits = [edit for r in repairs for edit in r.edits]
    if not edits:
        return package
    original = package.robot.getroottree()
    robot = copy.deepcopy(package.robot)
    tree = robot.getroottree()
    # Find every target before changing any: an edit may remove an element.
    targets = [(tree.xpath(original.getpath(element))[0], change) for element, change in edits]
    for element, change in targets:
        change(element)
    return dataclasses.replace(package, robot=robot)


# -- edits -------------------------------------------------------------------------------

def set_attribute(name: str, value: str) -> Callable[[etree._Element], None]:
    def change(element):
        element.set(name, value)
    return change


def remove_attributes(*names: str) -> Callable[[etree._Element], None]:
    def change(element):
        for name in names:
            element.attrib.pop(name, None)
    return change


def remove_element(element: etree._Element) -> None:
    parent = element.getparent()
    if parent is not None:
        parent.remove(element)


def make_fixed(joint: etree._Element) -> None:
    """Hold a joint at its zero position: a fixed joint, without limit, mimic or the
    transmissions that drove it."""
    joint.set("type", "fixed")
    for tag in ("limit", "mimic", "safety_controller", "axis", "dynamics"):
        for found in joint.findall(tag):
            joint.remove(found)
    _drop_transmissions(joint)


def make_unlimited(joint: etree._Element) -> None:
    """Let a joint move without limits and without the transmissions that drove it."""
    for tag in ("limit", "safety_controller"):
        for found in joint.findall(tag):
            joint.remove(found)
    _drop_transmissions(joint)


def _drop_transmissions(joint: etree._Element) -> None:
    robot, name = joint.getparent(), joint.get("name")
    if robot is None:
        return
    for transmission in robot.findall("transmission"):
        if any(j.get("name") == name for j in transmission.findall("joint")):
            robot.remove(transmission)


def write_inertial(mass: float, centre, tensor) -> Callable[[etree._Element], None]:
    """Replace a link's <inertial> (or give it one) with these values."""
    def change(link):
        for old in link.findall("inertial"):
            link.remove(old)
        inertial = etree.Element("inertial")
        etree.SubElement(inertial, "origin", xyz=" ".join(_number(v) for v in centre),
                         rpy="0 0 0")
        etree.SubElement(inertial, "mass", value=_number(mass))
        t = np.asarray(tensor, dtype=float)
        etree.SubElement(inertial, "inertia", ixx=_number(t[0, 0]), ixy=_number(t[0, 1]),
                         ixz=_number(t[0, 2]), iyy=_number(t[1, 1]), iyz=_number(t[1, 2]),
                         izz=_number(t[2, 2]))
        link.insert(0, inertial)
    return change


def write_tensor(tensor) -> Callable[[etree._Element], None]:
    """Set an <inertia> element's six terms from a symmetric 3 x 3 tensor."""
    t = np.asarray(tensor, dtype=float)

    def change(element):
        for term, (i, j) in zip(("ixx", "ixy", "ixz", "iyy", "iyz", "izz"),
                                ((0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2))):
            element.set(term, _number(t[i, j]))
    return change


def balanced(tensor: np.ndarray) -> np.ndarray:
    """The nearest tensor whose principal moments satisfy A + B >= C: the two smaller
    moments are raised together by the shortfall, the principal axes stay."""
    moments, axes = np.linalg.eigh(np.asarray(tensor, dtype=float))
    a, b, c = moments
    short = c - (a + b)
    if short > 0:
        # A margin of a few units in the last place, so that MuJoCo's own eigenvalues of
        # the tensor written out in 17 digits still satisfy the inequality.
        lift = short / 2 + 4 * np.finfo(float).eps * c
        moments = np.array([a + lift, b + lift, c])
    return (axes * moments) @ axes.T


def _number(value: float) -> str:
    return repr(float(value))
