#!/usr/bin/env python3
"""Practice 1's custom node, ROS 1 + Gazebo Classic version.

Every 10 s (0.1 Hz) it pauses the physics, asks Gazebo to apply 1 N·m to each wheel
joint for 1 s, and lets the simulation run again. Needs a running roscore and Gazebo
with the example_1 model spawned (roslaunch example_1 gazebo.launch).
"""

import rospy
from gazebo_msgs.srv import ApplyJointEffort
from std_srvs.srv import Empty

WHEEL_JOINTS = ["front_left_joint", "front_right_joint", "rear_left_joint", "rear_right_joint"]
TORQUE = 1.0      # N·m
PULSE = 1.0       # s
RATE_HZ = 0.1     # one pulse every 10 s


def main():
    rospy.init_node("periodic_force")
    for service in ("/gazebo/apply_joint_effort", "/gazebo/pause_physics", "/gazebo/unpause_physics"):
        rospy.wait_for_service(service)
    apply_effort = rospy.ServiceProxy("/gazebo/apply_joint_effort", ApplyJointEffort)
    pause = rospy.ServiceProxy("/gazebo/pause_physics", Empty)
    unpause = rospy.ServiceProxy("/gazebo/unpause_physics", Empty)

    # reset=True: when a reset sets the clock back, rate.sleep() returns and the period
    # starts again (without it, it raises ROSTimeMovedBackwardsException: the node dies).
    rate = rospy.Rate(RATE_HZ, reset=True)
    while not rospy.is_shutdown():
        pause()
        for joint in WHEEL_JOINTS:
            # start_time 0 means "now"; the effort stops by itself after `duration`.
            apply_effort(joint_name=joint, effort=TORQUE, start_time=rospy.Time(0),
                         duration=rospy.Duration(PULSE))
        unpause()
        rate.sleep()


if __name__ == "__main__":
    main()
