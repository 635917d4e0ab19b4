"""`sw2sim ros` runs a launch file that names robot_state_publisher's old node type,
`state_publisher` (what the exporter's early releases wrote; Noetic removed it), as the
type it became, says so, and leaves the user's file as it was."""

from __future__ import annotations

import shutil
import subprocess
import sys

from repository import ROOT


def test_state_publisher_runs_as_robot_state_publisher(ros, tmp_path):
    package = tmp_path / "example_3"
    shutil.copytree(ROOT / "examples" / "example_3", package)
    launch = package / "launch" / "gazebo.launch"
    old = launch.read_text(encoding="utf-8").replace('type="robot_state_publisher"',
                                                     'type="state_publisher"')
    launch.write_text(old, encoding="utf-8")
    run = subprocess.Popen([sys.executable, "-m", "sw2sim", "ros", str(package), "--duration", "6",
                            "--realtime", "5"], env=ros.env, stdout=subprocess.PIPE,
                           stderr=subprocess.STDOUT, text=True, start_new_session=True)
    try:
        out, _ = run.communicate(timeout=90)
    finally:
        if run.poll() is None:
            run.kill()
            run.communicate()
    assert run.returncode == 0, out[-3000:]
    assert ("node type robot_state_publisher/state_publisher was renamed robot_state_publisher"
            in out), out[:2000]
    assert "robot_state_publisher (robot_state_publisher/robot_state_publisher)" in out
    assert "process has died" not in out and "cannot launch node" not in out, out[-3000:]
    assert launch.read_text(encoding="utf-8") == old, "the user's launch file is untouched"
