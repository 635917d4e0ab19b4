"""Which file in a package a broken mesh path most likely means.

A package exported on Windows often names its meshes in ways only Windows forgives: a
different case (`base.stl` for `base.STL`), backslashes (`meshes\\base.STL`), an absolute
path of the exporting PC, or a folder the file is not in (a ROS 2 `setup.py` that installs
meshes flat). `matches` finds the files of the package that such a path can mean;
exactly one is a repair with one right answer, several or none are not. `closest` names
the files most like it, for a finding to show.
"""

from __future__ import annotations

import difflib
import os
from pathlib import Path, PurePosixPath

# Folders a package carries that never hold its meshes (version control, build output).
SKIPPED = {".git", ".hg", ".svn", "build", "devel", "install", "log", "__pycache__"}
# Files looked at, at most: a package is a few hundred files; a wrong path (a home folder)
# must not make the check walk a whole disk.
MAX_FILES = 20_000
MESH_SUFFIXES = {".stl", ".obj", ".msh", ".dae", ".ply", ".gltf", ".glb", ".3ds", ".off"}


def path_parts(filename: str) -> list[str]:
    """The parts of a mesh filename after its scheme and package name, with either slash."""
    text = filename.strip().replace("\\", "/")
    if text.startswith("package://"):
        text = text[len("package://"):].partition("/")[2]
    elif text.startswith("file://"):
        text = text[len("file://"):]
    return [p for p in PurePosixPath(text).parts if p not in ("/", ".", "..") and
            not (len(p) == 2 and p[1] == ":")]          # a drive letter, "C:"


def package_files(root: Path) -> list[Path]:
    """The regular files inside the package (not in version-control or build folders), as
    paths relative to `root`; links that lead outside the package are left out."""
    root = root.resolve()
    found: list[Path] = []
    for folder, dirs, files in os.walk(root):
        dirs[:] = sorted(d for d in dirs if d not in SKIPPED and not d.startswith("."))
        for name in sorted(files):
            path = Path(folder) / name
            try:
                real = path.resolve()
            except (OSError, RuntimeError):
                continue
            if root in real.parents and real.is_file():
                found.append(path.relative_to(root))
            if len(found) >= MAX_FILES:
                return found
    return found


def matches(files: list[Path], filename: str) -> list[Path]:
    """The files (relative paths) a mesh filename can mean, ignoring case and slashes: those
    with its file name whose folders agree with the most of its trailing folders. Where one
    of them agrees in capitals too, it is the file meant, and the only one returned (Linux
    would open it; its case variants beside it are copies)."""
    given = path_parts(filename)
    parts = [p.lower() for p in given]
    if not parts:
        return []
    same_name = [f for f in files if f.name.lower() == parts[-1]]
    best, chosen = -1, []
    for file in same_name:
        theirs = [p.lower() for p in file.parts]
        agree = 0
        while (agree < min(len(parts), len(theirs))
               and parts[-1 - agree] == theirs[-1 - agree]):
            agree += 1
        if agree > best:
            best, chosen = agree, [file]
        elif agree == best:
            chosen.append(file)
    exact = [f for f in chosen if list(f.parts[-best:]) == given[-best:]]
    return exact if len(chosen) > 1 and len(exact) == 1 else chosen


def case_variants(files: list[Path], file: Path) -> list[Path]:
    """The other files whose paths differ from `file`'s in capitals only."""
    key = file.as_posix().lower()
    return [f for f in files if f != file and f.as_posix().lower() == key]


def closest(files: list[Path], filename: str, count: int = 3) -> list[Path]:
    """The mesh files whose names are most like the one `filename` names."""
    parts = path_parts(filename)
    if not parts:
        return []
    meshes = [f for f in files if f.suffix.lower() in MESH_SUFFIXES]
    by_name: dict[str, list[Path]] = {}
    for file in meshes:
        by_name.setdefault(file.name.lower(), []).append(file)
    names = difflib.get_close_matches(parts[-1].lower(), list(by_name), n=count, cutoff=0.5)
    return [f for name in names for f in by_name[name]][:count]
