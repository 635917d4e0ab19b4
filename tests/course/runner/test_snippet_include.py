"""`{% include_code path %}` fences run the named file in the page's namespace."""

P = "tests/course/runner/samples/"


def test_include_runs_file_as_main(load_sample, run_sample):
    page = load_sample("include.md")
    block = page.blocks[1]
    assert (block.line, block.include) == (8, P + "sample_script.py")
    assert block.code.startswith('"""A small script a page includes."""')
    result = run_sample("include.md")
    assert result.ok, result.failure
    assert len(result.ran) == 3


def test_error_in_included_function_names_both(run_sample):
    result = run_sample("include_fail.md")
    assert [b.line for b in result.ran] == [4]
    assert result.failure.headline == (
        P + "include_fail.md:8: " + P + "sample_broken.py:6: ValueError: negative value -1"
    )


def test_error_while_including_names_both(run_sample):
    result = run_sample("include_raise.md")
    assert result.failure.headline == (
        P + "include_raise.md:4: " + P + "sample_raise.py:4: RuntimeError: setting is None"
    )
    assert f'File "{P}sample_raise.py", line 4, in <module>' in result.failure.traceback


def test_missing_include_is_an_error(load_sample):
    page = load_sample("include_missing.md")
    assert [str(e) for e in page.errors] == [
        P + "include_missing.md:4: include_code: no file examples/no_such_file.py "
        "(paths are relative to the repository root)"
    ]


def test_include_arguments_match_the_site_plugin(tmp_path):
    from course.snippets import parse_page

    (tmp_path / "lib.py").write_text("value = 1\n")
    page_file = tmp_path / "page.md"
    page_file.write_text(
        "- item\n\n"
        "  ```python\n  {% include_code 'lib.py' indent=2 %}\n  ```\n\n"  # block at line 4
        "```python\n{% include_code ../lib.py %}\n```\n\n"  # line 8
        "```python\n{% include_code lib.py %}\nvalue += 1\n```\n"  # line 12
    )
    page = parse_page(page_file, tmp_path)
    assert [(b.line, b.include, b.code) for b in page.blocks] == [(4, "lib.py", "value = 1\n")]
    assert [(e.line, e.message.split(":")[0]) for e in page.errors] == [
        (8, "include_code"),
        (12, "{% include_code ... %} must be the only content of its ```python fence"),
    ]
