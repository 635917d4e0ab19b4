"""Every ROS block of the lesson pages (`data-ros`) runs in page order under a real ROS 1
master, with `sw2sim ros`'s stand-in in Gazebo's place (course/snippets/ros.py); where a
page states what the ROS side does, the claim is checked on what the run publishes."""

from __future__ import annotations

import json
import math
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
    for page in ("practice-1/04-testing-and-modifying.md", "practice-1/05-custom-node.md",
                 "practice-3/04-controllers.md",
                 "practice-3/05-position-control.md", "practice-4/04-testing-and-scripting.md",
                 "practice-5/04-control-script.md"):
        assert f"_pages/{page}" in names


def _wheel_pulses(ros, session) -> None:
    """Practice 1: every pulse of the node adds the page's 62.6 rad/s to each wheel."""
    from course.practices import PRACTICES, design
    page_step = 62.6   # rad/s, _pages/practice-1/05-custom-node.md
    # A pulse every 10 s, 1 s long: 13 s hold a whole pulse wherever the recording begins.
    done = ros.python(RECORD, "+13", "/joint_states", timeout=120)
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-2000:]
    record = json.loads(done.stdout.splitlines()[-1])
    joints = design(PRACTICES[0]).robot().movable_joints()
    assert joints
    for joint in joints:
        speed = np.array([s[joint.name] for _, s in record["speeds"]])
        assert len(speed) > 100, "the wheels' states arrive on /joint_states"
        # Between pulses the speed holds; each pulse adds the same step. The recording may
        # begin during a pulse, so only speeds that hold count.
        plateaus = []
        for value, change in zip(speed[1:], np.diff(speed)):
            if abs(change) < 1e-6 and (not plateaus or abs(value - plateaus[-1]) > 1.0):
                plateaus.append(float(value))
        gains = np.diff(plateaus)
        assert len(gains) >= 1, (joint.name, plateaus)
        assert np.allclose(gains, page_step, atol=0.1), (joint.name, plateaus)


def _record(ros, seconds: float, states: str) -> dict:
    done = ros.python(RECORD, f"+{seconds:g}", states, timeout=120)
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-2000:]
    return json.loads(done.stdout.splitlines()[-1])


def _steady(record: dict, field: str, joint: str, last: float) -> np.ndarray:
    """One joint's position or speed over the record's last `last` seconds."""
    rows = record[field]
    end = rows[-1][0]
    values = np.array([v[joint] for t, v in rows if t >= end - last])
    assert len(values) >= 5, f"too few joint states for {joint}"
    return values


def _block_stops_at_the_target(ros, session) -> None:
    """Practice 4: after `rostopic pub -1 ... "data: 1.5"` the block stops within 5 mm of
    1.5 m (the integral term, with antiwindup, included)."""
    record = _record(ros, 12, "/example_4/joint_states")
    position = _steady(record, "states", "block_joint", 1.0)
    assert np.all(np.abs(position - 1.5) < 0.005), position[-5:]


def _car_steers_by_equation_4(ros, session) -> None:
    """Practice 5: after the page's two commands the centre joint stands at 0.3 rad, the
    knuckles at Equation 4's angles for it (within 0.5°), and every wheel turns at the
    speed of its own circle, omega * r = v * d / R (within 1 %)."""
    from course.practices import PRACTICES, design
    car = design(PRACTICES[4])
    l, w, r = car.mm(car.WHEELBASE), car.mm(car.TRACK), car.mm(car.WHEEL_RADIUS)
    steering, speed = 0.3, 0.5    # rad and m/s, as the page's rostopic pub commands
    record = _record(ros, 1, "/example_5/joint_states")
    phi = float(np.mean(_steady(record, "states", "steering_joint", 0.5)))
    assert abs(phi - steering) < math.radians(0.5), phi
    inner, outer = car.ackermann(phi, l, w)
    for joint, expected in (("left_knuckle_joint", inner), ("right_knuckle_joint", outer)):
        angle = _steady(record, "states", joint, 0.5)
        assert np.all(np.abs(angle - expected) < math.radians(0.5)), (joint, expected, angle)
    radius = l / math.tan(phi)
    offsets = {"front_left": (l, w / 2), "front_right": (l, -w / 2),
               "rear_left": (0.0, w / 2), "rear_right": (0.0, -w / 2)}
    for wheel, (along, left) in offsets.items():
        path = speed * math.hypot(along, radius - left) / radius
        omega = _steady(record, "speeds", f"{wheel}_wheel_joint", 0.5)
        assert np.all(np.abs(omega * r - path) < 0.01 * path), (wheel, path, omega * r)


CLAIMS = {"_pages/practice-1/05-custom-node.md": _wheel_pulses,
          "_pages/practice-4/04-testing-and-scripting.md": _block_stops_at_the_target,
          "_pages/practice-5/04-control-script.md": _car_steers_by_equation_4}


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
    assert not session.leftovers(), f"processes left running: {session.leftovers()}"
    if fault:
        pytest.fail(fault, pytrace=False)
