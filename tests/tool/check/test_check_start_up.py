"""What a `sw2sim check` process loads: no mesh library for the formats the check reads
itself (binary and text STL, OBJ and COLLADA of triangles: trimesh brings scipy and
networkx, seconds of start-up), no OpenGL library, since the check draws nothing, and no
OpenBLAS threads beside its own (they spin while they wait). A caller that runs the
check inside a process of its own (`main(argv)`: a test, a notebook) keeps its platform,
since it may draw afterwards, and its environment."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest
from packages import as_obj, copy_example


# Runs `sw2sim check` as the command line does (main() reading sys.argv) or as a caller
# does (main(argv)), then writes what the process holds to the file named first. The
# command line's check ends its process at once (sw2sim.cli._end_now): the record is
# written as it calls os._exit, and says so.
PROBE = """
import json, os, sys
out, how, path = sys.argv[1:4]
before = os.environ.get("MUJOCO_GL")
sys.argv = ["sw2sim", "check", path]

def record(status, ended_at_once):
    import mujoco
    loaded = sorted({m.split(".")[0] for m in sys.modules} & {"trimesh", "scipy", "networkx", "OpenGL"})
    with open(out, "w") as f:
        json.dump({"status": status, "loaded": loaded, "before": before,
                   "after": os.environ.get("MUJOCO_GL"), "draws": hasattr(mujoco, "GLContext"),
                   "ended_at_once": ended_at_once,
                   "blas": os.environ.get("OPENBLAS_NUM_THREADS"),
                   "threads": os.listdir("/proc/self/task") if os.path.isdir("/proc/self/task") else None}, f)

exit_now = os._exit
def ending(status):
    record(status, True)
    exit_now(status)
os._exit = ending
from sw2sim.cli import main
status = main() if how == "command" else main(["check", path])
record(status, False)
"""


def _probe(tmp_path: Path, how: str, package: Path, env: dict | None = None) -> dict:
    out = tmp_path / f"probe-{how}.json"
    if env is None:
        env = {k: v for k, v in os.environ.items() if k != "OPENBLAS_NUM_THREADS"}
    done = subprocess.run([sys.executable, "-c", PROBE, str(out), how, str(package)],
                          cwd=tmp_path, env=env, capture_output=True, text=True, timeout=300)
    assert out.is_file(), done.stdout + done.stderr
    return json.loads(out.read_text())


def test_the_command_loads_neither_a_mesh_library_nor_opengl(tmp_path):
    package = copy_example(1, tmp_path)
    found = _probe(tmp_path, "command", package)
    assert found["status"] == 0 and found["ended_at_once"]
    assert found["loaded"] == []
    assert not found["draws"], "MuJoCo was imported with drawing turned off"
    assert found["after"] == found["before"], "the platform chosen for drawing is put back"
    assert found["blas"] == "1"     # numpy's OpenBLAS starts no thread of its own


def test_the_users_own_blas_threads_are_kept(tmp_path):
    """OPENBLAS_NUM_THREADS=4 set by the user stays, and gives the process the threads
    (one per core beyond the first, up to 3) that the check's own choice leaves out."""
    package = copy_example(3, tmp_path)
    own = _probe(tmp_path, "command", package)
    users = _probe(tmp_path, "command", package,
                   {**os.environ, "OPENBLAS_NUM_THREADS": "4"})
    assert (own["blas"], users["blas"]) == ("1", "4")
    if own["threads"] is not None:
        extra = min(4, os.cpu_count() or 1) - 1
        assert len(users["threads"]) == len(own["threads"]) + extra


def test_an_obj_package_is_read_without_trimesh(tmp_path):
    package = as_obj(copy_example(3, tmp_path))
    found = _probe(tmp_path, "command", package)
    assert found["status"] == 0 and found["loaded"] == []


def _as_collada(package: Path) -> Path:
    """The package with each binary STL rewritten as COLLADA (by trimesh, here in the test),
    the STL removed, so that the model too reads the meshes through a conversion."""
    import trimesh
    urdf = next((package / "urdf").glob("*.urdf"))
    text = urdf.read_text()
    for stl in sorted((package / "meshes").glob("*.STL")):
        trimesh.load(stl).export(stl.with_suffix(".dae"))
        stl.unlink()
        text = text.replace(f"{stl.name}\"", f"{stl.stem}.dae\"")
    urdf.write_text(text)
    return package


def test_a_collada_package_is_read_without_trimesh(tmp_path):
    package = _as_collada(copy_example(3, tmp_path))
    found = _probe(tmp_path, "command", package)
    # status 1: MuJoCo cannot read COLLADA (mesh-format), which convert repairs
    assert found["status"] == 1 and found["loaded"] == []


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="OSMesa is Linux's")
def test_a_caller_of_main_keeps_its_platform(tmp_path):
    package = copy_example(4, tmp_path)
    env = {**os.environ, "MUJOCO_GL": "osmesa"}
    found = _probe(tmp_path, "argv", package, env)
    assert found["status"] == 0 and not found["ended_at_once"], "main(argv) returns"
    assert found["draws"] and "OpenGL" in found["loaded"]
    assert found["after"] == "osmesa"
    assert found["blas"] is None     # the caller's environment is its own
