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
from course.phone import DENSE_SUFFIX
from course.phone import SUFFIX as PHONE_SUFFIX
from course.sharp import SUFFIX as SHARP_SUFFIX
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


def page_links():
    """Every /media/ file a page links to (a drawing's whole sheet, under its views)."""
    for page in sorted((ROOT / "_pages").rglob("*.md")):
        for m in re.finditer(r"\]\((/media/[^)\s]+)\)", page.read_text()):
            yield m.group(1).lstrip("/")


def test_every_figure_is_shown_somewhere():
    shown = {src for _, src in page_images()} | set(page_links())
    unused = [f.output for f in FIGURES if f.output not in shown]
    assert not unused, f"figures no page shows or links to: {unused}"


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
    result = job.result()  # re-raises whatever the figure's code raised
    if isinstance(result, str):   # a program it needs is not installed here (RViz, say)
        pytest.skip(f"{fig.output} cannot be made here: {result}")
    # the figure, then its variants if it has them
    for output, made_now in zip(fig.outputs, (fresh, *fig.variants(fresh))):
        committed = ROOT / output
        if committed.suffix == ".svg":
            assert made_now.read_text() == committed.read_text(), f"{output} differs; run `make media`"
            continue
        a = np.asarray(Image.open(committed).convert("RGB"), dtype=float) / 255
        b = np.asarray(Image.open(made_now).convert("RGB"), dtype=float) / 255
        assert a.shape == b.shape, f"{output}: size {a.shape} now {b.shape}; run `make media`"
        rms = float(np.sqrt(np.mean((a - b) ** 2)))
        assert rms <= PNG_RMS_TOLERANCE, f"{output}: RMS difference {rms:.3f}; run `make media`"


def test_every_variant_is_made_by_the_figure_it_belongs_to():
    """media/ holds a phone variant (course/phone.py) and a plot's sharp file
    (course/sharp.py) for exactly the figures whose code makes them: none left over from a
    figure that no longer has one."""
    made = {output for fig in FIGURES for output in fig.outputs[1:]}
    on_disk = {p.relative_to(ROOT).as_posix()
               for pattern in (f"*{PHONE_SUFFIX}.*", f"*{PHONE_SUFFIX}{DENSE_SUFFIX}.*", f"*{SHARP_SUFFIX}.png")
               for p in (ROOT / "media").rglob(pattern)}
    assert on_disk == made, (f"left over: {sorted(on_disk - made)}; "
                             f"missing (run `make media`): {sorted(made - on_disk)}")


# The freshness mechanism the figures share with the notebooks (course/freshness.py).

def test_the_import_closure_follows_repository_imports_and_leaves_out_what_it_is_told(tmp_path):
    from course import freshness, media

    script = tmp_path / "script.py"
    script.write_text("import helper\n")
    (tmp_path / "helper.py").write_text(
        "import numpy\n\ndef later():\n    from course import plotting\n    import course.media\n")
    course = ROOT / "course"
    closure = freshness.imported_closure([script])
    assert {script, tmp_path / "helper.py", course / "__init__.py", course / "plotting.py",
            course / "media.py", course / "freshness.py"} <= closure
    assert not [f for f in closure if "site-packages" in f.parts]  # numpy is no repository file
    without = freshness.imported_closure([script], leave_out=[media.MODULE])
    assert course / "media.py" not in without and course / "freshness.py" not in without
    assert course / "plotting.py" in without


def test_a_fingerprint_changes_with_any_file_and_not_with_their_order(tmp_path):
    from course.freshness import Fingerprint

    a, b = tmp_path / "a.txt", tmp_path / "b.txt"
    a.write_text("one")
    b.write_text("two")
    first = Fingerprint().files([a, b], tmp_path).libraries(["numpy"]).hexdigest()
    assert first == Fingerprint().files([b, a, a], tmp_path).libraries(["numpy"]).hexdigest()
    assert first != Fingerprint().files([a, b], tmp_path, separator=b"\0").libraries(["numpy"]).hexdigest()
    b.write_text("three")
    assert first != Fingerprint().files([a, b], tmp_path).libraries(["numpy"]).hexdigest()
    assert len(first) == 16


def test_a_manifest_vouches_for_a_file_only_as_it_was_made_from_the_same_inputs(tmp_path):
    from course import freshness

    made = tmp_path / "figure.svg"
    made.write_text("<svg/>")
    manifest = {"figure.svg": freshness.manifest_entry(made, "inputs-1")}
    freshness.write_manifest(tmp_path / "manifest.json", manifest)
    manifest = freshness.read_manifest(tmp_path / "manifest.json")
    assert freshness.is_recorded(manifest, "figure.svg", made, lambda: "inputs-1")
    assert not freshness.is_recorded(manifest, "figure.svg", made, lambda: "inputs-2")
    assert not freshness.is_recorded(manifest, "other.svg", made, lambda: "inputs-1")
    made.write_text("<svg>by hand</svg>")

    def never() -> str:
        raise AssertionError("the inputs are not hashed when the file already tells")

    assert not freshness.is_recorded(manifest, "figure.svg", made, never)
    made.unlink()
    assert not freshness.is_recorded(manifest, "figure.svg", made, never)
    assert freshness.read_manifest(tmp_path / "none.json") == {}


@pytest.mark.parametrize("at_once", [1, 2])
def test_jobs_run_in_worker_processes_and_each_result_comes_back_with_its_item(tmp_path, at_once):
    from course import freshness

    files = []
    for i in range(3):
        files.append(tmp_path / f"{i}.txt")
        files[-1].write_text(str(i))
    done = dict(freshness.run_jobs(freshness.output_digest, [(f.name, (f,)) for f in files], at_once))
    assert done == {f.name: freshness.output_digest(f) for f in files}


def test_the_command_line_of_figures_and_notebooks(capsys):
    from course import freshness, media

    helps = dict(prog="p", description="d", force="f", check="c", jobs="j", only="o")
    args = freshness.command_line([], **helps)
    assert (args.check, args.force, args.jobs, args.only) == (False, False, freshness.cores(), [])
    args = freshness.command_line(["--check", "--jobs", "3", "a", "b"], **helps)
    assert (args.check, args.jobs, args.only) == (True, 3, ["a", "b"])
    assert freshness.chosen(["xa", "yb", "zc"], ["a", "b"], str) == ["xa", "yb"]
    assert freshness.chosen(["xa", "yb"], [], str) == ["xa", "yb"]
    assert freshness.report_stale([]) == 0
    assert freshness.report_stale(f"stale: {n}" for n in "xy") == 1
    assert capsys.readouterr().out == "stale: x\nstale: y\n"
    assert media.main(["--check", "no figure has this in its path"]) == 0
    assert capsys.readouterr().out == ""


def test_a_figure_that_cannot_be_made_here_is_kept_as_it_is_and_stays_stale(tmp_path, monkeypatch, capsys):
    from course import media

    kept = tmp_path / "rviz.png"
    kept.write_bytes(b"as committed")

    def make(path):
        raise media.Unavailable("RViz: not installed: rviz")

    monkeypatch.setattr(media, "all_figures", lambda: [media.Figure(str(kept), make)])
    monkeypatch.setattr(media, "MANIFEST", tmp_path / "manifest.json")
    assert media.make_figure(str(kept), kept) == "RViz: not installed: rviz"
    assert media.main(["--jobs", "1"]) == 0
    assert "kept as it is: RViz: not installed: rviz" in capsys.readouterr().out
    assert kept.read_bytes() == b"as committed"
    assert media.read_manifest() == {}
