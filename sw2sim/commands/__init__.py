"""The `sw2sim` commands: one module per command, named in one table.

Each module holds its command's help text, its options (`add_arguments`) and its entry
point (`run`). `sw2sim.cli` imports only the module of the command being run, so
`sw2sim --help` and `sw2sim check` pay nothing for the others.
"""

from __future__ import annotations

import difflib
import importlib
from types import ModuleType

# name: (module in this package, the one-line summary `sw2sim --help` lists)
COMMANDS: dict[str, tuple[str, str]] = {
    "check": ("check", "list what is wrong with a package, with fixes"),
    "compare": ("compare", "compare your export with a lesson's reference package"),
    "convert": ("convert", "write a MuJoCo model folder (robot, scene, meshes, README)"),
    "view": ("view", "open the package in MuJoCo's viewer"),
    "render": ("render", "save a picture of the package (no display needed)"),
    "ros": ("ros", "run the package's launch file under ROS 1, with MuJoCo in Gazebo's place"),
    "ros-env": ("ros_env", "print the lines that let a terminal's ROS 1 commands use MuJoCo "
                           "in Gazebo's place"),
    "ros2": ("ros2", "run a ROS 2 package's robot under rclpy, with MuJoCo in Gazebo Sim's "
                     "place"),
    "plot": ("plot", "plot topics' numeric fields over time under ROS 1 or ROS 2, in "
                     "rqt_plot's place"),
    "port": ("port", "write a ROS 2 Jazzy package from the ROS 1 package"),
    "edits": ("edits", "save a package's hand edits, and restore them after exporting again"),
}


def module(name: str) -> ModuleType:
    """The module of the command `name` (one of COMMANDS)."""
    return importlib.import_module(f"{__name__}.{COMMANDS[name][0]}")


def closest(name: str) -> str | None:
    """The command a mistyped `name` most likely meant, or None."""
    found = difflib.get_close_matches(name, COMMANDS, n=1, cutoff=0.6)
    return found[0] if found else None
