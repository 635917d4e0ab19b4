"""From a joint's command interfaces to the force MuJoCo applies: what gz_ros2_control
(Jazzy, gz_system.cpp `write`) and Gazebo Sim's DART physics do.

- `velocity` command: Gazebo's JointVelocityCmd, a servo that DART drives to the velocity
  with a force limited to the URDF's `<limit effort>`. Here: a damping law
  `K (v_cmd - v)` with K ten times the joint's inertia over the time step (the velocity
  is reached within a few steps), clamped to plus or minus the effort limit.
- `position` command: gz_ros2_control turns it into a velocity command,
  `position_proportional_gain * update_rate * (q_cmd - q)` (the plugin's gain, 0.1 by
  default, times the controller manager's rate), then as above.
- `effort` command: Gazebo's JointForceCmd; DART clamps it to the effort limit.
  With the controller manager's `enforce_command_limits: true` (false by default in
  Jazzy), ros2_control's saturation limiter clamps it first to the smaller of the URDF
  effort and the ros2_control interface's `min`/`max` params.
- A joint with command interfaces that no active controller claims is held: a zero
  velocity command (gz_ros2_control's `hold_joints`, true by default).

A joint's commands are taken in gz_system's order: velocity, then position, then effort.
Every law is affine in the joint's position q and velocity v, `c0 + cq q + cv v`, so that
MuJoCo integrates its velocity term implicitly (sw2sim.ros.hardware does the same for
ROS 1). Not modelled: the joint limiters' position and velocity rules, mimic joints.
"""

from __future__ import annotations

import math

from ..ros.hardware import Law, saturate

SERVO_STIFFNESS = 10.0   # the velocity servo's K, in joint inertias per time step


def clamp_law(law: Law, limit: float, q: float, v: float) -> Law:
    if not math.isfinite(limit):
        return law
    return saturate(law, -limit, limit, q, v)


def servo(target: Law, inertia: float, dt: float) -> Law:
    """K (target - v) for a velocity target that is itself affine in q (and v)."""
    k = SERVO_STIFFNESS * inertia / dt
    return (k * target[0], k * target[1], k * (target[2] - 1.0))


def joint_law(commands: dict, q: float, v: float, *, effort_limit: float, inertia: float,
              dt: float, position_gain: float, enforce: bool, interface_limits: dict) -> Law:
    """The force law for one joint given the values its active controllers wrote:
    `commands` maps an interface name to a number or to an effort Law; empty when no
    controller claims the joint (held)."""
    if "velocity" in commands:
        law = servo((float(commands["velocity"]), 0.0, 0.0), inertia, dt)
    elif "position" in commands:
        g = position_gain
        law = servo((g * float(commands["position"]), -g, 0.0), inertia, dt)
    elif "effort" in commands:
        law = commands["effort"]
        if not isinstance(law, tuple):
            law = (float(law), 0.0, 0.0)
        if enforce:
            low, high = interface_limits.get("effort", (-math.inf, math.inf))
            bound = min(effort_limit, abs(low), abs(high))
            law = clamp_law(law, bound, q, v)
    else:
        law = servo((0.0, 0.0, 0.0), inertia, dt)
    return clamp_law(law, effort_limit, q, v)
