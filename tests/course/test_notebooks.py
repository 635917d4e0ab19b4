"""Every lesson page with Python has a notebook made from the page itself, with outputs.

The committed notebooks under notebooks/ must be what `make media` makes from the pages
now: code cells that are exactly the blocks the page runner runs, in page order, and
outputs made from that code. Running every notebook again would repeat tests/course/test_pages.py,
so two short pages are run here, in a kernel as a reader would, to prove the notebooks run.
"""

import json
import os
import re
import subprocess
import sys
import textwrap
from pathlib import Path

import nbformat
import pytest

from course import notebooks
from course.notebooks import FOLDER, build, code_cells, notebook_file, setup_code
from course.snippets import find_pages, parse_page

from repository import ROOT
PAGES = notebooks.lesson_pages(ROOT)
PAGE_IDS = [p.relative_to(ROOT).as_posix() for p in PAGES]
# Short pages that between them have an included file, a skipped block and plain blocks.
RUN_HERE = ["_pages/practice-1/05-custom-node.md", "_pages/practice-2/03-testing-and-modifying.md"]
REMAKE = "run `make media` (or `.venv/bin/python -m course.notebooks`)"


def committed(page: Path) -> nbformat.NotebookNode:
    file = notebook_file(page)
    if not file.is_file():
        pytest.fail(f"{file.relative_to(ROOT)} is missing; {REMAKE}", pytrace=False)
    return nbformat.read(file, as_version=4)


def test_every_page_with_python_to_run_has_a_notebook_and_no_other_does():
    with_python = {notebooks.notebook_name(p) for p in find_pages(ROOT)
                   if parse_page(p, ROOT).runnable}
    assert len(with_python) >= 20
    assert {notebooks.notebook_name(p) for p in PAGES} == with_python
    assert {f.name for f in FOLDER.glob("*.ipynb")} == with_python, REMAKE


def test_notebook_names_follow_the_page_paths():
    assert notebooks.notebook_name(ROOT / "_pages/practice-1/05-custom-node.md") == \
        "practice-1-05-custom-node.ipynb"
    assert notebooks.notebook_name("_pages/reference/01-getting-started.md") == \
        "reference-01-getting-started.ipynb"


@pytest.mark.parametrize("page", PAGES, ids=PAGE_IDS)
def test_notebook_is_what_its_page_makes_now(page):
    nb = committed(page)
    nbformat.validate(nb)
    assert notebooks.source_form(nb) == notebooks.source_form(build(page, ROOT)), (
        f"{notebook_file(page).relative_to(ROOT)} differs from what {page.relative_to(ROOT)} "
        f"makes now; {REMAKE}")


@pytest.mark.parametrize("page", PAGES, ids=PAGE_IDS)
def test_code_cells_are_the_blocks_the_runner_runs(page):
    parsed = parse_page(page, ROOT)
    nb = committed(page)
    cells = code_cells(nb)
    assert [c.source for c in cells] == [b.code.rstrip("\n") for b in parsed.runnable]
    assert [c.metadata["sw2sim"]["line"] for c in cells] == [b.line for b in parsed.runnable]
    for cell, block in zip(cells, parsed.runnable):
        if block.include:  # the file's own text, not the include_code tag
            assert cell.metadata["sw2sim"]["file"] == block.include
            assert cell.source == (ROOT / block.include).read_text(encoding="utf-8").rstrip("\n")
    markdown = "\n".join(c.source for c in nb.cells if c.cell_type == "markdown")
    code = "\n".join(c.source for c in nb.cells if c.cell_type == "code")
    for block in parsed.skipped:  # shown with its reason, never run
        assert block.code.rstrip("\n") in markdown
        assert block.skip in markdown
        assert block.code.strip() not in code
    setup = [c for c in nb.cells if c.cell_type == "code" and c not in cells]
    assert [c.source for c in setup] == [setup_code(notebook_file(page).name)]
    assert nb.cells.index(setup[0]) == 1


@pytest.mark.parametrize("page", PAGES, ids=PAGE_IDS)
def test_outputs_come_from_this_code_and_have_no_errors(page):
    nb = committed(page)
    assert nb.metadata["sw2sim"]["outputs_of"] == notebooks.output_hash(build(page, ROOT), ROOT), (
        f"the code of {page.relative_to(ROOT)}, or a file it reads, changed since its notebook "
        f"ran; {REMAKE}")
    cells = code_cells(nb)
    assert all(c.execution_count for c in cells), "every code cell has been run"
    assert not [o for c in cells for o in c.outputs if o.output_type == "error"]
    assert any(c.outputs for c in cells), "the notebook shows what its code prints"


def _shape(nb):
    """The outputs of each page cell with digits masked: another CPU may round a last digit."""
    return [[(o.output_type, re.sub(r"\d", "#", o.get("text", ""))) for o in c.outputs]
            for c in code_cells(nb)]


@pytest.mark.parametrize("path", RUN_HERE)
def test_notebook_runs_in_a_kernel_and_shows_what_is_committed(path):
    page = ROOT / path
    nb = notebooks.execute(build(page, ROOT), timeout=120)
    cells = code_cells(nb)
    assert all(c.execution_count for c in cells)
    assert not [o for c in cells for o in c.outputs if o.output_type == "error"]
    assert _shape(nb) == _shape(committed(page))
    setup = nb.cells[1]
    assert setup.execution_count == 1 and setup.outputs == [], "it ran; its output is dropped"


def _setup_cell(cwd: Path) -> subprocess.CompletedProcess:
    code = (setup_code("practice-1-03-exported-package.ipynb")
            + "\nimport os, sys; print('cwd', os.getcwd()); print('argv', sys.argv)")
    env = {k: v for k, v in os.environ.items() if k != "SW2SIM_COURSE_SITE"}
    return subprocess.run([sys.executable, "-c", code], cwd=cwd, capture_output=True, text=True,
                          timeout=60, env=env)


def test_setup_cell_moves_to_the_repository_root_from_the_notebooks_folder():
    run = _setup_cell(FOLDER)
    assert run.returncode == 0, run.stderr
    assert f"cwd {ROOT}" in run.stdout
    assert "argv ['']" in run.stdout


def test_setup_cell_outside_a_clone_without_a_site_says_what_to_do(tmp_path):
    """The committed notebooks know no site (the site's build fills it in)."""
    run = _setup_cell(tmp_path)
    assert run.returncode != 0
    assert "RuntimeError: This notebook is not in a clone of the course repository" in run.stderr
    assert "SW2SIM_COURSE_SITE" in run.stderr and "notebooks/ folder" in run.stderr
    assert "Traceback" in run.stderr and run.stderr.count("File ") <= 2, "one short traceback"
    assert not any(tmp_path.iterdir()), "nothing written"


def test_the_files_manifest_lists_what_each_notebook_reads():
    manifest = json.loads(notebooks.FILES.read_text(encoding="utf-8"))
    assert manifest == notebooks.files_manifest(PAGES, ROOT), REMAKE
    modelling = manifest["practice-1-01-modelling.ipynb"]
    assert "course/practices/practice_1/design.py" in modelling and "course/__init__.py" in modelling
    assert modelling["course/parts.py"] == "notebooks/modules/course/parts.py"
    package = manifest["practice-1-03-exported-package.ipynb"]
    assert package["examples/example_1/urdf/example_1.urdf"] == "examples/example_1/urdf/example_1.urdf"
    assert not [n for files in manifest.values() for n in files if n.startswith("sw2sim/")], \
        "the tool comes from pip, not from the site"
    for files in manifest.values():
        for name in files:
            assert (ROOT / name).is_file(), name


SAMPLE = textwrap.dedent("""\
    ---
    title: "A sample lesson"
    permalink: /sample/
    ---

    ## Load it {#load}

    Torque $$\\tau$$ over ![a plot](/media/plot.png) and [another page](/other/).

    $$E = m c^2$$

    ```python
    x = 1
    ```

    ```python
    {% include_code examples/script.py %}
    ```
    {: data-file="examples/script.py"}

    ```python
    import rospy
    ```
    {: data-skip="needs ROS 1"}

    | a | b |
    |---|---|
    {: .parts-table}

    {% include calculator.html kind="rpm" %}

    ```yaml
    {% include_code examples/config.yaml %}
    ```

    {% raw %}
    Shown as is: {{ not liquid }}
    {% endraw %}
    """)


def test_page_conventions_become_plain_notebook_markdown(tmp_path):
    (tmp_path / "_pages").mkdir()
    (tmp_path / "media").mkdir()
    (tmp_path / "media" / "plot.png").write_bytes(b"png")
    (tmp_path / "examples").mkdir()
    (tmp_path / "examples" / "script.py").write_text("y = x + 1\nprint(y)\n")
    (tmp_path / "examples" / "config.yaml").write_text("a: 1\nb: 2\n")
    page = tmp_path / "_pages" / "sample.md"
    page.write_text(SAMPLE)
    nb = build(page, tmp_path)
    nbformat.validate(nb)

    kinds = [c.cell_type for c in nb.cells]
    assert kinds == ["markdown", "code", "markdown", "code", "markdown", "code", "markdown"]
    assert nb.cells[0].source.startswith("# A sample lesson\n")
    assert [c.source for c in code_cells(nb)] == ["x = 1", "y = x + 1\nprint(y)"]
    first, before_include, rest = (nb.cells[i].source for i in (2, 4, 6))
    assert first.startswith("## Load it\n")  # kramdown's heading id is dropped
    assert "Torque $\\tau$ over ![a plot](../media/plot.png) and another page." in first
    assert "$$E = m c^2$$" in first  # display maths stays display maths
    assert before_include == "File `examples/script.py`:"
    assert "> This code is not run in this notebook: needs ROS 1." in rest
    assert "```python\nimport rospy\n```" in rest
    assert "{:" not in rest and "calculator.html" not in rest
    assert notebooks.GENERATED_NOTE in rest
    assert "```yaml\na: 1\nb: 2\n```" in rest  # include_code in a shown block is expanded
    assert "Shown as is: {{ not liquid }}" in rest and "raw %}" not in rest
    assert notebooks.source_form(build(page, tmp_path)) == notebooks.source_form(nb)


def test_an_include_code_in_a_list_is_indented_as_the_site_shows_it(tmp_path):
    (tmp_path / "_pages").mkdir()
    (tmp_path / "examples").mkdir()
    (tmp_path / "examples" / "config.yaml").write_text("a: 1\n\nb: 2\n")
    page = tmp_path / "_pages" / "listed.md"
    page.write_text("---\ntitle: Listed\n---\n\n```python\nx = 1\n```\n\n1. Its settings:\n\n"
                    "   ```yaml\n   {% include_code examples/config.yaml indent=3 %}\n   ```\n"
                    "   {: data-file=\"examples/config.yaml\"}\n")
    rest = build(page, tmp_path).cells[-1].source
    assert "File `examples/config.yaml`:" in rest
    assert "   ```yaml\n   a: 1\n\n   b: 2\n   ```" in rest  # blank lines stay blank
    assert "{:" not in rest


def test_check_with_nothing_chosen_finds_nothing_stale(capsys):
    assert notebooks.main(["--check", "no page has this in its path"]) == 0
    assert capsys.readouterr().out == ""
