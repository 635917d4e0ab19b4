"""Every figure on the site, and `python -m sw2sim.media` to bring them up to date.

Each practice lists its figures in `sw2sim/practices/<practice>/figures.py` as
`FIGURES = [Figure(...), ...]`. A figure is stale when the hash of its inputs (the
module that draws it, the files it reads, the versions of the libraries that render
it) differs from the one recorded in media/manifest.json when it was last made.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import sys
import time
from dataclasses import dataclass, field
from importlib import import_module
from importlib.metadata import version
from pathlib import Path
from typing import Callable

from .practices import PRACTICES, ROOT

MANIFEST = ROOT / "media" / "manifest.json"
RENDERERS = ("mujoco", "matplotlib", "numpy", "trimesh", "manifold3d", "pillow")


@dataclass
class Figure:
    """One file under media/, and how to make it."""

    output: str                      # path from the repository root, e.g. media/practice-1/x.png
    make: Callable[[Path], None]     # writes the figure to the path it is given
    inputs: list[str] = field(default_factory=list)  # files or folders it reads, from the root
    caption: str = ""

    @property
    def path(self) -> Path:
        return ROOT / self.output

    def input_hash(self) -> str:
        h = hashlib.sha256()
        module = sys.modules[self.make.__module__]
        sources = [Path(module.__file__), *_files(self.inputs)]
        for src in sources:
            h.update(str(src.relative_to(ROOT)).encode())
            h.update(src.read_bytes())
        for lib in RENDERERS:
            h.update(f"{lib}=={version(lib)}".encode())
        h.update(self.make.__qualname__.encode())
        return h.hexdigest()[:16]


def _files(inputs: list[str]) -> list[Path]:
    out: list[Path] = []
    for rel in inputs:
        p = ROOT / rel
        if p.is_dir():
            out.extend(sorted(f for f in p.rglob("*") if f.is_file() and "__pycache__" not in f.parts))
        elif p.is_file():
            out.append(p)
        else:
            raise FileNotFoundError(f"figure input {rel!r} does not exist")
    return out


def all_figures() -> list[Figure]:
    figures: list[Figure] = []
    for practice in PRACTICES:
        module = import_module(f"sw2sim.practices.{practice}.figures")
        figures.extend(module.FIGURES)
    return figures


def read_manifest() -> dict[str, str]:
    return json.loads(MANIFEST.read_text()) if MANIFEST.is_file() else {}


def stale(figures: list[Figure], manifest: dict[str, str]) -> list[Figure]:
    return [f for f in figures if not f.path.is_file() or manifest.get(f.output) != f.input_hash()]


def _bar(done: int, total: int, width: int = 24) -> str:
    filled = round(width * done / total) if total else width
    return "[" + "#" * filled + "-" * (width - filled) + f"] {done}/{total}"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m sw2sim.media", description=__doc__.splitlines()[0])
    parser.add_argument("--force", action="store_true", help="remake every figure")
    parser.add_argument("--check", action="store_true", help="only list stale figures; exit 1 if any")
    parser.add_argument("only", nargs="*", help="make only figures whose path contains one of these")
    args = parser.parse_args(argv)

    figures = all_figures()
    if args.only:
        figures = [f for f in figures if any(s in f.output for s in args.only)]
    manifest = read_manifest()
    todo = figures if args.force else stale(figures, manifest)
    if args.check:
        for f in todo:
            print(f"stale: {f.output}")
        return 1 if todo else 0
    if not todo:
        print(f"media: all {len(figures)} figures are up to date")
        return 0
    interactive = sys.stdout.isatty()
    for i, fig in enumerate(todo, start=1):
        start = time.perf_counter()
        fig.path.parent.mkdir(parents=True, exist_ok=True)
        fig.make(fig.path)
        manifest[fig.output] = fig.input_hash()
        line = f"{_bar(i, len(todo))} {fig.output} ({time.perf_counter() - start:.1f} s)"
        print(("\r\033[K" + line) if interactive else line, end="" if interactive and i < len(todo) else "\n",
              flush=True)
        MANIFEST.write_text(json.dumps(dict(sorted(manifest.items())), indent=2) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
