"""Checks of the links' collision geometry at the rest pose (every joint at zero).

Two things can go wrong where links meet. Their meshes can pass through each other, which
real parts cannot: in a simulator that collides parent and child (Gazebo with self-collision,
PyBullet, MuJoCo where the parent is welded to the world) the joint locks or the part
bounces. And MuJoCo collides every mesh as its convex hull, so a wheel around its axle, or a
block in its rail, touches its neighbour although the meshes do not: harmless between parent
and child, which MuJoCo ignores, but a locked joint for any other pair.

Both are measured as volumes, with manifold3d's exact mesh intersection (a mesh that is
not closed has no inside, and is only measured by its hull); a pair is only reported when
the overlap is more than a touch (1% of the smaller part and 0.01 cm^3).
"""

from __future__ import annotations

import functools
import time

import manifold3d
import numpy as np

from ..xmlsafe import source_line
from .findings import WARNING, rule
from .geometry import FAR, Piece, Tree, closed_solid, enclosed_volume, hull_solid, link_geometry

# Overlaps smaller than either of these are contact, not interpenetration.
MIN_SHARE = 0.01        # of the smaller part's volume
MIN_VOLUME = 1e-8       # m^3, 0.01 cm^3
# At most this many pairs of neighbouring links are measured, for at most BUDGET seconds (a
# boolean of two detailed meshes takes up to a tenth of a second): a real robot needs a
# small part of either, and a pile of hundreds of links must not keep the check busy for
# minutes.
MAX_PAIRS = 1000
BUDGET = 5.0

rule("collision-overlap", WARNING, "collision", "Two links' collision meshes pass through "
     "each other at the rest pose",
     symptom="In a simulator that collides the two links the joint locks, or the part "
             "bounces and vibrates at its joint; in RViz one part shows inside the other.",
     cause="A mesh or a joint origin in the wrong place (the exporter offsets meshes of links "
           "whose coordinate system lies in a sub-assembly), or parts that really interfere "
           "in the assembly, such as a wheel pressed onto its axle.",
     fix="Check the joint's origin and the link's coordinate system in the exporter dialog "
         "and export again; where the parts really touch, leave clearance in the CAD model "
         "or give one of them a simpler collision shape that stays clear of the other.",
     seen_in=("solidworks_urdf_exporter#97", "solidworks_urdf_exporter#73",
              "solidworks_urdf_exporter#87"))
rule("collision-hull-contact", WARNING, "collision", "MuJoCo makes two links touch at the "
     "rest pose",
     symptom="In MuJoCo a joint does not move, or moves only with a jolt, although nothing "
             "blocks it in the CAD model; contacts show between the two links at rest.",
     cause="MuJoCo collides each mesh as its convex hull: a wheel's hull fills its hole, a "
           "fork's hull fills the gap between its arms. MuJoCo ignores a parent and its "
           "child, but not links further apart, such as a wheel and the chassis above its "
           "steering knuckle.",
     fix="Give the link a collision shape whose hull stays clear (a <cylinder> for a wheel, a "
         "few <box> elements for a fork), or tell MuJoCo to ignore the pair: "
         "spec.add_exclude(bodyname1=..., bodyname2=...) or <contact><exclude .../>.",
     seen_in=("mujoco#1751", "solidworks_urdf_exporter#97"))


def check(ctx) -> None:
    """Add a finding to ctx for every problem of this group."""
    tree = Tree(ctx)
    placed = {}
    for name, link in ctx.links.items():
        pose = tree.pose(name)
        pieces = None if pose is None else link_geometry(ctx, link, "collision")
        if pieces and np.all(np.abs(pose[:3, 3]) < FAR):
            placed[name] = [_Placed(piece, pose) for piece in pieces]
    deadline = time.monotonic() + BUDGET
    for a, b in _near_pairs(placed):
        if time.monotonic() > deadline:
            break
        if tree.body(a) != tree.body(b):
            _pair(ctx, tree, a, b, placed[a], placed[b])


def _near_pairs(placed: dict) -> list[tuple[str, str]]:
    """The pairs of links whose bounding boxes meet, in file order, at most MAX_PAIRS of
    them (sweeping along x, so that a long robot costs no more than its neighbours do)."""
    rank = {name: i for i, name in enumerate(placed)}
    boxes = {n: (np.min([p.bounds[0] for p in placed[n]], axis=0),
                 np.max([p.bounds[1] for p in placed[n]], axis=0)) for n in placed}
    order = sorted(placed, key=lambda n: boxes[n][0][0])
    pairs = []
    for i, a in enumerate(order):
        for b in order[i + 1:]:
            if boxes[b][0][0] > boxes[a][1][0] or len(pairs) >= MAX_PAIRS:
                break
            if np.all(boxes[a][0] <= boxes[b][1]) and np.all(boxes[b][0] <= boxes[a][1]):
                pairs.append((a, b) if rank[a] < rank[b] else (b, a))
    return sorted(pairs, key=lambda pair: (rank[pair[0]], rank[pair[1]]))


class _Placed:
    """A collision piece moved to its place at the rest pose, as manifold3d solids: its
    convex hull, and the mesh itself (None when it is not closed), made only for a pair
    whose hulls overlap (building the solid of a heavy mesh takes a tenth of a second)."""

    def __init__(self, piece: Piece, pose: np.ndarray):
        self.piece, self.pose = piece, pose
        piece.mesh.apply_transform(pose)  # link_geometry's own copy: moving it is safe
        self.bounds = piece.mesh.bounds
        self.volume = enclosed_volume(piece)   # None when the mesh is not closed
        self.hull = hull_solid(piece.local).transform((pose @ piece.pose)[:3, :4])

    @functools.cached_property
    def solid(self) -> manifold3d.Manifold | None:
        return closed_solid(self.piece, self.pose)


def _pair(ctx, tree: Tree, a: str, b: str, pieces_a, pieces_b) -> None:
    """Measure how far links a and b overlap, and report it once for the pair."""
    solid = hull = 0.0
    touching, overlapping = {}, []
    for pa in pieces_a:
        for pb in pieces_b:
            if np.any(pa.bounds[0] > pb.bounds[1]) or np.any(pb.bounds[0] > pa.bounds[1]):
                continue
            shared_hull = (pa.hull ^ pb.hull).volume()
            if shared_hull <= 0:
                continue
            hull += shared_hull
            # The meshes lie within their hulls: no need to intersect them for a mere touch.
            if shared_hull >= MIN_VOLUME and pa.volume is not None and pb.volume is not None:
                overlapping.append((pa, pb))
            touching.setdefault(a, pa.piece.element)
            touching.setdefault(b, pb.piece.element)
    if not touching:
        return
    smaller = min(_volume(pieces_a, solid=True), _volume(pieces_b, solid=True))
    # The meshes' common volume is at most their hulls': when even that would not be worth
    # a report, the meshes need no intersecting (a mesh boolean takes a fiftieth of a second).
    if _reportable(hull, smaller):
        for pa, pb in overlapping:
            if pa.solid is not None and pb.solid is not None:
                solid += (pa.solid ^ pb.solid).volume()
    parent = tree.parent(b) == a or tree.parent(a) == b
    child = a if tree.parent(a) == b else b  # the child of the two, else the later one
    relation = (f'parent and child, joint "{tree.joint_name(child)}"' if parent
                else "not parent and child")
    line = source_line(touching[child], None)
    if _reportable(solid, smaller):
        ctx.add("collision-overlap", f'the collision shapes of links "{a}" and "{b}" '
                f"({relation}) pass through each other at the rest pose: {solid * 1e6:.3g} "
                f"cm^3 in common, {100 * solid / smaller:.0f}% of the smaller", line=line)
        return
    smaller = min(_volume(pieces_a, solid=False), _volume(pieces_b, solid=False))
    if not tree.mujoco_ignores(a, b) and _reportable(hull, smaller):
        ctx.add("collision-hull-contact", f'links "{a}" and "{b}" ({relation}) touch in MuJoCo '
                f"at the rest pose: the convex hulls of their collision geometry share "
                f"{hull * 1e6:.3g} cm^3, {100 * hull / smaller:.0f}% of the smaller, and "
                "MuJoCo does not ignore this pair", line=line,
                fix=f'give "{child}" a collision shape that stays clear of the other link, or '
                    f'exclude the pair: spec.add_exclude(bodyname1="{a}", bodyname2="{b}")')


def _reportable(volume: float, smaller: float) -> bool:
    return smaller > 0 and volume >= MIN_VOLUME and volume >= MIN_SHARE * smaller


def _volume(pieces, solid: bool) -> float:
    """A link's volume: that of its closed meshes (solid), or of its pieces' hulls."""
    if solid:
        return sum(p.volume for p in pieces if p.volume is not None)
    return sum(p.hull.volume() for p in pieces)
