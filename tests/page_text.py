"""Helpers for tests that compare what a page shows with the files it describes."""

import re

from repository import ROOT


def fenced_blocks(text: str, language: str) -> list[str]:
    """The contents of a page's fences of one language (```xml, ```yaml, ...)."""
    return re.findall(rf"^[ \t]*```{re.escape(language)}\n(.*?)^[ \t]*```", text, re.S | re.M)


def xml_blocks(text: str) -> list[str]:
    """The contents of a page's ```xml fences."""
    return fenced_blocks(text, "xml")


def squash(xml: str) -> str:
    """XML with its layout removed, so a page's excerpt can be found in the file."""
    return re.sub(r"\s+", " ", xml).replace("> <", "><").strip()


def flat_page(path: str) -> str:
    """A page of _pages/ (e.g. "practice-1/02-exporting.md") with its line breaks as
    spaces, so that a phrase may wrap."""
    return " ".join((ROOT / "_pages" / path).read_text(encoding="utf-8").split())
