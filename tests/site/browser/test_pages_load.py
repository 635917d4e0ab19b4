"""Every page of the built site loads cleanly in a browser, from the local server alone."""

from pathlib import Path

# Folders of files the pages use, not pages.
NOT_PAGES = ("assets", "examples", "media")


def test_sitemap_lists_every_page(site):
    """The sitemap is what the browser tests walk: it must hold the whole site."""
    built = []
    for index in site.root.rglob("index.html"):
        folder = index.parent.relative_to(site.root)
        if folder == Path("."):
            built.append("/")
        elif folder.parts[0] not in NOT_PAGES:
            built.append(f"/{folder.as_posix()}/")
    assert site.pages == sorted(built), "sitemap.xml and the built pages differ"


def test_every_page_loads_without_errors(site, site_visits):
    problems = {path: visit.problems() for path, visit in site_visits.items() if visit.problems()}
    report = "\n".join(f"{path}:\n  " + "\n  ".join(lines) for path, lines in problems.items())
    assert not problems, (f"{len(problems)} of {len(site.pages)} pages did not load cleanly:\n"
                          + report)


def test_a_missing_page_is_reported(browser_page):
    problems = browser_page.visit("/no-such-page/").problems()
    assert "HTTP status 404" in problems
    assert any(line.startswith("error response: 404 ") for line in problems)


def test_a_missing_script_and_a_cdn_request_are_reported(site, browser_page):
    def load_broken_things(page):
        page.evaluate("""() => {
            const script = document.createElement("script");
            script.src = "/assets/js/no-such-script.js";
            document.head.append(script);
            return fetch("https://cdn.example.com/library.js").catch(() => null);
        }""")

    visit = browser_page.visit("/", then=load_broken_things)
    assert visit.error_responses == [f"404 {site.url('/assets/js/no-such-script.js')}"]
    assert visit.foreign_requests == ["https://cdn.example.com/library.js"]
    assert visit.console_errors, "the failed script load printed no console error"
