"""Every ```python block of every lesson page runs, in page order, as a reader would run it,
and prints what the page shows under it (_data/outputs/, course/snippets/outputs.py)."""

from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pytest
from parallel_jobs import selected, workers

from course.snippets import find_pages, format_failure, format_skipped, parse_page, run_page
from course.snippets import outputs

from repository import ROOT
PAGES = find_pages(ROOT)


def test_pages_found():
    assert PAGES, f"no lesson pages under {ROOT / '_pages'}"


@pytest.fixture(scope="module")
def runs(request):
    """The pages this session checks, each run in a fresh Python process of its own, several
    at once: path -> future of its PageResult."""
    with ThreadPoolExecutor(workers()) as pool:
        yield {path: pool.submit(run_page, parse_page(path, ROOT), ROOT)
               for path in selected(request, "test_page", "path")}
        pool.shutdown(cancel_futures=True)


@pytest.mark.parametrize("path", PAGES, ids=lambda p: p.relative_to(ROOT).as_posix())
def test_page(path: Path, record_property, runs) -> None:
    page = parse_page(path, ROOT)
    # Read by pytest_terminal_summary in tests/conftest.py (survives pytest-xdist).
    record_property("snippets_skipped", format_skipped(page.skipped))
    result = runs[path].result()
    record_property("snippets_ran", len(result.ran))
    if not result.ok:
        pytest.fail(format_failure(result), pytrace=False)
    # The same run checks the outputs the site shows under the blocks.
    if stale := outputs.differences(page, result, ROOT):
        pytest.fail(stale, pytrace=False)


def test_every_outputs_file_has_its_page():
    gone = [f.relative_to(ROOT).as_posix() for f in outputs.orphans(ROOT)]
    assert not gone, (f"outputs of pages that no longer exist: {', '.join(gone)}; "
                      f"`{outputs.COMMAND}` (all pages) removes them")
