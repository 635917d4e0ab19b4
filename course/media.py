"""Every figure on the site, and `python -m course.media` to bring them up to date.

Each practice lists its figures in `course/practices/<practice>/figures.py` as
`FIGURES = [Figure(...), ...]`. When a figure is made, media/manifest.json records the
hash of its inputs and a digest of the file written. Its inputs are the module that
draws it, every repository module that module (or a script it lists) imports, the files
it lists as read, and the versions of the libraries that can change it. A figure is
stale when either no longer matches: an input changed, or the file was changed by hand.
"""

from __future__ import annotations

import argparse
import ast
import hashlib
import json
import os
import sys
import time
from concurrent.futures import ProcessPoolExecutor, as_completed
from dataclasses import dataclass, field
from functools import cache
from importlib import import_module
from importlib.metadata import version
from multiprocessing import get_context
from pathlib import Path
from typing import Callable

from .practices import PRACTICES, ROOT

MANIFEST = ROOT / "media" / "manifest.json"
# Libraries whose version can change a figure: simulation, rendering, plots and their
# layout, meshes, the drawings' geometry, and the parsers of the files the scripts read.
RENDERERS = ("mujoco", "matplotlib", "numpy", "trimesh", "manifold3d", "pillow", "shapely",
             "scipy", "kiwisolver", "PyYAML", "lxml")


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
        module = Path(sys.modules[self.make.__module__].__file__)
        listed = _files(self.inputs)
        code = _imported_closure([module, *(f for f in listed if f.suffix == ".py")])
        for src in sorted({*listed, *code}):
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


def _module_file(name: str, script_dir: Path | None) -> Path | None:
    """The repository file that `import name` loads, or None if it is not in the repository.
    A script's own folder comes first on its path, as when it is run."""
    for folder in (script_dir, ROOT):
        if folder is None:
            continue
        base = folder.joinpath(*name.split("."))
        for candidate in (base.with_suffix(".py"), base / "__init__.py"):
            if candidate.is_file():
                return candidate
    return None


@cache
def _imports(file: Path) -> frozenset[Path]:
    """The repository files `file` imports, at the top or inside functions, and the
    `__init__.py` of every package on the way (Python runs those first)."""
    folder = file.parent
    in_package = (folder / "__init__.py").is_file()
    package = ".".join(folder.relative_to(ROOT).parts) if in_package else ""
    names: set[str] = set()
    for node in ast.walk(ast.parse(file.read_bytes(), str(file))):
        if isinstance(node, ast.Import):
            names.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                parts = package.split(".")[: len(package.split(".")) - node.level + 1]
                base = ".".join(parts + ([node.module] if node.module else []))
            names.add(base)
            names.update(f"{base}.{alias.name}" for alias in node.names)  # may be modules
    found: set[Path] = set()
    for name in filter(None, names):
        parts = name.split(".")
        for i in range(1, len(parts) + 1):
            path = _module_file(".".join(parts[:i]), None if in_package else folder)
            if path is not None:
                found.add(path)
    return frozenset(found)


def _imported_closure(start: list[Path]) -> set[Path]:
    """`start` and every repository file they import, directly or not, except this module:
    every figure module imports it for `Figure`, and it draws nothing."""
    seen: set[Path] = {Path(__file__).resolve()}
    todo = list(start)
    while todo:
        file = todo.pop()
        if file not in seen:
            seen.add(file)
            todo.extend(_imports(file))
    return seen - {Path(__file__).resolve()}


def output_digest(path: Path) -> str:
    """A digest of a figure file's bytes, as recorded in the manifest when it was made."""
    return hashlib.sha256(path.read_bytes()).hexdigest()[:16]


def all_figures() -> list[Figure]:
    figures: list[Figure] = []
    for practice in PRACTICES:
        module = import_module(f"course.practices.{practice}.figures")
        figures.extend(module.FIGURES)
    return figures


def make_figure(output: str, path: str | Path) -> float:
    """Make the figure whose output is `output` into `path`; return the seconds it took.

    It takes names, not a Figure, so that a worker process can run it: `make media` and
    the tests make several figures at once, each in a process of its own.
    """
    start = time.perf_counter()
    for fig in all_figures():
        if fig.output == output:
            fig.make(Path(path))
            return time.perf_counter() - start
    raise KeyError(f"no figure makes {output}")


def read_manifest() -> dict[str, dict[str, str]]:
    """output -> {"inputs": input hash, "output": digest of the file} as last made."""
    return json.loads(MANIFEST.read_text()) if MANIFEST.is_file() else {}


def is_current(fig: Figure, manifest: dict[str, dict[str, str]]) -> bool:
    """Whether the file is exactly what was made from inputs all as they are now."""
    entry = manifest.get(fig.output)
    return (isinstance(entry, dict) and fig.path.is_file()
            and entry.get("output") == output_digest(fig.path)
            and entry.get("inputs") == fig.input_hash())


def stale(figures: list[Figure], manifest: dict[str, dict[str, str]]) -> list[Figure]:
    return [f for f in figures if not is_current(f, manifest)]


def cores() -> int:
    """The CPU cores this process may use."""
    if hasattr(os, "sched_getaffinity"):  # not on macOS
        return len(os.sched_getaffinity(0))
    return os.cpu_count() or 1


def _bar(done: int, total: int, width: int = 24) -> str:
    filled = round(width * done / total) if total else width
    return "[" + "#" * filled + "-" * (width - filled) + f"] {done}/{total}"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m course.media", description=__doc__.splitlines()[0])
    parser.add_argument("--force", action="store_true", help="remake every figure")
    parser.add_argument("--check", action="store_true", help="only list stale figures; exit 1 if any")
    parser.add_argument("--jobs", type=int, default=cores(),
                        help="figures made at once, each in a process of its own (default: cores)")
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
    for fig in todo:
        fig.path.parent.mkdir(parents=True, exist_ok=True)
    interactive = sys.stdout.isatty()
    for i, (fig, seconds) in enumerate(_make_all(todo, args.jobs), start=1):
        manifest[fig.output] = {"inputs": fig.input_hash(), "output": output_digest(fig.path)}
        line = f"{_bar(i, len(todo))} {fig.output} ({seconds:.1f} s)"
        print(("\r\033[K" + line) if interactive else line, end="" if interactive and i < len(todo) else "\n",
              flush=True)
        MANIFEST.write_text(json.dumps(dict(sorted(manifest.items())), indent=2) + "\n")
    return 0


def _make_all(figures: list[Figure], jobs: int):
    """Make the figures, `jobs` at a time; yield (figure, seconds) as each is done."""
    if jobs <= 1:
        for fig in figures:
            yield fig, make_figure(fig.output, fig.path)
        return
    # spawn: each worker starts clean, as `python -m course.media` itself does
    pool = ProcessPoolExecutor(jobs, mp_context=get_context("spawn"))
    try:
        pending = {pool.submit(make_figure, fig.output, fig.path): fig for fig in figures}
        for job in as_completed(pending):
            yield pending[job], job.result()
    finally:
        pool.shutdown(cancel_futures=True)


if __name__ == "__main__":
    sys.exit(main())
