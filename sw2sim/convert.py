"""`sw2sim convert`: an exported package as a MuJoCo model folder that needs nothing else.

The folder follows the layout of the MuJoCo Menagerie's models:

    <name>.xml   the robot: bodies, joints, meshes, actuators
    scene.xml    includes <name>.xml and adds a floor, a light and a sky
    assets/      the mesh files
    README.md    what came from where, and what changed on the way

The robot is what `sw2sim.load_package` makes of the package, plus the actuators of
`sw2sim.actuators`, written out by MuJoCo itself (`MjSpec.to_xml`).
"""

from __future__ import annotations

import os
import re
import shutil
from dataclasses import dataclass, field
from pathlib import Path

import mujoco
import numpy as np
from lxml import etree

from .actuators import Actuator, add_actuators
from .browser_model import browser_form
from .limits import DAMPING_RATIO, HOLD
from .loader import load_package, lowest_collision_point
from .mesh_formats import converted_from
from .package import LoadError, Package, as_package
from .ros_control import read_joint_limits

SCENE = "scene.xml"
README = "README.md"
ASSETS = "assets"


class OutputNotEmpty(Exception):
    """The output folder holds files already, and overwriting was not asked for."""


@dataclass
class Conversion:
    """What one conversion wrote, and the facts its README reports."""

    name: str
    folder: Path
    files: list[Path] = field(default_factory=list)
    fixed: bool = True
    floor_z: float = 0.0
    actuators: list[Actuator] = field(default_factory=list)
    skipped: list[str] = field(default_factory=list)
    meshes: dict[str, str] = field(default_factory=dict)   # asset path -> package path
    converted: list[str] = field(default_factory=list)     # assets converted to STL
    excluded: list[tuple[str, str]] = field(default_factory=list)
    repairs: list = field(default_factory=list)    # the findings convert repaired


def file_stem(name: str) -> str:
    """The robot file's name: the model's name, safe as a file name, never "scene"."""
    stem = re.sub(r"[^A-Za-z0-9_.-]", "_", name).strip("._") or "robot"
    return "robot" if stem.lower() == Path(SCENE).stem else stem


def convert(source: str | os.PathLike | Package, folder: str | os.PathLike, *,
            force: bool = False, repairs=(), unactuated=()) -> Conversion:
    """Write the model folder for the package at `source` (a path or a Package) into `folder`.

    Raises LoadError when the package cannot be loaded, OutputNotEmpty when `folder`
    holds files and `force` is false, and OSError when it cannot be written. With
    `force`, only the files this conversion writes are replaced; nothing is deleted.
    `repairs` are the check's findings whose repairs `source` (a repaired Package) carries,
    for the README; `unactuated` names joints that get no actuator whatever drives them.
    """
    folder = Path(folder)
    if folder.exists() and not folder.is_dir():
        raise OutputNotEmpty(f"{folder} is a file, not a folder")
    if folder.is_dir() and any(folder.iterdir()) and not force:
        raise OutputNotEmpty(f"{folder} is not empty")

    package = as_package(source)
    fixed = package.world_fixed
    spec = load_package(package, fixed_base=fixed, scene=False)
    actuators, skipped = add_actuators(spec, package, leave=set(unactuated))
    try:
        model = spec.compile()
    except ValueError as exc:
        raise LoadError(package.urdf, f"MuJoCo cannot compile the model: {exc}") from None
    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    result = Conversion(name=file_stem(spec.modelname), folder=folder, fixed=fixed,
                        floor_z=_floor_height(model, data) if fixed else 0.0,
                        actuators=actuators, skipped=skipped,
                        excluded=[(e.bodyname1, e.bodyname2) for e in spec.excludes],
                        repairs=list(repairs))

    copies: dict[Path, str] = {}
    converted = dict(spec.assets)   # meshes the loader converted in memory (mesh_formats)
    for mesh in spec.meshes:
        source = Path(mesh.file)
        if source not in copies:
            copies[source] = _asset_name(package.root, source, set(copies.values()))
        mesh.file = copies[source]
    spec.meshdir = ASSETS
    result.meshes = {asset: (converted_from(str(source)) if str(source) in converted else source)
                     .relative_to(package.root).as_posix() for source, asset in copies.items()}
    result.converted = [asset for source, asset in copies.items() if str(source) in converted]

    folder.mkdir(parents=True, exist_ok=True)
    for source, asset in copies.items():
        target = folder / ASSETS / asset
        target.parent.mkdir(parents=True, exist_ok=True)
        if str(source) in converted:
            target.write_bytes(converted[str(source)])
        else:
            shutil.copyfile(source, target)
        result.files.append(target)
    spec.modelfiledir = str(folder.resolve())   # to_xml compiles: it must find the copies
    robot_file = folder / f"{result.name}.xml"
    header = (f"<!-- {spec.modelname}: converted by `sw2sim convert` from "
              f"{package.urdf.relative_to(package.root).as_posix()}; see README.md -->\n")
    # in the form the site's in-browser MuJoCo also reads and steps alike (browser_model.py)
    robot_file.write_text(header + browser_form(spec.to_xml()), encoding="utf-8", newline="\n")
    (folder / SCENE).write_text(_scene_xml(result, model), encoding="utf-8", newline="\n")
    (folder / README).write_text(readme(result, package), encoding="utf-8", newline="\n")
    result.files += [robot_file, folder / SCENE, folder / README]

    try:  # the folder must stand on its own: load it as anyone would
        mujoco.MjModel.from_xml_path(str(folder / SCENE))
    except ValueError as exc:
        raise LoadError(folder / SCENE,
                        f"the written model does not load in MuJoCo: {exc}") from None
    return result


def _asset_name(root: Path, source: Path, taken: set[str]) -> str:
    """Where a mesh goes under assets/: its path below the package's meshes/ folder
    (or below the package), so that two meshes of the same name cannot collide."""
    rel = source.relative_to(root)
    if rel.parts[0] == "meshes" and len(rel.parts) > 1:
        rel = Path(*rel.parts[1:])
    name, n = rel.as_posix(), 1
    while name in taken:
        n += 1
        name = f"{rel.with_suffix('').as_posix()}_{n}{rel.suffix}"
    return name


def _scene_xml(result: Conversion, model: mujoco.MjModel) -> str:
    """scene.xml: the robot file included, with a floor, a light and a sky around it."""
    root = etree.Element("mujoco", model=f"{result.name} scene")
    root.append(etree.Comment(f" open this file; the robot itself is in {result.name}.xml "))
    etree.SubElement(root, "include", file=f"{result.name}.xml")
    etree.SubElement(root, "statistic", center=_numbers(model.stat.center),
                     extent=f"{float(model.stat.extent):g}")
    visual = etree.SubElement(root, "visual")
    etree.SubElement(visual, "headlight", diffuse="0.45 0.45 0.45", ambient="0.15 0.15 0.15",
                     specular="0 0 0")
    etree.SubElement(visual, "global", azimuth="135", elevation="-25", offwidth="1600",
                     offheight="1200")
    asset = etree.SubElement(root, "asset")
    etree.SubElement(asset, "texture", type="skybox", builtin="gradient", rgb1="0.97 0.98 1",
                     rgb2="0.8 0.85 0.92", width="256", height="1536")
    etree.SubElement(asset, "texture", type="2d", name="groundplane", builtin="checker",
                     rgb1="0.82 0.84 0.87", rgb2="0.72 0.75 0.79", width="512", height="512")
    etree.SubElement(asset, "material", name="groundplane", texture="groundplane",
                     texrepeat="8 8", reflectance="0")
    world = etree.SubElement(root, "worldbody")
    etree.SubElement(world, "light", name="sun", pos="0 0 5", dir="0.3 0.4 -1",
                     diffuse="0.55 0.55 0.55", ambient="0.1 0.1 0.1", type="directional",
                     castshadow="true")
    etree.SubElement(world, "geom", name="floor", type="plane", size="0 0 0.05",
                     pos=f"0 0 {result.floor_z:g}", material="groundplane")
    return etree.tostring(root, encoding="unicode", pretty_print=True)


def _numbers(values) -> str:
    return " ".join(f"{float(v):g}" for v in np.asarray(values).ravel())


def _range(pair) -> str:
    return "none" if pair is None else f"{pair[0]:g} to {pair[1]:g}"


def readme(result: Conversion, package: Package) -> str:
    """README.md of the model folder: the files, their sources, and every change made."""
    name, urdf = result.name, package.urdf.relative_to(package.root).as_posix()
    robot = package.robot
    limits = read_joint_limits(package)
    links = [link.get("name") for link in robot.findall("link") if link.get("name") != "world"]
    joints = [(j.get("name"), j.get("type")) for j in robot.findall("joint")]
    gazebo = len(robot.findall("gazebo"))
    transmissions = len(robot.findall("transmission"))
    velocities = [(j, lim.velocity) for j, lim in limits.items() if lim.velocity]
    soft = [j for j, lim in limits.items() if lim.has_soft_limits]

    out = [f"# {name} in MuJoCo", "",
           f"A MuJoCo model of the package `{package.name}`, converted from `{urdf}` by "
           "`sw2sim convert`. It needs MuJoCo only: no ROS, no sw2sim.", "",
           "## Files", "",
           "| File | What it holds |", "|---|---|",
           f"| `{name}.xml` | the robot: bodies, joints, meshes and actuators |",
           f"| `{SCENE}` | includes `{name}.xml` and adds a floor, a light and a sky: "
           "open this one |",
           *([f"| `{ASSETS}/` | the mesh files, copied unchanged from the package" +
              (", but for those converted to binary STL (see Meshes below)"
               if result.converted else "") + " |"]
             if result.meshes else []),
           f"| `{README}` | this file |", "",
           "## Use", "", "```bash", f"python -m mujoco.viewer --mjcf={SCENE}", "```", "",
           "```python", "import mujoco", "",
           f'model = mujoco.MjModel.from_xml_path("{SCENE}")',
           "data = mujoco.MjData(model)", "mujoco.mj_step(model, data)", "```", "",
           "## What came from where", "",
           f"- **Links and joints** from `{urdf}`: {len(links)} link(s) became bodies, "
           f"{len(joints)} joint(s) became joints (" +
           ", ".join(f"`{j}` {t}" for j, t in joints) + "). Masses, centres of mass and "
           "inertias are the URDF's `<inertial>` values, " +
           ("unchanged but where Repairs says." if result.repairs else "unchanged."),
           "- **Base**: " + (
               "fixed, because the URDF fixes its root to a link named `world` (as Gazebo "
               "needs); MuJoCo's world body stands for that link." if result.fixed else
               "free (a free joint), because the URDF has no `world` link: in Gazebo it would "
               "fall free, too. It is lifted to rest on the floor at z = 0."),
           "- **Meshes**: " + (", ".join(f"`{ASSETS}/{a}` " + (
                                            "converted to binary STL from" if a in
                                            result.converted else "from") + f" `{s}`"
                                        for a, s in result.meshes.items()) + ". "
                               if result.meshes else "none; the shapes are URDF primitives. ") +
           "Each link keeps its visual shape (geom group 1, no contacts) and its collision "
           "shape (group 0); MuJoCo collides a mesh as its convex hull.",
           *(["- **Joint limits** are hard stops, as Gazebo's physics holds them: each limited "
              "joint's `solreflimit` (2 time steps, damping ratio "
              f"{DAMPING_RATIO:g}) and `solimplimit` (its impedance from its effort "
              f"limit and inertia) keep it within {HOLD:g} rad (or m) of its limit "
              "under the URDF's full effort; one reached at speed first passes it by up to "
              "one time step's travel (MuJoCo has no velocity limit to stop that)."]
             if any(kind in ("revolute", "prismatic") for _, kind in joints) else []),
           f"- **Floor** at z = {result.floor_z:g} m" + (
               ", under the model's lowest point." if result.floor_z < 0 else "."),
           ""]
    out += ["## Actuators", ""]
    if result.actuators:
        out += ["| Actuator | Joint | Kind | Gains | Control range | Force range | From |",
                "|---|---|---|---|---|---|---|"]
        out += [f"| `{a.name}` | `{a.joint}` | {a.kind} | {a.gains} | {_range(a.ctrlrange)} | "
                f"{_range(a.forcerange)} | {a.source} |" for a in result.actuators]
        out += ["", "Control ranges come from the joints' limits (position actuators) or "
                "velocity limits (velocity actuators); force ranges from the effort limits."]
    else:
        out += ["None: the package has no `<transmission>` and no joint controller in its "
                "`config/` YAML, so the model has no actuators. Add them in "
                f"`{name}.xml` (an `<actuator>` section) or from Python with "
                "`spec.add_actuator`."]
    out += ["", "A ROS `effort_controllers/JointPositionController` is a PID on the joint's "
            "position that outputs an effort. It became a MuJoCo position actuator, whose "
            "force is kp × (target − position) − kv × speed: the same law with kp = p and "
            "kv = d, so the control is a target position, as the controller's command topic "
            "is. MuJoCo computes it inside the step, and its `implicitfast` integrator treats "
            "the kv term implicitly, so strong damping stays stable. A "
            "`JointVelocityController` became a velocity actuator in the same way (kv = p). "
            "On the velocity interface, Gazebo drives the joint to the commanded velocity "
            "within its effort limit: a `velocity_controllers/JointVelocityController` became "
            "a velocity actuator with a stiff kv (K, ten times the joint's inertia per time "
            "step), and a `velocity_controllers/JointPositionController`, whose PID turns the "
            "position error into that velocity, a position actuator with kp = K p and "
            "kv = K (1 + d). "
            "A transmission without a controller became a motor, whose control is the effort "
            "itself, geared by the transmission's mechanical reduction.", ""]
    out += _repairs_section(result, package)
    out += ["## What changed on the way", ""]
    changes = []
    dropped = [f"`{a.name}`: {', '.join(a.dropped)}" for a in result.actuators if a.dropped]
    if dropped:
        changes.append("PID terms a MuJoCo actuator has no place for were dropped (there is no "
                       "integral term): " + "; ".join(dropped) + ".")
    if velocities:
        changes.append("Velocity limits were dropped, as MuJoCo has none: " + ", ".join(
            f"`{j}` {v:g}" for j, v in velocities) + " (rad/s or m/s). Enforce them in your "
            "controller.")
    if soft:
        changes.append("The `<safety_controller>` soft limits of " + ", ".join(
            f"`{j}`" for j in soft) + " were dropped; the joint ranges are the hard limits.")
    if any(limits[j].effort for j in limits):
        changes.append("Effort limits became each joint's `actuatorfrcrange`, which caps the "
                       "total actuator force on the joint; on a joint one actuator drives, "
                       "that actuator's `forcerange`, the same cap in the form MuJoCo's "
                       "in-browser build (3.14) also steps as 4.0 does.")
    if result.excluded:
        changes.append("Contacts were excluded between a body fixed to the world and each body "
                       "it carries, whose meshes overlap at the joints and would lock them: " +
                       ", ".join(f"`{a}`–`{b}`" for a, b in result.excluded) + ".")
    if transmissions:
        changes.append(f"The {transmissions} `<transmission>` element(s) were read for the "
                       "actuators; their hardware interfaces have no MuJoCo counterpart.")
    if gazebo:
        changes.append(f"The {gazebo} `<gazebo>` element(s) (Gazebo plugins and settings) were "
                       "left out.")
    mimics = [(j.get("name"), m.get("joint")) for j in robot.findall("joint")
              for m in j.findall("mimic")]
    if mimics:
        changes.append("Each `<mimic>` became an equality constraint that holds the joint at "
                       "the followed joint's position times the multiplier, plus the offset: " +
                       ", ".join(f"`{a}` follows `{b}`" for a, b in mimics) + ".")
    changes += [f"Not converted: {s}." for s in result.skipped]
    changes.append("The integrator is `implicitfast`, which keeps stiff joint damping stable; "
                   "the time step is MuJoCo's default, 2 ms.")
    out += [f"- {c}" for c in changes] + [""]
    return "\n".join(out)


def _repairs_section(result: Conversion, package: Package) -> list[str]:
    """README lines: each repair made, where, what was assumed, and the lasting fix."""
    if not result.repairs:
        return []
    out = ["## Repairs", "",
           "`sw2sim convert` repaired these problems in the model it wrote. Your package "
           "is unchanged: make each fix in SolidWorks (or in the files) so that ROS and "
           "Gazebo get it too, and run `sw2sim check` again. `sw2sim convert --strict` "
           "repairs nothing and refuses the package instead.", ""]
    for finding in result.repairs:
        where = _in_package(finding.file, package.root)
        where = f"{where}:{finding.line}" if finding.line else where
        out += [f"- **`{where}`** [{finding.rule}] {finding.message}.",
                f"  - Repaired: {finding.repair}.",
                f"  - To fix it for good: {finding.fix.rstrip('.')}."]
    return out + [""]


def _in_package(file: str | None, root: Path) -> str:
    """A finding's file as a path inside the package, where it is one."""
    if file is None:
        return "-"
    try:
        return Path(file).resolve().relative_to(root).as_posix()
    except ValueError:
        return file


def _floor_height(model, data) -> float:
    """0, or the model's lowest point when it reaches below 0 by more than a micrometre
    (the exporter's numbers carry rounding noise of 1e-9 m that should not move the floor)."""
    low = lowest_collision_point(model, data)
    return round(low, 6) if low < -1e-6 else 0.0
