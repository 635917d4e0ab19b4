"""The built site as a reader's browser sees it.

`make test` builds the site into _site/ first (`make site`); these fixtures serve that
folder on a free localhost port and drive Debian's Chromium through Playwright. One
server, one browser and two tabs serve the whole session:

- `site`: the served _site (`site.root`, `site.base_url`, `site.url(path)`, `site.pages`:
  every page of the built sitemap.xml). The server also hands test tools from
  node_modules to the browser, at `site.node_module_url("axe-core/axe.min.js")`;
- `site_visits`: every page of the site loaded once and audited by axe-core
  (axe_audit.py), path -> `Visit`, for the checks of every page (errors, requests,
  weight, images, accessibility);
- `browser_page`: the reused page; `browser_page.visit(path)` loads a page, waits until
  its fonts and requests have settled and returns a `Visit` with what went wrong
  (console errors, failed requests, error responses, requests that left the machine)
  and every response it received. `browser_page.page` is the Playwright page itself,
  for tests that click, type or run scripts; `visit(path, then=...)` runs such steps
  after the load, and their errors and requests are recorded with the page's.
  `second_browser_page` is another tab like it, for work that can overlap;
  `phone` is a tab of a module's own, 390 × 844 (PHONE);
- `link_check`: html-proofer over _site (html_proofer.py), started with the first
  browser test so that it runs on one core while the browser uses the other.

Nothing is downloaded: Playwright launches /usr/bin/chromium (or $CHROMIUM), and every
host other than the local server is unresolvable inside the browser, so a page that
reaches for a CDN fails its tests instead of working only online.
"""

from __future__ import annotations

import os
import shutil
import time
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable
from urllib.parse import urljoin, urlsplit

import pytest
from playwright.sync_api import Page, sync_playwright

import axe_audit
from html_proofer import HtmlProofer
from jekyll import newer_sources
from site_server import NODE_MODULES_URL, SiteServer

from repository import ROOT
# $SW2SIM_SITE points the tests at a site built elsewhere (several builds side by side).
SITE = Path(os.environ.get("SW2SIM_SITE") or ROOT / "_site")
NODE_MODULES = ROOT / "node_modules"
SITEMAP_NS = {"s": "http://www.sitemaps.org/schemas/sitemap/0.9"}

CHROMIUM_ARGS = [
    "--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
    "--disable-component-update", "--disable-sync", "--no-first-run", "--disable-dev-shm-usage",
]
# A page that settles takes well under a second here; this only bounds a hung one.
SETTLE_TIMEOUT_S = 10.0
PHONE = {"width": 390, "height": 844}   # CSS pixels of the phone the tests use

IMAGES_JS = """() => Array.from(document.images, img => ({
    src: img.currentSrc || img.src,
    loading: img.getAttribute("loading") || "",
    top: img.getBoundingClientRect().top + window.scrollY,
    in_main: img.closest("main") !== null,
    fetched: performance.getEntriesByName(img.currentSrc || img.src, "resource").length > 0,
}))"""


# ---- the built site -------------------------------------------------------------------


def built_site() -> Path:
    """_site, or a test failure that says how to make it (missing, or older than a source)."""
    sitemap = SITE / "sitemap.xml"
    if not sitemap.is_file():
        pytest.fail("_site/ has no sitemap.xml: build the site first with `make site` "
                    "(`make test` does it).", pytrace=False)
    newer = newer_sources(SITE)
    if newer:
        names = ", ".join(str(f.relative_to(ROOT)) for f in newer[:5])
        more = f" and {len(newer) - 5} more" if len(newer) > 5 else ""
        pytest.fail(f"_site/ is older than {names}{more}: rebuild it with `make site` "
                    "(`make test` does it).", pytrace=False)
    return SITE


def sitemap_paths(root: Path) -> list[str]:
    """The path of every page in the built sitemap.xml (jekyll-sitemap), sorted."""
    tree = ET.parse(root / "sitemap.xml")
    locations = [loc.text.strip() for loc in tree.findall("s:url/s:loc", SITEMAP_NS)]
    return sorted(urlsplit(loc).path for loc in locations)


@dataclass(frozen=True)
class Site:
    root: Path
    base_url: str
    pages: list[str]

    def url(self, path: str) -> str:
        return urljoin(self.base_url, path)

    def is_local(self, url: str) -> bool:
        return url.startswith(self.base_url)

    def is_test_tool(self, url: str) -> bool:
        return url.startswith(urljoin(self.base_url, NODE_MODULES_URL))

    def node_module_url(self, path: str) -> str:
        """The URL of node_modules/<path> (a test tool, not part of the site)."""
        if not (NODE_MODULES / path).is_file():
            pytest.fail(f"node_modules/{path} is missing: run `make setup` (npm ci).",
                        pytrace=False)
        return urljoin(self.base_url, NODE_MODULES_URL + path)


@pytest.fixture(scope="session")
def site():
    """The built _site, served on 127.0.0.1 at a free port for the whole session
    (tests/site/browser/site_server.py: compressed and cacheable as on GitHub Pages)."""
    root = built_site()
    server = SiteServer(root, NODE_MODULES)
    try:
        yield Site(root, server.base_url, sitemap_paths(root))
    finally:
        server.close()


# ---- the browser ----------------------------------------------------------------------


def chromium_path() -> str:
    path = os.environ.get("CHROMIUM") or shutil.which("chromium") or "/usr/bin/chromium"
    if not Path(path).is_file():
        pytest.fail("Chromium not found: run `make setup` (it installs Debian's `chromium`), "
                    "or point $CHROMIUM at a Chromium binary.", pytrace=False)
    return path


@dataclass
class Response:
    url: str
    status: int
    resource_type: str  # Playwright's: document, stylesheet, script, font, image, fetch, ...
    body_bytes: int


@dataclass
class Image:
    """An <img> of a visited page, as laid out in the window at the end of the load."""

    src: str  # absolute URL
    loading: str  # the `loading` attribute ("" when absent)
    top: float  # distance from the top of the page, in CSS pixels
    in_main: bool  # part of the page's own content (not header, sidebar or footer)
    fetched: bool  # requested by the end of the load


@dataclass
class Visit:
    """What loading one page did."""

    path: str
    status: int | None = None
    console_errors: list[str] = field(default_factory=list)
    page_errors: list[str] = field(default_factory=list)
    failed_requests: list[str] = field(default_factory=list)
    error_responses: list[str] = field(default_factory=list)
    foreign_requests: list[str] = field(default_factory=list)
    responses: list[Response] = field(default_factory=list)
    images: list[Image] = field(default_factory=list)
    viewport_height: int = 0
    axe_violations: list[dict] = field(default_factory=list)  # see axe_audit.py

    def problems(self) -> list[str]:
        """Every way the page failed to load cleanly, one line each."""
        lines = [] if self.status == 200 else [f"HTTP status {self.status}"]
        lines += [f"console error: {text}" for text in self.console_errors]
        lines += [f"uncaught exception: {text}" for text in self.page_errors]
        lines += [f"request failed: {text}" for text in self.failed_requests]
        lines += [f"error response: {text}" for text in self.error_responses]
        lines += [f"request off the local site: {url}" for url in self.foreign_requests]
        return lines


class BrowserPage:
    """One Playwright page, reused for every visit; records what each visit does."""

    def __init__(self, page, site: Site):
        self.page = page
        self.site = site
        self._visit = Visit("")
        # A request belongs to the document that made it: one the last page started just
        # before the next visit (an image a viewport change asked for) and that the
        # navigation then aborted is not the new page's failure. The old document lives,
        # and can still ask for things, until the new one commits (framenavigated).
        self._document_visit = self._visit
        self._owner: dict = {}
        self._pending: set = set()
        page.on("console", self._on_console)
        page.on("pageerror", lambda error: self._visit.page_errors.append(str(error)))
        page.on("request", self._on_request)
        page.on("framenavigated", self._on_frame_navigated)
        page.on("requestfailed", self._on_request_failed)
        page.on("requestfinished", self._on_request_finished)
        page.on("response", self._on_response)

    def visit(self, path: str, then: Callable[[Page], object] | None = None) -> Visit:
        """Load `path` (relative to the site), run `then(page)` if given, and wait until
        the page has settled: the load event, web fonts ready and no request in flight."""
        self._settle()
        # Chromium draws a tab in the background only now and then: a canvas screenshot
        # there waits seconds for a frame. The tab a test works in is the one in front.
        self.page.bring_to_front()
        self._visit = visit = Visit(path)
        response = self.page.goto(self.site.url(path), wait_until="load")
        visit.status = response.status if response else None
        self.page.evaluate("document.fonts.ready.then(() => true)")
        if then is not None:
            then(self.page)
        self._settle()
        visit.viewport_height = self.page.viewport_size["height"]
        visit.images = [Image(**image) for image in self.page.evaluate(IMAGES_JS)]
        return visit

    def _settle(self) -> None:
        deadline = time.monotonic() + SETTLE_TIMEOUT_S
        while self._pending and time.monotonic() < deadline:
            self.page.wait_for_timeout(20)
        if self._pending:
            stuck = ", ".join(sorted(r.url for r in self._pending))
            pytest.fail(f"{self._visit.path}: requests still running after "
                        f"{SETTLE_TIMEOUT_S:.0f} s: {stuck}", pytrace=False)

    def _on_console(self, message) -> None:
        if message.type == "error":
            where = message.location.get("url", "")
            text = f"{message.text} ({where})" if where else message.text
            self._visit.console_errors.append(text)

    def _on_frame_navigated(self, frame) -> None:
        if frame == self.page.main_frame:
            self._document_visit = self._visit

    def _on_request(self, request) -> None:
        main_document = request.is_navigation_request() and request.frame == self.page.main_frame
        self._owner[request] = self._visit if main_document else self._document_visit
        if urlsplit(request.url).scheme in ("http", "https", "ws", "wss"):
            self._pending.add(request)
            if not self.site.is_local(request.url):
                self._visit.foreign_requests.append(request.url)

    def _on_request_finished(self, request) -> None:
        self._pending.discard(request)
        self._owner.pop(request, None)

    def _on_request_failed(self, request) -> None:
        self._pending.discard(request)
        owner = self._owner.pop(request, self._visit)
        if self.site.is_local(request.url):
            owner.failed_requests.append(f"{request.url} ({request.failure})")

    def _on_response(self, response) -> None:
        if not self.site.is_local(response.url) or self.site.is_test_tool(response.url):
            return
        if response.status >= 400:
            self._visit.error_responses.append(f"{response.status} {response.url}")
        length = response.headers.get("content-length")
        self._visit.responses.append(Response(response.url, response.status,
                                              response.request.resource_type,
                                              int(length) if length else 0))


@pytest.fixture(scope="session")
def browser():
    """Debian's Chromium, headless, for the whole session. Every host but 127.0.0.1 is
    unresolvable in it: the site must work offline."""
    with sync_playwright() as playwright:
        browser = playwright.chromium.launch(
            executable_path=chromium_path(),
            args=CHROMIUM_ARGS + ["--host-resolver-rules=MAP * ~NOTFOUND, EXCLUDE 127.0.0.1"])
        try:
            yield browser
        finally:
            browser.close()


@pytest.fixture(scope="session")
def browser_context(browser):
    """One desktop-sized browsing context (shared cache) for the session's pages."""
    context = browser.new_context(viewport={"width": 1280, "height": 800})
    context.set_default_timeout(SETTLE_TIMEOUT_S * 1000)
    try:
        yield context
    finally:
        context.close()


@pytest.fixture(scope="session")
def browser_page(browser_context, site) -> BrowserPage:
    """The page every browser test uses."""
    return BrowserPage(browser_context.new_page(), site)


@pytest.fixture(scope="session")
def second_browser_page(browser_context, site) -> BrowserPage:
    """A second tab, for work that can overlap: each tab has its own renderer process, so
    a script can run in one while the next page loads in the other, on another core."""
    return BrowserPage(browser_context.new_page(), site)


@pytest.fixture(scope="session")
def site_visits(site, browser_page, second_browser_page) -> dict[str, Visit]:
    """Every page of the sitemap, loaded once and audited by axe: path -> Visit. Two
    tabs take turns: while axe works on a page in one, the next page loads in the other."""
    axe_url = site.node_module_url(axe_audit.AXE)
    tabs = [browser_page, second_browser_page]
    visits: dict[str, Visit] = {}
    auditing: dict[int, Visit] = {}  # tab number -> the visit axe is working on there
    for number, path in enumerate(site.pages):
        tab = number % 2
        if tab in auditing:
            auditing.pop(tab).axe_violations = axe_audit.collect(tabs[tab].page)
        visit = tabs[tab].visit(path, then=lambda page: page.add_script_tag(url=axe_url))
        axe_audit.start(tabs[tab].page, path)
        visits[path] = visit
        auditing[tab] = visit
    for tab, visit in auditing.items():
        visit.axe_violations = axe_audit.collect(tabs[tab].page)
    return visits


@pytest.fixture(scope="session", autouse=True)
def link_check(request) -> HtmlProofer | None:
    """html-proofer over _site, started before the first browser test when test_links.py
    is among the tests to run (it takes seconds, and has a core of its own meanwhile)."""
    if not any(item.path.name == "test_links.py" for item in request.session.items):
        yield None
        return
    check = HtmlProofer(built_site())
    try:
        yield check
    finally:
        check.stop()


@pytest.fixture(scope="module")
def phone(browser, site):
    """A tab the size of a phone (390 × 844 CSS pixels)."""
    context = browser.new_context(viewport=PHONE)
    context.set_default_timeout(SETTLE_TIMEOUT_S * 1000)
    try:
        yield BrowserPage(context.new_page(), site)
    finally:
        context.close()
