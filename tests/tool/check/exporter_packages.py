"""Packages byte for byte as the SolidWorks-to-URDF exporter writes them, for the checker's tests.

course/exporter_format.py writes the lessons' packages in the exporter's layout; this module
writes what the exporter itself puts on disk, so that `sw2sim check` is tested against what
its users really give it. The robots below are three exports from the exporter's own
repository (ros/solidworks_urdf_exporter, folder examples/), their numbers copied as the
exporter printed them:

- FOUR_WHEELER_NESTED: release 1.6 (build 1.6.9650), a chassis and four wheels on continuous
  joints, with full inertia tensors;
- ORIGINAL_3_DOF_ARM: release 1.4 (build 1.4.6968), two of whose joints are revolute with the
  exporter's default limit, lower = upper = effort = velocity = 0;
- THREE_DOF_ARM_EARLY: an export older than the version comment, whose inertia tensors are all
  zero and whose joints carry no safety controller;
- THREE_DOF_ARM: the same arm as the repository holds it now (release 1.4, build 1.4.6968), with
  its inertias, three continuous joints and no transmission: what a student's arm gives
  `sw2sim port`. Its package name is THREE_DOF_ARM_EARLY's, so it is not in REAL_EXPORTS.

How the exporter writes each file (from its source, SW2URDF/URDF and SW2URDF/ROS):
- URDF and launch files: .NET XmlWriter with Indent and NewLineOnAttributes, so every
  attribute on a line of its own, two-space indents, " />" for empty elements, Windows line
  ends (CRLF) and no line end after the last tag; the URDF opens with an XML declaration and
  the exporter's version comment;
- numbers: .NET's default double formatting, 15 significant digits, E-notation below 1E-04
  ("3.5234044049786E-05"); in some exports (ORIGINAL_3_DOF_ARM) joint origins have only 5;
- every link: inertial (origin at the centre of mass), visual and collision with the same
  package://<name>/meshes/<link>.STL, and `<material name="">` with an rgba colour;
- every joint of 1.4 and later: `<safety_controller k_velocity="0" />`; revolute and
  prismatic joints: `<limit>` with zeros unless the user typed limits;
- package.xml: no XML declaration, an empty `<maintainer email="TODO@email.com" />`; format 2
  in 1.6, format 2's <depend> tags without the format attribute in 1.4 (which catkin reads as
  format 1 and refuses), format 1's build_depend/run_depend in early exports;
- CMakeLists.txt and the joint-names YAML: written line by line with CRLF, the YAML's list
  starting with the base link's empty joint name: `['', 'joint_a', ]`;
- meshes: binary STL in metres in the link's frame, the 80-byte header overwritten with zeros;
- an empty textures/ folder, and export.log, a copy of the add-in's log4net log.

The meshes are not the originals (those are SolidWorks parts): each is a box or a cylinder
whose mass properties match the link's inertial, so mesh and inertia agree as in a real export.
"""

from __future__ import annotations

import csv
import io
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import trimesh

from course.exporter_format import CSV_COLUMNS, EXPORTER_GREY

CRLF = "\r\n"
GREY = " ".join(f"{c:.15G}" for c in EXPORTER_GREY)
SILVER = "0.752941176470588 0.752941176470588 0.752941176470588 1"
ZERO_INERTIA = ("0",) * 6


@dataclass(frozen=True)
class Link:
    name: str
    com: str                     # the inertial origin's xyz, as exported
    mass: str
    inertia: tuple[str, ...]     # ixx ixy ixz iyy iyz izz, as exported
    rgba: str = GREY
    component: str = ""          # the SolidWorks component(s), for the CSV


@dataclass(frozen=True)
class Joint:
    name: str
    type: str
    xyz: str
    rpy: str
    parent: str
    child: str
    axis: str
    limit: tuple[str, str, str, str] | None = None   # lower upper effort velocity
    safety: bool = True          # `<safety_controller k_velocity="0" />` (1.4 and later)


@dataclass(frozen=True)
class Export:
    name: str
    links: tuple[Link, ...]      # in the exporter's order: depth first from base_link
    joints: tuple[Joint, ...]
    version: tuple[str, str] | None = None   # (commit, build) of the URDF's comment
    manifest: str = "format2"    # package.xml: "format2" (1.6), "unversioned" (1.4: format 2
                                 # tags without the attribute) or "format1" (early exports)

    def joint_of(self, link: str) -> Joint | None:
        return next((j for j in self.joints if j.child == link), None)


def _wheel(name: str, com: str, inertia: tuple[str, ...], component: str) -> Link:
    return Link(name, com, "0.0948368282302419", inertia, SILVER, component)


FOUR_WHEELER_NESTED = Export(
    name="4_WHEELER_NESTED_description",
    version=("25f2e4c", "1.6.9650.27696"),
    links=(
        Link("base_link", "-0.0141165384615385 1.92116548051542E-18 0.0069190520362904",
             "0.563365165980808",
             ("0.00116991160584325", "1.08541480873037E-19", "-1.21271091266427E-20",
              "0.000379959750479481", "2.37730438953325E-20", "0.00131589792050722"),
             component="4_WHEELER_CHASSIS-1"),
        _wheel("front_right_link",
               "0.0160973084886128 -1.21430643318376E-17 -2.08166817117217E-17",
               ("4.90180492807281E-05", "1.59355527597186E-21", "-5.57899635461016E-22",
                "2.67081223942584E-05", "1.35119091414065E-21", "2.67081223942584E-05"),
               "4_WHEELER_WHEEL_DRIVER-2/4_WHEEL_DUAL_WHEEL-1"),
        _wheel("back_right_link",
               "0.0160973084886128 1.21430643318376E-17 -6.93889390390723E-18",
               ("4.90180492807281E-05", "1.02975700590794E-22", "2.17716963245722E-22",
                "2.67081223942584E-05", "-2.11467000306239E-21", "2.67081223942584E-05"),
               "4_WHEELER_WHEEL_DRIVER-1/4_WHEEL_DUAL_WHEEL-1"),
        _wheel("front_left_link",
               "0.0160973084886128 5.20417042793042E-18 -2.08166817117217E-17",
               ("4.90180492807281E-05", "7.5311181916667E-23", "1.07045414697907E-22",
                "2.67081223942584E-05", "2.12254491328202E-22", "2.67081223942584E-05"),
               "4_WHEELER_WHEEL_DRIVER-4/4_WHEEL_DUAL_WHEEL-1"),
        _wheel("back_left_link",
               "0.0160973084886128 6.93889390390723E-18 6.93889390390723E-18",
               ("4.90180492807281E-05", "-5.66724053795126E-22", "-4.24781852640203E-22",
                "2.67081223942584E-05", "5.0340698813362E-22", "2.67081223942584E-05"),
               "4_WHEELER_WHEEL_DRIVER-3/4_WHEEL_DUAL_WHEEL-1"),
    ),
    joints=(
        Joint("front_right_joint", "continuous",
              "-0.0516165384615384 -0.05 -0.00997411961288419",
              "1.5707963267949 0 3.14159265358979", "base_link", "front_right_link", "1 0 0"),
        Joint("back_right_joint", "continuous",
              "-0.0516165384615384 0.05 -0.00997411961288421",
              "1.5707963267949 0 3.14159265358979", "base_link", "back_right_link", "1 0 0"),
        Joint("front_left_joint", "continuous",
              "0.0233834615384615 -0.05 -0.0099741196128842",
              "1.5707963267949 0 0", "base_link", "front_left_link", "-1 0 0"),
        Joint("back_left_joint", "continuous",
              "0.0233834615384615 0.05 -0.00997411961288421",
              "1.5707963267949 0 0", "base_link", "back_left_link", "-1 0 0"),
    ),
)

ORIGINAL_3_DOF_ARM = Export(
    name="ORIGINAL_3_DOF_ARM_description",
    version=("1.4.4-6-g2742936-dirty", "1.4.6968.15956"),
    manifest="unversioned",
    links=(
        Link("base_link", "0.00857185004749454 0.0277890770314089 0.0379884681378223",
             "0.0450462948917676",
             ("3.73760183746963E-05", "7.37175916246715E-37", "-3.67341984631965E-37",
              "3.73760183746963E-05", "3.21685897560652E-21", "7.33038758972795E-05"),
             "0 0 1 0.5", "Arm_base-1"),
        Link("link1", "0.110757629166325 -8.47845058049579E-12 8.47839853879151E-12",
             "0.0483301725897621",
             ("2.34046418523273E-05", "-9.12469035853591E-15", "-9.1246965685776E-15",
              "6.7625497098099E-05", "-1.78995347833815E-11", "6.79761299610003E-05"),
             SILVER, "Arm_link-1"),
        Link("link2", "0.0943407218386796 5.81092854596774E-07 -9.84910960399876E-07",
             "0.0585758042581199",
             ("2.38164941843817E-05", "9.72727997584935E-10", "7.81793935667511E-10",
              "6.97154129782386E-05", "-1.99343905502661E-09", "6.97122641242123E-05"),
             SILVER, "Arm_link-2"),
        Link("link3", "0.0943408063355609 4.37197531205635E-07 -3.60101098773047E-07",
             "0.0585758669634938",
             ("2.38167246601106E-05", "-8.54495980074359E-12", "-6.80054618075403E-11",
              "6.97192250758933E-05", "-3.89114521030646E-09", "6.97121157840842E-05"),
             SILVER, "Arm_link-3"),
    ),
    joints=(
        Joint("joint1", "continuous", "0.0085719 0.027789 0.020415", "2.8348 -1.5708 0",
              "base_link", "link1", "-1 0 0"),
        Joint("joint2", "revolute", "0.18177 0 0", "-1.5708 0 -1.7091",
              "link1", "link2", "0 -1 0", limit=("0", "0", "0", "0")),
        Joint("joint3", "revolute", "0.18177 0 0", "-1.5708 0 -1.8796",
              "link2", "link3", "0 -1 0", limit=("0", "0", "0", "0")),
    ),
)

THREE_DOF_ARM_EARLY = Export(
    name="3_DOF_ARM_description",
    manifest="format1",
    links=(
        Link("base_link", "0.00249115384615384 -0.00884615384615385 -0.00579027972027972",
             "0.0510508806208342", ZERO_INERTIA, component="3_DOF_ARM_BASE-1"),
        Link("prox_link", "0.0952733818315821 0.00828143287166189 0.00249115410455718",
             "0.132570921155528", ZERO_INERTIA, component="3_DOF_ARM_SEGMENT-1"),
        Link("dist_Link", "0.095273381831582 -0.197491153151382 -0.00249115410455719",
             "0.132570921155528", ZERO_INERTIA, component="3_DOF_ARM_SEGMENT-2"),
        Link("effector_link", "0.186101612171612 -0.00249115384615409 0.0174911538461536",
             "0.0290597320457047", ZERO_INERTIA, component="3_DOF_ARM_END_EFFECTOR-1"),
    ),
    joints=(
        Joint("prox_joint", "continuous", "0.00249115384615384 0 0",
              "-1.5707963267949 -6.12303176911189E-17 -1.5707963267949",
              "base_link", "prox_link", "0 -1 0", safety=False),
        Joint("dist_joint", "continuous", "0 -0.18920972027972 0",
              "-1.5707963267949 -1.78622307916987E-17 -4.68021606411955E-34",
              "prox_link", "dist_Link", "1 0 0", safety=False),
        Joint("effector_joint", "continuous", "0 -0.18 0",
              "1.5707963267949 7.49830360911068E-33 6.12303176911189E-17",
              "dist_Link", "effector_link", "0 0 1", safety=False),
    ),
)

THREE_DOF_ARM = Export(
    name="3_DOF_ARM_description",
    version=("1.4.4-6-g2742936-dirty", "1.4.6968.15956"),
    manifest="unversioned",
    links=(
        Link("base_link", "0.00249115384615384 2.34558007901714E-18 0.00305587412587413",
             "0.0510508806208341",
             ("3.5234044049786E-05", "6.98466777397284E-37", "-2.22339710804804E-37",
              "3.5234044049786E-05", "-5.44519126841819E-22", "6.24882413753095E-05"),
             component="3_DOF_ARM_BASE-1"),
        Link("prox_link", "6.94771684018737E-10 -0.0881460587278585 2.58403333886631E-10",
             "0.132570921155528",
             ("0.000425622211946537", "7.66166107697545E-12", "1.12207653869985E-10",
              "6.78913907046572E-05", "2.10847233866869E-12", "0.000427554426874909"),
             component="3_DOF_ARM_SEGMENT-1"),
        Link("dist_Link", "6.94771724770697E-10 -0.101063661551862 -2.58403354269632E-10",
             "0.132570921155528",
             ("0.000425622211946537", "-7.66166112117889E-12", "-1.12207653890081E-10",
              "6.78913907046571E-05", "2.10847240386709E-12", "0.000427554426874909"),
             component="3_DOF_ARM_SEGMENT-2"),
        Link("effector_link", "7.89909498403104E-17 -1.94289029309402E-16 0.0118918918918916",
             "0.0290597320457048",
             ("4.42470815817501E-06", "1.74806527887155E-21", "-1.05670524275547E-20",
              "4.424708158175E-06", "4.84594662178836E-20", "5.90275807178375E-06"),
             component="3_DOF_ARM_END_EFFECTOR-1"),
    ),
    joints=(
        Joint("prox_joint", "continuous", "0.00249115384615384 0 0",
              "-1.5707963267949 0 -1.5707963267949", "base_link", "prox_link", "0 1 0"),
        Joint("dist_joint", "continuous", "0 -0.18920972027972 0", "-1.5707963267949 0 0",
              "prox_link", "dist_Link", "-1 0 0"),
        Joint("effector_joint", "continuous", "0 -0.18 0", "1.5707963267949 0 0",
              "dist_Link", "effector_link", "0 0 -1"),
    ),
)

REAL_EXPORTS = {e.name: e for e in (FOUR_WHEELER_NESTED, ORIGINAL_3_DOF_ARM, THREE_DOF_ARM_EARLY)}


# --- the URDF, as .NET's XmlWriter indents it ------------------------------------------------


class _Xml:
    """Indent=true, NewLineOnAttributes=true, two spaces: the exporter's XmlWriter settings."""

    def __init__(self, newline: str):
        self.newline = newline
        self.lines: list[str] = []

    def start(self, depth: int, tag: str, attrs: dict[str, str] = None, empty: bool = False):
        pad = "  " * depth
        end = " />" if empty else ">"
        if not attrs:
            self.lines.append(f"{pad}<{tag}{end}")
            return
        self.lines.append(f"{pad}<{tag}")
        items = list(attrs.items())
        for i, (key, value) in enumerate(items):
            self.lines.append(f'{pad}  {key}="{value}"' + (end if i == len(items) - 1 else ""))

    def empty(self, depth: int, tag: str, attrs: dict[str, str]):
        self.start(depth, tag, attrs, empty=True)

    def end(self, depth: int, tag: str):
        self.lines.append(f"{'  ' * depth}</{tag}>")

    def text(self) -> str:
        return self.newline.join(self.lines)


def _comment(version: tuple[str, str], newline: str) -> str:
    commit, build = version
    return ("<!-- This URDF was automatically created by SolidWorks to URDF Exporter! Originally "
            f"created by Stephen Brawner (brawner@gmail.com) {newline}"
            f"     Commit Version: {commit}  Build Version: {build}{newline}"
            "     For more information, please see http://wiki.ros.org/sw_urdf_exporter -->")


def urdf_text(export: Export, newline: str = CRLF) -> str:
    x = _Xml(newline)
    x.start(0, "robot", {"name": export.name})
    for link in export.links:
        _link(x, export, link)
        joint = export.joint_of(link.name)
        if joint is not None:
            _joint(x, joint)
    x.end(0, "robot")
    head = ""
    if export.version is not None:
        head = ('<?xml version="1.0" encoding="utf-8"?>' + newline
                + _comment(export.version, newline) + newline)
    return head + x.text()


def _link(x: _Xml, export: Export, link: Link) -> None:
    mesh = f"package://{export.name}/meshes/{link.name}.STL"
    x.start(1, "link", {"name": link.name})
    x.start(2, "inertial")
    x.empty(3, "origin", {"xyz": link.com, "rpy": "0 0 0"})
    x.empty(3, "mass", {"value": link.mass})
    x.empty(3, "inertia", dict(zip(("ixx", "ixy", "ixz", "iyy", "iyz", "izz"), link.inertia)))
    x.end(2, "inertial")
    for kind in ("visual", "collision"):
        x.start(2, kind)
        x.empty(3, "origin", {"xyz": "0 0 0", "rpy": "0 0 0"})
        x.start(3, "geometry")
        x.empty(4, "mesh", {"filename": mesh})
        x.end(3, "geometry")
        if kind == "visual":
            x.start(3, "material", {"name": ""})
            x.empty(4, "color", {"rgba": link.rgba})
            x.end(3, "material")
        x.end(2, kind)
    x.end(1, "link")


def _joint(x: _Xml, joint: Joint) -> None:
    x.start(1, "joint", {"name": joint.name, "type": joint.type})
    x.empty(2, "origin", {"xyz": joint.xyz, "rpy": joint.rpy})
    x.empty(2, "parent", {"link": joint.parent})
    x.empty(2, "child", {"link": joint.child})
    x.empty(2, "axis", {"xyz": joint.axis})
    if joint.limit is not None:
        x.empty(2, "limit", dict(zip(("lower", "upper", "effort", "velocity"), joint.limit)))
    if joint.safety:
        x.empty(2, "safety_controller", {"k_velocity": "0"})
    x.end(1, "joint")


# --- the other files -------------------------------------------------------------------------


def package_xml(export: Export, newline: str = CRLF) -> str:
    name = export.name
    gui = "_gui" if export.manifest == "format2" else ""
    runs = ("robot_state_publisher", "rviz", f"joint_state_publisher{gui}", "gazebo")
    if export.manifest == "format1":
        depends = ["  <build_depend>roslaunch</build_depend>",
                   *(f"  <run_depend>{d}</run_depend>" for d in runs)]
    else:
        depends = [f"  <depend>{d}</depend>" for d in ("roslaunch", *runs)]
    lines = [
        '<package format="2">' if export.manifest == "format2" else "<package>",
        f"  <name>{name}</name>",
        "  <version>1.0.0</version>",
        "  <description>",
        f"    <p>URDF Description package for {name}</p>",
        "    <p>This package contains configuration data, 3D models and launch files",
        f"for {name} robot</p>",
        "  </description>",
        "  <author>TODO</author>",
        '  <maintainer email="TODO@email.com" />',
        "  <license>BSD</license>",
        "  <buildtool_depend>catkin</buildtool_depend>",
        *depends,
        "  <export>",
        "    <architecture_independent />",
        "  </export>",
        "</package>",
    ]
    return newline.join(lines)


def cmakelists(export: Export) -> str:
    # StreamWriter.WriteLine with "\r\n" already in the text: a blank line after each statement.
    blocks = ["cmake_minimum_required(VERSION 2.8.3)", f"project({export.name})",
              "find_package(catkin REQUIRED)", "catkin_package()", "find_package(roslaunch)"]
    tail = ["foreach(dir config launch meshes urdf)", "\tinstall(DIRECTORY ${dir}/",
            "\t\tDESTINATION ${CATKIN_PACKAGE_SHARE_DESTINATION}/${dir})", "endforeach(dir)"]
    return "".join(b + CRLF + CRLF for b in blocks) + "".join(t + CRLF for t in tail)


def joint_names_yaml(export: Export) -> str:
    names = ["", *(j.name for j in export.joints if j.type != "fixed")]
    return "controller_joint_names: [" + "".join(f"'{n}', " for n in names) + "]" + CRLF


def display_launch(export: Export, newline: str = CRLF) -> str:
    x = _Xml(newline)
    find = f"$(find {export.name})"
    x.start(0, "launch")
    x.empty(1, "arg", {"name": "model"})
    x.empty(1, "param", {"name": "robot_description",
                         "textfile": f"{find}/urdf/{export.name}.urdf"})
    for node in ("joint_state_publisher_gui", "robot_state_publisher"):
        x.empty(1, "node", {"name": node, "pkg": node, "type": node})
    x.empty(1, "node", {"name": "rviz", "pkg": "rviz", "type": "rviz",
                        "args": f"-d {find}/urdf.rviz"})
    x.end(0, "launch")
    return x.text()


def gazebo_launch(export: Export, newline: str = CRLF) -> str:
    x = _Xml(newline)
    name = export.name
    x.start(0, "launch")
    x.empty(1, "include", {"file": "$(find gazebo_ros)/launch/empty_world.launch"})
    x.empty(1, "node", {"name": "tf_footprint_base", "pkg": "tf",
                        "type": "static_transform_publisher",
                        "args": "0 0 0 0 0 0 base_link base_footprint 40"})
    x.empty(1, "node", {"name": "spawn_model", "pkg": "gazebo_ros", "type": "spawn_model",
                        "args": f"-file $(find {name})/urdf/{name}.urdf -urdf -model {name}",
                        "output": "screen"})
    x.empty(1, "node", {"name": "fake_joint_calibration", "pkg": "rostopic", "type": "rostopic",
                        "args": "pub /calibrated std_msgs/Bool true"})
    x.end(0, "launch")
    return x.text()


def csv_text(export: Export) -> str:
    out = io.StringIO()
    writer = csv.writer(out, lineterminator=CRLF)
    writer.writerow(CSV_COLUMNS)
    for link in export.links:
        mesh = f"package://{export.name}/meshes/{link.name}.STL"
        row = [link.name, *link.com.split(), 0, 0, 0, link.mass, *link.inertia,
               0, 0, 0, 0, 0, 0, mesh, *link.rgba.split(), 0, 0, 0, 0, 0, 0, mesh, "",
               link.component]
        joint = export.joint_of(link.name)
        if joint is None:
            row += ["Origin_global", "", "", "", 0, 0, 0, 0, 0, 0, "", 0, 0, 0]
            limit = ["", "", "", ""]
        else:
            row += [f"Origin_{joint.name}", f"Axis_{joint.name}", joint.name, joint.type,
                    *joint.xyz.split(), *joint.rpy.split(), joint.parent, *joint.axis.split()]
            lower, upper, effort, velocity = joint.limit or ("", "", "", "")
            limit = [effort, velocity, lower, upper]
        safety = joint is None or joint.safety
        row += [*limit, "", "", "", "", "", "", "", 0 if safety else ""]
        writer.writerow(row)
    return out.getvalue()


def export_log(export: Export) -> str:
    """A short log in the add-in's log4net layout: date, level, source file, line, message."""
    home = f"C:\\Users\\user\\{export.name}\\"
    steps = [
        ("Logger.cs", 58, "Logging commencing for SW2URDF exporter"),
        ("ExportHelper.cs", 131, "Beginning the export process"),
        ("ExportHelper.cs", 137, f"Creating package directories with name {export.name} "
                                 "and save path C:\\Users\\user"),
        ("ExportHelper.cs", 146, f"Creating CMakeLists.txt at {home}CMakeLists.txt"),
        ("ExportHelper.cs", 150, f"Creating joint names config at {home}config\\"
                                 f"joint_names_{export.name}.yaml"),
        *(("ExportHelper.cs", 287, f"Saving STL to {home}meshes\\{link.name}.STL")
          for link in export.links),
        ("ExportHelper.cs", 210, f"Writing URDF file to {home}urdf\\{export.name}.urdf"),
        ("ExportHelper.cs", 215, "Copying log file"),
    ]
    return "".join(f"2021-06-14 10:31:{7 + i:02d},{100 + 37 * i:03d} INFO  {src}: {line} - "
                   f"{message}{CRLF}" for i, (src, line, message) in enumerate(steps))


# --- meshes ----------------------------------------------------------------------------------


def link_mesh(link: Link) -> trimesh.Trimesh:
    """A solid whose mass properties match the link's inertial: a cylinder when two principal
    moments agree (wheels, arm segments), else a box; a small cube when the tensor is zero."""
    mass = float(link.mass)
    com = np.array([float(v) for v in link.com.split()])
    ixx, ixy, ixz, iyy, iyz, izz = (float(v) for v in link.inertia)
    tensor = np.array([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]])
    if not tensor.any():
        mesh = trimesh.creation.box(extents=[(mass / 1000.0) ** (1 / 3)] * 3)
        mesh.apply_translation(com)
        return mesh
    moments, axes = np.linalg.eigh(tensor)
    if np.linalg.det(axes) < 0:
        axes[:, 0] = -axes[:, 0]
    gaps = [abs(moments[1] - moments[0]), abs(moments[2] - moments[1])]
    if min(gaps) < 0.02 * moments[2]:
        # The odd moment out is about the cylinder's axis: I_axis = m r^2 / 2.
        odd = 2 if gaps[0] < gaps[1] else 0
        side = float(np.mean(np.delete(moments, odd)))
        r2 = 2 * moments[odd] / mass
        h2 = max(12 * side / mass - 3 * r2, 1e-6)
        mesh = trimesh.creation.cylinder(radius=np.sqrt(r2), height=np.sqrt(h2), sections=32)
        turn = np.eye(4)
        turn[:3, :3] = np.roll(np.eye(3), 2 - odd, axis=1)   # the cylinder's z onto axis `odd`
        mesh.apply_transform(turn)
    else:
        a, b, c = moments
        sides = [6 * (b + c - a) / mass, 6 * (a + c - b) / mass, 6 * (a + b - c) / mass]
        mesh = trimesh.creation.box(extents=np.sqrt(np.maximum(sides, 1e-6)))
    place = np.eye(4)
    place[:3, :3] = axes
    place[:3, 3] = com
    mesh.apply_transform(place)
    return mesh


def stl_bytes(mesh: trimesh.Trimesh) -> bytes:
    """Binary STL with the header zeroed, as the exporter leaves it after SolidWorks saves it."""
    return bytes(80) + mesh.export(file_type="stl")[80:]


# --- the whole package -----------------------------------------------------------------------


def write_export(export: Export, folder: Path, *, newline: str = CRLF) -> Path:
    """Write `export` into folder/<name> as the exporter does; return the package folder.

    `newline="\\n"` gives the same package as it looks after a Git checkout on Linux.
    """
    root = Path(folder) / export.name
    name = export.name
    files: dict[str, str | bytes] = {
        "CMakeLists.txt": cmakelists(export),
        "package.xml": package_xml(export, newline),
        f"config/joint_names_{name}.yaml": joint_names_yaml(export),
        "launch/display.launch": display_launch(export, newline),
        "launch/gazebo.launch": gazebo_launch(export, newline),
        f"urdf/{name}.urdf": urdf_text(export, newline),
        f"urdf/{name}.csv": csv_text(export),
        "export.log": export_log(export),
    }
    for link in export.links:
        files[f"meshes/{link.name}.STL"] = stl_bytes(link_mesh(link))
    for rel, content in files.items():
        path = root / rel
        path.parent.mkdir(parents=True, exist_ok=True)
        if isinstance(content, str):
            content = content.replace(CRLF, newline).encode("utf-8")
        path.write_bytes(content)
    (root / "textures").mkdir(exist_ok=True)
    return root
