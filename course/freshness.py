"""Whether a generated file is still what its inputs make, and the command line that
brings generated files up to date: what the figures (course.media) and the notebooks
(course.notebooks) share.

A generated file records a hash of its inputs when it is made: the repository modules its
code imports, directly or not (found by reading the code, not by running it), the files
it reads, and the versions of the libraries that can change it. It is current while that
hash holds and the file is as it was made.
"""

from __future__ import annotations

import argparse
import ast
import hashlib
import json
import os
from collections.abc import Callable, Iterable, Iterator, Mapping
from concurrent.futures import ProcessPoolExecutor, as_completed
from functools import cache
from importlib.metadata import version
from multiprocessing import get_context
from pathlib import Path
from typing import Any, TypeVar

from . import ROOT

T = TypeVar("T")


# What code imports ----------------------------------------------------------------------

def module_file(name: str, script_dir: Path | None = None) -> Path | None:
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


def imports_of(source: str | bytes, filename: str = "<code>", package: str | None = None,
               script_dir: Path | None = None) -> frozenset[Path]:
    """The repository files `source` imports, at the top or inside functions, and the
    `__init__.py` of every package on the way (Python runs those first).

    `package` is the package the code is in, for its relative imports (code in no package
    has none: with None they are ignored); `script_dir` the folder of a script, which comes
    first on its path."""
    names: set[str] = set()
    for node in ast.walk(ast.parse(source, filename)):
        if isinstance(node, ast.Import):
            names.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                if package is None:
                    continue
                parts = package.split(".")[: len(package.split(".")) - node.level + 1]
                base = ".".join(parts + ([node.module] if node.module else []))
            names.add(base)
            names.update(f"{base}.{alias.name}" for alias in node.names)  # may be modules
    found: set[Path] = set()
    for name in filter(None, names):
        parts = name.split(".")
        for i in range(1, len(parts) + 1):
            path = module_file(".".join(parts[:i]), script_dir)
            if path is not None:
                found.add(path)
    return frozenset(found)


@cache
def imports(file: Path) -> frozenset[Path]:
    """The repository files the module or script `file` imports (see `imports_of`)."""
    folder = file.parent
    in_package = (folder / "__init__.py").is_file()
    package = ".".join(folder.relative_to(ROOT).parts) if in_package else ""
    return imports_of(file.read_bytes(), str(file), package, None if in_package else folder)


def imported_closure(start: Iterable[Path], leave_out: Iterable[Path] = ()) -> set[Path]:
    """`start` and every repository file they import, directly or not. A file in
    `leave_out` is neither counted nor followed: a module every input imports for the
    build's own classes, say, which makes nothing."""
    left_out = set(leave_out)
    seen = set(left_out)
    todo = list(start)
    while todo:
        file = todo.pop()
        if file not in seen:
            seen.add(file)
            todo.extend(imports(file))
    return seen - left_out


# Hashes ----------------------------------------------------------------------------------

def files_in(path: Path) -> list[Path]:
    """The file `path`, or the files under the folder `path` (without __pycache__), sorted;
    nothing if there is no such file or folder."""
    if path.is_dir():
        return sorted(f for f in path.rglob("*") if f.is_file() and "__pycache__" not in f.parts)
    return [path] if path.is_file() else []


class Fingerprint:
    """A short hash of what an output is made from, fed piece by piece."""

    def __init__(self) -> None:
        self._hash = hashlib.sha256()

    def text(self, text: str | bytes) -> Fingerprint:
        self._hash.update(text.encode() if isinstance(text, str) else text)
        return self

    def files(self, files: Iterable[Path], root: Path = ROOT,
              separator: bytes = b"") -> Fingerprint:
        """Each file's path from `root`, then `separator`, then its bytes, in path order.
        (The figures' hashes have no separator, the notebooks' a NUL: each keeps its own,
        so the hashes already recorded stay valid.)"""
        for file in sorted(set(files)):
            self.text(file.relative_to(root).as_posix().encode() + separator + file.read_bytes())
        return self

    def libraries(self, names: Iterable[str]) -> Fingerprint:
        """The installed version of each library."""
        for name in names:
            self.text(f"{name}=={version(name)}")
        return self

    def hexdigest(self) -> str:
        return self._hash.hexdigest()[:16]


def output_digest(path: Path) -> str:
    """A digest of a generated file's bytes, recorded when it was made."""
    return hashlib.sha256(path.read_bytes()).hexdigest()[:16]


# Is it current? ----------------------------------------------------------------------------

def is_current(path: Path, recorded_inputs: str | None, inputs: Callable[[], str],
               as_made: Callable[[], bool]) -> bool:
    """Whether the file at `path` is exactly what was made from inputs all as they are now:
    it exists, it is as it was made (`as_made`: not changed by hand since), and the hash of
    its inputs recorded then is `inputs()` now. The cheaper tests come first."""
    return (path.is_file() and recorded_inputs is not None and as_made()
            and recorded_inputs == inputs())


def read_manifest(file: Path) -> dict[str, dict[str, str]]:
    """A manifest: output -> {"inputs": input hash, "output": digest of the file} as last made."""
    return json.loads(file.read_text()) if file.is_file() else {}


def write_manifest(file: Path, manifest: Mapping[str, Mapping[str, str]]) -> None:
    file.write_text(json.dumps(dict(sorted(manifest.items())), indent=2) + "\n")


def manifest_entry(path: Path, inputs: str) -> dict[str, str]:
    """What a manifest records of the file at `path`, just made from inputs hashed `inputs`."""
    return {"inputs": inputs, "output": output_digest(path)}


def is_recorded(manifest: Mapping[str, Any], output: str, path: Path,
                inputs: Callable[[], str]) -> bool:
    """Whether the manifest's entry for `output` says the file at `path` is current."""
    entry = manifest.get(output)
    return isinstance(entry, dict) and is_current(
        path, entry.get("inputs"), inputs, lambda: entry.get("output") == output_digest(path))


# Making them ---------------------------------------------------------------------------------

class Unavailable(Exception):
    """A file that cannot be made on this machine (a program it needs is not installed):
    it is kept as it is, and stays stale."""


def cores() -> int:
    """The CPU cores this process may use."""
    if hasattr(os, "sched_getaffinity"):  # not on macOS
        return len(os.sched_getaffinity(0))
    return os.cpu_count() or 1


def run_jobs(function: Callable[..., Any], jobs: Iterable[tuple[T, tuple]],
             at_once: int) -> Iterator[tuple[T, Any]]:
    """Call `function(*args)` for each (item, args) of `jobs`, `at_once` at a time, each in a
    process of its own; yield (item, what it returned) as each is done. With `at_once` 1,
    one after the other in this process. An error in one stops the others not yet started.

    The function must be importable by name: a worker is spawned, starting clean (without
    this process's threads and GL contexts), as `python -m ...` itself does."""
    jobs = list(jobs)
    if at_once <= 1:
        for item, args in jobs:
            yield item, function(*args)
        return
    pool = ProcessPoolExecutor(at_once, mp_context=get_context("spawn"))
    try:
        pending = {pool.submit(function, *args): item for item, args in jobs}
        for job in as_completed(pending):
            yield pending[job], job.result()
    finally:
        pool.shutdown(cancel_futures=True)


# The command line --------------------------------------------------------------------------------

def command_line(argv: list[str] | None, *, prog: str, description: str, force: str,
                 check: str, jobs: str, only: str) -> argparse.Namespace:
    """`prog [--check] [--force] [--jobs N] [only ...]`, with each option's help given:
    --check changes nothing and (see `report_stale`) exits 1 if anything is stale; --force
    makes everything again; --jobs, how many at once (default: the cores this process may
    use); `only`, strings that the paths to make must contain one of (see `chosen`)."""
    parser = argparse.ArgumentParser(prog=prog, description=description)
    parser.add_argument("--force", action="store_true", help=force)
    parser.add_argument("--check", action="store_true", help=check)
    parser.add_argument("--jobs", type=int, default=cores(), help=jobs)
    parser.add_argument("only", nargs="*", help=only)
    return parser.parse_args(argv)


def chosen(items: Iterable[T], only: list[str], path: Callable[[T], str]) -> list[T]:
    """The items whose path contains one of the strings `only`; all of them if it is empty."""
    items = list(items)
    return [i for i in items if any(s in path(i) for s in only)] if only else items


def report_stale(lines: Iterable[str]) -> int:
    """Print what --check found out of date, a line each; the exit status: 1 if anything."""
    found = 0
    for line in lines:
        print(line)
        found += 1
    return 1 if found else 0
