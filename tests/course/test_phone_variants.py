"""A figure's phone variant (course/phone.py) is drawn by the same code as the figure:
`plotting.variants` gives the code its axes twice, laid out for the page and for a phone;
a plot (and a render) also gets a sharp file for 2× screens (course/sharp.py); a drawing too wide for a
phone's column gets its views one above the other, smaller if
they must be, the lettering as large as ever (course/drawing/narrow.py)."""

import re

import numpy as np
import pytest
from PIL import Image

from course import media, phone, plotting, sharp
from course.drawing import narrow, part_drawing_svg
from course.practices.practice_5 import design as practice_5
from course.sharp import COLUMN_PX, sharp_path


def test_a_plot_is_drawn_twice_and_its_phone_variant_reads_9_px_in_a_phones_column_at_2x_and_3x(tmp_path):
    path = tmp_path / "plot.png"
    shapes = []
    for fig, axes, on_phone in plotting.variants(path, 2, 2, figsize=(11, 5), sharex="col",
                                                  gridspec_kw={"height_ratios": [3, 1]}):
        shapes.append((np.shape(axes), on_phone))
        for ax in np.ravel(axes):
            ax.plot([0, 1, 2], [0, 1, 0])
            ax.set_xlabel("time [s]")
    assert shapes == [((2, 2), False), ((2, 2), True)], "the same axes, laid out twice"
    desktop, small, dense = Image.open(path), Image.open(phone.phone_path(path)), Image.open(phone.dense_path(path))
    assert (small.width, dense.width) == plotting.PHONE_PIXELS
    assert small.width >= 2 * 358 and dense.width >= 3 * 358, "2 and 3 pixels a CSS pixel on a 390 px phone"
    assert small.height > desktop.height and small.height > small.width, "the panels one above the other"
    assert abs(dense.height / dense.width - small.height / small.width) < 0.002, "the same picture"
    shown = [float(image.info[plotting.TEXT_KEY]) * phone.SHOWN_PX / image.width for image in (small, dense)]
    assert min(shown) >= phone.MIN_TEXT_PX - 0.01
    assert shown[0] == pytest.approx(shown[1], abs=0.01), "the same lettering at either density"
    assert small.mode == dense.mode == "P", "256 colours"
    sharp = Image.open(sharp_path(path))
    assert sharp.width == 2 * min(desktop.width, COLUMN_PX) and sharp.mode == "P", \
        "the desktop plot for 2× screens, as wide as the widest column shows it"
    assert abs(sharp.height / sharp.width - desktop.height / desktop.width) < 0.002, "the same picture"
    assert float(sharp.info[plotting.TEXT_KEY]) / sharp.width == \
        pytest.approx(float(desktop.info[plotting.TEXT_KEY]) / desktop.width, abs=0.0001), \
        "the same lettering"


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
    fits = f'<svg viewBox="0 0 {narrow.readable_width(views) - 1:.1f} 80"><text font-size="3.5">1</text></svg>'
    assert not narrow.too_wide(fits), "a drawing narrow enough as it is needs no variant"
    assert narrow.readable_width(views) == pytest.approx(3.5 * phone.SHOWN_PX / 11.0), \
        "3.5 mm lettering 11 px high in a 360 px phone's column"


def overlapping_texts(svg: str) -> list[tuple[str, str]]:
    """Pairs of texts of a drawing whose boxes (course.drawing.svg.Text.points) overlap."""
    import itertools
    import shapely
    from course.drawing.svg import Text
    texts = []
    for attributes, body in re.findall(r"<text ([^>]*)>([^<]*)</text>", svg):
        a = dict(re.findall(r'([\w-]+)="([^"]*)"', attributes))
        turned = re.match(r"rotate\(([-\d.]+)", a.get("transform", ""))
        text = Text(float(a["x"]), float(a["y"]), body, float(a["font-size"]), a.get("text-anchor", "start"),
                    float(turned[1]) if turned else 0.0)
        corners = text.points()
        texts.append((body, shapely.Polygon([corners[0], corners[1], corners[3], corners[2]]).buffer(-0.15)))
    return [(a, b) for (a, pa), (b, pb) in itertools.combinations(texts, 2) if pa.intersects(pb)]


def test_the_chassis_narrow_views_keep_every_dimension_with_no_text_on_another():
    """Drawn small for a phone, the chassis (the widest part) keeps each dimension's text,
    and a text that fits nowhere beside its line goes over its middle or under the line
    rather than on another text."""
    part = practice_5.chassis()
    views = part_drawing_svg(part, views_only=True)
    small = narrow.part_views_narrow(part, views)
    words = sorted(re.findall(r"<text [^>]*>([^<]*)</text>", views))
    assert sorted(re.findall(r"<text [^>]*>([^<]*)</text>", small)) == words
    assert overlapping_texts(views) == []
    assert overlapping_texts(small) == []


def text_boxes(svg: str) -> list[tuple[str, tuple[float, float, float, float]]]:
    """Each text of a drawing with its box (x0, y0, x1, y1; mm)."""
    from course.drawing.svg import Text
    out = []
    for attributes, body in re.findall(r"<text ([^>]*)>([^<]*)</text>", svg):
        a = dict(re.findall(r'([\w-]+)="([^"]*)"', attributes))
        turned = re.match(r"rotate\(([-\d.]+)", a.get("transform", ""))
        corners = Text(float(a["x"]), float(a["y"]), body, float(a["font-size"]), a.get("text-anchor", "start"),
                       float(turned[1]) if turned else 0.0).points()
        xs, ys = [x for x, _ in corners], [y for _, y in corners]
        out.append((body, (min(xs), min(ys), max(xs), max(ys))))
    return out


def test_every_phone_drawing_keeps_its_labels_apart_and_clear_of_its_edge():
    """Each drawing's phone variant in media/ (course/drawing) reads 11 px in a 360 px
    phone's column and shows what the page's drawing shows: a part's every text; an
    assembly's balloons and key, the joints' names in the key under a letter; no text on
    another, and none within 2 mm of the edge."""
    from course.practices import ROOT
    checked = 0
    for small in sorted((ROOT / "media").rglob("*-phone.svg")):
        views = small.with_name(small.name.replace(phone.SUFFIX, ""))
        if not views.with_name(f"{views.stem}-sheet.svg").is_file():
            continue   # a schematic of the exporter's windows, not a drawing
        checked += 1
        svg, desktop = small.read_text(), views.read_text()
        assert not narrow.too_wide(svg), small.name
        shown, page = [t for t, _ in text_boxes(svg)], [t for t, _ in text_boxes(desktop)]
        if views.stem == "assembly":
            words = " ".join(shown).split()
            assert all(word in words for text in page for word in text.split()), small.name
        else:
            assert sorted(shown) == sorted(page), small.name
        assert overlapping_texts(svg) == [], small.name
        x, y, w, h = (float(v) for v in re.search(r'viewBox="([^"]+)"', svg)[1].split())
        near = [t for t, (x0, y0, x1, y1) in text_boxes(svg)
                if min(x0 - x, y0 - y, x + w - x1, y + h - y1) < 2.0]
        assert near == [], f"{small.name}: at the edge: {near}"
    assert checked == 17


def test_an_assembly_key_too_wide_for_a_phone_breaks_between_words():
    from course.practices.practice_3 import design as practice_3
    robot = practice_3.robot()
    from course.drawing import assembly_drawing_svg
    desktop = assembly_drawing_svg(robot, views_only=True)
    small = narrow.assembly_views_narrow(robot, desktop)
    assert not narrow.too_wide(small)
    assert "End arm with fixed fingers (end_arm_link.SLDPRT) × 1" in desktop
    lines = re.findall(r"<text [^>]*>([^<]*)</text>", small)
    assert "3  End arm with fixed fingers" in lines and "(end_arm_link.SLDPRT) × 1" in lines


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
    assert media.Figure("media/x.png", with_variant, phone=True).outputs == \
        ["media/x.png", "media/x-2x.png", "media/x-phone.png", "media/x-phone-3x.png"], \
        "a plot's sharp file, and its phone variant in two files"
    assert media.Figure("media/x.svg", with_variant, phone=True).outputs == ["media/x.svg", "media/x-phone.svg"]


def test_a_render_declares_its_sharp_file_and_writes_it(tmp_path, monkeypatch):
    """A render's code writes its sharp file (course/sharp.py save_render): twice as wide,
    the same view, in 256 colours; a Figure that says sharp=True and writes none, or writes
    one and does not say so, is refused."""
    def picture(width, height):
        image = np.zeros((height, width, 3), dtype=np.uint8)
        image[:, : width // 2] = (200, 40, 40)   # the left half red at any size
        return image

    def render(path):
        sharp.save_render(path, picture, 120, 80)

    made = tmp_path / "x.png"
    render(made)
    plain, dense = Image.open(made), Image.open(sharp.sharp_path(made))
    assert plain.size == (120, 80) and dense.size == (240, 160) and dense.mode == "P"
    assert np.array_equal(np.asarray(dense.convert("RGB"))[::2, ::2], np.asarray(plain.convert("RGB")))
    assert media.Figure("media/x.png", render, sharp=True).outputs == ["media/x.png", "media/x-2x.png"]
    monkeypatch.setattr(media, "all_figures", lambda: [media.Figure("media/x.png", render)])
    with pytest.raises(RuntimeError, match="give it sharp=True"):
        media.make_figure("media/x.png", tmp_path / "y.png")
    plain_only = lambda path: Image.fromarray(picture(120, 80)).save(path)  # noqa: E731
    monkeypatch.setattr(media, "all_figures", lambda: [media.Figure("media/x.png", plain_only, sharp=True)])
    with pytest.raises(RuntimeError, match="give it sharp=False"):
        media.make_figure("media/x.png", tmp_path / "z.png")
