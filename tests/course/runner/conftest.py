"""Fixtures for the snippet runner's own tests: sample pages by name, run both ways."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import pytest

from course.snippets import Page, PageResult, parse_page, run_page

from repository import ROOT
SAMPLES = Path(__file__).resolve().parent / "samples"


@pytest.fixture
def load_sample() -> Callable[[str], Page]:
    """Parse `tests/course/runner/samples/<name>`."""
    return lambda name: parse_page(SAMPLES / name, ROOT)


@pytest.fixture(params=["forked", "plain"])
def fork(request) -> bool:
    """Whether the page process is forked from the fork server or a plain subprocess."""
    return request.param == "forked"


@pytest.fixture
def run_sample(fork) -> Callable[..., PageResult]:
    """Parse and run `tests/course/runner/samples/<name>` from the repository root, in a
    process forked from the fork server or in a plain subprocess (both are tested)."""
    return lambda name, timeout=None: run_page(parse_page(SAMPLES / name, ROOT), ROOT, timeout, fork=fork)
