"""Broken packages for the checker's tests, made by copying an example and editing it.

Every rule's test module exposes BATTERY: {rule id: maker}, where a maker takes an empty
folder and returns the path to give `sw2sim check` (a package folder or a .urdf file).
tests/tool/check/test_battery.py requires one maker for every registered rule.
"""

from __future__ import annotations

import re
import shutil
import zipfile
from pathlib import Path

from repository import ROOT

EXAMPLES = ROOT / "examples"


def copy_example(n: int, folder: Path, name: str | None = None) -> Path:
    """A copy of examples/example_<n> in `folder`, returned as the package folder.

    With `name`, the copy's folder is called so (its package.xml still says example_<n>).
    """
    target = Path(folder) / (name or f"example_{n}")
    shutil.copytree(EXAMPLES / f"example_{n}", target)
    return target


def zipped(folder: Path, archive_path: Path, *, backslashes=False, macos=False) -> Path:
    """`folder` zipped with the folder itself at the top, as "Send to > Compressed
    (zipped) folder" does; with backslashes in the names, as PowerShell 5's
    Compress-Archive writes them; with macOS's __MACOSX copies beside the files."""
    with zipfile.ZipFile(archive_path, "w", zipfile.ZIP_DEFLATED) as zf:
        for path in sorted(folder.rglob("*")):
            if path.is_file():
                name = path.relative_to(folder.parent).as_posix()
                zf.write(path, name.replace("/", "\\") if backslashes else name)
                if macos:
                    parent, _, base = name.rpartition("/")
                    zf.writestr(f"__MACOSX/{parent}/._{base}", b"\x00\x05\x16\x07 resource fork")
    return archive_path


def as_obj(package: Path, stray=None) -> Path:
    """The package with each binary STL rewritten as an OBJ of its merged triangles (the
    STL removed, the URDF naming the OBJ); `stray`, a point, is added to each as a corner
    that no face uses."""
    from sw2sim.check import trimeshes
    urdf = next((package / "urdf").glob("*.urdf"))
    text = urdf.read_text()
    for stl in sorted((package / "meshes").glob("*.STL")):
        mesh = trimeshes.read(stl)
        mesh.merge_vertices()
        lines = [f"v {x!r} {y!r} {z!r}" for x, y, z in mesh.vertices.tolist()]
        lines += [f"v {stray[0]!r} {stray[1]!r} {stray[2]!r}"] if stray is not None else []
        lines += [f"f {a} {b} {c}" for a, b, c in (mesh.faces + 1).tolist()]
        stl.with_suffix(".obj").write_text("\n".join(lines) + "\n")
        stl.unlink()
        text = text.replace(f"{stl.name}\"", f"{stl.stem}.obj\"")
    urdf.write_text(text)
    return package


def urdf_of(package: Path) -> Path:
    """The package's URDF file."""
    return next((package / "urdf").glob("*.urdf"))


def edit(path: Path, old: str, new: str, count: int = 1) -> Path:
    """Replace `old` by `new` in a file (exactly `count` times; fails loudly if absent)."""
    text = path.read_text()
    found = text.count(old)
    if found < count:
        raise AssertionError(f"{old!r} occurs {found} times in {path}, expected {count}")
    path.write_text(text.replace(old, new, count))
    return path


def edit_re(path: Path, pattern: str, new: str, count: int = 1) -> Path:
    """Replace a regular expression in a file; fails loudly if it does not match."""
    text, n = re.subn(pattern, new, path.read_text(), count=count, flags=re.S)
    if n == 0:
        raise AssertionError(f"{pattern!r} not found in {path}")
    path.write_text(text)
    return path


def line_of(path: Path, needle: str) -> int:
    """The 1-based line number of the first line containing `needle`."""
    for number, line in enumerate(path.read_text().splitlines(), start=1):
        if needle in line:
            return number
    raise AssertionError(f"{needle!r} not in {path}")


# The exit status each severity gives a report that has nothing worse.
STATUS = {"fatal": 2, "error": 1, "warning": 0}


def fires_at(package: Path, rule_id: str, needle: str | None, file: Path | None = None):
    """Check `package` and assert `rule_id` fires: first at the line of `file` (default: the
    URDF) holding `needle` (no line when None), with the exit status of its severity, a
    message and a fix. Returns the report and the rule's findings."""
    from sw2sim.check import RULES, check

    report = check(package, stability=False)
    hits = [f for f in report.findings if f.rule == rule_id]
    assert hits, report.format()
    file = file or urdf_of(package)
    assert Path(hits[0].file).resolve() == file.resolve(), report.format()
    assert hits[0].line == (None if needle is None else line_of(file, needle)), report.format()
    assert report.status == STATUS[RULES[rule_id].severity], report.format()
    assert f"[{rule_id}]" in report.format()
    assert hits[0].message and hits[0].fix
    return report, hits


def group_findings(report, group: str) -> list:
    """The report's findings of one rule group."""
    from sw2sim.check import RULES
    return [f for f in report.findings if RULES[f.rule].group == group]
