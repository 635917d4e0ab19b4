"""ROS 2 traffic never leaves this machine: the stand-in and an rclpy node given
sw2sim.ros2.discovery's environment, run under strace, bind every socket to 127.0.0.1 and
send to 127.0.0.1 (or local sockets) only, and /proc shows the stand-in's sockets on
127.0.0.1 alone. A node started as the pages tell a reader, with
ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST and no profile, finds the stand-in, and sends to
127.0.0.1 only too (its sockets are rmw_fastrtps's own, bound to 0.0.0.0: sw2sim.ros2.
discovery says why)."""

from __future__ import annotations

import json
import re
import shutil
import subprocess
from pathlib import Path

import pytest

from ros2_environment import PYTHON
from sw2sim.ros2 import discovery

CALL = re.compile(r"^\d+\s+(sendto|sendmsg|connect)\(.*")
BIND = re.compile(r"^\d+\s+bind\(\d+, \{sa_family=AF_INET6?,")
ADDRESS = re.compile(r'inet_addr\("([^"]+)"\)|inet_pton\(AF_INET6, "([^"]+)"')
TRACED = "trace=bind,sendto,sendmsg,connect"


def destinations(trace: str) -> list[str]:
    found = []
    for line in trace.splitlines():
        if CALL.match(line) and ("AF_INET" in line):
            for v4, v6 in ADDRESS.findall(line):
                found.append(v4 or v6)
    return found


def bound(trace: str) -> list[str]:
    """The addresses every bind asked for (also those that failed, or that strace shows
    unfinished while another thread runs)."""
    return [v4 or v6 for line in trace.splitlines() if BIND.match(line)
            for v4, v6 in ADDRESS.findall(line)]


def local(address: str) -> bool:
    return address.startswith("127.") or address == "::1"


def traced_child(tracer: int) -> int:
    """The process strace started (its first child)."""
    children = Path(f"/proc/{tracer}/task/{tracer}/children").read_text().split()
    assert children, f"strace ({tracer}) has no child"
    return int(children[0])


def test_the_standin_and_nodes_bind_and_talk_on_loopback_only(ros2, ported_example_3):
    strace = shutil.which("strace")
    if strace is None:
        pytest.skip("strace is not installed (Debian: strace)")
    trace = ros2.home / "trace"
    tracer = ros2.start(strace, "-f", "-qq", "-e", TRACED, "-o", str(trace), str(PYTHON),
                        "-m", "sw2sim", "ros2", str(ported_example_3), "--realtime", "0",
                        "--duration", "40", name="standin")
    # the reader's node: the pages' one setting, no profile
    reader_env = {k: v for k, v in ros2.env.items()
                  if k not in ("FASTRTPS_DEFAULT_PROFILES_FILE", "FASTDDS_DEFAULT_PROFILES_FILE")}
    reader_env["ROS_AUTOMATIC_DISCOVERY_RANGE"] = "LOCALHOST"
    recorders = {}
    for name, env in (("recorder", ros2.env), ("reader", reader_env)):
        recorders[name] = subprocess.Popen(
            [strace, "-f", "-qq", "-e", TRACED, "-o", str(ros2.home / f"trace-{name}"),
             str(PYTHON), str(ros2.here / "recorder.py"), "1"], env=env,
            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
            start_new_session=True)
        ros2.processes.append(recorders[name])
    heard = {}
    for name, process in recorders.items():
        out, err = process.communicate(timeout=60)
        assert process.returncode == 0, f"{name}: {err[-2000:]}\n{ros2.log('standin')}"
        heard[name] = json.loads(out)
    standin = traced_child(tracer.pid)
    sockets = discovery.sockets(standin)
    ros2.stop_all()

    for name, out in heard.items():   # both found the stand-in
        assert out["states"] and out["description"], name
    assert sockets, "/proc shows no socket of the stand-in"
    assert all(discovery.is_loopback(s) for s in sockets), f"the stand-in's sockets: {sockets}"
    ours = trace.read_text() + (ros2.home / "trace-recorder").read_text()
    binds = bound(ours)
    assert binds, "no bind was seen: the trace did not work"
    assert all(local(a) for a in binds), f"bound to {sorted(set(binds))}"
    seen = destinations(ours) + destinations((ros2.home / "trace-reader").read_text())
    assert seen, "no datagrams were seen: the trace did not work"
    outside = sorted({a for a in seen if not local(a)})
    assert not outside, f"sent to {outside}"
