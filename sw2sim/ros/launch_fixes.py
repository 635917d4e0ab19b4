"""Node types that older exports name and ROS Noetic no longer has, run as what they became.

The SolidWorks exporter wrote robot_state_publisher's node as `type="state_publisher"`
until April 2020 (ros/solidworks_urdf_exporter 33ab135, "Updated state_publisher to
robot_state_publisher to get rid of deprecated warning"). Up to ROS Melodic,
robot_state_publisher built `state_publisher` from the same source as
`robot_state_publisher` (CMakeLists.txt of melodic-devel: both from
src/joint_state_listener_node.cpp, the old name warning that it is deprecated); its
release 1.15.0, ROS Noetic's, removed it (CHANGELOG: "Remove state_publisher", #87).
Debian 12 ships 1.15.2: roslaunch says "cannot launch node of type
[robot_state_publisher/state_publisher]", starts the other nodes, and RViz has no
transforms for the robot's links.

`adapt()` leaves the user's files as they are: it writes a copy with the new name, every
other byte kept, and says what it changed, by file and line, so that the reader knows
what ran. A launch file of the same package that the launch file includes as
`$(find PACKAGE)/...` is adapted the same way, and the <include> pointed at its copy.
"""

from __future__ import annotations

import os
import re
import tempfile
from pathlib import Path

from lxml import etree

from .. import xmlsafe

# (package, old type) -> (new type, in which release and why)
RENAMED = {
    ("robot_state_publisher", "state_publisher"):
        ("robot_state_publisher", "ROS Noetic (robot_state_publisher 1.15.0)"),
}

# A comment, a CDATA section, or the start tag of a <node> or an <include> (attribute values
# may hold ">").
_TAG = re.compile(r"<!--.*?-->|<!\[CDATA\[.*?\]\]>"
                  r"|<(node|include)\b((?:[^>\"']|\"[^\"]*\"|'[^']*')*)>", re.S)
_ATTRIBUTE = re.compile(r"""([\w:.-]+)\s*=\s*(?:"([^"]*)"|'([^']*)')""")
_FIND = re.compile(r"\$\(find\s+([\w-]+)\)/(.+)")


def adapt(launch_file: Path, folder: Path) -> tuple[Path, list[str]]:
    """The launch file to give roslaunch, and what was changed in it.

    With nothing to change, `launch_file` itself and no notes. Otherwise a copy in
    `folder`/<package>/<its path in the package>, and notes such as
    "launch/display.launch:20: node type robot_state_publisher/state_publisher was renamed
    robot_state_publisher in ROS Noetic (robot_state_publisher 1.15.0); running that"."""
    given = Path(launch_file)
    package = _package_of(given.resolve())
    notes: list[str] = []
    adapted = _adapt(given.resolve(), package, Path(folder), notes, set())
    return adapted or given, notes


def _package_of(path: Path) -> tuple[str, Path] | None:
    """(name, root) of the ROS package holding `path`: the nearest package.xml above it."""
    for root in path.parents:
        manifest = root / "package.xml"
        if manifest.is_file():
            try:
                root_element = xmlsafe.parse_file(manifest, doctype=True)
            except (OSError, etree.XMLSyntaxError):
                return None
            name = None if root_element is None else root_element.findtext("name")
            return (name.strip(), root) if name and name.strip() else None
    return None


def _adapt(path: Path, package: tuple[str, Path] | None, folder: Path, notes: list[str],
           visiting: set[Path]) -> Path | None:
    """The adapted copy of `path`, or None when it needs no change."""
    if path in visiting:
        return None
    visiting.add(path)
    try:
        text = path.read_bytes().decode("utf-8")
    except (OSError, UnicodeDecodeError):
        return None           # roslaunch reports what is wrong with it
    inside = _inside(path, package)
    shown = inside or str(path)
    edits: list[tuple[int, int, str]] = []
    for tag in _TAG.finditer(text):
        if tag.group(1) is None:
            continue
        start = tag.start(2)
        attributes = {m.group(1): (start + m.start(m.lastindex), m.group(m.lastindex) or "")
                      for m in _ATTRIBUTE.finditer(tag.group(2))}
        if tag.group(1) == "node":
            edit = _renamed(text, attributes, shown, notes)
        else:
            edit = _included(attributes, package, folder, notes, visiting)
        if edit:
            edits.append(edit)
    if not edits:
        return None
    for begin, end, value in sorted(edits, reverse=True):
        text = text[:begin] + value + text[end:]
    # The copy lives elsewhere: $(dirname) must still name the original's folder.
    text = text.replace("$(dirname)", str(path.parent))
    target = folder / (f"{package[0]}/{inside}" if inside else path.name)
    _write(target, text.encode("utf-8"))
    return target


def _renamed(text: str, attributes: dict, shown: str,
             notes: list[str]) -> tuple[int, int, str] | None:
    pkg, kind = attributes.get("pkg"), attributes.get("type")
    if not pkg or not kind or (pkg[1], kind[1]) not in RENAMED:
        return None
    new, release = RENAMED[(pkg[1], kind[1])]
    line = text.count("\n", 0, kind[0]) + 1
    notes.append(f"{shown}:{line}: node type {pkg[1]}/{kind[1]} was renamed {new} in "
                 f"{release}; running that")
    return kind[0], kind[0] + len(kind[1]), new


def _included(attributes: dict, package: tuple[str, Path] | None, folder: Path,
              notes: list[str], visiting: set[Path]) -> tuple[int, int, str] | None:
    """An <include> of a launch file of the same package that needs adapting: pointed at
    its copy. Includes of other packages are left to roslaunch."""
    file = attributes.get("file")
    found = _FIND.fullmatch(file[1].strip()) if file and package else None
    if not found or found.group(1) != package[0]:
        return None
    included = (package[1] / found.group(2)).resolve()
    if not included.is_file():
        return None
    adapted = _adapt(included, package, folder, notes, visiting)
    return (file[0], file[0] + len(file[1]), str(adapted)) if adapted else None


def _inside(path: Path, package: tuple[str, Path] | None) -> str | None:
    """The path within its package (as the notes give it), or None outside one."""
    if package:
        try:
            return path.relative_to(package[1]).as_posix()
        except ValueError:
            pass
    return None


def _write(path: Path, data: bytes) -> None:
    """Write unless the file holds `data` already; through a rename, so that a launch of
    the same package starting at the same time never reads half a file."""
    if path.is_file() and path.read_bytes() == data:
        return
    path.parent.mkdir(parents=True, exist_ok=True)
    handle, scratch = tempfile.mkstemp(prefix=path.name + ".", dir=path.parent)
    with os.fdopen(handle, "wb") as stream:
        stream.write(data)
    os.chmod(scratch, 0o644)
    os.replace(scratch, path)
