"""The stability run gives MuJoCo the convex hull's corners of each closed collision mesh
(sw2sim/check/collision_hulls.py, sw2sim.loader's `hulls`): MuJoCo collides with the same
shape, the verdict and every figure of the run are those of the whole meshes, and a mesh
whose hull would change something (a link without <inertial>, an open mesh) keeps its
file."""

from __future__ import annotations

import json

import mujoco
import numpy as np
import pytest
import trimesh
from lxml import etree
from packages import as_obj, copy_example

import sw2sim
from sw2sim.check import check, collision_hulls, open_package, stability


@pytest.fixture
def heavy_arm(tmp_path):
    """Practice 3's arm whose middle link's mesh has 25,088 triangles (1.25 MB)."""
    package = copy_example(3, tmp_path)
    stl = package / "meshes" / "middle_arm_link.STL"
    mesh = trimesh.load(stl)
    for _ in range(3):
        mesh = mesh.subdivide()
    stl.write_bytes(mesh.export(file_type="stl"))
    return package


def _figures(report) -> dict:
    found = json.loads(report.to_json())
    found["stability"].pop("wall_time")
    found["stability"].pop("summary")
    return found


def _vertex_counts(model) -> dict[str, int]:
    return {model.mesh(i).name: int(model.mesh_vertnum[i]) for i in range(model.nmesh)}


@pytest.mark.parametrize("practice", [1, 3, 4, 5])
def test_the_verdict_and_the_figures_are_those_of_the_whole_meshes(tmp_path, practice,
                                                                   monkeypatch):
    package = copy_example(practice, tmp_path)
    assert collision_hulls.hulls(open_package(package)), "the lessons' parts are closed solids"
    with_hulls = _figures(check(package))
    monkeypatch.setattr(stability, "hulls", lambda ctx: {})
    whole = _figures(check(package))
    assert with_hulls == whole
    assert whole["stability"]["steps"] == 2000


def test_the_model_holds_the_hull_and_collides_where_the_mesh_does(heavy_arm):
    ctx = open_package(heavy_arm)
    hulls = collision_hulls.hulls(ctx)
    key = next(k for k in hulls if k[0].endswith("middle_arm_link.STL"))
    assert key[1] == (1.0, 1.0, 1.0)
    whole = sw2sim.load_package(heavy_arm, scene="floor").compile()
    light = sw2sim.load_package(heavy_arm, scene="floor", hulls=hulls).compile()
    counts, light_counts = _vertex_counts(whole), _vertex_counts(light)
    assert counts["middle_arm_link"] > 12_000
    assert light_counts["middle_arm_link"] <= len(hulls[key]) < 1_000
    # the same bodies, masses and inertias (the URDF's), and the same collision extent:
    # at the rest pose each collision geom's corners reach as far along every axis
    assert np.array_equal(whole.body_mass, light.body_mass)
    assert np.array_equal(whole.body_inertia, light.body_inertia)
    body = whole.body("middle_arm_link").id
    reach = []
    for model in (whole, light):
        data = mujoco.MjData(model)
        mujoco.mj_kinematics(model, data)
        geom = next(g for g in range(model.ngeom)
                    if model.geom_bodyid[g] == body and model.geom_contype[g])
        mesh = model.geom_dataid[geom]
        first = model.mesh_vertadr[mesh]
        local = model.mesh_vert[first:first + model.mesh_vertnum[mesh]]
        world = local @ data.geom_xmat[geom].reshape(3, 3).T + data.geom_xpos[geom]
        reach.append(np.concatenate([world.min(axis=0), world.max(axis=0)]))
    assert np.allclose(reach[0], reach[1], atol=1e-6)


def test_the_heavy_arm_is_checked_alike_either_way(heavy_arm, monkeypatch):
    with_hulls = _figures(check(heavy_arm))
    monkeypatch.setattr(stability, "hulls", lambda ctx: {})
    assert _figures(check(heavy_arm)) == with_hulls


def test_a_link_without_inertial_keeps_its_mesh(heavy_arm):
    """MuJoCo weighs such a link from its collision geoms, and a hull encloses more."""
    urdf = next((heavy_arm / "urdf").glob("*.urdf"))
    tree = etree.parse(str(urdf))
    link = tree.find("link[@name='middle_arm_link']")
    link.remove(link.find("inertial"))
    tree.write(str(urdf))
    ctx = open_package(heavy_arm)
    assert not any(k[0].endswith("middle_arm_link.STL") for k in collision_hulls.hulls(ctx))
    # and where a map names it anyway, the loader leaves it whole
    corners = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]]) * 0.01
    every = {(str(p.resolve()), (1.0, 1.0, 1.0)): corners
             for p in (heavy_arm / "meshes").glob("*.STL")}
    spec = sw2sim.load_package(heavy_arm, scene="floor", hulls=every)
    files = {m.name: m.file for m in spec.meshes}
    assert files["middle_arm_link"].endswith("middle_arm_link.STL")
    assert files["end_arm_link"] == ""


def test_an_open_mesh_keeps_its_file(heavy_arm):
    stl = heavy_arm / "meshes" / "middle_arm_link.STL"
    mesh = trimesh.load(stl)
    trimesh.Trimesh(mesh.vertices, mesh.faces[1:], process=False).export(stl)
    ctx = open_package(heavy_arm)
    assert not any(k[0].endswith("middle_arm_link.STL") for k in collision_hulls.hulls(ctx))
    assert any(k[0].endswith("end_arm_link.STL") for k in collision_hulls.hulls(ctx))




def test_obj_meshes_get_hulls_with_the_same_verdict(heavy_arm, monkeypatch):
    package = as_obj(heavy_arm)
    assert len(collision_hulls.hulls(open_package(package))) == 3
    with_hulls = _figures(check(package))
    monkeypatch.setattr(stability, "hulls", lambda ctx: {})
    assert _figures(check(package)) == with_hulls


def test_an_obj_corner_no_face_uses_is_in_the_hull_as_in_mujoco_s(tmp_path):
    """MuJoCo keeps a `v` line no face uses, and its hull reaches it: the hull given in the
    file's place reaches it too, so the model's collision extent is MuJoCo's own."""
    package = as_obj(copy_example(3, tmp_path), stray=(0.5, 0.5, 0.5))
    hulls = collision_hulls.hulls(open_package(package))
    assert len(hulls) == 3
    whole = sw2sim.load_package(package, scene="floor").compile()
    light = sw2sim.load_package(package, scene="floor", hulls=hulls).compile()
    reaches = []
    for model in (whole, light):
        data = mujoco.MjData(model)
        mujoco.mj_kinematics(model, data)
        found = []
        for geom in range(model.ngeom):
            mesh = model.geom_dataid[geom]
            if not model.geom_contype[geom] or mesh < 0:
                continue
            first = model.mesh_vertadr[mesh]
            local = model.mesh_vert[first:first + model.mesh_vertnum[mesh]]
            world = local @ data.geom_xmat[geom].reshape(3, 3).T + data.geom_xpos[geom]
            found.append(np.concatenate([world.min(axis=0), world.max(axis=0)]))
        reaches.append(np.array(found))
    assert np.allclose(reaches[0], reaches[1], atol=1e-6)
    assert (reaches[0][:, 3:] > 0.45).any()       # the stray corner is in MuJoCo's too
