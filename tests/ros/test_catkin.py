"""The example packages build and install with Debian's catkin, as Practice 1 builds them:
`catkin_make install` in a workspace of their own puts each package's ROS nodes where
`rosrun` finds them (catkin_install_python), and its folders where `roslaunch` does."""

from __future__ import annotations

import os
import re
import shutil
import subprocess

import pytest

from packages import EXAMPLES
from repository import practice_numbers

BUILD_TIMEOUT = 120.0


def _launched_nodes(package) -> set[str]:
    """The package's own Python nodes that its gazebo.launch starts."""
    launch = (package / "launch" / "gazebo.launch").read_text()
    name = package.name
    return {m[1] for m in re.finditer(r'<node\b[^>]*\bpkg="' + name + r'"[^>]*\btype="([^"]+\.py)"',
                                      launch, re.S)}


@pytest.mark.skipif(shutil.which("catkin_make") is None,
                    reason="catkin is not installed: `make setup` installs it from Debian where "
                           "the distribution ships ROS 1")
def test_catkin_make_install_puts_every_node_where_rosrun_finds_it(tmp_path):
    source = tmp_path / "catkin_ws" / "src"
    names = [f"example_{n}" for n in practice_numbers()]
    for name in names:
        shutil.copytree(EXAMPLES / name, source / name)
    env = {"PATH": f"/usr/bin{os.pathsep}/bin", "HOME": str(tmp_path), "LANG": "C.UTF-8"}
    done = subprocess.run(["catkin_make", "install"], cwd=source.parent, env=env,
                          capture_output=True, text=True, timeout=BUILD_TIMEOUT,
                          start_new_session=True)
    assert done.returncode == 0, done.stdout[-3000:] + done.stderr[-3000:]
    install = source.parent / "install"
    nodes_seen = 0
    for name in names:
        for folder in ("config", "launch", "meshes", "urdf"):
            assert (install / "share" / name / folder).is_dir(), (name, folder)
        for node in _launched_nodes(EXAMPLES / name):
            program = install / "lib" / name / node
            assert program.is_file(), f"{name}: {node} is not installed; CMakeLists.txt " \
                                      f"should list it in catkin_install_python"
            assert os.access(program, os.X_OK), program
            nodes_seen += 1
    assert nodes_seen >= 3, "Practices 1, 3 and 5 start nodes of their own"
