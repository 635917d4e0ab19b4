"""CLI: `python -m course.snippets [PAGES...]` runs pages (default: all of _pages/) and reports."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from . import find_pages, format_failure, format_skipped, format_summary, parse_page, run_page
from . import outputs
from .execute import shutdown
from .parse import display_path


def find_root(start: Path) -> Path:
    """The nearest directory at or above `start` holding `_pages/` (else `start`)."""
    for directory in (start, *start.parents):
        if (directory / "_pages").is_dir():
            return directory
    return start


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m course.snippets", description=__doc__)
    parser.add_argument("pages", nargs="*", type=Path, help="Markdown pages (default: every _pages/**/*.md)")
    parser.add_argument("--root", type=Path, help="repository root: the blocks' working directory")
    parser.add_argument("--timeout", type=float, help="seconds per block, overriding the pages' own")
    parser.add_argument("--plain", action="store_true",
                        help="start every page's process as a plain `python` subprocess, not from the fork server")
    parser.add_argument("--write-outputs", action="store_true",
                        help="store what each page's blocks print in _data/outputs/, for the site "
                             "(pages that fail keep theirs; see course/snippets/outputs.py)")
    parser.add_argument("--exclude", action="append", type=Path, default=[], metavar="PAGE",
                        help="leave this page out (repeatable): one that needs what this machine lacks")
    args = parser.parse_args(argv)
    root = (args.root or find_root(Path.cwd())).resolve()
    pages = args.pages or find_pages(root)
    excluded = {page.resolve() for page in args.exclude}
    unknown = sorted(str(page) for page in args.exclude if not page.is_file())
    if unknown:
        print(f"--exclude: no such page: {', '.join(unknown)}", file=sys.stderr)
        return 1
    left_out = [page for page in pages if page.resolve() in excluded]
    pages = [page for page in pages if page.resolve() not in excluded]
    if not pages:
        print(f"no pages found under {root / '_pages'}", file=sys.stderr)
        return 1

    failed, skipped, ran = 0, [], 0
    try:
        for path in pages:
            page = parse_page(path, root)
            result = run_page(page, root, args.timeout, fork=False if args.plain else None)
            print(format_summary(result), flush=True)
            if args.write_outputs and result.ok and (done := outputs.write(page, result, root)):
                print(f"       {done}", flush=True)
            if not result.ok:
                failed += 1
                print(format_failure(result), flush=True)
            ran += len(result.ran)
            skipped += page.skipped
    finally:
        shutdown()
    for file in outputs.orphans(root) if args.write_outputs and not args.pages else []:
        file.unlink()
        print(f"removed {file.relative_to(root)}: its page is gone")
    print(f"\n{len(pages)} pages, {failed} failed; snippet blocks run: {ran}; skipped snippet blocks: {len(skipped)}")
    for line in format_skipped(skipped):
        print(f"  {line}")
    if left_out:
        print(f"pages left out (--exclude): {len(left_out)}")
        for page in left_out:
            print(f"  {display_path(page, root)}")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
