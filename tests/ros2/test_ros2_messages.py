"""tf2_msgs and control_msgs as built here have upstream Jazzy's type hashes (the values
below are those of upstream's own .msg files, geometry2 jazzy and control_msgs 5.8.0,
built with the same generators): real ROS 2 nodes exchange them with the stand-in."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from ros2_environment import missing, run

UPSTREAM = {
    "tf2_msgs/msg/TFMessage":
        "RIHS01_e369d0f05a23ae52508854b66f6aa0437f3449d652e8cbf22d5abe85d020f087",
    "control_msgs/msg/JointTrajectoryControllerState":
        "RIHS01_51d8dd89cc624cbe9daaeeb4d80d6de9b86168ffdc3be41fefc0953e3c26e480",
    "control_msgs/msg/MultiDOFCommand":
        "RIHS01_033fb0fa1ffc63a872ca73c61a49ded83a22daa5cc3f074cc28949f73359e677",
    "control_msgs/msg/MultiDOFStateStamped":
        "RIHS01_08e47e3e734a7d08131b57e14e9f740782f3bf9a1aadabd2a16b54d27e551f0a",
    "control_msgs/msg/SingleDOFState":
        "RIHS01_fe8365f86265bddfefbd26698975a818bf024a1c267c8ce577cd366ef06d7163",
    "control_msgs/msg/SingleDOFStateStamped":
        "RIHS01_33859c01b46943f1458f83f2627249d34332b38e545c723ddbdabea2b6675af1",
}


def test_the_built_messages_have_upstreams_type_hashes():
    if missing():
        pytest.skip(missing())
    done = run("from sw2sim.ros2 import messages; print(messages.ensure())")
    assert done.returncode == 0, done.stderr
    where = Path(done.stdout.strip().splitlines()[-1])
    for name, expected in UPSTREAM.items():
        described = json.loads((where / "share" / f"{name}.json").read_text())
        assert described["type_hashes"][0]["hash_string"] == expected, name


def test_the_generation_entry_point_is_a_quick_no_op_when_done():
    """`make setup` runs it on every set-up: once built, it builds nothing again."""
    if missing():
        pytest.skip(missing())
    done = run("import os; from sw2sim.ros2 import messages; messages.ensure(); "
               "marker = messages._marker(messages.prefix()); before = os.stat(marker).st_mtime_ns; "
               "messages.ensure(); print(messages.ready(), os.stat(marker).st_mtime_ns == before)")
    assert done.returncode == 0, done.stderr
    assert done.stdout.split() == ["True", "True"], done.stdout
