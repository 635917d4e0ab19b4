"""Every rqt_plot line of the pages has `sw2sim plot` beside it, which runs here: the next
ROS block of the page, typed into the same terminal in the same folder, with the same
names (Debian ships no rqt; tests/ros/test_page_blocks.py runs these lines)."""

from __future__ import annotations

import shlex

from course.snippets import find_pages, parse_page
from course.snippets.terminal import commands
from repository import ROOT


def _lines():
    """(page, rqt_plot block, the ROS block after it) for each rqt_plot line."""
    for path in find_pages(ROOT):
        page = parse_page(path, ROOT)
        blocks = [b for b in page.ros_blocks if b.language == "bash"]
        for n, block in enumerate(blocks):
            if any(c.words[:1] == ["rqt_plot"] for c in commands(block)):
                yield page, block, blocks[n + 1] if n + 1 < len(blocks) else None


def test_each_rqt_plot_line_has_a_sw2sim_plot_line_beside_it():
    found = list(_lines())
    assert len(found) >= 4, "the pages' rqt_plot lines were not found"
    for page, block, after in found:
        (plot,) = [c for c in commands(block) if c.words[:1] == ["rqt_plot"]]
        assert after is not None, f"{block.location}: no block after rqt_plot"
        ours = [c for c in commands(after) if c.plots]
        assert ours, f"{block.location}: the block after rqt_plot gives no `sw2sim plot` line"
        assert ours[0].words[2:] == plot.words[1:], (block.location, ours[0].text)
        assert (after.ros, after.terminal) == (block.ros, block.terminal), block.location
        # what the reader types is what rqt_plot takes: no shell quoting needed
        assert shlex.split(ours[0].text) == ours[0].text.split()
