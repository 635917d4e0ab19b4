"""`sw2sim ros`: the package's own launch file under ROS 1, MuJoCo standing in for Gazebo."""

from __future__ import annotations

from .options import simulation, viewer_or_not

HELP = """\
Runs the package's own gazebo.launch (or --launch FILE) under ROS 1 unchanged, with
MuJoCo standing in for Gazebo: gazebo_ros (empty_world.launch, spawn_model, the
/gazebo services), controller_manager's spawner and the ros_control controllers the
package's YAML names (joint_state_controller, effort_controllers position, velocity and
effort controllers). It uses the master at ROS_MASTER_URI if one answers, else starts
its own there; when that port is taken by something else, it says what holds it (and
the kill that frees it) and starts its master on another port. It stops everything it
started on exit, Ctrl-C or --duration, and also when it is killed. Node types the
exporter wrote that Noetic renamed (robot_state_publisher's `state_publisher`) run as
what they became, in a copy of the launch file. Its line
"for ROS commands in another terminal" is what another terminal runs first, for
`rostopic` and `rosservice` there, with the master's address when it is not ROS's default.
Exit status: 0 done, 1 a node of the launch could not start or died (named), 2 it could
not run, 130 Ctrl-C, 143 SIGTERM, 129 SIGHUP.

examples:
  sw2sim ros examples/example_3 --duration 20
  sw2sim ros examples/example_5 --view
  sw2sim ros my_robot --launch my_robot/launch/gazebo.launch
"""


def add_arguments(parser) -> None:
    parser.add_argument("path", metavar="PATH", help="package folder or .zip of it")
    parser.add_argument("--launch", metavar="FILE", help="the launch file (default: "
                        "launch/gazebo.launch of the package)")
    simulation(parser)


def run(args) -> int:
    from ..ros.run import run as run_ros
    return run_ros(args.path, launch=args.launch, duration=args.duration,
                   realtime=args.realtime, view=viewer_or_not("ros", args.view),
                   say=lambda text: print(text, flush=True))
