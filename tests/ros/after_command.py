"""Record a robot's joint states from the moment commands arrive, for SECONDS of simulated
time, and print them as JSON:

    python after_command.py SECONDS JOINT_STATES_TOPIC COMMAND_TOPIC ...

The window opens when every COMMAND_TOPIC (std_msgs/Float64) has carried a message, so a
test can publish them as a reader would (`rostopic pub -1 ...`) while this node listens.

{"start": t, "commands": {topic: value}, "states": [[t, {joint: position}], ...],
 "speeds": [[t, {joint: velocity}], ...]}, with every state from `start` on.
Run by the ROS tests in a process of its own, as a separate rospy node.
"""

import json
import sys
import time

import rosgraph
import rospy
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64

WALL_TIMEOUT = 60.0


def wait_for_sim_time(deadline: float) -> None:
    """rospy reads use_sim_time once, at init_node: wait for the launch file to set it."""
    master = rosgraph.Master("/after_command")
    while time.monotonic() < deadline:
        try:
            if master.hasParam("/use_sim_time") and master.getParam("/use_sim_time"):
                return
        except OSError:
            pass
        time.sleep(0.05)


def main() -> int:
    seconds, states_topic, command_topics = float(sys.argv[1]), sys.argv[2], sys.argv[3:]
    deadline = time.monotonic() + WALL_TIMEOUT
    wait_for_sim_time(deadline)
    rospy.init_node("after_command", anonymous=True, disable_signals=True)
    commands, records = {}, []

    def command(message, topic):
        commands.setdefault(topic, message.data)

    def state(message):
        stamp = message.header.stamp.to_sec() or rospy.get_time()
        records.append((stamp, dict(zip(message.name, message.position)),
                        dict(zip(message.name, message.velocity))))

    rospy.Subscriber(states_topic, JointState, state)
    for topic in command_topics:
        rospy.Subscriber(topic, Float64, command, callback_args=topic)
    while len(commands) < len(command_topics) and time.monotonic() < deadline:
        time.sleep(0.01)
    start = rospy.get_time()
    while rospy.get_time() < start + seconds and time.monotonic() < deadline:
        time.sleep(0.01)
    done = len(commands) == len(command_topics) and rospy.get_time() >= start + seconds
    kept = [r for r in list(records) if r[0] >= start]
    print(json.dumps({"start": start, "commands": commands,
                      "states": [[t, q] for t, q, _ in kept],
                      "speeds": [[t, v] for t, _, v in kept]}))
    rospy.signal_shutdown("done")
    return 0 if done else 1


if __name__ == "__main__":
    sys.exit(main())
