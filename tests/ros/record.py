"""Record, on simulated time, a robot's joint states and its controllers' commands, and
print them as JSON once the clock passes UNTIL seconds:

    python record.py UNTIL JOINT_STATES_TOPIC COMMAND_TOPIC ...

UNTIL is a simulated time, `+S` for S seconds after the first joint state heard (a
subscription takes a wall-clock moment to connect, many simulated seconds when the
simulation runs faster than real time), or `+S@TOPIC` for S seconds after the first
message on TOPIC, one of the COMMAND_TOPICs (a command that a slow-starting `rostopic pub`
sends).

{"states": [[t, {joint: position}], ...], "speeds": [[t, {joint: velocity}], ...],
 "commands": {topic: [[t, value], ...]}}
Run by the ROS tests in a process of its own, as a separate rospy node.
"""

import json
import sys
import threading
import time

import rosgraph
import rospy
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64

WALL_TIMEOUT = 90.0


def main() -> int:
    until, states_topic, command_topics = sys.argv[1], sys.argv[2], sys.argv[3:]
    # rospy reads use_sim_time once, at init_node: wait for the launch file to set it.
    master, deadline = rosgraph.Master("/recorder"), time.monotonic() + WALL_TIMEOUT
    while time.monotonic() < deadline:
        try:
            if master.hasParam("/use_sim_time") and master.getParam("/use_sim_time"):
                break
        except OSError:
            pass
        time.sleep(0.1)
    rospy.init_node("recorder", anonymous=True, disable_signals=True)
    seconds, _, trigger = until.partition("@")
    relative = until.startswith("+")
    # a relative end is set by the first state, or by the trigger's first message
    until = float("inf") if relative else float(until)
    states, speeds, commands = [], [], {topic: [] for topic in command_topics}
    lock = threading.Lock()   # the callbacks' threads against the final print

    def command(topic, message):
        nonlocal until
        with lock:
            commands[topic].append([rospy.get_time(), message.data])
            if topic == trigger and len(commands[topic]) == 1:
                until = rospy.get_time() + float(seconds[1:])

    def state(message):
        nonlocal until
        # the simulation's own time of the state (the clock's messages may be coarser)
        t = message.header.stamp.to_sec() or rospy.get_time()
        with lock:
            if not states:
                if relative and not trigger:
                    until = t + float(seconds[1:])
                print("recording", file=sys.stderr, flush=True)   # a test may wait for this
            states.append([t, dict(zip(message.name, message.position))])
            speeds.append([t, dict(zip(message.name, message.velocity))])

    rospy.Subscriber(states_topic, JointState, state)
    for topic in command_topics:
        rospy.Subscriber(topic, Float64, lambda message, topic=topic: command(topic, message))
    deadline = time.monotonic() + WALL_TIMEOUT
    while rospy.get_time() < until and time.monotonic() < deadline:
        time.sleep(0.05)
    with lock:
        print(json.dumps({"states": states, "speeds": speeds, "commands": commands}))
    rospy.signal_shutdown("done")
    return 0 if rospy.get_time() >= until else 1


if __name__ == "__main__":
    sys.exit(main())
