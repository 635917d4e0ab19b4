"""The simulation node: MuJoCo where gzserver and gazebo_ros_control would run.

One process, started by the stand-in `gazebo_ros/empty_world.launch` (sw2sim.ros.packages),
gives ROS what the lessons use of Gazebo:

- `/clock` (rosgraph_msgs/Clock) at CLOCK_HZ of simulated time, and no more often than
  CLOCK_HZ times a second of wall time (run faster than real time, every node that
  follows the clock would otherwise spend its time reading it); the launch file sets
  `use_sim_time`;
- `/gazebo/spawn_urdf_model` (what `spawn_model` calls), `/gazebo/pause_physics`,
  `unpause_physics`, `reset_simulation`, `reset_world`, `apply_joint_effort`,
  `clear_joint_forces` and `get_joint_properties`, with upstream's types. The two resets
  do what Gazebo's do (World.reset_simulation and reset_world say what that is, and
  where it is in upstream's source): both put the model and its joints back where they
  were spawned, `reset_simulation` also sets simulated time back to 0, and the
  controllers keep their commands and integral terms;
- for a URDF with the gazebo_ros_control plugin, its controller manager under
  `<robotNamespace>/controller_manager/` (load, unload and switch), and the controllers
  the parameter server describes: `joint_state_controller/JointStateController`
  (`<ns>/joint_states` at its publish_rate) and the `effort_controllers` position,
  velocity and effort controllers (`<ns>/<name>/command` in, `<ns>/<name>/state` out).
  Each drives its joint through one MuJoCo actuator, set at every step to the effort
  gazebo_ros_control would apply (sw2sim.ros.hardware): the controller's P and D terms,
  a position command clamped to the joint's limits, then the limits handle its default
  hardware registers from the URDF. A joint with a `<safety_controller>` gets the soft
  limits (the speed held under the `<limit velocity>` with k_velocity, and brought down
  towards a soft limit with k_position), one without it the saturation (plus or minus the
  effort limit, and no push further past a position or the velocity limit). The PID's
  integral term is control_toolbox's, antiwindup included.

- gazebo_plugins' `libgazebo_ros_joint_state_publisher.so`: the joints it names on
  `<robotNamespace>/joint_states`.

Every publisher keeps to a rate on simulated time (sw2sim.ros.schedule): `publish_rate: 20`
gives 20 messages in each simulated second.

`SW2SIM_REALTIME` sets the real-time factor: 1 (the default) for people, 0 for as fast
as the machine goes (tests), kept from the last time simulated time was set back or held
(a reset, a pause), so that the simulation never races to make up for them.
`SW2SIM_VIEW=1` shows the simulation in MuJoCo's viewer (sw2sim.ros.viewer).
"""

from __future__ import annotations

import dataclasses
import os
import re
import tempfile
import threading
import time
from pathlib import Path

import mujoco

from . import hardware
from .schedule import SLACK, Schedule

CLOCK_HZ = 100.0          # /clock messages per simulated (and at most per wall) second
STATE_HZ = 50.0           # controller state messages per simulated second
QUEUE = 500               # messages a publisher holds for a slow reader: a wall second of
                          # controller states at --realtime 10, so a busy machine's pause
                          # loses none (rospy drops the oldest past it)
POSITION, VELOCITY, EFFORT = hardware.POSITION, hardware.VELOCITY, hardware.EFFORT
JOINT_STATE = "joint_state_controller/JointStateController"


def find_package_folder(name: str) -> Path | None:
    """The folder of the ROS package `name` on ROS_PACKAGE_PATH (as roslaunch finds it)."""
    for entry in os.environ.get("ROS_PACKAGE_PATH", "").split(os.pathsep):
        if not entry:
            continue
        base = Path(entry)
        for folder in [base, *sorted(p for p in base.glob("*") if p.is_dir())]:
            manifest = folder / "package.xml"
            if manifest.is_file() and re.search(rf"<name>\s*{re.escape(name)}\s*</name>",
                                                manifest.read_text(encoding="utf-8", errors="replace")):
                return folder
    return None


def package_of(model_xml: str):
    """A Package around the URDF text that `spawn_model` sent: read from the folder of the
    package its mesh paths name, with the URDF as sent."""
    from .. import xmlsafe
    from ..package import find_package
    names = re.findall(r"package://([^/\"']+)/", model_xml)
    folder = find_package_folder(names[0]) if names else None
    if folder is None:
        scratch = Path(tempfile.mkdtemp(prefix="sw2sim-spawn-"))
        (scratch / "robot.urdf").write_text(model_xml, encoding="utf-8")
        return find_package(scratch / "robot.urdf")
    package = find_package(folder)
    robot = xmlsafe.parse_bytes(model_xml.encode())
    return dataclasses.replace(package, robot=robot)


@dataclasses.dataclass
class Controller:
    name: str
    kind: str
    joint: str | None
    settings: dict
    running: bool = False
    actuator: str | None = None
    command: float = 0.0
    publishers: tuple = ()
    subscriber: object = None
    schedule: Schedule | None = None   # when it publishes next (set when it starts)
    plugin: bool = False      # gazebo_plugins' joint state publisher, not a ros_control one
    places: tuple | None = None   # (model, qpos address, dof address, actuator)
    error_sum: float = 0.0    # the PID's integrated error
    integral: float = 0.0     # the PID's integral term, in N or N·m



class World:
    """The model, its state and the ROS interfaces; `step` advances it."""

    def __init__(self, rospy):
        self.rospy = rospy
        self.lock = threading.RLock()
        self.spec = self.model = self.data = None
        self.namespace = ""
        self.paused = False
        self.controllers: dict[str, Controller] = {}
        self.efforts: list = []   # sw2sim.ros.gazebo_services.Effort: applied efforts
        self.handles: dict[str, hardware.Handle] = {}
        self.clock_ticks = Schedule(1.0 / CLOCK_HZ)
        self.next_clock_wall = 0.0
        # gazebo_ros_control's last_update_sim_time_ros_: the controllers' last update
        self.last_update = 0.0
        # (wall time, simulated time) from which the real-time factor is kept
        self.pace_from = (time.monotonic(), 0.0)

    # -- the model ---------------------------------------------------------------------
    def spawn(self, model_xml: str, namespace: str) -> str:
        from ..loader import load_package
        package = package_of(model_xml)
        spec = load_package(package, fixed_base=package.world_fixed)
        plugin = package.robot.find("gazebo/plugin[@filename='libgazebo_ros_control.so']")
        ns = plugin.findtext("robotNamespace") if plugin is not None else None
        with self.lock:
            self.handles = hardware.handles(package)
            self.spec, self.model = spec, spec.compile()
            self.data = mujoco.MjData(self.model)
            mujoco.mj_forward(self.model, self.data)
            self.namespace = "/" + (ns or namespace or "").strip("/")
            if self.namespace == "/":
                self.namespace = ""
            self.pace_from = (time.monotonic(), self.time)
        if plugin is not None:
            self._controller_manager()
        publisher = package.robot.find(
            "gazebo/plugin[@filename='libgazebo_ros_joint_state_publisher.so']")
        if publisher is not None:
            self._joint_state_plugin(publisher, package.name)
        return f"{package.name}: {self.model.njnt} joint(s), controllers under " \
               f"{self.namespace or '/'}"

    def joints(self) -> list[int]:
        moving = (int(mujoco.mjtJoint.mjJNT_HINGE), int(mujoco.mjtJoint.mjJNT_SLIDE))
        return [j for j in range(self.model.njnt) if int(self.model.jnt_type[j]) in moving]

    def step(self) -> None:
        """One physics step, and what is due after it. Under the lock from start to end:
        a reset between the step and its messages would otherwise let a time from before
        the reset out on /clock after it."""
        with self.lock:
            if self.model is None or self.paused:
                return
            m, d = self.model, self.data
            d.qfrc_applied[:] = 0
            for job in list(self.efforts):
                if job.until is not None and d.time >= job.until:
                    self.efforts.remove(job)
                elif d.time >= job.start - SLACK:
                    d.qfrc_applied[m.jnt_dofadr[m.joint(job.joint).id]] += job.effort
            # gazebo_ros_control_plugin.cpp Update: the period since the last update (one
            # step, except after a reset: see reset_world)
            period = d.time + float(m.opt.timestep) - self.last_update
            self.last_update += period
            for c in self.controllers.values():
                if c.running and c.actuator is not None:
                    self._drive(c, period)
            mujoco.mj_step(m, d)
            self._publish(d.time)

    def keep_pace(self, realtime: float) -> None:
        """Wait until simulated time runs no more than `realtime` times as fast as the
        wall clock, counted from `pace_from`."""
        wall, sim = self.pace_from
        ahead = (self.time - sim) / realtime - (time.monotonic() - wall)
        if ahead > 0.002:
            time.sleep(ahead)

    @property
    def time(self) -> float:
        return 0.0 if self.data is None else float(self.data.time)

    # -- controllers ---------------------------------------------------------------------
    def _controller_manager(self) -> None:
        from controller_manager_msgs.srv import (LoadController, LoadControllerResponse,
                                                 SwitchController, SwitchControllerResponse,
                                                 UnloadController, UnloadControllerResponse)
        rospy, base = self.rospy, f"{self.namespace}/controller_manager"
        rospy.Service(f"{base}/load_controller", LoadController,
                      lambda req: LoadControllerResponse(ok=self.load(req.name)))
        rospy.Service(f"{base}/unload_controller", UnloadController,
                      lambda req: UnloadControllerResponse(ok=self.unload(req.name)))
        rospy.Service(f"{base}/switch_controller", SwitchController,
                      lambda req: SwitchControllerResponse(
                          ok=self.switch(req.start_controllers, req.stop_controllers)))

    def _joint_state_plugin(self, plugin, model: str) -> None:
        """gazebo_plugins' joint state publisher: the joints named in <jointName>, at
        <updateRate>, on <robotNamespace>/joint_states (the model's name by default)."""
        from sensor_msgs.msg import JointState
        names = [n.strip() for n in (plugin.findtext("jointName") or "").split(",") if n.strip()]
        namespace = (plugin.findtext("robotNamespace") or model).strip().strip("/")
        topic = f"/{namespace}/joint_states" if namespace else "/joint_states"
        rate = float(plugin.findtext("updateRate") or 100)
        publisher = Controller("gazebo_joint_state_publisher", JOINT_STATE, None,
                               {"publish_rate": rate, "joints": names}, running=True,
                               plugin=True)
        # its Load sets last_update_time_ to the time: the first message one period later
        publisher.schedule = Schedule(self._period(publisher), self.time, 1)
        publisher.publishers = (self.rospy.Publisher(topic, JointState, queue_size=QUEUE),)
        self.controllers[publisher.name] = publisher

    def load(self, name: str) -> bool:
        rospy = self.rospy
        key = f"{self.namespace}/{name}"
        if name in self.controllers or not rospy.has_param(key):
            rospy.logerr("cannot load controller %s: %s", name,
                         "loaded already" if name in self.controllers else f"no parameter {key}")
            return False
        settings = rospy.get_param(key)
        kind = settings.get("type")
        if kind not in (JOINT_STATE, POSITION, VELOCITY, EFFORT):
            rospy.logerr("controller %s: type %s is not simulated here", name, kind)
            return False
        joint = settings.get("joint")
        if kind != JOINT_STATE:
            try:
                self.model.joint(joint)
            except (KeyError, TypeError):
                rospy.logerr("controller %s: the model has no joint %r", name, joint)
                return False
        self.controllers[name] = Controller(name, kind, joint, settings)
        return True

    def unload(self, name: str) -> bool:
        controller = self.controllers.get(name)
        if controller is None or controller.running:
            return False
        del self.controllers[name]
        return True

    def switch(self, start, stop) -> bool:
        if any(n not in self.controllers for n in [*start, *stop]):
            return False
        for name in stop:
            self._stop(self.controllers[name])
        for name in start:
            self._start(self.controllers[name])
        return True

    def _start(self, c: Controller) -> None:
        from sensor_msgs.msg import JointState
        from std_msgs.msg import Float64
        from control_msgs.msg import JointControllerState
        rospy = self.rospy
        if c.running:
            return
        topic = f"{self.namespace}/{c.name}"
        if c.kind == JOINT_STATE:
            c.publishers = (rospy.Publisher(f"{self.namespace}/joint_states", JointState,
                                            queue_size=QUEUE),)
        else:
            with self.lock:
                c.actuator = self._actuator(c)
                j = self.model.joint(c.joint).id
                c.command = float(self.data.qpos[self.model.jnt_qposadr[j]]) \
                    if c.kind == POSITION else 0.0
            c.publishers = (rospy.Publisher(f"{topic}/state", JointControllerState,
                                            queue_size=QUEUE),)

            def command(message, controller=c):
                controller.command = float(message.data)

            c.subscriber = rospy.Subscriber(f"{topic}/command", Float64, command)
        # JointStateController::starting sets last_publish_time_ a period and a bit back:
        # the first message at once
        c.schedule = Schedule(self._period(c), self.time)
        c.running = True

    def _stop(self, c: Controller) -> None:
        c.running = False
        if c.subscriber is not None:
            c.subscriber.unregister()
        for publisher in c.publishers:
            publisher.unregister()

    def _state_of(self, joint: str) -> tuple[float, float]:
        m, d = self.model, self.data
        j = m.joint(joint).id
        return float(d.qpos[m.jnt_qposadr[j]]), float(d.qvel[m.jnt_dofadr[j]])

    def _law(self, c: Controller) -> hardware.Law:
        """The controller's own effort law, before the joint's limits."""
        setpoint = hardware.command(c.kind, c.command, self.handles.get(c.joint))
        law = hardware.controller(c.kind, c.settings.get("pid") or {}, setpoint)
        return (law[0] + c.integral, law[1], law[2])

    def _drive(self, c: Controller, period: float) -> None:
        """Set the controller's actuator to the effort law that holds in this state:
        force = ctrl + biasprm[1] * q + biasprm[2] * v, after one update of the PID's
        integral term over `period` on this state's error; what `_law` gives, with the
        joint's and the actuator's places in the model looked up once per model (this
        runs every step, ten thousand times a second at ten times real time)."""
        m, d = self.model, self.data
        if c.places is None or c.places[0] is not m:
            j = m.joint(c.joint).id
            c.places = (m, int(m.jnt_qposadr[j]), int(m.jnt_dofadr[j]),
                        m.actuator(c.actuator).id)
        _, qadr, vadr, a = c.places
        q, v = float(d.qpos[qadr]), float(d.qvel[vadr])
        handle, pid = self.handles.get(c.joint), c.settings.get("pid") or {}
        setpoint = hardware.command(c.kind, c.command, handle)
        if c.kind in (POSITION, VELOCITY):
            error = setpoint - (q if c.kind == POSITION else v)
            c.error_sum, c.integral = hardware.integral(pid, c.error_sum, error, period)
        law = hardware.controller(c.kind, pid, setpoint)
        law = hardware.effort((law[0] + c.integral, law[1], law[2]), handle, q, v)
        d.ctrl[a] = law[0]
        m.actuator_biasprm[a, 1] = law[1]
        m.actuator_biasprm[a, 2] = law[2]

    def _actuator(self, c: Controller) -> str:
        """Add the controller's actuator (a force set by _drive at every step) and
        recompile, keeping the state."""
        name = f"ros_{c.name}"
        act = self.spec.add_actuator(name=name, target=c.joint, trntype=mujoco.mjtTrn.mjTRN_JOINT)
        act.gaintype, act.biastype = mujoco.mjtGain.mjGAIN_FIXED, mujoco.mjtBias.mjBIAS_AFFINE
        act.gainprm[0] = 1.0
        j = self.model.joint(c.joint).id
        if self.model.jnt_actfrclimited[j]:
            act.forcelimited = mujoco.mjtLimited.mjLIMITED_TRUE
            act.forcerange = list(self.model.jnt_actfrcrange[j])
        self.model, self.data = self.spec.recompile(self.model, self.data)
        return name

    # -- publishing ----------------------------------------------------------------------
    @staticmethod
    def _period(c: Controller) -> float:
        if c.kind != JOINT_STATE:
            return 1.0 / STATE_HZ
        return 1.0 / (float(c.settings.get("publish_rate", STATE_HZ)) or STATE_HZ)

    def _publish(self, now: float) -> None:
        rospy = self.rospy
        wall, period = time.monotonic(), self.clock_ticks.period
        # On wall time, ticks keep to a schedule of CLOCK_HZ a second, with half a period
        # of slack: at real time the wall clock's jitter then never holds a tick back.
        if self.clock_ticks.due(now) and wall + period / 2 >= self.next_clock_wall:
            from rosgraph_msgs.msg import Clock
            self.clock.publish(Clock(clock=rospy.Time.from_sec(now)))
            self.clock_ticks.advance(now)
            self.next_clock_wall = max(self.next_clock_wall, wall - period / 2) + period
        for c in list(self.controllers.values()):
            if not c.running or c.schedule is None or not c.schedule.due(now):
                continue
            c.schedule.advance()
            with self.lock:
                message = (self._joint_states(now, c.settings.get("joints"))
                           if c.kind == JOINT_STATE else self._state(c, now))
            c.publishers[0].publish(message)

    def _joint_states(self, now: float, names=None):
        from sensor_msgs.msg import JointState
        m, d = self.model, self.data
        joints = self.joints()
        if names:
            joints = [j for j in joints if m.joint(j).name in names]
        message = JointState(name=[m.joint(j).name for j in joints],
                             position=[float(d.qpos[m.jnt_qposadr[j]]) for j in joints],
                             velocity=[float(d.qvel[m.jnt_dofadr[j]]) for j in joints],
                             effort=[float(d.qfrc_actuator[m.jnt_dofadr[j]]) for j in joints])
        message.header.stamp = self.rospy.Time.from_sec(now)
        return message

    def _state(self, c: Controller, now: float):
        """The controller's state message: set point, measured value (a velocity for a
        velocity controller) and the effort its PID asks for, before the joint's limits."""
        from control_msgs.msg import JointControllerState
        q, v = self._state_of(c.joint)
        setpoint = hardware.command(c.kind, c.command, self.handles.get(c.joint))
        measured, rate = (v, 0.0) if c.kind == VELOCITY else (q, v)
        pid = c.settings.get("pid") or {}
        message = JointControllerState(
            set_point=setpoint, process_value=measured, process_value_dot=rate,
            error=setpoint - measured, time_step=float(self.model.opt.timestep),
            command=hardware.value(self._law(c), q, v),
            p=float(pid.get("p", 0.0)), i=float(pid.get("i", 0.0)), d=float(pid.get("d", 0.0)),
            i_clamp=float(pid.get("i_clamp", 0.0)), antiwindup=bool(pid.get("antiwindup", False)))
        message.header.stamp = self.rospy.Time.from_sec(now)
        return message

    # -- resets --------------------------------------------------------------------------
    def reset_simulation(self) -> None:
        """gazebo_ros_api_plugin.cpp resetSimulation calls World::Reset (gazebo11,
        World.cc): ResetTime sets simulated time back to 0, and every model is reset as by
        reset_world; the pause stays as it was. Of the publishers, each keeps its own
        schedule as upstream does: gazebo_plugins' joint state publisher starts again from
        the new time (gazebo_ros_joint_state_publisher.cpp OnUpdate, "Negative joint state
        update time difference detected"), a controller's state goes on (a position or
        velocity controller publishes it every tenth update, whatever the time:
        joint_position_controller.cpp update), while JointStateController
        keeps its `last_publish_time_` and stays silent until simulated time passes it
        again (joint_state_controller.cpp update; gazebo_ros_pkgs issue #1368). /clock
        gives the new time at the next step, whatever the wall clock says."""
        with self.lock:
            if self.model is None:
                return
            self._reset_model(0.0)
            self.clock_ticks.restart(0.0)
            self.next_clock_wall = 0.0
            for c in self.controllers.values():
                if c.schedule is None:
                    continue
                if c.plugin:
                    self.rospy.logwarn("Negative joint state update time difference detected.")
                    c.schedule.restart(0.0, at_once=False)
                elif c.kind != JOINT_STATE:
                    c.schedule.restart(0.0)
            self.pace_from = (time.monotonic(), 0.0)

    def reset_world(self) -> None:
        """gazebo_ros_api_plugin.cpp resetWorld calls World::ResetEntities(MODEL): each
        Model::Reset (gazebo11, Model.cc) puts the model's pose back, zeroes its links'
        velocities and forces and its joints' velocities, and calls its plugins' Reset.
        Simulated time goes on."""
        with self.lock:
            if self.model is not None:
                self._reset_model(self.time)

    def _reset_model(self, now: float) -> None:
        """The model as spawned, at simulated time `now`. What stays, as in Gazebo: each
        controller's command and integral term (gazebo_ros_control resets controllers only
        when an e-stop is released, never on a reset), and the queued efforts of
        apply_joint_effort, each still due at its own start time. gazebo_ros_control's
        Reset() sets its last update time back to 0 (gazebo_ros_control_plugin.cpp
        Reset), so the controllers' first update after a reset_world integrates the
        error over the whole time since 0."""
        m, d = self.model, self.data
        mujoco.mj_resetData(m, d)
        d.time = now
        mujoco.mj_forward(m, d)
        self.last_update = 0.0

    # -- /gazebo -------------------------------------------------------------------------
    def services(self) -> None:
        """/clock and the /gazebo services (sw2sim.ros.gazebo_services)."""
        from .gazebo_services import advertise
        advertise(self)
