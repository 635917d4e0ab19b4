"""An independent ROS 2 node (rclpy and the message packages only, no sw2sim) that tries
Practice 3's trajectory controllers the way a user's script or MoveIt would: goals on
`/<controller>/follow_joint_trajectory` (reached, refused, preempted, canceled, out of
tolerance) and bad messages on `~/joint_trajectory`. It prints one JSON object, one
entry per scenario, for tests/ros2/test_trajectory_action.py to check.

    python trajectory_client.py
"""

import json
import math
import sys
import time

import rclpy
from builtin_interfaces.msg import Duration
from control_msgs.action import FollowJointTrajectory
from control_msgs.msg import JointTolerance
from rclpy.action import ActionClient
from sensor_msgs.msg import JointState
from trajectory_msgs.msg import JointTrajectory, JointTrajectoryPoint

WALL_TIMEOUT = 30.0   # s for one wait
MIDDLE, END = "middle_arm_joint", "end_arm_joint"


def duration(seconds: float) -> Duration:
    whole = math.floor(seconds)
    return Duration(sec=int(whole), nanosec=int(round((seconds - whole) * 1e9)))


def stamp_seconds(stamp) -> float:
    return stamp.sec + stamp.nanosec * 1e-9


class Client:
    def __init__(self):
        self.node = rclpy.create_node("trajectory_client")
        self.action = ActionClient(self.node, FollowJointTrajectory,
                                   "/middle_arm_controller/follow_joint_trajectory")
        self.topic = self.node.create_publisher(JointTrajectory,
                                                "/end_arm_controller/joint_trajectory", 10)
        self.state = None   # (stamp, {joint: position})
        self.node.create_subscription(JointState, "/joint_states", self._state, 10)

    def _state(self, message):
        self.state = (stamp_seconds(message.header.stamp),
                      dict(zip(message.name, message.position)))

    def spin_until(self, done, timeout=WALL_TIMEOUT):
        deadline = time.monotonic() + timeout
        while not done():
            if time.monotonic() > deadline:
                raise TimeoutError("waited too long")
            rclpy.spin_once(self.node, timeout_sec=0.01)

    def now(self) -> float:
        return self.state[0]

    def wait(self, seconds: float) -> None:
        """`seconds` of simulated time, read from /joint_states."""
        until = self.now() + seconds
        self.spin_until(lambda: self.state[0] >= until)

    def wait_past(self, feedback, seconds: float) -> None:
        """`seconds` of simulated time past a goal's last feedback. (The joint state heard
        last may be older than the result: a loaded client takes its messages late.)"""
        if not feedback:
            return self.wait(seconds)
        until = stamp_seconds(feedback[-1].header.stamp) + seconds
        self.spin_until(lambda: self.state[0] >= until)

    def goal(self, positions, seconds, names=(MIDDLE,), path=None, goal=None,
             goal_time=0.0):
        request = FollowJointTrajectory.Goal()
        request.trajectory.joint_names = list(names)
        request.trajectory.points = [JointTrajectoryPoint(positions=list(positions),
                                                          time_from_start=duration(seconds))]
        if path is not None:
            request.path_tolerance = [JointTolerance(name=MIDDLE, position=path)]
        if goal is not None:
            request.goal_tolerance = [JointTolerance(name=MIDDLE, position=goal)]
        request.goal_time_tolerance = duration(goal_time)
        feedback = []
        sent = self.action.send_goal_async(
            request, feedback_callback=lambda m: feedback.append(m.feedback))
        self.spin_until(sent.done)
        return sent.result(), feedback

    def result(self, handle) -> dict:
        future = handle.get_result_async()
        self.spin_until(future.done)
        r = future.result()
        return {"status": r.status, "error_code": r.result.error_code,
                "error_string": r.result.error_string, "position": self.state[1][MIDDLE]}

    def publish(self, names, points, stamp=0.0) -> None:
        message = JointTrajectory(joint_names=list(names))
        message.header.stamp.sec = int(stamp)
        message.points = [JointTrajectoryPoint(positions=list(p), time_from_start=duration(t))
                          for t, p in points]
        self.topic.publish(message)


def main() -> int:
    rclpy.init()
    c = Client()
    out = {}
    assert c.action.wait_for_server(timeout_sec=WALL_TIMEOUT), "no action server"
    c.spin_until(lambda: c.state is not None and c.topic.get_subscription_count() > 0)

    # reached: SUCCESSFUL, with feedback on the way
    handle, feedback = c.goal([0.4], 1.0)
    out["success"] = {"accepted": handle.accepted, **c.result(handle),
                      "feedback": len(feedback),
                      "feedback_joints": list(feedback[-1].joint_names) if feedback else [],
                      "stamps": [stamp_seconds(f.header.stamp) for f in feedback],
                      "desired": [list(f.desired.positions) for f in feedback],
                      "actual": [list(f.actual.positions) for f in feedback]}
    c.wait_past(feedback, 0.5)
    out["success"]["settled"] = c.state[1][MIDDLE]

    # refused before they start: a joint the controller does not have, a NaN
    handle, _ = c.goal([0.2], 1.0, names=("elbow_joint",))
    out["unknown_joint"] = {"accepted": handle.accepted}
    handle, _ = c.goal([math.nan], 1.0)
    out["nan_goal"] = {"accepted": handle.accepted}

    # a new goal preempts the one running
    first, feedback = c.goal([-0.4], 20.0)
    c.spin_until(lambda: feedback)
    second, _ = c.goal([0.2], 0.5)
    out["preempted"] = {"accepted": first.accepted, **c.result(first)}
    out["preempting"] = {"accepted": second.accepted, **c.result(second)}
    # with no goal tolerance the goal succeeds when its time is up; the joint then settles
    c.wait(0.5)
    out["preempting"]["settled"] = c.state[1][MIDDLE]

    # canceled on the way: the joint holds where it was
    handle, feedback = c.goal([-0.5], 20.0)
    c.spin_until(lambda: feedback)
    c.wait(1.0)
    canceling = handle.cancel_goal_async()
    c.spin_until(canceling.done)
    out["canceled"] = {"canceling": len(canceling.result().goals_canceling), **c.result(handle)}
    c.wait(1.0)
    out["canceled"]["later"] = c.state[1][MIDDLE]

    # a path tolerance the controller cannot keep
    handle, _ = c.goal([0.6], 0.3, path=1e-4)
    out["path"] = {"accepted": handle.accepted, **c.result(handle)}
    # a goal past the joint's limit, which it cannot reach within goal_time_tolerance
    handle, _ = c.goal([5.0], 0.5, goal=0.01, goal_time=0.5)
    out["goal"] = {"accepted": handle.accepted, **c.result(handle)}

    # bad messages on the end arm's topic: each refused, the arm stays
    c.wait(0.2)
    before = c.state[1][END]
    c.publish([END], [(1.0, [math.nan])])
    c.publish([END], [])
    c.publish([END], [(1.0, [0.3]), (0.5, [0.1])])
    c.publish(["elbow_joint"], [(1.0, [0.3])])
    c.publish([END], [(1.0, [0.3])], stamp=max(math.floor(c.now()) - 5, 1))
    c.wait(1.5)
    out["bad_messages"] = {"before": before, "after": c.state[1][END]}
    # and a good one still moves it
    c.publish([END], [(0.5, [-0.3])])
    c.wait(1.5)
    out["good_message"] = {"after": c.state[1][END]}

    print(json.dumps(out))
    c.node.destroy_node()
    rclpy.shutdown()
    return 0


if __name__ == "__main__":
    sys.exit(main())
