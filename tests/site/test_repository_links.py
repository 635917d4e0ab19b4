"""Where "The course repository" and "Edit this page" lead (_plugins/repository.rb).

A local build links to the GitHub repository the clone came from, read from `git remote`
when the site is built, on the branch checked out; a clone without one, or `repository:
none`, gets no such links; owner/name in _config.yml (the Pages workflow) wins over both.
Never the placeholder github.com/OWNER/REPOSITORY. One test builds a tiny site with this
repository's configuration, includes and plugins, offline (tests/jekyll.py); the others
ask the plugin's module alone, with Ruby.
"""

from __future__ import annotations

import json
import re
import shutil
import subprocess

import pytest

from jekyll import assert_clean_build, bundle, jekyll_build, tiny_site  # noqa: F401
from repository import ROOT

PLUGIN = ROOT / "_plugins" / "repository.rb"

PAGE = """---
title: A lesson
permalink: /lesson/
---

Some text.
"""


def links(site) -> tuple[list[str], list[str]]:
    """The page's footer link to the course repository, and its "Edit this page" link."""
    page = (site / "lesson" / "index.html").read_text(encoding="utf-8")
    footer = re.findall(r'href="([^"]+)">The course repository', page)
    edit = re.findall(r'<p class="page-edit"><a href="([^"]+)">Edit this page', page)
    assert "OWNER/REPOSITORY" not in page
    return footer, edit


@pytest.fixture(autouse=True)
def need_ruby():
    if shutil.which("ruby") is None:
        pytest.skip("ruby is not installed (`make setup` installs Jekyll's)")


def git(folder, *args):
    subprocess.run(["git", "-C", str(folder), *args], check=True, capture_output=True)


def test_a_clone_links_to_its_own_remote_and_branch(bundle, tmp_path):
    source = tiny_site(tmp_path / "src", {"_pages/lesson.md": PAGE})
    git(source, "init", "--quiet", "--initial-branch", "lessons")
    git(source, "remote", "add", "upstream", "https://github.com/elsewhere/other.git")
    git(source, "remote", "add", "origin", "git@github.com:someone/course.git")
    result = jekyll_build(source, tmp_path / "site")
    assert_clean_build(result, "a clone with a GitHub remote")
    assert links(tmp_path / "site") == (["https://github.com/someone/course"],
                                        ["https://github.com/someone/course/edit/lessons/_pages/lesson.md"])


def resolve(folder, **config) -> dict:
    """_config.yml's two keys as _plugins/repository.rb leaves them for a build of `folder`."""
    script = (f"require {str(PLUGIN)!r}\n"
              "config = JSON.parse(ARGV[1])\n"
              "Sw2simSite::Repository.resolve(config, ARGV[0])\n"
              "print JSON.generate(config)\n")
    done = subprocess.run(["ruby", "-rjson", "-e", script, str(folder), json.dumps(config)],
                          capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


def test_without_a_remote_or_with_none_there_are_no_such_links(tmp_path):
    auto = {"repository": "auto", "repository_branch": "auto"}
    # Not a clone at all, then a clone whose only remote is not on GitHub.
    assert resolve(tmp_path, **auto) == {"repository": "", "repository_branch": "main"}
    git(tmp_path, "init", "--quiet", "--initial-branch", "lessons")
    git(tmp_path, "remote", "add", "origin", "https://gitlab.com/someone/course.git")
    assert resolve(tmp_path, **auto) == {"repository": "", "repository_branch": "lessons"}
    git(tmp_path, "remote", "set-url", "origin", "https://github.com/someone/course")
    assert resolve(tmp_path, **auto)["repository"] == "someone/course"
    # `none` leaves the links out; owner/name wins over the remote.
    assert resolve(tmp_path, repository="none", repository_branch="auto")["repository"] == ""
    assert resolve(tmp_path, repository="pages/site", repository_branch="main") == \
        {"repository": "pages/site", "repository_branch": "main"}


def test_a_wrong_value_stops_the_build_naming_the_setting(tmp_path):
    with pytest.raises(AssertionError, match=r"_config\.yml: repository is .*owner/name"):
        resolve(tmp_path, repository="https://github.com/someone/course", repository_branch="main")
