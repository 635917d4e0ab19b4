"""Slow, independent jobs of a test module, run a few at a time ahead of the tests that check them.

Each page and each figure is made in a process of its own anyway; on a machine with two or
more cores, starting them together for the whole module, then letting every test wait for
its own result, takes a fraction of the time of making them one after the other.
"""

import os


def workers() -> int:
    """How many jobs to run at once: this worker's share of the cores (pytest-xdist runs
    one test process per core already), at most four."""
    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count() or 1
    share = cores // int(os.environ.get("PYTEST_XDIST_WORKER_COUNT", "1"))
    return max(1, min(4, share))


def selected(request, test_name: str, param: str) -> list:
    """The values of `param` that this session will run `test_name` of the requesting module
    with, in the order it will run them (only those chosen by -k, node ids and so on)."""
    return [item.callspec.params[param] for item in request.session.items
            if getattr(item, "module", None) is request.module and item.originalname == test_name]
