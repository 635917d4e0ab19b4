"""The one way sw2sim reads XML, and finds the line an attribute is on.

A package's files are data, never instructions: entities are not expanded, no DTD is
loaded, nothing is fetched from the network, trees may not be huge, and a file that is
not a regular file (a named pipe, a device) or is larger than MAX_BYTES is refused before
it is opened. A document may not declare a DOCTYPE unless the caller allows one
(`doctype=True`: package.xml is read so, its DOCTYPE kept and never expanded). Every
module of sw2sim parses through here; a test of the tool's structure makes sure no other
module calls lxml's parsers.
"""

from __future__ import annotations

import os
import re
from collections import OrderedDict
from pathlib import Path

from lxml import etree

# Refuse files larger than this outright: an exported URDF is a few tens of kilobytes.
MAX_BYTES = 50_000_000


class NotRegularFile(OSError):
    """A named pipe or a device: reading it could wait for ever."""


class TooLarge(OSError):
    """A file larger than the limit; `size` is its size in bytes."""

    def __init__(self, path: str | os.PathLike, size: int):
        super().__init__(f"{path} is {size} bytes")
        self.size = size


class DoctypeDeclared(ValueError):
    """The document declares a DOCTYPE (or an entity); `line` is where, when known."""

    def __init__(self, line: int | None):
        super().__init__("the document declares a DOCTYPE")
        self.line = line


def parser() -> etree.XMLParser:
    """A new parser that never expands entities, loads a DTD or fetches anything."""
    return etree.XMLParser(resolve_entities=False, no_network=True, load_dtd=False,
                           huge_tree=False, remove_comments=False)


def read_bytes(path: str | os.PathLike, max_bytes: int = MAX_BYTES) -> bytes:
    """The bytes of a regular file of at most `max_bytes`.

    Raises IsADirectoryError, NotRegularFile, TooLarge or another OSError; a pipe or a
    device is refused from its metadata, without being opened.
    """
    path = Path(path)
    if path.is_dir():
        raise IsADirectoryError(path)
    if path.exists() and not path.is_file():
        raise NotRegularFile(f"{path} is not a regular file")
    size = path.stat().st_size
    if size > max_bytes:
        raise TooLarge(path, size)
    return path.read_bytes()


def parse_bytes(raw: bytes, *, url: str | os.PathLike | None = None,
                doctype: bool = False) -> etree._Element | None:
    """The root element of an XML document held in `raw` (from the file `url`, if any).

    Raises DoctypeDeclared for a document with a DOCTYPE unless `doctype` is true, and
    lxml's XMLSyntaxError for one that is not well-formed. (lxml gives None rather than
    an element only for a document libxml2 would already call empty; callers check.)
    """
    if not doctype and (b"<!DOCTYPE" in raw or b"<!ENTITY" in raw):
        raise DoctypeDeclared(raw[:raw.find(b"<!")].count(b"\n") + 1)
    root = etree.fromstring(raw, parser(), base_url=None if url is None else os.fspath(url))
    if root is not None and not doctype and root.getroottree().docinfo.doctype:
        # The byte test above cannot see a DOCTYPE in UTF-16 or UTF-32.
        raise DoctypeDeclared(None)
    if url is not None:
        _remember(os.fspath(url), _lines(raw))
    return root


def parse_file(path: str | os.PathLike, *, max_bytes: int = MAX_BYTES,
               doctype: bool = False) -> etree._Element | None:
    """The root element of the XML file at `path`: `read_bytes`, then `parse_bytes`."""
    return parse_bytes(read_bytes(path, max_bytes), url=path, doctype=doctype)


# The lines of the files parsed last, by file, for `source_line`. (lxml's elements cannot be
# weakly referenced, so the text is kept by file name, for a few files.)
_sources: OrderedDict[str, list[str]] = OrderedDict()
_KEEP = 8


def _remember(url: str, lines: list[str]) -> None:
    _sources[url] = lines
    _sources.move_to_end(url)
    while len(_sources) > _KEEP:
        _sources.popitem(last=False)


def _lines(raw: bytes) -> list[str]:
    # As a text file reads: UTF-8, newlines made "\n". lxml counts "\n" only, so the text is
    # split there and nowhere else.
    text = raw.decode("utf-8", errors="replace").replace("\r\n", "\n").replace("\r", "\n")
    return text.split("\n")


def _source(element) -> list[str]:
    """The lines of the file `element` was parsed from ([] when it is not known)."""
    url = element.getroottree().docinfo.URL
    if not url:
        return []
    if url not in _sources:   # parsed long ago: read the file again
        try:
            _remember(url, _lines(read_bytes(url)))
        except (OSError, ValueError):
            return []
    return _sources[url]


def source_lines(element) -> list[str]:
    """The lines of the file `element` was parsed from ([] when it is not known)."""
    return _source(element)


def source_line(element, attribute: str | None = "name") -> int | None:
    """The line holding `attribute` of `element`, else the line where its tag starts.

    lxml gives the line where a start tag ends; in the exporter's layout (one attribute
    per line) that is the last attribute's line, so the user would land on `type=` when
    the problem is the joint named two lines up.
    """
    end = element.sourceline
    if end is None:
        return None
    lines = _source(element)
    start = re.compile(rf"<{re.escape(element.tag)}(\s|/|>|$)")
    wanted = (re.compile(rf"(^|\s){re.escape(attribute)}\s*=")
              if attribute and element.get(attribute) is not None else None)
    for number in range(min(end, len(lines)), 0, -1):
        line = lines[number - 1]
        if (wanted and wanted.search(line)) or start.search(line):
            return number
    return end
