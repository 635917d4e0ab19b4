"""A joint's position limits as a hard stop, the way Gazebo Sim's physics holds them.

Gazebo Sim's DART engine treats a joint's `<limit lower upper>` as a constraint of the
step's velocity with an unbounded impulse (gz-physics sets every joint's limits enforced;
DART's JointConstraint): the joint stops at its limit whatever effort pushes it.

A MuJoCo limit is a soft constraint. At steady state, pushed with an acceleration `a0`
(the joint's effort over its effective inertia), it sinks in by about
`(1 - d) * a0 * timeconst**2` for a constant impedance d and a critically damped
reference of time constant `timeconst`. MuJoCo's defaults (timeconst 0.02 s, d from 0.9
to 0.95) let Practice 3's end arm, 1000 N·m on 0.0025 kg·m², sink in 8 rad. So each
limited hinge or slide joint gets:

- `solreflimit` = (2 time steps, 1): the shortest time constant MuJoCo accepts in this
  form (a shorter one is raised to it, for the integrator's sake), critically damped;
- `solimplimit` = (d, d, ...), one impedance at any depth, the smallest in
  [MuJoCo's default 0.95, MuJoCo's maximum 0.9999] that keeps the steady depth under the
  joint's own effort limit within HOLD (a tenth of the 0.02 the stop must hold to, for
  gravity and the other joints' push); a joint without an effort limit gets 0.9999;
- `margin` MARGIN: a joint that stands exactly at its limit counts as touching it, so
  that a push that starts there is held from the first step.

What stiffness cannot give: MuJoCo looks at a limit at the start of each step, so a joint
that reaches its limit at speed v first passes it by up to one step's travel, v times the
time step, and is back within a few steps. Gazebo avoids that with its velocity limit,
which MuJoCo has no place for (`sw2sim ros2` applies it, sw2sim.ros2.hardware).
"""

from __future__ import annotations

import math

import mujoco

HOLD = 0.002           # rad or m: the steady depth allowed under the joint's full effort
MARGIN = 1e-6          # rad or m: the distance from the limit at which it is touched
DAMPING_RATIO = 1.25
LEAST_IMPEDANCE = 0.95       # MuJoCo's default impedance at depth
MOST_IMPEDANCE = 0.9999      # mjMAXIMP: MuJoCo clamps anything above it


def stiffen(spec: mujoco.MjSpec, model: mujoco.MjModel) -> dict[str, tuple[float, float]]:
    """Set the limit parameters of every limited hinge or slide joint of `spec`;
    `model` is `spec` compiled (its effort ranges and inertias are read). Returns, by
    joint name, the (timeconst, impedance) chosen."""
    timeconst = 2 * float(model.opt.timestep)
    moving = (int(mujoco.mjtJoint.mjJNT_HINGE), int(mujoco.mjtJoint.mjJNT_SLIDE))
    chosen = {}
    for j in range(model.njnt):
        if model.jnt_type[j] not in moving or not model.jnt_limited[j]:
            continue
        name = model.joint(j).name
        effort = (float(abs(model.jnt_actfrcrange[j]).max())
                  if model.jnt_actfrclimited[j] else math.inf)
        d = impedance(effort * float(model.dof_invweight0[model.jnt_dofadr[j]]), timeconst)
        joint = spec.joint(name)
        joint.solref_limit = [timeconst, DAMPING_RATIO]
        joint.solimp_limit = [d, d, 0.001, 0.5, 2.0]
        joint.margin = MARGIN
        chosen[name] = (timeconst, d)
    return chosen


def impedance(acceleration: float, timeconst: float) -> float:
    """The least impedance d that holds a push of `acceleration` (rad/s² or m/s²) to a
    steady depth of HOLD: (1 - d) * acceleration * timeconst² = HOLD."""
    if not math.isfinite(acceleration):
        return MOST_IMPEDANCE
    if acceleration <= 0:
        return LEAST_IMPEDANCE
    need = 1.0 - HOLD / (acceleration * timeconst ** 2 * DAMPING_RATIO ** 2)
    return min(MOST_IMPEDANCE, max(LEAST_IMPEDANCE, need))

