"""The master's port: when ROS_MASTER_URI names a port of this machine that something else
holds (a killed run's leftover, another program), `sw2sim ros` says so, names the holder,
gives the command that frees the port, and prints the address of the port it uses instead
in the line for the second terminal. Before, it moved to 11311 without a word, and its
line for other terminals left ROS_MASTER_URI out: they looked at the taken port."""

from __future__ import annotations

import os
import re
import signal
import socket
import subprocess
import sys
import threading

import pytest

from packages import EXAMPLES
from sw2sim.ros import run as ros_run
from sw2sim.ros.run import descendants, missing, stop


def _held_port() -> socket.socket:
    """A free loopback port, listened on by this test (as a leftover would)."""
    held = socket.socket()
    held.bind(("127.0.0.1", 0))
    held.listen()
    return held


def _hang_up(held: socket.socket) -> None:
    """Answer every connection to `held` by closing it (a program that is no ROS master;
    one that never answers costs sw2sim ros its 3 s wait)."""
    while True:
        try:
            connection, _ = held.accept()
        except OSError:      # closed: the test is over
            return
        connection.close()


def test_a_taken_port_is_said_with_its_holder_and_another_port_chosen():
    with _held_port() as held:
        port = held.getsockname()[1]
        new, told = ros_run.master_address(f"http://localhost:{port}")
        text = "\n".join(told)
        assert new != port and ros_run._free(new)
        assert f"names port {port} of this machine" in text and "taken" in text
        assert f"by PID {os.getpid()} (" in text, text
        assert f"kill {os.getpid()}" in text
        assert f"uses port {new} instead" in text


def test_a_free_port_of_the_uri_is_used_without_a_word():
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        port = probe.getsockname()[1]
    assert ros_run.master_address(f"http://127.0.0.1:{port}") == (port, [])


def test_the_line_for_other_terminals_names_the_master_unless_theirs_already_finds_it():
    env = {"ROS_MASTER_URI": "http://127.0.0.1:11311"}
    assert "export" not in ros_run._terminal_line(env, None)
    assert "export" not in ros_run._terminal_line(env, "http://localhost:11311/")
    # the reader's ROS_MASTER_URI named a taken port: the run went to 11311
    line = ros_run._terminal_line(env, "http://127.0.0.1:40001")
    assert line.startswith("export ROS_MASTER_URI=http://127.0.0.1:11311; ")
    env = {"ROS_MASTER_URI": "http://127.0.0.1:40002"}
    assert ros_run._terminal_line(env, "http://127.0.0.1:40002").startswith(
        "export ROS_MASTER_URI=http://127.0.0.1:40002; ")


@pytest.mark.skipif(missing() is not None, reason=missing() or "")
def test_sw2sim_ros_says_the_port_is_taken_and_where_its_master_is(tmp_path):
    home = tmp_path / "ros_home"
    with _held_port() as held:
        threading.Thread(target=_hang_up, args=(held,), daemon=True).start()
        port = held.getsockname()[1]
        env = {**os.environ, "ROS_MASTER_URI": f"http://127.0.0.1:{port}",
               "ROS_HOME": str(home), "ROS_LOG_DIR": str(home / "log"), "ROS_IP": "127.0.0.1"}
        process = subprocess.Popen(
            [sys.executable, "-m", "sw2sim", "ros", str(EXAMPLES / "example_1"),
             "--duration", "0"], env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
            text=True, stdin=subprocess.DEVNULL, start_new_session=True)
        try:
            out, _ = process.communicate(timeout=60)
        finally:
            below = descendants(process.pid)
            stop(process)
            for pid in ros_run.running(below):
                os.kill(pid, signal.SIGKILL)
    assert process.returncode == 0, out[-3000:]
    assert f"names port {port} of this machine" in out and f"kill {os.getpid()}" in out, out
    # the master the run started answered at the address it then gives other terminals
    ran = re.search(r"gazebo\.launch on (http://127\.0\.0\.1:(\d+)), MuJoCo", out)
    assert ran and int(ran[2]) != port, out
    assert f"export ROS_MASTER_URI={ran[1]}; eval" in out, out
