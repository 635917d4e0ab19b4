"""The two ROS 2 launch files, written for the package at hand.

display.launch.py: robot_state_publisher with the URDF's text, joint_state_publisher_gui,
rviz2 (with the package's RViz configuration when it has one).
gazebo.launch.py: Gazebo Sim through ros_gz_sim's gz_sim.launch.py, robot_state_publisher on
simulated time with the URDF run through xacro (which turns the gz_ros2_control plugin's
`$(find <name>)` into the installed share folder), ros_gz_sim's `create` spawning from the
robot_description topic, the /clock bridge, and controller_manager's spawner for every
controller once the model exists. GZ_SIM_RESOURCE_PATH gets the folder holding the installed
package, so Gazebo finds package://<name>/meshes/... there.

Executables and launch files named here: robot_state_publisher (robot_state_publisher),
joint_state_publisher_gui (joint_state_publisher_gui), rviz2 (rviz2), xacro (xacro),
ros_gz_sim (create, launch/gz_sim.launch.py), ros_gz_bridge (parameter_bridge),
controller_manager (spawner); tests/tool/port/jazzy_packages.json cites where each is defined.
"""

from __future__ import annotations

import json

DISPLAY = '''\
"""Show {name} in RViz with a slider per joint (written by sw2sim port)."""

import os

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch_ros.actions import Node

PACKAGE = "{name}"


def generate_launch_description():
    share = get_package_share_directory(PACKAGE)
    with open(os.path.join(share, "urdf", "{urdf}"), encoding="utf-8") as f:
        description = f.read()
    return LaunchDescription([
        Node(package="robot_state_publisher", executable="robot_state_publisher",
             parameters=[{{"robot_description": description}}]),
        Node(package="joint_state_publisher_gui", executable="joint_state_publisher_gui"),
        Node(package="rviz2", executable="rviz2"{rviz}),
    ])
'''

RVIZ_ARGUMENT = ',\n             arguments=["-d", os.path.join(share, "rviz", "{rviz}")]'

GAZEBO = '''\
"""Spawn {name} in Gazebo Sim and start its controllers (written by sw2sim port)."""

import os

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.actions import (AppendEnvironmentVariable, IncludeLaunchDescription,
                            RegisterEventHandler)
from launch.event_handlers import OnProcessExit
from launch.launch_description_sources import PythonLaunchDescriptionSource
from launch.substitutions import Command, FindExecutable
from launch_ros.actions import Node
from launch_ros.parameter_descriptions import ParameterValue

PACKAGE = "{name}"
CONTROLLERS = {controllers}


def generate_launch_description():
    share = get_package_share_directory(PACKAGE)
    urdf = os.path.join(share, "urdf", "{urdf}")
    # xacro replaces $(find {name}) in the gz_ros2_control plugin's <parameters>.
    description = ParameterValue(Command([FindExecutable(name="xacro"), " ", urdf]),
                                 value_type=str)
    gz_sim = os.path.join(get_package_share_directory("ros_gz_sim"), "launch",
                          "gz_sim.launch.py")
    spawn = Node(package="ros_gz_sim", executable="create", output="screen",
                 arguments=["-topic", "robot_description", "-name", PACKAGE{spawn_z}])
    return LaunchDescription([
        # Gazebo finds package://{name}/... in the folder that holds the installed package.
        AppendEnvironmentVariable("GZ_SIM_RESOURCE_PATH", os.path.dirname(share)),
        IncludeLaunchDescription(PythonLaunchDescriptionSource(gz_sim),
                                 launch_arguments={{"gz_args": "-r empty.sdf"}}.items()),
        Node(package="robot_state_publisher", executable="robot_state_publisher",
             output="screen",
             parameters=[{{"robot_description": description, "use_sim_time": True}}]),
        spawn,
        Node(package="ros_gz_bridge", executable="parameter_bridge",
             arguments=["/clock@rosgraph_msgs/msg/Clock[gz.msgs.Clock"]),
        # The controller manager lives in the gz_ros2_control plugin, which loads with the
        # model: start the controllers once `create` has spawned it.
        RegisterEventHandler(OnProcessExit(
            target_action=spawn,
            on_exit=[Node(package="controller_manager", executable="spawner",
                          arguments=CONTROLLERS)])),
    ])
'''


def display_launch(name: str, urdf: str, rviz: str | None) -> str:
    return DISPLAY.format(name=name, urdf=urdf,
                          rviz=RVIZ_ARGUMENT.format(rviz=rviz) if rviz else "")


def gazebo_launch(name: str, urdf: str, controllers: list[str], z: float = 0.0) -> str:
    """The Gazebo Sim launch file; `z` is the height `create` spawns the model at (its -z
    flag, metres; ros_gz_sim's create.cpp), left out when 0."""
    spawn_z = f',\n                            "-z", "{z:.6g}"' if z else ""
    return GAZEBO.format(name=name, urdf=urdf, controllers=json.dumps(list(controllers)),
                         spawn_z=spawn_z)
