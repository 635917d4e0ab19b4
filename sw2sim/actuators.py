"""MuJoCo actuators for a package's joints, from what ROS would drive them with.

MuJoCo's URDF import makes no actuators. A package for ros_control says how each joint
is driven in two places: a `<transmission>` per joint in the URDF, and the controllers
in `config/*.yaml`. From those:

- an `effort_controllers/JointPositionController` becomes a MuJoCo *position* actuator:
  kp is the controller's p and kv its d, the control range is the joint's limits;
- an `effort_controllers/JointVelocityController` becomes a *velocity* actuator with
  kv the controller's p, its control range the joint's velocity limit;
- a `velocity_controllers/JointVelocityController` (or each joint of a
  `JointGroupVelocityController`) forwards its command to the joint's velocity interface,
  which gazebo_ros_control turns into a velocity servo that Gazebo drives within the effort
  limit (`SetParam("vel")` with `fmax`, default_robot_hw_sim.cpp): a *velocity* actuator
  with a stiff kv (SERVO_STIFFNESS);
- a `velocity_controllers/JointPositionController` runs a PID on the position error and
  sends its output as that velocity command (ros_controllers 0.21.2,
  velocity_controllers/src/joint_position_controller.cpp): with the servo's K, the force
  K (p (target - q) - d v - v) is a *position* actuator with kp = K p and kv = K (1 + d);
- a transmission without such a controller becomes a *motor* whose control is the
  actuator's effort, geared by the mechanical reduction (as `ros_control.add_motors`);
- each actuator's force is limited to the joint's effort limit.

`sliders=True` (the viewer) also gives every other hinge or slide joint an actuator, so
the viewer's Control panel has a slider for it: a position actuator over the joint's
limits, or a velocity actuator for a joint without limits.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass
from pathlib import Path

import mujoco
import numpy as np

from .package import Package, as_package
from .ros_control import read_controllers, read_joint_limits, read_transmissions

POSITION_PID = "effort_controllers/JointPositionController"
VELOCITY_PID = "effort_controllers/JointVelocityController"
VELOCITY_FORWARD = ("velocity_controllers/JointVelocityController",
                    "velocity_controllers/JointGroupVelocityController")
POSITION_TO_VELOCITY = "velocity_controllers/JointPositionController"
KINDS = (POSITION_PID, VELOCITY_PID, *VELOCITY_FORWARD, POSITION_TO_VELOCITY)
# The velocity servo's K, in joint inertias per time step: Gazebo's joint motor reaches the
# commanded velocity within a step when the effort limit allows; MuJoCo's implicit damping
# with this K reaches 10/11 of it in one.
SERVO_STIFFNESS = 10.0
SLIDER_HZ = 2.0           # natural frequency of a viewer-only position actuator
SLIDER_TIME = 0.1         # s, time constant of a viewer-only velocity actuator
SLIDER_SPEED = 2 * math.pi  # rad/s or m/s, a velocity slider's range when the URDF gives none


@dataclass(frozen=True)
class Actuator:
    """One actuator added to the model, and where its settings came from."""

    name: str
    joint: str
    kind: str                 # "position", "velocity" or "motor"
    source: str               # in words, e.g. "block_controller in config/x.yaml"
    gains: str                # e.g. "kp 2000, kv 200"
    ctrlrange: tuple[float, float] | None
    forcerange: tuple[float, float] | None
    dropped: tuple[str, ...] = ()   # settings of the source MuJoCo has no place for


def controllers(source: str | os.PathLike | Package) -> dict[str, tuple[dict, Path]]:
    """The joint controllers in the package's config/*.yaml: name -> (settings, file).

    Controllers may sit at the top level or under one namespace (the robot's name, as
    the exporter's launch files use). Raises LoadError for a YAML file that is not valid.
    """
    root = as_package(source).root
    found: dict[str, tuple[dict, Path]] = {}
    files = sorted((root / "config").glob("*.yaml")) + sorted((root / "config").glob("*.yml"))
    for file in files:
        data = read_controllers(file)
        if not isinstance(data, dict):
            continue
        for name, value in data.items():
            if _is_controller(value):
                found.setdefault(str(name), (value, file))
            elif isinstance(value, dict):
                for inner, settings in value.items():
                    if _is_controller(settings):
                        found.setdefault(str(inner), (settings, file))
    return found


def _is_controller(value) -> bool:
    return isinstance(value, dict) and "type" in value and (
        isinstance(value.get("joint"), str) or isinstance(value.get("joints"), list))


def _joints_of(settings: dict) -> list[str]:
    """The joint a controller drives, or each of a group controller's joints."""
    if isinstance(settings.get("joint"), str):
        return [settings["joint"]]
    return [str(j) for j in settings.get("joints", ()) if isinstance(j, (str, int))]


def _gain(pid, key: str) -> float | None:
    """A PID gain as a finite number, or None."""
    if not isinstance(pid, dict):
        return None
    try:
        value = float(pid.get(key))
    except (TypeError, ValueError):
        return None
    return value if math.isfinite(value) else None


def add_actuators(spec: mujoco.MjSpec, source: str | os.PathLike | Package, *,
                  sliders: bool = False, leave=frozenset()) -> tuple[list[Actuator], list[str]]:
    """Add actuators to `spec` for the package at `source` (a path or a Package).

    Returns the actuators in `data.ctrl` order, and a sentence for each controller or
    transmission that was left out, and why; the joints in `leave` get none (a repair
    left them unactuated). Raises LoadError when the URDF's limits,
    the transmissions or the YAML cannot be read.
    """
    package = as_package(source)
    root = package.root
    model = spec.compile()
    moving = (int(mujoco.mjtJoint.mjJNT_HINGE), int(mujoco.mjtJoint.mjJNT_SLIDE))
    joints = {model.joint(j).name: j for j in range(model.njnt) if model.jnt_type[j] in moving}
    limits = read_joint_limits(package)
    inertia = joint_inertia(model)
    added: list[Actuator] = []
    skipped: list[str] = []
    driven: set[str] = set()

    def joint_range(joint):
        j = joints[joint]
        return tuple(float(x) for x in model.jnt_range[j]) if model.jnt_limited[j] else None

    def effort(joint):
        e = limits[joint].effort if joint in limits else None
        return (-e, e) if e and e > 0 and math.isfinite(e) else None

    def velocity(joint):
        v = limits[joint].velocity if joint in limits else None
        return (-v, v) if v and v > 0 and math.isfinite(v) else None

    def place(name, joint, kind, source, gains, ctrl, force, dropped=()):
        act = spec.add_actuator(name=name, target=joint, trntype=mujoco.mjtTrn.mjTRN_JOINT)
        if kind == "position":
            act.set_to_position(kp=gains["kp"], kv=gains.get("kv", -1),
                                dampratio=gains.get("dampratio", -1))
        elif kind == "velocity":
            act.set_to_velocity(kv=gains["kv"])
        else:
            act.set_to_motor()
            act.gear[0] = gains["gear"]
        if ctrl is not None:
            act.ctrllimited = mujoco.mjtLimited.mjLIMITED_TRUE
            act.ctrlrange = list(ctrl)
        if force is not None:
            act.forcelimited = mujoco.mjtLimited.mjLIMITED_TRUE
            act.forcerange = list(force)
        words = ", ".join(f"{k} {v:g}" for k, v in gains.items())
        added.append(Actuator(name, joint, kind, source, words, ctrl, force, tuple(dropped)))
        driven.add(joint)

    def _from_controller(name, joint, settings, where):
        kind = settings.get("type")
        pid = settings.get("pid")
        p, i, d = _gain(pid, "p"), _gain(pid, "i"), _gain(pid, "d")
        if joint in leave:
            skipped.append(f"{name} in {where}: joint {joint!r} is left without an actuator "
                           "(its limits are the exporter's empty ones; see Repairs)")
            return
        if joint not in joints:
            skipped.append(f"{name} in {where}: the model has no hinge or slide joint {joint!r}")
            return
        if joint in driven:
            skipped.append(f"{name} in {where}: joint {joint!r} already has an actuator")
            return
        if kind not in KINDS:
            skipped.append(f"{name} in {where}: type {kind} has no MuJoCo counterpart here")
            return
        source = f"{name} ({kind}) in {where}"
        servo = SERVO_STIFFNESS * max(inertia[joints[joint]], 1e-9) / dt
        if kind in VELOCITY_FORWARD:   # no PID: the command is the velocity
            place(name, joint, "velocity", source, {"kv": servo}, velocity(joint),
                  effort(joint))
            return
        if p is None or p <= 0:
            skipped.append(f"{name} in {where}: its pid has no positive p")
            return
        dropped = []
        if i:
            dropped.append(f"i {i:g}")
        if _gain(pid, "i_clamp"):
            dropped.append(f"i_clamp {_gain(pid, 'i_clamp'):g}")
        if kind == POSITION_PID:
            gains = {"kp": p} | ({"kv": d} if d and d > 0 else {})
            place(name, joint, "position", source, gains, joint_range(joint), effort(joint),
                  dropped)
        elif kind == POSITION_TO_VELOCITY:
            gains = {"kp": servo * p, "kv": servo * (1 + (d if d and d > 0 else 0))}
            place(name, joint, "position", source, gains, joint_range(joint), effort(joint),
                  dropped)
        else:
            dropped += [f"d {d:g}"] if d else []
            place(name, joint, "velocity", source, {"kv": p}, velocity(joint), effort(joint),
                  dropped)

    dt = model.opt.timestep
    for group, (settings, file) in controllers(package).items():
        named = _joints_of(settings)
        for joint in named:
            name = group if len(named) == 1 else f"{group}_{joint}"
            _from_controller(name, joint, settings, file.relative_to(root).as_posix())

    for t in read_transmissions(package):
        if t.joint in driven:
            continue
        if t.joint not in joints or t.reduction == 0:
            reason = "a reduction of 0" if t.joint in joints else f"no joint {t.joint!r}"
            skipped.append(f"transmission {t.name} in the URDF: {reason}")
            continue
        force = effort(t.joint)
        ctrl = None if force is None else (force[0] / abs(t.reduction), force[1] / abs(t.reduction))
        place(t.actuator or f"{t.joint}_motor", t.joint, "motor",
              f"transmission {t.name} in the URDF", {"gear": t.reduction}, ctrl, None)

    if sliders:
        for joint, j in joints.items():
            if joint in driven or joint in leave:
                continue
            m = max(inertia[j], 1e-9)
            if joint_range(joint) is not None:
                kp = m * (2 * math.pi * SLIDER_HZ) ** 2
                place(f"{joint}_position", joint, "position", "added for the viewer",
                      {"kp": kp, "dampratio": 1.0}, joint_range(joint), effort(joint))
            else:
                place(f"{joint}_velocity", joint, "velocity", "added for the viewer",
                      {"kv": m / SLIDER_TIME},
                      velocity(joint) or (-SLIDER_SPEED, SLIDER_SPEED), effort(joint))
    return added, skipped


def joint_inertia(model: mujoco.MjModel) -> dict[int, float]:
    """Each joint's own effective inertia (kg·m² or kg) at the rest pose: the diagonal of
    the joint-space inertia matrix, what a unit torque or force alone would accelerate."""
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    full = np.zeros((model.nv, model.nv))
    mujoco.mj_fullM(model, data, full)
    return {j: float(full[model.jnt_dofadr[j], model.jnt_dofadr[j]]) for j in range(model.njnt)}
