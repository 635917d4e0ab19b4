"""ROS 2 traffic never leaves this machine: the stand-in and an rclpy node, run under
strace, send to and connect to 127.0.0.1 (or local sockets) only."""

from __future__ import annotations

import re
import shutil
import subprocess

import pytest

from ros2_environment import PYTHON


CALL = re.compile(r"^\d+\s+(sendto|sendmsg|connect)\(.*")
ADDRESS = re.compile(r'inet_addr\("([^"]+)"\)|inet_pton\(AF_INET6, "([^"]+)"')


def destinations(trace: str) -> list[str]:
    found = []
    for line in trace.splitlines():
        if CALL.match(line) and ("AF_INET" in line):
            for v4, v6 in ADDRESS.findall(line):
                found.append(v4 or v6)
    return found


def test_the_standin_and_a_node_talk_over_loopback_only(ros2, ported_example_3):
    strace = shutil.which("strace")
    if strace is None:
        pytest.skip("strace is not installed (Debian: strace)")
    trace = ros2.home / "trace"
    ros2.start(strace, "-f", "-qq", "-e", "trace=sendto,sendmsg,connect", "-o", str(trace),
               str(PYTHON), "-m", "sw2sim", "ros2", str(ported_example_3), "--realtime", "0",
               "--duration", "40", name="standin")
    record_trace = ros2.home / "trace-recorder"
    process = subprocess.run([strace, "-f", "-qq", "-e", "trace=sendto,sendmsg,connect", "-o",
                              str(record_trace), str(PYTHON), str(ros2.here / "recorder.py"), "1"],
                             env=ros2.env, capture_output=True, text=True, timeout=60,
                             start_new_session=True)
    assert process.returncode == 0, process.stderr[-2000:]
    ros2.stop_all()
    seen = destinations(trace.read_text()) + destinations(record_trace.read_text())
    assert seen, "no datagrams were seen: the trace did not work"
    outside = sorted({a for a in seen if not (a.startswith("127.") or a == "::1")})
    assert not outside, f"sent to {outside}"
