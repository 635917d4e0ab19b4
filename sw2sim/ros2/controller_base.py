"""What every controller of sw2sim.ros2.controllers shares: the Controller class (its
lifecycle hooks and the interfaces it lists for the controller manager), the reading of a
controller's `gains`, and the laws its efforts are kept as."""

from __future__ import annotations

import threading


class ConfigError(ValueError):
    """A controller's parameters cannot be used (the message says which and why)."""


def gains_of(params: dict, joint: str) -> dict:
    gains = params.get("gains") or {}
    found = gains.get(joint)
    if isinstance(found, dict):
        return found
    # the flattened form: gains.<joint>.p
    return {k.split(".", 2)[2]: v for k, v in params.items()
            if isinstance(k, str) and k.startswith(f"gains.{joint}.")}


def value(law, q: float, v: float) -> float:
    if isinstance(law, tuple):
        return law[0] + law[1] * q + law[2] * v
    return float(law)


class Controller:
    """One controller: `update` returns {joint: {interface: number or Law}}."""

    kind = ""
    state_topic = None

    chainable = False   # a ChainableControllerInterface (exports reference interfaces)

    def __init__(self, name: str, kind: str, params: dict, joints: dict):
        self.name, self.kind, self.params = name, kind, params
        self.lock = threading.Lock()
        self.available = joints    # joint -> JointInterfaces of the URDF's ros2_control
        self.output: dict[str, dict] = {}
        self.active = False        # set by the controller manager (sw2sim.ros2.manager)

    def check_joints(self, names) -> list[str]:
        names = [str(n) for n in (names or [])]
        if not names:
            raise ConfigError(f"{self.name}: no joints given")
        unknown = [n for n in names if n not in self.available]
        if unknown:
            raise ConfigError(f"{self.name}: joint(s) {', '.join(unknown)} not in the URDF's "
                              "<ros2_control> block")
        return names

    def activate(self, state) -> None:
        pass

    def deactivate(self) -> dict:
        """on_deactivate: what it writes to its command interfaces as it lets them go,
        {joint: {interface: value}}."""
        return {}

    def update(self, now: float, period: float, state) -> dict:
        return {}

    # what the controller manager lists: "joint/interface" names, in the controller's order
    def command_interface_names(self) -> list[str]:
        return []

    def state_interface_names(self, available: list[str]) -> list[str]:
        """`available`: the hardware's state interfaces (for a controller that takes all)."""
        return []

    def exported_interface_names(self) -> list[str]:
        """A chainable controller's reference (and exported state) interfaces."""
        return []
