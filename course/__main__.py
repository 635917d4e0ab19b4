"""Regenerate everything generated, in the order each step needs the last:

1. the example packages, from the practices' designs   (python -m course.practices)
2. the figures under media/, from the packages          (python -m course.media)
   and each practice's model for the site's Simulate mode (python -m course.browser_models)
3. the Troubleshooting page's data, from the rules      (python -m course.troubleshooting)
4. what the pages' blocks print, shown under them       (python -m course.snippets.outputs)
5. the lesson notebooks, from the pages and packages    (python -m course.notebooks)

Each step redoes only what is out of date (step 4 runs every page, a matter of seconds,
and writes only the files that change). `--check` changes nothing: it lists what is
stale and exits 1 if anything is. `make media` runs this.
"""

from __future__ import annotations

import argparse
import sys
import time

from . import browser_models, media, notebooks, troubleshooting
from .practices import __main__ as packages
from .snippets import outputs as page_outputs

STEPS = [
    ("example packages", packages.main),
    ("figures", media.main),
    ("browser models", browser_models.main),
    ("troubleshooting data", troubleshooting.main),
    ("page outputs", page_outputs.main),
    ("notebooks", notebooks.main),
]


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m course", description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true",
                        help="change nothing; list what is stale and exit 1 if anything is")
    args = parser.parse_args(argv)
    status = 0
    for title, step in STEPS:
        began = time.monotonic()
        print(f"== {title}", flush=True)
        result = step(["--check"] if args.check else [])
        print(f"   ({time.monotonic() - began:.1f} s)", flush=True)
        if result and not args.check:
            print(f"python -m course: {title} failed; later steps were not run", file=sys.stderr)
            return result
        status = status or result
    return status


if __name__ == "__main__":
    sys.exit(main())
