"""A joint trajectory as joint_trajectory_controller (Jazzy) follows it: the points of one
JointTrajectory message and the reference between them, interpolated as the controller's
`splines` method does (linear for points with positions only, cubic with velocities,
quintic with accelerations; the last point held)."""

from __future__ import annotations


class Trajectory:
    """One received JointTrajectory, in the controller's joint order: times (s, from its
    start) and per point (positions, velocities or None, accelerations or None)."""

    def __init__(self, start: float | None, times, points):
        self.start, self.times, self.points = start, times, points
        self.before = None           # (time, positions, velocities): the state at the start

    def sample(self, t: float):
        """(positions, velocities, accelerations) at time t, as JTC's splines give them."""
        n = len(self.before[1])
        t0, p0, v0 = self.before
        first = self.start + self.times[0]
        if t < first:
            pos, vel, acc = self.points[0]
            start_vel = (v0 or [0.0] * n) if vel is not None else None
            start_acc = [0.0] * n if acc is not None else None
            return _interpolate((p0, start_vel, start_acc), (pos, vel, acc), t - t0, first - t0)
        for i in range(len(self.times) - 1):
            ta, tb = self.start + self.times[i], self.start + self.times[i + 1]
            if ta <= t < tb:
                return _interpolate(self.points[i], self.points[i + 1], t - ta, tb - ta)
        pos, vel, acc = self.points[-1]
        return list(pos), list(vel or [0.0] * n), list(acc or [0.0] * n)


def _interpolate(a, b, s: float, span: float):
    (pa, va, aa), (pb, vb, ab) = a, b
    n = len(pa)
    has_velocity = va is not None and vb is not None
    has_acceleration = aa is not None and ab is not None
    if s <= 0:
        s, has_velocity, has_acceleration = 0.0, False, False
    if s >= span:
        s, has_velocity, has_acceleration = span, False, False
    positions, velocities, accelerations = [0.0] * n, [0.0] * n, [0.0] * n
    T = span
    for i in range(n):
        if not has_velocity and not has_acceleration:
            slope = (pb[i] - pa[i]) / T if T else 0.0
            positions[i], velocities[i] = pa[i] + slope * s, slope
        elif not has_acceleration:   # cubic through both positions and velocities
            c0, c1 = pa[i], va[i]
            c2 = c3 = 0.0
            if T:
                c2 = (-3 * pa[i] + 3 * pb[i] - 2 * va[i] * T - vb[i] * T) / T ** 2
                c3 = (2 * pa[i] - 2 * pb[i] + va[i] * T + vb[i] * T) / T ** 3
            positions[i] = c0 + c1 * s + c2 * s ** 2 + c3 * s ** 3
            velocities[i] = c1 + 2 * c2 * s + 3 * c3 * s ** 2
            accelerations[i] = 2 * c2 + 6 * c3 * s
        else:                        # quintic through positions, velocities, accelerations
            c0, c1, c2 = pa[i], va[i], 0.5 * aa[i]
            c3 = c4 = c5 = 0.0
            if T:
                T2, T3, T4, T5 = T ** 2, T ** 3, T ** 4, T ** 5
                c3 = (-20 * pa[i] + 20 * pb[i] - 3 * aa[i] * T2 + ab[i] * T2
                      - 12 * va[i] * T - 8 * vb[i] * T) / (2 * T3)
                c4 = (30 * pa[i] - 30 * pb[i] + 3 * aa[i] * T2 - 2 * ab[i] * T2
                      + 16 * va[i] * T + 14 * vb[i] * T) / (2 * T4)
                c5 = (-12 * pa[i] + 12 * pb[i] - aa[i] * T2 + ab[i] * T2
                      - 6 * va[i] * T - 6 * vb[i] * T) / (2 * T5)
            positions[i] = c0 + c1 * s + c2 * s ** 2 + c3 * s ** 3 + c4 * s ** 4 + c5 * s ** 5
            velocities[i] = c1 + 2 * c2 * s + 3 * c3 * s ** 2 + 4 * c4 * s ** 3 + 5 * c5 * s ** 4
            accelerations[i] = 2 * c2 + 6 * c3 * s + 12 * c4 * s ** 2 + 20 * c5 * s ** 3
    return positions, velocities, accelerations
