"""Every ROS block of the lesson pages (`data-ros`) runs in page order under a real ROS 1
master, with `sw2sim ros`'s stand-in in Gazebo's place (course/snippets/ros.py); where a
page states what the ROS side does, the claim is checked on what the run publishes."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from course.snippets import find_pages, parse_page
from course.snippets.ros import RosBlockError, Session
from repository import ROOT

RECORD = Path(__file__).with_name("record.py")
PAGES = [p for p in find_pages(ROOT) if parse_page(p, ROOT).ros_blocks]


def test_the_practices_with_ros_have_ros_blocks():
    """Pages of every practice whose package has a ROS node show it running; a page that
    lost its data-ros marks would silently leave the run."""
    names = {p.relative_to(ROOT).as_posix() for p in PAGES}
    for page in ("practice-1/05-custom-node.md", "practice-3/04-controllers.md",
                 "practice-3/05-position-control.md"):
        assert f"_pages/{page}" in names


def _wheel_pulses(ros, session) -> None:
    """Practice 1: every pulse of the node adds the page's 62.6 rad/s to each wheel."""
    from course.practices import PRACTICES, design
    page_step = 62.6   # rad/s, _pages/practice-1/05-custom-node.md
    done = ros.python(RECORD, "+12", "/joint_states", timeout=120)
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-2000:]
    record = json.loads(done.stdout.splitlines()[-1])
    joints = design(PRACTICES[0]).robot().movable_joints()
    assert joints
    for joint in joints:
        speed = np.array([s[joint.name] for _, s in record["speeds"]])
        assert len(speed) > 100, "the wheels' states arrive on /joint_states"
        # Between pulses the speed holds; each pulse adds the same step.
        plateaus = [float(speed[0])]
        for value, change in zip(speed[1:], np.diff(speed)):
            if abs(change) < 1e-6 and abs(value - plateaus[-1]) > 1.0:
                plateaus.append(float(value))
        gains = np.diff(plateaus)
        assert len(gains) >= 1, (joint.name, plateaus)
        assert np.allclose(gains, page_step, atol=0.1), (joint.name, plateaus)


CLAIMS = {"_pages/practice-1/05-custom-node.md": _wheel_pulses}


@pytest.mark.parametrize("path", PAGES, ids=lambda p: p.relative_to(ROOT).as_posix())
def test_page_ros_blocks(path, ros, tmp_path, record_property):
    page = parse_page(path, ROOT)
    assert not page.errors, "\n".join(map(str, page.errors))
    fault = None
    with Session(page, ROOT, tmp_path / "session", ros.env) as session:
        try:
            session.run()
            claim = CLAIMS.get(page.path)
            if claim:
                claim(ros, session)
            session.check()
        except RosBlockError as error:
            fault = str(error)
        # Read by pytest_terminal_summary in tests/conftest.py.
        record_property("ros_blocks_ran", len(session.ran))
        record_property("ros_windows", session.windows)
    if fault:
        pytest.fail(fault, pytrace=False)
