"""Under each ```python block the site shows what the block printed (_plugins/code_outputs.rb,
from _data/outputs/, which tests/course/test_pages.py keeps equal to what the blocks print)."""

from __future__ import annotations

import html
import json
import re
import shutil
from pathlib import Path

import pytest

from jekyll import (SITE_MACHINERY, assert_clean_build, build_log, built_page, bundle,  # noqa: F401
                    jekyll_build, whole_site)
from repository import ROOT

OUTPUTS = ROOT / "_data" / "outputs"
LONG = 15  # lines up to which an output is shown open (code_outputs.rb's LONG)
PYTHON_BLOCK = re.compile(
    r'<div\b[^>]*\bclass="[^"]*\blanguage-python\b[^"]*"[^>]*>.*?<code>(?P<code>.*?)</code>\s*</pre>\s*</div>\s*</div>'
    r'(?P<output><details class="code-output"(?P<open> open)?><summary>(?P<summary>[^<]*)</summary>'
    r'<div class="code-output-text" tabindex="0"><samp>(?P<text>.*?)</samp></div></details>)?', re.S)


def permalink(page: str) -> str:
    return re.search(r"^permalink:\s*(\S+)", (ROOT / page).read_text(encoding="utf-8"), re.M)[1]


LINE = re.compile(r'<span class="code-output-line" style="--indent: (\d+)">([^<]*)</span>')
# What counts as a line's indentation: spaces and the characters of a drawn tree.
INDENT = re.compile(r"[ \t│├└─┬┼┐┘┌]*")


def printed(m: re.Match) -> str:
    """The text an output box shows: what the block printed, its lines' spans taken away."""
    return html.unescape(re.sub(r"<[^>]+>", "", m["text"]))


def shown_blocks(page_html: str) -> list[tuple[str, re.Match]]:
    """Each python block of a built page: its first code line, and the match of it with
    the output shown under it, if any."""
    blocks = []
    for m in PYTHON_BLOCK.finditer(page_html):
        code = html.unescape(re.sub(r"<[^>]+>", "", m["code"]))
        first = next((line.strip() for line in code.splitlines() if line.strip()), "")
        blocks.append((first, m))
    return blocks


@pytest.fixture(scope="module")
def site(whole_site) -> Path:
    return whole_site


def test_a_page_shows_what_its_block_prints(site):
    page = built_page(site, permalink("_pages/practice-1/01-modelling.md")).read_text(encoding="utf-8")
    (first, m), = [(f, m) for f, m in shown_blocks(page) if m["output"]]
    assert first == "from course.practices.practice_1 import design"
    assert m["open"] and m["summary"] == "Output"
    assert printed(m).startswith("wheel: 3.051 kg, base: 2.654 kg\n")


def test_every_stored_output_is_under_its_block(site):
    """Each page with stored outputs shows each non-empty one, open or folded, under the
    block whose first line it names, and nothing under the other blocks."""
    files = sorted(OUTPUTS.glob("*.json"))
    assert files, "no stored outputs in _data/outputs/: run `python -m course.snippets --write-outputs`"
    folded = 0
    for file in files:
        stored = json.loads(file.read_text(encoding="utf-8"))
        page = built_page(site, permalink(stored["page"])).read_text(encoding="utf-8")
        blocks = shown_blocks(page)
        assert [first for first, _ in blocks] == [b["code"] for b in stored["blocks"]], file.name
        for (_, m), entry in zip(blocks, stored["blocks"]):
            expected = entry["output"]
            if not expected:
                assert m["output"] is None, f"{file.name}: an output under `{entry['code']}`"
                continue
            assert m["output"], f"{file.name}: no output under `{entry['code']}`"
            assert printed(m) == expected.rstrip()
            # Each printed line that is not empty in a span of its own (the stylesheet wraps
            # a long one with a hanging indent), the newlines between them.
            assert all(part == "" or LINE.fullmatch(part) for part in m["text"].split("\n")), \
                file.name
            # Each span says how far its line is indented, so that a wrap continues under it.
            for part in filter(None, m["text"].split("\n")):
                indent, text = LINE.fullmatch(part).groups()
                assert int(indent) == len(INDENT.match(html.unescape(text))[0]), (file.name, part)
            lines = len(expected.rstrip().splitlines())
            if lines > LONG:
                folded += 1
                assert not m["open"] and m["summary"] == f"Show output ({lines} lines)"
            else:
                assert m["open"] and m["summary"] == "Output"
    assert folded, "no output is long enough to be folded: the folding is not exercised"


def test_search_index_leaves_outputs_out(site):
    documents = json.loads((site / "assets" / "search-data.json").read_text(encoding="utf-8"))
    text = " ".join(d["text"] for d in documents)
    # Lines the blocks print, which no page's prose says.
    for printed in ("whole mechanism: 14.86 kg", "expected step per pulse: 62.6 rad/s"):
        assert printed not in text


# ---- a tiny site: outputs that no longer fit the page are not shown --------------------

PAGE = """\
---
title: Outputs
permalink: /outputs/
---

```python
print("one")
```

```python
import rospy
```
{: data-skip="needs ROS"}

```python
for i in range(20):
    print(i)
```
"""


def tiny_site(root: Path, blocks: list[dict]) -> Path:
    """A site of this repository's configuration, layout and plugins with one page of three
    python blocks, and `blocks` as its stored outputs."""
    root.mkdir(parents=True)
    for name in SITE_MACHINERY:
        source = ROOT / name
        if source.is_dir():
            shutil.copytree(source, root / name, ignore=shutil.ignore_patterns("outputs"))
        else:
            shutil.copy2(source, root / name)
    (root / "_pages").mkdir()
    (root / "_pages" / "outputs.md").write_text(PAGE, encoding="utf-8")
    (root / "_data" / "outputs").mkdir()
    (root / "_data" / "outputs" / "outputs.json").write_text(
        json.dumps({"page": "_pages/outputs.md", "blocks": blocks}), encoding="utf-8")
    return root


BLOCKS = [{"code": 'print("one")', "output": "one\n"},
          {"code": "import rospy", "output": None},
          {"code": "for i in range(20):", "output": "".join(f"{i}\n" for i in range(20))}]


def test_outputs_open_short_and_folded_long(bundle, tmp_path):
    source = tiny_site(tmp_path / "src", BLOCKS)
    result = jekyll_build(source, tmp_path / "out")
    assert_clean_build(result, "a page with outputs")
    blocks = shown_blocks((tmp_path / "out" / "outputs" / "index.html").read_text(encoding="utf-8"))
    assert [(first, m["summary"], bool(m["open"])) for first, m in blocks] == [
        ('print("one")', "Output", True), ("import rospy", None, False),
        ("for i in range(20):", "Show output (20 lines)", False)]
    assert printed(blocks[2][1]) == "\n".join(str(i) for i in range(20))


@pytest.mark.parametrize("blocks", [BLOCKS[:2], [BLOCKS[0], BLOCKS[2], BLOCKS[1]]],
                         ids=["a block too few", "blocks in another order"])
def test_outputs_for_other_blocks_are_not_shown(bundle, tmp_path, blocks):
    source = tiny_site(tmp_path / "src", blocks)
    result = jekyll_build(source, tmp_path / "out")
    assert result.returncode == 0, build_log(result)
    assert "Code outputs:" in build_log(result) and "--write-outputs" in build_log(result)
    built = (tmp_path / "out" / "outputs" / "index.html").read_text(encoding="utf-8")
    assert 'class="code-output"' not in built
