"""Finding one's way around: the phone menu, the links in the header and footer, the
"On this page" box that follows the reader, and the page for an address that does not exist.

The menu is _includes/sidebar.html, opened by the Menu button of _includes/header.html
(assets/js/site.js) and laid out by assets/css/main.css.
"""

from urllib.parse import urlsplit

import pytest
import yaml
from playwright.sync_api import TimeoutError as PlaywrightTimeout

import axe_audit
from conftest import PHONE
from repository import ROOT

NAVIGATION = ROOT / "_data" / "navigation.yml"


def last_navigation_url() -> str:
    """The url of the last entry of _data/navigation.yml (a section's last child)."""
    last = yaml.safe_load(NAVIGATION.read_text(encoding="utf-8"))[-1]
    return last["children"][-1]["url"] if "children" in last else last["url"]


def box(locator) -> dict:
    return locator.evaluate("""element => {
        const r = element.getBoundingClientRect();
        return {top: r.top, bottom: r.bottom, left: r.left, right: r.right,
                x: r.left + r.width / 2, y: r.top + r.height / 2};
    }""")


def scroll_into_drawer(page, drawer, target) -> None:
    """Turn the mouse wheel over the open menu, as a reader would, until `target` shows
    whole inside it; the page behind must not move."""
    behind = page.evaluate("window.scrollY")
    for _ in range(40):
        shown, seen = box(drawer), box(target)
        if seen["top"] >= shown["top"] and seen["bottom"] <= shown["bottom"]:
            break
        page.mouse.move(shown["x"], shown["y"])
        page.mouse.wheel(0, 150 if seen["bottom"] > shown["bottom"] else -150)
        page.wait_for_timeout(50)
    else:
        pytest.fail(f"{target} cannot be scrolled into the open menu: menu {box(drawer)}, "
                    f"entry {box(target)}", pytrace=False)
    assert page.evaluate("window.scrollY") == behind, "scrolling the menu scrolled the page"


def click_where_it_shows(page, target) -> None:
    """Click the middle of `target`, after checking that it is what shows there."""
    point = box(target)
    covered_by = target.evaluate("""(element, [x, y]) => {
        const there = document.elementFromPoint(x, y);
        return element.contains(there) ? "" : (there ? there.outerHTML.slice(0, 200) : "nothing");
    }""", [point["x"], point["y"]])
    assert not covered_by, f"the entry is not what shows at its place: {covered_by}"
    page.mouse.click(point["x"], point["y"])


@pytest.mark.parametrize("start", ["/", "/practice-1/modelling/"])
def test_the_phone_menu_reaches_the_last_page_of_the_navigation(phone, start):
    """At 390 × 844 the menu fills the window below the header and scrolls: from the home
    page (every section open) and from a page of Practice 1 (only that section open),
    the last entry of the navigation can be scrolled to, its section opened and the entry
    followed."""
    page = phone.page
    phone.visit(start)
    page.click(".nav-toggle")
    drawer = page.locator("#sidebar")
    page.wait_for_function("() => { const r = document.getElementById('sidebar')"
                           ".getBoundingClientRect(); return r.left >= 0 && r.width > 0; }")
    header = box(page.locator(".site-header"))
    shown = box(drawer)
    assert shown["top"] == pytest.approx(header["bottom"], abs=1), "the menu starts under the header"
    assert shown["bottom"] == pytest.approx(PHONE["height"], abs=1), \
        f"the menu ends at {shown['bottom']:.0f} px, not at the bottom of the window"

    url = last_navigation_url()
    entry = drawer.locator("a.nav-link").last
    assert urlsplit(entry.get_attribute("href")).path == url
    section = entry.locator("xpath=ancestor::details[1]")
    if section.count() and not section.evaluate("details => details.open"):
        summary = section.locator("summary")
        scroll_into_drawer(page, drawer, summary)
        click_where_it_shows(page, summary)
        assert section.evaluate("details => details.open"), "the section did not open"

    scroll_into_drawer(page, drawer, entry)
    with page.expect_navigation():
        click_where_it_shows(page, entry)
    assert urlsplit(page.url).path == url
    assert page.locator('#sidebar a[aria-current="page"]').get_attribute("href") == entry.get_attribute("href")


@pytest.mark.parametrize("size", [PHONE, {"width": 1366, "height": 900}], ids=["phone", "wide"])
def test_the_404_page_looks_like_the_site_and_leads_home(browser_page, site, size):
    """/404.html (what GitHub Pages shows for a missing address) loads cleanly with the
    site's stylesheet and header, passes axe, and its first link goes to the home page."""
    page = browser_page.page
    page.set_viewport_size(size)
    try:
        visit = browser_page.visit("/404.html", then=lambda p: p.add_script_tag(
            url=site.node_module_url(axe_audit.AXE)))
        assert not visit.problems(), visit.problems()
        axe_audit.start(page, "/404.html")
        assert not axe_audit.serious(axe_audit.collect(page))
        assert page.locator("h1").inner_text() == "Page not found"
        # main.css applies: the header sticks and the text is in the site's font.
        assert page.locator(".site-header").evaluate("e => getComputedStyle(e).position") == "sticky"
        assert "system-ui" in page.locator("main").evaluate("e => getComputedStyle(e).fontFamily")
        with page.expect_navigation():
            page.locator(".page-body a").first.click()
        assert urlsplit(page.url).path == "/"
    finally:
        page.set_viewport_size({"width": 1280, "height": 800})


TOC_PAGE = "/practice-1/modelling/"
CURRENT_ENTRY = """() => Array.from(document.querySelectorAll('.toc-list a[aria-current="location"]'),
                                 a => a.hash.slice(1))"""


def wait_until_marked(page, wanted: str, equal: bool = True) -> None:
    """Wait until the marked entries, joined, are (or are no longer) `wanted`."""
    test = "===" if equal else "!=="
    try:
        page.wait_for_function(f"() => ({CURRENT_ENTRY})().join() {test} {wanted!r}",
                               timeout=5000, polling=100)
    except PlaywrightTimeout:
        pytest.fail(f"waiting for the marked entry {test} {wanted!r}: marked "
                    f"{page.evaluate(CURRENT_ENTRY)} at scrollY {page.evaluate('window.scrollY')}",
                    pytrace=False)


def test_on_this_page_marks_the_section_in_view(browser_page):
    """At 1366 × 900, scrolling with the wheel to a heading marks its entry in "On this
    page" (assets/js/toc.js), one entry at a time, going down and back up; the End key
    marks the last entry, Home leaves at most the first one marked."""
    page = browser_page.page
    page.set_viewport_size({"width": 1366, "height": 900})
    try:
        visit = browser_page.visit(TOC_PAGE)
        assert not visit.problems(), visit.problems()
        ids = page.locator(".toc-list a").evaluate_all("links => links.map(a => a.hash.slice(1))")
        assert len(ids) >= 5, f"{TOC_PAGE} lists too few sections to follow: {ids}"
        header = box(page.locator(".site-header"))
        # Headings that can be scrolled up to the header before the page ends (near the
        # end, the last section on screen is marked instead).
        reachable = page.evaluate("""([ids, below]) => ids.filter(id =>
            document.getElementById(id).getBoundingClientRect().top + window.scrollY - below
            + window.innerHeight < document.documentElement.scrollHeight - 40)""",
                                  [ids, header["bottom"]])
        assert len(reachable) >= 4, reachable
        for target in (reachable[2], reachable[-1], reachable[1]):
            heading = box(page.locator(f"#{target}"))
            page.mouse.move(1350, 500)   # right of the column: never over an entry (hover)
            page.mouse.wheel(0, heading["top"] - header["bottom"] - 20)
            wait_until_marked(page, target)
            assert page.evaluate(CURRENT_ENTRY) == [target]
            # The marked entry is the one shown in the link colour.
            colours = page.locator(".toc-list a").evaluate_all(
                "links => links.map(a => getComputedStyle(a).color)")
            assert len(set(colours)) == 2 and colours.count(colours[ids.index(target)]) == 1
        page.keyboard.press("End")
        wait_until_marked(page, ids[-1])
        page.keyboard.press("Home")
        page.wait_for_function("() => window.scrollY === 0", timeout=5000, polling=100)
        wait_until_marked(page, ids[-1], equal=False)
        assert page.evaluate(CURRENT_ENTRY) in ([], [ids[0]])
    finally:
        page.set_viewport_size({"width": 1280, "height": 800})


# ---- reading on a phone: the whole title, a long page's groups ----------------------------

CONFIG = ROOT / "_config.yml"


@pytest.mark.parametrize("size", [PHONE, {"width": 320, "height": 640}], ids=["390", "320"])
def test_the_header_shows_the_whole_title_on_a_phone(browser_page, size):
    """On a phone the site's title wraps inside the header (assets/css/main.css, "The whole
    title on a phone") instead of ending in "From SolidWo…": none of it is cut off, and it
    leaves the menu button and the search box their room."""
    title = yaml.safe_load(CONFIG.read_text(encoding="utf-8"))["title"]
    page = browser_page.page
    page.set_viewport_size(size)
    try:
        browser_page.visit("/practice-1/modelling/")
        shown = page.locator(".site-title").evaluate("""e => {
            const r = e.getBoundingClientRect(), header = e.parentElement.getBoundingClientRect();
            const style = getComputedStyle(e);
            return {text: e.textContent.trim(), scrollWidth: e.scrollWidth, clientWidth: e.clientWidth,
                    scrollHeight: e.scrollHeight, clientHeight: e.clientHeight,
                    left: r.left, right: r.right, top: r.top, bottom: r.bottom,
                    headerTop: header.top, headerBottom: header.bottom,
                    ellipsis: style.textOverflow === 'ellipsis' && style.overflow !== 'visible',
                    menuRight: document.querySelector('.nav-toggle').getBoundingClientRect().right,
                    searchLeft: document.querySelector('.site-search').getBoundingClientRect().left};
        }""")
    finally:
        page.set_viewport_size({"width": 1280, "height": 800})
    assert shown["text"] == title
    assert shown["scrollWidth"] <= shown["clientWidth"], f"the title is cut: {shown}"
    assert shown["scrollHeight"] <= shown["clientHeight"] + 1, f"the title is cut: {shown}"
    assert not shown["ellipsis"], f"the title can still end in an ellipsis: {shown}"
    assert shown["headerTop"] <= shown["top"] and shown["bottom"] <= shown["headerBottom"], shown
    assert shown["menuRight"] <= shown["left"] and shown["right"] <= shown["searchLeft"], shown


TROUBLESHOOTING = "/reference/troubleshooting/"
RULES = ROOT / "_data" / "check_rules.json"


def test_troubleshooting_jumps_between_groups_on_a_phone(phone):
    """The Troubleshooting page, tens of thousands of pixels on a phone, lists its groups
    first (nav#groups), one link a group of _data/check_rules.json; a link to a group
    shows its heading; deep among the entries a link at the bottom of the window (sticky)
    leads back to the groups' list."""
    import json

    groups = json.loads(RULES.read_text(encoding="utf-8"))["groups"]
    page = phone.page
    visit = phone.visit(TROUBLESHOOTING)
    assert not visit.problems(), visit.problems()
    height = page.evaluate("document.scrollingElement.scrollHeight")
    assert height > 10 * PHONE["height"], f"the page is only {height} px tall: nothing to jump over"

    jump = page.locator("nav#groups")
    assert box(jump)["top"] < PHONE["height"], "the groups' list is not on the first screen"
    links = jump.locator("a").evaluate_all("links => links.map(a => [a.hash.slice(1), a.textContent])")
    assert links == [[g["id"], g["title"]] for g in groups], links
    header = box(page.locator(".site-header"))

    # A group's link brings its heading up under the header.
    last = groups[-1]["id"]
    click_where_it_shows(page, jump.locator(f'a[href="#{last}"]'))
    page.wait_for_function(f"() => location.hash === '#{last}'", timeout=5000)
    heading = box(page.locator(f"h2#{last}"))
    assert header["bottom"] <= heading["top"] < PHONE["height"] / 2, heading

    # Deep in the page, among the entries of the middle group, the way back is in view.
    middle = groups[len(groups) // 2]["rules"][-1]["id"]
    page.locator(f"h3#{middle}").scroll_into_view_if_needed()
    back = page.locator(".back-to-groups a")
    shown = box(back)
    assert header["bottom"] < shown["top"] and shown["bottom"] <= PHONE["height"], \
        f"the link back to the groups is not in the window: {shown}"
    click_where_it_shows(page, back)
    page.wait_for_function("() => location.hash === '#groups'", timeout=5000)
    top = box(jump)["top"]
    assert header["bottom"] <= top < PHONE["height"] / 2, f"the groups' list is not in view: {top}"
