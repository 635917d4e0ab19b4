"""Open a package for checking, and collect findings.

The package is read by `sw2sim.package.find_package` (safely, see `sw2sim.xmlsafe`), or
given already read. Nothing here raises on bad input. What makes the input unusable (a
missing path, an unreadable file, XML that is not well-formed or declares entities, a
root that is not <robot>) becomes a "fatal" finding, and `Context.usable` turns false.
"""

from __future__ import annotations

import math
import os
from functools import lru_cache
from pathlib import Path

from lxml import etree

from .. import archive
from ..mesh_paths import package_files
from ..package import LoadError, Package, find_package
from .findings import ADVICE, FATAL, RULES, WARNING, Finding, Report, rule
from .repairs import DEFAULT, Options, Repair, repaired

rule("input-missing", FATAL, "input", "The path does not exist, or holds no URDF",
     symptom="`sw2sim check` stops at once and names the path.",
     cause="A typo in the path, or a folder that is not an exported package: the exporter "
           "keeps the URDF in `urdf/<name>.urdf`. A folder that holds one package further "
           "down is read as that package; one that holds several (a workspace's `src/`) "
           "lists them.",
     fix="Give the package folder (the one holding package.xml), the .urdf file itself or "
         "a .zip of the package.")
rule("input-unreadable", FATAL, "input", "The URDF cannot be read",
     symptom="The file exists but cannot be opened, or it is a folder, or it is empty.",
     cause="File permissions, a broken link, or an export that was interrupted; for a .zip, "
           "an archive that is damaged, encrypted, too large, or names files outside itself.",
     fix="Check the file's permissions, or export the package again; unzip an archive that "
         "cannot be read yourself and give the package folder.")
rule("xml-syntax", FATAL, "input", "The URDF is not well-formed XML",
     symptom="MuJoCo and ROS refuse the file with a parser error.",
     cause="Usually a hand edit: an unclosed tag, a missing quote, `<` or `&` in a value, "
           "or two root elements.",
     fix="Open the file at the line given and repair the XML there; `xmllint --noout` "
         "shows the same position.")
rule("xml-doctype", FATAL, "input", "The URDF declares a DOCTYPE or entities",
     symptom="`sw2sim check` refuses the file without reading further.",
     cause="URDF never needs a DOCTYPE. Entities can expand to gigabytes or read files "
           "outside the package, so they are not followed.",
     fix="Delete the <!DOCTYPE ...> block and write the values out in full (use xacro "
         "properties if you need named values).")
rule("not-urdf", FATAL, "input", "The XML is not a URDF",
     symptom="MuJoCo reports that the top-level element is unknown.",
     cause="A different XML file was given (an SDF world, a MuJoCo MJCF, a launch file), "
           "the file is a xacro that was never expanded, or it is no XML at all: a "
           "SolidWorks document, a STEP file, a mesh, or a URDF that Notepad saved with "
           "`.txt` added.",
     fix="Give the exported package folder or its .urdf; expand xacro files first with "
         "`xacro model.urdf.xacro > model.urdf`.")

rule("xacro-needs-package", FATAL, "input", "The xacro needs another ROS package",
     symptom="`sw2sim check` stops: the package holds a .xacro, no URDF, and the xacro "
             "includes or refers to files of another package with $(find ...).",
     cause="xacro resolves $(find other_package) through a ROS installation; outside ROS only "
           "the package itself can be found (its own $(find) is resolved to its folder).",
     fix="Expand the xacro where that package is installed (`xacro robot.urdf.xacro > "
         "robot.urdf` in a sourced ROS workspace) and check the URDF, or copy what it "
         "includes into this package.")
rule("xacro-failed", FATAL, "input", "The xacro cannot be expanded",
     symptom="`sw2sim check` stops with xacro's own message.",
     cause="An error in the xacro: an undefined property or macro, a bad expression, a "
           "missing include, or XML that is not well-formed.",
     fix="Correct the xacro where xacro's message points (`xacro robot.urdf.xacro` prints "
         "the same message), or give the expanded URDF.")
rule("urdf-several", WARNING, "input", "The package holds several URDFs",
     symptom="The check, convert, view and render read one of them; another may be the "
             "robot you meant.",
     cause="A copy (\"robot - Copy.urdf\"), an older export, or the URDF of a world or "
           "another robot beside the main one.",
     fix="Nothing, if the one named is the robot. Otherwise give --urdf NAME; or move the "
         "others out of the package.",
     blocks=ADVICE)

# How each kind of LoadError the package's reading raises is reported.
_RULE_OF_KIND = {"syntax": "xml-syntax", "doctype": "xml-doctype", "not-urdf": "not-urdf",
                 "unreadable": "input-unreadable", "xacro": "xacro-failed",
                 "xacro-package": "xacro-needs-package"}


class Context:
    """One package under check: its files, its parsed URDF, and what was found so far.

    Made from a path, it holds no package until `open_package` reads it; made from a
    Package, it checks that one (read elsewhere, e.g. by the command that converts it).
    """

    def __init__(self, source: str | os.PathLike | Package, options: Options = DEFAULT):
        self.options = options
        self.repairs: list[Repair] = []
        self.package: Package | None = None
        self.robot: etree._Element | None = None
        if isinstance(source, Package):
            self.package, self.robot = source, source.robot
            source = source.source if source.source is not None else source.root
        self.path = Path(source)
        self.report = Report(path=str(source))
        self._meshes: dict[Path, object] = {}
        self._contents: dict[Path, object] = {}    # each mesh file's content_key
        self._by_content: dict[object, object] = {}
        self._mesh_files: dict[str, Path | None] = {}
        self._files: list[Path] | None = None

    # -- reporting -------------------------------------------------------------------
    @property
    def findings(self) -> list[Finding]:
        return self.report.findings

    @property
    def usable(self) -> bool:
        return self.robot is not None and not any(f.severity == FATAL for f in self.findings)

    def add(self, rule_id: str, message: str, *, element=None, line: int | None = None,
            file: str | os.PathLike | None = None, fix: str | None = None,
            repair: Repair | None = None) -> Finding:
        """Record one finding of a registered rule; the file defaults to the URDF.

        `repair` is what convert does about this finding; it is dropped in strict mode."""
        known = RULES[rule_id]
        if self.options.strict:
            repair = None
        elif repair is not None:
            self.repairs.append(repair)
        if file is None and self.package is not None:
            file = self.package.urdf
        if line is None and element is not None:
            line = element.sourceline
        expanded = self.package.expanded_from if self.package is not None else None
        if expanded is not None and file is not None and Path(file) == self.package.urdf:
            # The URDF exists only as xacro's output: the line the .xacro writes it on, where
            # it is written there literally, else the expanded URDF's line, said.
            file, line, message = expanded, *self._xacro_line(line, message)
        finding = Finding(rule=rule_id, severity=known.severity, message=message,
                          fix=fix or known.fix, file=None if file is None else display(file),
                          line=line, blocks=known.blocks,
                          repair=None if repair is None else repair.says)
        self.findings.append(finding)
        return finding

    def _xacro_line(self, line: int | None, message: str) -> tuple[int | None, str]:
        from ..xacro_lines import element_at, parsed_xacro, xacro_line
        found = None if line is None else element_at(self.robot, line)
        if found is not None:
            if not hasattr(self, "_xacro"):
                self._xacro = parsed_xacro(self.package.expanded_from)
            mapped = None if self._xacro is None else xacro_line(self._xacro, *found)
            if mapped is not None:
                return mapped, message
        where = f"line {line} of " if line else ""
        return None, message + (f" ({where}the URDF the xacro expands to; `xacro "
                                f"{self.package.expanded_from.name}` prints it)")

    def repaired_package(self) -> Package | None:
        """The package as convert simulates it: with every repair made, in a copy."""
        return None if self.package is None else repaired(self.package, self.repairs)

    # -- the URDF --------------------------------------------------------------------
    @property
    def links(self) -> dict[str, etree._Element]:
        """Links by name (the first, where a name repeats)."""
        return self.package.links

    @property
    def joints(self) -> dict[str, etree._Element]:
        """Joints by name (the first, where a name repeats)."""
        return self.package.joints

    def package_files(self) -> list[Path]:
        """The package's files, relative to its folder (read once; see sw2sim.mesh_paths)."""
        if self._files is None:
            self._files = package_files(self.package.root) if self.package else []
        return self._files

    def mesh_file(self, mesh: etree._Element) -> Path | None:
        """The file a <mesh filename=...> names, if it resolves to a file inside the package."""
        filename = mesh.get("filename")
        if not filename or self.package is None:
            return None
        # Each rule asks again for each mesh; resolving follows links on disk every time.
        if filename not in self._mesh_files:
            try:
                found = self.package.resolve_mesh(in_folder_given(filename, self.package.name),
                                                  mesh.sourceline)
            except (LoadError, OSError, ValueError, RuntimeError):  # RuntimeError: a link loop
                found = None
            self._mesh_files[filename] = found
        return self._mesh_files[filename]

    def mesh(self, mesh: etree._Element):
        """The mesh a <mesh> element names as a `trimeshes.Mesh` in metres (scale applied),
        or None when it cannot be found or read (meshes.check reports why)."""
        path = self.mesh_file(mesh)
        if path is None:
            return None
        if path not in self._meshes:
            # Files with the same bytes (the exporter writes one per link: four wheels, four
            # files) are read once, and share one Mesh: measured and merged once too.
            key = self._contents[path] = content_key(path)
            if key not in self._by_content:   # the bytes just read: not read again
                self._by_content[key] = _read_mesh(path, key if isinstance(key, bytes) else None)
            self._meshes[path] = self._by_content[key]
        loaded = self._meshes[path]
        if loaded is None:
            return None
        try:
            scale = [float(s) for s in (mesh.get("scale") or "1 1 1").split()]
        except ValueError:
            scale = [math.nan]
        if not all(math.isfinite(s) for s in scale):
            return None  # a malformed scale: structure.py reports it
        if scale != [1.0, 1.0, 1.0] and len(scale) == 3:
            loaded = loaded.copy()
            loaded.apply_scale(scale)
        return loaded


    def mesh_content(self, mesh: etree._Element):
        """What stands for the file a <mesh> names (`content_key`): equal for two files with
        the same bytes; None when the file cannot be found."""
        path = self.mesh_file(mesh)
        if path is None:
            return None
        if path not in self._contents:
            self.mesh(mesh)
        return self._contents.get(path, path)


def content_key(path: Path):
    """A file's bytes, which a dict hashes once and compares in full; the path itself when
    it cannot be read (reading it fails again, and is reported, where the mesh is read)."""
    try:
        return path.read_bytes()
    except OSError:
        return path


def in_folder_given(filename: str, name: str) -> str:
    """A package:// path as the check reads it: in the package at hand (named `name`),
    whatever package it names. A different name is package-name-mismatch's one finding;
    the files behind it are still looked for, read and measured, so that one finding never
    hides what is wrong with each mesh."""
    if filename.startswith("package://"):
        other, slash, rest = filename[len("package://"):].partition("/")
        if slash and other != name:
            return f"package://{name}/{rest}"
    return filename


def _read_mesh(path: Path, data: bytes | None):
    from .trimeshes import read
    return read(path, data)


def display(path: str | os.PathLike) -> str:
    """A path as the user would type it: relative to the working folder when inside it.

    Links are not followed (a package.xml that links elsewhere is still "package.xml"), and
    nothing is read from disk but the working folder's real name, once per folder: a report
    may hold thousands of findings."""
    inside = archive.shown(path)
    if inside is not None:
        return display(inside)
    path = Path(os.path.abspath(path))
    cwd = os.getcwd()
    for base in (Path(os.path.abspath(cwd)), _real(cwd)):
        try:
            return str(path.relative_to(base))
        except ValueError:
            continue
    return str(path)


@lru_cache(maxsize=16)
def _real(folder: str) -> Path:
    return Path(folder).resolve()


def open_package(source: str | os.PathLike | Package, options: Options = DEFAULT,
                 urdf: str | None = None) -> Context:
    """A Context for the package at `source` (read here unless it is a Package already;
    `urdf` picks one of several URDFs); input problems become fatal findings."""
    ctx = Context(source, options)
    if ctx.package is not None:
        return ctx
    given = Path(source)
    if not given.exists():
        ctx.add("input-missing", f"{display(given)} does not exist", file=given,
                fix="check the path; give the package folder or its .urdf file")
        return ctx
    try:
        ctx.package = find_package(source, urdf)
    except LoadError as exc:
        if exc.kind == "unsafe":    # "what is wrong; how to fix it"
            problem, _, fix = exc.message.partition("; ")
            ctx.add("input-unreadable", problem, file=exc.file, fix=fix or exc.fix)
        else:
            ctx.add(_RULE_OF_KIND.get(exc.kind, "input-missing"), exc.detail, file=exc.file,
                    line=exc.line, fix=exc.fix)
        return ctx
    ctx.robot = ctx.package.robot
    if (given.is_dir() and given.resolve() != ctx.package.root) or archive.is_zip(given):
        # the package found for a folder or an archive, where it is not the path given:
        # a urdf/ folder's package, the one package a wrapper folder or a zip holds
        ctx.report.path = display(ctx.package.root)
    _several(ctx)
    return ctx


def _several(ctx) -> None:
    package = ctx.package
    if not package.other_urdfs or not package.chosen_because:
        return
    chosen = package.urdf.relative_to(package.root).as_posix()
    others = [o.relative_to(package.root).as_posix() if o.is_absolute() and package.root in
              o.resolve().parents else str(o) for o in package.other_urdfs]
    ctx.add("urdf-several", f"read {chosen}, {package.chosen_because}; the package also holds "
            + ", ".join(others), file=package.urdf if package.expanded_from is None
            else package.expanded_from,
            fix=f"to read another, add --urdf {Path(others[0]).name} (or another name) to "
                "the command")
