"""Publish one set of joint positions for each robot and print, as JSON, every transform
its robot_state_publisher answers with: {namespace: {child: [parent, xyz, xyzw]}}.

    python tf_probe.py '{"/example_1": {"names": [...], "positions": [...], "frames": 4}, ...}'

Each robot's robot_state_publisher runs in the robot's namespace, with /tf and /tf_static
remapped into it (tests/ros/test_urdf_import.py), so that one probe (rospy allows one node
per process) reads them all apart. It stops once every robot has sent its frames.
"""

import json
import sys
import time

import rospy
from sensor_msgs.msg import JointState
from tf2_msgs.msg import TFMessage

TIMEOUT = 15.0


def main() -> int:
    robots = json.loads(sys.argv[1])
    rospy.init_node("tf_probe", anonymous=True, disable_signals=True)
    seen: dict[str, dict[str, list]] = {ns: {} for ns in robots}

    def take(message, ns):
        for t in message.transforms:
            p, q = t.transform.translation, t.transform.rotation
            seen[ns][t.child_frame_id.lstrip("/")] = [t.header.frame_id.lstrip("/"),
                                                      [p.x, p.y, p.z], [q.x, q.y, q.z, q.w]]

    publishers = {}
    for ns in robots:
        rospy.Subscriber(f"{ns}/tf", TFMessage, take, callback_args=ns)
        rospy.Subscriber(f"{ns}/tf_static", TFMessage, take, callback_args=ns)
        publishers[ns] = rospy.Publisher(f"{ns}/joint_states", JointState, queue_size=1)

    def done() -> bool:
        return all(len(seen[ns]) >= robot["frames"] for ns, robot in robots.items())

    deadline = time.monotonic() + TIMEOUT
    while not done() and time.monotonic() < deadline:
        for ns, robot in robots.items():
            state = JointState(name=robot["names"], position=robot["positions"])
            state.header.stamp = rospy.Time.now()
            publishers[ns].publish(state)
        time.sleep(0.05)
    print(json.dumps(seen))
    rospy.signal_shutdown("done")
    return 0 if done() else 1


if __name__ == "__main__":
    sys.exit(main())
