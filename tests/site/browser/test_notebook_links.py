"""Every lesson page with Python offers its notebook for download, and the link works."""

import json
import re
import urllib.request

import nbformat
import yaml

from course.notebooks import FOLDER, lesson_pages, notebook_name
from course.snippets import find_pages
from course.snippets.parse import split_front_matter

LINK = re.compile(r'<p class="notebook-link">\s*'
                  r'<a href="(?P<href>[^"]+)" download="(?P<name>[^"]+)"\s+'
                  r'data-notebook-site="(?P<site>[^"]+)">'
                  r"Download this\s+lesson as a Jupyter notebook</a>")


def permalink(page):
    front, _ = split_front_matter(page.read_text(encoding="utf-8").split("\n"))
    return yaml.safe_load("\n".join(front))["permalink"]


def test_every_lesson_page_with_python_links_its_notebook(site):
    with_notebook = {permalink(p): notebook_name(p) for p in lesson_pages()}
    assert with_notebook
    for page in find_pages(FOLDER.parent):
        path = permalink(page)
        html = (site.root / path.lstrip("/") / "index.html").read_text(encoding="utf-8")
        links = LINK.findall(html)
        if path not in with_notebook:
            assert not links and "notebook-link" not in html, f"{path} has no notebook to offer"
            continue
        name = with_notebook[path]
        assert len(links) == 1, f"{path}: no download link for {name}"
        href, download, root = links[0]
        assert download == name and href.endswith(f"/notebooks/{name}"), (path, href)
        # The site's root, from which the download's script makes the address it writes
        # into the notebook (assets/js/notebook-download.js).
        assert href == root.rstrip("/") + f"/notebooks/{name}", (path, href, root)
        # Served as the site serves it (baseurl included): the committed notebook, its code
        # and outputs unchanged (the site embeds its images: _plugins/notebooks.rb).
        with urllib.request.urlopen(site.url(href)) as response:
            body = response.read()
        served = nbformat.reads(body.decode("utf-8"), as_version=4)
        nbformat.validate(served)
        committed = nbformat.read(FOLDER / name, as_version=4)
        assert ([(c.source, c.get("outputs")) for c in served.cells if c.cell_type == "code"]
                == [(c.source, c.get("outputs")) for c in committed.cells if c.cell_type == "code"])
        made_from = json.loads(body)["metadata"]["sw2sim"]["page"]
        assert made_from == page.relative_to(FOLDER.parent).as_posix()
