"""Run a page's blocks in a fresh Python process and say where it failed."""

from __future__ import annotations

import json
import os
import select
import signal
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from sw2sim import gl

from .parse import Block, Page, ParseError

CHILD = Path(__file__).resolve().with_name("child.py")
# Time between the child's own stack dump and the parent's kill on a timeout.
DUMP_GRACE = 1.0
# Interpreter start-up may be slow on a busy machine: never hold it to a tiny block limit.
STARTUP_LIMIT = 60.0
# Longest stretch of a failing block's output kept in a report.
OUTPUT_LIMIT = 20_000


@dataclass
class Failure:
    """Why a page stopped."""

    block: Block  # the block that was running
    line: int  # page line of the failing statement (the block's line if unknown)
    message: str  # "ValueError: bad value", "block timed out after 5 s", ...
    include: str | None = None  # "examples/x.py:12" when the error is in an included file
    traceback: str = ""
    output: str = ""  # what the block printed, to stdout and stderr

    @property
    def headline(self) -> str:
        where = f"{self.block.page}:{self.line}: "
        if self.include:
            where += f"{self.include}: "
        return where + self.message


@dataclass
class PageResult:
    """Outcome of one page."""

    page: Page
    ran: list[Block] = field(default_factory=list)  # blocks that finished without error
    failure: Failure | None = None
    errors: list[ParseError] = field(default_factory=list)  # page mistakes; nothing ran
    seconds: float = 0.0

    @property
    def ok(self) -> bool:
        return self.failure is None and not self.errors


def child_command(job: Path, report_fd: int) -> list[str]:
    """The child's command line.

    child.py runs as a file, not as `-m course.snippets.child`: importing the sw2sim package
    would load its dependencies (and settle MUJOCO_GL) before the page's first line, which a
    reader's fresh interpreter does not do. `-c` also gives sys.path[0] == "" (the working
    directory), as in an interactive interpreter.
    """
    boot = "import runpy, sys; sys.argv = sys.argv[1:]; runpy.run_path(sys.argv[0], run_name='__main__')"
    return [sys.executable, "-c", boot, str(CHILD), str(job), str(report_fd)]


def child_env() -> dict[str, str]:
    """Environment of the child: off-screen rendering, no GUI windows, unbuffered output."""
    env = dict(os.environ)
    gl.choose(env)
    env["MPLBACKEND"] = "Agg"
    env["PYTHONUNBUFFERED"] = "1"  # keeps stdout and stderr in order in the capture
    env["PYTHONFAULTHANDLER"] = "1"  # a crash prints the page line it happened at
    return env


def run_page(page: Page, root: Path, timeout: float | None = None) -> PageResult:
    """Run the page's runnable blocks in order in one fresh process with cwd `root`.

    `timeout` (seconds per block) overrides the page's `snippet_timeout`.
    """
    result = PageResult(page, errors=list(page.errors))
    blocks = page.runnable
    if result.errors or not blocks:
        return result
    limit = timeout if timeout is not None else page.timeout
    began = time.monotonic()
    with tempfile.TemporaryDirectory(prefix="snippets-") as tmp:
        job = Path(tmp, "job.json")
        job.write_text(
            json.dumps(
                {
                    "page": page.path,
                    "timeout": limit,
                    "blocks": [{"line": b.line, "code": b.code, "filename": b.filename} for b in blocks],
                }
            ),
            encoding="utf-8",
        )
        output = Path(tmp, "output.txt")
        # Append mode: the child's writes never depend on where the parent reads.
        with open(output, "ab") as sink:
            read_fd, write_fd = os.pipe()
            try:
                proc = subprocess.Popen(
                    child_command(job, write_fd),
                    cwd=root,
                    env=child_env(),
                    stdin=subprocess.DEVNULL,
                    stdout=sink,
                    stderr=subprocess.STDOUT,
                    pass_fds=(write_fd,),
                    start_new_session=True,  # one process group: a timeout kills grandchildren too
                )
            finally:
                os.close(write_fd)
            try:
                _watch(proc, read_fd, blocks, limit, output, result)
            finally:
                os.close(read_fd)
                _kill_group(proc)
    result.seconds = time.monotonic() - began
    return result


def _watch(
    proc: subprocess.Popen[bytes],
    read_fd: int,
    blocks: list[Block],
    limit: float,
    output: Path,
    result: PageResult,
) -> None:
    """Follow the child's events until the page is done, failed, timed out or died."""
    current, running = 0, False  # index of the latest block, and whether it is under way
    offset = 0  # where the latest block's output starts in the capture
    deadline = time.monotonic() + max(limit, STARTUP_LIMIT) + DUMP_GRACE
    buffer = b""
    while True:
        ready, _, _ = select.select([read_fd], [], [], max(0.0, deadline - time.monotonic()))
        if not ready:
            _kill_group(proc)
            message = (
                f"block timed out after {limit:g} s"
                if running
                else "Python process stopped responding outside any block"
            )
            result.failure = Failure(blocks[current], blocks[current].line, message, output=_tail(output, offset))
            return
        chunk = os.read(read_fd, 65536)
        if not chunk:
            break
        buffer += chunk
        *lines, buffer = buffer.split(b"\n")
        for raw in lines:
            event: dict[str, Any] = json.loads(raw)
            kind = event["event"]
            if kind == "start":
                current, running = event["index"], True
                offset = event["offset"]
                deadline = time.monotonic() + limit + DUMP_GRACE
            elif kind == "ok":
                result.ran.append(blocks[current])
                running = False
            elif kind == "error":
                block = blocks[current]
                result.failure = Failure(
                    block,
                    event["page_line"] or block.line,
                    f"{event['type']}: {event['message']}" if event["message"] else event["type"],
                    event["include"],
                    event["traceback"],
                    _tail(output, offset),
                )
            elif kind == "done":
                return
    if result.failure is not None:
        return
    # The pipe closed without "done": the process ended inside a block (or outside any).
    status = proc.wait()
    how = f"died of {_signal_name(-status)}" if status < 0 else f"exited with status {status}"
    where = "while running this block" if running else "outside any block"
    block = blocks[current]
    result.failure = Failure(block, block.line, f"Python process {how} {where}", output=_tail(output, offset))


def _signal_name(number: int) -> str:
    try:
        return signal.Signals(number).name
    except ValueError:
        return f"signal {number}"


def _tail(output: Path, offset: int) -> str:
    """The captured output from byte `offset`, trimmed to its last OUTPUT_LIMIT characters."""
    with open(output, "rb") as f:
        f.seek(offset)
        text = f.read().decode("utf-8", errors="replace")
    if len(text) > OUTPUT_LIMIT:
        text = "[... earlier output cut ...]\n" + text[-OUTPUT_LIMIT:]
    return text


def _kill_group(proc: subprocess.Popen[bytes]) -> None:
    """Kill the child and anything it started, then reap it."""
    try:
        os.killpg(proc.pid, signal.SIGKILL)
    except (ProcessLookupError, PermissionError):
        pass
    proc.wait()
