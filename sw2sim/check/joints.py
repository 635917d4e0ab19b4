"""Checks of the joints: axes, limits and safety controllers.

What matters differs by consumer. ROS refuses a revolute or prismatic joint without a
<limit>, clips every command to the limit's effort and plans within lower..upper; MuJoCo
keeps the range and the effort but quietly drops a range it cannot use (lower >= upper),
so a joint locked in ROS turns freely in MuJoCo. Values that do not parse are reported
once, by structure's `number-invalid`, and skipped here.
"""

from __future__ import annotations

import difflib
import math

from ..xmlsafe import source_line
from .findings import ERROR, WARNING, rule
from .repairs import make_fixed, make_unlimited, remove_element, repair
from .urdf import number, vector

# Joint types whose <axis> is used, whose <limit> is required, and that a motor can drive.
AXIS_TYPES = ("revolute", "continuous", "prismatic", "planar")
LIMITED_TYPES = ("revolute", "prismatic")
DRIVEN_TYPES = ("revolute", "prismatic", "continuous")
# An axis this far from length 1 is a typo rather than rounding to 5 digits.
UNIT_TOLERANCE = 1e-3

DIALOG = "the exporter's joint properties (the window Preview and Export opens)"

rule("axis-zero", ERROR, "joint", "A joint's axis is all zeros",
     symptom="MuJoCo stops with \"axis too small in joint\"; ROS cannot tell which way the "
             "joint turns or slides.",
     cause="No reference axis was chosen for the joint in the exporter, or the axis was "
           "emptied by hand. (Older exports also write a zero axis on fixed joints, where it "
           "is unused and not reported.)",
     fix="Select the joint's reference axis in the exporter and export again, or write the "
         "direction in the child link's frame, e.g. <axis xyz=\"0 0 1\"/>.",
     repair="a joint that also has the exporter's empty limits (all 0) is a frame, such as "
            "a sensor's: it is locked, as a fixed joint. Any other stays an error.",
     seen_in=("solidworks_urdf_exporter#8",))
rule("axis-not-unit", WARNING, "joint", "A joint's axis is not of length 1",
     symptom="Nothing visible: ROS and MuJoCo scale the axis to length 1. But a length far "
             "from 1 usually means a typed value is wrong.",
     cause="A hand edit, such as \"0 0 10\" for \"0 0 1\" or \"1 1 0\" meant as a diagonal.",
     fix="Check the direction and write it as a unit vector, e.g. \"0 0.70711 0.70711\".")
rule("limit-missing", ERROR, "joint", "A revolute or prismatic joint has no <limit>",
     symptom="ROS refuses the URDF (\"joint is of type REVOLUTE but it does not specify "
             "limits\"); MuJoCo loads it with no range and no effort limit.",
     cause="The limit fields were left empty in the exporter, or the element was deleted.",
     fix=f"Fill in lower, upper, effort and velocity in {DIALOG}, or add "
         "<limit lower=\"...\" upper=\"...\" effort=\"...\" velocity=\"...\"/> to the joint.")
rule("limit-incomplete", ERROR, "joint", "A <limit> lacks its effort or velocity",
     symptom="ROS refuses the URDF (\"joint limit: no effort\" or \"no velocity\"); MuJoCo "
             "loads it.",
     cause="URDF requires effort and velocity on every <limit>; lower and upper may be left "
           "out, effort and velocity may not.",
     fix=f"Fill in effort and velocity in {DIALOG}, or add them to the <limit>.")
rule("limit-exporter-default", ERROR, "joint", "The joint still has the exporter's empty "
     "limit (everything 0)",
     symptom="In ROS and Gazebo the joint cannot move (its range is 0..0) and cannot be driven "
             "(its effort is 0). MuJoCo drops a 0..0 range, so there the same joint turns "
             "freely: the two simulations disagree.",
     cause="The exporter writes lower = upper = effort = velocity = 0 when the limit fields "
           "are left empty.",
     fix=f"Enter the real travel, the motor's peak effort and its top speed in {DIALOG}, then "
         "export again (or edit the <limit>).",
     repair="a revolute or prismatic joint becomes a joint without limits and without an "
            "actuator, with a warning, because all-zero limits are what the exporter writes "
            "for fields left empty, not a travel the designer chose; `--lock-default-limits` "
            "locks it at the home pose instead, as ROS reads it. A continuous joint keeps its "
            "actuator, without a force limit.")
rule("limit-range-empty", ERROR, "joint", "A joint's lower limit is not below its upper limit",
     symptom="ROS holds the joint at one position or rejects every target; MuJoCo ignores the "
             "range and lets the joint move without limits.",
     cause="Lower and upper swapped, a sign lost, or both typed as the same value.",
     fix="Write the lower end of travel in lower and the upper end in upper (radians for "
         "revolute, metres for prismatic), so that lower < upper.")
rule("effort-not-positive", ERROR, "joint", "A joint's effort limit is zero or negative",
     symptom="ROS controllers clip every command to the effort limit, so the joint never "
             "moves under its controller; MuJoCo ignores a zero effort limit, so the two "
             "disagree.",
     cause="The effort field was left at 0 or typed with a sign.",
     fix="Enter the motor's peak torque (N m) or force (N), a positive number, as effort.",
     repair="an effort of 0 sets no force limit: the joint's actuator may push as hard as its "
            "gains ask.")
rule("velocity-not-positive", ERROR, "joint", "A joint's velocity limit is zero or negative",
     symptom="ROS tools that respect the velocity limit (MoveIt, joint trajectory "
             "controllers, joint_limits_interface) refuse to move the joint.",
     cause="The velocity field was left at 0 or typed with a sign.",
     fix="Enter the joint's top speed (rad/s or m/s), a positive number, as velocity.",
     repair="nothing to change: MuJoCo has no velocity limit, and a velocity actuator gets no "
            "control range from it.")
# What follows a <mimic> that cannot couple anything, in ROS, as their sources read: urdfdom
# (check_urdf) never looks at the joint a mimic names; joint_state_publisher (noetic-devel)
# looks it up among the moving joints when it publishes, and a mimic chain that comes back
# to its start stops it.
MIMIC_REPAIR = ("the coupling is dropped, so the joint moves on its own, as MuJoCo would do "
                "with a warning.")
rule("mimic-joint-missing", ERROR, "joint", "A <mimic> names a joint that does not exist",
     symptom="check_urdf accepts the URDF (urdfdom never looks the name up), but "
             "joint_state_publisher stops with a KeyError when it publishes. MuJoCo says "
             "\"<mimic> on joint ... ignored; mimic requires revolute, continuous, or "
             "prismatic joints\", which points at the wrong problem, and drops the coupling.",
     cause="A typo in the mimicked joint's name, or a joint renamed in the exporter after the "
           "<mimic> was written by hand.",
     fix="Write the name of the joint to follow, exactly as its <joint name=...> spells it.",
     repair=MIMIC_REPAIR)
rule("mimic-joint-not-movable", ERROR, "joint", "A <mimic> names a joint that cannot move: "
     "a fixed, floating or planar joint, or the joint itself",
     symptom="check_urdf accepts the URDF (urdfdom never looks at the joint a mimic names). "
             "joint_state_publisher stops with a KeyError when it publishes (it keeps no "
             "position for fixed, floating and planar joints), or with \"Found an infinite "
             "recursive mimic chain\" for a joint that follows itself. MuJoCo says \"<mimic> "
             "on joint ... ignored; mimic requires revolute, continuous, or prismatic joints\" "
             "and drops the coupling, or stops (\"repeated in equality constraint\") on a "
             "joint that follows itself.",
     cause="The joint to follow was made fixed in the exporter after the <mimic> was "
           "written, or the <mimic> names the wrong joint (its own name, or the fixed joint "
           "beside the one meant).",
     fix="Name a revolute, continuous or prismatic joint in <mimic joint=...>, or make the "
         "named joint one of those types.",
     repair=MIMIC_REPAIR)
rule("limit-on-continuous", WARNING, "joint", "A continuous joint is given lower and upper "
     "limits",
     symptom="Nothing: ROS and MuJoCo ignore lower and upper on a continuous joint, so the "
             "joint turns without end although the file suggests a range.",
     cause="The joint was meant to be revolute, or the limits were copied from another joint.",
     fix="Make the joint revolute if it should stop at lower and upper; otherwise set both "
         "to 0 (or delete them) and keep effort and velocity.")
rule("safety-limits-misspelt", WARNING, "joint", "The safety controller's soft limits use "
     "misspelt attribute names",
     symptom="ROS reads soft limits of 0 and 0: MoveIt and the safety layer treat the joint "
             "as stuck at 0. MuJoCo ignores the element.",
     cause="Exporter versions before the fix wrote soft_lower and soft_upper, which URDF does "
           "not know, instead of soft_lower_limit and soft_upper_limit.",
     fix="Rename the attributes to soft_lower_limit and soft_upper_limit (or export again "
         "with a current exporter).",
     seen_in=("solidworks_urdf_exporter#119",))


def check(ctx) -> None:
    """Add a finding to ctx for every problem of this group."""
    for joint in ctx.robot.findall("joint"):
        kind = joint.get("type")
        name = joint.get("name", "")
        if kind in AXIS_TYPES:
            _axis(ctx, joint, name)
        _limit(ctx, joint, name, kind)
        _safety(ctx, joint, name)
        _mimic(ctx, joint, name)


def _axis(ctx, joint, name: str) -> None:
    axis = joint.find("axis")
    if axis is None:
        return  # URDF's default axis, x, is a valid one
    xyz = vector(axis.get("xyz"), 3)
    if xyz is None:
        return
    length = math.sqrt(sum(v * v for v in xyz))
    line = source_line(axis, "xyz")
    written = " ".join(_g(v) for v in xyz)
    if length < 1e-9:
        frame = _is_frame(joint)
        ctx.add("axis-zero", f'joint "{name}" has axis xyz="{written}"', line=line,
                repair=repair(f'"{name}" is locked (a fixed joint): with no axis and the '
                              "exporter's empty limits it is a frame, not a joint that moves",
                              (joint, make_fixed)) if frame else None)
    elif abs(length - 1.0) > UNIT_TOLERANCE:
        unit = " ".join(f"{v / length:.5g}" for v in xyz)
        ctx.add("axis-not-unit", f'joint "{name}" has axis xyz="{written}" of length '
                f"{length:.4g}", line=line,
                fix=f'check the direction; as a unit vector it reads xyz="{unit}"')


def _limit(ctx, joint, name: str, kind: str | None) -> None:
    limit = joint.find("limit")
    if limit is None:
        if kind in LIMITED_TYPES:
            ctx.add("limit-missing", f'{kind} joint "{name}" has no <limit>',
                    line=source_line(joint))
        return
    absent = [a for a in ("effort", "velocity") if limit.get(a) is None]
    if absent:
        ctx.add("limit-incomplete", f'the <limit> of joint "{name}" has no '
                f"{' and no '.join(absent)}", line=source_line(limit, None),
                fix=f"add {' and '.join(f'{a}=...' for a in absent)} (positive numbers) to "
                    f'the <limit> of "{name}"')
    if kind not in DRIVEN_TYPES:
        return  # fixed, floating and planar joints ignore <limit>
    # URDF's defaults: lower and upper are 0 when absent; effort and velocity are required.
    lower = number(limit.get("lower", "0"))
    upper = number(limit.get("upper", "0"))
    effort = number(limit.get("effort"))
    velocity = number(limit.get("velocity"))
    if effort == 0 and velocity == 0 and lower == 0 and upper == 0:
        fix = (f"enter the motor's peak torque as effort and the wheel's top speed as velocity "
               f'for "{name}" in {DIALOG}; lower and upper may stay 0'
               if kind == "continuous" else None)
        ctx.add("limit-exporter-default", f'{kind} joint "{name}" has lower = upper = effort = '
                "velocity = 0", line=source_line(limit, None), fix=fix,
                repair=_default_limit_repair(ctx, joint, name, kind))
        return
    if kind in LIMITED_TYPES and lower is not None and upper is not None and lower >= upper:
        ctx.add("limit-range-empty", f'{kind} joint "{name}" has lower {_g(lower)} and upper '
                f"{_g(upper)}", line=source_line(limit, "lower"),
                fix=("swap lower and upper" if lower > upper else
                     "make upper greater than lower, or make the joint fixed if it must not move"))
    if kind == "continuous" and (lower or upper):
        ctx.add("limit-on-continuous", f'continuous joint "{name}" has lower {_g(lower)} and '
                f"upper {_g(upper)}, which are ignored", line=source_line(limit, "lower"))
    if effort is not None and effort <= 0:
        ctx.add("effort-not-positive", f'joint "{name}" has effort {_g(effort)}',
                line=source_line(limit, "effort"),
                repair=repair(f'no force limit on "{name}" (an effort of 0 limits nothing in '
                              "MuJoCo)") if effort == 0 else None)
    if velocity is not None and velocity <= 0:
        ctx.add("velocity-not-positive", f'joint "{name}" has velocity {_g(velocity)}',
                line=source_line(limit, "velocity"),
                repair=repair("none needed: MuJoCo does not use the velocity limit"))


def _is_frame(joint) -> bool:
    """Whether a joint has neither an axis nor a travel: all-zero axis and limit, as the
    exporter writes for a coordinate frame (a sensor's, a tool's) made a joint."""
    axis = joint.find("axis")
    xyz = vector(axis.get("xyz"), 3) if axis is not None else None
    limit = joint.find("limit")
    return (xyz is not None and not any(xyz) and limit is not None and
            all(number(limit.get(a, "0")) == 0 for a in ("lower", "upper", "effort", "velocity")))


def _default_limit_repair(ctx, joint, name: str, kind: str):
    """The exporter's all-zero limit: free and undriven (the default), or locked."""
    if _is_frame(joint):
        return repair(f'"{name}" is locked (a fixed joint): with no axis and the exporter\'s '
                      "empty limits it is a frame, not a joint that moves", (joint, make_fixed))
    if kind == "continuous":
        return repair(f'no force limit on "{name}" and no velocity limit (MuJoCo ignores '
                      "values of 0)")
    travel = "slides" if kind == "prismatic" else "turns"
    if ctx.options.lock_default_limits:
        return repair(f'"{name}" is locked at its home pose (a fixed joint), as ROS reads a '
                      "range of 0 to 0 (--lock-default-limits)", (joint, make_fixed))
    return repair(f'"{name}" {travel} freely, without limits and without an actuator, since '
                  "all-zero limits are what the exporter writes for empty fields, not a "
                  "travel anyone chose (--lock-default-limits locks the joint instead)",
                  (joint, make_unlimited), unactuated=name)


def _mimic(ctx, joint, name: str) -> None:
    for mimic in joint.findall("mimic"):
        target = mimic.get("joint")
        if target is None:
            continue  # MuJoCo and ROS refuse it outright; structure reports missing names
        other = ctx.joints.get(target)
        if other is not None and other.get("type") in DRIVEN_TYPES and target != name:
            continue
        if other is None:
            moving = [n for n, j in ctx.joints.items()
                      if j.get("type") in DRIVEN_TYPES and n != name]
            near = difflib.get_close_matches(target, moving, n=3, cutoff=0.4)
            what = f'no joint is named "{target}"' + (
                f"; the closest names are {', '.join(repr(n) for n in near)}" if near else "")
            fix = (f'write mimic joint="{near[0]}" if that is the joint meant' if near else None)
        else:
            kind = "itself" if target == name else f'a {other.get("type")} joint'
            what, fix = f'"{target}" is {kind}, which cannot be followed', None
        rule_id = "mimic-joint-missing" if other is None else "mimic-joint-not-movable"
        ctx.add(rule_id, f'the <mimic> of joint "{name}" names "{target}": '
                f"{what}", line=source_line(mimic, "joint"), fix=fix,
                repair=repair(f'the coupling of "{name}" to "{target}" is dropped; "{name}" '
                              "moves on its own", (mimic, remove_element)))


def _safety(ctx, joint, name: str) -> None:
    for safety in joint.findall("safety_controller"):
        misspelt = [a for a in ("soft_lower", "soft_upper") if safety.get(a) is not None
                    and safety.get(f"{a}_limit") is None]
        if misspelt:
            names = " and ".join(misspelt)
            ctx.add("safety-limits-misspelt", f'the <safety_controller> of joint "{name}" has '
                    f"{names}, which URDF does not know",
                    line=source_line(safety, misspelt[0]),
                    fix=f"rename {names} to {' and '.join(f'{a}_limit' for a in misspelt)}")


def _g(value: float | None) -> str:
    return "?" if value is None else f"{value:g}"
