"""Checklists a reader can tick (_plugins/task_lists.rb, assets/js/site.js "Checklists").

Without scripts a page's checklist is a plain list (no disabled, pre-ticked boxes); with
them each item has a checkbox that starts unticked, the ticks are kept per page in
localStorage and survive a reload, the sidebar shows each practice's ticked items over its
pages' checklists, and a button clears the page's ticks.
"""

from __future__ import annotations

import re

PAGE = "/practice-1/custom-node/"
OTHER = "/practice-2/friction/"


def boxes(page) -> list[bool]:
    return [box.is_checked() for box in page.locator(".task-list-item-checkbox").all()]


def progress(page) -> dict[str, str]:
    """Each sidebar section with a checklist: its title -> the progress it shows."""
    return page.evaluate("""() => Object.fromEntries([...document.querySelectorAll('.nav-section')]
        .filter(s => s.querySelector('.checklist-progress'))
        .map(s => [s.querySelector('summary').firstChild.textContent.trim(),
                   s.querySelector('.checklist-progress').textContent]))""")


def test_without_scripts_a_checklist_is_a_plain_list(site):
    page = (site.root / PAGE.strip("/") / "index.html").read_text(encoding="utf-8")
    checklist = re.search(r'<ul class="task-list">(.*?)</ul>', page, re.S)
    assert checklist, f"{PAGE}: no checklist"
    assert "<input" not in checklist[1] and checklist[1].count('<li class="task-list-item">') == 4


def test_ticks_are_kept_per_page_shown_in_the_sidebar_and_cleared(browser_page):
    page = browser_page.page
    try:
        browser_page.visit(PAGE)
        assert boxes(page) == [False] * 4, "a checklist starts unticked"
        assert progress(page) == {"Practice 1: The simple wheel": "0/4",
                                  "Practice 2: Friction and an angle": "0/6"}
        page.locator(".task-list-label").nth(1).click()      # its text ticks it too
        page.locator(".task-list-item-checkbox").nth(3).check()
        assert progress(page)["Practice 1: The simple wheel"] == "2/4"
        browser_page.visit(PAGE)
        assert boxes(page) == [False, True, False, True], "the ticks did not survive a reload"
        browser_page.visit(OTHER)
        assert boxes(page) == [False] * 6, "another page's checklist took this page's ticks"
        assert progress(page)["Practice 1: The simple wheel"] == "2/4"
        browser_page.visit(PAGE)
        page.locator(".checklist-clear").click()
        assert boxes(page) == [False] * 4
        browser_page.visit(PAGE)
        assert boxes(page) == [False] * 4 and progress(page)["Practice 1: The simple wheel"] == "0/4"
        assert not browser_page.visit(PAGE).problems()
    finally:
        page.evaluate("localStorage.clear()")
