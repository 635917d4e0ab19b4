"""Reading transmissions, limits and controller YAML from a package: good input and bad."""

import shutil

import pytest

import sw2sim
from sw2sim.loader import LoadError
from repository import ROOT
from sw2sim.ros_control import add_motors, read_controllers, read_joint_limits, read_transmissions

EXAMPLE_3 = ROOT / "examples" / "example_3"


@pytest.fixture
def package(tmp_path):
    copy = tmp_path / "example_3"
    shutil.copytree(EXAMPLE_3, copy)
    return copy


def edit_urdf(package, old, new):
    urdf = package / "urdf" / "example_3.urdf"
    text = urdf.read_text()
    assert old in text
    urdf.write_text(text.replace(old, new, 1))
    return urdf


def test_limits_and_safety_are_read():
    limits = read_joint_limits(EXAMPLE_3)
    middle = limits["middle_arm_joint"]
    assert (middle.lower, middle.upper, middle.effort, middle.velocity) == (-0.7854, 0.7854, 1000, 2)
    assert middle.has_soft_limits and middle.k_velocity == 10 and middle.k_position == 20


def test_a_joint_without_safety_controller_has_no_soft_limits(package):
    urdf = package / "urdf" / "example_3.urdf"
    text = urdf.read_text()
    start = text.index("<safety_controller")
    urdf.write_text(text[:start] + text[text.index("/>", start) + 2:])
    assert not read_joint_limits(package)["middle_arm_joint"].has_soft_limits


def test_a_limit_that_is_not_a_number_names_file_and_line(package):
    urdf = edit_urdf(package, 'effort="1000"', 'effort="1000 N.m"')
    with pytest.raises(LoadError) as err:
        read_joint_limits(package)
    assert err.value.file == str(urdf.resolve()) and err.value.line
    assert urdf.read_text().splitlines()[err.value.line - 1].strip() == 'effort="1000 N.m"'
    assert "is not a number" in str(err.value)


def test_a_transmission_without_a_joint_is_refused_with_its_line(package):
    urdf = edit_urdf(package, '<joint name="end_arm_joint">\n      <hardwareInterface>hardware_interface/EffortJointInterface'
                     '</hardwareInterface>\n    </joint>\n', "")
    with pytest.raises(LoadError, match="needs a <joint> and an <actuator>") as err:
        read_transmissions(package)
    assert urdf.read_text().splitlines()[err.value.line - 1].strip().startswith('<transmission name="end_arm')


def test_a_mechanical_reduction_becomes_the_motor_gear(package):
    edit_urdf(package, "<mechanicalReduction>1</mechanicalReduction>", "<mechanicalReduction>50</mechanicalReduction>")
    spec = sw2sim.load_package(package)
    add_motors(spec, package)
    model = spec.compile()
    assert model.actuator_gear[0, 0] == 50
    assert list(model.actuator_ctrlrange[0]) == [-20, 20], "1000 N·m at the joint is 20 N·m at the motor"


def test_bad_yaml_names_the_line(tmp_path):
    config = tmp_path / "controllers.yaml"
    config.write_text("example_3:\n  middle_arm_controller:\n    pid: {p: 100, i: [\n")
    with pytest.raises(LoadError, match="not valid YAML") as err:
        read_controllers(config)
    assert err.value.line >= 3


def test_a_missing_yaml_file_is_a_clear_error(tmp_path):
    with pytest.raises(LoadError, match="cannot read the controller configuration"):
        read_controllers(tmp_path / "nowhere.yaml")
