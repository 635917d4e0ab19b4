"""`sw2sim ros-env`: the shell lines that give a terminal's ROS 1 commands the stand-ins."""

from __future__ import annotations

HELP = """\
Prints the shell lines that let this terminal's own ROS 1 commands use what `sw2sim
ros` uses: `roslaunch PKG gazebo.launch` then runs with MuJoCo in Gazebo's place, and
`rostopic` and `rosservice` know the message types Debian does not ship (gazebo_msgs,
control_msgs, controller_manager_msgs). Run it through eval, once in each terminal:

  eval "$(sw2sim ros-env examples)"

FOLDER (any number) is a package, or a folder holding packages, that roslaunch should
find. A catkin workspace built after this line keeps the stand-ins, and Debian's own
ROS packages (/usr/share), when its devel/setup.bash is sourced.

examples:
  eval "$(sw2sim ros-env examples)"
  eval "$(sw2sim ros-env examples ~/catkin_ws/src)"
"""


def add_arguments(parser) -> None:
    parser.add_argument("folders", metavar="FOLDER", nargs="*",
                        help="a package, or a folder holding packages, for ROS_PACKAGE_PATH")


def run(args) -> int:
    from ..ros.run import missing
    from ..ros.terminal import main
    return main(args.folders, missing())
