"""Run a page's ROS 2 blocks (`data-ros2`) in page order, as a reader following the page
with this site's tools would: `sw2sim port` writes the ROS 2 package, `sw2sim ros2` runs
it with MuJoCo in Gazebo Sim's place, and the page's rclpy nodes talk to it.

A ```bash block is split into its commands (course.snippets.ros.commands), each run by
bash in the session's folder, which holds a copy of the example packages the page ports:

- `sw2sim ros2 PACKAGE` keeps running, as in a terminal of its own; the runner adds
  `--realtime` (simulated seconds per wall second) unless the page gives it;
- `python PACKAGE/scripts/NODE.py ...` starts a node of the page and goes on: the node
  keeps running, or ends by itself with status 0 (a one-shot command). Followed by
  another command of its block, it runs to its end first (status 0, no error printed),
  as the terminal it is typed in gives the prompt back only then: a client that sends
  one goal and prints its result, before the next node starts;
- every other command (`sw2sim port`, `cd`, ...) must end with status 0; what it changes
  of the shell (`cd`, `export`) holds for the next.

A ```python block is a node file of a ported package: `data-ros2` names the package (the
folder `sw2sim port` wrote), `data-file` the file in it. The runner writes the block's
code there when the page reaches it. A command may start a node that another page shows
(Practice 2 runs Practice 1's); the runner takes its code from that page.

Every process runs with ROS 2 kept on 127.0.0.1 in the session's own domain id, in a
process group of its own, and `close()` stops them all, also after a failure. A page's
`export ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST` gives way to sw2sim.ros2.discovery's
setting, which keeps every socket on 127.0.0.1 where LOCALHOST alone does not
(tests/ros2/test_loopback.py runs a node with LOCALHOST alone against `sw2sim ros2`).
Blocks marked `data-ros2-needs` (ROS 2 Jazzy's own `ros2` command, Gazebo Sim) are not
run.
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

from . import shell
from .parse import Block, Page, find_pages, parse_page
from .ros import Command, Running, commands

# The Python environment the entry page has the reader make for ROS 2 (`make setup` makes
# it in a clone): ROS 2's message packages share their module names with ROS 1's, so they
# live apart from .venv, which reaches ROS 1 from Debian.
ENVIRONMENT = ".venv-ros2"
COMMAND_TIMEOUT = 60.0   # s for a command that ends (sw2sim port included)
# Simulated seconds per wall second: fast enough to keep the tests short, slow enough for
# the nodes (which see the clock through /clock) to keep up.
REALTIME = 5.0
# What no process of the page may print.
FAULTS = re.compile(r"Traceback \(most recent call last\)|\[ERROR\]", re.MULTILINE)


class Ros2BlockError(Exception):
    """A ROS 2 block that did not do what the page says, at its page line."""

    def __init__(self, location: str, message: str):
        super().__init__(f"{location}: {message}")
        self.location = location


def environment(domain: int, base: dict[str, str]) -> dict[str, str]:
    """`base` with ROS 2 kept on this machine, in domain `domain`."""
    from sw2sim.ros2.discovery import environment as ros2_environment
    return ros2_environment(domain, base)


@dataclass
class Session:
    """One page's ROS 2 blocks in one folder and one ROS 2 domain."""

    page: Page
    root: Path
    folder: Path      # where the packages are copied and ported, and the logs go
    domain: int       # ROS_DOMAIN_ID of every process of the page
    realtime: float = REALTIME
    env: dict[str, str] = field(default_factory=dict)
    ran: list[str] = field(default_factory=list)        # "page.md:line: command"
    started: list[Running] = field(default_factory=list)
    written: dict[str, Block] = field(default_factory=dict)   # node files written, by path
    stopped: list[int] = field(default_factory=list)
    cwd: Path | None = None
    # Called once `sw2sim ros2` has started, before the next command: it returns when the
    # simulation is up, as a reader looks before starting a node in a second terminal.
    # Without it the runner waits for the stand-in's line naming its controllers.
    simulation_up: Callable[[], None] | None = None

    def __enter__(self) -> Session:
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    # -- set-up ------------------------------------------------------------------------
    def prepare(self) -> None:
        """The folder with a copy of each example package the page ports, the logs, and
        the environment: the ROS 2 environment's scripts first on PATH (`python`,
        `sw2sim`), as activating it does."""
        if self.env:
            return
        self.folder.mkdir(parents=True, exist_ok=True)
        for block in self.page.ros2_commands:
            for command in commands(block):
                source = ported_source(command)
                if source and not (self.folder / source).exists():
                    shutil.copytree(self.root / source, self.folder / source)
        self.logs = self.folder / "logs"
        self.logs.mkdir(exist_ok=True)
        home = self.folder / "home"
        home.mkdir(exist_ok=True)
        bin_dir = str(self.root / ENVIRONMENT / "bin")
        base = {**os.environ, "PATH": os.pathsep.join([bin_dir, os.environ.get("PATH", "")]),
                "HOME": str(home), "ROS_HOME": str(home / ".ros"),
                "ROS_LOG_DIR": str(self.logs / "ros"), "PYTHONUNBUFFERED": "1"}
        self.env = environment(self.domain, base)
        self.cwd = self.folder

    # -- the blocks --------------------------------------------------------------------
    def run(self) -> None:
        """Run every ROS 2 block of the page in order; raise Ros2BlockError at the first
        fault."""
        self.prepare()
        for block in self.page.ros2_blocks:
            if block.language == "bash":
                found = commands(block)
                for k, command in enumerate(found):
                    self.command(command, last=k == len(found) - 1)
            else:
                self.write_node(block)

    def write_node(self, block: Block) -> None:
        if not block.data_file or block.data_file.startswith(("/", "..")):
            raise Ros2BlockError(block.location, "a ROS 2 node block names its file in the "
                                                 'package: {: data-ros2="example_1" '
                                                 'data-file="scripts/NODE.py"}')
        path = self.folder / block.ros2 / block.data_file
        if not path.parent.parent.is_dir():
            raise Ros2BlockError(block.location, f"no package {block.ros2}/ to put "
                                                 f"{block.data_file} in: port it first")
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(block.code, encoding="utf-8")
        path.chmod(0o755)
        self.written[f"{block.ros2}/{block.data_file}"] = block

    def node_path(self, package: str, file: str) -> Path:
        """Where the page's node file `file` of the ported `package` is."""
        return self.folder / package / file

    def command(self, command: Command, last: bool = True) -> None:
        words = command.words
        if not words:
            return
        if words[:2] == ["sw2sim", "ros2"]:
            text = command.text
            if "--realtime" not in words:
                text += f" --realtime {self.realtime:g}"
            self.wait_until_up(self.start(command, text))
        elif words[0] in ("python", "python3") and len(words) > 1 and words[1].endswith(".py"):
            self.ensure_node(command, words[1])
            if last:
                self.start(command, command.text)
            else:   # the next command of the block is typed once this one has ended
                output = self.finish(command)
                if m := FAULTS.search(output):
                    raise Ros2BlockError(command.location, f"`{command.text}` printed a fault:"
                                                           f"\n{output[max(0, m.start() - 600):]}"
                                                           [:2500])
        else:
            self.finish(command)
        self.ran.append(f"{command.location}: {command.text}")

    def wait_until_up(self, standin: Running) -> None:
        if self.simulation_up:
            self.simulation_up()
            return
        deadline = time.monotonic() + COMMAND_TIMEOUT
        while "controllers:" not in _tail(standin.log):
            if standin.process.poll() is not None or time.monotonic() > deadline:
                raise Ros2BlockError(standin.command.location, f"`{standin.command.text}` did "
                                                               f"not come up:\n{_tail(standin.log)}")
            time.sleep(0.05)

    def ensure_node(self, command: Command, file: str) -> None:
        """The node file a command starts: written by this page, else taken from the page
        that shows it."""
        path = (self.cwd / file).resolve()
        if path.is_file():
            return
        relative = os.path.relpath(path, self.folder)
        block = node_blocks(self.root).get(relative)
        if block is None:
            raise Ros2BlockError(command.location, f"`{command.text}`: no page shows "
                                                   f"{relative} (a python block with "
                                                   f"data-ros2 and data-file)")
        self.write_node(block)

    def start(self, command: Command, text: str) -> Running:
        log = self.logs / f"{len(self.ran):02d}-{_slug(command)}.log"
        started = Running(command, shell.start(text, self.cwd, self.env, log), log)
        self.started.append(started)
        return started

    def finish(self, command: Command) -> str:
        """Run a command to its end, and keep what it changed of the shell; what it
        printed."""
        try:
            ended = shell.finish(command.text, self.cwd, self.env, self.folder / "shell",
                                 COMMAND_TIMEOUT)
        except subprocess.TimeoutExpired:
            raise Ros2BlockError(command.location, f"`{command.text}` did not end within "
                                                   f"{COMMAND_TIMEOUT:g} s") from None
        if ended.done.returncode != 0:
            raise Ros2BlockError(command.location,
                                 f"`{command.text}` exited with {ended.done.returncode}:\n"
                                 f"{(ended.done.stdout + ended.done.stderr)[-1500:]}")
        # what the command exported holds, but ROS 2 stays on 127.0.0.1 in the session's
        # domain (the pages' `export ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST` included)
        self.cwd, self.env = ended.cwd, environment(self.domain, ended.env)
        return ended.done.stdout + ended.done.stderr

    # -- the end -----------------------------------------------------------------------
    def check(self) -> None:
        """Whatever the page started still runs, or ended by itself with status 0, and
        none of it printed a traceback or an error."""
        for s in self.started:
            status = s.process.poll()
            text = _tail(s.log, 100_000)
            if status not in (None, 0):
                raise Ros2BlockError(s.command.location, f"`{s.command.text}` stopped with "
                                                         f"{status}:\n{text[-1500:]}")
            if status == 0 and s.command.words[:2] == ["sw2sim", "ros2"]:
                raise Ros2BlockError(s.command.location, f"`{s.command.text}` ended early:"
                                                         f"\n{text[-1500:]}")
            if m := FAULTS.search(text):
                raise Ros2BlockError(s.command.location, f"`{s.command.text}` printed a fault:"
                                                         f"\n{text[max(0, m.start() - 600):]}"
                                                         [:2500])

    def stopped_cleanly(self) -> None:
        """After close(): nothing the page started printed a traceback on its way out (a
        node must end on Ctrl-C without one)."""
        for s in self.started:
            text = _tail(s.log, 100_000)
            if m := FAULTS.search(text):
                raise Ros2BlockError(s.command.location, f"`{s.command.text}` printed a fault "
                                                         f"when stopped with Ctrl-C:\n"
                                                         f"{text[m.start():][:2000]}")

    def close(self) -> None:
        from sw2sim.ros.run import descendants, stop
        running = [s.process for s in self.started]
        for process in running:
            self.stopped += [process.pid, *descendants(process.pid)]
        stop(*running)

    def leftovers(self) -> list[int]:
        """The processes it started (and those below them) still running after close()."""
        from sw2sim.ros.run import running
        return running(self.stopped)


def ported_source(command: Command) -> str | None:
    """`examples/example_1` of `sw2sim port examples/example_1 -o ...`, else None."""
    words = command.words
    if words[:2] == ["sw2sim", "port"] and len(words) > 2 and words[2].startswith("examples/"):
        return words[2].rstrip("/")
    return None


def node_blocks(root: Path) -> dict[str, Block]:
    """Every ROS 2 node file the pages show, by `PACKAGE/FILE`."""
    found = {}
    for path in find_pages(root):
        for block in parse_page(path, root).blocks:
            if block.ros2 and block.data_file:
                found[f"{block.ros2}/{block.data_file}"] = block
    return found


def ros2_pages(pages: list[Page]) -> list[Page]:
    """The pages with ROS 2 blocks."""
    return [p for p in pages if p.ros2_blocks]


def _slug(command: Command) -> str:
    words = command.words
    name = Path(words[1]).stem if words[0].startswith("python") and len(words) > 1 else \
        "-".join(words[:2])
    return re.sub(r"[^\w.-]", "_", name)


def _tail(log: Path, size: int = 1500) -> str:
    try:
        return log.read_text(errors="replace")[-size:]
    except OSError:
        return ""
