"""axe-core audits of loaded pages (axe-core from npm, served by the test server).

A serious or critical finding stops some readers from using a page; lesser ones
("minor", "moderate") are not failures here, so an audit runs only the default rules
(WCAG 2 A and AA, best practices) that can report a serious or critical finding.

Two parts of a page are audited once rather than on every page, which keeps the run
quick: the sidebar, the same on every page but for which link is current and which
section is open, is audited on the home page, where every section is open; and the
highlighted text of code blocks, thousands of one-word <span>s whose only possible
problem is their colour, is left to test_accessibility.py, which checks every
highlighting class the site uses at once.

An audit is started and collected apart, so that a page can be audited in one tab while
the next one loads in another.
"""

from __future__ import annotations

AXE = "axe-core/axe.min.js"  # in node_modules
FAILING_IMPACTS = ("serious", "critical")

HIGHLIGHTED_CODE = "pre.highlight > code"
SIDEBAR = "#sidebar"
# The page whose sidebar has every section open.
FULL_SIDEBAR_PAGE = "/"

# Starts axe once the current task is done, so that the call returns at once (axe works
# in long synchronous stretches, and any call into the page waits for them to end).
START_AXE = """([context, options]) => {
    const canBeSerious = rule => [...rule.any, ...rule.all, ...rule.none].some(check =>
        ["serious", "critical"].includes(axe._audit.data.checks[check.id]?.impact));
    const rules = axe._audit.rules.filter(rule => rule.enabled && canBeSerious(rule));
    options = {runOnly: {type: "rule", values: rules.map(rule => rule.id)}, ...options};
    window.axeViolations = new Promise(resolve => setTimeout(resolve, 0))
        .then(() => axe.run(context, {...options, resultTypes: ["violations"]}))
        .then(results => results.violations.map(v => ({
            id: v.id, impact: v.impact, help: v.help,
            targets: v.nodes.map(n => n.target.join(" ")),
        })));
}"""
COLLECT_AXE = "() => window.axeViolations"


def default_context(path: str) -> dict:
    """The page less highlighted code and, but on the home page, the sidebar."""
    skipped = [HIGHLIGHTED_CODE] if path == FULL_SIDEBAR_PAGE else [HIGHLIGHTED_CODE, SIDEBAR]
    return {"exclude": [[selector] for selector in skipped]}


def start(page, path: str, context: dict | None = None, options: dict | None = None) -> None:
    """Start axe on a loaded page that has axe injected (`path` is the page's, for the
    default context). Call it last: later calls into the page wait for axe."""
    page.evaluate(START_AXE, [context or default_context(path), options or {}])


def collect(page) -> list[dict]:
    """The violations of the audit started on `page`: id, impact, help, targets."""
    return page.evaluate(COLLECT_AXE)


def serious(violations: list[dict]) -> list[dict]:
    return [v for v in violations if v["impact"] in FAILING_IMPACTS]
