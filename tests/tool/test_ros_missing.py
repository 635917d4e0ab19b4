"""`sw2sim ros` where ROS 1 is not installed: one message that says what to install, and
status 2, before anything is started."""

from __future__ import annotations

import importlib.util
import shutil

from sw2sim.ros import run as ros_run


def test_without_ros_it_says_what_to_install(monkeypatch, tmp_path):
    monkeypatch.setattr(shutil, "which", lambda name, *a, **k: None)
    said = []
    status = ros_run.run(str(tmp_path), say=said.append)
    assert status == 2 and len(said) == 1
    message = said[0]
    assert message.startswith("sw2sim ros: ROS 1 is not installed")
    for package in ("python3-rospy", "python3-roslaunch", "ros-robot-state-publisher"):
        assert package in message
    assert "sudo apt install" in message and "WSL2" in message


def test_rospy_missing_counts_as_missing(monkeypatch):
    real = importlib.util.find_spec
    monkeypatch.setattr(importlib.util, "find_spec",
                        lambda name, *a: None if name == "rospy" else real(name, *a))
    monkeypatch.setattr(shutil, "which", lambda name, *a, **k: f"/usr/bin/{name}")
    assert ros_run.missing() is not None
