"""The practices, found by their folders.

A practice N is a set of folders and files of one shape; nothing lists them by hand:

    course/practices/practice_N/design.py    parts, dimensions, the robot, write()
    course/practices/practice_N/figures.py   FIGURES = [Figure(...), ...]
    examples/<design.PACKAGE>/                the exported package (written by write())
    _pages/practice-N/*.md                    the lesson pages
    media/practice-N/                         the figures
    tests/course/test_practice_N.py           the practice's own tests
    _data/navigation.yml                      an entry linking to the pages

`PRACTICES` holds the names of the practice_N packages found here, in number order;
`practices()` gives each as a `Practice` with its paths. `python -m course.practices`
regenerates every example package.
"""

from __future__ import annotations

import importlib.util
import re
from dataclasses import dataclass
from functools import cached_property
from importlib import import_module
from pathlib import Path

from .. import ROOT

_FOLDER = re.compile(r"^practice_(?P<n>[1-9]\d*)$")


def _discover() -> list[str]:
    here = Path(__file__).parent
    found = [(int(m["n"]), p.name) for p in here.iterdir()
             if p.is_dir() and (m := _FOLDER.match(p.name)) and (p / "__init__.py").is_file()]
    return [name for _, name in sorted(found)]


PRACTICES: list[str] = _discover()


@dataclass(frozen=True)
class Practice:
    """One practice and where each of its parts lives."""

    name: str  # "practice_3"

    @property
    def number(self) -> int:
        return int(self.name.rsplit("_", 1)[1])

    @property
    def slug(self) -> str:
        """The name the site uses: practice-3."""
        return f"practice-{self.number}"

    @cached_property
    def design(self):
        return design(self.name)

    @cached_property
    def figures(self):
        return import_module(f"{__name__}.{self.name}.figures")

    @property
    def package_dir(self) -> Path:
        return ROOT / "examples" / self.design.PACKAGE

    @property
    def pages_dir(self) -> Path:
        return ROOT / "_pages" / self.slug

    @property
    def media_dir(self) -> Path:
        return ROOT / "media" / self.slug

    @property
    def test_file(self) -> Path:
        return ROOT / "tests" / "course" / f"test_{self.name}.py"


def practices() -> list[Practice]:
    """Every practice, in number order."""
    return [Practice(name) for name in PRACTICES]


def design(practice: str):
    """The `design` module of a practice, e.g. design("practice_1")."""
    return import_module(f"{__name__}.{practice}.design")


def package_dir(practice: str) -> Path:
    return ROOT / "examples" / design(practice).PACKAGE


def load_script(path: str):
    """Import a lesson script (such as examples/example_1/scripts/periodic_force.py) by its path."""
    file = ROOT / path
    spec = importlib.util.spec_from_file_location(file.stem, file)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module
