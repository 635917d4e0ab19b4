"""The mesh rules of `sw2sim check`: files found inside the package, readable by MuJoCo, in
metres; and that a mesh path never makes the check open a file outside the package."""

from __future__ import annotations

import builtins
import io
import os
from pathlib import Path

import numpy as np
import pytest
import trimesh
from lxml import etree
from packages import EXAMPLES, copy_example, edit, fires_at, group_findings, line_of, urdf_of
from repository import practice_numbers

from sw2sim.check import all_rules, check
from sw2sim.check.geometry import millimetre_suspect
from sw2sim.check.meshes import _flatness

GROUP = "mesh"
STL = "package://example_1/meshes/base_link.STL"
WHEEL = "package://example_1/meshes/front_left_wheel.STL"


def _example_1(folder: Path, old: str, new: str, count: int = 1) -> Path:
    package = copy_example(1, folder)
    edit(urdf_of(package), old, new, count)
    return package


def _base_stl(folder: Path, data) -> Path:
    """Example 1 with its base_link.STL replaced by `data` (bytes, or a function of the old
    file's bytes)."""
    package = copy_example(1, folder)
    stl = package / "meshes" / "base_link.STL"
    stl.write_bytes(data(stl.read_bytes()) if callable(data) else data)
    return package


def _repeated(stl: bytes, times: int) -> bytes:
    """A binary STL with every triangle of `stl` repeated `times` times."""
    body = stl[84:] * times
    return stl[:80] + (len(body) // 50).to_bytes(4, "little") + body


def _outside(folder: Path) -> Path:
    package = copy_example(1, folder)
    (folder / "outside.STL").write_bytes((package / "meshes" / "base_link.STL").read_bytes())
    edit(urdf_of(package), STL, "../../outside.STL")
    return package


# A Git LFS pointer as a clone without Git LFS leaves it in place of the mesh (git-lfs's
# docs/spec.md gives this example).
LFS_POINTER = (b"version https://git-lfs.github.com/spec/v1\n"
               b"oid sha256:4d7a214614ab2935c943f9e0ff69d22eadbb8f32b1258daaa5e2ca24d17e2393\n"
               b"size 12345\n")


def _collada(folder: Path) -> Path:
    package = copy_example(1, folder)
    trimesh.load(package / "meshes" / "base_link.STL").export(package / "meshes" / "base_link.dae")
    edit(urdf_of(package), "base_link.STL", "base_link.dae", 2)
    return package


def _ascii(old: bytes) -> bytes:
    mesh = trimesh.load(io.BytesIO(old), file_type="stl")
    return trimesh.exchange.stl.export_stl_ascii(mesh).encode()


def _flat(old: bytes) -> bytes:
    square = trimesh.Trimesh([[0, 0, 0], [0.3, 0, 0], [0.3, 0.4, 0], [0, 0.4, 0]],
                             [[0, 1, 2], [0, 2, 3]])
    return trimesh.exchange.stl.export_stl(square)


def _in_millimetres(old: bytes) -> bytes:
    mesh = trimesh.load(io.BytesIO(old), file_type="stl")
    mesh.apply_scale(1000)
    return trimesh.exchange.stl.export_stl(mesh)


def _heavy_wheel(folder: Path) -> Path:
    # The collision names the same file by another spelling, so that its line is unique.
    package = _example_1(folder, f'{WHEEL}" />\n      </geometry>\n    </collision>',
                         f'{WHEEL.replace("meshes/", "meshes/./")}" />\n      </geometry>\n'
                         "    </collision>")
    stl = package / "meshes" / "front_left_wheel.STL"
    stl.write_bytes(_repeated(stl.read_bytes(), 9))
    return package


# Each maker breaks one thing; WHERE gives the text on the line the finding must point at.
# A file's problem is reported at the first <mesh> naming it: base_link's <visual>.
BATTERY = {
    "mesh-no-filename": lambda d: _example_1(d, f'filename="{STL}"', 'filename=""'),
    "mesh-outside-package": _outside,
    "mesh-not-found": lambda d: _example_1(d, STL, STL.replace("base_link", "base_lnk")),
    "mesh-format": _collada,
    "mesh-ascii-stl": lambda d: _base_stl(d, _ascii),
    "mesh-empty": lambda d: _base_stl(d, b"solid base_link".ljust(80)),
    "mesh-unreadable": lambda d: _base_stl(d, lambda old: old[:-20]),
    "mesh-flat": lambda d: _base_stl(d, _flat),
    "mesh-too-many-faces": lambda d: _base_stl(d, lambda old: _repeated(old, 130)),
    "mesh-units": lambda d: _base_stl(d, _in_millimetres),
    "mesh-heavy-collision": _heavy_wheel,
    "mesh-lfs-pointer": lambda d: _base_stl(d, LFS_POINTER),
}
WHERE = {
    "mesh-no-filename": 'filename=""',
    "mesh-outside-package": "../../outside.STL",
    "mesh-not-found": "base_lnk.STL",
    "mesh-format": "base_link.dae",
    "mesh-ascii-stl": STL,
    "mesh-empty": STL,
    "mesh-unreadable": STL,
    "mesh-flat": STL,
    "mesh-too-many-faces": STL,
    "mesh-units": STL,
    "mesh-heavy-collision": "meshes/./front_left_wheel.STL",
    "mesh-lfs-pointer": STL,
}


def ours(report) -> list:
    return group_findings(report, GROUP)


def test_battery_covers_every_mesh_rule():
    assert set(BATTERY) == set(WHERE) == {r.id for r in all_rules().values() if r.group == GROUP}


@pytest.mark.parametrize("rule_id", sorted(BATTERY))
def test_rule_fires_at_the_offending_line(rule_id, tmp_path):
    report, hits = fires_at(BATTERY[rule_id](tmp_path), rule_id, WHERE[rule_id])
    assert len(hits) == 1, report.format()   # once, although two <mesh> elements name the file


@pytest.mark.parametrize("n", practice_numbers())
def test_examples_are_clean(n):
    assert ours(check(EXAMPLES / f"example_{n}", stability=False)) == []


def test_a_file_named_twice_is_reported_once_with_both_lines(tmp_path):
    package = _example_1(tmp_path, STL, STL.replace("base_link", "base_lnk"), 2)
    (hit,) = ours(check(package, stability=False))
    lines = [n for n, text in enumerate(urdf_of(package).read_text().splitlines(), 1)
             if "base_lnk" in text]
    assert hit.line == lines[0] and f"also named at line {lines[1]}" in hit.message


def test_a_missing_mesh_says_where_it_looked(tmp_path):
    package = BATTERY["mesh-not-found"](tmp_path)
    (hit,) = ours(check(package, stability=False))
    assert str(package.resolve() / "meshes" / "base_lnk.STL") in hit.message
    assert "package://example_1/" in hit.message


def test_a_wrong_package_name_is_left_to_the_package_rule(tmp_path):
    package = _example_1(tmp_path, "package://example_1/", "package://other_robot/", 10)
    report = check(package, stability=False)
    assert ours(report) == [] and "package-name-mismatch" in report.rules()


def test_a_relative_path_inside_the_package_is_fine(tmp_path):
    package = _example_1(tmp_path, STL, "../meshes/base_link.STL", 2)
    assert ours(check(package, stability=False)) == []


def test_a_scale_to_metres_makes_a_millimetre_mesh_fine(tmp_path):
    package = BATTERY["mesh-units"](tmp_path)
    edit(urdf_of(package), f'{STL}" />', f'{STL}" scale="0.001 0.001 0.001" />', 2)
    assert ours(check(package, stability=False)) == []


def test_a_binary_stl_whose_header_says_solid_is_binary(tmp_path):
    # SolidWorks starts its binary STL headers with "solid", as text STL files start.
    solid = b"solid base_link".ljust(80)
    assert ours(check(_base_stl(tmp_path / "whole", lambda old: solid + old[80:]),
                      stability=False)) == []
    cut = _base_stl(tmp_path / "cut", lambda old: (solid + old[80:])[:-20])
    assert [f.rule for f in ours(check(cut, stability=False))] == ["mesh-unreadable"]


def test_a_symbolic_link_loop_is_a_missing_mesh(tmp_path):
    package = copy_example(1, tmp_path)
    stl = package / "meshes" / "base_link.STL"
    stl.unlink()
    stl.symlink_to("base_link.STL")
    (hit,) = ours(check(package, stability=False))
    assert hit.rule == "mesh-not-found" and "symbolic links" in hit.message


# --- never open a file outside the package ---------------------------------------------------

def _relative(package: Path, outside: Path) -> str:
    return "../../outside.STL"


def _absolute(package: Path, outside: Path) -> str:
    return str(outside)


def _file_url(package: Path, outside: Path) -> str:
    return f"file://{outside}"


def _dotdot_in_package_url(package: Path, outside: Path) -> str:
    return "package://example_1/../outside.STL"


def _symlink(package: Path, outside: Path) -> str:
    (package / "meshes" / "secret.STL").symlink_to(outside)
    return "package://example_1/meshes/secret.STL"


@pytest.mark.parametrize("path_to", [_relative, _absolute, _file_url, _dotdot_in_package_url,
                                     _symlink])
def test_a_mesh_outside_the_package_is_reported_and_never_opened(path_to, tmp_path,
                                                                 monkeypatch):
    package = copy_example(1, tmp_path)
    # A perfectly good mesh: were it opened, nothing else would give that away.
    outside = tmp_path / "outside.STL"
    outside.write_bytes((package / "meshes" / "base_link.STL").read_bytes())
    urdf = urdf_of(package)
    filename = path_to(package, outside)
    edit(urdf, STL, filename)

    opened = []

    def recording(original):
        def wrapper(file, *args, **kwargs):
            if isinstance(file, (str, bytes, os.PathLike)):
                opened.append(os.path.realpath(file))
            return original(file, *args, **kwargs)
        return wrapper

    monkeypatch.setattr(builtins, "open", recording(builtins.open))
    monkeypatch.setattr(io, "open", recording(io.open))
    monkeypatch.setattr(os, "open", recording(os.open))
    monkeypatch.setattr(trimesh, "load", recording(trimesh.load))
    report = check(package, stability=False)
    monkeypatch.undo()

    assert os.path.realpath(urdf) in opened                # the recording works
    assert os.path.realpath(outside) not in opened
    hits = [f for f in report.findings if f.rule == "mesh-outside-package"]
    assert len(hits) == 1 and report.status == 1, report.format()
    assert hits[0].line == line_of(urdf, filename)
    assert ("symbolic link" in hits[0].message) == (path_to is _symlink)


# --- the heuristics, on their own --------------------------------------------------------------

def _link(mass: float | None, moment: float) -> etree._Element:
    inertial = "" if mass is None else (
        f'<inertial><mass value="{mass}"/><inertia ixx="{moment}" iyy="{moment}" '
        f'izz="{moment}" ixy="0" ixz="0" iyz="0"/></inertial>')
    return etree.fromstring(f'<link name="part">{inertial}</link>')


def _cube_inertia(mass: float, side: float) -> float:
    return mass * side ** 2 / 6


@pytest.mark.parametrize("side", [0.005, 0.05, 0.5])
def test_a_cube_read_in_millimetres_is_suspect_and_in_metres_is_not(side):
    link = _link(0.3, _cube_inertia(0.3, side))
    assert millimetre_suspect(link, trimesh.creation.box([side * 1000] * 3))
    assert not millimetre_suspect(link, trimesh.creation.box([side] * 3))


def test_a_long_light_arm_on_a_heavy_core_is_not_millimetres():
    # 1 kg in a 10 cm cube with a 1 m arm of 1 g: the mesh is 20 times the mass's spread.
    moment = _cube_inertia(1.0, 0.1) + 0.001 * 1.0 ** 2 / 3
    mesh = trimesh.util.concatenate([trimesh.creation.box([0.1] * 3),
                                     trimesh.creation.box([1.0, 0.01, 0.01])])
    assert not millimetre_suspect(_link(1.001, moment), mesh)


def test_a_placeholder_inertia_does_not_pass_for_millimetres():
    assert not millimetre_suspect(_link(1.0, 1e-12), trimesh.creation.box([0.1] * 3))


def test_without_an_inertia_only_size_counts():
    assert millimetre_suspect(_link(None, 0), trimesh.creation.box([50.0] * 3))
    assert not millimetre_suspect(_link(None, 0), trimesh.creation.box([2.0] * 3))


def test_a_thin_plate_is_not_flat_but_a_plane_is():
    plate = trimesh.creation.box([0.1, 0.1, 1e-5]).vertices
    assert _flatness(plate) is None
    tilted = plate @ trimesh.transformations.euler_matrix(0.3, 0.5, 0.7)[:3, :3].T
    assert _flatness(tilted) is None
    plane = np.column_stack([plate[:, :2], np.zeros(len(plate))])
    assert _flatness(plane) and _flatness(plate[:3])


def test_files_of_the_same_bytes_are_read_once_and_each_is_still_reported(tmp_path):
    """Example 1's four wheels are four files of the same bytes: one Mesh for all of them
    (read, merged and measured once); a fault in them is still reported for each file, and
    a wheel file changed by a byte is a mesh of its own."""
    from sw2sim.check import open_package
    package = copy_example(1, tmp_path / "same")
    wheels = sorted((package / "meshes").glob("*wheel.STL"))
    assert len(wheels) == 4 and len({w.read_bytes() for w in wheels}) == 1
    ctx = open_package(package)
    meshes = {w.name: ctx.mesh(el) for el in ctx.robot.iter("mesh")
              for w in wheels if el.get("filename").endswith("/" + w.name)}
    assert len(meshes) == 4 and len({id(m) for m in meshes.values()}) == 1

    changed = copy_example(1, tmp_path / "changed")
    wheel = changed / "meshes" / wheels[0].name
    data = bytearray(wheel.read_bytes())
    data[0] ^= 1   # the header: the same triangles, other bytes
    wheel.write_bytes(bytes(data))
    ctx = open_package(changed)
    read = {el.get("filename"): ctx.mesh(el) for el in ctx.robot.iter("mesh")
            if "wheel" in el.get("filename")}
    assert len({id(m) for m in read.values()}) == 2

    # every wheel file the same text STL: four files, a finding for each
    text = copy_example(1, tmp_path / "text")
    ascii_stl = trimesh.load(str(wheels[0]), force="mesh").export(file_type="stl_ascii")
    for wheel in sorted((text / "meshes").glob("*wheel.STL")):
        wheel.write_text(ascii_stl)
    found = [f for f in check(text).findings if f.rule == "mesh-ascii-stl"]
    assert len(found) == 4 and all(sum(w.name in f.message for f in found) == 1
                                   for w in wheels), [f.message for f in found]
