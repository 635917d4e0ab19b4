"""Load a package in the SolidWorks-to-URDF exporter's layout as a MuJoCo model specification.

MuJoCo reads URDF, but an exported package does not load as it is: mesh paths use
`package://`, visual meshes are thrown away by default, meshes made for RViz may be
COLLADA, which MuJoCo cannot decode, a base welded to the world collides with its own
wheels, a joint's limit gives way under the URDF's effort (MuJoCo's limits are soft,
Gazebo's hard), and there is nothing to stand on or look through. `load_package` fixes
exactly those things and nothing else, and says what is wrong (with the file and line)
when the package itself is broken.
"""

from __future__ import annotations

import copy
import os
import sys
from collections.abc import Mapping
from contextlib import contextmanager
from pathlib import Path

import numpy as np
from lxml import etree

import mujoco

from . import limits
from .mesh_formats import (LFS_FIX, Unconvertible, converted_name, lfs_pointer, stand_in,
                           stl_bytes)
from .package import LoadError, Package, as_package, find_package, resolve_mesh


__all__ = ["LoadError", "Package", "as_package", "find_package", "load_package",
           "lowest_collision_point", "resolve_mesh", "world_fixed"]


def world_fixed(source: str | os.PathLike | Package) -> bool:
    """Whether the URDF fixes its root link to a link named `world` (`Package.world_fixed`).

    That is how a URDF says "bolted down" to Gazebo; without it the model falls free
    there, even though MuJoCo's URDF import welds a jointless root to the world.
    """
    return as_package(source).world_fixed


def load_package(source: str | os.PathLike | Package, *, fixed_base: bool = True,
                 scene: bool | str = True,
                 hulls: Mapping[tuple[str, tuple[float, ...]], np.ndarray] | None = None
                 ) -> mujoco.MjSpec:
    """A MuJoCo model specification of an exported package, ready to compile.

    - `package://` mesh paths resolve to files inside the package;
    - a mesh MuJoCo cannot decode (COLLADA, PLY, glTF) is read from the same-named STL, OBJ
      or MSH beside it, else converted to STL in memory (`sw2sim.mesh_formats.stand_in`);
      a Git LFS pointer where a mesh should be is a LoadError that says `git lfs pull`;
    - visual meshes are kept (collision geoms: group 0; visual geoms: group 1, no contacts);
    - a base fixed to the world does not collide with the links it carries directly
      (their meshes overlap at the axles and would lock the joints);
    - each limited joint's limit is a hard stop, as Gazebo's physics holds it: per-joint
      solreflimit, solimplimit and margin (`sw2sim.limits`);
    - a floor (at z = 0, or under the model's lowest point if that is lower), a light
      and a camera named "overview" are added;
    - `fixed_base=False` gives the root link a free joint instead, lifted so it rests
      on the floor;
    - `scene=False` leaves out the floor, the light, the camera and their textures, for a
      model file of the robot alone (a free base is still lifted to rest on z = 0);
      `scene="floor"` adds the floor alone, plain, for a model that is simulated and never
      drawn (making the textures takes a hundredth of a second at every compile);
    - `hulls` maps (a mesh file, resolved; its scale) to the corners of its convex hull,
      scale applied: MuJoCo is given those corners in place of the file where every geom
      of that mesh belongs to a link with an <inertial>. It collides with the same shape
      (MuJoCo collides a mesh as its hull) and processes a few hundred points instead of
      every triangle; only for a model that is simulated and never drawn (sw2sim.check's
      stability run, which makes the map: sw2sim.check.collision_hulls).

    `source` is a package folder, a .urdf file or a Package already read; a Package's
    tree is left as it is (the mesh paths are rewritten in a copy).
    """
    package = as_package(source)
    urdf = package.urdf
    robot = copy.deepcopy(package.robot)

    assets: dict[str, bytes] = {}    # meshes converted in memory, by the name they go by
    for mesh in robot.iter("mesh"):
        filename = mesh.get("filename")
        if not filename:
            raise LoadError(urdf, "<mesh> without a filename", mesh.sourceline)
        path = package.resolve_mesh(filename, mesh.sourceline)
        mesh.set("filename", _decodable(package, path, mesh.sourceline, assets))

    for old in robot.findall("mujoco"):
        robot.remove(old)
    extension = etree.SubElement(robot, "mujoco")
    etree.SubElement(extension, "compiler", discardvisual="false", strippath="false",
                     fusestatic="false", balanceinertia="false")

    xml = etree.tostring(robot, encoding="unicode")
    try:
        with _c_output_silenced():
            spec = mujoco.MjSpec.from_string(xml, assets=assets or None)
    except ValueError as exc:
        raise LoadError(urdf, f"MuJoCo cannot read this URDF: {exc}") from None
    spec.modelname = robot.get("name") or package.name
    spec.option.integrator = mujoco.mjtIntegrator.mjINT_IMPLICITFAST

    if hulls:
        _take_hulls(spec, hulls)
    root_body = _root_body(spec, urdf)
    if fixed_base:
        _exclude_static_children(spec)
    else:
        root_body.add_freejoint()
    try:
        model = spec.compile()
    except ValueError as exc:
        raise LoadError(urdf, f"MuJoCo cannot compile this model: {exc}") from None
    limits.stiffen(spec, model)
    _add_scene(spec, model, root_body, lift=not fixed_base, dress=scene)
    return spec


def _decodable(package: Package, path: Path, line: int | None, assets: dict[str, bytes]) -> str:
    """The file MuJoCo reads for the mesh file `path`: itself, the readable file of the same
    name beside it, or a binary STL converted from it, put in `assets` under the name
    returned. A Git LFS pointer, or a file nothing can read, is a LoadError."""
    shown = path.relative_to(package.root).as_posix()
    if lfs_pointer(path):
        raise LoadError(package.urdf, f"the mesh {shown} is a Git LFS pointer, a small text "
                        "file in place of the mesh", line, fix=LFS_FIX)
    found = stand_in(path)
    if found is not None:
        return str(found)
    name = converted_name(path)
    if name not in assets:
        try:
            assets[name] = stl_bytes(path)
        except Unconvertible as exc:
            raise LoadError(package.urdf, f"MuJoCo cannot read the mesh {shown} (it reads "
                            f".stl, .obj and .msh), and it cannot be converted: {exc}", line,
                            fix="save it as binary STL beside it, with the same name") from None
    return name


def _take_hulls(spec: mujoco.MjSpec,
                hulls: Mapping[tuple[str, tuple[float, ...]], np.ndarray]) -> None:
    """Give each mesh that `hulls` names its hull's corners in place of its file, where no
    link whose mass MuJoCo would work out from its geoms (no <inertial>) uses it."""
    weighed_by_geoms = {geom.meshname for body in spec.bodies if not body.explicitinertial
                        for geom in body.geoms}
    for mesh in spec.meshes:
        if not mesh.file or mesh.name in weighed_by_geoms:
            continue
        corners = hulls.get((str(Path(mesh.file).resolve()),
                             tuple(float(s) for s in mesh.scale)))
        if corners is None:
            continue
        mesh.file = ""
        mesh.uservert = np.asarray(corners, dtype=np.float64).ravel()
        mesh.scale = [1.0, 1.0, 1.0]


@contextmanager
def _c_output_silenced():
    """Keep MuJoCo's URDF reader from printing on the process's standard output and error
    (it prints one warning, about duplicate geom names, that no handler catches; `sw2sim
    check` reports it as a finding of its own, geom-name-duplicate)."""
    saved = []
    try:
        for stream in (sys.stdout, sys.stderr):
            try:
                stream.flush()
                fd = stream.fileno()
            except (AttributeError, OSError, ValueError):   # no real file behind it
                continue
            saved.append((fd, os.dup(fd)))
            with open(os.devnull, "wb") as null:
                os.dup2(null.fileno(), fd)
        yield
    finally:
        for fd, copy_of in saved:
            os.dup2(copy_of, fd)
            os.close(copy_of)


def _root_body(spec: mujoco.MjSpec, urdf: Path) -> mujoco.MjsBody:
    roots = [b for b in spec.worldbody.bodies]
    if not roots:
        raise LoadError(urdf, "the URDF has no links that MuJoCo can simulate")
    if len(roots) > 1:
        names = ", ".join(b.name for b in roots)
        raise LoadError(urdf, f"several root links ({names}); join them to one base_link with joints")
    return roots[0]


def _exclude_static_children(spec: mujoco.MjSpec) -> None:
    """Exclude contacts between a body held by the world and each body it carries directly.

    MuJoCo filters parent-child contacts only when the parent moves; for a base welded
    to the world the overlapping meshes at each axle would lock the wheels.
    """

    def walk(body, static: bool):
        for child in body.bodies:
            if static and body is not spec.worldbody:
                spec.add_exclude(bodyname1=body.name, bodyname2=child.name)
            walk(child, static and not child.joints)

    walk(spec.worldbody, True)


def _add_scene(spec: mujoco.MjSpec, model: mujoco.MjModel, root: mujoco.MjsBody, lift: bool,
               dress: bool | str = True) -> None:
    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    low = lowest_collision_point(model, data)
    if lift:
        root.pos = np.asarray(root.pos) + [0, 0, max(0.0, -low) + 0.001]
        floor_z = 0.0
    else:
        floor_z = min(0.0, low)
    if not dress:
        return
    if dress == "floor":
        spec.worldbody.add_geom(name="floor", type=mujoco.mjtGeom.mjGEOM_PLANE,
                                size=[0, 0, 0.05], pos=[0, 0, floor_z])
        return

    tex = spec.add_texture(name="sw2sim_grid", type=mujoco.mjtTexture.mjTEXTURE_2D,
                           builtin=mujoco.mjtBuiltin.mjBUILTIN_CHECKER, width=512, height=512,
                           rgb1=[0.82, 0.84, 0.87], rgb2=[0.72, 0.75, 0.79])
    spec.add_material(name="sw2sim_floor", texrepeat=[8, 8], reflectance=0.0,
                      textures=["", tex.name])
    spec.add_texture(name="sw2sim_sky", type=mujoco.mjtTexture.mjTEXTURE_SKYBOX,
                     builtin=mujoco.mjtBuiltin.mjBUILTIN_GRADIENT, width=256, height=256,
                     rgb1=[0.97, 0.98, 1.0], rgb2=[0.80, 0.85, 0.92])
    spec.visual.headlight.diffuse = [0.45, 0.45, 0.45]
    spec.visual.headlight.ambient = [0.15, 0.15, 0.15]
    spec.worldbody.add_geom(name="floor", type=mujoco.mjtGeom.mjGEOM_PLANE, size=[0, 0, 0.05],
                            pos=[0, 0, floor_z], material="sw2sim_floor")
    spec.worldbody.add_light(name="sun", type=mujoco.mjtLightType.mjLIGHT_DIRECTIONAL,
                             pos=[0, 0, 5], dir=[0.3, 0.4, -1], diffuse=[0.55, 0.55, 0.55],
                             ambient=[0.1, 0.1, 0.1], castshadow=True)

    centre, extent = model.stat.center.copy(), float(model.stat.extent)
    distance = 2.2 * extent
    azimuth, elevation = np.radians(-135.0), np.radians(-30.0)
    forward = np.array([np.cos(elevation) * np.cos(azimuth), np.cos(elevation) * np.sin(azimuth),
                        np.sin(elevation)])
    right = np.cross(forward, [0, 0, 1])
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    spec.worldbody.add_camera(name="overview", pos=centre - distance * forward,
                              xyaxes=[*right, *up], fovy=40)
    spec.visual.global_.offwidth = max(spec.visual.global_.offwidth, 1600)
    spec.visual.global_.offheight = max(spec.visual.global_.offheight, 1200)
    spec.stat.center = centre
    spec.stat.extent = extent


def lowest_collision_point(model: mujoco.MjModel, data: mujoco.MjData) -> float:
    """The lowest z of any colliding geom at the rest pose (mesh vertices where available)."""
    low = np.inf
    for g in range(model.ngeom):
        if model.geom_contype[g] == 0 and model.geom_conaffinity[g] == 0:
            continue
        if model.geom_type[g] == mujoco.mjtGeom.mjGEOM_MESH:
            m = model.geom_dataid[g]
            start, count = model.mesh_vertadr[m], model.mesh_vertnum[m]
            verts = model.mesh_vert[start:start + count]
            world = verts @ data.geom_xmat[g].reshape(3, 3).T + data.geom_xpos[g]
            low = min(low, float(world[:, 2].min()))
        else:
            low = min(low, float(data.geom_xpos[g][2] - model.geom_rbound[g]))
    return 0.0 if low == np.inf else low
