"""robot_state_publisher's transforms, computed from the URDF's joints.

For each joint, the transform from its parent link's frame to its child link's frame:
the joint's `<origin>` (xyz, then roll-pitch-yaw as fixed axes X, Y, Z), followed by the
motion along or about its `<axis>` (revolute and continuous: a rotation by the position;
prismatic: a translation). Fixed joints go once on /tf_static; the moving joints on /tf,
for every joint state that names them, stamped with the state's time. Floating and
planar joints are left out, as robot_state_publisher (KDL) does.
"""

from __future__ import annotations

import dataclasses
import math

MOVING = ("revolute", "continuous", "prismatic")


@dataclasses.dataclass(frozen=True)
class Joint:
    name: str
    kind: str
    parent: str
    child: str
    xyz: tuple[float, float, float]
    rotation: tuple[float, float, float, float]   # x, y, z, w
    axis: tuple[float, float, float]


def _numbers(text: str | None, default: tuple[float, ...]) -> tuple[float, ...]:
    if not text:
        return default
    try:
        values = tuple(float(v) for v in text.split())
    except ValueError:
        return default
    return values if len(values) == len(default) else default


def quaternion_rpy(roll: float, pitch: float, yaw: float) -> tuple[float, float, float, float]:
    cr, sr = math.cos(roll / 2), math.sin(roll / 2)
    cp, sp = math.cos(pitch / 2), math.sin(pitch / 2)
    cy, sy = math.cos(yaw / 2), math.sin(yaw / 2)
    return (sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy,
            cr * cp * sy - sr * sp * cy, cr * cp * cy + sr * sp * sy)


def multiply(a, b):
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return (aw * bx + ax * bw + ay * bz - az * by, aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw, aw * bw - ax * bx - ay * by - az * bz)


def rotate(q, v):
    x, y, z, w = q
    vx, vy, vz = v
    # v + 2 w (u x v) + 2 u x (u x v), u = (x, y, z)
    cx, cy, cz = y * vz - z * vy, z * vx - x * vz, x * vy - y * vx
    return (vx + 2 * (w * cx + y * cz - z * cy), vy + 2 * (w * cy + z * cx - x * cz),
            vz + 2 * (w * cz + x * cy - y * cx))


def joints(robot) -> list[Joint]:
    found = []
    for joint in robot.findall("joint"):
        origin = joint.find("origin")
        xyz = _numbers(origin.get("xyz") if origin is not None else None, (0.0, 0.0, 0.0))
        rpy = _numbers(origin.get("rpy") if origin is not None else None, (0.0, 0.0, 0.0))
        axis_element = joint.find("axis")
        axis = _numbers(axis_element.get("xyz") if axis_element is not None else None,
                        (1.0, 0.0, 0.0))
        norm = math.sqrt(sum(a * a for a in axis)) or 1.0
        parent, child = joint.find("parent"), joint.find("child")
        if parent is None or child is None:
            continue
        found.append(Joint(joint.get("name"), joint.get("type", "fixed"), parent.get("link"),
                           child.get("link"), xyz, quaternion_rpy(*rpy),
                           tuple(a / norm for a in axis)))
    return found


def transform(joint: Joint, position: float = 0.0):
    """(translation, rotation) from the joint's parent frame to its child frame."""
    if joint.kind in ("revolute", "continuous"):
        half = position / 2
        s = math.sin(half)
        motion = (joint.axis[0] * s, joint.axis[1] * s, joint.axis[2] * s, math.cos(half))
        return joint.xyz, multiply(joint.rotation, motion)
    if joint.kind == "prismatic":
        offset = rotate(joint.rotation, tuple(a * position for a in joint.axis))
        return tuple(o + d for o, d in zip(joint.xyz, offset)), joint.rotation
    return joint.xyz, joint.rotation


def stamped(joint: Joint, position: float, stamp):
    """A geometry_msgs/TransformStamped for the joint at `position`."""
    from geometry_msgs.msg import TransformStamped
    message = TransformStamped()
    message.header.stamp = stamp
    message.header.frame_id = joint.parent
    message.child_frame_id = joint.child
    (tx, ty, tz), (qx, qy, qz, qw) = transform(joint, position)
    t, r = message.transform.translation, message.transform.rotation
    t.x, t.y, t.z = float(tx), float(ty), float(tz)
    r.x, r.y, r.z, r.w = float(qx), float(qy), float(qz), float(qw)
    return message
