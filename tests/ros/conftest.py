"""A ROS 1 master of its own for each test, on a free loopback port, and every process a
test starts stopped by its process group when the test ends, also when it fails.

ROS comes from Debian (`make setup` installs it where the distribution ships it). Where it
is missing, the tests that need it are skipped with the reason.
"""

from __future__ import annotations

import importlib.util
import os
import shutil
import signal
import socket
import subprocess
import sys
import time
import uuid
import xmlrpc.client
from pathlib import Path

import pytest

# Why the ROS tests cannot run here, or None when they can.
MISSING = (None if shutil.which("rosmaster") and importlib.util.find_spec("rospy")
           else "ROS 1 is not installed: `make setup` installs it from Debian where the "
                "distribution ships it (Debian 12 does; Ubuntu 24.04 and Debian 13 do not)")
ROSOUT = "/usr/lib/rosout/rosout"   # Debian's
MASTER_TIMEOUT = 15.0   # s for rosmaster to answer
STOP_TIMEOUT = 5.0      # s between SIGINT and SIGKILL


def free_port() -> int:
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class Ros:
    """One test's ROS world: the environment its processes get, and the processes."""

    def __init__(self, home: Path):
        self.port = free_port()
        self.uri = f"http://127.0.0.1:{self.port}"
        home.mkdir(parents=True, exist_ok=True)
        self.env = {**os.environ, "ROS_MASTER_URI": self.uri, "ROS_IP": "127.0.0.1",
                    "ROS_HOSTNAME": "127.0.0.1", "ROS_HOME": str(home),
                    "ROS_LOG_DIR": str(home / "log"),
                    # Debian's nodes start with /usr/bin/env python3: theirs, with rospy
                    "PATH": f"/usr/bin{os.pathsep}{os.environ.get('PATH', '')}"}
        self.processes: list[subprocess.Popen] = []
        self.below: list[int] = []   # what ran below them when they were stopped
        self.logs = home / "processes"
        self.logs.mkdir(exist_ok=True)

    def start(self, *command: str, name: str) -> subprocess.Popen:
        """Start a process in a session (and process group) of its own; its output goes to
        a log file named `name`."""
        log = open(self.logs / f"{name}.log", "wb")
        from sw2sim.ros.run import with_ctrl_c
        process = subprocess.Popen(list(command), env=self.env, stdout=log,
                                   stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL,
                                   start_new_session=True, preexec_fn=with_ctrl_c)
        log.close()
        self.processes.append(process)
        return process

    def run(self, *command: str, timeout: float = 30.0) -> subprocess.CompletedProcess:
        """Run a command to its end (in its own process group, killed on timeout)."""
        from sw2sim.ros.run import with_ctrl_c
        process = subprocess.Popen(list(command), env=self.env, stdout=subprocess.PIPE,
                                   stderr=subprocess.PIPE, text=True, start_new_session=True,
                                   preexec_fn=with_ctrl_c)
        try:
            out, err = process.communicate(timeout=timeout)
        except subprocess.TimeoutExpired:
            from sw2sim.ros.run import descendants
            _stop([process], descendants(process.pid))
            out, err = process.communicate()
            raise AssertionError(f"{command[0]} did not finish in {timeout:.0f} s:\n{out}\n{err}")
        return subprocess.CompletedProcess(command, process.returncode, out, err)

    def python(self, script: Path, *args: str, timeout: float = 30.0):
        """Run a Python script of the tests with ROS's environment."""
        return self.run(sys.executable, str(script), *args, timeout=timeout)

    def wait_for_master(self) -> None:
        deadline = time.monotonic() + MASTER_TIMEOUT
        while time.monotonic() < deadline:
            try:
                with xmlrpc.client.ServerProxy(self.uri) as master:
                    master.getSystemState("/test")
                return
            except OSError:
                time.sleep(0.1)
        raise AssertionError(f"rosmaster did not answer on {self.uri} in {MASTER_TIMEOUT:.0f} s:\n"
                             + (self.logs / "rosmaster.log").read_text(errors="replace"))

    def stop_all(self) -> None:
        """Everything at once, then the master last (nodes unregister from it as they go)."""
        from sw2sim.ros.run import descendants
        for process in self.processes:
            self.below.extend(descendants(process.pid))
        nodes, master = self.processes[1:], self.processes[:1]
        for group in (nodes, master):
            _stop(group, self.below)

    def leftovers(self) -> list[int]:
        """The processes started here (and below them) that are still running."""
        from sw2sim.ros.run import running
        return running([p.pid for p in self.processes] + self.below)


def _stop(processes: list[subprocess.Popen], below: list[int]) -> None:
    """The processes, their groups and every process below them, as `sw2sim ros` stops
    them; then whatever of `below` still runs is killed."""
    from sw2sim.ros.run import running, stop
    stop(*processes)
    for pid in running(below):
        try:
            os.kill(pid, signal.SIGKILL)
        except (ProcessLookupError, PermissionError):
            pass


@pytest.fixture
def ros(tmp_path):
    """A running master of the test's own; every process started through it is stopped at
    the end, and the test fails if one of them outlives that."""
    if MISSING:
        pytest.skip(MISSING)
    world = Ros(tmp_path / "ros_home")
    try:
        # What `roscore` starts, without the roslaunch process it runs them under (a
        # second or so of start-up per test): the master, the run id, the /rosout node.
        world.start("rosmaster", "--core", "-p", str(world.port), "-w", "3", name="rosmaster")
        world.wait_for_master()
        # roscore's run id: `roslaunch --wait` waits for it
        with xmlrpc.client.ServerProxy(world.uri) as master:
            master.setParam("/roscore", "/run_id", str(uuid.uuid1()))
        world.start(ROSOUT, "__name:=rosout", name="rosout")
        yield world
    finally:
        world.stop_all()
    assert not world.leftovers(), f"ROS processes left running: {world.leftovers()}"
