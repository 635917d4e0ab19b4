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

import time

import manifold3d
import numpy as np

from .findings import WARNING, rule
from .meshes import FAR, Piece, closed_solid, link_geometry, origin_matrix
from .structure import source_line

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
    """A collision piece moved to its place at the rest pose, as manifold3d solids: the mesh
    itself (None when it is not closed) and its convex hull."""

    def __init__(self, piece: Piece, pose: np.ndarray):
        self.piece = piece
        piece.mesh.apply_transform(pose)  # link_geometry's own copy: moving it is safe
        self.bounds = piece.mesh.bounds
        self.solid = closed_solid(piece, pose)
        self.hull = manifold3d.Manifold.hull_points(piece.mesh.vertices)


def _pair(ctx, tree: Tree, a: str, b: str, pieces_a, pieces_b) -> None:
    """Measure how far links a and b overlap, and report it once for the pair."""
    solid = hull = 0.0
    touching = {}
    for pa in pieces_a:
        for pb in pieces_b:
            if np.any(pa.bounds[0] > pb.bounds[1]) or np.any(pb.bounds[0] > pa.bounds[1]):
                continue
            shared_hull = (pa.hull ^ pb.hull).volume()
            if shared_hull <= 0:
                continue
            hull += shared_hull
            # The meshes lie within their hulls: no need to intersect them for a mere touch.
            if shared_hull >= MIN_VOLUME and pa.solid is not None and pb.solid is not None:
                solid += (pa.solid ^ pb.solid).volume()
            touching.setdefault(a, pa.piece.element)
            touching.setdefault(b, pb.piece.element)
    if not touching:
        return
    parent = tree.parent(b) == a or tree.parent(a) == b
    child = a if tree.parent(a) == b else b  # the child of the two, else the later one
    relation = (f'parent and child, joint "{tree.joint_name(child)}"' if parent
                else "not parent and child")
    line = source_line(ctx, touching[child], None)
    smaller = min(_volume(pieces_a, solid=True), _volume(pieces_b, solid=True))
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
        return sum(p.solid.volume() for p in pieces if p.solid is not None)
    return sum(p.hull.volume() for p in pieces)
