"""`sw2sim plot` under ROS 2: an rclpy node finds the topics by discovery, rosidl's
classes describe the types, and its subscriptions take the publishers' reliability and
durability as rqt_plot's `choose_qos` does
(https://github.com/ros-visualization/rqt_plot/blob/1.4.0/src/rqt_plot/rosplot.py#L105-L147).

The node's clock follows /clock (use_sim_time) once a publisher of /clock is found, so
its time is the simulation's under `sw2sim ros2` or Gazebo Sim's bridge. Like every ROS 2
process the tool starts, it keeps to 127.0.0.1 in the terminal's ROS_DOMAIN_ID
(sw2sim.ros2.discovery). Ctrl-C is the command's to handle (rclpy's signal handler is
off), and the executor's thread is stopped before the node is destroyed.
"""

from __future__ import annotations

import importlib
import os
import re
import sys
import threading

from .fields import PlotError, Slot

NAME = "ROS 2"
QUEUE = 10_000   # messages a subscription holds until the plot takes them
NUMBERS = {"float", "double", "long double", "char", "octet", "int8", "uint8", "int16",
           "uint16", "int32", "uint32", "int64", "uint64"}


def problem() -> str | None:
    """Why ROS 2 cannot be used here, or None."""
    from ..ros2.run import missing
    return missing()


def prepare() -> None:
    """Before rclpy loads: this machine only, and the built message packages' libraries
    (the process starts again where the loader must see another LD_LIBRARY_PATH)."""
    from ..ros2 import discovery, messages
    if messages.ready():
        env = messages.environment()
        if env.get("LD_LIBRARY_PATH") != os.environ.get("LD_LIBRARY_PATH"):
            os.execve(sys.executable, sys.orig_argv, env)
    os.environ.update(discovery.environment(discovery.domain_id()))
    for variable in ("ROS_LOCALHOST_ONLY", "ROS_STATIC_PEERS"):
        os.environ.pop(variable, None)


def slot(text: str) -> Slot:
    """A rosidl field type (`double`, `sequence<double>`, `double[3]`, `std_msgs/Header`)
    as a Slot."""
    size = None
    if m := re.fullmatch(r"sequence<(.+?)(?:,\s*\d+)?>", text):
        text, size = m[1], -1
    elif m := re.fullmatch(r"(.+)\[(\d+)\]", text):
        text, size = m[1], int(m[2])
    if text in NUMBERS:
        return Slot(text, "number", size)
    if text == "boolean":
        return Slot(text, "bool", size)
    if re.fullmatch(r"w?string(<\d+>)?", text):
        return Slot(text, "text", size)
    return Slot(text, "message", size)


def _full(kind: str) -> str:
    """`std_msgs/Header` as rosidl names it in a type's fields -> `std_msgs/msg/Header`."""
    parts = kind.split("/")
    return f"{parts[0]}/msg/{parts[1]}" if len(parts) == 2 else kind


class Source:
    """The ROS 2 side of one plot: one node, `sw2sim_plot`, spun in a thread of its own."""

    name = NAME

    def __init__(self):
        import rclpy
        from rclpy.executors import SingleThreadedExecutor
        from rclpy.signals import SignalHandlerOptions
        self.rclpy = rclpy
        self.context = rclpy.Context()
        rclpy.init(context=self.context, signal_handler_options=SignalHandlerOptions.NO)
        self.node = rclpy.create_node("sw2sim_plot", context=self.context)
        self.executor = SingleThreadedExecutor(context=self.context)
        self.executor.add_node(self.node)
        self.stop = threading.Event()
        self.spinner = threading.Thread(target=self._spin, daemon=True)
        self.spinner.start()
        self.sim_time = False

    def _spin(self) -> None:
        while not self.stop.is_set():
            try:
                self.executor.spin_once(timeout_sec=0.05)
            except Exception:  # noqa: BLE001  (the context is shutting down)
                if self.stop.is_set():
                    return
                raise

    def topics(self) -> dict[str, str]:
        """The topics with a publisher, and their types; /clock switches on use_sim_time."""
        found = {}
        for name, types in self.node.get_topic_names_and_types():
            if types and self.node.count_publishers(name):
                found[name] = types[0]
        if "/clock" in found and not self.sim_time:
            from rclpy.parameter import Parameter
            self.node.set_parameters([Parameter("use_sim_time", Parameter.Type.BOOL, True)])
            self.sim_time = True
        return found

    def _class(self, kind: str):
        """The class of `pkg/msg/Name`, from the module `pkg.msg` (as rosidl_runtime_py's
        get_message finds it, which the wheels here do not include)."""
        package, _, name = _full(kind).partition("/msg/")
        try:
            return getattr(importlib.import_module(f"{package}.msg"), name)
        except (AttributeError, ImportError, ValueError):
            raise PlotError(f"the message type {kind} is not known to this Python: its "
                            f"package's messages are not installed") from None

    def describe(self, kind: str) -> dict[str, Slot]:
        return {name: slot(text)
                for name, text in self._class(kind).get_fields_and_field_types().items()}

    def subscribe(self, topic: str, kind: str, on_message) -> None:
        self.node.create_subscription(self._class(kind), topic, on_message,
                                      self._qos(topic))

    def _qos(self, topic: str):
        from rclpy.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy
        # deep enough for a slow or busy plotter to catch up on a simulation that runs
        # far faster than real time (rqt_plot keeps 10: it draws the newest, not each one)
        qos = QoSProfile(depth=QUEUE)
        publishers = self.node.get_publishers_info_by_topic(topic)
        if publishers:
            every = lambda test: all(test(p.qos_profile) for p in publishers)  # noqa: E731
            qos.reliability = (ReliabilityPolicy.RELIABLE
                               if every(lambda q: q.reliability == ReliabilityPolicy.RELIABLE)
                               else ReliabilityPolicy.BEST_EFFORT)
            qos.durability = (DurabilityPolicy.TRANSIENT_LOCAL
                              if every(lambda q: q.durability == DurabilityPolicy.TRANSIENT_LOCAL)
                              else DurabilityPolicy.VOLATILE)
        return qos

    def now(self) -> float:
        return self.node.get_clock().now().nanoseconds * 1e-9

    def stamp(self, message) -> float | None:
        """The message's header stamp, None without one or unset."""
        header = getattr(message, "header", None)
        stamp = getattr(header, "stamp", None)
        if stamp is None or not (stamp.sec or stamp.nanosec):
            return None
        return stamp.sec + stamp.nanosec * 1e-9

    def uses_sim_time(self) -> bool:
        return self.sim_time

    def close(self) -> None:
        self.stop.set()
        self.executor.shutdown(timeout_sec=1.0)
        self.spinner.join(timeout=2.0)
        self.node.destroy_node()
        if self.context.ok():
            self.rclpy.shutdown(context=self.context)
