"""Lighter collision meshes for a port: a <collision> that names a heavy mesh (the exporter
writes each part's STL for both <visual> and <collision>, as finely as SolidWorks
tessellated it) gets a simplified copy in meshes/simplified/, and only the <collision>
is pointed at it; the <visual> keeps the whole mesh.

Gazebo Sim's own guide pairs a complex visual mesh with a simplified collision for speed
(SOURCE). The copy is made with manifold3d's `simplify`, which keeps a subset of the
vertices and moves no surface by more than its tolerance: the smallest tolerance of
TOLERANCES (fractions of the mesh's bounding-box diagonal) that brings the mesh to TARGET
triangles or fewer. A mesh that is not a closed surface, or that simplifying would not
halve, is left whole, and the report says why.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path, PurePosixPath

import numpy as np

from ..check.geometry import as_solid
from ..check.trimeshes import read    # the check's mesh readers: STL, OBJ, COLLADA
from ..mesh_formats import binary_stl

SOURCE = ("https://github.com/gazebosim/gz-sim/blob/gz-sim8_8.10.0/tutorials/adding_visuals.md"
          "#L20-L25")
HEAVY = 20_000    # triangles: above this a collision mesh gets a simplified copy (as the
                  # check's mesh-heavy-collision warns: sw2sim.check.meshes.HEAVY_FACES)
TARGET = 2_000           # triangles the copy aims at
TOLERANCES = (0.0005, 0.001, 0.002, 0.005)   # of the bounding-box diagonal, tried in order
FOLDER = "meshes/simplified"


@dataclass
class Simplified:
    """What simplifying a port's collision meshes made and said."""
    files: dict[str, bytes] = field(default_factory=dict)   # new path in the package -> STL
    choices: list[str] = field(default_factory=list)


@dataclass
class _Result:
    rel: str              # the copy's path in the package, or "" when the mesh stays whole
    before: int
    after: int = 0
    within_mm: float = 0.0
    why_not: str = ""


def simplify(robot, meshes: dict[str, Path], new_name: str, taken=()) -> Simplified:
    """Point each <collision> whose mesh (a path of `meshes`, package://<new_name>/...) is
    heavy at a simplified copy; return the copies and one line of what was done. A copy
    takes no path of `meshes` or `taken` (the other files the package gets)."""
    out = Simplified()
    prefix = f"package://{new_name}/"
    done: dict[str, _Result] = {}
    taken = set(meshes) | set(taken)
    for collision in robot.iter("collision"):
        for mesh in collision.iterfind("geometry/mesh"):
            filename = (mesh.get("filename") or "").strip()
            rel = filename[len(prefix):] if filename.startswith(prefix) else None
            if rel not in meshes:
                continue
            if rel not in done:
                done[rel] = _simplified(meshes[rel], rel, _scale(mesh), taken, out.files)
            if done[rel].rel:
                mesh.set("filename", prefix + done[rel].rel)
    made = {rel: r for rel, r in done.items() if r.rel}
    whole = {rel: r for rel, r in done.items() if r.why_not}
    if made:
        saved = sum(r.before - r.after for r in made.values())
        each = "; ".join(f"{rel} {r.before:,} -> {r.after:,} triangles (surfaces within "
                         f"{r.within_mm:.2g} mm)" for rel, r in made.items())
        out.choices.append(
            f"{len(made)} collision mesh(es) over {HEAVY:,} triangles got a simplified copy in "
            f"{FOLDER}/, which their <collision> now names ({saved:,} triangles fewer for "
            f"Gazebo's contact checks; the <visual> keeps the whole mesh, as Gazebo's guide "
            f"advises, {SOURCE}): {each}. --keep-collision-meshes keeps them whole.")
    for rel, r in whole.items():
        out.choices.append(f"{rel} ({r.before:,} triangles) names a <collision>, but {r.why_not}; "
                           "it is used whole.")
    return out


def _scale(mesh) -> float:
    """The largest factor of the <mesh>'s scale (1 when it has none or it is unreadable)."""
    try:
        values = [abs(float(v)) for v in (mesh.get("scale") or "1 1 1").split()]
    except ValueError:
        return 1.0
    return max(values) if len(values) == 3 else 1.0


def _simplified(source: Path, rel: str, scale: float, taken: set[str],
                files: dict[str, bytes]) -> _Result:
    """Simplify one mesh file into files[the copy's path]; what came of it."""
    mesh = read(source)
    if mesh is None or len(mesh.faces) <= HEAVY:
        return _Result("", 0 if mesh is None else len(mesh.faces))
    before = len(mesh.faces)
    mesh.merge_vertices()
    solid = as_solid(mesh)
    if solid is None:
        return _Result("", before, why_not="it is not a closed surface, which simplifying needs "
                       "(`sw2sim check` on the source says where it is open)")
    diagonal = float(np.linalg.norm(mesh.extents))
    for fraction in TOLERANCES:
        tolerance = diagonal * fraction
        smaller = solid.simplify(tolerance)
        if smaller.num_tri() <= TARGET:
            break
    after, within = smaller.num_tri(), tolerance * scale * 1000
    if after < 4:
        return _Result("", before, why_not=f"simplifying it within {within:.2g} mm leaves no "
                       "solid (the part is too thin for that)")
    if after * 2 > before:
        return _Result("", before, why_not=f"simplifying it within {within:.2g} mm leaves "
                       f"{after:,} triangles, not half as many")
    copy = _free_name(rel, taken)
    taken.add(copy)
    files[copy] = _stl(smaller)
    return _Result(copy, before, after, within)


def _free_name(rel: str, taken: set[str]) -> str:
    """meshes/simplified/<the path under meshes/>, as .STL; another name if that is taken."""
    inside = PurePosixPath(rel)
    inside = inside.relative_to("meshes") if inside.parts[0] == "meshes" else inside
    stem = (PurePosixPath(FOLDER) / inside).with_suffix("")
    name, n = f"{stem}.STL", 2
    while name in taken:
        name, n = f"{stem}_{n}.STL", n + 1
    return name


def _stl(solid) -> bytes:
    """The solid as binary STL."""
    mesh = solid.to_mesh()
    vertices = np.asarray(mesh.vert_properties, dtype=np.float64)[:, :3]
    return binary_stl(vertices[np.asarray(mesh.tri_verts, dtype=np.int64)])
