"""html-proofer (Debian's ruby-html-proofer 3.19) run over a folder of HTML, offline.

It checks that each internal link, image and script of every page points at a file of
the folder, that each #fragment names an element of its target page, and that each
image has alt text. External links are not followed. The run starts in the background
when the object is made; `result()` waits for it.
"""

from __future__ import annotations

import re
import shutil
import subprocess
import tempfile
from dataclasses import dataclass
from pathlib import Path

import pytest

OPTIONS = ["--disable-external", "--allow-hash-href", "--log-level", ":error"]
ANSI_COLOUR = re.compile(r"\x1b\[[0-9;]*m")
TIMEOUT_S = 300


@dataclass
class Result:
    passed: bool
    report: str  # what html-proofer printed, without colours


class HtmlProofer:
    def __init__(self, folder: Path):
        if shutil.which("htmlproofer") is None:
            pytest.fail("`htmlproofer` not found: run `make setup` "
                        "(it installs ruby-html-proofer).", pytrace=False)
        # A file, not a pipe: a long report must not stall the run until someone reads it.
        self._output = tempfile.TemporaryFile(mode="w+")
        self._result: Result | None = None
        self._process = subprocess.Popen(["htmlproofer", str(folder), *OPTIONS],
                                         stdout=self._output, stderr=subprocess.STDOUT, text=True)

    def result(self) -> Result:
        if self._result is None:
            self._process.wait(timeout=TIMEOUT_S)
            with self._output:
                self._output.seek(0)
                report = ANSI_COLOUR.sub("", self._output.read())
            self._result = Result(self._process.returncode == 0, report)
        return self._result

    def stop(self) -> None:
        if self._process.poll() is None:
            self._process.kill()
            self._process.wait()
        self._output.close()
