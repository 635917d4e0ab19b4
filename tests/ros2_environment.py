"""The ROS 2 environment the tests run `sw2sim ros2`, the pages' rclpy nodes and colcon in:
.venv-ros2, which `make setup` makes (Makefile). ROS 2's message packages share their
module names with ROS 1's (std_msgs, sensor_msgs, ...), which the tests' own environment
reaches from Debian, so ROS 2 runs only in processes of that other Python."""

from __future__ import annotations

import subprocess
from functools import cache

from repository import ROOT

VENV = ROOT / ".venv-ros2"
PYTHON = VENV / "bin" / "python"
COLCON = VENV / "bin" / "colcon"


@cache
def missing() -> str | None:
    """Why ROS 2 cannot run here, or None when it can."""
    if not PYTHON.exists():
        return (f"no ROS 2 environment at {VENV.relative_to(ROOT)}: `make setup` makes it "
                "where PyPI has ROS 2 Jazzy's wheels for this Python and CPU (Linux)")
    done = subprocess.run([str(PYTHON), "-c", "import sw2sim.ros2 as r; print(r.missing() or '')"],
                          capture_output=True, text=True, timeout=60)
    if done.returncode != 0:
        return f"{PYTHON} cannot import sw2sim.ros2: {done.stderr.strip()[-300:]}"
    return done.stdout.strip() or None


def run(code: str, *args: str, timeout: float = 120) -> subprocess.CompletedProcess:
    """Python code run by the ROS 2 environment's Python."""
    return subprocess.run([str(PYTHON), "-c", code, *args], capture_output=True, text=True,
                          timeout=timeout, cwd=ROOT)
