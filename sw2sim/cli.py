"""The `sw2sim` command: check, compare, convert, view and render an exported package.

Every command takes the package folder (the one holding package.xml), its .urdf file or
a .zip of it (sw2sim.archive), reads it once (`sw2sim.package.find_package`, inside the check every command starts with)
and hands the Package on; `compare` reads two, without the check. MuJoCo is imported only
inside a command: `view` must choose its GL platform first.

The module is over 500 lines because every command's help text sits here, next to the
options it explains, so that `sw2sim COMMAND --help` is written and read in one place.
"""

from __future__ import annotations

import argparse
import contextlib
import os
import sys
from pathlib import Path

from . import gl

EXIT_OK, EXIT_ERRORS, EXIT_UNUSABLE = 0, 1, 2
EXIT_BROKEN_PIPE = 141   # 128 + SIGPIPE: what a shell reports when the reader went away
FORMATS = ("text", "json", "github", "sarif")   # what `check --format` prints

DESCRIPTION = """\
From a SolidWorks-exported URDF package to a MuJoCo simulation: check the package
and say how to fix what is wrong, compare it with a lesson's reference package,
convert it to a MuJoCo model folder, open it in MuJoCo's viewer, or save a picture
of it.

PATH is the package folder (the one holding package.xml), its .urdf file, or a .zip
of the package folder (read as it is; nothing is unpacked beside it).
Exit status: 0 done (warnings allowed), 1 the package has errors, 2 it cannot be
used at all (or the command could not run).
"""

EXAMPLES = """\
examples:
  sw2sim check examples/example_4
  sw2sim check my_robot/urdf/my_robot.urdf --json > report.json
  sw2sim check my_robot.zip
  sw2sim compare my_export examples/example_1
  sw2sim convert examples/example_4 -o example_4_mujoco
  sw2sim view examples/example_4
  sw2sim render examples/example_4 -o example_4.png --azimuth 200
  sw2sim edits save examples/example_1        # before exporting again
Run `sw2sim COMMAND --help` for each command's options.
"""

CHECK_HELP = """\
Reads the package as ROS, Gazebo and MuJoCo would: the XML, package.xml, the
meshes, masses and inertias, joints and limits, collisions. Then, unless --no-sim
is given, it simulates the model for 4 s (2 s at rest, 2 s with small random
inputs) to catch a model that blows up or flies apart. The base is fixed when the
URDF joins it to a link named `world`, free otherwise, as in Gazebo.

Each finding is one line:
  FILE:LINE: SEVERITY [RULE-ID] what is wrong. Fix: what to do
ending with "Convert repairs it: ..." where `sw2sim convert` would repair it in
the model it writes, followed by a summary. Exit status: 0 no errors (warnings allowed), 1 errors,
2 the input cannot be used (missing path, not XML, not a URDF).

Several PATHs are checked one after the other, each with its own summary, then a
line for them all; the exit status is the worst of theirs, and --json prints a list.

For CI, --format github prints each finding as a GitHub Actions workflow command
(::error file=FILE,line=LINE,title=RULE-ID::what is wrong. Fix: ...; warnings as
::warning), which a workflow shows as annotations on the files, and --format sarif
prints SARIF 2.1.0, the format code scanning reads. Their paths are relative to the
working folder: run it from the repository's root.

examples:
  sw2sim check examples/example_4
  sw2sim check my_robot --no-sim
  sw2sim check my_robot --json | python -m json.tool
  sw2sim check submissions/*.zip --no-sim
  sw2sim check exports/* --format github       # in a GitHub Actions step
  sw2sim check exports/* --format sarif > sw2sim.sarif
"""

COMPARE_HELP = """\
Compares your export of a lesson's model (MINE) with the lesson's package
(REFERENCE, examples/example_N), link by link and joint by joint: the link tree,
joint types, origins, axes and limits, and each link's mass, centre of mass,
inertia and mesh size. Links are matched by name, or by their place in the tree
where the names differ (which is reported). Directions are the model's: the axes
of the base link's frame. A mesh with no triangles or no volume, a number off by
a unit's factor (millimetres, centimetres, degrees, or the decimal point) and an
inertia taken about the link's origin instead of its centre of mass are named so.

A correct SolidWorks model matches within: mass 1 %, inertia 2 % (the lesson's
masses come from faceted meshes, SolidWorks' from the exact solid), 1 mm and
0.5 degrees. Each difference is one line:
  FILE:LINE: [CODE] joint or link: yours, the reference's (by how much). Cause and fix
Packages of two different robots are not compared: when under half of the links
are alike (by name, or by place and joint type), or when MINE agrees (place and
mass) with another lesson's package in examples/ in at least half of its links
and with REFERENCE in fewer, the message says it looks like another lesson's
package and names the one it resembles most.
Exit status: 0 the export matches, 1 it differs, 2 nothing was compared (a
package cannot be read, or it looks like another lesson's package).

examples:
  sw2sim compare my_export examples/example_1
  sw2sim compare my_arm/urdf/my_arm.urdf examples/example_3 --json
"""

CONVERT_HELP = """\
Writes a folder in the layout of the MuJoCo Menagerie's models:
  NAME.xml    the robot: bodies, joints, meshes, and actuators made from the
              package's transmissions and controller YAML
  scene.xml   includes NAME.xml and adds a floor, a light and a sky
  assets/     the mesh files, copied
  README.md   what came from where, and what was changed or dropped
The result needs plain MuJoCo only: python -m mujoco.viewer --mjcf=DIR/scene.xml

The package is checked first (as `sw2sim check`). Problems with exactly one right
answer are repaired in the written model, never in your package, and listed in
README.md under Repairs with the lasting fix: a mesh path that differs from its
file in capitals or slashes, the exporter's empty (all-zero) joint limits, an
effort of 0, an inertia that breaks A + B >= C by rounding. Problems that only
ROS's build tools care about (package.xml) are reported and do not stop it. Any
other error stops it: nothing is written, and the exit status is 1.

An existing non-empty DIR is refused unless --force is given; --force replaces
only the files convert writes and deletes nothing.

examples:
  sw2sim convert examples/example_5 -o example_5_mujoco
  sw2sim convert my_robot -o my_robot_mujoco --force
  sw2sim convert my_robot -o my_robot_mujoco --strict        # repair nothing
  sw2sim convert my_robot -o my_robot_mujoco --density 2700  # masses from the meshes
"""

VIEW_HELP = """\
Opens MuJoCo's interactive viewer (it needs a display). Each joint gets a slider
in the viewer's Control panel: joints with a controller in the package's YAML
get that controller's actuator (as in `sw2sim convert`), the others a position
actuator over their limits, or a velocity actuator if they have none.

The package is checked first (without the simulation); findings are printed,
and the model opens as long as MuJoCo can load it, so you can look at a problem.
Without a display (a server, a container), use `sw2sim render` instead, or log in
with `ssh -X` so the window opens on your screen.

examples:
  sw2sim view examples/example_4
"""

RENDER_HELP = """\
Saves a PNG picture of the model at its start pose, drawn off-screen (no display
needed). The camera looks from AZIMUTH and ELEVATION degrees and frames the whole
robot as it stands on the floor. An existing file is kept unless --force is given.

The package is checked first (without the simulation); findings are printed,
and the picture is made as long as MuJoCo can load the model.

examples:
  sw2sim render examples/example_4 -o example_4.png
  sw2sim render examples/example_5 -o car.png --width 1600 --height 1000 \
      --azimuth 210 --elevation -15 --shadows
"""


ROS_HELP = """\
Runs the package's own gazebo.launch (or --launch FILE) under ROS 1 unchanged, with
MuJoCo standing in for Gazebo: gazebo_ros (empty_world.launch, spawn_model, the
/gazebo services), controller_manager's spawner and the ros_control controllers the
package's YAML names (joint_state_controller, effort_controllers position, velocity and
effort controllers). It uses the master at ROS_MASTER_URI if one answers, else starts
its own, and stops everything it started on exit, Ctrl-C or --duration, and also when it
is killed. Node types the exporter wrote that Noetic renamed (robot_state_publisher's
`state_publisher`) run as what they became, in a copy of the launch file. Its second
line is what another terminal runs first, for `rostopic` and `rosservice` there.
Exit status: 0 done, 1 a node of the launch could not start or died (named), 2 it could
not run, 130 Ctrl-C, 143 SIGTERM, 129 SIGHUP.

examples:
  sw2sim ros examples/example_3 --duration 20
  sw2sim ros examples/example_5 --view
  sw2sim ros my_robot --launch my_robot/launch/gazebo.launch
"""

ROS_ENV_HELP = """\
Prints the shell lines that let this terminal's own ROS 1 commands use what `sw2sim
ros` uses: `roslaunch PKG gazebo.launch` then runs with MuJoCo in Gazebo's place, and
`rostopic` and `rosservice` know the message types Debian does not ship (gazebo_msgs,
control_msgs, controller_manager_msgs). Run it through eval, once in each terminal:

  eval "$(sw2sim ros-env examples)"

FOLDER (any number) is a package, or a folder holding packages, that roslaunch should
find. A catkin workspace built after this line keeps the stand-ins when its
devel/setup.bash is sourced.
"""


PORT_HELP = """\
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
  README.md                how to build and run it, and every choice made for you
Each choice is also printed. The source is never changed. OUT must be new, empty, or
an earlier output of sw2sim port (which is replaced). A name ROS 2 refuses
(Arm_Assembly, robot.SLDASM, 2wd_car) is made legal (arm_assembly, robot_sldasm,
r2wd_car); --name chooses another. The ROS 1 scripts/ are not ported: rospy nodes
need rewriting with rclpy. Exit status: 0 written, 2 the input or OUT cannot be used.

examples:
  sw2sim port examples/example_3 -o ~/ros2_ws/src/example_3
  sw2sim port my_robot.zip -o ~/ros2_ws/src/my_robot --name my_robot
  sw2sim port examples/example_1 -o ~/ros2_ws/src/example_1 \\
      --effort-joints front_left_joint,front_right_joint,rear_left_joint,rear_right_joint
"""


ROS2_HELP = """\
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


EDITS_HELP = """\
Both of the exporter's buttons rewrite the URDF and its CSV, package.xml,
CMakeLists.txt, config/joint_names_NAME.yaml and the two launch files, so exporting
again wipes what was added to them by hand. Keep the hand edits across a re-export:

  save     copies those files into PKG/hand_edits/ (with a manifest and a README),
           a folder the exporter never writes. Run it after each hand edit.
  restore  after the re-export: puts the saved package.xml, CMakeLists.txt, launch
           files and joint-names YAML back, and carries into the new URDF what the
           exporter never writes (transmissions, <gazebo> elements, a `world` link and
           its joint, joints' <dynamics>, links' colours), keeping the new numbers.
           Each restored item is one line; what it does not carry is named. A file
           changed more than a minute after the new URDF was written is not
           overwritten (--force does), and joints that are gone or new are named.

Exit status: 0 done, 1 restore refused (a file edited since the re-export) or save
refused (the saved copy has hand edits the URDF lacks: restore first), 2 nothing
saved, or the package cannot be read.

examples:
  sw2sim edits save examples/example_1
  sw2sim edits restore examples/example_1
"""


def _simulation_options(parser) -> None:
    """The options `ros` and `ros2` share: how long, how fast, and the viewer."""
    parser.add_argument("--duration", type=float, metavar="S", help="stop after S seconds")
    parser.add_argument("--realtime", type=float, default=1.0, metavar="F",
                        help="real-time factor: 1 (default) as in Gazebo, 0 as fast as possible")
    parser.add_argument("--view", action="store_true",
                        help="show the simulation in MuJoCo's viewer (needs a display)")

def main(argv: list[str] | None = None) -> int:
    """Run one command; return its exit status (never raise on bad input)."""
    parser = _parser()
    args = parser.parse_args(argv)
    if args.command is None:
        parser.print_help()
        return EXIT_UNUSABLE
    try:
        with _drawing_for(args.command, argv):
            status = args.run(args)
        sys.stdout.flush()   # a closed pipe shows here, not in Python's flush at exit
        if argv is None and args.command in ENDS_AT_ONCE:
            _end_now(status)
        return status
    except KeyboardInterrupt:
        return 130
    except BrokenPipeError:
        # Whatever read the output stopped early (`sw2sim check PATH | head`): stop quietly,
        # as other command-line tools do, and keep Python from failing again on the pipe
        # when it flushes at exit.
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return EXIT_BROKEN_PIPE
    except Exception as exc:  # noqa: BLE001  (a bug in sw2sim: say so plainly, no traceback)
        _say(f"sw2sim {args.command}: unexpected error ({type(exc).__name__}: {exc}). "
             "This is a fault in sw2sim, not necessarily in your package; please report it "
             "with the command you ran.")
        return EXIT_UNUSABLE


# Commands that, run from the command line, end the process as soon as their output is out
# (`_end_now`): they only read the user's files, and write nothing but their report.
ENDS_AT_ONCE = frozenset({"check"})


def _end_now(status: int) -> None:
    """End the process with `status` without Python's finalisation, which takes `sw2sim
    check` a tenth of a second (numpy's and MuJoCo's modules torn down one object at a
    time) after everything is said. The folders of unpacked archives are removed first, as
    at a normal exit; the command's output is flushed."""
    from . import archive
    archive.discard()
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(status)


def _drawing_for(command: str, argv: list[str] | None):
    """The GL platform a command runs with. The command line's own `sw2sim check` (no
    argv: the process ends with it) draws nothing, so MuJoCo, imported by the stability
    run, loads no OpenGL library; a caller that passes argv (a test, a notebook) may draw
    afterwards in the same process, and keeps its platform."""
    if argv is None and command == "check":
        return gl.not_drawing()
    return contextlib.nullcontext()


class _Version(argparse.Action):
    """--version, looked up only when asked for: reading the installed package's metadata
    costs every command a twentieth of a second of start-up."""

    def __init__(self, option_strings, dest=argparse.SUPPRESS, **kwargs):
        super().__init__(option_strings, dest, nargs=0, default=argparse.SUPPRESS,
                         help="show program's version number and exit")

    def __call__(self, parser, namespace, values, option_string=None):
        print(f"{parser.prog} {_version()}")
        parser.exit()


def _parser() -> argparse.ArgumentParser:
    raw = argparse.RawDescriptionHelpFormatter
    parser = argparse.ArgumentParser(prog="sw2sim", description=DESCRIPTION, epilog=EXAMPLES,
                                     formatter_class=raw)
    parser.add_argument("--version", action=_Version)
    parser.set_defaults(command=None)
    commands = parser.add_subparsers(title="commands", metavar="COMMAND")

    check = commands.add_parser("check", help="list what is wrong with a package, with fixes",
                                description=CHECK_HELP, formatter_class=raw)
    check.add_argument("path", metavar="PATH", nargs="+",
                       help="package folder, .urdf file or .zip of the package (several: each "
                            "is checked in turn)")
    check.add_argument("--urdf", metavar="NAME", help="which URDF to read, where the package "
                         "holds several (its file name)")
    check.add_argument("--json", action="store_true", help="print the report as JSON "
                       "(the same as --format json)")
    check.add_argument("--format", choices=FORMATS, help="how to print the findings: text "
                       "(the default), json, github (GitHub Actions workflow commands) or "
                       "sarif (SARIF 2.1.0)")
    check.add_argument("--no-sim", action="store_true", help="skip the 4 s stability run")
    check.set_defaults(command="check", run=_check)

    compare = commands.add_parser("compare", help="compare your export with a lesson's "
                                  "reference package", description=COMPARE_HELP,
                                  formatter_class=raw)
    compare.add_argument("mine", metavar="MINE", help="your package folder, .urdf file or .zip")
    compare.add_argument("reference", metavar="REFERENCE", help="the lesson's package folder "
                         "(examples/example_N) or .urdf file")
    compare.add_argument("--urdf", metavar="NAME", help="which URDF of MINE to read, where it "
                         "holds several (its file name)")
    compare.add_argument("--reference-urdf", metavar="NAME", help="the same for REFERENCE")
    compare.add_argument("--json", action="store_true", help="print the differences as JSON")
    compare.set_defaults(command="compare", run=_compare)

    convert = commands.add_parser("convert", help="write a MuJoCo model folder (robot, scene, "
                                  "meshes, README)",
                                  description=CONVERT_HELP, formatter_class=raw)
    convert.add_argument("path", metavar="PATH",
                         help="package folder, .urdf file or .zip of the package")
    convert.add_argument("--urdf", metavar="NAME", help="which URDF to read, where the package "
                         "holds several (its file name)")
    convert.add_argument("-o", "--output", metavar="DIR", required=True,
                         help="the folder to write (created if missing)")
    convert.add_argument("--force", action="store_true",
                         help="write into a non-empty DIR, replacing only convert's own files")
    convert.add_argument("--strict", action="store_true",
                         help="repair nothing: refuse the package on any error that affects the "
                              "simulation")
    convert.add_argument("--lock-default-limits", action="store_true",
                         help="lock joints whose limits are the exporter's empty ones (all 0) "
                              "instead of letting them move freely")
    convert.add_argument("--density", type=_density, metavar="KG_PER_M3",
                         help="recompute zero or implausible masses and inertias from the "
                              "meshes, as solids of this density (aluminium 2700, steel 7850, "
                              "ABS 1050)")
    convert.set_defaults(command="convert", run=_convert)

    view = commands.add_parser("view", help="open the package in MuJoCo's viewer",
                               description=VIEW_HELP, formatter_class=raw)
    view.add_argument("path", metavar="PATH",
                      help="package folder, .urdf file or .zip of the package")
    view.add_argument("--urdf", metavar="NAME", help="which URDF to read, where the package "
                         "holds several (its file name)")
    view.set_defaults(command="view", run=_view)

    render = commands.add_parser("render", help="save a picture of the package (no display "
                                 "needed)",
                                 description=RENDER_HELP, formatter_class=raw)
    render.add_argument("path", metavar="PATH",
                        help="package folder, .urdf file or .zip of the package")
    render.add_argument("--urdf", metavar="NAME", help="which URDF to read, where the package "
                         "holds several (its file name)")
    render.add_argument("-o", "--output", metavar="FILE", required=True, help="the PNG to write")
    render.add_argument("--width", type=_pixels, default=960, help="pixels (default 960)")
    render.add_argument("--height", type=_pixels, default=640, help="pixels (default 640)")
    render.add_argument("--azimuth", type=float, default=135.0,
                        help="camera direction around the vertical, degrees (default 135)")
    render.add_argument("--elevation", type=float, default=-25.0,
                        help="camera height, degrees; negative looks down (default -25)")
    render.add_argument("--shadows", action="store_true",
                        help="draw shadows (software rendering can speckle them on large models)")
    render.add_argument("--force", action="store_true", help="overwrite FILE if it exists")
    render.set_defaults(command="render", run=_render)

    ros = commands.add_parser("ros", help="run the package's launch file under ROS 1, with "
                              "MuJoCo in Gazebo's place", description=ROS_HELP,
                              formatter_class=raw)
    ros.add_argument("path", metavar="PATH", help="package folder or .zip of it")
    ros.add_argument("--launch", metavar="FILE", help="the launch file (default: "
                     "launch/gazebo.launch of the package)")
    _simulation_options(ros)
    ros.set_defaults(command="ros", run=_ros)

    ros_env = commands.add_parser("ros-env", help="print the lines that let a terminal's ROS 1 "
                                  "commands use MuJoCo in Gazebo's place",
                                  description=ROS_ENV_HELP, formatter_class=raw)
    ros_env.add_argument("folders", metavar="FOLDER", nargs="*",
                         help="a package, or a folder holding packages, for ROS_PACKAGE_PATH")
    ros_env.set_defaults(command="ros-env", run=_ros_env)

    ros2 = commands.add_parser("ros2", help="run a ROS 2 package's robot under rclpy, with "
                               "MuJoCo in Gazebo Sim's place", description=ROS2_HELP,
                               formatter_class=raw)
    ros2.add_argument("path", metavar="PATH", help="package folder or .zip of it (ROS 2, or a "
                      "ROS 1 export, ported first)")
    _simulation_options(ros2)
    ros2.set_defaults(command="ros2", run=_ros2)

    port = commands.add_parser("port", help="write a ROS 2 Jazzy package from the ROS 1 "
                               "package", description=PORT_HELP, formatter_class=raw)
    port.add_argument("path", metavar="PATH", help="package folder, .urdf file or .zip of "
                      "the package")
    port.add_argument("-o", "--output", metavar="OUT", required=True,
                      help="the new package's folder (created; an earlier port is replaced)")
    port.add_argument("--name", metavar="NEW", help="the ROS 2 package's name (default: the "
                      "source's, made legal)")
    port.add_argument("--effort-joints", metavar="NAME[,NAME...]", action="append", default=[],
                      help="joints without a transmission to drive with an effort command, "
                           "together, by effort_controller (JointGroupEffortController)")
    port.add_argument("--no-controllers", dest="default_controllers", action="store_false",
                      help="give an export without transmissions and controllers none: its "
                           "joints then only report their state")
    port.add_argument("--urdf", metavar="NAME", help="which URDF to read, where the package "
                      "holds several (its file name)")
    port.set_defaults(command="port", run=_port)

    edits = commands.add_parser("edits", help="save a package's hand edits, and restore them "
                                "after exporting again", description=EDITS_HELP,
                                formatter_class=raw)
    edits.add_argument("action", choices=("save", "restore"),
                       help="save before exporting again, restore after")
    edits.add_argument("path", metavar="PKG", help="the package folder")
    edits.add_argument("--force", action="store_true", help="save over a copy with more hand "
                       "edits, or restore over files edited since the re-export")
    edits.set_defaults(command="edits", run=_edits)
    return parser


def _version() -> str:
    from importlib.metadata import PackageNotFoundError, version
    try:
        return version("sw2sim")
    except PackageNotFoundError:
        return "(not installed)"


def _pixels(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a whole number of pixels") from None
    if not 16 <= value <= 4096:
        raise argparse.ArgumentTypeError(f"{value} is outside 16 to 4096 pixels")
    return value


def _density(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number of kg/m^3") from None
    if not 1 <= value <= 25_000:
        raise argparse.ArgumentTypeError(f"{value:g} kg/m^3 is outside 1 to 25,000; write the "
                                         "density in kg/m^3 (aluminium: 2700)")
    return value


def _say(message: str) -> None:
    print(message, file=sys.stderr)


# -- check -----------------------------------------------------------------------------
def _check(args) -> int:
    from . import archive
    from .check import check
    from .check.workflow_commands import commands
    if args.urdf and len(args.path) > 1:
        _say("sw2sim check: --urdf picks a URDF of one package; give one PATH with it")
        return EXIT_UNUSABLE
    if args.json and args.format not in (None, "json"):
        _say(f"sw2sim check: --json and --format {args.format} ask for two formats; give one")
        return EXIT_UNUSABLE
    form = "json" if args.json else args.format or "text"
    reports = []
    for path in args.path:
        reports.append(check(path, stability=not args.no_sim, urdf=args.urdf))
        archive.discard()   # a class's worth of zips needs no disk for all of them at once
        if form in ("text", "github"):   # as each package is done: a class takes minutes
            shown = reports[-1].format() if form == "text" else commands(reports[-1])
            print(("\n" if len(reports) > 1 and form == "text" else "") + shown, flush=True)
    if form == "json":
        print(reports[0].to_json() if len(reports) == 1 else
              "[\n" + ",\n".join(r.to_json() for r in reports) + "\n]")
    elif form == "sarif":
        print(_sarif(reports))
    elif len(reports) > 1:
        print(("\n" if form == "text" else "") + _checked(reports))
    return max(r.status for r in reports)


def _sarif(reports) -> str:
    import json
    from .check import all_rules
    from .check.sarif import log
    return json.dumps(log(reports, all_rules(), _version()), indent=2)


def _checked(reports) -> str:
    """The line that sums up the check of several packages."""
    counts = {status: sum(r.status == status for r in reports) for status in (0, 1, 2)}
    return (f"{len(reports)} packages checked: {counts[0]} without errors, {counts[1]} with "
            f"errors, {counts[2]} that could not be used")


# -- compare ---------------------------------------------------------------------------
def _compare(args) -> int:
    from .compare import compare
    result = compare(args.mine, args.reference, urdf=args.urdf,
                     reference_urdf=args.reference_urdf)
    if result.error and not args.json:
        _say(result.format())
    else:
        print(result.to_json() if args.json else result.format())
    return result.status


# -- convert ---------------------------------------------------------------------------
def _convert(args) -> int:
    from .check import PACKAGING, RULES, Options, check_package
    out = Path(args.output)
    if out.exists() and not out.is_dir():
        _say(f"sw2sim convert: {out} is a file; give a folder to write the model into.")
        return EXIT_UNUSABLE
    if out.is_dir() and any(out.iterdir()) and not args.force:
        _say(f"sw2sim convert: {out} is not empty, so nothing was written. Choose a new "
             "folder, or add --force to replace the files convert writes there (other files "
             "are left alone).")
        return EXIT_UNUSABLE
    options = Options(strict=args.strict, lock_default_limits=args.lock_default_limits,
                      density=args.density)
    checked = check_package(args.path, options=options, urdf=args.urdf)
    report = checked.report
    if report.status == EXIT_UNUSABLE or report.simulation_stoppers:
        print(report.format())
        _say("sw2sim convert: not converted; fix the errors above and run it again." + (
            "" if args.strict or not report.repaired else
            " (The problems marked \"Convert repairs it\" need nothing more.)"))
        masses = [f for f in report.simulation_stoppers
                  if "--density" in (RULES[f.rule].repair or "")]
        if masses and args.density is None and not args.strict:
            _say(f"{len(masses)} of them are masses or inertias: --density KG_PER_M3 (your "
                 "material's, e.g. 2700 for aluminium) computes them from the meshes instead.")
        return report.status
    if report.findings:
        print(report.format())
    packaging = sum(f.severity == "error" and f.blocks == PACKAGING for f in report.findings)
    if packaging:
        print(f"{packaging} error(s) above matter only to ROS's build and package tools; "
              "MuJoCo does not read package.xml, so the model is converted anyway.")
    if report.repaired:
        print(f"{len(report.repaired)} problem(s) above are repaired in the written model "
              "(your package is unchanged); README.md lists them under Repairs, with the "
              "lasting fix for each.")
    from .check.stability import mujoco_warnings
    from .convert import OutputNotEmpty, convert
    from .package import LoadError
    try:
        with mujoco_warnings():   # the check has reported them; no MUJOCO_LOG.TXT here
            result = convert(checked.repaired_package(), out, force=args.force,
                             repairs=report.repaired,
                             unactuated=[r.unactuated for r in checked.repairs if r.unactuated])
    except LoadError as exc:
        _say(f"sw2sim convert: {exc}")
        return EXIT_ERRORS
    except OutputNotEmpty as exc:
        _say(f"sw2sim convert: {exc}; nothing was written.")
        return EXIT_UNUSABLE
    except OSError as exc:
        _say(f"sw2sim convert: cannot write into {out}: {exc.strerror or exc}")
        return EXIT_UNUSABLE
    free = [r.unactuated for r in checked.repairs if r.unactuated]
    if free:
        print(f"WARNING: {', '.join(free)} move(s) freely in the model, without limits and "
              "without an actuator: the package gives the exporter's empty limits (all 0). "
              "Enter the real limits in the exporter and export again, or convert with "
              "--lock-default-limits to lock them.")
    meshes = f" and {len(result.meshes)} mesh file(s) in assets/" if result.meshes else ""
    print(f"wrote {out}: {result.name}.xml, scene.xml, README.md{meshes}; "
          f"{len(result.actuators)} actuator(s)")
    print(f"open it with: python -m mujoco.viewer --mjcf={out / 'scene.xml'}")
    return EXIT_OK


# -- ros -----------------------------------------------------------------------------
def _ros(args) -> int:
    from .ros.run import run
    view = args.view
    if view and (reason := _no_display()):
        _say(f"sw2sim ros: --view: {reason}; the simulation runs without the viewer")
        view = False
    return run(args.path, launch=args.launch, duration=args.duration, realtime=args.realtime,
               view=view, say=lambda text: print(text, flush=True))


def _ros_env(args) -> int:
    from .ros.run import missing
    from .ros.terminal import main
    return main(args.folders, missing())


# -- port ----------------------------------------------------------------------------
def _port(args) -> int:
    from .package import LoadError, find_package
    from .port import PortError, port
    try:
        package = find_package(args.path, urdf=args.urdf)
        report = port(package, args.output, name=args.name, effort_joints=args.effort_joints,
                      default_controllers=args.default_controllers)
    except (LoadError, PortError) as exc:
        _say(f"sw2sim port: {exc}")
        return EXIT_UNUSABLE
    except OSError as exc:
        _say(f"sw2sim port: cannot write {args.output}: {exc.strerror or exc}")
        return EXIT_UNUSABLE
    print(report.format())
    return EXIT_OK


# -- edits ---------------------------------------------------------------------------
def _edits(args) -> int:
    from . import edits
    from .package import LoadError
    where = args.path
    try:
        if args.action == "save":
            files = edits.save(args.path, force=args.force)
            print(f"saved {len(files)} file(s) in {Path(where) / edits.FOLDER}: "
                  f"{', '.join(files)}")
            return EXIT_OK
        result = edits.restore(args.path, force=args.force)
    except LoadError as exc:
        _say(f"sw2sim edits: {exc}")
        return EXIT_UNUSABLE
    except edits.NothingSaved as exc:
        _say(f"sw2sim edits restore: nothing saved ({exc}). Run `sw2sim edits save {where}` "
             "before re-exporting; the hand edits a re-export removed must now be made again.")
        return EXIT_UNUSABLE
    except edits.WouldLoseEdits as exc:
        _say(f"sw2sim edits save: the saved copy in {Path(where) / edits.FOLDER} has hand edits "
             f"the URDF lacks ({exc}): after a re-export, run `sw2sim edits restore {where}` "
             "first. If you removed them on purpose, add --force.")
        return EXIT_ERRORS
    except edits.EditedSince as exc:
        _say(f"sw2sim edits restore: nothing restored: {exc} changed after the re-export (more "
             "than a minute after the URDF), and restoring would overwrite that. Copy what you "
             f"want to keep into {Path(where) / edits.FOLDER} (the saved copies), or add --force.")
        return EXIT_ERRORS
    except (OSError, ValueError, SyntaxError) as exc:   # lxml's XMLSyntaxError is a SyntaxError
        _say(f"sw2sim edits {args.action}: {exc}")
        return EXIT_UNUSABLE
    for line in result.done:
        print(line)
    for line in result.warnings:
        print(f"WARNING: {line}")
    return EXIT_OK


def _ros2(args) -> int:
    from .ros2.run import run
    view = args.view
    if view and (reason := _no_display()):
        _say(f"sw2sim ros2: --view: {reason}; the simulation runs without the viewer")
        view = False
    return run(args.path, duration=args.duration, realtime=args.realtime, view=view,
               say=lambda text: print(text, flush=True))


# -- view and render -------------------------------------------------------------------
def _no_display() -> str | None:
    """Why no window can open here, or None when one can."""
    if sys.platform == "darwin" or sys.platform.startswith("win"):
        return None
    if os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY"):
        return None
    return "neither DISPLAY nor WAYLAND_DISPLAY is set, so there is no screen to open a window on"


def _display_name() -> str:
    return os.environ.get("WAYLAND_DISPLAY") or os.environ.get("DISPLAY") or "(default)"


def _glfw_starts() -> bool:
    """Whether GLFW can reach the display. The viewer would otherwise stop the whole
    process from inside MuJoCo, with no message but "could not initialize GLFW"."""
    try:
        import glfw
    except ImportError:
        return False
    reporting, glfw.ERROR_REPORTING = glfw.ERROR_REPORTING, "ignore"
    try:
        return bool(glfw.init())
    finally:
        glfw.ERROR_REPORTING = reporting


def _model(args, *, sliders: bool = False, size: tuple[int, int] | None = None):
    """The package's model as the viewer or a picture shows it, or an exit status.

    The static check runs first: a package it cannot use stops here; other findings
    are printed and the model is still loaded, since looking at it is how to find
    what they mean.
    """
    from .check import check_package
    from .check.stability import mujoco_warnings
    from .package import LoadError
    checked = check_package(args.path, stability=False, urdf=args.urdf)
    report = checked.report
    if report.status == EXIT_UNUSABLE:
        print(report.format())
        return EXIT_UNUSABLE
    if report.findings:
        print(report.format())
    try:
        with mujoco_warnings():   # the check has reported them; no MUJOCO_LOG.TXT here
            return _compiled(checked.package, sliders, size)
    except LoadError as exc:
        _say(f"sw2sim {args.command}: {exc}")
        return EXIT_ERRORS
    except ValueError as exc:
        message = " ".join(str(exc).split())
        _say(f"sw2sim {args.command}: MuJoCo cannot compile the model: {message}")
        return EXIT_ERRORS


def _compiled(package, sliders: bool, size: tuple[int, int] | None):
    from .actuators import add_actuators
    from .loader import load_package
    from .package import LoadError
    fixed = package.world_fixed
    spec = load_package(package, fixed_base=fixed)
    if sliders:
        try:
            add_actuators(spec, package, sliders=True)
        except LoadError as exc:
            print(f"no sliders: {exc}")
            spec = load_package(package, fixed_base=fixed)
    if size is not None:
        spec.visual.global_.offwidth = max(spec.visual.global_.offwidth, size[0])
        spec.visual.global_.offheight = max(spec.visual.global_.offheight, size[1])
    return spec.compile()


def _view(args) -> int:
    reason = _no_display()
    if reason:
        _say(f"sw2sim view: {reason}. Make a picture instead:\n"
             f"    sw2sim render {args.path} -o picture.png\n"
             "or log in with `ssh -X` (or run on a machine with a screen) so the viewer's "
             "window can open.")
        return EXIT_UNUSABLE
    # The viewer draws through GLFW; `import sw2sim` chose an off-screen platform for
    # pictures, and MuJoCo reads the choice once, when it is first imported.
    gl.for_window()
    if not _glfw_starts():
        _say(f"sw2sim view: no window can open on display {_display_name()}. Check that "
             "the display works (`xeyes`, say), or make a picture instead:\n"
             f"    sw2sim render {args.path} -o picture.png")
        return EXIT_UNUSABLE
    model = _model(args, sliders=True)
    if isinstance(model, int):
        return model
    try:
        import mujoco.viewer
        mujoco.viewer.launch(model)
    except Exception as exc:  # noqa: BLE001  (GLFW and the display fail in many ways)
        _say(f"sw2sim view: the viewer could not open a window ({type(exc).__name__}: {exc}). "
             f"Check that the display works, or make a picture instead: "
             f"sw2sim render {args.path} -o picture.png")
        return EXIT_UNUSABLE
    return EXIT_OK


def _render(args) -> int:
    out = Path(args.output)
    if out.is_dir():
        _say(f"sw2sim render: {out} is a folder; give the PNG file to write, "
             f"e.g. {out / 'picture.png'}")
        return EXIT_UNUSABLE
    if out.exists() and not args.force:
        _say(f"sw2sim render: {out} exists; add --force to overwrite it, or choose another name.")
        return EXIT_UNUSABLE
    if not out.parent.is_dir():
        _say(f"sw2sim render: the folder {out.parent} does not exist; create it first.")
        return EXIT_UNUSABLE
    model = _model(args, size=(args.width, args.height))
    if isinstance(model, int):
        return model
    import mujoco
    from .render import render, save_png
    try:
        image = render(model, mujoco.MjData(model), width=args.width, height=args.height,
                       azimuth=args.azimuth, elevation=args.elevation, shadows=args.shadows,
                       frame=True)
    except Exception as exc:  # noqa: BLE001  (no OpenGL here: say how to get one)
        _say(f"sw2sim render: cannot draw off-screen ({type(exc).__name__}: {exc}). On Debian or "
             "Ubuntu install libosmesa6 (sudo apt install libosmesa6), or set MUJOCO_GL=egl.")
        return EXIT_UNUSABLE
    try:
        save_png(image, out)
    except OSError as exc:
        _say(f"sw2sim render: cannot write {out}: {exc.strerror or exc}")
        return EXIT_UNUSABLE
    print(f"wrote {out} ({args.width}x{args.height})")
    return EXIT_OK
