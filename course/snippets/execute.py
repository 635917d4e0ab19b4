"""Run a page's blocks in a fresh Python process and say where it failed.

Each page gets a process of its own, which starts as a fresh interpreter would. Two ways:

- forked from the fork server (forkserver.py), a process that has already imported the
  heavy libraries (PRELOAD), so a page's `import numpy` is instant while its sys.modules
  still starts empty of them; Linux and other Unix systems but macOS;
- a plain subprocess, `python -c ... child.py` (elsewhere, when the server cannot start,
  or with `run_page(..., fork=False)` or COURSE_SNIPPETS_FORK=0 in the environment).

The plain way works on Windows too: there the child gets the report pipe as an inherited
handle instead of a file descriptor, the pipe is read by a thread (select() takes only
sockets there), and a page's processes are a process group (CREATE_NEW_PROCESS_GROUP)
that a timeout ends with `taskkill /T`, where POSIX has a session and killpg().

The server starts with the first page a process runs (that page runs in a plain process
meanwhile) and stops when the process exits, or with `shutdown()`.
"""

from __future__ import annotations

import atexit
import json
import os
import queue
import select
import signal
import subprocess
import sys
import tempfile
import threading
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Union

from sw2sim import gl

from .forkserver import AVAILABLE, ForkedProcess, ForkServer, ForkServerError
from .parse import Block, Page, ParseError

CHILD = Path(__file__).resolve().with_name("child.py")
BOOT = "import runpy, sys; sys.argv = sys.argv[1:]; runpy.run_path(sys.argv[0], run_name='__main__')"
# What the fork server imports: the third-party libraries that take a page process long to
# import (not sw2sim or course: they import in a few hundredths of a second after these).
PRELOAD = (
    "numpy",
    "mujoco",
    "matplotlib.pyplot",  # with the Agg backend: the server has the pages' environment
    "trimesh",
    "scipy.spatial",
    "PIL.Image",
    "yaml",
    "lxml.etree",
)
# "0" (or "no", "false", "off"): every page in a plain subprocess; "1": wait for the server.
FORK_VARIABLE = "COURSE_SNIPPETS_FORK"
# Environment variables that change from test to test but not what the server imports.
# Where a process makes its temporary files (tempfile.gettempdir reads them in this order).
TEMP_VARIABLES = ("TMPDIR", "TEMP", "TMP")
# Not part of a fork server's identity: what changes from test to test, and each page's
# temporary folder.
VOLATILE = frozenset({"PYTEST_CURRENT_TEST", *TEMP_VARIABLES})
# Time between the child's own stack dump and the parent's kill on a timeout.
DUMP_GRACE = 1.0
# Interpreter start-up may be slow on a busy machine: never hold it to a tiny block limit.
STARTUP_LIMIT = 60.0
# Longest stretch of a failing block's output kept in a report.
OUTPUT_LIMIT = 20_000
WINDOWS = os.name == "nt"
# Whether select() can wait on the report pipe (POSIX); elsewhere a thread reads it.
SELECTABLE_PIPES = not WINDOWS


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
    # What each block of `ran` printed, stdout and stderr as they came (course/snippets/outputs.py)
    outputs: list[str] = field(default_factory=list)
    # The page's temporary folder, as its process saw it (removed with what the page put there)
    temp: str | None = None

    @property
    def ok(self) -> bool:
        return self.failure is None and not self.errors


def child_command(job: Path, report_fd: int) -> list[str]:
    """The child's command line.

    child.py runs as a file, not as `-m course.snippets.child`: importing the sw2sim package
    would load its dependencies (and settle MUJOCO_GL) before the page's first line, which a
    reader's fresh interpreter does not do. `-c` also gives sys.path[0] == "" (the working
    directory), as in an interactive interpreter. On Windows `report_fd` is the pipe's
    inheritable handle, which child.py turns back into a file descriptor.
    """
    return [sys.executable, "-c", BOOT, str(CHILD), str(job), str(report_fd)]


def server_command(control_fd: int) -> list[str]:
    """The fork server's command line: a page process's, with child.py's `--serve`."""
    return [sys.executable, "-c", BOOT, str(CHILD), "--serve", str(control_fd), json.dumps(PRELOAD)]


def child_env() -> dict[str, str]:
    """Environment of the child: off-screen rendering, no GUI windows, unbuffered output."""
    env = dict(os.environ)
    gl.choose(env)
    env["MPLBACKEND"] = "Agg"
    env["PYTHONUNBUFFERED"] = "1"  # keeps stdout and stderr in order in the capture
    env["PYTHONFAULTHANDLER"] = "1"  # a crash prints the page line it happened at
    if WINDOWS:
        # Output to a file is in the ANSI code page there; a console (and the capture) is UTF-8.
        env["PYTHONIOENCODING"] = "utf-8"
    return env


def run_page(page: Page, root: Path, timeout: float | None = None, *, fork: bool | None = None) -> PageResult:
    """Run the page's runnable blocks in order in one fresh process with cwd `root`.

    `timeout` (seconds per block) overrides the page's `snippet_timeout`. `fork`: True,
    fork the process from the fork server (starting it and waiting for it if need be);
    False, a plain subprocess; None (default), as COURSE_SNIPPETS_FORK says, else the
    server once it has been started (the first page runs in a plain subprocess meanwhile).
    Either way, a server that cannot start means plain subprocesses.
    """
    result = PageResult(page, errors=list(page.errors))
    blocks = page.runnable
    if result.errors or not blocks:
        return result
    limit = timeout if timeout is not None else page.timeout
    began = time.monotonic()
    # Windows cannot delete a file a leftover process still has open: leave it to the system.
    with tempfile.TemporaryDirectory(prefix="snippets-", ignore_cleanup_errors=WINDOWS) as tmp:
        # The page's own temporary folder: what its blocks make there (a scratch copy with
        # tempfile.mkdtemp, an unpacked zip) goes when the page is done, as the reader's
        # system would clear it in time.
        temp = Path(tmp, "tmp")
        temp.mkdir()
        result.temp = str(temp)
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
                proc = _start(job, root, write_fd, sink, fork, temp)
            finally:
                os.close(write_fd)
            reader = _PipeReader(read_fd)
            try:
                _watch(proc, reader, blocks, limit, output, result)
            finally:
                # The page's processes first: on Windows the reading thread then sees the
                # end of the pipe, and the pipe is not closed under it.
                _kill_group(proc)
                reader.close()
    result.seconds = time.monotonic() - began
    return result


Process = Union["subprocess.Popen[bytes]", ForkedProcess]


def _start(job: Path, root: Path, write_fd: int, sink: Any, fork: bool | None,
           temp: Path) -> Process:
    """The page's process, forked by the server or else a plain subprocess, with `temp` as
    its temporary folder."""
    env = child_env()
    server = _server(root, env, fork)
    env.update(dict.fromkeys(TEMP_VARIABLES, str(temp)))
    if server is not None:
        try:
            return server.start(job, root, env, write_fd, sink.fileno())
        except ForkServerError as exc:
            _give_up(server, str(exc))
    if WINDOWS:
        import msvcrt

        # No pass_fds there: the child inherits the pipe's handle, and only that one besides
        # its standard streams (handle_list), and gets its number on the command line.
        handle = msvcrt.get_osfhandle(write_fd)
        os.set_handle_inheritable(handle, True)
        return subprocess.Popen(
            child_command(job, handle),
            cwd=root,
            env=env,
            stdin=subprocess.DEVNULL,
            stdout=sink,
            stderr=subprocess.STDOUT,
            startupinfo=subprocess.STARTUPINFO(lpAttributeList={"handle_list": [handle]}),
            creationflags=subprocess.CREATE_NEW_PROCESS_GROUP,  # ended as a tree on a timeout
        )
    return subprocess.Popen(
        child_command(job, write_fd),
        cwd=root,
        env=env,
        stdin=subprocess.DEVNULL,
        stdout=sink,
        stderr=subprocess.STDOUT,
        pass_fds=(write_fd,),
        start_new_session=True,  # one process group: a timeout kills grandchildren too
    )


_servers: dict[tuple[Any, ...], ForkServer] = {}  # by root and environment
_failed: set[tuple[Any, ...]] = set()  # servers that could not start: plain processes there
_servers_lock = threading.Lock()


def _server(root: Path, env: dict[str, str], fork: bool | None) -> ForkServer | None:
    """The fork server for pages run in `root` with `env`, once it is ready; None for a plain process."""
    if fork is None:
        setting = os.environ.get(FORK_VARIABLE, "").strip().lower()
        fork = False if setting in ("0", "no", "false", "off") else True if setting else None
    if fork is False or not AVAILABLE:
        return None
    key = _key(root, env)
    with _servers_lock:
        if key in _failed:
            return None
        server = _servers.get(key)
        if server is not None and server.owner != os.getpid():
            server = None  # this process is a fork of the one that started it
        if server is None:
            if not _servers:
                atexit.register(shutdown)
            try:
                server = _servers[key] = ForkServer(server_command, root, env)
            except OSError as exc:
                _failed.add(key)
                print(f"course.snippets: cannot start the fork server ({exc}); pages run in plain processes",
                      file=sys.stderr)
                return None
            if fork is None:
                return None  # this page does not wait for the server's imports
    if server.wait_ready(STARTUP_LIMIT):
        return server
    _give_up(server, "it stopped or did not get ready in time:\n" + server.output()[-OUTPUT_LIMIT:])
    return None


def _key(root: Path, env: dict[str, str]) -> tuple[Any, ...]:
    """Pages share a server if they run in the same directory with the same environment."""
    return (str(root), sys.executable, tuple(sorted((k, v) for k, v in env.items() if k not in VOLATILE)))


def _give_up(server: ForkServer, why: str) -> None:
    """Plain processes from now on where `server` would have forked them."""
    with _servers_lock:
        for key, known in list(_servers.items()):
            if known is server:
                del _servers[key]
                _failed.add(key)
    server.close()
    print(f"course.snippets: fork server unusable, pages run in plain processes: {why}", file=sys.stderr)


def shutdown() -> None:
    """Stop the fork servers this process started (run at exit too)."""
    with _servers_lock:
        servers = list(_servers.values())
        _servers.clear()
    for server in servers:
        server.close()


class _PipeReader:
    """The read end of the report pipe, read with a time limit: select() where pipes can be
    selected (POSIX), else a thread that hands the chunks over through a queue (Windows)."""

    CHUNK = 65536

    def __init__(self, fd: int, threaded: bool | None = None):
        self.fd = fd
        self._chunks: queue.Queue[bytes] | None = None
        self._thread: threading.Thread | None = None
        if not SELECTABLE_PIPES if threaded is None else threaded:
            self._chunks = queue.Queue()
            self._thread = threading.Thread(target=self._pump, name="snippets-report", daemon=True)
            self._thread.start()

    def _pump(self) -> None:
        assert self._chunks is not None
        while True:
            try:
                chunk = os.read(self.fd, self.CHUNK)
            except OSError:
                chunk = b""
            self._chunks.put(chunk)
            if not chunk:
                return

    def read(self, timeout: float) -> bytes | None:
        """The next bytes (b"" at the end of the pipe), or None if none came within `timeout` s."""
        if self._chunks is None:
            ready, _, _ = select.select([self.fd], [], [], timeout)
            return os.read(self.fd, self.CHUNK) if ready else None
        try:
            return self._chunks.get(timeout=timeout)
        except queue.Empty:
            return None

    def close(self) -> None:
        if self._thread is not None:
            # Every writer has ended by now, so the thread is at the end of the pipe; one
            # held by a leftover process is not waited for longer than this.
            self._thread.join(5.0)
            if self._thread.is_alive():
                return  # closing the pipe under a blocked read could hang: the thread keeps it
        os.close(self.fd)


def _watch(
    proc: Process,
    reader: _PipeReader,
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
        chunk = reader.read(max(0.0, deadline - time.monotonic()))
        if chunk is None:
            _kill_group(proc)
            message = (
                f"block timed out after {limit:g} s"
                if running
                else "Python process stopped responding outside any block"
            )
            result.failure = Failure(blocks[current], blocks[current].line, message, output=_tail(output, offset))
            return
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
                result.outputs.append(_tail(output, offset, limit=None, end=event.get("end")))
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
    if status is None:
        how = "ended (its fork server stopped, so its status is unknown)"
    else:
        how = f"died of {_signal_name(-status)}" if status < 0 else f"exited with status {status}"
    where = "while running this block" if running else "outside any block"
    block = blocks[current]
    result.failure = Failure(block, block.line, f"Python process {how} {where}", output=_tail(output, offset))


def _signal_name(number: int) -> str:
    try:
        return signal.Signals(number).name
    except ValueError:
        return f"signal {number}"


def _tail(output: Path, offset: int, limit: int | None = OUTPUT_LIMIT, end: int | None = None) -> str:
    """The captured output from byte `offset` (to byte `end`), trimmed to its last `limit` characters."""
    with open(output, "rb") as f:
        f.seek(offset)
        text = f.read(-1 if end is None else max(0, end - offset)).decode("utf-8", errors="replace")
    if limit is not None and len(text) > limit:
        text = "[... earlier output cut ...]\n" + text[-limit:]
    return text


def _kill_group(proc: Process) -> None:
    """Kill the child and anything it started, then reap it."""
    if WINDOWS:
        _end_tree(proc)
        return
    try:
        os.killpg(proc.pid, signal.SIGKILL)
    except (ProcessLookupError, PermissionError):
        pass
    proc.wait()


def _end_tree(proc: Process) -> None:
    """Windows: end the child and the processes below it (`taskkill /T`), else the child
    alone, then reap it. There is no group kill there for processes whose parent has gone."""
    if proc.poll() is None:
        try:
            subprocess.run(["taskkill", "/F", "/T", "/PID", str(proc.pid)], stdin=subprocess.DEVNULL,
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, timeout=30, check=False)
        except (OSError, subprocess.SubprocessError):
            pass
        if proc.poll() is None:
            try:
                proc.terminate()
            except OSError:
                pass
    proc.wait()
