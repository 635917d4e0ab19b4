"""Every figure's lettering is at least 10 px high where a page shows it, on a laptop
(1366 × 900): measured on the picture as the browser lays it out.

- A drawing (SVG): its smallest font size, scaled by the width the page gives the picture
  over its viewBox's width. The pages show the views cropped close (course/drawing); the
  whole A4 sheet, title block and all, is linked under each.
- A plot (PNG): its smallest text in image pixels, which course/plotting.py records in the
  file, scaled by the shown width over the image's width.
Pictures of the simulation carry no text and are not measured.
"""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET

from PIL import Image

from course.plotting import TEXT_KEY

LAPTOP = {"width": 1366, "height": 900}
READABLE_PX = 10.0
SVG = "{http://www.w3.org/2000/svg}"

FIGURES = """() => Array.from(document.querySelectorAll('.page-body img'), img => {
    return {src: img.getAttribute('src'), shown: img.getBoundingClientRect().width};
}).filter(f => f.src.includes('/media/'))"""


def smallest_svg_text(path) -> tuple[float, float]:
    """(viewBox width, smallest font size) of an SVG figure."""
    root = ET.parse(path).getroot()
    width = float(root.attrib["viewBox"].split()[2])
    sizes: list[float] = []

    def walk(element, size):
        style = dict(part.split(":", 1) for part in element.attrib.get("style", "").split(";")
                     if ":" in part)
        given = style.get("font-size", element.attrib.get("font-size"))
        size = float(re.sub(r"px$", "", given.strip())) if given else size
        if element.tag == f"{SVG}text" and "".join(element.itertext()).strip():
            sizes.append(size)
        for child in element:
            walk(child, size)

    walk(root, 16.0)   # the browser's default
    return width, min(sizes, default=float("inf"))


def test_figure_text_is_readable_at_the_page_width(browser_page, site):
    page = browser_page.page
    page.set_viewport_size(LAPTOP)
    measured, small = {"svg": 0, "plot": 0}, []
    try:
        for path in site.pages:
            browser_page.visit(path)
            for figure in page.evaluate(FIGURES):
                file = site.root / re.sub(r"^/", "", figure["src"])
                shown = figure["shown"]
                if file.suffix == ".svg":
                    width, size = smallest_svg_text(file)
                    px, kind = size * shown / width, "svg"
                else:
                    image = Image.open(file)
                    if TEXT_KEY not in image.info:
                        continue   # a picture of the simulation: no text
                    px, kind = float(image.info[TEXT_KEY]) * shown / image.width, "plot"
                measured[kind] += 1
                if px < READABLE_PX:
                    small.append(f"{path}: {figure['src']} shown {shown:.0f} px wide: "
                                 f"smallest text {px:.1f} px")
    finally:
        page.set_viewport_size({"width": 1280, "height": 800})
    assert measured["svg"] >= 20 and measured["plot"] >= 15, measured
    assert not small, "\n".join(small)


def test_each_drawing_links_its_whole_sheet(site):
    """A drawing shows its views on the page; its caption links the whole sheet."""
    drawings = sorted(site.root.glob("media/practice-*/*-sheet.svg"))
    assert len(drawings) >= 17
    pages = {p: p.read_text(encoding="utf-8") for p in site.root.glob("practice-*/*/index.html")}
    for sheet in drawings:
        views = sheet.with_name(sheet.name.replace("-sheet.svg", ".svg"))
        address = "/" + sheet.relative_to(site.root).as_posix()
        shown = [p for p, html in pages.items() if f'src="/{views.relative_to(site.root).as_posix()}"' in html]
        assert shown, f"{views.name} is on no page"
        for page in shown:
            caption = re.search(rf'src="/{re.escape(views.relative_to(site.root).as_posix())}".*?</figcaption>',
                                pages[page], re.S)
            assert caption and f'href="{address}"' in caption[0], f"{page}: no link to {address}"
        root = ET.parse(sheet).getroot()
        assert root.attrib["viewBox"] == "0 0 297 210", "the sheet is the whole A4 sheet"
        assert smallest_svg_text(views)[0] < 297, "the page shows the views cropped"
