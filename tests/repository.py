"""Where the repository's parts are, for every test: the root, the pages, the practices."""

from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PAGES = ROOT / "_pages"
EXAMPLES = ROOT / "examples"


def page(path: str) -> str:
    """The text of a page under _pages/, e.g. page("practice-1/01-modelling.md")."""
    return (PAGES / path).read_text(encoding="utf-8")


def practice_numbers() -> list[int]:
    """The number of every practice the course registry finds, in order."""
    from course.practices import practices
    return [p.number for p in practices()]
