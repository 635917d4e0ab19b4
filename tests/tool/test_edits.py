"""`sw2sim edits save|restore` on a package as the exporter writes it (CRLF, one attribute per
line, its version comment): a student's hand edits survive a re-export, the re-export's
numbers are kept, a file edited after the re-export is never overwritten, and changed joints
are named."""

import os
import sys
from pathlib import Path

import pytest

from sw2sim import cli
from sw2sim.edits import urdf_carry
from sw2sim.package import find_package

sys.path.insert(0, str(Path(__file__).resolve().parent / "check"))
from exporter_packages import FOUR_WHEELER_NESTED, write_export  # noqa: E402  (tests/tool/check)

CRLF = "\r\n"
WORLD = ('  <link\r\n    name="world" />\r\n  <joint\r\n    name="world_joint"\r\n'
         '    type="fixed">\r\n    <origin\r\n      xyz="0 0 0.1"\r\n      rpy="0 0 0" />\r\n'
         '    <parent\r\n      link="world" />\r\n    <child\r\n      link="base_link" />\r\n'
         '  </joint>\r\n')
DYNAMICS = '    <dynamics\r\n      damping="0.01"\r\n      friction="0.2" />\r\n'
ROS_CONTROL = ('  <transmission name="front_left_transmission">\r\n'
               '    <type>transmission_interface/SimpleTransmission</type>\r\n'
               '    <joint name="front_left_joint">\r\n'
               '      <hardwareInterface>hardware_interface/VelocityJointInterface'
               '</hardwareInterface>\r\n    </joint>\r\n'
               '    <actuator name="front_left_motor">\r\n'
               '      <mechanicalReduction>1</mechanicalReduction>\r\n    </actuator>\r\n'
               '  </transmission>\r\n  <gazebo>\r\n'
               '    <plugin name="gazebo_ros_control" filename="libgazebo_ros_control.so" />\r\n'
               '  </gazebo>\r\n')
RED = "1 0 0 1"
SILVER = "0.752941176470588 0.752941176470588 0.752941176470588 1"
NODE = ('  <node\r\n    name="driver"\r\n    pkg="4_WHEELER_NESTED_description"\r\n'
        '    type="driver.py" />\r\n')


def run(*argv) -> int:
    return cli.main(["edits", *map(str, argv)])


def urdf(package: Path) -> Path:
    return package / "urdf" / f"{package.name}.urdf"


def text(path: Path) -> str:
    return path.read_bytes().decode("utf-8")


def write(path: Path, content: str) -> None:
    path.write_bytes(content.encode("utf-8"))


def hand_edit(package: Path) -> None:
    """What a lesson does to the export: a world link, a colour, friction, ros_control, a
    node in gazebo.launch and its install line in CMakeLists.txt."""
    robot = text(urdf(package))
    base_end = robot.index("  </link>\r\n") + len("  </link>\r\n")
    robot = robot[:robot.index("  <link")] + WORLD.split("  <joint")[0] + \
        robot[robot.index("  <link"):base_end] + "  <joint" + WORLD.split("  <joint")[1] + \
        robot[base_end:]
    robot = robot.replace(SILVER, RED, 1)   # the first wheel's colour
    at = robot.index('name="front_left_joint"')
    at = robot.index("    <safety_controller", at)
    robot = robot[:at] + DYNAMICS + robot[at:]
    robot = robot.replace("</robot>", ROS_CONTROL + "</robot>")
    write(urdf(package), robot)
    launch = package / "launch" / "gazebo.launch"
    write(launch, text(launch).replace("</launch>", NODE + "</launch>"))
    cmake = package / "CMakeLists.txt"
    write(cmake, text(cmake) + "\r\ncatkin_install_python(PROGRAMS scripts/driver.py\r\n"
          "\tDESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})\r\n")


def reexport(package: Path, mass: str | None = None) -> None:
    """Export again over the package; with `mass`, as if the base's mass changed meanwhile."""
    write_export(FOUR_WHEELER_NESTED, package.parent)
    if mass:
        write(urdf(package), text(urdf(package)).replace('value="0.563365165980808"',
                                                         f'value="{mass}"'))


@pytest.fixture
def edited(tmp_path) -> Path:
    package = write_export(FOUR_WHEELER_NESTED, tmp_path)
    hand_edit(package)
    return package


def test_restore_puts_every_hand_edit_back_and_keeps_the_new_numbers(edited, capsys):
    assert run("save", edited) == 0
    lessons = {rel: (edited / rel).read_bytes() for rel in
               ("CMakeLists.txt", "launch/gazebo.launch", f"urdf/{edited.name}.urdf")}
    reexport(edited, mass="0.6")
    assert NODE not in text(edited / "launch" / "gazebo.launch")
    capsys.readouterr()
    assert run("restore", edited) == 0
    said = capsys.readouterr().out
    for line in ("restored launch/gazebo.launch", "restored CMakeLists.txt", "carried link world",
                 "carried joint world_joint", "<dynamics> of joint front_left_joint",
                 f"colour of link front_right_link (rgba {RED})",
                 '<transmission name="front_left_transmission">',
                 "<gazebo> (plugin libgazebo_ros_control.so)"):
        assert line in said, said
    for rel in ("CMakeLists.txt", "launch/gazebo.launch"):
        assert (edited / rel).read_bytes() == lessons[rel]
    # The URDF is the hand-edited one with the re-export's new mass, and nothing else changed.
    assert text(urdf(edited)) == lessons[f"urdf/{edited.name}.urdf"].decode().replace(
        'value="0.563365165980808"', 'value="0.6"')
    assert "\n" not in text(urdf(edited)).replace(CRLF, "")   # the exporter's line ends
    assert find_package(edited).world_fixed
    capsys.readouterr()
    assert run("restore", edited) == 0    # a second restore finds nothing missing
    assert "carried" not in capsys.readouterr().out


def test_restore_without_a_saved_copy_says_to_save_first(edited, capsys):
    assert run("restore", edited) == 2
    assert f"sw2sim edits save {edited}" in capsys.readouterr().err


def test_saving_a_bare_re_export_over_the_saved_edits_is_refused(edited, capsys):
    assert run("save", edited) == 0
    reexport(edited)
    assert run("save", edited) == 1
    err = capsys.readouterr().err
    assert "link world" in err and f"sw2sim edits restore {edited}" in err
    assert WORLD.split("  <joint")[0] in text(edited / "hand_edits" / "urdf" / (urdf(edited).name + ".saved"))


def test_a_file_edited_after_the_re_export_is_not_overwritten(edited, capsys):
    assert run("save", edited) == 0
    reexport(edited)
    launch = edited / "launch" / "gazebo.launch"
    mine = text(launch).replace("</launch>", "  <!-- mine -->\r\n</launch>")
    write(launch, mine)
    later = urdf(edited).stat().st_mtime + 120
    os.utime(launch, (later, later))
    bare = text(urdf(edited))
    assert run("restore", edited) == 1
    assert "launch/gazebo.launch" in capsys.readouterr().err
    assert text(launch) == mine and text(urdf(edited)) == bare   # nothing written at all
    assert run("restore", edited, "--force") == 0
    assert NODE in text(launch)


def test_joints_gone_and_new_since_the_save_are_named(edited, capsys):
    assert run("save", edited) == 0
    reexport(edited)
    write(urdf(edited), text(urdf(edited)).replace('"back_left_joint"', '"rear_left_joint"'))
    capsys.readouterr()
    assert run("restore", edited) == 0
    said = capsys.readouterr().out
    assert "not carried: joint back_left_joint" in said   # its old name's <dynamics> and all
    warning = [line for line in said.splitlines() if line.startswith("WARNING: the joints")]
    assert len(warning) == 1 and "gone: back_left_joint" in warning[0] \
        and "new: rear_left_joint" in warning[0], warning
    assert "config/joint_names_" in warning[0] and "launch/gazebo.launch" in warning[0]


def test_what_the_new_export_writes_itself_is_kept_and_named():
    saved = ('<robot name="r">\n  <link name="a" />\n  <link name="gone">\n    <visual />\n'
             '  </link>\n  <joint name="j" type="revolute">\n    <parent link="a" />\n'
             '    <child link="b" />\n    <dynamics damping="1" />\n  </joint>\n</robot>\n')
    new = ('<robot name="r">\n  <link name="a" />\n  <link name="b" />\n'
           '  <joint name="j" type="revolute">\n    <parent link="a" />\n'
           '    <child link="b" />\n    <dynamics damping="2" />\n  </joint>\n</robot>\n')
    result = urdf_carry.carry(saved, new)
    assert result.text == new and not result.carried
    assert any("link gone" in n for n in result.not_carried)
    assert any('<dynamics> of joint j (the new export writes its own: damping="2"' in n
               for n in result.not_carried), result.not_carried


def test_a_carried_joint_child_goes_where_the_exporter_orders_it():
    saved = ('<robot name="r">\n  <joint name="j" type="revolute">\n    <parent link="a" />\n'
             '    <child link="b" />\n    <limit lower="0" />\n    <dynamics damping="1" />\n'
             '    <safety_controller k_velocity="0" />\n  </joint>\n</robot>\n')
    new = saved.replace('    <dynamics damping="1" />\n', "")
    assert urdf_carry.carry(saved, new).text == saved
