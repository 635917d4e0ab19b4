"""The "source" link of a sentence about a tool's behaviour (_includes/source.html): it renders
as a small superscript link to the entry of _data/sources.yml, also inside a table cell, and
an id the data file lacks stops the build instead of leaving an empty link.

Each test builds a tiny site with this repository's configuration, includes, data and
plugins, offline (tests/jekyll.py).
"""

from __future__ import annotations

import html
import re
from pathlib import Path

import pytest
import yaml

from jekyll import SITE_MACHINERY, assert_clean_build, build_log, bundle, jekyll_build, tiny_site  # noqa: F401
from repository import ROOT

PAGE = """---
title: Sources
permalink: /sources/
---

The exporter changes the sign of each product.{% include source.html id="inertia-signs" %} Next.

| Field | What the exporter does |
|---|---|
| Color | The exporter copies the first part's colour.{% include source.html id="colour" %}{% include source.html id="mass-properties" %} |
"""


def link(entry: dict) -> str:
    """The HTML the include renders for an entry."""
    title = f'{entry["file"]}:{entry["lines"]} at {entry["tag"]}'
    return (f'<sup class="source"><a href="{entry["url"]}" title="{html.escape(title)}">'
            'source</a></sup>')


def test_the_link_renders_after_its_sentence_and_in_a_table_cell(bundle, tmp_path):
    data = yaml.safe_load((ROOT / "_data" / "sources.yml").read_text(encoding="utf-8"))
    source = tiny_site(tmp_path / "src", {"_pages/sources.md": PAGE})
    assert_clean_build(jekyll_build(source, tmp_path / "site"), "a page with source links")
    built = (tmp_path / "site" / "sources" / "index.html").read_text(encoding="utf-8")
    assert f'each product.{link(data["inertia-signs"])} Next.' in built
    cell = re.search(r"<td\b[^>]*>The exporter copies.*?</td>", built, re.S)
    assert cell, "the include broke the table row"
    assert link(data["colour"]) + link(data["mass-properties"]) in cell.group(0)


def test_an_unknown_id_stops_the_build(bundle, tmp_path):
    page = PAGE.replace('id="colour"', 'id="no-such-entry"')
    result = jekyll_build(tiny_site(tmp_path / "src", {"_pages/sources.md": page}), tmp_path / "site")
    assert result.returncode != 0, "the build should have failed:\n" + build_log(result)
    log = build_log(result)
    assert "undefined variable no-such-entry" in log and "sources.md" in log, log
