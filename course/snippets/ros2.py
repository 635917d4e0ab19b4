"""Run a page's ROS 2 blocks (`data-ros2`) in page order, as a reader following the page
with this site's tools would: `sw2sim port` writes the ROS 2 package, `sw2sim ros2` runs
it with MuJoCo in Gazebo Sim's place, and the page's rclpy nodes talk to it.

The reader's terminals are modelled one by one, as course.snippets.ros does for ROS 1: a
block is typed into terminal 1 unless its `data-terminal="N"` names another, and a block
typed into a terminal that a running command keeps busy stops it first (Ctrl-C). A terminal
opens in the reader's home folder with only a login's variables (HOME, PATH, LANG), reads
~/.bashrc as an interactive bash does, and runs Getting started's line for every ROS 2
terminal (its block marked `data-ros2-setup`); Getting started's line that the reader runs
once in the clone's folder (`data-ros2-once`) has run before, when the clone was made. The
clone holds copies of the example packages and this repository's .venv-ros2; several pages
can be followed in one clone and one home folder, one after the other (`clone`, `home`), as
Practice 2's page follows Practice 1's. What the pages create inside the clone is listed by
`created_in_clone()`.

A ```bash block is split into its commands (course.snippets.terminal.commands), each run
by bash in its terminal:

- `sw2sim ros2 PACKAGE` keeps running, as in a terminal of its own; the runner adds
  `--realtime` (simulated seconds per wall second) unless the page gives it;
- `python ~/ros2_ws/src/PACKAGE/scripts/NODE.py ...` starts a node of the page and goes
  on (it keeps its terminal busy): the node
  keeps running, or ends by itself with status 0 (a one-shot command). Followed by
  another command of its block, it runs to its end first (status 0, no error printed),
  as the terminal it is typed in gives the prompt back only then: a client that sends
  one goal and prints its result, before the next node starts;
- every other command (`sw2sim port`, `cd`, ...) must end with status 0; what it changes
  of the shell (`cd`, `export`) holds for the next of its terminal. A `sw2sim port ... -o
  FOLDER` tells the runner where the package is (`~` and `$NAME` read as bash reads them).

A ```python block is a node file of a ported package: `data-ros2` names the package (the
folder `sw2sim port ... -o FOLDER` wrote, found by its name), `data-file` the file in it.
The runner writes the block's code there when the page reaches it. A command may start a
node that another page shows (Practice 2 runs Practice 1's): it is there when that page
was followed in the same clone, else the runner takes its code from that page.

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
from .terminal import LOGIN_PATH, SETUP_PAGE, Command, Running, Terminal, commands

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


def terminal_lines(root: Path) -> tuple[Block, Block]:
    """Getting started's blocks for the ROS 2 pages: what the reader runs once in the
    clone's folder, and what every new terminal runs first."""
    page = parse_page(root / SETUP_PAGE, root)
    if page.ros2_once is None or page.ros2_setup is None:
        raise Ros2BlockError(SETUP_PAGE, "no ```bash blocks marked data-ros2-once and "
                                         "data-ros2-setup: the ROS 2 pages' terminals have "
                                         "nothing to start from")
    return page.ros2_once, page.ros2_setup


def expand(word: str, env: dict[str, str], cwd: Path) -> Path:
    """A path word of a command as bash reads it in `env` and `cwd`: `~` and `$NAME`."""
    if word == "~" or word.startswith("~/"):
        word = env.get("HOME", "") + word[1:]
    word = re.sub(r"\$\{(\w+)\}|\$(\w+)", lambda m: env.get(m[1] or m[2], ""), word)
    return Path(os.path.normpath(cwd / word))


@dataclass
class Session:
    """One page's ROS 2 blocks in the reader's clone and home folder, in one ROS 2 domain."""

    page: Page
    root: Path
    folder: Path      # the logs, and (unless given) the clone and the home folder
    domain: int       # ROS_DOMAIN_ID of every process of the page
    realtime: float = REALTIME
    clone: Path | None = None   # the reader's clone: shared by pages followed one after another
    home: Path | None = None    # the reader's home folder: so is it
    env: dict[str, str] = field(default_factory=dict)   # terminal 1's, once set up
    ran: list[str] = field(default_factory=list)        # "page.md:line: command"
    started: list[Running] = field(default_factory=list)
    written: dict[str, Block] = field(default_factory=dict)   # node files written, by path
    stopped: list[int] = field(default_factory=list)
    terminals: dict[int, Terminal] = field(default_factory=dict)
    packages: dict[str, Path] = field(default_factory=dict)   # name -> folder ported to
    printed: dict[str, str] = field(default_factory=dict)     # command -> what it printed
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
        """The reader's clone (a copy of each example package the page ports, and this
        repository's .venv-ros2), made once, with Getting started's once-only line run in
        it; the home folder; terminal 1, opened and set up."""
        if self.env:
            return
        self.clone = self.clone or self.folder / "clone"
        self.home = self.home or self.folder / "home"
        for block in self.page.ros2_commands:
            for command in commands(block):
                source = ported_source(command)
                if source and not (self.clone / source).exists():
                    shutil.copytree(self.root / source, self.clone / source)
        self.clone.mkdir(parents=True, exist_ok=True)
        venv = self.clone / ENVIRONMENT
        if not venv.exists():
            venv.symlink_to(self.root / ENVIRONMENT, target_is_directory=True)
        self.home.mkdir(parents=True, exist_ok=True)
        self.logs = self.folder / "logs"
        self.logs.mkdir(parents=True, exist_ok=True)
        once, self.setup = terminal_lines(self.root)
        done = self.home.parent / f".{self.home.name}-ros2-once"   # beside the home folder
        if not done.exists():
            t = Terminal(0, self.clone, self.login())
            for command in commands(once):
                self.finish(command, t)
            done.touch()
        self.env = self.terminal(1, f"{self.page.path}:1").env

    def login(self) -> dict[str, str]:
        """A new terminal's variables before it reads ~/.bashrc."""
        return environment(self.domain, {
            "HOME": str(self.home), "PATH": LOGIN_PATH, "LANG": "C.UTF-8",
            "USER": os.environ.get("USER", "reader"), "SHELL": "/bin/bash",
            # what a terminal shows at once; a log file would get it in blocks
            "PYTHONUNBUFFERED": "1"})

    def terminal(self, number: int, location: str) -> Terminal:
        """Terminal `number`, opened in the home folder and set up the first time it is
        used."""
        if number in self.terminals:
            return self.terminals[number]
        if number > 1 and number - 1 not in self.terminals:
            raise Ros2BlockError(location, f"terminal {number} before terminal {number - 1}: "
                                           "number the page's terminals in the order it opens "
                                           "them")
        t = Terminal(number, self.home, self.login())
        self.terminals[number] = t
        if (self.home / ".bashrc").is_file():   # an interactive bash reads it
            self.finish(Command("source ~/.bashrc", location, None), t)
        for command in commands(self.setup):
            self.finish(command, t)
        return t

    # -- the blocks --------------------------------------------------------------------
    def run(self) -> None:
        """Run every ROS 2 block of the page in order; raise Ros2BlockError at the first
        fault."""
        self.prepare()
        for block in self.page.ros2_blocks:
            if block.language == "bash":
                t = self.terminal(block.terminal, block.location)
                found = commands(block)
                for k, command in enumerate(found):
                    self.command(command, t, first=k == 0, last=k == len(found) - 1)
            else:
                self.write_node(block)

    def write_node(self, block: Block) -> None:
        if not block.data_file or block.data_file.startswith(("/", "..")):
            raise Ros2BlockError(block.location, "a ROS 2 node block names its file in the "
                                                 'package: {: data-ros2="example_1" '
                                                 'data-file="scripts/NODE.py"}')
        if block.ros2 not in self.packages:
            raise Ros2BlockError(block.location, f"no package {block.ros2}/ to put "
                                                 f"{block.data_file} in: port it first")
        path = self.packages[block.ros2] / block.data_file
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(block.code, encoding="utf-8")
        path.chmod(0o755)
        self.written[f"{block.ros2}/{block.data_file}"] = block

    def node_path(self, package: str, file: str) -> Path:
        """Where the page's node file `file` of the ported `package` is."""
        return self.packages[package] / file

    def command(self, command: Command, t: Terminal, first: bool = True,
                last: bool = True) -> None:
        words = command.words
        if not words:
            return
        if t.busy is not None:
            if not first:
                raise Ros2BlockError(command.location, f"terminal {t.number} is busy with "
                                                       f"`{t.busy.command.text}`: put this "
                                                       "command in a block of its own, typed "
                                                       "into another terminal (data-terminal)")
            from sw2sim.ros.run import descendants, stop
            self.stopped += [t.busy.process.pid, *descendants(t.busy.process.pid)]
            stop(t.busy.process)             # the reader's Ctrl-C, to type here
            t.busy = None
        if words[:2] == ["sw2sim", "ros2"]:
            text = command.text
            if "--realtime" not in words:
                text += f" --realtime {self.realtime:g}"
            t.busy = self.start(command, text, t)
            self.wait_until_up(t.busy)
        elif words[0] in ("python", "python3") and len(words) > 1 and words[1].endswith(".py"):
            self.ensure_node(command, t, words[1])
            if last:
                t.busy = self.start(command, command.text, t)
            else:   # the next command of the block is typed once this one has ended
                output = self.finish(command, t)
                if m := FAULTS.search(output):
                    raise Ros2BlockError(command.location, f"`{command.text}` printed a fault:"
                                                           f"\n{output[max(0, m.start() - 600):]}"
                                                           [:2500])
        else:
            self.printed[command.text] = self.finish(command, t)
            if words[:2] == ["sw2sim", "port"] and "-o" in words[:-1]:
                out = expand(words[words.index("-o") + 1], t.env, t.cwd)
                self.packages[out.name] = out
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

    def ensure_node(self, command: Command, t: Terminal, file: str) -> None:
        """The node file a command starts: written by this page (or an earlier one in the
        same clone), else taken from the page that shows it."""
        path = expand(file, t.env, t.cwd)
        if path.is_file():
            return
        for key, block in node_blocks(self.root).items():
            package, rel = key.split("/", 1)
            if package in self.packages and self.packages[package] / rel == path:
                self.write_node(block)
                return
        raise Ros2BlockError(command.location, f"`{command.text}`: no page shows {path} (a "
                                               "python block with data-ros2 and data-file, in "
                                               "a package the page ports)")

    def start(self, command: Command, text: str, t: Terminal) -> Running:
        log = self.logs / f"{len(self.ran):02d}-{_slug(command)}.log"
        started = Running(command, shell.start(text, t.cwd, t.env, log), log, t.number)
        self.started.append(started)
        return started

    def finish(self, command: Command, t: Terminal) -> str:
        """Run a command to its end in terminal `t`, and keep what it changed of the
        terminal's shell; what it printed."""
        try:
            ended = shell.finish(command.text, t.cwd, t.env, self.folder / "shell",
                                 COMMAND_TIMEOUT)
        except subprocess.TimeoutExpired:
            raise Ros2BlockError(command.location, f"`{command.text}` did not end within "
                                                   f"{COMMAND_TIMEOUT:g} s") from None
        if ended.done.returncode != 0:
            raise Ros2BlockError(command.location,
                                 f"`{command.text}` exited with {ended.done.returncode} in "
                                 f"terminal {t.number}:\n"
                                 f"{(ended.done.stdout + ended.done.stderr)[-1500:]}")
        # what the command exported holds, but ROS 2 stays on 127.0.0.1 in the session's
        # domain (the pages' `export ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST` included)
        t.cwd, t.env = ended.cwd, environment(self.domain, ended.env)
        return ended.done.stdout + ended.done.stderr

    def created_in_clone(self) -> list[str]:
        """What following the pages made inside the clone: every path there but the
        example packages' copies and the .venv-ros2 link, relative to the clone."""
        found = []
        for path in sorted(self.clone.rglob("*")):
            rel = path.relative_to(self.clone)
            if rel.parts[0] in ("examples", ENVIRONMENT):
                continue
            found.append(rel.as_posix() + ("/" if path.is_dir() else ""))
        return found

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
    """`examples/example_1` of `sw2sim port "$SW2SIM_COURSE/examples/example_1" -o ...`
    (or of `examples/example_1`), else None."""
    words = command.words
    if words[:2] == ["sw2sim", "port"] and len(words) > 2:
        if m := re.search(r"(?:^|/)(examples/[^/]+)/?$", words[2]):
            return m[1]
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
