"""The faults of a launch, read from roslaunch's error output as it passes to the user.

roslaunch keeps running when one of its nodes cannot start or dies: it prints a line and
goes on with the others (roslaunch/launch.py, roslaunch/pmon.py), and ends with status 0
once none is left. A simulation without its simulator or its controller then looks alive
but does nothing, and a script running `sw2sim ros --duration N` could not tell. So
`sw2sim ros` reads roslaunch's standard error (where roslaunch's printerrlog writes, and
where nodes with output="screen" write theirs), passes every line on to its own standard
error unchanged, as it comes, and watches for:

    ERROR: cannot launch node of type [PACKAGE/TYPE]: REASON
    [NAME-N] process has died [pid P, exit code C, cmd ...].
    ...REQUIRED process [NAME-N] has died!      (then "process has died [pid ..." alone)

(printerrlog wraps each in a colour escape, `\\033[31m...\\033[0m`; the watch reads past
it.) A node that ends with exit code 0 on its own (spawn_model, `rostopic pub -1`) is no
fault: roslaunch says "process has finished cleanly" on standard output.

Only standard error is read: standard output, where roslaunch and the nodes print most,
stays the terminal itself, so that it is shown as before, and a Python process writing to
it keeps the line buffering a terminal gives it. Python's standard error is line buffered
also into a pipe, so roslaunch's error lines arrive as they are printed.

The summary names the node with its package and type as the launch file gives them,
read with roslaunch's own loader (the names in roslaunch's lines are NAME-N, the node's
name with a counter; "cannot launch" names the type only).
"""

from __future__ import annotations

import contextlib
import io
import os
import re
import signal
import threading
import time
from dataclasses import dataclass
from pathlib import Path

_ESCAPE = re.compile(r"\x1b\[[0-9;]*[A-Za-z]")
_NOT_STARTED = re.compile(r"^ERROR: cannot launch node of type \[(?P<package>[^/\]]+)/"
                          r"(?P<type>[^\]]+)\]: (?P<reason>.*)$")
_DIED = re.compile(r"^(?:\[(?P<process>[^\]\s]+)\] )?process has died \[pid \d+, "
                   r"exit code (?P<code>-?\d+), cmd .*\]\.?$")
_REQUIRED = re.compile(r"REQUIRED process \[(?P<process>[^\]\s]+)\] has died!")


@dataclass
class Fault:
    """A node that could not start (`code` None) or died with a non-zero exit code."""
    process: str | None = None   # roslaunch's name for the process: NAME-N
    package: str | None = None   # given by "cannot launch node of type [PACKAGE/TYPE]"
    type: str | None = None
    code: int | None = None
    reason: str = ""
    at: float = 0.0              # time.monotonic() when it was read

    @property
    def node(self) -> str | None:
        """The node's name (with its namespace, no leading /), from NAME-N."""
        return self.process.rsplit("-", 1)[0] if self.process else None


class FaultReader:
    """Reads roslaunch's error lines one at a time and keeps the faults."""

    def __init__(self):
        self.faults: list[Fault] = []
        self._required: str | None = None   # REQUIRED process [...]: its "died" line follows

    def read(self, line: str) -> Fault | None:
        text = _ESCAPE.sub("", line).strip()
        fault = None
        if m := _NOT_STARTED.match(text):
            fault = Fault(package=m["package"], type=m["type"], reason=m["reason"].strip())
        elif m := _REQUIRED.search(text):
            self._required = m["process"]
        elif m := _DIED.match(text):
            process = m["process"] or self._required
            self._required = None
            if int(m["code"]) != 0:
                fault = Fault(process=process, code=int(m["code"]))
        if fault:
            fault.at = time.monotonic()
            self.faults.append(fault)
        return fault


class ErrorPassage:
    """roslaunch's standard error, passed line by line to this process's (file descriptor
    2, unbuffered) by a thread, and read by a FaultReader until `stop_watching()`."""

    def __init__(self, stream, out: int = 2):
        self.reader = FaultReader()
        self._stream, self._out = stream, out
        self._watching = True
        self._thread = threading.Thread(target=self._pass, name="roslaunch stderr", daemon=True)
        self._thread.start()

    @property
    def faults(self) -> list[Fault]:
        return self.reader.faults

    def stop_watching(self) -> None:
        """The run is stopping: lines about nodes that end now are no faults."""
        self._watching = False

    def wait(self, timeout: float) -> None:
        """Until roslaunch's error output ends (it and its nodes are gone), at most `timeout` s."""
        self._thread.join(timeout)

    def _pass(self) -> None:
        shown = True
        for line in iter(self._stream.readline, b""):
            if shown:
                shown = _write(self._out, line)
            if self._watching:
                self.reader.read(line.decode("utf-8", errors="replace"))
        self._stream.close()


def _write(fd: int, data: bytes) -> bool:
    """All of `data` to `fd`; False once that fails (the terminal is gone): the lines are
    then still read, so that roslaunch never blocks on a full pipe."""
    try:
        while data:
            data = data[os.write(fd, data):]
        return True
    except OSError:
        return False


def launch_nodes(launch_file: Path, env: dict[str, str]) -> list[tuple[str, str, str]]:
    """(name, package, type) of each node the launch file starts, in its order, as
    roslaunch loads it with `env` (for $(find), $(env) and $(optenv)); empty when it cannot
    be loaded here."""
    saved = dict(os.environ)
    try:
        os.environ.clear()
        os.environ.update(env)
        import rosgraph.names
        import roslaunch.config
        with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
            config = roslaunch.config.load_config_default([str(launch_file)], None)
        return [(rosgraph.names.ns_join(n.namespace, n.name).lstrip("/"), n.package, n.type)
                for n in config.nodes]
    except Exception:   # roslaunch's loader raises many kinds; roslaunch has said why
        return []
    finally:
        os.environ.clear()
        os.environ.update(saved)


def _exit(code: int) -> str:
    if code < 0:
        try:
            return f"killed by {signal.Signals(-code).name} (exit code {code})"
        except ValueError:
            pass
    return f"exit code {code}"


def _reason(fault: Fault) -> str:
    # rospkg's ResourceNotFound says only the package's name (then the ROS paths)
    if fault.reason == fault.package:
        return (f"there is no package {fault.package} on ROS_PACKAGE_PATH (check the node's "
                f"pkg= in the launch file)")
    return fault.reason


def summary(faults: list[Fault], nodes: list[tuple[str, str, str]]) -> list[str]:
    """One line per fault, naming the node with its package and type."""
    types = {name: f"{package}/{kind}" for name, package, kind in nodes}
    unnamed = [(name, f"{package}/{kind}") for name, package, kind in nodes]
    lines = []
    for fault in faults:
        if fault.code is None:
            kind = f"{fault.package}/{fault.type}"
            # roslaunch says this once per node of that type, in the launch file's order
            name = next((n for n, k in unnamed if k == kind), None)
            if name is not None:
                unnamed.remove((name, kind))
                lines.append(f"could not start node {name} ({kind}): {_reason(fault)}")
            else:
                lines.append(f"could not start a node of type {kind}: {_reason(fault)}")
        else:
            node = fault.node or "(unnamed)"
            kind = f" ({types[node]})" if node in types else ""
            lines.append(f"node {node}{kind} died: {_exit(fault.code)}; see the lines above")
    return lines
