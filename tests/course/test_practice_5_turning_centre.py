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


# ---- the phone drawing against the desktop one ------------------------------------------

def _drawn(monkeypatch, tmp_path) -> dict[bool, dict]:
    """What each variant shows, as laid out when it is saved: phone? -> its texts with
    their boxes, its lines' points and its dimension arrows' ends (display pixels), the
    figure's size and its smallest text in image pixels."""
    import numpy as np
    from matplotlib.text import Annotation

    from course import phone, plotting
    seen = {}
    save = plotting.save

    def recording(fig, path, layout=plotting.DESKTOP, **files):
        on_phone = layout is plotting.PHONE
        fig.canvas.draw()
        renderer = fig.canvas.get_renderer()
        ax = fig.axes[0]
        texts = [(t.get_text(), t.get_window_extent(renderer)) for t in plotting._texts(fig)
                 if not isinstance(t, Annotation)]
        lines = [ax.transData.transform(line.get_xydata()) for line in ax.lines]
        arrows = [ax.transData.transform([a.xy, a.xyann]) for a in ax.texts if isinstance(a, Annotation)]
        save(fig, path, layout, **files)
        seen[on_phone] = dict(texts=texts, lines=lines, arrows=arrows, width=fig.bbox.width,
                              height=fig.bbox.height)
    monkeypatch.setattr(plotting, "save", recording)
    ackermann_diagram.draw(tmp_path / "turning_centre.png")
    from PIL import Image
    small = Image.open(phone.phone_path(tmp_path / "turning_centre.png"))
    seen[True]["smallest_px"] = float(small.info[plotting.TEXT_KEY]) * phone.SHOWN_PX / small.width
    seen[True]["np"] = np
    return seen


def _segments_through(box, points, np, step=1.0) -> bool:
    """Whether the polyline `points` passes inside `box` (shrunk by a pixel)."""
    for a, b in zip(points[:-1], points[1:]):
        count = max(2, int(np.hypot(*(b - a)) / step))
        for t in np.linspace(0.0, 1.0, count):
            x, y = a + t * (b - a)
            if box.x0 + 1 < x < box.x1 - 1 and box.y0 + 1 < y < box.y1 - 1:
                return True
    return False


def test_the_phone_drawing_shows_what_the_desktop_one_shows_clear_of_its_lines(monkeypatch, tmp_path):
    """Side by side: every label and dimension of the desktop drawing is on the phone's too;
    there no label touches another, a line or a dimension's arrow, none is within 6 px of
    the edge, every dimension line runs whole between its arrows, and the smallest text is
    11 px or more in a 360 px phone's column."""
    seen = _drawn(monkeypatch, tmp_path)
    desktop, small = seen[False], seen[True]
    np = small["np"]
    shown = [text for text, _ in small["texts"]]
    missing = [text for text, _ in desktop["texts"] if not any(text in s for s in shown)]
    assert not missing, f"the phone drawing lacks {missing}"
    assert len(small["arrows"]) == len(desktop["arrows"]) == 3, "l, w and R each have a dimension line"
    problems = []
    boxes = small["texts"]
    for i, (text, box) in enumerate(boxes):
        if min(box.x0, box.y0, small["width"] - box.x1, small["height"] - box.y1) < 6:
            problems.append(f"{text!r} at the edge")
        problems += [f"{text!r} overlaps {other!r}" for other, box2 in boxes[i + 1:] if box.overlaps(box2)]
        problems += [f"{text!r} lies on a line" for points in small["lines"]
                     if _segments_through(box, points, np)]
        problems += [f"{text!r} lies on a dimension line" for points in small["arrows"]
                     if _segments_through(box, points, np)]
    assert not problems, problems
    assert small["smallest_px"] >= 11.0, f"smallest text {small['smallest_px']:.1f} px on a 360 px phone"
