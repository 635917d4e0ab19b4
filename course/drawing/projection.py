"""The lines of one orthographic view of a part, and its centre lines.

A part's lines are computed from its features exactly, not from its mesh: every edge, face seen
edge-on and cylinder silhouette of every feature is a candidate line (`Projector`); a candidate is
drawn where it is really on the solid's boundary, as a visible line where nothing lies between it
and the viewer, dashed where something does (`trace_view`). Cylinders get centre lines, equal
holes on a circle a pitch circle; `view_prims` turns a traced view into sheet primitives.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Callable

import numpy as np
import shapely
from shapely.geometry import LineString

from .solids import Shape, Solid
from .svg import Arc, Circle, Line, Poly

# Views as the Dimension docstring fixes them: (viewing direction, horizontal, vertical).
# Each is right-handed: horizontal x vertical points back at the viewer.
VIEWS = {
    "front": ((0.0, 1.0, 0.0), (1.0, 0.0, 0.0), (0.0, 0.0, 1.0)),
    "top": ((0.0, 0.0, -1.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)),
    "side": ((-1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)),
}

CENTRE_EXT = 3.0  # centre lines run this far past the feature
SAMPLE_STEP = 0.4  # sheet mm between samples when tracing a candidate line
MIN_RUN = 0.2  # sheet mm: shorter line pieces and gaps are numerical noise


# --- the lines of one view ---------------------------------------------------------------------


@dataclass
class _Curve:
    """A candidate line of a view, traced by a parameter t in [0, period).

    kind 'seg' is a straight segment (t in [0, 1]), 'arc' a circle about `centre` (t an angle),
    'poly' any other closed curve. `state(t)` is 0 where the candidate is not on the solid's
    boundary, 1 where it is hidden and 2 where it is visible.
    """

    kind: str
    shape: int
    role: str
    where: Callable[[np.ndarray], np.ndarray]  # t -> (N, 3) points of the part
    state: Callable[[np.ndarray], np.ndarray]
    period: float = 1.0
    centre: tuple = (0.0, 0.0)
    radius: float = 0.0


@dataclass
class ViewLines:
    """The traced lines of one view, in metres of the part, view plane (h right, v up)."""

    visible: list = field(default_factory=list)  # (curve, t0, t1)
    hidden: list = field(default_factory=list)
    centre: list = field(default_factory=list)  # ('line', p, q) or ('circle', centre, radius)


class Projector:
    """One of the three views of a solid: projection, candidate lines and their visibility."""

    def __init__(self, solid: Solid, view: str):
        d, h, v = (np.array(x) for x in VIEWS[view])
        self.solid, self.name, self.d, self.h, self.v = solid, view, d, h, v
        self.P = np.stack([h, v])

    def project(self, X: np.ndarray) -> np.ndarray:
        return np.asarray(X, dtype=float) @ self.P.T

    # candidate states ---------------------------------------------------------------------------

    def _sweep_state(self, B, n, s0, s1):
        """A surface containing the viewing direction: drawn where it bounds the solid somewhere
        along the sight line, visible when its nearest such point can be seen."""
        eps, d, solid = self.solid.eps, self.d, self.solid
        cuts, occ = solid.pieces([B + eps * n, B - eps * n], d, s0, s1)
        exists = occ[0] != occ[1]
        has = exists.any(axis=1)
        state = np.zeros(len(B), dtype=int)
        if not has.any():
            return state
        rows = np.nonzero(has)[0]
        i = exists[rows].argmax(axis=1)
        start, end = cuts[rows, i], cuts[rows, i + 1]
        q = B[rows] + (start + np.minimum((end - start) / 2, 10 * eps))[:, None] * d
        side = np.where(occ[0][rows, i], -eps, eps)  # step off the surface on its empty side
        seen = ~solid.blocked(q + side[:, None] * n[rows], -d)
        state[rows] = np.where(seen, 2, 1)
        return state

    def _probe_state(self, B, offsets, exists_fn):
        """An edge or silhouette at B: exists by the material pattern around it, visible when
        one of its empty sides can see the viewer."""
        solid = self.solid
        occ = [solid.contains(B + o) for o in offsets]
        exists = exists_fn(occ)
        seen = np.zeros(len(B), dtype=bool)
        for o, oc in zip(offsets, occ):
            ask = exists & ~oc & ~seen
            if ask.any():
                seen[ask] = ~solid.blocked((B + o)[ask], -self.d)
        return np.where(exists, np.where(seen, 2, 1), 0)

    # candidates of each feature -------------------------------------------------------------------

    def curves(self) -> list[_Curve]:
        out = []
        for i, s in enumerate(self.solid.shapes):
            out += self._box_curves(i, s) if s.kind == "box" else self._cylinder_curves(i, s)
        return out

    def _box_curves(self, i: int, s: Shape) -> list[_Curve]:
        d, out = self.d, []
        for ax in range(3):
            for sign in (-1.0, 1.0):
                n = sign * s.E[ax]
                if abs(n @ d) < 1e-9:  # a face seen edge-on: it draws as a segment
                    out.append(self._box_face(i, s, ax, n))
        for ax in range(3):
            e = s.E[ax]
            if abs(abs(e @ d) - 1) < 1e-9:
                continue  # an edge along the sight line draws as a point
            j, k = [x for x in range(3) if x != ax]
            for sj in (-1.0, 1.0):
                for sk in (-1.0, 1.0):
                    n1, n2 = sj * s.E[j], sk * s.E[k]
                    if abs(n1 @ d) < 1e-9 or abs(n2 @ d) < 1e-9:
                        continue  # drawn by the face seen edge-on
                    mid = s.c + sj * s.h[j] * s.E[j] + sk * s.h[k] * s.E[k]
                    out.append(self._edge(i, mid - s.h[ax] * e, mid + s.h[ax] * e, n1, n2))
        return out

    def _box_face(self, i, s, ax, n) -> _Curve:
        d = self.d
        cf = s.c + (n @ s.E[ax]) * s.h[ax] * s.E[ax]
        w = np.cross(n, d)
        w /= np.linalg.norm(w)
        inplane = [(s.E[x], s.h[x]) for x in range(3) if x != ax]
        ext = sum(h * abs(e @ w) for e, h in inplane)

        def where(t):
            return cf + ((2 * np.asarray(t) - 1) * ext)[:, None] * w

        def state(t):
            B = where(t)
            s0, s1 = np.full(len(B), -np.inf), np.full(len(B), np.inf)
            for e, h in inplane:
                o, we = (B - cf) @ e, float(d @ e)
                if abs(we) > 1e-12:
                    a, b = (-h - o) / we, (h - o) / we
                    s0, s1 = np.maximum(s0, np.minimum(a, b)), np.minimum(s1, np.maximum(a, b))
            s0, s1 = np.maximum(s0, -self.solid.reach), np.minimum(s1, self.solid.reach)
            return self._sweep_state(B, np.broadcast_to(n, B.shape), s0, np.maximum(s1, s0))

        return _Curve("seg", i, "face", where, state)

    def _edge(self, i, p0, p1, n1, n2) -> _Curve:
        eps = self.solid.eps
        offs = [eps * (a * n1 + b * n2) for a in (1, -1) for b in (1, -1)]

        def where(t):
            return p0 + np.asarray(t)[:, None] * (p1 - p0)

        def state(t):
            B = where(t)
            return self._probe_state(B, [np.broadcast_to(o, B.shape) for o in offs], _is_edge)

        return _Curve("seg", i, "edge", where, state)

    def _cylinder_curves(self, i: int, s: Shape) -> list[_Curve]:
        d, eps = self.d, self.solid.eps
        along = abs(s.a @ d)
        if along > 1 - 1e-9:  # seen end-on: the round surface draws as a circle
            h, v = self.h, self.v

            def where(t):
                t = np.asarray(t)
                return s.c + s.r * (np.cos(t)[:, None] * h + np.sin(t)[:, None] * v)

            def state(t):
                t = np.asarray(t)
                n = np.cos(t)[:, None] * h + np.sin(t)[:, None] * v
                full = np.full(len(t), s.hl)
                return self._sweep_state(where(t), n, -full, full)

            c2 = self.project(s.c)
            return [_Curve("arc", i, "lateral", where, state, 2 * math.pi, (c2[0], c2[1]), s.r)]
        out = []
        m = np.cross(s.a, d)
        m /= np.linalg.norm(m)
        for sign in (-1.0, 1.0):  # the two silhouette lines, where the surface turns away
            n = sign * m
            p0, p1 = s.c + s.r * n - s.hl * s.a, s.c + s.r * n + s.hl * s.a

            def where(t, p0=p0, p1=p1):
                return p0 + np.asarray(t)[:, None] * (p1 - p0)

            def state(t, n=n, where=where):
                B = where(t)
                offs = [np.broadcast_to(eps * n, B.shape), np.broadcast_to(-eps * n, B.shape)]
                return self._probe_state(B, offs, lambda occ: occ[0] != occ[1])

            out.append(_Curve("seg", i, "silhouette", where, state))
        for end in (-1.0, 1.0):
            out.append(self._disc(i, s, end) if along < 1e-9 else self._rim(i, s, end))
        return out

    def _disc(self, i, s, end) -> _Curve:
        """An end face of a cylinder seen edge-on: a segment across it."""
        d = self.d
        n = end * s.a
        cf = s.c + end * s.hl * s.a
        w = np.cross(n, d)
        w /= np.linalg.norm(w)

        def where(t):
            return cf + (s.r * (2 * np.asarray(t) - 1))[:, None] * w

        def state(t):
            B = where(t)
            half = np.sqrt(np.maximum(s.r ** 2 - np.sum((B - cf) ** 2, axis=1), 0.0))
            return self._sweep_state(B, np.broadcast_to(n, B.shape), -half, half)

        return _Curve("seg", i, "face", where, state)

    def _rim(self, i, s, end) -> _Curve:
        """An end circle of a cylinder seen at a slant: an ellipse, treated as an edge."""
        eps = self.solid.eps
        e1 = np.cross(s.a, [0.0, 0.0, 1.0] if abs(s.a[2]) < 0.9 else [1.0, 0.0, 0.0])
        e1 /= np.linalg.norm(e1)
        e2 = np.cross(s.a, e1)
        ce = s.c + end * s.hl * s.a

        def where(t):
            t = np.asarray(t)
            return ce + s.r * (np.cos(t)[:, None] * e1 + np.sin(t)[:, None] * e2)

        def state(t):
            t = np.asarray(t)
            radial = np.cos(t)[:, None] * e1 + np.sin(t)[:, None] * e2
            offs = [eps * (a * end * s.a + b * radial) for a in (1, -1) for b in (1, -1)]
            return self._probe_state(where(t), offs, _is_edge)

        return _Curve("poly", i, "edge", where, state, 2 * math.pi)


def _is_edge(occ: list[np.ndarray]) -> np.ndarray:
    """From the material in the four quadrants around a line (++, +-, -+, --): an edge unless
    all four agree or the material fills exactly one half (a flat face through the line)."""
    pp, pm, mp, mm_ = occ
    same = (pp == pm) & (pm == mp) & (mp == mm_)
    half = ((pp == pm) & (mp == mm_) & (pp != mp)) | ((pp == mp) & (pm == mm_) & (pp != pm))
    return ~same & ~half


def _runs(f, lo: float, hi: float, n: int, periodic: bool = False) -> list[tuple[float, float, int]]:
    """Split [lo, hi] into runs where the integer function f is constant; run ends are bisected."""
    t = lo + (hi - lo) * (np.arange(n) + 0.5) / n
    s = np.asarray(f(t))
    cut = np.nonzero(s[1:] != s[:-1])[0]
    a, b, sa = t[cut], t[cut + 1], s[cut]
    for _ in range(16 if len(cut) else 0):
        m = (a + b) / 2
        same = np.asarray(f(m)) == sa
        a, b = np.where(same, m, a), np.where(same, b, m)
    edges = [lo, *((a + b) / 2).tolist(), hi]
    states = [int(s[0]), *(int(x) for x in s[cut + 1])]
    runs = [(edges[i], edges[i + 1], states[i]) for i in range(len(states))]
    if periodic and len(runs) > 1 and runs[0][2] == runs[-1][2]:
        first, last = runs.pop(0), runs.pop()
        runs.append((last[0], first[1] + (hi - lo), first[2]))
    return runs


def _tidy(runs, length) -> list[tuple[float, float, int]]:
    """Give runs shorter than MIN_RUN their neighbours' state (or none), then merge equal runs."""
    runs = list(runs)
    for i, (t0, t1, s) in enumerate(runs):
        if length(t0, t1) >= MIN_RUN:
            continue
        prev = runs[i - 1][2] if i > 0 else None
        nxt = runs[i + 1][2] if i + 1 < len(runs) else None
        if prev is None and nxt is None:
            continue
        if prev is not None and nxt is not None:
            new = prev if prev == nxt else 0  # a blip inside a line takes the line's state
        elif s == 0:
            new = prev if nxt is None else nxt  # a sliver of gap at an end: the line runs on
        else:
            new = 0  # a sliver of line at an end
        runs[i] = (t0, t1, new)
    merged = []
    for r in runs:
        if merged and merged[-1][2] == r[2]:
            merged[-1] = (merged[-1][0], r[1], r[2])
        else:
            merged.append(r)
    return merged


def _curve_points(curve: _Curve, proj: Projector, t0: float, t1: float, step: float) -> np.ndarray:
    """The run's 2D points (metres), enough to follow it within a fraction of `step`."""
    if curve.kind == "seg":
        return proj.project(curve.where(np.array([t0, t1])))
    if curve.kind == "arc":
        n = max(3, int(math.ceil(curve.radius * (t1 - t0) / step)) + 1)
    else:
        rough = proj.project(curve.where(np.linspace(t0, t1, 17)))
        n = max(3, int(math.ceil(np.linalg.norm(np.diff(rough, axis=0), axis=1).sum() / step)) + 1)
    return proj.project(curve.where(np.linspace(t0, t1, n)))


def _length_fn(curve: _Curve, proj: Projector, k: float):
    """Sheet length (mm) of a piece [t0, t1] of the curve."""
    def length(t0, t1):
        pts = _curve_points(curve, proj, t0, t1, 1.0 / k)
        return k * float(np.linalg.norm(np.diff(pts, axis=0), axis=1).sum())
    return length


def _cover_test(geoms: list, tol: float):
    """A function telling which 2D points lie within `tol` of lines already drawn."""
    if not geoms:
        return lambda P: np.zeros(len(P), dtype=bool)
    tree = shapely.STRtree(geoms)

    def covered(P):
        hits = tree.query(shapely.points(P), predicate="dwithin", distance=tol)
        out = np.zeros(len(P), dtype=bool)
        out[hits[0]] = True
        return out

    return covered


def trace_view(solid: Solid, view: str, k: float) -> ViewLines:
    """All lines of one view at k sheet-mm per metre: visible and hidden runs, centre lines."""
    proj = Projector(solid, view)
    traced = []  # (curve, runs, sheet length)
    for curve in proj.curves():
        length = _length_fn(curve, proj, k)
        span = length(0.0, curve.period)
        if span < MIN_RUN:
            continue
        n = max(8, int(math.ceil(span / SAMPLE_STEP)))
        runs = _runs(curve.state, 0.0, curve.period, n, periodic=curve.period != 1.0)
        traced.append((curve, _tidy(runs, length), span))
    lines = ViewLines()
    drawn: list = []
    lines.visible = _undrawn(traced, 2, proj, k, drawn)
    lines.hidden = _undrawn(traced, 1, proj, k, drawn)  # a visible line hides a hidden one
    lines.centre = _centre_lines(proj, traced, k)
    return lines


def _undrawn(traced, state: int, proj: Projector, k: float, drawn: list) -> list:
    """The runs in `state` minus whatever lies on a line already drawn (which `drawn` collects),
    longest candidates first, so that a short line lying on a long one is the one dropped."""
    out = []
    for curve, runs, _ in sorted(traced, key=lambda c: -c[2]):
        length = _length_fn(curve, proj, k)
        for t0, t1, s in runs:
            if s != state:
                continue
            covered = _cover_test(drawn, 0.1 / k)

            def on_drawn(t, curve=curve, covered=covered):
                return covered(proj.project(curve.where(t))).astype(int)

            n = max(4, int(math.ceil(length(t0, t1) / SAMPLE_STEP)))
            for a, b, c in _tidy(_runs(on_drawn, t0, t1, n), length):
                if c == 0:
                    out.append((curve, a, b))
                    drawn.append(LineString(_curve_points(curve, proj, a, b, SAMPLE_STEP / k)))
    return out


def _centre_lines(proj: Projector, traced, k: float) -> list:
    """Centre lines of every cylinder that is part of the solid: a cross where it is seen end-on,
    its axis over its drawn length otherwise; a pitch circle through equal holes on a circle."""
    ext = CENTRE_EXT / k
    lines, ends = [], []  # ends: (centre, radius) of the cylinders seen end-on
    for i, s in enumerate(proj.solid.shapes):
        if s.kind != "cyl":
            continue
        mine = [(c, [r for r in runs if r[2]]) for c, runs, _ in traced if c.shape == i]
        mine = [(c, runs) for c, runs in mine if runs and c.role in ("lateral", "silhouette")]
        if not mine:
            continue
        if mine[0][0].role == "lateral":
            c2 = proj.project(s.c)
            reach = s.r + ext
            lines.append((c2 - [reach, 0], c2 + [reach, 0]))
            lines.append((c2 - [0, reach], c2 + [0, reach]))
            ends.append((c2, s.r))
            continue
        ts = [t for _, runs in mine for r in runs for t in r[:2]]
        a0, a1 = s.c + (2 * min(ts) - 1) * s.hl * s.a, s.c + (2 * max(ts) - 1) * s.hl * s.a
        p, q = proj.project(a0), proj.project(a1)
        u = (q - p) / max(np.linalg.norm(q - p), 1e-12)
        lines.append((p - ext * u, q + ext * u))
    out = [("line", p, q) for p, q in _merge_collinear(lines)]
    out += [("circle", c, r) for c, r in _pitch_circles(ends)]
    return out


def _merge_collinear(lines) -> list:
    """Join centre lines that lie on one line and overlap (a hole's cross on the wheel's axis)."""
    groups: dict = {}
    for p, q in lines:
        u = (q - p) / np.linalg.norm(q - p)
        if u[0] < -1e-9 or (abs(u[0]) <= 1e-9 and u[1] < 0):
            u = -u
        key = (round(float(u[0]), 6), round(float(u[1]), 6), round(float(u[0] * p[1] - u[1] * p[0]), 7))
        groups.setdefault(key, []).append(sorted((float(p @ u), float(q @ u))))
    out = []
    for (ux, uy, off), spans in groups.items():
        u, nrm = np.array([ux, uy]), np.array([-uy, ux])
        spans.sort()
        merged = [spans[0]]
        for a, b in spans[1:]:
            if a <= merged[-1][1] + 1e-9:
                merged[-1][1] = max(merged[-1][1], b)
            else:
                merged.append([a, b])
        out += [(a * u + off * nrm, b * u + off * nrm) for a, b in merged]
    return out


def _pitch_circles(ends) -> list:
    """Three or more equal circles whose centres lie on one circle: that circle (a PCD)."""
    groups: dict = {}
    for c, r in ends:
        groups.setdefault(round(r, 7), []).append(c)
    out = []
    for centres in groups.values():
        pts = np.unique(np.round(np.array(centres), 9), axis=0)  # a hole seen twice is one hole
        if len(pts) < 3:
            continue
        mid = pts.mean(axis=0)
        dist = np.linalg.norm(pts - mid, axis=1)
        if dist.min() > 1e-6 and dist.max() - dist.min() < 1e-6:
            out.append((mid, float(dist.mean())))
    return out


def view_prims(lines: ViewLines, proj: Projector, k: float) -> list:
    """Sheet primitives (mm, about the part's origin, y down) of a traced view."""
    def sheet(p):
        return float(k * p[0]), float(-k * p[1])

    out = []
    for style, runs in (("visible", lines.visible), ("hidden", lines.hidden)):
        for curve, t0, t1 in runs:
            if curve.kind == "seg":
                (x1, y1), (x2, y2) = (sheet(p) for p in proj.project(curve.where(np.array([t0, t1]))))
                out.append(Line(x1, y1, x2, y2, style))
            elif curve.kind == "arc":
                cx, cy = sheet(curve.centre)
                if t1 - t0 >= 2 * math.pi - 1e-9:
                    out.append(Circle(cx, cy, k * curve.radius, style))
                else:
                    out.append(Arc(cx, cy, k * curve.radius, t0, t1, style))
            else:
                line = LineString(k * _curve_points(curve, proj, t0, t1, 0.2 / k) * [1, -1]).simplify(0.05)
                out.append(Poly((tuple(map(tuple, np.asarray(line.coords))),), False, style))
    for kind, a, b in lines.centre:
        if kind == "line":
            (x1, y1), (x2, y2) = sheet(a), sheet(b)
            out.append(Line(x1, y1, x2, y2, "centre"))
        else:
            cx, cy = sheet(a)
            out.append(Circle(cx, cy, k * b, "centre"))
    return out
