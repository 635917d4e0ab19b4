"""A part's features as an exact solid: turned boxes and cylinders, added or cut, queried for
the points inside and where lines cross them (no mesh, no sampling in depth)."""

from __future__ import annotations

import math

import numpy as np

from ..parts import Box, Cylinder

# --- exact point and line queries on a part's features ----------------------------------------


def _yaw_matrix(deg: float) -> np.ndarray:
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


class Shape:
    """One feature as a solid the queries understand: a turned box or a cylinder."""

    def __init__(self, f: Box | Cylinder):
        rot = _yaw_matrix(f.yaw)
        self.feature = f
        self.c = np.asarray(f.center, dtype=float)
        if isinstance(f, Box):
            self.kind = "box"
            self.E = rot.T.copy()  # rows: the box's own x, y, z in the part frame
            self.h = np.asarray(f.size, dtype=float) / 2
        else:
            if f.axis not in ("x", "y", "z"):
                raise ValueError(f"cylinder axis must be 'x', 'y' or 'z', not {f.axis!r}")
            self.kind = "cyl"
            self.a = rot @ np.eye(3)[{"x": 0, "y": 1, "z": 2}[f.axis]]
            self.r = float(f.radius)
            self.hl = float(f.length) / 2

    def contains(self, P: np.ndarray) -> np.ndarray:
        rel = P - self.c
        if self.kind == "box":
            return np.all(np.abs(rel @ self.E.T) <= self.h + 1e-12, axis=1)
        s = rel @ self.a
        radial2 = np.einsum("ij,ij->i", rel, rel) - s * s
        return (np.abs(s) <= self.hl + 1e-12) & (radial2 <= self.r * self.r + 1e-15)

    def span(self, O: np.ndarray, u: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Where the lines O + t u are inside: (t_in, t_out), empty when t_in >= t_out."""
        n = len(O)
        t0, t1 = np.full(n, -np.inf), np.full(n, np.inf)
        rel = O - self.c
        if self.kind == "box":
            slabs = [(rel @ e, float(u @ e), h) for e, h in zip(self.E, self.h)]
        else:
            slabs = [(rel @ self.a, float(u @ self.a), self.hl)]
        for o, w, h in slabs:
            if abs(w) < 1e-12:
                out = np.abs(o) > h
                t0[out], t1[out] = np.inf, -np.inf
            else:
                a, b = (-h - o) / w, (h - o) / w
                t0, t1 = np.maximum(t0, np.minimum(a, b)), np.minimum(t1, np.maximum(a, b))
        if self.kind == "cyl":
            sa, ua = rel @ self.a, float(u @ self.a)
            w0 = rel - sa[:, None] * self.a
            wu = u - ua * self.a
            A, B = float(wu @ wu), 2 * (w0 @ wu)
            C = np.einsum("ij,ij->i", w0, w0) - self.r ** 2
            if A < 1e-18:  # a line along the axis: inside the whole way or not at all
                out = C > 0
                t0[out], t1[out] = np.inf, -np.inf
            else:
                disc = B * B - 4 * A * C
                sq = np.sqrt(np.maximum(disc, 0.0))
                r0, r1 = (-B - sq) / (2 * A), (-B + sq) / (2 * A)
                r0[disc < 0], r1[disc < 0] = np.inf, -np.inf
                t0, t1 = np.maximum(t0, r0), np.minimum(t1, r1)
        return t0, t1


class Solid:
    """The part as added and cut features, queried exactly (no mesh, no sampling in depth)."""

    def __init__(self, features):
        self.shapes = [Shape(f) for f in features]
        self.added = [s for s in self.shapes if not s.feature.cut]
        self.cuts = [s for s in self.shapes if s.feature.cut]
        corners = np.concatenate([shape_corners(s) for s in self.added])
        self.lo, self.hi = corners.min(0), corners.max(0)
        self.reach = float(np.linalg.norm(self.hi - self.lo)) + 1e-3
        self.eps = 1e-6 * max(1.0, self.reach)

    def contains(self, P: np.ndarray) -> np.ndarray:
        inside = np.zeros(len(P), dtype=bool)
        for s in self.added:
            inside |= s.contains(P)
        for s in self.cuts:
            inside &= ~s.contains(P)
        return inside

    def pieces(self, origins: list[np.ndarray], u: np.ndarray, lo, hi):
        """Cut the lines O + t u, t in [lo, hi], at every feature boundary (all origin sets alike).

        Returns the sorted cut points (N, K) and, for each origin set, whether each of the K-1
        pieces is material (M, N, K-1). A piece of zero length is reported empty.
        """
        n = len(origins[0])
        lo, hi = np.broadcast_to(lo, (n,)).astype(float), np.broadcast_to(hi, (n,)).astype(float)
        cols = [lo, hi]
        for O in origins:
            for s in self.shapes:
                t0, t1 = s.span(O, u)
                ok = t0 < t1
                cols += [np.where(ok, t0, lo), np.where(ok, t1, lo)]
        cuts = np.sort(np.clip(np.stack(cols, axis=1), lo[:, None], hi[:, None]), axis=1)
        mid = (cuts[:, 1:] + cuts[:, :-1]) / 2
        real = (cuts[:, 1:] - cuts[:, :-1]) > 1e-10
        occ = np.stack([
            self.contains((O[:, None, :] + mid[..., None] * u).reshape(-1, 3)).reshape(mid.shape) & real
            for O in origins])
        return cuts, occ

    def blocked(self, O: np.ndarray, u: np.ndarray) -> np.ndarray:
        """Whether material lies on the rays O + t u, t > 0 (the part is hidden there)."""
        if not len(O):
            return np.zeros(0, dtype=bool)
        cuts, occ = self.pieces([O], u, 0.0, 2 * self.reach)
        return (((cuts[:, 1:] - cuts[:, :-1]) > 1e-9 * self.reach) & occ[0]).any(axis=1)


def shape_corners(s: Shape) -> np.ndarray:
    """Points whose hull contains the shape (exact extents along any of the part's axes)."""
    if s.kind == "box":
        signs = np.array([[i, j, k] for i in (-1, 1) for j in (-1, 1) for k in (-1, 1)], dtype=float)
        return s.c + (signs * s.h) @ s.E
    pts = []
    for end in (-1, 1):
        ce = s.c + end * s.hl * s.a
        for axis in np.eye(3):
            perp = axis - (axis @ s.a) * s.a
            norm = np.linalg.norm(perp)
            if norm > 1e-12:
                pts += [ce + s.r * perp / norm, ce - s.r * perp / norm]
        pts.append(ce)
    return np.array(pts)
