"""What ros_control reads from a package, for use in MuJoCo.

MuJoCo's URDF import keeps a joint's position range and effort limit but drops the
rest of what a ROS controller relies on: the velocity limit, the `<safety_controller>`
soft limits, the `<transmission>` elements (so the model has no actuators) and the
controller YAML. These functions read them from the package so a lesson script can
apply them itself.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path

import mujoco

from .package import LoadError, Package, as_package
from .xmlsafe import source_line


@dataclass(frozen=True)
class JointLimits:
    """A joint's `<limit>` and `<safety_controller>`, as ros_control's joint_limits_interface reads them."""

    lower: float | None
    upper: float | None
    effort: float | None
    velocity: float | None
    soft_lower: float | None = None
    soft_upper: float | None = None
    k_position: float | None = None
    k_velocity: float | None = None

    @property
    def has_soft_limits(self) -> bool:
        return self.k_velocity is not None


@dataclass(frozen=True)
class Transmission:
    name: str
    joint: str
    actuator: str
    interface: str
    reduction: float


def _number(element, attribute: str, file: Path) -> float | None:
    text = element.get(attribute)
    if text is None:
        return None
    try:
        return float(text)
    except ValueError:
        raise LoadError(file, f"<{element.tag} {attribute}={text!r}> is not a number; write it in SI units "
                        "without a unit, e.g. 1000", source_line(element, attribute)) from None


def read_joint_limits(source: str | os.PathLike | Package) -> dict[str, JointLimits]:
    """The limits of every joint that has a `<limit>`, by joint name (package folder, .urdf
    or Package)."""
    package = as_package(source)
    urdf = package.urdf
    limits = {}
    for joint in package.robot.iter("joint"):
        limit = joint.find("limit")
        if limit is None:
            continue
        safety = joint.find("safety_controller")
        soft = {}
        if safety is not None:
            soft = dict(soft_lower=_number(safety, "soft_lower_limit", urdf),
                        soft_upper=_number(safety, "soft_upper_limit", urdf),
                        k_position=_number(safety, "k_position", urdf),
                        k_velocity=_number(safety, "k_velocity", urdf))
        limits[joint.get("name")] = JointLimits(
            lower=_number(limit, "lower", urdf), upper=_number(limit, "upper", urdf),
            effort=_number(limit, "effort", urdf), velocity=_number(limit, "velocity", urdf), **soft)
    return limits


def read_transmissions(source: str | os.PathLike | Package) -> list[Transmission]:
    """The simple transmissions declared in the URDF (package folder, .urdf or Package)."""
    package = as_package(source)
    urdf = package.urdf
    found = []
    for t in package.robot.iter("transmission"):
        joint, actuator = t.find("joint"), t.find("actuator")
        if joint is None or actuator is None:
            raise LoadError(urdf, f"transmission {t.get('name')!r} needs a <joint> and an <actuator>",
                            t.sourceline)
        reduction = (actuator.findtext("mechanicalReduction") or "1").strip()
        try:
            ratio = float(reduction)
        except ValueError:
            raise LoadError(urdf, f"mechanicalReduction {reduction!r} is not a number", actuator.sourceline) from None
        found.append(Transmission(
            name=t.get("name", ""), joint=joint.get("name", ""), actuator=actuator.get("name", ""),
            interface=(joint.findtext("hardwareInterface") or "").strip(), reduction=ratio))
    return found


def add_motors(spec: mujoco.MjSpec, source: str | os.PathLike | Package) -> list[str]:
    """Give the model one motor per transmission; return the motors' names, in `data.ctrl` order.

    A motor's control is the actuator's torque; `gear` is the transmission's mechanical
    reduction, and the control is limited to the joint's effort limit divided by it.
    """
    package = as_package(source)
    limits = read_joint_limits(package)
    names = []
    for t in read_transmissions(package):
        motor = spec.add_actuator(name=t.actuator, target=t.joint, trntype=mujoco.mjtTrn.mjTRN_JOINT)
        motor.set_to_motor()
        motor.gear[0] = t.reduction
        effort = limits.get(t.joint, JointLimits(None, None, None, None)).effort
        if effort:
            motor.ctrllimited = mujoco.mjtLimited.mjLIMITED_TRUE
            motor.ctrlrange = [-effort / t.reduction, effort / t.reduction]
        names.append(t.actuator)
    return names


def read_controllers(path: str | os.PathLike) -> dict:
    """The controller configuration (the YAML a launch file loads with `<rosparam>`)."""
    import yaml   # here: `sw2sim check` reads no YAML, and the import costs it 15-30 ms

    path = Path(path)
    try:
        with open(path, encoding="utf-8") as f:
            return yaml.safe_load(f) or {}
    except OSError as exc:
        raise LoadError(path, f"cannot read the controller configuration: {exc.strerror}") from None
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        raise LoadError(path, f"not valid YAML: {getattr(exc, 'problem', exc)}",
                        mark.line + 1 if mark else None) from None
