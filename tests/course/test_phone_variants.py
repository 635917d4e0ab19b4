"""A figure's phone variant (course/phone.py) is drawn by the same code as the figure:
`plotting.variants` gives the code its axes twice, laid out for the page and for a phone;
a drawing too wide for a phone's column gets its views one above the other, smaller if
they must be, the lettering as large as ever (course/drawing/narrow.py)."""

import re

import numpy as np
import pytest
from PIL import Image

from course import media, phone, plotting
from course.drawing import narrow, part_drawing_svg
from course.practices.practice_5 import design as practice_5


def test_a_plot_is_drawn_twice_and_its_phone_variant_reads_9_px_in_a_phones_column(tmp_path):
    path = tmp_path / "plot.png"
    shapes = []
    for fig, axes, on_phone in plotting.variants(path, 2, 2, figsize=(11, 5), sharex="col",
                                                  gridspec_kw={"height_ratios": [3, 1]}):
        shapes.append((np.shape(axes), on_phone))
        for ax in np.ravel(axes):
            ax.plot([0, 1, 2], [0, 1, 0])
            ax.set_xlabel("time [s]")
    assert shapes == [((2, 2), False), ((2, 2), True)], "the same axes, laid out twice"
    desktop, small = Image.open(path), Image.open(phone.phone_path(path))
    assert small.width == round(plotting.PHONE_WIDTH_IN * 130) < desktop.width
    assert small.height > desktop.height and small.height > small.width, "the panels one above the other"
    smallest = float(small.info[plotting.TEXT_KEY]) * phone.SHOWN_PX / small.width
    assert smallest >= phone.MIN_TEXT_PX - 0.01


def test_on_a_phone_the_columns_of_panels_go_one_above_the_other():
    fig, axes = plotting.phone_figure(2, 2, figsize=(11, 5), sharex="col",
                                      gridspec_kw={"height_ratios": [3, 1], "width_ratios": [2, 1]})
    rows = [[ax.get_subplotspec().rowspan.start for ax in row] for row in axes]
    assert rows == [[0, 2], [1, 3]], "each column's panels together, the columns in order"
    assert axes[0, 0].get_shared_x_axes().joined(axes[0, 0], axes[1, 0])
    assert not axes[0, 0].get_shared_x_axes().joined(axes[0, 0], axes[0, 1])
    ratios = axes[0, 0].get_subplotspec().get_gridspec().get_height_ratios()
    assert ratios[0] > ratios[1] and ratios[2] > ratios[3], "a short row stays short"
    fig, strip = plotting.phone_figure(1, 4, figsize=(12, 2.4), phone_grid=(2, 2))
    assert [(ax.get_subplotspec().rowspan.start, ax.get_subplotspec().colspan.start) for ax in strip] == \
        [(0, 0), (0, 1), (1, 0), (1, 1)]
    with pytest.raises(ValueError, match="fewer places"):
        plotting.phone_figure(1, 4, figsize=(12, 2.4), phone_grid=(1, 3))


def view_box_width(svg: str) -> float:
    return float(re.search(r'viewBox="\S+ \S+ (\S+) \S+"', svg).group(1))


def test_a_drawing_too_wide_for_a_phone_gets_narrow_views_with_lettering_as_large():
    part = practice_5.chassis()
    views = part_drawing_svg(part, views_only=True)
    assert narrow.too_wide(views)
    small = narrow.part_views_narrow(part, views)
    assert not narrow.too_wide(small)
    assert view_box_width(small) <= narrow.readable_width(views) < view_box_width(views)
    sizes = {float(s) for s in re.findall(r'font-size="([\d.]+)"', small)}
    assert min(sizes) == min(float(s) for s in re.findall(r'font-size="([\d.]+)"', views))
    order = [re.search(rf'<g id="view-{v}">', small).start() for v in ("front", "top", "side")]
    assert order == sorted(order)
    assert not narrow.too_wide(part_drawing_svg(practice_5.knuckle(), views_only=True)), \
        "a drawing narrow enough as it is needs no variant"


def test_a_figure_whose_code_and_declaration_disagree_about_its_phone_variant_is_refused(
        tmp_path, monkeypatch):
    def with_variant(path):
        path.write_text("<svg/>")
        phone.phone_path(path).write_text("<svg/>")

    monkeypatch.setattr(media, "all_figures", lambda: [media.Figure("media/x.svg", with_variant)])
    with pytest.raises(RuntimeError, match="give it phone=True"):
        media.make_figure("media/x.svg", tmp_path / "x.svg")
    monkeypatch.setattr(media, "all_figures",
                        lambda: [media.Figure("media/x.svg", lambda p: p.write_text("<svg/>"), phone=True)])
    with pytest.raises(RuntimeError, match="give it phone=False"):
        media.make_figure("media/x.svg", tmp_path / "x.svg")
    assert media.Figure("media/x.png", with_variant, phone=True).outputs == ["media/x.png", "media/x-phone.png"]
