"""_plugins/phone_figures.rb: a figure with a phone variant (course/phone.py) reaches the
page as a <picture> whose <source> offers the variant to narrow windows, a plot's in its
two files (for screens of 2 and 3 pixels to the CSS pixel) by their widths; the <img>
keeps its alt text, its own file and size. _plugins/sharp_images.rb: a plot's <img> offers
its sharp file (course/sharp.py) to screens of 2 pixels to the CSS pixel. Checked on a
tiny site published under a sub-path, as the Pages workflow builds it, and on the real
site (every variant and every sharp file is offered)."""

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

![A drawing with a phone variant](/media/drawing.svg)

![A photo without one](/media/photo.png)

![A plot wider than the column, with its sharp file](/media/wide.png)
"""
BASE = "/course"


@pytest.fixture(scope="module")
def tiny(bundle, tmp_path_factory) -> str:
    """The page, built under BASE with plot.png (1040 × 546), its sharp plot-2x.png,
    plot-phone.png (720 × 1080) and plot-phone-3x.png (1080 × 1620), drawing.svg and
    drawing-phone.svg, photo.png, and wide.png (1560 × 598) with its sharp file twice the
    widest column (2016 px): its HTML."""
    source = tmp_path_factory.mktemp("phone-src")
    for name in SITE_MACHINERY:
        copy = shutil.copytree if (ROOT / name).is_dir() else shutil.copy2
        copy(ROOT / name, source / name)
    (source / "tools").symlink_to(ROOT / "tools", target_is_directory=True)
    (source / "_pages").mkdir()
    (source / "_pages" / "figures.md").write_text(PAGE, encoding="utf-8")
    (source / "media").mkdir()
    for name, size in (("plot.png", (1040, 546)), ("plot-2x.png", (2080, 1092)),
                       ("plot-phone.png", (720, 1080)), ("plot-phone-3x.png", (1080, 1620)),
                       ("photo.png", (960, 600)), ("wide.png", (1560, 598)),
                       ("wide-2x.png", (2016, 773))):
        Image.new("RGB", size, "white").save(source / "media" / name)
    for name, width in (("drawing.svg", 180), ("drawing-phone.svg", 100)):
        (source / "media" / name).write_text(
            f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}mm" height="60mm" '
            f'viewBox="0 0 {width} 60"></svg>', encoding="utf-8")
    config = source / "_config.base.yml"
    config.write_text(f'baseurl: "{BASE}"\n', encoding="utf-8")
    destination = tmp_path_factory.mktemp("phone-site")
    assert_clean_build(jekyll_build(source, destination, config), "the tiny site")
    return (destination / "figures" / "index.html").read_text(encoding="utf-8")


def test_a_figure_with_a_phone_variant_becomes_a_picture_under_the_sites_path(tiny):
    picture = re.search(r"<picture\b.*?</picture>", tiny, re.S)
    assert picture, tiny
    source = re.search(r"<source\b[^>]*>", picture[0])[0]
    assert f'srcset="{BASE}/media/plot-phone.png 720w, {BASE}/media/plot-phone-3x.png 1080w"' in source, \
        "both files, by their widths"
    assert 'sizes="(max-width: 59.99rem) calc(100vw - 2rem), calc(100vw - 22rem)"' in source, \
        "the column's width, for the browser to choose"
    assert 'width="720" height="1080"' in source, "the variant's own size"
    assert "max-width: 41.99rem" in source
    img = re.search(r"<img\b[^>]*>", picture[0])[0]
    assert f'src="{BASE}/media/plot.png"' in img and 'alt="A plot with a phone variant"' in img
    assert 'width="1040" height="546"' in img
    assert re.search(r'<figure class="figure"><picture\b.*?</picture><figcaption>A caption.</figcaption>',
                     tiny, re.S), "the caption stays the figure's"


def test_a_drawings_phone_variant_is_one_file(tiny):
    source = re.search(r'<source\b[^>]*drawing-phone[^>]*>', tiny)
    assert source and f'srcset="{BASE}/media/drawing-phone.svg"' in source[0], tiny
    assert "sizes=" not in source[0] and "3x" not in source[0]


def test_an_image_without_a_phone_variant_stays_an_img(tiny):
    assert tiny.count("<picture") == 2
    assert re.search(rf'<p><img\b[^>]*src="{BASE}/media/photo.png"[^>]*></p>', tiny), tiny


def test_the_site_offers_every_phone_variant_on_a_page(whole_site):  # noqa: F811
    offered = {candidate.split()[0].lstrip("/") for page in whole_site.rglob("*.html")
               for srcset in re.findall(r'<source [^>]*srcset="([^"]+)"', page.read_text(encoding="utf-8"))
               for candidate in srcset.split(",")}
    variants = {p.relative_to(ROOT).as_posix() for pattern in ("*-phone.*", "*-phone-3x.png")
                for p in (ROOT / "media").rglob(pattern)}
    assert len(variants) >= 25 and any(v.endswith("-3x.png") for v in variants)
    assert offered == variants, f"not offered: {sorted(variants - offered)}"


def test_a_plot_offers_its_sharp_file_by_its_width(tiny):
    """The <img> offers the plain and the sharp file by their widths, with the width the
    page shows it at (its own, or the column's where that is narrower, at most 63rem), and
    keeps its src and size; the photo offers nothing."""
    img = re.search(r'<img\b[^>]*src="[^"]*/plot.png"[^>]*>', tiny)[0]
    assert f'srcset="{BASE}/media/plot.png 1040w, {BASE}/media/plot-2x.png 2080w"' in img, img
    assert ('sizes="(max-width: 59.99rem) min(calc(100vw - 2rem), 1040px), '
            'min(calc(100vw - 22rem), 1040px, 63rem)"') in img, img
    assert 'width="1040" height="546"' in img
    wide = re.search(r'<img\b[^>]*src="[^"]*/wide.png"[^>]*>', tiny)[0]
    assert f'srcset="{BASE}/media/wide.png 1560w, {BASE}/media/wide-2x.png 2016w"' in wide, wide
    photo = re.search(r'<img\b[^>]*src="[^"]*/photo.png"[^>]*>', tiny)[0]
    assert "srcset" not in photo


def test_the_site_offers_every_sharp_file(whole_site):  # noqa: F811
    offered = {candidate.split()[0].lstrip("/") for page in whole_site.rglob("*.html")
               for srcset in re.findall(r'<img [^>]*srcset="([^"]+)"', page.read_text(encoding="utf-8"))
               for candidate in srcset.split(",")}
    sharp = {p.relative_to(ROOT).as_posix() for p in (ROOT / "media").rglob("*-2x.png")}
    assert len(sharp) >= 22 and {"media/practice-3/model-2x.png", "media/practice-1/joint_axes-2x.png"} <= sharp
    assert sharp <= offered, f"not offered: {sorted(sharp - offered)}"
