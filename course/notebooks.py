"""Each lesson page with Python as a Jupyter notebook, and `python -m course.notebooks` to
bring them up to date.

A notebook is made from its page with the page runner's own parser (course.snippets), so
its code cells are exactly the blocks the tests run, in page order: the text of the fence,
or of the file an `{% include_code %}` fence shows. The prose between them becomes
Markdown cells; a block the page marks `data-skip` stays Markdown (shown, not run) with
its reason. A first code cell moves the kernel to the repository root, where the pages'
code runs; outside a clone it fetches the files the lesson reads (listed for every
notebook in notebooks/files.json) from the course site, and installs sw2sim with pip.

Notebooks are written to notebooks/ with their outputs and committed, as the figures
under media/ are, so that the site (and its Pages build, which has no Python) serves them
as they are. Each notebook records a hash of what its outputs depend on: its code cells,
the repository files that code imports or names, and the libraries' versions. While that
hash holds, a change to the prose only rewrites the Markdown and keeps the outputs; any
other change runs the notebook again.
"""

from __future__ import annotations

import json
import os
import re
import sys
import tempfile
import time
from functools import cache
from pathlib import Path

import nbformat
import yaml
from nbformat import NotebookNode
from nbformat.v4 import new_code_cell, new_markdown_cell, new_notebook

from . import freshness, media, sources
from .freshness import Fingerprint
from .media import RENDERERS
from .notebook_setup import named_files, needed_files, on_site, read_by, setup_code
from .practices import ROOT
from .snippets import Block, Page, find_pages, parse_page
from .snippets.execute import TEMP_VARIABLES
from .snippets.parse import (INCLUDE_CODE, include_code_arguments, split_front_matter,
                             without_raw_tags)

FOLDER = ROOT / "notebooks"
KERNEL = {"name": "python3", "display_name": "Python 3", "language": "python"}
# Libraries whose version can change what a page's code prints, besides the figures' ones.
KERNEL_LIBRARIES = (*RENDERERS, "ipykernel")

# Liquid other than {% raw %} and {% include_code %} is the site's own templating: a
# notebook cannot evaluate it, so such a region of a page becomes a note.
_LIQUID = re.compile(r"\{%.*?%\}|\{\{.*?\}\}")
_LIQUID_OPEN = re.compile(r"\{%-?\s*(?:for|if|unless|case|capture)\b")
_LIQUID_CLOSE = re.compile(r"\{%-?\s*end(?:for|if|unless|case|capture)\b")
# kramdown extras Jupyter's Markdown does not know (the parse finds the attribute lines).
_HEADING_ID = re.compile(r"^(#{1,6}\s.*?)\s*\{#[\w-]+\}\s*$")
_INLINE_MATH = re.compile(r"\$\$(.+?)\$\$")
_ROOT_LINK = re.compile(r"(?P<bang>!?)\[(?P<text>[^\]]*)\]\((?P<path>/(?!/)[^)\s]*)\)")
_ROOT_ATTR = re.compile(r"""(?P<attr>\b(?:src|href))="(?P<path>/(?!/)[^"]*)\"""")

GENERATED_NOTE = ("*Here the page shows something the site builds (an interactive tool, or a "
                  "list made from the course's data): see it on the course site.*")


def notebook_name(page_path: Path | str) -> str:
    """practice-1-05-custom-node.ipynb for _pages/practice-1/05-custom-node.md: the page's
    path under _pages/ with '-' for '/', so the folder lists the lessons in reading order.
    _includes/notebook-link.html derives the same name from `page.path`."""
    parts = Path(page_path).parts
    relative = parts[parts.index("_pages") + 1:]
    return "-".join(relative)[: -len(".md")] + ".ipynb"


def lesson_pages(root: Path = ROOT) -> list[Path]:
    """The pages that get a notebook: those with at least one block the runner runs."""
    return [p for p in find_pages(root) if parse_page(p, root).runnable]


def build(path: Path, root: Path = ROOT) -> NotebookNode:
    """The notebook of the page at `path`, without outputs."""
    page = parse_page(path, root)
    if page.errors:
        raise ValueError("the page has mistakes the runner reports:\n" +
                         "\n".join(str(e) for e in page.errors))
    lines = path.read_text(encoding="utf-8").split("\n")
    front_lines, body_start = split_front_matter(lines)
    front = yaml.safe_load("\n".join(front_lines)) or {}
    body = [""] * body_start + lines[body_start:]

    cells = [new_markdown_cell(_introduction(front, page)),
             new_code_cell(setup_code(notebook_name(path)))]
    cells[1].metadata["tags"] = ["setup"]
    prose: list[str] = []
    cursor = body_start
    for block in page.blocks:
        start, end = block.fence
        prose += _markdown(body[cursor:start], cursor, page, root)
        cursor = end + 1 if block.attributes is not None else end
        shown = block.data_file or block.include
        if block.skip is not None or block.ros or block.ros2:
            prose += _skipped(block, shown)
            continue
        if shown:
            prose += ["", f"File `{shown}`:"]
        if text := _tidy(prose):
            cells.append(new_markdown_cell(text))
        prose = []
        cell = new_code_cell(block.code.rstrip("\n"))
        cell.metadata["sw2sim"] = {"line": block.line}
        if block.include:
            cell.metadata["sw2sim"]["file"] = block.include
        cells.append(cell)
    prose += _markdown(body[cursor:], cursor, page, root)
    if text := _tidy(prose):
        cells.append(new_markdown_cell(text))

    for i, cell in enumerate(cells):
        cell.id = f"cell-{i}"  # stable ids: a notebook made twice from one page is the same file
    nb = new_notebook(cells=cells, metadata={"kernelspec": dict(KERNEL),
                                             "language_info": {"name": "python"}})
    nb.metadata["sw2sim"] = {"page": page.path, "timeout": page.timeout}
    return nb


def _introduction(front: dict, page: Page) -> str:
    title = str(front.get("title") or Path(page.path).stem)
    where = f" (`{front['permalink']}` on the course site)" if front.get("permalink") else ""
    return "\n".join([
        f"# {title}",
        "",
        f"This notebook is the lesson page *{title}*{where}, made from the page itself: its "
        "code cells are the page's Python blocks, in order, and the site's tests run exactly "
        "these. A block the page shows but cannot run here (it needs ROS, say, or a window) "
        "is shown as text, with the reason.",
        "",
        "**Where to run it.** Anywhere with Python 3.10 or newer: Jupyter, VS Code or Colab. "
        "The code reads the lesson's files by their paths from the root of the course "
        "repository, such as `examples/example_1`. The first code cell sets that up: in a "
        "clone of the repository it works from the clone's root; anywhere else it fetches "
        "the files this lesson reads from the course site into the notebook's folder, and "
        "installs the `sw2sim` tool with pip if it is missing.",
    ])


ROS_NODE = "it is a ROS 1 node, which the page's commands start under ROS"
ROS2_NODE = "it is a ROS 2 node, which the page's commands start under ROS 2"


def _skipped(block: Block, shown: str | None) -> list[str]:
    what = f"The file `{shown}` is" if shown else "This code is"
    fence = "````" if "```" in block.code else "```"
    reason = block.skip or (ROS2_NODE if block.ros2 else ROS_NODE)
    return ["", f"> {what} not run in this notebook: {reason}. Read it here, and run it "
            "where that is available.", "", fence + "python", block.code.rstrip("\n"), fence]


def _markdown(lines: list[str], first: int, page: Page, root: Path) -> list[str]:
    """Page lines (from 0-based line `first`) as Jupyter Markdown."""
    out: list[str] = []
    liquid = _liquid_regions(lines, first, page)
    for n, text in enumerate(lines, start=first):
        if any(start == n for start, _ in liquid):
            out += ["", GENERATED_NOTE, ""]
        if any(start <= n < end for start, end in liquid):
            continue
        text = without_raw_tags(text)
        if n in page.code_lines:
            if not page.in_raw(n) and (m := INCLUDE_CODE.search(text)):
                text = text[:m.start()] + _included(m["args"], root) + text[m.end():]
            if n - 1 not in page.code_lines and (name := page.data_files.get(n)):
                out += [f"File `{name}`:", ""]
            out.append(text)
            continue
        if n in page.attribute_lines:
            continue
        text = sources.as_markdown(text, _sources())
        text = _HEADING_ID.sub(r"\1", text)
        if not text.strip().startswith("$$"):
            text = _INLINE_MATH.sub(r"$\1$", text)
        text = _ROOT_LINK.sub(lambda m: _link(m, root), text)
        text = _ROOT_ATTR.sub(
            lambda m: f'{m["attr"]}="{_repository_path(m["path"], root) or m["path"]}"', text)
        out.append(text)
    return out


def _liquid_regions(lines: list[str], first: int, page: Page) -> list[tuple[int, int]]:
    """Spans of template code the notebook cannot evaluate, widened to whole HTML blocks."""
    spans: list[tuple[int, int]] = []
    depth, start = 0, None
    for n, text in enumerate(lines, start=first):
        stripped = sources.INCLUDE.sub("", INCLUDE_CODE.sub("", without_raw_tags(text)))
        if page.in_raw(n) or n in page.code_lines or not _LIQUID.search(stripped):
            if depth == 0 and start is not None:
                spans.append((start, n))
                start = None
            continue
        start = n if start is None else start
        opened = len(_LIQUID_OPEN.findall(stripped)) - len(_LIQUID_CLOSE.findall(stripped))
        depth = max(0, depth + opened)
        if depth == 0:
            spans.append((start, n + 1))
            start = None
    if start is not None:
        spans.append((start, first + len(lines)))
    # An HTML block cut in the middle would leave its other half as stray tags.
    widened = []
    for a, b in spans:
        for h0, h1 in page.html_blocks:
            if h0 < b and h1 > a:
                a, b = max(first, min(a, h0)), min(first + len(lines), max(b, h1))
        widened.append((a, b))
    merged: list[tuple[int, int]] = []
    for a, b in sorted(widened):
        gap = range(merged[-1][1], a) if merged else range(0)
        if merged and all(not lines[i - first].strip() for i in gap):
            merged[-1] = (merged[-1][0], max(merged[-1][1], b))
        else:
            merged.append((a, b))
    return merged


@cache
def _sources() -> dict[str, sources.Source]:
    """_data/sources.yml: a page's `{% include source.html %}` links become Markdown links
    (course.sources), not a note that the site builds something here."""
    return sources.load()


def _included(args: str, root: Path) -> str:
    """What `{% include_code %}` puts in a page (as _plugins/include_code.rb does)."""
    tag = include_code_arguments(args)
    if tag is None:
        raise ValueError(f"include_code expects `path [indent=N]`, got {args!r}")
    pad = " " * tag.indent
    lines = (root / tag.path).read_text(encoding="utf-8").replace("\r\n", "\n").rstrip().split("\n")
    return "\n".join(line if i == 0 or not line else pad + line for i, line in enumerate(lines))


def _repository_path(path: str, root: Path) -> str | None:
    """A site path that is a repository file (media/..., examples/...), relative to notebooks/."""
    relative = path.lstrip("/").split("#")[0]
    if relative and (root / relative).exists() and not relative.startswith("notebooks"):
        return "../" + path.lstrip("/")
    return None


def _link(m: re.Match[str], root: Path) -> str:
    """A root-relative Markdown link or image. Repository files keep working from notebooks/;
    a lesson with a notebook links to that notebook, next to this one; a link to any other
    page keeps only its words (a notebook cannot know the site's address)."""
    target = _repository_path(m["path"], root)
    if target is None and not m["bang"]:
        target = _notebooks_by_permalink(root).get(m["path"].split("#")[0])
    if target is not None:
        return f"{m['bang']}[{m['text']}]({target})"
    return m["text"]


@cache
def _notebooks_by_permalink(root: Path) -> dict[str, str]:
    """permalink -> notebook name, for every page that has a notebook."""
    names = {}
    for path in lesson_pages(root):
        front, _ = split_front_matter(path.read_text(encoding="utf-8").split("\n"))
        permalink = (yaml.safe_load("\n".join(front)) or {}).get("permalink")
        if permalink:
            names[permalink] = notebook_name(path)
    return names


def _tidy(lines: list[str]) -> str:
    """Markdown text without leading or trailing blank lines (lines inside are kept as they
    are: they may be code)."""
    return "\n".join(lines).strip("\n")


def code_cells(nb: NotebookNode) -> list[NotebookNode]:
    """The code cells that come from the page (every code cell but the setup cell)."""
    return [c for c in nb.cells
            if c.cell_type == "code" and "setup" not in c.metadata.get("tags", [])]


def source_form(nb: NotebookNode) -> list[tuple]:
    """What a notebook says, without what running it added: compares a committed notebook
    with one made from its page now."""
    return [(c.cell_type, c.id, c.source, {k: v for k, v in c.metadata.items() if k != "execution"})
            for c in nb.cells]


def output_hash(nb: NotebookNode, root: Path = ROOT) -> str:
    """A hash of everything a notebook's outputs depend on: its code cells, the repository
    files that code imports or names by path, the Python and library versions."""
    sources = [c.source for c in nb.cells if c.cell_type == "code"]
    fingerprint = Fingerprint()
    for source in sources:
        fingerprint.text(source.encode() + b"\0")
    return (fingerprint.files(_files_read(sources, root), root, separator=b"\0")
            .text(f"python {sys.version_info.major}.{sys.version_info.minor}")
            .libraries(KERNEL_LIBRARIES).hexdigest())


def _files_read(sources: list[str], root: Path) -> set[Path]:
    """Repository modules the code imports (with what they import) and files or folders
    it names by a relative path, such as "examples/example_1"."""
    modules, strings = read_by(sources)
    data = {f for text in strings for f in named_files(text, root)}
    # course/media.py is the build's own, as for the figures (their modules import it too).
    return freshness.imported_closure(sorted(modules), leave_out=[media.MODULE]) | data


FILES = FOLDER / "files.json"


def files_manifest(pages: list[Path], root: Path = ROOT) -> dict[str, dict[str, str]]:
    """notebook name -> {file: its path on the site}, for the files its setup cell fetches
    (notebooks/files.json). The example packages are on the site at their own paths."""
    def fetched(page: Path) -> list[str]:
        return needed_files([c.source for c in code_cells(build(page, root))], root)
    return {notebook_name(p): {name: on_site(name) for name in fetched(p)} for p in pages}


def write_files_manifest(pages: list[Path]) -> bool:
    """Write notebooks/files.json; True if it changed."""
    text = json.dumps(files_manifest(pages), indent=1, sort_keys=True) + "\n"
    if FILES.is_file() and FILES.read_text(encoding="utf-8") == text:
        return False
    FOLDER.mkdir(exist_ok=True)
    FILES.write_text(text, encoding="utf-8")
    return True


def _manifest_is_current() -> bool:
    return FILES.is_file() and (json.loads(FILES.read_text(encoding="utf-8"))
                                == files_manifest(lesson_pages()))


def execute(nb: NotebookNode, timeout: float, folder: Path = FOLDER) -> NotebookNode:
    """Run the notebook in a fresh python3 kernel started in `folder` (notebooks/), as a
    reader would."""
    # Only needed to run notebooks, not to compare them.
    from traitlets.config import Config
    from nbclient import NotebookClient

    folder.mkdir(exist_ok=True)
    # A kernel on this machine only: local sockets, one folder of them per kernel, rather
    # than unencrypted TCP.
    # Its temporary folder goes with it too: what the lessons make there (scratch copies,
    # unpacked zips) does not pile up in the machine's at every run.
    with tempfile.TemporaryDirectory(prefix="kernel-") as sockets:
        local = Config(KernelManager={"transport": "ipc", "ip": f"{sockets}/ipc"})
        temp = Path(sockets, "tmp")
        temp.mkdir()
        env = {**os.environ, **dict.fromkeys(TEMP_VARIABLES, str(temp))}
        NotebookClient(nb, kernel_name=KERNEL["name"], timeout=timeout, record_timing=False,
                       config=local, resources={"metadata": {"path": str(folder)}}
                       ).execute(env=env)
    for cell in nb.cells:
        # The setup cell prints this machine's folder: not something to publish.
        if "setup" in cell.metadata.get("tags", []):
            cell.outputs = []
        elif cell.cell_type == "code":
            cell.outputs = _joined_streams(cell.outputs)
    return nb


def _joined_streams(outputs: list[NotebookNode]) -> list[NotebookNode]:
    """Outputs with consecutive pieces of one stream joined: how a kernel cuts what a cell
    prints depends on timing, and the notebook should not."""
    joined: list[NotebookNode] = []
    for out in outputs:
        previous = joined[-1] if joined else None
        if (out.output_type == "stream" and previous is not None
                and previous.output_type == "stream" and previous.name == out.name):
            previous.text += out.text
        else:
            joined.append(out)
    return joined


def notebook_file(page_path: Path) -> Path:
    return FOLDER / notebook_name(page_path)


def is_current(page_path: Path, root: Path = ROOT) -> bool:
    """Whether the committed notebook is what its page makes now, with outputs made from
    the code and files as they are now."""
    file = notebook_file(page_path)
    if not file.is_file():
        return False
    committed = nbformat.read(file, as_version=4)
    fresh = build(page_path, root)
    return freshness.is_current(file, committed.metadata.get("sw2sim", {}).get("outputs_of"),
                                lambda: output_hash(fresh, root),
                                as_made=lambda: source_form(committed) == source_form(fresh))


def refresh(page: str, force: bool = False) -> tuple[str, float]:
    """Bring the notebook of `page` (a path) up to date; say what was done and how long it took.

    Takes a path, not a Page, so that a worker process can run it."""
    began = time.monotonic()
    path = Path(page)
    file = notebook_file(path)
    fresh = build(path)
    wanted = output_hash(fresh)
    old = nbformat.read(file, as_version=4) if file.is_file() else None
    if not force and old is not None and old.metadata.get("sw2sim", {}).get("outputs_of") == wanted:
        if source_form(old) == source_form(fresh):
            return "up to date", time.monotonic() - began
        # Same code and inputs: the outputs still hold; only the prose changed.
        for new, done in zip((c for c in fresh.cells if c.cell_type == "code"),
                             (c for c in old.cells if c.cell_type == "code")):
            new.outputs, new.execution_count = done.outputs, done.execution_count
        if "language_info" in old.metadata:
            fresh.metadata["language_info"] = old.metadata["language_info"]
        status = "prose updated"
    else:
        execute(fresh, fresh.metadata["sw2sim"]["timeout"])
        status = "executed"
    fresh.metadata["sw2sim"]["outputs_of"] = wanted
    nbformat.validate(fresh)
    FOLDER.mkdir(exist_ok=True)
    nbformat.write(fresh, file)
    return status, time.monotonic() - began


def main(argv: list[str] | None = None) -> int:
    args = freshness.command_line(
        argv, prog="python -m course.notebooks",
        description=" ".join(__doc__.split("\n\n")[0].split()),  # its first sentence
        force="run every notebook again", check="only list stale notebooks; exit 1 if any",
        jobs="notebooks run at once, each in a kernel of its own (default: cores)",
        only="only pages whose path contains one of these")
    pages = freshness.chosen(lesson_pages(), args.only, Path.as_posix)
    wanted = {notebook_name(p) for p in lesson_pages()}
    orphans = sorted(f for f in FOLDER.glob("*.ipynb") if f.name not in wanted)
    if args.check:
        return freshness.report_stale([
            *(f"stale: {notebook_file(p).relative_to(ROOT)} (from {p.relative_to(ROOT)})"
              for p in pages if not is_current(p)),
            *(f"no page: {f.relative_to(ROOT)}" for f in orphans),
            *([] if _manifest_is_current() else [f"stale: {FILES.relative_to(ROOT)}"])])
    for f in orphans:
        f.unlink()
        print(f"removed {f.relative_to(ROOT)}: its page has no Python to run any more")
    counts: dict[str, int] = {}
    done = freshness.run_jobs(refresh, [(p, (str(p), args.force)) for p in pages], args.jobs)
    for page, (status, seconds) in done:
        counts[status] = counts.get(status, 0) + 1
        if status != "up to date":
            name = notebook_file(page).relative_to(ROOT)
            print(f"{status:13} {name} ({seconds:.1f} s)", flush=True)
    if write_files_manifest(lesson_pages()):
        print(f"wrote {FILES.relative_to(ROOT)}: the files each notebook fetches outside a clone")
    print("notebooks: " + ", ".join(f"{n} {status}" for status, n in sorted(counts.items())))
    return 0


if __name__ == "__main__":
    sys.exit(main())
