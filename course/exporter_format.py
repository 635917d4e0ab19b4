"""Write a robot as the SolidWorks-to-URDF exporter (1.6) writes it.

The lessons' example packages are generated from part parameters, but they must
look exactly like a real export: the same folder layout, one XML attribute per
line, joint origins rounded to 5 significant digits, inertials with 15 and
E-notation, the CSV with one row per link, the joint-names YAML with its empty
first entry. What the lessons add by hand afterwards (colours, a world link,
joint dynamics, transmissions) is marked as such in `Robot`.

The module is over 500 lines because it is the exporter's writers side by side (URDF,
CSV, package.xml, CMakeLists.txt, YAML, launch files, STL), each next to the others whose
layout it must match; `write_package` and `write_exported` are the two ways of calling
them, the lesson's package and a bare re-export.
"""

from __future__ import annotations

import csv
import io
import re
from dataclasses import dataclass, field
from pathlib import Path

from .parts import Part
from .rviz_config import rviz_text

EXPORTER_GREY = (0.792156862745098, 0.819607843137255, 0.933333333333333, 1.0)


def g5(v: float) -> str:
    """Joint origins and axes: the exporter keeps 5 significant digits."""
    return _clean(f"{v:.5G}")


def g15(v: float) -> str:
    """Masses and inertias: 15 significant digits, E-notation below 1E-05 (.NET's default)."""
    return _clean(f"{v:.15G}")


def _clean(s: str) -> str:
    return "0" if s in ("-0", "0") else s


def vec(values, fmt=g5) -> str:
    return " ".join(fmt(float(v)) for v in values)


@dataclass(frozen=True)
class Limit:
    lower: float = 0.0
    upper: float = 0.0
    effort: float = 0.0
    velocity: float = 0.0


@dataclass(frozen=True)
class Dynamics:
    damping: float = 0.0
    friction: float = 0.0


@dataclass(frozen=True)
class Safety:
    """The exporter's "Safety" fields: soft limits and the gains that hold a joint inside them."""

    soft_lower: float = 0.0
    soft_upper: float = 0.0
    k_position: float = 0.0
    k_velocity: float = 0.0


@dataclass(frozen=True)
class Transmission:
    """A ros_control transmission: one actuator driving one joint (added by hand after the export)."""

    joint: str
    interface: str = "hardware_interface/EffortJointInterface"
    reduction: float = 1.0

    @property
    def name(self) -> str:
        return self.joint.removesuffix("_joint") + "_transmission"

    @property
    def actuator(self) -> str:
        return self.joint.removesuffix("_joint") + "_motor"


@dataclass
class Link:
    name: str
    part: Part | None  # None: a frame with no body, such as the added `world` link
    rgba: tuple[float, float, float, float] = EXPORTER_GREY
    component: str = ""  # the SolidWorks component, for the CSV


@dataclass
class Joint:
    name: str
    type: str
    parent: str
    child: str
    xyz: tuple[float, float, float] = (0.0, 0.0, 0.0)
    rpy: tuple[float, float, float] = (0.0, 0.0, 0.0)
    axis: tuple[float, float, float] | None = None
    limit: Limit | None = None
    dynamics: Dynamics | None = None
    safety: Safety | None = None
    coordinate_system: str = ""
    axis_name: str = ""


@dataclass
class Robot:
    name: str
    links: list[Link]
    joints: list[Joint]
    # Set after the export, by hand in the lessons: kept apart so the "as exported" view can drop them.
    added_links: list[Link] = field(default_factory=list)
    added_joints: list[Joint] = field(default_factory=list)
    colours: dict[str, tuple[float, float, float, float]] = field(default_factory=dict)
    dynamics: dict[str, Dynamics] = field(default_factory=dict)
    transmissions: list[Transmission] = field(default_factory=list)
    gazebo_plugin: str = ""       # e.g. "libgazebo_ros_control.so", loaded with namespace /<name>
    joint_state_rate: float = 0.0  # Hz: gazebo_plugins' joint state publisher on /joint_states
    depends: list[str] = field(default_factory=list)   # extra <depend> lines in package.xml

    def movable_joints(self) -> list[Joint]:
        return [j for j in self.joints if j.type != "fixed"]


# --- XML in the exporter's layout -------------------------------------------------------------


class _Writer:
    def __init__(self) -> None:
        self.lines: list[str] = []

    def open(self, depth: int, tag: str, attrs: dict[str, str] | None = None, close: bool = False) -> None:
        pad = "  " * depth
        end = " />" if close else ">"
        if not attrs:
            self.lines.append(f"{pad}<{tag}{end}")
            return
        self.lines.append(f"{pad}<{tag}")
        items = list(attrs.items())
        for i, (k, v) in enumerate(items):
            tail = end if i == len(items) - 1 else ""
            self.lines.append(f'{pad}  {k}="{v}"{tail}')

    def leaf(self, depth: int, tag: str, attrs: dict[str, str]) -> None:
        self.open(depth, tag, attrs, close=True)

    def close(self, depth: int, tag: str) -> None:
        self.lines.append(f"{'  ' * depth}</{tag}>")


HEADER = (
    '<?xml version="1.0" encoding="utf-8"?>\n'
    "<!-- This URDF follows the output of the SolidWorks to URDF Exporter 1.6.\n"
    "     It was generated from the part parameters in course/practices; edit those and run\n"
    "     `python -m course.practices` rather than this file. -->\n"
)


def urdf_text(robot: Robot, *, as_exported: bool = False) -> str:
    """The URDF file. `as_exported=True` leaves out what the lessons add by hand."""
    w = _Writer()
    w.open(0, "robot", {"name": robot.name})
    links = robot.links if as_exported else [*robot.added_links, *robot.links]
    joints = robot.joints if as_exported else [*robot.added_joints, *robot.joints]
    joints_by_child = {j.child: j for j in joints}
    for link in links:
        _write_link(w, robot, link, as_exported)
        if link.name in joints_by_child:
            _write_joint(w, robot, joints_by_child[link.name], as_exported)
    if not as_exported:
        _write_ros_control(w, robot)
    w.close(0, "robot")
    return HEADER + "\n".join(w.lines) + "\n"


def _write_link(w: _Writer, robot: Robot, link: Link, as_exported: bool) -> None:
    if link.part is None:
        w.leaf(1, "link", {"name": link.name})
        return
    w.open(1, "link", {"name": link.name})
    mass, com, inertia = link.part.mass_properties()
    w.open(2, "inertial")
    w.leaf(3, "origin", {"xyz": vec(com, g15), "rpy": "0 0 0"})
    w.leaf(3, "mass", {"value": g15(mass)})
    w.leaf(3, "inertia", {
        "ixx": g15(inertia[0, 0]), "ixy": g15(inertia[0, 1]), "ixz": g15(inertia[0, 2]),
        "iyy": g15(inertia[1, 1]), "iyz": g15(inertia[1, 2]), "izz": g15(inertia[2, 2]),
    })
    w.close(2, "inertial")
    rgba = link.rgba if as_exported else robot.colours.get(link.name, link.rgba)
    mesh = f"package://{robot.name}/meshes/{link.name}.STL"
    for kind in ("visual", "collision"):
        w.open(2, kind)
        w.leaf(3, "origin", {"xyz": "0 0 0", "rpy": "0 0 0"})
        w.open(3, "geometry")
        w.leaf(4, "mesh", {"filename": mesh})
        w.close(3, "geometry")
        if kind == "visual":
            w.open(3, "material", {"name": ""})
            w.leaf(4, "color", {"rgba": vec(rgba, g15)})
            w.close(3, "material")
        w.close(2, kind)
    w.close(1, "link")


def _write_joint(w: _Writer, robot: Robot, joint: Joint, as_exported: bool) -> None:
    w.open(1, "joint", {"name": joint.name, "type": joint.type})
    w.leaf(2, "origin", {"xyz": vec(joint.xyz), "rpy": vec(joint.rpy)})
    w.leaf(2, "parent", {"link": joint.parent})
    w.leaf(2, "child", {"link": joint.child})
    if joint.axis is not None:
        w.leaf(2, "axis", {"xyz": vec(joint.axis)})
    if joint.limit is not None:
        lim = joint.limit
        w.leaf(2, "limit", {"lower": g5(lim.lower), "upper": g5(lim.upper),
                            "effort": g5(lim.effort), "velocity": g5(lim.velocity)})
    dyn = joint.dynamics if as_exported else robot.dynamics.get(joint.name, joint.dynamics)
    if dyn is not None:
        w.leaf(2, "dynamics", {"damping": g5(dyn.damping), "friction": g5(dyn.friction)})
    if joint.safety is not None:
        s = joint.safety
        w.leaf(2, "safety_controller", {"soft_lower_limit": g5(s.soft_lower), "soft_upper_limit": g5(s.soft_upper),
                                        "k_position": g5(s.k_position), "k_velocity": g5(s.k_velocity)})
    w.close(1, "joint")


def _write_ros_control(w: _Writer, robot: Robot) -> None:
    """Transmissions and the Gazebo plugin: added by hand, in the usual compact ROS style."""
    for t in robot.transmissions:
        w.lines += [
            f'  <transmission name="{t.name}">',
            "    <type>transmission_interface/SimpleTransmission</type>",
            f'    <joint name="{t.joint}">',
            f"      <hardwareInterface>{t.interface}</hardwareInterface>",
            "    </joint>",
            f'    <actuator name="{t.actuator}">',
            f"      <hardwareInterface>{t.interface}</hardwareInterface>",
            f"      <mechanicalReduction>{g5(t.reduction)}</mechanicalReduction>",
            "    </actuator>",
            "  </transmission>",
        ]
    if robot.gazebo_plugin:
        w.lines += [
            "  <gazebo>",
            f'    <plugin name="gazebo_ros_control" filename="{robot.gazebo_plugin}">',
            f"      <robotNamespace>/{robot.name}</robotNamespace>",
            "    </plugin>",
            "  </gazebo>",
        ]
    if robot.joint_state_rate:
        # Without ros_control nothing publishes the joints' states; this plugin of
        # gazebo_plugins does, on /joint_states.
        names = ", ".join(j.name for j in robot.movable_joints())
        w.lines += [
            "  <gazebo>",
            '    <plugin name="joint_state_publisher" '
            'filename="libgazebo_ros_joint_state_publisher.so">',
            "      <robotNamespace>/</robotNamespace>",
            f"      <jointName>{names}</jointName>",
            f"      <updateRate>{g5(robot.joint_state_rate)}</updateRate>",
            "    </plugin>",
            "  </gazebo>",
        ]


# --- the other files of the package ----------------------------------------------------------

CSV_COLUMNS = (
    "Link Name,Center of Mass X,Center of Mass Y,Center of Mass Z,Center of Mass Roll,"
    "Center of Mass Pitch,Center of Mass Yaw,Mass,Moment Ixx,Moment Ixy,Moment Ixz,Moment Iyy,"
    "Moment Iyz,Moment Izz,Visual X,Visual Y,Visual Z,Visual Roll,Visual Pitch,Visual Yaw,"
    "Mesh Filename,Color Red,Color Green,Color Blue,Color Alpha,Collision X,Collision Y,"
    "Collision Z,Collision Roll,Collision Pitch,Collision Yaw,Collision Mesh Filename,"
    "Material Name,SW Components,Coordinate System,Axis Name,Joint Name,Joint Type,"
    "Joint Origin X,Joint Origin Y,Joint Origin Z,Joint Origin Roll,Joint Origin Pitch,"
    "Joint Origin Yaw,Parent,Joint Axis X,Joint Axis Y,Joint Axis Z,Limit Effort,"
    "Limit Velocity,Limit Lower,Limit Upper,Calibration rising,Calibration falling,"
    "Dynamics Damping,Dynamics Friction,Safety Soft Upper,Safety Soft Lower,"
    "Safety K Position,Safety K Velocity"
).split(",")


def csv_text(robot: Robot) -> str:
    """One row per exported link, as the exporter writes it next to the URDF."""
    out = io.StringIO()
    wr = csv.writer(out, lineterminator="\n")
    wr.writerow(CSV_COLUMNS)
    joints_by_child = {j.child: j for j in robot.joints}
    for link in robot.links:
        mass, com, inertia = link.part.mass_properties()
        mesh = f"package://{robot.name}/meshes/{link.name}.STL"
        j = joints_by_child.get(link.name)
        row = [link.name, *(g15(c) for c in com), 0, 0, 0, g15(mass),
               *(g15(inertia[i, k]) for i, k in ((0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2))),
               0, 0, 0, 0, 0, 0, mesh, *(g15(c) for c in link.rgba),
               0, 0, 0, 0, 0, 0, mesh, "", link.component]
        if j is None:
            row += ["Origin_global", "", "", "", 0, 0, 0, 0, 0, 0, "", 0, 0, 0]
            row += [""] * 12
        else:
            lim = j.limit
            row += [j.coordinate_system, j.axis_name, j.name, j.type,
                    *(g15(v) for v in j.xyz), *(g15(v) for v in j.rpy), j.parent,
                    *(g15(v) for v in (j.axis or (0, 0, 0)))]
            row += [g15(lim.effort), g15(lim.velocity), g15(lim.lower), g15(lim.upper)] if lim else ["", "", "", ""]
            row += ["", ""]
            row += [g15(j.dynamics.damping), g15(j.dynamics.friction)] if j.dynamics else ["", ""]
            sf = j.safety
            row += [g15(sf.soft_upper), g15(sf.soft_lower), g15(sf.k_position), g15(sf.k_velocity)] if sf \
                else ["", "", "", ""]
        row[-1] = row[-1] if row[-1] != "" else 0  # the exporter ends each row with 0
        wr.writerow(row)
    return out.getvalue()


def package_xml(name: str, depends: list[str] = ()) -> str:
    extra = "".join(f"\n  <depend>{d}</depend>" for d in depends)
    return f"""<?xml version="1.0"?>
<package format="2">
  <name>{name}</name>
  <version>1.0.0</version>
  <description>
    <p>URDF Description package for {name}</p>
    <p>This package contains configuration data, 3D models and launch files
for {name} robot</p>
  </description>
  <author>TODO</author>
  <maintainer email="TODO@email.com">TODO</maintainer>
  <license>BSD</license>
  <buildtool_depend>catkin</buildtool_depend>
  <depend>roslaunch</depend>
  <depend>robot_state_publisher</depend>
  <depend>rviz</depend>
  <depend>joint_state_publisher_gui</depend>
  <depend>gazebo</depend>{extra}
  <export>
    <architecture_independent />
  </export>
</package>
"""


def cmakelists(name: str, programs: list[str] = ()) -> str:
    """The exporter's CMakeLists.txt; `programs` (the lesson's ROS nodes, added by hand) are
    installed as catkin installs Python nodes: where rosrun finds them, #! line fixed."""
    nodes = "".join(f"\t{p}\n" for p in programs)
    install_nodes = (f"\ncatkin_install_python(PROGRAMS\n{nodes}"
                     f"\tDESTINATION ${{CATKIN_PACKAGE_BIN_DESTINATION}})\n" if programs else "")
    return f"""cmake_minimum_required(VERSION 2.8.3)

project({name})

find_package(catkin REQUIRED)

catkin_package()

find_package(roslaunch)

foreach(dir config launch meshes urdf)
\tinstall(DIRECTORY ${{dir}}/
\t\tDESTINATION ${{CATKIN_PACKAGE_SHARE_DESTINATION}}/${{dir}})
endforeach(dir)
{install_nodes}"""


def launch_programs(name: str, nodes: str) -> list[str]:
    """The package's own Python nodes that launch-file lines start, as scripts/ paths."""
    found = []
    for node in re.findall(r"<node\b[^>]*>", nodes):
        pkg, kind = re.search(r'pkg="([^"]*)"', node), re.search(r'type="([^"]*\.py)"', node)
        if pkg and kind and pkg[1] == name and f"scripts/{kind[1]}" not in found:
            found.append(f"scripts/{kind[1]}")
    return found


def joint_names_yaml(robot: Robot) -> str:
    names = "".join(f"'{j.name}', " for j in robot.movable_joints())
    return f"controller_joint_names: ['', {names}]\n"


def display_launch(name: str) -> str:
    return f"""<launch>
  <arg
    name="model" />
  <param
    name="robot_description"
    textfile="$(find {name})/urdf/{name}.urdf" />
  <node
    name="joint_state_publisher_gui"
    pkg="joint_state_publisher_gui"
    type="joint_state_publisher_gui" />
  <node
    name="robot_state_publisher"
    pkg="robot_state_publisher"
    type="robot_state_publisher" />
  <node
    name="rviz"
    pkg="rviz"
    type="rviz"
    args="-d $(find {name})/urdf.rviz" />
</launch>
"""


def gazebo_launch(name: str, extra_nodes: str = "") -> str:
    # The exporter's file spawns the model from the URDF file and sets no robot_description:
    # enough for Gazebo alone. The nodes a practice adds need it: robot_state_publisher
    # exits without it, and gazebo_ros_control reads the transmissions from it.
    needs_description = any(node in extra_nodes for node in
                            ("robot_state_publisher", "controller_manager"))
    description = (f"""  <param
    name="robot_description"
    textfile="$(find {name})/urdf/{name}.urdf" />
""" if needs_description else "")
    return f"""<launch>
{description}  <include
    file="$(find gazebo_ros)/launch/empty_world.launch" />
  <node
    name="tf_footprint_base"
    pkg="tf"
    type="static_transform_publisher"
    args="0 0 0 0 0 0 base_link base_footprint 40" />
  <node
    name="spawn_model"
    pkg="gazebo_ros"
    type="spawn_model"
    args="-file $(find {name})/urdf/{name}.urdf -urdf -model {name}"
    output="screen" />
  <node
    name="fake_joint_calibration"
    pkg="rostopic"
    type="rostopic"
    args="pub /calibrated std_msgs/Bool true" />
{extra_nodes}</launch>
"""


def write_package(robot: Robot, folder: Path, *, gazebo_nodes: str = "", config: str = "",
                  rviz: bool = True) -> list[Path]:
    """Write the whole package into `folder` (created if needed); return the files written.

    `gazebo_nodes` is added to launch/gazebo.launch and `config` replaces the joint-names YAML
    (both are what a lesson changes by hand); `rviz=False` leaves out urdf.rviz, which
    display.launch names but the exporter does not write. Generated files are overwritten;
    anything else in the folder (scripts/, README) is left alone. A package with hand edits
    also gets them saved in hand_edits/, as `sw2sim edits save` saves them, so that a
    student's re-export can be followed by `sw2sim edits restore` and `sw2sim check` finds
    them saved.
    """
    folder = Path(folder)
    name = robot.name
    files: dict[str, str | bytes] = {
        "CMakeLists.txt": cmakelists(name, launch_programs(name, gazebo_nodes)),
        "package.xml": package_xml(name, robot.depends),
        f"config/joint_names_{name}.yaml": config or joint_names_yaml(robot),
        "launch/display.launch": display_launch(name),
        "launch/gazebo.launch": gazebo_launch(name, gazebo_nodes),
        f"urdf/{name}.urdf": urdf_text(robot),
        f"urdf/{name}.csv": csv_text(robot),
    }
    if rviz:
        files["urdf.rviz"] = rviz_text(robot)
    written = _write_files(folder, robot, files)
    if {rel: text for rel, text in files.items() if rel != "urdf.rviz"} != _exported_files(robot):
        from sw2sim.edits import FOLDER, save
        save(folder, force=True)   # the design is the truth: its edits replace any saved
        saved = folder / FOLDER
        written += sorted(p for p in saved.rglob("*") if p.is_file())
    return written


def write_exported(robot: Robot, folder: Path) -> list[Path]:
    """Write what the exporter itself writes for this robot, over `folder`: the lesson's
    package as a student's re-export leaves it, every hand edit gone (the URDF and CSV,
    package.xml, CMakeLists.txt, the joint-names YAML, both launch files and the meshes;
    nothing else in the folder is touched)."""
    return _write_files(Path(folder), robot, _exported_files(robot))


def _exported_files(robot: Robot) -> dict[str, str | bytes]:
    name = robot.name
    return {
        "CMakeLists.txt": cmakelists(name),
        "package.xml": package_xml(name),
        f"config/joint_names_{name}.yaml": joint_names_yaml(robot),
        "launch/display.launch": display_launch(name),
        "launch/gazebo.launch": gazebo_launch(name),
        f"urdf/{name}.urdf": urdf_text(robot, as_exported=True),
        f"urdf/{name}.csv": csv_text(robot),
    }


def _write_files(folder: Path, robot: Robot, files: dict[str, str | bytes]) -> list[Path]:
    files = {**files, **{f"meshes/{link.name}.STL": stl_bytes(link.part) for link in robot.links}}
    written = []
    for rel, content in files.items():
        path = folder / rel
        path.parent.mkdir(parents=True, exist_ok=True)
        if isinstance(content, str):
            path.write_text(content)
        else:
            path.write_bytes(content)
        written.append(path)
    return written


def stl_bytes(part: Part) -> bytes:
    """A binary STL in metres, in the link's frame, with a header naming the part."""
    data = part.mesh.export(file_type="stl")
    header = f"{part.name} - binary STL, metres".encode()[:80].ljust(80, b" ")
    return header + data[80:]

