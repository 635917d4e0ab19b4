"""The links' shapes and masses as the checks measure them: each link's visual or
collision geometry as meshes in its frame, closed solids, inertials, and the link tree
with each link's pose at rest. Rule modules build on this one and never on each other.
"""

from __future__ import annotations

import math
import weakref
from dataclasses import dataclass

import manifold3d
import numpy as np

from .trimeshes import (Mesh, box, corners, cylinder, euler_matrix, hull, solid_properties,
                        sphere)
from .urdf import number, vector


# MuJoCo's STL decoder refuses files with more triangles than this (mujoco#327).
STL_FACE_LIMIT = 200_000


# Geometry placed farther out than this (in metres) is not measured: such numbers are
# typos, and hulls and mesh booleans lose their precision there.
FAR = 1e5


def millimetre_suspect(link, mesh: Mesh) -> str | None:
    """Why `mesh` (in metres as the URDF scales it) looks like millimetres, or None.

    A link's inertia says how far its mass lies from its centre: with mass m and moments
    Ixx, Iyy, Izz about the centre of mass, r = sqrt((Ixx + Iyy + Izz) / (2 m)) is the
    root-mean-square distance of the mass from the centre. A mesh that holds that mass is
    a few times r across: its bounding-box diagonal d is 3 to 6 r for solids, plates and
    rods, and rarely above 50 r even for a heavy core with a long light arm. A mesh in
    millimetres is read 1000 times too large, so d / r lands near 1000 times those values.
    The warning needs d / 1000 to agree with r again (0.3 r to 60 r): a mesh that is merely
    odd, or an inertia that is itself wrong, does not pass for millimetres. A link without
    a usable inertia is judged by size alone: over 10 m across.
    """

    if len(mesh.vertices) == 0:
        return None
    diagonal = float(np.linalg.norm(mesh.extents))
    inertial = inertial_of(link)
    spread = None if inertial is None else inertial.spread
    if spread:
        ratio = diagonal / spread
        if 300 <= ratio <= 60_000:
            return (f"it is {diagonal:.3g} m across, while the link's inertia puts its mass "
                    f"within about {spread:.3g} m of the centre of mass ({ratio:.0f} times less)")
        return None
    if diagonal > 10:
        return f"it is {diagonal:.3g} m across"
    return None


@dataclass(frozen=True)
class Piece:
    """One <visual> or <collision> of a link, as a triangle mesh in the link's frame."""

    element: object             # the <visual> or <collision> element
    shape: object               # its <mesh>, <box>, <cylinder> or <sphere>
    mesh: Mesh       # metres, link frame, vertices merged; its own copy
    pose: np.ndarray            # the element's <origin>: where `local` sits in the link
    local: Mesh      # the shape in its own frame, shared: never change it


def link_geometry(ctx, link, kind: str = "collision") -> list[Piece] | None:
    """The link's <visual> or <collision> geometry in its frame; [] when it has none, and
    None when some of it cannot be known (a missing or unreadable mesh, a malformed origin
    or size, a mesh that looks like millimetres or has more triangles than MuJoCo reads):
    then checks that need all of it skip."""
    pieces = []
    for element in link.findall(kind):
        geometry = element.find("geometry")
        shape = None if geometry is None else next(
            (s for s in geometry if s.tag in ("mesh", "box", "cylinder", "sphere")), None)
        pose = origin_matrix(element)
        local = None if shape is None else _shape_mesh(ctx, link, shape)
        if local is None or pose is None:
            return None
        mesh = local.copy()
        mesh.apply_transform(pose)
        if not np.all(np.abs(mesh.vertices) < FAR):
            return None
        pieces.append(Piece(element, shape, mesh, pose, local))
    return pieces


def origin_matrix(element) -> np.ndarray | None:
    """The 4 x 4 pose given by an element's <origin> (identity without one); None when a
    number in it is malformed (structure.py reports that)."""
    origin = element.find("origin")
    if origin is None:
        return np.eye(4)
    xyz = vector(origin.get("xyz", "0 0 0"), 3)
    rpy = vector(origin.get("rpy", "0 0 0"), 3)
    if xyz is None or rpy is None:
        return None
    pose = euler_matrix(*rpy)  # URDF: roll about x, then pitch about y, then yaw about z
    pose[:3, 3] = xyz
    return pose


# Each context's meshes with their vertices merged (the context reads them unmerged), by
# file content and scale: closed meshes are then recognised as closed, and merging is done
# once for all the files of the same bytes.
_merged: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def _shape_mesh(ctx, link, shape) -> Mesh | None:
    """The shape as a mesh in its own frame (shared: copy it before changing it)."""
    if shape.tag == "mesh":
        mesh = merged_mesh(ctx, shape)
        if mesh is None or millimetre_suspect(link, mesh):
            return None
        return mesh
    if shape.tag == "box":
        size = vector(shape.get("size"), 3)
        return box(size) if size and _sizes_ok(*size) else None
    radius = number(shape.get("radius"))
    if shape.tag == "sphere":
        return sphere(radius) if _sizes_ok(radius) else None
    length = number(shape.get("length"))
    if not _sizes_ok(radius, length):
        return None
    return cylinder(radius, length, sections=48)


def merged_mesh(ctx, shape) -> Mesh | None:
    """The file a <mesh> names, scale applied, vertices merged (shared: copy it before
    changing it); None when it cannot be read, has a coordinate that is not finite, or has
    more triangles than MuJoCo reads from an STL (the model does not load then, and
    measuring would take seconds)."""
    cache = _merged.setdefault(ctx, {})
    key = (ctx.mesh_content(shape), shape.get("scale"))   # files of the same bytes: once
    if key not in cache:
        mesh = ctx.mesh(shape)
        if mesh is not None and len(mesh.faces) <= STL_FACE_LIMIT \
                and np.isfinite(mesh.vertices).all():
            mesh = Mesh(mesh.vertices, mesh.faces)   # merging makes new arrays: no copy
            mesh.merge_vertices()
        else:
            mesh = None
        cache[key] = mesh
    return cache[key]


def hull_solid(mesh: Mesh) -> manifold3d.Manifold:
    """The convex hull of a shared shape mesh's vertices, worked out once (the collision
    checks place it, the stability run gives its corners to MuJoCo)."""
    if mesh not in _hulls:
        _hulls[mesh] = manifold3d.Manifold.hull_points(np.asarray(mesh.vertices,
                                                                  dtype=np.float64))
    return _hulls[mesh]


def closed_volume(mesh: Mesh) -> float | None:
    """The volume a shared shape mesh encloses (`_enclosed_volume`), worked out once."""
    if mesh not in _volumes:
        _volumes[mesh] = _enclosed_volume(mesh)
    return _volumes[mesh]


def _sizes_ok(*sizes) -> bool:
    """Whether every size of a primitive is one this check can mesh: above a nanometre, below
    FAR (smaller or larger ones are typos that other rules or MuJoCo report)."""
    return all(size is not None and 1e-9 < size < FAR for size in sizes)


# Each shared shape mesh as a closed solid (or False), so that a file is built once.
_volumes: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()
_solids: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()
_hulls: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def enclosed_volume(piece: Piece) -> float | None:
    """The volume the piece's mesh encloses, in m^3, when it is a closed solid; None when
    its mesh is open, inverted or broken (the meshes `closed_solid` refuses)."""
    return closed_volume(piece.local)


def _enclosed_volume(mesh: Mesh) -> float | None:
    """The volume of a closed, outward-facing mesh; None for any other.

    Closed means that every edge of a face, taken in the face's own direction, is used by
    no other face in that direction and by exactly one face in the opposite one: each edge
    joins two faces that agree on which side is outside. That is manifold3d's condition
    for a solid (tests/tool/check/test_enclosed_volume.py compares the two), met here with
    two sorts of the edges instead of building its half-edge structure, a quarter of the
    time on a mesh of 100,000 triangles. The volume is the sum of the signed tetrahedra
    each face makes with the vertices' centre."""
    faces = mesh.faces
    if not len(faces):
        return None
    count = int(faces.max()) + 1
    following = faces[:, [1, 2, 0]]
    edges = (faces * count + following).ravel()
    opposite = (following * count + faces).ravel()
    edges.sort()
    opposite.sort()
    if (edges[1:] == edges[:-1]).any() or not np.array_equal(edges, opposite):
        return None
    corners = mesh.vertices[faces] - mesh.vertices.mean(axis=0)   # near 0: less cancellation
    volume = float(np.einsum("ij,ij->", corners[:, 0],
                             np.cross(corners[:, 1], corners[:, 2]))) / 6
    return volume if volume > 0 else None


def closed_solid(piece: Piece, pose: np.ndarray | None = None) -> manifold3d.Manifold | None:
    """The piece as a manifold3d solid, for booleans with others, in the link's frame or
    moved on by `pose`; None when its mesh is not closed (see `enclosed_volume`)."""
    if enclosed_volume(piece) is None:
        return None
    if piece.local not in _solids:
        _solids[piece.local] = as_solid(piece.local) or False
    solid = _solids[piece.local]
    if not solid:
        return None
    place = piece.pose if pose is None else pose @ piece.pose
    return solid.transform(place[:3, :4])


def as_solid(mesh: Mesh) -> manifold3d.Manifold | None:
    """The mesh as a manifold3d solid when it is closed, without self-contradicting edges,
    and outward-facing (positive volume); None for an open, inverted or broken mesh."""
    try:
        solid = manifold3d.Manifold(manifold3d.Mesh64(
            vert_properties=np.asarray(mesh.vertices, dtype=np.float64),
            tri_verts=np.asarray(mesh.faces, dtype=np.uint64)))
    except Exception:  # noqa: BLE001  (manifold3d refuses malformed arrays)
        return None
    if solid.status() != manifold3d.Error.NoError or solid.volume() <= 0:
        return None
    return solid


def solid_triangles(ctx, link):
    """(kind, closed, triangles in link axes) of the solid the link's collision geometry
    makes, else its visual's: the meshes themselves when all are closed, else their convex
    hull; None when neither can be measured."""
    for kind in ("collision", "visual"):
        pieces = link_geometry(ctx, link, kind)
        if pieces:
            break
    else:
        return None
    closed = all(enclosed_volume(p) is not None for p in pieces)
    if closed:
        return kind, True, np.vstack([p.mesh.triangles for p in pieces])
    shape = hull(np.vstack([p.mesh.vertices for p in pieces]))
    return None if shape is None else (kind, False, shape.triangles)


def solid_of(ctx, link):
    """(kind, closed, volume, inertia tensor about its centroid at density 1, link axes) of
    the link's solid (`solid_triangles`); None when it cannot be measured."""
    solid = solid_triangles(ctx, link)
    if solid is None:
        return None
    kind, closed, triangles = solid
    volume, _, tensor = solid_properties(triangles)
    if not volume > 0 or not np.all(np.isfinite(tensor)):
        return None
    return kind, closed, volume, tensor


def model_size(ctx, tree: "Tree") -> float:
    """The diagonal of the box around the model at rest: every link's origin and the corners
    of the boxes around its visual and collision geometry, in the root's frame."""
    points = []
    for name, link in ctx.links.items():
        pose = tree.pose(name)
        if pose is None:
            continue
        points.append(pose[:3, 3])
        for kind in ("visual", "collision"):
            for piece in link_geometry(ctx, link, kind) or ():
                low, high = corners(piece.mesh.vertices)
                box = np.array([[x, y, z] for x in (low[0], high[0]) for y in (low[1], high[1])
                                for z in (low[2], high[2])])
                points.extend(box @ pose[:3, :3].T + pose[:3, 3])
    if not points:
        return 0.0
    low, high = corners(np.array(points))
    return float(np.linalg.norm(high - low))


INERTIA_TERMS = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")


@dataclass(frozen=True)
class Inertial:
    """A link's <inertial>, with what could be read from it (None where a value is absent or
    malformed; structure.py reports malformed numbers)."""

    element: object
    mass: float | None
    centre: np.ndarray | None      # the centre of mass in the link's frame
    tensor: np.ndarray | None      # 3 x 3, about the centre of mass, in the link's axes
    missing: tuple[str, ...]       # what is absent: "<mass>", "<inertia>", "ixy", ...

    @property
    def spread(self) -> float | None:
        """The root-mean-square distance of the mass from the centre of mass, in metres."""
        if self.tensor is None or not self.mass or self.mass <= 0:
            return None
        trace = float(np.trace(self.tensor))
        return math.sqrt(trace / (2 * self.mass)) if trace > 0 else None


def inertial_of(link) -> Inertial | None:
    """The link's first <inertial>, read; None when it has none."""
    element = link.find("inertial")
    if element is None:
        return None
    missing = []
    mass_el = element.find("mass")
    if mass_el is None or mass_el.get("value") is None:
        missing.append("<mass value>")
    mass = None if mass_el is None else number(mass_el.get("value"))
    inertia_el = element.find("inertia")
    terms = {}
    if inertia_el is None:
        missing.append("<inertia>")
    else:
        for term in INERTIA_TERMS:
            if inertia_el.get(term) is None:
                missing.append(term)
            terms[term] = number(inertia_el.get(term))
    pose = origin_matrix(element)
    tensor = None
    if pose is not None and terms and None not in terms.values():
        t = terms
        local = np.array([[t["ixx"], t["ixy"], t["ixz"]],
                          [t["ixy"], t["iyy"], t["iyz"]],
                          [t["ixz"], t["iyz"], t["izz"]]])
        turn = pose[:3, :3]
        tensor = turn @ local @ turn.T
    centre = None if pose is None else pose[:3, 3].copy()
    return Inertial(element, mass, centre, tensor, tuple(missing))


class Tree:
    """The links as the joints connect them, and where each one is at the rest pose.

    Robust to broken input (structure.py reports it): a link that is the child of two
    joints keeps the first, a cycle ends the walk up the tree, and long chains are walked
    without recursion.
    """

    def __init__(self, ctx):
        self.links = ctx.links
        self._joint: dict[str, object] = {}
        for joint in ctx.robot.findall("joint"):
            parent, child = joint.find("parent"), joint.find("child")
            if parent is None or child is None:
                continue
            if parent.get("link") in self.links and child.get("link") in self.links:
                self._joint.setdefault(child.get("link"), joint)
        self._body: dict[str, str | None] = {}
        self._poses: dict[str, np.ndarray | None] = {}
        self._members: dict[str | None, list[str]] | None = None

    def parent(self, name: str | None) -> str | None:
        joint = self._joint.get(name)
        return None if joint is None else joint.find("parent").get("link")

    def joint_name(self, name: str) -> str:
        joint = self._joint.get(name)
        return "" if joint is None else joint.get("name", "")

    def moves(self, name: str) -> bool:
        """Whether the joint above the link lets it move relative to its parent."""
        joint = self._joint.get(name)
        return joint is not None and joint.get("type") != "fixed"

    def _upwards(self, name: str, known: dict) -> tuple[list[str], bool]:
        """The links from `name` upwards that `known` lacks, and whether the walk stopped at
        a known link (True) rather than at the root or a cycle (False)."""
        path, seen = [], set()
        while name is not None and name not in known:
            if name in seen:
                return path, False
            seen.add(name)
            path.append(name)
            name = self.parent(name)
        return path, name is not None

    def body(self, name: str | None) -> str | None:
        """The moving link whose rigid body `name` belongs to (itself, or the nearest link
        above it whose joint is not fixed); None when it is welded to the world."""
        if name is None:
            return None
        path, stopped = self._upwards(name, self._body)
        found = self._body[self.parent(path[-1])] if stopped and path else None
        for link in reversed(path):  # from the top down
            found = link if self.moves(link) else found
            self._body[link] = found
        return self._body.get(name)

    def rigid_body(self, head: str) -> list[str]:
        """The links that move as one with `head`: it and those fixed to it."""
        if self._members is None:
            self._members = {}
            for name in self.links:
                self._members.setdefault(self.body(name), []).append(name)
        return self._members.get(head, [])

    def pose(self, name: str) -> np.ndarray | None:
        """The link's pose in the root's frame with every joint at zero; None when an origin
        on the way is malformed or the joints form a cycle."""
        path, stopped = self._upwards(name, self._poses)
        if stopped:
            pose = self._poses[self.parent(path[-1])] if path else self._poses[name]
        else:
            cycle = bool(path) and self.parent(path[-1]) is not None
            pose = None if cycle else np.eye(4)
        for link in reversed(path):  # from the top down
            joint = self._joint.get(link)
            if joint is not None:
                local = origin_matrix(joint)
                pose = None if pose is None or local is None else pose @ local
            self._poses[link] = pose
        return self._poses.get(name)

    def mujoco_ignores(self, a: str, b: str) -> bool:
        """Whether MuJoCo, with the model as sw2sim.load_package builds it, never looks for
        contacts between links a and b.

        MuJoCo skips pairs within one rigid body, and a body and its parent body unless the
        parent is welded to the world; load_package also skips a link welded to the world
        and each link it carries directly.
        """
        body_a, body_b = self.body(a), self.body(b)
        if body_a == body_b:
            return True
        if body_a is not None and body_b is not None:
            return self.body(self.parent(body_a)) == body_b or \
                self.body(self.parent(body_b)) == body_a
        return (body_a is None and self.parent(b) == a) or (body_b is None and self.parent(a) == b)
