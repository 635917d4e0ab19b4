"""Publish one set of joint positions on /joint_states and print, as JSON, every transform
robot_state_publisher answers with on /tf and /tf_static: child -> [parent, xyz, xyzw].

    python tf_probe.py '["joint_a", ...]' '[0.5, ...]' FRAMES

Run by tests/ros/test_urdf_import.py in a process of its own (rospy allows one node per
process), with the test's ROS_MASTER_URI; it stops once FRAMES transforms have arrived.
"""

import json
import sys
import time

import rospy
from sensor_msgs.msg import JointState
from tf2_msgs.msg import TFMessage

TIMEOUT = 15.0


def main() -> int:
    names, positions, frames = json.loads(sys.argv[1]), json.loads(sys.argv[2]), int(sys.argv[3])
    rospy.init_node("tf_probe", anonymous=True, disable_signals=True)
    seen: dict[str, list] = {}

    def take(message):
        for t in message.transforms:
            p, q = t.transform.translation, t.transform.rotation
            seen[t.child_frame_id.lstrip("/")] = [t.header.frame_id.lstrip("/"),
                                                  [p.x, p.y, p.z], [q.x, q.y, q.z, q.w]]

    rospy.Subscriber("/tf", TFMessage, take)
    rospy.Subscriber("/tf_static", TFMessage, take)
    publisher = rospy.Publisher("/joint_states", JointState, queue_size=1)
    deadline = time.monotonic() + TIMEOUT
    while len(seen) < frames and time.monotonic() < deadline:
        state = JointState(name=names, position=positions)
        state.header.stamp = rospy.Time.now()
        publisher.publish(state)
        time.sleep(0.05)
    print(json.dumps(seen))
    rospy.signal_shutdown("done")
    return 0 if len(seen) >= frames else 1


if __name__ == "__main__":
    sys.exit(main())
