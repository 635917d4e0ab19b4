"""A package read for comparison: its link tree, each joint's frame, axis and limits, and
each link's mass properties and visual mesh, with every frame's pose at rest. A mesh
with no triangles, or with no volume, is kept as the link's `mesh_fault` (`meshes`).

A URDF that cannot be compared (a joint naming a missing link, links not joined into
one tree, a number that is not one) raises CompareError naming the file and line;
`sw2sim check` lists every such problem with its fix.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..check.geometry import inertial_of, origin_matrix
from ..check.trimeshes import Mesh, box, cylinder, read, sphere
from ..check.urdf import number, vector
from ..package import LoadError, Package, find_package
from .meshes import MeshFault, emptiness, flatness

LIMIT_FIELDS = ("lower", "upper", "effort", "velocity")
MOVING = ("revolute", "continuous", "prismatic")
TYPES = MOVING + ("fixed", "floating", "planar")


class CompareError(Exception):
    """A package that cannot be compared; the message names the file (and line)."""


@dataclass
class Joint:
    name: str
    type: str
    parent: str
    child: str
    origin: np.ndarray              # 4 x 4, the joint's frame in the parent link's frame
    rpy: tuple[float, float, float]  # as written
    axis: np.ndarray                # unit vector in the joint's frame
    axis_given: bool
    limit: dict | None              # LIMIT_FIELDS -> float (0 where absent); None: no <limit>
    line: int | None


@dataclass
class Link:
    name: str
    mass: float | None              # None: no <inertial>
    centre: np.ndarray | None       # the centre of mass in the link's frame
    tensor: np.ndarray | None       # about the centre of mass, in the link's axes
    mesh: Mesh | None               # the visual geometry in the link's frame, in metres
    line: int | None
    mesh_fault: MeshFault | None = None   # a visual mesh with no triangles or no volume

    @property
    def bare(self) -> bool:
        """Neither mass nor shape: a `world` link, or a frame."""
        return self.mass is None and self.mesh is None

    @property
    def volume(self) -> float | None:
        """The mesh's enclosed volume (m^3), or None without a mesh."""
        if self.mesh is None or not len(self.mesh.faces):
            return None
        t = self.mesh.triangles
        return abs(float(np.einsum("ij,ij->i", t[:, 0], np.cross(t[:, 1], t[:, 2])).sum()) / 6)


class Model:
    """One package's robot: links, joints, the tree, and each link's pose at rest.

    `base` is the robot's first real link: the root, or the one child of a root that is
    a bare link joined to it by a fixed joint (`world`, when the URDF bolts the robot
    down); `world` is then that root. `pose` gives a link's frame in the base's frame.
    """

    def __init__(self, package: Package):
        self.package = package
        self.file = shown(package.urdf)
        self.links = {name: _link(self, element) for name, element in package.links.items()}
        self.joints: dict[str, Joint] = {}
        self.above: dict[str, Joint] = {}           # child link -> its joint
        self.children: dict[str, list[Joint]] = {name: [] for name in self.links}
        for kind in ("link", "joint"):
            names = [e.get("name", "") for e in package.robot.findall(kind)]
            twice = next((e for e in package.robot.findall(kind)
                          if names.count(e.get("name", "")) > 1), None)
            if twice is not None:
                raise self.error(twice, f'two {kind}s are named "{twice.get("name", "")}"')
        for element in package.robot.findall("joint"):
            joint = _joint(self, element)
            if joint.child in self.above:
                raise self.error(element, f'link "{joint.child}" is the child of two joints, '
                                 f'"{self.above[joint.child].name}" and "{joint.name}"')
            self.joints.setdefault(joint.name, joint)
            self.above[joint.child] = joint
            self.children[joint.parent].append(joint)
        roots = [name for name in self.links if name not in self.above]
        if len(roots) != 1:
            why = "every link has a parent" if not roots else "unjoined: " + ", ".join(roots)
            raise CompareError(f"{self.file}: the links do not form one tree ({why}); "
                               f"`sw2sim check {self.file}` says how to fix it")
        self.root = roots[0]
        self.world, self.base = None, self.root
        below = self.children[self.root]
        if (self.links[self.root].bare or self.root == "world") and len(below) == 1 \
                and below[0].type == "fixed":
            self.world, self.base = self.root, below[0].child
        self.pose = {self.base: np.eye(4)}
        order = [self.base]
        for name in order:
            for joint in self.children[name]:
                self.pose[joint.child] = self.pose[name] @ joint.origin
                order.append(joint.child)
        unreached = [n for n in self.links if n not in self.pose and n != self.world]
        if unreached:
            raise CompareError(f"{self.file}: the joints form a loop through link "
                               f'"{unreached[0]}"; a URDF is a tree')

    def error(self, element, message: str) -> CompareError:
        line = getattr(element, "sourceline", None)
        where = f"{self.file}:{line}" if line else self.file
        return CompareError(f"{where}: {message}; `sw2sim check {self.file}` lists every "
                            "problem of the package with its fix")

    def subtree(self, name: str) -> list[str]:
        """The link and every link below it."""
        found = [name]
        for link in found:
            found += [j.child for j in self.children[link]]
        return found

    def mass_below(self, name: str) -> float:
        return sum(self.links[n].mass or 0.0 for n in self.subtree(name))


def read_model(path: str | os.PathLike, urdf: str | None = None) -> Model:
    """The package at `path` (folder or .urdf), read; CompareError when it cannot be."""
    try:
        return Model(find_package(path, urdf))
    except LoadError as exc:
        raise CompareError(str(exc)) from None


def shown(path: Path) -> str:
    """A path as the user would write it: relative to the working folder when inside it."""
    try:
        return str(Path(path).relative_to(Path.cwd()))
    except ValueError:
        return str(path)


def _joint(model: Model, element) -> Joint:
    name = element.get("name", "")
    kind = element.get("type", "")
    if kind not in TYPES:
        raise model.error(element, f'joint "{name}" has type "{kind}"; a URDF joint is one '
                          f"of {', '.join(TYPES)}")
    ends = []
    for end in ("parent", "child"):
        found = element.find(end)
        link = None if found is None else found.get("link")
        if link not in model.links:
            raise model.error(element, f'joint "{name}" names {end} link "{link}", which '
                              "the URDF does not define")
        ends.append(link)
    origin = origin_matrix(element)
    if origin is None:
        raise model.error(element.find("origin"), f'joint "{name}": the <origin> holds '
                          "something other than numbers")
    axis_element = element.find("axis")
    axis = np.array([1.0, 0.0, 0.0])
    if axis_element is not None:
        given = vector(axis_element.get("xyz", "1 0 0"), 3)
        if given is None or (kind in MOVING and not np.any(given)):
            raise model.error(axis_element, f'joint "{name}": the axis is not a direction')
        if np.any(given):
            axis = np.array(given) / np.linalg.norm(given)
    limit = None
    limit_element = element.find("limit")
    if limit_element is not None:
        limit = {}
        for field in LIMIT_FIELDS:
            text = limit_element.get(field)
            limit[field] = 0.0 if text is None else number(text)
            if limit[field] is None:
                raise model.error(limit_element, f'joint "{name}": limit {field}="{text}" '
                                  "is not a number")
    written = element.find("origin")
    rpy = (0.0, 0.0, 0.0) if written is None else vector(written.get("rpy", "0 0 0"), 3)
    return Joint(name, kind, ends[0], ends[1], origin, rpy, axis, axis_element is not None,
                 limit, element.sourceline)


def _link(model: Model, element) -> Link:
    name = element.get("name", "")
    inertial = inertial_of(element)
    mass = centre = tensor = None
    if inertial is not None:
        mass, centre, tensor = inertial.mass, inertial.centre, inertial.tensor
        if mass is None or centre is None or tensor is None:
            raise model.error(inertial.element, f'link "{name}": the <inertial> is incomplete '
                              f"or holds something other than numbers")
    mesh, fault = _visual(model.package, element)
    return Link(name, mass, centre, tensor, mesh, element.sourceline, fault)


def _visual(package: Package, link) -> tuple[Mesh | None, MeshFault | None]:
    """The link's visual geometry as one mesh in its frame, and the first of its meshes
    that has no triangles or no volume. The mesh is None when there is none, or some of
    it cannot be read or is faulty (the comparison of sizes and volumes is then skipped)."""
    vertices, faces, count, fault, whole = [], [], 0, None, True
    for visual in link.findall("visual"):
        shapes = [s for s in visual.iterfind("geometry/*") if isinstance(s.tag, str)]
        mesh, wrong = _shape(package, shapes[0]) if shapes else (None, None)
        fault = fault or wrong
        pose = origin_matrix(visual)
        if mesh is None or pose is None:
            whole = False
            continue
        mesh.apply_transform(pose)
        vertices.append(mesh.vertices)
        faces.append(mesh.faces + count)
        count += len(mesh.vertices)
    if not whole or not vertices:
        return None, fault
    return Mesh(np.vstack(vertices), np.vstack(faces)), fault


def _inside(package: Package, file: Path) -> str:
    """A mesh file as the package names it: meshes/part.STL."""
    try:
        return Path(file).relative_to(package.root).as_posix()
    except ValueError:
        return shown(file)


def _shape(package: Package, shape) -> tuple[Mesh | None, MeshFault | None]:
    """One <geometry>'s shape in metres, or None; and its fault, for a faulty mesh file."""
    if shape.tag == "mesh":
        try:
            file = package.resolve_mesh(shape.get("filename", ""))
        except LoadError:
            return None, None
        scale = vector(shape.get("scale", "1 1 1"), 3)
        empty = emptiness(file)
        if empty:
            return None, MeshFault(_inside(package, file), empty, True)
        mesh = read(file)
        if mesh is None or scale is None:
            return None, None
        mesh.apply_scale(scale)
        flat = flatness(mesh.vertices)
        if flat:
            return None, MeshFault(_inside(package, file), flat, False, not all(scale))
        return mesh, None
    sizes = {"box": ("size", 3), "cylinder": ("radius", 1), "sphere": ("radius", 1)}
    if shape.tag not in sizes:
        return None, None
    values = vector(shape.get(sizes[shape.tag][0]), sizes[shape.tag][1])
    if values is None:
        return None, None
    if shape.tag == "box":
        return box(values), None
    if shape.tag == "sphere":
        return sphere(values[0]), None
    length = number(shape.get("length"))
    return (None if length is None else cylinder(values[0], length)), None
