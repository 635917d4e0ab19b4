"""/clock as _pages/reference/08-ros-without-gazebo.md states it: every 10 ms of simulated
time, never more than 100 times a second of wall time, so in steps of 0.1 s at ten times
real time."""

from __future__ import annotations

import pytest

from sw2sim.ros.run import missing

pytestmark = pytest.mark.skipif(bool(missing()), reason=str(missing()))


class Recorder:
    def __init__(self):
        self.sent = []

    def publish(self, message):
        self.sent.append(message.clock.to_sec())


def ticks(monkeypatch, realtime: float, seconds: float = 2.0) -> list[float]:
    """The clock messages of `seconds` of simulation in 1 ms steps, the wall clock running
    at 1/realtime of simulated time."""
    import rospy

    from sw2sim.ros import world as world_module
    now = {"wall": 0.0}
    monkeypatch.setattr(world_module.time, "monotonic", lambda: now["wall"])
    world = world_module.World(rospy)
    world.clock = Recorder()
    for step in range(int(seconds * 1000) + 1):
        t = step / 1000
        now["wall"] = t / realtime
        world._publish(t)
    return world.clock.sent


def test_the_clock_ticks_every_10_ms_at_real_time(monkeypatch):
    from sw2sim.ros.world import CLOCK_HZ
    assert CLOCK_HZ == 100                 # the page's 10 ms and 100 a second
    sent = ticks(monkeypatch, realtime=1.0)
    gaps = [b - a for a, b in zip(sent, sent[1:])]
    assert len(sent) == 201 and max(gaps) == pytest.approx(0.01) == min(gaps)


def test_at_ten_times_real_time_the_clock_moves_in_steps_of_a_tenth(monkeypatch):
    sent = ticks(monkeypatch, realtime=10.0)
    gaps = [b - a for a, b in zip(sent, sent[1:])]
    # after the first tick, on a schedule of 100 a wall second
    # (within a simulation step: a tick waits for the first step past its time)
    assert len(sent) >= 20
    assert max(gaps[1:]) == pytest.approx(0.1, abs=0.0011) == min(gaps[1:])
