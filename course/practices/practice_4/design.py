"""Practice 4, linear movement: a bar held by two end plates, and a block that slides along it.

Every number on the Practice 4 drawings comes from here, in millimetres as on the
drawings. The block's origin is at its middle (on the bar's axis), and the joint's
limits, 0 to 2.69 m, are where that origin may go: at 0 the block is 10 mm from the
left end plate, at 2.69 m it is 10 mm from the right one.
"""

from pathlib import Path

from ... import ros_control_files
from ...exporter_format import Joint, Limit, Link, Robot, Safety, Transmission, write_package
from ...ros_control_files import ROS_CONTROL_DEPENDS, ros_control_nodes
from ...parts import Box, Cylinder, Dimension, Material, Part
from ..shared import mm

PACKAGE = "example_4"
ALUMINIUM = Material("Aluminium 6061-T6", 2700.0)


# --- the travel --------------------------------------------------------------------------------
TRAVEL = 2690                 # the joint's upper limit, in mm; the lower one is 0
CLEARANCE = 10                # between the block and an end plate at either limit

# --- the block (carriage) --------------------------------------------------------------------
BLOCK = (150, 100, 100)       # length along the bar (x), width (y), height (z)
BORE = 42                     # the hole the bar runs through: 1 mm clear all round

# --- the bar (rail) and its end plates -------------------------------------------------------
BAR_DIAMETER = 40
PLATE = (20, 120, 160)        # thickness (x), width (y), height (z); they stand on the floor
AXIS_HEIGHT = 100             # the bar's axis above the floor
BAR_LENGTH = TRAVEL + BLOCK[0] + 2 * CLEARANCE   # between the end plates' inner faces: 2860
OVERALL = BAR_LENGTH + 2 * PLATE[0]              # outside the end plates: 2900

# --- the joint -------------------------------------------------------------------------------
LOWER, UPPER = 0.0, TRAVEL / 1000               # m, of the block's origin
EFFORT = 200.0                # N: what a small toothed-belt axis pushes
VELOCITY = 1.0                # m/s: a belt axis's comfortable speed; the whole travel in 2.7 s
K_POSITION = 20.0             # 1/s: the largest speed towards a soft limit is k_position × distance
K_VELOCITY = 400.0            # N per m/s: the effort is at most k_velocity × (limit − speed), at every speed

COLOURS = {
    "base_link": (0.55, 0.57, 0.60, 1.0),
    "block_link": (0.85, 0.33, 0.10, 1.0),
}


def bar() -> Part:
    """The bar between two end plates. Origin: on the floor, below the bar's axis, at the
    outer face of the left end plate; x along the bar."""
    t, w, h = PLATE
    r, z = BAR_DIAMETER / 2, AXIS_HEIGHT
    return Part(
        name="base_link",
        title="Bar with end plates",
        material=ALUMINIUM,
        features=[
            Box(mm(t, w, h), mm(t / 2, 0, h / 2)),
            Box(mm(t, w, h), mm(OVERALL - t / 2, 0, h / 2)),
            Cylinder(mm(r), mm(BAR_LENGTH), "x", mm(OVERALL / 2, 0, z)),
        ],
        dimensions=[
            Dimension("front", mm(0, 0, 0), mm(OVERALL, 0, 0), "h", -0.06),
            Dimension("front", mm(t, 0, z), mm(OVERALL - t, 0, z), "h", 0.12, f"{BAR_LENGTH} between plates"),
            Dimension("front", mm(OVERALL, 0, 0), mm(OVERALL, 0, h), "v", 0.06),
            Dimension("front", mm(0, 0, 0), mm(0, 0, z), "v", -0.06),
            Dimension("top", mm(0, -w / 2, 0), mm(t, -w / 2, 0), "h", -0.05),
            Dimension("top", mm(OVERALL, -w / 2, 0), mm(OVERALL, w / 2, 0), "v", 0.06),
            Dimension("side", mm(0, -r, z), mm(0, r, z), "h", 0.09, f"Ø{BAR_DIAMETER}"),
        ],
    )


def block() -> Part:
    """The block, with a bore for the bar. Origin: its centre, on the bore's axis."""
    length, w, h = BLOCK
    return Part(
        name="block_link",
        title="Block",
        material=ALUMINIUM,
        features=[
            Box(mm(length, w, h)),
            Cylinder(mm(BORE / 2), mm(length + 2), "x", cut=True),
        ],
        dimensions=[
            Dimension("front", mm(-length / 2, 0, -h / 2), mm(length / 2, 0, -h / 2), "h", -0.02),
            Dimension("front", mm(length / 2, 0, -h / 2), mm(length / 2, 0, h / 2), "v", 0.02),
            Dimension("side", mm(0, -w / 2, -h / 2), mm(0, w / 2, -h / 2), "h", -0.02),
            Dimension("side", mm(0, -BORE / 2, 0), mm(0, BORE / 2, 0), "h", 0.07, f"Ø{BORE} THRU"),
        ],
    )


def joint_origin() -> tuple[float, float, float]:
    """Where the block's origin is at the lower limit, in the bar's frame, m."""
    return mm(PLATE[0] + CLEARANCE + BLOCK[0] / 2, 0, AXIS_HEIGHT)


def bar_end() -> float:
    """The block position (m) at which the block's back face passes the bar's far end."""
    return mm(OVERALL) - joint_origin()[0] + mm(BLOCK[0]) / 2


JOINT = "block_joint"
CONTROLLER = "block_controller"
# PID gains of the effort-based position controller (config/joint_names_example_4.yaml):
# N per m of error, N per m·s of integrated error, N per m/s; i_clamp in N; antiwindup
# holds the integrated error where the integral term reaches i_clamp
GAINS = {"p": 2000.0, "i": 500.0, "d": 200.0, "i_clamp": 50.0, "antiwindup": True}
STATE_RATE = 20               # Hz, joint_state_controller's publish rate


def controllers_yaml() -> str:
    return ros_control_files.controllers_yaml(
        robot(), {JOINT: (CONTROLLER, GAINS)}, STATE_RATE,
        "Added for Practice 4: the controllers, loaded by launch/gazebo.launch")


GAZEBO_NODES = ros_control_nodes(PACKAGE, [CONTROLLER])


def robot(upper: float = UPPER) -> Robot:
    """The assembly as exported, plus what Practice 4 adds by hand (colours, world link,
    ros_control). `upper` is there to make the typo of the limit page: robot(upper=26.9)."""
    joint = Joint(JOINT, "prismatic", "base_link", "block_link", xyz=joint_origin(), axis=(1, 0, 0),
                  limit=Limit(LOWER, upper, EFFORT, VELOCITY),
                  safety=Safety(LOWER, upper, K_POSITION, K_VELOCITY),
                  coordinate_system=f"Origin_{JOINT}", axis_name="Axis_bar")
    links = [Link("base_link", bar(), component="bar-1"),
             Link("block_link", block(), component="block-1")]
    r = Robot(PACKAGE, links, [joint])
    r.added_links = [Link("world", None)]
    r.added_joints = [Joint("world_joint", "fixed", "world", "base_link")]
    r.colours = dict(COLOURS)
    r.transmissions = [Transmission(JOINT)]
    r.gazebo_plugin = "libgazebo_ros_control.so"
    r.depends = list(ROS_CONTROL_DEPENDS)
    return r


def parts() -> list[Part]:
    """The distinct parts, one drawing each."""
    return [bar(), block()]


def write(root: Path | None = None) -> list[Path]:
    from ... import ROOT
    return write_package(robot(), (root or ROOT / "examples") / PACKAGE,
                         gazebo_nodes=GAZEBO_NODES, config=controllers_yaml())
