"""From a SolidWorks-exported URDF package to a MuJoCo simulation.

`import sw2sim` before `import mujoco` when rendering off-screen: it picks the GL
platform (OSMesa, or EGL where OSMesa is missing) unless MUJOCO_GL is already set.
MuJoCo itself is imported only when `load_package` is first used, so tools that never
simulate (the page runner, the figure list) start quickly.
"""

import ctypes.util
import os

if "MUJOCO_GL" not in os.environ:
    os.environ["MUJOCO_GL"] = "osmesa" if ctypes.util.find_library("OSMesa") else "egl"

__all__ = ["LoadError", "load_package"]


def __getattr__(name):
    if name in __all__:
        from . import loader
        return getattr(loader, name)
    raise AttributeError(f"module 'sw2sim' has no attribute {name!r}")
