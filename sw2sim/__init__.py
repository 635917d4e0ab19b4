"""From a SolidWorks-exported URDF package to a MuJoCo simulation.

`import sw2sim` before `import mujoco` when rendering off-screen: it picks the GL
platform (OSMesa, or EGL where OSMesa is missing) unless MUJOCO_GL is already set.
"""

import ctypes.util
import os

if "MUJOCO_GL" not in os.environ:
    os.environ["MUJOCO_GL"] = "osmesa" if ctypes.util.find_library("OSMesa") else "egl"

from .loader import LoadError, load_package  # noqa: E402

__all__ = ["LoadError", "load_package"]
