"""`sw2sim check` and `sw2sim convert` need no OpenGL: they work where no off-screen library
can be found and MUJOCO_GL is not set, as on a reader's Windows or macOS machine
(tests/without_gl.py says how that is made here)."""

from __future__ import annotations

import subprocess
import sys

import pytest

from repository import EXAMPLES
from without_gl import environment, processes


def sw2sim(env: dict[str, str], cwd, *args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-m", "sw2sim", *args], cwd=cwd, env=env, stdin=subprocess.DEVNULL,
                          capture_output=True, text=True, encoding="utf-8", timeout=300, check=False)


@pytest.mark.parametrize("desktop", [True, False], ids=["display-without-gl", "headless-without-osmesa"])
def test_check_and_convert_work_without_an_opengl_library(tmp_path, desktop):
    env, log = environment(tmp_path, desktop=desktop)
    # What sw2sim chooses there: nothing (MuJoCo's own default, GLFW, which has no display
    # to draw on), or on Linux without a display EGL, since OSMesa cannot be found. On
    # Windows and macOS (.github/workflows/other-systems.yml) it is nothing either way.
    chosen = subprocess.run([sys.executable, "-c", "import os, sw2sim; print(os.environ.get('MUJOCO_GL', 'unset'))"],
                            env=env, capture_output=True, text=True, timeout=120, check=True)
    headless_linux = sys.platform.startswith("linux") and not desktop
    assert chosen.stdout.strip() == ("egl" if headless_linux else "unset")

    done = sw2sim(env, tmp_path, "check", str(EXAMPLES / "example_1"))
    assert done.returncode == 0, done.stdout + done.stderr
    done = sw2sim(env, tmp_path, "convert", str(EXAMPLES / "example_1"), "-o", "out")
    assert done.returncode == 0, done.stdout + done.stderr
    scene = tmp_path / "out" / "scene.xml"
    assert scene.is_file()
    # The same bytes on every system: "\n" line ends, never "\r\n".
    for written in (tmp_path / "out").glob("*.*"):
        if written.suffix in (".xml", ".md"):
            assert b"\r\n" not in written.read_bytes(), written.name
    # Every command ran with the hook, and none had MUJOCO_GL set from outside.
    started = processes(log)
    assert len(started) >= 3 and all(setting == "" for _, setting in started), started


def test_the_hook_hides_osmesa(tmp_path):
    """Without the hook this machine finds OSMesa (or not); with it, never."""
    env, _ = environment(tmp_path, desktop=False)
    done = subprocess.run([sys.executable, "-c", "import ctypes.util; print(ctypes.util.find_library('OSMesa'))"],
                          env=env, capture_output=True, text=True, timeout=60, check=True)
    assert done.stdout.strip() == "None"
    done = subprocess.run([sys.executable, "-c", "from sw2sim import gl; print(gl.osmesa_installed())"],
                          env=env, capture_output=True, text=True, timeout=60, check=True)
    assert done.stdout.strip() == "False"
