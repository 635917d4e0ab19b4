"""`sw2sim ros PACKAGE`: the package's own launch file under ROS 1, with MuJoCo in
Gazebo's place.

It uses the master at ROS_MASTER_URI when one answers, and starts its own otherwise (on
127.0.0.1, at ROS_MASTER_URI's port when that names this machine; when that port is
taken, it says so, names what holds it, and prints the line that reaches the port it uses
instead). Everything it starts runs in process groups of its own, stopped (SIGINT, then
SIGKILL) at the end: after
--duration seconds, when the launch ends, when a node of the launch could not start or
died (sw2sim.ros.launch_faults: the node is named, the status is 1), or on SIGINT, SIGTERM
or SIGHUP (sw2sim.ros.stop_signals: status 128 + the signal's number). Should `sw2sim ros`
itself be killed, the watchdog it starts first stops the rest (sw2sim.ros.watchdog).
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
import urllib.parse
from pathlib import Path

from . import wire

DEBIAN = ("python3-rospy python3-roslaunch python3-rostopic python3-rosservice python3-rosnode "
          "rosout python3-std-msgs python3-std-srvs python3-sensor-msgs python3-rosgraph-msgs "
          "python3-tf2-msgs python3-genpy python3-genmsg ros-std-msgs ros-geometry-msgs "
          "ros-robot-state-publisher")
STOP_WAIT = 5.0
FAULT_SETTLE = 1.0   # s after a first fault for the lines about others, before stopping
LOCAL_NAMES = ("127.0.0.1", "localhost")


def missing() -> str | None:
    """What to install for ROS 1, or None when it is here."""
    if shutil.which("roslaunch") and shutil.which("roscore") and importlib.util.find_spec("rospy"):
        return None
    return ("ROS 1 is not installed. On Debian 12: sudo apt install " + DEBIAN + "; then make "
            "Debian's rospy visible to this Python (`make setup` does both in a clone of the "
            "course). Other systems: ROS 1 needs Debian 12, Ubuntu 20.04 or WSL2 with one of them.")


def _free(port: int) -> bool:
    with socket.socket() as s:
        try:
            s.bind(("127.0.0.1", port))
            return True
        except OSError:
            return False


DEFAULT_URI = "http://localhost:11311"   # ROS's, where ROS_MASTER_URI is unset


def _any_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _listening_inodes(port: int) -> set[str]:
    """The socket inodes that listen on `port` (Linux: /proc/net/tcp and tcp6)."""
    found = set()
    for table in ("/proc/net/tcp", "/proc/net/tcp6"):
        try:
            lines = Path(table).read_text(encoding="ascii", errors="replace").splitlines()[1:]
        except OSError:
            continue
        for line in lines:
            fields = line.split()
            # local address "ADDR:PORT" in hex, state 0A: LISTEN; field 9: the inode
            if len(fields) > 9 and fields[3] == "0A" and int(fields[1].rsplit(":", 1)[1], 16) == port:
                found.add(fields[9])
    return found


def holder(port: int) -> str | None:
    """What listens on `port` of this machine, as "PID (command line)", when /proc says
    (only the processes of this user, or all as root, can be read); None otherwise."""
    inodes = {f"socket:[{inode}]" for inode in _listening_inodes(port)}
    if not inodes:
        return None
    for entry in Path("/proc").glob("[0-9]*"):
        try:
            fds = list((entry / "fd").iterdir())
        except OSError:
            continue
        links = set()
        for fd in fds:
            try:
                links.add(os.readlink(fd))
            except OSError:      # closed meanwhile (the listing's own, for one)
                pass
        if links & inodes:
            try:
                line = (entry / "cmdline").read_bytes().replace(b"\0", b" ").decode(errors="replace")
            except OSError:
                line = ""
            return f"{entry.name} ({line.strip() or '?'})"
    return None


def master_address(uri: str | None) -> tuple[int, list[str]]:
    """The port for the master started here, when none answers at ROS_MASTER_URI (`uri`,
    ROS's default when unset), and what to tell the reader about it: ROS_MASTER_URI's port
    when it names this machine and is free, so that other terminals with the same
    ROS_MASTER_URI find the master. A port that is taken, or an address on another
    machine, is said, with what holds the port, the command that frees it, and another
    port for this run (its address then goes into the line for other terminals)."""
    given = uri or DEFAULT_URI
    try:
        parsed = urllib.parse.urlsplit(given)
        host, port = parsed.hostname, parsed.port
    except ValueError:
        host = port = None
    if host in LOCAL_NAMES and port:
        if _free(port):
            return port, []
        new = _any_port()
        who = holder(port)
        told = [f"ROS_MASTER_URI={given} names port {port} of this machine, where no ROS "
                f"master answers, and the port is taken"
                + (f" by PID {who}" if who else f" (/proc shows no process of this user "
                   f"listening there; `ss -tanp 'sport = :{port}'` as root shows what holds it)")
                + ".",
                f"This run's master uses port {new} instead; other terminals need its "
                f"address (the line below)."]
        if who:
            told.append(f"To use port {port} again, stop what holds it: kill {who.split()[0]}")
        return new, told
    chosen = 11311 if _free(11311) else _any_port()
    why = (f"ROS_MASTER_URI={given} is not an address of this machine (127.0.0.1 or localhost)"
           if port or host else f"ROS_MASTER_URI={given} is not a master's address "
                                f"(http://HOST:PORT)")
    return chosen, [f"{why}, and no master answers there: this run starts its own on port "
                    f"{chosen} of this machine; other terminals need its address (the line below)."]


def environment(package_root: Path, realtime: float) -> dict[str, str]:
    """This process's environment with what `sw2sim ros-env` gives a terminal (the
    stand-ins, the message classes; sw2sim.ros.terminal), the package's folder on
    ROS_PACKAGE_PATH, and the real-time factor."""
    from .terminal import variables
    env = dict(os.environ)
    env.update(variables([package_root.parent], env))
    env["SW2SIM_REALTIME"] = f"{realtime:g}"
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
    from . import messages
    from .launch_fixes import adapt
    launch_file, notes = adapt(launch_file, Path(env[messages.FOLDER_VARIABLE]).parent
                               / "launch-files")
    for note in notes:
        say(f"sw2sim ros: {note}")
    if view:
        env["SW2SIM_VIEW"] = "1"
        from .. import gl
        gl.for_window(env)           # the viewer's window, not the off-screen default
    return _Run(launch_file, env, _told(say)).run(duration)


def _terminal_line(env: dict[str, str], given: str | None = None) -> str:
    """What another terminal runs to reach this run: `sw2sim ros-env` through the course's
    sw2sim, after the master's address unless it is ROS's default and the one this run
    was given (`given`, ROS_MASTER_URI before the run: a terminal with that value set
    would look there)."""
    uri = env.get("ROS_MASTER_URI", "")
    beside = Path(sys.executable).with_name("sw2sim")   # this environment's, activated or not
    line = f'eval "$({beside if beside.is_file() else "sw2sim"} ros-env)"'
    if _place(uri) != _place(DEFAULT_URI) or _place(given or DEFAULT_URI) != _place(uri):
        line = f"export ROS_MASTER_URI={uri}; {line}"
    return line


def _place(uri: str) -> tuple:
    """Where a master's address leads: (host, port), this machine's names as one."""
    try:
        parsed = urllib.parse.urlsplit(uri)
        host, port = parsed.hostname, parsed.port
    except ValueError:
        return (uri,)
    return ("127.0.0.1" if host in LOCAL_NAMES else host, port)


def _told(say):
    """`say`, silent once there is nowhere to say it (SIGHUP: the terminal is gone)."""
    def tell(text: str) -> None:
        try:
            say(text)
        except OSError:
            pass
    return tell


class _Run:
    """One run: the watchdog, the master (when none answers), roslaunch; stopped in the
    reverse order, however the run ends."""

    def __init__(self, launch_file: Path, env: dict[str, str], tell):
        self.launch_file, self.env, self.tell = launch_file, env, tell
        self.started: list[subprocess.Popen] = []
        self.roslaunch: subprocess.Popen | None = None
        self.errors = None            # launch_faults.ErrorPassage, once roslaunch runs
        self.launch_ended = False     # roslaunch ended by itself

    def run(self, duration: float | None) -> int:
        from . import watchdog
        from .stop_signals import Stopped, StopSignals
        mark = watchdog.new_mark()
        self.env[watchdog.VARIABLE] = mark   # on every process of the run
        guard = None
        with StopSignals() as signals:
            try:
                guard = watchdog.start(mark)
                status = self._launch(duration)
            except Stopped:
                status = None
                self.tell(f"sw2sim ros: {signals.name}: stopping the launch and its nodes")
            finally:
                signals.hold()
                self._stop()
                if guard:
                    watchdog.finish(guard)
        return self._verdict(status, signals)

    def _launch(self, duration: float | None) -> int | None:
        """Start the master (if needed) and the launch, and wait for the run's end; a
        status to return, or None for the verdict on the launch."""
        env = self.env
        given = uri = env.get("ROS_MASTER_URI")
        if not uri or not wire.master_answers(uri):
            port, told = master_address(uri)
            for line in told:
                self.tell(f"sw2sim ros: {line}")
            uri = env["ROS_MASTER_URI"] = f"http://127.0.0.1:{port}"
            self.started.append(subprocess.Popen(["roscore", "-p", str(port)], env=env,
                                                 start_new_session=True, preexec_fn=with_ctrl_c,
                                                 stdout=subprocess.DEVNULL,
                                                 stderr=subprocess.DEVNULL))
            deadline = time.monotonic() + 15
            while not wire.master_answers(uri):
                if time.monotonic() > deadline:
                    self.tell("sw2sim ros: roscore did not start")
                    return 2
                time.sleep(0.1)
        else:
            host, port = (_place(uri) + (None,))[:2]
            who = holder(port) if host == "127.0.0.1" and port else None
            self.tell(f"sw2sim ros: a ROS master already answers at {uri}"
                      + (f" (PID {who})" if who else "") + ": this run uses it, and leaves it "
                      "running at the end")
        from ..archive import shown
        from .launch_faults import ErrorPassage
        self.tell(f"sw2sim ros: {shown(self.launch_file) or self.launch_file} on {uri}, MuJoCo "
                  "standing in for Gazebo")
        self.tell("sw2sim ros: for ROS commands in another terminal, run there first: "
                  + _terminal_line(env, given))
        self.roslaunch = subprocess.Popen(["roslaunch", "--wait", str(self.launch_file)],
                                          env=env, start_new_session=True,
                                          preexec_fn=with_ctrl_c, stderr=subprocess.PIPE)
        self.started.append(self.roslaunch)
        self.errors = ErrorPassage(self.roslaunch.stderr)
        end = None if duration is None else time.monotonic() + duration
        while self.roslaunch.poll() is None:
            now = time.monotonic()
            if end is not None and now >= end:
                return None
            if self.errors.faults and now - self.errors.faults[0].at >= FAULT_SETTLE:
                return None
            time.sleep(0.1)
        self.launch_ended = True
        self.errors.wait(FAULT_SETTLE)   # its last lines, still in the pipe
        return None

    def _stop(self) -> None:
        """The launch first, then the master its nodes unregister from."""
        if self.errors:
            self.errors.stop_watching()
        for process in reversed(self.started):
            stop(process)
        if self.errors:
            self.errors.wait(STOP_WAIT)

    def _verdict(self, status: int | None, signals) -> int:
        faults = self.errors.faults if self.errors else []
        if faults:
            from .launch_faults import launch_nodes, summary
            for line in summary(faults, launch_nodes(self.launch_file, self.env)):
                self.tell(f"sw2sim ros: {line}")
        if signals.received:
            return signals.exit_status
        if status is not None:
            return status
        if faults:
            return 1
        code = self.roslaunch.returncode if self.roslaunch else None
        if self.launch_ended and code != 0:
            self.tell(f"sw2sim ros: roslaunch ended with exit code {code}; see the lines above")
            return 1
        return 0
