"""Find the ```python blocks of a lesson page, with their page lines and skip reasons,
the blocks that run under ROS 1 (`data-ros`, python or bash) for course.snippets.ros, and
those that run under ROS 2 (`data-ros2`) for course.snippets.ros2. A block marked
`data-ros2-needs="WHAT"` is shown only: it needs what this machine lacks (ROS 2 Jazzy's
`ros2` command, Gazebo Sim), and a python block so marked is skipped with that reason.

The parse also records where the page's other syntax is, for course.notebooks to turn the
rest of the page into notebook Markdown: every code listing and its attribute line,
`{% raw %}` regions and HTML blocks, all by 0-based page line.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field, replace
from pathlib import Path

from markdown_it import MarkdownIt

DEFAULT_TIMEOUT = 120.0
LANGUAGE = "python"

# A kramdown block attribute list on a line of its own, possibly inside a blockquote.
_IAL = re.compile(r"^\s*(?:>\s*)*\{:(?P<body>.*)\}\s*$")
_SKIP = re.compile(r"""(?<![\w-])data-skip\s*=\s*(?:"(?P<dq>[^"]*)"|'(?P<sq>[^']*)')""")
_DATA_ROS = re.compile(r"""(?<![\w-])data-ros\s*=\s*(?:"(?P<dq>[^"]*)"|'(?P<sq>[^']*)')""")
_DATA_ROS2 = re.compile(r"""(?<![\w-])data-ros2\s*=\s*(?:"(?P<dq>[^"]*)"|'(?P<sq>[^']*)')""")
_ROS2_NEEDS = re.compile(r"""(?<![\w-])data-ros2-needs\s*=\s*(?:"(?P<dq>[^"]*)"|'(?P<sq>[^']*)')""")
_ROS_LANGUAGES = (LANGUAGE, "bash")
_TERMINAL = re.compile(r"""(?<![\w-])data-terminal\s*=\s*(?:"(?P<dq>[^"]*)"|'(?P<sq>[^']*)')""")
_ROS_SETUP = re.compile(r"(?<![\w-])data-ros-setup(?![\w-])")
_ROS2_SETUP = re.compile(r"(?<![\w-])data-ros2-setup(?![\w-])")
_ROS2_ONCE = re.compile(r"(?<![\w-])data-ros2-once(?![\w-])")
_ROS_RUNNING = re.compile(r"^ros_running\s*:\s*(?P<value>.+?)\s*(?:#.*)?$")
_DATA_FILE = re.compile(r"""(?<![\w-])data-file\s*=\s*(?:"(?P<dq>[^"]*)"|'(?P<sq>[^']*)')""")
# An `{% include_code ... %}` tag anywhere in a line; `args` is what follows the name.
INCLUDE_CODE = re.compile(r"\{%-?\s*include_code\s+(?P<args>.*?)\s*-?%\}")
# Same arguments as _plugins/include_code.rb: a path, optionally quoted, and `indent=N`.
_INCLUDE_ARGS = re.compile(
    r"""^(?:"(?P<dq>[^"]+)"|'(?P<sq>[^']+)'|(?P<bare>\S+))(?:\s+indent=(?P<indent>\d+))?$""")
_RAW_TAG = re.compile(r"\{%-?\s*(?P<end>end)?raw\s*-?%\}")
_TIMEOUT = re.compile(r"^snippet_timeout\s*:\s*(?P<value>\S+)\s*(?:#.*)?$")
_NO_LIQUID = re.compile(r"^render_with_liquid\s*:\s*false\s*(?:#.*)?$")
# Names that look like Python but are not run: better an error than a silent hole.
_PYTHON_LIKE = re.compile(r"^(?:python\S*|py|py3)$", re.IGNORECASE)


@dataclass(frozen=True)
class Block:
    """One ```python fence of a page."""

    page: str  # page path as reported, relative to the repository root
    line: int  # 1-based page line of the first code line
    code: str  # what runs: the fence's text, or the included file's text
    skip: str | None = None  # reason from `{: data-skip="..."}`, None = runs
    include: str | None = None  # file named by `{% include_code ... %}`
    fence: tuple[int, int] = (0, 0)  # 0-based page lines [start, end) of the fence, ``` included
    attributes: int | None = None  # 0-based line of the `{: ...}` line right after the fence
    data_file: str | None = None  # its `data-file="..."`: the file shown above the block
    # its `data-ros="PACKAGE"`: it runs under ROS 1 in that example package, not in Python
    ros: str | None = None
    # its `data-ros2="PACKAGE"`: it runs under ROS 2 with the package `sw2sim port` wrote
    ros2: str | None = None
    language: str = LANGUAGE
    # its `data-terminal="N"`: the reader's terminal a ROS command block is typed in (1 is
    # the first; a number not used before is a new terminal, opened as Getting started says)
    terminal: int = 1

    @property
    def filename(self) -> str:
        """File name the code is compiled under, so tracebacks point at it."""
        return self.include or self.page

    @property
    def location(self) -> str:
        return f"{self.page}:{self.line}"


@dataclass(frozen=True)
class ParseError:
    """A page mistake that would make CI untrustworthy, at a page line."""

    page: str
    line: int
    message: str

    def __str__(self) -> str:
        return f"{self.page}:{self.line}: {self.message}"


@dataclass
class Page:
    """A lesson page: its python blocks in page order, plus anything wrong with it."""

    path: str
    blocks: list[Block] = field(default_factory=list)
    timeout: float = DEFAULT_TIMEOUT
    errors: list[ParseError] = field(default_factory=list)
    # Where the rest of the page's syntax is, by 0-based page line. Code: in a fence of any
    # language (its ``` lines too) or an indented code block.
    code_lines: set[int] = field(default_factory=set)
    data_files: dict[int, str] = field(default_factory=dict)  # first line of code -> its data-file
    attribute_lines: set[int] = field(default_factory=set)  # kramdown `{: ...}` lines outside code
    # (line of a {% raw %}, line of its {% endraw %}; the page's end if there is none)
    raw_regions: list[tuple[int, int]] = field(default_factory=list)
    html_blocks: list[tuple[int, int]] = field(default_factory=list)  # [start, end) of HTML blocks
    commands: list[Block] = field(default_factory=list)  # ```bash blocks with data-ros
    # Front matter `ros_running: roslaunch PKG FILE`: what the page assumes already runs.
    ros_running: str | None = None
    # A ```bash block marked `data-ros-setup`: what every new terminal runs before a ROS 1
    # command (Getting started has it; the ROS page runner opens each terminal with it).
    ros_setup: Block | None = None
    # Getting started's ```bash blocks for the ROS 2 pages: what the reader runs once in the
    # clone's folder (`data-ros2-once`), and what every new terminal of a ROS 2 page runs
    # first (`data-ros2-setup`); the ROS 2 page runner opens its terminals with them.
    ros2_once: Block | None = None
    ros2_setup: Block | None = None
    ros2_commands: list[Block] = field(default_factory=list)  # ```bash blocks with data-ros2
    # Blocks of any language marked data-ros2-needs="WHAT": (block, WHAT). Shown, not run.
    ros2_needs: list[tuple[Block, str]] = field(default_factory=list)

    @property
    def runnable(self) -> list[Block]:
        """The python blocks the page runner runs."""
        return [b for b in self.blocks if b.skip is None and b.ros is None and b.ros2 is None]

    @property
    def ros_blocks(self) -> list[Block]:
        """The blocks that run under ROS 1, python and bash, in page order."""
        return sorted([b for b in self.blocks if b.ros] + self.commands, key=lambda b: b.line)

    @property
    def ros2_blocks(self) -> list[Block]:
        """The blocks that run under ROS 2, python nodes and bash commands, in page order."""
        return sorted([b for b in self.blocks if b.ros2] + self.ros2_commands,
                      key=lambda b: b.line)

    @property
    def skipped(self) -> list[Block]:
        return [b for b in self.blocks if b.skip is not None]

    def in_raw(self, line: int) -> bool:
        """Whether Liquid is inside a `{% raw %}` region at the end of 0-based `line`: from
        the line that opens it to the line before the one that closes it."""
        return any(start <= line < end for start, end in self.raw_regions)


@dataclass(frozen=True)
class IncludeCode:
    """The arguments of an `{% include_code path [indent=N] %}` tag."""

    path: str  # from the repository root
    # Spaces the site puts before every line but the first, for a fence in a list (only the
    # rendered page needs them: the runner gets the fence's content dedented).
    indent: int = 0


def include_code_arguments(args: str) -> IncludeCode | None:
    """An include_code tag's arguments as _plugins/include_code.rb reads them, or None if
    they are not `path [indent=N]`. The path is not checked."""
    a = _INCLUDE_ARGS.match(args.strip())
    if a is None:
        return None
    return IncludeCode(a["dq"] or a["sq"] or a["bare"], int(a["indent"] or 0))


def without_raw_tags(text: str) -> str:
    """Text as Liquid leaves it: without `{% raw %}` and `{% endraw %}` tags."""
    return _RAW_TAG.sub("", text)


def find_pages(root: Path) -> list[Path]:
    """Every lesson page under `root/_pages`, sorted."""
    return sorted((root / "_pages").rglob("*.md"))


def display_path(path: Path, root: Path) -> str:
    """Path relative to the repository root when inside it (what tracebacks show)."""
    path = path.resolve()
    try:
        return path.relative_to(root.resolve()).as_posix()
    except ValueError:
        return str(path)


def split_front_matter(lines: list[str]) -> tuple[list[str], int]:
    """Jekyll front matter lines and how many page lines it takes (0 if none)."""
    if lines and lines[0].rstrip() == "---":
        for i in range(1, len(lines)):
            if lines[i].rstrip() in ("---", "..."):
                return lines[1:i], i + 1
    return [], 0


def parse_page(path: Path, root: Path) -> Page:
    """Read a page and collect its python blocks; mistakes go to `Page.errors`."""
    page = Page(display_path(path, root))
    lines = path.read_text(encoding="utf-8").split("\n")
    front, body_start = split_front_matter(lines)
    # Blank the front matter rather than cut it, so token line numbers stay page lines.
    scan = _Scan(page, root, [""] * body_start + lines[body_start:])
    scan.front_matter(front)
    scan.fences()
    scan.stray_attributes()
    return page


@dataclass
class _Scan:
    """State of one page's parse."""

    page: Page
    root: Path
    body: list[str]  # page lines, front matter blanked
    liquid: bool = True  # whether Jekyll runs Liquid over the page
    attached: set[int] = field(default_factory=set)  # 0-based attribute lines after a fence

    def error(self, line: int, message: str) -> None:
        self.page.errors.append(ParseError(self.page.path, line, message))

    def front_matter(self, front: list[str]) -> None:
        for line, text in enumerate(front, start=2):
            text = text.strip()
            if m := _TIMEOUT.match(text):
                try:
                    self.page.timeout = float(m["value"])
                except ValueError:
                    self.page.timeout = 0
                if not self.page.timeout > 0:
                    self.page.timeout = DEFAULT_TIMEOUT
                    self.error(line, f"snippet_timeout must be a positive number of seconds, not {m['value']!r}")
            elif _NO_LIQUID.match(text):
                self.liquid = False
            elif m := _ROS_RUNNING.match(text):
                self.page.ros_running = m["value"].strip().strip("\"'")

    def fences(self) -> None:
        raw = self.page.raw_regions = _raw_regions(self.body)
        for token in MarkdownIt("commonmark").parse("\n".join(self.body)):
            if token.type == "html_block" and token.map is not None:
                self.page.html_blocks.append((token.map[0], token.map[1]))
            if token.type not in ("fence", "code_block") or token.map is None:
                continue
            start, end = token.map
            self.page.code_lines.update(range(start, end))
            ial = _IAL.match(self.body[end]) if end < len(self.body) else None
            if ial and (f := _DATA_FILE.search(ial["body"])):
                self.page.data_files[start] = f["dq"] if f["dq"] is not None else f["sq"]
            if token.type != "fence":
                continue
            if ial:
                self.attached.add(end)
            info = token.info.strip()
            ros = self.ros_package(ial, info, end)
            ros2 = self.ros2_package(ial, info, end)
            needs = self.ros2_needs(ial, end)
            if needs:
                self.page.ros2_needs.append((Block(self.page.path, start + 2,
                                                   without_raw_tags(token.content),
                                                   fence=(start, end), attributes=end,
                                                   language=info), needs))
            if info == "bash" and ros2:
                code = without_raw_tags(token.content)
                self.page.ros2_commands.append(Block(self.page.path, start + 2, code,
                                                     fence=(start, end), attributes=end,
                                                     ros2=ros2, language="bash",
                                                     terminal=self.terminal(ial, end)))
                continue
            for pattern, name in ((_ROS2_ONCE, "ros2_once"), (_ROS2_SETUP, "ros2_setup")):
                if info == "bash" and ial and pattern.search(ial["body"]):
                    setattr(self.page, name, Block(self.page.path, start + 2,
                                                   without_raw_tags(token.content),
                                                   fence=(start, end), attributes=end,
                                                   language="bash"))
            if info == "bash" and ial and _ROS_SETUP.search(ial["body"]):
                self.page.ros_setup = Block(self.page.path, start + 2,
                                            without_raw_tags(token.content), fence=(start, end),
                                            attributes=end, language="bash")
                continue
            if info == "bash" and ros:
                code = without_raw_tags(token.content)
                self.page.commands.append(Block(self.page.path, start + 2, code, fence=(start, end),
                                                attributes=end, ros=ros, language="bash",
                                                terminal=self.terminal(ial, end)))
                continue
            if info != LANGUAGE:
                if info and _PYTHON_LIKE.match(info.split()[0]):
                    self.error(
                        start + 1,
                        f"fence info string {info!r} is not exactly 'python': the site would not "
                        "show it as Python code and it would not run; write ```python and put any "
                        "option on an attribute line right after the closing fence, e.g. "
                        '{: data-skip="why it cannot run"}',
                    )
                continue
            protected = any(a <= end - 1 and b >= start for a, b in raw)
            block = self.block(token.content, start, end, protected)
            if block is not None:
                if needs and block.skip is None:
                    block = replace(block, skip=f"needs {needs}")
                self.page.blocks.append(replace(block, fence=(start, end), attributes=end if ial else None,
                                                data_file=self.page.data_files.get(start), ros=ros,
                                                ros2=ros2))

    def terminal(self, ial, end: int) -> int:
        """The terminal a ROS command block's `data-terminal="N"` names (1 without one)."""
        t = _TERMINAL.search(ial["body"]) if ial else None
        if t is None:
            return 1
        value = (t["dq"] if t["dq"] is not None else t["sq"]).strip()
        if not value.isdigit() or int(value) < 1:
            self.error(end + 1, f'data-terminal names the reader\'s terminal by its number, 1, 2, '
                                f'...: {{: data-ros="example_3" data-terminal="2"}}, not {value!r}')
            return 1
        return int(value)

    def ros_package(self, ial, info: str, end: int) -> str | None:
        """The package a block's `data-ros="PACKAGE"` names, or None; mistakes are errors."""
        if not ial or not re.search(r"(?<![\w-])data-ros\s*=", ial["body"]):
            return None
        r = _DATA_ROS.search(ial["body"])
        package = (r["dq"] if r["dq"] is not None else r["sq"]).strip() if r else ""
        if not package or not re.fullmatch(r"[A-Za-z]\w*(/\.\.)?", package):
            self.error(end + 1, 'data-ros names the example package the block runs in, or the '
                                'folder that holds it: {: data-ros="example_3"} or '
                                '{: data-ros="example_3/.."}')
            return None
        if info not in _ROS_LANGUAGES:
            self.error(end + 1, f"data-ros is for ```python nodes and ```bash commands, not {info!r}")
            return None
        if "data-skip" in ial["body"]:
            self.error(end + 1, "a block has data-ros (it runs under ROS) or data-skip (it does not), "
                                "not both")
            return None
        if not (self.root / "examples" / package.split("/")[0]).is_dir():
            self.error(end + 1, f"data-ros: no package examples/{package.split('/')[0]}")
            return None
        return package

    def ros2_package(self, ial, info: str, end: int) -> str | None:
        """The package a block's `data-ros2="PACKAGE"` names (the folder `sw2sim port`
        writes), or None; mistakes are errors."""
        if not ial or not re.search(r"(?<![\w-])data-ros2\s*=", ial["body"]):
            return None
        r = _DATA_ROS2.search(ial["body"])
        package = (r["dq"] if r["dq"] is not None else r["sq"]).strip() if r else ""
        if not re.fullmatch(r"[A-Za-z]\w*", package):
            self.error(end + 1, 'data-ros2 names the ROS 2 package the block works with, as '
                                '`sw2sim port` writes it: {: data-ros2="example_3"}')
            return None
        if info not in _ROS_LANGUAGES:
            self.error(end + 1, f"data-ros2 is for ```python nodes and ```bash commands, not {info!r}")
            return None
        for other in ("data-skip", "data-ros2-needs", "data-ros"):
            if re.search(rf"(?<![\w-]){other}\s*=", ial["body"]):
                self.error(end + 1, f"a block has data-ros2 (it runs under ROS 2 here) or {other}, "
                                    "not both")
                return None
        return package

    def ros2_needs(self, ial, end: int) -> str | None:
        """What a block marked `data-ros2-needs="WHAT"` needs, or None."""
        if not ial or "data-ros2-needs" not in ial["body"]:
            return None
        n = _ROS2_NEEDS.search(ial["body"])
        what = (n["dq"] if n["dq"] is not None else n["sq"]).strip() if n else ""
        if not what:
            self.error(end + 1, 'data-ros2-needs says what the block needs: '
                                '{: data-ros2-needs="ros2 launch and Gazebo Sim"}')
            return None
        if "data-skip" in ial["body"]:
            self.error(end + 1, "a block has data-ros2-needs or data-skip, not both")
            return None
        return what

    def block(self, content: str, start: int, end: int, protected: bool) -> Block | None:
        """The Block of a python fence over 0-based lines [start, end), or None on error."""
        line = start + 2  # 1-based line of the first code line
        skip = None
        if end < len(self.body) and (m := _IAL.match(self.body[end])) and "data-skip" in m["body"]:
            s = _SKIP.search(m["body"])
            reason = (s["dq"] if s["dq"] is not None else s["sq"]) if s else None
            if reason is None or not reason.strip():
                self.error(end + 1, 'data-skip needs a non-empty quoted reason: {: data-skip="why"}')
                return None
            skip = reason.strip()

        # Liquid runs before Markdown on the site: the reader sees code without raw tags.
        code = without_raw_tags(content)
        if m := INCLUDE_CODE.fullmatch(code.strip()):
            return self.include(m["args"], line, skip)
        if "include_code" in code and "{%" in code:
            self.error(line, "{% include_code ... %} must be the only content of its ```python fence")
            return None
        if self.liquid and not protected and ("{{" in code or "{%" in code):
            self.error(
                line,
                "Liquid would rewrite '{{' or '{%' in this block on the site; wrap the fence in "
                "{% raw %} ... {% endraw %} (or set render_with_liquid: false in the front matter)",
            )
            return None
        return Block(self.page.path, line, code, skip)

    def include(self, args: str, line: int, skip: str | None) -> Block | None:
        """The Block running the file an `{% include_code %}` fence shows."""
        tag = include_code_arguments(args)
        if tag is None:
            self.error(line, f"include_code expects `path [indent=N]`, got {args!r}")
            return None
        path = tag.path
        if path.startswith(("/", "~")) or ".." in re.split(r"[/\\]", path):
            self.error(line, f"include_code: {path} must be relative to the repository root, without '..'")
            return None
        target = self.root / path
        if not target.is_file():
            self.error(line, f"include_code: no file {path} (paths are relative to the repository root)")
            return None
        return Block(self.page.path, line, target.read_text(encoding="utf-8"), skip, path)

    def stray_attributes(self) -> None:
        """Note the attribute lines outside code. A data-skip line kramdown would not attach
        to a fence hides nothing: say so."""
        for i, text in enumerate(self.body):
            if i in self.page.code_lines:
                continue
            if _IAL.match(without_raw_tags(text)):
                self.page.attribute_lines.add(i)
            if i in self.attached:
                continue
            if (m := _IAL.match(text)) and "data-skip" in m["body"]:
                self.error(
                    i + 1,
                    "data-skip attribute is not on the line right after a closing ``` fence "
                    "(kramdown would attach it to another element); move it there",
                )


def _raw_regions(lines: list[str]) -> list[tuple[int, int]]:
    """0-based line spans between `{% raw %}` and `{% endraw %}`."""
    regions: list[tuple[int, int]] = []
    opened: int | None = None
    for i, text in enumerate(lines):
        for m in _RAW_TAG.finditer(text):
            if m["end"] is None and opened is None:
                opened = i
            elif m["end"] is not None and opened is not None:
                regions.append((opened, i))
                opened = None
    if opened is not None:
        regions.append((opened, len(lines)))
    return regions
