"""The example packages' launch files under a real ROS 1 master.

Gazebo and ros_control are not in Debian, so their parts are left out here; what remains
of each gazebo.launch (its parameters and the nodes Debian has, robot_state_publisher
first) is launched with roslaunch, unchanged otherwise. robot_state_publisher exits at
once when the launch file sets no robot_description, as it did in Practices 3-5.
"""

from __future__ import annotations

import time
from pathlib import Path

import pytest
import yaml
from lxml import etree

from packages import EXAMPLES
from repository import practice_numbers

# The packages of the launch files' nodes that Debian's ROS 1 provides.
DEBIAN = {"robot_state_publisher", "rostopic"}
ALIVE_FOR = 2.0   # s a node must keep running to count as started


def debian_part(launch: Path, out: Path) -> tuple[Path, list[str]]:
    """The launch file without what needs Gazebo or ros_control; and the nodes kept."""
    root = etree.parse(str(launch)).getroot()
    kept = []
    for element in list(root):
        if element.tag == "include" or (element.tag == "node" and element.get("pkg") not in DEBIAN):
            root.remove(element)
        elif element.tag == "node":
            kept.append(element.get("name"))
    out.write_bytes(etree.tostring(root))
    return out, kept


def with_robot_state_publisher() -> list[int]:
    found = [n for n in practice_numbers()
             if b'pkg="robot_state_publisher"' in
             (EXAMPLES / f"example_{n}" / "launch" / "gazebo.launch").read_bytes()]
    assert found, "no gazebo.launch starts robot_state_publisher"
    return found


@pytest.mark.parametrize("n", with_robot_state_publisher())
def test_gazebo_launch_gives_robot_state_publisher_its_description(ros, tmp_path, n):
    launch, kept = debian_part(EXAMPLES / f"example_{n}" / "launch" / "gazebo.launch",
                               tmp_path / "gazebo_debian.launch")
    assert "robot_state_publisher" in kept
    ros.env["ROS_PACKAGE_PATH"] = f"{EXAMPLES}:/usr/share"
    ros.start("roslaunch", "--wait", str(launch), name="roslaunch")
    deadline = time.monotonic() + 15
    while time.monotonic() < deadline:
        nodes = ros.run("rosnode", "list").stdout.split()
        if "/robot_state_publisher" in nodes:
            break
        time.sleep(0.2)
    time.sleep(ALIVE_FOR)
    nodes = ros.run("rosnode", "list").stdout.split()
    log = (ros.logs / "roslaunch.log").read_text(errors="replace")
    assert "/robot_state_publisher" in nodes, log
    assert "process has died" not in log, log
    description = yaml.safe_load(ros.run("rosparam", "get", "/robot_description").stdout)
    assert f'name="example_{n}"' in description
