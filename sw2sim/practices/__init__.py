"""The five practices: each is a subpackage with `design.py` (parts, robot) and `figures.py`.

`python -m sw2sim.practices` regenerates every example package under examples/.
"""

import importlib.util
from importlib import import_module
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
PRACTICES = ["practice_1", "practice_2", "practice_3", "practice_4", "practice_5"]


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
