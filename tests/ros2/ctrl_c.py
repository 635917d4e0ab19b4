"""Ctrl-C on a lesson's ROS 2 node, as a reader presses it: SIGINT to the node's process
group while it runs against `sw2sim ros2`, once the node is in its loop taking messages
(spinning/sitecustomize.py says when), a random moment later. The node must end with status
0 and print no traceback and no [ERROR].

tests/ros2/test_ros2_page_blocks.py stops each node a few times on its page's run;
`tools/benchmark.py ctrl-c` stops each 50 times beside busy processes and counts."""

from __future__ import annotations

import os
import random
import re
import select
import signal
import subprocess
import time
from pathlib import Path

HOOK = Path(__file__).with_name("spinning")
FAULTS = re.compile(r"Traceback \(most recent call last\)|\[ERROR\]")
# The lesson nodes that run until Ctrl-C: the package `sw2sim port` writes, and the file
# the page saves in it.
NODES = (("example_1", "scripts/wheel_pulse.py"), ("example_3", "scripts/random_setpoints.py"),
         ("example_5", "scripts/ackermann.py"))
# The one-shot nodes, with their arguments: they end by themselves once they have sent their
# command, and are stopped while they wait for the controller they send it to (in a domain
# where nothing answers). Stopped, they end with 0 or 1 (move_arm.py: the goal was not
# reached).
ONE_SHOTS = (("example_3", "scripts/move_arm.py", ("0.5", "2")),
             ("example_4", "scripts/block_target.py", ("1.5",)),
             ("example_5", "scripts/drive_once.py", ("0.5", "0.3")))
UP_TIMEOUT = 60.0     # s for a node to reach its loop (a loaded machine imports slowly)
STOP_TIMEOUT = 10.0   # s for it to end after Ctrl-C


def stop_once(command: list[str], env: dict[str, str], cwd: Path,
              rng: random.Random | None = None, latest: float = 0.5,
              in_take: bool = False, statuses: tuple[int, ...] = (0,)) -> str | None:
    """Start `command` (a node), press Ctrl-C up to `latest` s after it spins, or with
    `in_take` while rclpy converts a /clock message it took (spinning/sitecustomize.py);
    None when it ended cleanly, else why not and what it printed."""
    rng = rng or random.Random()
    pythonpath = os.pathsep.join(filter(None, [str(HOOK), env.get("PYTHONPATH")]))
    extra = {"PYTHONPATH": pythonpath, **({"SW2SIM_CTRL_C_IN_TAKE": "1"} if in_take else {})}
    process = subprocess.Popen(command, cwd=cwd, env={**env, **extra},
                               stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                               start_new_session=True)
    printed = ""
    try:
        deadline = time.monotonic() + UP_TIMEOUT
        while "SPINNING\n" not in printed:
            if time.monotonic() > deadline or process.poll() is not None:
                return f"never reached its loop:\n{printed}{process.stdout.read()}"
            if select.select([process.stdout], [], [], 0.1)[0]:
                printed += process.stdout.readline()
        if not in_take:
            time.sleep(rng.uniform(0, latest))
            os.killpg(process.pid, signal.SIGINT)
        try:
            out, _ = process.communicate(timeout=STOP_TIMEOUT)
        except subprocess.TimeoutExpired:
            return f"still running {STOP_TIMEOUT:g} s after Ctrl-C:\n{printed}"
        printed += out
        if process.returncode not in statuses or FAULTS.search(printed):
            return f"ended with status {process.returncode}:\n{printed[-2500:]}"
        return None
    finally:
        if process.poll() is None:
            os.killpg(process.pid, signal.SIGKILL)
            process.communicate()
