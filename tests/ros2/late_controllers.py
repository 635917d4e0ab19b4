"""An independent ROS 2 node (rclpy only) in the place of a simulation whose controllers are
found late: it publishes /clock from 10 s of simulated time (5 simulated seconds per wall
second), subscribes to Practice 3's two trajectory topics only after LATE wall seconds,
stops the clock LATE + LISTEN seconds after its start, listens one more second, and prints
what it received as JSON: {topic: [[clock, position], ...]}.

    python late_controllers.py LATE LISTEN
"""

import json
import sys
import time

import rclpy
from rosgraph_msgs.msg import Clock
from trajectory_msgs.msg import JointTrajectory

TOPICS = ("/middle_arm_controller/joint_trajectory", "/end_arm_controller/joint_trajectory")
START, SPEED = 10.0, 5.0   # simulated s, simulated s per wall s


def main() -> int:
    late, listen = float(sys.argv[1]), float(sys.argv[2])
    rclpy.init()
    node = rclpy.create_node("late_controllers")
    clock = node.create_publisher(Clock, "/clock", 10)
    received = {t: [] for t in TOPICS}
    now, listening = START, False
    began = time.monotonic()
    while (elapsed := time.monotonic() - began) < late + listen + 1.0:
        if elapsed < late + listen:
            now = START + SPEED * elapsed
            message = Clock()
            message.clock.sec, message.clock.nanosec = int(now), int(now % 1 * 1e9)
            clock.publish(message)
        if elapsed >= late and not listening:
            listening = True
            for topic in TOPICS:
                node.create_subscription(
                    JointTrajectory, topic,
                    lambda m, t=topic: received[t].append([now, m.points[0].positions[0]]), 10)
        rclpy.spin_once(node, timeout_sec=0.01)
    print(json.dumps(received))
    node.destroy_node()
    rclpy.shutdown()
    return 0


if __name__ == "__main__":
    sys.exit(main())
