"""A joint trajectory as joint_trajectory_controller (Jazzy) follows it: the points of one
JointTrajectory message and the reference between them, interpolated as the controller's
`splines` method does (linear for points with positions only, cubic with velocities,
quintic with accelerations; the last point held).

Also what the controller checks a trajectory and a FollowJointTrajectory goal against,
as ros2_controllers 4.42.1 does (joint_trajectory_controller.cpp's
validate_trajectory_msg, tolerances.hpp): `refusal` (the message the controller logs
when it refuses one), the tolerances of the YAML's `constraints` and of a goal, and
`Goal`, an accepted goal while the controller follows it.
"""

from __future__ import annotations

import dataclasses
import math

# FollowJointTrajectory's result codes (control_msgs 5.8.0)
SUCCESSFUL, INVALID_GOAL, INVALID_JOINTS, OLD_HEADER_TIMESTAMP = 0, -1, -2, -3
PATH_TOLERANCE_VIOLATED, GOAL_TOLERANCE_VIOLATED = -4, -5
FLOAT_EPSILON = 1.1920928955078125e-07   # std::numeric_limits<float>::epsilon()
ERASE = -1.0                             # JointTolerance's "no tolerance"


def refusal(names, stamp: float, points, *, joints, partial: bool, nonzero_end: bool,
            effort: bool, now: float | None) -> str | None:
    """Why joint_trajectory_controller refuses this trajectory (its log line), or None.
    `points`: (time_from_start, positions, velocities, accelerations, effort) each;
    `stamp` 0 means "now". The checks and their order are validate_trajectory_msg's;
    the last one, a value that is not finite, is the stand-in's own (see below)."""
    names = list(names)
    if not partial and len(names) != len(joints):
        return "Joints on incoming trajectory don't match the controller joints."
    if not names:
        return "Empty joint names on incoming trajectory."
    if not points:
        return "Empty trajectory received."
    for name in names:
        if name not in joints:
            return f"Incoming joint {name} doesn't match the controller's joints."
    if len(set(names)) != len(names):   # upstream takes it, and mixes up the joints' values
        return (f"joint_names {names} names a joint twice: refused here (joint_trajectory_"
                "controller would take it and give one joint another's values)")
    if not nonzero_end:
        for name, velocity in zip(names, points[-1][2]):
            if abs(velocity) > FLOAT_EPSILON:
                return (f"Velocity of last trajectory point of joint {name} is not zero: "
                        f"{velocity:.15f}")
    if stamp != 0.0 and now is not None:
        end = stamp + points[-1][0]
        if end < now:
            return (f"Received trajectory with non-zero start time ({stamp:f}) that ends in "
                    f"the past ({end:f})")
    previous = 0.0
    for i, (t, *fields) in enumerate(points):
        if i > 0 and t <= previous:
            return (f"Time between points {i - 1} and {i} is not strictly increasing, it is "
                    f"{previous:f} and {t:f} respectively")
        previous = t
        for field, values, may_be_empty in zip(("positions", "velocities", "accelerations"),
                                               fields, (False, True, True)):
            if not (may_be_empty and not values) and len(values) != len(names):
                return (f"Mismatch between joint_names size ({len(names)}) and {field} "
                        f"({len(values)}) at point #{i}.")
        if not effort and fields[3]:
            return ("Trajectories with effort fields are only supported for controllers "
                    "using the 'effort' command interface.")
    # joint_trajectory_controller 4.42.1 takes NaN and infinities as they are: the
    # reference becomes NaN, control_toolbox's PID answers NaN ("Received a non-finite
    # error/error_dot value") and the joint's command is NaN. The stand-in refuses it.
    for i, (t, *fields) in enumerate(points):
        for field, values in zip(("positions", "velocities", "accelerations", "effort"),
                                 fields):
            for name, x in zip(names, values):
                if not math.isfinite(x):
                    return (f"points[{i}].{field} of joint {name} is {x}: refused here "
                            "(joint_trajectory_controller 4.42.1 does not check for it and "
                            "would command the joint with NaN)")
    return None


def constraints(params: dict) -> dict:
    """The controller's `constraints` parameters, nested or flattened
    (`constraints.goal_time`, `constraints.joint.goal`)."""
    found = params.get("constraints")
    found = {k: (dict(v) if isinstance(v, dict) else v)
             for k, v in found.items()} if isinstance(found, dict) else {}
    for key, value in params.items():
        if isinstance(key, str) and key.startswith("constraints."):
            *path, last = key.split(".")[1:]
            place = found
            for part in path:
                place = place.setdefault(part, {})
            place[last] = value
    return found


@dataclasses.dataclass
class Tolerances:
    """SegmentTolerances: per joint, (position, velocity, acceleration) while the
    trajectory runs (`path`) and past its last point (`goal`), 0 meaning not checked; and
    how long after the last point's time the goal may take (`goal_time`, 0: as long as
    it takes)."""

    path: list
    goal: list
    goal_time: float


def default_tolerances(params: dict, joints, where: str = "constraints") -> Tolerances:
    """get_segment_tolerances(params): `constraints.goal_time` (0),
    `stopped_velocity_tolerance` (0.01, the goal's velocity), and per joint
    `<joint>.trajectory` and `<joint>.goal` (positions, 0)."""
    c = constraints(params)

    def number(value, key):
        try:
            return float(value)
        except (TypeError, ValueError):
            raise ValueError(f"{where}.{key}: {value!r} is not a number") from None
    goal_time = number(c.get("goal_time", 0.0), "goal_time")
    if goal_time < 0:
        raise ValueError(f"{where}.goal_time: {goal_time} must be >= 0")
    stopped = number(c.get("stopped_velocity_tolerance", 0.01), "stopped_velocity_tolerance")
    path, goal = [], []
    for joint in joints:
        mine = c.get(joint) if isinstance(c.get(joint), dict) else {}
        path.append((number(mine.get("trajectory", 0.0), f"{joint}.trajectory"), 0.0, 0.0))
        goal.append((number(mine.get("goal", 0.0), f"{joint}.goal"), stopped, 0.0))
    return Tolerances(path, goal, goal_time)


def _resolve(default: float, value: float) -> float:
    """resolve_tolerance_source: > 0 replaces the default, -1 erases it, 0 keeps it."""
    if value > 0.0:
        return value
    if abs(value - ERASE) < FLOAT_EPSILON:
        return 0.0
    if value < 0.0:
        raise ValueError
    return default


def goal_tolerances(default: Tolerances, path, goal, goal_time: float, joints):
    """get_segment_tolerances(default, goal): (Tolerances, the error logged or None).
    `path` and `goal`: (name, position, velocity, acceleration) per JointTolerance.
    Any bad entry gives the defaults, as upstream."""
    try:
        time = _resolve(default.goal_time, goal_time)
    except ValueError:
        return default, (f"Specified illegal goal_time_tolerance: {goal_time:f}. Using "
                         "default tolerances")
    found = Tolerances(list(default.path), list(default.goal), time)
    for field, entries, table in (("path_tolerance", path, found.path),
                                  ("goal_tolerance", goal, found.goal)):
        for name, *values in entries:
            if name not in joints:
                return default, (f"joint '{name}' specified in goal.{field} does not exist. "
                                 "Using default tolerances.")
            k = list(joints).index(name)
            resolved = []
            for interface, before, value in zip(("position", "velocity", "acceleration"),
                                                table[k], values):
                try:
                    resolved.append(_resolve(before, value))
                except ValueError:
                    return default, (f"joint '{name}' specified in goal.{field} has a invalid "
                                     f"{interface} tolerance. Using default tolerances.")
            table[k] = tuple(resolved)
    return found, None


def violations(error, tolerance) -> list[str]:
    """check_state_tolerance_per_joint: what of (position, velocity, acceleration)
    `error` exceeds its non-zero tolerance, as the controller logs it."""
    return [f"{name} Error: {e:f}, {name} Tolerance: {tol:f}"
            for name, e, tol in zip(("Position", "Velocity", "Acceleration"), error, tolerance)
            if tol > 0.0 and abs(e) > tol]


class Goal:
    """An accepted FollowJointTrajectory goal while the controller follows it.
    `end(outcome, error_code, error_string)` is called once, outcome "succeeded",
    "aborted" or "canceled"; `feedback(data)` with the update's feedback, at most once
    every `period` s of simulated time (the action monitor's rate, 20 Hz by default)."""

    def __init__(self, end, feedback=None, period: float = 0.05):
        self._end, self._feedback, self.period = end, feedback, period
        self.ended = False
        self.next_feedback = -math.inf

    def finish(self, outcome: str, code: int = SUCCESSFUL, text: str = "") -> None:
        if not self.ended:
            self.ended = True
            self._end(outcome, code, text)

    def report(self, now: float, data) -> None:
        if self._feedback is not None and not self.ended and now >= self.next_feedback - 1e-9:
            following = self.next_feedback + self.period   # on the grid of the first
            self.next_feedback = following if following > now else now + self.period
            self._feedback(data)


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
