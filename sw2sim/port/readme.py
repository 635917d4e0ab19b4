"""README.md of the ported package: what it is, how to build and run it, what was chosen."""

from __future__ import annotations


def readme(name: str, source: str, controllers: list[str], choices: list[str],
           files: list[str], usage: list[str] = ()) -> str:
    """`usage`: Markdown lines saying how to command the controllers the port added."""
    out = [f"# {name}", "",
           f"A ROS 2 Jazzy package (ament_cmake) made by `sw2sim port` from the ROS 1 package "
           f"`{source}` that the SolidWorks-to-URDF exporter wrote. It shows the robot in "
           "RViz and simulates it in Gazebo Sim (Harmonic) with ros2_control.", "",
           "## Build and run", "",
           "```bash",
           "mkdir -p ~/ros2_ws/src && cp -r " + name + " ~/ros2_ws/src/",
           "cd ~/ros2_ws",
           "rosdep install --from-paths src --ignore-src -y",
           "colcon build",
           "source install/setup.bash",
           f"ros2 launch {name} display.launch.py   # RViz, a slider per joint",
           f"ros2 launch {name} gazebo.launch.py    # Gazebo Sim with the controllers",
           "```", "",
           "`ros2 control list_controllers` then lists " +
           ", ".join(f"`{c}`" for c in controllers) + ".", "",
           *(["## Moving the joints", "",
              "The exported package had no transmissions and no controllers, so the port "
              "added the controllers below (`sw2sim port --no-controllers` leaves them out). "
              "Once the launch file is running:", "", *usage] if usage else []),
           "## Files", "",
           *(f"- `{f}`" for f in files), "",
           "## Choices made for you", "",
           *(f"- {c}" for c in choices), ""]
    return "\n".join(out)
