"""joint_state_publisher_gui as `sw2sim ros` stands in for it: a window with one slider per
movable joint of /robot_description, and the sliders' positions published as
sensor_msgs/JointState on `joint_states`, for robot_state_publisher and RViz.

    python -m sw2sim.ros.sliders [ROS remappings, e.g. __name:=joint_state_publisher_gui]

Every exported package's display.launch starts joint_state_publisher_gui. Debian 12 ships
joint_state_publisher_gui 1.15.1, which stops as it opens: it gives its Qt sliders floats
(`slider.setValue(RANGE/2)`), and the PyQt5 of Debian 12 accepts only ints. So this is a
node of its own rather than a patched copy of Debian's: Tk (the standard library's
tkinter; Debian's python3-tk) instead of Qt, and nothing of the joint_state_publisher
Python module, so the tool needs no more of ROS than rospy and sensor_msgs.

It does what upstream's does (ros/joint_state_publisher, noetic-devel), for what exported
packages hold:
- the joints it publishes are the robot's revolute, continuous and prismatic ones, in the
  URDF's order; a continuous joint's slider spans -pi..pi, the others span their <limit>,
  narrowed to the <safety_controller>'s soft limits unless `use_smallest_joint_limits` is
  false; a joint with a <mimic> follows its joint and has no slider;
- a joint whose range is empty (the exporter writes lower = upper = 0 when its limit
  fields are left empty) is published at that position, without a slider, as upstream does;
- it starts each joint at `zeros/<joint>` when that parameter is set, else at 0, or at the
  middle of a range that does not hold 0; Center goes back there, Randomize picks random
  positions;
- `rate` (10 Hz) is how often it publishes; `num_rows` lays the sliders out in columns of
  that many (0: one column). Each parameter is read in the node's namespace first, then
  globally, as upstream reads them.

Debian's package is not installed by `make setup`: roslaunch takes the first package of a
name on ROS_PACKAGE_PATH, Debian's (/usr/share) comes before the stand-ins, and it would
be Debian's broken node that runs.
"""

from __future__ import annotations

import math
import random
import signal
import sys
from dataclasses import dataclass

from lxml import etree

from .. import xmlsafe

TITLE = "Joint State Publisher: {node}"   # the window's title (tests find it by it)
STEPS = 1000                              # positions per slider
MOVABLE = ("revolute", "continuous", "prismatic")
WATCH_MS = 100                            # how often the window looks for a shutdown


class DescriptionError(ValueError):
    """The robot description cannot be read; the message says why."""


@dataclass
class Joint:
    name: str
    lower: float
    upper: float
    zero: float = 0.0
    mimic: tuple[str, float, float] | None = None   # (joint, multiplier, offset)

    @property
    def slides(self) -> bool:
        return self.mimic is None and self.upper > self.lower


def joints(description: str, zeros: dict[str, float] | None = None,
           smallest_limits: bool = True) -> list[Joint]:
    """The movable joints of a URDF text, in its order, with their sliders' ranges."""
    try:
        robot = xmlsafe.parse_bytes(description.encode("utf-8"))
    except (etree.XMLSyntaxError, xmlsafe.DoctypeDeclared) as error:
        raise DescriptionError(f"/robot_description is not a URDF's XML ({error})") from None
    if robot is None or robot.tag != "robot":
        raise DescriptionError("/robot_description is not a URDF: its root is <"
                               f"{'nothing' if robot is None else robot.tag}>, not <robot>")
    found = []
    for element in robot.findall("joint"):
        kind, name = element.get("type"), element.get("name", "")
        if kind not in MOVABLE:
            continue
        if kind == "continuous":
            lower, upper = -math.pi, math.pi
        else:
            limit = element.find("limit")
            lower = _number(limit, "lower", name) if limit is not None else 0.0
            upper = _number(limit, "upper", name) if limit is not None else 0.0
        safety = element.find("safety_controller")
        if smallest_limits and safety is not None:
            if safety.get("soft_lower_limit") is not None:
                lower = max(lower, _number(safety, "soft_lower_limit", name))
            if safety.get("soft_upper_limit") is not None:
                upper = min(upper, _number(safety, "soft_upper_limit", name))
        mimic = element.find("mimic")
        follows = None if mimic is None else (
            mimic.get("joint", ""), _number(mimic, "multiplier", name, 1.0),
            _number(mimic, "offset", name, 0.0))
        zero = (zeros or {}).get(name) or (0.0 if lower <= 0.0 <= upper
                                           else (lower + upper) / 2)
        found.append(Joint(name, lower, upper, zero, follows))
    return found


def _number(element, attribute: str, joint: str, default: float = 0.0) -> float:
    text = element.get(attribute)
    if text is None:
        return default
    try:
        return float(text)
    except ValueError:
        raise DescriptionError(f"joint {joint}: {element.tag} {attribute}=\"{text}\" is not a "
                               "number") from None


def positions(found: list[Joint], chosen: dict[str, float]) -> list[float]:
    """Each joint's position: its slider's, its zero, or (mimic) its joint's, scaled."""
    by_name = {j.name: j for j in found}
    out = []
    for joint in found:
        factor, offset, seen = 1.0, 0.0, {joint.name}
        while joint.mimic is not None and joint.mimic[0] in by_name:
            offset += factor * joint.mimic[2]
            factor *= joint.mimic[1]
            joint = by_name[joint.mimic[0]]
            if joint.name in seen:    # a loop of mimics (upstream stops on it): cut here
                break
            seen.add(joint.name)
        out.append(chosen.get(joint.name, joint.zero) * factor + offset)
    return out


def _param(rospy, name: str, default):
    for key in (f"~{name}", name):
        if rospy.has_param(key):
            return rospy.get_param(key)
    return default


class Window:
    """The sliders, laid out in columns of `rows`, with Randomize and Center below."""

    def __init__(self, root, title: str, found: list[Joint], rows: int):
        import tkinter
        self.root, self.joints = root, found
        root.title(title)
        self.values: dict[str, tkinter.DoubleVar] = {}
        grid = tkinter.Frame(root)
        grid.pack(fill="both", expand=True, padx=6, pady=6)
        sliding = [j for j in found if j.slides]
        rows = rows if rows > 0 else max(len(sliding), 1)
        for index, joint in enumerate(sliding):
            cell = tkinter.Frame(grid)
            cell.grid(row=index % rows, column=index // rows, sticky="ew", padx=4, pady=2)
            value = tkinter.DoubleVar(root, joint.zero)
            shown = tkinter.StringVar(root)
            value.trace_add("write", lambda *_, v=value, s=shown: s.set(f"{v.get():.2f}"))
            shown.set(f"{joint.zero:.2f}")
            tkinter.Label(cell, text=joint.name, font=("Helvetica", 9, "bold")).grid(
                row=0, column=0, sticky="w")
            tkinter.Label(cell, textvariable=shown, width=8, anchor="e").grid(
                row=0, column=1, sticky="e")
            tkinter.Scale(cell, variable=value, from_=joint.lower, to=joint.upper,
                          resolution=(joint.upper - joint.lower) / STEPS, orient="horizontal",
                          showvalue=False, length=320).grid(row=1, column=0, columnspan=2,
                                                            sticky="ew")
            cell.columnconfigure(0, weight=1)
            self.values[joint.name] = value
        if not sliding:
            tkinter.Label(grid, text="This robot has no joint to move.").grid(row=0, column=0)
        tkinter.Button(root, text="Randomize", command=self.randomize).pack(fill="x")
        tkinter.Button(root, text="Center", command=self.center).pack(fill="x")

    def chosen(self) -> dict[str, float]:
        return {name: value.get() for name, value in self.values.items()}

    def randomize(self) -> None:
        for joint in self.joints:
            if joint.name in self.values:
                self.values[joint.name].set(random.uniform(joint.lower, joint.upper))

    def center(self) -> None:
        for joint in self.joints:
            if joint.name in self.values:
                self.values[joint.name].set(joint.zero)


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv if argv is None else argv
    try:
        import tkinter
    except ImportError:
        print("joint_state_publisher_gui: this Python has no tkinter, which its window needs. "
              "On Debian: sudo apt install python3-tk (`make setup` installs it with ROS 1).",
              file=sys.stderr)
        return 1
    import rospy
    from sensor_msgs.msg import JointState

    rospy.init_node("joint_state_publisher_gui", argv=argv, disable_signals=True)
    description = _param(rospy, "robot_description", None)
    if description is None:
        rospy.logerr("joint_state_publisher_gui: the parameter robot_description is not set; "
                     "the launch file sets it with <param name=\"robot_description\" "
                     "textfile=\"$(find PACKAGE)/urdf/PACKAGE.urdf\" />")
        return 1
    rate = _param(rospy, "rate", 10)
    if isinstance(rate, bool) or not isinstance(rate, (int, float)) or not rate > 0:
        rospy.logerr(f"joint_state_publisher_gui: its parameter rate is {rate!r}; give the "
                     "publishing rate in Hz, above 0 (10 when not set)")
        return 1
    try:
        zeros = _param(rospy, "zeros", {})
        found = joints(description, zeros if isinstance(zeros, dict) else {},
                       bool(_param(rospy, "use_smallest_joint_limits", True)))
    except DescriptionError as error:
        rospy.logerr(f"joint_state_publisher_gui: {error}")
        return 1
    for joint in found:
        if joint.mimic is None and joint.upper <= joint.lower:
            rospy.loginfo(f"joint_state_publisher_gui: {joint.name} has no slider: its limits "
                          f"leave it no range (lower {joint.lower:g}, upper {joint.upper:g}; "
                          "`sw2sim check` tells why)")
    try:
        root = tkinter.Tk(className="joint_state_publisher_gui")
    except tkinter.TclError as error:
        rospy.logerr(f"joint_state_publisher_gui: cannot open its window ({error}); it needs "
                     "a screen (DISPLAY)")
        return 1
    window = Window(root, TITLE.format(node=rospy.get_name()), found,
                    int(_param(rospy, "num_rows", 0)))
    publisher = rospy.Publisher("joint_states", JointState, queue_size=5)
    period_ms = max(1, round(1000 / rate))
    stopping = []

    def publish() -> None:
        message = JointState(name=[j.name for j in found],
                             position=positions(found, window.chosen()))
        message.header.stamp = rospy.Time.now()
        if message.name:
            publisher.publish(message)
        root.after(period_ms, publish)

    def watch() -> None:
        if stopping or rospy.is_shutdown():
            root.destroy()
        else:
            root.after(WATCH_MS, watch)

    # roslaunch stops its nodes with SIGINT, then SIGTERM; the window closes on either.
    for sig in (signal.SIGINT, signal.SIGTERM):
        signal.signal(sig, lambda *_: stopping.append(True))
    root.protocol("WM_DELETE_WINDOW", lambda: stopping.append(True))
    publish()
    watch()
    root.mainloop()
    rospy.signal_shutdown("window closed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
