"""Shared pytest configuration: how `make test` shares the tests among its workers
(tests/scheduling.py), and the summary of the page blocks it ran."""

import pytest

import sw2sim  # noqa: F401  (chooses the GL platform before any test module imports mujoco)
from scheduling import scheduling


@pytest.hookimpl(optionalhook=True)
def pytest_xdist_make_scheduler(config, log):
    if config.getoption("dist") != "loadscope":
        return None
    return scheduling(config, log)


def pytest_terminal_summary(terminalreporter, exitstatus, config):
    """How many page snippet blocks ran, and which were skipped and why (tests/course/test_pages.py);
    how many ROS commands of the pages ran, and which open a window (tests/ros/test_page_blocks.py)."""
    ran, skipped, pages = 0, [], 0
    ros_ran, windows, ros_pages = 0, [], 0
    for reports in terminalreporter.stats.values():
        for report in reports:
            if getattr(report, "when", None) != "call":
                continue
            properties = dict(getattr(report, "user_properties", ()))
            if "snippets_ran" in properties:
                pages += 1
            ran += properties.get("snippets_ran", 0)
            skipped += properties.get("snippets_skipped", [])
            if "ros_blocks_ran" in properties:
                ros_pages += 1
            ros_ran += properties.get("ros_blocks_ran", 0)
            windows += properties.get("ros_windows", [])
    if not pages and not skipped and not ros_pages:
        return
    terminalreporter.section("page snippets")
    terminalreporter.write_line(f"snippet blocks run: {ran} (in {pages} pages)")
    terminalreporter.write_line(f"skipped snippet blocks: {len(skipped)}")
    for line in skipped:
        terminalreporter.write_line(f"  {line}")
    if ros_pages:
        terminalreporter.write_line(f"ROS commands run under the stand-in: {ros_ran} "
                                    f"(in {ros_pages} pages)")
        terminalreporter.write_line(f"ROS commands not run, they open a window: {len(windows)}")
        for line in windows:
            terminalreporter.write_line(f"  {line}")
