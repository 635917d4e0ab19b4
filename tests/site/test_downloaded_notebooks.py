"""A notebook downloaded from the site runs in an empty folder: its first cell fetches the
files the lesson reads from the site (here the built site, served on 127.0.0.1), and its
Markdown carries its images (_plugins/notebooks.rb, course/notebooks.py).

A local build does not know its address (the Pages build is given it). Downloaded from
its page's link, the notebook gets the address the page was served from anyway
(assets/js/notebook-download.js), so it runs with nothing set and nothing reachable but
the local server; a reader without scripts sets SW2SIM_COURSE_SITE, as the page says."""

from __future__ import annotations

import functools
import http.server
import json
import os
import re
import shutil
import socket
import subprocess
import threading
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import nbformat
import pytest

from course import notebooks
from course.notebooks import code_cells
from jekyll import bundle, whole_site  # noqa: F401
from repository import ROOT

# A lesson that imports the course's modules, downloaded from its page's link in a browser,
# and one that reads an example package, taken as the site publishes it and run with
# SW2SIM_COURSE_SITE set (what the page tells a reader without scripts to do).
DOWNLOADED = [("practice-2-01-modelling.ipynb", "page link"),
              ("practice-1-03-exported-package.ipynb", "SW2SIM_COURSE_SITE")]
PLUGIN = ROOT / "_plugins" / "notebooks.rb"
LINK_TEXT = "Download this lesson as a Jupyter notebook"
# The browser reaches nothing but the local server.
CHROMIUM_ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
                 "--host-resolver-rules=MAP * ~NOTFOUND, EXCLUDE 127.0.0.1"]
PROXY_VARIABLES = ("http_proxy", "https_proxy", "all_proxy", "HTTP_PROXY", "HTTPS_PROXY", "ALL_PROXY")


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


def chromium() -> str:
    path = os.environ.get("CHROMIUM") or shutil.which("chromium") or "/usr/bin/chromium"
    if not Path(path).is_file():
        pytest.fail("Chromium not found: run `make setup` (it installs Debian's `chromium`), "
                    "or point $CHROMIUM at a Chromium binary.", pytrace=False)
    return path


def page_of(notebook: Path) -> str:
    """The address (permalink) of the page a notebook is made from."""
    page = json.loads(notebook.read_text(encoding="utf-8"))["metadata"]["sw2sim"]["page"]
    return re.search(r"^permalink:\s*(\S+)", (ROOT / page).read_text(encoding="utf-8"), re.M)[1]


def download_from_its_page(address: str, name: str, folder: Path, site: Path) -> Path:
    """Click the download link on the notebook's page, served at `address`, in Chromium,
    and save what the browser downloads in `folder`.

    In a thread of its own: Playwright's synchronous API will not start in a thread where
    an event loop runs already, as the browser tests' session (tests/site/browser/
    conftest.py) leaves one running when both run in one process."""
    with ThreadPoolExecutor(max_workers=1) as thread:
        return thread.submit(_download, address, name, folder, site).result()


def _download(address: str, name: str, folder: Path, site: Path) -> Path:
    from playwright.sync_api import sync_playwright

    with sync_playwright() as playwright:
        browser = playwright.chromium.launch(executable_path=chromium(), args=CHROMIUM_ARGS)
        try:
            page = browser.new_page(accept_downloads=True)
            page.goto(address + page_of(site / "notebooks" / name), wait_until="load")
            with page.expect_download() as download:
                page.get_by_role("link", name=LINK_TEXT).click()
            assert download.value.suggested_filename == name
            download.value.save_as(folder / name)
        finally:
            browser.close()
    return folder / name


@pytest.fixture
def offline(monkeypatch):
    """Nothing but 127.0.0.1 reachable from the notebook's kernel: every other address goes
    to a proxy at a local port that refuses connections (a socket bound, never listening,
    for the test's length), which Python's urllib and pip both obey."""
    with socket.socket() as refusing:
        refusing.bind(("127.0.0.1", 0))
        proxy = f"http://127.0.0.1:{refusing.getsockname()[1]}"
        for variable in PROXY_VARIABLES:
            monkeypatch.setenv(variable, proxy)
        monkeypatch.setenv("no_proxy", "127.0.0.1")
        monkeypatch.setenv("NO_PROXY", "127.0.0.1")
        yield


@pytest.mark.parametrize("name, how", DOWNLOADED)
def test_a_downloaded_notebook_runs_in_an_empty_folder(name, how, served, tmp_path, monkeypatch,
                                                       offline):
    site, address = served
    folder = tmp_path / "downloads"
    folder.mkdir()
    published = json.loads((site / "notebooks" / name).read_text(encoding="utf-8"))
    monkeypatch.delenv("SW2SIM_COURSE_SITE", raising=False)
    if how == "page link":
        downloaded = json.loads(download_from_its_page(address, name, folder, site).read_text(
            encoding="utf-8"))
        # The local build published no address; the download carries the one the page was
        # served from, and is otherwise the published file.
        setup = [i for i, c in enumerate(published["cells"]) if "setup" in c["metadata"].get("tags", [])]
        assert len(setup) == 1, f"{name}: no setup cell"
        published_setup = "".join(published["cells"][setup[0]]["source"])
        assert 'site=""' in published_setup, "the local build knows an address: not a local build?"
        assert "".join(downloaded["cells"][setup[0]]["source"]) == \
            published_setup.replace('site=""', f'site="{address}"', 1)
        for cells in (downloaded["cells"], published["cells"]):
            del cells[setup[0]]
        assert downloaded == published, "the download changed more than the setup cell's address"
    else:
        shutil.copy(site / "notebooks" / name, folder / name)
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
