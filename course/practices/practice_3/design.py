"""Practice 3, a 2-axis arm: a base with a centre pivot, a middle arm and an end arm with fixed fingers.

Every number on the Practice 3 drawings comes from here, in millimetres as on the
drawings. Both arms measure the same from axis to end (ARM_LENGTH), which is what
makes the arm's end sit at 67.5° from the centre pivot when both joints are at +45°.
"""

import math
from pathlib import Path

from ... import ros_control_files
from ...exporter_format import Joint, Limit, Link, Robot, Safety, Transmission, write_package
from ...ros_control_files import ROS_CONTROL_DEPENDS, ros_control_nodes
from ...parts import Box, Cylinder, Dimension, Material, Part
from ..shared import mm

PACKAGE = "example_3"
ALUMINIUM = Material("Aluminium 6061-T6", 2700.0)


# --- the arm's geometry -----------------------------------------------------------------------
ARM_LENGTH = 225              # centre pivot to elbow axis, and elbow axis to the fingertips
BAR_WIDTH = 50                # both arms, also the diameter of their rounded ends
BAR_THICKNESS = 20

# --- the base --------------------------------------------------------------------------------
FOOT = (200, 200, 20)         # square foot plate on the floor
COLUMN_DIAMETER = 60
PIVOT_HEIGHT = 150            # top of the column: the middle arm turns on it

# --- the end arm: a bar, a palm and two fixed fingers --------------------------------------
PALM_X = 150                  # where the palm starts, from the elbow axis
PALM = (20, 80)               # length (x), width (y)
FINGER_WIDTH = 12
FINGER_GAP = 44               # between the fingers' inner faces

# --- joints -----------------------------------------------------------------------------------
LIMIT_DEGREES = 45.0
LIMIT = round(math.radians(LIMIT_DEGREES), 4)   # 0.7854 rad, as typed into the exporter
VELOCITY = 2.0                # rad/s
EFFORT = 1000.0               # N·m
# Soft limits (the exporter's "Safety" fields): the same as the hard limits; the gains tell
# ros_control how hard to hold a joint inside them. k_velocity bounds the effort at every
# speed, at most k_velocity × (velocity limit − speed) (N·m per rad/s; joint_limits_interface's
# EffortJointSoftLimitsHandle): 20 N·m at rest for the middle joint.
K_POSITION = 20.0             # 1/s: the largest speed towards a limit is k_position × distance to it
K_VELOCITY = {"middle_arm_joint": 10.0, "end_arm_joint": 2.0}

COLOURS = {
    "base_link": (0.25, 0.25, 0.28, 1.0),
    "middle_arm_link": (0.20, 0.45, 0.75, 1.0),
    "end_arm_link": (0.93, 0.55, 0.13, 1.0),
}


def base() -> Part:
    fx, fy, fz = FOOT
    column = PIVOT_HEIGHT - fz
    r = COLUMN_DIAMETER / 2
    return Part(
        name="base_link",
        title="Base",
        material=ALUMINIUM,
        features=[
            Box(mm(fx, fy, fz), mm(0, 0, fz / 2)),
            Cylinder(mm(r), mm(column), "z", mm(0, 0, fz + column / 2)),
        ],
        dimensions=[
            Dimension("front", mm(-fx / 2, 0, 0), mm(fx / 2, 0, 0), "h", -0.04),
            Dimension("front", mm(-r, 0, PIVOT_HEIGHT), mm(r, 0, PIVOT_HEIGHT), "h", 0.04, f"Ø{COLUMN_DIAMETER}"),
            Dimension("front", mm(fx / 2, 0, 0), mm(fx / 2, 0, fz), "v", 0.03),
            Dimension("front", mm(r, 0, fz), mm(r, 0, PIVOT_HEIGHT), "v", 0.03),
            Dimension("front", mm(-fx / 2, 0, 0), mm(-fx / 2, 0, PIVOT_HEIGHT), "v", -0.05),
            Dimension("top", mm(fx / 2, -fy / 2, 0), mm(fx / 2, fy / 2, 0), "v", 0.04),
        ],
    )


def _rounded_bar(length: float) -> list:
    """A bar from x = 0 to x = length with a round end (Ø BAR_WIDTH) centred on x = 0."""
    t, w = BAR_THICKNESS, BAR_WIDTH
    return [
        Box(mm(length, w, t), mm(length / 2, 0, t / 2)),
        Cylinder(mm(w / 2), mm(t), "z", mm(0, 0, t / 2)),
    ]


def _round_end(centre, degrees: float) -> Dimension:
    """The radius of a bar's round end, from its centre out to the arc at `degrees` (top view)."""
    r = mm(BAR_WIDTH / 2)
    a = math.radians(degrees)
    x, y, z = centre
    return Dimension("top", centre, (x + r * math.cos(a), y + r * math.sin(a), z), "a", 0.0, f"R{BAR_WIDTH // 2}")


def middle_arm() -> Part:
    t, w, L = BAR_THICKNESS, BAR_WIDTH, ARM_LENGTH
    return Part(
        name="middle_arm_link",
        title="Middle arm",
        material=ALUMINIUM,
        features=[*_rounded_bar(L), Cylinder(mm(w / 2), mm(t), "z", mm(L, 0, t / 2))],
        dimensions=[
            Dimension("top", mm(0, 0, t), mm(L, 0, t), "h", 0.05, f"{L} (axis to axis)"),
            Dimension("top", mm(L + w / 2, -w / 2, t), mm(L + w / 2, w / 2, t), "v", 0.03),
            Dimension("front", mm(L + w / 2, 0, 0), mm(L + w / 2, 0, t), "v", 0.03),
            _round_end(mm(L, 0, t), 45),
        ],
    )


def end_arm() -> Part:
    t, L, w = BAR_THICKNESS, ARM_LENGTH, BAR_WIDTH
    px, (pl, pw) = PALM_X, PALM
    finger_len = L - (px + pl)
    finger_y = FINGER_GAP / 2 + FINGER_WIDTH / 2
    fingers = [Box(mm(finger_len, FINGER_WIDTH, t), mm(px + pl + finger_len / 2, s * finger_y, t / 2))
               for s in (1, -1)]
    return Part(
        name="end_arm_link",
        title="End arm with fixed fingers",
        material=ALUMINIUM,
        features=[*_rounded_bar(px), Box(mm(pl, pw, t), mm(px + pl / 2, 0, t / 2)), *fingers],
        dimensions=[
            Dimension("top", mm(0, -pw / 2, t), mm(L, -pw / 2, t), "h", -0.05, f"{L} (axis to fingertips)"),
            Dimension("top", mm(0, pw / 2, t), mm(px, pw / 2, t), "h", 0.04),
            Dimension("top", mm(px, pw / 2, t), mm(px + pl, pw / 2, t), "h", 0.04),
            Dimension("top", mm(px + pl, finger_y + FINGER_WIDTH / 2, t), mm(L, finger_y + FINGER_WIDTH / 2, t),
                      "h", 0.04 + (pw / 2 - finger_y - FINGER_WIDTH / 2) / 1000),
            Dimension("top", mm(px / 2, -w / 2, t), mm(px / 2, w / 2, t), "v", 1e-6),
            _round_end(mm(0, 0, t), 135),
            Dimension("top", mm(L, -pw / 2, t), mm(L, pw / 2, t), "v", 0.04),
            Dimension("top", mm(L, -FINGER_GAP / 2, t), mm(L, FINGER_GAP / 2, t), "v", 0.02),
            Dimension("top", mm(L, FINGER_GAP / 2, t), mm(L, FINGER_GAP / 2 + FINGER_WIDTH, t), "v", 0.02),
            Dimension("front", mm(L, 0, 0), mm(L, 0, t), "v", 0.03),
        ],
    )


def tool_tip() -> tuple[float, float, float]:
    """The arm's end in the end arm's frame, m: between the fingertips, at mid-thickness."""
    return mm(ARM_LENGTH, 0, BAR_THICKNESS / 2)


JOINTS = ["middle_arm_joint", "end_arm_joint"]
CONTROLLERS = {"middle_arm_joint": "middle_arm_controller", "end_arm_joint": "end_arm_controller"}
# PID gains of the effort-based position controllers (config/joint_names_example_3.yaml).
# The horizontal arm carries no steady load, so the integral term gets little room: at
# i_clamp / p = 0.005 rad it can hold neither joint further than that from its set point.
GAINS = {
    "middle_arm_joint": {"p": 100.0, "i": 10.0, "d": 10.0, "i_clamp": 0.5, "antiwindup": True},
    "end_arm_joint": {"p": 40.0, "i": 4.0, "d": 2.0, "i_clamp": 0.2, "antiwindup": True},
}
STATE_RATE = 20               # Hz, joint_state_controller's publish rate


def controllers_yaml() -> str:
    return ros_control_files.controllers_yaml(
        robot(), {j: (CONTROLLERS[j], GAINS[j]) for j in JOINTS}, STATE_RATE,
        "Added for Practice 3: the controllers, loaded by launch/gazebo.launch")


GAZEBO_NODES = ros_control_nodes(PACKAGE, CONTROLLERS.values()) + f"""  <node
    name="random_setpoints"
    pkg="{PACKAGE}"
    type="random_setpoints_node.py"
    output="screen">
    <remap
      from="mid_arm"
      to="/{PACKAGE}/middle_arm_controller/command" />
    <remap
      from="end_arm"
      to="/{PACKAGE}/end_arm_controller/command" />
  </node>
"""


def robot() -> Robot:
    """The assembly as exported, plus what Practice 3 adds by hand (colours, world link, ros_control)."""
    def joint(name, parent, child, xyz, axis_name):
        return Joint(name, "revolute", parent, child, xyz=xyz, axis=(0, 0, 1),
                     limit=Limit(-LIMIT, LIMIT, EFFORT, VELOCITY),
                     safety=Safety(-LIMIT, LIMIT, K_POSITION, K_VELOCITY[name]),
                     coordinate_system=f"Origin_{name}", axis_name=axis_name)

    links = [Link("base_link", base(), component="base-1"),
             Link("middle_arm_link", middle_arm(), component="middle_arm-1"),
             Link("end_arm_link", end_arm(), component="end_arm-1")]
    joints = [joint("middle_arm_joint", "base_link", "middle_arm_link", mm(0, 0, PIVOT_HEIGHT), "Axis_pivot"),
              joint("end_arm_joint", "middle_arm_link", "end_arm_link", mm(ARM_LENGTH, 0, BAR_THICKNESS),
                    "Axis_elbow")]
    r = Robot(PACKAGE, links, joints)
    r.added_links = [Link("world", None)]
    r.added_joints = [Joint("world_joint", "fixed", "world", "base_link")]
    r.colours = {name: rgba for name, rgba in COLOURS.items()}
    r.transmissions = [Transmission(j) for j in JOINTS]
    r.gazebo_plugin = "libgazebo_ros_control.so"
    r.depends = list(ROS_CONTROL_DEPENDS)
    return r


def parts() -> list[Part]:
    """The distinct parts, one drawing each."""
    return [base(), middle_arm(), end_arm()]


def write(root: Path | None = None) -> list[Path]:
    from ... import ROOT
    return write_package(robot(), (root or ROOT / "examples") / PACKAGE,
                         gazebo_nodes=GAZEBO_NODES, config=controllers_yaml())
