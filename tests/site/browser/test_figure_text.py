"""Every figure's lettering is large enough where a page shows it: at least 10 px high on
a laptop (1366 × 900), and on phones 360 and 390 px wide at least 11 px on the engineering
drawings (course/drawing: dimensions and balloons are read one by one) and 9 px on the
plots and the schematics of the exporter's windows, measured on the picture as the browser
lays it out.

- A drawing (SVG): its smallest font size, scaled by the width the page gives the picture
  over its viewBox's width. The pages show the views cropped close (course/drawing); the
  whole A4 sheet, title block and all, is linked under each.
- A plot (PNG): its smallest text in image pixels, which course/plotting.py records in the
  file, scaled by the shown width over the image's width.
Pictures of the simulation carry no text and are not measured.

On a phone a figure with lettering shows its phone variant (course/phone.py), which the
page offers in a <picture> (_plugins/phone_figures.rb); the test measures the file the
browser chose.
"""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET

from PIL import Image

from course.plotting import TEXT_KEY

LAPTOP = {"width": 1366, "height": 900}
READABLE_PX = 10.0
DESKTOP_DENSITY = 2.0
PHONES = [{"width": 360, "height": 780}, {"width": 390, "height": 844}]
READABLE_ON_A_PHONE_PX = 9.0
DRAWING_ON_A_PHONE_PX = 11.0   # course/phone.py DRAWING_MIN_TEXT_PX
SVG = "{http://www.w3.org/2000/svg}"
CSS_RULE = re.compile(r"([^{}]+)\{([^}]*)\}")

# Every figure of the page's body, loaded (lazy ones too) so that the browser has chosen
# which file to show: its src, the file shown and the width it is shown at.
FIGURES = """async () => {
    const images = Array.from(document.querySelectorAll('.page-body img'))
        .filter(img => img.getAttribute('src').includes('/media/'));
    images.forEach(img => { img.loading = 'eager'; });
    await Promise.all(images.map(img => img.decode().catch(() => null)));
    return images.map(img => ({src: img.getAttribute('src'), file: new URL(img.currentSrc).pathname,
                               srcset: img.getAttribute('srcset'),
                               shown: img.getBoundingClientRect().width}));
}"""


def _declarations(text: str) -> dict[str, str]:
    return {k.strip(): v.strip() for k, v in (part.split(":", 1) for part in text.split(";") if ":" in part)}


def _style_sheet(root) -> dict[str, str]:
    """font-size by selector from the SVG's <style> (the schematics set their lettering
    there: `text { font-size: 11.5px }`, `text.title { ... }`)."""
    sizes = {}
    for style in root.iter(f"{SVG}style"):
        for selectors, body in CSS_RULE.findall(style.text or ""):
            size = _declarations(body).get("font-size")
            for selector in selectors.split(","):
                if size:
                    sizes[selector.strip()] = size
    return sizes


def smallest_svg_text(path) -> tuple[float, float]:
    """(viewBox width, smallest font size) of an SVG figure. A text's size is, first found:
    its style attribute's, its class's rule in <style>, the rule for all texts, its
    font-size attribute, its parent's."""
    root = ET.parse(path).getroot()
    width = float(root.attrib["viewBox"].split()[2])
    rules = _style_sheet(root)
    sizes: list[float] = []

    def walk(element, size):
        tag = element.tag.removeprefix(SVG)
        classes = element.attrib.get("class", "").split()
        given = (_declarations(element.attrib.get("style", "")).get("font-size")
                 or next((rules[f"{tag}.{c}"] for c in classes if f"{tag}.{c}" in rules), None)
                 or rules.get(tag) or element.attrib.get("font-size"))
        size = float(re.sub(r"px$", "", given.strip())) if given else size
        if element.tag == f"{SVG}text" and "".join(element.itertext()).strip():
            sizes.append(size)
        for child in element:
            walk(child, size)

    walk(root, 16.0)   # the browser's default
    return width, min(sizes, default=float("inf"))


def smallest_text_shown(site, figure) -> tuple[str, float] | None:
    """(kind, height in CSS px of the smallest text) of a figure as the page shows it, or
    None for a picture without text."""
    file = site.root / figure["file"].lstrip("/")
    if file.suffix == ".svg":
        width, size = smallest_svg_text(file)
        return "svg", size * figure["shown"] / width
    image = Image.open(file)
    if TEXT_KEY not in image.info:
        return None   # a picture of the simulation: no text
    return "plot", float(image.info[TEXT_KEY]) * figure["shown"] / image.width


def pages_with_figures(site) -> list[str]:
    return [path for path in site.pages
            if 'src="/media/' in (site.root / path.strip("/") / "index.html").read_text(encoding="utf-8")]


def test_figure_text_is_readable_at_the_page_width(browser_page, site):
    """On a laptop every figure's smallest text is at least READABLE_PX high, and every plot
    offers a file with at least DESKTOP_DENSITY image pixels to each CSS pixel it is shown
    across, for 2× screens (course/sharp.py)."""
    page = browser_page.page
    page.set_viewport_size(LAPTOP)
    measured, small, soft = {"svg": 0, "plot": 0}, [], []
    try:
        for path in pages_with_figures(site):
            browser_page.visit(path)
            for figure in page.evaluate(FIGURES):
                found = smallest_text_shown(site, figure)
                if found is None:
                    continue
                kind, px = found
                measured[kind] += 1
                if px < READABLE_PX:
                    small.append(f"{path}: {figure['file']} shown {figure['shown']:.0f} px wide: "
                                 f"smallest text {px:.1f} px")
                if kind == "plot":
                    width = max(Image.open(site.root / candidate.split()[0].lstrip("/")).width
                                for candidate in (figure["srcset"] or figure["file"]).split(","))
                    if width < DESKTOP_DENSITY * figure["shown"]:
                        soft.append(f"{path}: {figure['file']} shown {figure['shown']:.0f} px "
                                    f"wide: its sharpest file is {width} px")
    finally:
        page.set_viewport_size({"width": 1280, "height": 800})
    assert measured["svg"] >= 20 and measured["plot"] >= 15, measured
    assert not small, "\n".join(small)
    assert not soft, "\n".join(soft)


def is_drawing(site, figure) -> bool:
    """Whether the figure is an engineering drawing's views: its whole sheet lies beside it."""
    src = site.root / figure["src"].lstrip("/")
    return src.suffix == ".svg" and src.with_name(f"{src.stem}-sheet.svg").is_file()


def test_on_a_phone_every_figure_shows_text_at_least_9_px_high_and_drawings_11(phone, site):
    """At 390 and 360 px every figure with lettering shows it at least 9 px high, and every
    engineering drawing at least 11 px: the phone variants where the figure has one (all
    the plots and the drawings, the schematics of the exporter's windows), the figure
    itself where it needs none."""
    page = phone.page
    measured, drawings, variants, small = 0, 0, set(), []
    try:
        for size in PHONES:
            page.set_viewport_size(size)
            for path in pages_with_figures(site):
                phone.visit(path)
                for figure in page.evaluate(FIGURES):
                    found = smallest_text_shown(site, figure)
                    if found is None:
                        continue
                    measured += 1
                    if figure["file"] != figure["src"]:
                        variants.add(figure["file"])
                    px = found[1]
                    drawing = is_drawing(site, figure)
                    drawings += drawing
                    if px < (DRAWING_ON_A_PHONE_PX if drawing else READABLE_ON_A_PHONE_PX):
                        small.append(f"{size['width']} px, {path}: {figure['file']} shown "
                                     f"{figure['shown']:.0f} px wide: smallest text {px:.1f} px")
    finally:
        page.set_viewport_size(PHONES[-1])
    assert measured >= 2 * 35 and drawings >= 2 * 17, (measured, drawings)
    assert all(re.search(r"-phone(-3x)?\.", file) for file in variants), variants
    assert len(variants) >= 25, f"phone variants shown: {sorted(variants)}"
    assert not small, "\n".join(small)


def test_a_phone_fetches_the_plot_file_its_screen_needs(browser, site):
    """A plot's phone variant is two files (course/plotting.py): a 360 px phone with 1 or 2
    device pixels to the CSS pixel shows the 720 px one, with 3 the 1080 px one, each
    sharp there (at least as many image pixels as device pixels across the column)."""
    path = next(p for p in pages_with_figures(site)
                if "-phone-3x.png" in (site.root / p.strip("/") / "index.html").read_text(encoding="utf-8"))
    shown = {}
    for density in (1, 2, 3):
        context = browser.new_context(viewport=PHONES[0], device_scale_factor=density)
        try:
            page = context.new_page()
            page.goto(site.url(path))
            plots = [f for f in page.evaluate(FIGURES) if f["src"].endswith(".png") and "-phone" in f["file"]]
            assert plots, f"{path}: no plot shows a phone variant"
            shown[density] = {f["file"].rsplit("-phone", 1)[1] for f in plots}
            for figure in plots:
                width = Image.open(site.root / figure["file"].lstrip("/")).width
                assert width >= density * figure["shown"], f"{figure['file']}: {width} px for {density} × {figure['shown']:.0f}"
        finally:
            context.close()
    assert shown == {1: {".png"}, 2: {".png"}, 3: {"-3x.png"}}, shown


def test_a_laptop_fetches_the_plot_file_its_screen_needs(browser, site):
    """On a laptop with 1 device pixel to the CSS pixel a plot shows its own file; with 2,
    its sharp one (course/sharp.py), at least twice as wide as it is shown, in the same
    place on the page."""
    path = "/practice-3/exporting/"
    shown = {}
    for density in (1, 2):
        context = browser.new_context(viewport=LAPTOP, device_scale_factor=density)
        try:
            page = context.new_page()
            page.goto(site.url(path))
            plots = [f for f in page.evaluate(FIGURES) if f["src"].endswith(".png") and f["srcset"]]
            assert plots, f"{path}: no plot offers a sharp file"
            shown[density] = {(f["src"], round(f["shown"])): f["file"] for f in plots}
            for figure in plots:
                width = Image.open(site.root / figure["file"].lstrip("/")).width
                assert width >= density * figure["shown"], f"{figure['file']}: {width} px for {density} × {figure['shown']:.0f}"
        finally:
            context.close()
    assert shown[1].keys() == shown[2].keys(), "the same plots, as wide"
    assert all(not file.endswith("-2x.png") for file in shown[1].values()), shown[1]
    assert all(file.endswith("-2x.png") for file in shown[2].values()), shown[2]


def test_a_render_s_sharp_file_goes_to_the_screens_that_need_it(browser, site):
    """A MuJoCo render has a sharp file too (course/sharp.py save_render). A laptop at 1
    device pixel to the CSS pixel fetches the plain file; at 2, the sharp one; a phone at 3,
    whose column would show the plain 960 px at 2.7 image pixels to the CSS pixel, the
    sharp one as well, which in 256 colours weighs at most half as much again as the plain
    one. Each file has at least as many pixels across as the screen shows."""
    path = "/practice-3/modelling/"
    seen = {}
    for name, viewport, density in (("laptop 1x", LAPTOP, 1), ("laptop 2x", LAPTOP, 2),
                                    ("phone 3x", PHONES[1], 3)):
        context = browser.new_context(viewport=viewport, device_scale_factor=density)
        try:
            page = context.new_page()
            page.goto(site.url(path))
            renders = [f for f in page.evaluate(FIGURES)
                       if f["src"].endswith("/model.png") and f["shown"]]   # not the 3D viewer's still
            assert len(renders) == 1, f"{path}: the render of the model, once: {renders}"
            seen[name] = renders[0]["file"].rsplit("/", 1)[1]
            width = Image.open(site.root / renders[0]["file"].lstrip("/")).width
            assert width >= density * renders[0]["shown"], (name, width, renders[0]["shown"])
        finally:
            context.close()
    assert seen == {"laptop 1x": "model.png", "laptop 2x": "model-2x.png", "phone 3x": "model-2x.png"}, seen
    media = site.root / "media" / "practice-3"
    assert (media / "model-2x.png").stat().st_size <= 1.5 * (media / "model.png").stat().st_size


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
