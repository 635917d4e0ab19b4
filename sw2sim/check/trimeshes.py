"""Triangle meshes as the checks need them, without a mesh library's start-up cost.

`sw2sim check` must answer within a second, and importing a full mesh library (with the
scientific stack behind it) took most of that. The checks only need vertices and faces,
moved, scaled and merged; the primitives of URDF as closed meshes; and binary STL, which
is what the exporter writes. `read` decodes binary STL here and hands anything else (text
STL, OBJ, other formats) to trimesh, imported only then.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

# Vertices closer than this (metres) are one vertex once merged: STL repeats each vertex
# for every triangle that uses it, with exactly the same numbers.
MERGE_DIGITS = 8

_STL_RECORD = np.dtype([("normal", "<f4", (3,)), ("points", "<f4", (3, 3)), ("attr", "<u2")])


class Mesh:
    """Vertices (n x 3 floats) and faces (m x 3 vertex indices), counter-clockwise seen from
    outside for a closed mesh."""

    def __init__(self, vertices, faces):
        self.vertices = np.asarray(vertices, dtype=np.float64).reshape(-1, 3)
        self.faces = np.asarray(faces, dtype=np.int64).reshape(-1, 3)

    def copy(self) -> "Mesh":
        return Mesh(self.vertices.copy(), self.faces.copy())

    @property
    def triangles(self) -> np.ndarray:
        return self.vertices[self.faces]

    @property
    def bounds(self) -> np.ndarray:
        return np.array([self.vertices.min(axis=0), self.vertices.max(axis=0)])

    @property
    def extents(self) -> np.ndarray:
        return np.ptp(self.vertices, axis=0) if len(self.vertices) else np.zeros(3)

    def apply_transform(self, matrix: np.ndarray) -> None:
        matrix = np.asarray(matrix, dtype=np.float64)
        self.vertices = self.vertices @ matrix[:3, :3].T + matrix[:3, 3]

    def apply_scale(self, scale) -> None:
        self.vertices = self.vertices * np.asarray(scale, dtype=np.float64)

    def merge_vertices(self) -> None:
        """Make vertices that share their coordinates (to MERGE_DIGITS) one vertex."""
        if not len(self.vertices):
            return
        keys = np.round(self.vertices, MERGE_DIGITS)
        unique, first, inverse = np.unique(keys, axis=0, return_index=True, return_inverse=True)
        self.vertices = self.vertices[first]
        self.faces = inverse.reshape(-1)[self.faces]


def read(path: str | Path) -> Mesh | None:
    """The mesh in a file, unmerged, or None when it holds no triangles or cannot be read."""
    path = Path(path)
    mesh = _binary_stl(path) if path.suffix.lower() == ".stl" else None
    if mesh is None:
        mesh = _with_trimesh(path)
    return mesh if mesh is not None and len(mesh.faces) else None


def _binary_stl(path: Path) -> Mesh | None:
    """A binary STL whose size agrees with its triangle count, else None (let trimesh try)."""
    try:
        data = path.read_bytes()
    except OSError:
        return None
    if len(data) < 84:
        return None
    count = int.from_bytes(data[80:84], "little")
    if len(data) != 84 + 50 * count or count == 0:
        return None
    records = np.frombuffer(data, dtype=_STL_RECORD, count=count, offset=84)
    vertices = records["points"].reshape(-1, 3).astype(np.float64)
    return Mesh(vertices, np.arange(3 * count).reshape(-1, 3))


def _with_trimesh(path: Path) -> Mesh | None:
    import trimesh
    from ..mesh_formats import in_metres   # a COLLADA file's <unit>, as MuJoCo gets it
    try:
        loaded = trimesh.load(str(path), force="mesh", process=False)
    except Exception:  # noqa: BLE001  (any reader failure means "unreadable"; meshes.check says so)
        return None
    if not isinstance(loaded, trimesh.Trimesh) or not in_metres(loaded):
        return None
    return Mesh(loaded.vertices, loaded.faces)


# -- URDF's primitives, as closed meshes ---------------------------------------------------

def box(size) -> Mesh:
    """A box of edge lengths `size`, centred on the origin."""
    corners = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], float)
    faces = [[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
             [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]]
    return Mesh(corners * np.asarray(size, dtype=float) / 2, faces)


def cylinder(radius: float, length: float, sections: int = 48) -> Mesh:
    """A cylinder along z, centred on the origin, as a prism of `sections` sides."""
    angles = np.arange(sections) * 2 * math.pi / sections
    ring = np.column_stack([radius * np.cos(angles), radius * np.sin(angles)])
    low = np.column_stack([ring, np.full(sections, -length / 2)])
    high = np.column_stack([ring, np.full(sections, length / 2)])
    vertices = np.vstack([low, high, [[0, 0, -length / 2], [0, 0, length / 2]]])
    bottom, top = 2 * sections, 2 * sections + 1
    faces = []
    for i in range(sections):
        j = (i + 1) % sections
        faces += [[i, j, sections + j], [i, sections + j, sections + i],
                  [bottom, j, i], [top, sections + i, sections + j]]
    return Mesh(vertices, faces)


def sphere(radius: float, rings: int = 16, segments: int = 32) -> Mesh:
    """A sphere centred on the origin, as a polyhedron of `rings` bands."""
    vertices = [[0.0, 0.0, radius]]
    for r in range(1, rings):
        polar = math.pi * r / rings
        for s in range(segments):
            azimuth = 2 * math.pi * s / segments
            vertices.append([radius * math.sin(polar) * math.cos(azimuth),
                             radius * math.sin(polar) * math.sin(azimuth),
                             radius * math.cos(polar)])
    vertices.append([0.0, 0.0, -radius])
    south = len(vertices) - 1
    faces = []

    def at(r, s):
        return 1 + (r - 1) * segments + s % segments

    for s in range(segments):
        faces.append([0, at(1, s), at(1, s + 1)])
        faces.append([south, at(rings - 1, s + 1), at(rings - 1, s)])
    for r in range(1, rings - 1):
        for s in range(segments):
            faces += [[at(r, s), at(r + 1, s), at(r + 1, s + 1)],
                      [at(r, s), at(r + 1, s + 1), at(r, s + 1)]]
    return Mesh(vertices, faces)


def euler_matrix(roll: float, pitch: float, yaw: float) -> np.ndarray:
    """The 4 x 4 rotation of URDF's rpy: roll about x, then pitch about y, then yaw about z
    (all about the fixed axes), R = Rz(yaw) Ry(pitch) Rx(roll)."""
    cr, sr, cp, sp, cy, sy = (math.cos(roll), math.sin(roll), math.cos(pitch),
                              math.sin(pitch), math.cos(yaw), math.sin(yaw))
    matrix = np.eye(4)
    matrix[:3, :3] = [[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                      [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                      [-sp, cp * sr, cp * cr]]
    return matrix


def hull_volume(points: np.ndarray) -> float:
    """The volume of the points' convex hull (0 for flat or too few points)."""
    import manifold3d
    if len(points) < 4:
        return 0.0
    return float(manifold3d.Manifold.hull_points(np.asarray(points, dtype=np.float64)).volume())


def hull(points: np.ndarray) -> Mesh | None:
    """The points' convex hull as a closed mesh; None when they span no volume."""
    import manifold3d
    if len(points) < 4:
        return None
    solid = manifold3d.Manifold.hull_points(np.asarray(points, dtype=np.float64))
    if solid.volume() <= 0:
        return None
    mesh = solid.to_mesh()
    return Mesh(np.asarray(mesh.vert_properties, dtype=np.float64)[:, :3],
                np.asarray(mesh.tri_verts, dtype=np.int64))


def hull_planes(points: np.ndarray) -> np.ndarray | None:
    """The face planes of the points' convex hull as rows (n, d), n outward and of length 1,
    with n.x + d <= 0 inside; None when the points span no volume."""
    shape = hull(points)
    if shape is None:
        return None
    triangles = shape.triangles
    normals = np.cross(triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0])
    lengths = np.linalg.norm(normals, axis=1)
    keep = lengths > 0
    normals = normals[keep] / lengths[keep, None]
    offsets = -np.einsum("ij,ij->i", normals, triangles[keep, 0])
    return np.column_stack([normals, offsets])
