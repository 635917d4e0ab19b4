"""The OpenGL platform is chosen in sw2sim.gl, and only there."""

import os
import re
import subprocess
import sys

import pytest

from repository import ROOT
from sw2sim import gl


def no_osmesa():
    return False


def osmesa():
    return True


@pytest.mark.parametrize("system, environ, has, expected", [
    ("linux", {}, osmesa, "osmesa"),                          # a server or CI with libosmesa6
    ("linux", {}, no_osmesa, "egl"),                          # where Mesa dropped OSMesa
    ("linux", {"DISPLAY": ":0"}, osmesa, None),               # a desktop: MuJoCo's default
    ("linux", {"WAYLAND_DISPLAY": "wayland-0"}, osmesa, None),
    ("win32", {}, osmesa, None),                              # never EGL on Windows or macOS
    ("darwin", {}, no_osmesa, None),
    ("linux", {"MUJOCO_GL": "egl"}, osmesa, "egl"),           # the reader's own choice stays
    ("win32", {"MUJOCO_GL": "glfw"}, osmesa, "glfw"),
])
def test_platform_for(system, environ, has, expected):
    assert gl.platform_for(environ, system, has) == expected


def test_the_viewer_asks_for_a_window_even_where_pictures_use_osmesa():
    environ = {}
    assert gl.platform_for(environ, "linux", osmesa) == "osmesa"
    assert gl.for_window(environ) == "glfw" and environ["MUJOCO_GL"] == "glfw"


def test_choose_sets_only_what_it_chose():
    desktop = {"DISPLAY": ":0"}
    assert gl.choose(desktop) is None and "MUJOCO_GL" not in desktop
    assert gl.choose({"MUJOCO_GL": "osmesa"}) == "osmesa"


def test_no_other_module_sets_mujoco_gl():
    assignment = re.compile(r"""(environ|env)(\[["']MUJOCO_GL["']\]\s*=(?!=)|\.setdefault\(\s*["']MUJOCO_GL)""")
    offenders = []
    for folder in ("sw2sim", "course", "tests", "tools", "examples"):
        for path in (ROOT / folder).rglob("*.py"):
            if path == ROOT / "sw2sim" / "gl.py" or "__pycache__" in path.parts:
                continue
            for n, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
                if assignment.search(line):
                    offenders.append(f"{path.relative_to(ROOT)}:{n}: {line.strip()}")
    makefile = (ROOT / "Makefile").read_text(encoding="utf-8")
    if re.search(r"^\s*export\s+MUJOCO_GL", makefile, re.M):
        offenders.append("Makefile exports MUJOCO_GL")
    assert not offenders, "set MUJOCO_GL through sw2sim.gl only:\n" + "\n".join(offenders)


def test_the_ros_simulation_loads_no_opengl_unless_it_shows_a_window():
    """sw2sim ros's simulation node draws nothing without --view: MuJoCo is imported with
    drawing turned off (no OpenGL library loaded); with --view it draws in a window."""
    probe = ("import sys, os, sw2sim.ros.gzserver; "
             "print(os.environ['MUJOCO_GL'], 'OpenGL' in sys.modules)")
    for view, expected in (("0", "disable False"), ("1", "osmesa True")):
        env = {**os.environ, "MUJOCO_GL": "osmesa", "SW2SIM_VIEW": view}
        done = subprocess.run([sys.executable, "-c", probe], env=env, capture_output=True,
                              text=True, cwd=ROOT, timeout=60)
        assert done.stdout.split("\n")[0] == expected, done.stdout + done.stderr


def test_osmesa_is_found_without_starting_ldconfig(monkeypatch):
    """`import sw2sim` looks for OSMesa at every start: in the library folders, not with
    ctypes' search, which runs `ldconfig -p` in a process of its own."""
    import ctypes.util
    from pathlib import Path
    if not any(Path(f).glob("libOSMesa.so*") for f in gl.LIBRARY_FOLDERS if Path(f).is_dir()):
        pytest.skip("OSMesa is not installed in a library folder here (libosmesa6)")

    def no_search(name):
        raise AssertionError(f"ctypes.util.find_library({name!r}) starts ldconfig")

    monkeypatch.setattr(ctypes.util, "find_library", no_search)
    assert gl.osmesa_installed()
    assert gl.platform_for({}, system="linux") == "osmesa"
