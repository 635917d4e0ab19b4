"""Every box fits the screen it is read on (issues 16 and 35).

Every page is loaded once at each of 1366 × 900 (a laptop), 390 × 844 and 360 × 780 (two
phones), and every box of it measured in one script (BOXES): tables, code blocks, output
(what a python block printed, and ```text blocks), displayed formulas and figures. The
tests below then hold each kind to its rule, and a failure names the page, the box and
the width:

- no page is wider than the window;
- tables: none wider than its column at 1366 px; on a phone a table fits, or shows each
  row as a card (_plugins/tables.rb `table-cards`), or scrolls in its own box with its
  first column pinned (`table-pinned`) and a shadow where more lies;
- code: at most 1 % of the code blocks scroll sideways at 1366 px; one that scrolls, at
  any width, shows it (a shadow at the edge it continues beyond), has its Wrap button,
  and its Copy button stays in view;
- output never scrolls sideways: a long line wraps, under its own indentation;
- formulas fit, or scroll in their own box with a tab stop and the shadow;
- figures are no wider than the column.
"""

from __future__ import annotations

import pytest

SIZES = {1366: {"width": 1366, "height": 900}, 390: {"width": 390, "height": 844},
         360: {"width": 360, "height": 780}}
PHONES = [390, 360]
# At most this share of the site's code blocks may scroll sideways at 1366 px.
MOST_SCROLLING = 0.01
# A box may overrun its limit by this much (sub-pixel layout).
SLACK = 1

# One script measures every box of the page as it is laid out now. Output boxes folded
# shut are opened first, so that they have a width.
BOXES = """() => {
    const column = document.querySelector('.page-body').getBoundingClientRect();
    const box = e => e.getBoundingClientRect();
    const scrolls = e => e.scrollWidth > e.clientWidth + 1;
    const longest = text => text.split('\\n').reduce((a, b) => (b.length > a.length ? b : a), '').trim();
    document.querySelectorAll('details.code-output').forEach(d => { d.open = true; });
    const tables = [...document.querySelectorAll('main table')].map((table, i) => {
        const holder = table.closest('.table-box');
        const wrap = table.closest('.table-wrap');
        const first = table.querySelector('tbody tr > :first-child');
        return {index: i + 1, head: (table.querySelector('th') || {}).textContent || '',
                width: Math.round(box(table).width), right: box(table).right,
                mode: holder ? (holder.classList.contains('table-cards') ? 'cards'
                               : holder.classList.contains('table-pinned') ? 'pinned' : '') : '',
                display: getComputedStyle(table).display,
                wrapRight: wrap ? box(wrap).right : null, wrapScrolls: wrap ? scrolls(wrap) : false,
                wrapFocus: wrap ? wrap.getAttribute('tabindex') : null,
                pinned: first ? getComputedStyle(first).position === 'sticky' : false,
                cue: holder ? holder.classList.contains('more-right') : false,
                emptyHeaders: [...table.querySelectorAll('th')].filter(th => !th.textContent.trim()).length};
    });
    const code = [...document.querySelectorAll('div.highlighter-rouge:not(.language-text) pre')].map((pre, i) => {
        const block = pre.closest('div.highlighter-rouge');
        const copy = block.querySelector('.copy-button');
        return {index: i + 1, scrolls: scrolls(pre), hidden: pre.scrollWidth - pre.clientWidth,
                line: longest(pre.textContent).slice(0, 80), right: box(block).right,
                cue: block.classList.contains('more-right'), wrap: !!block.querySelector('.wrap-button'),
                copy: copy ? box(copy).right <= box(block).right + 1 && box(copy).width > 0 : false};
    });
    const outputs = [...document.querySelectorAll('.code-output-text, div.language-text pre')].map((out, i) => ({
        index: i + 1, kind: out.matches('pre') ? 'text block' : 'output', scrolls: scrolls(out),
        hidden: out.scrollWidth - out.clientWidth, line: longest(out.textContent).slice(0, 80)}));
    const formulas = [...document.querySelectorAll('.katex-display')].map((f, i) => ({
        index: i + 1, scrolls: scrolls(f), right: box(f).right, focus: f.getAttribute('tabindex'),
        cue: f.classList.contains('more-right'),
        tex: ((f.querySelector('annotation') || {}).textContent || '').slice(0, 60)}));
    const figures = [...document.querySelectorAll('.page-body img')].map((img, i) => ({
        index: i + 1, src: img.currentSrc.split('/').pop(), width: Math.round(box(img).width),
        right: box(img).right}));
    return {pageWidth: document.scrollingElement.scrollWidth, column: {left: column.left, right: column.right},
            tables, code, outputs, formulas, figures};
}"""


@pytest.fixture(scope="module")
def measured(browser_page, site) -> dict[int, dict[str, dict]]:
    """width -> page path -> what BOXES measured there."""
    page = browser_page.page
    found: dict[int, dict[str, dict]] = {}
    try:
        for width, size in SIZES.items():
            page.set_viewport_size(size)
            found[width] = {}
            for path in site.pages:
                browser_page.visit(path)
                found[width][path] = page.evaluate(BOXES)
    finally:
        page.set_viewport_size({"width": 1280, "height": 800})
    assert sum(len(m["code"]) for m in found[1366].values()) > 50, "few code blocks: is the site built?"
    return found


def report(problems: list[str], what: str) -> None:
    assert not problems, f"{len(problems)} {what}:\n" + "\n".join(problems)


@pytest.mark.parametrize("width", SIZES)
def test_no_page_is_wider_than_the_window(measured, width):
    report([f"{path} at {width} px: the page is {m['pageWidth']} px wide"
            for path, m in measured[width].items() if m["pageWidth"] > width], "pages scroll sideways")


def test_no_table_is_wider_than_its_column_on_a_laptop(measured):
    report([f"{path} at 1366 px: table {t['index']} ({t['head']}...) is {t['width']} px wide, "
            f"{t['right'] - m['column']['right']:.0f} px past its column"
            for path, m in measured[1366].items() for t in m["tables"]
            if t["right"] > m["column"]["right"] + SLACK], "tables wider than their column")


@pytest.mark.parametrize("width", PHONES)
def test_every_wide_table_on_a_phone_reflows_or_pins_its_first_column(measured, width):
    problems = []
    for path, m in measured[width].items():
        for t in m["tables"]:
            where = f"{path} at {width} px: table {t['index']} ({t['head']}..., {t['mode'] or 'no mode'})"
            if t["emptyHeaders"]:
                problems.append(f"{where}: {t['emptyHeaders']} header cell(s) without a name")
            if t["mode"] == "cards":
                if t["display"] != "block" or t["right"] > m["column"]["right"] + SLACK:
                    problems.append(f"{where}: not shown as cards within the column "
                                    f"(display {t['display']}, {t['width']} px)")
            elif t["right"] > m["column"]["right"] + SLACK:
                # Wider than the column: it must scroll in its own box, first column pinned.
                if t["mode"] != "pinned" or not t["pinned"]:
                    problems.append(f"{where}: {t['width']} px wide, its first column not pinned")
                elif not t["wrapScrolls"] or t["wrapRight"] > width or t["wrapFocus"] != "0":
                    problems.append(f"{where}: {t['width']} px wide and its box does not scroll in the window")
                elif not t["cue"]:
                    problems.append(f"{where}: {t['width']} px wide, no shadow where more of it lies")
    report(problems, "tables that lose their rows' names on a phone")


def test_few_code_blocks_scroll_sideways_on_a_laptop(measured):
    blocks = [(path, c) for path, m in measured[1366].items() for c in m["code"]]
    scrolling = [(path, c) for path, c in blocks if c["scrolls"]]
    share = len(scrolling) / len(blocks)
    assert share <= MOST_SCROLLING, (
        f"{len(scrolling)} of {len(blocks)} code blocks ({share:.1%}) scroll sideways at 1366 px, "
        f"at most {MOST_SCROLLING:.0%} may:\n" + "\n".join(
            f"{path}: code block {c['index']}, {c['hidden']} px hidden: {c['line']}"
            for path, c in sorted(scrolling, key=lambda item: -item[1]["hidden"])))


@pytest.mark.parametrize("width", SIZES)
def test_a_code_block_that_scrolls_shows_it_and_keeps_its_buttons(measured, width):
    problems = []
    for path, m in measured[width].items():
        for c in m["code"]:
            where = f"{path} at {width} px: code block {c['index']} ({c['line'][:40]}...)"
            if not c["copy"]:
                problems.append(f"{where}: its Copy button is out of view")
            if c["scrolls"] and not (c["cue"] and c["wrap"]):
                problems.append(f"{where}: scrolls {c['hidden']} px without "
                                + " and ".join(w for w, ok in (("its shadow", c["cue"]), ("a Wrap button", c["wrap"]))
                                               if not ok))
    report(problems, "code blocks that hide what they hold")


@pytest.mark.parametrize("width", SIZES)
def test_no_output_scrolls_sideways(measured, width):
    report([f"{path} at {width} px: {o['kind']} {o['index']} scrolls {o['hidden']} px: {o['line']}"
            for path, m in measured[width].items() for o in m["outputs"] if o["scrolls"]],
           "outputs that scroll sideways")


@pytest.mark.parametrize("width", SIZES)
def test_formulas_fit_or_scroll_in_their_own_box_visibly(measured, width):
    problems = []
    for path, m in measured[width].items():
        for f in m["formulas"]:
            where = f"{path} at {width} px: formula {f['index']} ({f['tex']}...)"
            if f["right"] > width + SLACK:
                problems.append(f"{where}: runs past the window's edge")
            elif f["scrolls"] and not (f["focus"] == "0" and f["cue"]):
                problems.append(f"{where}: scrolls without a tab stop and a shadow")
    report(problems, "formulas cut off")


@pytest.mark.parametrize("width", SIZES)
def test_no_figure_is_wider_than_its_column(measured, width):
    report([f"{path} at {width} px: figure {f['index']} ({f['src']}) is {f['width']} px wide"
            for path, m in measured[width].items() for f in m["figures"]
            if f["right"] > m["column"]["right"] + SLACK], "figures wider than their column")


def test_the_search_box_shows_its_whole_placeholder_on_a_narrow_phone(browser_page):
    page = browser_page.page
    try:
        page.set_viewport_size(SIZES[360])
        browser_page.visit("/")
        text, room = page.evaluate("""() => {
            const input = document.querySelector('.site-search-input');
            const style = getComputedStyle(input);
            const context = document.createElement('canvas').getContext('2d');
            context.font = style.font;
            return [context.measureText(input.placeholder).width,
                    input.clientWidth - parseFloat(style.paddingLeft) - parseFloat(style.paddingRight)];
        }""")
    finally:
        page.set_viewport_size({"width": 1280, "height": 800})
    assert text <= room, f"at 360 px the search box's placeholder needs {text:.0f} px, it has {room:.0f}"


def test_a_long_output_line_wraps_under_its_own_indentation(browser_page):
    """On a phone a `sw2sim check` line of "Your own model" wraps: its "Fix: ..." is inside
    the box, and the lines after the first are indented two characters further than the
    line's own text."""
    page = browser_page.page
    try:
        page.set_viewport_size(SIZES[390])
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
            const probe = document.createElement('span');
            probe.textContent = 'x'.repeat(10);
            line.parentNode.appendChild(probe);
            const ch = probe.getBoundingClientRect().width / 10;
            probe.remove();
            return {characters: line.textContent.length, right: Math.max(...rects.map(r => r.right)),
                    boxRight: box.right, height: rects[0].height, lefts, ch,
                    leading: line.textContent.match(/^ */)[0].length,
                    lineHeight: parseFloat(getComputedStyle(line).lineHeight)};
        }""")
    finally:
        page.set_viewport_size({"width": 1280, "height": 800})
    assert line, "no `sw2sim check` line with a Fix: in an output box of /reference/your-own-model/"
    assert line["right"] <= line["boxRight"], f"the line runs out of its box: {line}"
    assert line["height"] >= 3 * line["lineHeight"], f"a {line['characters']}-character line on a phone " \
        f"takes fewer than three lines: {line}"
    # The first piece starts at the line's start; the wrapped pieces its indentation + 2 further in.
    assert len(line["lefts"]) == 2 and line["lefts"][1] - line["lefts"][0] == \
        pytest.approx((line["leading"] + 2) * line["ch"], abs=1.5), line


def test_a_blocks_output_is_as_wide_as_the_block(browser_page):
    """At 1366 × 900 the output under a block lines up with the block's both edges."""
    page = browser_page.page
    try:
        page.set_viewport_size(SIZES[1366])
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


def test_the_wrap_button_wraps_every_code_block_and_the_site_remembers(browser_page):
    """On a phone, Wrap on one page's block wraps every block of the page, and of the next
    page visited (localStorage); pressed again, the blocks scroll again there too."""
    page = browser_page.page
    scrolling = """() => [...document.querySelectorAll('div.highlighter-rouge:not(.language-text) pre')]
        .filter(pre => pre.scrollWidth > pre.clientWidth + 1).length"""
    try:
        page.set_viewport_size(SIZES[390])
        browser_page.visit("/practice-2/friction/")
        assert page.evaluate(scrolling) > 0, "no code block scrolls on a phone: nothing to wrap"
        page.locator(".wrap-button").first.click()
        assert page.evaluate(scrolling) == 0
        assert page.locator(".wrap-button").first.get_attribute("aria-pressed") == "true"
        browser_page.visit("/practice-1/custom-node/")
        assert page.evaluate(scrolling) == 0, "the next page forgot the choice"
        assert page.locator(".wrap-button").count() > 0, "no Wrap button to undo it with"
        page.locator(".wrap-button").first.click()
        browser_page.visit("/practice-1/custom-node/")
        assert page.evaluate(scrolling) > 0, "Wrap pressed again did not stick"
    finally:
        page.evaluate("localStorage.clear()")
        page.set_viewport_size({"width": 1280, "height": 800})
