"""Practice 2, friction and an angle: Practice 1's wheel on a base whose arms bend 45°.

The wheel is Practice 1's part itself, imported, not redrawn. The base is new: its four
arms leave the plate straight, then bend 45° in the plane of the plate, so each axle
points its own way and no two wheels share an axis line. Lengths in millimetres as on
the drawings, converted to metres once, in `mm`.
"""

import math
from pathlib import Path

from ...exporter_format import Dynamics, Joint, Link, Robot, write_package
from ...parts import Angle, Box, Cylinder, Dimension, Part
# The wheel, its numbers, the material and the stand are Practice 1's, used from there.
from ..practice_1 import design as practice_1
from ..practice_1.design import (ALUMINIUM, BORE_DIAMETER, COLOURS, STAND_HEIGHT, WHEEL_DIAMETER,
                                 WHEEL_WIDTH, mm, wheel)

PACKAGE = "example_2"

# --- the base ------------------------------------------------------------------------------
PLATE = (300, 100, 20)        # length (x), width (y), thickness (z), as in Practice 1
ARM_WIDTH = 40
ARM_X = 130                   # centre line of the straight part of each arm, front (+x) and rear (-x)
STRAIGHT = 30                 # outer edge of an arm, from the plate to the bend
BEND = 45                     # degrees the arm turns, in the plane of the plate, away from the middle
BENT = 90                     # outer edge of an arm, from the bend to the arm's end
AXLE_DIAMETER = BORE_DIAMETER  # the wheel's bore fits it
AXLE_LENGTH = 50              # from the arm's end outwards, along the bent arm
WHEEL_GAP = 10                # between an arm's end and its wheel

# --- what Practice 2 adds by hand after the export ------------------------------------------
FRICTION = 0.7                # N·m, Coulomb friction in the joints of the FRICTION_JOINTS
FRICTION_JOINTS = ("front_left_joint", "front_right_joint")

SIDES = {  # link name: (sign of x, sign of y)
    "front_left_wheel": (1, 1),
    "front_right_wheel": (1, -1),
    "rear_left_wheel": (-1, 1),
    "rear_right_wheel": (-1, -1),
}


def joint_name(wheel_link: str) -> str:
    return wheel_link.replace("_wheel", "_joint")


def _arm(sx: int, sy: int):
    """One arm's key points (mm, in the base frame) and directions.

    Returns (outer bend corner, u: unit vector along the bent arm, towards its end,
    n: unit vector across it, towards the inside of the bend, centre of the arm's end face).
    """
    a = math.radians(BEND)
    u = (sx * math.sin(a), sy * math.cos(a))
    n = (sx * math.cos(a), -sy * math.sin(a))
    corner = (sx * (ARM_X - ARM_WIDTH / 2), sy * (PLATE[1] / 2 + STRAIGHT))
    end = (corner[0] + BENT * u[0] + ARM_WIDTH / 2 * n[0], corner[1] + BENT * u[1] + ARM_WIDTH / 2 * n[1])
    return corner, u, n, end


def axle_yaw(sx: int, sy: int) -> float:
    """Degrees about z that turn the y axis onto the axle, keeping it towards the base's left (+y).

    The same choice as Practice 1, where every wheel axis is +y: a positive torque on every
    wheel then turns each one the same way.
    """
    return -sx * sy * BEND


def wheel_centre(link: str) -> tuple[float, float, float]:
    """Centre of a wheel (mm, base frame): on its axle, WHEEL_GAP beyond the arm's end."""
    _, u, _, end = _arm(*SIDES[link])
    along = WHEEL_GAP + WHEEL_WIDTH / 2
    return (end[0] + along * u[0], end[1] + along * u[1], 0.0)


def axle_direction(link: str) -> tuple[float, float, float]:
    """Unit vector of a wheel's joint axis in the base frame (the axle, towards +y)."""
    yaw = math.radians(axle_yaw(*SIDES[link]))
    return (-math.sin(yaw), math.cos(yaw), 0.0)


def base() -> Part:
    lx, ly, lz = PLATE
    w = ARM_WIDTH
    features = [Box(mm(lx, ly, lz))]
    for sx, sy in SIDES.values():
        corner, u, n, end = _arm(sx, sy)
        yaw = axle_yaw(sx, sy)
        features.append(Box(mm(w, STRAIGHT, lz), mm(sx * ARM_X, sy * (ly / 2 + STRAIGHT / 2), 0)))
        # The bent part starts at the outer bend corner and overlaps the straight part: a mitred bend.
        c = (corner[0] + BENT / 2 * u[0] + w / 2 * n[0], corner[1] + BENT / 2 * u[1] + w / 2 * n[1])
        features.append(Box(mm(w, BENT, lz), mm(*c, 0), yaw=yaw))
        a = (end[0] + AXLE_LENGTH / 2 * u[0], end[1] + AXLE_LENGTH / 2 * u[1])
        features.append(Cylinder(mm(AXLE_DIAMETER / 2), mm(AXLE_LENGTH), "y", mm(*a, 0), yaw=yaw))
    return Part(name="base_link", title="Base", material=ALUMINIUM, features=features,
                dimensions=_base_dimensions())


def _base_dimensions() -> list:
    """The base is symmetric: each arm's numbers are shown once, on whichever arm has room."""
    lx, ly, lz = PLATE
    w, r = ARM_WIDTH, AXLE_DIAMETER / 2

    def point(p, along=0.0, across=0.0, u=(0, 0), n=(0, 0)):
        return mm(p[0] + along * u[0] + across * n[0], p[1] + along * u[1] + across * n[1], 0)

    corner, u, n, end = _arm(1, 1)        # front left: the bend and the arm's width
    angle = Angle("top", point(corner), point(corner, 30, u=(0, 1)), point(corner, BENT, u=u), 0.07)
    width = Dimension("top", point(end, across=-w / 2, u=u, n=n), point(end, across=w / 2, u=u, n=n), "a",
                      (AXLE_LENGTH + 25) / 1000)
    corner, u, n, end = _arm(-1, 1)       # rear left: the bent edge and the axle
    bent = Dimension("top", point(corner), point(corner, BENT, u=u), "a", -0.03)
    axle = Dimension("top", point(end, across=-r, u=u, n=n), point(end, AXLE_LENGTH, -r, u, n), "a", -0.04)
    _, u, n, end = _arm(-1, -1)           # rear right: the axle's diameter
    dia = Dimension("top", point(end, 30, r, u, n), point(end, 30, -r, u, n), "a", -0.035, f"Ø{AXLE_DIAMETER}")
    corner, *_ = _arm(1, -1)              # front right: the straight part of an arm
    gap = ly / 2 + STRAIGHT / 2           # across the notch between two arms, arrows on its sides
    return [
        Dimension("top", mm(-ARM_X + w / 2, gap, 0), mm(ARM_X - w / 2, gap, 0), "h", 1e-6),
        Dimension("top", mm(ARM_X - w / 2, -gap, 0), mm(ARM_X + w / 2, -gap, 0), "h", 1e-6),
        Dimension("top", mm(-lx / 2, -ly / 2, 0), mm(-lx / 2, ly / 2, 0), "v", -0.12),
        Dimension("top", mm(*corner, 0), mm(corner[0], -ly / 2, 0), "v", -0.02),
        angle, width, bent, axle, dia,
        Dimension("front", mm(-lx / 2, 0, -lz / 2), mm(-lx / 2, 0, lz / 2), "v", -0.04),
        Dimension("front", mm(-lx / 2, 0, -lz / 2), mm(lx / 2, 0, -lz / 2), "h", -0.02),
    ]


# Added to launch/gazebo.launch: Practice 1's pulse node, started from its own package.
GAZEBO_NODES = practice_1.GAZEBO_NODES


def robot() -> Robot:
    """The assembly as exported, plus what Practice 2 adds by hand: colours, the world link,
    friction in two joints and the dependency on Practice 1's package."""
    wheel_part = wheel()
    links = [Link("base_link", base(), component="base-1")]
    joints = []
    for i, name in enumerate(SIDES, start=1):
        links.append(Link(name, wheel_part, component=f"wheel-{i}"))
        joint = joint_name(name)
        joints.append(Joint(joint, "continuous", "base_link", name, xyz=mm(*wheel_centre(name)),
                            rpy=(0.0, 0.0, math.radians(axle_yaw(*SIDES[name]))), axis=(0, 1, 0),
                            coordinate_system=f"Origin_{joint}", axis_name=f"Axis_{name[:-len('_wheel')]}"))
    r = Robot(PACKAGE, links, joints)
    r.added_links = [Link("world", None)]
    r.added_joints = [Joint("world_joint", "fixed", "world", "base_link", xyz=(0, 0, mm(STAND_HEIGHT)))]
    r.colours = {lk.name: COLOURS["base_link"] if lk.name == "base_link" else COLOURS["wheel"] for lk in links}
    r.dynamics = {j: Dynamics(damping=0.0, friction=FRICTION) for j in FRICTION_JOINTS}
    r.depends = ["example_1"]  # gazebo.launch starts Practice 1's node from its own package
    return r


def parts() -> list[Part]:
    """The part this practice draws; the wheel's drawing is Practice 1's."""
    return [base()]


def write(root: Path | None = None) -> list[Path]:
    from ... import ROOT
    return write_package(robot(), (root or ROOT / "examples") / PACKAGE, gazebo_nodes=GAZEBO_NODES)
