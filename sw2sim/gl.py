"""Which OpenGL platform MuJoCo draws with: chosen here, and nowhere else.

MuJoCo reads `MUJOCO_GL` once, when `mujoco` is first imported, so `import sw2sim`
makes the choice before anything imports MuJoCo:

- `MUJOCO_GL` already set: kept, whatever it says;
- Linux without a display (a server, CI, WSL without WSLg, a container): OSMesa when the
  library is installed (Debian and Ubuntu: `libosmesa6`), EGL otherwise;
- Linux with a display, Windows and macOS: left unset, so MuJoCo uses its own default,
  the window system's OpenGL (`MUJOCO_GL=egl` would stop MuJoCo from starting there).

`sw2sim view` draws in a window, so it asks for GLFW (`for_window`) before it imports
MuJoCo, whatever was chosen for pictures. A process that never draws turns drawing off
(`without_drawing`, the ROS stand-in's simulation node; `not_drawing` around the command
line's own `sw2sim check`): MuJoCo then loads no OpenGL library at all.
"""

from __future__ import annotations

import ctypes.util
import os
import sys
from collections.abc import Callable, Iterator, MutableMapping
from contextlib import contextmanager


def platform_for(environ: MutableMapping[str, str], system: str = sys.platform,
                 has_osmesa: Callable[[], bool] | None = None) -> str | None:
    """The `MUJOCO_GL` value for this environment, or None for MuJoCo's own default."""
    if environ.get("MUJOCO_GL"):
        return environ["MUJOCO_GL"]
    if not system.startswith("linux") or environ.get("DISPLAY") or environ.get("WAYLAND_DISPLAY"):
        return None
    found = has_osmesa() if has_osmesa is not None else osmesa_installed()
    return "osmesa" if found else "egl"


# Where Debian, Ubuntu, Fedora and Arch put shared libraries.
LIBRARY_FOLDERS = ("/usr/lib/x86_64-linux-gnu", "/usr/lib/aarch64-linux-gnu", "/usr/lib64",
                   "/usr/lib", "/lib/x86_64-linux-gnu", "/lib64", "/usr/local/lib")


def osmesa_installed() -> bool:
    """Whether the OSMesa library is installed: a look into the usual library folders, and
    only where it is not there ctypes' search, which runs `ldconfig -p` in a new process
    (some 20 ms at every `import sw2sim`, more on a busy machine)."""
    for folder in LIBRARY_FOLDERS:
        try:
            if any(name.startswith("libOSMesa.so") for name in os.listdir(folder)):
                return True
        except OSError:
            continue
    return ctypes.util.find_library("OSMesa") is not None


def choose(environ: MutableMapping[str, str] | None = None) -> str | None:
    """Set `MUJOCO_GL` in `environ` (default: this process's) as `platform_for` says."""
    environ = os.environ if environ is None else environ
    chosen = platform_for(environ)
    if chosen is not None:
        environ["MUJOCO_GL"] = chosen
    return chosen


def for_window(environ: MutableMapping[str, str] | None = None) -> str:
    """Set `MUJOCO_GL=glfw`, for MuJoCo's viewer window. Call it before `mujoco` is first
    imported: MuJoCo reads the variable once."""
    environ = os.environ if environ is None else environ
    environ["MUJOCO_GL"] = "glfw"
    return "glfw"


def without_drawing(environ: MutableMapping[str, str] | None = None) -> str:
    """Set `MUJOCO_GL=disable`, for a process that only simulates: MuJoCo then does not
    load an OpenGL library at import. Call it before `mujoco` is first imported."""
    environ = os.environ if environ is None else environ
    environ["MUJOCO_GL"] = "disable"
    return "disable"


@contextmanager
def not_drawing(environ: MutableMapping[str, str] | None = None) -> Iterator[None]:
    """`MUJOCO_GL=disable` while the block runs, and the value before it put back after.

    MuJoCo imported inside the block loads no OpenGL library (OSMesa's start-up is a fifth
    of a second of CPU) and cannot draw for the rest of the process: use it around work
    that ends the process, such as the `sw2sim check` command. Processes started after
    the block get the platform chosen for drawing again."""
    environ = os.environ if environ is None else environ
    before = environ.get("MUJOCO_GL")
    environ["MUJOCO_GL"] = "disable"
    try:
        yield
    finally:
        if before is None:
            environ.pop("MUJOCO_GL", None)
        else:
            environ["MUJOCO_GL"] = before
