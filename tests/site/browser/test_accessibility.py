"""No page has a serious or critical accessibility problem that axe-core can find.

Every page is audited as it is loaded for the session (conftest.py, `site_visits`; what
an audit covers is in axe_audit.py). The colours of code highlighting, left out of those
audits, are checked here all at once.
"""

import re

import pytest

import axe_audit

# Shown per violation; the rest are counted.
TARGETS_SHOWN = 5

CODE_BLOCK = re.compile(r'<pre class="highlight"[^>]*><code>(.*?)</code></pre>', re.S)
TOKEN_CLASS = re.compile(r'<span class="([^"]+)">')

# Replaces the text of the page's first code block with one word per highlighting class.
SHOW_EVERY_TOKEN_CLASS = """(classes) => {
    const code = document.querySelector("pre.highlight > code");
    code.replaceChildren("plain ");
    for (const name of classes) {
        const token = document.createElement("span");
        token.className = name;
        token.textContent = `token ${name} `;
        code.append(token);
    }
    code.parentElement.id = "every-token-class";
}"""
EVERY_TOKEN_CLASS = {"include": [["#every-token-class"]]}
CONTRAST_ONLY = {"runOnly": ["color-contrast"]}


@pytest.fixture(scope="module")
def axe(site, browser_page):
    """axe(path, context=None, options=None, prepare=None) -> the violations of one page
    (every impact); `prepare(page)` runs on the loaded page first. `context` and
    `options` are axe.run's; the defaults are those of the site audit."""
    axe_url = site.node_module_url(axe_audit.AXE)

    def run(path, context=None, options=None, prepare=None):
        def inject(page):
            if prepare is not None:
                prepare(page)
            page.add_script_tag(url=axe_url)

        visit = browser_page.visit(path, then=inject)
        assert visit.status == 200, f"{path}: HTTP {visit.status}"
        axe_audit.start(browser_page.page, path, context, options)
        return axe_audit.collect(browser_page.page)

    return run


def describe(path: str, violation: dict) -> str:
    targets = violation["targets"]
    lines = targets[:TARGETS_SHOWN]
    if len(targets) > TARGETS_SHOWN:
        lines.append(f"... and {len(targets) - TARGETS_SHOWN} more")
    return (f"{path}: [{violation['impact']}] {violation['id']}: {violation['help']}\n"
            + "".join(f"      {line}\n" for line in lines))


def test_no_serious_accessibility_violations(site_visits):
    report = [describe(path, v) for path, visit in site_visits.items()
              for v in axe_audit.serious(visit.axe_violations)]
    assert not report, (f"{len(report)} serious or critical accessibility violations "
                        "(page: [impact] rule: what is wrong, then the elements):\n"
                        + "".join(report))


def pages_with_code(site) -> dict[str, list[str]]:
    """Path -> the HTML inside each highlighted code block of that page."""
    blocks = {path: CODE_BLOCK.findall((site.root / path.lstrip("/") / "index.html").read_text())
              for path in site.pages}
    return {path: found for path, found in blocks.items() if found}


def test_every_code_highlighting_colour_has_enough_contrast(site, axe):
    code = pages_with_code(site)
    classes = sorted({name for blocks in code.values() for block in blocks
                      for name in TOKEN_CLASS.findall(block)})
    assert classes, "no highlighted code found on any page"
    page = next(iter(code))
    violations = axe(page, context=EVERY_TOKEN_CLASS, options=CONTRAST_ONLY,
                     prepare=lambda p: p.evaluate(SHOW_EVERY_TOKEN_CLASS, classes))
    report = [describe(page, v) for v in axe_audit.serious(violations)]
    assert not report, "code highlighting colours with too little contrast:\n" + "".join(report)


def test_axe_reports_an_image_without_alt_text(axe):
    def add_image_without_alt(page):
        page.evaluate("""() => {
            const img = document.createElement("img");
            img.src = "data:image/gif;base64,R0lGODlhAQABAAAAACw=";
            document.querySelector("main").append(img);
        }""")

    found = axe("/", prepare=add_image_without_alt)
    assert [v["id"] for v in axe_audit.serious(found)] == ["image-alt"], found


def test_axe_reports_a_code_colour_without_contrast(site, axe):
    def pale_keywords(page):
        page.add_style_tag(content=".highlight .k { color: #d0d7de; }")
        page.evaluate(SHOW_EVERY_TOKEN_CLASS, ["k"])

    page = next(iter(pages_with_code(site)))
    found = axe(page, context=EVERY_TOKEN_CLASS, options=CONTRAST_ONLY, prepare=pale_keywords)
    assert [v["id"] for v in found] == ["color-contrast"], found
