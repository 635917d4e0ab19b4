"""Parsing: which fences are python blocks, their page lines, front matter."""

from course.snippets import DEFAULT_TIMEOUT

P = "tests/course/runner/samples/"


def test_only_python_fences_are_blocks(load_sample):
    page = load_sample("passing.md")
    assert page.path == P + "passing.md"
    assert page.errors == []
    # First code line of each ```python fence, including in a list and a blockquote.
    assert [b.line for b in page.blocks] == [11, 32, 36]
    assert page.blocks[0].code.startswith("import math\n\nradius = 2.0\n")
    assert page.blocks[1].code == "assert round(area, 2) == 12.57\n"  # list indentation removed
    assert page.blocks[2].code == "quoted = True\n"
    assert all(b.skip is None and b.include is None for b in page.blocks)
    assert page.timeout == DEFAULT_TIMEOUT


def test_front_matter_lines_count(load_sample):
    page = load_sample("front_matter.md")
    assert [b.line for b in page.blocks] == [10, 14]
    assert page.timeout == 30


def test_fence_with_options_is_an_error(load_sample):
    page = load_sample("bad_fence.md")
    assert page.blocks == []
    assert [(e.line, e.message.split(":")[0]) for e in page.errors] == [
        (3, "fence info string 'python skip=yes' is not exactly 'python'"),
        (7, "fence info string 'python3' is not exactly 'python'"),
    ]
    assert str(page.errors[0]).startswith(P + "bad_fence.md:3: ")
    assert "data-skip" in page.errors[0].message


def test_liquid_in_code_needs_raw(load_sample):
    page = load_sample("liquid.md")
    assert [str(e).split(";")[0] for e in page.errors] == [
        P + "liquid.md:4: Liquid would rewrite '{{' or '{%' in this block on the site"
    ]
    assert [b.line for b in page.blocks] == [9]


def test_page_without_python_runs_nothing(tmp_path, run_sample):
    from course.snippets import parse_page, run_page

    page_file = tmp_path / "plain.md"
    page_file.write_text("# Title\n\n```bash\nfalse\n```\n")
    page = parse_page(page_file, tmp_path)
    assert page.path == "plain.md" and page.blocks == [] and page.errors == []
    result = run_page(page, tmp_path)
    assert result.ok and result.ran == []
