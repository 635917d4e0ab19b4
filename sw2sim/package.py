"""A package in the SolidWorks-to-URDF exporter's layout, found and read once.

`find_package` locates the URDF and the package root from a package folder or a .urdf
file (or from a .zip, a folder around the package, its urdf/ folder: `sw2sim.locate`),
reads package.xml and the URDF safely (`sw2sim.xmlsafe`), and returns a `Package`:
what every command needs to know about the package, read from disk once. The functions
that take a package (`load_package`, `world_fixed`, the `ros_control` readers,
`add_actuators`, `convert`, `check`) accept a path or a Package; `as_package` is how.

Nothing here changes a Package's tree; code that needs to change it works on a copy.
"""

from __future__ import annotations

import os
import re
from dataclasses import dataclass
from functools import cached_property
from pathlib import Path

from lxml import etree

from . import package_name, xmlsafe
from .errors import LoadError
from .locate import no_urdf, package_path, urdf_candidates, urdf_stem


@dataclass(frozen=True, eq=False)
class Package:
    """A package as read from disk: where its files are, and its parsed URDF.

    `robot` and `manifest` are shared by everything that reads the package: never change
    them (copy.deepcopy the element first, as `load_package` does).
    """

    root: Path          # the folder holding package.xml (or the URDF's folder when there is none)
    name: str           # the name package:// URLs must use
    urdf: Path
    robot: etree._Element                   # the URDF's <robot> element
    manifest: etree._Element | None = None  # package.xml's top element, when there is one
    source: str | os.PathLike | None = None  # the path it was read from, as given
    chosen_because: str = ""                 # why this URDF, when the package holds several
    other_urdfs: tuple[Path, ...] = ()       # the URDFs (and xacros) not chosen
    expanded_from: Path | None = None        # the .xacro the URDF was expanded from
    name_from: str = "package.xml"           # where `name` was read (sw2sim.package_name)

    @property
    def manifest_file(self) -> Path:
        return self.root / "package.xml"

    @cached_property
    def links(self) -> dict[str, etree._Element]:
        """Links by name (the first, where a name repeats)."""
        found: dict[str, etree._Element] = {}
        for link in self.robot.findall("link"):
            found.setdefault(link.get("name", ""), link)
        return found

    @cached_property
    def joints(self) -> dict[str, etree._Element]:
        """Joints by name (the first, where a name repeats)."""
        found: dict[str, etree._Element] = {}
        for joint in self.robot.findall("joint"):
            found.setdefault(joint.get("name", ""), joint)
        return found

    @property
    def world_fixed(self) -> bool:
        """Whether the URDF fixes its root link to a link named `world`.

        That is how a URDF says "bolted down" to Gazebo; without it the model falls free
        there, even though MuJoCo's URDF import welds a jointless root to the world.
        """
        return any(link.get("name") == "world" for link in self.robot.findall("link"))

    def resolve_mesh(self, filename: str, line: int | None = None) -> Path:
        """The file a URDF mesh filename names, inside the package; else LoadError."""
        return resolve_mesh(self, filename, self.urdf, line)


def as_package(source: str | os.PathLike | Package) -> Package:
    """`source` itself when it is a Package already, else the package it locates, read."""
    return source if isinstance(source, Package) else find_package(source)


def find_package(path: str | os.PathLike, urdf: str | None = None) -> Package:
    """Locate the URDF and the package root from a package folder or a .urdf file, and
    read both package.xml and the URDF; raise LoadError when they cannot be used.

    In a folder holding several URDFs (or xacros), `urdf` names the one to read (its file
    name, or its path inside the package); without it, `choose_urdf` decides.
    """
    given = path
    path = Path(path)
    if not path.exists():
        raise LoadError(path, "no such file or folder; give a package folder or a .urdf file",
                        kind="missing")
    path = package_path(path)   # a zip, a folder around the package, a stray file
    # A .urdf in urdf/ belongs to the folder above; given from inside urdf/ itself
    # (`sw2sim check my_robot.urdf`), its parent is ".", which has no name of its own.
    parent = path.parent
    in_urdf = Path(os.path.abspath(parent)).name == "urdf"
    root = path if path.is_dir() else (
        Path(os.path.normpath(parent / "..")) if in_urdf else parent)
    name = root.name if root.name not in ("", "..") else Path(os.path.abspath(root)).name
    manifest_file = root / "package.xml"
    if manifest_file.is_symlink() and root.resolve() not in manifest_file.resolve().parents:
        raise LoadError(manifest_file, "package.xml is a link to a file outside the package; "
                        "copy the file into the package instead", kind="unsafe")
    manifest, name_from = None, package_name.FOLDER
    if manifest_file.is_file():
        manifest = _read_manifest(manifest_file)
        found = manifest.findtext("name") if manifest is not None else None
        if found:
            name, name_from = found.strip(), "package.xml"
    else:   # a raw export copied elsewhere: what the exporter's log or CSV says, if anything
        name, name_from = package_name.from_files(root, None, None)
    because, others = "", ()
    if path.is_dir():
        candidates = urdf_candidates(path)
        if not candidates:
            no_urdf(path)
            raise LoadError(path, "no URDF found; an exported package keeps it in "
                            "urdf/<name>.urdf", kind="missing")
        chosen, because = choose_urdf(path, candidates, name, urdf)
        others = tuple(c for c in candidates if c != chosen)
    else:
        chosen = path
    chosen = chosen.resolve()
    expanded = None
    if _is_xacro(chosen):
        robot, expanded = _read_xacro(chosen, root.resolve(), name), chosen
    else:
        robot = _read_urdf(chosen)
    if manifest is None and not manifest_file.is_file():
        named, where = package_name.from_files(root, robot, chosen)
        if where == package_name.MESHES:   # the name its mesh paths resolve with wins
            name, name_from = named, where
    return Package(root=root.resolve(), name=name, urdf=chosen, robot=robot,
                   manifest=manifest, source=given, chosen_because=because,
                   other_urdfs=others, expanded_from=expanded, name_from=name_from)


def _is_xacro(path: Path) -> bool:
    return path.suffix.lower() == ".xacro"


def choose_urdf(folder: Path, candidates: list[Path], package: str,
                wanted: str | None) -> tuple[Path, str]:
    """The URDF to read, and why: the one asked for, else the one named like the package
    (package.xml's <name>), else the one the launch files load, else the one named like the
    folder, else the first by name."""
    if wanted:
        hits = [c for c in candidates if wanted in (c.name, urdf_stem(c)) or
                c.relative_to(folder).as_posix() == wanted.replace("\\", "/")]
        if not hits:
            listed = ", ".join(c.relative_to(folder).as_posix() for c in candidates)
            raise LoadError(folder, f"--urdf {wanted}: no such URDF in the package", kind="missing",
                            fix=f"choose one of {listed}")
        return hits[0], "asked for with --urdf"
    if len(candidates) == 1:
        return candidates[0], ""
    for c in candidates:
        if urdf_stem(c) == package:
            return c, f'named after the package ("{package}" in package.xml)'
    launched = _launched(folder, candidates)
    if launched is not None:
        return launched
    for c in candidates:
        if urdf_stem(c) == folder.name:
            return c, "named after the folder"
    return candidates[0], "the first by name"


def _launched(folder: Path, candidates: list[Path]) -> tuple[Path, str] | None:
    """The candidate a launch file of the package loads, and which launch file."""
    files = [f for pattern in ("*.launch", "*.launch.xml", "*.launch.py", "*.xml")
             for f in sorted((folder / "launch").glob(pattern))]
    for launch in dict.fromkeys(files):
        try:
            text = launch.read_text(encoding="utf-8", errors="replace")[:1_000_000]
        except OSError:
            continue
        for c in candidates:
            if re.search(rf"[/\\'\"\s]{re.escape(c.name)}(?![\w.])", text):
                return c, f"loaded by launch/{launch.name}"
    return None


def _read_xacro(xacro_file: Path, root: Path, name: str) -> etree._Element:
    """The URDF a .xacro expands to (see sw2sim.xacro_expand), read as any URDF is."""
    from .xacro_expand import ExpandError, NeedsPackage, expand
    try:
        raw = expand(xacro_file, root, name)
    except NeedsPackage as exc:
        raise LoadError(xacro_file, f"the xacro needs the package \"{exc.package}\" "
                        f"($(find {exc.package})), which only a ROS workspace can provide",
                        kind="xacro-package",
                        fix=f"expand it where {exc.package} is installed (`xacro "
                            f"{xacro_file.name} > {urdf_stem(xacro_file)}.urdf`) and give the "
                            "URDF, or copy what it includes into this package") from None
    except ExpandError as exc:
        raise LoadError(xacro_file, f"xacro cannot expand the file: {exc}", kind="xacro",
                        fix="correct the xacro where xacro's message points, or expand it "
                            "in ROS and give the URDF") from None
    except ImportError:
        raise LoadError(xacro_file, "the package holds a .xacro, and the xacro package is "
                        "not installed", kind="xacro",
                        fix="pip install xacro, or expand it first: xacro robot.urdf.xacro "
                            "> robot.urdf") from None
    try:
        robot = xmlsafe.parse_bytes(raw, url=None)
    except (xmlsafe.DoctypeDeclared, etree.XMLSyntaxError) as exc:
        raise LoadError(xacro_file, f"the expanded xacro is not well-formed XML ({exc})",
                        kind="xacro") from None
    if robot is not None and isinstance(robot.tag, str) and robot.tag.startswith("{"):
        _drop_namespaces(robot)
    if robot is None or robot.tag != "robot":
        raise LoadError(xacro_file, "the xacro does not expand to a <robot>", kind="not-urdf")
    # One attribute per line, so that a finding's line names one (sw2sim.xacro_lines).
    from .xacro_lines import laid_out
    return xmlsafe.parse_bytes(laid_out(robot), url=f"{xacro_file}#expanded")


def _read_manifest(file: Path) -> etree._Element | None:
    # A DOCTYPE is parsed (never expanded) here: the package checks report what it leaves.
    try:
        return xmlsafe.parse_file(file, doctype=True)
    except etree.XMLSyntaxError as exc:
        raise LoadError(file, f"not well-formed XML: {exc.msg}", exc.lineno,
                        kind="syntax") from None
    except xmlsafe.TooLarge as exc:
        raise LoadError(file, f"package.xml is {exc.size / 1e6:.0f} MB; a package manifest is "
                        "a few kilobytes", kind="unreadable",
                        fix="restore the exported package.xml") from None
    except OSError as exc:
        raise LoadError(file, f"cannot read package.xml ({_why(exc)})", kind="unreadable") from None


def _read_urdf(urdf: Path) -> etree._Element:
    try:
        raw = xmlsafe.read_bytes(urdf)
    except xmlsafe.NotRegularFile:
        raise LoadError(urdf, "the URDF is not a regular file (a pipe or a device)",
                        kind="unreadable", fix="give the exported .urdf file itself") from None
    except xmlsafe.TooLarge as exc:
        raise LoadError(urdf, f"the URDF is {exc.size / 1e6:.0f} MB; an exported URDF is a few "
                        "tens of kilobytes", kind="unreadable",
                        fix="give the exported .urdf, not another file") from None
    except OSError as exc:
        raise LoadError(urdf, f"cannot read the URDF ({_why(exc)})", kind="unreadable") from None
    if not raw.strip():
        raise LoadError(urdf, "the URDF is empty", kind="unreadable",
                        fix="export the package again")
    try:
        robot = xmlsafe.parse_bytes(raw, url=urdf)
    except xmlsafe.DoctypeDeclared as exc:
        raise LoadError(urdf, "the file declares a DOCTYPE; entities are not expanded", exc.line,
                        kind="doctype") from None
    except etree.XMLSyntaxError as exc:
        raise LoadError(urdf, f"not well-formed XML: {exc.msg}", exc.lineno or None,
                        kind="syntax", detail=exc.msg) from None
    if robot is not None and isinstance(robot.tag, str) and robot.tag.startswith("{"):
        _drop_namespaces(robot)
    if robot is None or robot.tag != "robot":
        tag = "nothing" if robot is None else f"<{robot.tag}>"
        raise LoadError(urdf, f"the root element is {tag}, a URDF starts with <robot>",
                        None if robot is None else robot.sourceline, kind="not-urdf",
                        detail=f"the top element is {tag}; a URDF starts with <robot name=\"...\">")
    return robot


def _drop_namespaces(root: etree._Element) -> None:
    """Read `<robot xmlns="...">` as `<robot>`: the reference parser (urdfdom) matches
    elements by their local names, so a namespaced URDF is a URDF."""
    for element in root.iter():
        if isinstance(element.tag, str) and element.tag.startswith("{"):
            element.tag = etree.QName(element).localname
        for name in [n for n in element.attrib if n.startswith("{")]:
            value = element.attrib.pop(name)
            element.set(etree.QName(name).localname, value)
    etree.cleanup_namespaces(root)


def _why(exc: OSError) -> str:
    return exc.strerror or type(exc).__name__


def resolve_mesh(package: Package, filename: str, urdf: Path, line: int | None) -> Path:
    """Turn a URDF mesh filename into a file inside the package, or raise LoadError."""
    if filename.startswith("package://"):
        rest = filename[len("package://"):]
        pkg, _, rel = rest.partition("/")
        if pkg != package.name:
            raise LoadError(urdf, f"mesh {filename!r} names package {pkg!r}, but this package is "
                            f"{package.name!r} (package.xml); rename one so they match", line)
        target = package.root / rel
    elif filename.startswith("file://"):
        target = Path(filename[len("file://"):])
    else:
        target = urdf.parent / filename
    target = target.resolve()
    if package.root not in target.parents:
        raise LoadError(urdf, f"mesh {filename!r} points outside the package folder {package.root}; "
                        "copy the mesh into meshes/ and use package://", line)
    if not target.is_file():
        raise LoadError(urdf, f"mesh {filename!r} not found (looked for {target}); "
                        "export again with meshes, or fix the path", line)
    return target
