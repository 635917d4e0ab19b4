"""Commands written across lines as a reader types them (`\\` at a line's end, a YAML
message continued inside its quotes) run in CI exactly as shown: for every such command of
the blocks the ROS page runners run (data-ros, data-ros2) and of the ROS 2 blocks whose
names and message fields the tests check (data-ros2-needs), the runner's words
(course.snippets.ros.commands) are the words bash makes of the lines as written, up to the
spaces inside a YAML message, which YAML ignores."""

from __future__ import annotations

import re
import subprocess

from course.snippets import find_pages, parse_page
from course.snippets.parse import Block
from course.snippets.terminal import commands
from repository import ROOT

# Only plain words are handed to bash: nothing it would run or redirect. A variable
# ($SW2SIM_COURSE) and ~ are kept as written: bash is given each as its own name.
PLAIN = re.compile(r"(?:[^$`;|&<>()*?!\\]|\$[A-Za-z_]\w*)*")
VARIABLE = re.compile(r"\$([A-Za-z_]\w*)")


def bash_words(lines: str) -> list[str]:
    env = {name: f"${name}" for name in VARIABLE.findall(lines)} | {"HOME": "~"}
    done = subprocess.run(["bash", "--norc", "-c", f'printf "%s\\0" {lines}'], capture_output=True,
                          text=True, timeout=10, check=True, env=env)
    return done.stdout.split("\0")[:-1]


def continued(block) -> list[tuple[str, int]]:
    """Each command of the block written on more than one line: its lines, its first line."""
    found, lines, first = [], [], None
    for n, line in enumerate(block.code.split("\n"), start=block.line):
        if not lines and (not line.strip() or line.lstrip().startswith("#")):
            continue
        first = n if not lines else first
        lines.append(line)
        if not line.endswith("\\"):
            if len(lines) > 1:
                found.append(("\n".join(lines), first))
            lines = []
    return found


def spaced(words: list[str]) -> list[str]:
    return [" ".join(word.split()) for word in words]


def problems(block) -> tuple[int, list[str]]:
    """How many commands of the block are written across lines, and where the runner's
    words differ from bash's."""
    runs = {c.location: c for c in commands(block)}
    checked, found = 0, []
    for text, first in continued(block):
        if not PLAIN.fullmatch(text.replace("\\\n", "")):
            continue
        command = runs[f"{block.page}:{first}"]
        checked += 1
        if spaced(command.words) != spaced(bash_words(text)):
            found.append(f"{block.page}:{first}: the runner runs {command.words}, "
                         f"bash reads {bash_words(text)}")
    return checked, found


def test_a_command_across_lines_runs_as_bash_reads_it():
    checked, found = 0, []
    for path in find_pages(ROOT):
        page = parse_page(path, ROOT)
        needs = [block for block, _ in page.ros2_needs if block.language == "bash"]
        for block in page.commands + page.ros2_commands + needs:
            n, wrong = problems(block)
            checked, found = checked + n, found + wrong
    assert checked >= 8, f"only {checked} commands across lines found on the pages"
    assert not found, "\n".join(found)


def test_a_continuation_without_its_space_is_caught():
    """bash joins `example_1\\` and the unindented next line's `--effort-joints` into one
    word; the runner, which joins the lines with a space, would run two."""
    block = Block("page.md", 3, "sw2sim port examples/example_1 -o example_1\\\n"
                  "--effort-joints front_left_joint", ros2="example_1")
    checked, found = problems(block)
    assert checked == 1 and len(found) == 1 and "example_1--effort-joints" in found[0], found
