"""The effort a ROS controller puts on a joint in Gazebo, as a law MuJoCo integrates.

Between an `effort_controllers` command and the force on the joint, ROS 1 (Noetic) does:

1. The controller. `JointPositionController` clamps the command to the URDF's
   `<limit lower upper>` (revolute and prismatic joints) and runs a PID on the position
   error; `JointVelocityController` runs one on the velocity error; `JointEffortController`
   passes the command on. For a steady position command the D term on the error's rate
   is `-d * velocity`. The integral term is control_toolbox's `Pid::computeCommand`: the
   error summed over time, its term `i * sum` clamped to `i_clamp`; with `antiwindup`
   the sum itself is held where the term reaches `i_clamp`, so it cannot wind up.
2. gazebo_ros_control's `DefaultRobotHWSim` (default_robot_hw_sim.cpp, registerJointLimits
   and writeSim) reads each transmission joint's `<limit>` (joint_limits_urdf.h: position
   limits for revolute and prismatic joints only, velocity and effort for every joint)
   and `<safety_controller>`, and registers for an effort joint one of two handles of
   joint_limits_interface.h, enforced before every `SetForce`:

   - with a `<safety_controller>`: `EffortJointSoftLimitsHandle`. The speed allowed
     towards each soft limit is `clamp(-k_position * (q - soft_limit), -velocity,
     velocity)` (continuous joints: plus or minus the velocity limit); the effort is then
     clamped between `clamp(-k_velocity * (v - lowest speed), -effort, effort)` and
     `clamp(-k_velocity * (v - highest speed), -effort, effort)`. The velocity limit is
     held by a spring on the speed, k_velocity N (or N·m) per m/s (rad/s) over it.
   - without: `EffortJointSaturationHandle`. The effort is clamped to plus or minus the
     effort limit, and to zero in the direction that goes further past a position limit
     or past the velocity limit, once the joint is past it. The velocity limit is a gate
     there, not a spring: under it the full effort is allowed.

3. Gazebo's own `Joint::SetForce` clamps again to the effort limit and zeroes an effort
   that pushes further past the velocity limit; after either handle that changes nothing.

Each piece of these laws is affine in the joint's position q and velocity v, so the
effort at a state is `c0 + cq * q + cv * v` for the piece active there. World sets its
actuator to that piece at every step, which lets MuJoCo integrate the velocity term
implicitly, as it does a position actuator's damping (the integral term is a constant
within a step). Not modelled: the D term's kick when the command jumps, the parameter server's `joint_limits/`
and position or velocity interfaces.
"""

from __future__ import annotations

import dataclasses

from ..ros_control import JointLimits, read_joint_limits

# effort = c0 + cq * q + cv * v
Law = tuple[float, float, float]

POSITION = "effort_controllers/JointPositionController"
VELOCITY = "effort_controllers/JointVelocityController"
EFFORT = "effort_controllers/JointEffortController"
POSITIONAL = ("revolute", "prismatic")


@dataclasses.dataclass(frozen=True)
class Handle:
    """What DefaultRobotHWSim registers for one joint: its limits, and whether they include
    a position range (revolute and prismatic joints)."""

    limits: JointLimits
    positional: bool

    @property
    def soft(self) -> bool:
        return self.limits.has_soft_limits


def handles(package) -> dict[str, Handle]:
    """The joints of a Package that get a limits handle: those whose `<limit>` gives an
    effort and a velocity (a handle cannot be made without both)."""
    kinds = {j.get("name"): j.get("type") for j in package.robot.findall("joint")}
    return {name: Handle(limits, kinds.get(name) in POSITIONAL)
            for name, limits in read_joint_limits(package).items()
            if limits.effort is not None and limits.velocity is not None}


def value(law: Law, q: float, v: float) -> float:
    """The effort the law gives at (q, v)."""
    return law[0] + law[1] * q + law[2] * v


def saturate(law: Law, low: float, high: float, q: float, v: float) -> Law:
    """The piece of joint_limits_interface's `saturate(law, low, high)`, which is
    `min(max(law, low), high)`, that holds at (q, v)."""
    x = value(law, q, v)
    if max(x, low) > high:
        return (high, 0.0, 0.0)
    return (low, 0.0, 0.0) if x < low else law


def command(kind: str, setpoint: float, handle: Handle | None) -> float:
    """The set point a controller works to: a position controller's clamped into the
    joint's position limits, as JointPositionController::enforceJointLimits does."""
    if kind != POSITION or handle is None or not handle.positional:
        return setpoint
    lower, upper = handle.limits.lower or 0.0, handle.limits.upper or 0.0
    return min(max(setpoint, lower), upper)


def controller(kind: str, pid: dict, setpoint: float) -> Law:
    """The controller's effort law (P and D) for a set point already clamped."""
    p, d = float(pid.get("p", 0.0)), float(pid.get("d", 0.0))
    if kind == POSITION:
        return (p * setpoint, -p, -d)
    if kind == VELOCITY:
        return (p * setpoint, 0.0, -p)
    return (setpoint, 0.0, 0.0)


def integral(pid: dict, total: float, error: float, dt: float) -> tuple[float, float]:
    """control_toolbox's integral term (pid.cpp, computeCommand): the new sum of the
    error over time and the term it gives, `i * sum`, within plus or minus `i_clamp`.
    Without antiwindup the term is clamped and the sum grows on; with it the sum is."""
    i = float(pid.get("i", 0.0))
    if not i:
        return total, 0.0
    clamp = abs(float(pid.get("i_clamp", 0.0)))
    total += error * dt
    if pid.get("antiwindup") in (True, "true", "True", 1):
        total = min(max(total, -clamp / abs(i)), clamp / abs(i))
        return total, i * total
    return total, min(max(i * total, -clamp), clamp)


def bounds(handle: Handle, q: float, v: float) -> tuple[Law, Law]:
    """The lowest and highest effort the joint's handle lets through at (q, v)."""
    return (_soft_bounds if handle.soft else _saturation_bounds)(handle, q, v)


def _saturation_bounds(handle: Handle, q: float, v: float) -> tuple[Law, Law]:
    """EffortJointSaturationHandle::enforceLimits."""
    lim = handle.limits
    low, high = -lim.effort, lim.effort
    if handle.positional:
        if q < (lim.lower or 0.0):
            low = 0.0
        elif q > (lim.upper or 0.0):
            high = 0.0
    if v < -lim.velocity:
        low = 0.0
    elif v > lim.velocity:
        high = 0.0
    return (low, 0.0, 0.0), (high, 0.0, 0.0)


def _soft_bounds(handle: Handle, q: float, v: float) -> tuple[Law, Law]:
    """EffortJointSoftLimitsHandle::enforceLimits."""
    lim = handle.limits
    top, kp, kv = lim.velocity, lim.k_position or 0.0, lim.k_velocity
    found = []
    for soft, fallback in ((lim.soft_lower, -top), (lim.soft_upper, top)):
        if handle.positional:
            speed = saturate((kp * (soft or 0.0), -kp, 0.0), -top, top, q, v)
        else:
            speed = (fallback, 0.0, 0.0)
        # -k_velocity * (v - speed)
        effort = (kv * speed[0], kv * speed[1], kv * speed[2] - kv)
        found.append(saturate(effort, -lim.effort, lim.effort, q, v))
    return found[0], found[1]


def effort(law: Law, handle: Handle | None, q: float, v: float) -> Law:
    """The controller's law after the joint's handle: the piece that holds at (q, v)."""
    if handle is None:
        return law
    low, high = bounds(handle, q, v)
    # min(max(law, low), high), with bounds that are laws themselves
    piece = low if value(law, q, v) < value(low, q, v) else law
    return high if value(piece, q, v) > value(high, q, v) else piece
