"""Practices 4 and 5 under `sw2sim ros`: each package's own gazebo.launch, the commands
the pages type (`rostopic pub -1`, Debian's rostopic), and the result observed from a
separate rospy node (after_command.py) from the moment the commands arrive. Then the
limits gazebo_ros_control puts on an effort joint, checked against its source."""

from __future__ import annotations

import json
import math
import shlex
import sys
import time
import xmlrpc.client
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np
import pytest

from packages import EXAMPLES

PROBE = Path(__file__).with_name("after_command.py")
READY_TIMEOUT = 30.0     # s (wall) for the launch file's nodes to subscribe
RUN_TIMEOUT = 30.0       # s (wall) for a probe or a typed command

# Practice 4: _pages/practice-4/04-testing-and-scripting.md sends the block to 1.5 m.
BLOCK_TARGET = 1.5       # m
BLOCK_TOLERANCE = 0.005  # m: "stops there, within 5 mm"
BLOCK_SETTLE = 3.0       # s of simulated time: 1.5 m at the 1 m/s limit, and stopping
SPEED_MARGIN = 1.02      # the soft limits hold the speed at the limit, not under it

# Practice 5: _pages/practice-5/04-control-script.md's two commands.
STEERING = 0.3           # rad, on /example_5/steering_controller/command
SPEED = 0.5              # m/s, on /example_5/cmd_speed
KNUCKLE_TOLERANCE = math.radians(0.5)
WHEEL_TOLERANCE = 0.01   # of each wheel's path speed
CAR_SETTLE = 2.0         # s of simulated time
STEADY = 0.5             # s at the end of the window that count as steady


def launch(ros, example: str) -> None:
    ros.start(sys.executable, "-m", "sw2sim", "ros", str(EXAMPLES / example),
              "--realtime", "0", name="sw2sim_ros")


def wait_for_subscribers(ros, topics: dict[str, int]) -> None:
    """Until each topic has at least its number of subscribers (the master's view)."""
    master = xmlrpc.client.ServerProxy(ros.uri)
    deadline = time.monotonic() + READY_TIMEOUT
    while time.monotonic() < deadline:
        _, _, (_, subscribed, _) = master.getSystemState("/test")
        counts = {topic: len(nodes) for topic, nodes in subscribed}
        if all(counts.get(t, 0) >= n for t, n in topics.items()):
            return
        time.sleep(0.05)
    log = ros.logs / "sw2sim_ros.log"
    raise AssertionError(f"not subscribed in {READY_TIMEOUT:.0f} s: {topics}\n"
                         + (log.read_text(errors="replace")[-3000:] if log.exists() else ""))


def type_and_record(ros, seconds: float, states: str, typed: dict[str, str]) -> dict:
    """Start the probe on `states` and the topics of `typed` (topic -> the command line a
    reader types for it); once it and the launch file's nodes listen, run every command
    line at once, as from terminals of their own; return the probe's record."""
    with ThreadPoolExecutor(1 + len(typed)) as pool:
        probe = pool.submit(ros.python, PROBE, str(seconds), states, *typed, timeout=RUN_TIMEOUT)
        wait_for_subscribers(ros, {topic: 2 for topic in typed})
        runs = [pool.submit(ros.run, *shlex.split(line), timeout=RUN_TIMEOUT)
                for line in typed.values()]
        for line, run in zip(typed.values(), runs):
            done = run.result()
            assert done.returncode == 0, (line, done.stdout, done.stderr)
        done = probe.result()
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-2000:]
    return json.loads(done.stdout.splitlines()[-1])


def series(record: dict, field: str, joint: str) -> tuple[np.ndarray, np.ndarray]:
    """Time since the commands arrived, and one joint's position or velocity."""
    rows = record[field]
    return (np.array([t for t, _ in rows]) - record["start"],
            np.array([values[joint] for _, values in rows]))


def test_practice_4s_block_stops_where_rostopic_sends_it(ros):
    """`rostopic pub -1 /example_4/block_controller/command std_msgs/Float64 "data: 1.5"`:
    the block travels the 1.5 m and stops there within 5 mm, never faster than the URDF's
    1 m/s velocity limit."""
    from sw2sim.ros_control import read_joint_limits
    limit = read_joint_limits(EXAMPLES / "example_4")["block_joint"].velocity
    launch(ros, "example_4")
    topic = "/example_4/block_controller/command"
    record = type_and_record(ros, BLOCK_SETTLE, "/example_4/joint_states", {
        topic: f'rostopic pub -1 {topic} std_msgs/Float64 "data: {BLOCK_TARGET}"'})
    assert record["commands"][topic] == BLOCK_TARGET
    t, position = series(record, "states", "block_joint")
    _, speed = series(record, "speeds", "block_joint")
    assert len(t) > 20, "joint states arrive at the joint state controller's 20 Hz"
    assert abs(position[-1] - BLOCK_TARGET) < BLOCK_TOLERANCE, position[-5:]
    assert np.max(np.abs(speed)) < limit * SPEED_MARGIN, np.max(np.abs(speed))
    assert np.max(np.abs(speed)) > limit / SPEED_MARGIN, "a long move runs at the limit"


def test_practice_5s_car_steers_by_equation_4_and_drives_each_wheel_at_its_speed(ros):
    """The page's two commands, with -1 so that they return: the centre joint stands at
    0.3 rad, the knuckles at Equation 4's angles for it (within 0.5°), and every wheel
    turns at the speed its own circle needs: omega * r = v * d / R (within 1 %)."""
    from course.practices import PRACTICES, design
    car = design(PRACTICES[4])
    l, w, r = car.mm(car.WHEELBASE), car.mm(car.TRACK), car.mm(car.WHEEL_RADIUS)
    launch(ros, "example_5")
    steering, speed = "/example_5/steering_controller/command", "/example_5/cmd_speed"
    record = type_and_record(ros, CAR_SETTLE, "/example_5/joint_states", {
        steering: f'rostopic pub -1 {steering} std_msgs/Float64 "data: {STEERING}"',
        speed: f'rostopic pub -1 {speed} std_msgs/Float64 "data: {SPEED}"'})
    t, phi = series(record, "states", "steering_joint")
    steady = t > t[-1] - STEADY
    assert steady.sum() >= 10, "joint states arrive at the joint state controller's 50 Hz"
    phi = float(np.mean(phi[steady]))
    assert abs(phi - STEERING) < KNUCKLE_TOLERANCE, phi
    inner, outer = car.ackermann(phi, l, w)
    for joint, expected in (("left_knuckle_joint", inner), ("right_knuckle_joint", outer)):
        _, angle = series(record, "states", joint)
        assert np.all(np.abs(angle[steady] - expected) < KNUCKLE_TOLERANCE), (
            joint, math.degrees(expected), np.degrees(angle[steady]))
    radius = l / math.tan(phi)
    for wheel, (along, left) in wheel_offsets(l, w).items():
        path = SPEED * math.hypot(along, radius - left) / radius
        _, omega = series(record, "speeds", f"{wheel}_wheel_joint")
        assert np.all(np.abs(omega[steady] * r - path) < WHEEL_TOLERANCE * path), (
            wheel, path, omega[steady] * r)


def wheel_offsets(l: float, w: float) -> dict[str, tuple[float, float]]:
    """Each wheel's (forward, left) offset from the rear axle's centre."""
    return {"front_left": (l, w / 2), "front_right": (l, -w / 2),
            "rear_left": (0.0, w / 2), "rear_right": (0.0, -w / 2)}


# (example, joint, q, v, the controller's effort) -> the effort gazebo_ros_control applies:
# joint_limits_interface.h's two handles, worked by hand from the URDFs' numbers.
HANDLED = [
    # example_4's block: <safety_controller> k_position 20, k_velocity 400; 1 m/s, 200 N
    ("example_4", "block_joint", 1.0, 0.0, 3000.0, 200.0),        # effort limit
    ("example_4", "block_joint", 1.0, 0.9, 3000.0, 40.0),         # 400 * (1 - 0.9)
    ("example_4", "block_joint", 1.0, 1.2, 3000.0, -80.0),        # over the limit: brakes
    ("example_4", "block_joint", 1.0, 1.2, -3000.0, -200.0),
    ("example_4", "block_joint", 2.68, 0.0, 3000.0, 80.0),        # 400 * 20 * 0.01
    ("example_4", "block_joint", 1.0, 0.5, 50.0, 50.0),           # inside: as asked
    # example_5's steering joint: k_position 20, k_velocity 1; 3 rad/s, 5 N·m
    ("example_5", "steering_joint", 0.0, 0.0, 4.0, 3.0),          # 1 * (3 - 0)
    ("example_5", "steering_joint", 0.6, 0.0, 0.0, -1.528),       # past the soft limit
    # example_5's wheels: no <safety_controller>, continuous; 30 rad/s, 10 N·m
    ("example_5", "rear_left_wheel_joint", 0.0, 0.0, 25.0, 10.0),
    ("example_5", "rear_left_wheel_joint", 0.0, 31.0, 5.0, 0.0),  # past the velocity limit
    ("example_5", "rear_left_wheel_joint", 0.0, 31.0, -5.0, -5.0),
]


@pytest.mark.parametrize("example, joint, q, v, asked, applied", HANDLED)
def test_the_effort_is_limited_as_gazebo_ros_control_limits_it(example, joint, q, v, asked,
                                                               applied):
    from sw2sim.package import find_package
    from sw2sim.ros import hardware
    handle = hardware.handles(find_package(EXAMPLES / example))[joint]
    law = hardware.effort((asked, 0.0, 0.0), handle, q, v)
    assert hardware.value(law, q, v) == pytest.approx(applied, abs=1e-9)
