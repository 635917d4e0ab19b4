"""`sw2sim ros2 PACKAGE`: a ROS 2 package under real rclpy, with MuJoCo standing in for
Gazebo Sim, gz_ros2_control (the controller manager and the controllers its YAML names)
and robot_state_publisher."""

from __future__ import annotations

import importlib.util

INSTALL = ('ROS 2 (rclpy) is not installed for this Python: pip install "sw2sim[ros2]" '
           '(Linux, Python 3.10-3.12, in an environment without ROS 1), or in a clone of the '
           'course `make setup`, then .venv-ros2/bin/sw2sim')


def missing() -> str | None:
    """Why `sw2sim ros2` cannot run with this Python, or None when it can."""
    try:
        found = importlib.util.find_spec("rclpy") is not None
    except (ImportError, ValueError):
        found = False
    return None if found else INSTALL
