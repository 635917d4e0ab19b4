"""MuJoCo's work on the package's meshes, begun on another core while the checks run.

Compiling a model makes MuJoCo read each mesh file, merge its vertices and, for a mesh that
collides, compute its convex hull: a third of a second of one core per 100,000 triangles.
MuJoCo keeps the result in its asset cache, by file, and a later model that names the same
file with the same scale and options takes it from there (mujoco's src/user/user_mesh.cc,
mjCMesh::LoadCachedMesh; the result is the same either way). The stability run compiles the
package only after the static checks, which decide the repairs it simulates and take as
long again. `start` has a thread compile a model made of nothing but the package's
collision meshes, as its URDF names them, while those checks run: MuJoCo's compile lets go
of Python's lock, so on two cores both go on at once. `finish` waits for the thread before
anything else in the process uses MuJoCo, whose warning handler is one for the process.

A warning MuJoCo gives while it processes a mesh ("Could not construct convex hull graph")
would then not come again when the stability run loads the model, and the check reports
the warnings of that load: after any warning here the cache is emptied, so that the
stability run processes the meshes itself and hears it. Small meshes are not worth a
thread: below WORTH_IT bytes of mesh files nothing is started.
"""

from __future__ import annotations

import threading
from pathlib import Path

from ..mesh_formats import lfs_pointer, stand_in
from .urdf import vector

# Bytes of collision mesh files below which MuJoCo's work on them is not worth a thread: a
# binary STL of 20,000 triangles, which MuJoCo processes in some 50 ms.
WORTH_IT = 1_000_000


def start(ctx) -> threading.Thread | None:
    """Begin MuJoCo's processing of the package's collision meshes in a thread; None when
    there is too little to process."""
    meshes = _collision_meshes(ctx)
    if sum(size for size in meshes.values()) < WORTH_IT:
        return None
    thread = threading.Thread(target=_process, args=(list(meshes),), daemon=True,
                              name="sw2sim mesh cache")
    thread.start()
    return thread


def finish(thread: threading.Thread | None) -> None:
    """Wait until the thread `start` began is done with MuJoCo."""
    if thread is not None:
        thread.join()


def _collision_meshes(ctx) -> dict[tuple[str, tuple[float, float, float]], int]:
    """(the file MuJoCo reads, the scale) of each mesh a <collision> names, with the file's
    size: the file as `sw2sim.load_package` hands it to MuJoCo (the mesh's own, or the
    readable one beside it), and only where that is a file (no conversion in memory)."""
    found = {}
    for link in ctx.robot.findall("link"):
        for mesh in link.findall("collision/geometry/mesh"):
            path = ctx.mesh_file(mesh)
            scale = vector(mesh.get("scale") or "1 1 1", 3)
            if path is None or scale is None or lfs_pointer(path):
                continue
            file = stand_in(path)
            if file is not None:
                try:
                    found[(str(file), tuple(scale))] = Path(file).stat().st_size
                except OSError:
                    continue
    return found


def _process(meshes: list[tuple[str, tuple[float, float, float]]]) -> None:
    """Compile a model of these meshes, each in a geom that collides, so that MuJoCo keeps
    them processed in its cache. Whatever goes wrong is left for the stability run to meet."""
    try:
        import mujoco
    except Exception:  # noqa: BLE001  (the stability run reports what is wrong with MuJoCo)
        return
    heard: list[str] = []
    previous = mujoco.get_mju_user_warning()
    mujoco.set_mju_user_warning(heard.append)
    try:
        spec = mujoco.MjSpec()
        for n, (file, scale) in enumerate(meshes):
            spec.add_mesh(name=f"mesh{n}", file=file, scale=list(scale))
            spec.worldbody.add_geom(type=mujoco.mjtGeom.mjGEOM_MESH, meshname=f"mesh{n}")
        spec.compile()
    except Exception:  # noqa: BLE001  (the stability run compiles again and reports it)
        pass
    finally:
        mujoco.set_mju_user_warning(previous)
        if heard:
            mujoco.mj_clearCache(mujoco.mj_getCache())
