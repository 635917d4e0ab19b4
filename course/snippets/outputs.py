"""What each ```python block of a page prints, kept in _data/outputs/ so that the site
shows it under the block (_plugins/code_outputs.rb), and checked against what the block
prints now by the run that tests the page (tests/course/test_pages.py).

One JSON file a page, `_data/outputs/<path under _pages/, '/' as '__'>.json`, for a
page whose blocks print anything:

    {"page": "_pages/practice-1/01-modelling.md",
     "blocks": [{"code": "from course.practices.practice_1 import design",
                 "output": "wheel: 3.051 kg, base: 2.654 kg\\n..."},
                {"code": "mujoco.viewer.launch(model)", "output": null}, ...]}

`blocks` has every ```python fence of the page in page order, as the runner's parser finds
them and the site renders them: `code` is the block's first non-blank line (the plugin
checks it against the block it renders, so an output never lands under the wrong block);
`output` is what the block printed, stdout and stderr as they came, or null for a block
the runner does not run (`data-skip`, `data-ros`). No page line is kept, so a change to
the prose around the blocks changes nothing here.

What differs from machine to machine or run to run is made the same (`normalise`): the
repository's folder, the home folder and the temporary folder, and the wall-clock time
`sw2sim check` reports for its stability run.

`python -m course.snippets --write-outputs` (or `python -m course.snippets.outputs`, a step
of `python -m course`) runs the pages and writes the files; `--check` writes nothing and
lists the files that are out of date.
"""

from __future__ import annotations

import argparse
import difflib
import json
import re
import sys
import tempfile
from collections.abc import Iterable
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
from typing import Any

from .execute import PageResult, run_page, shutdown
from .parse import Page, find_pages, parse_page
from .report import format_failure

FOLDER = Path("_data", "outputs")
COMMAND = ".venv/bin/python -m course.snippets --write-outputs"

# Wall-clock times a block prints, each as the text that replaces the number: a time differs
# on every run, so the page shows that it varies instead of one run's figure.
_TIMINGS = [
    # sw2sim check's summary: "4.0 s simulated (2000 steps) in 0.07 s; ..."
    (re.compile(r"(\(\d+ steps\) in )\d+(?:\.\d+)?( s\b)"), r"\1…\2"),
]


def data_file(page: str | Path, root: Path) -> Path:
    """The outputs file of the page at `page` (a path from the repository root, or absolute):
    _data/outputs/practice-1__01-modelling.json for _pages/practice-1/01-modelling.md."""
    path = Path(page)
    if path.is_absolute():
        path = path.relative_to(root)
    parts = path.with_suffix("").parts
    return root / FOLDER / ("__".join(parts[parts.index("_pages") + 1:]) + ".json")


def first_line(code: str) -> str:
    """A block's first non-blank line, stripped: how a stored output names its block."""
    return next((line.strip() for line in code.splitlines() if line.strip()), "")


def _folder_pattern(folder: str) -> re.Pattern[str]:
    """`folder` as a path, or as the start of a path inside it; not the start of a longer name."""
    return re.compile(re.escape(folder.rstrip("/")) + r"(?:(?P<inside>/)|(?![\w.-]))")


def normalise(text: str, root: Path, temp: str | None = None) -> str:
    """What a block printed, with what differs between machines and runs made the same:
    paths inside the repository relative to it (the blocks run in its root), the home
    folder as `~`, the temporary folder (the page's own, `temp`, where it had one) as
    `/tmp`, wall-clock times as `…`."""
    text = text.replace("\r\n", "\n")
    folders = [(str(root.resolve()), ".", ""), (str(Path.home()), "~", "~/"),
               (tempfile.gettempdir(), "/tmp", "/tmp/")]
    if temp:
        folders.append((temp, "/tmp", "/tmp/"))
    # The longest first: the repository may be inside the home or the temporary folder.
    for folder, alone, prefix in sorted(folders, key=lambda f: -len(f[0])):
        if folder not in ("", "/") and folder != alone:
            text = _folder_pattern(folder).sub(lambda m: prefix if m["inside"] else alone, text)
    for pattern, replacement in _TIMINGS:
        text = pattern.sub(replacement, text)
    return text


def entries(page: Page, result: PageResult, root: Path) -> list[dict[str, Any]]:
    """Every python block of the page in page order, with what it printed (None: not run).
    `result` is a successful run of the page."""
    printed = {b.line: normalise(text, root, result.temp)
               for b, text in zip(result.ran, result.outputs)}
    return [{"code": first_line(b.code), "output": printed.get(b.line)} for b in page.blocks]


def record(page: Page, result: PageResult, root: Path) -> dict[str, Any] | None:
    """The outputs file's content for a successful run, or None if no block printed anything."""
    blocks = entries(page, result, root)
    if not any(b["output"] for b in blocks):
        return None
    return {"page": page.path, "blocks": blocks}


def dumps(content: dict[str, Any]) -> str:
    return json.dumps(content, indent=1, ensure_ascii=False) + "\n"


def read(file: Path) -> dict[str, Any] | None:
    return json.loads(file.read_text(encoding="utf-8")) if file.is_file() else None


def write(page: Page, result: PageResult, root: Path) -> str | None:
    """Bring the page's outputs file up to date with a successful run; what was done, or None
    if nothing changed."""
    file = data_file(page.path, root)
    content = record(page, result, root)
    name = file.relative_to(root).as_posix()
    if content is None:
        if file.is_file():
            file.unlink()
            return f"removed {name}: the page's blocks print nothing"
        return None
    text = dumps(content)
    if file.is_file() and file.read_text(encoding="utf-8") == text:
        return None
    file.parent.mkdir(parents=True, exist_ok=True)
    file.write_text(text, encoding="utf-8")
    return f"wrote {name}"


def orphans(root: Path) -> list[Path]:
    """Outputs files of pages that no longer exist."""
    wanted = {data_file(p, root) for p in find_pages(root)}
    return sorted(f for f in (root / FOLDER).glob("*.json") if f not in wanted)


def differences(page: Page, result: PageResult, root: Path) -> str | None:
    """Why the stored outputs of a page that ran without error are not what its blocks
    printed now (each block's page line and a diff), with the command that refreshes
    them; None if they are."""
    file = data_file(page.path, root)
    name = file.relative_to(root).as_posix()
    fresh = record(page, result, root)
    stored = read(file)
    refresh = f"Run `{COMMAND} {page.path}` to refresh the stored outputs, and commit {name}."
    if fresh is None and stored is None:
        return None
    if stored is None:
        return f"{page.path}: its blocks print output but {name} does not exist. {refresh}"
    if fresh is None:
        return f"{page.path}: its blocks print nothing but {name} holds outputs for them. {refresh}"
    old = stored.get("blocks") or []
    new = fresh["blocks"]
    if [b.get("code") for b in old] != [b["code"] for b in new]:
        return (f"{page.path}: {name} was written for other python blocks "
                f"({len(old)} stored, {len(new)} on the page now, or their first lines differ):\n"
                + _diff([b.get("code") or "" for b in old], [b["code"] for b in new], "stored blocks",
                        "blocks now") + f"\n{refresh}")
    problems = []
    for block, was, now in zip(page.blocks, old, new):
        if was.get("output") != now["output"]:
            problems.append(f"{block.location}: the stored output differs from what the block prints now:\n"
                            + _diff(_lines(was.get("output")), _lines(now["output"]),
                                    f"{name} (stored)", "printed now"))
    if stored != fresh and not problems:
        problems.append(f"{page.path}: {name} is not as {COMMAND} writes it")
    return "\n".join(problems) + f"\n{refresh}" if problems else None


def _lines(output: str | None) -> list[str]:
    return ["(not run)"] if output is None else output.splitlines()


def _diff(old: list[str], new: list[str], old_name: str, new_name: str) -> str:
    return "\n".join("    " + line.rstrip("\n")
                     for line in difflib.unified_diff(old, new, old_name, new_name, lineterm=""))


# The command line ------------------------------------------------------------------------

def run_pages(paths: Iterable[Path], root: Path, at_once: int = 4,
              timeout: float | None = None) -> Iterable[tuple[Page, PageResult]]:
    """Each page parsed and run, several at once, in the order given."""
    pages = [parse_page(p, root) for p in paths]
    with ThreadPoolExecutor(max(1, at_once)) as pool:
        results = [pool.submit(run_page, page, root, timeout) for page in pages]
        for page, result in zip(pages, results):
            yield page, result.result()


def refresh(paths: list[Path], root: Path, check: bool = False, at_once: int = 4,
            timeout: float | None = None, every_page: bool = True) -> int:
    """Run the pages and write their outputs files (with `check`, list the stale ones
    instead); the exit status: 1 if a page failed, or with `check` if anything is stale.
    `every_page`: the pages are all of them, so files of pages that are gone go too."""
    status = 0
    try:
        for page, result in run_pages(paths, root, at_once, timeout):
            if not result.ok:
                print(f"{page.path} failed; its outputs file is left as it is:\n{format_failure(result)}",
                      file=sys.stderr, flush=True)
                status = 1
            elif check:
                if differences(page, result, root):
                    print(f"stale: {data_file(page.path, root).relative_to(root)} (from {page.path})")
                    status = 1
            elif done := write(page, result, root):
                print(done, flush=True)
    finally:
        shutdown()
    for file in orphans(root) if every_page else []:
        if check:
            print(f"no page: {file.relative_to(root)}")
            status = 1
        else:
            file.unlink()
            print(f"removed {file.relative_to(root)}: its page is gone")
    return status


def main(argv: list[str] | None = None) -> int:
    """`python -m course.snippets.outputs [--check] [only ...]`: a step of `python -m course`."""
    from .. import ROOT
    from ..freshness import chosen, cores

    parser = argparse.ArgumentParser(prog="python -m course.snippets.outputs",
                                     description="Run the pages and store what their python blocks print.")
    parser.add_argument("--check", action="store_true",
                        help="write nothing; list the stale outputs files and exit 1 if any")
    parser.add_argument("--jobs", type=int, default=cores(), help="pages run at once (default: cores)")
    parser.add_argument("only", nargs="*", help="only pages whose path contains one of these")
    args = parser.parse_args(argv)
    pages = chosen(find_pages(ROOT), args.only, lambda p: p.relative_to(ROOT).as_posix())
    return refresh(pages, ROOT, args.check, args.jobs, every_page=not args.only)


if __name__ == "__main__":
    sys.exit(main())
