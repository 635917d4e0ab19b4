"""From a joint's command interfaces to the force MuJoCo applies: what gz_ros2_control
(Jazzy, gz_system.cpp `write`) and Gazebo Sim's DART physics do.

- `velocity` command: Gazebo's JointVelocityCmd, a servo that DART drives to the velocity
  (clipped to the URDF's `<limit velocity>` and to the speed that reaches a position
  limit in one step) with a force limited to the URDF's `<limit effort>`. Here: a damping
  law `K (v_cmd - v)` with K ten times the joint's inertia over the time step (the
  velocity is reached within a few steps), clamped to plus or minus the effort limit.
- `position` command: gz_ros2_control turns it into a velocity command,
  `position_proportional_gain * update_rate * (q_cmd - q)` (the plugin's gain, 0.1 by
  default, times the controller manager's rate), then as above.
- `effort` command: Gazebo's JointForceCmd; DART clamps it to the effort limit.
  With the controller manager's `enforce_command_limits: true` (false by default in
  Jazzy), ros2_control's saturation limiter clamps it first to the smaller of the URDF
  effort and the ros2_control interface's `min`/`max` params.
- A joint with command interfaces that no active controller claims gets what
  gz_system's `hold_joints` (true by default) and Gazebo Sim's kept command components
  give it (`JointCommand`, below): a velocity of 0, or, once an effort controller has
  driven it, no force at all.

A joint's commands are taken in gz_system's order: velocity, then position, then effort.
Every law is affine in the joint's position q and velocity v, `c0 + cq q + cv v`, so that
MuJoCo integrates its velocity term implicitly (sw2sim.ros.hardware does the same for
ROS 1). After each step, DART's joint constraints hold every joint's velocity within its
velocity limit and stop it on its position limits, whatever the effort (`constrain`,
below). Not modelled: the joint limiters' position and velocity rules, mimic joints.
"""

from __future__ import annotations

import dataclasses
import math

import mujoco
import numpy as np

from ..ros.hardware import Law, saturate
from ..ros_control import read_joint_limits

SERVO_STIFFNESS = 10.0   # the velocity servo's K, in joint inertias per time step


def clamp_law(law: Law, limit: float, q: float, v: float) -> Law:
    if not math.isfinite(limit):
        return law
    return saturate(law, -limit, limit, q, v)


def servo(target: Law, inertia: float, dt: float, q: float = 0.0,
          allowed: tuple[float, float] | None = (-math.inf, math.inf)) -> Law:
    """K (target - v) for a velocity target that is itself affine in q (and v), its value
    at q clipped to `allowed` (DART's clip, `servo_range`; None: no servo force)."""
    if allowed is None:
        return (0.0, 0.0, 0.0)
    at = target[0] + target[1] * q
    if not allowed[0] <= at <= allowed[1]:
        target = (min(max(at, allowed[0]), allowed[1]), 0.0, 0.0)
    k = SERVO_STIFFNESS * inertia / dt
    return (k * target[0], k * target[1], k * (target[2] - 1.0))


def joint_law(commands: dict, q: float, v: float, *, effort_limit: float, inertia: float,
              dt: float, position_gain: float, enforce: bool, interface_limits: dict,
              allowed: tuple[float, float] | None = (-math.inf, math.inf)) -> Law:
    """The force law for one joint given the values its active controllers wrote:
    `commands` maps an interface name to a number or to an effort Law; empty when no
    controller claims the joint (held). `allowed` is the servo's `servo_range`."""
    if "velocity" in commands:
        law = servo((float(commands["velocity"]), 0.0, 0.0), inertia, dt, q, allowed)
    elif "position" in commands:
        g = position_gain
        law = servo((g * float(commands["position"]), -g, 0.0), inertia, dt, q, allowed)
    elif "effort" in commands:
        law = commands["effort"]
        if not isinstance(law, tuple):
            law = (float(law), 0.0, 0.0)
        if enforce:
            low, high = interface_limits.get("effort", (-math.inf, math.inf))
            bound = min(effort_limit, abs(low), abs(high))
            law = clamp_law(law, bound, q, v)
    else:
        law = servo((0.0, 0.0, 0.0), inertia, dt, q, allowed)
    return clamp_law(law, effort_limit, q, v)


# -- DART's joint limits: what Gazebo Sim's physics does with the URDF's <limit> -------------
#
# sdformat turns a URDF `<limit>` into the SDF axis's lower, upper, effort and velocity
# (continuous joints: effort and velocity only, no position range). gz-physics' dartsim
# plugin gives them to DART, a negative effort or velocity as no limit, and enforces every
# joint's limits (SDFFeatures.cc, CopyStandardJointAxisProperties). Then DART, at each step,
# after adding the step's forces to the velocities and before moving the positions
# (World::step), holds each joint's velocity within a range (JointConstraint::update):
#
# - past a position limit: back towards it, at the speed that undoes the excess in one
#   step, at most MAX_ERROR_REDUCTION_VELOCITY, and not further out;
# - otherwise within plus or minus the velocity limit, and within the speed that reaches
#   each position limit in one step (so the joint lands on a limit, not past it);
# - with an impulse that has no bound: no effort limit applies to it.
# A force command is clipped to the effort limit (GenericJoint::setCommand); a velocity
# command (a servo) is clipped to the velocity limit there, then to the speed that reaches
# a position limit, and driven with at most the effort limit (JointConstraint::update).
# A joint past a position limit gets no servo force in that step.
#
# Here: `servo_range` clips the servo's target for joint_law; after MuJoCo's step, which
# moves the positions with the new velocities as DART does, `constrain` gives the joints
# whose velocity left its range the impulse that brings it back, solved together through
# the matrix the step itself used (`step_inverse`), and moves their positions by what it
# changed.

MAX_ERROR_REDUCTION_VELOCITY = 10.0   # DART's JointConstraint default, rad/s or m/s


@dataclasses.dataclass(frozen=True)
class Bounds:
    """One joint axis's limits as DART holds them (infinite where there are none)."""

    lower: float = -math.inf
    upper: float = math.inf
    velocity: float = math.inf
    effort: float = math.inf


def _no_limit_if_negative(value) -> float:
    """gz-physics' rule for an SDF effort or velocity: negative means none; a URDF
    `<limit>` without the attribute gives none either."""
    return math.inf if value is None or value < 0 else float(value)


def joint_bounds(package) -> dict[str, Bounds]:
    """Every revolute, prismatic and continuous joint's Bounds, by name, from a Package."""
    limits = read_joint_limits(package)
    found = {}
    for joint in package.robot.findall("joint"):
        name, kind = joint.get("name"), joint.get("type")
        if kind not in ("revolute", "prismatic", "continuous"):
            continue
        lim = limits.get(name)
        if lim is None:
            found[name] = Bounds()
            continue
        lower, upper = -math.inf, math.inf
        if kind != "continuous":
            lower, upper = sorted((lim.lower or 0.0, lim.upper or 0.0))   # sdformat swaps
        found[name] = Bounds(lower, upper, _no_limit_if_negative(lim.velocity),
                             _no_limit_if_negative(lim.effort))
    return found


def velocity_range(b: Bounds, q: float, dt: float) -> tuple[float, float]:
    """The velocity DART allows a joint at the end of a step that starts at position q."""
    if q < b.lower:
        return min((b.lower - q) / dt, MAX_ERROR_REDUCTION_VELOCITY), math.inf
    if q > b.upper:
        return -math.inf, max((b.upper - q) / dt, -MAX_ERROR_REDUCTION_VELOCITY)
    return max(-b.velocity, (b.lower - q) / dt), min(b.velocity, (b.upper - q) / dt)


def servo_range(b: Bounds, q: float, dt: float) -> tuple[float, float] | None:
    """The range a servo's target is clipped to; None past a position limit (no servo)."""
    if q < b.lower or q > b.upper:
        return None
    return velocity_range(b, q, dt)


def constrained_joints(model, bounds: dict[str, Bounds]) -> list[tuple[int, int, Bounds]]:
    """(qpos address, dof address, Bounds) of the joints of `model` that have limits, for
    `constrain`, which then holds them alone: MuJoCo's own limit constraints of these
    joints are switched off in `model` (two separate solves would each push for the other)."""
    joints = []
    for name, b in bounds.items():
        if b == Bounds():
            continue
        j = model.joint(name).id
        model.jnt_limited[j] = 0
        joints.append((int(model.jnt_qposadr[j]), int(model.jnt_dofadr[j]), b))
    return joints


def step_inverse(model, data) -> np.ndarray:
    """The inverse of the matrix that turned the step's forces into its change of velocity
    (after `mujoco.mj_step`, so at the step's start): M, less the time step times the
    velocity derivative of the forces for the implicit integrators (the actuators' laws
    damp implicitly), so that an impulse acts as the step's own forces did. DART applies
    its impulses through the inverse inertia after an explicit step; the same impulse
    through M alone would leave a joint held against its limit unable to move the link
    that carries it."""
    full = np.zeros((model.nv, model.nv))
    mujoco.mj_fullM(model, data, full)
    if model.opt.integrator in (mujoco.mjtIntegrator.mjINT_IMPLICIT,
                                mujoco.mjtIntegrator.mjINT_IMPLICITFAST) and model.nD:
        derivative = np.zeros((model.nv, model.nv))
        mujoco.mju_sparse2dense(derivative, data.qDeriv, model.D_rownnz, model.D_rowadr,
                                model.D_colind)
        if model.opt.integrator == mujoco.mjtIntegrator.mjINT_IMPLICITFAST:
            lower = np.tril(derivative)   # implicitfast keeps the lower half, symmetric
            derivative = lower + np.tril(derivative, -1).T
        full -= model.opt.timestep * derivative
    return np.linalg.inv(full)


def constrain(model, data, joints, positions) -> int:
    """After `mujoco.mj_step`: the impulses of DART's joint constraints. `joints` lists
    (qpos address, dof address, Bounds) of hinge and slide joints, `positions` their
    positions at the step's start. Returns how many joints it held.

    DART solves, in one go, the joints it found outside their range before solving; here a
    joint that the others' impulses push out of its range (an arm's reaction on the link
    that carries it) is held as well, so that every joint ends the step within its range."""
    dt = float(model.opt.timestep)
    velocities = data.qvel.tolist()
    ranges = [velocity_range(b, q, dt) for (_, _, b), q in zip(joints, positions)]
    if all(low <= velocities[dof] <= high for (_, dof, _), (low, high) in zip(joints, ranges)):
        return 0                             # (most steps: in plain Python, it is quicker)
    ranges = np.array(ranges)
    dofs = np.array([dof for _, dof, _ in joints], dtype=int)
    v = data.qvel[dofs].copy()
    columns = step_inverse(model, data)[:, dofs].T   # the change of every velocity that
    inverse = columns[:, dofs]                       # a unit impulse on each joint makes
    side = np.zeros(len(dofs), dtype=int)    # 0 free, -1 held at its lowest, +1 at its highest
    impulse = np.zeros(len(dofs))
    for _ in range(4 * len(dofs) + 1):
        moved = v + inverse @ impulse
        low, high = moved < ranges[:, 0] - 1e-12, moved > ranges[:, 1] + 1e-12
        pulling = ((side < 0) & (impulse < 0)) | ((side > 0) & (impulse > 0))
        if pulling.any():                    # an impulse may only push: let that joint go
            side[np.flatnonzero(pulling)[0]] = 0
        elif low.any() or high.any():
            side[low], side[high] = -1, 1
        else:
            break
        held = np.flatnonzero(side)
        impulse = np.zeros(len(dofs))
        if len(held):
            target = np.where(side[held] < 0, ranges[held, 0], ranges[held, 1])
            impulse[held] = np.linalg.solve(inverse[np.ix_(held, held)], target - v[held])
    dv = impulse @ columns
    data.qvel[:] += dv
    mujoco.mj_integratePos(model, data.qpos, dv, dt)
    return int(np.count_nonzero(side))


# -- gz_system's write and gz-sim's Physics: which command reaches a joint -------------------
#
# gz_ros2_control (1.2.7, gz_system.cpp `write`, every simulation step) looks at the joint's
# control modes, the command interfaces the active controllers claimed: velocity, else
# position (turned into a velocity), else effort, else, for a joint with command
# interfaces and `hold_joints` (true by default), a velocity of 0. Each writes a command
# component on the joint, created the first time (a velocity or effort component is created
# holding 0; the value follows from the next step on). Gazebo Sim's Physics (gz-sim8
# 8.10.0, what Jazzy's gz_sim_vendor builds; Physics.cc) then applies the force component
# if the joint has one, else the velocity component, and at the end of the step sets every
# command component to 0 without removing it. So a joint that was ever driven by effort gets a force from then on, 0 when nothing
# writes one (its velocity components are ignored), and is free once its controller is
# deactivated, whatever `hold_joints` says; a joint driven by velocity or position keeps a
# velocity command of 0 once nothing writes one, `hold_joints` or not; `hold_joints` alone
# decides for a joint that no controller has driven yet.


class JointCommand:
    """One joint's command components, as gz_system and gz-sim's Physics keep them."""

    def __init__(self, actuated: bool, hold: bool):
        self.actuated, self.hold = actuated, hold
        self.force = self.velocity = False   # JointForceCmd / JointVelocityCmd components exist

    def step(self, modes, values: dict) -> dict:
        """The command DART gets in this step, in joint_law's form ({"velocity": x},
        {"position": x} or {"effort": number or Law}); `modes` are the joint's claimed
        command interfaces, `values` what the command interfaces hold."""
        written = None
        if "velocity" in modes:
            written = {"velocity": values.get("velocity", 0.0) if self.velocity else 0.0}
            self.velocity = True
        elif "position" in modes:
            written, self.velocity = {"position": values.get("position", 0.0)}, True
        elif "effort" in modes:
            force = values.get("effort", 0.0) if self.force else 0.0
            self.force = True
            return {"effort": force}
        elif self.actuated and self.hold:
            written, self.velocity = {"velocity": 0.0}, True
        if self.force:   # the force component wins; nothing wrote it in this step
            return {"effort": 0.0}
        if self.velocity:
            return written or {"velocity": 0.0}
        return {"effort": 0.0}   # no command component: the joint is free


def finite_command(command: dict) -> dict:
    """gz-physics' dartsim plugin ignores a non-finite force or velocity command (and DART
    starts each step from a zero command): such a command becomes 0."""
    (kind, x), = command.items()
    numbers = x if isinstance(x, tuple) else (x,)
    return command if all(math.isfinite(n) for n in numbers) else {
        "effort" if kind == "effort" else "velocity": 0.0}
