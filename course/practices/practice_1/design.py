"""Practice 1, the simple wheel: a base with four straight arms and four wheels on two axles.

Every number on the Practice 1 drawings comes from here. Lengths in millimetres as on
the drawings, converted to metres once, in `mm`.
"""

from pathlib import Path

from ...exporter_format import Joint, Link, Robot, write_package
from ...parts import Box, Cylinder, Dimension, Material, Part
from ..shared import holed_wheel, mm

PACKAGE = "example_1"
ALUMINIUM = Material("Aluminium 6061-T6", 2700.0)


# --- the wheel -----------------------------------------------------------------------------
WHEEL_DIAMETER = 200
WHEEL_WIDTH = 40
BORE_DIAMETER = 20            # the axle fits through it
HOLE_DIAMETER = 30            # four lightening holes show the wheel turning
HOLE_PITCH_DIAMETER = 110

# --- the base ------------------------------------------------------------------------------
PLATE = (300, 100, 20)        # length (x), width (y), thickness (z)
ARM = (40, 100, 20)           # each arm: width (x), reach (y), thickness (z)
AXLE_X = 130                  # the two axles, front (+x) and rear (-x) of the centre
AXLE_DIAMETER = 20
AXLE_LENGTH = 50              # from the arm's end outwards
WHEEL_GAP = 10                # between an arm's end and its wheel

ARM_END_Y = PLATE[1] / 2 + ARM[1]                  # 150
WHEEL_CENTRE_Y = ARM_END_Y + WHEEL_GAP + WHEEL_WIDTH / 2  # 180
STAND_HEIGHT = 150            # the added world joint holds the base this high (wheels clear the floor)

WHEELS = {  # link name: (x, y) of its centre, mm
    "front_left_wheel": (AXLE_X, WHEEL_CENTRE_Y),
    "front_right_wheel": (AXLE_X, -WHEEL_CENTRE_Y),
    "rear_left_wheel": (-AXLE_X, WHEEL_CENTRE_Y),
    "rear_right_wheel": (-AXLE_X, -WHEEL_CENTRE_Y),
}
COLOURS = {
    "base_link": (0.20, 0.33, 0.55, 1.0),
    "wheel": (0.93, 0.55, 0.13, 1.0),
}


def wheel(name: str = "wheel") -> Part:
    return holed_wheel(ALUMINIUM, WHEEL_DIAMETER, WHEEL_WIDTH, BORE_DIAMETER, HOLE_DIAMETER,
                       HOLE_PITCH_DIAMETER, offsets=(0.13, -0.135, 0.125, 0.125, 0.12), name=name)


def base() -> Part:
    lx, ly, lz = PLATE
    ax, ay, az = ARM
    arm_cy = ly / 2 + ay / 2
    axle_cy = ARM_END_Y + AXLE_LENGTH / 2
    features = [Box(mm(lx, ly, lz))]
    for x in (AXLE_X, -AXLE_X):
        for side in (1, -1):
            features.append(Box(mm(ax, ay, az), mm(x, side * arm_cy, 0)))
            features.append(Cylinder(mm(AXLE_DIAMETER / 2), mm(AXLE_LENGTH), "y", mm(x, side * axle_cy, 0)))
    end = ARM_END_Y + AXLE_LENGTH
    return Part(
        name="base_link",
        title="Base",
        material=ALUMINIUM,
        features=features,
        dimensions=[
            Dimension("top", mm(-lx / 2, -ARM_END_Y, 0), mm(lx / 2, -ARM_END_Y, 0), "h", -0.07),
            Dimension("top", mm(-AXLE_X, end, 0), mm(AXLE_X, end, 0), "h", 0.06),
            Dimension("top", mm(AXLE_X - ax / 2, ARM_END_Y, 0), mm(AXLE_X + ax / 2, ARM_END_Y, 0), "h", 0.08),
            Dimension("top", mm(lx / 2, -ly / 2, 0), mm(lx / 2, ly / 2, 0), "v", 0.05),
            Dimension("top", mm(-lx / 2, ly / 2, 0), mm(-lx / 2, ARM_END_Y, 0), "v", -0.05),
            Dimension("top", mm(-lx / 2, ARM_END_Y, 0), mm(-lx / 2, end, 0), "v", -0.05),
            Dimension("top", mm(-AXLE_X - AXLE_DIAMETER / 2, -end, 0),
                      mm(-AXLE_X - AXLE_DIAMETER / 2, end, 0), "v", -0.12),
            Dimension("front", mm(lx / 2, 0, -lz / 2), mm(lx / 2, 0, lz / 2), "v", 0.04),
            Dimension("side", mm(0, end, -AXLE_DIAMETER / 2), mm(0, end, AXLE_DIAMETER / 2), "v", 0.015,
                      f"Ø{AXLE_DIAMETER}"),
        ],
    )


# Added to launch/gazebo.launch in "A custom node": the ROS version of the pulse script.
GAZEBO_NODES = """  <node
    name="periodic_force"
    pkg="example_1"
    type="periodic_force_node.py"
    output="screen" />
"""


def robot() -> Robot:
    """The assembly as exported, plus what Practice 1 adds by hand (colours, the world link)."""
    wheel_part = wheel()
    links = [Link("base_link", base(), component="base-1")]
    joints = []
    for i, (name, (x, y)) in enumerate(WHEELS.items(), start=1):
        links.append(Link(name, wheel_part, component=f"wheel-{i}"))
        joint = name.replace("_wheel", "_joint")
        axle = "front" if x > 0 else "rear"
        joints.append(Joint(joint, "continuous", "base_link", name, xyz=mm(x, y, 0), axis=(0, 1, 0),
                            coordinate_system=f"Origin_{joint}", axis_name=f"Axis_{axle}"))
    r = Robot(PACKAGE, links, joints)
    r.added_links = [Link("world", None)]
    r.added_joints = [Joint("world_joint", "fixed", "world", "base_link", xyz=(0, 0, mm(STAND_HEIGHT)))]
    r.colours = {lk.name: COLOURS["base_link"] if lk.name == "base_link" else COLOURS["wheel"] for lk in links}
    # The wheels' states on /joint_states, for the custom node page's plot.
    r.joint_state_rate = 50.0
    r.depends = ["gazebo_plugins"]
    return r


def parts() -> list[Part]:
    """The distinct parts, one drawing each."""
    return [base(), wheel()]


def write(root: Path | None = None) -> list[Path]:
    from ... import ROOT
    return write_package(robot(), (root or ROOT / "examples") / PACKAGE, gazebo_nodes=GAZEBO_NODES)
