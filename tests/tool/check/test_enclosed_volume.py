"""The check's test of a closed mesh (sw2sim/check/geometry.py, `enclosed_volume`) against
manifold3d's, which it stands in for: on the lessons' meshes, URDF's primitives and every
way of breaking them that an export or a hand edit makes, both say the same about whether
the mesh is a solid, and give the same volume."""

from __future__ import annotations

from pathlib import Path

import manifold3d
import numpy as np
import pytest

from sw2sim.check.geometry import _enclosed_volume
from sw2sim.check.trimeshes import Mesh, box, cylinder, read, sphere

ROOT = Path(__file__).resolve().parents[3]


def _manifold_volume(mesh: Mesh) -> float | None:
    try:
        solid = manifold3d.Manifold(manifold3d.Mesh64(
            vert_properties=np.asarray(mesh.vertices, dtype=np.float64),
            tri_verts=np.asarray(mesh.faces, dtype=np.uint64)))
    except Exception:  # noqa: BLE001
        return None
    if solid.status() != manifold3d.Error.NoError or solid.volume() <= 0:
        return None
    return solid.volume()


def _meshes() -> dict[str, Mesh]:
    found = {"box": box([0.1, 0.2, 0.3]), "cylinder": cylinder(0.05, 0.2),
             "sphere": sphere(0.04)}
    for path in sorted(ROOT.glob("examples/example_*/meshes/*.STL")):
        mesh = read(path)
        mesh.merge_vertices()
        found[path.relative_to(ROOT).as_posix()] = mesh
    return found


def _broken(mesh: Mesh) -> dict[str, Mesh]:
    """The mesh as it is and as exports and edits break it."""
    v, f = mesh.vertices, mesh.faces
    flipped, degenerate = f.copy(), f.copy()
    flipped[0] = flipped[0][::-1]
    degenerate[0, 1] = degenerate[0, 0]
    return {
        "as it is": mesh,
        "a face missing": Mesh(v, f[1:]),
        "a face turned over": Mesh(v, flipped),
        "a face twice": Mesh(v, np.vstack([f, f[:1]])),
        "a face with a corner twice": Mesh(v, degenerate),
        "inside out": Mesh(v, f[:, ::-1]),
        "each face both ways": Mesh(v, np.vstack([f, f[:, ::-1]])),
        "two shells": Mesh(np.vstack([v, v + 10]), np.vstack([f, f + len(v)])),
        "a vertex no face uses": Mesh(np.vstack([v, [[9.0, 9.0, 9.0]]]), f),
        "no faces": Mesh(v, np.zeros((0, 3), dtype=np.int64)),
    }


CASES = [(name, how, broken) for name, mesh in _meshes().items()
         for how, broken in _broken(mesh).items()]


@pytest.mark.parametrize("name, how, mesh", CASES, ids=[f"{n}: {h}" for n, h, _ in CASES])
def test_a_closed_mesh_is_what_manifold3d_calls_a_solid(name, how, mesh):
    expected, found = _manifold_volume(mesh), _enclosed_volume(mesh)
    assert (found is None) == (expected is None), (expected, found)
    if expected is not None:
        # (the sums of tetrahedra differ in rounding: a mesh 10 m from the origin loses digits)
        assert found == pytest.approx(expected, rel=1e-7)


def test_the_lessons_meshes_are_solids_and_their_breakages_are_not():
    # Without this, agreement could come from both always saying "not a solid".
    solids = {(name, how) for name, how, mesh in CASES if _enclosed_volume(mesh) is not None}
    assert {name for name, how in solids if how == "as it is"} == set(_meshes())
    assert {how for _, how in solids} <= {"as it is", "two shells", "a vertex no face uses"}
