"""joint_trajectory_controller's action, `/<controller>/follow_joint_trajectory`
(control_msgs/action/FollowJointTrajectory), served for each trajectory controller the
stand-in runs, as ros2_controllers 4.42.1 serves it (joint_trajectory_controller.cpp):

- a goal is checked as a message on `~/joint_trajectory` is (validate_trajectory_msg:
  joint names, empty points, times that do not increase, sizes, a stamped trajectory
  that ends in the past) and rejected with the controller's log line when it fails, or
  when the controller is not active; it is not answered with a result code;
- an accepted goal aborts the active one (INVALID_GOAL, "Current goal preempted by new
  incoming action."), and its trajectory replaces the current one; its path and goal
  tolerances and goal_time_tolerance replace the YAML's `constraints` (0 keeps the
  YAML's value, -1 removes it);
- while it runs, feedback (desired, actual and error) at `action_monitor_rate` (20 Hz)
  of simulated time; it ends SUCCESSFUL once the last point's time has passed with every
  joint within its goal tolerances (by default only `stopped_velocity_tolerance`, 0.01,
  on the velocity error), PATH_TOLERANCE_VIOLATED when a joint leaves its path
  tolerance, GOAL_TOLERANCE_VIOLATED when the goal tolerances are not met
  `goal_time` after the last point's time (never, with goal_time 0); the joints then
  hold (sw2sim.ros2.controllers.JointTrajectory.update);
- a cancel of the active goal ends it canceled (an empty result) and holds the joints
  where they are.

The goal's end comes from the simulation's thread: a goal handle is moved to its end
state, and its result sent, by a task on the node's executor; no execute callback waits
for it (rclpy's executor would run a waiting coroutine at every turn, a busy loop beside
the simulation).

`from_message` turns a trajectory_msgs/JointTrajectory into the controller's form, for
the topic and the action alike.
"""

from __future__ import annotations

import collections
import math

from . import trajectory


def seconds(stamp) -> float:
    return stamp.sec + stamp.nanosec * 1e-9


def from_message(message):
    """(joint names, stamp in s, points as (time_from_start, positions, velocities,
    accelerations, effort))."""
    points = [(seconds(p.time_from_start), list(p.positions), list(p.velocities),
               list(p.accelerations), list(p.effort)) for p in message.points]
    return list(message.joint_names), seconds(message.header.stamp), points


def position_limits(sim) -> dict[str, tuple[float, float]]:
    """The URDF's position limits of its revolute and prismatic joints."""
    from ..ros_control import read_joint_limits
    kinds = {j.name: j.kind for j in sim.urdf_joints}
    found = {}
    for name, limit in read_joint_limits(sim.setup.urdf).items():
        if kinds.get(name) in ("revolute", "prismatic") and \
                limit.lower is not None and limit.upper is not None:
            found[name] = (min(limit.lower, limit.upper), max(limit.lower, limit.upper))
    return found


def _duration(t: float):
    from builtin_interfaces.msg import Duration
    whole = math.floor(t)
    return Duration(sec=int(whole), nanosec=min(int(round((t - whole) * 1e9)), 999_999_999))


def serve(sim, c) -> None:
    """The action server of trajectory controller `c` on the simulation's node; the
    controller's log lines go to the node's log."""
    from control_msgs.action import FollowJointTrajectory
    from rclpy.action import ActionServer, CancelResponse, GoalResponse
    from trajectory_msgs.msg import JointTrajectoryPoint

    node = sim.node
    logger = node.get_logger()

    def say(level: str, text: str) -> None:
        # one call per severity: rclpy's logger refuses a second severity from one line
        if level == "error":
            logger.error(f"{c.name}: {text}")
        elif level == "warn":
            logger.warning(f"{c.name}: {text}")
        else:
            logger.info(f"{c.name}: {text}")
    c.say = say
    c.position_limits = position_limits(sim)
    goals: dict[bytes, trajectory.Goal] = {}
    # What the simulation's thread hands to the executor's, in order (the executor runs
    # the newest of its pending tasks first: each task sends everything queued)
    outbox: collections.deque = collections.deque()

    def post(function, *args) -> None:
        outbox.append((function, args))
        node.executor.create_task(send)

    def send() -> None:
        while outbox:
            function, args = outbox.popleft()
            function(*args)

    class Server(ActionServer):
        def notify_execute(self, goal_handle, execute_callback):
            # goal_handle.execute() only moves the goal to EXECUTING; its end is sent by
            # _finish's own execute callback
            if execute_callback is not None:
                super().notify_execute(goal_handle, execute_callback)

    def received(request):
        c.say("info", "Received new action goal")
        try:
            names, stamp, points = from_message(request.trajectory)
            problem = c.goal_refusal(names, stamp, points, now=sim.time)
        except Exception as exc:  # noqa: BLE001  (the executor's thread must go on)
            problem = f"the goal cannot be read: {exc}"
        if problem:
            c.say("error", problem)
            return GoalResponse.REJECT
        c.say("info", "Accepted new action goal")
        return GoalResponse.ACCEPT

    def accepted(goal_handle):
        request = goal_handle.request
        goal_handle.execute()
        tolerances, problem = trajectory.goal_tolerances(
            c.defaults,
            [(t.name, t.position, t.velocity, t.acceleration) for t in request.path_tolerance],
            [(t.name, t.position, t.velocity, t.acceleration) for t in request.goal_tolerance],
            seconds(request.goal_time_tolerance), c.joints)
        if problem:
            c.say("error", problem)
        key = bytes(goal_handle.goal_id.uuid)
        goal = trajectory.Goal(
            end=lambda outcome, code, text: post(_finish, goal_handle, key, outcome, code, text),
            feedback=lambda data: post(_feedback, goal_handle, data),
            period=1.0 / c.monitor_rate)
        goals[key] = goal
        try:
            c.start_goal(goal, *from_message(request.trajectory), tolerances)
        except Exception as exc:  # noqa: BLE001  (the executor's thread must go on)
            c.say("error", f"the goal cannot be followed: {exc}")
            goal.finish("aborted", trajectory.INVALID_GOAL, str(exc))

    def cancel(goal_handle):
        c.say("info", "Got request to cancel goal")
        goal = goals.get(bytes(goal_handle.goal_id.uuid))
        if goal is not None and c.cancel_goal(goal):
            c.say("info", "Canceling active action goal because cancel callback received.")
        return CancelResponse.ACCEPT

    def _finish(goal_handle, key, outcome, code, text):
        goals.pop(key, None)
        if not goal_handle.is_active:
            return
        {"succeeded": goal_handle.succeed, "aborted": goal_handle.abort,
         "canceled": goal_handle.canceled}[outcome]()
        result = FollowJointTrajectory.Result(error_code=code, error_string=text)
        server.notify_execute(goal_handle, lambda _: result)

    def point(fields: dict) -> JointTrajectoryPoint:
        p = JointTrajectoryPoint()
        for name in ("positions", "velocities", "accelerations", "effort"):
            setattr(p, name, [float(x) for x in fields.get(name, [])])
        if "time_from_start" in fields:
            p.time_from_start = _duration(max(fields["time_from_start"], 0.0))
        return p

    def _feedback(goal_handle, data):
        if not goal_handle.is_active:
            return
        message = FollowJointTrajectory.Feedback()
        message.header.stamp = sim._stamp(data["time"])
        message.joint_names = data["joint_names"]
        message.desired = point(data["desired"])
        message.actual = point(data["actual"])
        message.error = point(data["error"])
        goal_handle.publish_feedback(message)

    server = Server(node, FollowJointTrajectory, f"/{c.name}/follow_joint_trajectory",
                    execute_callback=lambda goal_handle: FollowJointTrajectory.Result(),
                    goal_callback=received, handle_accepted_callback=accepted,
                    cancel_callback=cancel)
