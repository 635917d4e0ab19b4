"""What `sw2sim ros` started is stopped when `sw2sim ros` ends, however it ends: also when
it is killed (SIGKILL) and cannot stop anything itself.

`sw2sim ros` starts this watchdog first, as a process of its own (in a session of its own,
so that a terminal's Ctrl-C or hang-up, meant for `sw2sim ros`, does not end it), and keeps
the writing end of a pipe to it. Every process the run starts gets a mark in its
environment, SW2SIM_ROS_RUN=<a new random value>. The watchdog blocks reading the pipe; the
pipe reaches its end when `sw2sim ros` exits for whatever reason, since no other process
holds that end (Python opens pipes close-on-exec, and subprocess closes the rest). Then the
watchdog finds every process whose /proc/PID/environ carries the mark, sends each SIGINT
(Ctrl-C: roslaunch stops its nodes, rospy nodes shut down cleanly), and SIGKILL to whatever
is left GRACE seconds later. After a normal end, `sw2sim ros` has already stopped
everything: the watchdog finds nothing and ends at once.

Why a mark in the environment, rather than the alternatives:
- Every process the run starts inherits it: roslaunch gives each node a copy of its own
  environment (roslaunch.core.setup_env copies os.environ), also to the nodes it starts in
  sessions of their own, where signalling roslaunch's process group does not reach them.
  A process stays marked after its parent dies and it is moved under PID 1, where a
  process tree read after `sw2sim ros` died no longer shows it.
- It is read only when needed. Snapshotting the tree below `sw2sim ros` every 0.2 s would
  walk /proc five times a second for the whole run and still miss a process started
  since the last snapshot.
- A process number can be reused by an unrelated process; each one is opened as a pidfd
  (which keeps referring to the same process) and its mark read again before it is sent a
  signal through that pidfd.
- PR_SET_PDEATHSIG is not inherited across fork(): it would reach roscore and roslaunch
  but none of the nodes, and roslaunch, asked to stop, gives a node 15 s after SIGINT and
  2 s after SIGTERM before SIGKILL; a killed roslaunch stops nothing. PR_SET_CHILD_SUBREAPER
  on `sw2sim ros` keeps orphans below it while it lives, but does nothing once it is
  killed.
A process that replaces its whole environment (`env -i`) is not found; neither roslaunch,
rosmaster nor the stand-in's nodes do that.

It is a script with the standard library only, run with `python -I`: it starts in a few
tens of milliseconds and depends on nothing that could fail to import.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
import uuid
from pathlib import Path

VARIABLE = "SW2SIM_ROS_RUN"
GRACE = 3.0         # s between SIGINT and SIGKILL; rosmaster and rospy nodes need < 1 s
POLL = 0.05         # s between looks at what is left
FINISH_WAIT = 2 * GRACE + 2.0   # s `sw2sim ros` waits for the watchdog at its end


def new_mark() -> str:
    """A value for VARIABLE that no other run has."""
    return uuid.uuid4().hex


def start(mark: str) -> subprocess.Popen:
    """The watchdog for the processes marked with `mark`, reading a pipe from this process."""
    return subprocess.Popen([sys.executable, "-I", str(Path(__file__).resolve()), mark],
                            stdin=subprocess.PIPE, start_new_session=True)


def finish(watchdog: subprocess.Popen) -> None:
    """At the end of a run: close the pipe (the watchdog then stops what is left, normally
    nothing) and wait for the watchdog to end."""
    try:
        watchdog.stdin.close()
    except OSError:
        pass
    try:
        watchdog.wait(timeout=FINISH_WAIT)
    except subprocess.TimeoutExpired:
        pass   # it ends on its own once it has stopped what it found


def _needle(mark: str) -> bytes:
    return f"\0{VARIABLE}={mark}\0".encode()


def _has(pid: int, needle: bytes) -> bool:
    """Whether process `pid` carries the mark. A zombie's environment reads as empty: it
    runs no more, its parent has only to collect it."""
    try:
        return needle in b"\0" + Path(f"/proc/{pid}/environ").read_bytes()
    except OSError:     # gone, or another user's
        return False


def marked(mark: str) -> list[int]:
    """The processes (other than this one) whose environment carries the mark."""
    needle, own = _needle(mark), os.getpid()
    return [int(entry.name) for entry in Path("/proc").glob("[0-9]*")
            if int(entry.name) != own and _has(int(entry.name), needle)]


def _send(pid: int, sig: int, needle: bytes) -> bool:
    """Signal `pid` if it is (still) a marked process; False when it is not."""
    try:
        handle = os.pidfd_open(pid)
    except OSError:
        return False
    try:
        if not _has(pid, needle):    # the number went to another process meanwhile
            return False
        signal.pidfd_send_signal(handle, sig)
        return True
    except OSError:
        return False
    finally:
        os.close(handle)


def _name(pid: int) -> str:
    """The program's name: the script's for `python3 /usr/bin/roslaunch ...`, the module's
    for `python -m sw2sim.ros.gzserver ...`."""
    try:
        words = Path(f"/proc/{pid}/cmdline").read_bytes().decode(errors="replace").split("\0")
    except OSError:
        return f"pid {pid}"
    words = [w for w in words if w]
    if words and Path(words[0]).name.startswith("python"):
        words = [w for w in words[1:] if not w.startswith("-")] or words
    return f"{Path(words[0]).name} (pid {pid})" if words else f"pid {pid}"


def sweep(mark: str, grace: float = GRACE) -> list[str]:
    """Stop every marked process: SIGINT, then SIGKILL after `grace` seconds to what is
    left. Processes that appear meanwhile (started by one that is stopping) get the same.
    Returns the names of the processes signalled."""
    needle = _needle(mark)
    names: dict[int, str] = {}
    for sig in (signal.SIGINT, signal.SIGKILL):
        sent: set[int] = set()
        deadline = time.monotonic() + grace
        while True:
            left = marked(mark)
            if not left:
                return list(names.values())
            for pid in left:
                if pid not in sent:
                    name = _name(pid)
                    if _send(pid, sig, needle):
                        sent.add(pid)
                        names.setdefault(pid, name)
            if time.monotonic() > deadline:
                break
            time.sleep(POLL)
    return list(names.values())


def main(argv: list[str]) -> int:
    mark = argv[0]
    # Asked to stop by a terminal or a script, `sw2sim ros` stops first; this one ends
    # after it, when the pipe closes.
    for sig in (signal.SIGINT, signal.SIGHUP):
        signal.signal(sig, signal.SIG_IGN)
    while sys.stdin.buffer.read(4096):
        pass
    stopped = sweep(mark)
    if stopped:
        try:
            print(f"sw2sim ros: stopped {len(stopped)} process(es) of the run that were still "
                  f"running when it ended: {', '.join(stopped)}", file=sys.stderr, flush=True)
        except OSError:
            pass    # no terminal to tell any more
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
