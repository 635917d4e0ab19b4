"""`sw2sim plot` under ROS 2: from a live `sw2sim ros2` run of Practice 3's arm it draws a
PNG until Ctrl-C, and the samples it plotted (its --csv) are what an independent rclpy
node (recorder.py) heard in the messages of the same stamps.

The stand-in runs at real time here, not flat out as elsewhere: flat out it sends
thousands of joint states a wall second, and two loaded subscribers then each lose a
different share of them (the publisher keeps 10), leaving too few in common to compare."""

from __future__ import annotations

import csv
import os
import signal
import time

import numpy as np
from PIL import Image

from ros2_environment import PYTHON


def test_plot_draws_the_live_joint_states_on_simulated_time(ros2, ported_example_3, tmp_path):
    ros2.standin(ported_example_3, "--realtime", "1")
    png, table = tmp_path / "plot.png", tmp_path / "plot.csv"
    plot = ros2.start(str(PYTHON), "-m", "sw2sim", "plot", "/joint_states/position[0]:velocity[0]",
                      "-o", str(png), "--csv", str(table), name="plot")
    # until Ctrl-C: from before the recorder listens until after it is done
    deadline = time.monotonic() + 60
    while "sw2sim plot: plotting" not in ros2.log("plot"):
        assert plot.poll() is None and time.monotonic() < deadline, ros2.log("plot")
        time.sleep(0.05)
    heard = ros2.record("1.5", "--trajectory", "middle_arm_controller", "middle_arm_joint",
                        "0.5", "1")
    os.killpg(plot.pid, signal.SIGINT)   # Ctrl-C in its terminal
    plot.wait(timeout=30)
    said = ros2.log("plot")
    assert plot.returncode == 0 and f"wrote {png}" in said, said
    assert "2 series from /joint_states (ROS 2)" in said and "Traceback" not in said, said

    rows = list(csv.DictReader(table.open()))
    at = {round(t, 6): (q, v) for t, q, v in heard["states"]}
    first = next(iter(heard["states"][0][1]))   # the joint states' first name: [0]
    checked, moved = 0, set()
    for row in rows:
        t = round(float(row["ros_time"]), 6)
        if t in at:
            q, v = at[t]
            value = (q if row["series"].endswith("position[0]") else v)[first]
            assert float(row["value"]) == value, row
            checked += 1
            moved.add(value)
    # the recorder's messages are on the plot (a loaded machine may drop one of a burst),
    # and they changed as the arm moved
    assert checked >= 0.9 * 2 * len(heard["states"]) >= 40, (checked, len(heard["states"]))
    assert len(moved) > 10
    times = [float(r["time"]) for r in rows]
    # simulated seconds from the first sample; the plot listened from before the recorder
    # until after it was done, so it spans at least the recorder's states
    span = heard["states"][-1][0] - heard["states"][0][0]
    assert min(times) == 0 and max(times) >= span - 0.05, (max(times), span)
    picture = np.asarray(Image.open(png).convert("RGB")).astype(int)
    assert picture.shape == (450, 800, 3)
    for colour in ((31, 119, 180), (255, 127, 14)):   # matplotlib's C0 and C1: both series
        assert np.all(np.abs(picture - colour) < 40, axis=2).sum() > 100, colour
