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


def discover(folder: Path = Path(__file__).parent) -> list[str]:
    """The names of the practice_N packages in `folder`, in number order."""
    found = [(int(m["n"]), p.name) for p in folder.iterdir()
             if p.is_dir() and (m := _FOLDER.match(p.name)) and (p / "__init__.py").is_file()]
    return [name for _, name in sorted(found)]


PRACTICES: list[str] = discover()


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

    def missing(self) -> list[str]:
        """What this practice lacks of the parts every practice has, each with where it
        belongs; empty when it is whole."""
        gaps = []
        try:
            module = self.design
        except ImportError:
            gaps.append(f"design: course/practices/{self.name}/design.py")
        else:
            for name in ("PACKAGE", "robot", "parts", "write"):
                if not hasattr(module, name):
                    gaps.append(f"design: {name} in course/practices/{self.name}/design.py")
            package = ROOT / "examples" / getattr(module, "PACKAGE", f"example_{self.number}")
            if not (package / "package.xml").is_file() or not list(package.glob("urdf/*.urdf")):
                gaps.append(f"example package: {package.relative_to(ROOT)}/ "
                            f"(write it with `python -m course.practices {self.name}`)")
        try:
            if not getattr(self.figures, "FIGURES", None):
                gaps.append(f"figures: FIGURES in course/practices/{self.name}/figures.py")
        except ImportError:
            gaps.append(f"figures: course/practices/{self.name}/figures.py")
        pages = sorted(self.pages_dir.glob("*.md"))
        if not pages:
            gaps.append(f"pages: _pages/{self.slug}/*.md")
        navigation = (ROOT / "_data" / "navigation.yml").read_text(encoding="utf-8")
        if f"/{self.slug}/" not in navigation:
            gaps.append(f"navigation: an entry for /{self.slug}/ in _data/navigation.yml")
        if not self.test_file.is_file():
            gaps.append(f"tests: {self.test_file.relative_to(ROOT)}")
        if pages and not list((ROOT / "notebooks").glob(f"{self.slug}-*.ipynb")):
            gaps.append(f"notebook: notebooks/{self.slug}-*.ipynb (made by `python -m course`)")
        return gaps


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
