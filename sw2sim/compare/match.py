"""Which link of the student's export is which link of the reference.

The two trees are walked together from their base links. A pair of matched links has
its children paired by the child link's name, then by the joint's name, then, for what
is left, by place: where the joint sits (seen from the base), its type and how many
links hang below it. So a student who kept the lesson's names is matched by name, and
one who renamed is matched by the tree; every pair whose names differ is reported.
A link found under another parent than the reference's is paired by name afterwards.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .model import Model

# What a difference of type or of subtree size weighs against a distance, in metres,
# when children are paired by place.
MISFIT = 0.05


@dataclass
class Matching:
    links: dict[str, str] = field(default_factory=dict)     # reference link -> yours
    joints: dict[str, str] = field(default_factory=dict)    # reference joint -> yours
    moved: set[str] = field(default_factory=set)            # reference links under another parent
    missing: list[str] = field(default_factory=list)        # reference links with no match (tops)
    extra: list[str] = field(default_factory=list)          # your links with no match (tops)
    world: str | None = None       # "missing" or "extra" when only one URDF has a world link
    reroot: tuple[str, str] | None = None   # (your base, the reference's) when the tree is
                                            # rooted at another of the same links


def match(ref: Model, mine: Model) -> Matching:
    found = Matching()
    if ref.base != mine.base and (mine.base in ref.links or ref.base in mine.links):
        found.reroot = (mine.base, ref.base)
        return found
    if ref.world and mine.world:
        found.links[ref.world] = mine.world
        found.joints[ref.above[ref.base].name] = mine.above[mine.base].name
    elif ref.world or mine.world:
        found.world = "missing" if ref.world else "extra"
    queue = [(ref.base, mine.base)]
    while queue:
        for r, m in queue:
            found.links[r] = m
        pairs = [pair for r, m in queue for pair in _children(ref, mine, r, m)]
        queue = []
        for rj, mj in pairs:
            found.joints[rj.name] = mj.name
            queue.append((rj.child, mj.child))
        if not queue:
            queue = _moved(ref, mine, found)
    mine_matched = set(found.links.values())
    found.missing = [n for n in ref.links if n not in found.links and n != ref.world and
                     ref.above[n].parent in found.links]
    found.extra = [n for n in mine.links if n not in mine_matched and n != mine.world and
                   mine.above[n].parent in mine_matched]
    return found


def _children(ref: Model, mine: Model, r: str, m: str) -> list[tuple]:
    """The child joints of reference link r and of your link m, paired."""
    left, right = list(ref.children[r]), list(mine.children[m])
    pairs = []
    for key in (lambda j: j.child, lambda j: j.name):
        for rj in list(left):
            hit = next((mj for mj in right if key(mj) == key(rj)), None)
            if hit is not None:
                pairs.append((rj, hit))
                left.remove(rj)
                right.remove(hit)
    costs = sorted((_cost(ref, mine, rj, mj), i, k) for i, rj in enumerate(left)
                   for k, mj in enumerate(right))
    taken_r, taken_m = set(), set()
    for _, i, k in costs:
        if i not in taken_r and k not in taken_m:
            pairs.append((left[i], right[k]))
            taken_r.add(i)
            taken_m.add(k)
    return pairs


def _cost(ref: Model, mine: Model, rj, mj) -> float:
    here = np.linalg.norm(ref.pose[rj.child][:3, 3] - mine.pose[mj.child][:3, 3])
    return float(here) + MISFIT * ((rj.type != mj.type) +
                                   (len(ref.subtree(rj.child)) != len(mine.subtree(mj.child))))


def _moved(ref: Model, mine: Model, found: Matching) -> list[tuple[str, str]]:
    """Unmatched links present in both under the same name: hung from another parent."""
    mine_matched = set(found.links.values())
    pairs = []
    for name in ref.links:
        if name in found.links or name == ref.world or name not in mine.links \
                or name in mine_matched or name == mine.world:
            continue
        found.moved.add(name)
        found.joints[ref.above[name].name] = mine.above[name].name
        pairs.append((name, name))
    return pairs
