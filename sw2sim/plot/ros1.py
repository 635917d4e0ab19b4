"""`sw2sim plot` under ROS 1: the master at ROS_MASTER_URI lists the published topics and
their types, genpy's classes describe the types, and a rospy node subscribes.

rospy follows /clock when the master's /use_sim_time is true (as every Gazebo launch and
`sw2sim ros` set it), so its time is then the simulation's. The message classes Debian
lacks (control_msgs, gazebo_msgs) are the stand-in's (sw2sim.ros.messages).
"""

from __future__ import annotations

import importlib
import os
import re
import socket
from urllib.parse import urlparse

from .fields import PlotError, Slot

NAME = "ROS 1"
NUMBERS = {"int8", "uint8", "int16", "uint16", "int32", "uint32", "int64", "uint64",
           "float32", "float64", "byte", "char"}
CONNECT_TIMEOUT = 2.0   # s for the master's port to answer
QUEUE = 10_000          # messages held for a busy plotter to catch up on


def master_uri() -> str:
    return os.environ.get("ROS_MASTER_URI", "http://localhost:11311")


def problem() -> str | None:
    """Why ROS 1 cannot be used here, or None."""
    try:
        import rospy  # noqa: F401
    except ImportError:
        return ("rospy is not importable in this Python: run `sw2sim plot` from the ROS 1 "
                "environment (.venv, which `make setup` gives Debian's ROS 1)")
    uri = master_uri()
    where = urlparse(uri)
    try:
        with socket.create_connection((where.hostname or "localhost", where.port or 11311),
                                      timeout=CONNECT_TIMEOUT):
            pass
    except OSError:
        return (f"no ROS 1 master answers at ROS_MASTER_URI={uri}: start the simulation first "
                "(`sw2sim ros PACKAGE`, or roslaunch), or export the ROS_MASTER_URI its "
                "first lines print")
    return None


def slot(text: str) -> Slot:
    """A genpy slot type (`float64`, `float64[]`, `uint8[4]`, `std_msgs/Header`) as a Slot."""
    m = re.fullmatch(r"([^\[\]]+)(?:\[(\d*)\])?", text)
    if not m:
        return Slot(text, "message")
    base, size = m[1], None if m[2] is None else (int(m[2]) if m[2] else -1)
    if base in NUMBERS:
        return Slot(base, "number", size)
    if base == "bool":
        return Slot(base, "bool", size)
    if base == "string":
        return Slot(base, "text", size)
    if base == "Header":
        base = "std_msgs/Header"
    return Slot(base, "message", size)


class Source:
    """The ROS 1 side of one plot: one anonymous rospy node, `sw2sim_plot_...`."""

    name = NAME

    def __init__(self):
        import rosgraph
        import rospy
        from ..ros import messages
        messages.ensure()   # control_msgs and gazebo_msgs, which Debian does not ship
        self.rospy = rospy
        self.master = rosgraph.Master("/sw2sim_plot")
        self.sim_time = False
        self.subscribers = []

    def _node(self) -> None:
        """The node, started at the first subscription: by then the topics are published,
        so a launch file has set /use_sim_time, which rospy reads once, at init_node."""
        if not self.rospy.core.is_initialized():
            self.rospy.init_node("sw2sim_plot", anonymous=True, disable_signals=True)
            self.sim_time = bool(self.rospy.get_param("/use_sim_time", False))

    def topics(self) -> dict[str, str]:
        """The published topics and their types."""
        return dict(self.master.getPublishedTopics("/"))

    def describe(self, kind: str) -> dict[str, Slot]:
        if kind in ("time", "duration"):
            return {"secs": Slot("int32", "number"), "nsecs": Slot("int32", "number")}
        cls = self._class(kind)
        return {name: slot(text) for name, text in zip(cls.__slots__, cls._slot_types)}

    def _class(self, kind: str):
        """The class of `pkg/Name`, from the module `pkg.msg`, where genpy's
        get_message_class finds it too."""
        package, _, name = kind.partition("/")
        try:
            cls = getattr(importlib.import_module(f"{package}.msg"), name, None)
        except ImportError:
            cls = None
        if cls is None:
            raise PlotError(f"the message type {kind} is not importable here (no module "
                            f"{package}.msg): build or install its package, then source "
                            f"the workspace's devel/setup.bash in this terminal")
        return cls

    def subscribe(self, topic: str, kind: str, on_message) -> None:
        self._node()
        self.subscribers.append(self.rospy.Subscriber(topic, self._class(kind), on_message,
                                                      queue_size=QUEUE))

    def now(self) -> float:
        return self.rospy.get_time()

    def stamp(self, message) -> float | None:
        """The message's header stamp (rqt_plot's time for it), None without one or unset."""
        if not getattr(type(message), "_has_header", False):
            return None
        stamp = message.header.stamp
        return stamp.to_sec() if (stamp.secs or stamp.nsecs) else None

    def uses_sim_time(self) -> bool:
        return self.sim_time

    def close(self) -> None:
        for subscriber in self.subscribers:
            subscriber.unregister()
        if self.rospy.core.is_initialized():
            self.rospy.signal_shutdown("sw2sim plot is done")
