"""No broken link, image, script or anchor in the built site (html-proofer, offline).

The check over _site starts with the first browser test (conftest.py, `link_check`).
"""

from html_proofer import HtmlProofer


def test_no_broken_links_images_or_anchors(link_check):
    result = link_check.result()
    assert result.passed, f"html-proofer found problems in _site:\n{result.report}"


def test_htmlproofer_reports_what_is_broken(tmp_path):
    (tmp_path / "page").mkdir()
    (tmp_path / "page" / "index.html").write_text(
        '<!DOCTYPE html><html lang="en"><body><h2 id="here">Here</h2></body></html>')
    (tmp_path / "index.html").write_text(
        '<!DOCTYPE html><html lang="en"><body>'
        '<a href="/page/">a page</a> <a href="/page/#here">a heading</a> '
        '<a href="/missing/">a missing page</a> <a href="/page/#nowhere">a missing anchor</a> '
        '<img src="/missing.png" alt="A missing image"> '
        '<a href="https://example.com/">not followed offline</a></body></html>')
    result = HtmlProofer(tmp_path).result()
    assert not result.passed
    for problem in ("internally linking to /missing/", "internal hash #nowhere",
                    "internal image /missing.png does not exist"):
        assert problem in result.report, result.report
    for fine in ("/page/#here", "example.com"):
        assert fine not in result.report, result.report
