"""Ctrl-C reaches what the ROS tests and `sw2sim ros` start, even when they themselves
run where it is ignored (in the background of a shell without job control): otherwise
every stop would wait for its timeout and end with SIGKILL, nodes unclean."""

from __future__ import annotations

import signal
import sys
import time

from sw2sim.ros.run import STOP_WAIT, stop


def test_a_process_started_where_ctrl_c_is_ignored_still_stops_on_it(ros):
    previous = signal.signal(signal.SIGINT, signal.SIG_IGN)   # as a background job has it
    try:
        sleeper = ros.start(sys.executable, "-c", "import time; time.sleep(60)", name="sleeper")
    finally:
        signal.signal(signal.SIGINT, previous)
    time.sleep(0.5)   # past Python's start, into the sleep
    began = time.monotonic()
    stop(sleeper)
    assert sleeper.returncode == -signal.SIGINT, "stopped by Ctrl-C, not killed"
    assert time.monotonic() - began < STOP_WAIT
