"""Controllers for an export that commands nothing: the exporter writes no transmissions and
no controllers, so its port would only report the joints' state. Unless `--no-controllers`
is given, every movable joint of such a package (those of --effort-joints aside) gets a
command interface and a controller:

- a wheel gets `velocity`, and the wheels share `wheel_velocity_controller`
  (velocity_controllers/JointGroupVelocityController): one speed per wheel on
  `~/commands`, held until the next message, so a wheel keeps turning. A wheel is a
  continuous joint that carries no other movable joint and hangs below no continuous
  joint (an arm's last joint does; a wheel on a steering joint does not);
- every other joint gets `position`, and they share `joint_trajectory_controller`
  (joint_trajectory_controller/JointTrajectoryController), which takes a trajectory of
  positions on `~/joint_trajectory` or the `~/follow_joint_trajectory` action.
  gz_ros2_control turns a position command into a velocity servo, so no gains are needed.

The exporter's empty limit (lower = upper = effort = velocity = 0, what it writes for fields
left empty) would keep a joint still in Gazebo Sim: a travel of 0 to 0, and a force limit
of 0 for DART. A revolute joint with it becomes continuous, without the <limit>, as
`sw2sim convert` frees such a joint; a continuous one loses the empty <limit>; a prismatic
one gets no controller (no travel can be guessed). Joints that mimic another, and joints
without an axis, get none either. Every decision is a line of `choices`.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from lxml import etree

from .controllers import Controller

TRAJECTORY = "joint_trajectory_controller"
WHEELS = "wheel_velocity_controller"
JTC = "joint_trajectory_controller/JointTrajectoryController"
VELOCITY = "velocity_controllers/JointGroupVelocityController"
LIMIT_FIELDS = ("lower", "upper", "effort", "velocity")


@dataclass
class Defaults:
    controllers: list[Controller] = field(default_factory=list)
    choices: list[str] = field(default_factory=list)
    usage: list[str] = field(default_factory=list)   # README lines: how to command them


def applies(robot: etree._Element, ros1_commanded: set[str]) -> bool:
    """Whether the package commands nothing by itself: no transmission, and no ROS 1
    controller that drives a joint."""
    return robot.find("transmission") is None and not ros1_commanded


def plan(robot: etree._Element, joints: dict[str, str], leave: set[str], urdf: str) -> Defaults:
    """The controllers for the movable `joints` (name -> type) not in `leave`. Repairs the
    exporter's empty limits in `robot`, the URDF being ported (a copy)."""
    result = Defaults()
    elements = {j.get("name"): j for j in robot.findall("joint")}
    arm, wheels, skipped = [], [], []
    freed, emptied, no_force = [], [], []
    for name, kind in joints.items():
        if name in leave:
            continue
        joint = elements[name]
        if joint.find("mimic") is not None:
            skipped.append(f"{name} (it mimics {joint.find('mimic').get('joint')})")
            continue
        if _no_axis(joint):
            skipped.append(f"{name} (its axis is 0 0 0)")
            continue
        limit = joint.find("limit")
        if limit is not None and _empty(limit):
            if kind == "prismatic":
                skipped.append(f"{name} (the exporter's empty limit, lower = upper = 0: it "
                               "cannot slide, and no travel can be guessed for it)")
                continue
            joint.remove(limit)
            if kind == "revolute":
                joint.set("type", "continuous")
                freed.append(name)
            else:
                emptied.append(name)
        elif limit is not None and _number(limit.get("effort")) == 0:
            no_force.append(name)
        (wheels if _is_wheel(name, joints, elements) else arm).append(name)
    where = f"{urdf}: " if urdf else ""
    if freed:
        result.choices.append(
            f"{where}{', '.join(freed)} had the exporter's empty limit (lower = upper = effort "
            "= velocity = 0, what it writes for fields left empty): in Gazebo such a joint "
            "cannot move (a travel of 0 and a force limit of 0). In the port each is a "
            "continuous joint without a <limit>, so that it turns; enter its real travel, "
            "effort and speed in the exporter, export again and port again.")
    if emptied:
        result.choices.append(
            f"{where}{', '.join(emptied)}: the exporter's empty <limit> (effort and velocity 0) "
            "was removed, as Gazebo would give the joint no force at all; a continuous joint "
            "needs no <limit>.")
    if no_force:
        result.choices.append(
            f"{', '.join(no_force)}: the <limit> gives effort 0, and Gazebo's physics (DART) "
            "caps the joint's force at it, so the joint will not follow its controller until "
            "you enter the motor's real effort and port again.")
    if skipped:
        result.choices.append("No controller for " + "; ".join(skipped) + ".")
    if arm:
        result.controllers.append(Controller(
            TRAJECTORY, JTC,
            {"joints": arm, "command_interfaces": ["position"],
             "state_interfaces": ["position", "velocity"],
             "allow_partial_joints_goal": True},
            {j: "position" for j in arm}))
        result.choices.append(
            f"The export has no transmissions and no controllers, so {_listed(arm)} got a "
            f"`position` command interface and `{TRAJECTORY}` ({JTC}): send it a "
            f"trajectory_msgs/msg/JointTrajectory on /{TRAJECTORY}/joint_trajectory, or a goal "
            f"to the /{TRAJECTORY}/follow_joint_trajectory action. A trajectory may name only "
            "some of the joints (allow_partial_joints_goal); the others hold. "
            "--no-controllers leaves the controllers out.")
        result.usage += _trajectory_usage(arm, joints)
    if wheels:
        result.controllers.append(Controller(WHEELS, VELOCITY, {"joints": wheels},
                                             {j: "velocity" for j in wheels}))
        result.choices.append(
            f"{_listed(wheels)} {'look' if len(wheels) > 1 else 'looks'} like "
            f"{'wheels' if len(wheels) > 1 else 'a wheel'} (continuous, carrying no other "
            f"joint): {'they' if len(wheels) > 1 else 'it'} got a `velocity` command interface "
            f"and `{WHEELS}` ({VELOCITY}): publish one speed per wheel, in this order, in rad/s, "
            f"as a std_msgs/msg/Float64MultiArray on /{WHEELS}/commands; each wheel keeps that "
            "speed until the next message. --no-controllers leaves the controllers out.")
        result.usage += _wheel_usage(wheels)
    return result


def _listed(names: list[str]) -> str:
    return ", ".join(names[:-1]) + (" and " if len(names) > 1 else "") + names[-1]


def _number(text) -> float | None:
    try:
        return float(text)
    except (TypeError, ValueError):
        return None


def _empty(limit: etree._Element) -> bool:
    """The exporter's empty limit: every one of lower, upper, effort, velocity 0 (or absent)."""
    values = [_number(limit.get(a, "0")) for a in LIMIT_FIELDS]
    return all(v == 0 for v in values)


def _no_axis(joint: etree._Element) -> bool:
    axis = joint.find("axis")
    if axis is None:
        return False   # URDF's default axis is 1 0 0
    values = [_number(v) for v in (axis.get("xyz") or "").split()]
    return len(values) == 3 and all(v == 0 for v in values)


def _is_wheel(name: str, joints: dict[str, str], elements: dict) -> bool:
    """A continuous joint (as the export gives it) that carries no movable joint and hangs
    below no continuous joint."""
    if joints[name] != "continuous":
        return False
    by_parent: dict[str, list] = {}
    by_child = {}
    for j in elements.values():
        parent, child = j.find("parent"), j.find("child")
        if parent is None or child is None:
            continue
        by_parent.setdefault(parent.get("link"), []).append(j)
        by_child[child.get("link")] = j
    below = [elements[name].find("child").get("link")]
    while below:
        for j in by_parent.get(below.pop(), []):
            if j.get("name") in joints:
                return False
            below.append(j.find("child").get("link"))
    seen = set()
    link = elements[name].find("parent").get("link")
    while link in by_child and link not in seen:
        seen.add(link)
        above = by_child[link]
        if joints.get(above.get("name")) == "continuous":
            return False
        link = above.find("parent").get("link")
    return True


def _trajectory_usage(names: list[str], joints: dict[str, str]) -> list[str]:
    goal = ", ".join("0.5" for _ in names)
    lines = [f"`{TRAJECTORY}` moves {_listed(names)} along a trajectory of positions "
             "(radians, metres for a prismatic joint); here to 0.5 within 2 s:", "",
             "```bash",
             f"ros2 topic pub --once /{TRAJECTORY}/joint_trajectory "
             "trajectory_msgs/msg/JointTrajectory \\",
             f"  \"{{joint_names: [{', '.join(names)}], points: [{{positions: [{goal}], "
             "time_from_start: {sec: 2}}]}\"",
             "```", ""]
    if any(joints[n] == "continuous" for n in names):
        lines += ["For a continuous joint the controller takes a goal as an angle on the "
                  "circle (angle_wraparound): give goals within half a turn of where the "
                  "joint is.", ""]
    return lines


def _wheel_usage(names: list[str]) -> list[str]:
    speeds = ", ".join("1.0" for _ in names)
    return [f"`{WHEELS}` turns {_listed(names)} at the speeds you publish, one per wheel in "
            "this order (rad/s), until the next message:", "",
            "```bash",
            f"ros2 topic pub --once /{WHEELS}/commands std_msgs/msg/Float64MultiArray "
            f"\"{{data: [{speeds}]}}\"",
            "```", ""]
