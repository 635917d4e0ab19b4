"""Record, on simulated time, a robot's /joint_states and the commands nodes publish, and
print them as JSON once the clock is SECONDS past the trigger:

    python record.py SECONDS TRIGGER TOPIC=KIND ... [expect:TOPIC ...]

KIND is `trajectory` (trajectory_msgs/msg/JointTrajectory: its last point's positions),
`array` (std_msgs/msg/Float64MultiArray) or `float` (std_msgs/msg/Float64). TRIGGER is
one of the TOPICs (its first message), or `motion:JOINT`: the first joint state in which
JOINT moves (a node's one message may come before this recorder has found its publisher;
the motion it causes cannot). An `expect:TOPIC` (a topic the page's lines name) keeps the
recorder listing the run's topics after the recording, until each is there or EXPECT_WAIT
seconds have passed: a node started last may be discovered late on a busy machine.

{"start": t, "states": [[t, {joint: position}], ...], "speeds": [[t, {joint: velocity}], ...],
 "topics": {topic: [[t, value], ...]}, "graph": {topic: [type, ...]}}

A plain rclpy node in a process of its own, independent of what it records (it imports
nothing of sw2sim); the ROS 2 page tests start it before the page's blocks.
"""

import json
import sys
import time

import rclpy
from rclpy.node import Node
from rclpy.parameter import Parameter
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64, Float64MultiArray
from trajectory_msgs.msg import JointTrajectory

WALL_TIMEOUT = 60.0
EXPECT_WAIT = 10.0   # s of wall time
MOVING = 1e-3   # rad/s or m/s: faster than this, a joint moves
KINDS = {
    "trajectory": (JointTrajectory,
                   lambda m: {n: p for n, p in zip(m.joint_names, m.points[-1].positions)}
                   if m.points else {}),
    "array": (Float64MultiArray, lambda m: list(m.data)),
    "float": (Float64, lambda m: m.data),
}


def main() -> int:
    seconds, trigger = float(sys.argv[1]), sys.argv[2]
    kinds = dict(arg.split("=", 1) for arg in sys.argv[3:] if "=" in arg)
    expected = {arg.removeprefix("expect:") for arg in sys.argv[3:] if arg.startswith("expect:")}
    rclpy.init()
    node = Node("recorder", parameter_overrides=[Parameter("use_sim_time", value=True)])
    now = lambda: node.get_clock().now().nanoseconds / 1e9  # noqa: E731
    record = {"start": None, "states": [], "speeds": [], "topics": {t: [] for t in kinds}}

    moving = trigger.removeprefix("motion:") if trigger.startswith("motion:") else None

    def state(message):
        t = message.header.stamp.sec + message.header.stamp.nanosec / 1e9 or now()
        speeds = dict(zip(message.name, message.velocity))
        if not record["states"]:
            print("recording", file=sys.stderr, flush=True)   # the test waits for this line
        record["states"].append([t, dict(zip(message.name, message.position))])
        record["speeds"].append([t, speeds])
        if moving and record["start"] is None and abs(speeds.get(moving, 0.0)) > MOVING:
            record["start"] = t

    def command(topic, value):
        t = now()   # 0 until this node's first /clock message: then taken as the clock's start
        record["topics"][topic].append([t, value])
        if topic == trigger and record["start"] is None:
            record["start"] = t

    node.create_subscription(JointState, "/joint_states", state, 100)
    for topic, kind in kinds.items():
        message_type, value = KINDS[kind]
        node.create_subscription(message_type, topic,
                                 lambda m, topic=topic, value=value: command(topic, value(m)),
                                 100)
    # The topics of the run and their types, as `ros2 topic list -t` would list them: read
    # through the run, since discovery of a node started late can lag behind on a busy machine.
    graph, listed = {}, 0.0

    def list_topics():
        for name, types in node.get_topic_names_and_types():
            graph.setdefault(name, [])
            graph[name] += [t for t in types if t not in graph[name]]

    deadline = time.monotonic() + WALL_TIMEOUT
    while time.monotonic() < deadline:
        rclpy.spin_once(node, timeout_sec=0.05)
        if time.monotonic() - listed > 0.5:
            list_topics()
            listed = time.monotonic()
        if record["start"] == 0.0 and now() > 0:
            record["start"] = first_clock = now()
            for messages in record["topics"].values():
                messages[:] = [[t or first_clock, v] for t, v in messages]
        if record["start"] and now() >= record["start"] + seconds:
            break
    done = bool(record["start"]) and now() >= record["start"] + seconds
    list_topics()
    waited = time.monotonic() + EXPECT_WAIT
    while expected - set(graph) and time.monotonic() < waited:
        rclpy.spin_once(node, timeout_sec=0.1)
        list_topics()
    record["graph"] = graph
    print(json.dumps(record))
    node.destroy_node()
    rclpy.try_shutdown()
    return 0 if done else 1


if __name__ == "__main__":
    sys.exit(main())
