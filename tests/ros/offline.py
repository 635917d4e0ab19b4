"""The simulation node (sw2sim.ros.world) without a ROS master: rospy's publishers,
subscribers, services and parameters replaced by ones that keep what they are given, so
that a test steps the simulation itself and reads what it would have sent, with no
process, no port and no waiting on a wall clock.

    world, node = start("example_4", ["joint_state_controller", "block_controller"], mp)
    run(world, 2.0)                      # to 2 s of simulated time
    node.topics["/example_4/joint_states"].sent
"""

from __future__ import annotations

import yaml

from packages import EXAMPLES


class Topic:
    """A publisher that keeps every message."""

    def __init__(self, name: str):
        self.name = name
        self.sent = []

    def publish(self, message) -> None:
        self.sent.append(message)

    def unregister(self) -> None:
        pass


class Node:
    """What World uses of rospy, over a parameter dictionary."""

    def __init__(self, parameters: dict):
        import rospy
        self.Time = rospy.Time
        self.parameters = parameters
        self.topics: dict[str, Topic] = {}
        self.subscribers: dict[str, object] = {}
        self.services: dict[str, object] = {}
        self.log: list[str] = []

    def Publisher(self, name, kind, queue_size=None, latch=False):  # noqa: N802  (rospy's)
        return self.topics.setdefault(name, Topic(name))

    def Subscriber(self, name, kind, callback):  # noqa: N802
        self.subscribers[name] = callback
        return Topic(name)

    def Service(self, name, kind, handler):  # noqa: N802
        self.services[name] = handler

    def _lookup(self, key: str):
        value = self.parameters
        for part in key.strip("/").split("/"):
            value = value[part]
        return value

    def has_param(self, key: str) -> bool:
        try:
            self._lookup(key)
        except (KeyError, TypeError):
            return False
        return True

    def get_param(self, key: str):
        return self._lookup(key)

    def logwarn(self, text, *args):
        self.log.append(text % args if args else text)

    logerr = loginfo = logwarn


def start(example: str, controllers: list[str], monkeypatch):
    """A World with the example's model spawned and `controllers` loaded and started, as
    the example's gazebo.launch has them; the wall clock is held to simulated time (real
    time), so that /clock ticks as it would at a real-time factor of 1."""
    from sw2sim.ros import messages
    from sw2sim.ros import world as world_module
    messages.ensure()
    monkeypatch.setenv("ROS_PACKAGE_PATH", str(EXAMPLES))
    package = EXAMPLES / example
    config = package / "config" / f"joint_names_{example}.yaml"
    node = Node(yaml.safe_load(config.read_text()))
    world = world_module.World(node)
    monkeypatch.setattr(world_module.time, "monotonic", lambda: world.time)
    world.services()
    world.spawn((package / "urdf" / f"{example}.urdf").read_text(), "")
    for name in controllers:
        assert world.load(name), name
    assert world.switch(controllers, [])
    return world, node


def run(world, until: float) -> None:
    """Step the simulation to `until` seconds of simulated time."""
    while world.time < until - 1e-9:
        world.step()


def call(node: Node, service: str, request=None):
    return node.services[service](request)


def stamps(topic: Topic) -> list[float]:
    return [m.header.stamp.to_sec() for m in topic.sent]
