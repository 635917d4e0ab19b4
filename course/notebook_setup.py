"""The first code cell of every lesson notebook, and the files it fetches outside a clone.

In a clone of the repository the cell moves the kernel to the repository's root, where
the pages' code runs. Anywhere else it fetches the files the lesson reads
(`needed_files`, listed for every notebook in notebooks/files.json) from the course site,
at the addresses `on_site` gives, and installs sw2sim with pip if it is missing.
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

from . import freshness
from .practices import ROOT

# The first code cell of every notebook, with the notebook's name filled in (setup_code).
# It defines one function and removes it again, so the namespace the page's blocks see is
# the one the page runner gives them. `site` and `tool` are empty here: the site's build
# (_plugins/notebooks.rb) fills them in the copies it publishes, with the site's address
# and a pip requirement for sw2sim from the repository.
SETUP_TEMPLATE = '''\
def _set_up_the_lesson(notebook="@NOTEBOOK@", site="", tool=""):
    """Work where the lesson's files are. In a clone of the course repository that is its
    root. Anywhere else (an empty folder, Colab) it is the folder this notebook runs in:
    the files the lesson reads are fetched there from the course site (a file already
    there is kept), and sw2sim is installed with pip if it is missing."""
    import importlib
    import json
    import os
    import subprocess
    import sys
    import urllib.request
    from pathlib import Path

    here = Path.cwd().resolve()
    clones = [f for f in (here, *here.parents)
              if (f / "examples").is_dir() and (f / "course").is_dir()]
    root = clones[0] if clones else here
    if not clones:
        site = (os.environ.get("SW2SIM_COURSE_SITE") or site).rstrip("/")
        if not site:
            raise RuntimeError(
                "This notebook is not in a clone of the course repository and does not "
                "know the course site to fetch its files from. Set SW2SIM_COURSE_SITE to "
                "the site's address, or clone the repository and open the notebook in its "
                "notebooks/ folder.")
        try:
            with urllib.request.urlopen(f"{site}/notebooks/files.json", timeout=30) as answer:
                names = json.load(answer)[notebook]   # {file: where the site has it}
            fetched = 0
            for name, address in names.items():
                target = here / name
                if not target.exists():
                    target.parent.mkdir(parents=True, exist_ok=True)
                    with urllib.request.urlopen(f"{site}/{address}", timeout=30) as answer:
                        target.write_bytes(answer.read())
                    fetched += 1
        except (OSError, KeyError, ValueError) as error:
            raise RuntimeError(f"Could not fetch the lesson's files from {site}: {error}. Check "
                               "the address and your connection, then run this cell again.") from None
        print(f"{len(names)} lesson files in {here} ({fetched} fetched from {site})")
    if str(root) not in sys.path:
        sys.path.insert(0, str(root))  # import the lesson's modules (and a clone's sw2sim)
    try:
        import sw2sim  # noqa: F401  (chooses how MuJoCo draws: off-screen without a screen)
    except ImportError:
        if not tool:
            raise RuntimeError("sw2sim is not installed. In a clone of the course repository "
                               'run `pip install ".[course]"`, then restart the kernel.') from None
        print("Installing sw2sim and the lessons' libraries:", tool)
        subprocess.check_call([sys.executable, "-m", "pip", "install", "--quiet", tool])
        importlib.invalidate_caches()
        import sw2sim  # noqa: F401
    os.chdir(root)
    sys.argv = [""]  # the pages' scripts see an empty command line, as in a Python prompt
    print("Working in", root)


_set_up_the_lesson()
del _set_up_the_lesson'''


def setup_code(name: str) -> str:
    """The first code cell of the notebook called `name`."""
    return SETUP_TEMPLATE.replace("@NOTEBOOK@", name)


# Where the site publishes the lesson modules (course/...) notebooks import: under
# notebooks/, so that the course build itself stays out of the site.
MODULES_ON_SITE = "notebooks/modules/"


def on_site(name: str) -> str:
    """Where the site publishes a file a notebook fetches."""
    return name if name.startswith("examples/") else MODULES_ON_SITE + name


def needed_files(sources: list[str], root: Path = ROOT) -> list[str]:
    """The repository files a notebook's code cells (`sources`) read, as paths from the
    root: what its setup cell fetches from the site outside a clone. The tool (sw2sim/) is
    installed with pip instead."""
    modules, strings = read_by(sources)
    data = {f for text in strings for f in named_files(text, root)}
    for text in strings:   # a package named on its own, as in Path("examples") / "example_5"
        if re.fullmatch(r"[\w-]+", text) and (root / "examples" / text).is_dir():
            data.update(freshness.files_in(root / "examples" / text))
    # Code that reads one file of an example package may build the path to another: the
    # package comes whole.
    for file in list(data):
        parts = file.relative_to(root).parts
        if parts[0] == "examples" and len(parts) > 2:
            data.update(freshness.files_in(root / "examples" / parts[1]))
    files = freshness.imported_closure(sorted(modules)) | data   # __init__ files included
    names = {f.relative_to(root).as_posix() for f in files}
    return sorted(n for n in names if not n.startswith("sw2sim/"))


def read_by(sources: list[str]) -> tuple[set[Path], list[str]]:
    """The repository modules code imports, and the strings it holds (paths among them)."""
    modules: set[Path] = set()
    strings: list[str] = []
    for source in sources:
        modules |= freshness.imports_of(source)
        strings += [node.value for node in ast.walk(ast.parse(source))
                    if isinstance(node, ast.Constant) and isinstance(node.value, str)]
    return modules, strings


def named_files(text: str, root: Path) -> list[Path]:
    """The repository files a string names, if it is a relative path inside the repository."""
    if not re.fullmatch(r"[\w.-]+(?:/[\w.-]+)+/?|[\w-]+\.\w+", text) or ".." in text:
        return []
    return freshness.files_in(root / text)
