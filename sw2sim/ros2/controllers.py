"""The ros2_controllers (Jazzy) the stand-in runs, without ROS: each reads the joints'
state, keeps what its topics sent, and, while active, writes its command interfaces at
every update of the controller manager (sw2sim.ros2.manager activates and deactivates
them; what an inactive one receives is dropped). sw2sim.ros2.node connects them to rclpy.

- joint_state_broadcaster/JointStateBroadcaster: the joints' state interfaces.
- joint_trajectory_controller/JointTrajectoryController: a JointTrajectory on
  `~/joint_trajectory` replaces the current one. It starts at the message's stamp (or at
  the first update, stamp 0) from the state the joints are in then; between two points
  the reference is interpolated as JTC's `splines` method does: linearly for points
  with positions only (the velocity being the slope), cubic with velocities, quintic
  with accelerations; after the last point it holds it. On activation it holds the
  current position. With a lone `effort` (or `velocity`) command interface each joint
  has a PID (sw2sim.ros2.pid, control_toolbox's) on the position and velocity errors,
  plus `ff_velocity_scale` times the next point's velocity outside its clamp; on
  deactivation it zeroes its velocity and effort interfaces. A `position` interface gets
  the reference's position. `~/controller_state` is a JointTrajectoryControllerState.
- forward_command_controller's JointGroupEffortController, JointGroupVelocityController
  and JointGroupPositionController: `~/commands` (Float64MultiArray, one value per joint)
  written to the interface as they are (a non-finite one dropped; the interfaces keep
  their value until the first after activation). pid_controller: sw2sim.ros2.pid.

An effort a PID computes is kept as a law affine in the joint's position and velocity
(sw2sim.ros2.hardware), its integral term updated once per controller update.
Not simulated: goal tolerances, the action server, partial goals unless
`allow_partial_joints_goal`, speed scaling, chained controllers.
"""

from __future__ import annotations

import math

from .controller_base import ConfigError, Controller, gains_of, value
from .pid import Pid, PidController
from .trajectory import Trajectory

JSB = "joint_state_broadcaster/JointStateBroadcaster"
JTC = "joint_trajectory_controller/JointTrajectoryController"
FORWARD = {"effort_controllers/JointGroupEffortController": "effort",
           "velocity_controllers/JointGroupVelocityController": "velocity",
           "position_controllers/JointGroupPositionController": "position",
           "forward_command_controller/ForwardCommandController": None}
PID = "pid_controller/PidController"
SUPPORTED = (JSB, JTC, PID, *FORWARD)


class JointStateBroadcaster(Controller):
    """Publishes every state interface when `joints` or `interfaces` is empty (ALL),
    else the named ones."""

    def update(self, now, period, state):
        return {}

    def state_interface_names(self, available):
        joints = [str(j) for j in self.params.get("joints") or []]
        interfaces = [str(i) for i in self.params.get("interfaces") or []]
        if not joints or not interfaces:
            return list(available)
        return [f"{j}/{i}" for j in joints for i in interfaces]


class Forward(Controller):
    def __init__(self, name, kind, params, joints):
        super().__init__(name, kind, params, joints)
        self.joints = self.check_joints(params.get("joints"))
        self.interface = FORWARD[kind] or str(params.get("interface_name", ""))
        for joint in self.joints:
            if self.interface not in self.available[joint].command:
                raise ConfigError(f"{name}: joint {joint} has no {self.interface!r} command "
                                  "interface in the URDF's <ros2_control> block")
        self.values: list[float] | None = None
        self.errors: list[str] = []

    def activate(self, state):
        # a command that came while inactive is dropped; until the next one the interfaces
        # keep what the hardware holds (gz_system starts them at 0, or at initial_value)
        with self.lock:
            self.values = None

    def deactivate(self):
        with self.lock:
            self.values = None
        return {}

    def command(self, data) -> None:
        data = list(data)
        if not all(math.isfinite(x) for x in data):
            self.errors.append("Non-finite value received. Dropping message")
            return
        if len(data) != len(self.joints):
            self.errors.append(f"command size ({len(data)}) does not match number of "
                               f"interfaces ({len(self.joints)})")
            return
        with self.lock:
            self.values = [float(x) for x in data]

    def command_interface_names(self):
        return [f"{j}/{self.interface}" for j in self.joints]

    def update(self, now, period, state):
        with self.lock:
            values = list(self.values or [])
        return {j: {self.interface: x} for j, x in zip(self.joints, values)}


class JointTrajectory(Controller):
    def __init__(self, name, kind, params, joints):
        super().__init__(name, kind, params, joints)
        self.joints = self.check_joints(params.get("joints"))
        self.command_interfaces = [str(i) for i in params.get("command_interfaces") or []]
        self.state_interfaces = [str(i) for i in params.get("state_interfaces") or []]
        if not self.command_interfaces or not self.state_interfaces:
            raise ConfigError(f"{name}: command_interfaces and state_interfaces must be given")
        for joint in self.joints:
            for interface in self.command_interfaces:
                if interface not in self.available[joint].command:
                    raise ConfigError(f"{name}: joint {joint} has no {interface!r} command "
                                      "interface in the URDF's <ros2_control> block")
        only = self.command_interfaces if len(self.command_interfaces) == 1 else []
        # the PID adapter: on a lone velocity interface (unless open_loop_control) or a
        # lone effort interface
        self.closed_loop = only == ["effort"] or (
            only == ["velocity"] and not params.get("open_loop_control"))
        self.pids = {j: Pid(gains_of(params, j), "jtc", f"{name}: gains.{j}")
                     for j in self.joints} if self.closed_loop else {}
        self.ff = {j: float(gains_of(params, j).get("ff_velocity_scale", 0.0)) for j in self.joints}
        self.partial = bool(params.get("allow_partial_joints_goal", False))
        self.pending: Trajectory | None = None
        self.trajectory: Trajectory | None = None
        self.reference = self.error = None
        self.last_output: dict = {}
        self.errors: list[str] = []

    def activate(self, state):
        # hold the current position
        positions = [state[j][0] for j in self.joints]
        self.pending = Trajectory(None, [0.0], [(positions, None, None)])
        for pid in self.pids.values():
            pid.reset()

    def deactivate(self):
        """on_deactivate: the velocity and effort interfaces set to 0 (the position one
        keeps its value), the trajectory dropped."""
        with self.lock:
            self.pending = None
        self.trajectory = None
        return {j: {i: 0.0 for i in self.command_interfaces if i in ("velocity", "effort")}
                for j in self.joints}

    def command_interface_names(self):
        return [f"{j}/{i}" for j in self.joints for i in self.command_interfaces]

    def state_interface_names(self, available):
        return [f"{j}/{i}" for j in self.joints for i in self.state_interfaces]

    def receive(self, names, stamp: float, points) -> None:
        """A JointTrajectory: joint names, header stamp (s, 0 = now), points as
        (time_from_start, positions, velocities, accelerations)."""
        names = list(names)
        if not points:
            self.errors.append("empty trajectory received")
            return
        if any(n not in self.joints for n in names) or len(set(names)) != len(names):
            self.errors.append(f"incoming joint names {names} are not the controller's {self.joints}")
            return
        if len(names) != len(self.joints) and not self.partial:
            self.errors.append("joints on incoming trajectory don't match the controller joints")
            return
        times = [float(t) for t, *_ in points]
        if any(b <= a for a, b in zip(times, times[1:])):
            self.errors.append("time between points is not strictly increasing")
            return
        order = [names.index(j) if j in names else None for j in self.joints]
        converted = []
        for _, positions, velocities, accelerations in points:
            if len(positions) != len(names):
                self.errors.append("a point has no position for each joint")
                return

            def pick(values):
                if not values:
                    return None
                if len(values) != len(names):
                    return None
                return [values[k] if k is not None else math.nan for k in order]
            converted.append((pick(positions), pick(velocities), pick(accelerations)))
        with self.lock:
            self.pending = Trajectory(stamp or None, times, converted)

    def update(self, now, period, state):
        with self.lock:
            pending, self.pending = self.pending, None
        if pending is not None:
            q = [state[j][0] for j in self.joints]
            v = [state[j][1] for j in self.joints]
            if pending.start is None:
                pending.start = now
            # joints a partial goal leaves out keep their current position
            for positions, _, _ in pending.points:
                for k, x in enumerate(positions):
                    if isinstance(x, float) and math.isnan(x):
                        positions[k] = q[k]
            pending.before = (now, q, v if "velocity" in self.state_interfaces else None)
            self.trajectory = pending
        if self.trajectory is None:
            return {}
        desired = self.trajectory.sample(now)
        following = self.trajectory.sample(now + period)
        self.reference = desired
        output = {}
        errors_p, errors_v = [], []
        for k, joint in enumerate(self.joints):
            q, v = state[joint]
            error = desired[0][k] - q
            errors_p.append(error)
            errors_v.append(desired[1][k] - v)
            commands = {}
            if self.closed_loop:
                # ff_velocity_scale times the next command's velocity, plus the PID on the
                # position and velocity errors (its u_clamp applies to the PID alone)
                pid = self.pids[joint]
                pid.command(error, desired[1][k] - v, period)
                law = pid.affine(pid.p * desired[0][k] + pid.d * desired[1][k], -pid.p, -pid.d,
                                 feedforward=following[1][k] * self.ff[joint])
                commands[self.command_interfaces[0]] = (
                    law if self.command_interfaces[0] == "effort" else value(law, q, v))
            else:
                if "position" in self.command_interfaces:
                    commands["position"] = following[0][k]
                if "velocity" in self.command_interfaces:
                    commands["velocity"] = following[1][k]
                if "effort" in self.command_interfaces:
                    commands["effort"] = 0.0
            output[joint] = commands
        self.error = (errors_p, errors_v)
        self.last_output = output
        return output

    def state_message(self, stamp, state):
        from control_msgs.msg import JointTrajectoryControllerState
        message = JointTrajectoryControllerState()
        message.header.stamp = stamp
        message.joint_names = list(self.joints)
        message.speed_scaling_factor = 1.0
        if self.reference is None:
            return message
        positions, velocities, accelerations = self.reference
        message.reference.positions = [float(x) for x in positions]
        message.reference.velocities = [float(x) for x in velocities]
        message.reference.accelerations = [float(x) for x in accelerations]
        message.feedback.positions = [float(state[j][0]) for j in self.joints]
        message.error.positions = [float(x) for x in self.error[0]]
        if "velocity" in self.state_interfaces:
            message.feedback.velocities = [float(state[j][1]) for j in self.joints]
            message.error.velocities = [float(x) for x in self.error[1]]
        out = {"position": [], "velocity": [], "effort": []}
        for joint in self.joints:
            q, v = state[joint]
            for interface, law in self.last_output.get(joint, {}).items():
                out[interface].append(float(value(law, q, v)))
        message.output.positions = out["position"]
        message.output.velocities = out["velocity"]
        message.output.effort = out["effort"]
        return message


CLASSES = {JSB: JointStateBroadcaster, JTC: JointTrajectory, PID: PidController,
           **{kind: Forward for kind in FORWARD}}


def create(name: str, kind: str, params: dict, joints: dict) -> Controller:
    if kind == JSB:
        return JointStateBroadcaster(name, kind, params, joints)
    if kind == JTC:
        return JointTrajectory(name, kind, params, joints)
    if kind in FORWARD:
        return Forward(name, kind, params, joints)
    if kind == PID:
        return PidController(name, kind, params, joints)
    raise ConfigError(f"{name}: type {kind} is not simulated here (these are: "
                      f"{', '.join(SUPPORTED)})")
