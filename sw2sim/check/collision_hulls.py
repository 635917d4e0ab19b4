"""The convex hulls the stability run hands MuJoCo in place of the package's closed
collision meshes.

MuJoCo collides a mesh as its convex hull. Compiling a model still makes it process every
triangle of every mesh (merge the vertices, orient the faces, find the normals, the
inertia and the hull): a quarter of a second of CPU per 100,000 triangles, most of a
check's time on a finely exported part, and two or three times that on a machine a class's
CI keeps busy. Given the hull's corners alone, it collides with the same shape, and the
links weigh what their <inertial> says, as before.

A mesh keeps its file where the hull would change anything the check reports:
- its link has no <inertial>: MuJoCo then weighs the link from its collision geometry,
  and a hull encloses more than the mesh (`sw2sim.loader` checks this on the model);
- it is not a closed, outward-facing STL or OBJ of a volume (an open, inverted or flat
  mesh, a COLLADA file, an OBJ in a form the check's own reader does not read, one
  beyond MuJoCo's 200,000 triangles): MuJoCo's own complaints about it, which the check
  reports as `mujoco-compile` or `sim-warning`, must come.
An OBJ's hull is made of every `v` line, as MuJoCo's is, also of a corner no face uses.
For a closed solid MuJoCo has none: its mesh checks fail only for a surface of no area or
no volume, or a mass distribution no solid has (mujoco's src/user/user_mesh.cc,
mjCMesh::Process).
"""

from __future__ import annotations

import numpy as np
from manifold3d import Manifold

from ..mesh_formats import stand_in
from .geometry import closed_volume, hull_solid, merged_mesh
from .urdf import vector

# m^3: a solid below this is left to MuJoCo, whose own limit (mjMINVAL) is 1e-15.
SMALLEST = 1e-12


def hulls(ctx) -> dict[tuple[str, tuple[float, ...]], np.ndarray]:
    """(the file MuJoCo reads, resolved; the <mesh>'s scale) -> the corners of its convex hull,
    scale applied, for each closed collision mesh of a link with an <inertial>."""
    found: dict[tuple[str, tuple[float, ...]], np.ndarray | None] = {}
    for link in ctx.robot.findall("link"):
        if link.find("inertial") is None:
            continue
        for shape in link.findall("collision/geometry/mesh"):
            path = ctx.mesh_file(shape)
            scale = vector(shape.get("scale") or "1 1 1", 3)
            if path is None or scale is None or path.suffix.lower() not in (".stl", ".obj") \
                    or stand_in(path) != path:
                continue
            key = (str(path.resolve()), tuple(float(s) for s in scale))
            if key not in found:
                found[key] = _corners(ctx, shape, obj=path.suffix.lower() == ".obj")
    return {key: corners for key, corners in found.items() if corners is not None}


def _corners(ctx, shape, obj: bool) -> np.ndarray | None:
    mesh = merged_mesh(ctx, shape)
    if mesh is None:
        return None
    volume = closed_volume(mesh)
    if volume is None or volume < SMALLEST:
        return None
    try:
        if obj:
            # MuJoCo's hull takes every `v` line, also a corner no face uses: the check's
            # reader leaves those out of the vertices, as trimesh does, and keeps them aside
            read = ctx.mesh(shape)   # scale applied, not merged
            if read is None or read.loose is None:
                return None
            solid = Manifold.hull_points(np.concatenate([read.vertices, read.loose]))
        else:
            solid = hull_solid(mesh)     # the collision checks' own
    except Exception:  # noqa: BLE001  (manifold3d refuses some inputs: MuJoCo reads the file)
        return None
    if solid.volume() <= 0:
        return None
    return np.asarray(solid.to_mesh().vert_properties, dtype=np.float64)[:, :3]
