"""The error every command reports a package it cannot use with."""

from __future__ import annotations

from pathlib import Path

from .archive import shown


class LoadError(Exception):
    """A package that cannot be loaded; the message names the file (and line) and the fix."""

    # What kind of problem it is, for tools that sort them (sw2sim check): "invalid" (the
    # default), "missing" (no such file), "unreadable" (a pipe, a folder, too large, empty),
    # "syntax" (not well-formed XML), "doctype" (a URDF declaring a DOCTYPE), "not-urdf"
    # (another kind of XML), "unsafe" (a path leading outside the package). `fix` is what
    # to do, when the message does not say it already; `detail` is the problem in the words
    # `sw2sim check` reports it with (the message, unless it is given).
    def __init__(self, file: Path | str, message: str, line: int | None = None, *,
                 kind: str = "invalid", fix: str | None = None, detail: str | None = None):
        self.file, self.line, self.message, self.kind = str(file), line, message, kind
        self.fix, self.detail = fix, message if detail is None else detail
        named = shown(self.file) or self.file   # a file of an unpacked .zip: through it
        where = f"{named}:{line}" if line else named
        super().__init__(f"{where}: {message}" + (f"; {fix}" if fix else ""))
