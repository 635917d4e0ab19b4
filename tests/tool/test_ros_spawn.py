"""The stand-in's spawn, without ROS: a URDF the simulation cannot load is reported the way
`spawn_model` prints it on the launch's screen."""

import pytest

from packages import EXAMPLES
from sw2sim.ros.gazebo_services import why_not_spawned
from sw2sim.ros.world import World


def test_a_model_that_cannot_load_is_reported_on_one_line_with_the_check(monkeypatch):
    monkeypatch.setenv("ROS_PACKAGE_PATH", str(EXAMPLES))   # as roslaunch finds the package
    urdf = (EXAMPLES / "Arm_Assembly" / "urdf" / "Arm_Assembly.urdf").read_text()
    with pytest.raises(Exception) as error:
        World(rospy=None).spawn(urdf, "")
    assert "\n" in str(error.value), "MuJoCo's message takes two lines"
    said = why_not_spawned(error.value)
    assert "end_arm_link.STL" in said and "\n" not in said
    assert said.endswith("(`sw2sim check` on the package lists every problem, each with its fix)")

