"""The samples of a plot, on ROS time, shared between the subscribers' threads and the
loop that draws them, and the CSV they make.

Each sample's time is the message's header stamp where the message has a header and the
stamp is set, as rqt_plot takes it (rosplot.py's `_ros_cb`,
https://github.com/ros-visualization/rqt_plot/blob/0.4.14/src/rqt_plot/rosplot.py#L116-L134),
else the ROS time at which it arrived: simulated time while a simulation publishes /clock.
The plot's time axis counts from the first sample of any series. (rqt_plot counts from
when it started; Jazzy's takes the wall clock for messages without a header, and
subtracts the wall clock's start from header stamps, which puts simulated stamps about
1.7e9 s before zero:
https://github.com/ros-visualization/rqt_plot/blob/1.4.0/src/rqt_plot/rosplot.py#L160-L166,
https://github.com/ros-visualization/rqt_plot/blob/1.4.0/src/rqt_plot/plot_widget.py#L208;
1.4.0 is Jazzy's first release, and the changelog of its later ones names no change to
either. Here both generations use ROS time.)
"""

from __future__ import annotations

import csv
import threading
from pathlib import Path
from time import monotonic

from .fields import PlotError, Series


class Recording:
    """Samples per series: (ROS time in s, value)."""

    def __init__(self, series: list[Series]):
        self.series = list(series)
        self.samples: dict[str, list[tuple[float, float]]] = {s.name: [] for s in self.series}
        self.first: float | None = None     # ROS time of the first sample
        self.error: PlotError | None = None
        self.lock = threading.Lock()
        self.arrived = 0.0                  # time.monotonic() of the newest sample

    def add(self, name: str, time: float, value: float) -> None:
        with self.lock:
            if self.first is None:
                self.first = time
            self.samples[name].append((time, value))
            self.arrived = monotonic()

    def fail(self, error: PlotError) -> None:
        with self.lock:
            if self.error is None:
                self.error = error

    def count(self) -> int:
        with self.lock:
            return sum(len(v) for v in self.samples.values())

    def cut(self, seconds: float) -> None:
        """Keep the samples of the first `seconds` (those that came while the plot was
        being stopped are dropped)."""
        with self.lock:
            if self.first is not None:
                end = self.first + seconds + 1e-9
                for rows in self.samples.values():
                    rows[:] = [row for row in rows if row[0] <= end]

    def since_start(self) -> dict[str, tuple[list[float], list[float]]]:
        """Each series' times (s since the first sample) and values."""
        with self.lock:
            first = self.first or 0.0
            return {name: ([t - first for t, _ in rows], [v for _, v in rows])
                    for name, rows in self.samples.items()}

    def span(self) -> float:
        """Seconds from the first sample to the last."""
        with self.lock:
            last = max((rows[-1][0] for rows in self.samples.values() if rows), default=None)
            return 0.0 if last is None or self.first is None else last - self.first

    def write_csv(self, path: Path) -> None:
        """One row per sample: `series,ros_time,time,value` (time: s since the first
        sample, the plot's axis), in the order the samples came, series by series."""
        with self.lock:
            first = self.first or 0.0
            with open(path, "w", newline="", encoding="utf-8") as out:
                writer = csv.writer(out)
                writer.writerow(["series", "ros_time", "time", "value"])
                for name, rows in self.samples.items():
                    for t, v in rows:
                        writer.writerow([name, f"{t:.9f}", f"{t - first:.9f}", repr(v)])
