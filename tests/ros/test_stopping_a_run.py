"""`sw2sim ros` leaves nothing running, however it is stopped: SIGINT (also where a script's
`cmd &` made it inherit SIGINT ignored), SIGTERM, SIGHUP, or SIGKILL of `sw2sim ros` itself,
which its watchdog answers. And it fails, naming the node, when a node of the launch cannot
start, instead of running to its --duration and ending with status 0.

Each test runs the real thing: `sw2sim ros examples/example_1` with its own master, on a
free port, and waits until the simulation's clock runs and the launch's nodes are
registered. "The run's processes" are the process tree below `sw2sim ros` just before the
signal, and every process whose environment or command line names the test's master port
(every process the run starts has that ROS_MASTER_URI). Whatever is left is killed at the
end, also when a test fails.
"""

from __future__ import annotations

import os
import shlex
import shutil
import signal
import socket
import subprocess
import sys
import time
import xmlrpc.client
from pathlib import Path

import pytest

from packages import EXAMPLES
from sw2sim.ros.run import descendants, missing

pytestmark = pytest.mark.skipif(missing() is not None, reason=missing() or "")

START_TIMEOUT = 120.0   # s for the run's clock and nodes (a busy 2-core machine)
GONE_TIMEOUT = 10.0     # s for the run's processes to end after the signal
NODES = {"/gazebo", "/tf_footprint_base", "/fake_joint_calibration", "/periodic_force"}


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _environment(tmp_path: Path) -> tuple[dict[str, str], int]:
    port = _free_port()
    home = tmp_path / "ros_home"
    env = {**os.environ, "ROS_MASTER_URI": f"http://127.0.0.1:{port}", "ROS_HOME": str(home),
           "ROS_LOG_DIR": str(home / "log"), "ROS_IP": "127.0.0.1"}
    return env, port


def _start_time(pid: int) -> int | None:
    try:
        stat = Path(f"/proc/{pid}/stat").read_text(errors="replace")
    except OSError:
        return None
    fields = stat.rsplit(")", 1)[1].split()
    return None if fields[0] == "Z" else int(fields[19])   # a zombie runs no more


def _names_port(pid: int, port: int) -> bool:
    try:
        environ = Path(f"/proc/{pid}/environ").read_bytes()
        cmdline = Path(f"/proc/{pid}/cmdline").read_bytes()
    except OSError:
        return False
    return (f"ROS_MASTER_URI=http://127.0.0.1:{port}\0".encode() in environ
            or f"127.0.0.1:{port}".encode() in cmdline or f"\0-p\0{port}\0".encode() in cmdline)


def _of_the_run(pid: int, port: int) -> dict[int, int]:
    """pid -> start time of `sw2sim ros` (pid), everything below it, and every process
    marked with the test's port."""
    found = {pid, *descendants(pid)}
    found |= {int(e.name) for e in Path("/proc").glob("[0-9]*")
              if int(e.name) != os.getpid() and _names_port(int(e.name), port)}
    return {p: start for p in found if (start := _start_time(p)) is not None}


def _running(processes: dict[int, int]) -> dict[int, int]:
    return {pid: start for pid, start in processes.items() if _start_time(pid) == start}


def _command(pid: int) -> str:
    try:
        return Path(f"/proc/{pid}/cmdline").read_bytes().replace(b"\0", b" ").decode(
            errors="replace")[:160]
    except OSError:
        return "?"


def _kill(processes: dict[int, int]) -> None:
    for pid in _running(processes):
        try:
            os.kill(pid, signal.SIGKILL)
        except (ProcessLookupError, PermissionError):
            pass


def _wait_until_it_runs(uri: str, log: Path, ended) -> None:
    """Until the master lists a publisher of /clock and the launch's nodes."""
    master = xmlrpc.client.ServerProxy(uri)
    deadline = time.monotonic() + START_TIMEOUT
    while time.monotonic() < deadline:
        assert not ended(), f"sw2sim ros ended early:\n{log.read_text(errors='replace')[-3000:]}"
        try:
            publishers, subscribers, services = master.getSystemState("/test")[2]
        except OSError:
            time.sleep(0.3)
            continue
        nodes = {n for _, names in publishers + subscribers + services for n in names}
        clock = any(topic == "/clock" and names for topic, names in publishers)
        if clock and NODES <= nodes:
            return
        time.sleep(0.3)
    raise AssertionError(f"the launch's nodes and /clock did not appear in {START_TIMEOUT:.0f} "
                         f"s:\n{log.read_text(errors='replace')[-3000:]}")


def _sw2sim_ros(package: Path, duration: int) -> list[str]:
    return [sys.executable, "-m", "sw2sim", "ros", str(package), "--duration", str(duration)]


@pytest.mark.parametrize("how, status", [
    ("SIGINT from a script's background", 128 + signal.SIGINT),
    ("SIGTERM", 128 + signal.SIGTERM),
    ("SIGHUP", 128 + signal.SIGHUP),
    ("SIGKILL", -signal.SIGKILL),
])
def test_nothing_of_the_run_is_left_however_it_is_stopped(tmp_path, how, status):
    env, port = _environment(tmp_path)
    log = tmp_path / "sw2sim_ros.log"
    command = _sw2sim_ros(EXAMPLES / "example_1", 60)
    if how.startswith("SIGINT"):
        # A non-interactive shell starts `cmd &` with SIGINT ignored (as a script's
        # background job); its `wait` reports the job's status as its own.
        script = f"{shlex.join(command)} >{shlex.quote(str(log))} 2>&1 & echo $!; wait $!"
        started = subprocess.Popen(["bash", "-c", script], env=env, stdout=subprocess.PIPE,
                                   text=True, start_new_session=True)
        pid = int(started.stdout.readline())
        sig = signal.SIGINT
    else:
        with open(log, "wb") as out:
            started = subprocess.Popen(command, env=env, stdout=out, stderr=subprocess.STDOUT,
                                       stdin=subprocess.DEVNULL, start_new_session=True)
        pid = started.pid
        sig = getattr(signal, how)
    run = {started.pid: _start_time(started.pid) or 0}
    try:
        _wait_until_it_runs(env["ROS_MASTER_URI"], log, lambda: started.poll() is not None)
        run.update(_of_the_run(pid, port))
        assert len(run) >= 8, "sw2sim, its watchdog, roscore, rosmaster, roslaunch and nodes"
        os.kill(pid, sig)
        deadline = time.monotonic() + GONE_TIMEOUT
        while _running(run) and time.monotonic() < deadline:
            time.sleep(0.1)
        started.wait(timeout=GONE_TIMEOUT)
        text = log.read_text(errors="replace")
        left = {p: _command(p) for p in _running(run)}
        assert not left, f"left running after {how}: {left}\n{text[-3000:]}"
        later = {p: _command(p) for p in _running(_of_the_run(pid, port))}
        assert not later, f"left running after {how}: {later}"
        assert started.returncode == status, text[-3000:]
        assert "died:" not in text and "could not start" not in text, text[-3000:]
        if sig == signal.SIGKILL:
            assert "sw2sim ros: stopped" in text, "the watchdog stopped them"
    finally:
        if started.poll() is None:
            os.killpg(started.pid, signal.SIGKILL)
        _kill(run)
        _kill(_of_the_run(pid, port))
        started.wait()


def test_a_node_that_cannot_start_fails_the_run_naming_it(tmp_path):
    package = tmp_path / "example_1"
    shutil.copytree(EXAMPLES / "example_1", package)
    launch = package / "launch" / "gazebo.launch"
    text = launch.read_text()
    assert 'type="periodic_force_node.py"' in text
    launch.write_text(text.replace('type="periodic_force_node.py"', 'type="no_such_node.py"'))
    env, port = _environment(tmp_path)
    # far longer than the test waits: it must stop at the fault, not at --duration
    process = subprocess.Popen(_sw2sim_ros(package, 3600), env=env, stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, text=True, stdin=subprocess.DEVNULL,
                               start_new_session=True)
    try:
        out, err = process.communicate(timeout=START_TIMEOUT)
    except subprocess.TimeoutExpired:
        out, err = "", ""
    finally:
        left = _of_the_run(process.pid, port)
        if process.poll() is None:
            os.killpg(process.pid, signal.SIGKILL)
        _kill(left)
        process.wait()
    assert process.returncode == 1, f"status {process.returncode}:\n{out[-2000:]}\n{err[-2000:]}"
    # roslaunch's own line passes through, then the summary names the node
    assert "ERROR: cannot launch node of type [example_1/no_such_node.py]" in err
    assert ("sw2sim ros: could not start node periodic_force (example_1/no_such_node.py): "
            "Cannot locate node of type [no_such_node.py] in package [example_1]") in out
    assert not left, {p: _command(p) for p in left}
