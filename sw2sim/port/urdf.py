"""The URDF for ROS 2: ros2_control and the gz_ros2_control plugin instead of ROS 1's
transmissions and gazebo_ros_control, mesh URIs in the new package's name.

Everything else (links, joints, limits, inertias, materials, comments, other <gazebo>
elements) is kept as it is. The element and parameter names are gz_ros2_control's (jazzy
branch: gz_hardware_plugins.xml names the hardware plugin `gz_ros2_control/GazeboSimSystem`,
gz_ros2_control_plugin.cpp the system plugin `gz_ros2_control::GazeboSimROS2ControlPlugin`
in the library `gz_ros2_control-system`, which reads the YAML named in <parameters>).
"""

from __future__ import annotations

import copy
import difflib
from dataclasses import dataclass, field
from pathlib import Path

from lxml import etree

from .. import mesh_paths, xmlsafe
from ..package import Package

# ROS 1 hardware interfaces (hardware_interface/..., or bare) -> ros2_control command interface
INTERFACES = {"EffortJointInterface": "effort", "VelocityJointInterface": "velocity",
              "PositionJointInterface": "position"}
STATE_ONLY = {"JointStateInterface"}
STATE_INTERFACES = ("position", "velocity", "effort")
MOVABLE = ("revolute", "continuous", "prismatic")
ROS_CONTROL_PLUGIN = "libgazebo_ros_control.so"
JOINT_STATE_PLUGIN = "libgazebo_ros_joint_state_publisher.so"
HARDWARE = "gz_ros2_control/GazeboSimSystem"


@dataclass
class Transmissions:
    commands: dict[str, list[str]] = field(default_factory=dict)   # joint -> interfaces
    choices: list[str] = field(default_factory=list)


def read_tree(package: Package) -> etree._ElementTree:
    """A copy of the package's URDF document, comments included, to rewrite."""
    if package.expanded_from is None:
        return xmlsafe.parse_bytes(xmlsafe.read_bytes(package.urdf), url=package.urdf) \
            .getroottree()
    return copy.deepcopy(package.robot.getroottree())


def movable_joints(robot: etree._Element) -> dict[str, str]:
    """Movable joints by name, with their types, in the URDF's order."""
    return {j.get("name"): j.get("type") for j in robot.findall("joint")
            if j.get("type") in MOVABLE and j.get("name")}


def read_transmissions(robot: etree._Element, urdf: str) -> Transmissions:
    """Each transmitted joint's command interfaces, from its <hardwareInterface> elements."""
    found = Transmissions()
    for t in robot.findall("transmission"):
        where = f"{urdf}:{t.sourceline}" if t.sourceline else urdf
        for joint in t.findall("joint"):
            name = joint.get("name", "")
            kinds = [(h.text or "").strip() for h in joint.findall("hardwareInterface")]
            if not kinds:   # the pre-Indigo form puts it on the actuator only
                kinds = [(h.text or "").strip() for h in t.findall("actuator/hardwareInterface")]
            for kind in kinds:
                bare = kind.rsplit("/", 1)[-1]
                if bare in INTERFACES:
                    interfaces = found.commands.setdefault(name, [])
                    if INTERFACES[bare] not in interfaces:
                        interfaces.append(INTERFACES[bare])
                elif bare not in STATE_ONLY:
                    found.choices.append(f"{where}: transmission `{t.get('name')}` gives {name} "
                                         f"the interface {kind!r}, which ros2_control has no "
                                         "counterpart for; the joint reports its state only.")
        for actuator in t.findall("actuator"):
            reduction = (actuator.findtext("mechanicalReduction") or "1").strip()
            try:
                geared = float(reduction) != 1.0
            except ValueError:
                geared = True
            if geared:
                found.choices.append(f"{where}: transmission `{t.get('name')}` has a mechanical "
                                     f"reduction of {reduction}; gz_ros2_control commands the "
                                     "joint directly, so the reduction is not applied. Scale your "
                                     "commands and limits by it.")
    return found


def control_period(robot: etree._Element) -> float | None:
    """gazebo_ros_control's <controlPeriod> (seconds), when the URDF gives one."""
    for plugin in robot.findall("gazebo/plugin"):
        if plugin.get("filename", "").endswith(ROS_CONTROL_PLUGIN):
            text = (plugin.findtext("controlPeriod") or "").strip()
            try:
                value = float(text)
            except ValueError:
                return None
            return value if value > 0 else None
    return None


def joint_state_rate(robot: etree._Element) -> float | None:
    """The gazebo_ros joint_state_publisher plugin's <updateRate> (Hz), when it gives one."""
    for plugin in robot.findall("gazebo/plugin"):
        if plugin.get("filename", "").endswith(JOINT_STATE_PLUGIN):
            try:
                value = float((plugin.findtext("updateRate") or "").strip())
            except ValueError:
                return None
            return value if value > 0 else None
    return None


@dataclass
class Rewrite:
    robot: etree._Element     # the new URDF, changed in place until `text` is read
    choices: list[str]
    meshes: dict[str, Path]   # the new package:// path inside the package -> the source file

    @property
    def text(self) -> str:
        return _serialize(self.robot)


def rewrite(tree: etree._ElementTree, package: Package, new_name: str,
            commands: dict[str, list[str]], state_joints: list[str]) -> Rewrite:
    """The ROS 2 URDF text. `commands` gives each commanded joint's command interfaces;
    `state_joints` every joint the ros2_control block lists (in order)."""
    robot = tree.getroot()
    urdf = package.urdf.relative_to(package.root).as_posix()
    choices: list[str] = []
    meshes = _rename_meshes(robot, package, new_name, urdf, choices)
    dropped = {"transmission": 0, "control": 0, "state": 0}
    for t in robot.findall("transmission"):
        _remove(t)
        dropped["transmission"] += 1
    for gazebo in robot.findall("gazebo"):
        for plugin in gazebo.findall("plugin"):
            filename = plugin.get("filename", "")
            if filename.endswith(ROS_CONTROL_PLUGIN):
                _remove(plugin)
                dropped["control"] += 1
            elif filename.endswith(JOINT_STATE_PLUGIN):
                _remove(plugin)
                dropped["state"] += 1
            elif filename.startswith("libgazebo_ros"):
                choices.append(f"{urdf}:{plugin.sourceline}: the Gazebo Classic plugin "
                               f"{filename} was kept, but Gazebo Sim does not load it; "
                               "replace it with its gz-sim or ros_gz counterpart.")
        if len(gazebo) == 0 and not gazebo.attrib:
            _remove(gazebo)
    if dropped["transmission"]:
        choices.append(f"The {dropped['transmission']} <transmission> element(s) were replaced by "
                       "the <ros2_control> block, which names each joint's command interface.")
    if dropped["control"]:
        choices.append("The gazebo_ros_control plugin was replaced by gz_ros2_control's "
                       "(gz_ros2_control::GazeboSimROS2ControlPlugin), which reads "
                       "config/controllers.yaml.")
    if dropped["state"]:
        choices.append("The gazebo_ros joint_state_publisher plugin was removed: "
                       "joint_state_broadcaster publishes /joint_states in ROS 2.")
    _append(robot, _ros2_control_block(robot, commands, state_joints, choices))
    _append(robot, _gz_plugin(new_name))
    return Rewrite(robot, choices, meshes)


def keep_ros2(tree: etree._ElementTree, package: Package, new_name: str,
              fix) -> tuple[Rewrite, list[str]]:
    """The URDF of a package already in ROS 2 form: its <ros2_control> blocks and plugins
    kept, mesh URIs in the new name, what `fix` (sw2sim.port.ros2_form.fix_urdf) finds
    fixed; gz_ros2_control's plugin added only where it has none. Returns the rewrite and
    the fixes, in words."""
    robot = tree.getroot()
    choices: list[str] = []
    meshes = _rename_meshes(robot, package, new_name,
                            package.urdf.relative_to(package.root).as_posix(), choices)
    fixes = fix(robot, package.root, new_name)
    if not any("gz_ros2_control" in (p.get("name") or "") + (p.get("filename") or "")
               for p in robot.iter("plugin")):
        _append(robot, _gz_plugin(new_name))
        fixes.append("it had no gz_ros2_control plugin, which starts the controllers in "
                     "Gazebo Sim: one reading config/controllers.yaml was added")
    return Rewrite(robot, choices, meshes), fixes


# ros2_control (Jazzy, 4.x) reads every <mimic> of a joint in a <ros2_control> block and looks
# the joint it names up among the block's joints, stopping the controller manager with
# "Mimic joint '...' not found in <ros2_control> tag" when it is not there
# (hardware_interface/src/component_parser.cpp, parse_control_resources_from_urdf).
MIMIC_SOURCE = ("https://github.com/ros-controls/ros2_control/blob/4.46.0/hardware_interface/"
                "src/component_parser.cpp#L1061-L1076")


def drop_broken_mimics(robot: etree._Element, urdf: str) -> list[str]:
    """Remove each <mimic> that names no movable joint of the URDF (a typo, a renamed or
    fixed joint, the joint itself); say which, and the fix."""
    movable = movable_joints(robot)
    said = []
    for joint in robot.findall("joint"):
        name = joint.get("name", "")
        for mimic in joint.findall("mimic"):
            target = mimic.get("joint") or ""
            if target in movable and target != name:
                continue
            where = f"{urdf}:{mimic.sourceline}" if mimic.sourceline else urdf
            others = [n for n in movable if n != name]
            near = difflib.get_close_matches(target, others, n=1, cutoff=0.4)
            why = ("is the joint itself" if target == name else
                   f"is a {_type_of(robot, target)} joint" if _type_of(robot, target) else
                   "is not a joint of the URDF")
            _remove(mimic)
            said.append(f"{where}: the <mimic> of joint {name} names {target!r}, which {why}; "
                        "ros2_control would stop on it (\"Mimic joint ... not found in "
                        "<ros2_control> tag\"), so it was left out and "
                        f"{name} moves on its own. Fix: write <mimic joint=\""
                        f"{near[0] if near else 'NAME'}\"> in the source" +
                        (" if that is the joint meant" if near else
                         ", NAME a revolute, continuous or prismatic joint") +
                        f", and port again ({MIMIC_SOURCE}).")
    return said


def _type_of(robot: etree._Element, name: str) -> str | None:
    for joint in robot.findall("joint"):
        if joint.get("name") == name:
            return joint.get("type")
    return None


def _serialize(robot: etree._Element) -> str:
    """The document: declaration, the comments around <robot> each on its own line, <robot>."""
    before, after = [], []
    node = robot.getprevious()
    while node is not None:
        before.insert(0, node)
        node = node.getprevious()
    node = robot.getnext()
    while node is not None:
        after.append(node)
        node = node.getnext()
    parts = ['<?xml version="1.0" encoding="utf-8"?>']
    parts += [_alone(n) for n in before]
    parts.append(_alone(robot))
    parts += [_alone(n) for n in after]
    return "\n".join(parts) + "\n"


def _alone(node) -> str:
    tail, node.tail = node.tail, None
    try:
        return etree.tostring(node, encoding="unicode").strip()
    finally:
        node.tail = tail


def _ros2_control_block(robot, commands, state_joints, choices) -> etree._Element:
    limits = {j.get("name"): j.find("limit") for j in robot.findall("joint")}
    block = etree.Element("ros2_control", name="GazeboSimSystem", type="system")
    hardware = etree.SubElement(block, "hardware")
    etree.SubElement(hardware, "plugin").text = HARDWARE
    unlimited = []
    for name in state_joints:
        joint = etree.SubElement(block, "joint", name=name)
        for interface in commands.get(name, []):
            command = etree.SubElement(joint, "command_interface", name=interface)
            bound = _bound(limits.get(name), interface)
            if bound:
                etree.SubElement(command, "param", name="min").text = f"{-bound:g}"
                etree.SubElement(command, "param", name="max").text = f"{bound:g}"
            elif interface in ("effort", "velocity"):
                unlimited.append(f"{name} ({interface})")
        for interface in STATE_INTERFACES:
            etree.SubElement(joint, "state_interface", name=interface)
    if unlimited:
        choices.append("No min/max on the command of " + ", ".join(unlimited) + ": the URDF "
                       "gives no positive limit for it (the exporter's default is 0). Enter the "
                       "real limits in the exporter, or in the joint's <limit>, and port again.")
    state_only = [j for j in state_joints if j not in commands]
    if state_only:
        choices.append("Joints without a transmission get state interfaces only, so "
                       "joint_state_broadcaster reports them and nothing drives them: " +
                       ", ".join(state_only) + " (--effort-joints gives them an effort command).")
    return block


def _bound(limit, interface: str) -> float | None:
    if limit is None or interface not in ("effort", "velocity"):
        return None
    try:
        value = float(limit.get(interface, ""))
    except ValueError:
        return None
    return value if value > 0 else None


def _gz_plugin(new_name: str) -> etree._Element:
    gazebo = etree.Element("gazebo")
    plugin = etree.SubElement(gazebo, "plugin", filename="gz_ros2_control-system",
                              name="gz_ros2_control::GazeboSimROS2ControlPlugin")
    etree.SubElement(plugin, "parameters").text = f"$(find {new_name})/config/controllers.yaml"
    return gazebo


def _append(robot: etree._Element, element: etree._Element, indent: str = "  ") -> None:
    """Add `element` at the end of <robot>, indented as the file is."""
    _indent(element, indent, 1)
    last = robot[-1] if len(robot) else None
    if last is None:
        robot.text = "\n" + indent
    else:
        last.tail = "\n" + indent
    robot.append(element)
    element.tail = "\n"


def _indent(element, indent: str, level: int) -> None:
    if len(element):
        element.text = "\n" + indent * (level + 1)
        for child in element:
            _indent(child, indent, level + 1)
            child.tail = "\n" + indent * (level + 1)
        element[-1].tail = "\n" + indent * level


def _remove(element: etree._Element) -> None:
    """Remove an element and the whitespace before it, keeping what follows in place."""
    parent = element.getparent()
    previous = element.getprevious()
    if previous is not None:
        previous.tail = element.tail
    else:
        parent.text = element.tail
    parent.remove(element)


def _rename_meshes(robot, package: Package, new_name: str, urdf: str,
                   choices: list[str]) -> dict[str, Path]:
    """Point every mesh at package://<new_name>/<path in the package>; return what to copy."""
    files = None
    copies: dict[str, Path] = {}
    renamed: dict[str, int] = {}            # the package a renamed path named -> how many
    elsewhere: dict[str, list[str]] = {}    # another package -> where its meshes are named
    for mesh in robot.iter("mesh"):
        filename = (mesh.get("filename") or "").strip()
        if not filename:
            continue
        where = f"{urdf}:{mesh.sourceline}" if mesh.sourceline else urdf
        if filename.startswith("package://"):
            named = filename[len("package://"):].partition("/")[0]
            if named not in (package.name, package.root.name):
                elsewhere.setdefault(named, []).append(where)
                continue
        if files is None:
            files = mesh_paths.package_files(package.root)
        found = [f for f in mesh_paths.matches(files, filename)]
        given = "/".join(mesh_paths.path_parts(filename))
        if len(found) != 1:
            choices.append(f"{where}: the mesh {filename} names no single file of the package "
                           f"({len(found)} found); its path was only renamed to the new package. "
                           "Run `sw2sim check` on the source for the fix.")
            rel = given
        else:
            rel = found[0].as_posix()
            if rel.split("/")[0] not in ("meshes",):
                rel = f"meshes/{rel}"
                choices.append(f"{where}: the mesh {filename} is not in meshes/; it was copied to "
                               f"{rel}, the folder the package installs.")
            elif rel != given:
                choices.append(f"{where}: the mesh {filename} means the file {found[0].as_posix()} "
                               "(capitals or slashes differ); the URDF now names it exactly, as "
                               "Linux needs.")
            copies[rel] = package.root / found[0]
        new = f"package://{new_name}/{rel}"
        if new != filename:
            mesh.set("filename", new)
            old = filename[len("package://"):].partition("/")[0] \
                if filename.startswith("package://") else ""
            renamed[old] = renamed.get(old, 0) + 1
    if renamed:
        before = [f"package://{old}/" if old else "a path without package://"
                  for old in renamed if old != new_name]
        choices.append(f"{sum(renamed.values())} mesh path(s) now start with "
                       f"package://{new_name}/" +
                       (f" (they named {' and '.join(before)})" if before else "") + ".")
    for named, places in elsewhere.items():
        choices.append(f"{len(places)} mesh path(s) name the package {named} (first at "
                       f"{places[0]}), whose files are not in this one; they were left as "
                       "they are, so that package must be installed too.")
    return copies
