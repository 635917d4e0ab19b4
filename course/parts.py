"""Parts described the way a drawing describes them: simple solids added and cut.

A part is a list of features (boxes and cylinders, each added or cut) plus the
dimensions its drawing shows. The same feature list produces the STL mesh, its
mass properties and the SVG drawing, so the three cannot disagree.

All lengths are in metres, in the part's own frame (the frame the exporter
writes the mesh in).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property

import numpy as np
import trimesh

@dataclass(frozen=True)
class Material:
    name: str
    density: float  # kg/m^3


@dataclass(frozen=True)
class Box:
    """A rectangular block of `size` (x, y, z) centred at `center`, turned `yaw` degrees about z."""

    size: tuple[float, float, float]
    center: tuple[float, float, float] = (0.0, 0.0, 0.0)
    yaw: float = 0.0
    cut: bool = False

    def mesh(self, sections: int = 0) -> trimesh.Trimesh:
        m = trimesh.creation.box(extents=self.size)
        return _place(m, self.center, self.yaw)


@dataclass(frozen=True)
class Cylinder:
    """A round bar of `radius` and `length` along `axis` ('x', 'y' or 'z'), centred at `center`.

    `yaw` turns it about z after it is laid along its axis.
    """

    radius: float
    length: float
    axis: str = "z"
    center: tuple[float, float, float] = (0.0, 0.0, 0.0)
    yaw: float = 0.0
    cut: bool = False

    def mesh(self, sections: int = 96) -> trimesh.Trimesh:
        m = trimesh.creation.cylinder(radius=self.radius, height=self.length, sections=sections)
        if self.axis == "x":
            m.apply_transform(trimesh.transformations.rotation_matrix(np.pi / 2, [0, 1, 0]))
        elif self.axis == "y":
            m.apply_transform(trimesh.transformations.rotation_matrix(-np.pi / 2, [1, 0, 0]))
        elif self.axis != "z":
            raise ValueError(f"cylinder axis must be 'x', 'y' or 'z', not {self.axis!r}")
        return _place(m, self.center, self.yaw)


def _place(m: trimesh.Trimesh, center, yaw_deg: float) -> trimesh.Trimesh:
    if yaw_deg:
        m.apply_transform(trimesh.transformations.rotation_matrix(np.radians(yaw_deg), [0, 0, 1]))
    m.apply_translation(center)
    return m


Feature = Box | Cylinder


@dataclass(frozen=True)
class Dimension:
    """A dimension line on the drawing, measured between two 3D points of the part.

    Views (first-angle arrangement is the drawing module's business; the axes are fixed here):
    'front' looks along +y: horizontal = x, vertical = z.
    'top' looks down -z: horizontal = x, vertical = y.
    'side' looks along -x from +x: horizontal = y, vertical = z.
    `direction` 'h' measures the horizontal distance between `a` and `b` in that view and
    draws a horizontal dimension line at vertical position max(a_v, b_v) + offset when
    offset > 0, or min(a_v, b_v) + offset when offset < 0; 'v' likewise with the roles
    swapped. `offset` is in metres of the part. The text is the measured length in mm unless
    `label` is given (e.g. "Ø20 THRU").
    'a' (aligned) measures the true distance between `a` and `b` in the view and draws the
    dimension line parallel to it, `offset` to the left of the direction from `a` to `b`
    (to the right when negative).
    """

    view: str
    a: tuple[float, float, float]
    b: tuple[float, float, float]
    direction: str = "h"
    offset: float = 0.02
    label: str | None = None  # override the text, e.g. "Ø20 THRU"


@dataclass(frozen=True)
class Angle:
    """An angular dimension on the drawing: the angle at `vertex` between the line towards `a`
    and the line towards `b`, both in the plane of `view` (the smaller of the two angles).

    It is drawn as an arc of `radius` (metres of the part) about the vertex, with an arrowhead
    on each leg. A leg whose point lies inside the arc is not an edge of the part but one
    produced past the vertex: it is drawn as an extension line from the vertex to beyond the
    arc. The text is the angle in degrees unless `label` is given.
    """

    view: str
    vertex: tuple[float, float, float]
    a: tuple[float, float, float]
    b: tuple[float, float, float]
    radius: float = 0.03
    label: str | None = None


@dataclass
class Part:
    name: str
    material: Material
    features: list[Feature]
    dimensions: list[Dimension | Angle] = field(default_factory=list)
    title: str = ""
    sections: int = 96  # facets around a cylinder: the exporter's "fine" quality

    @cached_property
    def mesh(self) -> trimesh.Trimesh:
        """The solid: every added feature united, every cut feature subtracted."""
        added = [f.mesh(self.sections) for f in self.features if not f.cut]
        cuts = [f.mesh(self.sections) for f in self.features if f.cut]
        solid = added[0] if len(added) == 1 else trimesh.boolean.union(added, engine="manifold")
        if cuts:
            solid = trimesh.boolean.difference([solid, *cuts], engine="manifold")
        solid.merge_vertices()
        if not solid.is_watertight:
            raise ValueError(f"part {self.name!r}: the solid is not watertight; check its features")
        return solid

    @property
    def mass(self) -> float:
        return float(self.mesh.volume * self.material.density)

    def mass_properties(self) -> tuple[float, np.ndarray, np.ndarray]:
        """(mass kg, centre of mass (3,), inertia tensor about the centre of mass (3, 3))."""
        m = self.mesh.copy()
        m.density = self.material.density
        return float(m.mass), np.asarray(m.center_mass), np.asarray(m.moment_inertia)
