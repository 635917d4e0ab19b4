"""`python -m course.snippets PAGES...` prints the same reports and fails with status 1."""

import subprocess
import sys
from pathlib import Path

from repository import ROOT
P = "tests/course/runner/samples/"


def cli(*pages: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "course.snippets", "--root", str(ROOT), *pages],
        check=False,
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=120,
    )


def test_cli_passes():
    done = cli(P + "passing.md", P + "skipped.md")
    assert done.returncode == 0, done.stdout + done.stderr
    assert "snippet blocks run: 5; skipped snippet blocks: 2" in done.stdout
    assert f"  {P}skipped.md:8: needs a ROS master" in done.stdout


def test_cli_fails():
    done = cli(P + "failing.md")
    assert done.returncode == 1
    assert P + "failing.md:15: ZeroDivisionError: division by zero" in done.stdout.splitlines()
