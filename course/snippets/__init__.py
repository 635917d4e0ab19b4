"""Run the ```python blocks of the lesson pages as a reader pasting them in order would."""

from .execute import Failure, PageResult, run_page
from .parse import DEFAULT_TIMEOUT, Block, Page, ParseError, find_pages, parse_page
from .report import format_failure, format_skipped, format_summary

__all__ = [
    "DEFAULT_TIMEOUT",
    "Block",
    "Failure",
    "Page",
    "PageResult",
    "ParseError",
    "find_pages",
    "format_failure",
    "format_skipped",
    "format_summary",
    "parse_page",
    "run_page",
]
