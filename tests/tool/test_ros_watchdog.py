"""The watchdog of `sw2sim ros` (sw2sim.ros.watchdog), without ROS: when the process that
started it is killed, it stops every process carrying the run's mark, also those in
sessions of their own and those that ignore Ctrl-C; it leaves every other process alone,
and ends at once after a run that stopped everything itself."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

from sw2sim.ros import watchdog

# What `sw2sim ros` does, in small: the watchdog first, then processes with the mark, in
# sessions of their own (as roslaunch starts nodes); then it waits to be killed.
RUN = """
import os, subprocess, sys, time
from sw2sim.ros import watchdog
mark = sys.argv[1]
guard = watchdog.start(mark)
env = {**os.environ, watchdog.VARIABLE: mark}
sleeper = "import time; print(flush=True); time.sleep(120)"
deaf = ("import signal, time; signal.signal(signal.SIGINT, signal.SIG_IGN); print(flush=True); "
        "time.sleep(120)")
started = [subprocess.Popen([sys.executable, "-c", code], env=env, start_new_session=True,
                            stdout=subprocess.PIPE) for code in (sleeper, deaf)]
for process in started:
    process.stdout.readline()    # set up: the deaf one ignores SIGINT from now on
print(guard.pid, *(p.pid for p in started), flush=True)
time.sleep(120)
"""


def _running(pid: int) -> bool:
    try:
        return Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


def test_killing_the_run_stops_what_it_marked_and_nothing_else():
    mark = watchdog.new_mark()
    run = subprocess.Popen([sys.executable, "-c", RUN, mark], stdout=subprocess.PIPE,
                           stderr=subprocess.PIPE, text=True, start_new_session=True)
    other = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(120)"],
                             start_new_session=True)
    pids: list[int] = []
    try:
        pids = [int(p) for p in run.stdout.readline().split()]
        assert sorted(watchdog.marked(mark)) == sorted(pids[1:])
        run.kill()
        run.wait()
        deadline = time.monotonic() + 3 * watchdog.GRACE
        while any(_running(p) for p in pids) and time.monotonic() < deadline:
            time.sleep(0.05)
        assert not [p for p in pids if _running(p)], "the watchdog, and all it stopped, ended"
        assert _running(other.pid), "a process without the mark is left alone"
        said = run.stderr.read()
        assert "stopped 2 process(es) of the run" in said, said
    finally:
        for pid in [*pids, other.pid]:
            try:
                os.kill(pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
        other.wait()
        run.kill()
        run.wait()


def test_after_a_run_that_stopped_everything_it_ends_at_once_and_says_nothing(capfd):
    guard = watchdog.start(watchdog.new_mark())
    try:
        watchdog.finish(guard)
        assert guard.returncode == 0
        assert capfd.readouterr().err == ""
    finally:
        if guard.poll() is None:
            guard.kill()
            guard.wait()
