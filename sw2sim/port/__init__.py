"""`sw2sim port`: a ROS 1 exporter package as a ROS 2 Jazzy ament_cmake package.

    package.xml              format 3, ament_cmake, the run-time dependencies (manifest.py)
    CMakeLists.txt           installs the folders into share/<name> (cmake.py)
    urdf/<name>.urdf         ros2_control and gz_ros2_control instead of transmissions and
                             gazebo_ros_control; mesh paths in the new name (urdf.py)
    config/controllers.yaml  the ROS 1 controllers' ROS 2 counterparts (controllers.py); for an
                             export that commands nothing, a trajectory controller and a
                             wheel velocity controller (defaults.py)
    launch/*.launch.py       RViz, and Gazebo Sim with the controllers (launch.py)
    rviz/<file>.rviz         the package's RViz configuration, for RViz 2 (rviz.py)
    meshes/                  copied as they are; meshes/simplified/ holds a lighter copy of
                             each heavy mesh that a <collision> names (collision_meshes.py)
    README.md                how to build and run it, and every choice made (readme.py)

A package already in ROS 2 form (an ament package.xml or a <ros2_control> block) keeps its
controllers' YAML and its <ros2_control> blocks as they are; only what cannot be installed
is fixed, and said (ros2_form.py). A package without package.xml is named by its own files
(sw2sim.package_name).

The source is read as every command reads it (a folder or a .zip; a .xacro-only package is
expanded) and never written to. Every decision taken for the user is a line of
`PortReport.choices`, printed by the command and listed in README.md.

Porting again into an earlier port's folder replaces only what the port writes: the files
the user added there (a node in scripts/, notes) stay, and so do the port's files the user
changed when the new port would write them as before (a CMakeLists.txt with an install()
line added, as the ROS 2 pages have the reader do). The marker file, MARKER, lists the
files a port wrote with the SHA-256 of each, which tells the two apart.
"""

from __future__ import annotations

import hashlib
import json
import math
import os
import shutil
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

from .. import mesh_paths
from ..archive import shown
from ..package import Package, as_package
from . import (cmake, collision_meshes, controllers, defaults, launch, manifest, naming,
               ros2_form, rviz, urdf)
from .readme import readme

MARKER = ".sw2sim-port"   # names the files an earlier port wrote, so it may be replaced
MINE = ".mine"            # a port's file the user changed, set aside beside the new one

__all__ = ["PortError", "PortReport", "port"]


class PortError(Exception):
    """The port cannot be made as asked (the output folder, an option); says what to do."""


@dataclass
class PortReport:
    name: str
    package_dir: Path
    choices: list[str] = field(default_factory=list)
    files: list[str] = field(default_factory=list)
    controllers: list[str] = field(default_factory=list)
    source: str = ""
    replaced: bool = False
    # what an earlier port's folder held that was kept: the user's own files, and the
    # port's files the user changed (kept as they are, or beside the new one as FILE.mine)
    kept: list[str] = field(default_factory=list)
    kept_changed: list[str] = field(default_factory=list)
    set_aside: list[str] = field(default_factory=list)

    def format(self) -> str:
        meshes = sum(f.startswith("meshes/") for f in self.files)
        listed = [f for f in self.files if not f.startswith("meshes/")]
        lines = [f"sw2sim port: {self.source} -> {self.package_dir} "
                 f"(ROS 2 Jazzy package `{self.name}`)",
                 f"{len(self.choices)} choice(s) made for you (README.md lists them too):"]
        lines += [f"  - {c}" for c in self.choices]
        lines.append(("replaced the earlier port in " if self.replaced else "wrote ") +
                     f"{self.package_dir}: {', '.join(listed)}" +
                     (f" and {meshes} mesh file(s) in meshes/" if meshes else ""))
        if self.kept:
            lines.append(f"kept your files, which the port does not write: {', '.join(self.kept)}")
        if self.kept_changed:
            lines.append(f"kept as you changed them: {', '.join(self.kept_changed)} (the port "
                         "would write them as it did before)")
        for aside in self.set_aside:
            rel = aside[:aside.rindex(MINE)]
            lines.append(f"{rel}: you had changed it, and the port now writes it differently: "
                         f"yours is kept as {aside}; carry your changes over to the new {rel}")
        workspace = Path(os.path.abspath(self.package_dir)).parent
        where = (f"run `colcon build` in {workspace.parent}" if workspace.name == "src" else
                 "copy the folder into a workspace's src/, run `colcon build`")
        lines.append(f"build it: {where}, then `source install/setup.bash` and "
                     f"`ros2 launch {self.name} gazebo.launch.py`")
        return "\n".join(lines)


def port(source: str | os.PathLike | Package, out: str | os.PathLike, *,
         name: str | None = None, effort_joints=(), default_controllers: bool = True,
         maintainer: str | None = None, license: str | None = None,
         simplify_collisions: bool = True) -> PortReport:
    """Write the ROS 2 package for the ROS 1 package at `source` into the folder `out`.

    A package with no transmissions and no ROS 1 controllers (an export as the exporter
    writes it) gets a controller for each movable joint that --effort-joints does not name
    (sw2sim.port.defaults), unless `default_controllers` is False. A heavy collision mesh
    gets a simplified copy (sw2sim.port.collision_meshes) unless `simplify_collisions` is
    False.

    Raises sw2sim.LoadError when the source cannot be read, PortError when `out` or an
    option cannot be used; nothing is written then. `out` must be missing, empty, or an
    earlier port's output: its files that the port wrote are replaced, the user's own kept
    (PortReport.kept, kept_changed and set_aside say which).
    """
    package = as_package(source)
    out = Path(out)
    shown_source = shown(package.root) or str(package.source or package.root)
    choices: list[str] = []
    new_name = _name(package, name, choices)
    person = None
    if maintainer is not None:
        try:
            person = manifest.parse_maintainer(maintainer)
        except ValueError as exc:
            raise PortError(f"--maintainer: {exc}") from None
    if license is not None and not license.strip():
        raise PortError("--license: give the licence's name, such as Apache-2.0 or "
                        "BSD-3-Clause (SPDX identifiers)")
    if package.manifest is None:
        choices.append(f"The source has no package.xml: its name `{package.name}` was read from "
                       f"{package.name_from}, and package.xml and CMakeLists.txt were written "
                       f"for `{new_name}`.")
    _check_out(out, package.root)

    tree = urdf.read_tree(package)
    robot = tree.getroot()
    urdf_rel = package.urdf.relative_to(package.root).as_posix()
    if package.expanded_from is not None:
        choices.append(f"{urdf_rel} was expanded with xacro into urdf/{new_name}.urdf.")
    elif package.chosen_because:
        choices.append(f"{urdf_rel} was ported ({package.chosen_because}); the package's other "
                       "URDFs were left out.")
    choices += urdf.drop_broken_mimics(robot, urdf_rel)
    joints = urdf.movable_joints(robot)
    effort = _effort_joints(effort_joints, joints)
    form = ros2_form.recognise(package, robot)
    if form is not None:
        if effort:
            raise PortError("--effort-joints gives ROS 1 joints without a transmission a "
                            f"command; {urdf_rel} is already ROS 2 ({', '.join(form.signs)}): "
                            "give the joints their command interface in its <ros2_control> "
                            "block instead")
        planned = controllers.Plan(controllers=[controllers.Controller(n, t) for n, t in
                                                form.controllers.items()])
        added = defaults.Defaults()
        rewritten, fixes = urdf.keep_ros2(tree, package, new_name, ros2_form.fix_urdf)
        choices.insert(0, ros2_form.summary(form, fixes))
        choices += rewritten.choices
    else:
        planned, added, rewritten = _ros1(package, tree, new_name, urdf_rel, joints, effort,
                                          default_controllers, choices)

    files: dict[str, str | Path | bytes] = {}
    for rel in _mesh_files(package.root):
        files[rel] = package.root / rel
    files.update(rewritten.meshes)
    if simplify_collisions:
        simplified = collision_meshes.simplify(rewritten.robot, rewritten.meshes, new_name,
                                                   taken=files)
        files.update(simplified.files)
        choices += simplified.choices
    empty = [rel for rel, path in rewritten.meshes.items()
             if path.suffix.lower() == ".stl" and path.stat().st_size <= 84]
    if empty:
        choices.append(f"{', '.join(empty)}: empty (an STL header and no triangles), copied as "
                       "it is; Gazebo, RViz and MuJoCo show nothing for it. Export the part "
                       "again (`sw2sim check` on the source says how).")
    files[f"urdf/{new_name}.urdf"] = rewritten.text
    files["config/controllers.yaml"] = (
        ros2_form.yaml_text(form, package.root, new_name)
        if form is not None and form.yaml_file is not None else
        controllers.yaml_text(planned, new_name, [c.name for c in added.controllers]))
    rviz_file = rviz.find(package.root)
    if rviz_file is not None:
        text = rviz_file.read_text(encoding="utf-8", errors="replace")
        if rviz.looks_like_rviz1(text):
            text, changed = rviz.convert(text)
            choices.append(f"{rviz_file.relative_to(package.root).as_posix()} was installed as "
                           f"rviz/{rviz_file.name} with its {changed} RViz 1 class names changed "
                           "to RViz 2's, and its RobotModel reading /robot_description; open it "
                           "in RViz 2 and save it again.")
        files[f"rviz/{rviz_file.name}"] = text
    files["launch/display.launch.py"] = launch.display_launch(
        new_name, f"{new_name}.urdf", rviz_file.name if rviz_file else None)
    files["launch/gazebo.launch.py"] = launch.gazebo_launch(
        new_name, f"{new_name}.urdf", planned.names, _spawn_height(package, choices))
    folders = sorted({rel.split("/")[0] for rel in files})
    choices += _left_behind(package.root) if form is None else \
        ros2_form.left_behind(package.root, form)
    files["package.xml"] = manifest.package_xml(
        new_name, package.manifest, [c.package for c in planned.controllers], choices,
        maintainer=person, license=license)
    files["CMakeLists.txt"] = cmake.cmakelists(new_name, folders)
    order = ["package.xml", "CMakeLists.txt", "README.md"]
    listed = order + sorted(f for f in files if f not in order)
    files["README.md"] = readme(new_name, package.name, planned.names, choices, listed,
                                added.usage)

    keep = _keep(out, files)
    replaced = _write(out, files, keep)
    return PortReport(name=new_name, package_dir=out, choices=choices,
                      files=[f for f in listed if f in files], controllers=planned.names,
                      source=shown_source, replaced=replaced, kept=keep.own,
                      kept_changed=keep.changed, set_aside=keep.aside)


def _ros1(package: Package, tree, new_name: str, urdf_rel: str, joints, effort,
          default_controllers: bool, choices: list[str]):
    """The controllers and URDF of a ROS 1 (or raw exporter) package: (plan, the default
    controllers added, the rewritten URDF); what was chosen is appended to `choices`."""
    robot = tree.getroot()
    transmissions = urdf.read_transmissions(robot, urdf_rel)
    period = urdf.control_period(robot)
    ros1, read = controllers.find_ros1_controllers(package.root)
    try:
        planned = controllers.plan(ros1, joints, effort_joints=effort,
                                   update_rate=max(1, round(1 / period)) if period else None,
                                   state_rate=urdf.joint_state_rate(robot))
    except controllers.Conflict as exc:
        raise PortError(f"{exc}. Leave the joint out of --effort-joints, or remove one of the "
                        "controllers from the ROS 1 YAML.") from None
    planned.sources = read
    added = defaults.Defaults()
    ros1_commanded = {j for c in planned.controllers for j in c.commands} - set(effort)
    if default_controllers and defaults.applies(robot, ros1_commanded):
        added = defaults.plan(robot, joints, set(effort), urdf_rel)
        planned.controllers += added.controllers
        planned.choices += added.choices
    commands = _commands(transmissions, planned, joints, effort, choices,
                         {c.name for c in added.controllers})
    rewritten = urdf.rewrite(tree, package, new_name, commands, list(joints))
    choices += transmissions.choices + planned.choices + rewritten.choices
    return planned, added, rewritten


def _spawn_height(package: Package, choices: list[str]) -> float:
    """The height at which Gazebo spawns a free-floating robot so that its lowest collision
    point at the rest pose touches the ground (z = 0), as `sw2sim convert` places it; 0 for
    a robot fixed to the world, or one already standing on z = 0 (within a micrometre)."""
    if package.world_fixed:
        return 0.0
    try:
        import mujoco

        from ..loader import load_package, lowest_collision_point
        model = load_package(package).compile()
        data = mujoco.MjData(model)
        mujoco.mj_kinematics(model, data)
        low = lowest_collision_point(model, data)
    except Exception as exc:  # noqa: BLE001  (any model MuJoCo refuses: spawn as given)
        why = getattr(exc, "message", None) or str(exc)
        choices.append("The robot is spawned at z = 0: its lowest point could not be measured, "
                       f"as MuJoCo does not load the source ({why.splitlines()[0]}); "
                       "`sw2sim check` on the source says how to fix it.")
        return 0.0
    if abs(low) <= 1e-6:
        return 0.0
    height = math.ceil(-low * 1e6) / 1e6     # up to the micrometre: never inside the ground
    choices.append(f"launch/gazebo.launch.py spawns the robot at z = {height:g} m (create's -z): "
                   f"its lowest collision point at the rest pose is at z = {low:.7g} m, so it "
                   "starts on the ground instead of " +
                   ("inside it." if low < 0 else "falling onto it."))
    return height


def _name(package: Package, wanted: str | None, choices: list[str]) -> str:
    if wanted is not None:
        if not naming.is_legal(wanted):
            raise PortError(f"--name {wanted!r}: ROS 2 refuses package names with "
                            f"{naming.why_illegal(wanted)}; use lower-case letters, digits and "
                            f"single underscores, starting with a letter, such as "
                            f"{naming.legal_name(wanted)!r}")
        if wanted != package.name:
            choices.append(f"The package is named `{wanted}` (--name), not `{package.name}`.")
        return wanted
    if naming.is_legal(package.name):
        return package.name
    new = naming.legal_name(package.name)
    choices.append(f"The package is named `{new}`: ROS 2 refuses `{package.name}` "
                   f"({naming.why_illegal(package.name)}). --name NEW chooses another.")
    return new


def _effort_joints(given, joints: dict[str, str]) -> list[str]:
    names = []
    for item in given:
        names += [n.strip() for n in str(item).split(",") if n.strip()]
    unknown = [n for n in names if n not in joints]
    if unknown:
        raise PortError(f"--effort-joints: {', '.join(unknown)} is not a movable joint of the "
                        f"URDF; its movable joints are {', '.join(joints) or '(none)'}")
    return list(dict.fromkeys(names))


def _commands(transmissions, planned, joints, effort, choices,
              reported=frozenset()) -> dict[str, list[str]]:
    """Each joint's command interfaces; `reported` names controllers whose choices already
    say which interface they gave."""
    commands = {j: list(i) for j, i in transmissions.commands.items() if j in joints}
    unknown = [j for j in transmissions.commands if j not in joints]
    if unknown:
        choices.append("Transmissions name joints the URDF does not have as movable joints, and "
                       "were left out: " + ", ".join(unknown) + ".")
    for c in planned.controllers:
        for joint, interface in c.commands.items():
            have = commands.setdefault(joint, [])
            if interface in have:
                continue
            if c.commands and joint not in effort and c.name not in reported:
                choices.append(f"{joint} got a `{interface}` command interface for `{c.name}`" +
                               (f" besides its transmission's {', '.join(have)}" if have else
                                ", though it has no transmission") + ".")
            have.append(interface)
    return commands


def _mesh_files(root: Path) -> list[str]:
    meshes = root / "meshes"
    if not meshes.is_dir():
        return []
    return [rel.as_posix() for rel in mesh_paths.package_files(root)
            if rel.parts[0] == "meshes"]


def _left_behind(root: Path) -> list[str]:
    notes = []
    scripts = root / "scripts"
    if scripts.is_dir():
        names = sorted(p.name for p in scripts.iterdir() if p.is_file())
        if names:
            notes.append("scripts/ was not ported: " + ", ".join(names) + " are ROS 1 (rospy) "
                         "nodes; rewrite them with rclpy, and talk to the controllers' ROS 2 "
                         "topics named above.")
    launches = sorted(p.name for p in (root / "launch").glob("*.launch")) \
        if (root / "launch").is_dir() else []
    if launches:
        notes.append("The ROS 1 launch files (" + ", ".join(launches) + ") were replaced by "
                     "launch/display.launch.py and launch/gazebo.launch.py.")
    yamls = sorted(p.name for p in (root / "config").glob("*.y*ml")) \
        if (root / "config").is_dir() else []
    if yamls:
        notes.append("The ROS 1 configuration (" + ", ".join(f"config/{y}" for y in yamls) +
                     ") was not copied: ROS 2 reads config/controllers.yaml.")
    return notes


def _check_out(out: Path, source: Path) -> None:
    """Refuse an output folder that is a file, holds or is inside the source, or holds
    files that no earlier port wrote."""
    target = Path(os.path.abspath(out))
    real = target.resolve() if target.exists() else target
    if real == source or source in real.parents:
        raise PortError(f"{out} is inside the source package {source}; sw2sim port never "
                        "writes there. Give a folder outside it, e.g. ../"
                        f"{source.name}_ros2")
    if real in source.parents:
        raise PortError(f"{out} holds the source package {source}; give a new folder")
    if out.exists() and not out.is_dir():
        raise PortError(f"{out} is a file; give a folder to write the package into")
    if not out.is_dir() or not any(out.iterdir()):
        return
    if _earlier(out) is None:
        raise PortError(f"{out} is not empty and is not an earlier output of sw2sim port, so "
                        "nothing was written. Choose a new folder, or empty this one.")


def _earlier(out: Path) -> dict[str, str | None] | None:
    """The files an earlier port wrote into `out`, each with the SHA-256 it wrote (None
    from a port that recorded none); None when `out` is no earlier port's."""
    try:
        marker = json.loads((out / MARKER).read_text(encoding="utf-8"))
        listed, digests = marker["files"], marker.get("sha256", {})
        return {str(f): digests.get(f) for f in listed}
    except (OSError, ValueError, KeyError, TypeError, AttributeError):
        return None


def _digest(content: str | Path | bytes) -> str:
    if isinstance(content, Path):
        content = content.read_bytes()
    elif isinstance(content, str):
        content = content.encode("utf-8")
    return hashlib.sha256(content).hexdigest()


@dataclass
class _Keep:
    """What of an earlier port's folder goes into the new one."""
    copy: dict[str, str] = field(default_factory=dict)   # old rel -> new rel
    folders: list[str] = field(default_factory=list)     # the user's empty folders
    own: list[str] = field(default_factory=list)
    changed: list[str] = field(default_factory=list)
    aside: list[str] = field(default_factory=list)


def _keep(out: Path, files: dict[str, str | Path | bytes]) -> _Keep:
    """What of `out`, if it is an earlier port, stays: every file the port did not write,
    and each file it wrote that the user changed since (kept in place when the new port
    writes it as the earlier did, else set aside as FILE.mine)."""
    keep = _Keep()
    earlier = _earlier(out) if out.is_dir() else None
    if earlier is None:
        return keep
    for path in sorted(out.rglob("*")):
        rel = path.relative_to(out).as_posix()
        if rel == MARKER:
            continue
        if path.is_dir() and not path.is_symlink():
            if not any(path.iterdir()):
                keep.folders.append(rel)
            continue
        wrote = earlier.get(rel, "")      # "" for a file no port wrote
        if rel in earlier and (wrote is None or path.is_symlink() or _digest(path) == wrote):
            continue          # the port's own, unchanged (or a port that kept no digests)
        if rel not in files:
            keep.copy[rel] = rel
            keep.own.append(rel)
        elif not path.is_symlink() and _digest(path) == _digest(files[rel]):
            continue          # already what the new port writes
        elif rel in earlier and _digest(files[rel]) == wrote:
            keep.copy[rel] = rel
            keep.changed.append(rel)
        else:
            aside, n = rel + MINE, 2
            while (out / aside).exists() or aside in files:   # an older FILE.mine stays
                aside, n = f"{rel}{MINE}{n}", n + 1
            keep.copy[rel] = aside
            keep.aside.append(aside)
    return keep


def _write(out: Path, files: dict[str, str | Path | bytes], keep: _Keep | None = None) -> bool:
    """Write the package into a new folder beside `out`, with what `keep` keeps of it, then
    put it in `out`'s place."""
    keep = keep or _Keep()
    out = Path(os.path.abspath(out))
    out.parent.mkdir(parents=True, exist_ok=True)
    scratch = Path(tempfile.mkdtemp(prefix=f".{out.name}-", dir=out.parent))
    try:
        digests = {}
        for rel, content in files.items():
            target = scratch / rel
            target.parent.mkdir(parents=True, exist_ok=True)
            if isinstance(content, Path):
                shutil.copyfile(content, target)
            elif isinstance(content, bytes):
                target.write_bytes(content)
            else:
                target.write_text(content, encoding="utf-8", newline="\n")
            digests[rel] = _digest(content)
        for old, new in keep.copy.items():
            target = scratch / new
            target.parent.mkdir(parents=True, exist_ok=True)
            if target.exists() or target.is_symlink():
                target.unlink()
            shutil.copy2(out / old, target, follow_symlinks=False)
        for rel in keep.folders:
            (scratch / rel).mkdir(parents=True, exist_ok=True)
        (scratch / MARKER).write_text(json.dumps({"files": sorted(files), "sha256": digests},
                                                 indent=1, sort_keys=True) + "\n",
                                      encoding="utf-8")
        scratch.chmod(0o755)
        replaced = out.exists() and any(out.iterdir())
        if out.exists():
            shutil.rmtree(out)
        scratch.rename(out)
        return replaced
    except BaseException:
        shutil.rmtree(scratch, ignore_errors=True)
        raise
