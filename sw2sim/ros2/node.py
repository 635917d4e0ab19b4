"""The simulation node: MuJoCo where Gazebo Sim, gz_ros2_control and robot_state_publisher
would run, as one rclpy node (named `sw2sim`) in the `sw2sim ros2` process.

It publishes, with the real ROS 2 types:
- `/clock` (rosgraph_msgs/Clock): the simulated time, CLOCK_HZ times per simulated second
  and no more often than CLOCK_HZ times per wall second (as `sw2sim ros` does, and for
  the same reason: run faster than real time, every node that follows the clock would
  otherwise spend its time reading it);
- `/robot_description` (std_msgs/String, transient local, depth 1) and `/tf_static`
  (tf2_msgs/TFMessage, transient local) once, as robot_state_publisher does; `/tf` with
  the moving joints' transforms of a joint state whose stamp is at least 50 ms past the
  last ones sent (robot_state_publisher's rule at its default 20 Hz, `_publish_tf`);
- `/joint_states` (sensor_msgs/JointState) from each active joint_state_broadcaster at
  its `update_rate` (the controller manager's by default), and each active controller's
  topics (sw2sim.ros2.controllers), its `~/controller_state` at the same rate.
No topic is published more often than CLOCK_HZ times per simulated second (the real
controllers publish their state at every update, a thousand times a second). The
controller manager's node and services are sw2sim.ros2.manager's.

The model is `sw2sim.load_package`'s, stepped at its own time step; the controller
manager updates the active controllers every `1 / update_rate` of simulated time (at
most once per step, as gz_ros2_control does), after any switch a service asked for. The
command interfaces keep the last value written (gz_system starts them at 0, or at the
state interface's `initial_value`), and at every step each joint gets what gz_system and
Gazebo Sim make of the claimed ones (sw2sim.ros2.hardware.JointCommand, then the force
laws there).
"""

from __future__ import annotations

import math
import threading
import time

import mujoco
import numpy as np

from ..ros.schedule import Schedule
from . import config as config_module
from . import controllers as ctl
from . import description, hardware
from .manager import ControllerManager

CLOCK_HZ = 100.0
TF_PUBLISH_FREQUENCY = 20.0   # robot_state_publisher's publish_frequency default
TF_INTERVAL_NS = int(1000.0 / TF_PUBLISH_FREQUENCY) * 1_000_000


class Simulation:
    """The model, the controllers and the ROS interfaces; `step` advances it."""

    def __init__(self, package, setup: config_module.Setup, node, say=print):
        from ..loader import load_package
        self.node, self.setup, self.say = node, setup, say
        self.spec = load_package(package, fixed_base=package.world_fixed)
        self.joint_names = [j for j in setup.joints]
        for name in self.joint_names:
            self.spec.add_actuator(name=f"ros2_control_{name}", target=name,
                                   trntype=mujoco.mjtTrn.mjTRN_JOINT,
                                   gaintype=mujoco.mjtGain.mjGAIN_FIXED,
                                   biastype=mujoco.mjtBias.mjBIAS_AFFINE, gainprm=[1] + [0] * 9)
        self.model = self.spec.compile()
        self.data = mujoco.MjData(self.model)
        m = self.model
        # initial_value params of the position and velocity state interfaces
        for name, joint in setup.joints.items():
            j = m.joint(name).id
            if "position" in joint.initial:
                self.data.qpos[m.jnt_qposadr[j]] = joint.initial["position"]
            if "velocity" in joint.initial:
                self.data.qvel[m.jnt_dofadr[j]] = joint.initial["velocity"]
        mujoco.mj_forward(m, self.data)
        self.lock = threading.RLock()
        self.places = {}
        # the URDF's limits as Gazebo's DART holds them (sw2sim.ros2.hardware)
        self.bounds = hardware.joint_bounds(package)
        for name, b in self.bounds.items():
            zero = [f'{k}="0"' for k in ("effort", "velocity") if getattr(b, k) == 0]
            if zero:
                say(f"sw2sim ros2: joint {name}: <limit {' '.join(zero)}> in the URDF, which "
                    "Gazebo's DART takes as it is: the joint cannot be "
                    f"{'moved' if b.velocity == 0 else 'driven'}. Enter the joint's real "
                    "limits in the exporter (or the URDF).")
        self.constrained = hardware.constrained_joints(m, self.bounds)
        for name in self.joint_names:
            j = m.joint(name).id
            self.places[name] = (int(m.jnt_qposadr[j]), int(m.jnt_dofadr[j]),
                                 m.actuator(f"ros2_control_{name}").id,
                                 self.bounds.get(name, hardware.Bounds()).effort,
                                 1.0 / max(float(m.dof_invweight0[m.jnt_dofadr[j]]), 1e-9))
        self.dt = float(m.opt.timestep)
        self.period = max(1.0 / setup.update_rate, self.dt)
        # on exact grids of simulated time, as the controller manager's loop and the
        # controllers' publishers keep them (sw2sim.ros.schedule)
        self.updates = Schedule(self.period)
        self.urdf_joints = description.joints(package.robot)
        self.controllers: dict[str, ctl.Controller] = {}   # the configured ones, by name
        # what each joint's command interfaces hold (gz_system starts them at 0, or at the
        # state interface's initial_value), and its command components (hardware.JointCommand)
        self.commands: dict[str, dict] = {
            n: {i: j.initial.get(i, 0.0) for i in j.command} for n, j in setup.joints.items()}
        self.gz = {n: hardware.JointCommand(bool(j.command), setup.hold_joints)
                   for n, j in setup.joints.items()}
        self.manager = ControllerManager(self)
        self.extra_nodes = []                 # nodes besides `node` for the executor to spin
        self.tf_published: dict[str, int] = {}   # joint -> stamp (ns) of its last /tf
        self.publishers = {}
        self.publishing: dict[str, Schedule] = {}
        self.next_clock = self.next_clock_wall = 0.0
        self.text = package.urdf.read_text(encoding="utf-8")

    # -- state ---------------------------------------------------------------------------
    def state(self) -> dict[str, tuple[float, float]]:
        d = self.data
        return {n: (float(d.qpos[p[0]]), float(d.qvel[p[1]])) for n, p in self.places.items()}

    @property
    def time(self) -> float:
        return float(self.data.time)

    # -- ROS -----------------------------------------------------------------------------
    def start(self) -> None:
        from rclpy.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy
        from rosgraph_msgs.msg import Clock
        from sensor_msgs.msg import JointState
        from std_msgs.msg import String
        from tf2_msgs.msg import TFMessage
        node = self.node
        latched = QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL,
                             reliability=ReliabilityPolicy.RELIABLE)
        self.clock = node.create_publisher(Clock, "/clock", 10)
        self.description = node.create_publisher(String, "/robot_description", latched)
        self.tf_static = node.create_publisher(TFMessage, "/tf_static", latched)
        self.tf = node.create_publisher(TFMessage, "/tf", 100)
        self.description.publish(String(data=self.text))
        stamp = self._stamp(self.time)
        fixed = [description.stamped(j, 0.0, stamp) for j in self.urdf_joints
                 if j.kind == "fixed"]
        self.tf_static.publish(TFMessage(transforms=fixed))
        for problem in self.setup.problems:
            self.say(f"sw2sim ros2: {problem}")
        # the controller manager's node and services (sw2sim.ros2.manager), then every
        # controller of the YAML loaded, configured and activated as the spawner would
        self.manager.serve(node.context)
        self.extra_nodes.append(self.manager.node)
        with self.lock:
            _, failures = self.manager.start(self.state())
        for failure in failures:
            self.say(f"sw2sim ros2: controller {failure}; not started")
        self.say(f"sw2sim ros2: {self.setup.name}: {len(self.joint_names)} joint(s) under "
                 f"ros2_control; controllers: {', '.join(self.controllers) or 'none'}")

    def _controller_topics(self, c: ctl.Controller) -> None:
        from rclpy.qos import QoSProfile, ReliabilityPolicy
        node, base = self.node, f"/{c.name}"
        if isinstance(c, ctl.JointTrajectory):
            from control_msgs.msg import JointTrajectoryControllerState
            from trajectory_msgs.msg import JointTrajectory

            from . import action

            def trajectory(message, c=c):
                c.receive(*action.from_message(message), now=self.time)
                self._report(c)
            node.create_subscription(JointTrajectory, f"{base}/joint_trajectory", trajectory, 10)
            self.publishers[c.name] = node.create_publisher(
                JointTrajectoryControllerState, f"{base}/controller_state", 10)
            action.serve(self, c)   # ~/follow_joint_trajectory
        elif isinstance(c, ctl.Forward):
            from std_msgs.msg import Float64MultiArray

            def commands(message, c=c):
                c.command(message.data)
                self._report(c)
            node.create_subscription(Float64MultiArray, f"{base}/commands", commands, 10)
        elif isinstance(c, ctl.PidController):
            from control_msgs.msg import MultiDOFCommand, MultiDOFStateStamped

            def reference(message, c=c):
                c.receive(message.dof_names, message.values, message.values_dot)
                self._report(c)
            best_effort = QoSProfile(depth=1, reliability=ReliabilityPolicy.BEST_EFFORT)
            node.create_subscription(MultiDOFCommand, f"{base}/reference", reference,
                                     best_effort)
            self.publishers[c.name] = node.create_publisher(
                MultiDOFStateStamped, f"{base}/controller_state", 10)
            from std_srvs.srv import SetBool

            def feedforward(request, response, c=c):
                c.set_feedforward(request.data)
                self._report(c)
                response.success = True
                return response
            node.create_service(SetBool, f"{base}/set_feedforward_control", feedforward)

    def _report(self, c) -> None:
        while getattr(c, "errors", None):
            self.node.get_logger().error(f"{c.name}: {c.errors.pop(0)}")
        while getattr(c, "warnings", None):
            self.node.get_logger().warning(f"{c.name}: {c.warnings.pop(0)}")

    # -- the controller manager's hooks (sw2sim.ros2.manager; the caller holds the lock) --
    def _entities(self) -> list:
        node = self.node
        return [*node.publishers, *node.subscriptions, *node.services, *node.clients,
                *node.timers, *node.waitables]

    def configured(self, c: ctl.Controller) -> list:
        """A controller configured: its topics and services made; the ROS entities that
        were made for it."""
        from sensor_msgs.msg import JointState
        before = {id(e) for e in self._entities()}
        rate = float(c.params.get("update_rate") or self.setup.update_rate)
        c.publish_period = 1.0 / min(rate, CLOCK_HZ)
        self.publishing[c.name] = Schedule(c.publish_period)
        if c.kind == ctl.JSB:
            self.publishers[c.name] = self.node.create_publisher(JointState, "/joint_states", 10)
        else:
            self._controller_topics(c)
        self.controllers[c.name] = c
        return [e for e in self._entities() if id(e) not in before]

    def cleaned_up(self, c: ctl.Controller, entities: list) -> None:
        """A controller cleaned up: what configure made for it destroyed."""
        node = self.node
        for entity in entities:
            for kind, destroy in (("Publisher", node.destroy_publisher),
                                  ("Subscription", node.destroy_subscription),
                                  ("Service", node.destroy_service),
                                  ("Client", node.destroy_client), ("Timer", node.destroy_timer)):
                if type(entity).__name__ == kind:
                    destroy(entity)
                    break
            else:
                if hasattr(entity, "destroy"):   # an action server
                    entity.destroy()
        for table in (self.publishers, self.publishing, self.controllers):
            table.pop(c.name, None)

    def write_commands(self, written: dict) -> None:
        """Values a controller writes to its command interfaces (as it deactivates)."""
        for joint, values in written.items():
            self.commands.setdefault(joint, {}).update(values)

    @staticmethod
    def _stamp(t: float):
        from builtin_interfaces.msg import Time
        sec = int(math.floor(t))
        return Time(sec=sec, nanosec=min(int(round((t - sec) * 1e9)), 999_999_999))

    # -- stepping ------------------------------------------------------------------------
    def step(self) -> None:
        with self.lock:
            m, d = self.model, self.data
            now = float(d.time)
            if self.updates.due(now):
                state = self.state()
                self.manager.apply(state)    # a switch the services asked for
                for c in self.controllers.values():
                    if c.active:   # the command interfaces keep what is not written again
                        self.write_commands(c.update(now, self.period, state))
                self.updates.advance(now)
            gain = self.setup.position_proportional_gain * self.setup.update_rate
            for name, (qa, va, a, limit, inertia) in self.places.items():
                q, v = float(d.qpos[qa]), float(d.qvel[va])
                joint = self.setup.joints[name]
                # what gz_system writes and gz-sim's Physics applies in this step
                command = hardware.finite_command(self.gz[name].step(
                    self.manager.joint_modes.get(name, ()), self.commands.get(name, {})))
                law = hardware.joint_law(
                    command, q, v, effort_limit=limit, inertia=inertia,
                    dt=self.dt, position_gain=gain, enforce=self.setup.enforce_command_limits,
                    interface_limits=joint.limits, allowed=hardware.servo_range(
                        self.bounds.get(name, hardware.Bounds()), q, self.dt)
                ) if joint.command else (0.0, 0.0, 0.0)
                d.ctrl[a] = law[0]
                m.actuator_biasprm[a, 1] = law[1]
                m.actuator_biasprm[a, 2] = law[2]
            before = [float(d.qpos[qa]) for qa, _, _ in self.constrained]
            mujoco.mj_step(m, d)
            hardware.constrain(m, d, self.constrained, before)
        self._publish(float(self.data.time))

    def _publish(self, now: float) -> None:
        from rosgraph_msgs.msg import Clock
        wall, period = time.monotonic(), 1.0 / CLOCK_HZ
        if now >= self.next_clock - 1e-9 and wall + period / 2 >= self.next_clock_wall:
            self.clock.publish(Clock(clock=self._stamp(now)))
            self.next_clock = now + period
            self.next_clock_wall = max(self.next_clock_wall, wall - period / 2) + period
        with self.lock:   # (the controller manager's services change the lists)
            running = [(n, c, self.publishing[n]) for n, c in self.controllers.items()
                       if c.active]
        for name, c, schedule in running:   # an inactive controller publishes nothing
            if not schedule.due(now):
                continue
            schedule.advance(now)
            with self.lock:   # (a service may destroy the publisher: not in between)
                if name not in self.publishers or not c.active:
                    continue
                stamp = self._stamp(now)
                if isinstance(c, ctl.JointStateBroadcaster):
                    message = self._joint_states(stamp)
                else:
                    message = c.state_message(stamp, self.state())
                self.publishers[name].publish(message)
            if isinstance(c, ctl.JointStateBroadcaster):
                self._publish_tf(message)

    def _joint_states(self, stamp):
        from sensor_msgs.msg import JointState
        d = self.data
        message = JointState()
        message.header.stamp = stamp
        names = list(self.joint_names)
        message.name = names
        fields = {"position": [], "velocity": [], "effort": []}
        present = {k: any(k in self.setup.joints[n].state for n in names) for k in fields}
        for n in names:
            qa, va, _, _, _ = self.places[n]
            have = self.setup.joints[n].state
            # gz_system.cpp (gz_ros2_control 1.2.7) reads position and velocity from Gazebo
            # Sim each step, never the force (its line is commented out): the effort state
            # keeps the interface's initial_value, 0 unless the URDF gives one
            # (https://github.com/ros-controls/gz_ros2_control/blob/1.2.7/gz_ros2_control/src/gz_system.cpp#L300-L351,
            # #L538-L549)
            values = {"position": float(d.qpos[qa]), "velocity": float(d.qvel[va]),
                      "effort": self.setup.joints[n].initial.get("effort", 0.0)}
            for k in fields:
                if present[k]:
                    fields[k].append(values[k] if k in have else math.nan)
        message.position, message.velocity, message.effort = (
            fields["position"], fields["velocity"], fields["effort"])
        return message

    def _publish_tf(self, joint_state) -> None:
        """robot_state_publisher's callbackJointState (3.3.3): the moving joints'
        transforms, stamped with the joint state's stamp, when that stamp is at least
        1/publish_frequency (20 Hz by default: 50 ms, whole milliseconds) past the stamp of
        the last /tf of the least recently published of its joints (0 at first)."""
        from tf2_msgs.msg import TFMessage
        stamp = joint_state.header.stamp.sec * 1_000_000_000 + joint_state.header.stamp.nanosec
        last = min((self.tf_published.get(n, 0) for n in joint_state.name), default=0)
        if stamp < last + TF_INTERVAL_NS:
            return
        for n in joint_state.name:
            self.tf_published[n] = stamp
        positions = dict(zip(joint_state.name, joint_state.position))
        transforms = [description.stamped(j, positions[j.name], joint_state.header.stamp)
                      for j in self.urdf_joints
                      if j.kind in description.MOVING and j.name in positions]
        if transforms:
            self.tf.publish(TFMessage(transforms=transforms))


def body_pose(sim: Simulation, link: str) -> np.ndarray:
    """A link's position in the world frame, from MuJoCo (for checks)."""
    return np.array(sim.data.body(link).xpos)
