"""Every figure on the pages comes from code in this repository and matches what that code makes now."""

import re

import numpy as np
import pytest
from PIL import Image

from sw2sim.media import all_figures, read_manifest, stale
from sw2sim.practices import ROOT

FIGURES = all_figures()
BY_OUTPUT = {f.output: f for f in FIGURES}
IMAGE_REF = re.compile(r"!\[[^\]]*\]\((/[^)\s]+)|<img[^>]+src=\"(/[^\"]+)\"")
# A re-rendered picture may differ from the committed one by a few grey levels (another
# CPU's rounding in the software renderer); more than this is a different picture.
PNG_RMS_TOLERANCE = 0.02  # of full scale


def page_images():
    for page in sorted((ROOT / "_pages").rglob("*.md")):
        for n, line in enumerate(page.read_text().splitlines(), 1):
            for m in IMAGE_REF.finditer(line):
                yield f"{page.relative_to(ROOT)}:{n}", (m.group(1) or m.group(2)).lstrip("/")


def test_every_image_on_a_page_exists_and_is_made_by_code():
    problems = []
    for where, src in page_images():
        if src not in BY_OUTPUT:
            problems.append(f"{where}: {src} is not produced by any Figure in sw2sim/practices/*/figures.py")
        elif not (ROOT / src).is_file():
            problems.append(f"{where}: {src} is missing; run `make media`")
    assert not problems, "\n".join(problems)


def test_every_figure_is_shown_somewhere():
    shown = {src for _, src in page_images()}
    unused = [f.output for f in FIGURES if f.output not in shown]
    assert not unused, f"figures no page shows: {unused}"


def test_no_figure_is_stale():
    out_of_date = [f.output for f in stale(FIGURES, read_manifest())]
    assert not out_of_date, f"inputs changed since these were made; run `make media`: {out_of_date}"


@pytest.mark.parametrize("fig", FIGURES, ids=[f.output for f in FIGURES])
def test_figure_matches_what_its_code_makes(fig, tmp_path):
    fresh = tmp_path / fig.path.name
    fig.make(fresh)
    if fig.path.suffix == ".svg":
        assert fresh.read_text() == fig.path.read_text(), f"{fig.output} differs; run `make media`"
        return
    a = np.asarray(Image.open(fig.path).convert("RGB"), dtype=float) / 255
    b = np.asarray(Image.open(fresh).convert("RGB"), dtype=float) / 255
    assert a.shape == b.shape, f"{fig.output}: size {a.shape} now {b.shape}; run `make media`"
    rms = float(np.sqrt(np.mean((a - b) ** 2)))
    assert rms <= PNG_RMS_TOLERANCE, f"{fig.output}: RMS difference {rms:.3f}; run `make media`"
