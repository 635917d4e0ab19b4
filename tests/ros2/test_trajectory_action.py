"""joint_trajectory_controller's FollowJointTrajectory action and its refusals, in one run
of `sw2sim ros2` on Practice 3's ported package, seen by an independent rclpy process
(trajectory_client.py): what it gets is what ros2_controllers 4.42.1's
joint_trajectory_controller.cpp answers, and the stand-in's log says why. And Practice 3's
node, on a busy machine beside controllers found late (late_controllers.py), loses no
set point."""

from __future__ import annotations

import json
import re
import subprocess
import sys
import time

import numpy as np
import pytest

from conftest import HERE, Ros2, group_alive
from ros2_environment import PYTHON, missing

# action_msgs/GoalStatus
SUCCEEDED, CANCELED, ABORTED = 4, 5, 6
LIMIT = 0.7854   # rad, middle_arm_joint's URDF limit


@pytest.fixture(scope="module")
def run(tmp_path_factory, ported_example_3):
    """One stand-in, one client with every scenario: (the client's JSON, the stand-in's log)."""
    if reason := missing():
        pytest.skip(reason)
    world = Ros2(tmp_path_factory.mktemp("action") / "ros_home")
    try:
        world.standin(ported_example_3, "--duration", "120")
        client = subprocess.run([str(PYTHON), str(HERE / "trajectory_client.py")],
                                env=world.env, capture_output=True, text=True, timeout=150,
                                start_new_session=True)
        time.sleep(0.2)   # the stand-in's last log lines
        log = world.log("standin")
        assert client.returncode == 0, f"{client.stderr[-3000:]}\n{log[-3000:]}"
        yield json.loads(client.stdout.splitlines()[-1]), log
    finally:
        world.stop_all()
        assert not [p.pid for p in world.processes if group_alive(p.pid)]


def test_a_goal_is_reached_with_feedback_on_the_way(run):
    out, log = run
    r = out["success"]
    assert r["accepted"] and r["status"] == SUCCEEDED, r
    assert r["error_code"] == 0 and r["error_string"] == "Goal successfully reached!"
    assert abs(r["settled"] - 0.4) < 0.01, r["settled"]
    # feedback at the action monitor's 20 Hz of simulated time (a loaded client keeps the
    # last 10 of a burst: gaps of 50 ms or a few times that)
    assert r["feedback"] >= 3 and r["feedback_joints"] == ["middle_arm_joint"], r
    gaps = np.diff(r["stamps"]) / 0.05
    assert np.allclose(gaps, np.round(gaps), atol=1e-3) and gaps.min() == pytest.approx(1), gaps
    desired = [d[0] for d in r["desired"]]
    assert desired == sorted(desired) and 0 < desired[len(desired) // 2] < 0.4, desired
    assert "middle_arm_controller: Goal reached, success!" in log


def test_a_goal_naming_another_joint_or_holding_nan_is_rejected(run):
    out, log = run
    # joint_trajectory_controller rejects the goal (no result, no INVALID_JOINTS code)
    assert out["unknown_joint"] == {"accepted": False}
    assert "Incoming joint elbow_joint doesn't match the controller's joints." in log
    assert out["nan_goal"] == {"accepted": False}
    assert re.search(r"middle_arm_controller: points\[0\]\.positions of joint "
                     r"middle_arm_joint is nan: refused", log), log


def test_a_new_goal_preempts_the_running_one(run):
    out, _ = run
    old, new = out["preempted"], out["preempting"]
    assert old["accepted"] and old["status"] == ABORTED
    assert old["error_code"] == -1   # INVALID_GOAL
    assert old["error_string"] == "Current goal preempted by new incoming action."
    assert new["status"] == SUCCEEDED and abs(new["settled"] - 0.2) < 0.02, new


def test_a_canceled_goal_ends_canceled_and_the_joint_holds(run):
    out, log = run
    r = out["canceled"]
    assert r["canceling"] == 1 and r["status"] == CANCELED
    assert r["error_code"] == 0 and r["error_string"] == ""
    # on its way from 0.2 to -0.5 over 20 s: stopped about 1 s in, and held there
    assert -0.2 < r["position"] < 0.2 and abs(r["later"] - r["position"]) < 0.01, r
    assert "Canceling active action goal because cancel callback received." in log


def test_path_and_goal_tolerances_abort_the_goal(run):
    out, log = run
    path, goal = out["path"], out["goal"]
    assert path["accepted"] and path["status"] == ABORTED and path["error_code"] == -4
    assert path["error_string"] == "Aborted due to path tolerance violation"
    assert "Aborted due to state tolerance violation" in log
    assert goal["accepted"] and goal["status"] == ABORTED and goal["error_code"] == -5
    assert goal["error_string"].startswith("Aborted due to goal_time_tolerance exceeding by ")
    # the 5 rad goal is taken (the controller does not check limits), said once in the log
    said = re.findall(r"middle_arm_joint to 5 at points\[0\], outside its URDF limits "
                      r"\[-0\.7854, 0\.7854\]", log)
    assert len(said) == 1, log
    assert goal["position"] < LIMIT + 0.1


def test_bad_messages_on_the_topic_are_refused_with_the_field_named(run):
    out, log = run
    bad = out["bad_messages"]
    assert abs(bad["after"] - bad["before"]) < 0.01, bad
    for line in (r"end_arm_controller: points\[0\]\.positions of joint end_arm_joint is nan",
                 r"end_arm_controller: Empty trajectory received\.",
                 r"end_arm_controller: Time between points 0 and 1 is not strictly increasing",
                 r"end_arm_controller: Incoming joint elbow_joint doesn't match",
                 r"end_arm_controller: Received trajectory with non-zero start time \([\d.]+\) "
                 r"that ends in the past"):
        assert re.search(line, log), line
    assert abs(out["good_message"]["after"] + 0.3) < 0.01, out["good_message"]


def test_the_pages_node_sends_its_set_points_only_to_controllers_it_has_found(ros2, tmp_path):
    """Practice 3's node (random_setpoints.py, as the page shows it) beside a clock already
    past 5 s and controllers found only 1.5 s later, on a machine kept busy: every set
    point it says it sent reaches its controller (it once published before discovery had
    found them, and that set point was lost)."""
    from course.snippets.ros2 import node_blocks
    from repository import ROOT
    node = tmp_path / "random_setpoints.py"
    node.write_text(node_blocks(ROOT)["example_3/scripts/random_setpoints.py"].code)
    busy = [subprocess.Popen([sys.executable, "-c", "while True: pass"]) for _ in range(2)]
    try:
        started = ros2.start(str(PYTHON), str(node), "--ros-args", "-p", "use_sim_time:=true",
                             name="random_setpoints")
        done = subprocess.run([str(PYTHON), str(HERE / "late_controllers.py"), "1.5", "3"],
                              env=ros2.env, capture_output=True, text=True, timeout=60,
                              start_new_session=True)
    finally:
        for process in busy:
            process.kill()
            process.wait()
    assert done.returncode == 0, done.stderr
    received = json.loads(done.stdout)
    ros2.stop_all()
    assert started.poll() is not None
    said = re.findall(r"(\w+_joint): new set point (-?[\d.]+) rad", ros2.log("random_setpoints"))
    for controller, joint in (("middle_arm_controller", "middle_arm_joint"),
                              ("end_arm_controller", "end_arm_joint")):
        sent = [float(x) for j, x in said if j == joint]
        got = [round(x, 4) for _, x in received[f"/{controller}/joint_trajectory"]]
        assert got and got == sent, (joint, sent, got)
