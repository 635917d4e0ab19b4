"""MuJoCo's processing of a package's meshes, begun while the static checks run
(sw2sim/check/mesh_cache.py): it fills MuJoCo's cache with what the stability run then
needs, leaves MuJoCo's warning handler as it found it, and changes no verdict."""

from __future__ import annotations

import json

import mujoco
import pytest
import trimesh
from packages import copy_example

from sw2sim.check import check, mesh_cache, open_package


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


def test_the_meshes_are_in_mujoco_s_cache_when_the_checks_are_done(heavy_arm):
    ctx = open_package(heavy_arm)
    cache = mujoco.mj_getCache()
    mujoco.mj_clearCache(cache)
    handler = mujoco.get_mju_user_warning()
    thread = mesh_cache.start(ctx)
    assert thread is not None, "1.25 MB of collision meshes are worth a thread"
    mesh_cache.finish(thread)
    assert not thread.is_alive()
    assert mujoco.mj_getCacheSize(cache) > 1_000_000   # the mesh, its hull and its tree
    assert mujoco.get_mju_user_warning() is handler


def test_small_meshes_start_no_thread(tmp_path):
    ctx = open_package(copy_example(3, tmp_path))
    assert mesh_cache.start(ctx) is None


def test_the_verdict_is_the_same_with_or_without_it(heavy_arm, monkeypatch):
    mujoco.mj_clearCache(mujoco.mj_getCache())
    early = check(heavy_arm)
    mujoco.mj_clearCache(mujoco.mj_getCache())
    monkeypatch.setattr(mesh_cache, "WORTH_IT", float("inf"))
    late = check(heavy_arm)
    assert _figures(early) == _figures(late)
    assert early.stability["steps"] == 2000
