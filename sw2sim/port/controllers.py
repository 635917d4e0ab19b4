"""ROS 1 controller YAML (ros_control) to ROS 2 Jazzy's config/controllers.yaml (ros2_control).

ROS 1 packages declare each controller as a mapping with a `type`, anywhere in a YAML file
under config/ (the exporter's `config/joint_names_<pkg>.yaml` holds only
`controller_joint_names`; packages add the controllers there, under the robot's namespace).
ROS 2 lists every controller's type under `controller_manager: ros__parameters:` and gives
each its own top-level section with `ros__parameters`.

The counterparts and their parameter names are those of ros2_controllers' jazzy branch
(release 4.42.1), read from each controller's parameter definition file; the reference page
/reference/ros2-controllers/ links every one.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

import yaml

from ..errors import LoadError

STATE_RATE = 50      # Hz: /joint_states when nothing says how often
UPDATE_RATE = 1000   # Hz: Gazebo Classic's default step is 1 ms, and gazebo_ros_control ran the
                     # controllers at every step unless <controlPeriod> said otherwise
JOINT_STATE = "joint_state_broadcaster"


@dataclass
class Controller:
    """One ROS 2 controller: its section in controllers.yaml and what it needs of the URDF."""

    name: str
    type: str
    parameters: dict = field(default_factory=dict)
    commands: dict[str, str] = field(default_factory=dict)   # joint -> command interface

    @property
    def package(self) -> str:
        """The ROS 2 package the controller's plugin comes from."""
        return self.type.split("/")[0]


@dataclass
class Plan:
    controllers: list[Controller] = field(default_factory=list)
    update_rate: int = UPDATE_RATE
    choices: list[str] = field(default_factory=list)
    sources: list[str] = field(default_factory=list)   # the YAML files read, inside the package

    @property
    def names(self) -> list[str]:
        return [c.name for c in self.controllers]


@dataclass(frozen=True)
class Ros1Controller:
    name: str
    type: str
    values: dict
    file: str
    line: int | None


# -- reading ROS 1 YAML --------------------------------------------------------------------
def find_ros1_controllers(root: Path) -> tuple[list[Ros1Controller], list[str]]:
    """Every mapping with a controller `type` ("package/Class") in the package's config/
    YAML files, with the files read (relative to `root`)."""
    found, read = [], []
    folder = root / "config"
    files = sorted(p for p in folder.glob("*") if p.suffix.lower() in (".yaml", ".yml")
                   and p.is_file()) if folder.is_dir() else []
    for file in files:
        rel = file.relative_to(root).as_posix()
        try:
            text = file.read_text(encoding="utf-8-sig")
            nodes = yaml.compose(text, Loader=yaml.SafeLoader)
            data = yaml.safe_load(text)
        except OSError as exc:
            raise LoadError(file, f"cannot read the controller configuration "
                            f"({exc.strerror or exc})", kind="unreadable") from None
        except yaml.YAMLError as exc:
            mark = getattr(exc, "problem_mark", None)
            raise LoadError(file, f"not valid YAML: {getattr(exc, 'problem', exc)}",
                            mark.line + 1 if mark else None, kind="syntax",
                            fix="correct the YAML there (indent with spaces, `key: value`), "
                                "or move the file out of config/") from None
        read.append(rel)
        _collect(data, nodes, rel, found)
    return found, read


def _collect(data, node, file: str, found: list) -> None:
    if not isinstance(data, dict):
        return
    lines = {}
    if isinstance(node, yaml.MappingNode):
        lines = {k.value: (k.start_mark.line + 1, v) for k, v in node.value
                 if isinstance(k, yaml.ScalarNode)}
    for key, value in data.items():
        line, child = lines.get(str(key), (None, None))
        if isinstance(value, dict) and isinstance(value.get("type"), str) \
                and "/" in value["type"]:
            found.append(Ros1Controller(str(key), value["type"].strip(), value, file, line))
        elif isinstance(value, dict):
            _collect(value, child, file, found)


# -- mapping ------------------------------------------------------------------------------
def plan(ros1: list[Ros1Controller], joints: dict[str, str], *, update_rate: int | None,
         effort_joints: list[str], state_rate: float | None = None) -> Plan:
    """The ROS 2 controllers for the ROS 1 ones, with every decision in `choices`.
    `joints` maps each movable joint of the URDF to its type."""
    result = Plan()
    if update_rate is None:
        result.choices.append(
            f"The controller manager runs at {UPDATE_RATE} Hz (update_rate): Gazebo Classic's "
            "default step is 1 ms and gazebo_ros_control updated the controllers at every step.")
    else:
        result.update_rate = update_rate
        result.choices.append(f"The controller manager runs at {update_rate} Hz (update_rate), "
                              "from the gazebo_ros_control plugin's <controlPeriod>.")
    state = [c for c in ros1 if _bare(c.type) == "joint_state_controller/JointStateController"]
    if state:
        result.controllers.append(_joint_state(state[0], result.choices))
        for extra in state[1:]:
            result.choices.append(f"{_where(extra)}: a second joint state controller "
                                  f"`{extra.name}` was left out; one joint_state_broadcaster "
                                  "publishes every joint.")
    else:
        added = Controller(JOINT_STATE, "joint_state_broadcaster/JointStateBroadcaster")
        added.parameters["update_rate"] = max(1, round(state_rate or STATE_RATE))
        result.controllers.append(added)
        why = ("the gazebo_ros joint_state_publisher plugin's <updateRate>" if state_rate
               else "ROS 1's usual publish_rate; without one it would publish at the "
                    "controller manager's rate")
        result.choices.append("joint_state_broadcaster was added (the package has no joint "
                              "state controller): in Gazebo Sim it is what publishes "
                              "/joint_states for robot_state_publisher. It publishes "
                              f"{added.parameters['update_rate']} times a second ({why}).")
    for c in ros1:
        if c in state:
            continue
        mapper = MAPPINGS.get(_bare(c.type))
        if mapper is None:
            result.choices.append(
                f"{_where(c)}: `{c.name}` ({c.type}) has no counterpart here and was left out. "
                "Find its ROS 2 controller in ros2_controllers (control.ros.org lists them), "
                "then add it under controller_manager in config/controllers.yaml with a "
                "section of its own.")
            continue
        made = mapper(c, joints, result.choices)
        if made is not None:
            result.controllers.append(made)
    if effort_joints:
        result.controllers.append(_effort_group(effort_joints, result))
    _check_claims(result)
    return result


def _bare(kind: str) -> str:
    return kind.strip().lstrip("/")


def _where(c: Ros1Controller) -> str:
    return f"{c.file}:{c.line}" if c.line else c.file


def _joint_state(c: Ros1Controller, choices: list[str]) -> Controller:
    made = Controller(JOINT_STATE, "joint_state_broadcaster/JointStateBroadcaster")
    rate = c.values.get("publish_rate")
    text = (f"{_where(c)}: `{c.name}` (joint_state_controller/JointStateController) became "
            "`joint_state_broadcaster` (joint_state_broadcaster/JointStateBroadcaster)")
    if isinstance(rate, (int, float)) and not isinstance(rate, bool) and rate > 0:
        made.parameters["update_rate"] = max(1, round(rate))
        text += f"; publish_rate {rate:g} became its update_rate {made.parameters['update_rate']}"
        if rate != round(rate):
            text += " (a whole number of Hz in ROS 2)"
    choices.append(text + ".")
    return made


def _joint(c: Ros1Controller, joints: dict[str, str], choices: list[str]) -> str | None:
    joint = c.values.get("joint")
    if not isinstance(joint, str) or not joint:
        choices.append(f"{_where(c)}: `{c.name}` names no `joint:` and was left out; give it "
                       "the joint it drives and port again.")
        return None
    if joint not in joints:
        choices.append(f"{_where(c)}: `{c.name}` drives `{joint}`, which is not a movable joint "
                       "of the URDF, and was left out; correct the joint name and port again.")
        return None
    return joint


def _joints(c: Ros1Controller, joints: dict[str, str], choices: list[str]) -> list[str] | None:
    names = c.values.get("joints")
    if not isinstance(names, list) or not names or not all(isinstance(n, str) for n in names):
        choices.append(f"{_where(c)}: `{c.name}` has no `joints:` list and was left out.")
        return None
    missing = [n for n in names if n not in joints]
    if missing:
        choices.append(f"{_where(c)}: `{c.name}` names {', '.join(missing)}, not movable joints "
                       "of the URDF, and was left out; correct the names and port again.")
        return None
    return names


def _gains(pid, c: Ros1Controller, joint: str, choices: list[str]) -> dict:
    """A ROS 1 `pid:` mapping as Jazzy's per-joint gains (control_toolbox's names)."""
    if not isinstance(pid, dict):
        choices.append(f"{_where(c)}: `{c.name}` has no `pid:` gains for {joint}; its gains are "
                       "0 until you set p, i and d under gains.")
        return {"p": 0.0, "i": 0.0, "d": 0.0}
    gains = {k: float(pid[k]) for k in ("p", "i", "d") if _number(pid.get(k))}
    clamp = pid.get("i_clamp")
    high, low = pid.get("i_clamp_max"), pid.get("i_clamp_min")
    if _number(clamp):
        gains["i_clamp_max"], gains["i_clamp_min"] = abs(float(clamp)), -abs(float(clamp))
    if _number(high):
        gains["i_clamp_max"] = float(high)
    if _number(low):
        gains["i_clamp_min"] = float(low)
    dropped = sorted(set(pid) - {"p", "i", "d", "i_clamp", "i_clamp_max", "i_clamp_min",
                                 "antiwindup"})
    if "antiwindup" in pid:
        choices.append(f"{_where(c)}: `{c.name}`'s `antiwindup: {pid['antiwindup']}` was dropped: "
                       "Jazzy's PID (control_toolbox) clamps the stored integral term to "
                       "[i_clamp_min, i_clamp_max] at every step, which is what `antiwindup: true` "
                       "did in ROS 1.")
    if dropped:
        choices.append(f"{_where(c)}: `{c.name}`'s pid keys {', '.join(dropped)} have no Jazzy "
                       "counterpart and were dropped.")
    return gains


def _number(value) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)


def _position_pid(interface: str):
    """effort_controllers/ and velocity_controllers/JointPositionController: a PID on the
    position error, out an effort or a velocity. Jazzy's joint_trajectory_controller runs
    the same PID on a lone effort or velocity command interface (its closed-loop PID
    adapter, joint_trajectory_controller.cpp 4.42.1; ff_velocity_scale is 0 unless set)."""
    def mapper(c, joints, choices) -> Controller | None:
        joint = _joint(c, joints, choices)
        if joint is None:
            return None
        choices.append(
            f"{_where(c)}: `{c.name}` ({interface}_controllers/JointPositionController) became "
            "a joint_trajectory_controller/JointTrajectoryController on "
            f"`{interface}`, with its PID under gains.{joint}: Jazzy has no single-joint "
            f"{interface} position controller. Its command is now a trajectory: "
            f"/{c.name}/joint_trajectory (trajectory_msgs/msg/JointTrajectory) or the "
            f"/{c.name}/follow_joint_trajectory action, instead of a std_msgs/Float64 on "
            f"/{c.name}/command.")
        gains = _gains(c.values.get("pid"), c, joint, choices)
        return Controller(c.name, "joint_trajectory_controller/JointTrajectoryController",
                          {"joints": [joint], "command_interfaces": [interface],
                           "state_interfaces": ["position", "velocity"],
                           "gains": {joint: gains}},
                          {joint: interface})
    return mapper


def _velocity_pid(c, joints, choices) -> Controller | None:
    """effort_controllers/JointVelocityController: a PID on velocity error, out an effort."""
    joint = _joint(c, joints, choices)
    if joint is None:
        return None
    choices.append(
        f"{_where(c)}: `{c.name}` (effort_controllers/JointVelocityController) became a "
        "pid_controller/PidController that reads the joint's velocity and writes its effort, "
        "the same PID on velocity error. Its set point is now "
        f"/{c.name}/reference (control_msgs/msg/MultiDOFCommand, dof_names [{joint}]) instead of "
        f"a std_msgs/Float64 on /{c.name}/command.")
    gains = _gains(c.values.get("pid"), c, joint, choices)
    return Controller(c.name, "pid_controller/PidController",
                      {"dof_names": [joint], "command_interface": "effort",
                       "reference_and_state_interfaces": ["velocity"],
                       "gains": {joint: gains}},
                      {joint: "effort"})


def _forward(kind: str, interface: str, *, group: bool):
    def mapper(c, joints, choices) -> Controller | None:
        names = _joints(c, joints, choices) if group else _joint(c, joints, choices)
        if names is None:
            return None
        names = names if group else [names]
        made = Controller(c.name, kind, {"joints": names}, {j: interface for j in names})
        choices.append(
            f"{_where(c)}: `{c.name}` ({c.type}) became {kind}; its command is now a "
            f"std_msgs/msg/Float64MultiArray on /{c.name}/commands (one value per joint) "
            f"instead of {'a Float64MultiArray' if group else 'a std_msgs/Float64'} on "
            f"/{c.name}/command.")
        return made
    return mapper


def _trajectory(interface: str):
    def mapper(c, joints, choices) -> Controller | None:
        names = _joints(c, joints, choices)
        if names is None:
            return None
        params = {"joints": names, "command_interfaces": [interface],
                  "state_interfaces": ["position", "velocity"]}
        gains = c.values.get("gains")
        if interface != "position" and isinstance(gains, dict):
            params["gains"] = {j: _gains(gains.get(j), c, j, choices) for j in names}
        made = Controller(c.name, "joint_trajectory_controller/JointTrajectoryController",
                          params, {j: interface for j in names})
        choices.append(f"{_where(c)}: `{c.name}` ({c.type}) became "
                       "joint_trajectory_controller/JointTrajectoryController on "
                       f"`{interface}`; the constraints and other settings were not carried over.")
        return made
    return mapper


def _group_position_pid(c, joints, choices) -> Controller | None:
    names = _joints(c, joints, choices)
    if names is None:
        return None
    gains = {j: _gains((c.values.get(j) or {}).get("pid"), c, j, choices) for j in names}
    choices.append(f"{_where(c)}: `{c.name}` (effort_controllers/JointGroupPositionController) "
                   "became joint_trajectory_controller/JointTrajectoryController on `effort`, "
                   f"with each joint's PID under gains; its command is /{c.name}/joint_trajectory.")
    return Controller(c.name, "joint_trajectory_controller/JointTrajectoryController",
                      {"joints": names, "command_interfaces": ["effort"],
                       "state_interfaces": ["position", "velocity"], "gains": gains},
                      {j: "effort" for j in names})


ACKERMANN_KEYS = {"base_frame_id": "base_frame_id", "odom_frame_id": "odom_frame_id",
                  "enable_odom_tf": "enable_odom_tf", "open_loop": "open_loop",
                  "velocity_rolling_window_size": "velocity_rolling_window_size",
                  "cmd_vel_timeout": "reference_timeout",
                  "pose_covariance_diagonal": "pose_covariance_diagonal",
                  "twist_covariance_diagonal": "twist_covariance_diagonal",
                  "wheel_separation_h": "wheelbase", "wheel_radius": "traction_wheel_radius"}


def _ackermann(c, joints, choices) -> Controller | None:
    """ackermann_steering_controller/AckermannSteeringController (ROS 1): one rear wheel
    joint (velocity) and one front steering joint (position), a bicycle model."""
    rear, steer = c.values.get("rear_wheel"), c.values.get("front_steer")
    missing = [f"{key} ({value})" for key, value in (("rear_wheel", rear), ("front_steer", steer))
               if not isinstance(value, str) or value not in joints]
    if missing:
        choices.append(f"{_where(c)}: `{c.name}` (ackermann_steering_controller) was left out: "
                       f"{', '.join(missing)} is not a movable joint of the URDF.")
        return None
    params = {"traction_joints_names": [rear], "steering_joints_names": [steer]}
    for old, new in ACKERMANN_KEYS.items():
        if old in c.values:
            params[new] = c.values[old]
    dropped = sorted(set(c.values) - set(ACKERMANN_KEYS) - {"type", "rear_wheel", "front_steer"})
    unset = [k for k in ("wheelbase", "traction_wheel_radius") if k not in params]
    choices.append(
        f"{_where(c)}: `{c.name}` (ackermann_steering_controller/AckermannSteeringController) "
        "became bicycle_steering_controller/BicycleSteeringController: ROS 1's controller drives "
        "one rear wheel and one steering joint (a bicycle model), which is what Jazzy's "
        "bicycle controller does; Jazzy's ackermann_steering_controller needs two traction and "
        "two steering joints. wheel_separation_h became wheelbase, wheel_radius "
        "traction_wheel_radius, cmd_vel_timeout reference_timeout. Its command is now "
        f"/{c.name}/reference (geometry_msgs/msg/TwistStamped) instead of /{c.name}/cmd_vel."
        + (f" Set {' and '.join(unset)} (ROS 1 read them from the URDF; Jazzy does not)."
           if unset else "")
        + (f" Not carried over: {', '.join(dropped)}." if dropped else ""))
    return Controller(c.name, "bicycle_steering_controller/BicycleSteeringController", params,
                      {rear: "velocity", steer: "position"})


MAPPINGS = {
    "effort_controllers/JointPositionController": _position_pid("effort"),
    "velocity_controllers/JointPositionController": _position_pid("velocity"),
    "effort_controllers/JointVelocityController": _velocity_pid,
    "effort_controllers/JointEffortController":
        _forward("effort_controllers/JointGroupEffortController", "effort", group=False),
    "velocity_controllers/JointVelocityController":
        _forward("velocity_controllers/JointGroupVelocityController", "velocity", group=False),
    "position_controllers/JointPositionController":
        _forward("position_controllers/JointGroupPositionController", "position", group=False),
    "effort_controllers/JointGroupEffortController":
        _forward("effort_controllers/JointGroupEffortController", "effort", group=True),
    "velocity_controllers/JointGroupVelocityController":
        _forward("velocity_controllers/JointGroupVelocityController", "velocity", group=True),
    "position_controllers/JointGroupPositionController":
        _forward("position_controllers/JointGroupPositionController", "position", group=True),
    "effort_controllers/JointGroupPositionController": _group_position_pid,
    "effort_controllers/JointTrajectoryController": _trajectory("effort"),
    "velocity_controllers/JointTrajectoryController": _trajectory("velocity"),
    "position_controllers/JointTrajectoryController": _trajectory("position"),
    "ackermann_steering_controller/AckermannSteeringController": _ackermann,
}

EFFORT_GROUP = "effort_controller"


def _effort_group(names: list[str], result: Plan) -> Controller:
    name, n = EFFORT_GROUP, 1
    while name in result.names:
        n += 1
        name = f"{EFFORT_GROUP}_{n}"
    result.choices.append(
        f"--effort-joints: {', '.join(names)} got an `effort` command interface and are driven "
        f"together by `{name}` (effort_controllers/JointGroupEffortController): publish one "
        f"effort per joint, in this order, as a std_msgs/msg/Float64MultiArray on /{name}/commands.")
    return Controller(name, "effort_controllers/JointGroupEffortController",
                      {"joints": list(names)}, {j: "effort" for j in names})


class Conflict(Exception):
    """Two controllers claim the same joint's command interface."""


def _check_claims(result: Plan) -> None:
    owner: dict[str, str] = {}
    for c in result.controllers:
        for joint in c.commands:
            if joint in owner:
                raise Conflict(f"{joint} is driven by both `{owner[joint]}` and `{c.name}`; "
                               "ros2_control lets one active controller command a joint")
            owner[joint] = c.name


# -- writing ------------------------------------------------------------------------------
def yaml_text(result: Plan, package: str, added: list[str] = ()) -> str:
    """config/controllers.yaml: the controller manager's section, then one per controller.
    `added`: the controllers the port gave a package that commands no joint."""
    manager: dict = {"update_rate": result.update_rate}
    for c in result.controllers:
        manager[c.name] = {"type": c.type}
    document: dict = {"controller_manager": {"ros__parameters": manager}}
    for c in result.controllers:
        if c.parameters:
            document[c.name] = {"ros__parameters": c.parameters}
    head = [f"# {package}'s controllers for ROS 2 Jazzy (ros2_control), written by sw2sim port",
            "# from " + (", ".join(result.sources) if result.sources else
                         "no ROS 1 controller configuration") + ".",
            *([f"# {', '.join(added)}: added, as the package commands no joint "
               "(sw2sim port --no-controllers leaves them out)."] if added else []),
            "# The gz_ros2_control plugin in urdf/ reads this file; the launch file's spawner "
            "starts each controller.", ""]
    body = []
    for key, value in document.items():
        body.append(yaml.safe_dump({key: value}, sort_keys=False, default_flow_style=None,
                                   width=100).rstrip())
    return "\n".join(head) + "\n" + "\n\n".join(body) + "\n"
