"""From a SolidWorks-exported URDF package to a MuJoCo simulation.

`import sw2sim` before `import mujoco` when rendering without a screen: it chooses the
OpenGL platform MuJoCo will use (see `sw2sim.gl`). MuJoCo itself is imported only when
`load_package` is first used, so commands that never simulate start quickly.
"""

from . import gl

gl.choose()

__all__ = ["LoadError", "load_package"]


def __getattr__(name):
    if name in __all__:
        from . import loader
        return getattr(loader, name)
    raise AttributeError(f"module 'sw2sim' has no attribute {name!r}")
