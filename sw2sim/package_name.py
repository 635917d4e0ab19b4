"""The name of a package that has no package.xml, from what its own files say.

A raw export copied into another repository keeps the exporter's files but loses its
folder's name (and often package.xml): `my_repo/arm/` holding `urdf/Arm_Assembly.urdf`
whose meshes are `package://Arm_Assembly/meshes/...`. The name its files agree on is the
one its mesh paths must resolve with, so it is read from them, in this order:

1. the URDF's `package://NAME/` mesh paths whose files are in this folder (the most used
   NAME, when several are);
2. the exporter's `export.log`: "Creating package directories with name NAME and save
   path ..." (ExportHelper.cs logs it before it writes anything);
3. the exporter's CSV beside the URDF (`urdf/NAME.csv`): its "Mesh Filename" column holds
   the same package:// paths the URDF was written with.

Only when none says anything is the folder's name used.
"""

from __future__ import annotations

import csv
import re
from collections import Counter
from pathlib import Path

from lxml import etree

from . import mesh_paths

LOG_LINE = re.compile(r"Creating package directories with name (\S+) and save path")
FOLDER = "the folder's name"
MESHES = "the URDF's package:// mesh paths"
MAX_READ = 1_000_000   # bytes of export.log or a CSV read at most


def from_files(root: Path, robot: etree._Element | None, urdf: Path | None) -> tuple[str, str]:
    """(name, where it came from) for the package folder `root`, which has no package.xml;
    `robot` is its URDF's <robot>, `urdf` the URDF's file."""
    named = _from_meshes(root, robot) if robot is not None else None
    if named:
        return named, MESHES
    named = _from_log(root / "export.log")
    if named:
        return named, "the exporter's export.log"
    for table in _csv_files(root, urdf):
        named = _from_csv(table)
        if named:
            return named, f"the exporter's {table.relative_to(root).as_posix()}"
    return _folder_name(root), FOLDER


def _folder_name(root: Path) -> str:
    return root.name if root.name not in ("", "..") else root.resolve().name


def _from_meshes(root: Path, robot: etree._Element) -> str | None:
    counts: Counter[str] = Counter()
    files = None
    for mesh in robot.iter("mesh"):
        filename = (mesh.get("filename") or "").strip()
        if not filename.startswith("package://"):
            continue
        name = filename[len("package://"):].partition("/")[0]
        if not name:
            continue
        if files is None:
            files = mesh_paths.package_files(root)
        if mesh_paths.matches(files, filename):   # the file is here: this package's path
            counts[name] += 1
    return counts.most_common(1)[0][0] if counts else None


def _head(path: Path) -> str:
    try:
        with path.open("rb") as stream:
            return stream.read(MAX_READ).decode("utf-8", errors="replace")
    except OSError:
        return ""


def _from_log(log: Path) -> str | None:
    if not log.is_file():
        return None
    found = LOG_LINE.findall(_head(log))
    return found[-1] if found else None    # the last export, where the log holds several


def _csv_files(root: Path, urdf: Path | None) -> list[Path]:
    tables = []
    if urdf is not None:
        tables.append(urdf.with_suffix(".csv"))
    tables += sorted((root / "urdf").glob("*.csv")) if (root / "urdf").is_dir() else []
    return [t for t in dict.fromkeys(tables) if t.is_file()]


def _from_csv(table: Path) -> str | None:
    rows = csv.reader(_head(table).splitlines())
    header = next(rows, [])
    columns = [i for i, title in enumerate(header)
               if title.strip() in ("Mesh Filename", "Collision Mesh Filename")]
    for row in rows:
        for i in columns:
            value = row[i].strip() if i < len(row) else ""
            if value.startswith("package://"):
                name = value[len("package://"):].partition("/")[0]
                if name:
                    return name
    return None
