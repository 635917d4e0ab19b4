"""`sw2sim port`: a ROS 2 Jazzy package written from a ROS 1 export."""

from __future__ import annotations

from .options import EXIT_OK, EXIT_UNUSABLE, package_path, say, urdf_choice

HELP = """\
Writes a ROS 2 Jazzy package (ament_cmake) from a ROS 1 package the exporter wrote,
into the folder OUT (the package's folder: put it in a workspace's src/):
  package.xml              format 3, with what the launch files and controllers need
  CMakeLists.txt           installs urdf, meshes, launch, config (and rviz) into share/
  urdf/NAME.urdf           a <ros2_control> block (gz_ros2_control) in place of the
                           transmissions and the gazebo_ros_control plugin
  config/controllers.yaml  each ROS 1 controller's ROS 2 counterpart, and
                           joint_state_broadcaster; an export with no transmissions and
                           no controllers gets joint_trajectory_controller (position) for
                           its joints and wheel_velocity_controller (velocity) for its
                           wheels, unless --no-controllers
  launch/display.launch.py, launch/gazebo.launch.py   RViz; Gazebo Sim with the controllers
  meshes/                  copied; a <collision> mesh over 20,000 triangles gets a copy in
                           meshes/simplified/ (no surface moved by more than 0.5 % of the
                           part's size), unless --keep-collision-meshes
  README.md                how to build and run it, and every choice made for you
Each choice is also printed. The source is never changed. OUT must be new, empty, or
an earlier output of sw2sim port: porting again replaces only what the port writes and
keeps your files there (a node in scripts/), and the port's files you changed (kept as
they are when the port writes them as before, else as FILE.mine). A name ROS 2 refuses
(Arm_Assembly, robot.SLDASM, 2wd_car) is made legal (arm_assembly, robot_sldasm,
r2wd_car); --name chooses another. The ROS 1 scripts/ are not ported: rospy nodes
need rewriting with rclpy. A package already in ROS 2 form (ament, <ros2_control>,
ROS 2 YAML) keeps its controllers and its <ros2_control> block; the report says what was
fixed (absolute paths of the source folder, xacro's header), or that nothing was.
Without package.xml, the name is the one the URDF's package:// paths, export.log or the
exporter's CSV say. Exit status: 0 written, 2 the input or OUT cannot be used.

examples:
  sw2sim port examples/example_3 -o ~/ros2_ws/src/example_3
  sw2sim port my_robot.zip -o ~/ros2_ws/src/my_robot --name my_robot \\
      --maintainer "Ada Lovelace <ada@example.org>" --license Apache-2.0
  sw2sim port examples/example_1 -o ~/ros2_ws/src/example_1 \\
      --effort-joints front_left_joint,front_right_joint,rear_left_joint,rear_right_joint
"""


def add_arguments(parser) -> None:
    package_path(parser)
    parser.add_argument("-o", "--output", metavar="OUT", required=True,
                        help="the new package's folder (created; in an earlier port's, your own "
                             "files are kept)")
    parser.add_argument("--name", metavar="NEW", help="the ROS 2 package's name (default: the "
                        "source's, made legal)")
    parser.add_argument("--effort-joints", metavar="NAME[,NAME...]", action="append",
                        default=[],
                        help="joints without a transmission to drive with an effort command, "
                             "together, by effort_controller (JointGroupEffortController)")
    parser.add_argument("--no-controllers", dest="default_controllers", action="store_false",
                        help="give an export without transmissions and controllers none: its "
                             "joints then only report their state")
    parser.add_argument("--maintainer", metavar='"NAME <E-MAIL>"',
                        help="package.xml's maintainer (default: the source's; the exporter "
                             "leaves TODO)")
    parser.add_argument("--license", metavar="LICENCE",
                        help="package.xml's licence, such as Apache-2.0 or BSD-3-Clause "
                             "(default: the source's, else TODO)")
    parser.add_argument("--keep-collision-meshes", dest="simplify_collisions",
                        action="store_false",
                        help="use each <collision>'s mesh whole (by default one over 20,000 "
                             "triangles gets a simplified copy in meshes/simplified/)")
    urdf_choice(parser)


def run(args) -> int:
    from ..package import LoadError, find_package
    from ..port import PortError, port
    try:
        package = find_package(args.path, urdf=args.urdf)
        report = port(package, args.output, name=args.name, effort_joints=args.effort_joints,
                      default_controllers=args.default_controllers,
                      maintainer=args.maintainer, license=args.license,
                      simplify_collisions=args.simplify_collisions)
    except (LoadError, PortError) as exc:
        say(f"sw2sim port: {exc}")
        return EXIT_UNUSABLE
    except OSError as exc:
        say(f"sw2sim port: cannot write {args.output}: {exc.strerror or exc}")
        return EXIT_UNUSABLE
    print(report.format())
    return EXIT_OK
