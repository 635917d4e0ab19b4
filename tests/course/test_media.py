"""Every figure on the pages comes from code in this repository and matches what that code makes now.

A figure whose file and inputs are as the manifest recorded when `make media` made it is
what its code makes now, and is not made again; any other is made again and compared.
SW2SIM_REMAKE_FIGURES=1 makes every figure again, to check that this machine still draws
what the committed files show (after an update of the system's OpenGL, say).
"""

import os
import re
from concurrent.futures import ProcessPoolExecutor
from multiprocessing import get_context

import numpy as np
import pytest
from parallel_jobs import selected, workers
from PIL import Image

from course.media import all_figures, is_current, make_figure, read_manifest
from repository import ROOT

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
            problems.append(f"{where}: {src} is not produced by any Figure in course/practices/*/figures.py")
        elif not (ROOT / src).is_file():
            problems.append(f"{where}: {src} is missing; run `make media`")
    assert not problems, "\n".join(problems)


def test_every_figure_is_shown_somewhere():
    shown = {src for _, src in page_images()}
    unused = [f.output for f in FIGURES if f.output not in shown]
    assert not unused, f"figures no page shows: {unused}"


@pytest.fixture(scope="module")
def current():
    """Whether each figure's file and inputs are as the manifest recorded when `make media`
    made it: output -> bool."""
    manifest = read_manifest()
    return {f.output: is_current(f, manifest) for f in FIGURES}


def test_no_figure_is_stale(current):
    out_of_date = [output for output, ok in current.items() if not ok]
    assert not out_of_date, (
        f"inputs or files changed since `make media` made these; run `make media`: {out_of_date}")


@pytest.fixture(scope="module")
def made(request, tmp_path_factory, current):
    """The figures this session checks that the manifest cannot vouch for, made afresh by
    their code in worker processes, several at once: output -> (future, path of the file)."""
    remake_all = os.environ.get("SW2SIM_REMAKE_FIGURES") == "1"
    folder = tmp_path_factory.mktemp("figures")
    # spawn: a worker starts clean, without the GL contexts and threads of this process
    with ProcessPoolExecutor(workers(), mp_context=get_context("spawn")) as pool:
        jobs = {}
        for fig in selected(request, "test_figure_matches_what_its_code_makes", "fig"):
            if remake_all or not current[fig.output]:
                path = folder / fig.output
                path.parent.mkdir(parents=True, exist_ok=True)
                jobs[fig.output] = (pool.submit(make_figure, fig.output, path), path)
        yield jobs
        pool.shutdown(cancel_futures=True)


@pytest.mark.parametrize("fig", FIGURES, ids=[f.output for f in FIGURES])
def test_figure_matches_what_its_code_makes(fig, made, current):
    if fig.output not in made:
        # The manifest vouches for it: its bytes are those `make media` wrote when its code,
        # every module that code imports, the files it reads and the libraries' versions
        # were all as they are now.
        assert current[fig.output]
        return
    job, fresh = made[fig.output]
    job.result()  # re-raises whatever the figure's code raised
    if fig.path.suffix == ".svg":
        assert fresh.read_text() == fig.path.read_text(), f"{fig.output} differs; run `make media`"
        return
    a = np.asarray(Image.open(fig.path).convert("RGB"), dtype=float) / 255
    b = np.asarray(Image.open(fresh).convert("RGB"), dtype=float) / 255
    assert a.shape == b.shape, f"{fig.output}: size {a.shape} now {b.shape}; run `make media`"
    rms = float(np.sqrt(np.mean((a - b) ** 2)))
    assert rms <= PNG_RMS_TOLERANCE, f"{fig.output}: RMS difference {rms:.3f}; run `make media`"
