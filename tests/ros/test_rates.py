"""Publishing rates on simulated time (sw2sim.ros.schedule): N messages in every simulated
second, as joint_state_controller and gazebo_plugins' joint state publisher count from
their last due time, not from when the last message went out. A publisher that did the
latter lost a 2 ms step whenever MuJoCo's summed time fell a hair short: 46 to 48 messages
a second for Practice 1's 50, 19.4 for Practice 3's 20.

The stand-in is stepped here without ROS (offline.py); test_reset.py counts the same over
ROS, on what a subscriber receives."""

from __future__ import annotations

import numpy as np
import pytest

from offline import run, stamps, start
from sw2sim.ros.run import missing

pytestmark = pytest.mark.skipif(bool(missing()), reason=str(missing()))


def test_a_schedule_keeps_to_its_grid_on_summed_steps():
    from sw2sim.ros.schedule import Schedule
    schedule, now, sent = Schedule(1 / 50), 0.0, []
    for _ in range(5000):                    # 10 s of 2 ms steps, summed as MuJoCo sums them
        now += 0.002
        if schedule.due(now):
            sent.append(now)
            schedule.advance()
    sent = np.array(sent)
    # whole seconds, counted from half a step past a tick (a tick's summed time may fall
    # either side of the second's exact end)
    assert np.count_nonzero((sent >= 1.001) & (sent < 9.001)) == 8 * 50
    assert np.allclose(np.diff(sent[1:]), 0.02, atol=1e-9)


def test_a_held_back_schedule_drops_its_missed_ticks():
    from sw2sim.ros.schedule import Schedule
    schedule = Schedule(0.01)
    schedule.advance(now=0.237)              # the clock's, after the wall clock held it
    assert schedule.next_time == pytest.approx(0.24)
    schedule.restart(0.0, at_once=False)
    assert schedule.next_time == pytest.approx(0.01)


@pytest.mark.parametrize("example, controllers, topic, rate", [
    ("example_1", [], "/joint_states", 50),   # gazebo_plugins' <updateRate>50
    ("example_3", ["joint_state_controller"], "/example_3/joint_states", 20),  # publish_rate
    ("example_4", ["joint_state_controller"], "/example_4/joint_states", 20),
])
def test_joint_states_come_at_their_rate_in_every_simulated_second(example, controllers, topic,
                                                                   rate, monkeypatch):
    world, node = start(example, controllers, monkeypatch)
    run(world, 6.0)
    times = np.array(stamps(node.topics[topic]))
    for second in range(1, 5):   # from half a step past a tick, as above
        window = (times >= second + 0.001) & (times < second + 1.001)
        assert np.count_nonzero(window) == rate, (second, times[window])
    assert np.allclose(np.diff(times[times >= 1]), 1 / rate, atol=1e-9)


def test_the_clock_ticks_100_times_a_simulated_second(monkeypatch):
    world, node = start("example_1", [], monkeypatch)
    run(world, 3.0)
    clock = np.array([m.clock.to_sec() for m in node.topics["/clock"].sent])
    assert np.count_nonzero((clock >= 1.001) & (clock < 2.001)) == 100
    assert np.allclose(np.diff(clock[1:]), 0.01, atol=1e-9)   # after the first step's tick
