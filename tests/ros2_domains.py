"""ROS 2 domain ids for tests, one per test that no other test holds at the same time:
not another xdist worker's, nor another test run's on this machine.

ROS 2 traffic stays on 127.0.0.1 here, so every process on the machine shares it: two tests
in one domain hear each other's topics (a trajectory meant for one stand-in reaches
another). A domain is claimed by an exclusive lock on a file named after it, held until
the test releases it or its process ends; the kernel drops the lock of a killed process.
The ids are 1 to 101, the ones the ROS 2 documentation calls safe on Linux: above 101 the
ports DDS derives from the id run into the range the kernel hands out to other sockets.
"""

from __future__ import annotations

import fcntl
import os
import tempfile
from pathlib import Path

FIRST, LAST = 1, 101
LOCKS = Path(tempfile.gettempdir()) / "sw2sim-test-ros2-domains"


class Domain:
    """A claimed domain id; `release()` (or the process's end) gives it back."""

    def __init__(self, number: int, handle) -> None:
        self.id = number
        self._handle = handle

    def release(self) -> None:
        if self._handle is not None:
            self._handle.close()   # closing the file drops its lock
            self._handle = None


def claim() -> Domain:
    """The first free domain id, looking from a place that differs by process, so that
    workers starting together rarely try the same files."""
    LOCKS.mkdir(exist_ok=True)
    count = LAST - FIRST + 1
    start = os.getpid() % count
    for step in range(count):
        number = FIRST + (start + step) % count
        handle = open(LOCKS / f"{number}.lock", "a")
        try:
            fcntl.flock(handle, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            handle.close()
            continue
        return Domain(number, handle)
    raise RuntimeError(f"every ROS 2 domain id from {FIRST} to {LAST} is held by a test "
                       f"(locks in {LOCKS}); are other test runs still going?")
