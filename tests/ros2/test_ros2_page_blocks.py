"""Every ROS 2 block of the practices' ROS 2 pages (`data-ros2`) runs in page order under
real rclpy, with `sw2sim ros2` in Gazebo Sim's place (course/snippets/ros2.py); what each
page says the robot does is checked on what an independent recorder (record.py, a plain
rclpy node) sees, and every `ros2 topic` command the page shows for Jazzy names a topic
the run has, with its type and the message's fields (jazzy_commands.py)."""

from __future__ import annotations

import json
import math
import re
import select
import subprocess
import time
from pathlib import Path

import numpy as np
import pytest

from course.snippets import find_pages, parse_page
from course.snippets.ros2 import Ros2BlockError, Session
import ctrl_c
from jazzy_commands import (action_problems, action_types, field_tables, jazzy_commands,
                            topic_line, topic_problems, topic_types)
from repository import ROOT
import ros2_domains
from ros2_environment import PYTHON, missing

RECORD = Path(__file__).with_name("record.py")
PAGES = [p for p in find_pages(ROOT) if parse_page(p, ROOT).ros2_blocks]
WHEELS = ["front_left_joint", "front_right_joint", "rear_left_joint", "rear_right_joint"]
PULSE = 1.0   # s: the pulse nodes' length of a pulse
# How each lesson node is started again and stopped with Ctrl-C on its page's run, beside the
# stop at a random moment that ends the run: while rclpy converts a message it took, where a
# KeyboardInterrupt becomes rclpy's RuntimeError (tools/benchmark.py ctrl-c stops each 50
# times at random moments).
CTRL_C_IN_TAKE = (True,)


def test_every_practice_has_a_ros2_page_that_runs():
    """The last page of each practice is its ROS 2 page, and its blocks run here."""
    names = {p.relative_to(ROOT).as_posix() for p in PAGES}
    for folder in sorted((ROOT / "_pages").glob("practice-*")):
        last = sorted(folder.glob("*.md"))[-1]
        assert last.name.endswith("-ros2.md"), last
        assert last.relative_to(ROOT).as_posix() in names, last


# -- what the pages say, checked on the recording ---------------------------------------
def _page_text(page: str) -> str:
    """The page's text, each run of spaces and line breaks one space."""
    return re.sub(r"\s+", " ", (ROOT / page).read_text(encoding="utf-8"))


def _page_number(page: str, pattern: str) -> float:
    """A number the page states, found by a pattern with one group."""
    m = re.search(pattern, _page_text(page))
    assert m, f"{page} no longer says {pattern!r}"
    return float(m.group(1))


def _series(record: dict, field: str, joint: str) -> tuple[np.ndarray, np.ndarray]:
    rows = [(t, v[joint]) for t, v in record[field] if joint in v]
    assert len(rows) > 10, f"too few joint states for {joint}"
    t, v = np.array(rows).T
    return t, v


def _wheel_pulses(record: dict) -> None:
    """Practice 1: each pulse adds about 62.6 rad/s to every wheel (within the page's 2 %)."""
    page = "_pages/practice-1/06-ros2.md"
    step = _page_number(page, r"Each pulse adds about ([\d.]+) rad/s")
    share = _page_number(page, r"accept (\d+) %") / 100
    start = record["start"]           # when the wheels begin to turn: the pulse's start
    for joint in WHEELS:
        t, speed = _series(record, "speeds", joint)
        after = speed[t > start + PULSE + 0.2]
        assert len(after) > 5, (joint, t[-1], start)
        assert np.ptp(after) < 1e-3, (joint, "the speed holds between pulses")
        assert abs(after.mean() - step) < share * step, (joint, after.mean(), step)


def _friction_and_pulses(record: dict) -> None:
    """Practice 2: the wheels without friction gain 62.6 rad/s a pulse; those with 0.7 N·m
    reach about 18.8 rad/s and stand still about 0.43 s after the pulse."""
    page = "_pages/practice-2/05-ros2.md"
    free = _page_number(page, r"gain about ([\d.]+) rad/s")
    # the pulse's length: Practice 1's node, so Practice 1's page says how close
    share = _page_number("_pages/practice-1/06-ros2.md", r"accept (\d+) %") / 100
    peak = _page_number(page, r"reach about ([\d.]+) rad/s")
    stops = _page_number(page, r"stand still again about ([\d.]+) s later")
    end = record["start"] + PULSE
    for joint in ("rear_left_joint", "rear_right_joint"):
        t, speed = _series(record, "speeds", joint)
        after = speed[t > end + 0.2]
        assert abs(after.mean() - free) < share * free, (joint, after.mean())
    for joint in ("front_left_joint", "front_right_joint"):
        t, speed = _series(record, "speeds", joint)
        assert abs(speed.max() - peak) < 0.02 * peak, (joint, speed.max())
        still = t[(t > end) & (np.abs(speed) < 0.01 * peak)]
        assert len(still), (joint, "the wheel stops")
        assert abs(still[0] - end - stops) < 0.05, (joint, still[0] - end)


def _arm_follows_setpoints(record: dict) -> None:
    """Practice 3: from 2.5 s after each set point to the next, every joint is within
    0.01 rad of it."""
    page = "_pages/practice-3/06-ros2.md"
    tolerance = _page_number(page, r"stays within ([\d.]+) rad of its set point")
    arrive = _page_number(page, r"From ([\d.]+) s after the set point to the next one")
    # The timer counts from the clock's 0, not from the node's start: every set point but
    # the first (which comes at once from a node started past the first period) falls on
    # the period's grid. The recorder stamps a message with its own clock when it takes
    # it in, which a loaded run was seen to put 28 ms late; a timer counted from the node's
    # start would be off the grid by wherever in the period the node started.
    period = _page_number(page, r"fires every ([\d.]+) s of the simulation's clock")
    assert "counted from the clock's 0 and not from the node's start" in _page_text(page)
    for topic in ("/middle_arm_controller/joint_trajectory", "/end_arm_controller/joint_trajectory"):
        times = [ts for ts, _ in record["topics"][topic]]
        assert len(times) >= 2, (topic, times)
        off = [ts for ts in times[1:] if abs(ts - period * round(ts / period)) > 0.2]
        assert not off, (topic, times)
    checked = 0
    for topic, joint in (("/middle_arm_controller/joint_trajectory", "middle_arm_joint"),
                         ("/end_arm_controller/joint_trajectory", "end_arm_joint")):
        sent = record["topics"][topic]
        t, q = _series(record, "states", joint)
        for (ts, target), following in zip(sent, [*sent[1:], [t[-1], None]]):
            window = (t >= ts + arrive) & (t < following[0])
            if window.sum() < 10:
                continue
            error = np.abs(q[window] - target[joint])
            assert error.max() < tolerance, (joint, ts, target, error.max())
            checked += 1
    assert checked >= 2, record["topics"]


def _block_reaches_target(record: dict) -> None:
    """Practice 4: the block travels 1.5 m in about 3 s and stops within 5 mm of it."""
    page = "_pages/practice-4/05-ros2.md"
    target = _page_number(page, r"block_target\.py ([\d.]+) ")
    seconds = _page_number(page, r"travels the [\d.]+ m in about (\d+) s")
    tolerance = _page_number(page, r"within (\d+) mm, as it did in ROS 1") / 1000
    start = record["start"]
    t, x = _series(record, "states", "block_joint")
    there = t[np.abs(x - target) < tolerance]
    assert len(there), x[-5:]
    assert abs(there[0] - start - seconds) < 0.5, there[0] - start
    settled = t > start + seconds + 0.5
    assert np.all(np.abs(x[settled] - target) < tolerance), x[settled][-5:]
    _, v = _series(record, "speeds", "block_joint")
    assert np.abs(v).max() < 1.0, "under the 1 m/s velocity limit"


def _car_steers_by_equation_4(record: dict) -> None:
    """Practice 5: once the steering trajectory's 1 s is over, the centre joint stands at
    0.3 rad, and 0.3 s later the knuckles at Equation 4's angles for it (within 0.5°)."""
    from course.practices import PRACTICES, design
    car = design(PRACTICES[4])
    l, w = car.mm(car.WHEELBASE), car.mm(car.TRACK)
    page = "_pages/practice-5/06-ros2.md"
    steering = _page_number(page, r"drive_once\.py [\d.]+ ([\d.]+) ")
    left, right = (math.degrees(a) for a in car.ackermann(steering, l, w))
    assert f"{left:.2f}° on the left and {right:.2f}° on the right" in _page_text(page)
    tolerance = math.radians(_page_number(page, r"right, within ([\d.]+)°"))
    turn = _page_number(page, r"in the (\d+) s its trajectory")
    settle = _page_number(page, r"From ([\d.]+) s after the turn on")
    # `start` is when the knuckles begin to move; a joint state comes every 20 ms.
    start = record["start"] + 0.05
    t, phi = _series(record, "states", "steering_joint")
    settled = t > start + turn
    assert settled.sum() > 10
    assert np.all(np.abs(phi[settled] - steering) < tolerance), phi[settled][-5:]
    for joint, index in (("left_knuckle_joint", 0), ("right_knuckle_joint", 1)):
        tk, angle = _series(record, "states", joint)
        expected = np.array([car.ackermann(p, l, w)[index] for p in np.interp(tk, t, phi)])
        late = tk > start + turn + settle
        assert np.all(np.abs(angle[late] - expected[late]) < tolerance), joint


# page -> (simulated seconds per wall second, seconds to record after the first message
# on the trigger, trigger, topics the recorder subscribes to, the claim)
#
# Practices 1 and 2 time a pulse on the node's side, so the node's delays lengthen or
# shorten it. A reader's idle machine delays it by about a tick (10 ms); a test machine
# running other tests beside it was seen to add 22 ms of wall time. At half speed, those
# delays cost half as much simulated time, and the page's 2 % holds.
CLAIMS = {
    "_pages/practice-1/06-ros2.md": (0.5, 2.5, "motion:rear_left_joint", {}, _wheel_pulses),
    "_pages/practice-2/05-ros2.md": (0.5, 2.0, "motion:rear_left_joint", {},
                                     _friction_and_pulses),
    "_pages/practice-3/06-ros2.md": (3.0, 10.5, "/middle_arm_controller/joint_trajectory",
                                     {"/middle_arm_controller/joint_trajectory": "trajectory",
                                      "/end_arm_controller/joint_trajectory": "trajectory"},
                                     _arm_follows_setpoints),
    "_pages/practice-4/05-ros2.md": (5.0, 5.0, "motion:block_joint", {}, _block_reaches_target),
    # the knuckles: they move once both the steering and the Ackermann node's commands
    # arrive, whichever comes last (discovery between new nodes can take seconds)
    "_pages/practice-5/06-ros2.md": (2.0, 2.5, "motion:left_knuckle_joint", {},
                                     _car_steers_by_equation_4),
}


def test_every_ros2_page_has_its_claim():
    assert sorted(CLAIMS) == sorted(p.relative_to(ROOT).as_posix() for p in PAGES)


def _wait_for_line(process: subprocess.Popen, line: str, timeout: float = 30.0) -> None:
    """Wait until a process prints `line` on its standard error."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if select.select([process.stderr], [], [], 0.1)[0]:
            text = process.stderr.readline()
            if text.strip() == line:
                return
            if not text:
                break
    raise Ros2BlockError("the recorder", f"no joint states within {timeout:g} s")


# A page followed in the clone and home folder that an earlier page left, as its reader does:
# Practice 2's ROS 2 page ports example_1 again, where Practice 1's page saved its node.
FOLLOWS = {"_pages/practice-2/05-ros2.md": "_pages/practice-1/06-ros2.md"}
CLONES: dict[str, tuple[Path, Path]] = {}   # page -> (clone, home) its run left


def _clone_after(earlier: str, folder: Path) -> tuple[Path, Path]:
    """The clone and home folder after `earlier`'s page was followed: its run in this test
    session if it passed, else that page's blocks followed here first."""
    if earlier in CLONES:
        return CLONES[earlier]
    domain = ros2_domains.claim()
    try:
        with Session(parse_page(ROOT / earlier, ROOT), ROOT, folder, domain.id,
                     realtime=CLAIMS[earlier][0]) as session:
            session.run()
            session.check()
        return session.clone, session.home
    finally:
        domain.release()


def _says_what_the_port_kept(page, session: Session) -> None:
    """Porting example_1 again where the earlier page saved its node keeps the node, and
    prints the line the page quotes."""
    quoted = re.search(r"its output says `([^`]+)`", _page_text(page.path))
    assert quoted, f"{page.path} no longer quotes what the port prints when it keeps files"
    ported = [text for text in session.printed if "examples/example_1" in text]
    assert ported and quoted[1] in session.printed[ported[0]], session.printed
    assert session.node_path("example_1", "scripts/wheel_pulse.py").is_file()


def _outside_git(session: Session) -> list[str]:
    """What the page made inside the reader's clone that git would show as new: every such
    path must be one the repository's .gitignore covers."""
    created = session.created_in_clone()
    if not created:
        return []
    done = subprocess.run(["git", "-C", str(ROOT), "check-ignore", "--no-index", "--stdin"],
                          input="\n".join(created), capture_output=True, text=True, timeout=30)
    ignored = set(done.stdout.splitlines())
    return [path for path in created if path not in ignored]


def _ctrl_c_stops(page, session: Session) -> None:
    """The page's own node that runs until Ctrl-C, started again and stopped with Ctrl-C
    while the simulation runs: it ends with status 0 and no traceback, also when the Ctrl-C
    comes while rclpy takes a message in. A one-shot node of the page, stopped while it
    waits for its controller, ends without a traceback too."""
    for package, file in ctrl_c.NODES:
        if not any(b.ros2 == package and b.data_file == file for b in page.blocks):
            continue
        command = [str(PYTHON), str(session.node_path(package, file)), "--ros-args", "-p",
                   "use_sim_time:=true"]
        for in_take in CTRL_C_IN_TAKE:
            fault = ctrl_c.stop_once(command, session.env, session.home, in_take=in_take)
            if fault:
                raise Ros2BlockError(page.path, f"{package}/{file} on Ctrl-C: {fault}")
    for package, file, args in ctrl_c.ONE_SHOTS:
        if not any(b.ros2 == package and b.data_file == file for b in page.blocks):
            continue
        nobody = ros2_domains.claim()   # no controller answers there: the node waits
        try:
            fault = ctrl_c.stop_once([str(PYTHON), str(session.node_path(package, file)), *args],
                                     {**session.env, "ROS_DOMAIN_ID": str(nobody.id)},
                                     session.home, statuses=(0, 1))
        finally:
            nobody.release()
        if fault:
            raise Ros2BlockError(page.path, f"{package}/{file} on Ctrl-C while it waits: {fault}")


@pytest.mark.parametrize("path", PAGES, ids=lambda p: p.relative_to(ROOT).as_posix())
def test_page_ros2_blocks(path, tmp_path, record_property, request):
    if reason := missing():
        pytest.skip(reason)
    page = parse_page(path, ROOT)
    assert not page.errors, "\n".join(map(str, page.errors))
    realtime, seconds, trigger, topics, claim = CLAIMS[page.path]
    fault, recorder = None, None
    domain = ros2_domains.claim()   # no other test's traffic in it
    request.addfinalizer(domain.release)
    clone = home = None
    if page.path in FOLLOWS:
        clone, home = _clone_after(FOLLOWS[page.path], tmp_path / "earlier")
    with Session(page, ROOT, tmp_path / "session", domain.id, realtime=realtime, clone=clone,
                 home=home) as session:
        try:
            session.prepare()
            named = {topic_line(c)[1] for c in jazzy_commands(page)} - {None}
            recorder = subprocess.Popen(
                [str(PYTHON), str(RECORD), f"{seconds:g}", trigger,
                 *(f"{t}={k}" for t, k in topics.items()),
                 *(f"expect:{t}" for t in sorted(named))],
                env=session.env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                start_new_session=True)
            # The recorder listens before any node starts, as a reader's plot would.
            session.simulation_up = lambda: _wait_for_line(recorder, "recording")
            session.run()
            out, err = recorder.communicate(timeout=90)
            assert recorder.returncode == 0, f"the recorder saw too little:\n{err[-2000:]}" \
                                             f"\n{out[-1000:]}"
            record = json.loads(out.splitlines()[-1])
            session.check()
            claim(record)
            # What the page's lines for Jazzy name is what this run had.
            lines = jazzy_commands(page)
            tables = field_tables(topic_types(lines, record["graph"]) | action_types(lines))
            problems = [p for c in lines for check in (topic_problems, action_problems)
                        for p in check(c, record["graph"], tables)]
            assert not problems, "\n".join(problems)
            _ctrl_c_stops(page, session)
            if page.path in FOLLOWS:
                _says_what_the_port_kept(page, session)
            new = _outside_git(session)
            assert not new, f"following the page left files in the clone that git shows: {new}"
        except Ros2BlockError as error:
            fault = str(error)
        finally:
            if recorder and recorder.poll() is None:
                recorder.kill()
                recorder.communicate()
        record_property("ros2_blocks_ran", len(session.ran))
    assert not session.leftovers(), f"processes left running: {session.leftovers()}"
    if not fault:
        try:
            session.stopped_cleanly()
        except Ros2BlockError as error:
            fault = str(error)
    if fault:
        pytest.fail(fault, pytrace=False)
    CLONES[page.path] = (session.clone, session.home)
