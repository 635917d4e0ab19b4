"""The search box in the header: it finds pages, says when nothing matches, works from the
keyboard, stays out of a page's first load, and its results lead to real headings.

The documents come from _plugins/search_index.rb (assets/search-data.json); the box and
the index in the browser from assets/js/search.js and _includes/search.html.
"""

import gzip
import json
import re
from urllib.parse import urlsplit

import pytest

import axe_audit

BOX = "#site-search-input"
STATUS = "#site-search-status"
RESULT_LINKS = ".site-search-list .site-search-link"
DOCUMENTS = "assets/search-data.json"
# The documents are fetched on the first search; a budget keeps them from growing
# unnoticed (the whole site's text is about 70 kB compressed).
DOCUMENTS_BUDGET_BYTES = 150_000
LAZY_FILES = ("search-data.json", "lunr.min.js")
MARKUP = r"</?(?:p|a|code|span|em|strong|div|pre|li|h\d)\b[^>]*>|\bclass=\"|&[a-z]+;|\\[(\[]"


def search(page, text: str) -> list[str]:
    """Type `text` into the box (reached with "/") and return the result links' paths."""
    page.keyboard.press("/")
    page.keyboard.type(text)
    page.wait_for_function(
        "text => document.querySelector('#site-search-status').textContent.includes(text)",
        arg=text)
    return [urlsplit(href).path + (f"#{urlsplit(href).fragment}" if urlsplit(href).fragment
                                   else "")
            for href in page.locator(RESULT_LINKS).evaluate_all("links => links.map(a => a.href)")]


@pytest.fixture(scope="module")
def documents(site) -> list[dict]:
    return json.loads((site.root / DOCUMENTS).read_text())


def test_documents_are_plain_text_sections_and_small(site, documents):
    raw = (site.root / DOCUMENTS).read_bytes()
    assert len(gzip.compress(raw)) < DOCUMENTS_BUDGET_BYTES
    pages = {urlsplit(doc["url"]).path for doc in documents}
    assert pages == set(site.pages), "every page, and only pages, is searchable"
    assert len(documents) > 2 * len(pages), "pages are split into their sections"
    for doc in documents:
        # No markup, entities or TeX in the text the excerpts show (a tag written as
        # inline code, `<node>`, is text).
        assert not re.search(MARKUP, doc["text"]), doc
        assert doc["text"] or doc["code"], doc


def test_every_result_leads_to_a_heading_that_exists(site, documents):
    missing = []
    for doc in documents:
        parts = urlsplit(doc["url"])
        html = (site.root / parts.path.lstrip("/") / "index.html").read_text()
        if parts.fragment and f'id="{parts.fragment}"' not in html:
            missing.append(doc["url"])
    assert not missing, "search results pointing at anchors the page lacks:\n" + "\n".join(missing)


def test_ackermann_lists_practice_5_first_and_loads_search_only_when_used(browser_page):
    visit = browser_page.visit("/")
    assert not [r.url for r in visit.responses if r.url.endswith(LAZY_FILES)], \
        "lunr and the documents must not be part of a page's first load"

    found = search(browser_page.page, "Ackermann")
    assert found[0].startswith("/practice-5/"), found
    assert "/practice-5/ackermann-geometry/" in found, found
    assert sum(path.startswith("/practice-5/") for path in found[:5]) >= 4, found
    first = browser_page.page.locator(".site-search-hit").first
    assert first.locator("mark").first.inner_text().lower() == "ackermann"
    assert {r.url.rsplit("/", 1)[-1] for r in visit.responses} >= set(LAZY_FILES)
    assert not visit.problems(), visit.problems()


def test_a_query_without_matches_says_so(browser_page):
    def no_match(page):
        search(page, "qzxwvj")

    visit = browser_page.visit("/practice-1/modelling/", then=no_match)
    page = browser_page.page
    assert page.inner_text(STATUS).startswith("No results for “qzxwvj”")
    assert page.locator(RESULT_LINKS).count() == 0
    assert not visit.problems(), visit.problems()


def test_enter_opens_the_first_result_at_its_heading(browser_page):
    target = {}

    def search_and_press_enter(page):
        target["path"] = search(page, "knuckle limit")[0]
        with page.expect_navigation():
            page.keyboard.press("Enter")

    visit = browser_page.visit("/reference/glossary/", then=search_and_press_enter)
    page = browser_page.page
    path, _, anchor = target["path"].partition("#")
    assert urlsplit(page.url).path == path
    assert anchor and urlsplit(page.url).fragment == anchor, target
    assert page.locator(f"#{anchor}").is_visible()
    assert page.title(), "the result's page loaded"
    assert not visit.problems(), visit.problems()


def test_keyboard_slash_arrows_and_escape(browser_page):
    browser_page.visit("/reference/troubleshooting/")
    page = browser_page.page
    found = search(page, "inertia")
    assert page.evaluate("document.activeElement.id") == BOX.lstrip("#"), "/ focuses the box"
    assert page.input_value(BOX) == "inertia", "the / that focused the box is not typed"
    assert found

    page.keyboard.press("ArrowDown")
    assert page.evaluate("document.activeElement.className") == "site-search-link"
    page.keyboard.press("ArrowUp")
    assert page.evaluate("document.activeElement.id") == BOX.lstrip("#")

    page.keyboard.press("Escape")
    assert page.locator(RESULT_LINKS).first.is_hidden(), "Escape closes the results"
    assert page.input_value(BOX) == "inertia", "Escape keeps the query"
    assert page.evaluate("document.activeElement.id") == BOX.lstrip("#")

    page.keyboard.type("/x")
    assert page.input_value(BOX) == "inertia/x", "a / typed in the box stays in it"


def test_identifiers_in_code_are_found(browser_page):
    browser_page.visit("/")
    page = browser_page.page
    assert search(page, "load_package")
    code_only = page.locator(".site-search-excerpt", has_text="In the code:")
    assert code_only.count(), "no section found by load_package in its code alone"
    assert code_only.first.locator("mark").inner_text() == "load_package"


def test_open_search_has_no_serious_accessibility_problems(site, browser_page):
    axe_url = site.node_module_url(axe_audit.AXE)

    def open_results(page):
        search(page, "friction")
        page.add_script_tag(url=axe_url)

    browser_page.visit("/practice-2/friction/", then=open_results)
    axe_audit.start(browser_page.page, "/practice-2/friction/",
                    context={"include": [[".site-header"]]})
    report = [f"[{v['impact']}] {v['id']}: {v['help']} {v['targets'][:3]}"
              for v in axe_audit.serious(axe_audit.collect(browser_page.page))]
    assert not report, "\n".join(report)
