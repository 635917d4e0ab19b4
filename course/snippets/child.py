"""Child process: run one page's blocks in one namespace, as a reader pasting them would.

Usage: python child.py JOB.json REPORT_FD   (stdlib only: it must not import sw2sim;
                                           on Windows REPORT_FD is an inherited handle)
       python child.py --serve CONTROL_FD PRELOAD_JSON
                                           the fork server (forkserver.py): imports the
                                           libraries, then forks one process per page that
                                           runs `main` as the first form would

JOB.json holds {"page": str, "timeout": float, "blocks": [{"line", "code", "filename"}]}.
Events go to REPORT_FD as JSON lines, never to stdout/stderr, which belong to the blocks:
  {"event": "start", "index": i, "offset": n} a block begins; its output starts at byte n
  {"event": "ok", "index": i, "seconds": t, "end": n}
                                            it finished; its output ends at byte n
  {"event": "error", "index": i, ...}       it raised; nothing more runs
  {"event": "done"}                         the page is over
"""

from __future__ import annotations

import faulthandler
import json
import os
import sys
import time
import traceback
import types
from types import TracebackType
from typing import Any, TextIO


def main(argv: list[str]) -> None:
    with open(argv[1], encoding="utf-8") as f:
        job = json.load(f)
    fd = _report_fd(int(argv[2]))
    # Processes the blocks start must not hold the pipe open after this one dies.
    os.set_inheritable(fd, False)
    # newline="\n": one event a line as the runner splits them, "\r\n" on no system.
    report = os.fdopen(fd, "w", encoding="utf-8", newline="\n", buffering=1)
    page: str = job["page"]
    filenames = {page} | {b["filename"] for b in job["blocks"]}
    sys.argv = [""]  # what an interactive interpreter has
    # The namespace is a real __main__ module, so pickle and multiprocessing find what
    # the blocks define, as they would in the reader's interpreter.
    main_module = types.ModuleType("__main__")
    sys.modules["__main__"] = main_module
    namespace: dict[str, Any] = main_module.__dict__

    for index, block in enumerate(job["blocks"]):
        _flush()
        _send(report, event="start", index=index, offset=_output_size())
        # Dump where the block is stuck shortly before the parent kills it.
        faulthandler.dump_traceback_later(job["timeout"], exit=False)
        began = time.monotonic()
        error = _run(block, namespace, page, filenames)
        faulthandler.cancel_dump_traceback_later()
        _flush()
        if error is not None:
            _send(report, event="error", index=index, **error)
            break
        _send(report, event="ok", index=index, seconds=round(time.monotonic() - began, 3), end=_output_size())
    _send(report, event="done")
    report.close()
    # Skip interpreter teardown: leftover threads or GL contexts must not hang or crash it.
    os._exit(0)


def _report_fd(number: int) -> int:
    """The report pipe's file descriptor: `number` itself, or on Windows, where a child
    inherits handles and not descriptors, a descriptor opened on the handle `number`."""
    if os.name != "nt":
        return number
    import msvcrt

    return msvcrt.open_osfhandle(number, os.O_WRONLY)


def _run(block: dict[str, Any], namespace: dict[str, Any], page: str, filenames: set[str]) -> dict[str, Any] | None:
    """Run one block; return the error event's fields, or None on success."""
    filename = block["filename"]
    # Pad page code so that its line numbers in tracebacks are page lines.
    source = block["code"] if filename != page else "\n" * (block["line"] - 1) + block["code"]
    try:
        # dont_inherit: the page must not get this module's `from __future__` flags.
        exec(compile(source, filename, "exec", dont_inherit=True), namespace)
    except SystemExit as exc:
        # A script ending in sys.exit(main()) succeeded if the status is 0.
        if exc.code in (None, 0):
            return None
        return _describe(exc, page, filenames)
    except BaseException as exc:  # noqa: BLE001 - a block may raise anything
        return _describe(exc, page, filenames)
    return None


def _describe(exc: BaseException, page: str, filenames: set[str]) -> dict[str, Any]:
    """Where a block failed: deepest page frame and deepest included-file frame."""
    frames = [(f.filename, f.lineno) for f in traceback.extract_tb(exc.__traceback__)]
    if isinstance(exc, SyntaxError) and exc.filename:
        frames.append((exc.filename, exc.lineno))
    page_line = include = None
    for filename, lineno in frames:
        if filename == page:
            page_line, include = lineno, None  # a deeper included frame must follow it
        elif filename in filenames:
            include = f"{filename}:{lineno}"
    kind = type(exc)
    name = kind.__qualname__ if kind.__module__ == "builtins" else f"{kind.__module__}.{kind.__qualname__}"
    message = exc.msg if isinstance(exc, SyntaxError) else str(exc)
    return {
        "type": name,
        "message": message,
        "page_line": page_line,
        "include": include,
        "traceback": "".join(traceback.format_exception(kind, exc, _user_frames(exc.__traceback__))),
    }


def _user_frames(tb: TracebackType | None) -> TracebackType | None:
    """Drop this module's own frames from the top of a traceback."""
    while tb is not None and tb.tb_frame.f_code.co_filename == __file__:
        tb = tb.tb_next
    return tb


def _send(report: TextIO, **event: Any) -> None:
    report.write(json.dumps(event) + "\n")


def _output_size() -> int:
    """Bytes captured so far: where the next block's output starts (known only here, race-free)."""
    try:
        return os.fstat(1).st_size
    except OSError:
        return 0


def _flush() -> None:
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except Exception:  # noqa: BLE001 - a block may have replaced or closed them
            pass


if __name__ == "__main__":
    if sys.argv[1:2] == ["--serve"]:
        # What is imported from here on, a page process does not have: the server stashes it.
        keep = set(sys.modules)
        import runpy

        server = runpy.run_path(os.path.join(os.path.dirname(__file__), "forkserver.py"), run_name="__snippets_forkserver__")
        server["serve"](main, keep, int(sys.argv[2]), json.loads(sys.argv[3]))
    else:
        main(sys.argv)
