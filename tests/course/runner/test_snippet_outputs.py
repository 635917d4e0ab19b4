"""What each block prints, as the site shows it under the block (course/snippets/outputs.py)."""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
from pathlib import Path

from course.snippets import format_failure
from course.snippets.outputs import data_file, differences, entries, normalise, record, write

from repository import ROOT

SAMPLES = Path(__file__).resolve().parent / "samples"

PRINTED = ["first\nsecond\n", "to stdout\nto stderr\n", "", "from a subprocess\nafter it\n"]


def test_each_block_gets_what_it_printed(run_sample):
    result = run_sample("prints.md")
    assert result.ok, format_failure(result)
    assert result.outputs == PRINTED


def test_entries_list_every_python_block_with_its_first_line(run_sample, load_sample):
    page = load_sample("prints.md")
    result = run_sample("prints.md")
    assert entries(page, result, ROOT) == [
        {"code": 'print("first")', "output": PRINTED[0]},
        {"code": "import sys", "output": PRINTED[1]},
        {"code": "quiet = True", "output": ""},
        {"code": "import os", "output": None},  # skipped: not run
        {"code": "import subprocess", "output": PRINTED[3]},
    ]


def test_normalise_makes_machine_and_run_the_same(tmp_path):
    root = tmp_path / "checkout"
    text = (f"{root}/examples/example_1 and {root}\n"
            f"{root}-other/x\n"
            f"{Path.home()}/catkin_ws\n"
            "stability run: 4.0 s simulated (2000 steps) in 0.07 s; fixed base\r\n")
    assert normalise(text, root) == (
        "examples/example_1 and .\n"
        f"{root}-other/x\n"  # another folder whose name only starts the same
        "~/catkin_ws\n"
        "stability run: 4.0 s simulated (2000 steps) in … s; fixed base\n")


def test_data_file_names():
    assert data_file("_pages/practice-1/01-modelling.md", ROOT) == ROOT / "_data/outputs/practice-1__01-modelling.json"
    assert data_file(ROOT / "_pages/index.md", ROOT) == ROOT / "_data/outputs/index.json"


def test_a_changed_output_is_reported_with_its_line_and_a_diff(run_sample, load_sample, tmp_path):
    """Written to a scratch root, then changed by hand: the report names the block's page
    line, shows the difference and the command that refreshes the outputs."""
    page = load_sample("prints.md")
    result = run_sample("prints.md")
    root = tmp_path / "root"
    (root / "_pages").mkdir(parents=True)
    page.path = "_pages/prints.md"
    assert write(page, result, root) == "wrote _data/outputs/prints.json"
    assert write(page, result, root) is None  # unchanged
    assert differences(page, result, root) is None

    file = data_file(page.path, root)
    stored = json.loads(file.read_text(encoding="utf-8"))
    stored["blocks"][1]["output"] = "to stdout\nsomething else\n"
    file.write_text(json.dumps(stored), encoding="utf-8")
    report = differences(page, result, root)
    lines = report.splitlines()
    assert lines[0] == f"{page.blocks[1].location}: the stored output differs from what the block prints now:"
    assert "    -something else" in lines and "    +to stderr" in lines
    assert lines[-1].startswith("Run `.venv/bin/python -m course.snippets --write-outputs _pages/prints.md`")

    stored["blocks"].pop()
    file.write_text(json.dumps(stored), encoding="utf-8")
    assert "was written for other python blocks" in differences(page, result, root)

    file.unlink()
    assert "does not exist" in differences(page, result, root)


def test_a_page_that_prints_nothing_has_no_file(run_sample, load_sample):
    result = run_sample("include.md")
    assert result.ok and result.outputs == ["", "", ""]
    assert record(load_sample("include.md"), result, ROOT) is None


def test_the_command_writes_the_outputs_and_removes_those_of_pages_gone(tmp_path):
    """`python -m course.snippets --write-outputs` on a scratch repository of one page."""
    (tmp_path / "_pages").mkdir()
    shutil.copy(SAMPLES / "prints.md", tmp_path / "_pages" / "prints.md")
    gone = tmp_path / "_data" / "outputs" / "gone.json"
    gone.parent.mkdir(parents=True)
    gone.write_text("{}", encoding="utf-8")

    def write_outputs() -> str:
        done = subprocess.run([sys.executable, "-m", "course.snippets", "--write-outputs", "--root",
                               str(tmp_path)], cwd=ROOT, capture_output=True, text=True, timeout=120)
        assert done.returncode == 0, done.stdout + done.stderr
        return done.stdout

    printed = write_outputs()
    assert "wrote _data/outputs/prints.json" in printed
    assert "removed _data/outputs/gone.json: its page is gone" in printed
    stored = json.loads((tmp_path / "_data" / "outputs" / "prints.json").read_text(encoding="utf-8"))
    assert stored["page"] == "_pages/prints.md"
    assert [b["output"] for b in stored["blocks"]] == [*PRINTED[:3], None, PRINTED[3]]
    assert "wrote" not in write_outputs()  # nothing changed
