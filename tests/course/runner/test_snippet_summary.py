"""The pytest run ends with the blocks run and the skipped blocks with their reasons."""

import shutil
import subprocess
import sys
from pathlib import Path

from repository import ROOT

TESTS = ROOT / "tests"


def test_terminal_summary(tmp_path):
    for helper in ("conftest.py", "scheduling.py"):
        shutil.copy(TESTS / helper, tmp_path / helper)
    (tmp_path / "test_fake_pages.py").write_text(
        "def test_a(record_property):\n"
        "    record_property('snippets_skipped', ['_pages/a.md:8: needs ROS'])\n"
        "    record_property('snippets_ran', 3)\n"
        "def test_b(record_property):\n"
        "    record_property('snippets_skipped', [])\n"
        "    record_property('snippets_ran', 2)\n"
        "    assert False\n"
    )
    done = subprocess.run(
        [sys.executable, "-m", "pytest", "-p", "no:cacheprovider", "--rootdir", str(tmp_path), str(tmp_path)],
        check=False,
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=120,
    )
    lines = done.stdout.splitlines()
    assert "snippet blocks run: 5 (in 2 pages)" in lines
    i = lines.index("skipped snippet blocks: 1")
    assert lines[i + 1] == "  _pages/a.md:8: needs ROS"
