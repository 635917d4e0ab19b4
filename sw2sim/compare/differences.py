"""Every difference between two matched trees, one line per quantity.

Positions and directions are compared in the base link's axes, at rest, so a frame
turned or moved upstream is reported once, where it happens, and not again at every
link below it: a joint's origin is reported when both its offset from the parent's frame
and its place in the model differ, and so is a centre of mass (offset from the link's
frame, and place). A student's base frame that is turned or shifted as a whole (another
Global Origin Coordinate System) is recognised first, reported once, and undone before
anything else is compared.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass

import numpy as np

from . import causes, inertia, slips
from . import tolerances as tol
from .causes import num, vec
from .match import Matching
from .model import LIMIT_FIELDS, MOVING, Model



def _quarter_turns() -> list[np.ndarray]:
    """The 24 turns that map the axes onto the axes (a model on its side, or facing back)."""
    found = []
    for order in itertools.permutations(range(3)):
        for signs in itertools.product((1, -1), repeat=3):
            turn = np.eye(3)[list(order)] * np.array(signs)[:, None]
            if np.linalg.det(turn) > 0:
                found.append(turn)
    return found


QUARTER_TURNS = _quarter_turns()


@dataclass
class Difference:
    code: str           # what kind of difference, e.g. "axis-flipped"
    subject: str        # 'joint "x"', or 'link "y" (the reference\'s "z")'
    what: str           # the quantity: "axis", "mass", "origin xyz", ...
    mine: str
    reference: str
    by: str             # how much, in words
    cause: str          # what usually causes it, and the fix
    file: str
    line: int | None = None
    summary: str = ""   # said instead of the two values, where there are none

    @property
    def text(self) -> str:
        where = f"{self.file}:{self.line}" if self.line else self.file
        said = self.summary or (f"{self.what} {self.mine} in yours, {self.reference} in the "
                                f"reference" + (f" ({self.by})" if self.by else ""))
        cause = self.cause.rstrip(".")
        return f"{where}: [{self.code}] {self.subject}: {said}. {cause[:1].upper()}{cause[1:]}."


def angle(turn: np.ndarray) -> float:
    return math.acos(max(-1.0, min(1.0, (float(np.trace(turn)) - 1) / 2)))


def explains(excess: float, part: float, whole: float) -> bool:
    """Whether a link `excess` kg heavier than the reference's (of `whole` kg) holds a
    part of `part` kg: within the faceting difference of both (half the mass tolerance of
    the link, the whole tolerance of the part)."""
    return part > 0 and abs(excess - part) <= tol.MASS / 2 * whole + tol.MASS * part


def subject(kind: str, mine: str, ref: str) -> str:
    return f'{kind} "{mine}"' + ("" if mine == ref else f' (the reference\'s "{ref}")')


class Comparer:
    """Compares `mine` with `ref`, link pairs and joint pairs as `found` matched them."""

    def __init__(self, ref: Model, mine: Model, found: Matching):
        self.ref, self.mine, self.found = ref, mine, found
        self.turn, self.shift = np.eye(3), np.zeros(3)   # your base frame, in the reference's
        self.out: list[Difference] = []

    def add(self, code, subj, what="", mine="", ref="", by="", cause="", line=None, summary=""):
        self.out.append(Difference(code, subj, what, mine, ref, by, cause, self.mine.file, line,
                                   summary))

    def run(self) -> list[Difference]:
        ref, mine, found = self.ref, self.mine, self.found
        if found.reroot:
            self.add("tree-root", "the link tree", line=mine.links[mine.base].line, summary=(
                f'starts at link "{mine.base}" in yours, at "{ref.base}" in the reference'),
                cause=f"the root is the first link of the exporter's link tree: make "
                      f'"{ref.base}" the root, with the lesson\'s Global Origin Coordinate '
                      "System, and hang the other links from it as the reference does; nothing "
                      "else is compared until the roots agree")
            return self.out
        self._placement()
        self._world()
        for name in ref.subtree(ref.base):
            if name not in found.links:
                continue
            if name != ref.base:
                self._joint(ref.above[name], mine.above[found.links[name]])
            self._link(name, found.links[name])
        self._unmatched()
        return self.out

    # -- where things are, in the reference base's axes ---------------------------------
    def rot(self, model: Model, link: str) -> np.ndarray:
        r = model.pose[link][:3, :3]
        return r if model is self.ref else self.turn @ r

    def pos(self, model: Model, link: str) -> np.ndarray:
        p = model.pose[link][:3, 3]
        return p if model is self.ref else self.shift + self.turn @ p

    def _placement(self) -> None:
        """Recognise a base frame turned a quarter or half turn, or moved, as a whole."""
        ref, mine, found = self.ref, self.mine, self.found
        pairs = [(ref.joints[r], mine.joints[m]) for r, m in found.joints.items()
                 if ref.joints[r].child != ref.base and ref.joints[r].child not in found.moved]
        vectors = [(ref.pose[rj.child][:3, :3] @ rj.axis, mine.pose[mj.child][:3, :3] @ mj.axis,
                    math.sin(tol.ANGLE)) for rj, mj in pairs
                   if rj.type in MOVING and mj.type in MOVING]
        kids = [(ref.pose[rj.child][:3, 3], mine.pose[mj.child][:3, 3]) for rj, mj in pairs
                if rj.parent == ref.base]
        vectors += [(r - kids[0][0], m - kids[0][1], tol.LENGTH) for r, m in kids[1:]]

        def fits(turn):
            return [r for r, m, within in vectors if np.linalg.norm(turn @ m - r) <= within]

        best = max(QUARTER_TURNS, key=lambda t: (len(fits(t)), np.allclose(t, np.eye(3))))
        if len(fits(best)) > len(fits(np.eye(3))) and np.linalg.matrix_rank(
                np.array(fits(best)), tol=1e-3) >= 2:
            self.turn = best
            by, _ = causes.rotation(best, "the model's")
            self.add("base-turned", subject("link", mine.base, ref.base),
                     line=mine.links[mine.base].line,
                     summary=f"the whole model is {by} against the reference (its joints and "
                             "axes agree once turned back)",
                     cause="the export's Global Origin Coordinate System is not the lesson's: make "
                           "it with Z pointing up and X forward (SolidWorks draws with Y up; "
                           "Automatically Generate turns the assembly's axes so that Z is "
                           "SolidWorks' up and X stays the assembly's X)")
        rb, mb = ref.links[ref.base], mine.links[mine.base]
        if rb.mass is None or mb.mass is None or not kids:
            return
        shift = rb.centre - self.turn @ mb.centre
        if np.linalg.norm(shift) > tol.LENGTH and any(
                np.linalg.norm(r - shift - self.turn @ m) <= tol.LENGTH <
                np.linalg.norm(r - self.turn @ m) for r, m in kids):
            self.shift = shift
            self.add("base-origin", subject("link", mine.base, ref.base),
                     line=mine.links[mine.base].line,
                     summary=f"the whole model is measured from another point: your base frame "
                             f"is {causes.along(shift)} from the reference's",
                     cause="the Global Origin Coordinate System is at another point of the base "
                           "than the lesson's: put it where the lesson's is (the base's centre "
                           "of mass and every joint on the base are measured from it)")

    def _world(self) -> None:
        ref, mine, found = self.ref, self.mine, self.found
        if found.world == "missing":
            joint = ref.above[ref.base]
            self.add("world-missing", f'link "{ref.world}"', summary=(
                f'missing in yours; the reference bolts "{ref.base}" to the world with the '
                f'fixed joint "{joint.name}" at xyz {vec(joint.origin[:3, 3])}'),
                cause="without it Gazebo lets the robot fall free, while MuJoCo welds a "
                      "jointless root to the world, so the two disagree: add the world link and "
                      "its fixed joint to the URDF as the lesson shows")
        elif found.world == "extra":
            joint = mine.above[mine.base]
            self.add("world-extra", f'link "{mine.world}"', line=mine.links[mine.world].line,
                     summary=f'yours bolts "{mine.base}" to the world with the fixed joint '
                             f'"{joint.name}"; the reference\'s robot is free',
                     cause="the lesson's robot moves over the floor: remove the world link and "
                           "its joint")
        elif ref.world:
            self._joint(ref.above[ref.base], mine.above[mine.base], top=True)

    # -- joints ---------------------------------------------------------------------------
    def _joint(self, rj, mj, top: bool = False) -> None:
        ref, mine = self.ref, self.mine
        subj = subject("joint", mj.name, rj.name)
        moved = rj.child in self.found.moved
        if rj.name != mj.name:
            self.add("joint-name", subj, line=mj.line, summary=(
                f'named "{mj.name}" in yours, "{rj.name}" in the reference (matched by its '
                "place in the tree)"), cause=f'the lesson\'s controllers, launch files and '
                f'scripts name it "{rj.name}": rename it in the exporter\'s link tree (Joint '
                "Name) and export again")
        if rj.type != mj.type:
            self.add("joint-type", subj, "type", mj.type, rj.type, "",
                     causes.joint_type(mj.type, rj.type), mj.line)
        if top:   # the world joint: where your base frame is, against where it should be
            off_r, off_m = rj.origin[:3, 3], mj.origin[:3, 3]
            placed = off_m - off_r - rj.origin[:3, :3] @ self.shift
        else:
            off_r = self.rot(ref, rj.parent) @ rj.origin[:3, 3]
            off_m = self.rot(mine, mj.parent) @ mj.origin[:3, 3]
            placed = self.pos(mine, mj.child) - self.pos(ref, rj.child)
        if moved and np.linalg.norm(placed) > tol.LENGTH:
            self.add("origin-offset", subj, line=mj.line, summary=(
                f"the joint sits {causes.along(placed)} from where the reference has it, and "
                "hangs from another link (see the link's line)"),
                cause="once the link hangs from the reference's parent, export again and "
                      "compare: the exporter measures the origin from the new parent")
        elif np.linalg.norm(placed) > tol.LENGTH and np.linalg.norm(off_m - off_r) > tol.LENGTH:
            slipped = slips.slip(mj.origin[:3, 3], rj.origin[:3, 3], "length", tol.LENGTH)
            code, by, cause = causes.origin_units(slipped, "xyz") if slipped else \
                causes.origin(off_m - off_r, off_m, off_r, self._sizes(rj),
                              None if top else self._part_moved(rj, mj))
            self.add(code, subj, "origin xyz", vec(mj.origin[:3, 3]), vec(rj.origin[:3, 3]), by,
                     cause, mj.line)
        turn = rj.origin[:3, :3].T @ mj.origin[:3, :3]
        whole = (rj.origin[:3, :3] @ self.turn).T @ mj.origin[:3, :3] if top else \
            self.rot(ref, rj.child).T @ self.rot(mine, mj.child)
        if angle(turn) > tol.ANGLE and angle(whole) > tol.ANGLE:
            slipped = slips.slip(mj.rpy, rj.rpy, "angle", tol.ANGLE)
            code, by, cause = causes.origin_units(slipped, "rpy") if slipped else \
                ("origin-turned", *causes.rotation(turn))
            self.add(code, subj, "origin rpy", vec(mj.rpy), vec(rj.rpy), by, cause, mj.line)
        if rj.type in MOVING and mj.type in MOVING:
            a_r = self.rot(ref, rj.child) @ rj.axis
            a_m = self.rot(mine, mj.child) @ mj.axis
            if math.acos(max(-1.0, min(1.0, float(a_r @ a_m)))) > tol.ANGLE:
                code, by, cause = causes.axis(a_m, a_r, rj.type)
                by += self._turned(rj.child, mj.child)
                written = vec(mj.axis) + ("" if mj.axis_given else " (no <axis>: the default)")
                self.add(code, subj, "axis", written, vec(rj.axis), by, cause, mj.line)
        if rj.type == mj.type:
            self._limits(rj, mj, subj)

    def _turned(self, rn: str, mn: str) -> str:
        """Said after a difference measured in the model's axes, when the link's frame is
        turned against the reference's (its written numbers may then look equal)."""
        if angle(self.rot(self.ref, rn).T @ self.rot(self.mine, mn)) <= tol.ANGLE:
            return ""
        return ", in the model's axes: the link's frame is turned (see the joint's origin rpy)"

    def _sizes(self, rj) -> list[tuple[str, np.ndarray]]:
        """The sizes of the joint's two links along the model's axes, for thicknesses."""
        found = []
        for name in (rj.child, rj.parent):
            link = self.ref.links[name]
            if link.mesh is not None and name in self.ref.pose:
                turned = link.mesh.vertices @ self.rot(self.ref, name).T
                found.append((name, np.ptp(turned, axis=0)))
        return found

    def _part_moved(self, rj, mj) -> bool | None:
        r, m = self.ref.links[rj.child], self.mine.links[mj.child]
        if r.centre is None or m.centre is None:
            return None
        at_r = self.pos(self.ref, rj.child) + self.rot(self.ref, rj.child) @ r.centre
        at_m = self.pos(self.mine, mj.child) + self.rot(self.mine, mj.child) @ m.centre
        return bool(np.linalg.norm(at_m - at_r) > tol.LENGTH)

    def _limits(self, rj, mj, subj: str) -> None:
        if rj.limit is None:
            return
        fields = LIMIT_FIELDS if rj.type in ("revolute", "prismatic") else ("effort", "velocity")
        ref, mine = rj.limit, mj.limit
        if (mine is None or not any(mine[f] for f in fields)) and any(ref[f] for f in fields):
            self.add("limits-empty", subj, "limit",
                     "none" if mine is None else " ".join(f"{f} 0" for f in fields),
                     " ".join(f"{f} {num(ref[f])}" for f in fields), "",
                     "the exporter's empty default: enter " + ", ".join(fields) + " in "
                     "Configure Joint Properties (" + ("metres and N" if rj.type == "prismatic"
                                                       else "radians and N*m") + ")", mj.line)
            return
        if mine is None:
            return
        position = tol.LENGTH if rj.type == "prismatic" else tol.ANGLE
        if "lower" in fields and abs(mine["lower"] - ref["lower"]) > position and \
                abs(mine["lower"] - ref["upper"]) <= position >= abs(mine["upper"] - ref["lower"]):
            self.add("limit-swapped", subj, "limit lower/upper",
                     f"{num(mine['lower'])}/{num(mine['upper'])}",
                     f"{num(ref['lower'])}/{num(ref['upper'])}", "swapped",
                     "lower and upper are swapped: lower is the smaller number", mj.line)
            fields = ("effort", "velocity")
        for field in fields:
            within = position if field in ("lower", "upper") else \
                tol.EFFORT_VELOCITY * abs(ref[field])
            if abs(mine[field] - ref[field]) > within:
                code, by, cause = causes.limit(field, mine[field], ref[field], rj.type)
                self.add(code, subj, f"limit {field}", num(mine[field]), num(ref[field]), by,
                         cause, mj.line)

    # -- links ----------------------------------------------------------------------------
    def _link(self, rn: str, mn: str) -> None:
        ref, mine = self.ref, self.mine
        r, m = ref.links[rn], mine.links[mn]
        subj, line = subject("link", mn, rn), m.line
        if rn != mn:
            self.add("link-name", subj, line=line, summary=(
                f'named "{mn}" in yours, "{rn}" in the reference (matched by its place in the '
                "tree)"), cause=f'the lesson\'s files name it "{rn}" (its mesh is '
                f"meshes/{rn}.STL): rename it in the exporter's Link Name and export again")
        if rn in self.found.moved:
            parent = ref.above[rn].parent
            self.add("link-parent", subj, line=line, summary=(
                f'hangs from "{mine.above[mn].parent}" in yours, from "{parent}" in the '
                "reference"), cause=f'in the exporter\'s link tree drag it onto "{parent}", so '
                "that it moves with it")
        if m.mesh_fault and not r.mesh_fault:
            self._mesh_fault(r, m, subj)
        if r.mass is None or m.mass is None:
            if r.mass is not None:
                self.add("inertial-missing", subj, line=line, summary=(
                    f"no <inertial> in yours; {num(r.mass)} kg in the reference"),
                    cause="the exporter writes one for each link with parts: give the link its "
                          "Link Components (MuJoCo would make up a mass for it)")
            elif m.mass is not None:
                self.add("inertial-extra", subj, line=line, summary=(
                    f"{num(m.mass)} kg in yours; the reference's has no <inertial>"),
                    cause="the reference's link is a frame without parts: empty its Link "
                          "Components")
            return
        rot_r, rot_m = self.rot(ref, rn), self.rot(mine, mn)
        tensor_r, tensor_m = rot_r @ r.tensor @ rot_r.T, rot_m @ m.tensor @ rot_m.T
        folded = False
        if abs(m.mass - r.mass) > tol.MASS * r.mass:
            code, by, cause = self._mass_cause(rn, mn)
            if r.mass > 0:
                scaled = tensor_r * m.mass / r.mass
                folded = np.linalg.norm(tensor_m - scaled) <= tol.INERTIA * np.linalg.norm(scaled)
            if folded:
                cause += ". Its inertia differs by the same factor, from the same cause"
            self.add(code, subj, "mass", f"{num(m.mass)} kg", f"{num(r.mass)} kg", by, cause, line)
        offset_r, offset_m = rot_r @ r.centre, rot_m @ m.centre
        placed = self.pos(mine, mn) + offset_m - self.pos(ref, rn) - offset_r
        if np.linalg.norm(offset_m - offset_r) > tol.LENGTH and np.linalg.norm(placed) > tol.LENGTH:
            code, by, cause = causes.centre(offset_m, offset_r)
            by += self._turned(rn, mn)
            self.add(code, subj, "centre of mass", vec(m.centre), vec(r.centre), by, cause, line)
        if not folded:
            self._inertia(subj, tensor_m, tensor_r, line, m.mass, offset_m)
        if r.mesh is not None and m.mesh is not None:
            size_r = np.ptp(r.mesh.vertices @ rot_r.T, axis=0)
            size_m = np.ptp(m.mesh.vertices @ rot_m.T, axis=0)
            if np.any(np.abs(size_m - size_r) > tol.MESH_ABSOLUTE + tol.MESH_RELATIVE * size_r):
                code, by, cause = causes.mesh(size_m, size_r)
                self.add(code, subj, "mesh size", vec(np.round(size_m, 6)) + " m",
                         vec(np.round(size_r, 6)) + " m", by, cause, line)

    def _inertia(self, subj: str, tensor_m, tensor_r, line, mass: float, centre) -> None:
        """`centre`: your centre of mass from the link's origin, in the model's axes."""
        found = inertia.difference(tensor_m, tensor_r)
        moments_r, moments_m = np.linalg.eigvalsh(tensor_r), np.linalg.eigvalsh(tensor_m)
        if found and inertia.about_origin(tensor_m, tensor_r, mass, centre):
            self.add("inertia-origin", subj, "principal moments", f"{vec(moments_m)} kg*m^2",
                     f"{vec(moments_r)} kg*m^2", causes.about_origin_by(mass, centre),
                     causes.ABOUT_ORIGIN, line)
        elif found == "moments":
            code, by, cause = causes.moments(moments_m, moments_r)
            self.add(code, subj, "principal moments", f"{vec(moments_m)} kg*m^2",
                     f"{vec(moments_r)} kg*m^2", by, cause, line)
        elif found == "turned":
            share = np.linalg.norm(tensor_m - tensor_r) / np.linalg.norm(tensor_r)
            self.add("inertia-turned", subj, line=line, summary=(
                f"the principal moments agree, the inertia tensor in the model's axes differs by "
                f"{share:.0%}"), cause="the part is turned in the assembly: a mate orients it "
                "differently from the reference's")

    def _mesh_fault(self, r, m, subj: str) -> None:
        fault = m.mesh_fault
        size = "" if r.mesh is None else \
            f"; the reference's measures {vec(np.round(np.ptp(r.mesh.vertices, axis=0), 6))} m"
        self.add("mesh-empty" if fault.empty else "mesh-flat", subj, line=m.line,
                 summary=f"its mesh {fault.file} {fault.why}{size}",
                 cause=causes.mesh_fault(fault))

    def _mass_cause(self, rn: str, mn: str) -> tuple[str, str, str]:
        ref, mine, found = self.ref, self.mine, self.found
        r, m = ref.links[rn], mine.links[mn]
        by = causes.mass(m.mass, r.mass, None, None, None)[1]
        for names, model, sign in (
                ([n for n in found.missing if ref.above[n].parent == rn], ref, 1),
                ([n for n in found.extra if mine.above[n].parent == mn], mine, -1)):
            more = sum(model.mass_below(n) for n in names)
            if names and explains(sign * (m.mass - r.mass), more, r.mass):
                listed = ", ".join(f'"{n}"' for n in names)
                return ("mass-parts", by, f"it holds the parts of the reference's link {listed} "
                        "too (see the line on it)" if sign > 0 else f"the parts of your link "
                        f"{listed} belong to this link in the reference (see the line on it)")
        v_r, v_m = r.volume, m.volume
        v = v_m if v_m and v_r and 0.1 < v_m / v_r < 10 else v_r
        return causes.mass(m.mass, r.mass, m.mass / v if v else None,
                           r.mass / v_r if v_r else None, v / v_r if v and v_r else None)

    def _unmatched(self) -> None:
        ref, mine, found = self.ref, self.mine, self.found
        for name in found.missing:
            joint = ref.above[name]
            below = len(ref.subtree(name)) - 1
            where = found.links.get(joint.parent, joint.parent)
            heavier, lighter = mine.links.get(where), ref.links[joint.parent]
            extra = None if heavier is None or heavier.mass is None or lighter.mass is None \
                else heavier.mass - lighter.mass
            merged = extra is not None and explains(extra, ref.mass_below(name), lighter.mass)
            self.add("link-missing", f'link "{name}"', summary=(
                f'missing in yours; in the reference it hangs from "{joint.parent}" by the '
                f'{joint.type} joint "{joint.name}"' + (f", with {below} link(s) below it"
                                                       if below else "")),
                cause=(f'its parts are among "{where}"\'s Link Components (that link is '
                       f"{num(extra)} kg heavier): give them a link of their own" if merged else
                       f'add it to the exporter\'s link tree as a child of "{where}" (Add Child '
                       "Link), with its parts as its Link Components"))
        for name in found.extra:
            joint = mine.above[name]
            self.add("link-extra", f'link "{name}"', line=mine.links[name].line, summary=(
                f'not in the reference; yours hangs it from "{joint.parent}" by the {joint.type} '
                f'joint "{joint.name}"'), cause="the reference has these parts in another link: "
                "move them into that link's Link Components and remove this link from the "
                "exporter's link tree")
