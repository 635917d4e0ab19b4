"""Per-block time limit from the front matter; the stuck block is named."""

import time

P = "tests/course/runner/samples/"


def test_block_timeout(load_sample, run_sample):
    assert load_sample("timeout.md").timeout == 1
    began = time.monotonic()
    result = run_sample("timeout.md")
    assert time.monotonic() - began < 15
    assert [b.line for b in result.ran] == [6]
    assert result.failure.headline == P + "timeout.md:11: block timed out after 1 s"
    # The child dumps its stack before it is killed: the output shows the stuck line.
    assert "going to sleep" in result.failure.output
    assert f'File "{P}timeout.md", line 12' in result.failure.output


def test_timeout_override(run_sample):
    result = run_sample("passing.md", timeout=30)
    assert result.ok


def test_bad_timeout_is_an_error(tmp_path):
    from course.snippets import DEFAULT_TIMEOUT, parse_page

    page_file = tmp_path / "page.md"
    page_file.write_text("---\ntitle: t\nsnippet_timeout: soon\n---\n")
    page = parse_page(page_file, tmp_path)
    assert page.timeout == DEFAULT_TIMEOUT
    assert [str(e) for e in page.errors] == [
        "page.md:3: snippet_timeout must be a positive number of seconds, not 'soon'"
    ]
