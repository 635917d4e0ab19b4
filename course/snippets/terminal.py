"""What a reader's terminal holds, for the ROS page runners (ros.py, ros2.py): the commands
of a ```bash block as the reader types them, with the page line each starts on and what each
does to its terminal (keeps running, publishes once, plots, opens a window); the terminals
themselves; and Getting started's set-up that every new terminal runs first."""

from __future__ import annotations

import shlex
import subprocess
from dataclasses import dataclass
from pathlib import Path

from .parse import Block

# Programs that open a window: not run here, reported.
WINDOWS = frozenset({"rqt_plot", "rviz", "rqt", "rqt_graph", "rqt_console", "rqt_gui",
                     "rqt_publisher", "rqt_ez_publisher", "joint_state_publisher_gui"})


class RosBlockError(Exception):
    """A ROS block that did not do what the page says, at its page line."""

    def __init__(self, location: str, message: str):
        super().__init__(f"{location}: {message}")
        self.location = location


@dataclass
class Command:
    """One command of a ```bash block."""

    text: str
    location: str   # page.md:line of its first line
    package: str    # the block's data-ros: the package, or a folder beside it

    @property
    def words(self) -> list[str]:
        try:
            return shlex.split(self.text, comments=True)
        except ValueError:
            return self.text.split()

    @property
    def program(self) -> str:
        words = self.words
        if words[:1] == ["rosrun"] and len(words) >= 3:
            return words[2]
        return words[0] if words else ""

    @property
    def keeps_running(self) -> bool:
        w = self.words
        if w[:1] in (["roslaunch"], ["rosrun"], ["roscore"]):
            return True
        if w[:2] in (["rostopic", "echo"], ["rostopic", "hz"]):
            return True
        if self.plots:
            return "--duration" not in w
        return w[:2] == ["rostopic", "pub"] and not {"-1", "--once"} & set(w)

    @property
    def plots(self) -> bool:
        """`sw2sim plot`, which the pages give beside rqt_plot."""
        return self.words[:2] == ["sw2sim", "plot"]


    @property
    def publishes_once(self) -> bool:
        """`rostopic pub -1`: it publishes at once, then keeps the message latched for
        3 s before it returns."""
        w = self.words
        return w[:2] == ["rostopic", "pub"] and bool({"-1", "--once"} & set(w))


def commands(block: Block) -> list[Command]:
    """The commands of a bash block, with the page line each starts on."""
    found, text, first = [], "", None
    for n, line in enumerate(block.code.split("\n"), start=block.line):
        if first is None:
            if not line.strip() or line.lstrip().startswith("#"):
                continue
            first = n
        text += (line[:-1].strip() + " ") if line.endswith("\\") else line.strip()
        if not line.endswith("\\"):
            found.append(Command(text.strip(), f"{block.page}:{first}", block.ros))
            text, first = "", None
    return found


@dataclass
class Running:
    command: Command
    process: subprocess.Popen
    log: Path
    terminal: int = 1


@dataclass
class Terminal:
    """One of the reader's terminals: where its shell is, its variables, and the command
    that keeps it busy (None when the reader can type)."""

    number: int
    cwd: Path
    env: dict[str, str]
    busy: Running | None = None


# What a login shell has before the reader types anything (Debian's default PATH).
LOGIN_PATH = "/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin"
SETUP_PAGE = "_pages/reference/01-getting-started.md"
DEBIAN_PACKAGES = "/usr/share"   # where Debian's ROS packages are (rviz, robot_state_publisher)


def terminal_setup(root: Path) -> Block:
    """Getting started's block of what every new terminal runs (`data-ros-setup`)."""
    from .parse import parse_page
    block = parse_page(root / SETUP_PAGE, root).ros_setup
    if block is None:
        raise RosBlockError(SETUP_PAGE, "no ```bash block marked data-ros-setup: the ROS pages' "
                                        "terminals have nothing to start from")
    return block


def package_of(ros: str) -> str:
    """The package a `data-ros` value names: its first folder."""
    return ros.split("/", 1)[0]
