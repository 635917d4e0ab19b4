"""Parsing: which fences are python blocks, their page lines, front matter."""

from course.snippets import DEFAULT_TIMEOUT, parse_page

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


LAYOUT = (
    "# Title\n"                                       # 0
    "\n"
    "```python\n"                                     # 2
    "x = 1\n"
    "```\n"
    '{: data-file="examples/a.py" data-skip="not here"}\n'  # 5
    "\n"
    "1. A step\n"                                     # 7
    "\n"
    "   ```yaml\n"                                    # 9
    "   {% include_code examples/b.yaml indent=3 %}\n"
    "   ```\n"
    "   {: data-file='examples/b.yaml'}\n"            # 12
    "\n"
    "{% raw %}\n"                                     # 14
    "Shown as is: {{ x }}\n"
    "{% endraw %}\n"                                  # 16
    "{% raw %}{{ y }}{% endraw %}\n"                  # 17
    "\n"
    "<div>\n"                                         # 19
    "text\n"
    "</div>\n"
    "\n"
    "| a |\n"                                         # 23
    "|---|\n"
    "{: .parts-table}\n"                              # 25
    "\n"
    "```python\n"                                     # 27
    "y = 2\n"
    "```\n"
)


def test_the_parse_says_where_each_block_and_the_pages_other_syntax_are(tmp_path):
    page_file = tmp_path / "layout.md"
    page_file.write_text(LAYOUT)
    page = parse_page(page_file, tmp_path)
    assert page.errors == []
    first, last = page.blocks
    assert (first.fence, first.attributes, first.data_file) == ((2, 5), 5, "examples/a.py")
    assert first.skip == "not here"
    assert (last.fence, last.attributes, last.data_file) == ((27, 30), None, None)
    assert page.code_lines == {2, 3, 4, 9, 10, 11, 27, 28, 29}
    assert page.data_files == {2: "examples/a.py", 9: "examples/b.yaml"}
    assert page.attribute_lines == {5, 12, 25}
    assert page.raw_regions == [(14, 16), (17, 17)]
    assert [n for n in range(31) if page.in_raw(n)] == [14, 15]  # a raw region on one line holds none
    assert page.html_blocks == [(19, 22)]


def test_include_code_arguments_as_the_site_reads_them():
    from course.snippets.parse import INCLUDE_CODE, IncludeCode, include_code_arguments

    assert include_code_arguments("examples/a.py") == IncludeCode("examples/a.py", 0)
    assert include_code_arguments(' "with space.py"  indent=3 ') == IncludeCode("with space.py", 3)
    assert include_code_arguments("'q.py' indent=12") == IncludeCode("q.py", 12)
    assert include_code_arguments("a.py indent=three") is None
    assert include_code_arguments("a.py b.py") is None
    m = INCLUDE_CODE.search("   {%- include_code examples/b.yaml indent=3 -%} # shown")
    assert m["args"] == "examples/b.yaml indent=3"


def test_without_raw_tags_is_what_liquid_leaves():
    from course.snippets.parse import without_raw_tags

    assert without_raw_tags("{% raw %}{{ x }}{%- endraw -%}") == "{{ x }}"
    assert without_raw_tags("{% rawness %}") == "{% rawness %}"
