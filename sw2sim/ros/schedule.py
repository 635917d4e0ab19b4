"""When the simulation node publishes: ticks on simulated time at an exact rate.

A publisher that, after each message, sets its next one `period` after the current time
loses a step whenever the float sum of MuJoCo's steps falls a hair short of that time:
at 50 Hz on 2 ms steps its gaps alternate between 20 and 22 ms, 47 messages a simulated
second instead of 50. The ROS publishers the node stands in for count from their last
due time instead: joint_state_controller.cpp (update) adds `1 / publish_rate` to
`last_publish_time_`, gazebo_ros_joint_state_publisher.cpp (OnUpdate) adds its
`update_period_` to `last_update_time_`. A Schedule does the same: its ticks lie on the
grid `anchor + k * period`, each due at the first step that reaches it, so that a rate of
N gives N messages in every simulated second (one more or less where the second's ends
fall between two ticks).
"""

from __future__ import annotations

import dataclasses
import math

SLACK = 1e-6   # s: MuJoCo's time is a sum of steps, a little off the grid's exact times


@dataclasses.dataclass
class Schedule:
    """Ticks at `anchor + count * period` of simulated time."""

    period: float
    anchor: float = 0.0
    count: int = 0

    @property
    def next_time(self) -> float:
        return self.anchor + self.count * self.period

    def due(self, now: float) -> bool:
        return now >= self.next_time - SLACK

    def advance(self, now: float | None = None) -> None:
        """On to the next tick. Given `now`, on to the first tick after it instead: ticks
        that were held back (the clock's, by the wall clock) are dropped, not sent in a
        burst."""
        self.count += 1
        if now is not None and self.due(now):
            self.count = math.floor((now + SLACK - self.anchor) / self.period) + 1

    def restart(self, now: float, at_once: bool = True) -> None:
        """A grid anchored at `now`, as after simulated time was set back: the first tick
        at `now` itself, or one period later."""
        self.anchor, self.count = now, 0 if at_once else 1
