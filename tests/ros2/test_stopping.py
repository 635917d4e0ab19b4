"""`sw2sim ros2` leaves nothing running: on Ctrl-C (also where it was started with Ctrl-C
ignored, as in the background of a script), SIGTERM, --duration and its parent's death."""

from __future__ import annotations

import signal
import subprocess
import sys
import time

import pytest

from repository import ROOT
from ros2_environment import PYTHON


def _wait_up(ros2, timeout=20.0):
    deadline = time.monotonic() + timeout
    while "controllers:" not in ros2.log("standin"):
        assert time.monotonic() < deadline, ros2.log("standin")
        time.sleep(0.1)


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM])
def test_a_signal_stops_it_promptly(ros2, ported_example_3, sig):
    previous = signal.signal(signal.SIGINT, signal.SIG_IGN)   # as a background job has it
    try:
        process = ros2.standin(ported_example_3)
    finally:
        signal.signal(signal.SIGINT, previous)
    _wait_up(ros2)
    began = time.monotonic()
    process.send_signal(sig)
    assert process.wait(timeout=5) == 0
    assert time.monotonic() - began < 3
    assert not ros2.group_alive(process.pid)


def test_duration_ends_it(ros2, ported_example_3):
    process = ros2.start(str(PYTHON), "-m", "sw2sim", "ros2", str(ported_example_3),
                         "--realtime", "0", "--duration", "1", name="standin")
    assert process.wait(timeout=20) == 0


def test_it_ends_with_its_parent(ros2, ported_example_3):
    # a parent that starts it and is then killed without a chance to stop it
    parent = ros2.start(str(PYTHON), "-c",
                        "import subprocess, sys, time; "
                        f"p = subprocess.Popen([sys.executable, '-m', 'sw2sim', 'ros2', "
                        f"{str(ported_example_3)!r}, '--realtime', '0', '--duration', '60']); "
                        "print(p.pid, flush=True); time.sleep(60)", name="parent")
    deadline = time.monotonic() + 20
    while not (ros2.home / "parent.log").read_text().strip():
        assert time.monotonic() < deadline
        time.sleep(0.1)
    child = int((ros2.home / "parent.log").read_text().split()[0])
    time.sleep(3)
    parent.kill()
    parent.wait()
    deadline = time.monotonic() + 5
    while time.monotonic() < deadline:
        try:
            with open(f"/proc/{child}/stat") as stat:
                if stat.read().rsplit(")", 1)[1].split()[0] == "Z":
                    break
        except FileNotFoundError:
            break
        time.sleep(0.1)
    else:
        raise AssertionError("sw2sim ros2 outlived its parent")


def test_without_rclpy_it_says_what_to_install_on_one_line(tmp_path, monkeypatch):
    import sw2sim.ros2.run as run_module
    monkeypatch.setattr(run_module, "missing", lambda: run_module.INSTALL)
    said = []
    assert run_module.run("examples/example_3", say=said.append) == 2
    assert len(said) == 1 and "\n" not in said[0]
    assert 'pip install "sw2sim[ros2]"' in said[0] and "make setup" in said[0]


def test_a_python_without_rclpy_is_told_so():
    """The tests' own environment has no rclpy (ROS 2 lives in .venv-ros2): there, the
    command says on one line what to install, and exits 2."""
    import importlib.util
    if importlib.util.find_spec("rclpy") is not None:
        pytest.skip("this Python has rclpy")
    done = subprocess.run([sys.executable, "-m", "sw2sim", "ros2", "examples/example_3",
                           "--duration", "1"], cwd=ROOT, capture_output=True, text=True,
                          timeout=60)
    assert done.returncode == 2, done.stdout + done.stderr
    said = (done.stdout + done.stderr).strip().splitlines()
    assert len(said) == 1 and 'pip install "sw2sim[ros2]"' in said[0], said
