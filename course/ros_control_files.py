"""The ros_control files the lessons add by hand to an exported package.

The exporter writes a joint-names YAML and a launch file that only spawns the model;
Practices 3 to 5 turn the YAML into a controller configuration and add the nodes that
load and start the controllers. Kept apart from `exporter_format`, which writes only
what the exporter itself writes.
"""

from __future__ import annotations

from .exporter_format import Robot, joint_names_yaml

POSITION_CONTROLLER = "effort_controllers/JointPositionController"
ROS_CONTROL_DEPENDS = ["gazebo_ros_control", "controller_manager", "joint_state_controller",
                       "effort_controllers"]


def controllers_yaml(robot: Robot, controllers: dict[str, tuple[str, dict]], state_rate: int,
                     note: str) -> str:
    """The joint-names YAML turned into a controller configuration, as the lessons do by hand:
    a joint state controller and, per joint, an effort-based position controller with its
    PID gains. `controllers` maps a joint to (controller name, gains)."""
    entries = "".join(
        f"\n  {name}:\n    type: {POSITION_CONTROLLER}\n    joint: {joint}\n"
        f"    pid: {{{', '.join(f'{k}: {v}' for k, v in gains.items())}}}\n"
        for joint, (name, gains) in controllers.items())
    return (f"{joint_names_yaml(robot)}\n# {note}\n{robot.name}:\n"
            f"  joint_state_controller:\n    type: joint_state_controller/JointStateController\n"
            f"    publish_rate: {state_rate}\n{entries}")


def ros_control_nodes(name: str, controllers) -> str:
    """Launch-file lines that load the controller YAML, start the controllers and publish
    the robot's frames from the namespaced joint states."""
    return f"""  <rosparam
    file="$(find {name})/config/joint_names_{name}.yaml"
    command="load" />
  <node
    name="controller_spawner"
    pkg="controller_manager"
    type="spawner"
    ns="/{name}"
    args="joint_state_controller {' '.join(controllers)}"
    output="screen" />
  <node
    name="robot_state_publisher"
    pkg="robot_state_publisher"
    type="robot_state_publisher">
    <remap
      from="/joint_states"
      to="/{name}/joint_states" />
  </node>
"""
