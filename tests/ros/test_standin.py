"""`sw2sim ros`: an exported package's own gazebo.launch, unchanged, under a real ROS 1
master with MuJoCo in Gazebo's place, observed from a separate rospy node."""

from __future__ import annotations

import json
import shutil
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from packages import EXAMPLES

RECORD = Path(__file__).with_name("record.py")
NS = "/example_3"
TOLERANCE = 0.01   # rad: Practice 3's claim
SETTLE = 4.0       # s of simulated time
REALTIME = "10"    # as the page runner runs it (course/snippets/ros.py)


def test_the_arm_reaches_each_random_setpoint(ros):
    """`sw2sim ros examples/example_3`: the package's gazebo.launch with its random setpoint
    node; a separate rospy node sees each joint within 0.01 rad of each setpoint within 4 s."""
    ros.start(sys.executable, "-m", "sw2sim", "ros", str(EXAMPLES / "example_3"),
              "--realtime", REALTIME, name="sw2sim_ros")
    commands = {"middle_arm_joint": f"{NS}/middle_arm_controller/command",
                "end_arm_joint": f"{NS}/end_arm_controller/command"}
    # 21 s from when the recorder starts, wherever the simulation is by then: four
    # setpoints every 5 s, each held long enough to be judged.
    done = ros.python(RECORD, "+21", f"{NS}/joint_states", *commands.values(), timeout=120)
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-2000:]
    record = json.loads(done.stdout.splitlines()[-1])
    times = np.array([t for t, _ in record["states"]])
    assert len(times) > 100, "joint states arrive at the controller's publish_rate"
    reached = 0
    for joint, topic in commands.items():
        positions = np.array([s[joint] for _, s in record["states"]])
        setpoints = record["commands"][topic]
        assert setpoints, f"no setpoints on {topic}"
        for (t, target), following in zip(setpoints, [*setpoints[1:], [np.inf, None]]):
            window = (times >= t) & (times <= min(t + SETTLE, following[0]))
            if t + SETTLE > times[-1] or following[0] - t < SETTLE:
                continue   # the recording (or the next setpoint) ends before it could settle
            assert np.any(np.abs(positions[window] - target) < TOLERANCE), (joint, t, target)
            reached += 1
    assert reached >= 4, f"only {reached} setpoints could be judged"



@pytest.mark.skipif(shutil.which("Xvfb") is None, reason="Xvfb is not installed (`make setup` "
                    "installs it with ROS 1)")
def test_view_shows_the_simulation_in_mujocos_viewer(ros):
    """`sw2sim ros PACKAGE --view` opens MuJoCo's viewer on a display, showing the robot
    the launch file spawned (on a virtual screen here, black until a window opens)."""
    from course import rviz_picture
    with rviz_picture.xvfb((800, 600)) as screen:
        ros.env["DISPLAY"] = screen.display
        ros.start(sys.executable, "-m", "sw2sim", "ros", str(EXAMPLES / "example_3"), "--view",
                  "--realtime", REALTIME, name="sw2sim_ros")
        deadline, lit = time.monotonic() + 30, 0.0
        while time.monotonic() < deadline and lit < 0.1:
            time.sleep(0.5)
            lit = float(np.mean(rviz_picture.grab(screen.display).max(axis=2) > 40))
        log = (ros.logs / "sw2sim_ros.log").read_text(errors="replace")
        assert lit >= 0.1, f"no viewer on the screen ({lit:.0%} lit):\n{log[-2000:]}"
        assert "could not open a window" not in log
        ros.stop_all()
