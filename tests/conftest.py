"""Shared pytest configuration."""

import pytest

import sw2sim  # noqa: F401  (chooses the GL platform before any test module imports mujoco)

# Folders whose test modules share session fixtures that are costly to make: the browser
# tests load and audit every page of the site once, for all their modules. Under
# `--dist loadscope` (make test) each such folder goes to one pytest-xdist worker whole,
# instead of each worker making the fixtures again for the modules it was given.
SHARED_SESSION_FOLDERS = ("tests/site/browser/",)


# Modules whose tests are long and share nothing: each test is a unit of its own, so that
# the workers split them (every ROS page runs its own master and simulation).
SPLIT_MODULES = ("tests/ros/test_page_blocks.py",)


def scope_of(nodeid: str) -> str:
    """The unit of work a test belongs to: its folder if listed above, the test itself in
    a split module, else its module."""
    for folder in SHARED_SESSION_FOLDERS:
        if nodeid.startswith(folder):
            return folder
    module = nodeid.split("::", 1)[0]
    return nodeid if module in SPLIT_MODULES else module


@pytest.hookimpl(optionalhook=True)
def pytest_xdist_make_scheduler(config, log):
    if config.getoption("dist") != "loadscope":
        return None
    from xdist.scheduler import LoadScopeScheduling

    class SharedFolderScheduling(LoadScopeScheduling):
        def _split_scope(self, nodeid: str) -> str:
            return scope_of(nodeid)

    return SharedFolderScheduling(config, log)


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
