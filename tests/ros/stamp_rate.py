"""The rate at which a ROS publisher sends, read from the stamps of what a subscriber heard.

A subscriber on a busy machine misses messages (the publisher's queue drops them), which
leaves a double gap between two stamps: counting messages would read that as a lower rate.
One over the usual (median) gap is the publisher's own rate; a publisher at another rate
still shows as one.
"""

from __future__ import annotations

import numpy as np


def sent_per_second(stamps) -> float:
    """Messages per second of the stamps' clock (simulated time, for a simulation's topic);
    at least 11 distinct stamps are needed."""
    gaps = np.diff(np.unique(np.round(stamps, 6)))
    assert len(gaps) >= 10, f"too few messages: {len(gaps) + 1}"
    return 1.0 / float(np.median(gaps))
