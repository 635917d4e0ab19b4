"""Code blocks, outputs and tables fit the window (issue 16).

On a laptop screen (1366 × 900) the code blocks take the whole width of the page column
while the prose keeps its line length (assets/css/main.css: --measure, --wide), so that
almost no code block needs a scroll bar. What a block printed (its output box,
_plugins/code_outputs.rb) wraps a line too long for the box, indented under its start,
so that the end of a `sw2sim check` line ("Fix: ...") is read without scrolling, on a
laptop and on a phone. At every width, from a phone up, the page itself never scrolls
sideways and no table is cut off: a table wider than the column scrolls in its own box.
"""

from __future__ import annotations

import pytest

LAPTOP = {"width": 1366, "height": 900}
PHONE = {"width": 390, "height": 844}
SIZES = [PHONE, {"width": 768, "height": 1024}, LAPTOP]
# At most this share of the site's code blocks may scroll sideways at 1366 px.
MOST_SCROLLING = 0.05
# At most this share of the site's output boxes may scroll sideways, by window width.
MOST_OUTPUTS_SCROLLING = {1366: 0.05, 390: 0.20}

CODE_BLOCKS = """() => Array.from(document.querySelectorAll('.highlight pre'), pre => {
    const lines = pre.textContent.split('\\n');
    const longest = lines.reduce((a, b) => (b.length > a.length ? b : a), '');
    return {scrolls: pre.scrollWidth > pre.clientWidth + 1, overflow: pre.scrollWidth - pre.clientWidth,
            characters: longest.length, line: longest.trim().slice(0, 90)};
})"""

# Each output box of the page (open or folded: a folded one is opened to be measured),
# whether its text runs wider than the box, and its longest line.
OUTPUT_BOXES = """() => Array.from(document.querySelectorAll('details.code-output'), details => {
    details.open = true;
    const box = details.querySelector('.code-output-text');
    const lines = box.textContent.split('\\n');
    const longest = lines.reduce((a, b) => (b.length > a.length ? b : a), '');
    return {scrolls: box.scrollWidth > box.clientWidth + 1, overflow: box.scrollWidth - box.clientWidth,
            characters: longest.length, line: longest.trim().slice(0, 90)};
})"""

# Every table of the page: fits in the page column, or its nearest ancestor that scrolls
# sideways shows all of it (scrollWidth) and itself fits the window.
TABLES = """() => {
    const column = document.querySelector('.page-body').getBoundingClientRect();
    return Array.from(document.querySelectorAll('main table'), (table, index) => {
        const box = table.getBoundingClientRect();
        if (box.right <= column.right + 1 && box.left >= column.left - 1) return null;
        for (let e = table.parentElement; e && e.tagName !== 'MAIN'; e = e.parentElement) {
            if (!/auto|scroll/.test(getComputedStyle(e).overflowX)) continue;
            const own = e.getBoundingClientRect();
            if (e.scrollWidth + 1 >= table.offsetWidth && own.right <= innerWidth) return null;
            break;
        }
        return `table ${index + 1} (${Math.round(box.width)} px wide, right edge at `
             + `${Math.round(box.right)} px, column ends at ${Math.round(column.right)} px)`;
    }).filter(Boolean);
}"""


def with_viewport(browser_page, size):
    page = browser_page.page
    page.set_viewport_size(size)
    return page


def test_few_code_blocks_scroll_sideways_on_a_laptop(browser_page, site):
    """At 1366 × 900, at most 5 % of the code blocks over every page scroll sideways;
    the ones that still do are printed with their longest line."""
    page = with_viewport(browser_page, LAPTOP)
    try:
        blocks = []
        for path in site.pages:
            browser_page.visit(path)
            blocks += [(path, block) for block in page.evaluate(CODE_BLOCKS)]
    finally:
        page.set_viewport_size({"width": 1280, "height": 800})
    scrolling = [(path, block) for path, block in blocks if block["scrolls"]]
    assert len(blocks) > 50, f"only {len(blocks)} code blocks found: is the site built?"
    share = len(scrolling) / len(blocks)
    print(f"\n{len(scrolling)} of {len(blocks)} code blocks ({share:.1%}) scroll sideways at 1366 px:")
    for path, block in sorted(scrolling, key=lambda item: -item[1]["overflow"]):
        print(f"  {path}: {block['characters']} characters, {block['overflow']} px hidden: "
              f"{block['line']}")
    assert share <= MOST_SCROLLING, (
        f"{len(scrolling)} of {len(blocks)} code blocks scroll sideways at 1366 px: "
        + "; ".join(f"{path} ({block['characters']} ch)" for path, block in scrolling))


@pytest.mark.parametrize("size", [LAPTOP, PHONE], ids=["1366", "390"])
def test_few_output_boxes_scroll_sideways(browser_page, site, size):
    """At 1366 × 900 at most 5 %, at 390 × 844 at most 20 % of the output boxes over every
    page scroll sideways (a long printed line wraps instead); the ones that still do are
    printed with their longest line."""
    page = with_viewport(browser_page, size)
    try:
        boxes = []
        for path in site.pages:
            browser_page.visit(path)
            boxes += [(path, box) for box in page.evaluate(OUTPUT_BOXES)]
    finally:
        page.set_viewport_size({"width": 1280, "height": 800})
    assert len(boxes) > 50, f"only {len(boxes)} output boxes found: is the site built?"
    scrolling = [(path, box) for path, box in boxes if box["scrolls"]]
    share = len(scrolling) / len(boxes)
    print(f"\n{len(scrolling)} of {len(boxes)} output boxes ({share:.1%}) scroll sideways "
          f"at {size['width']} px:")
    for path, box in sorted(scrolling, key=lambda item: -item[1]["overflow"]):
        print(f"  {path}: {box['characters']} characters, {box['overflow']} px hidden: {box['line']}")
    assert share <= MOST_OUTPUTS_SCROLLING[size["width"]], (
        f"{len(scrolling)} of {len(boxes)} output boxes scroll sideways at {size['width']} px: "
        + "; ".join(f"{path} ({box['characters']} ch)" for path, box in scrolling))


def test_a_long_output_line_wraps_under_its_start(browser_page):
    """On a phone a `sw2sim check` line of "Your own model" wraps: its "Fix: ..." is inside
    the box, and the lines after the first are indented under the line's start."""
    page = with_viewport(browser_page, PHONE)
    try:
        browser_page.visit("/reference/your-own-model/")
        line = page.evaluate("""() => {
            const line = [...document.querySelectorAll('.code-output-line')]
                .find(span => /\\[[a-z-]+\\] .* Fix: /.test(span.textContent));
            if (!line) return null;
            const box = line.closest('.code-output-text').getBoundingClientRect();
            const rects = [...line.getClientRects()];
            const range = document.createRange();
            range.selectNodeContents(line.firstChild);
            // Where each wrapped line of the text starts: the leftmost of its pieces.
            const starts = new Map();
            for (const r of range.getClientRects()) {
                const top = Math.round(r.top);
                starts.set(top, Math.min(starts.get(top) ?? Infinity, Math.round(r.left)));
            }
            const lefts = [...new Set(starts.values())].sort((a, b) => a - b);
            return {characters: line.textContent.length, right: Math.max(...rects.map(r => r.right)),
                    boxRight: box.right, height: rects[0].height, lefts,
                    lineHeight: parseFloat(getComputedStyle(line).lineHeight),
                    indent: parseFloat(getComputedStyle(line).paddingLeft)};
        }""")
    finally:
        page.set_viewport_size({"width": 1280, "height": 800})
    assert line, "no `sw2sim check` line with a Fix: in an output box of /reference/your-own-model/"
    assert line["right"] <= line["boxRight"], f"the line runs out of its box: {line}"
    assert line["height"] >= 3 * line["lineHeight"], f"a {line['characters']}-character line on a phone " \
        f"takes fewer than three lines: {line}"
    # The first piece starts at the line's start; the wrapped pieces one indent further in.
    assert len(line["lefts"]) == 2 and line["lefts"][1] - line["lefts"][0] == \
        pytest.approx(line["indent"], abs=1), line


@pytest.mark.parametrize("size", SIZES, ids=[str(size["width"]) for size in SIZES])
def test_no_page_scrolls_sideways_and_no_table_is_cut(browser_page, site, size):
    """At 390, 768 and 1366 px wide no page is wider than the window, and every table fits
    its column or scrolls whole in its own box."""
    page = with_viewport(browser_page, size)
    wide_pages, cut_tables = [], []
    try:
        for path in site.pages:
            browser_page.visit(path)
            width = page.evaluate("document.scrollingElement.scrollWidth")
            if width > size["width"]:
                wide_pages.append(f"{path} ({width} px)")
            cut_tables += [f"{path}: {table}" for table in page.evaluate(TABLES)]
    finally:
        page.set_viewport_size({"width": 1280, "height": 800})
    assert not wide_pages, f"pages wider than {size['width']} px: {wide_pages}"
    assert not cut_tables, f"tables cut off at {size['width']} px: {cut_tables}"


def test_a_blocks_output_is_as_wide_as_the_block(browser_page):
    """At 1366 × 900 the output under a block lines up with the block's both edges."""
    page = with_viewport(browser_page, LAPTOP)
    try:
        browser_page.visit("/practice-1/modelling/")
        pairs = page.evaluate("""() => [...document.querySelectorAll('details.code-output')]
            .map(out => [out.previousElementSibling.getBoundingClientRect(),
                         out.getBoundingClientRect()])
            .map(([code, out]) => [code.left, code.right, out.left, out.right])""")
    finally:
        page.set_viewport_size({"width": 1280, "height": 800})
    assert pairs, "no block output on /practice-1/modelling/"
    for code_left, code_right, out_left, out_right in pairs:
        assert abs(code_left - out_left) < 1 and abs(code_right - out_right) < 1, pairs
