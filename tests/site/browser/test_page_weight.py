"""Pages stay light: a reader on a slow connection gets the text quickly, and the figures
arrive as they scroll to them.

The weight of a page is what a first visit transfers, less images: the HTML, the
stylesheets, the scripts and the web fonts, compressed as GitHub Pages sends them (the
test server gzips text the same way; see site_server.py), whatever the browser had
cached from the pages before.
"""

from pathlib import Path

from PIL import Image

from repository import ROOT

MEDIA = ROOT / "media"

PAGE_BUDGET_BYTES = 300_000
# Playwright's resource types that make up a page's weight (images are checked apart).
COUNTED_TYPES = ("document", "stylesheet", "script", "font")

# Chromium starts fetching a lazy image when it comes within 1250 to 2500 CSS pixels of
# the window, depending on the connection; an image further down than this below the
# first screen must not be fetched by the first load.
LAZY_MARGIN_PX = 3000

PNG_BUDGET_BYTES = 400_000
# An uncompressed RGBA PNG is 32 bits per pixel; the site's renders and plots are 1 to 3.
PNG_MAX_BITS_PER_PIXEL = 6


def weight(visit) -> int:
    return sum(r.body_bytes for r in visit.responses if r.resource_type in COUNTED_TYPES)


def test_pages_without_images_stay_under_budget(site_visits):
    weights = {path: weight(visit) for path, visit in site_visits.items()}
    heavy = {path: w for path, w in weights.items() if w > PAGE_BUDGET_BYTES}
    heaviest = max(weights, key=weights.get)
    assert weights[heaviest] > 0, "no page downloaded anything: the responses were not recorded"
    assert not heavy, (f"pages over {PAGE_BUDGET_BYTES // 1000} kB without their images: "
                       + ", ".join(f"{path} {w // 1000} kB" for path, w in heavy.items()))


def test_content_images_load_lazily(site_visits):
    """Every image of a page's content but the first says loading="lazy" (the first may
    load at once, as it is often on the first screen)."""
    eager = [f"{path}: {image.src}" for path, visit in site_visits.items()
             for image in [i for i in visit.images if i.in_main][1:] if image.loading != "lazy"]
    assert not eager, ("content images without loading=\"lazy\" (see _plugins/lazy_images.rb):\n"
                       + "\n".join(eager))


def test_images_far_down_a_page_are_not_fetched_on_load(site_visits):
    far_down = 0
    fetched = []
    for path, visit in site_visits.items():
        for image in visit.images:
            if image.top > visit.viewport_height + LAZY_MARGIN_PX:
                far_down += 1
                if image.fetched:
                    fetched.append(f"{path}: {image.src} ({image.top:.0f} px down)")
    assert far_down, "no page has an image far enough down to show lazy loading"
    assert not fetched, ("images fetched before the reader scrolled near them:\n"
                         + "\n".join(fetched))


def test_pngs_are_compressed():
    report = []
    for png in sorted(MEDIA.rglob("*.png")):
        size = png.stat().st_size
        with Image.open(png) as image:
            bits_per_pixel = size * 8 / (image.width * image.height)
        report.append((size, bits_per_pixel, str(png.relative_to(MEDIA.parent))))
    assert report, "no PNG in media/"
    too_big = [f"{name}: {size // 1000} kB, {bpp:.1f} bits per pixel" for size, bpp, name in report
               if size > PNG_BUDGET_BYTES or bpp > PNG_MAX_BITS_PER_PIXEL]
    largest = max(report)
    assert not too_big, (f"PNGs over {PNG_BUDGET_BYTES // 1000} kB or "
                         f"{PNG_MAX_BITS_PER_PIXEL} bits per pixel:\n" + "\n".join(too_big)
                         + f"\n(largest: {largest[2]}, {largest[0] // 1000} kB)")
