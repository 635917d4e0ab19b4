"""An environment for a subprocess that has no off-screen OpenGL to fall back on, as a
reader's Windows or macOS machine (or a Linux machine without libosmesa6) has it.

- `MUJOCO_GL` is not set;
- a `sitecustomize` module, first on PYTHONPATH, makes `ctypes.util.find_library` and the
  listings of folders blind to OSMesa and EGL (how sw2sim/gl.py looks for OSMesa: in the
  library folders, then with ctypes' search), and writes a line to a log for each
  process it is loaded in, so a test can tell that the processes it cared about had it;
- `desktop=True` gives a DISPLAY at which no X server listens: `sw2sim` leaves MUJOCO_GL
  unset, as it does on Windows and macOS, and any attempt to draw fails, since MuJoCo's own
  default (GLFW) finds no display. `desktop=False`: no display at all, so `sw2sim` falls
  back to EGL, which nothing must need unless it draws.
"""

from __future__ import annotations

import os
from pathlib import Path

HOOK = '''\
import ctypes.util
import os
import sys

_find_library = ctypes.util.find_library


def find_library(name):
    """None for the off-screen GL libraries, as where they are not installed."""
    return None if name in ("OSMesa", "EGL") else _find_library(name)


ctypes.util.find_library = find_library
_listdir = os.listdir


def listdir(path="."):
    """A folder's names without the off-screen GL libraries' files."""
    return [n for n in _listdir(path) if not str(n).startswith(("libOSMesa", "libEGL"))]


os.listdir = listdir
_log = os.environ.get("WITHOUT_GL_LOG")
if _log:
    with open(_log, "a", encoding="utf-8") as f:
        f.write(f"{os.getpid()} MUJOCO_GL={os.environ.get('MUJOCO_GL', '')}\\n")
'''
# A display number no X server on this machine answers at.
NO_SUCH_DISPLAY = ":173"


def environment(folder: Path, *, desktop: bool) -> tuple[dict[str, str], Path]:
    """The subprocess environment, and the log of the processes that loaded the hook."""
    hook = folder / "without_gl"
    hook.mkdir(parents=True, exist_ok=True)
    (hook / "sitecustomize.py").write_text(HOOK, encoding="utf-8")
    log = folder / "without_gl.log"
    log.write_text("", encoding="utf-8")
    env = {k: v for k, v in os.environ.items()
           if k not in ("MUJOCO_GL", "PYOPENGL_PLATFORM", "DISPLAY", "WAYLAND_DISPLAY", "COURSE_SNIPPETS_FORK")}
    env["PYTHONPATH"] = os.pathsep.join([str(hook), *filter(None, [os.environ.get("PYTHONPATH")])])
    env["WITHOUT_GL_LOG"] = str(log)
    if desktop:
        assert not Path(f"/tmp/.X11-unix/X{NO_SUCH_DISPLAY[1:]}").exists(), "that display exists here"
        env["DISPLAY"] = NO_SUCH_DISPLAY
    return env, log


def processes(log: Path) -> list[tuple[int, str]]:
    """(pid, MUJOCO_GL at its start) of every process that loaded the hook."""
    entries = []
    for line in log.read_text(encoding="utf-8").splitlines():
        pid, setting = line.split(" ", 1)
        entries.append((int(pid), setting.removeprefix("MUJOCO_GL=")))
    return entries
