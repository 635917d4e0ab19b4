"""Practice 5's turning-centre diagram shows Equation 4's angles for the design's l and w."""

import math
import re

import pytest

from course import ackermann_diagram
from course.practices import ROOT
from course.practices.practice_5 import design


def test_the_diagrams_angles_are_equation_4s(tmp_path):
    n = ackermann_diagram.draw(tmp_path / "turning_centre.png")
    l, w = design.mm(design.WHEELBASE), design.mm(design.TRACK)
    inner, outer = design.ackermann(math.radians(n["phi"]), l, w)
    assert (n["l"], n["w"]) == (l, w)
    assert n["inner"] == pytest.approx(math.degrees(inner), abs=1e-9)
    assert n["outer"] == pytest.approx(math.degrees(outer), abs=1e-9)
    assert n["R"] == pytest.approx(l / math.tan(math.radians(n["phi"])))
    # the right-angled triangles give the same angles
    assert math.radians(n["inner"]) == pytest.approx(math.atan(l / (n["R"] - w / 2)))
    assert math.radians(n["outer"]) == pytest.approx(math.atan(l / (n["R"] + w / 2)))


def test_the_page_states_the_diagrams_numbers():
    text = " ".join((ROOT / "_pages/practice-5/03-ackermann-geometry.md").read_text().split())
    n = ackermann_diagram.numbers()
    figure = text[text.index("(/media/practice-5/turning_centre.png)") - 600:]
    figure = figure[:figure.index(".*") + 2]
    assert f"at a {n['phi']:.0f}° centre angle" in figure
    assert f"{n['R']:.3f} m" in figure
    for key in ("inner", "outer"):
        assert len(re.findall(re.escape(f"{n[key]:.2f}°"), figure)) == 2, key
    assert f"l = {n['l'] * 1000:.0f} mm" in figure and f"w = {n['w'] * 1000:.0f} mm" in figure
