"""What usually causes each kind of difference in SolidWorks, recognised from the numbers.

Each function takes the two values of one quantity (and what else is known about the
link or joint) and returns (code, by, cause): a short code for programs and tests, by
how much the values differ, and the cause with the fix in the exporter's or SolidWorks'
words. Directions are the model's: the axes of the base link's frame.
"""

from __future__ import annotations

import math

import numpy as np

from . import slips
from . import tolerances as tol

# Length units a student may have used where URDF wants metres, by their factor.
LENGTH_UNITS = {1000.0: "millimetres", 100.0: "centimetres", 1 / 0.0254: "inches"}
AXES = "xyz"


# -- formatting --------------------------------------------------------------------------
def num(x: float) -> str:
    return "0" if abs(x) < 1e-9 else f"{x:.6g}"


def vec(values) -> str:
    return " ".join(num(float(x)) for x in values)


def length(metres: float) -> str:
    return f"{metres:.3g} m" if abs(metres) >= 1 else f"{metres * 1000:.3g} mm"


def along(d: np.ndarray) -> str:
    """A displacement in words: "+20 mm along z", or its size and components."""
    big = [i for i in range(3) if abs(d[i]) > tol.LENGTH]
    if len(big) == 1:
        i = big[0]
        return f"{'+' if d[i] > 0 else '-'}{length(abs(d[i]))} along {AXES[i]}"
    parts = ", ".join(f"{AXES[i]} {round(d[i] * 1000, 1) + 0:+g}" for i in range(3))
    return f"{length(float(np.linalg.norm(d)))} apart ({parts} mm)"


def direction(u: np.ndarray) -> str:
    """A unit vector as "+z" when it lies along an axis of the model, else its numbers."""
    for i in range(3):
        if abs(abs(u[i]) - 1) < 1 - math.cos(tol.ANGLE):
            return f"{'+' if u[i] > 0 else '-'}{AXES[i]}"
    return f"({vec(np.round(u, 3))})"


def unit_factor(mine, ref) -> tuple[float, str] | None:
    """(factor, unit) when `mine` is `ref` in another length unit, else None."""
    mine, ref = np.atleast_1d(np.asarray(mine, float)), np.atleast_1d(np.asarray(ref, float))
    if np.linalg.norm(ref) <= tol.LENGTH:
        return None
    k = float(mine @ ref / (ref @ ref))
    if np.linalg.norm(mine - k * ref) > tol.UNIT_RATIO * np.linalg.norm(mine):
        return None
    for factor, unit in LENGTH_UNITS.items():
        if abs(k / factor - 1) <= tol.UNIT_RATIO:
            return factor, unit
    return None


def close(value: float, target: float) -> bool:
    return abs(value - target) <= max(tol.LENGTH, tol.UNIT_RATIO * abs(target))


# -- joints ------------------------------------------------------------------------------
def origin(d, off_mine, off_ref, thicknesses, part_moved) -> tuple[str, str, str]:
    """A joint origin `d` away from the reference's; `thicknesses` are (link, size of its
    mesh along each axis of the model); `part_moved` whether the part moved with it. An
    origin in another unit is recognised before (`origin_units`)."""
    big = [i for i in range(3) if abs(d[i]) > tol.LENGTH]
    note = "" if part_moved is None else (
        ". The part moved with it: the mates place the part elsewhere as well" if part_moved
        else ". The part itself is where the reference has it; only the joint's frame (and "
             "the centre of mass and mesh written in it) is off")
    if len(big) == 1:
        i = big[0]
        if abs(off_ref[i]) > tol.LENGTH and close(off_mine[i], -off_ref[i]):
            return ("origin-mirrored", f"on the other side along {AXES[i]}",
                    "the joint's Reference Coordinate System is that of the twin part on "
                    "the other side (left for right, front for back), or the part is "
                    "mated on the wrong side: pick this side's coordinate system" + note)
        for link, sizes in thicknesses:
            if close(abs(d[i]), sizes[i]):
                return ("origin-face", f"{along(d)}, the thickness of \"{link}\"",
                        "the joint's Reference Coordinate System sits on the opposite face "
                        "of the part: put its origin on the face the reference uses (the "
                        "one the parts meet on)" + note)
            if close(abs(d[i]), sizes[i] / 2):
                return ("origin-face", f"{along(d)}, half the thickness of \"{link}\"",
                        "the joint's Reference Coordinate System sits on a face of the part "
                        "where the reference has it on the mid-plane, or the other way round: "
                        "put its origin where the reference's is" + note)
    return ("origin-offset", along(d),
            "the joint's Reference Coordinate System has its origin on another point, edge or "
            "face than the reference's, or a dimension between the two frames differs from "
            "the drawing: place it as the lesson's coordinate system is placed" + note)


def rotation(turn: np.ndarray, frame: str = "the joint's frame's") -> tuple[str, str]:
    """(by, cause) for a frame turned by `turn` (in the reference frame's axes)."""
    angle = math.degrees(math.acos(max(-1.0, min(1.0, (np.trace(turn) - 1) / 2))))
    if angle > 179:
        w, v = np.linalg.eigh((turn + turn.T) / 2)
        axis = v[:, int(np.argmax(w))]
    else:
        axis = np.array([turn[2, 1] - turn[1, 2], turn[0, 2] - turn[2, 0], turn[1, 0] - turn[0, 1]])
        axis = axis / (np.linalg.norm(axis) or 1)
    by = f"turned {angle:.3g} degrees about {frame} {direction(axis).lstrip('+-')} axis"
    if abs(angle - 180) < 1:
        return by, ("the Reference Coordinate System's axes point the other way (Z down or X "
                    "backwards): make it with the directions the reference's has")
    if abs(angle - 90) < 1:
        return by, ("the Reference Coordinate System's X or Z axis lies along another edge: "
                    "make it with the axes the reference's has")
    return by, ("the Reference Coordinate System is turned by an angle the reference's is "
                "not: check the edges or planes it is made from")


FLIPPED = ("the joint's axis points the other way: in the exporter's joint properties "
           "reverse the axis, or pick the opposite edge/face")


def axis(a_mine, a_ref, kind: str) -> tuple[str, str, str]:
    angle = math.degrees(math.acos(max(-1.0, min(1.0, float(a_mine @ a_ref)))))
    if angle >= 180 - math.degrees(tol.ANGLE):
        return "axis-flipped", "180 degrees apart", FLIPPED
    line = "line of motion" if kind == "prismatic" else "hinge line"
    return ("axis-direction",
            f"{angle:.3g} degrees apart: {direction(a_mine)} in yours, {direction(a_ref)} "
            "in the reference",
            f"the joint moves about or along another direction entirely: the Reference Axis "
            f"is another edge or face (or the axis in Configure Joint Properties was typed "
            f"along another direction); pick an edge, axis or cylindrical face along the "
            f"joint's {line}")


def joint_type(mine: str, ref: str) -> str:
    if {mine, ref} == {"continuous", "revolute"}:
        if ref == "revolute":
            return ("a continuous joint turns without end, and the reference's stops at its "
                    "limits: choose revolute in the exporter's Joint Type and enter the limits "
                    "in Configure Joint Properties")
        return ("the reference's turns without end (a wheel); a revolute one stops at its "
                "limits, and with the exporter's empty limits cannot turn at all: choose "
                "continuous in the exporter's Joint Type")
    if mine == "fixed":
        return (f"Joint Type was left on Automatically Detect and the mates lock the part, or "
                f"fixed was chosen: choose {ref} and give the joint its Reference Axis")
    if ref == "fixed":
        return ("the reference welds this part to its parent: choose fixed in the exporter's "
                "Joint Type (or put the part in its parent's Link Components)")
    return (f"the part must {'slide' if ref == 'prismatic' else 'turn'}: choose {ref} in the "
            f"exporter's Joint Type, with a Reference Axis along its "
            f"{'line of motion' if ref == 'prismatic' else 'hinge line'}")


def origin_units(found: slips.Slip, what: str) -> tuple[str, str, str]:
    """An origin's xyz or rpy typed in another unit (`what`: "xyz" or "rpy")."""
    if what == "xyz":
        return ("origin-units", found.by, f"{found.example()} URDF wants metres, and the "
                "exporter writes what Configure Joint Properties holds: type the origin in "
                "metres, or let the exporter read it from the Reference Coordinate System "
                "again")
    converted = (f" ({num(found.mine)} degrees is {math.radians(found.mine):.4f} rad)"
                 if found.unit == "degrees" else "")
    return ("rpy-units", found.by, f"{found.example()} URDF wants the origin's roll, pitch "
            f"and yaw in radians{converted}: let the exporter read them from the Reference "
            "Coordinate System again, or type them in radians")


def limit(field: str, mine: float, ref: float, kind: str) -> tuple[str, str, str]:
    """One limit value that differs."""
    ratio = mine / ref if ref else math.inf
    if mine == 0:
        return ("limit-empty", "not entered",
                f"0 is the exporter's default: enter the {field} in Configure Joint Properties")
    slides = kind == "prismatic"
    quantity = {"effort": "effort", "velocity": "speed" if slides else "velocity"}.get(
        field, "length" if slides else "angle")
    within = tol.LENGTH if quantity == "length" else tol.ANGLE if quantity == "angle" else \
        tol.EFFORT_VELOCITY * abs(ref)
    found = slips.slip(mine, ref, quantity, within)
    if found:
        wanted = slips.wanted(quantity, kind)
        converted = (f" ({num(mine)} degrees is {math.radians(mine):.4f} rad)"
                     if found.unit == "degrees" else "")
        return ("limit-units", found.by, f"{found.example()} URDF wants {wanted}, and the "
                f"exporter writes what Configure Joint Properties holds{converted}: enter the "
                f"{field} limit in {wanted}")
    if field in ("lower", "upper"):
        by = f"{mine - ref:+.4g} {'m' if kind == 'prismatic' else 'rad'}"
        return ("limit", by, "the joint's range differs from the lesson's: enter the range "
                "the drawing gives (its end stops) in Configure Joint Properties")
    by = f"{ratio:.3g} times the reference's"
    what = "motor's largest torque or force" if field == "effort" else "joint's top speed"
    return ("limit", by, f"the {what} differs from the lesson's: enter the lesson's value in "
            "Configure Joint Properties")


# -- links -------------------------------------------------------------------------------
def mass(mine: float, ref: float, density_mine: float | None,
         density_ref: float | None, volume_ratio: float | None) -> tuple[str, str, str]:
    ratio = mine / ref if ref else math.inf
    by = f"{ratio:.3g} times the reference's" if not 0.5 < ratio < 2 else f"{ratio - 1:+.1%}"
    wanted = tol.material(density_ref) if density_ref else None
    apply = (f"apply {wanted} to the part (Edit Material; {density_ref:.0f} kg/m^3)" if wanted
             else "apply the lesson's material to the part (Edit Material)") + " and export again"
    if mine == 0:
        return "mass-zero", "", f"a mass of 0: the part has no material, or the mass was " \
                                    f"cleared in Configure Link Properties; {apply}"
    if mine == 1 and abs(ref - 1) > tol.MASS:
        return ("mass-placeholder", by, "exactly 1 kg is a placeholder typed in Configure Link "
                f"Properties, not the part's mass: let the exporter compute it; {apply}")
    if abs(ratio / 1000 - 1) <= tol.UNIT_RATIO:
        return "mass-units", f"{by}: grams", "the mass is in grams: URDF wants kilograms"
    if density_mine and density_ref:
        if abs(density_mine / density_ref - 1) <= tol.DENSITY:
            return ("mass-volume", f"{by}; the same density, {density_ref:.0f} kg/m^3",
                    f"the part's volume is {volume_ratio - 1:+.1%}: a dimension or feature "
                    "(a hole, a fillet, a chamfer) differs from the drawing, or the link's "
                    "Link Components hold a part more or less than the reference's (a part "
                    "in no link adds its mass to none, exporter issue #101)")
        found = tol.material(density_mine)
        if found == tol.MATERIALS[1000]:
            return ("mass-material", f"{by}: {density_mine:.0f} kg/m^3 against "
                    f"{density_ref:.0f}", f"no material was applied to the part, so SolidWorks "
                    f"used its default density 1000 kg/m^3 (a mass typed in Override Mass "
                    f"Properties never reaches the URDF, #172); {apply}")
        return ("mass-material", f"{by}: {density_mine:.0f} kg/m^3 against {density_ref:.0f}",
                f"the part's material is {found or 'not a common one'}"
                f" ({density_mine:.0f} kg/m^3); {apply}")
    return ("mass", by, "check the part's material (Edit Material) and which parts are the "
            "link's Link Components")


def centre(c_mine, c_ref) -> tuple[str, str, str]:
    units = unit_factor(c_mine, c_ref)
    if units:
        return ("centre-units", f"{units[0]:.4g} times: {units[1]}",
                f"the centre of mass is in {units[1]}: URDF wants metres")
    return ("centre", along(np.asarray(c_mine) - np.asarray(c_ref)),
            "the mass sits elsewhere in the part: a feature or dimension differs from the "
            "drawing, or a part of the link is mated elsewhere (check its Link Components)")


def moments(mine, ref) -> tuple[str, str, str]:
    ratio = float(np.sum(mine) / np.sum(ref)) if np.sum(ref) else math.inf
    if abs(ratio / 1e6 - 1) <= tol.UNIT_RATIO:
        return ("inertia-units", f"{ratio:.3g} times: kg*mm^2",
                "the inertia is in kg*mm^2: URDF wants kg*m^2")
    change = ", ".join(f"{m / r - 1:+.1%}" if r else "new" for m, r in zip(mine, ref))
    return ("inertia", change, "the mass is spread differently: a dimension or feature of "
            "the part differs, or a part of the link sits elsewhere (Configure Link "
            "Properties shows SolidWorks' own numbers: check the part, not the numbers)")


ABOUT_ORIGIN = ("the inertia is taken about the joint's frame (the link's origin) instead of "
                "the centre of mass: URDF's <inertia> is about the centre of mass, and so is "
                "the exporter's. In SolidWorks' Mass Properties the moments \"taken at the "
                "center of mass\" (Lxx, Lxy, ...) are the ones; those \"taken at the output "
                "coordinate system\" (Ixx, Ixy, ...) are not. Type those, or let the exporter "
                "compute the link's inertia again")


def about_origin_by(mass: float, centre) -> str:
    """How an inertia about the link's origin differs: by the parallel-axis term."""
    return (f"the reference's plus m(|d|^2*1 - d*d^T) for m = {num(mass)} kg and the centre of "
            f"mass d = {vec(np.round(centre, 6))} m from the origin")


def mesh_fault(fault) -> str:
    """The cause of a link mesh with no triangles, or with no volume."""
    if fault.empty:
        return ("SolidWorks wrote an STL with no triangles: the link's part was hidden or "
                "suppressed, or had no solid body (only surfaces or sketches), when the "
                "exporter saved the link's mesh. Show it (unsuppress it, or make it a solid) "
                "and export again; until then RViz and Gazebo draw nothing for the link")
    if fault.scale_zero:
        return ("its <mesh scale> has a 0 in it, which flattens the mesh: write the scale "
                "the reference's mesh has (1 1 1 for a mesh in metres)")
    return ("the part exported is a surface or a sketch, not a solid: make it a solid body "
            "(Thicken the surface, or Knit Surface with \"Try to form solid\") and export "
            "again")


def mesh(ext_mine, ext_ref) -> tuple[str, str, str]:
    units = unit_factor(ext_mine, ext_ref)
    if units:
        return ("mesh-units", f"{units[0]:.4g} times: {units[1]}",
                f"the mesh is in {units[1]}: the STL was saved in another unit than metres, "
                "or the <mesh scale> lacks the factor that turns it into metres")
    shrunk = unit_factor(ext_ref, ext_mine)
    if shrunk:
        return ("mesh-units", f"{shrunk[0]:.4g} times smaller", "the mesh is scaled twice: "
                "a <mesh scale> such as 0.001 on a mesh that is in metres already")
    return ("mesh-size", along(np.asarray(ext_mine) - np.asarray(ext_ref)),
            "the part's size differs from the drawing: a dimension of the part, or another "
            "part among the link's Link Components")
