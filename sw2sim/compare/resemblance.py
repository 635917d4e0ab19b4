"""Whether two packages are of the same lesson at all, and which lesson's a package is.

Matching pairs links by place where their names differ, so any two trees are "matched":
two lessons' robots (Practice 2's cart against Practice 4's slider) would be compared
link by link, into a screenful of confident causes, most of them meaningless. Before
anything is compared, two measures are taken of the student's tree against the
reference's:

- alike: links with a counterpart, of the same name, or in the same place in the tree
  (matched by place, with the same joint type and as many links below). A student who
  renames links keeps their places; one who forgets or adds a link keeps the others.
  Under half of the links (of the larger tree, a `world` link not counted) alike, the
  trees are not the same robot.
- agree: of those, links where the two agree: frame at the same place seen from the
  base, and the same mass, within the comparison's tolerances.

When the reference is one of the lessons' packages (examples/example_N) and the student's
tree agrees with it in under half of its links, the tree is measured against each
lesson's package too (about 30 ms for all five: their URDFs and meshes are small). The
most alike names the lesson the package seems to be of. And a package that agrees with
another lesson's in at least half of its links, but with the reference in fewer, is
that lesson's even where names and tree are shared (Practices 1 and 2 both have a base
and four wheels of the same names).
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from . import tolerances as tol
from .match import match
from .model import CompareError, Model, read_model, shown

LESSON = re.compile(r"example_(\d+)")


@dataclass
class Likeness:
    alike: int      # links with a counterpart, by name or by place
    agree: int      # of those, at the same place from the base and of the same mass
    total: int      # the links of the larger tree, a world link not counted

    @property
    def resembles(self) -> bool:
        return 2 * self.alike >= self.total

    @property
    def agrees(self) -> bool:
        return 2 * self.agree >= self.total

    def key(self) -> tuple[float, float]:
        return self.alike / self.total, self.agree / self.total


@dataclass
class Lesson:
    folder: Path        # examples/example_N
    number: int
    likeness: Likeness

    @property
    def name(self) -> str:
        return f"{shown(self.folder)} (Practice {self.number}'s package)"


def likeness(ref: Model, mine: Model, found=None) -> Likeness:
    """How far `mine` resembles `ref`; `found` is their Matching, when it is at hand."""
    found = found or match(ref, mine)
    alike = agree = 0
    for name in _links(ref):
        other = name if name in mine.links else found.links.get(name)
        if other is None or other == mine.world:
            continue
        if other != name and not _same_place(ref, mine, name, other):
            continue
        alike += 1
        agree += _agree(ref, mine, name, other)
    total = max(len(_links(ref)), len(_links(mine)), 1)
    return Likeness(alike, agree, total)


def lessons(ref: Model, mine: Model) -> list[Lesson] | None:
    """`mine` measured against each lesson's package beside the reference, most alike
    first; None when the reference is not a lesson's (examples/example_N)."""
    root = ref.package.root
    if not LESSON.fullmatch(root.name):
        return None
    found = []
    for folder in sorted(root.parent.iterdir()):
        number = LESSON.fullmatch(folder.name)
        if not number or not folder.is_dir() or folder.resolve() == root.resolve():
            continue
        try:
            model = read_model(folder)
        except CompareError:
            continue
        found.append(Lesson(folder, int(number[1]), likeness(model, mine)))
    return sorted(found, key=lambda lesson: lesson.likeness.key(), reverse=True)


def _links(model: Model) -> list[str]:
    return [name for name in model.links if name != model.world]


def _same_place(ref: Model, mine: Model, r: str, m: str) -> bool:
    """Whether links of different names matched by place are the same link renamed."""
    if r == ref.base or m == mine.base:
        return r == ref.base and m == mine.base
    rj, mj = ref.above.get(r), mine.above.get(m)
    return rj is not None and mj is not None and rj.type == mj.type and \
        len(ref.subtree(r)) == len(mine.subtree(m))


def _agree(ref: Model, mine: Model, r: str, m: str) -> bool:
    if r not in ref.pose or m not in mine.pose:
        return False
    placed = np.linalg.norm(ref.pose[r][:3, 3] - mine.pose[m][:3, 3]) <= tol.LENGTH
    a, b = ref.links[r].mass, mine.links[m].mass
    weighed = (a is None and b is None) or (
        a is not None and b is not None and abs(b - a) <= tol.MASS * max(a, b))
    return bool(placed and weighed)


def another_lesson(ref: Model, mine: Model, found, yours: str, reference: str
                   ) -> tuple[str, Lesson | None] | None:
    """(why nothing can be compared, the lesson `mine` resembles most) when `mine` looks
    like another lesson's package than `ref`; None when the two are of one robot. The
    lessons are read only when the package agrees with the reference in under half of
    its links (a correct export, the common case, costs nothing)."""
    own = likeness(ref, mine, found)
    if own.resembles and own.agrees:
        return None
    others = lessons(ref, mine)
    if own.resembles:
        closer = [lesson for lesson in others or []
                  if lesson.likeness.agrees and lesson.likeness.agree > own.agree]
        if not closer:
            return None
        best = max(closer, key=lambda lesson: lesson.likeness.agree)
        said = (f"{yours} agrees with {shown(best.folder)} in {best.likeness.agree} of "
                f"{best.likeness.total} links (where each sits, and its mass), with "
                f"{reference} in {own.agree} of {own.total}")
    else:
        best = next((lesson for lesson in others or [] if lesson.likeness.resembles), None)
        said = (f"{yours} and {reference} have little in common: {own.alike} of {own.total} "
                "links match by name, or by their place in the tree and joint type")
    said += ". This looks like another lesson's package"
    if best is not None:
        said += (f": it resembles {best.name} most ({best.likeness.alike} of "
                 f"{best.likeness.total} links alike). Compare it with that one: sw2sim "
                 f"compare {yours} {shown(best.folder)}")
    elif others is not None:
        said += (f", and none of the lessons' packages in {shown(ref.package.root.parent)} "
                 f"resembles it: check that {yours} is your export of a lesson's model")
    else:
        said += f": check that {reference} is the package of your lesson (examples/example_N)"
    return said + ". Nothing was compared.", best
