"""Off-screen pictures of a model, for the pages' figures."""

from __future__ import annotations

from pathlib import Path

import numpy as np

import mujoco
from PIL import Image


def render(model: mujoco.MjModel, data: mujoco.MjData, *, width: int = 960, height: int = 640,
           lookat=None, distance: float | None = None, azimuth: float = 135.0,
           elevation: float = -25.0, shadows: bool = True, show_joints: bool = False,
           show_frames: bool = False) -> np.ndarray:
    """An RGB picture (height, width, 3) of the current state from a free camera.

    The camera looks at `lookat` (default: the model's centre) from `distance`
    (default: a little more than the model's extent).
    """
    mujoco.mj_forward(model, data)
    cam = mujoco.MjvCamera()
    cam.type = mujoco.mjtCamera.mjCAMERA_FREE
    cam.lookat[:] = model.stat.center if lookat is None else lookat
    cam.distance = 1.6 * model.stat.extent if distance is None else distance
    cam.azimuth, cam.elevation = azimuth, elevation
    opt = mujoco.MjvOption()
    opt.flags[mujoco.mjtVisFlag.mjVIS_JOINT] = show_joints
    if show_frames:
        opt.frame = mujoco.mjtFrame.mjFRAME_BODY
    with mujoco.Renderer(model, height, width) as renderer:
        renderer.update_scene(data, camera=cam, scene_option=opt)
        renderer.scene.flags[mujoco.mjtRndFlag.mjRND_SHADOW] = shadows
        return renderer.render().copy()


def save_png(image: np.ndarray, path: str | Path) -> None:
    """Save without metadata, so the same picture always gives the same file."""
    Image.fromarray(image).save(path, format="PNG", optimize=True)
