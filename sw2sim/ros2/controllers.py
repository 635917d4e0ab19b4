"""The ros2_controllers (Jazzy) the stand-in runs, without ROS: each reads the joints'
state, keeps what its topics sent, and, while active, writes its command interfaces at
every update of the controller manager (sw2sim.ros2.manager activates and deactivates
them; what an inactive one receives is dropped). sw2sim.ros2.node connects them to rclpy.

- joint_state_broadcaster/JointStateBroadcaster: the joints' state interfaces.
- joint_trajectory_controller/JointTrajectoryController: a JointTrajectory on
  `~/joint_trajectory`, or a FollowJointTrajectory goal (sw2sim.ros2.action), replaces
  the current one once it passes the controller's checks (sw2sim.ros2.trajectory; a
  refused one is logged with upstream's line, and NaN is refused where upstream would
  command it; points outside the URDF's position limits are taken, and said once). It
  starts at the message's stamp (or at the first update, stamp 0) from the state the
  joints are in then; between two points
  the reference is interpolated as JTC's `splines` method does: linearly for points
  with positions only (the velocity being the slope), cubic with velocities, quintic
  with accelerations; after the last point it holds it. On activation it holds the
  current position. With a lone `effort` (or `velocity`) command interface each joint
  has a PID (sw2sim.ros2.pid, control_toolbox's) on the position and velocity errors,
  plus `ff_velocity_scale` times the next point's velocity outside its clamp; on
  deactivation it zeroes its velocity and effort interfaces. A `position` interface gets
  the reference's position. `~/controller_state` is a JointTrajectoryControllerState.
  The YAML's `constraints` (path and goal tolerances, goal_time,
  stopped_velocity_tolerance) are checked as upstream checks them, for the action's
  goals and the topic's trajectories alike; a violation holds the joints.
- forward_command_controller's JointGroupEffortController, JointGroupVelocityController
  and JointGroupPositionController: `~/commands` (Float64MultiArray, one value per joint)
  written to the interface as they are (a non-finite one dropped; the interfaces keep
  their value until the first after activation). pid_controller: sw2sim.ros2.pid.

An effort a PID computes is kept as a law affine in the joint's position and velocity
(sw2sim.ros2.hardware), its integral term updated once per controller update.
Not simulated: the trajectory's effort feed-forward, angle wraparound of continuous
joints, decelerate_on_cancel, interpolate_from_desired_state, speed scaling, the
query_state service, chained controllers.

It is over 500 lines because joint_trajectory_controller's update (tolerances, goal
endings, partial goals) reads best as one class beside the others it is compared with.
"""

from __future__ import annotations

import math

from . import trajectory
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
        self.nonzero_end = bool(params.get("allow_nonzero_velocity_at_trajectory_end", False))
        try:
            self.defaults = trajectory.default_tolerances(params, self.joints,
                                                          f"{name}: constraints")
            self.cmd_timeout = float(params.get("cmd_timeout", 0.0))
            self.monitor_rate = float(params.get("action_monitor_rate", 20.0))
        except (TypeError, ValueError) as exc:
            raise ConfigError(str(exc)) from None
        if self.monitor_rate < 0.1:
            raise ConfigError(f"{name}: action_monitor_rate ({self.monitor_rate}) must be "
                              ">= 0.1")
        self.tolerances = self.defaults          # active_tolerances_: a goal's stay on
        self.pending: Trajectory | None = None
        self.trajectory: Trajectory | None = None
        self.goal: trajectory.Goal | None = None  # the action's active goal
        self.holding = True                      # rt_is_holding_: no tolerance checks
        self.current = None                      # (positions, velocities) at the last update
        self.reference = self.error = None
        self.last_output: dict = {}
        self.errors: list[str] = []
        self.warnings: list[str] = []
        # the URDF's position limits, joint -> (lower, upper) (sw2sim.ros2.action sets
        # them), and where the controller's log lines go: say(level, text); without it
        # they wait in errors and warnings
        self.position_limits: dict[str, tuple[float, float]] = {}
        self.say = None

    def _log(self, level: str, text: str) -> None:
        if self.say is not None:
            self.say(level, text)
        else:
            (self.errors if level == "error" else self.warnings).append(text)

    def activate(self, state):
        # hold the current position
        positions = [state[j][0] for j in self.joints]
        self.current = (positions, [state[j][1] for j in self.joints])
        if 0 < self.cmd_timeout <= self.defaults.goal_time:
            self._log("warn", f"Command timeout must be higher than goal_time tolerance "
                              f"({self.cmd_timeout:f} vs. {self.defaults.goal_time:f})")
            self.cmd_timeout = 0.0
        with self.lock:
            self.pending = self._hold()
            self.holding = True
            self.active = True
        for pid in self.pids.values():
            pid.reset()

    def deactivate(self):
        """on_deactivate: the velocity and effort interfaces set to 0 (the position one
        keeps its value), the trajectory dropped, the action's goal aborted."""
        with self.lock:
            self.pending = None
            self.active = False
            goal, self.goal = self.goal, None
        if goal is not None:
            goal.finish("aborted", trajectory.INVALID_GOAL,
                        "Current goal cancelled during deactivate transition.")
        self.trajectory = None
        return {j: {i: 0.0 for i in self.command_interfaces if i in ("velocity", "effort")}
                for j in self.joints}

    def command_interface_names(self):
        return [f"{j}/{i}" for j in self.joints for i in self.command_interfaces]

    def state_interface_names(self, available):
        return [f"{j}/{i}" for j in self.joints for i in self.state_interfaces]

    def refusal(self, names, stamp: float, points, now: float | None = None) -> str | None:
        """Why the controller refuses a trajectory (the line it logs), or None."""
        return trajectory.refusal(names, stamp, points, joints=self.joints,
                                  partial=self.partial, nonzero_end=self.nonzero_end,
                                  effort="effort" in self.command_interfaces, now=now)

    def receive(self, names, stamp: float, points, now: float | None = None) -> bool:
        """A JointTrajectory on ~/joint_trajectory: joint names, header stamp (s, 0 =
        now), points as (time_from_start, positions, velocities, accelerations[, effort]);
        `now`, the simulated time, for the check of a stamped trajectory's end. It
        replaces the trajectory being followed (not the action's goal, which ends when
        this trajectory does, as upstream's); a refused one is logged and dropped."""
        points = [(*p, []) if len(p) == 4 else p for p in points]
        problem = self.refusal(names, stamp, points, now)
        if problem:
            self._log("error", problem)
            return False
        if not self.active:
            self._log("warn", "the controller is not active: trajectory dropped")
            return False
        self._notes("the trajectory on ~/joint_trajectory", names, points)
        with self.lock:
            self.pending = self._trajectory(names, stamp, points)
            self.holding = False
        return True

    # -- the action (sw2sim.ros2.action serves it) ------------------------------------
    def goal_refusal(self, names, stamp: float, points, now: float | None = None):
        """goal_received_callback: why a goal is rejected, or None to accept it."""
        if not self.active:
            return "Can't accept new action goals. Controller is not running."
        return self.refusal(names, stamp, [(*p, []) if len(p) == 4 else p for p in points], now)

    def start_goal(self, goal: trajectory.Goal, names, stamp: float, points,
                   tolerances: trajectory.Tolerances) -> None:
        """goal_accepted_callback: the active goal, if any, is aborted (INVALID_GOAL,
        preempted), and this one's trajectory and tolerances replace the current ones."""
        points = [(*p, []) if len(p) == 4 else p for p in points]
        with self.lock:
            old, self.goal = self.goal, None
        if old is not None:
            old.finish("aborted", trajectory.INVALID_GOAL,
                       "Current goal preempted by new incoming action.")
        self._notes("the goal", names, points)
        with self.lock:
            self.pending = self._trajectory(names, stamp, points)
            self.holding = False
            self.goal = goal
            self.tolerances = tolerances

    def cancel_goal(self, goal: trajectory.Goal) -> bool:
        """goal_cancelled_callback: the active goal ends canceled (an empty result) and
        the joints hold where they were at the last update; any other goal is left."""
        with self.lock:
            if self.goal is not goal:
                return False
            self.goal = None
            self.pending = self._hold()
            self.holding = True
        goal.finish("canceled")
        return True

    # -- trajectories ------------------------------------------------------------------
    def _hold(self, point=None) -> Trajectory:
        """set_hold_position: a trajectory of one point at time 0, the positions of the
        last update (with zero velocities for a velocity command interface); or
        set_success_trajectory_point: the given point so."""
        if point is not None:
            return Trajectory(None, [0.0], [point])
        positions = list(self.current[0]) if self.current else [0.0] * len(self.joints)
        moving = "velocity" in self.command_interfaces or \
            "acceleration" in self.command_interfaces
        return Trajectory(None, [0.0], [(positions, [0.0] * len(positions) if moving else None,
                                         None)])

    def _trajectory(self, names, stamp: float, points) -> Trajectory:
        """The message's points in the controller's joint order; a joint a partial goal
        leaves out keeps its position (filled in at the update that takes it, as
        fill_partial_goal does) with zero velocity and acceleration."""
        names = list(names)
        order = [names.index(j) if j in names else None for j in self.joints]

        def pick(values, missing):
            if not values:
                return None
            return [float(values[k]) if k is not None else missing for k in order]
        converted = [(pick(positions, None), pick(velocities, 0.0), pick(accelerations, 0.0))
                     for _, positions, velocities, accelerations, _ in points]
        return Trajectory(stamp or None, [float(p[0]) for p in points], converted)

    def _notes(self, what: str, names, points) -> None:
        """Once per trajectory, what the stand-in takes but does not do as upstream, and
        the joints whose points lie outside their URDF position limits.
        joint_trajectory_controller 4.42.1 does not check a trajectory against them (it
        reads the URDF for continuous joints and velocity limits only): it sends it on,
        and Gazebo's physics stops the joint at its limit."""
        if any(p[4] for p in points):
            self._log("warn", f"{what} has effort values: joint_trajectory_controller adds "
                              "them to its command as a feed-forward; the stand-in leaves "
                              "them out")
        outside = []
        for k, name in enumerate(names):
            lower, upper = self.position_limits.get(name, (-math.inf, math.inf))
            for i, (_, positions, *_) in enumerate(points):
                if k < len(positions) and not lower <= positions[k] <= upper:
                    outside.append(f"{name} to {positions[k]:g} at points[{i}], outside its "
                                   f"URDF limits [{lower:g}, {upper:g}]")
                    break
        if outside:
            self._log("warn", f"{what} sends {'; '.join(outside)}. joint_trajectory_controller "
                              "does not check a trajectory against the joint limits: the "
                              "joint stops at its limit")

    def update(self, now, period, state):
        """One update, as JointTrajectoryController::update: take a new trajectory, sample
        it now (the reference) and one period on (the command), check the tolerances,
        write the commands, and end the action's goal when it is reached or violated."""
        q_now = [state[j][0] for j in self.joints]
        v_now = [state[j][1] for j in self.joints]
        self.current = (q_now, v_now)
        with self.lock:
            pending, self.pending = self.pending, None
            goal, holding, tolerances = self.goal, self.holding, self.tolerances
        first = pending is not None
        if pending is not None:
            if pending.start is None:
                pending.start = now
            # joints a partial goal leaves out keep their current position command, else
            # their position
            for positions, _, _ in pending.points:
                for k, x in enumerate(positions):
                    if x is None:
                        last = self.last_output.get(self.joints[k], {}).get("position")
                        positions[k] = float(last) if isinstance(last, (int, float)) and \
                            math.isfinite(last) else q_now[k]
            pending.before = (now, q_now, v_now if "velocity" in self.state_interfaces else None)
            self.trajectory = pending
        if self.trajectory is None:
            return {}
        path = self.trajectory
        desired = path.sample(now)
        following = path.sample(now + period)
        self.reference = desired
        end = path.start + path.times[-1]
        before_last = now + period < end - 1e-9   # the command's sample is not past the end
        late = now - end                          # time past the last point
        if not before_last and not holding and self.cmd_timeout > 0 and late > self.cmd_timeout:
            self._log("warn", "Aborted due to command timeout")
            holding = self._replace(self._hold(), goal)
        velocity_error = "velocity" in self.state_interfaces and (
            "velocity" in self.command_interfaces or "effort" in self.command_interfaces)
        violated = outside = False
        in_time = True
        errors_p, errors_v = [], []
        for k, joint in enumerate(self.joints):
            error = (desired[0][k] - q_now[k],
                     desired[1][k] - v_now[k] if velocity_error else 0.0, 0.0)
            errors_p.append(error[0])
            errors_v.append(error[1])
            if holding:
                continue
            if before_last or first:
                bad = trajectory.violations(error, tolerances.path[k])
                if bad:
                    violated = True
                    self._log("error", f"State tolerances failed for joint {joint}: "
                                       f"{'; '.join(bad)}")
            if not before_last:
                bad = trajectory.violations(error, tolerances.goal[k])
                if bad:
                    outside = True
                    if tolerances.goal_time != 0.0 and late > tolerances.goal_time:
                        in_time = False
                        self._log("error", f"State tolerances failed for joint {joint}: "
                                           f"{'; '.join(bad)}")
        self.error = (errors_p, errors_v)
        if violated or not in_time:
            # no new command this update: the interfaces keep their values
            output = {joint: {i: value(law, *state[joint]) for i, law in commands.items()}
                      for joint, commands in self.last_output.items()}
        else:
            output = self._commands(desired, following, period, state)
        self.last_output = output
        if goal is not None:
            goal.report(now, self._feedback(now, path, desired, state))
            if violated:
                self._end(goal, "aborted", trajectory.PATH_TOLERANCE_VIOLATED,
                          "Aborted due to path tolerance violation",
                          ("warn", "Aborted due to state tolerance violation"), self._hold())
            elif not before_last and not outside:
                self._end(goal, "succeeded", trajectory.SUCCESSFUL, "Goal successfully reached!",
                          ("info", "Goal reached, success!"), self._hold(path.points[-1]))
            elif not before_last and not in_time:
                text = f"Aborted due to goal_time_tolerance exceeding by {late:f} seconds"
                self._end(goal, "aborted", trajectory.GOAL_TOLERANCE_VIOLATED, text,
                          ("warn", text), self._hold())
        elif violated:
            self._log("error", "Holding position due to state tolerance violation")
            self._replace(self._hold(), None)
        elif not before_last and not in_time:
            self._log("error", "Exceeded goal_time_tolerance: holding position...")
            self._replace(self._hold(), None)
        return output

    def _replace(self, hold: Trajectory, goal) -> bool:
        """The hold trajectory for the next update, unless a newer trajectory or goal
        came in the meantime; True (holding)."""
        with self.lock:
            if self.pending is None and self.goal is goal:
                self.pending = hold
                self.holding = True
        return True

    def _end(self, goal, outcome, code, text, log, hold) -> None:
        with self.lock:
            mine = self.goal is goal
            if mine:
                self.goal = None
                if self.pending is None:
                    self.pending = hold
                    self.holding = True
        if mine:
            self._log(*log)
            goal.finish(outcome, code, text)

    def _commands(self, desired, following, period, state) -> dict:
        output = {}
        for k, joint in enumerate(self.joints):
            q, v = state[joint]
            commands = {}
            if self.closed_loop:
                # ff_velocity_scale times the next command's velocity, plus the PID on the
                # position and velocity errors (its u_clamp applies to the PID alone)
                pid = self.pids[joint]
                pid.command(desired[0][k] - q, desired[1][k] - v, period)
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
        return output

    def _feedback(self, now, path, desired, state) -> dict:
        """The action's feedback: desired, actual and error as JointTrajectoryPoints
        (lists per field; empty where the controller has no such interface)."""
        with_velocity = "velocity" in self.state_interfaces
        efforts = [value(self.last_output.get(j, {}).get("effort", math.nan), *state[j])
                   for j in self.joints] if "effort" in self.command_interfaces else []
        return {
            "time": now, "joint_names": list(self.joints),
            "desired": {"positions": list(desired[0]), "velocities": list(desired[1]),
                        "accelerations": list(desired[2]), "time_from_start": now - path.start},
            "actual": {"positions": list(self.current[0]),
                       "velocities": list(self.current[1]) if with_velocity else [],
                       "effort": efforts, "time_from_start": now - path.start},
            "error": {"positions": list(self.error[0]),
                      "velocities": list(self.error[1]) if with_velocity else []},
        }

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
