"""Helpers for tests that compare what a page shows with the files it describes."""

import re


def fenced_blocks(text: str, language: str) -> list[str]:
    """The contents of a page's fences of one language (```xml, ```yaml, ...)."""
    return re.findall(rf"^[ \t]*```{re.escape(language)}\n(.*?)^[ \t]*```", text, re.S | re.M)


def xml_blocks(text: str) -> list[str]:
    """The contents of a page's ```xml fences."""
    return fenced_blocks(text, "xml")


def squash(xml: str) -> str:
    """XML with its layout removed, so a page's excerpt can be found in the file."""
    return re.sub(r"\s+", " ", xml).replace("> <", "><").strip()
