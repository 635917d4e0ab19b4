"""A notebook downloaded from the site runs in an empty folder: its first cell fetches the
files the lesson reads from the site (here the built site, served on 127.0.0.1), and its
Markdown carries its images (_plugins/notebooks.rb, course/notebooks.py)."""

from __future__ import annotations

import functools
import http.server
import json
import re
import shutil
import subprocess
import threading
from pathlib import Path

import nbformat
import pytest

from course import notebooks
from course.notebooks import code_cells
from jekyll import bundle, whole_site  # noqa: F401
from repository import ROOT

# A lesson that imports the course's modules and one that reads an example package.
DOWNLOADED = ["practice-2-01-modelling.ipynb", "practice-1-03-exported-package.ipynb"]
PLUGIN = ROOT / "_plugins" / "notebooks.rb"


@pytest.fixture(scope="module")
def served(whole_site):
    """The built site on a free port of 127.0.0.1, stopped when the module's tests end."""
    handler = functools.partial(_Quiet, directory=str(whole_site))
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    try:
        yield whole_site, f"http://127.0.0.1:{server.server_address[1]}"
    finally:
        server.shutdown()
        server.server_close()
        thread.join(timeout=10)


class _Quiet(http.server.SimpleHTTPRequestHandler):
    def log_message(self, *args):
        pass


def _outputs(nb) -> list[list[tuple[str, str]]]:
    """Each page cell's outputs with digits masked (another CPU may round a last digit)."""
    return [[(o.output_type, re.sub(r"\d", "#", o.get("text", ""))) for o in c.outputs]
            for c in code_cells(nb)]


@pytest.mark.parametrize("name", DOWNLOADED)
def test_a_downloaded_notebook_runs_in_an_empty_folder(name, served, tmp_path, monkeypatch):
    site, address = served
    folder = tmp_path / "downloads"
    folder.mkdir()
    shutil.copy(site / "notebooks" / name, folder / name)
    # A local build does not know its address (the Pages build does): say it, as a reader
    # with a local copy of the site would.
    monkeypatch.setenv("SW2SIM_COURSE_SITE", address)
    wanted = json.loads((ROOT / "notebooks" / "files.json").read_text(encoding="utf-8"))[name]
    modules = any(f.startswith("course/") for f in wanted)
    nb = nbformat.read(folder / name, as_version=4)
    # Where the kernel works, and where the lesson's modules come from: the fetched copies.
    probe = nbformat.v4.new_code_cell("import os\nprint(os.getcwd())" +
                                      ("\nimport course\nprint(course.__file__)" if modules else ""))
    nb.cells.append(probe)
    nb = notebooks.execute(nb, timeout=180, folder=folder)
    errors = [o for c in nb.cells if c.cell_type == "code" for o in c.outputs
              if o.output_type == "error"]
    assert not errors, "\n".join(f"{e.ename}: {e.evalue}" for e in errors)
    for file in wanted:
        assert (folder / file).read_bytes() == (ROOT / file).read_bytes(), file
    where = probe.outputs[0].text.split()
    assert Path(where[0]) == folder.resolve()
    if modules:
        assert Path(where[1]).is_relative_to(folder.resolve()), where
    committed = nbformat.read(ROOT / "notebooks" / name, as_version=4)
    assert _outputs(nb)[:-1] == _outputs(committed), "it prints what the committed notebook shows"


def test_published_notebooks_carry_their_images(whole_site):
    for committed in sorted((ROOT / "notebooks").glob("*.ipynb")):
        published = json.loads((whole_site / "notebooks" / committed.name).read_text(encoding="utf-8"))
        for cell in published["cells"]:
            text = "".join(cell["source"])
            assert not re.search(r'!\[[^\]]*\]\(\.\./|src="\.\./', text), \
                (committed.name, "an image left as a path")
            for name in re.findall(r"attachment:([^)\"\s]+)", text):
                data = cell.get("attachments", {}).get(name)
                assert data and len(data) == 1, (committed.name, name)
        shown = len(re.findall(r"!\[[^\]]*\]\(\.\./media/", committed.read_text(encoding="utf-8")))
        embedded = sum(len(c.get("attachments", {})) for c in published["cells"])
        assert embedded >= min(shown, 1), committed.name


def test_the_pages_build_tells_the_setup_cell_the_site_and_the_tool(tmp_path):
    """With url, baseurl and repository set (as the Pages workflow sets them), the published
    setup cell fetches from the site and installs sw2sim from the repository's archive."""
    if shutil.which("ruby") is None:
        pytest.skip("ruby is not installed (`make setup` installs Jekyll's)")
    source = ROOT / "notebooks" / "practice-1-01-modelling.ipynb"
    script = (f"require {str(PLUGIN)!r}\n"
              "config = {'url' => 'https://example.org', 'baseurl' => '/course',"
              " 'repository' => 'someone/course', 'repository_branch' => 'main'}\n"
              "n = Sw2simSite::Notebooks\n"
              "print n.publish(File.read(ARGV[0]), site: n.address(config), tool: n.tool(config),"
              " media: ->(path) { nil })\n")
    done = subprocess.run(["ruby", "-e", script, str(source)], capture_output=True, text=True,
                          timeout=60)
    assert done.returncode == 0, done.stderr
    cells = json.loads(done.stdout)["cells"]
    setup = "".join(cells[1]["source"])
    markdown = "".join("".join(c["source"]) for c in cells if c["cell_type"] == "markdown")
    assert "](../" not in markdown, "links to the repository's files point at the site"
    assert "](https://example.org/course/media/practice-1/base-sheet.svg)" in markdown
    assert 'site="https://example.org/course"' in setup
    assert ('tool="sw2sim[course] @ https://github.com/someone/course/archive/refs/heads/main.zip"'
            in setup)
    placeholder = subprocess.run(
        ["ruby", "-e", f"require {str(PLUGIN)!r}\n"
         "print Sw2simSite::Notebooks.tool({'repository' => 'OWNER/REPOSITORY'}).inspect"],
        capture_output=True, text=True, timeout=60)
    assert placeholder.stdout == '""', "no pip requirement for a repository not yet named"
