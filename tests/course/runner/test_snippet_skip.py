"""Skipping: only with a visible reason on an attribute line after the fence."""

P = "tests/course/runner/samples/"


def test_skip_reasons(load_sample):
    page = load_sample("skipped.md")
    assert page.errors == []
    assert [(b.line, b.skip) for b in page.blocks] == [
        (4, None),
        (8, "needs a ROS master"),
        (14, "opens a window"),  # single quotes, other attributes on the line
        (19, None),
    ]
    assert [b.line for b in page.runnable] == [4, 19]


def test_skipped_blocks_do_not_run(run_sample):
    result = run_sample("skipped.md")
    assert result.ok, result.failure
    assert [b.line for b in result.ran] == [4, 19]


def test_empty_or_detached_skip_is_an_error(load_sample, run_sample):
    page = load_sample("bad_skip.md")
    assert [(e.line, e.message.split(":")[0]) for e in page.errors] == [
        (6, "data-skip needs a non-empty quoted reason"),
        (
            12,
            "data-skip attribute is not on the line right after a closing ``` fence (kramdown would attach it to another element); move it there",
        ),
    ]
    result = run_sample("bad_skip.md")
    assert not result.ok and result.ran == []
