"""sw2sim port gives a heavy collision mesh a simplified copy: the exporter writes each part's
STL, as finely as SolidWorks tessellated it, for both <visual> and <collision>. The copy
goes to meshes/simplified/ and only the <collision> names it; it is closed, holds a subset
of the original's vertices, keeps the part's volume and size, and the report's numbers are
the files'. --keep-collision-meshes, an open mesh and a light one leave the mesh whole.
The colcon build that installs meshes/simplified/ is in test_port_packages.py."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest
import trimesh
from lxml import etree

import sw2sim
from sw2sim.check.geometry import as_solid
from sw2sim.check.trimeshes import read
from sw2sim.cli import main
from sw2sim.port import collision_meshes, port

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "check"))
from exporter_packages import THREE_DOF_ARM, write_export  # noqa: E402  (tests/tool/check)

PACKAGE = "r3_dof_arm_description"


def fine_part(path: Path, sections: int = 3000) -> trimesh.Trimesh:
    """A ring 100 mm across, tessellated as finely as a "fine" SolidWorks export of a round
    part (8 triangles per section: 24,000 with the default), written as binary STL."""
    ring = trimesh.creation.annulus(r_min=0.01, r_max=0.05, height=0.02, sections=sections)
    ring.export(path)
    return ring


def heavy_arm(folder: Path, open_surface: bool = False) -> Path:
    """The exporter's 3-DOF arm with the proximal segment's mesh a fine round part (closed,
    or with one triangle missing)."""
    package = write_export(THREE_DOF_ARM, folder)
    stl = package / "meshes" / "prox_link.STL"
    ring = fine_part(stl)
    if open_surface:
        trimesh.Trimesh(ring.vertices, ring.faces[1:], process=False).export(stl)
    return package


@pytest.fixture(scope="module")
def source(tmp_path_factory) -> Path:
    """The arm with its fine part, written once for the tests that only read it."""
    return heavy_arm(tmp_path_factory.mktemp("heavy_arm"))


def mesh_paths(urdf: Path, kind: str) -> dict[str, str]:
    """link -> the filename of its <kind> mesh."""
    return {link.get("name"): link.find(f"{kind}/geometry/mesh").get("filename")
            for link in etree.parse(str(urdf)).iterfind("link")
            if link.find(f"{kind}/geometry/mesh") is not None}


def test_the_heavy_collision_mesh_gets_a_faithful_simplified_copy(source, tmp_path):
    src = source
    out = tmp_path / "out"
    report = port(src, out)
    urdf = out / "urdf" / f"{PACKAGE}.urdf"
    collisions, visuals = mesh_paths(urdf, "collision"), mesh_paths(urdf, "visual")
    prefix = f"package://{PACKAGE}/"
    assert collisions["prox_link"] == prefix + "meshes/simplified/prox_link.STL"
    assert visuals["prox_link"] == prefix + "meshes/prox_link.STL"      # the visual stays whole
    for link in ("base_link", "dist_Link", "effector_link"):            # light: left alone
        assert collisions[link] == visuals[link] == prefix + f"meshes/{link}.STL"
    assert sorted(p.name for p in (out / "meshes" / "simplified").iterdir()) == ["prox_link.STL"]

    whole, copy = read(out / "meshes" / "prox_link.STL"), read(out / "meshes/simplified/prox_link.STL")
    assert len(whole.faces) == 24_000 and len(copy.faces) <= collision_meshes.TARGET
    whole.merge_vertices(), copy.merge_vertices()
    solid, simple = as_solid(whole), as_solid(copy)
    assert simple is not None                                  # closed and outward-facing
    assert abs(simple.volume() / solid.volume() - 1) < 0.01
    assert np.allclose(copy.bounds, whole.bounds, atol=0.5e-3)  # the part's size, within 0.5 mm
    # manifold3d keeps a subset of the vertices (to the STL's float32 precision)
    known = {tuple(v) for v in np.round(whole.vertices, 6)}
    assert all(tuple(v) in known for v in np.round(copy.vertices, 6))

    said = [c for c in report.choices if "simplified" in c]
    assert len(said) == 1
    assert (f"1 collision mesh(es) over 20,000 triangles got a simplified copy in "
            f"meshes/simplified/") in said[0]
    assert f"meshes/prox_link.STL 24,000 -> {len(copy.faces):,} triangles" in said[0]
    assert f"({24_000 - len(copy.faces):,} triangles fewer" in said[0]
    assert collision_meshes.SOURCE in said[0] and "--keep-collision-meshes" in said[0]
    assert "meshes/simplified/" in (out / "README.md").read_text(encoding="utf-8")
    # the stand-in (`sw2sim ros2`) loads the port with it: 4 collision and 4 visual meshes,
    # the visual one whole
    model = sw2sim.load_package(out).compile()
    faces = {model.mesh(i).name: int(model.mesh_facenum[i]) for i in range(model.nmesh)}
    assert sorted(faces.values())[-1] >= 24_000 // 2 and len(faces) == 5


def test_porting_again_writes_the_same_copy(source, tmp_path):
    src = source
    out = tmp_path / "out"
    port(src, out)
    first = (out / "meshes/simplified/prox_link.STL").read_bytes()
    again = port(src, out)
    assert again.replaced and not again.set_aside and not again.kept_changed
    assert (out / "meshes/simplified/prox_link.STL").read_bytes() == first


def test_keep_collision_meshes_uses_them_whole(source, tmp_path, capsys):
    src = source
    out = tmp_path / "out"
    assert main(["port", str(src), "-o", str(out), "--keep-collision-meshes"]) == 0
    assert "simplified" not in capsys.readouterr().out
    assert not (out / "meshes" / "simplified").exists()
    collisions = mesh_paths(out / "urdf" / f"{PACKAGE}.urdf", "collision")
    assert collisions["prox_link"] == f"package://{PACKAGE}/meshes/prox_link.STL"


def test_an_open_heavy_mesh_is_used_whole_and_the_report_says_why(tmp_path):
    src = heavy_arm(tmp_path / "src", open_surface=True)
    report = port(src, tmp_path / "out")
    said = [c for c in report.choices if "prox_link.STL" in c and "collision" in c]
    assert said == ["meshes/prox_link.STL (23,999 triangles) names a <collision>, but it is not "
                    "a closed surface, which simplifying needs (`sw2sim check` on the source "
                    "says where it is open); it is used whole."]
    assert not (tmp_path / "out" / "meshes" / "simplified").exists()


def test_a_copy_takes_a_free_name_beside_the_packages_own_simplified_folder():
    taken = {"meshes/simplified/prox_link.STL"}
    assert collision_meshes._free_name("meshes/prox_link.stl", taken) == \
        "meshes/simplified/prox_link_2.STL"
    assert collision_meshes._free_name("meshes/visual/arm.dae", set()) == \
        "meshes/simplified/visual/arm.STL"


@pytest.mark.parametrize("sections", [300, 2500])
def test_a_mesh_at_or_below_the_threshold_is_left_alone(tmp_path, sections):
    """2,400 and 20,000 triangles: at most HEAVY, so the collision keeps the mesh."""
    package = write_export(THREE_DOF_ARM, tmp_path / "src")
    fine_part(package / "meshes" / "prox_link.STL", sections)
    report = port(package, tmp_path / "out")
    assert not any("simplified" in c for c in report.choices)
    assert not (tmp_path / "out" / "meshes" / "simplified").exists()


def test_the_page_and_the_help_state_the_numbers_the_port_uses():
    """The threshold and the largest tolerance, as /reference/ros1-to-ros2/ and
    `sw2sim port --help` state them."""
    from repository import ROOT
    from sw2sim.commands.port import HELP
    page = " ".join((ROOT / "_pages/reference/05-ros1-to-ros2.md").read_text(
        encoding="utf-8").split())
    help_text = " ".join(HELP.split())
    most = f"{max(collision_meshes.TOLERANCES) * 100:g} %"
    for text in (page, help_text):
        assert f"over {collision_meshes.HEAVY:,} triangles" in text or \
            f"more than {collision_meshes.HEAVY:,} triangles" in text
        assert f"by more than {most} of the part's size" in text
    assert "meshes/simplified/" in page and collision_meshes.FOLDER == "meshes/simplified"


def test_the_port_calls_heavy_what_the_check_calls_heavy():
    """A mesh `sw2sim check` warns about (mesh-heavy-collision) is one the port lightens."""
    from sw2sim.check.meshes import HEAVY_FACES
    assert collision_meshes.HEAVY == HEAVY_FACES


def test_a_copy_never_replaces_a_file_the_package_has_in_meshes_simplified(tmp_path):
    """A package's own meshes/simplified/prox_link.STL (no URDF names it) is copied as it
    is; the port's copy takes another name."""
    src = heavy_arm(tmp_path / "src")
    own = src / "meshes" / "simplified" / "prox_link.STL"
    own.parent.mkdir()
    own.write_bytes((src / "meshes" / "base_link.STL").read_bytes())
    out = tmp_path / "out"
    port(src, out)
    assert (out / "meshes/simplified/prox_link.STL").read_bytes() == own.read_bytes()
    collisions = mesh_paths(out / "urdf" / f"{PACKAGE}.urdf", "collision")
    assert collisions["prox_link"] == f"package://{PACKAGE}/meshes/simplified/prox_link_2.STL"
    assert len(read(out / "meshes/simplified/prox_link_2.STL").faces) <= collision_meshes.TARGET
