"""ROS 2 (rclpy) tests: each test gets a domain id of its own and a ROS home in its
temporary folder; every process it starts runs in a process group of its own, kept on
127.0.0.1 (sw2sim.ros2.discovery), and is stopped when the test ends, also when it fails.
They run in the ROS 2 environment, .venv-ros2 (tests/ros2_environment.py), and are skipped
with its reason where it is missing."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import time
from pathlib import Path

import pytest

import ros2_domains
from ros2_environment import PYTHON, missing
from sw2sim.ros2 import discovery

HERE = Path(__file__).parent
EXAMPLE_3 = HERE.parents[1] / "examples" / "example_3"
STOP_TIMEOUT = 5.0


class Ros2:
    def __init__(self, home: Path):
        home.mkdir(parents=True, exist_ok=True)
        self._claim = ros2_domains.claim()   # no other test's traffic in it
        self.domain = self._claim.id
        self.env = discovery.environment(self.domain)
        self.env.update(ROS_HOME=str(home), ROS_LOG_DIR=str(home / "log"),
                        PYTHONUNBUFFERED="1")
        self.home = home
        self.here = HERE
        self.group_alive = group_alive
        self.processes: list[subprocess.Popen] = []

    def start(self, *command: str, name: str, **kwargs) -> subprocess.Popen:
        log = open(self.home / f"{name}.log", "wb")
        process = subprocess.Popen(list(command), env=self.env, stdout=log,
                                   stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL,
                                   start_new_session=True, **kwargs)
        log.close()
        self.processes.append(process)
        return process

    def standin(self, package, *args: str) -> subprocess.Popen:
        return self.start(str(PYTHON), "-m", "sw2sim", "ros2", str(package), "--realtime", "0",
                          "--duration", "40", *args, name="standin")

    def record(self, *args: str, timeout: float = 45.0) -> dict:
        process = subprocess.Popen([str(PYTHON), str(HERE / "recorder.py"), *args],
                                   env=self.env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                   text=True, start_new_session=True)
        self.processes.append(process)
        out, err = process.communicate(timeout=timeout)
        assert process.returncode == 0, f"recorder failed:\n{err[-2000:]}\n{self.log('standin')}"
        return json.loads(out)

    def log(self, name: str) -> str:
        path = self.home / f"{name}.log"
        return path.read_text(errors="replace") if path.is_file() else ""

    def stop_all(self) -> None:
        for process in self.processes:
            stop(process)
        self._claim.release()


def stop(process: subprocess.Popen) -> None:
    """SIGINT to the process group, SIGKILL after STOP_TIMEOUT."""
    for sig in (signal.SIGINT, signal.SIGKILL):
        try:
            os.killpg(process.pid, sig)
        except (ProcessLookupError, PermissionError):
            pass
        try:
            process.wait(timeout=STOP_TIMEOUT)
            return
        except subprocess.TimeoutExpired:
            continue


def group_alive(pgid: int) -> bool:
    try:
        os.killpg(pgid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    for entry in Path("/proc").glob("[0-9]*"):   # zombies do not count
        try:
            fields = (entry / "stat").read_text().rsplit(")", 1)[1].split()
        except (OSError, IndexError):
            continue
        if int(fields[2]) == pgid and fields[0] != "Z":
            return True
    return False


@pytest.fixture
def ros2(tmp_path):
    reason = missing()
    if reason:
        pytest.skip(reason)
    world = Ros2(tmp_path / "ros_home")
    try:
        yield world
    finally:
        world.stop_all()
    left = [p.pid for p in world.processes if group_alive(p.pid)]
    assert not left, f"ROS 2 processes left running: {left}"


@pytest.fixture(scope="session")
def ported_example_3(tmp_path_factory):
    """example_3 as `sw2sim port` writes it."""
    if missing():
        pytest.skip(missing())
    from sw2sim.port import port
    return port(EXAMPLE_3, tmp_path_factory.mktemp("ported") / "example_3").package_dir
