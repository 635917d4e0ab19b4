"""Helpers for tests that compare what a page shows with the files it describes."""

import re


def xml_blocks(text: str) -> list[str]:
    """The contents of a page's ```xml fences."""
    return re.findall(r"```xml\n(.*?)```", text, re.S)


def squash(xml: str) -> str:
    """XML with its layout removed, so a page's excerpt can be found in the file."""
    return re.sub(r"\s+", " ", xml).replace("> <", "><").strip()
