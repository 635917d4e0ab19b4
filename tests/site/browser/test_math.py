"""Formulas on a phone: typeset when the site was built (_plugins/math.rb), so the page
loads no KaTeX script. Every displayed formula fits a phone's column: the pages break a
long one into lines (`\\begin{aligned}`). One still wider than its column, on the
narrowest phones, scrolls inside its own line instead of widening the page, and shows
that it does: it takes a tab stop, and a shadow darkens each edge beyond which more of it
lies, however little (assets/js/site.js marks it more-left / more-right; the shadows are
in assets/css/main.css, "Formulas that scroll show it").
"""

import io

from PIL import Image

import axe_audit
from conftest import PHONE

ACKERMANN = "/practice-5/ackermann-geometry/"
# Equation 4 of the Ackermann page, the widest formula of the site: both wheels' angles,
# one a line; this is the outer wheel's.
EQUATION_4 = r"\Phi_o &= \arctan \left(\frac{2l \sin \Phi}{2l \cos \Phi + w \sin \Phi} \right)"
# The narrowest phones in use (CSS pixels): some formulas do not fit their column there.
NARROW = {"width": 320, "height": 640}

PAGE_WIDTH_JS = "() => [document.scrollingElement.scrollWidth, window.innerWidth]"
BOX_JS = """e => {
    const r = e.getBoundingClientRect();
    return {left: r.left, right: r.right, top: r.top, bottom: r.bottom, height: r.height,
            scrollWidth: e.scrollWidth, clientWidth: e.clientWidth,
            overflowX: getComputedStyle(e).overflowX, tabindex: e.getAttribute("tabindex"),
            tex: (e.querySelector("annotation") || {}).textContent};
}"""
# How far the edges of a scrolling formula are checked for a shadow (CSS pixels), and
# the median grey (0 black, 255 white) that tells a shadowed edge from a plain one:
# the median leaves out the formula's own strokes, which cover little of an edge.
EDGE_PX = 4
SHADOWED_BELOW = 242
PLAIN_FROM = 250


def math_pages(site) -> list[str]:
    pages = [path for path in site.pages if path.endswith("/") and 'class="katex' in
             (site.root / path.lstrip("/") / "index.html").read_text(encoding="utf-8")]
    assert pages, "no page of the site has a formula"
    return pages


def equation_4(page):
    formulas = page.locator(".katex-display").filter(
        has=page.locator("annotation", has_text=EQUATION_4))
    assert formulas.count() == 1, f"{ACKERMANN}: Equation 4 not found as one displayed formula"
    return formulas.first


def edges(formula) -> tuple[float, float]:
    """The median grey of the formula's left and right edge, as drawn now."""
    picture = Image.open(io.BytesIO(formula.screenshot())).convert("L")
    scale = picture.width / formula.evaluate("e => e.getBoundingClientRect().width")
    strip = max(1, round(EDGE_PX * scale))

    def median(left: int) -> int:
        counts = picture.crop((left, 0, left + strip, picture.height)).histogram()
        half, seen = strip * picture.height / 2, 0
        for grey, count in enumerate(counts):
            seen += count
            if seen >= half:
                return grey
        return 255

    return median(0), median(picture.width - strip)


def scrolling_problems(formula) -> list[str]:
    """How a formula wider than its column fails to show that it scrolls (none: it does)."""
    box = formula.evaluate(BOX_JS)
    problems = []
    if box["overflowX"] not in ("auto", "scroll"):
        problems.append(f"cut off, not scrolling (overflow-x: {box['overflowX']})")
    if box["tabindex"] != "0":
        problems.append("takes no tab stop, so the keyboard cannot scroll it")
    scroll_to(formula, "0")
    left, right = edges(formula)
    if not (right < SHADOWED_BELOW and left >= PLAIN_FROM):
        problems.append(f"at its start, no shadow at the right edge only (greys {left}, {right})")
    end = scroll_to(formula, "e.scrollWidth")
    if end < box["scrollWidth"] - box["clientWidth"] - 1:
        problems.append(f"its end cannot be scrolled to ({end} of "
                        f"{box['scrollWidth'] - box['clientWidth']} px)")
    left, right = edges(formula)
    if not (left < SHADOWED_BELOW and right >= PLAIN_FROM):
        problems.append(f"at its end, no shadow at the left edge only (greys {left}, {right})")
    scroll_to(formula, "0")
    return problems


def scroll_to(formula, where: str) -> float:
    """Scroll the formula to `where` (a script expression of `e`, the formula) and return
    its scrollLeft once the page has drawn it (scroll events come before the next frame)."""
    return formula.evaluate(f"""e => {{
        e.scrollLeft = {where};
        return new Promise(done => requestAnimationFrame(() =>
            requestAnimationFrame(() => done(e.scrollLeft))));
    }}""")


def displayed_formulas(browser_page, path):
    """The displayed formulas of the page at `path`, loaded in `browser_page`; at a phone's
    width, the page must not scroll sideways with them."""
    visit = browser_page.visit(path)
    assert not visit.problems(), (path, visit.problems())
    page = browser_page.page
    width, window = page.evaluate(PAGE_WIDTH_JS)
    assert window < PHONE["width"] or width <= window, \
        f"{path} scrolls sideways: {width} px wide in {window} px"
    formulas = page.locator(".katex-display")
    return [formulas.nth(i) for i in range(formulas.count())]


def test_equation_4_fits_a_phone(phone):
    visit = phone.visit(ACKERMANN)
    assert not visit.problems(), visit.problems()
    page = phone.page
    scripts = [r.url for r in visit.responses if r.resource_type == "script" and "katex" in r.url.lower()]
    assert not scripts, f"the page loads KaTeX's script: {scripts}"

    width, window = page.evaluate(PAGE_WIDTH_JS)
    assert width <= window, f"{ACKERMANN} scrolls sideways on a phone: {width} px wide in {window} px"

    formula = equation_4(page)
    formula.scroll_into_view_if_needed()
    assert formula.is_visible()
    shown = formula.evaluate(BOX_JS)
    assert shown["left"] >= 0 and shown["right"] <= window, f"Equation 4 leaves the screen: {shown}"
    assert 0 <= shown["top"] and shown["bottom"] <= PHONE["height"] and shown["height"] > 20, shown
    # Two lines, one a wheel: the whole of it in view, nothing to scroll.
    assert shown["scrollWidth"] <= shown["clientWidth"], f"Equation 4 scrolls on a phone: {shown}"


def test_every_displayed_formula_fits_a_phone_or_visibly_scrolls(phone, site):
    """At 390 × 844 each displayed formula of the site fits its column (some 360 px), or
    scrolls in it with a tab stop and a shadow at the edge it continues beyond."""
    fitting, failures = 0, []
    for path in math_pages(site):
        for formula in displayed_formulas(phone, path):
            box = formula.evaluate(BOX_JS)
            if box["scrollWidth"] <= box["clientWidth"]:
                fitting += 1
                continue
            print(f"\n{path}: {box['scrollWidth']} px in {box['clientWidth']} px: {box['tex'][:70]}")
            failures += [f"{path}: {box['tex'][:50]!r} {problem}"
                         for problem in scrolling_problems(formula)]
    assert fitting >= 14, f"only {fitting} displayed formulas fit: are the math pages built?"
    assert not failures, "formulas wider than a phone that do not show they scroll:\n" + \
        "\n".join(failures)


def test_a_formula_wider_than_a_narrow_phone_visibly_scrolls(phone, site):
    """At 320 px some formulas are wider than their column (288 px): each scrolls, takes a
    tab stop and shows a shadow at the edge it continues beyond, on the side it does."""
    page = phone.page
    page.set_viewport_size(NARROW)
    scrolling, failures = 0, []
    try:
        for path in math_pages(site):
            for formula in displayed_formulas(phone, path):
                box = formula.evaluate(BOX_JS)
                if box["right"] > NARROW["width"]:
                    failures.append(f"{path}: {box['tex'][:50]!r} reaches out of the window "
                                    f"to {box['right']:.0f} px")
                if box["scrollWidth"] <= box["clientWidth"]:
                    assert box["tabindex"] is None, f"{path}: a formula that fits takes a tab stop"
                    continue
                scrolling += 1
                failures += [f"{path}: {box['tex'][:50]!r} {problem}"
                             for problem in scrolling_problems(formula)]
    finally:
        page.set_viewport_size(PHONE)
    assert scrolling, "no formula is wider than a 320 px phone: the scrolling is not exercised"
    assert not failures, "\n".join(failures)


def test_formulas_on_a_phone_are_accessible(phone, site):
    """On a narrow phone Equation 4 scrolls, so the keyboard can reach it (assets/js/site.js
    gives it a tab stop; axe's scrollable-region-focusable); the page passes the audit there."""
    page = phone.page
    page.set_viewport_size(NARROW)
    try:
        phone.visit(ACKERMANN, then=lambda page: page.add_script_tag(url=site.node_module_url(axe_audit.AXE)))
        formula = equation_4(page).evaluate(BOX_JS)
        assert formula["scrollWidth"] > formula["clientWidth"], f"Equation 4 fits at 320 px: {formula}"
        assert formula["tabindex"] == "0", "Equation 4 scrolls but takes no focus"
        axe_audit.start(page, ACKERMANN)
        serious = axe_audit.serious(axe_audit.collect(page))
        assert not serious, serious
        # Not among the rules axe_audit runs by default (its checks are not all serious).
        axe_audit.start(page, ACKERMANN, options={
            "runOnly": {"type": "rule", "values": ["scrollable-region-focusable"]}})
        unreachable = axe_audit.collect(page)
        assert not unreachable, unreachable
    finally:
        page.set_viewport_size(PHONE)
