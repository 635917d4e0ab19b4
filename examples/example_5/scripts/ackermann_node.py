#!/usr/bin/env python3
"""Practice 5, ROS 1 version: Ackermann steering for the knuckles and four wheels.

It reads the centre steering joint from /example_5/joint_states, sets the two
knuckle controllers by Equation 4 and each wheel's velocity controller to the
speed its own turning radius needs. The driver's input is a speed in m/s on
`cmd_speed` and a centre angle in rad on steering_controller/command (both
std_msgs/Float64). Launched in the /example_5 namespace by launch/gazebo.launch.
"""

import math

import rospy
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64

WHEELBASE = 0.4     # l, m: from the URDF, rear wheel joints to the knuckle joints
TRACK = 0.3         # w, m: between the two knuckle joints
RADIUS = 0.06       # r, m: the wheels' radius
RATE = 100          # Hz
WHEELS = ("front_left", "front_right", "rear_left", "rear_right")


def knuckle_angles(phi, l=WHEELBASE, w=TRACK):
    """Equation 4: left and right knuckle angles for the centre angle phi."""
    s, c = math.sin(phi), math.cos(phi)
    return (math.atan2(2 * l * s, 2 * l * c - w * s),
            math.atan2(2 * l * s, 2 * l * c + w * s))


def wheel_speeds(speed, phi, l=WHEELBASE, w=TRACK, r=RADIUS):
    """rad/s for each wheel, the rear axle's centre moving at `speed` m/s."""
    k = math.tan(phi) / l
    rear = {"left": 1 - k * w / 2, "right": 1 + k * w / 2}
    out = {}
    for side, share in rear.items():
        out["rear_" + side] = speed * share / r
        out["front_" + side] = speed * math.hypot(share, k * l) / r
    return out


class Ackermann:
    def __init__(self):
        self.phi, self.speed = 0.0, 0.0
        self.knuckles = [rospy.Publisher(f"{side}_knuckle_controller/command", Float64,
                                         queue_size=1) for side in ("left", "right")]
        self.wheels = {key: rospy.Publisher(f"{key}_wheel_controller/command", Float64,
                                            queue_size=1) for key in WHEELS}
        rospy.Subscriber("joint_states", JointState, self.on_joint_states)
        rospy.Subscriber("cmd_speed", Float64, self.on_speed)

    def on_joint_states(self, msg):
        if "steering_joint" in msg.name:
            self.phi = msg.position[msg.name.index("steering_joint")]

    def on_speed(self, msg):
        self.speed = msg.data

    def update(self):
        for publisher, angle in zip(self.knuckles, knuckle_angles(self.phi)):
            publisher.publish(Float64(angle))
        for key, omega in wheel_speeds(self.speed, self.phi).items():
            self.wheels[key].publish(Float64(omega))


def main():
    rospy.init_node("ackermann")
    node = Ackermann()
    rate = rospy.Rate(RATE, reset=True)   # carries on when a reset sets the clock back
    while not rospy.is_shutdown():
        node.update()
        rate.sleep()


if __name__ == "__main__":
    try:
        main()
    except rospy.ROSInterruptException:
        pass
