"""Run a page's ROS blocks (`data-ros`) in page order under ROS 1, with sw2sim's stand-in in
Gazebo's place, as a reader following the page in terminals would.

The reader's terminals are modelled one by one. A block is typed into terminal 1 unless
its `data-terminal="N"` names another. A terminal is opened as a reader opens one: a
fresh bash with only a login's variables (HOME, a fresh folder; PATH; LANG) and the
master's address, in a folder laid out as the reader's clone of this repository (the
example packages as copies, `.venv` this repository's), where it first runs Getting
started's terminal set-up (its block marked `data-ros-setup`). Nothing else is given: what
a command needs must come from that set-up or from the page's own earlier commands in the
same terminal. The one liberty taken is speed: SW2SIM_REALTIME makes the stand-in run
REALTIME times faster than real time, and what the pages state is on simulated time.

A ```bash block is split into its commands (a line ending in `\\` goes on), each run by
bash as in that terminal. A terminal opens in the clone's folder, runs Getting started's
set-up, and goes to the folder its first block's `data-ros` names (`example_1`, the
package's copy, or `example_1/..`, the folder that holds it), as Getting started and the
pages tell the reader; from then on it stays where the page's commands leave it: what a
command changes of the shell (`cd`, `source devel/setup.bash`, `export`) holds for the
terminal's next command, in later blocks too. A command must not take Debian's packages
(/usr/share) off the terminal's ROS_PACKAGE_PATH.

A page whose front matter says what already runs (`ros_running: roslaunch example_1
gazebo.launch`, started on an earlier page) first replays, in its terminal 1, the bash
blocks of terminal 1 of the page that shows that command, up to it: the reader comes from
there, in that folder and shell.

- `roslaunch`, `rosrun`, `rostopic echo` and a `rostopic pub` without `-1` keep running and
  keep their terminal busy. A block typed into a busy terminal stops what runs there
  first, as the reader's Ctrl-C does; a command after one that keeps running, in the same
  block, is a page fault. After a launch the runner waits until the nodes it starts have
  registered and simulated time runs.
- `rostopic pub -1` sends its message at once and returns 3 s later (rostopic's
  _ONCE_DELAY, on the wall clock), with status 0; the runner goes on once it is sent.
- Every other command must end, with status 0 (`grep` may say 1: nothing found). Before a
  command that names a topic or a service, the runner waits until it exists, as a reader
  waits for Gazebo to come up.
- A command that opens a window (`rqt_plot`, `rviz`, a launch file that starts RViz) is
  not run; it is reported.
- `sw2sim plot` (rqt_plot's stand-in) without `--duration` keeps running and keeps its
  terminal busy, as in the reader's terminal; with no display here it draws into a PNG.
  At the end it must have plotted, and once stopped (`plots_written()`, after
  `close()`), have ended with status 0 and its PNG written. With `--duration` it is a
  command that ends.

A ```python block is a node file of the package (`data-file`): the page's commands start
it. At the end every node the page shows must be running, what keeps running must still
run, and no launch may have printed a traceback, an ERROR or a dead process.

Everything started runs in a process group of its own and is stopped by `close()`.
"""

from __future__ import annotations

import os
import re
import shlex
import shutil
import subprocess
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

from . import shell
from .parse import Block, Page
from .terminal import (DEBIAN_PACKAGES, LOGIN_PATH, WINDOWS, Command, RosBlockError, Running,
                       Terminal, commands, package_of, terminal_setup)

COMMAND_TIMEOUT = 30.0   # s for a command that ends, or for what it names to exist
SETTLE_TIMEOUT = 30.0    # s for a launch to come up
QUIET = 0.5              # s without a new node: the launch is up
# Simulated seconds per wall second. Ten times real time passes the pages' minutes of
# simulated time in seconds, while the simulation still leaves the machine's cores to
# the nodes (at 0, as fast as it goes, it would take a core of its own throughout).
REALTIME = 10.0
# What a launch must not print.
LAUNCH_FAULTS = re.compile(r"Traceback \(most recent call last\)|process has died|\[ERROR\]"
                           r"|^ERROR:", re.MULTILINE)
# roslaunch's colours and terminal titles, around its lines ("\x1b[31mERROR: ...")
TERMINAL_CODES = re.compile(r"\x1b\[[0-9;]*[A-Za-z]|\x1b\][^\x07]*\x07")


@dataclass
class Session:
    """One page's ROS blocks against one ROS master (`master`, its ROS_MASTER_URI)."""

    page: Page
    root: Path
    folder: Path          # the reader's clone: package copies, logs, HOME
    master_uri: str
    ran: list[str] = field(default_factory=list)
    windows: list[str] = field(default_factory=list)   # "page.md:line: command" not run
    plots: list[Running] = field(default_factory=list)   # every `sw2sim plot` started
    running: list[Running] = field(default_factory=list)
    nodes: list[Block] = field(default_factory=list)
    stopped: list[int] = field(default_factory=list)   # every process id it has stopped
    terminals: dict[int, Terminal] = field(default_factory=dict)
    # What each command that ended printed (standard output, then error), by page.md:line.
    printed: dict[str, str] = field(default_factory=dict)
    # Called with each command about to be typed, before anything of it (the Ctrl-C of
    # its block included) happens: a test's observer starts or ends listening there.
    before_command: Callable[[Command], None] | None = None

    def __enter__(self) -> Session:
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    # -- set-up ------------------------------------------------------------------------
    @property
    def earlier_pages(self) -> list[Page]:
        """The pages with ROS blocks before this one (by path: a practice numbers its
        pages in reading order)."""
        from .parse import find_pages, parse_page
        found = []
        for path in find_pages(self.root):
            if path.resolve() == (self.root / self.page.path).resolve():
                break
            page = parse_page(path, self.root)
            if page.ros_blocks:
                found.append(page)
        return found

    def prepare_packages(self, page: Page) -> None:
        """The packages `page` uses, copied into the reader's clone."""
        examples = self.folder / "examples"
        for name in sorted({package_of(b.ros) for b in page.ros_blocks}):
            if not (examples / name).exists():
                shutil.copytree(self.root / "examples" / name, examples / name)

    def prepare(self) -> None:
        """The reader's clone: the packages the page uses, copied, and this repository's
        `.venv` (made by `make setup`, as Getting started says)."""
        self.prepare_packages(self.page)
        venv = self.folder / ".venv"
        if not venv.exists():
            venv.symlink_to(self.root / ".venv", target_is_directory=True)
        self.home = self.folder / "home"
        self.home.mkdir(exist_ok=True)
        self.logs = self.folder / "logs"
        self.logs.mkdir(parents=True, exist_ok=True)
        self.setup = terminal_setup(self.root)

    def login(self) -> dict[str, str]:
        """A new terminal's variables before its set-up."""
        return {"HOME": str(self.home), "PATH": LOGIN_PATH, "LANG": "C.UTF-8",
                "USER": os.environ.get("USER", "reader"), "SHELL": "/bin/bash",
                "ROS_MASTER_URI": self.master_uri, "SW2SIM_REALTIME": f"{REALTIME:g}",
                # what a terminal shows at once; a log file would get it in blocks
                "PYTHONUNBUFFERED": "1"}

    def terminal(self, number: int, location: str, ros: str) -> Terminal:
        """Terminal `number`, opened the first time it is used: in the clone's folder, set
        up, then in the folder `ros` (the first block's data-ros) names."""
        if number in self.terminals:
            return self.terminals[number]
        if number > 1 and number - 1 not in self.terminals:
            raise RosBlockError(location, f"terminal {number} before terminal {number - 1}: "
                                          "number the page's terminals in the order it opens them")
        t = Terminal(number, self.folder, self.login())
        self.terminals[number] = t
        for command in commands(self.setup):
            self.finish(command, t)
        t.cwd = self.place(ros)
        return t

    # -- the blocks --------------------------------------------------------------------
    def run(self) -> None:
        """Run every ROS block of the page in order; raise RosBlockError at the first fault."""
        blocks = self.page.ros_blocks
        if not blocks:
            return
        self.prepare()
        if self.page.ros_running:
            self.replay(self.page.ros_running)
        for block in blocks:
            if block.language != "bash":
                self.node(block)
                continue
            t = self.terminal(block.terminal, block.location, block.ros)
            for n, command in enumerate(commands(block)):
                self.command(command, t, opens_block=n == 0)

    def replay(self, running: str) -> None:
        """What the page says already runs: terminal 1's blocks of the page that starts it,
        up to that command, typed into this page's terminal 1."""
        where = f"{self.page.path}:1 (ros_running)"
        words = shlex.split(running, comments=True)
        for page in self.earlier_pages:
            first = [b for b in page.ros_blocks if b.language == "bash" and b.terminal == 1]
            if not any(c.words == words for b in first for c in commands(b)):
                continue
            self.prepare_packages(page)
            for block in first:
                t = self.terminal(1, where, block.ros)
                for n, command in enumerate(commands(block)):
                    self.command(command, t, opens_block=n == 0)
                    if command.words == words:
                        return
        raise RosBlockError(where, f"`ros_running: {running}`: no page before this one starts "
                                   "it in its terminal 1; give the command as that page has it")

    def place(self, ros: str) -> Path:
        """The folder a block's `data-ros` names, in the reader's clone."""
        return (self.folder / "examples" / ros).resolve()

    def node(self, block: Block) -> None:
        shown, package = block.data_file or block.include, package_of(block.ros)
        if not shown or not shown.startswith(f"examples/{package}/"):
            raise RosBlockError(block.location, f"a ROS node block shows a file of examples/"
                                                f"{package}/ (include_code and data-file)")
        self.nodes.append(block)

    def command(self, command: Command, t: Terminal, opens_block: bool = True) -> None:
        """Type `command` into terminal `t`; the first of a block also changes to the
        block's folder, after a Ctrl-C of what keeps the terminal busy."""
        words = command.words
        if not words:
            return
        if self.before_command is not None:
            self.before_command(command)
        if t.busy is not None:
            if not opens_block:
                raise RosBlockError(command.location, f"terminal {t.number} is busy with "
                                    f"`{t.busy.command.text}`: put this command in a block "
                                    f"of its own, typed into another terminal "
                                    f"(data-terminal), and say so on the page")
            self.check_running()            # what it printed until now, faults included
            self._stop(t.busy)              # the reader's Ctrl-C, to type here
            self.running.remove(t.busy)
            t.busy = None
        if command.program in WINDOWS or self.launches_a_window(command, t):
            self.windows.append(f"{command.location}: {command.text} (opens a window)")
            return
        self.wait_for_names(command)
        if command.keeps_running:
            if words[0] == "roslaunch":
                self.stop_launches()
            t.busy = self.start(command, t)
            if words[0] == "roslaunch":
                self.settle(t.busy)
        elif command.publishes_once:
            self.published(self.start(command, t))
        else:
            self.finish(command, t)
        self.ran.append(f"{command.location}: {command.text}")

    def start(self, command: Command, t: Terminal) -> Running:
        log = self.logs / f"{len(self.running) + len(self.ran):02d}-{command.program}.log"
        running = Running(command, shell.start(command.text, t.cwd, t.env, log), log, t.number)
        self.running.append(running)
        if command.plots:
            self.plots.append(running)
        return running

    def finish(self, command: Command, t: Terminal) -> None:
        """Run a command to its end, and keep what it changed of the terminal's shell."""
        try:
            ended = shell.finish(command.text, t.cwd, t.env, self.folder / "shell",
                                 COMMAND_TIMEOUT)
        except subprocess.TimeoutExpired:
            raise RosBlockError(command.location, f"`{command.text}` did not end within "
                                                  f"{COMMAND_TIMEOUT:g} s") from None
        self.printed[command.location] = ended.done.stdout + ended.done.stderr
        allowed = (0, 1) if command.program == "grep" else (0,)
        if ended.done.returncode not in allowed:
            raise RosBlockError(command.location,
                                f"`{command.text}` exited with {ended.done.returncode} in "
                                f"terminal {t.number}:\n"
                                f"{(ended.done.stdout + ended.done.stderr)[-1500:]}")
        t.cwd, t.env = ended.cwd, ended.env
        packages = t.env.get("ROS_PACKAGE_PATH")
        if packages is not None and DEBIAN_PACKAGES not in packages.split(os.pathsep):
            raise RosBlockError(command.location,
                                f"after `{command.text}`, terminal {t.number}'s ROS_PACKAGE_PATH "
                                f"({packages}) has lost {DEBIAN_PACKAGES}, where Debian's ROS "
                                f"packages are (rviz, robot_state_publisher)")

    def launches_a_window(self, command: Command, t: Terminal) -> bool:
        """`roslaunch PACKAGE FILE` of a launch file that starts RViz or a GUI."""
        w = command.words
        if w[:1] != ["roslaunch"] or len(w) < 3:
            return False
        for top in (self.folder / "examples", Path(t.env.get("HOME", "/nonexistent"))):
            for launch in top.rglob(f"{w[1]}/launch/{w[2]}"):
                text = launch.read_text(errors="replace")
                if any(f'pkg="{gui}"' in text for gui in WINDOWS):
                    return True
        return False

    def published(self, r: Running) -> None:
        """Go on once `rostopic pub -1` has sent its message (it then holds it latched for
        subscribers for 3 s and returns; check() wants status 0 of it at the end)."""
        deadline = time.monotonic() + COMMAND_TIMEOUT
        while time.monotonic() < deadline:
            if "publishing and latching" in _tail(r.log):
                return
            if r.process.poll() not in (None, 0):
                raise RosBlockError(r.command.location, f"`{r.command.text}` exited with "
                                                        f"{r.process.returncode}:\n{_tail(r.log)}")
            time.sleep(0.05)
        raise RosBlockError(r.command.location, f"`{r.command.text}` published nothing in "
                                                f"{COMMAND_TIMEOUT:g} s:\n{_tail(r.log)}")

    # -- waiting like a reader ---------------------------------------------------------
    def master(self):
        import rosgraph
        return rosgraph.Master("/sw2sim_page_runner", master_uri=self.master_uri)

    def wait_for_names(self, command: Command) -> None:
        """Before a command that uses a topic or a service, wait until it exists."""
        w = command.words
        if w[:2] == ["rostopic", "pub"]:
            name, index = _first_name(w[2:]), 1          # someone subscribes
        elif w[:2] in (["rostopic", "echo"], ["rostopic", "hz"]):
            name, index = _first_name(w[2:]), 0          # someone publishes
        elif w[:2] == ["rosservice", "call"]:
            name, index = _first_name(w[2:]), 2
        else:
            return
        if not name:
            return
        deadline = time.monotonic() + COMMAND_TIMEOUT
        while time.monotonic() < deadline:
            self.check_running()
            state = self.master().getSystemState()
            # `rostopic echo /topic/field` names a field of the topic's message
            if any((entry[0] == name or name.startswith(entry[0] + "/")) and entry[1]
                   for entry in state[index]):
                return
            time.sleep(0.1)
        what = ("publisher of", "subscriber on", "service")[index]
        raise RosBlockError(command.location, f"`{command.text}`: no {what} {name} after "
                                              f"{COMMAND_TIMEOUT:g} s")

    def settle(self, launch: Running) -> None:
        """Wait until the launch's nodes have registered (none new for QUIET s) and the
        simulated clock runs."""
        deadline = time.monotonic() + SETTLE_TIMEOUT
        nodes, since = None, time.monotonic()
        while time.monotonic() < deadline:
            if launch.process.poll() is not None:
                raise RosBlockError(launch.command.location,
                                    f"`{launch.command.text}` ended:\n{_tail(launch.log)}")
            state = self.master().getSystemState()
            now = {n for entries in state for _, names in entries for n in names}
            if now != nodes:
                nodes, since = now, time.monotonic()
            clock = any(topic == "/clock" and pubs for topic, pubs in state[0])
            if clock and time.monotonic() - since >= QUIET:
                return
            time.sleep(0.1)
        raise RosBlockError(launch.command.location, f"`{launch.command.text}` did not come up "
                                                     f"in {SETTLE_TIMEOUT:g} s:\n{_tail(launch.log)}")

    # -- the end -----------------------------------------------------------------------
    def check_running(self) -> None:
        """What keeps running still runs, and no launch printed a fault."""
        for r in self.running:
            if r.process.poll() not in (None, 0):
                raise RosBlockError(r.command.location, f"`{r.command.text}` stopped with "
                                                        f"{r.process.returncode}:\n{_tail(r.log)}")
            if r.command.words[0] == "roslaunch":
                text = TERMINAL_CODES.sub("", r.log.read_text(errors="replace"))
                if m := LAUNCH_FAULTS.search(text):
                    start = max(0, m.start() - 600)
                    raise RosBlockError(r.command.location, f"`{r.command.text}` printed a "
                                                            f"fault:\n{text[start:m.end() + 900]}")

    def check(self) -> None:
        """At the end: everything still runs, every node the page shows runs, and every
        `rostopic echo` has printed a message."""
        self.check_running()
        from sw2sim.ros.run import descendants
        lines = []
        for r in self.running:
            for pid in [r.process.pid, *descendants(r.process.pid)]:
                try:
                    lines.append(Path(f"/proc/{pid}/cmdline").read_bytes().replace(b"\0", b" ")
                                 .decode(errors="replace"))
                except OSError:
                    pass
        for block in self.nodes:
            script = Path(block.data_file or block.include).name
            if not any(script in line for line in lines):
                raise RosBlockError(block.location, f"the node {script} is not running: no "
                                                    f"command of the page started it")
        for r in self.running:
            if r.command.words[:2] == ["rostopic", "echo"]:
                deadline = time.monotonic() + COMMAND_TIMEOUT
                while not r.log.stat().st_size and time.monotonic() < deadline:
                    time.sleep(0.1)
                if not r.log.stat().st_size:
                    raise RosBlockError(r.command.location, f"`{r.command.text}` printed nothing "
                                                            f"in {COMMAND_TIMEOUT:g} s")
        for r in self.running:
            if r.command.plots:
                self.plotting(r)

    def plotting(self, r: Running) -> None:
        """A `sw2sim plot` that keeps running has plotted."""
        deadline = time.monotonic() + COMMAND_TIMEOUT
        while "sw2sim plot: plotting" not in _tail(r.log) and time.monotonic() < deadline:
            if r.process.poll() is not None:
                break
            time.sleep(0.1)
        if "sw2sim plot: plotting" not in _tail(r.log):
            raise RosBlockError(r.command.location, f"`{r.command.text}` plotted nothing in "
                                                    f"{COMMAND_TIMEOUT:g} s:\n{_tail(r.log)}")

    def plots_written(self) -> list[Path]:
        """After close(): each `sw2sim plot` the reader's Ctrl-C (or a later block in its
        terminal) ended did so with status 0 and the PNG it names written; the PNGs."""
        pngs = []
        for r in self.plots:
            written = re.search(r"sw2sim plot: wrote (\S+\.png)", _tail(r.log))
            if r.process.poll() != 0 or not written:
                raise RosBlockError(r.command.location, f"`{r.command.text}` did not end with "
                                    f"its PNG on Ctrl-C (status {r.process.poll()}):\n"
                                    f"{_tail(r.log)}")
            pngs.append(self.place(r.command.package) / written[1])
        return pngs

    def stop_launches(self) -> None:
        launches = [r for r in self.running if r.command.words[0] == "roslaunch"]
        if launches:
            self.check_running()
            self._stop(*launches)
            self.running = [r for r in self.running if r not in launches]
            for t in self.terminals.values():
                if t.busy in launches:
                    t.busy = None

    def close(self) -> None:
        self._stop(*self.running)

    def _stop(self, *running: Running) -> None:
        """Stop them all at once, as closing their terminals would."""
        from sw2sim.ros.run import descendants, stop
        for r in running:
            self.stopped += [r.process.pid, *descendants(r.process.pid)]
        stop(*(r.process for r in running))

    def leftovers(self) -> list[int]:
        """The processes it started (and those below them) that still run after close()."""
        from sw2sim.ros.run import running
        return running(self.stopped)


def _first_name(words: list[str]) -> str:
    for word in words:
        if word.startswith("/"):
            return word
    return ""


def _tail(log: Path, size: int = 1500) -> str:
    try:
        return log.read_text(errors="replace")[-size:]
    except OSError:
        return ""


def ros_pages(pages: list[Page]) -> list[Page]:
    """The pages with ROS blocks."""
    return [p for p in pages if p.ros_blocks]


