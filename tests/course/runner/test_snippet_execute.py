"""Execution and reports: one process per page, one namespace, page line numbers."""

from course.snippets import format_failure

P = "tests/course/runner/samples/"


def test_passing_page(run_sample):
    result = run_sample("passing.md")
    assert result.ok, format_failure(result)
    assert [b.line for b in result.ran] == [11, 32, 36]
    assert format_failure(result) == ""


def test_failure_names_page_line(run_sample):
    result = run_sample("failing.md")
    assert not result.ok
    assert [b.line for b in result.ran] == [6]  # the third block never runs
    failure = result.failure
    assert failure.headline == P + "failing.md:15: ZeroDivisionError: division by zero"
    assert failure.block.line == 13
    assert failure.output == "about to fail\n"
    assert f'File "{P}failing.md", line 15, in <module>' in failure.traceback
    assert "ratio = total / 0" in failure.traceback  # source shown from the page itself
    assert "child.py" not in failure.traceback
    report = format_failure(result)
    assert report.splitlines()[0] == failure.headline
    assert f"in the block starting at {P}failing.md:13" in report
    assert "| about to fail" in report


def test_front_matter_keeps_line_numbers(run_sample):
    result = run_sample("front_matter.md")
    assert result.failure.headline == (P + "front_matter.md:15: NameError: name 'undefined_name' is not defined")


def test_namespace_is_shared_and_deepest_page_frame_wins(run_sample):
    result = run_sample("namespace.md")
    assert [b.line for b in result.ran] == [4, 9]
    # The error is inside the function from the first block, called from the third.
    assert result.failure.headline == (P + "namespace.md:5: TypeError: 'NoneType' object is not iterable")
    assert result.failure.block.line == 15


def test_syntax_error_line(run_sample):
    result = run_sample("syntax.md")
    assert result.failure.headline == P + "syntax.md:9: SyntaxError: expected ':'"
    assert result.failure.block.line == 8


def test_exit_status(run_sample):
    result = run_sample("exit_zero.md")
    assert [b.line for b in result.ran] == [4]
    assert result.failure.headline == P + "exit_zero.md:11: SystemExit: 2"


def test_process_exit_is_reported_with_its_block(run_sample):
    result = run_sample("dies.md")
    assert result.failure.headline == (P + "dies.md:8: Python process exited with status 3 while running this block")
    assert result.failure.output == "bye\n"


def test_crash_is_reported_with_its_block(run_sample):
    result = run_sample("segfault.md")
    assert result.failure.headline == (P + "segfault.md:8: Python process died of SIGSEGV while running this block")
    # The fault handler's dump points at the page line.
    assert f'File "{P}segfault.md", line 8' in result.failure.output


def test_child_environment(tmp_path, fork):
    from course.snippets import parse_page, run_page

    page_file = tmp_path / "env.md"
    page_file.write_text(
        "```python\nimport os, pathlib, sys\n"
        "assert sys.path[0] == '' and sys.argv == ['']\n"
        "assert 'sw2sim' not in sys.modules and 'numpy' not in sys.modules\n"
        "def f(x: int): pass\n"
        "assert f.__annotations__ == {'x': int}  # no inherited __future__ flags\n"
        "import pickle\n"
        "class Point: pass\n"
        "assert type(pickle.loads(pickle.dumps(Point()))) is Point  # __main__ is the namespace\n"
        "assert os.environ['MPLBACKEND'] == 'Agg'\n"
        "assert os.environ['MUJOCO_GL']\n"
        f"assert pathlib.Path.cwd() == pathlib.Path({str(tmp_path.resolve())!r})\n```\n"
    )
    result = run_page(parse_page(page_file, tmp_path), tmp_path, fork=fork)
    assert result.ok, format_failure(result)
