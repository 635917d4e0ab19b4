"""`sw2sim edits save|restore`: keep a package's hand edits across a re-export.

Both of the exporter's buttons rewrite the URDF and its CSV, package.xml, CMakeLists.txt,
config/joint_names_<name>.yaml and the two launch files, so exporting an assembly again
wipes whatever was added to those files by hand (colours, a `world` link, transmissions,
<gazebo> plugins, nodes in gazebo.launch, a controller YAML). `save` copies those files
into PKG/hand_edits/, a folder the exporter never writes; `restore`, after the re-export,
puts the saved template files back and carries the URDF's hand edits into the new URDF,
whose numbers it keeps (`sw2sim.edits.urdf_carry`).

The manifest holds no time, only the files and their SHA-256: saving an unchanged package
twice writes the same bytes (the course commits the lessons' saved copies).
"""

from __future__ import annotations

import json
import shutil
from dataclasses import dataclass, field
from pathlib import Path

from ..package import Package, find_package

FOLDER = "hand_edits"
SUFFIX = ".saved"   # on every saved copy (copy_of)
MANIFEST = "manifest.json"
# A file edited this long after the re-export wrote the URDF was edited by hand since.
EDITED_AFTER_S = 60.0


class NothingSaved(Exception):
    """The package has no saved hand edits to restore."""


class WouldLoseEdits(Exception):
    """The saved copy holds hand edits the package's URDF lacks: saving would lose them."""

    def __init__(self, edits: list[str]):
        self.edits = edits
        super().__init__(", ".join(edits))


class EditedSince(Exception):
    """Files that were changed after the re-export: restoring would overwrite that work."""

    def __init__(self, files: list[str]):
        self.files = files
        super().__init__(", ".join(files))


def exporter_files(package: Package) -> list[str]:
    """The text files the exporter writes into this package, as paths inside it (those
    present). The URDF comes first; the CSV is named after it, as the exporter names both."""
    urdf = package.urdf.relative_to(package.root).as_posix()
    stem = package.urdf.stem
    names = [urdf, f"urdf/{stem}.csv", "package.xml", "CMakeLists.txt",
             f"config/joint_names_{package.name}.yaml", "launch/display.launch",
             "launch/gazebo.launch"]
    return [n for n in dict.fromkeys(names) if (package.root / n).is_file()]


def _text(path: Path) -> str:
    """A file's text with its line ends as they are (read_text would turn CRLF into LF)."""
    return path.read_bytes().decode("utf-8")


def _digest(path: Path) -> str:
    import hashlib   # here: `sw2sim check` reads this module's names and saves nothing
    return hashlib.sha256(path.read_bytes()).hexdigest()


def readme(name: str) -> str:
    return f"""\
What this folder is
===================
Copies of the files of the package {name} that the SolidWorks-to-URDF exporter writes
(the URDF and its CSV, package.xml, CMakeLists.txt, the joint-names YAML and the two
launch files), saved with their hand edits by `sw2sim edits save`, each name ending in
.saved so that ROS never takes a copy for the package's own file. The exporter never
writes this folder, so the copies survive exporting the assembly again.

After a re-export, put the hand edits back with:

    sw2sim edits restore {name}

(give the package's folder). It restores the saved launch files, package.xml,
CMakeLists.txt and YAML, and carries the URDF's hand edits (colours, the world link,
joint dynamics, transmissions, <gazebo> elements) into the new URDF, keeping its numbers.
Save again after each hand edit: sw2sim edits save {name}
"""


def save(path, *, force: bool = False) -> list[str]:
    """Copy the package's exporter-written files into PKG/hand_edits/; return them.

    Saving right after a re-export, before restoring, would replace the hand edits with
    the bare export: raises WouldLoseEdits instead, unless `force` is given."""
    package = find_package(path)
    folder = package.root / FOLDER
    files = exporter_files(package)
    old = _manifest(folder)
    if old and not force and copy_of(folder, old["urdf"]).is_file() and old["urdf"] in files:
        from .urdf_carry import carry   # here: `sw2sim check` saves nothing
        missing = carry(_text(copy_of(folder, old["urdf"])),
                        _text(package.root / old["urdf"])).carried
        if missing:
            raise WouldLoseEdits(missing)
    for rel in (old or {}).get("files", {}):
        if rel not in files and copy_of(folder, rel).is_file():
            copy_of(folder, rel).unlink()   # a file the package no longer has
    for rel in files:
        target = copy_of(folder, rel)
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(package.root / rel, target)
    manifest = {"saved_by": "sw2sim edits save", "package": package.name, "urdf": files[0],
                "files": {rel: _digest(package.root / rel) for rel in files}}
    (folder / MANIFEST).write_text(json.dumps(manifest, indent=2) + "\n")
    (folder / "README.txt").write_text(readme(package.name))
    return files


def copy_of(folder: Path, rel: str) -> Path:
    """Where the saved copy of the package's file `rel` is: under FOLDER, its name ending
    in SUFFIX, so that no tool takes it for the package's own file (roslaunch looks for
    `roslaunch PKG gazebo.launch` in every folder of the package and refuses two)."""
    return folder / (rel + SUFFIX)


def _manifest(folder: Path) -> dict | None:
    try:
        return json.loads((folder / MANIFEST).read_text())
    except (OSError, ValueError):
        return None


@dataclass
class Restored:
    """What `restore` did, one line a thing, and what the user must look at."""

    done: list[str] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)


def restore(path, *, force: bool = False) -> Restored:
    """Put the saved hand edits back after a re-export (see the module's docstring).

    Raises NothingSaved when there is no saved copy, EditedSince (before writing anything)
    when a file was changed after the re-export and `force` is not given."""
    package = find_package(path)
    folder = package.root / FOLDER
    manifest = _manifest(folder)
    if manifest is None:
        raise NothingSaved(f"{package.root / FOLDER / MANIFEST} is missing")
    urdf = manifest["urdf"]
    saved_urdf = _text(copy_of(folder, urdf))
    new_urdf = _text(package.root / urdf) \
        if (package.root / urdf).is_file() else None
    if new_urdf is None:
        raise FileNotFoundError(f"{package.root / urdf} is missing: export the package first")
    exported = (package.root / urdf).stat().st_mtime
    templates = [rel for rel in manifest["files"] if rel != urdf and not rel.endswith(".csv")]
    edited = [rel for rel in templates
              if (package.root / rel).is_file()
              and (package.root / rel).read_bytes() != copy_of(folder, rel).read_bytes()
              and (package.root / rel).stat().st_mtime > exported + EDITED_AFTER_S]
    if edited and not force:
        raise EditedSince(edited)
    result = Restored()
    for rel in templates:
        current, copy = package.root / rel, copy_of(folder, rel)
        if current.is_file() and current.read_bytes() == copy.read_bytes():
            result.done.append(f"unchanged {rel}")
            continue
        current.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(copy, current)
        result.done.append(f"restored {rel} (the saved copy)")
    from .urdf_carry import carry   # here: `sw2sim check` restores nothing
    carried = carry(saved_urdf, new_urdf)
    if carried.text != new_urdf:
        (package.root / urdf).write_bytes(carried.text.encode("utf-8"))
    result.done += [f"{urdf}: carried {what}" for what in carried.carried]
    if not carried.carried:
        result.done.append(f"unchanged {urdf} (no hand edit missing from it)")
    result.warnings += [f"{urdf}: not carried: {what}" for what in carried.not_carried]
    gone, new = _joint_changes(saved_urdf, carried.text)
    if gone or new:
        said = "; ".join(part for part in (
            f"gone: {', '.join(gone)}" if gone else "",
            f"new: {', '.join(new)}" if new else "") if part)
        result.warnings.append(
            f"the joints differ from the saved URDF's ({said}); the restored files name the "
            f"old joints: check {', '.join(t for t in templates if t.startswith(('config/', 'launch/gazebo')))} "
            "and the URDF's transmissions by hand")
    return result


def _joint_changes(saved: str, new: str) -> tuple[list[str], list[str]]:
    from .. import xmlsafe
    before = [j.get("name") for j in xmlsafe.parse_bytes(saved.encode("utf-8")).iter("joint")
              if j.getparent().tag == "robot"]
    after = [j.get("name") for j in xmlsafe.parse_bytes(new.encode("utf-8")).iter("joint")
             if j.getparent().tag == "robot"]
    return [j for j in before if j not in after], [j for j in after if j not in before]
