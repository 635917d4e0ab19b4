"""Every ```python block of every lesson page runs, in page order, as a reader would run it."""

from pathlib import Path

import pytest

from sw2sim.snippets import find_pages, format_failure, format_skipped, parse_page, run_page

ROOT = Path(__file__).resolve().parents[1]
PAGES = find_pages(ROOT)


def test_pages_found():
    assert PAGES, f"no lesson pages under {ROOT / '_pages'}"


@pytest.mark.parametrize("path", PAGES, ids=lambda p: p.relative_to(ROOT).as_posix())
def test_page(path: Path, record_property) -> None:
    page = parse_page(path, ROOT)
    # Read by pytest_terminal_summary in tests/conftest.py (survives pytest-xdist).
    record_property("snippets_skipped", format_skipped(page.skipped))
    result = run_page(page, ROOT)
    record_property("snippets_ran", len(result.ran))
    if not result.ok:
        pytest.fail(format_failure(result), pytrace=False)
