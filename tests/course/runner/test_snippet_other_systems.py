"""The page runner as it runs on Windows (and macOS): every page in a plain subprocess,
never the fork server, the report pipe read by a thread rather than select(), with no
off-screen OpenGL library to be found and MUJOCO_GL not set (tests/without_gl.py).

What only Windows has (the pipe handed over as a handle, CREATE_NEW_PROCESS_GROUP,
taskkill) runs in .github/workflows/other-systems.yml, not here.
"""

from __future__ import annotations

import subprocess
import sys
import time

import pytest

from course.snippets import execute, parse_page, run_page

from repository import ROOT
from without_gl import environment, processes

SAMPLES = "tests/course/runner/samples/"
# Real pages, reading the exported package with yourdfpy and MuJoCo, that draw nothing.
PAGES = ["_pages/practice-1/02-exporting.md", "_pages/reference/01-getting-started.md"]
# The runner as a system without fork() and without select() on pipes has it.
WITHOUT_FORK = """\
import sys

from course.snippets import execute

execute.AVAILABLE = False  # no fork server, as where os.fork is missing
execute.SELECTABLE_PIPES = False  # the report pipe read by a thread, as on Windows
from course.snippets.__main__ import main

status = main(sys.argv[1:])
assert not execute._servers and not execute._failed, "a fork server was asked for"
sys.exit(status)
"""
# A page that says what its process has: no MUJOCO_GL, no OSMesa to be found.
PROBE = """\
---
title: Probe
---

```python
import ctypes.util
import os

print("MUJOCO_GL:", os.environ.get("MUJOCO_GL", "unset"))
assert "MUJOCO_GL" not in os.environ
assert ctypes.util.find_library("OSMesa") is None
```
"""


def runner(env: dict[str, str], *args: str, plain: bool) -> subprocess.CompletedProcess[str]:
    command = [sys.executable, "-m", "course.snippets", "--plain"] if plain else [sys.executable, "-c", WITHOUT_FORK]
    return subprocess.run([*command, "--root", str(ROOT), *args], cwd=ROOT, env=env, stdin=subprocess.DEVNULL,
                          capture_output=True, text=True, encoding="utf-8", timeout=600, check=False)


@pytest.mark.parametrize("plain", [True, False], ids=["--plain", "no-fork"])
def test_pages_run_without_fork_and_without_an_opengl_library(tmp_path, plain):
    env, log = environment(tmp_path, desktop=True)
    probe = tmp_path / "probe.md"
    probe.write_text(PROBE, encoding="utf-8")
    done = runner(env, str(probe), *PAGES, plain=plain)
    assert done.returncode == 0, done.stdout + done.stderr
    assert "3 pages, 0 failed" in done.stdout, done.stdout
    assert "fork server" not in done.stderr, done.stderr
    # The runner and one process per page, each with the hook and without MUJOCO_GL.
    started = processes(log)
    assert len(started) >= 1 + 3 and all(setting == "" for _, setting in started), started


def test_excluded_pages_are_left_out_and_listed(tmp_path):
    env, _ = environment(tmp_path, desktop=True)
    done = runner(env, SAMPLES + "passing.md", SAMPLES + "failing.md", "--exclude", SAMPLES + "failing.md",
                  plain=True)
    assert done.returncode == 0, done.stdout + done.stderr
    assert "1 pages, 0 failed" in done.stdout
    assert f"pages left out (--exclude): 1\n  {SAMPLES}failing.md" in done.stdout
    done = runner(env, SAMPLES + "passing.md", "--exclude", SAMPLES + "no-such-page.md", plain=True)
    assert done.returncode == 1 and "no such page" in done.stderr


@pytest.fixture
def threaded(monkeypatch):
    """Pages in plain processes whose report pipe a thread reads, as on Windows."""
    monkeypatch.setattr(execute, "SELECTABLE_PIPES", False)
    return lambda name, timeout=None: run_page(parse_page(ROOT / SAMPLES / name, ROOT), ROOT, timeout, fork=False)


def test_threaded_reader_runs_a_page(threaded):
    result = threaded("passing.md")
    assert result.ok and result.ran


def test_threaded_reader_times_a_block_out(threaded):
    began = time.monotonic()
    result = threaded("timeout.md")
    assert time.monotonic() - began < 15
    assert result.failure.headline == SAMPLES + "timeout.md:11: block timed out after 1 s"
    assert "going to sleep" in result.failure.output


def test_threaded_reader_sees_a_process_die(threaded):
    result = threaded("dies.md")
    assert result.failure.headline == SAMPLES + "dies.md:8: Python process exited with status 3 while running this block"


def test_the_pipe_reader_reads_and_times_out():
    import os

    for threaded_read in (False, True):
        read_fd, write_fd = os.pipe()
        reader = execute._PipeReader(read_fd, threaded=threaded_read)
        assert reader.read(0.05) is None
        os.write(write_fd, b"one\n")
        assert reader.read(5.0) == b"one\n"
        os.close(write_fd)
        assert reader.read(5.0) == b""
        reader.close()
