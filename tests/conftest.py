"""Shared pytest configuration."""

import sw2sim  # noqa: F401  (chooses the GL platform before any test module imports mujoco)


def pytest_terminal_summary(terminalreporter, exitstatus, config):
    """How many page snippet blocks ran, and which were skipped and why (tests/course/test_pages.py)."""
    ran, skipped, pages = 0, [], 0
    for reports in terminalreporter.stats.values():
        for report in reports:
            if getattr(report, "when", None) != "call":
                continue
            properties = dict(getattr(report, "user_properties", ()))
            if "snippets_ran" in properties:
                pages += 1
            ran += properties.get("snippets_ran", 0)
            skipped += properties.get("snippets_skipped", [])
    if not pages and not skipped:
        return
    terminalreporter.section("page snippets")
    terminalreporter.write_line(f"snippet blocks run: {ran} (in {pages} pages)")
    terminalreporter.write_line(f"skipped snippet blocks: {len(skipped)}")
    for line in skipped:
        terminalreporter.write_line(f"  {line}")
