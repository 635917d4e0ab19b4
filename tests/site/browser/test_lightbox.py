"""A page's image opens enlarged in a dialog (assets/js/site.js): from the mouse or the
keyboard, closed with Escape, focus back on the image. On a phone a drawing opens at its
own size, wider than the screen, and the reader pans across it; so does a plot, which the
page shows as its phone variant (_plugins/phone_figures.rb) and the dialog at full size."""

from __future__ import annotations

PHONE = {"width": 390, "height": 844}
LAPTOP = {"width": 1366, "height": 900}
PAGE = "/practice-5/modelling/"
DRAWING = '.zoom-button:has(img[src$="/media/practice-5/chassis.svg"])'

OPENED = """() => {
    const dialog = document.querySelector('dialog.lightbox');
    const image = dialog.querySelector('.lightbox-image');
    const close = dialog.querySelector('.lightbox-close').getBoundingClientRect();
    return {open: dialog.open, src: image.getAttribute('src'), image: image.getBoundingClientRect().width,
            scrollWidth: dialog.scrollWidth, clientWidth: dialog.clientWidth,
            closeVisible: close.left >= 0 && close.right <= innerWidth && close.top >= 0};
}"""


def _open(browser_page, size):
    page = browser_page.page
    page.set_viewport_size(size)

    def click(page):
        page.locator(DRAWING).scroll_into_view_if_needed()
        # a tap while the lazy picture still loads would cancel its request (a failed
        # request to the visit); a reader taps the drawing they see
        page.wait_for_function(f"() => document.querySelector('{DRAWING} img').complete")
        page.locator(DRAWING).click()
        page.wait_for_function("() => document.querySelector('.lightbox-image').complete")

    visit = browser_page.visit(PAGE, then=click)
    assert not visit.problems(), visit.problems()
    return page, page.evaluate(OPENED)


def test_on_a_laptop_the_drawing_opens_within_the_window_and_escape_closes_it(browser_page):
    try:
        page, shown = _open(browser_page, LAPTOP)
        assert shown["open"] and shown["src"].endswith("/media/practice-5/chassis.svg")
        assert shown["image"] <= LAPTOP["width"] and shown["scrollWidth"] <= shown["clientWidth"] + 1
        page.keyboard.press("Escape")
        assert not page.evaluate("() => document.querySelector('dialog.lightbox').open")
        assert page.evaluate("() => document.activeElement.classList.contains('zoom-button')")
    finally:
        browser_page.page.set_viewport_size({"width": 1280, "height": 800})


def test_on_a_phone_the_drawing_opens_at_its_own_size_and_pans(browser_page):
    try:
        page, shown = _open(browser_page, PHONE)
        assert shown["open"]
        assert shown["image"] > 1.5 * PHONE["width"], "the enlarged drawing is wider than the phone"
        assert shown["scrollWidth"] > shown["clientWidth"], "the dialog scrolls sideways"
        page.evaluate("() => document.querySelector('dialog.lightbox').scrollBy(300, 0)")
        assert page.evaluate("() => document.querySelector('dialog.lightbox').scrollLeft") > 0
        assert page.evaluate(OPENED)["closeVisible"], "Close stays on the screen while panning"
        page.get_by_role("button", name="Close").click()
        assert not page.evaluate("() => document.querySelector('dialog.lightbox').open")
    finally:
        browser_page.page.set_viewport_size({"width": 1280, "height": 800})


PLOT_PAGE = "/practice-5/control-script/"
PLOT = "/media/practice-5/knuckle_angles.png"
PLOT_BUTTON = f'.zoom-button:has(img[src$="{PLOT}"])'

PLOT_SHOWN = f"""() => {{
    const img = document.querySelector('{PLOT_BUTTON} img');
    return {{file: new URL(img.currentSrc).pathname, inPicture: img.parentNode.nodeName === 'PICTURE',
             focused: document.activeElement === img.closest('.zoom-button')}};
}}"""
ENLARGED = """() => {
    const dialog = document.querySelector('dialog.lightbox');
    const image = dialog.querySelector('.lightbox-image');
    return {open: dialog.open, file: image.src && new URL(image.src).pathname,
            offers: image.getAttribute('srcset'), width: image.getBoundingClientRect().width, natural: image.naturalWidth,
            scrollWidth: dialog.scrollWidth, clientWidth: dialog.clientWidth};
}"""


def test_on_a_phone_a_plot_shows_its_phone_variant_and_a_tap_opens_it_at_full_size(phone):
    page = phone.page

    def tap(page):
        page.locator(PLOT_BUTTON).scroll_into_view_if_needed()
        page.wait_for_function(f"() => document.querySelector('{PLOT_BUTTON} img').complete")
        page.locator(PLOT_BUTTON).click()
        page.wait_for_function("() => document.querySelector('.lightbox-image').complete")

    visit = phone.visit(PLOT_PAGE, then=tap)
    assert not visit.problems(), visit.problems()
    shown = page.evaluate(PLOT_SHOWN)
    assert shown["inPicture"] and shown["file"] == PLOT.replace(".png", "-phone.png"), shown
    enlarged = page.evaluate(ENLARGED)
    assert enlarged["open"] and enlarged["file"] == PLOT, enlarged
    assert enlarged["width"] == enlarged["natural"] > 2 * PHONE["width"], "shown at its own size"
    assert enlarged["scrollWidth"] > enlarged["clientWidth"], "the dialog scrolls sideways"
    page.keyboard.press("Escape")
    assert not page.evaluate("() => document.querySelector('dialog.lightbox').open")
    assert page.evaluate(PLOT_SHOWN)["focused"], "focus is back on the figure"


def test_from_the_keyboard_a_plot_opens_enlarged_and_escape_gives_focus_back(browser_page):
    page = browser_page.page
    page.set_viewport_size(LAPTOP)
    try:
        def reach(page):
            page.locator(PLOT_BUTTON).scroll_into_view_if_needed()
            page.wait_for_function(f"() => document.querySelector('{PLOT_BUTTON} img').complete")

        visit = browser_page.visit(PLOT_PAGE, then=reach)
        assert not visit.problems(), visit.problems()
        assert page.evaluate(PLOT_SHOWN)["file"] == PLOT, "a laptop shows the figure itself"
        page.locator(PLOT_BUTTON).focus()
        page.keyboard.press("Enter")
        page.wait_for_function("() => document.querySelector('.lightbox-image').complete")
        enlarged = page.evaluate(ENLARGED)
        assert enlarged["open"] and enlarged["file"] == PLOT, enlarged
        assert PLOT.replace(".png", "-2x.png") in (enlarged["offers"] or ""), \
            "the enlarged plot offers its sharp file to a 2× screen, as the page does"
        assert enlarged["width"] <= LAPTOP["width"], "within the window"
        assert page.evaluate("() => document.activeElement.className") == "lightbox-close"
        page.keyboard.press("Escape")
        assert not page.evaluate("() => document.querySelector('dialog.lightbox').open")
        assert page.evaluate(PLOT_SHOWN)["focused"], "focus is back on the figure"
    finally:
        page.set_viewport_size({"width": 1280, "height": 800})
