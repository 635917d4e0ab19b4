#!/usr/bin/env python3
"""Practice 3, ROS 1 version of the movement script: random set points every 5 s.

It publishes std_msgs/Float64 on the topics `mid_arm` and `end_arm`;
launch/gazebo.launch remaps them to the two controllers' command topics.
"""

import random

import rospy
from std_msgs.msg import Float64

LIMIT = 0.7854   # rad, the joints' limits in the URDF
RATE = 0.2       # Hz: a new setpoint every 5 s


def main():
    rospy.init_node("random_setpoints")
    middle = rospy.Publisher("mid_arm", Float64, queue_size=1)
    end = rospy.Publisher("end_arm", Float64, queue_size=1)
    rate = rospy.Rate(RATE, reset=True)   # carries on when a reset sets the clock back
    while not rospy.is_shutdown():
        a, b = random.uniform(-LIMIT, LIMIT), random.uniform(-LIMIT, LIMIT)
        rospy.loginfo("new setpoints: middle %.4f rad, end %.4f rad", a, b)
        middle.publish(Float64(a))
        end.publish(Float64(b))
        rate.sleep()


if __name__ == "__main__":
    try:
        main()
    except rospy.ROSInterruptException:
        pass
