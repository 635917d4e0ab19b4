"""What a ROS 2 package tells ros2_control: the URDF's `<ros2_control>` block (each joint's
command and state interfaces and their `min`/`max` params), the gz_ros2_control plugin's
settings (`position_proportional_gain`, `hold_joints`), and the controllers' YAML in
ros2_control's format (read generically: a node's `ros__parameters`, with the `/**`
wildcard's under them)."""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import yaml

GZ_PLUGINS = ("gz_ros2_control-system", "libgz_ros2_control-system.so",
              "ign_ros2_control-system", "libign_ros2_control-system.so")


@dataclasses.dataclass
class JointInterfaces:
    name: str
    command: list[str]
    state: list[str]
    limits: dict[str, tuple[float, float]]   # command interface -> (min, max) params
    initial: dict[str, float]                # state interface -> initial_value param


@dataclasses.dataclass
class Setup:
    name: str
    root: Path
    urdf: Path
    joints: dict[str, JointInterfaces]
    update_rate: float
    enforce_command_limits: bool
    position_proportional_gain: float
    controllers: dict[str, str]              # name -> type, in the YAML's order
    parameters: dict[str, dict]              # node name -> its parameters
    hold_joints: bool = True                 # the gz_ros2_control plugin's <hold_joints>
    hardware: list[tuple[str, str, list[str]]] = dataclasses.field(default_factory=list)
    # each <ros2_control> block: (name, its <hardware><plugin>, its joints)
    problems: list[str] = dataclasses.field(default_factory=list)   # to tell the user

    def params(self, node: str) -> dict:
        return {**self.parameters.get("**", {}), **self.parameters.get(node, {})}


def _float(text, default=math.nan) -> float:
    try:
        return float(text)
    except (TypeError, ValueError):
        return default


def read_ros2_control(robot) -> dict[str, JointInterfaces]:
    joints: dict[str, JointInterfaces] = {}
    for block in robot.findall("ros2_control"):
        for joint in block.findall("joint"):
            command, state, limits, initial = [], [], {}, {}
            for interface in joint.findall("command_interface"):
                name = interface.get("name", "")
                command.append(name)
                params = {p.get("name"): p.text for p in interface.findall("param")}
                if "min" in params or "max" in params:
                    limits[name] = (_float(params.get("min"), -math.inf),
                                    _float(params.get("max"), math.inf))
            for interface in joint.findall("state_interface"):
                name = interface.get("name", "")
                state.append(name)
                params = {p.get("name"): p.text for p in interface.findall("param")}
                if "initial_value" in params:
                    initial[name] = _float(params["initial_value"], 0.0)
            joints[joint.get("name")] = JointInterfaces(joint.get("name"), command, state,
                                                        limits, initial)
    return joints


def hardware_components(robot) -> list[tuple[str, str, list[str]]]:
    """Each <ros2_control> block's name, hardware plugin and joints, in the URDF's order."""
    return [(block.get("name", ""), (block.findtext("hardware/plugin") or "").strip(),
             [j.get("name") for j in block.findall("joint")])
            for block in robot.findall("ros2_control")]


def sdf_bool(text: str | None, default: bool) -> bool | None:
    """An SDF boolean as sdformat reads it: true/1 or false/0 (any case); None when the
    text is neither."""
    if text is None or not text.strip():
        return default
    word = text.strip().lower()
    return True if word in ("true", "1") else False if word in ("false", "0") else None


def gz_plugin(robot):
    for plugin in robot.iter("plugin"):
        if (plugin.get("filename") or "") in GZ_PLUGINS or "gz_ros2_control" in (plugin.get("name") or ""):
            return plugin
    return None


def _nodes(document) -> dict[str, dict]:
    """Node name (without a leading slash) -> its ros__parameters, wildcards merged under."""
    if not isinstance(document, dict):
        return {}
    wildcard = {}
    found = {}
    for key, value in document.items():
        if not isinstance(value, dict):
            continue
        params = value.get("ros__parameters")
        if params is None:   # a namespace level: /ns: {node: {ros__parameters: ...}}
            for inner, sub in _nodes(value).items():
                found[inner] = sub
            continue
        name = str(key).strip("/")
        if name in ("**", "*"):
            wildcard.update(params or {})
        else:
            found[name] = dict(params or {})
    return {name: {**wildcard, **params} for name, params in found.items()} | (
        {"**": wildcard} if wildcard else {})


def parameters_of(document) -> dict[str, dict]:
    """A ROS 2 parameter file's nodes: node name -> its parameters, wildcards merged."""
    return _nodes(document)


def controllers_yaml(root: Path, plugin) -> Path | None:
    """The YAML the plugin names (`<parameters>`, a package:// or $(find ...) path), else
    config/controllers.yaml, else the package's only config/*.yaml holding a controller
    manager."""
    if plugin is not None:
        text = (plugin.findtext("parameters") or "").strip()
        if text:
            for marker in ("package://", "$(find "):
                if marker in text:
                    rest = text.split(marker, 1)[1].replace(")", "", 1)
                    candidate = root / rest.split("/", 1)[1] if "/" in rest else None
                    if candidate is not None and candidate.is_file():
                        return candidate
            candidate = Path(text)
            if candidate.is_file():
                return candidate
            candidate = root / "config" / Path(text).name
            if candidate.is_file():
                return candidate
    default = root / "config" / "controllers.yaml"
    if default.is_file():
        return default
    for candidate in sorted((root / "config").glob("*.yaml")):
        if "controller_manager" in candidate.read_text(encoding="utf-8", errors="replace"):
            return candidate
    return None


def read(package) -> Setup:
    """The Setup of a ROS 2 package (a sw2sim Package)."""
    robot = package.robot
    plugin = gz_plugin(robot)
    source = controllers_yaml(package.root, plugin)
    parameters = _nodes(yaml.safe_load(source.read_text(encoding="utf-8"))) if source else {}
    manager = parameters.get("controller_manager", {})
    controllers = {}
    for key, value in manager.items():
        if isinstance(value, dict) and "type" in value:
            controllers[key] = str(value["type"])
    # the flattened form: controller_manager.ros__parameters has "name.type": "..."
    for key, value in manager.items():
        if isinstance(key, str) and key.endswith(".type") and isinstance(value, str):
            controllers[key[:-5]] = value
    gain = 0.1
    hold, problems = True, []
    if plugin is not None:
        gain = _float(plugin.findtext("position_proportional_gain"), 0.1)
        text = plugin.findtext("hold_joints")
        hold = sdf_bool(text, True)
        if hold is None:
            problems.append(f"{package.urdf.name}: the gz_ros2_control plugin's <hold_joints> is "
                            f"{text.strip()!r}; write true or false (taken as true, the default)")
            hold = True
    return Setup(name=package.name, root=package.root, urdf=package.urdf,
                 joints=read_ros2_control(robot),
                 update_rate=_float(manager.get("update_rate"), 100.0),
                 enforce_command_limits=bool(manager.get("enforce_command_limits", False)),
                 position_proportional_gain=gain, controllers=controllers,
                 parameters=parameters, hold_joints=hold,
                 hardware=hardware_components(robot), problems=problems)
