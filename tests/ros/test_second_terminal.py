"""A reader's second terminal, opened while a launch runs: with nothing but the master's
address, Debian's `rostopic` and `rosservice` cannot load the types of the stand-in's
controllers and services (Debian packages neither control_msgs nor gazebo_msgs); after
Getting started's two lines (`sw2sim ros-env`), both work."""

from __future__ import annotations

import subprocess
import time

import pytest

from course.snippets.terminal import LOGIN_PATH
from repository import ROOT
from sw2sim.ros.terminal import variables

STATE = "/example_3/middle_arm_controller/state"
SETUP = f"source '{ROOT}/.venv/bin/activate' && eval \"$(sw2sim ros-env)\" && "


@pytest.fixture
def launched(ros, tmp_path):
    """example_3's gazebo.launch, up and publishing its controllers' state."""
    ros.env.update(variables([ROOT / "examples"], ros.env), SW2SIM_REALTIME="5")
    ros.start("roslaunch", "--wait", "example_3", "gazebo.launch", name="launch")
    import rosgraph
    master = rosgraph.Master("/test", master_uri=ros.uri)
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline:
        if any(topic == STATE for topic, _ in master.getPublishedTopics("")):
            return ros
        time.sleep(0.2)
    pytest.fail("the launch published no controller state in 60 s:\n"
                + (ros.logs / "launch.log").read_text(errors="replace")[-2000:])


def _terminal(ros, home, line: str) -> subprocess.CompletedProcess:
    """`line` in a new terminal: a login's PATH and HOME, and the master's address."""
    home.mkdir(exist_ok=True)
    env = {"PATH": LOGIN_PATH, "HOME": str(home), "LANG": "C.UTF-8",
           "ROS_MASTER_URI": ros.uri, "ROS_IP": "127.0.0.1"}
    return subprocess.run(["bash", "-c", line], env=env, capture_output=True, text=True,
                          timeout=60, start_new_session=True)


def test_a_bare_terminal_lacks_the_types_and_getting_starteds_lines_give_them(launched, tmp_path):
    echo = f"rostopic echo -n 1 {STATE}"
    call = "rosservice call /gazebo/get_joint_properties 'joint_name: middle_arm_joint'"
    bare = _terminal(launched, tmp_path / "bare", echo)
    assert "Cannot load message class for [control_msgs/JointControllerState]" in bare.stderr
    bare = _terminal(launched, tmp_path / "bare", call)
    assert bare.returncode != 0 and "gazebo_msgs/GetJointProperties" in bare.stderr

    echoed = _terminal(launched, tmp_path / "set", SETUP + echo)
    assert echoed.returncode == 0, echoed.stderr
    assert "set_point:" in echoed.stdout and "process_value:" in echoed.stdout
    called = _terminal(launched, tmp_path / "set", SETUP + call)
    assert called.returncode == 0, called.stderr
    assert "success: True" in called.stdout
