"""From what a user gives a command to the package folder or URDF file that
`sw2sim.package.find_package` reads, and the URDFs a package folder holds.

People give more than the package folder: a .zip of it (sw2sim.archive), the folder a
download or an archive wraps around it, its `urdf/` folder, or a file that is no URDF at
all (the SolidWorks assembly, a STEP file, a mesh, a URDF Notepad saved as text). Where
the package is clear it is used; where it is not, LoadError says what was given and what
to give instead.
"""

from __future__ import annotations

from itertools import islice
from pathlib import Path

from . import archive
from .errors import LoadError


def package_path(path: Path) -> Path:
    """The package folder or URDF file that `path` stands for (LoadError if none)."""
    path = _package_folder(_unpacked(path))
    if path.is_file():
        _not_a_urdf(path)
    return path


def urdf_stem(path: Path) -> str:
    """A URDF's robot name from its file name: robot.urdf, robot.urdf.xacro, robot.xacro."""
    name = path.name
    for suffix in (".xacro", ".urdf"):
        if name.lower().endswith(suffix):
            name = name[:-len(suffix)]
    return name


def urdf_candidates(folder: Path) -> list[Path]:
    """The URDFs of a package folder, in urdf/ or at its top, then its xacros where no URDF
    of the same name sits beside them (an expanded URDF is preferred to its source)."""
    urdfs = sorted((folder / "urdf").glob("*.[uU][rR][dD][fF]")) + sorted(
        folder.glob("*.[uU][rR][dD][fF]"))
    names = {urdf_stem(u) for u in urdfs}
    xacros = [x for x in sorted((folder / "urdf").glob("*.xacro")) + sorted(folder.glob("*.xacro"))
              if urdf_stem(x) not in names]
    return urdfs + xacros


def no_urdf(folder: Path) -> None:
    """In a folder without a URDF, what it holds instead, with the fix: a URDF saved as
    text, or SolidWorks documents (a Pack and Go folder or zip, sent instead of an export)."""
    for saved in sorted((folder / "urdf").glob("*.[uU][rR][dD][fF].[tT][xX][tT]")):
        _not_a_urdf(saved)
    below = (p for depth in range(1, SEARCH_DEPTH + 1)
             for p in folder.glob("/".join(["*"] * depth)))
    documents = [p for p in islice(below, SEARCH_ENTRIES)
                 if p.suffix.lower() in (".sldasm", ".sldprt") and p.is_file()]
    if documents:
        assemblies = sum(p.suffix.lower() == ".sldasm" for p in documents)
        parts = len(documents) - assemblies
        counted = (f"{assemblies} assembl{'y' if assemblies == 1 else 'ies'}, "
                   f"{parts} part{'' if parts == 1 else 's'}")
        raise LoadError(folder, f"SolidWorks documents ({counted}), not an exported package",
                        kind="not-urdf", fix=_EXPORT)


def _unpacked(path: Path) -> Path:
    """The folder a .zip archive unpacks to (sw2sim.archive); any other path as it is."""
    if archive.is_zip(path):
        try:
            return archive.unpack(path, shown_as=str(path))
        except archive.ArchiveError as exc:
            raise LoadError(path, exc.message, kind=exc.kind, fix=exc.fix) from None
    kind = archive.other_archive(path)
    if kind:
        raise LoadError(path, f"a {kind} archive, which is not read here", kind="unreadable",
                        fix="unpack it and give the package folder it holds (a .zip is read "
                            "as it is)")
    return path


# Files people give instead of the package, by their ending: what each is, and what to give.
_EXPORT = ("export the assembly with the exporter (Tools > Export as URDF, with the assembly "
           "open) and give the package folder it writes")
NOT_URDFS = {
    (".sldasm", ".sldprt", ".slddrw"):
        ("a SolidWorks document ({ending}), not an export", _EXPORT),
    (".step", ".stp", ".iges", ".igs", ".x_t", ".x_b", ".3mf"):
        ("a CAD exchange file ({ending}), not a URDF package", _EXPORT),
    (".stl", ".dae", ".obj", ".ply", ".glb", ".gltf"):
        ("a mesh ({ending}), one part of a package",
         "give the package folder that holds it (the one with package.xml, urdf/ and meshes/)"),
    (".urdf.txt", ".xacro.txt"):
        ("a URDF saved with .txt added, as Notepad does when the type is Text Documents",
         "rename it without the .txt (in Explorer, turn on View > File name extensions "
         "to see it)"),
}


def _not_a_urdf(path: Path) -> None:
    """Refuse, with what to give instead, a file that by its ending is no URDF."""
    name = path.name.lower()
    for endings, (what, fix) in NOT_URDFS.items():
        if name.endswith(endings):
            raise LoadError(path, what.format(ending=path.suffix), kind="not-urdf", fix=fix)


# How far below a given folder a package is looked for, and how many folders at most.
SEARCH_DEPTH, SEARCH_FOLDERS = 3, 2000
SEARCH_ENTRIES = 20_000   # files and folders looked at for SolidWorks documents, at most
LISTED = 8   # packages named when a folder holds several


def _package_folder(path: Path) -> Path:
    """The package a folder stands for. A package's `urdf/` folder, or another of its
    folders that holds no package, stands for the package.
    A folder without package.xml or a URDF of its own that holds exactly one package up to
    SEARCH_DEPTH below (the folder a zip or a download wraps around an export) stands for
    that package; one that holds several is refused with their list."""
    if not path.is_dir() or (path / "package.xml").is_file():
        return path
    if path.name.lower() == "urdf" and (path.parent / "package.xml").is_file():
        return path.parent
    if urdf_candidates(path):
        return path
    found = _packages_below(path)
    if not found and (path.parent / "package.xml").is_file():
        return path.parent          # a package's meshes/, launch/ or config/ folder
    if len(found) == 1:
        return found[0]
    if found:
        names = [f"{f.relative_to(path).as_posix()}/" for f in found]
        inside = archive.shown(path)
        example = f"{path / names[0]}" if inside is None else None
        listed = ", ".join(names[:LISTED]) + (f" and {len(names) - LISTED} more"
                                               if len(names) > LISTED else "")
        raise LoadError(path, f"no URDF here, but {len(found)} packages below: {listed}",
                        kind="missing",
                        fix=f"give one of them, such as {example}" if example else
                        "unzip the archive and give one of them")
    return path


def _packages_below(top: Path) -> list[Path]:
    """The package folders under `top` (holding package.xml, or a URDF where a package keeps
    it), nearest first; not below a package, not in hidden folders or `__MACOSX`."""
    found, level, seen = [], [top], 0
    for _ in range(SEARCH_DEPTH):
        below = []
        for folder in level:
            try:
                children = sorted(c for c in folder.iterdir() if c.is_dir() and not c.is_symlink())
            except OSError:
                continue
            for child in children:
                seen += 1
                if seen > SEARCH_FOLDERS:
                    return found
                if child.name.startswith(".") or child.name == "__MACOSX":
                    continue
                if (child / "package.xml").is_file() or urdf_candidates(child):
                    found.append(child)
                else:
                    below.append(child)
        level = below
    return found
