"""Triangle meshes as the checks need them, without a mesh library's start-up cost.

`sw2sim check` must answer within half a second, and importing a full mesh library (with
the scientific stack behind it) takes seconds. The checks only need vertices and faces,
moved, scaled and merged; the primitives of URDF as closed meshes; and the simple formats
exporters write: binary STL (the SolidWorks exporter's), text STL, OBJ of triangles and
COLLADA of triangles (sw2sim/collada_reader.py). `read` decodes those here, and hands
anything else (PLY, glTF, an OBJ of quads, materials or negative indices, COLLADA with
quads or instanced nodes, a file these readers do not fully understand) to trimesh,
imported only then. What the readers here accept, trimesh reads to the same triangles
(tests/tool/check/test_mesh_readers.py compares them), so a check's verdict never depends
on which of them read the file.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

# Vertices closer than this (metres) are one vertex once merged: STL repeats each vertex
# for every triangle that uses it, with exactly the same numbers.
MERGE_DIGITS = 8

_STL_RECORD = np.dtype([("normal", "<f4", (3,)), ("points", "<f4", (3, 3)), ("attr", "<u2")])


def corners(points: np.ndarray) -> np.ndarray:
    """The lowest and the highest corner of the box around n x 3 points, as 2 x 3; the same
    numbers as `points.min(axis=0)` and `.max(axis=0)`, which numpy computes a tenth as fast
    (a row of three at a time: 20 ms for a mesh of 100,000 triangles)."""
    columns = points.T
    return np.array([[column.min() for column in columns], [column.max() for column in columns]])


class Mesh:
    """Vertices (n x 3 floats) and faces (m x 3 vertex indices), counter-clockwise seen from
    outside for a closed mesh. `loose`: the file's points that no face uses (k x 3), which
    the vertices leave out as trimesh does and MuJoCo's hull of the file takes in; None
    where the reader cannot tell (only the OBJ reader here tells)."""

    def __init__(self, vertices, faces, loose=None):
        self.vertices = np.asarray(vertices, dtype=np.float64).reshape(-1, 3)
        self.faces = np.asarray(faces, dtype=np.int64).reshape(-1, 3)
        self.loose = None if loose is None else \
            np.asarray(loose, dtype=np.float64).reshape(-1, 3)

    def copy(self) -> "Mesh":
        return Mesh(self.vertices.copy(), self.faces.copy(),
                    None if self.loose is None else self.loose.copy())

    @property
    def triangles(self) -> np.ndarray:
        return self.vertices[self.faces]

    @property
    def bounds(self) -> np.ndarray:
        return corners(self.vertices)

    @property
    def extents(self) -> np.ndarray:
        if not len(self.vertices):
            return np.zeros(3)
        low, high = corners(self.vertices)
        return high - low

    def apply_transform(self, matrix: np.ndarray) -> None:
        matrix = np.asarray(matrix, dtype=np.float64)
        self.vertices = self.vertices @ matrix[:3, :3].T + matrix[:3, 3]
        if self.loose is not None:
            self.loose = self.loose @ matrix[:3, :3].T + matrix[:3, 3]

    def apply_scale(self, scale) -> None:
        self.vertices = self.vertices * np.asarray(scale, dtype=np.float64)
        if self.loose is not None:
            self.loose = self.loose * np.asarray(scale, dtype=np.float64)

    def merge_vertices(self) -> None:
        """Make vertices that share their coordinates (to MERGE_DIGITS) one vertex."""
        if not len(self.vertices):
            return
        # np.unique(keys, axis=0) gives the same vertices in the same order, but sorts the
        # rows as records, five times slower than this stable sort on the three columns.
        keys = np.round(self.vertices, MERGE_DIGITS)
        order = np.lexsort((keys[:, 2], keys[:, 1], keys[:, 0]))
        ordered = keys[order]
        starts = np.empty(len(order), dtype=bool)
        starts[0] = True
        np.any(ordered[1:] != ordered[:-1], axis=1, out=starts[1:])
        inverse = np.empty(len(order), dtype=np.int64)
        inverse[order] = np.cumsum(starts) - 1
        self.vertices = self.vertices[order[starts]]
        self.faces = inverse[self.faces]


class _NotSimple(Exception):
    """The file is not in the simple form the readers here understand: trimesh reads it."""


def read(path: str | Path, data: bytes | None = None) -> Mesh | None:
    """The mesh in a file, unmerged, or None when it holds no triangles or cannot be read;
    `data` is the file's bytes when the caller has read them already."""
    path = Path(path)
    reader = _READERS.get(path.suffix.lower())
    if reader is None:
        mesh = _with_trimesh(path)
    else:
        try:
            mesh = reader(path.read_bytes() if data is None else data)
        except OSError:
            return None
        except _NotSimple:
            mesh = _with_trimesh(path)
    return mesh if mesh is not None and len(mesh.faces) else None


def _stl(data: bytes) -> Mesh | None:
    """Binary STL, when the size agrees with the triangle count (as trimesh decides), else
    text STL."""
    if len(data) >= 84:
        count = int.from_bytes(data[80:84], "little")
        if len(data) == 84 + 50 * count:
            if count == 0:
                return None
            records = np.frombuffer(data, dtype=_STL_RECORD, count=count, offset=84)
            vertices = records["points"].reshape(-1, 3).astype(np.float64)
            return Mesh(vertices, np.arange(3 * count).reshape(-1, 3))
    return _text_stl(data)


def _text_stl(data: bytes) -> Mesh:
    """A text STL of one solid, taken apart as trimesh takes it apart (between "solid" and
    "endsolid", the numbers after each "vertex" to the end of its line); anything else
    (several solids, a facet that is no triangle, a word that is no number) is left to it."""
    text = _decoded(data).strip().lower()
    found, position = [], 0
    for _ in range(len(text)):
        start, end = text.find("solid", position), text.find("endsolid", position)
        position = end + len("endsolid")
        if start < 0 or end < 0:
            break
        if start > end:
            raise _NotSimple
        pieces = text[start:end].split("vertex")[1:]
        numbers = _parsed(" ".join(piece[: piece.find("\n")] for piece in pieces), np.float64)
        if len(numbers) >= 3:
            found.append(numbers)
    if len(found) != 1 or len(found[0]) % 9 or not np.isfinite(found[0]).all():
        raise _NotSimple
    vertices = found[0].reshape(-1, 3)
    return Mesh(vertices, np.arange(len(vertices)).reshape(-1, 3))


# The OBJ statements read here (v, f) or passed over: normals and texture coordinates,
# which are only counted; object, group, smoothing and material names (trimesh splits faces
# by material only, at `usemtl`); comments. Any other line leaves the file to trimesh.
_OBJ_STATEMENTS = (b"v ", b"f ", b"vn ", b"vt ", b"o ", b"g ", b"s ", b"mtllib ", b"usemtl ", b"#")

# The forms of a face corner, by the slashes in it: `1`, `1/2`, `1//3`, `1/2/3`: how many
# slashes, whether two are adjacent, and which counts (besides the vertices') index into.
_OBJ_FORMS = {(0, False): (), (1, False): (b"vt ",), (2, True): (b"vn ",),
              (2, False): (b"vt ", b"vn ")}

_DIGITS_SLASH_SPACE = np.zeros(256, dtype=bool)
_DIGITS_SLASH_SPACE[list(b"0123456789/ \n")] = True


def _obj(data: bytes) -> Mesh:
    """An OBJ whose faces are all triangles, with positive indices in one form throughout
    (`1`, `1/2`, `1//3` or `1/2/3`), three numbers per vertex, and no `usemtl` after the
    first face (trimesh would split the faces there and put them back in another order).

    trimesh keeps only the vertices the faces use and, where faces also name texture
    coordinates or normals, one vertex per distinct combination; the same is done here.
    The lines are sorted out with byte counts and the numbers read by numpy: a loop over
    the lines in Python would take a second for a million triangles."""
    text, counts, vertices = _obj_positions(data)
    faces = _statements(text, b"f ", counts[b"f "])[1:] + b"\n"
    columns = _corner_columns(faces, counts[b"f "])
    limits = [len(vertices)] + [counts[key] for key in columns]
    refs = _parsed(faces.replace(b"/", b" "), np.int64)
    if len(refs) != 3 * len(limits) * counts[b"f "]:
        raise _NotSimple
    refs = refs.reshape(-1, len(limits)) - 1
    if (refs < 0).any() or (refs >= limits).any() or math.prod(limits) >= 2 ** 62:
        raise _NotSimple   # an index 0 or past the end (trimesh fails or wraps it round)
    key, scale = refs[:, 0], 1
    for column, limit in zip(refs.T[1:], limits[1:]):
        key, scale = key * limit + column, scale * limit
    combos, inverse = np.unique(key, return_inverse=True)
    kept = combos // scale   # the vertex of each distinct corner
    used = np.zeros(len(vertices), dtype=bool)
    used[kept] = True
    return Mesh(vertices[kept], inverse.reshape(-1, 3), loose=vertices[~used])


def _obj_positions(data: bytes) -> tuple[bytes, dict[bytes, int], np.ndarray]:
    """An OBJ in the simple form `_obj` reads: its text (each line after a newline), its
    statement counts, and every `v` line's position (n x 3), also of a corner no face uses;
    else _NotSimple."""
    _decoded(data)   # another encoding: trimesh guesses which
    if b"\\" in data or b"\t" in data or data.count(b"\r") != data.count(b"\r\n"):
        raise _NotSimple   # continued lines, tabs, old Mac line ends: trimesh's own ways
    text = b"\n" + data.replace(b"\r\n", b"\n")
    counts, empty, lines = _statement_counts(text)
    if sum(counts.values()) + empty != lines \
            or counts[b"usemtl "] > 1 or data.count(b"usemtl") != counts[b"usemtl "] \
            or not counts[b"f "] or not counts[b"v "]:
        raise _NotSimple   # another statement; materials, or "usemtl" in a name
    if counts[b"usemtl "] and text.find(b"\nusemtl ") > text.find(b"\nf "):
        raise _NotSimple
    for key in (b"vt ", b"vn "):   # unused, but trimesh fails where they are no numbers
        if counts[key]:
            _parsed(_statements(text, key, counts[key]), np.float64)
    positions = _statements(text, b"v ", counts[b"v "])
    vertices = _parsed(positions, np.float64)
    first = positions[1:positions.find(b"\n", 1)] if b"\n" in positions[1:] else positions[1:]
    if len(first.split()) != 3 or len(vertices) != 3 * counts[b"v "] \
            or not np.isfinite(vertices).all():
        raise _NotSimple   # vertices with colours or weights, not-a-number
    return text, counts, vertices.reshape(-1, 3)


def _statements(text: bytes, key: bytes, count: int) -> bytes:
    """What follows `key` on each of the `count` lines of `text` that begin with it, each
    after a newline ("\\n1 2 3\\n4 5 6" for "f "). Exporters write each kind of statement
    in one run of lines: then the run is cut out whole, instead of a loop over the lines in
    Python (a fifth of a second for 300,000 lines); else the lines are picked one by one."""
    start, last = text.find(b"\n" + key), text.rfind(b"\n" + key)
    end = text.find(b"\n", last + 1)
    run = text[start:] if end < 0 else text[start:end]
    if run.count(b"\n") == count:   # every line of the run begins with `key`
        return run.replace(b"\n" + key, b"\n")
    return b"".join(b"\n" + line[len(key):] for line in text.split(b"\n")
                    if line[:len(key)] == key)


_HEAD = max(len(key) for key in _OBJ_STATEMENTS)


def _statement_counts(text: bytes) -> tuple[dict[bytes, int], int, int]:
    """How many lines of `text` (each begun by a newline) begin with each of
    _OBJ_STATEMENTS, how many are empty, and how many there are: the first bytes of every
    line compared at once (`text.count` for each statement reads the whole file ten times)."""
    chars = np.frombuffer(text, dtype=np.uint8)
    starts = np.flatnonzero(chars == ord("\n")) + 1
    padded = np.concatenate([chars, np.zeros(_HEAD, dtype=np.uint8)])   # the last line's
    heads = [padded[starts + n] for n in range(_HEAD)]   # each line's n-th byte
    counts = {}
    for key in _OBJ_STATEMENTS:
        match = heads[0] == key[0]
        for n in range(1, len(key)):
            match &= heads[n] == key[n]
        counts[key] = int(np.count_nonzero(match))
    empty = int(np.count_nonzero(heads[0] == ord("\n"))) + bool(starts[-1] == len(chars))
    return counts, empty, len(starts)


def _corner_columns(faces: bytes, count: int) -> tuple[bytes, ...]:
    """Which counts a face's indices after the vertex index refer to, when `faces` (the
    text after each "f ", a line each) is `count` lines of three corners of one form,
    separated by single spaces; else _NotSimple."""
    chars = np.frombuffer(faces, dtype=np.uint8)
    if not _DIGITS_SLASH_SPACE[chars].all() or b"  " in faces or b" \n" in faces \
            or b"\n " in faces or faces.startswith(b" "):
        raise _NotSimple
    ends = np.flatnonzero(chars == ord("\n"))
    spaces = np.flatnonzero(chars == ord(" "))
    if len(ends) != count or len(spaces) != 2 * count \
            or (np.bincount(np.searchsorted(ends, spaces), minlength=count) != 2).any():
        raise _NotSimple   # quads and polygons
    # each corner's first character, and the slashes in each corner
    starts = np.sort(np.r_[0, spaces + 1, ends[:-1] + 1])
    slashes = np.bincount(np.searchsorted(starts, np.flatnonzero(chars == ord("/")),
                                          side="right") - 1, minlength=len(starts))
    stops = np.r_[starts[1:] - 2, len(chars) - 2]
    first, adjacent = int(slashes[0]), faces.count(b"//")
    form = (first, adjacent > 0)
    if form not in _OBJ_FORMS or (slashes != first).any() or adjacent not in (0, len(starts)) \
            or (chars[starts] == ord("/")).any() or (chars[stops] == ord("/")).any():
        raise _NotSimple   # another form, or corners of several forms
    return _OBJ_FORMS[form]


def _dae(data: bytes) -> Mesh | None:
    """COLLADA in its common simple form (sw2sim/collada_reader.py); a document that declares
    a DOCTYPE is refused (None: no mesh), not handed to trimesh."""
    from .. import collada_reader
    try:
        vertices, faces = collada_reader.read_collada(data)
    except collada_reader.NotSimple:
        raise _NotSimple from None
    except collada_reader.Refused:
        return None
    return Mesh(vertices, faces)


# The readers here, by file extension (any case).
_READERS = {".stl": _stl, ".obj": _obj, ".dae": _dae}


def _decoded(data: bytes) -> str:
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError:
        raise _NotSimple from None


def _parsed(text: bytes | str, dtype) -> np.ndarray:
    """The numbers in `text`, separated by white space, read as trimesh reads them (numpy's
    text parser); _NotSimple where something else stands between them."""
    try:
        return np.fromstring(text, dtype=dtype, sep=" ")
    except ValueError:
        raise _NotSimple from None


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


def solid_properties(triangles: np.ndarray) -> tuple[float, np.ndarray, np.ndarray]:
    """Volume, centroid and inertia tensor about the centroid (at density 1) of the solid
    that closed, outward-facing triangles (n x 3 x 3) bound.

    Each triangle and the origin make a tetrahedron of signed volume det / 6, with
    det = a . (b x c); its second moment sum(x x^T) over the volume is det / 120 times
    (a a^T + b b^T + c c^T + s s^T), s = a + b + c. Summed, moved to the centroid, and
    turned into the inertia tensor: trace(C) I - C."""
    a, b, c = triangles[:, 0], triangles[:, 1], triangles[:, 2]
    det = np.einsum("ij,ij->i", a, np.cross(b, c))
    volume = float(det.sum()) / 6
    s = a + b + c
    centroid = (det[:, None] * s).sum(axis=0) / (24 * volume)
    second = np.einsum("i,ij,ik->jk", det, a, a) + np.einsum("i,ij,ik->jk", det, b, b) \
        + np.einsum("i,ij,ik->jk", det, c, c) + np.einsum("i,ij,ik->jk", det, s, s)
    second = second / 120 - volume * np.outer(centroid, centroid)
    return volume, centroid, np.trace(second) * np.eye(3) - second
