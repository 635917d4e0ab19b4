"""What each block prints, as the site shows it under the block (course/snippets/outputs.py)."""

from __future__ import annotations

import json
from pathlib import Path

from course.snippets import format_failure
from course.snippets.outputs import data_file, differences, entries, normalise, record, write

from repository import ROOT

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
