"""_plugins/phone_figures.rb: a figure with a phone variant (course/phone.py) reaches the
page as a <picture> whose <source> offers the variant to narrow windows; the <img> keeps
its alt text, its own file and size. Checked on a tiny site published under a sub-path,
as the Pages workflow builds it, and on the real site (every variant is offered)."""

from __future__ import annotations

import re
import shutil
from pathlib import Path

import pytest
from PIL import Image

from jekyll import SITE_MACHINERY, assert_clean_build, bundle, jekyll_build, whole_site  # noqa: F401
from repository import ROOT

PAGE = """\
---
title: Figures
permalink: /figures/
---

![A plot with a phone variant](/media/plot.png)
*A caption.*

![A photo without one](/media/photo.png)
"""
BASE = "/course"


@pytest.fixture(scope="module")
def tiny(bundle, tmp_path_factory) -> str:
    """The page, built under BASE with plot.png (1040 × 546), plot-phone.png (650 × 975)
    and photo.png: its HTML."""
    source = tmp_path_factory.mktemp("phone-src")
    for name in SITE_MACHINERY:
        copy = shutil.copytree if (ROOT / name).is_dir() else shutil.copy2
        copy(ROOT / name, source / name)
    (source / "tools").symlink_to(ROOT / "tools", target_is_directory=True)
    (source / "_pages").mkdir()
    (source / "_pages" / "figures.md").write_text(PAGE, encoding="utf-8")
    (source / "media").mkdir()
    for name, size in (("plot.png", (1040, 546)), ("plot-phone.png", (650, 975)), ("photo.png", (960, 600))):
        Image.new("RGB", size, "white").save(source / "media" / name)
    config = source / "_config.base.yml"
    config.write_text(f'baseurl: "{BASE}"\n', encoding="utf-8")
    destination = tmp_path_factory.mktemp("phone-site")
    assert_clean_build(jekyll_build(source, destination, config), "the tiny site")
    return (destination / "figures" / "index.html").read_text(encoding="utf-8")


def test_a_figure_with_a_phone_variant_becomes_a_picture_under_the_sites_path(tiny):
    picture = re.search(r"<picture\b.*?</picture>", tiny, re.S)
    assert picture, tiny
    source = re.search(r"<source\b[^>]*>", picture[0])[0]
    assert f'srcset="{BASE}/media/plot-phone.png"' in source
    assert 'width="650" height="975"' in source, "the variant's own size"
    assert "max-width: 41.99rem" in source
    img = re.search(r"<img\b[^>]*>", picture[0])[0]
    assert f'src="{BASE}/media/plot.png"' in img and 'alt="A plot with a phone variant"' in img
    assert 'width="1040" height="546"' in img
    assert re.search(r'<figure class="figure"><picture\b.*?</picture><figcaption>A caption.</figcaption>',
                     tiny, re.S), "the caption stays the figure's"


def test_an_image_without_a_phone_variant_stays_an_img(tiny):
    assert tiny.count("<picture") == 1
    assert re.search(rf'<p><img\b[^>]*src="{BASE}/media/photo.png"[^>]*></p>', tiny), tiny


def test_the_site_offers_every_phone_variant_on_a_page(whole_site):  # noqa: F811
    offered = {m for page in whole_site.rglob("*.html")
               for m in re.findall(r'<source [^>]*srcset="/(media/[^"]+)"', page.read_text(encoding="utf-8"))}
    variants = {p.relative_to(ROOT).as_posix() for p in (ROOT / "media").rglob("*-phone.*")}
    assert len(variants) >= 25
    assert offered == variants, f"not offered: {sorted(variants - offered)}"
