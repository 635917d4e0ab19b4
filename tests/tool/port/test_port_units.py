"""sw2sim port, piece by piece: names, the controller mapping, the URDF rewrite, package.xml."""

from __future__ import annotations

import json
from pathlib import Path

import yaml
import pytest
from lxml import etree

import ros2_environment
from packages import copy_example, edit
from sw2sim.port import PortError, controllers, naming, port, urdf
from sw2sim.port.controllers import Ros1Controller

JOINTS = {"a": "revolute", "b": "revolute", "wheel": "continuous", "steer": "revolute"}


@pytest.mark.parametrize("given, legal", [
    ("Arm_Assembly", "arm_assembly"), ("robot.SLDASM", "robot_sldasm"), ("2wd_car", "r2wd_car"),
    ("my--Robot", "my_robot"), ("_x_", "x"), ("...", "robot"), ("example_3", "example_3")])
def test_names_are_made_legal(given, legal):
    assert naming.legal_name(given) == legal
    assert naming.is_legal(legal)
    assert naming.is_legal(given) == (given == legal)


def test_the_legal_pattern_is_stricter_than_catkin_pkgs():
    for bad in ("Arm", "a-b", "a.b", "1a", "a__b", "a_"):
        assert not naming.is_legal(bad), bad


def _plan(*ros1, effort=()):
    return controllers.plan(list(ros1), JOINTS, update_rate=None, effort_joints=list(effort))


def _c(name, kind, **values):
    return Ros1Controller(name, kind, {"type": kind, **values}, "config/c.yaml", 3)


def test_joint_state_controller_becomes_the_broadcaster_with_its_rate():
    plan = _plan(_c("joint_state_controller", "joint_state_controller/JointStateController",
                    publish_rate=50))
    [jsb] = plan.controllers
    assert (jsb.name, jsb.type) == ("joint_state_broadcaster",
                                    "joint_state_broadcaster/JointStateBroadcaster")
    assert jsb.parameters == {"update_rate": 50}
    assert plan.update_rate == 1000


def test_a_broadcaster_is_added_when_the_source_has_none():
    plan = _plan()
    assert plan.names == ["joint_state_broadcaster"]
    assert any("was added" in c for c in plan.choices)
    # Without a rate of its own it would publish at the controller manager's 1000 Hz.
    assert plan.controllers[0].parameters == {"update_rate": controllers.STATE_RATE}


def test_an_added_broadcaster_keeps_the_gazebo_joint_state_publishers_rate():
    """Practice 1's URDF has gazebo_ros' joint_state_publisher at <updateRate>50</updateRate>;
    its broadcaster publishes as often."""
    robot = etree.fromstring(
        '<robot name="r"><gazebo><plugin name="jsp" filename="libgazebo_ros_joint_state_publisher.so">'
        "<updateRate>25</updateRate></plugin></gazebo></robot>")
    rate = urdf.joint_state_rate(robot)
    assert rate == 25
    plan = controllers.plan([], JOINTS, update_rate=None, effort_joints=[], state_rate=rate)
    assert plan.controllers[0].parameters == {"update_rate": 25}
    assert any("<updateRate>" in c for c in plan.choices)


def test_effort_position_pid_becomes_a_trajectory_controller_with_jazzy_gain_keys():
    plan = _plan(_c("arm", "effort_controllers/JointPositionController", joint="a",
                    pid={"p": 100, "i": 10, "d": 5, "i_clamp": 0.5, "antiwindup": True}))
    arm = plan.controllers[1]
    assert arm.type == "joint_trajectory_controller/JointTrajectoryController"
    assert arm.parameters == {"joints": ["a"], "command_interfaces": ["effort"],
                              "state_interfaces": ["position", "velocity"],
                              "gains": {"a": {"p": 100.0, "i": 10.0, "d": 5.0,
                                              "i_clamp_max": 0.5, "i_clamp_min": -0.5}}}
    assert arm.commands == {"a": "effort"}
    assert any("antiwindup" in c and "dropped" in c for c in plan.choices)


# Every class ROS 1 (ros_controllers, noetic-devel) registers under velocity_controllers/:
# velocity_controllers_plugins.xml, and joint_trajectory_controller's ros_control_plugins.xml
VELOCITY_CONTROLLERS = ("JointVelocityController", "JointPositionController",
                        "JointGroupVelocityController", "JointTrajectoryController")


@pytest.mark.parametrize("kind", VELOCITY_CONTROLLERS)
def test_every_ros1_velocity_controller_has_its_jazzy_counterpart(kind):
    jazzy = json.loads((Path(__file__).with_name("jazzy_packages.json")).read_text())
    group = kind.startswith("JointGroup") or kind == "JointTrajectoryController"
    values = {"joints": ["a", "b"]} if group else {"joint": "a", "pid": {"p": 2.0}}
    plan = _plan(_c("v", f"velocity_controllers/{kind}", **values))
    made = plan.controllers[1]
    assert made.type in jazzy["controller_types"]
    assert set(made.commands.values()) == {"velocity"}


def test_velocity_position_pid_becomes_a_trajectory_controller_on_velocity():
    # ROS 1: a PID on the position error whose output is the joint's velocity command
    plan = _plan(_c("arm", "velocity_controllers/JointPositionController", joint="a",
                    pid={"p": 8, "i": 0.5, "d": 0.1}))
    arm = plan.controllers[1]
    assert arm.type == "joint_trajectory_controller/JointTrajectoryController"
    assert arm.parameters == {"joints": ["a"], "command_interfaces": ["velocity"],
                              "state_interfaces": ["position", "velocity"],
                              "gains": {"a": {"p": 8.0, "i": 0.5, "d": 0.1}}}
    assert any("velocity_controllers/JointPositionController" in c and "no counterpart" not in c
               for c in plan.choices)


def test_effort_velocity_pid_becomes_pid_controller_on_velocity():
    plan = _plan(_c("w", "effort_controllers/JointVelocityController", joint="wheel",
                    pid={"p": 5.0, "i": 0.0, "d": 0.0}))
    w = plan.controllers[1]
    assert w.type == "pid_controller/PidController"
    assert w.parameters == {"dof_names": ["wheel"], "command_interface": "effort",
                            "reference_and_state_interfaces": ["velocity"],
                            "gains": {"wheel": {"p": 5.0, "i": 0.0, "d": 0.0}}}
    assert any("/w/reference" in c for c in plan.choices)


@pytest.mark.parametrize("ros1, ros2, interface", [
    ("effort_controllers/JointEffortController", "effort_controllers/JointGroupEffortController",
     "effort"),
    ("velocity_controllers/JointVelocityController",
     "velocity_controllers/JointGroupVelocityController", "velocity"),
    ("position_controllers/JointPositionController",
     "position_controllers/JointGroupPositionController", "position")])
def test_single_joint_forward_controllers_become_group_controllers(ros1, ros2, interface):
    made = _plan(_c("x", ros1, joint="b")).controllers[1]
    assert (made.type, made.parameters, made.commands) == (ros2, {"joints": ["b"]},
                                                           {"b": interface})


def test_ackermann_becomes_the_bicycle_controller_with_jazzy_names():
    plan = _plan(_c("car", "ackermann_steering_controller/AckermannSteeringController",
                    rear_wheel="wheel", front_steer="steer", wheel_separation_h=0.3,
                    wheel_radius=0.05, cmd_vel_timeout=0.5, publish_rate=50))
    car = plan.controllers[1]
    assert car.type == "bicycle_steering_controller/BicycleSteeringController"
    assert car.parameters == {"traction_joints_names": ["wheel"], "steering_joints_names": ["steer"],
                              "wheelbase": 0.3, "traction_wheel_radius": 0.05,
                              "reference_timeout": 0.5}
    assert car.commands == {"wheel": "velocity", "steer": "position"}
    assert any("publish_rate" in c and "Not carried over" in c for c in plan.choices)


def test_unknown_types_and_unknown_joints_are_left_out_and_reported():
    plan = _plan(_c("odd", "my_controllers/Magic", joint="a"),
                 _c("typo", "effort_controllers/JointEffortController", joint="nope"))
    assert plan.names == ["joint_state_broadcaster"]
    assert any("`odd`" in c and "left out" in c for c in plan.choices)
    assert any("`typo`" in c and "nope" in c for c in plan.choices)


def test_effort_joints_share_one_group_controller_and_conflicts_are_refused():
    plan = _plan(effort=["a", "b"])
    assert plan.controllers[1].name == "effort_controller"
    assert plan.controllers[1].parameters == {"joints": ["a", "b"]}
    with pytest.raises(controllers.Conflict):
        _plan(_c("x", "effort_controllers/JointEffortController", joint="a"), effort=["a"])


def test_the_yaml_has_the_controller_manager_section_first():
    plan = _plan(_c("x", "effort_controllers/JointEffortController", joint="a"))
    data = yaml.safe_load(controllers.yaml_text(plan, "pkg"))
    assert list(data) == ["controller_manager", "joint_state_broadcaster", "x"]
    manager = data["controller_manager"]["ros__parameters"]
    assert manager == {"update_rate": 1000,
                       "joint_state_broadcaster": {"type": "joint_state_broadcaster/"
                                                           "JointStateBroadcaster"},
                       "x": {"type": "effort_controllers/JointGroupEffortController"}}


# -- the URDF -----------------------------------------------------------------------------
def _urdf(out, name):
    return etree.parse(str(out / "urdf" / f"{name}.urdf")).getroot()


def test_the_urdf_gets_ros2_control_from_the_transmissions(tmp_path):
    src = copy_example(3, tmp_path / "src")
    report = port(src, tmp_path / "out", name="arm")
    robot = _urdf(tmp_path / "out", "arm")
    assert robot.findall("transmission") == []
    assert not [p for p in robot.iter("plugin") if "gazebo_ros_control" in p.get("filename", "")]
    block = robot.find("ros2_control")
    assert block.findtext("hardware/plugin") == "gz_ros2_control/GazeboSimSystem"
    joints = {j.get("name"): j for j in block.findall("joint")}
    assert list(joints) == ["middle_arm_joint", "end_arm_joint"]
    for joint in joints.values():
        [command] = joint.findall("command_interface")
        assert command.get("name") == "effort"
        assert {p.get("name"): p.text for p in command.findall("param")} == {"min": "-1000",
                                                                            "max": "1000"}
        assert [s.get("name") for s in joint.findall("state_interface")] == [
            "position", "velocity", "effort"]
    plugin = robot.find("gazebo/plugin[@filename='gz_ros2_control-system']")
    assert plugin.get("name") == "gz_ros2_control::GazeboSimROS2ControlPlugin"
    assert plugin.findtext("parameters") == "$(find arm)/config/controllers.yaml"
    meshes = [m.get("filename") for m in robot.iter("mesh")]
    assert meshes and all(m.startswith("package://arm/meshes/") for m in meshes)
    assert any(isinstance(c, etree._Comment) for c in robot.iter(etree.Comment)) or \
        "<!--" in (tmp_path / "out/urdf/arm.urdf").read_text()
    assert report.name == "arm" and any("--name" in c for c in report.choices)


def test_bare_and_velocity_interfaces_are_read(tmp_path):
    src = copy_example(3, tmp_path / "src")
    urdf = src / "urdf" / "example_3.urdf"
    text = urdf.read_text()
    head, _, tail = text.partition('<joint name="end_arm_joint">')
    tail = tail.replace("hardware_interface/EffortJointInterface", "VelocityJointInterface", 2)
    urdf.write_text(head.replace("hardware_interface/EffortJointInterface",
                                 "EffortJointInterface") + '<joint name="end_arm_joint">' + tail)
    edit(src / "config" / "joint_names_example_3.yaml", "effort_controllers/JointPositionController\n"
         "    joint: end_arm_joint", "velocity_controllers/JointVelocityController\n"
         "    joint: end_arm_joint")
    port(src, tmp_path / "out")
    block = _urdf(tmp_path / "out", "example_3").find("ros2_control")
    end = block.find("joint[@name='end_arm_joint']/command_interface")
    assert end.get("name") == "velocity"
    assert {p.get("name"): p.text for p in end.findall("param")} == {"min": "-2", "max": "2"}
    assert block.find("joint[@name='middle_arm_joint']/command_interface").get("name") == "effort"


def test_joints_without_a_transmission_report_state_and_effort_joints_get_a_command(tmp_path):
    wheels = "front_left_joint,front_right_joint,rear_left_joint,rear_right_joint"
    report = port(copy_example(1, tmp_path / "src"), tmp_path / "out", effort_joints=[wheels])
    block = _urdf(tmp_path / "out", "example_1").find("ros2_control")
    for joint in block.findall("joint"):
        assert joint.find("command_interface").get("name") == "effort"
    assert "effort_controller" in report.controllers
    robot = _urdf(tmp_path / "out", "example_1")
    assert not [p for p in robot.iter("plugin") if "joint_state_publisher" in p.get("filename", "")]
    bare = port(copy_example(1, tmp_path / "src2"), tmp_path / "out2", default_controllers=False)
    block = _urdf(tmp_path / "out2", "example_1").find("ros2_control")
    assert [j.find("command_interface") for j in block.findall("joint")] == [None] * 4
    assert any("state interfaces only" in c for c in bare.choices)


def test_unknown_effort_joints_and_illegal_names_are_refused(tmp_path):
    src = copy_example(3, tmp_path / "src")
    with pytest.raises(PortError, match="not a movable joint"):
        port(src, tmp_path / "out", effort_joints=["nope"])
    with pytest.raises(PortError, match="arm_2"):
        port(src, tmp_path / "out", name="Arm.2")
    assert not (tmp_path / "out").exists()


def test_package_xml_passes_catkin_pkg_validation_in_format_3(tmp_path):
    """catkin_pkg (colcon's reader of package.xml, in the ROS 2 environment) parses the
    ported package.xml as format 3 and validates it without a warning."""
    if not ros2_environment.PYTHON.exists():
        pytest.skip(ros2_environment.missing())
    src = copy_example(3, tmp_path / "src", name="Arm_Assembly")
    edit(src / "package.xml", 'email="TODO@email.com"', 'email="a@b.c"')
    for path in (src / "package.xml", src / "urdf" / "example_3.urdf"):
        path.write_text(path.read_text().replace("example_3", "Arm_Assembly"))
    port(src, tmp_path / "out")
    done = ros2_environment.run(
        "import json, sys; from catkin_pkg.package import parse_package\n"
        "p = parse_package(sys.argv[1]); warnings = []; p.validate(warnings=warnings)\n"
        "print(json.dumps({'format': p.package_format, 'warnings': warnings, 'name': p.name,\n"
        "  'buildtool': [d.name for d in p.buildtool_depends],\n"
        "  'exec': [d.name for d in p.exec_depends]}))",
        str(tmp_path / "out" / "package.xml"))
    assert done.returncode == 0, done.stderr
    package = json.loads(done.stdout)
    assert package["format"] == 3 and package["warnings"] == []
    assert package["name"] == "arm_assembly"
    assert package["buildtool"] == ["ament_cmake"]
    assert {"joint_trajectory_controller", "gz_ros2_control", "ros_gz_sim"} <= set(package["exec"])


def test_maintainer_and_license_options_give_a_package_xml_catkin_pkg_takes_silently(
        tmp_path, capsys):
    """The exporter leaves the maintainer TODO (TODO@email.com, which catkin_pkg refuses) and
    no licence: --maintainer and --license put the user's, and catkin_pkg validates the
    result in format 3 without a warning."""
    from sw2sim.cli import main
    if not ros2_environment.PYTHON.exists():
        pytest.skip(ros2_environment.missing())
    src = copy_example(3, tmp_path / "src")
    out = tmp_path / "out"
    assert main(["port", str(src), "-o", str(out), "--maintainer",
                 "Ada Lovelace <ada.lovelace@example.org>", "--license", "Apache-2.0"]) == 0
    assert "placeholder (TODO)" not in capsys.readouterr().out
    done = ros2_environment.run(
        "import json, sys; from catkin_pkg.package import parse_package\n"
        "warnings = []; p = parse_package(sys.argv[1], warnings=warnings)\n"
        "p.validate(warnings=warnings)\n"
        "print(json.dumps({'warnings': warnings, 'licenses': [str(x) for x in p.licenses],\n"
        "  'maintainers': [[m.name, m.email] for m in p.maintainers]}))",
        str(out / "package.xml"))
    assert done.returncode == 0, done.stderr
    package = json.loads(done.stdout)
    assert package == {"warnings": [], "licenses": ["Apache-2.0"],
                       "maintainers": [["Ada Lovelace", "ada.lovelace@example.org"]]}
    for bad in ("ada@example.org", "Ada <ada@example>"):
        assert main(["port", str(src), "-o", str(tmp_path / "bad"), "--maintainer", bad]) == 2
        assert "--maintainer" in capsys.readouterr().err
    assert not (tmp_path / "bad").exists()
