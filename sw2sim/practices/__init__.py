"""The five practices: each is a subpackage with `design.py` (parts, robot) and `figures.py`.

`python -m sw2sim.practices` regenerates every example package under examples/.
"""

from importlib import import_module
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
PRACTICES = ["practice_1"]


def design(practice: str):
    """The `design` module of a practice, e.g. design("practice_1")."""
    return import_module(f"{__name__}.{practice}.design")


def package_dir(practice: str) -> Path:
    return ROOT / "examples" / design(practice).PACKAGE
