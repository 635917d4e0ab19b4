"""`sw2sim check` on packages exactly as the SolidWorks-to-URDF exporter writes them.

The packages come from tests/tool/check/exporter_packages.py: three exports from the exporter's own
repository, rebuilt byte for byte. What the checker should say about each:

- 4_WHEELER_NESTED (release 1.6): no errors. Warnings it may carry are true of every export:
  author and maintainer left as TODO, an upper-case name (catkin only warns about it), the
  visual mesh reused for collision, continuous joints without effort or velocity limits.
- ORIGINAL_3_DOF_ARM (release 1.4): errors for joint2 and joint3, whose limits are the
  exporter's zeros (MuJoCo then ignores the limit and lets the joint turn freely, Gazebo holds
  it at 0), and for package.xml, which uses format-2 <depend> tags without format="2", so
  catkin reads it as format 1 and refuses it. Nothing else is an error.
- 3_DOF_ARM (an early export): errors for the all-zero inertia of each moving link, which
  MuJoCo refuses to compile.
"""

from __future__ import annotations

import dataclasses
import re

import pytest

import sw2sim
from sw2sim.check import ERROR, FATAL, RULES, check
from exporter_packages import (FOUR_WHEELER_NESTED, ORIGINAL_3_DOF_ARM, THREE_DOF_ARM_EARLY,
                               csv_text, joint_names_yaml, package_xml, urdf_text, write_export)

# Verbatim from ros/solidworks_urdf_exporter, examples/4_WHEELER_NESTED (line ends as stored).
REAL_NESTED_URDF_START = """\
<?xml version="1.0" encoding="utf-8"?>
<!-- This URDF was automatically created by SolidWorks to URDF Exporter! Originally created \
by Stephen Brawner (brawner@gmail.com)\x20
     Commit Version: 25f2e4c  Build Version: 1.6.9650.27696
     For more information, please see http://wiki.ros.org/sw_urdf_exporter -->
<robot
  name="4_WHEELER_NESTED_description">
  <link
    name="base_link">
    <inertial>
      <origin
        xyz="-0.0141165384615385 1.92116548051542E-18 0.0069190520362904"
        rpy="0 0 0" />
      <mass
        value="0.563365165980808" />
      <inertia
        ixx="0.00116991160584325"
        ixy="1.08541480873037E-19"
        ixz="-1.21271091266427E-20"
        iyy="0.000379959750479481"
        iyz="2.37730438953325E-20"
        izz="0.00131589792050722" />
    </inertial>
    <visual>
      <origin
        xyz="0 0 0"
        rpy="0 0 0" />
      <geometry>
        <mesh
          filename="package://4_WHEELER_NESTED_description/meshes/base_link.STL" />
      </geometry>
      <material
        name="">
        <color
          rgba="0.792156862745098 0.819607843137255 0.933333333333333 1" />
      </material>
    </visual>
    <collision>
      <origin
        xyz="0 0 0"
        rpy="0 0 0" />
      <geometry>
        <mesh
          filename="package://4_WHEELER_NESTED_description/meshes/base_link.STL" />
      </geometry>
    </collision>
  </link>
"""

REAL_NESTED_JOINT = """\
  <joint
    name="front_right_joint"
    type="continuous">
    <origin
      xyz="-0.0516165384615384 -0.05 -0.00997411961288419"
      rpy="1.5707963267949 0 3.14159265358979" />
    <parent
      link="base_link" />
    <child
      link="front_right_link" />
    <axis
      xyz="1 0 0" />
    <safety_controller
      k_velocity="0" />
  </joint>
"""

REAL_NESTED_PACKAGE_XML = """\
<package format="2">
  <name>4_WHEELER_NESTED_description</name>
  <version>1.0.0</version>
  <description>
    <p>URDF Description package for 4_WHEELER_NESTED_description</p>
    <p>This package contains configuration data, 3D models and launch files
for 4_WHEELER_NESTED_description robot</p>
  </description>
  <author>TODO</author>
  <maintainer email="TODO@email.com" />
  <license>BSD</license>
  <buildtool_depend>catkin</buildtool_depend>
  <depend>roslaunch</depend>
  <depend>robot_state_publisher</depend>
  <depend>rviz</depend>
  <depend>joint_state_publisher_gui</depend>
  <depend>gazebo</depend>
  <export>
    <architecture_independent />
  </export>
</package>"""

REAL_NESTED_CSV_ROW = (
    "front_right_link,0.0160973084886128,-1.21430643318376E-17,-2.08166817117217E-17,0,0,0,"
    "0.0948368282302419,4.90180492807281E-05,1.59355527597186E-21,-5.57899635461016E-22,"
    "2.67081223942584E-05,1.35119091414065E-21,2.67081223942584E-05,0,0,0,0,0,0,"
    "package://4_WHEELER_NESTED_description/meshes/front_right_link.STL,0.752941176470588,"
    "0.752941176470588,0.752941176470588,1,0,0,0,0,0,0,"
    "package://4_WHEELER_NESTED_description/meshes/front_right_link.STL,,"
    "4_WHEELER_WHEEL_DRIVER-2/4_WHEEL_DUAL_WHEEL-1,Origin_front_right_joint,"
    "Axis_front_right_joint,front_right_joint,continuous,-0.0516165384615384,-0.05,"
    "-0.00997411961288419,1.5707963267949,0,3.14159265358979,base_link,1,0,0,,,,,,,,,,,,0")

# Verbatim from examples/ORIGINAL_3_DOF_ARM.
REAL_ORIGINAL_YAML = "controller_joint_names: ['', 'joint1', 'joint2', 'joint3', ]\n"


def errors(report):
    return [f for f in report.findings if f.severity in (FATAL, ERROR)]


def about(report, name: str, group: str | None = None):
    """Findings whose message names `name` (a link or joint), optionally of one rule group."""
    word = re.compile(rf"(?<!\w){re.escape(name)}(?!\w)")
    return [f for f in report.findings
            if word.search(f.message) and (group is None or RULES[f.rule].group == group)]


@pytest.fixture(scope="module")
def exports(tmp_path_factory):
    """Each export written once, with the exporter's CRLF line ends."""
    folder = tmp_path_factory.mktemp("exports")
    return {e.name: write_export(e, folder) for e in
            (FOUR_WHEELER_NESTED, ORIGINAL_3_DOF_ARM, THREE_DOF_ARM_EARLY)}


def test_the_builder_writes_what_the_exporter_wrote():
    urdf = urdf_text(FOUR_WHEELER_NESTED, newline="\n")
    assert urdf.startswith(REAL_NESTED_URDF_START)
    assert REAL_NESTED_JOINT in urdf
    assert urdf.endswith("</robot>")
    assert package_xml(FOUR_WHEELER_NESTED, newline="\n") == REAL_NESTED_PACKAGE_XML
    assert REAL_NESTED_CSV_ROW + "\r\n" in csv_text(FOUR_WHEELER_NESTED)
    assert joint_names_yaml(ORIGINAL_3_DOF_ARM) == REAL_ORIGINAL_YAML.replace("\n", "\r\n")


def test_the_package_has_the_exporters_files(exports):
    root = exports[FOUR_WHEELER_NESTED.name]
    name = root.name
    expected = {"CMakeLists.txt", "package.xml", "export.log", f"config/joint_names_{name}.yaml",
                "launch/display.launch", "launch/gazebo.launch", f"urdf/{name}.urdf",
                f"urdf/{name}.csv", *(f"meshes/{link.name}.STL" for link in
                                      FOUR_WHEELER_NESTED.links)}
    assert {p.relative_to(root).as_posix() for p in root.rglob("*") if p.is_file()} == expected
    assert (root / "textures").is_dir()
    assert b"\r\n" in (root / "urdf" / f"{name}.urdf").read_bytes()
    assert (root / "meshes" / "base_link.STL").read_bytes()[:80] == bytes(80)


@pytest.mark.parametrize("newline", ["\r\n", "\n"], ids=["as-exported", "git-checkout"])
def test_a_1_6_export_has_no_errors(tmp_path, newline):
    root = write_export(FOUR_WHEELER_NESTED, tmp_path, newline=newline)
    report = check(root, stability=False)
    assert not errors(report), report.format()
    assert report.status == 0


def test_the_exporters_zero_limits_are_flagged_on_each_revolute_joint(exports):
    report = check(exports[ORIGINAL_3_DOF_ARM.name], stability=False)
    for joint in ("joint2", "joint3"):
        assert about(report, joint, "joint"), f"{joint}'s all-zero <limit> is not flagged:\n" \
                                              f"{report.format()}"
    # joint1 is continuous and has no <limit>: whatever flags the zeros must leave it alone.
    zero_limit_rules = {f.rule for f in about(report, "joint2", "joint")}
    assert not [f for f in about(report, "joint1") if f.rule in zero_limit_rules], report.format()


def test_a_1_4_package_xml_without_its_format_is_an_error(tmp_path):
    # Renamed to lower case, so that only the missing format can make package.xml wrong.
    export = dataclasses.replace(ORIGINAL_3_DOF_ARM, name="original_3_dof_arm_description")
    report = check(write_export(export, tmp_path), stability=False)
    manifest = [f for f in errors(report) if (f.file or "").endswith("package.xml")]
    assert manifest, report.format()


def test_a_1_4_export_has_no_other_errors(exports):
    report = check(exports[ORIGINAL_3_DOF_ARM.name], stability=False)
    expected = set(map(id, about(report, "joint2") + about(report, "joint3")))
    unexpected = [f for f in errors(report) if id(f) not in expected
                  and not (f.file or "").endswith("package.xml")]
    assert not unexpected, report.format()


def test_an_early_exports_zero_inertia_is_an_error_for_each_moving_link(exports):
    root = exports[THREE_DOF_ARM_EARLY.name]
    report = check(root, stability=False)
    for link in ("prox_link", "dist_Link", "effector_link"):
        found = [f for f in about(report, link, "inertia") if f.severity == ERROR]
        assert found, f"{link}'s zero inertia is not an error:\n{report.format()}"
    with pytest.raises(sw2sim.LoadError, match="mjMINVAL"):
        sw2sim.load_package(root)


def test_real_exports_load_in_mujoco(exports):
    wheeler = sw2sim.load_package(exports[FOUR_WHEELER_NESTED.name]).compile()
    assert wheeler.njnt == 4 and wheeler.nmesh == 5
    arm = sw2sim.load_package(exports[ORIGINAL_3_DOF_ARM.name]).compile()
    # MuJoCo drops a limit whose lower equals its upper: the "locked" joint turns freely.
    assert arm.njnt == 3 and not arm.jnt_limited.any()


def test_the_stability_run_on_a_real_export_finishes(tmp_path):
    # Lower case, as most users name their assembly, so that the stability run is reached.
    export = dataclasses.replace(FOUR_WHEELER_NESTED, name="four_wheeler_nested_description")
    report = check(write_export(export, tmp_path), stability=True)
    assert not errors(report), report.format()
    assert isinstance(report.stability, dict)
    assert report.format() and report.to_json()
