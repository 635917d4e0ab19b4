"""RViz as the exported display.launch opens it, on a virtual screen (Xvfb): the package's
urdf.rviz shows the robot, every link where robot_state_publisher puts it.

The launch file runs unchanged; Debian's joint_state_publisher stands in for
joint_state_publisher_gui, which stops at start on Debian 12 (course/rviz_picture.py).
"""

from __future__ import annotations

import numpy as np
import pytest
from lxml import etree

from course import rviz_picture
from packages import EXAMPLES

PACKAGE = EXAMPLES / "example_1"
MISSING = rviz_picture.missing()


def link_colours(urdf) -> list[np.ndarray]:
    """The distinct colours of the URDF's visuals, as RGB fractions."""
    found = {tuple(float(v) for v in c.get("rgba").split()[:3])
             for c in etree.parse(str(urdf)).iter("color")}
    return [np.array(c) for c in sorted(found)]


def share_of(view: np.ndarray, rgb: np.ndarray) -> float:
    """The share of the view's pixels of the colour `rgb` as RViz lights it: brighter or
    darker, the same proportions of red, green and blue."""
    pixels = view.astype(float) + 1e-6
    shade = pixels / pixels.sum(axis=2, keepdims=True)
    return float((np.abs(shade - rgb / rgb.sum()).max(axis=2) < 0.04).mean())


def test_display_launch_shows_every_link_of_the_robot(ros, tmp_path):
    if MISSING:
        pytest.skip(f"RViz: {MISSING}")
    with rviz_picture.xvfb() as screen:
        prefix = rviz_picture.joint_state_publisher_gui(tmp_path / "stand-in")
        ros.env = rviz_picture.environment(ros.env, PACKAGE, screen.display, prefix,
                                           tmp_path / "home")
        launch = ros.start("roslaunch", "--wait", PACKAGE.name, "display.launch", name="roslaunch")
        try:
            # Waits for the robot with no link in RViz's white error material (a link
            # without a transform), the picture settled; as long as the figures may wait,
            # since software rendering is slow on a machine busy with the other tests.
            view = rviz_picture.wait_for_robot(screen.display, lambda: launch.poll() is None)
        finally:
            ros.stop_all()   # RViz first, then its screen
    assert screen.process.poll() is not None, "Xvfb still runs"
    log = (ros.logs / "roslaunch.log").read_text(errors="replace")
    assert "process has died" not in log, log
    assert rviz_picture.robot_pixels(view).mean() > 0.05
    assert not rviz_picture.unplaced_pixels(view).any()
    # Each link's colour from the URDF is on the screen: the base and the four wheels are
    # drawn with their own materials where their transforms put them.
    for rgb in link_colours(PACKAGE / "urdf" / f"{PACKAGE.name}.urdf"):
        assert share_of(view, rgb) > 0.01, f"no pixels of the colour {rgb}"
