"""`sw2sim ros PACKAGE`: the package's own launch file under ROS 1, with MuJoCo in
Gazebo's place.

It uses the master at ROS_MASTER_URI when one answers, and starts its own otherwise (on
127.0.0.1). Everything it starts runs in process groups of its own, stopped (SIGINT, then
SIGKILL) at the end: after --duration seconds, when the launch ends, or on Ctrl-C.
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
from pathlib import Path

DEBIAN = ("python3-rospy python3-roslaunch python3-rostopic python3-rosservice python3-rosnode "
          "rosout python3-std-msgs python3-std-srvs python3-sensor-msgs python3-rosgraph-msgs "
          "python3-tf2-msgs python3-genpy python3-genmsg ros-std-msgs ros-geometry-msgs "
          "ros-robot-state-publisher")
STOP_WAIT = 5.0


def missing() -> str | None:
    """What to install for ROS 1, or None when it is here."""
    if shutil.which("roslaunch") and shutil.which("roscore") and importlib.util.find_spec("rospy"):
        return None
    return ("ROS 1 is not installed. On Debian 12: sudo apt install " + DEBIAN + "; then make "
            "Debian's rospy visible to this Python (`make setup` does both in a clone of the "
            "course). Other systems: ROS 1 needs Debian 12, Ubuntu 20.04 or WSL2 with one of them.")


def _answers(uri: str) -> bool:
    import rosgraph
    return bool(rosgraph.is_master_online(master_uri=uri))


def _free(port: int) -> bool:
    with socket.socket() as s:
        try:
            s.bind(("127.0.0.1", port))
            return True
        except OSError:
            return False


def _port() -> int:
    if _free(11311):
        return 11311
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def environment(package_root: Path, realtime: float) -> dict[str, str]:
    from . import messages, packages
    generated = messages.ensure()
    standins = packages.write(generated.parent / "ros-packages")
    env = dict(os.environ)
    user = env.get("ROS_PACKAGE_PATH") or "/usr/share"
    env["ROS_PACKAGE_PATH"] = os.pathsep.join([str(package_root.parent), user, str(standins)])
    env["PYTHONPATH"] = os.pathsep.join(p for p in [str(generated), env.get("PYTHONPATH")] if p)
    env[messages.FOLDER_VARIABLE] = str(generated)
    env["SW2SIM_PYTHON"] = sys.executable
    env["SW2SIM_REALTIME"] = f"{realtime:g}"
    env.setdefault("ROS_IP", "127.0.0.1")
    # Nodes that start with `#!/usr/bin/env python3` need the Python that has rospy.
    env["PATH"] = os.pathsep.join(["/usr/bin", env.get("PATH", "")])
    return env


def descendants(pid: int) -> list[int]:
    """Every process below `pid` (Linux: read from /proc). roslaunch starts each node in a
    session of its own, so signalling its process group does not reach them."""
    children: dict[int, list[int]] = {}
    for entry in Path("/proc").glob("[0-9]*"):
        try:
            fields = (entry / "stat").read_text(encoding="utf-8", errors="replace").rsplit(")", 1)[1].split()
        except (OSError, IndexError):
            continue
        children.setdefault(int(fields[1]), []).append(int(entry.name))
    found, todo = [], [pid]
    while todo:
        for child in children.get(todo.pop(), []):
            found.append(child)
            todo.append(child)
    return found


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


def running(pids) -> list[int]:
    """The processes of `pids` that still run."""
    return [pid for pid in pids if _alive(pid)]


def with_ctrl_c() -> None:
    """For `preexec_fn`: Ctrl-C (SIGINT) and SIGQUIT as they are by default. A process
    started in the background of a shell without job control inherits both ignored, and
    ROS nodes that ignore Ctrl-C stop only when killed, seconds later, without cleaning up."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)
    signal.signal(signal.SIGQUIT, signal.SIG_DFL)


def stop(*processes: subprocess.Popen) -> None:
    """Stop processes, their groups and everything below them: SIGINT to each group first
    (as Ctrl-C, which lets roslaunch stop its nodes in order), SIGINT to the nodes it left
    after STOP_WAIT, SIGKILL for what is left after that."""
    below = [pid for process in processes for pid in descendants(process.pid)]

    def alive() -> bool:
        return any(p.poll() is None for p in processes) or any(_alive(pid) for pid in below)

    for sig in (signal.SIGINT, signal.SIGKILL):
        for process in processes:
            with _quiet():
                os.killpg(process.pid, sig)
        if sig == signal.SIGKILL:
            for pid in below:
                with _quiet():
                    os.kill(pid, signal.SIGKILL)
        deadline = time.monotonic() + STOP_WAIT
        while time.monotonic() < deadline and alive():
            time.sleep(0.05)
        if not alive():
            break
        if sig == signal.SIGINT:   # the nodes roslaunch left: Ctrl-C them too
            for pid in below:
                with _quiet():
                    os.kill(pid, signal.SIGINT)
    for process in processes:
        with _quiet():
            process.wait(timeout=STOP_WAIT)


class _quiet:
    def __enter__(self):
        return self

    def __exit__(self, kind, value, trace):
        return kind is not None and issubclass(kind, (ProcessLookupError, PermissionError,
                                                      subprocess.TimeoutExpired))


def run(path: str, launch: str | None = None, duration: float | None = None,
        realtime: float = 1.0, view: bool = False, say=print) -> int:
    reason = missing()
    if reason:
        say(f"sw2sim ros: {reason}")
        return 2
    from ..package import LoadError, find_package
    try:
        package = find_package(path)
    except LoadError as exc:
        say(f"sw2sim ros: {exc}")
        return 2
    launch_file = Path(launch) if launch else package.root / "launch" / "gazebo.launch"
    if not launch_file.is_file():
        say(f"sw2sim ros: {launch_file} does not exist; give the launch file with --launch FILE")
        return 2
    env = environment(package.root, realtime)
    if view:
        env["SW2SIM_VIEW"] = "1"
        from .. import gl
        gl.for_window(env)           # the viewer's window, not the off-screen default
    started: list[subprocess.Popen] = []
    try:
        uri = env.get("ROS_MASTER_URI")
        if not uri or not _answers(uri):
            port = _port()
            uri = env["ROS_MASTER_URI"] = f"http://127.0.0.1:{port}"
            started.append(subprocess.Popen(["roscore", "-p", str(port)], env=env,
                                            start_new_session=True, preexec_fn=with_ctrl_c,
                                            stdout=subprocess.DEVNULL,
                                            stderr=subprocess.DEVNULL))
            deadline = time.monotonic() + 15
            while not _answers(uri):
                if time.monotonic() > deadline:
                    say("sw2sim ros: roscore did not start")
                    return 2
                time.sleep(0.1)
        from ..archive import shown
        say(f"sw2sim ros: {shown(launch_file) or launch_file} on {uri}, MuJoCo standing in "
            "for Gazebo")
        roslaunch = subprocess.Popen(["roslaunch", "--wait", str(launch_file)], env=env,
                                     start_new_session=True, preexec_fn=with_ctrl_c)
        started.append(roslaunch)
        end = None if duration is None else time.monotonic() + duration
        while roslaunch.poll() is None and (end is None or time.monotonic() < end):
            time.sleep(0.1)
        return 0 if roslaunch.returncode in (None, 0) else 1
    except KeyboardInterrupt:
        return 130
    finally:
        # the launch first, then the master its nodes unregister from
        for process in reversed(started):
            stop(process)
