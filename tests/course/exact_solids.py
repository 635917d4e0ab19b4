"""The volume of a part as SolidWorks measures it: the exact solid, round faces round.

`course.parts.Part.mass` weighs the part's STL mesh, whose cylinders are prisms of 96
facets. SolidWorks' mass properties come from the exact geometry, so the masses a student
sees in *Evaluate > Mass Properties* (and in the URDF the exporter writes) are these.

The parts of the lessons are boxes and cylinders, added or cut, that overlap at most two at
a time. So the volume is each feature's own volume, less what each pair of added features
share, less what each cut takes out of the added feature it meets. Every overlap that
occurs is a prism: two shapes with parallel axes, sharing a stretch of that axis, so its
volume is the area two plane figures (rectangles, circles) share times that stretch. The
test that uses this also weighs a very fine mesh of each part, which catches an overlap
of three features or of two cuts, which this sum would count wrongly.
"""

from __future__ import annotations

import itertools
import math

import numpy as np
import shapely
import shapely.affinity

from course.parts import Box, Cylinder, Part

AXES = {"x": 0, "y": 1, "z": 2}


def feature_volume(f: Box | Cylinder) -> float:
    if isinstance(f, Box):
        return float(np.prod(f.size))
    return math.pi * f.radius ** 2 * f.length


def _turn(point, degrees: float) -> np.ndarray:
    """A point turned `degrees` about z."""
    a = math.radians(degrees)
    x, y, z = point
    return np.array([x * math.cos(a) - y * math.sin(a), x * math.sin(a) + y * math.cos(a), z])


def _section(f: Box | Cylinder, axis: int, yaw: float):
    """The feature in the frame turned `yaw` about z: (its plane figure across `axis`, as a
    shapely polygon or a (centre, radius) circle, and its interval along `axis`)."""
    centre = _turn(f.center, -yaw)
    across = [i for i in range(3) if i != axis]
    if isinstance(f, Box):
        half = np.asarray(f.size) / 2
        lo, hi = centre - half, centre + half
        figure = shapely.box(lo[across[0]], lo[across[1]], hi[across[0]], hi[across[1]])
        return figure, (lo[axis], hi[axis])
    along = AXES[f.axis]
    if along != axis:
        raise ValueError("a cylinder seen across its axis is not a plane figure")
    return (centre[across], f.radius), (centre[axis] - f.length / 2, centre[axis] + f.length / 2)


def _circle_polygon_area(centre, radius: float, polygon) -> float:
    """Exact area shared by a circle and a convex polygon: the sum, over the polygon's
    edges, of the signed area the circle shares with the triangle (centre, edge)."""
    points = np.asarray(polygon.exterior.coords) - centre
    total = 0.0
    for a, b in zip(points[:-1], points[1:]):
        total += _circle_triangle(a, b, radius)
    return abs(total)


def _circle_triangle(a, b, r: float) -> float:
    """Signed area shared by the circle of radius r about the origin and the triangle (0, a, b)."""
    d = b - a
    # where the segment a + t d crosses the circle, 0 < t < 1
    qa, qb, qc = d @ d, 2 * (a @ d), a @ a - r * r
    cuts = [0.0]
    disc = qb * qb - 4 * qa * qc
    if disc > 0:
        root = math.sqrt(disc)
        cuts += sorted(t for t in ((-qb - root) / (2 * qa), (-qb + root) / (2 * qa)) if 0 < t < 1)
    cuts.append(1.0)
    area = 0.0
    for t0, t1 in zip(cuts[:-1], cuts[1:]):
        p, q = a + t0 * d, a + t1 * d
        mid = a + (t0 + t1) / 2 * d
        cross = p[0] * q[1] - p[1] * q[0]
        if mid @ mid <= r * r:
            area += cross / 2                                   # inside: a triangle
        else:
            area += r * r * math.atan2(cross, p @ q) / 2        # outside: a sector
    return area


def _circle_circle_area(c1, r1: float, c2, r2: float) -> float:
    d = float(np.hypot(*(np.asarray(c1) - np.asarray(c2))))
    if d >= r1 + r2:
        return 0.0
    if d <= abs(r1 - r2):
        return math.pi * min(r1, r2) ** 2
    a1 = r1 * r1 * math.acos((d * d + r1 * r1 - r2 * r2) / (2 * d * r1))
    a2 = r2 * r2 * math.acos((d * d + r2 * r2 - r1 * r1) / (2 * d * r2))
    return a1 + a2 - 0.5 * math.sqrt((-d + r1 + r2) * (d + r1 - r2) * (d - r1 + r2) * (d + r1 + r2))


def _area(first, second) -> float:
    circles = [s for s in (first, second) if isinstance(s, tuple)]
    polygons = [s for s in (first, second) if not isinstance(s, tuple)]
    if len(polygons) == 2:
        return first.intersection(second).area
    if len(circles) == 2:
        return _circle_circle_area(*first, *second)
    (centre, radius), = circles
    return _circle_polygon_area(centre, radius, polygons[0])


def _bounds(f: Box | Cylinder) -> tuple[np.ndarray, np.ndarray]:
    """A box that holds the feature (not the tightest one for a cylinder)."""
    if isinstance(f, Box):
        half = np.asarray(f.size) / 2
        signs = itertools.product((-1, 1), repeat=3)
        corners = np.array([_turn(half * np.array(s), f.yaw) for s in signs]) + f.center
        return corners.min(axis=0), corners.max(axis=0)
    direction = np.zeros(3)
    direction[AXES[f.axis]] = f.length / 2
    ends = np.array([_turn(direction, f.yaw), _turn(-direction, f.yaw)]) + f.center
    return ends.min(axis=0) - f.radius, ends.max(axis=0) + f.radius


def shared_volume(f: Box | Cylinder, g: Box | Cylinder) -> float:
    """The volume two features share, when they are prisms along one common axis."""
    (lo_f, hi_f), (lo_g, hi_g) = _bounds(f), _bounds(g)
    if np.any(np.minimum(hi_f, hi_g) <= np.maximum(lo_f, lo_g)):
        return 0.0
    cylinders = [h for h in (f, g) if isinstance(h, Cylinder)]
    if all(h.axis == "z" for h in cylinders):
        # Both stand on z (a box always does): figures in the plane z = 0, turned by their own yaw.
        sections = []
        for h in (f, g):
            figure, span = _section(h, 2, h.yaw)
            if isinstance(figure, tuple):
                figure = (np.asarray(h.center[:2]), figure[1])
            else:
                figure = shapely.affinity.rotate(figure, h.yaw, origin=(0, 0))
            sections.append((figure, span))
    else:
        if f.yaw != g.yaw or len({h.axis for h in cylinders}) > 1:
            raise NotImplementedError(f"features that cross at an angle: {f}, {g}")
        axis = AXES[cylinders[0].axis]
        sections = [_section(h, axis, f.yaw) for h in (f, g)]
    (fig1, (lo1, hi1)), (fig2, (lo2, hi2)) = sections
    length = min(hi1, hi2) - max(lo1, lo2)
    if length <= 0:
        return 0.0
    return _area(fig1, fig2) * length


def exact_volume(part: Part) -> float:
    added = [f for f in part.features if not f.cut]
    cuts = [f for f in part.features if f.cut]
    volume = sum(feature_volume(f) for f in added)
    for i, f in enumerate(added):
        for g in added[i + 1:]:
            volume -= shared_volume(f, g)
    for c in cuts:
        volume -= sum(shared_volume(c, f) for f in added)
    return volume


def exact_mass(part: Part) -> float:
    """kg, as SolidWorks' Mass Properties gives it for the part in its material."""
    return exact_volume(part) * part.material.density
