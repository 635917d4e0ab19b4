"""The message classes Debian lacks are generated once: the nodes `sw2sim ros` starts find
the caller's copy through their environment, whatever their HOME (the page runner gives
every page a HOME of its own), instead of generating them again at every start."""

from __future__ import annotations

import os
import subprocess
import sys

import pytest

from sw2sim.ros import messages
from sw2sim.ros.run import environment

from packages import EXAMPLES


def test_nodes_with_another_home_reuse_the_generated_classes(tmp_path):
    if not (messages.GENPY / "genmsg_py.py").is_file():
        pytest.skip("genpy is not installed (`make setup` installs ROS 1 from Debian)")
    env = environment(EXAMPLES / "example_3", realtime=1.0)
    generated = env[messages.FOLDER_VARIABLE]
    home = tmp_path / "home"
    home.mkdir()
    env = {**env, "HOME": str(home)}
    env.pop("XDG_CACHE_HOME", None)
    probe = ("from sw2sim.ros import messages; print(messages.ensure()); "
             "from gazebo_msgs.srv import SpawnModel; print(SpawnModel._type)")
    done = subprocess.run([sys.executable, "-c", probe], env=env, capture_output=True,
                          text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    folder, kind = done.stdout.split()
    assert folder == generated and kind == "gazebo_msgs/SpawnModel"
    assert not (home / ".cache").exists(), "the node generated the classes again"


def test_a_folder_of_other_definitions_is_not_used(tmp_path, monkeypatch):
    stale = tmp_path / "ros-messages-000000000000"
    stale.mkdir()
    (stale / ".done").write_text("old\n")
    monkeypatch.setenv(messages.FOLDER_VARIABLE, str(stale))
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))
    assert messages.folder() == tmp_path / "cache" / "sw2sim" / messages.folder().name
    assert messages.folder() != stale
