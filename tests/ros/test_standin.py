"""`sw2sim ros`: an exported package's own gazebo.launch, unchanged, under a real ROS 1
master with MuJoCo in Gazebo's place, observed from a separate rospy node."""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np

from packages import EXAMPLES

RECORD = Path(__file__).with_name("record.py")
NS = "/example_3"
TOLERANCE = 0.01   # rad: Practice 3's claim
SETTLE = 4.0       # s of simulated time


def test_the_arm_reaches_each_random_setpoint(ros):
    ros.start(sys.executable, "-m", "sw2sim", "ros", str(EXAMPLES / "example_3"),
              "--realtime", "0", name="sw2sim_ros")
    commands = {"middle_arm_joint": f"{NS}/middle_arm_controller/command",
                "end_arm_joint": f"{NS}/end_arm_controller/command"}
    done = ros.python(RECORD, "21", f"{NS}/joint_states", *commands.values(), timeout=120)
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


def test_practice_1s_node_pulses_the_wheels_as_the_mujoco_script_does(ros):
    """Practice 1's launch file with its periodic_force node: every pulse through
    /gazebo/apply_joint_effort adds the 62.6 rad/s the page derives, seen on /joint_states."""
    from course.practices import PRACTICES, design
    page_step = 62.6   # rad/s, _pages/practice-1/05-custom-node.md
    ros.start(sys.executable, "-m", "sw2sim", "ros", str(EXAMPLES / "example_1"),
              "--realtime", "0", name="sw2sim_ros")
    done = ros.python(RECORD, "26", "/joint_states", timeout=120)
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-2000:]
    record = json.loads(done.stdout.splitlines()[-1])
    joints = design(PRACTICES[0]).robot().movable_joints()
    assert joints
    for joint in joints:
        speed = np.array([s[joint.name] for _, s in record["speeds"]])
        assert len(speed) > 100, "the wheels' states arrive on /joint_states"
        steps = np.diff(speed)
        # Between pulses the speed holds; each pulse adds the same step.
        plateaus = [float(speed[0])]
        for value, change in zip(speed[1:], steps):
            if abs(change) < 1e-6 and abs(value - plateaus[-1]) > 1.0:
                plateaus.append(float(value))
        gains = np.diff(plateaus)
        assert len(gains) >= 1, (joint.name, plateaus)
        assert np.allclose(gains, page_step, atol=0.1), (joint.name, plateaus)
