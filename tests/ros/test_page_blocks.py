"""Every ROS block of the lesson pages (`data-ros`) runs in page order under a real ROS 1
master, with `sw2sim ros`'s stand-in in Gazebo's place (course/snippets/ros.py); where a
page states what the ROS side does, the claim is checked on what the run publishes."""

from __future__ import annotations

import json
import math
import os
import re
import select
import signal
import subprocess
import sys
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest

from course.snippets import find_pages, parse_page
from course.snippets.ros import RosBlockError, Session
from page_text import flat_page
from repository import ROOT
from stamp_rate import sent_per_second

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


def _page_numbers(page: str, pattern: str) -> list[float]:
    """The numbers a page states, found by a pattern whose groups are numbers (the page's
    line breaks read as spaces)."""
    m = re.search(pattern, flat_page(page.removeprefix("_pages/")))
    assert m, f"{page} no longer says {pattern!r}"
    return [float(g) for g in m.groups()]


def _series(record: dict, field: str, joint: str) -> tuple[np.ndarray, np.ndarray]:
    """One joint's positions or speeds over the recording, with their simulated times."""
    rows = [(t, v[joint]) for t, v in record[field] if joint in v]
    assert len(rows) > 10, f"too few joint states for {joint}"
    t, v = np.array(rows).T
    return t, v


def _steady(record: dict, field: str, joint: str, last: float) -> np.ndarray:
    """One joint's position or speed over the record's last `last` seconds."""
    t, v = _series(record, field, joint)
    values = v[t >= t[-1] - last]
    assert len(values) >= 5, f"too few joint states for {joint}"
    return values


def _echoed(session, topic: str, messages: int = 20) -> str:
    """What the page's `rostopic echo TOPIC` printed, once it has printed `messages`
    messages (each ends with `---`), or after 30 s."""
    for r in session.running:
        if r.command.words[:3] == ["rostopic", "echo", topic]:
            deadline = time.monotonic() + 30
            while time.monotonic() < deadline:
                text = r.log.read_text(errors="replace")
                if text.count("\n---") >= messages:
                    break
                time.sleep(0.1)
            return text
    raise AssertionError(f"the page has no `rostopic echo {topic}` that ran")


def _rate(record: dict, field: str = "states") -> float:
    """Messages per simulated second, as the publisher sends them: one over the usual gap
    between the messages' stamps. (A publisher's queue drops messages that a slow
    subscriber has not taken, as real ROS does; a drop leaves a double gap, which a count
    would read as a lower rate.)"""
    return sent_per_second([row[0] for row in record[field]])


PULSE_PAGE = "_pages/practice-1/05-custom-node.md"


def _one_wheel_pushed(record: dict, session) -> None:
    """Practice 1, the effort service: the front left wheel gains the page's 62.6 rad/s
    more than the others (the node's pulses, if one falls in, push every wheel alike)."""
    step, = _page_numbers(PULSE_PAGE, r"spins up for one second of simulated time, to the "
                                      r"same ([\d.]+) rad/s")
    t, pushed = _series(record, "speeds", "front_left_joint")
    _, other = _series(record, "speeds", "rear_left_joint")
    gain = (pushed - other)[-1] - (pushed - other)[0]
    assert abs(gain - step) < 0.01 * step, (gain, step)


def _wheel_pulses(record: dict, session) -> None:
    """Practice 1: every pulse of the node adds the page's 62.6 rad/s to each wheel, and
    the joint states come at the page's rate, per simulated second."""
    from course.practices import PRACTICES, design
    step, = _page_numbers(PULSE_PAGE, r"each pulse adds the same ([\d.]+) rad/s")
    rate, = _page_numbers(PULSE_PAGE, r"on `/joint_states` (\d+) times per second of simulated time")
    assert abs(_rate(record) - rate) < 0.01 * rate, _rate(record)
    joints = design(PRACTICES[0]).robot().movable_joints()
    assert joints
    for joint in joints:
        _, speed = _series(record, "speeds", joint.name)
        # Between pulses the speed holds; each pulse adds the same step. The recording may
        # begin during a pulse, so only speeds that hold count.
        plateaus = []
        for value, change in zip(speed[1:], np.diff(speed)):
            if abs(change) < 1e-6 and (not plateaus or abs(value - plateaus[-1]) > 1.0):
                plateaus.append(float(value))
        gains = np.diff(plateaus)
        assert len(gains) >= 1, (joint.name, plateaus)
        assert np.allclose(gains, step, atol=0.1), (joint.name, plateaus)


ARM_PAGE = "_pages/practice-3/04-controllers.md"


def _moves_from(t: np.ndarray, v: np.ndarray) -> float:
    """When a joint at rest sets off: its first state faster than 1 mm/s (or mrad/s). The
    command's own time, as a recorder hears it, may be off by the wall clock's delays
    (tenths of a simulated second at REALTIME)."""
    moving = t[np.abs(v) > 1e-3]
    assert len(moving), "the joint never moves"
    return float(moving[0])


def _arm_goes_to_the_command(record: dict, session) -> None:
    """Practice 3, by hand: with the random node stopped, the middle joint goes to the
    page's 0.5 rad, its error under 0.01 rad within the page's time, and stays; the state
    comes at the page's rate, and `rostopic echo .../state` shows the same."""
    target, = _page_numbers(ARM_PAGE, r'middle_arm_controller/command std_msgs/Float64 "data: ([\d.]+)"')
    within, = _page_numbers(ARM_PAGE, r"The error shrinks below 0\.01 rad within ([\d.]+) s")
    rate, = _page_numbers(ARM_PAGE, r"come at the YAML's `publish_rate`, (\d+) per second")
    gazebo, here = _page_numbers(ARM_PAGE, r"runs at every step of the physics: (\d+) times per "
                                           r"second of simulated time in Gazebo, whose step is 1 ms, "
                                           r"and (\d+) with MuJoCo's 2 ms step")
    assert (gazebo, here) == (1 / 0.001 / 10, 1 / 0.002 / 10)
    commands = record["commands"]["/example_3/middle_arm_controller/command"]
    assert [v for _, v in commands] == [target], "only the page's command: the random node is stopped"
    t, q = _series(record, "states", "middle_arm_joint")
    start = _moves_from(t, _series(record, "speeds", "middle_arm_joint")[1])
    settled = t >= start + within
    assert settled.sum() >= 10 and np.all(np.abs(q[settled] - target) < 0.01), q[settled][:5]
    assert abs(_rate(record) - rate) < 0.01 * rate, _rate(record)
    echoed = _echoed(session, "/example_3/middle_arm_controller/state")
    messages = [m for m in echoed.split("---") if "set_point" in m]
    assert messages, echoed[-500:]
    stamps = [int(secs) + int(nsecs) / 1e9 for secs, nsecs in
              re.findall(r"^\s+secs: (\d+)\n\s+nsecs: +(\d+)$", echoed, re.M)]
    assert len(stamps) > 10, echoed[-500:]
    state_rate = sent_per_second(stamps)
    assert abs(state_rate - here) < 0.02 * here, state_rate
    last = dict(re.findall(r"^(set_point|process_value|error): (\S+)$", messages[-1], re.M))
    assert float(last["set_point"]) == target, last
    assert abs(float(last["error"])) < 0.01 and abs(float(last["process_value"]) - target) < 0.01


def _arm_follows_random_setpoints(record: dict, session) -> None:
    """Practice 3, the movement script: every joint arrives at each new set point within
    the page's time and stays within 0.01 rad of it for the last three seconds of five."""
    page = "_pages/practice-3/05-position-control.md"
    arrive, = _page_numbers(page, r"arrives at every new set point within (\d+) s")
    checked = 0
    for topic, joint in (("/example_3/middle_arm_controller/command", "middle_arm_joint"),
                         ("/example_3/end_arm_controller/command", "end_arm_joint")):
        sent = record["commands"][topic]
        t, q = _series(record, "states", joint)
        for (ts, target), following in zip(sent, [*sent[1:], [t[-1], None]]):
            # (the recorder hears the next set point a state or two after the simulation)
            window = (t >= ts + arrive) & (t < following[0] - 0.1)
            if following[1] is None or window.sum() < 10:
                continue
            assert np.abs(q[window] - target).max() < 0.01, (joint, ts, target)
            late = (t >= following[0] - 3.0) & (t < following[0] - 0.1)
            assert np.abs(q[late] - target).max() < 0.01
            checked += 1
    assert checked >= 2, record["commands"]


BLOCK_PAGE = "_pages/practice-4/04-testing-and-scripting.md"


def _block_travels_and_settles(record: dict, session) -> None:
    """Practice 4: after `rostopic pub -1 ... "data: 1.5"` the block reaches 1.5 m when the
    page says, overshoots by what it says, is within 5 mm from when it says, at no more
    than 1 m/s; `rostopic echo` then prints 1.5 to within 0.005."""
    target, = _page_numbers(BLOCK_PAGE, r'block_controller/command std_msgs/Float64 "data: ([\d.]+)"')
    arrive, overshoot, within = _page_numbers(
        BLOCK_PAGE, r"first reaches [\d.]+ m about ([\d.]+) s after it sets off\. Its momentum "
                    r"carries it ([\d.]+) mm past; .*? from about ([\d.]+) s after setting off "
                    r"it stays within 5 mm")
    commands = record["commands"]["/example_4/block_controller/command"]
    assert [v for _, v in commands] == [target]
    t, x = _series(record, "states", "block_joint")
    _, v = _series(record, "speeds", "block_joint")
    start = _moves_from(t, v)
    assert abs(t[x >= target][0] - start - arrive) < 0.1, t[x >= target][0] - start
    assert abs((x.max() - target) * 1000 - overshoot) < 0.5, x.max()
    outside = t[np.abs(x - target) >= 0.005]
    assert abs(outside[-1] - start - within) < 0.3, outside[-1] - start
    assert np.abs(v).max() <= 1.0 + 1e-3, np.abs(v).max()
    echoed = _echoed(session, "/example_4/block_controller/state/process_value")
    # `rostopic echo` of a message's field prints its value alone, then `---`
    values = [float(v) for v in re.findall(r"^(-?[\d.]+(?:e[-+]?\d+)?)$", echoed, re.M)]
    assert len(values) >= 5, echoed[-300:]
    assert all(abs(v - target) < 0.005 for v in values[-5:]), values[-5:]


def _car_steers_by_equation_4(record: dict, session) -> None:
    """Practice 5: after the page's two commands the centre joint stands at the commanded
    angle, the knuckles at the page's angles, which are Equation 4's for it, and every wheel
    turns at the page's speed, that of its own circle, omega * r = v * d / R (within 1 %)."""
    from course.practices import PRACTICES, design
    page = "_pages/practice-5/04-control-script.md"
    car = design(PRACTICES[4])
    l, w, r = car.mm(car.WHEELBASE), car.mm(car.TRACK), car.mm(car.WHEEL_RADIUS)
    # what the page's two `rostopic pub` commands send
    steering, = _page_numbers(page, r'steering_controller/command std_msgs/Float64 "data: ([\d.]+)"')
    speed, = _page_numbers(page, r'cmd_speed std_msgs/Float64 "data: ([\d.]+)"')
    said = _page_numbers(page, r"knuckles at Equation 4's angles for it: ([\d.]+)° on the left.*?"
                               r"and ([\d.]+)° on the right\. The turn's centre lies ([\d.]+) m")
    wheels = _page_numbers(page, r"([\d.]+) and ([\d.]+) rad/s at the back, ([\d.]+) and "
                                 r"([\d.]+) rad/s at the front")
    inner, outer = car.ackermann(steering, l, w)
    radius = l / math.tan(steering)
    assert np.allclose(said, [math.degrees(inner), math.degrees(outer), radius], atol=0.006)
    offsets = {"rear_left": (0.0, w / 2), "rear_right": (0.0, -w / 2),
               "front_left": (l, w / 2), "front_right": (l, -w / 2)}
    paths = {k: speed * math.hypot(along, radius - left) / radius
             for k, (along, left) in offsets.items()}
    assert np.allclose(wheels, [paths[k] / r for k in offsets], atol=0.006)

    phi = float(np.mean(_steady(record, "states", "steering_joint", 0.5)))
    assert abs(phi - steering) < math.radians(0.5), phi
    inner, outer = car.ackermann(phi, l, w)
    for joint, expected in (("left_knuckle_joint", inner), ("right_knuckle_joint", outer)):
        angle = _steady(record, "states", joint, 0.5)
        assert np.all(np.abs(angle - expected) < math.radians(0.5)), (joint, expected, angle)
    for wheel, path in paths.items():
        omega = _steady(record, "speeds", f"{wheel}_wheel_joint", 0.5)
        assert np.all(np.abs(omega * r - path) < 0.01 * path), (wheel, path, omega * r)


@dataclass(frozen=True)
class Claim:
    """What a page says the ROS side does, checked on a recording (tests/ros/record.py)."""

    check: Callable[[dict, Session], None]
    topics: tuple[str, ...]   # the joint states' topic, then std_msgs/Float64 topics
    seconds: float            # simulated seconds to record
    # The recording starts just before the page's command that starts with this (and ends
    # before the next command runs), or after the page's last command when None.
    before: str | None = None
    # The seconds are counted from the first message on the first Float64 topic (the
    # command a `rostopic pub` sends, a second or so of the wall clock after it starts).
    from_command: bool = False

    @property
    def until(self) -> str:
        return f"+{self.seconds:g}" + (f"@{self.topics[1]}" if self.from_command else "")


CLAIMS = {
    # (rosservice takes a second or so of the wall clock to start: time enough)
    PULSE_PAGE: (Claim(_one_wheel_pushed, ("/joint_states",), 20, "rosservice call"),
                 # a pulse every 10 s, 1 s long: 13 s hold a whole one wherever they begin
                 Claim(_wheel_pulses, ("/joint_states",), 13)),
    ARM_PAGE: (Claim(_arm_goes_to_the_command, ("/example_3/joint_states",
                                                "/example_3/middle_arm_controller/command"),
                     4, "rostopic pub -1 /example_3", from_command=True),),
    "_pages/practice-3/05-position-control.md": (
        Claim(_arm_follows_random_setpoints, ("/example_3/joint_states",
                                              "/example_3/middle_arm_controller/command",
                                              "/example_3/end_arm_controller/command"), 16),),
    BLOCK_PAGE: (Claim(_block_travels_and_settles, ("/example_4/joint_states",
                                                    "/example_4/block_controller/command"),
                       12, "rostopic pub -1 /example_4", from_command=True),),
    "_pages/practice-5/04-control-script.md": (
        Claim(_car_steers_by_equation_4, ("/example_5/joint_states",), 1),),
}


class Recorders:
    """The page's recordings, each a record.py process started when its claim says."""

    def __init__(self, ros, claims):
        self.ros, self.claims = ros, claims
        self.started: dict[Claim, subprocess.Popen] = {}
        self.records: dict[Claim, dict] = {}

    def start(self, claim: Claim) -> None:
        process = subprocess.Popen(
            [sys.executable, str(RECORD), claim.until, *claim.topics], env=self.ros.env,
            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True)
        self.started[claim] = process
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline and process.poll() is None:
            if select.select([process.stderr], [], [], 0.1)[0]:
                if process.stderr.readline().strip() == "recording":
                    return
        raise AssertionError(f"the recorder heard nothing on {claim.topics[0]}")

    def finish(self, claim: Claim) -> None:
        process = self.started[claim]
        out, err = process.communicate(timeout=120)
        assert process.returncode == 0, out[-2000:] + err[-2000:]
        self.records[claim] = json.loads(out.splitlines()[-1])

    def before(self, command) -> None:
        """The session's hook: end the recordings of the command before, start this one's."""
        for claim in self.started:
            if claim not in self.records:
                self.finish(claim)
        for claim in self.claims:
            if claim.before and command.text.startswith(claim.before) and claim not in self.started:
                self.start(claim)

    def close(self) -> None:
        for process in self.started.values():
            if process.poll() is None:
                os.killpg(process.pid, signal.SIGKILL)
                process.communicate()


KDL_WARNING = "has an inertia specified in the URDF, but KDL does not support a root link"


def _log_lines_said(session, page) -> None:
    """What the reader meets in the page's terminals and cannot place is said on the page:
    KDL's warning about the root link's inertia where a launch prints it, and what a
    `grep` of the log printed (nothing, on a clean run)."""
    text = flat_page(page.path.removeprefix("_pages/"))
    for log in sorted(session.logs.glob("*.log")):
        if KDL_WARNING in log.read_text(errors="replace"):
            assert KDL_WARNING.split(",")[0] in text and "kdl-root-inertia" in text, (
                f"{page.path}: a launch prints KDL's warning ({log.name}); say on the page what "
                f"it means (the root link's <inertial>), citing kdl-root-inertia")
    for location, output in session.printed.items():
        line = int(location.rsplit(":", 1)[1])
        block = next((b for b in page.ros_blocks if b.line <= line <= b.line +
                      b.code.count("\n")), None)
        if block and block.code.lstrip().startswith("grep") and not output.strip():
            assert "`grep` prints nothing" in text, (
                f"{location}: the grep of the log printed nothing on this clean run; the page "
                "should say so (`grep` prints nothing)")


def _missing_tools_said(session, page) -> None:
    """A `rosrun` block the runner could not run (a window) has `rosrun` here (the Makefile
    installs rosbash), and a package Debian does not ship is said to be missing, with the
    line that does its work here."""
    import shutil
    text = flat_page(page.path.removeprefix("_pages/"))
    for window in session.windows:
        command = window.split(": ", 1)[1].rsplit(" (opens a window)", 1)[0]
        if not command.startswith("rosrun "):
            continue
        assert shutil.which("rosrun"), f"{window}: no rosrun here; the Makefile's ROS_PACKAGES " \
                                       "installs it with rosbash"
        package = command.split()[1]
        found = subprocess.run(["rospack", "find", package], capture_output=True, text=True,
                               env={**os.environ, "ROS_PACKAGE_PATH": "/usr/share"})
        if found.returncode != 0:
            assert "Debian 12 packages no" in text and "not found" in text, (
                f"{window}: Debian has no {package}; say so beside it, with the line that "
                "does the same here")


def _pub_once_said(page) -> None:
    """A page that sends with `rostopic pub -1` says that it returns only after holding
    the message latched for rostopic's 3 s (_ONCE_DELAY), not at once."""
    import rostopic
    if not any("rostopic pub -1" in b.code for b in page.ros_blocks):
        return
    text = flat_page(page.path.removeprefix("_pages/"))
    said = re.search(r"latched for (\d+) s", text)
    assert said and float(said[1]) == rostopic._ONCE_DELAY, (
        f"{page.path}: `rostopic pub -1` returns after {rostopic._ONCE_DELAY:g} s; say "
        "'latched for 3 s'")
    assert not re.search(r"sends (the message|one position) (once )?and returns", text), page.path


def test_apt_lines_of_the_ros_pages_name_the_distribution_they_are_for():
    """Debian 12 packages no ros-noetic-* (nor ros_control, nor Gazebo): an apt line with
    those names on a ROS 1 page is introduced as Ubuntu's and Noetic's."""
    for path in PAGES:
        page = parse_page(path, ROOT)
        lines = path.read_text(encoding="utf-8").splitlines()
        for block in page.blocks:
            if "apt install ros-noetic-" in block.code:
                before = " ".join(lines[max(0, block.line - 4):block.line - 1])
                assert "Ubuntu" in before and "Noetic" in before, (
                    f"{page.path}:{block.line}: ros-noetic-* packages are Ubuntu's, for ROS "
                    "Noetic; say so before the block (Debian 12 has none of them)")


@pytest.mark.parametrize("path", PAGES, ids=lambda p: p.relative_to(ROOT).as_posix())
def test_page_ros_blocks(path, ros, tmp_path, record_property):
    page = parse_page(path, ROOT)
    assert not page.errors, "\n".join(map(str, page.errors))
    claims = CLAIMS.get(page.path, ())
    fault = None
    recorders = Recorders(ros, claims)
    with Session(page, ROOT, tmp_path / "session", ros.uri) as session:
        try:
            session.before_command = recorders.before
            session.run()
            for claim in claims:
                if claim.before is None:
                    recorders.start(claim)
            for claim in claims:
                if claim in recorders.started and claim not in recorders.records:
                    recorders.finish(claim)
            assert set(recorders.records) == set(claims), "a claim's command never ran"
            session.check()   # (which waits for every `rostopic echo` to print)
            for claim in claims:
                claim.check(recorders.records[claim], session)
            _log_lines_said(session, page)
            _missing_tools_said(session, page)
            _pub_once_said(page)
        except RosBlockError as error:
            fault = str(error)
        finally:
            recorders.close()
        # Read by pytest_terminal_summary in tests/conftest.py.
        record_property("ros_blocks_ran", len(session.ran))
        record_property("ros_windows", session.windows)
    assert not session.leftovers(), f"processes left running: {session.leftovers()}"
    if not fault:
        try:   # each `sw2sim plot`, stopped as the reader's Ctrl-C stops it, wrote its PNG
            assert all(png.is_file() for png in session.plots_written())
        except RosBlockError as error:
            fault = str(error)
    if fault:
        pytest.fail(fault, pytrace=False)
