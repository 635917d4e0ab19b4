"""Practice 5, a simple vehicle: a chassis, two steering knuckles, four driven wheels and a
centre steering link that the control script reads.

Every number on the Practice 5 drawings comes from here, in millimetres as on the
drawings. The chassis' origin is the middle of the rear axle, at the height of the wheel
centres; x points forward, y to the left, z up. Each front wheel hangs in a fork-shaped
knuckle whose steering axis passes vertically through the wheel's centre, so the wheel
turns on the spot where it touches the floor: the wheelbase l and the track w of the
Ackermann geometry (Equation 4) are then exactly the distances between the joints.
"""

import math
from pathlib import Path

from ...exporter_format import Joint, Limit, Link, Robot, Safety, Transmission, write_package
from ...ros_control_files import ROS_CONTROL_DEPENDS, ros_control_nodes
from ...parts import Box, Cylinder, Dimension, Material, Part
from ..shared import holed_wheel, mm

PACKAGE = "example_5"
ALUMINIUM = Material("Aluminium 6061-T6", 2700.0)


# --- the layout ------------------------------------------------------------------------------
WHEELBASE = 400               # l: rear axle to the front steering axes
TRACK = 300                   # w: between the left and right wheel centres (and steering axes)

# --- the wheel -------------------------------------------------------------------------------
WHEEL_DIAMETER = 120
WHEEL_WIDTH = 30
BORE_DIAMETER = 10            # the fork's axle pin runs through it
HOLE_DIAMETER = 16            # four lightening holes show the wheel turning
HOLE_PITCH_DIAMETER = 64

# --- the forks (the knuckles in front, the same shape fixed to the chassis at the rear) -----
FORK_GAP = 5                  # between the wheel and each fork plate
FORK_PLATE = (30, 6)          # each side plate: length along x, thickness
FORK_BELOW = 15               # the plates reach this far below the axle
FORK_CLEARANCE = 6            # between the wheel's top and the fork's bridge
BRIDGE_THICKNESS = 6
KINGPIN_DIAMETER = 12         # the knuckle's pin up to the chassis
AXLE_PIN_DIAMETER = BORE_DIAMETER

# --- the chassis -----------------------------------------------------------------------------
PLATE = (560, 160, 10)        # length (x), width (y), thickness (z)
PLATE_BACK = -80              # where the plate starts, from the rear axle
CROSS_MEMBER = (40, 10)       # front and rear beams out to the forks: width (x), thickness (z)
HUB_DIAMETER = 30             # the boss around each kingpin, at the end of the front beam

WHEEL_RADIUS = WHEEL_DIAMETER / 2                                   # 60
FORK_INNER = WHEEL_WIDTH / 2 + FORK_GAP                             # 20, plate's inner face
FORK_PLATE_Y = FORK_INNER + FORK_PLATE[1] / 2                       # 23, plate's centre
BRIDGE_BOTTOM = WHEEL_RADIUS + FORK_CLEARANCE                       # 66
BRIDGE_TOP = BRIDGE_BOTTOM + BRIDGE_THICKNESS                       # 72
PLATE_BOTTOM = 90             # the chassis' underside above the wheel centres
PLATE_TOP = PLATE_BOTTOM + PLATE[2]                                 # 100
BEAM_HALF = TRACK / 2 + FORK_PLATE_Y + FORK_PLATE[1] / 2            # 176, to the fork's outside

# --- the centre steering link ----------------------------------------------------------------
STEER_X = 320                 # the steering joint, on the chassis' centre line
STEER_DISC = (40, 10)         # diameter, height
STEER_BAR = (16, 120, 8)      # the bar across the disc: x, y, z (like a servo horn)

# --- joints ----------------------------------------------------------------------------------
STEER_LIMIT_DEGREES = 30.0    # the centre steering joint's travel each way
STEER_LIMIT = round(math.radians(STEER_LIMIT_DEGREES), 4)   # 0.5236 rad, as typed in
STEER_EFFORT, STEER_VELOCITY = 5.0, 3.0          # N·m, rad/s
KNUCKLE_EFFORT, KNUCKLE_VELOCITY = 20.0, 6.0     # N·m, rad/s
WHEEL_EFFORT, WHEEL_VELOCITY = 10.0, 30.0        # N·m, rad/s (30 rad/s: 1.8 m/s on Ø120)
K_POSITION = 20.0             # 1/s, the soft limits' gain towards a limit
K_VELOCITY = 1.0              # N·m per rad/s over the velocity limit

COLOURS = {
    "base_link": (0.22, 0.24, 0.28, 1.0),
    "steering_link": (0.85, 0.20, 0.15, 1.0),
    "knuckle": (0.20, 0.45, 0.75, 1.0),
    "wheel": (0.93, 0.55, 0.13, 1.0),
}

SIDES = {"left": 1, "right": -1}
KNUCKLES = {side: f"{side}_knuckle_joint" for side in SIDES}
WHEEL_JOINTS = {f"{end}_{side}": f"{end}_{side}_wheel_joint" for end in ("front", "rear") for side in SIDES}
STEERING_JOINT = "steering_joint"


def ackermann(phi: float, l: float = mm(WHEELBASE), w: float = mm(TRACK)) -> tuple[float, float]:
    """Equation 4: the (inner, outer) knuckle angles, rad, for a centre angle `phi` > 0."""
    inner = math.atan2(2 * l * math.sin(phi), 2 * l * math.cos(phi) - w * math.sin(phi))
    outer = math.atan2(2 * l * math.sin(phi), 2 * l * math.cos(phi) + w * math.sin(phi))
    return inner, outer


# The knuckles may turn as far as the inner wheel must at the centre joint's limit: rounded
# up to the 4 decimals typed into the exporter, so the limit never cuts Equation 4 short.
KNUCKLE_LIMIT = math.ceil(ackermann(STEER_LIMIT)[0] * 1e4) / 1e4   # 0.6351 rad (36.39°)


def wheel(name: str = "wheel") -> Part:
    return holed_wheel(ALUMINIUM, WHEEL_DIAMETER, WHEEL_WIDTH, BORE_DIAMETER, HOLE_DIAMETER,
                       HOLE_PITCH_DIAMETER, offsets=(0.08, -0.085, 0.08, 0.095, 0.08), name=name)


def _fork(x: float = 0.0, y: float = 0.0, kingpin: bool = True) -> list:
    """A fork around a wheel whose centre is at (x, y, 0): two side plates, a bridge over the
    wheel, an axle pin through it and (for a knuckle) the kingpin up to the chassis."""
    length, t = FORK_PLATE
    height = BRIDGE_TOP + FORK_BELOW
    plate_z = BRIDGE_TOP - height / 2
    span = 2 * (FORK_INNER + t)
    features = [Box(mm(length, t, height), mm(x, y + s * FORK_PLATE_Y, plate_z)) for s in (1, -1)]
    features += [
        Box(mm(length, span, BRIDGE_THICKNESS), mm(x, y, BRIDGE_BOTTOM + BRIDGE_THICKNESS / 2)),
        Cylinder(mm(AXLE_PIN_DIAMETER / 2), mm(span), "y", mm(x, y, 0)),
    ]
    if kingpin:
        pin = PLATE_BOTTOM - BRIDGE_TOP
        features.append(Cylinder(mm(KINGPIN_DIAMETER / 2), mm(pin), "z", mm(x, y, BRIDGE_TOP + pin / 2)))
    else:   # a rear fork is part of the chassis: a post the size of the kingpin joins it on
        pin = PLATE_BOTTOM - BRIDGE_TOP
        features.append(Box(mm(length, KINGPIN_DIAMETER, pin), mm(x, y, BRIDGE_TOP + pin / 2)))
    return features


def chassis() -> Part:
    lx, ly, lz = PLATE
    bx, bz = CROSS_MEMBER
    l, half = WHEELBASE, TRACK / 2
    zc = PLATE_BOTTOM + lz / 2
    length, t = FORK_PLATE
    fork, post = FORK_INNER + t, KINGPIN_DIAMETER / 2
    features = [
        Box(mm(lx, ly, lz), mm(PLATE_BACK + lx / 2, 0, zc)),
        Box(mm(bx, 2 * BEAM_HALF, bz), mm(0, 0, zc)),                   # rear beam
        Box(mm(bx, 2 * half, bz), mm(l, 0, zc)),                        # front beam
    ]
    for s in (1, -1):
        features.append(Cylinder(mm(HUB_DIAMETER / 2), mm(lz), "z", mm(l, s * half, zc)))
        features += _fork(0, s * half, kingpin=False)
    front = PLATE_BACK + lx
    return Part(
        name="base_link",
        title="Chassis",
        material=ALUMINIUM,
        features=features,
        dimensions=[
            Dimension("top", mm(0, half, PLATE_TOP), mm(l, half, PLATE_TOP), "h", 0.09,
                      f"{WHEELBASE} (l, wheelbase)"),
            Dimension("top", mm(PLATE_BACK, -ly / 2, PLATE_TOP), mm(front, -ly / 2, PLATE_TOP), "h", -0.12),
            Dimension("top", mm(PLATE_BACK, -ly / 2, PLATE_TOP), mm(0, -ly / 2, PLATE_TOP), "h", -0.06),
            Dimension("top", mm(l, -half, PLATE_TOP), mm(l, half, PLATE_TOP), "v", 0.10 + (front - l) / 1000,
                      f"{TRACK} (w, track)"),
            Dimension("top", mm(front, -ly / 2, PLATE_TOP), mm(front, ly / 2, PLATE_TOP), "v", 0.05),
            Dimension("top", mm(-bx / 2, -BEAM_HALF, PLATE_TOP), mm(-bx / 2, BEAM_HALF, PLATE_TOP), "v",
                      -0.06 + PLATE_BACK / 1000),
            Dimension("top", mm(0, 0, PLATE_TOP), mm(STEER_X, 0, PLATE_TOP), "h", 0.0,
                      f"{STEER_X} (steering joint)"),
            Dimension("front", mm(front, 0, 0), mm(front, 0, PLATE_TOP), "v", 0.04),
            Dimension("front", mm(PLATE_BACK, 0, PLATE_BOTTOM), mm(PLATE_BACK, 0, PLATE_TOP), "v", -0.015),
            Dimension("side", mm(l, half - HUB_DIAMETER / 2, PLATE_TOP), mm(l, half + HUB_DIAMETER / 2, PLATE_TOP),
                      "h", 0.03, f"Ø{HUB_DIAMETER}"),
            Dimension("side", mm(0, -half, -FORK_BELOW), mm(0, -half, PLATE_BOTTOM), "v", -0.05),
            # the beams' width, and the rear forks (the knuckle's shape, with a post for its kingpin)
            Dimension("top", mm(l - bx / 2, -half, PLATE_TOP), mm(l + bx / 2, -half, PLATE_TOP), "h", -0.04),
            Dimension("front", mm(-length / 2, 0, -FORK_BELOW), mm(length / 2, 0, -FORK_BELOW), "h", -0.015),
            Dimension("side", mm(0, half - fork, -FORK_BELOW), mm(0, half + fork, -FORK_BELOW), "h", -0.015),
            Dimension("side", mm(0, half + fork, -FORK_BELOW), mm(0, half + fork, BRIDGE_TOP), "v", 0.03),
            Dimension("side", mm(0, half + fork, BRIDGE_BOTTOM), mm(0, half + fork, BRIDGE_TOP), "v", 0.06),
            Dimension("side", mm(0, half + fork, BRIDGE_TOP), mm(0, half + post, PLATE_BOTTOM), "v", 0.06),
            Dimension("side", mm(0, -half - fork, -FORK_BELOW), mm(0, -half - fork + t, -FORK_BELOW), "h",
                      -0.015),
            Dimension("side", mm(0, -half - post, BRIDGE_TOP), mm(0, -half + post, BRIDGE_TOP), "h",
                      -0.045 - (FORK_BELOW + BRIDGE_TOP) / 1000),
            Dimension("side", mm(0, -half + fork, -AXLE_PIN_DIAMETER / 2), mm(0, -half + fork, AXLE_PIN_DIAMETER / 2),
                      "v", 0.04, f"Ø{AXLE_PIN_DIAMETER} pin"),
        ],
    )


def knuckle(name: str = "knuckle") -> Part:
    """A steering knuckle: a fork whose kingpin axis is its z axis, through the wheel centre.
    Origin: the wheel centre (on the axle pin's axis)."""
    length, t = FORK_PLATE
    return Part(
        name=name,
        title="Steering knuckle",
        material=ALUMINIUM,
        features=_fork(),
        dimensions=[
            Dimension("side", mm(0, -FORK_INNER, -FORK_BELOW), mm(0, FORK_INNER, -FORK_BELOW), "h", -0.015),
            Dimension("side", mm(0, FORK_INNER, -FORK_BELOW), mm(0, FORK_INNER + t, -FORK_BELOW), "h", -0.015),
            Dimension("side", mm(0, -FORK_INNER - t, -FORK_BELOW), mm(0, FORK_INNER + t, -FORK_BELOW), "h",
                      -0.03),
            Dimension("side", mm(0, FORK_INNER + t, -FORK_BELOW), mm(0, FORK_INNER + t, 0), "v", 0.015),
            Dimension("side", mm(0, FORK_INNER + t, 0), mm(0, FORK_INNER + t, BRIDGE_TOP), "v", 0.015),
            Dimension("side", mm(0, FORK_INNER + t, -FORK_BELOW), mm(0, FORK_INNER + t, BRIDGE_TOP), "v", 0.03),
            Dimension("side", mm(0, -FORK_INNER - t, BRIDGE_BOTTOM), mm(0, -FORK_INNER - t, BRIDGE_TOP), "v",
                      -0.015),
            Dimension("side", mm(0, -FORK_INNER - t, BRIDGE_TOP), mm(0, -KINGPIN_DIAMETER / 2, PLATE_BOTTOM), "v",
                      -0.015),
            Dimension("side", mm(0, -FORK_INNER - t, 0), mm(0, -FORK_INNER - t, PLATE_BOTTOM), "v", -0.03),
            Dimension("side", mm(0, -KINGPIN_DIAMETER / 2, PLATE_BOTTOM),
                      mm(0, KINGPIN_DIAMETER / 2, PLATE_BOTTOM), "h", 0.012, f"Ø{KINGPIN_DIAMETER}"),
            Dimension("front", mm(-length / 2, 0, -FORK_BELOW), mm(length / 2, 0, -FORK_BELOW), "h", -0.015),
            Dimension("front", mm(-AXLE_PIN_DIAMETER / 2, 0, 0), mm(AXLE_PIN_DIAMETER / 2, 0, 0), "h", 0.105,
                      f"Ø{AXLE_PIN_DIAMETER} pin"),
        ],
    )


def steering_link() -> Part:
    """The centre steering link: a disc with a bar across it, on the chassis' top.
    Origin: on the joint's axis, at the plate's top face."""
    d, h = STEER_DISC
    bx, by, bz = STEER_BAR
    return Part(
        name="steering_link",
        title="Centre steering link",
        material=ALUMINIUM,
        features=[
            Cylinder(mm(d / 2), mm(h), "z", mm(0, 0, h / 2)),
            Box(mm(bx, by, bz), mm(0, 0, h + bz / 2)),
        ],
        dimensions=[
            Dimension("top", mm(bx / 2, -by / 2, h + bz), mm(bx / 2, by / 2, h + bz), "v", 0.03),
            Dimension("top", mm(-bx / 2, by / 2, h + bz), mm(bx / 2, by / 2, h + bz), "h", 0.01),
            Dimension("front", mm(-d / 2, 0, 0), mm(d / 2, 0, 0), "h", -0.02, f"Ø{d}"),
            Dimension("front", mm(d / 2, 0, 0), mm(d / 2, 0, h), "v", 0.015),
            Dimension("front", mm(-bx / 2, 0, h), mm(-bx / 2, 0, h + bz), "v", -0.015),
        ],
    )


def wheel_centre(end: str, side: str) -> tuple[float, float, float]:
    """A wheel's centre in the chassis frame, m."""
    return mm(WHEELBASE if end == "front" else 0, SIDES[side] * TRACK / 2, 0)


JOINTS = [STEERING_JOINT, *KNUCKLES.values(), *WHEEL_JOINTS.values()]
STEERING_CONTROLLER = "steering_controller"
KNUCKLE_CONTROLLERS = {side: f"{side}_knuckle_controller" for side in SIDES}
WHEEL_CONTROLLERS = {key: f"{key}_wheel_controller" for key in WHEEL_JOINTS}
POSITION = "effort_controllers/JointPositionController"
VELOCITY = "effort_controllers/JointVelocityController"
# PID gains (config/joint_names_example_5.yaml). Position controllers: N·m per rad and
# N·m per rad/s; velocity controllers: N·m per rad/s of speed error.
STEERING_GAINS = {"p": 20.0, "i": 0.0, "d": 0.5}
KNUCKLE_GAINS = {"p": 200.0, "i": 0.0, "d": 2.0}
WHEEL_GAINS = {"p": 5.0, "i": 0.0, "d": 0.0}
STATE_RATE = 50               # Hz, joint_state_controller's publish rate


def controllers_yaml() -> str:
    def entry(name, kind, joint, gains):
        pid = ", ".join(f"{k}: {v}" for k, v in gains.items())
        return f"""
  {name}:
    type: {kind}
    joint: {joint}
    pid: {{{pid}}}
"""
    entries = entry(STEERING_CONTROLLER, POSITION, STEERING_JOINT, STEERING_GAINS)
    entries += "".join(entry(KNUCKLE_CONTROLLERS[s], POSITION, KNUCKLES[s], KNUCKLE_GAINS) for s in SIDES)
    entries += "".join(entry(WHEEL_CONTROLLERS[k], VELOCITY, WHEEL_JOINTS[k], WHEEL_GAINS)
                       for k in WHEEL_JOINTS)
    names = "".join(f"'{j}', " for j in JOINTS)
    return f"""controller_joint_names: ['', {names}]

# Added for Practice 5: the controllers, loaded by launch/gazebo.launch. The centre
# steering joint is the driver's input; scripts/ackermann_node.py reads it and commands
# the knuckles and the four wheels.
{PACKAGE}:
  joint_state_controller:
    type: joint_state_controller/JointStateController
    publish_rate: {STATE_RATE}
{entries}"""


def _gazebo_nodes() -> str:
    controllers = [STEERING_CONTROLLER, *KNUCKLE_CONTROLLERS.values(), *WHEEL_CONTROLLERS.values()]
    return ros_control_nodes(PACKAGE, controllers) + f"""  <node
    name="ackermann"
    pkg="{PACKAGE}"
    type="ackermann_node.py"
    ns="/{PACKAGE}"
    output="screen" />
"""


GAZEBO_NODES = _gazebo_nodes()


def robot() -> Robot:
    """The assembly as exported, plus what Practice 5 adds by hand (colours, ros_control).
    No world link: the car drives on the floor."""
    def limit(lower, upper, effort, velocity):
        return Limit(lower, upper, effort, velocity)

    links = [Link("base_link", chassis(), component="chassis-1"),
             Link("steering_link", steering_link(), component="steering_link-1")]
    joints = [Joint(STEERING_JOINT, "revolute", "base_link", "steering_link", xyz=mm(STEER_X, 0, PLATE_TOP),
                    axis=(0, 0, 1), limit=limit(-STEER_LIMIT, STEER_LIMIT, STEER_EFFORT, STEER_VELOCITY),
                    safety=Safety(-STEER_LIMIT, STEER_LIMIT, K_POSITION, K_VELOCITY),
                    coordinate_system=f"Origin_{STEERING_JOINT}", axis_name="Axis_steering")]
    knuckle_part, wheel_part = knuckle(), wheel()
    for i, side in enumerate(SIDES, start=1):
        name = f"{side}_knuckle"
        links.append(Link(name, knuckle_part, component=f"knuckle-{i}"))
        joints.append(Joint(KNUCKLES[side], "revolute", "base_link", name, xyz=wheel_centre("front", side),
                            axis=(0, 0, 1),
                            limit=limit(-KNUCKLE_LIMIT, KNUCKLE_LIMIT, KNUCKLE_EFFORT, KNUCKLE_VELOCITY),
                            safety=Safety(-KNUCKLE_LIMIT, KNUCKLE_LIMIT, K_POSITION, K_VELOCITY),
                            coordinate_system=f"Origin_{KNUCKLES[side]}", axis_name=f"Axis_kingpin_{side}"))
    for i, (key, joint) in enumerate(WHEEL_JOINTS.items(), start=1):
        end, side = key.split("_")
        name = f"{key}_wheel"
        links.append(Link(name, wheel_part, component=f"wheel-{i}"))
        parent, xyz = ("base_link", wheel_centre(end, side)) if end == "rear" else (f"{side}_knuckle", (0, 0, 0))
        joints.append(Joint(joint, "continuous", parent, name, xyz=xyz, axis=(0, 1, 0),
                            limit=Limit(0, 0, WHEEL_EFFORT, WHEEL_VELOCITY),
                            coordinate_system=f"Origin_{joint}", axis_name=f"Axis_{end}_axle"))
    r = Robot(PACKAGE, links, joints)
    r.colours = {}
    for lk in links:
        kind = "wheel" if lk.name.endswith("_wheel") else "knuckle" if "knuckle" in lk.name else lk.name
        r.colours[lk.name] = COLOURS[kind]
    r.transmissions = [Transmission(j) for j in JOINTS]
    r.gazebo_plugin = "libgazebo_ros_control.so"
    r.depends = list(ROS_CONTROL_DEPENDS)
    return r


def parts() -> list[Part]:
    """The distinct parts, one drawing each."""
    return [chassis(), knuckle(), wheel(), steering_link()]


def write(root: Path | None = None) -> list[Path]:
    from ... import ROOT
    return write_package(robot(), (root or ROOT / "examples") / PACKAGE,
                         gazebo_nodes=GAZEBO_NODES, config=controllers_yaml())
