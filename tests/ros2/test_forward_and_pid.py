"""A velocity forward command controller and a pid_controller, from an independent node;
and `sw2sim plot` under ROS 2, beside that node, plotting what it hears."""

from __future__ import annotations

import csv
import os
import shutil
import signal
import subprocess
import time

import numpy as np
import pytest
from PIL import Image

from ros2_environment import PYTHON

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
    ros2.standin(package)
    # `sw2sim plot` until Ctrl-C, from before the recorder listens until after it is done
    plot = ros2.start(str(PYTHON), "-m", "sw2sim", "plot", "/joint_states/position[0]:velocity[0]",
                      "-o", str(tmp_path / "plot.png"), "--csv", str(tmp_path / "plot.csv"),
                      name="plot")
    deadline = time.monotonic() + 60
    while "sw2sim plot: plotting" not in ros2.log("plot"):
        assert plot.poll() is None and time.monotonic() < deadline, ros2.log("plot")
        time.sleep(0.05)
    out = ros2.record("2.5", "--commands", "end_velocity", "0.2",
                      "--reference", "middle_pid", "middle_arm_joint", "0.4",
                      "--state", "middle_pid", "pid")
    _plotted_as_heard(ros2, plot, out, tmp_path)
    # The broadcaster's 50 a second, on the 20 ms grid of simulated time its controller
    # manager keeps (each message at the first 2 ms step that reaches its tick): a message
    # the recorder missed leaves a gap of 40 ms, never one of 22.
    stamps = np.array([s[0] for s in out["states"]])
    assert np.median(np.diff(stamps)) == pytest.approx(0.02, abs=1e-6)
    assert np.all(np.abs(stamps * 50 - np.round(stamps * 50)) / 50 <= 0.002 + 1e-9), stamps[:8]
    t, q, v = out["states"][-1]
    assert abs(v["end_arm_joint"] - 0.2) < 0.01
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


def _plotted_as_heard(ros2, plot: subprocess.Popen, heard: dict, folder) -> None:
    """`sw2sim plot` drew a PNG from the live /joint_states, on simulated time, and each
    sample it plotted is what the recorder heard in the message of the same stamp."""
    os.killpg(plot.pid, signal.SIGINT)   # Ctrl-C in its terminal
    plot.wait(timeout=60)
    said = ros2.log("plot")
    assert plot.returncode == 0 and f"wrote {folder / 'plot.png'}" in said, said
    assert "1 series" not in said and "2 series from /joint_states (ROS 2)" in said, said
    rows = list(csv.DictReader((folder / "plot.csv").open()))
    heard_at = {round(t, 6): (q, v) for t, q, v in heard["states"]}
    first = next(iter(heard["states"][0][1]))   # the joint states' first name: [0]
    checked = 0
    for row in rows:
        t = round(float(row["ros_time"]), 6)
        if t in heard_at:
            q, v = heard_at[t]
            field = q if row["series"].endswith("position[0]") else v
            assert float(row["value"]) == field[first], row
            checked += 1
    # the recorder's messages are on the plot (a loaded machine may drop one or two of a
    # burst from either subscriber's queue)
    assert checked >= 0.9 * 2 * len(heard["states"]) >= 40, (checked, len(heard["states"]))
    times = [float(r["time"]) for r in rows]
    assert min(times) == 0 and max(times) > 2.5, max(times)   # simulated seconds
    # a picture in matplotlib's C0 and C1, the two series (the position's line is mostly
    # under the speed's, both at 0 while the simulation ran before the commands: where
    # the lines are drawn is tests/tool/test_plot.py's to check)
    picture = np.asarray(Image.open(folder / "plot.png").convert("RGB")).astype(int)
    assert picture.shape == (450, 800, 3)
    for colour in ((31, 119, 180), (255, 127, 14)):
        assert np.all(np.abs(picture - colour) < 40, axis=2).sum() > 20, colour


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
