"""Fixtures for the snippet runner's own tests: sample pages by name."""

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


@pytest.fixture
def run_sample() -> Callable[..., PageResult]:
    """Parse and run `tests/course/runner/samples/<name>` from the repository root."""
    return lambda name, timeout=None: run_page(parse_page(SAMPLES / name, ROOT), ROOT, timeout)
