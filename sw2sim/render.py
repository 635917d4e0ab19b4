"""Off-screen pictures of a model, for `sw2sim render` and the pages' figures."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

import mujoco
from PIL import Image


def render(model: mujoco.MjModel, data: mujoco.MjData, *, width: int = 960, height: int = 640,
           lookat=None, distance: float | None = None, azimuth: float = 135.0,
           elevation: float = -25.0, shadows: bool = True, show_joints: bool = False,
           show_frames: bool = False, frame: bool = False) -> np.ndarray:
    """An RGB picture (height, width, 3) of the current state from a free camera.

    The camera looks at `lookat` (default: the model's centre) from `distance`
    (default: a little more than the model's extent). With `frame`, both are chosen so
    that the robot as it stands fills the picture (`robot_view`). A picture larger than
    the model's offscreen buffer (its <visual><global offwidth offheight>) grows the buffer.
    """
    mujoco.mj_forward(model, data)
    if frame and lookat is None and distance is None:
        lookat, distance = robot_view(model, data, azimuth, elevation, width, height)
    cam = mujoco.MjvCamera()
    cam.type = mujoco.mjtCamera.mjCAMERA_FREE
    cam.lookat[:] = model.stat.center if lookat is None else lookat
    cam.distance = 1.6 * model.stat.extent if distance is None else distance
    cam.azimuth, cam.elevation = azimuth, elevation
    opt = mujoco.MjvOption()
    opt.flags[mujoco.mjtVisFlag.mjVIS_JOINT] = show_joints
    if show_frames:
        opt.frame = mujoco.mjtFrame.mjFRAME_BODY
    model.vis.global_.offwidth = max(model.vis.global_.offwidth, width)
    model.vis.global_.offheight = max(model.vis.global_.offheight, height)
    with mujoco.Renderer(model, height, width) as renderer:
        renderer.update_scene(data, camera=cam, scene_option=opt)
        renderer.scene.flags[mujoco.mjtRndFlag.mjRND_SHADOW] = shadows
        return renderer.render().copy()


def robot_bounds(model: mujoco.MjModel, data: mujoco.MjData) -> np.ndarray | None:
    """The corners (2 x 3) of the box around every geom of the robot (not the world's:
    the floor) at the current state, after mj_forward; None when there is none."""
    points = []
    for g in range(model.ngeom):
        if model.geom_bodyid[g] == 0 or model.geom_type[g] == mujoco.mjtGeom.mjGEOM_PLANE:
            continue
        turn, place = data.geom_xmat[g].reshape(3, 3), data.geom_xpos[g]
        if model.geom_type[g] == mujoco.mjtGeom.mjGEOM_MESH:
            m = model.geom_dataid[g]
            start, count = model.mesh_vertadr[m], model.mesh_vertnum[m]
            local = model.mesh_vert[start:start + count]
        else:   # the geom's own box: centre and half sizes in its frame
            centre, half = model.geom_aabb[g, :3], model.geom_aabb[g, 3:]
            local = centre + half * np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1)
                                              for z in (-1, 1)])
        points.append(local @ turn.T + place)
    if not points:
        return None
    points = np.vstack(points)
    return np.array([points.min(axis=0), points.max(axis=0)])


def robot_view(model: mujoco.MjModel, data: mujoco.MjData, azimuth: float, elevation: float,
               width: int, height: int, margin: float = 0.06) -> tuple[np.ndarray, float]:
    """(lookat, distance) for a free camera at `azimuth` and `elevation` (degrees) whose
    picture of `width` x `height` holds the whole robot, with `margin` of the picture left
    free around it.

    MuJoCo's free camera sits at lookat - distance * forward, with forward =
    (cos el cos az, cos el sin az, sin el). A point p lies in the picture when, in the
    camera's axes, |x| <= tan(fovx / 2) (distance + z) and likewise for y: each corner of
    the robot's box gives a least distance, and the largest one is used.
    """
    mujoco.mj_forward(model, data)
    box = robot_bounds(model, data)
    if box is None:
        return np.asarray(model.stat.center, dtype=float), 1.6 * float(model.stat.extent)
    centre = box.mean(axis=0)
    az, el = math.radians(azimuth), math.radians(elevation)
    forward = np.array([math.cos(el) * math.cos(az), math.cos(el) * math.sin(az), math.sin(el)])
    up = np.array([-math.sin(el) * math.cos(az), -math.sin(el) * math.sin(az), math.cos(el)])
    right = np.cross(forward, up)
    tan_y = math.tan(math.radians(model.vis.global_.fovy) / 2) * (1 - 2 * margin)
    tan_x = tan_y * width / height
    corners = np.array([[x, y, z] for x in box[:, 0] for y in box[:, 1] for z in box[:, 2]])
    relative = corners - centre
    across, upward, depth = relative @ right, relative @ up, relative @ forward
    needed = np.maximum(np.abs(across) / tan_x, np.abs(upward) / tan_y) - depth
    size = float(np.linalg.norm(box[1] - box[0]))
    return centre, max(float(needed.max()), 0.05 * size, 1e-3)


def save_png(image: np.ndarray, path: str | Path) -> None:
    """Save without metadata, so the same picture always gives the same file."""
    Image.fromarray(image).save(path, format="PNG", optimize=True)
