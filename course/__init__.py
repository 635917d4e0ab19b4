"""The course build: everything that turns this repository into the site.

It is never installed; run it from the repository root with `python -m course` (regenerate
everything generated) or one of its modules (`python -m course.snippets PAGE` runs a page).
It uses the installable `sw2sim` tool; the tool never imports anything from here.
"""

from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
