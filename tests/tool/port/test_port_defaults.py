"""sw2sim port on exports that command nothing (no transmissions, no controllers): the
exporter's own arms and four-wheeler get a command interface on every movable joint and a
controller to send it to, said in the report and the README; --no-controllers leaves them
out. The exporter's empty limits, which would keep a joint still in Gazebo, are repaired."""

from __future__ import annotations

import re
import sys
from pathlib import Path

import yaml
from lxml import etree

import sw2sim
from packages import copy_example, edit, edit_re
from sw2sim.cli import main
from sw2sim.port import port

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "check"))
from exporter_packages import (FOUR_WHEELER_NESTED, ORIGINAL_3_DOF_ARM,  # noqa: E402
                               THREE_DOF_ARM, write_export)

JTC = "joint_trajectory_controller/JointTrajectoryController"
VELOCITY = "velocity_controllers/JointGroupVelocityController"


def _yaml(out: Path) -> dict:
    return yaml.safe_load((out / "config" / "controllers.yaml").read_text())


def _commands(out: Path) -> dict[str, list[str]]:
    """Each joint of the ported URDF's <ros2_control> block: its command interfaces."""
    [urdf] = (out / "urdf").glob("*.urdf")
    block = etree.parse(str(urdf)).getroot().find("ros2_control")
    return {j.get("name"): [c.get("name") for c in j.findall("command_interface")]
            for j in block.findall("joint")}


def _launched(out: Path) -> list[str]:
    text = (out / "launch" / "gazebo.launch.py").read_text()
    return yaml.safe_load(re.search(r"^CONTROLLERS = (.*)$", text, re.M).group(1))


def test_the_exporters_3_dof_arm_gets_a_trajectory_controller_on_position(tmp_path):
    src = write_export(THREE_DOF_ARM, tmp_path / "src")
    out = tmp_path / "out"
    report = port(src, out)
    joints = ["prox_joint", "dist_joint", "effector_joint"]
    config = _yaml(out)
    manager = config["controller_manager"]["ros__parameters"]
    assert manager["joint_trajectory_controller"] == {"type": JTC}
    assert config["joint_trajectory_controller"]["ros__parameters"] == {
        "joints": joints, "command_interfaces": ["position"],
        "state_interfaces": ["position", "velocity"], "allow_partial_joints_goal": True}
    assert _commands(out) == {j: ["position"] for j in joints}
    assert report.controllers == ["joint_state_broadcaster", "joint_trajectory_controller"]
    assert _launched(out) == report.controllers
    said = [c for c in report.choices if "joint_trajectory_controller" in c]
    assert len(said) == 1 and "no transmissions and no controllers" in said[0]
    assert "prox_joint, dist_joint and effector_joint" in said[0] and "`position`" in said[0]
    assert "--no-controllers" in said[0]
    # the README says how to move them, with a command that names every joint
    readme = (out / "README.md").read_text()
    assert said[0] in readme and "## Moving the joints" in readme
    assert ("ros2 topic pub --once /joint_trajectory_controller/joint_trajectory "
            "trajectory_msgs/msg/JointTrajectory") in readme
    assert "joint_names: [prox_joint, dist_joint, effector_joint]" in readme
    assert "angle_wraparound" in readme    # continuous joints: goals on the circle
    assert "added, as the package commands no joint" in (out / "config/controllers.yaml").read_text()
    depends = etree.parse(str(out / "package.xml")).getroot().findall("exec_depend")
    assert "joint_trajectory_controller" in {d.text for d in depends}


def test_the_report_printed_says_so_and_no_controllers_leaves_them_out(tmp_path, capsys):
    src = write_export(THREE_DOF_ARM, tmp_path / "src")
    assert main(["port", str(src), "-o", str(tmp_path / "with")]) == 0
    printed = capsys.readouterr().out
    assert "`position` command interface and `joint_trajectory_controller`" in printed
    assert main(["port", str(src), "-o", str(tmp_path / "without"), "--no-controllers"]) == 0
    printed = capsys.readouterr().out
    out = tmp_path / "without"
    assert "joint_trajectory_controller" not in printed
    assert "state interfaces only" in printed
    assert list(_yaml(out)["controller_manager"]["ros__parameters"]) == [
        "update_rate", "joint_state_broadcaster"]
    assert _commands(out) == {j: [] for j in ("prox_joint", "dist_joint", "effector_joint")}
    assert "Moving the joints" not in (out / "README.md").read_text()
    assert _launched(out) == ["joint_state_broadcaster"]


def test_the_four_wheelers_wheels_get_a_velocity_controller(tmp_path):
    src = write_export(FOUR_WHEELER_NESTED, tmp_path / "src")
    out = tmp_path / "out"
    report = port(src, out)
    wheels = ["front_right_joint", "back_right_joint", "front_left_joint", "back_left_joint"]
    config = _yaml(out)
    assert config["controller_manager"]["ros__parameters"]["wheel_velocity_controller"] == {
        "type": VELOCITY}
    assert config["wheel_velocity_controller"]["ros__parameters"] == {"joints": wheels}
    assert "joint_trajectory_controller" not in config
    assert _commands(out) == {w: ["velocity"] for w in wheels}
    assert any("look like wheels" in c and "/wheel_velocity_controller/commands" in c
               for c in report.choices)
    readme = (out / "README.md").read_text()
    assert ('/wheel_velocity_controller/commands std_msgs/msg/Float64MultiArray '
            '"{data: [1.0, 1.0, 1.0, 1.0]}"') in readme
    assert sw2sim.load_package(out).compile().nmesh == 5   # the port loads, every mesh with it


def test_the_exporters_empty_limits_are_freed_so_that_the_joints_can_move(tmp_path):
    """ORIGINAL_3_DOF_ARM's joint2 and joint3 have lower = upper = effort = velocity = 0: in
    Gazebo they could not move. The port makes them continuous, without the <limit>."""
    src = write_export(ORIGINAL_3_DOF_ARM, tmp_path / "src")
    out = tmp_path / "out"
    report = port(src, out)
    [urdf] = (out / "urdf").glob("*.urdf")
    robot = etree.parse(str(urdf)).getroot()
    kinds = {j.get("name"): (j.get("type"), j.find("limit")) for j in robot.findall("joint")}
    assert kinds == {"joint1": ("continuous", None), "joint2": ("continuous", None),
                     "joint3": ("continuous", None)}
    assert _commands(out) == {j: ["position"] for j in ("joint1", "joint2", "joint3")}
    [freed] = [c for c in report.choices if "empty limit" in c]
    assert "joint2, joint3" in freed and "continuous" in freed and "export again" in freed
    # the source keeps its limits; the port's model turns the freed joints
    assert "<limit" in (src / "urdf" / f"{ORIGINAL_3_DOF_ARM.name}.urdf").read_text()
    model = sw2sim.load_package(out).compile()
    assert not model.jnt_limited[model.joint("joint2").id]
    # --no-controllers repairs nothing: the joints stay as exported
    port(src, tmp_path / "bare", default_controllers=False)
    [urdf] = (tmp_path / "bare" / "urdf").glob("*.urdf")
    assert etree.parse(str(urdf)).getroot().find("joint[@name='joint2']").get("type") == "revolute"


def test_a_prismatic_joint_with_empty_limits_gets_no_controller(tmp_path):
    src = copy_example(4, tmp_path / "src")
    urdf = src / "urdf" / "example_4.urdf"
    edit_re(urdf, r"<transmission.*?</transmission>\s*", "")
    edit_re(urdf, r'(name="block_joint".*?<limit)\s+lower="[^"]*"\s+upper="[^"]*"\s+'
            r'effort="[^"]*"\s+velocity="[^"]*"', r'\1 lower="0" upper="0" effort="0" velocity="0"')
    for path in (src / "config").glob("*.yaml"):
        path.write_text("controller_joint_names: ['', 'block_joint', ]\n")
    report = port(src, tmp_path / "out")
    assert _commands(tmp_path / "out") == {"block_joint": []}
    assert report.controllers == ["joint_state_broadcaster"]
    assert any("block_joint (the exporter's empty limit" in c and "cannot slide" in c
               for c in report.choices)


def test_wheels_are_told_from_an_arms_joints_by_the_tree(tmp_path):
    """Practice 5's car without its transmissions and controllers: the steering joints are
    arm-like (position), the four wheels, two of them on steering knuckles, are wheels.
    The 3-DOF arm's last joint, continuous and carrying nothing, is not a wheel: it hangs
    below continuous joints."""
    src = copy_example(5, tmp_path / "src")
    edit_re(src / "urdf" / "example_5.urdf", r"\s*<transmission.*</transmission>", "")
    for path in (src / "config").glob("*.yaml"):
        path.write_text("controller_joint_names: []\n")
    report = port(src, tmp_path / "out")
    config = _yaml(tmp_path / "out")
    assert config["joint_trajectory_controller"]["ros__parameters"]["joints"] == [
        "steering_joint", "left_knuckle_joint", "right_knuckle_joint"]
    assert config["wheel_velocity_controller"]["ros__parameters"]["joints"] == [
        "front_left_wheel_joint", "front_right_wheel_joint", "rear_left_wheel_joint",
        "rear_right_wheel_joint"]
    assert report.controllers[1:] == ["joint_trajectory_controller", "wheel_velocity_controller"]


def test_defaults_go_to_joints_nothing_else_commands(tmp_path):
    """--effort-joints keep their controller and the other joints get the defaults; a package
    with transmissions or controllers of its own gets none."""
    src = copy_example(1, tmp_path / "src")
    report = port(src, tmp_path / "out", effort_joints=["front_left_joint,front_right_joint"])
    assert _commands(tmp_path / "out") == {
        "front_left_joint": ["effort"], "front_right_joint": ["effort"],
        "rear_left_joint": ["velocity"], "rear_right_joint": ["velocity"]}
    assert report.controllers == ["joint_state_broadcaster", "effort_controller",
                                  "wheel_velocity_controller"]
    # every joint named: nothing is added (the practices' pages port so)
    every = "front_left_joint,front_right_joint,rear_left_joint,rear_right_joint"
    report = port(src, tmp_path / "all", effort_joints=[every])
    assert report.controllers == ["joint_state_broadcaster", "effort_controller"]
    # Practice 3's package has transmissions and controllers: the port maps them only
    report = port(copy_example(3, tmp_path / "src3"), tmp_path / "out3")
    assert report.controllers == ["joint_state_broadcaster", "middle_arm_controller",
                                  "end_arm_controller"]
    assert not any("--no-controllers" in c for c in report.choices)
    # a transmission alone (no ROS 1 controller) also says the package was configured
    src = copy_example(3, tmp_path / "src4")
    edit(src / "config" / "joint_names_example_3.yaml", "effort_controllers/", "nothing/", 2)
    report = port(src, tmp_path / "out4")
    assert "joint_trajectory_controller" not in report.controllers


def test_mimic_joints_axisless_joints_and_an_effort_of_0_are_named(tmp_path):
    """A joint that mimics another and one with the axis 0 0 0 get no controller; a joint
    with a travel but an effort of 0 gets one, and is named, as Gazebo gives it no force."""
    src = write_export(ORIGINAL_3_DOF_ARM, tmp_path / "src")
    urdf = src / "urdf" / f"{ORIGINAL_3_DOF_ARM.name}.urdf"
    edit_re(urdf, r'(name="joint1".*?xyz=)"-1 0 0"', r'\1"0 0 0"')
    edit_re(urdf, r'(name="joint2".*?lower=)"0"(\s+upper=)"0"', r'\1"-1"\2"1"')
    edit_re(urdf, r'(name="joint3".*?)(<safety_controller)',
            r'\1<mimic joint="joint2" multiplier="1" offset="0" />\n    \2')
    report = port(src, tmp_path / "out")
    assert _commands(tmp_path / "out") == {"joint1": [], "joint2": ["position"], "joint3": []}
    assert any("joint1 (its axis is 0 0 0)" in c and "joint3 (it mimics joint2)" in c
               for c in report.choices)
    assert any(c.startswith("joint2: the <limit> gives effort 0") for c in report.choices)


def test_a_mimic_naming_no_joint_is_named_with_its_fix_and_left_out(tmp_path):
    # A hand-added <mimic> with a typo (as in real exports): ros2_control would stop on it
    src = write_export(THREE_DOF_ARM, tmp_path / "src", newline="\n")
    urdf = src / "urdf" / f"{THREE_DOF_ARM.name}.urdf"
    edit_re(urdf, r'(name="effector_joint"\s+type="continuous">)',
            r'\1\n    <mimic\n      joint="dist_jiont" />')
    line = urdf.read_text().splitlines().index('      joint="dist_jiont" />') + 1
    out = tmp_path / "out"
    report = port(src, out)
    (said,) = [c for c in report.choices if "<mimic>" in c]
    assert said.startswith(f"urdf/{THREE_DOF_ARM.name}.urdf:{line}:")
    assert "'dist_jiont', which is not a joint of the URDF" in said
    assert '<mimic joint="dist_joint">' in said and "component_parser.cpp" in said
    ported = etree.parse(str(out / "urdf" / "r3_dof_arm_description.urdf")).getroot()
    assert ported.find(".//mimic") is None
    # the joint moves on its own, so it has a command like the others
    assert _commands(out)["effector_joint"] == ["position"]
