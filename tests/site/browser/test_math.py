"""Formulas on a phone: typeset when the site was built (_plugins/math.rb), so the page
loads no KaTeX script, and a displayed formula wider than the screen scrolls inside its
own line (.katex-display in assets/css/main.css) instead of widening the page.
"""

import pytest

import axe_audit
from conftest import PHONE

ACKERMANN = "/practice-5/ackermann-geometry/"
# Equation 4 of the Ackermann page, the widest formula of the site: both wheels' angles.
EQUATION_4 = r"\Phi_o = \arctan \left(\frac{2l \sin \Phi}{2l \cos \Phi + w \sin \Phi} \right)"

PAGE_WIDTH_JS = "() => [document.scrollingElement.scrollWidth, window.innerWidth]"


def equation_4(page):
    formulas = page.locator(".katex-display").filter(
        has=page.locator("annotation", has_text=EQUATION_4))
    assert formulas.count() == 1, f"{ACKERMANN}: Equation 4 not found as one displayed formula"
    return formulas.first


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
    shown = formula.evaluate("""e => {
        const r = e.getBoundingClientRect();
        return {left: r.left, right: r.right, top: r.top, bottom: r.bottom, height: r.height,
                scrollWidth: e.scrollWidth, clientWidth: e.clientWidth,
                overflowX: getComputedStyle(e).overflowX};
    }""")
    assert shown["left"] >= 0 and shown["right"] <= window, f"Equation 4 leaves the screen: {shown}"
    assert 0 <= shown["top"] and shown["bottom"] <= PHONE["height"] and shown["height"] > 20, shown
    # Wider than the phone: it scrolls in its own box, and its end can be scrolled to.
    if shown["scrollWidth"] > shown["clientWidth"]:
        assert shown["overflowX"] == "auto", shown
        end = formula.evaluate("e => { e.scrollLeft = e.scrollWidth; return e.scrollLeft; }")
        assert end >= shown["scrollWidth"] - shown["clientWidth"] - 1, (end, shown)


def test_formulas_on_a_phone_are_accessible(phone, site):
    """Equation 4 scrolls on a phone, so the keyboard can reach it (assets/js/site.js gives
    it a tab stop; axe's scrollable-region-focusable); the page passes the audit there."""
    page = phone.page
    phone.visit(ACKERMANN, then=lambda page: page.add_script_tag(url=site.node_module_url(axe_audit.AXE)))
    assert equation_4(page).get_attribute("tabindex") == "0", "Equation 4 scrolls but takes no focus"
    axe_audit.start(page, ACKERMANN)
    serious = axe_audit.serious(axe_audit.collect(page))
    assert not serious, serious
    # Not among the rules axe_audit runs by default (its checks are not all serious).
    axe_audit.start(page, ACKERMANN, options={
        "runOnly": {"type": "rule", "values": ["scrollable-region-focusable"]}})
    unreachable = axe_audit.collect(page)
    assert not unreachable, unreachable


def test_no_page_with_math_scrolls_sideways_on_a_phone(phone, site):
    wide = []
    math_pages = [path for path in site.pages if path.endswith("/") and 'class="katex' in
                  (site.root / path.lstrip("/") / "index.html").read_text(encoding="utf-8")]
    assert math_pages, "no page of the site has a formula"
    for path in math_pages:
        visit = phone.visit(path)
        assert not visit.problems(), (path, visit.problems())
        width, window = phone.page.evaluate(PAGE_WIDTH_JS)
        if width > window:
            wide.append(f"{path}: {width} px in {window} px")
    assert not wide, "pages wider than a phone:\n" + "\n".join(wide)
