"""`sw2sim compare`: does a student's export match the lesson's reference package?

    from sw2sim.compare import compare
    result = compare("my_export", "examples/example_3")
    print(result.format()); raise SystemExit(result.status)

Both are read as every command reads a package (`model`): the link tree, each joint's
type, origin, axis and limits, each link's mass, centre of mass, inertia and mesh. The
links are matched by the tree and by name (`match`), and every quantity of every matched
pair is compared within the tolerances of `tolerances`, which says why they are what
they are (`differences`). Each difference is one line naming the joint or link, the two
values, by how much they differ, and what in SolidWorks usually causes it (`causes`):
a frame on the wrong face, an axis the other way, a missing material, millimetres, the
exporter's empty limits, a missing link, a mesh with no triangles, a unit slip, an
inertia about the link's origin and the rest. Two trees that are not of one robot are
not compared at all (`resemblance`): the message says the package looks like another
lesson's, and names the lesson's package it resembles most. Status 0: the export
matches; 1: it differs; 2: nothing could be compared (a package cannot be read, and the
message names the file; or it looks like another lesson's package).
"""

from __future__ import annotations

import json
import os
from dataclasses import asdict, dataclass, field

from . import tolerances
from .differences import Comparer, Difference
from .match import match
from .model import CompareError, read_model, shown
from .resemblance import another_lesson

__all__ = ["compare", "Comparison", "Difference", "CompareError"]


@dataclass
class Comparison:
    mine: str
    reference: str
    differences: list[Difference] = field(default_factory=list)
    links: dict[str, str] = field(default_factory=dict)    # reference link -> yours
    joints: dict[str, str] = field(default_factory=dict)   # reference joint -> yours
    counts: tuple[int, int] = (0, 0)                        # the reference's links, joints
    error: str | None = None
    resembles: str | None = None   # the lesson's package it resembles, when it is another's

    @property
    def status(self) -> int:
        return 2 if self.error else 1 if self.differences else 0

    def format(self) -> str:
        if self.error:
            return f"sw2sim compare: {self.error}"
        lines = [d.text for d in self.differences]
        matched = (f"{len(self.links)} of {self.counts[0]} links and {len(self.joints)} of "
                   f"{self.counts[1]} joints matched")
        if self.differences:
            lines.append(f"{self.mine} differs from {self.reference}: "
                         f"{len(self.differences)} difference(s); {matched}")
        else:
            lines.append(f"{self.mine} matches {self.reference} ({matched}; tolerances: mass "
                         f"{tolerances.MASS:.0%}, inertia {tolerances.INERTIA:.0%}, "
                         f"{tolerances.LENGTH * 1000:g} mm, "
                         f"{tolerances.as_dict()['angle_deg']:g} degrees)")
        return "\n".join(lines)

    def to_json(self) -> str:
        return json.dumps({"mine": self.mine, "reference": self.reference,
                           "status": self.status, "error": self.error,
                           "resembles": self.resembles,
                           "differences": [dict(asdict(d), text=d.text) for d in self.differences],
                           "matched": {"links": self.links, "joints": self.joints},
                           "tolerances": tolerances.as_dict()}, indent=2)


def compare(mine: str | os.PathLike, reference: str | os.PathLike, *,
            urdf: str | None = None, reference_urdf: str | None = None) -> Comparison:
    """Compare the package (folder or .urdf) `mine` with `reference`; never raises on bad
    input (the Comparison's `error` says what could not be read, status 2)."""
    result = Comparison(str(mine), str(reference))
    try:
        ref_model = read_model(reference, reference_urdf)
        mine_model = read_model(mine, urdf)
    except CompareError as exc:
        result.error = str(exc)
        return result
    found = match(ref_model, mine_model)
    foreign = another_lesson(ref_model, mine_model, found, result.mine, result.reference)
    if foreign:
        result.error, lesson = foreign
        result.resembles = shown(lesson.folder) if lesson else None
        return result
    result.differences = Comparer(ref_model, mine_model, found).run()
    result.links, result.joints = found.links, found.joints
    result.counts = (len(ref_model.links), len(ref_model.joints))
    return result
