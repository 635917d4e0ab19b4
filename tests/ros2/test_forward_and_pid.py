"""A velocity forward command controller and a pid_controller, from an independent node."""

from __future__ import annotations

import shutil

import numpy as np
import pytest

YAML = """\
controller_manager:
  ros__parameters:
    update_rate: 1000
    joint_state_broadcaster: {type: joint_state_broadcaster/JointStateBroadcaster}
    middle_pid: {type: pid_controller/PidController}
    end_velocity: {type: velocity_controllers/JointGroupVelocityController}
joint_state_broadcaster:
  ros__parameters: {update_rate: 50}
middle_pid:
  ros__parameters:
    dof_names: [middle_arm_joint]
    command_interface: effort
    reference_and_state_interfaces: [position, velocity]
    gains:
      middle_arm_joint: {p: 100.0, i: 10.0, d: 10.0, i_clamp_max: 0.5, i_clamp_min: -0.5}
end_velocity:
  ros__parameters: {joints: [end_arm_joint]}
"""


def test_velocity_commands_and_a_pid_reference(ros2, ported_example_3, tmp_path):
    package = tmp_path / "example_3"
    shutil.copytree(ported_example_3, package)
    (package / "config" / "controllers.yaml").write_text(YAML)
    urdf = package / "urdf" / "example_3.urdf"
    text = urdf.read_text()
    end = text.index('<joint name="end_arm_joint">', text.index("<ros2_control"))
    text = text[:end] + text[end:].replace('<command_interface name="effort">',
                                           '<command_interface name="velocity">', 1)
    urdf.write_text(text)
    # at real time: the two commands take effect within a few milliseconds of each other,
    # where as fast as it goes the simulation runs on for seconds between two deliveries
    # (the end arm reached its limit before the middle arm's set point arrived)
    ros2.standin(package, "--realtime", "1")
    out = ros2.record("2.5", "--commands", "end_velocity", "0.2", "--moves", "end_arm_joint", "0.2",
                      "--reference", "middle_pid", "middle_arm_joint", "0.4",
                      "--state", "middle_pid", "pid")
    # The broadcaster's 50 a second, on the 20 ms grid of simulated time its controller
    # manager keeps (each message at the first 2 ms step that reaches its tick): a message
    # the recorder missed leaves a gap of 40 ms, never one of 22.
    stamps = np.array([s[0] for s in out["states"]])
    assert np.median(np.diff(stamps)) == pytest.approx(0.02, abs=1e-6)
    assert np.all(np.abs(stamps * 50 - np.round(stamps * 50)) / 50 <= 0.002 + 1e-9), stamps[:8]
    t, q, v = out["states"][-1]
    assert abs(v["end_arm_joint"] - 0.2) < 0.01, (out.get("sent_at"), ros2.log("standin")[-3000:])
    earlier = [s for s in out["states"] if s[0] <= t - 0.5][-1]   # moving at 0.2 rad/s
    assert abs((q["end_arm_joint"] - earlier[1]["end_arm_joint"]) / (t - earlier[0]) - 0.2) < 0.01
    assert abs(q["middle_arm_joint"] - 0.4) < 0.01
    state = out["controller_state"]["middle_pid"][0]
    assert state["name"] == "middle_arm_joint" and state["reference"] == 0.4
    assert abs(state["error"]) < 0.01
    # /tf as robot_state_publisher sends it: the transforms of a joint state at least
    # 50 ms (its publish_frequency of 20 Hz) past the last ones sent, so with joint states
    # every 20 ms, every third: 60 ms apart (a missed one makes a gap of 120 ms; a loaded
    # recorder may hear only the first few)
    tf = sorted({m[0][2] for m in out["tf"] if m})
    gaps = np.diff(tf)
    assert len(tf) >= 5 and np.all(gaps > 0.05 - 1e-6), gaps[:10]
    assert np.median(gaps) == pytest.approx(0.06, abs=1e-6), gaps[:10]


def test_a_rate_that_is_no_multiple_of_the_step_keeps_its_grid(ros2, ported_example_3, tmp_path):
    """30 messages a second on 2 ms steps: each falls on the first step that reaches k/30 s,
    so that gaps of 32 and 34 ms make 30 a second (counting 33.3 ms on from each message's
    own step would give gaps of 34 ms, 29.4 a second, drifting off the grid)."""
    package = tmp_path / "example_3"
    shutil.copytree(ported_example_3, package)
    yaml = YAML.replace("joint_state_broadcaster:\n  ros__parameters: {update_rate: 50}",
                        "joint_state_broadcaster:\n  ros__parameters: {update_rate: 30}")
    assert yaml != YAML
    (package / "config" / "controllers.yaml").write_text(yaml)
    ros2.standin(package)
    stamps = np.array([s[0] for s in ros2.record("2.0")["states"]])
    assert len(stamps) >= 5   # (a busy machine's recorder may miss some: gaps of 66 ms, ...)
    step = 0.002   # the simulation's: every stamp is a multiple of it
    assert np.allclose(stamps / step, np.round(stamps / step), atol=1e-6), stamps[:8]
    assert np.all(np.abs(stamps * 30 - np.round(stamps * 30)) / 30 <= step + 1e-9), stamps[:8]
    # every third gap is 32 ms; the other way round, all would be 34 ms
    assert np.any(np.abs(np.diff(stamps) - 0.032) < 1e-6), np.diff(stamps)[:8]
