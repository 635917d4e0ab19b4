"""The stand-in ROS packages, written where roslaunch finds them: `gazebo_ros`,
`controller_manager` and `tf`, with the launch file and node names the exported
packages' launch files use, and `joint_state_publisher_gui`, the sliders' window their
display.launch opens. Their nodes run sw2sim.ros.gzserver (the simulation,
sw2sim.ros.world), sw2sim.ros.nodes and sw2sim.ros.sliders with the Python that runs
sw2sim (SW2SIM_PYTHON).

They go on ROS_PACKAGE_PATH after the user's own packages and Debian's, so a package's
gazebo.launch and display.launch run unchanged. Debian 12's own joint_state_publisher_gui
stops as it opens (sw2sim.ros.sliders says why); installed, it would come first, so
`make setup` leaves it out.
"""

from __future__ import annotations

import stat
from pathlib import Path

EMPTY_WORLD = """<launch>
  <!-- MuJoCo stands in for gzserver here (sw2sim ros); Gazebo's own arguments are
       accepted, and those without a MuJoCo meaning are ignored. -->
  <arg name="paused" default="false" />
  <arg name="use_sim_time" default="true" />
  <arg name="gui" default="true" />
  <arg name="gui_required" default="false" />
  <arg name="headless" default="false" />
  <arg name="debug" default="false" />
  <arg name="verbose" default="false" />
  <arg name="world_name" default="worlds/empty.world" />
  <arg name="physics" default="ode" />
  <arg name="recording" default="false" />
  <arg name="extra_gazebo_args" default="" />
  <arg name="respawn_gazebo" default="false" />
  <arg name="output" default="screen" />
  <arg name="server_required" default="false" />
  <arg name="enable_ros_network" default="true" />
  <arg name="pub_clock_frequency" default="100" />
  <arg name="use_clock_frequency" default="false" />
  <param name="/use_sim_time" value="$(arg use_sim_time)" />
  <node name="gazebo" pkg="gazebo_ros" type="gzserver"
        args="$(eval '-u' if arg('paused') else '')" output="$(arg output)"
        required="$(arg server_required)" />
</launch>
"""

# package -> {file: (module and node, or None for a data file)}
NODES = {
    "gazebo_ros": {"gzserver": "sw2sim.ros.gzserver", "spawn_model": "sw2sim.ros.nodes spawn_model"},
    "controller_manager": {"spawner": "sw2sim.ros.nodes spawner"},
    "tf": {"static_transform_publisher": "sw2sim.ros.nodes static_transform_publisher"},
    "joint_state_publisher_gui": {"joint_state_publisher_gui": "sw2sim.ros.sliders"},
}


def _manifest(name: str) -> str:
    return (f'<?xml version="1.0"?>\n<package format="2">\n  <name>{name}</name>\n'
            f"  <version>0.0.0</version>\n  <description>{name} as sw2sim ros stands in for it"
            f"</description>\n  <maintainer email=\"sw2sim@example.com\">sw2sim</maintainer>\n"
            f"  <license>MIT</license>\n</package>\n")


def write(folder: Path) -> Path:
    """Write the packages into `folder` (once per content) and return it."""
    for package, nodes in NODES.items():
        root = folder / package
        root.mkdir(parents=True, exist_ok=True)
        _write(root / "package.xml", _manifest(package))
        for node, module in nodes.items():
            script = root / "nodes" / node
            script.parent.mkdir(exist_ok=True)
            _write(script, f'#!/bin/sh\nexec "${{SW2SIM_PYTHON:-python3}}" -m {module} "$@"\n')
            script.chmod(script.stat().st_mode | stat.S_IXUSR | stat.S_IXGRP | stat.S_IXOTH)
    _write(folder / "gazebo_ros" / "launch" / "empty_world.launch", EMPTY_WORLD)
    return folder


def _write(path: Path, text: str) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    if not path.is_file() or path.read_text(encoding="utf-8") != text:
        path.write_text(text, encoding="utf-8")
