"""The ros2_controllers (Jazzy) the stand-in runs, without ROS: each reads the joints'
state, keeps what its topics sent, and writes its command interfaces at every update of
the controller manager. sw2sim.ros2.node connects them to rclpy.

- joint_state_broadcaster/JointStateBroadcaster: the joints' state interfaces.
- joint_trajectory_controller/JointTrajectoryController: a JointTrajectory on
  `~/joint_trajectory` replaces the current one. It starts at the message's stamp (or at
  the first update, stamp 0) from the state the joints are in then; between two points
  the reference is interpolated as JTC's `splines` method does: linearly for points
  with positions only (the velocity being the slope), cubic with velocities, quintic
  with accelerations; after the last point it holds it. On activation it holds the
  current position. With a single `effort` (or `velocity`) command interface each joint
  has a PID (control_toolbox) on the position error and the velocity error, plus
  `ff_velocity_scale` times the reference's velocity; a `position` interface gets the
  reference's position. `~/controller_state` is a JointTrajectoryControllerState.
- forward_command_controller's JointGroupEffortController, JointGroupVelocityController
  and JointGroupPositionController: `~/commands` (Float64MultiArray, one value per joint)
  written to the interface as they are.
- pid_controller/PidController: `~/reference` (MultiDOFCommand: values, and values_dot
  when `reference_and_state_interfaces` has two), a PID per degree of freedom from the
  first state interface's error (and the second's, else the error's change), written to
  `command_interface`; `~/controller_state` is a MultiDOFStateStamped.

An effort a PID computes is kept as a law affine in the joint's position and velocity
(sw2sim.ros2.hardware), with the integral term updated once per controller update.
Not simulated: goal tolerances, the action server, partial goals unless
`allow_partial_joints_goal`, speed scaling, chained controllers.
"""

from __future__ import annotations

import math
import threading

from .trajectory import Trajectory

JSB = "joint_state_broadcaster/JointStateBroadcaster"
JTC = "joint_trajectory_controller/JointTrajectoryController"
FORWARD = {"effort_controllers/JointGroupEffortController": "effort",
           "velocity_controllers/JointGroupVelocityController": "velocity",
           "position_controllers/JointGroupPositionController": "position",
           "forward_command_controller/ForwardCommandController": None}
PID = "pid_controller/PidController"
SUPPORTED = (JSB, JTC, PID, *FORWARD)


class ConfigError(ValueError):
    """A controller's parameters cannot be used (the message says which and why)."""


def _gains(params: dict, joint: str) -> dict:
    gains = params.get("gains") or {}
    found = gains.get(joint)
    if isinstance(found, dict):
        return found
    # the flattened form: gains.<joint>.p
    return {k.split(".", 2)[2]: v for k, v in params.items()
            if isinstance(k, str) and k.startswith(f"gains.{joint}.")}


class Pid:
    """control_toolbox's Pid (Jazzy, `compute_command(error, error_dot, dt)`), with its
    proportional and derivative terms returned as parts of an affine law."""

    def __init__(self, gains: dict):
        f = lambda key, default: float(gains.get(key, default))  # noqa: E731
        self.p, self.i, self.d = f("p", 0.0), f("i", 0.0), f("d", 0.0)
        i_clamp = f("i_clamp", math.inf)
        self.i_max = f("i_clamp_max", math.inf)
        self.i_min = f("i_clamp_min", -math.inf)
        if not math.isfinite(self.i_max):
            self.i_max = abs(i_clamp)
        if not math.isfinite(self.i_min):
            self.i_min = -abs(i_clamp)
        self.u_max, self.u_min = f("u_clamp_max", math.inf), f("u_clamp_min", -math.inf)
        self.strategy = str(gains.get("antiwindup_strategy", "legacy"))
        self.legacy_antiwindup = bool(gains.get("antiwindup", False))
        self.deadband = f("error_deadband", 0.0)
        self.i_term = 0.0
        self.last_error = 0.0

    def reset(self) -> None:
        self.i_term, self.last_error = 0.0, 0.0

    def integrate(self, error: float, dt: float) -> float:
        """One update of the integral term on this update's error; the term to add."""
        if dt <= 0 or not math.isfinite(error):
            return self._clamped_i()
        if abs(error) > self.deadband:
            step = self.i * dt * error
            if self.strategy == "legacy":
                self.i_term += step
                if self.legacy_antiwindup:
                    self.i_term = min(max(self.i_term, self.i_min), self.i_max)
            else:   # none, conditional integration and back calculation: integrate, clamp
                self.i_term += step
        if self.strategy != "legacy":
            self.i_term = min(max(self.i_term, self.i_min), self.i_max)
        return self._clamped_i()

    def _clamped_i(self) -> float:
        if self.strategy == "legacy" and not self.legacy_antiwindup:
            return min(max(self.i_term, self.i_min), self.i_max)
        return self.i_term

    def law(self, reference: float, reference_dot: float, error: float, dt: float,
            feedforward: float = 0.0):
        """p (reference - q) + d (reference_dot - v) + i_term + feedforward, as
        (c0, cq, cv) in the joint's q and v; the integral updated with `error`."""
        i_term = self.integrate(error, dt)
        return (self.p * reference + self.d * reference_dot + i_term + feedforward,
                -self.p, -self.d)

    def clamp(self, law, q: float, v: float):
        from ..ros.hardware import saturate
        if math.isfinite(self.u_min) or math.isfinite(self.u_max):
            return saturate(law, self.u_min, self.u_max, q, v)
        return law


def value(law, q: float, v: float) -> float:
    if isinstance(law, tuple):
        return law[0] + law[1] * q + law[2] * v
    return float(law)


class Controller:
    """One controller: `update` returns {joint: {interface: number or Law}}."""

    kind = ""
    state_topic = None

    def __init__(self, name: str, kind: str, params: dict, joints: dict):
        self.name, self.kind, self.params = name, kind, params
        self.lock = threading.Lock()
        self.available = joints    # joint -> JointInterfaces of the URDF's ros2_control
        self.output: dict[str, dict] = {}

    def check_joints(self, names) -> list[str]:
        names = [str(n) for n in (names or [])]
        if not names:
            raise ConfigError(f"{self.name}: no joints given")
        unknown = [n for n in names if n not in self.available]
        if unknown:
            raise ConfigError(f"{self.name}: joint(s) {', '.join(unknown)} not in the URDF's "
                              "<ros2_control> block")
        return names

    def activate(self, state) -> None:
        pass

    def update(self, now: float, period: float, state) -> dict:
        return {}


class JointStateBroadcaster(Controller):
    def update(self, now, period, state):
        return {}


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
        # the interfaces keep what the hardware holds: 0 for effort and velocity (gz_system
        # starts them so), the current position for position
        self.values = [state[j][0] if self.interface == "position" else 0.0 for j in self.joints]

    def command(self, data) -> None:
        data = list(data)
        if len(data) != len(self.joints):
            self.errors.append(f"command size ({len(data)}) does not match number of "
                               f"interfaces ({len(self.joints)})")
            return
        with self.lock:
            self.values = [float(x) for x in data]

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
        self.closed_loop = only in (["effort"], ["velocity"]) and not params.get("open_loop_control")
        self.pids = {j: Pid(_gains(params, j)) for j in self.joints} if self.closed_loop else {}
        self.ff = {j: float(_gains(params, j).get("ff_velocity_scale", 0.0)) for j in self.joints}
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
                pid = self.pids[joint]
                law = pid.law(desired[0][k], desired[1][k], error, period,
                              feedforward=following[1][k] * self.ff[joint])
                law = pid.clamp(law, q, v)
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


class PidController(Controller):
    def __init__(self, name, kind, params, joints):
        super().__init__(name, kind, params, joints)
        self.joints = self.check_joints(params.get("dof_names"))
        self.interface = str(params.get("command_interface", ""))
        self.measured = [str(i) for i in params.get("reference_and_state_interfaces") or []]
        if not self.interface or not 1 <= len(self.measured) <= 2:
            raise ConfigError(f"{name}: command_interface and one or two "
                              "reference_and_state_interfaces must be given")
        for joint in self.joints:
            if self.interface not in self.available[joint].command:
                raise ConfigError(f"{name}: joint {joint} has no {self.interface!r} command "
                                  "interface in the URDF's <ros2_control> block")
        self.pids = {j: Pid(_gains(params, j)) for j in self.joints}
        self.feedforward = {j: float(_gains(params, j).get("feedforward_gain", 0.0))
                            for j in self.joints}
        self.reference = {j: [math.nan, math.nan] for j in self.joints}
        self.incoming = None
        self.last = {}
        self.errors: list[str] = []

    def _measure(self, joint, state):
        q, v = state[joint]
        pick = {"position": (q, v), "velocity": (v, math.nan), "effort": (math.nan, math.nan)}
        first = pick.get(self.measured[0], (math.nan, math.nan))
        second = pick.get(self.measured[1])[0] if len(self.measured) == 2 and \
            self.measured[1] in pick else math.nan
        return first[0], second

    def activate(self, state):
        if self.params.get("set_current_state_as_first_setpoint", True):
            for joint in self.joints:
                self.reference[joint] = list(self._measure(joint, state))
        for pid in self.pids.values():
            pid.reset()

    def receive(self, names, values, values_dot) -> None:
        names, values, values_dot = list(names), list(values), list(values_dot)
        if not names and len(values) == len(self.joints):
            names = list(self.joints)
        if len(names) != len(self.joints) or len(values) != len(self.joints) or \
                any(n not in self.joints for n in names):
            self.errors.append(f"size of input data names ({len(names)}) and/or values "
                               f"({len(values)}) is not matching the expected size "
                               f"({len(self.joints)})")
            return
        with self.lock:
            self.incoming = {n: (values[k], values_dot[k] if k < len(values_dot) else math.nan)
                             for k, n in enumerate(names)}

    def update(self, now, period, state):
        with self.lock:
            incoming, self.incoming = self.incoming, None
        if incoming:
            for joint, (x, x_dot) in incoming.items():
                if not math.isnan(x):
                    self.reference[joint] = [x, x_dot if len(self.measured) == 2 else math.nan]
        output = {}
        for joint in self.joints:
            q, v = state[joint]
            ref, ref_dot = self.reference[joint]
            measured, measured_dot = self._measure(joint, state)
            if not (math.isfinite(ref) and math.isfinite(measured)):
                continue
            pid = self.pids[joint]
            error = ref - measured
            ff = ref * self.feedforward[joint] if len(self.measured) == 1 else \
                (ref_dot if math.isfinite(ref_dot) else 0.0) * self.feedforward[joint]
            on_position = self.measured[0] == "position"
            if len(self.measured) == 2 and math.isfinite(ref_dot) and math.isfinite(measured_dot):
                if on_position:   # the error and its rate are affine in q and v
                    law = pid.law(ref, ref_dot, error, period, feedforward=ff)
                else:             # a velocity error: its own rate is not a joint state
                    i_term = pid.integrate(error, period)
                    law = (pid.p * ref + pid.d * (ref_dot - measured_dot) + i_term + ff,
                           0.0, -pid.p)
            else:
                # the error's rate from the last update, as compute_command(error, dt) does
                rate = (error - pid.last_error) / period if period > 0 else 0.0
                pid.last_error = error
                i_term = pid.integrate(error, period)
                law = (pid.p * error + pid.d * rate + i_term + ff, 0.0, 0.0)
            law = pid.clamp(law, q, v)
            output[joint] = {self.interface: law if self.interface == "effort"
                             else value(law, q, v)}
            self.last[joint] = (ref, measured, measured_dot, error,
                                (ref_dot - measured_dot) if len(self.measured) == 2 else 0.0,
                                period, value(law, q, v))
        return output

    def state_message(self, stamp, state):
        from control_msgs.msg import MultiDOFStateStamped, SingleDOFState
        message = MultiDOFStateStamped()
        message.header.stamp = stamp
        for joint in self.joints:
            ref, measured, measured_dot, error, error_dot, step, out = self.last.get(
                joint, (math.nan,) * 7)
            message.dof_states.append(SingleDOFState(
                name=joint, reference=float(ref), feedback=float(measured),
                feedback_dot=float(measured_dot if len(self.measured) == 2 else 0.0),
                error=float(error), error_dot=float(error_dot), time_step=float(step),
                output=float(out)))
        return message


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
