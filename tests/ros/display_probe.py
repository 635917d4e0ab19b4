"""Listen to what a running display.launch publishes and print it, as JSON, once every
expected joint and frame has been seen (or after TIMEOUT s):

    python display_probe.py '{"joints": [...], "frames": [...]}'

{"joints": the names of the first /joint_states message holding every expected joint (or
of the last one), "publishers": the nodes that sent them, "tf": {child frame: the node that
sent its transform on /tf}}. Run by the ROS tests in a process of its own, as a separate
rospy node.
"""

import json
import sys
import time

import rospy
from sensor_msgs.msg import JointState
from tf2_msgs.msg import TFMessage

TIMEOUT = 40.0   # s: RViz's start on a busy machine slows the others


def main() -> int:
    expected = json.loads(sys.argv[1])
    rospy.init_node("display_probe", anonymous=True, disable_signals=True)
    seen = {"joints": [], "publishers": [], "tf": {}}

    def joint_states(message):
        if not set(expected["joints"]) <= set(seen["joints"]):
            seen["joints"] = list(message.name)
        sender = message._connection_header["callerid"]
        if sender not in seen["publishers"]:
            seen["publishers"].append(sender)

    def tf(message):
        sender = message._connection_header["callerid"]
        for transform in message.transforms:
            seen["tf"][transform.child_frame_id.lstrip("/")] = sender

    rospy.Subscriber("/joint_states", JointState, joint_states)
    rospy.Subscriber("/tf", TFMessage, tf)

    def done() -> bool:
        return (set(expected["joints"]) <= set(seen["joints"])
                and set(expected["frames"]) <= set(seen["tf"]))

    deadline = time.monotonic() + TIMEOUT
    while not done() and time.monotonic() < deadline:
        time.sleep(0.05)
    print(json.dumps(seen))
    rospy.signal_shutdown("done")
    return 0


if __name__ == "__main__":
    sys.exit(main())
