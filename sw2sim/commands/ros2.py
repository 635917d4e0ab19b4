"""`sw2sim ros2`: a ROS 2 package's robot under rclpy, MuJoCo standing in for Gazebo Sim."""

from __future__ import annotations

from .options import simulation, viewer_or_not

HELP = """\
Runs a ROS 2 package's robot under real ROS 2 (rclpy, Jazzy), with MuJoCo standing in
for Gazebo Sim, gz_ros2_control and robot_state_publisher, in one process: /clock,
/robot_description, /tf and /tf_static, /joint_states from joint_state_broadcaster, and
the topics of the controllers config/controllers.yaml names
(joint_trajectory_controller, the forward command controllers, pid_controller), with
ros2_controllers' names and types. A ROS 1 export is ported first (`sw2sim port`) into a
temporary folder. ROS 2 traffic stays on this machine, in ROS_DOMAIN_ID (0 if unset);
give a second terminal the same ROS_DOMAIN_ID and ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST.
It stops on Ctrl-C, SIGTERM or --duration.

examples:
  sw2sim ros2 my_robot_ros2 --duration 20
  sw2sim ros2 examples/example_3 --view
  ROS_DOMAIN_ID=7 sw2sim ros2 my_robot_ros2 --realtime 0
"""


def add_arguments(parser) -> None:
    parser.add_argument("path", metavar="PATH", help="package folder or .zip of it (ROS 2, or a "
                        "ROS 1 export, ported first)")
    simulation(parser)


def run(args) -> int:
    from ..ros2.run import run as run_ros2
    return run_ros2(args.path, duration=args.duration, realtime=args.realtime,
                    view=viewer_or_not("ros2", args.view),
                    say=lambda text: print(text, flush=True))
