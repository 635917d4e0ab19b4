"""Building a Jekyll site with this repository's Gemfile, offline, for the tests that need one."""

from __future__ import annotations

import os
import re
import shutil
import subprocess
from pathlib import Path

import pytest

from repository import ROOT

# How Jekyll reports problems that do not stop a build ("Liquid Warning:", "Build
# Warning:", "Conflict:", "Deprecation:").
LOG_PROBLEM = re.compile(r"(?i)\b(warning|conflict|deprecation|error)\b")

# The site files a tiny test site borrows from the repository.
SITE_MACHINERY = ["_config.yml", "_layouts", "_includes", "_plugins", "_data"]


# ---- running Jekyll ------------------------------------------------------------------


def need_tool(tool: str) -> None:
    if shutil.which(tool) is None:
        pytest.fail(f"`{tool}` not found: run `make setup` (it installs Jekyll, Bundler and Node).",
                    pytrace=False)


def bundle_env() -> dict[str, str]:
    env = dict(os.environ)
    # Tiny sites in temporary directories use this repository's Gemfile and plugins.
    env["BUNDLE_GEMFILE"] = str(ROOT / "Gemfile")
    env["BUNDLE_SILENCE_ROOT_WARNING"] = "1"
    env.setdefault("JEKYLL_ENV", "production")
    return env


def run_bundled(command: list[str], cwd: Path = ROOT) -> subprocess.CompletedProcess:
    return subprocess.run(command, cwd=cwd, env=bundle_env(), capture_output=True, text=True, timeout=600)


def jekyll_build(source: Path, destination: Path) -> subprocess.CompletedProcess:
    return run_bundled(["bundle", "exec", "jekyll", "build", "--source", str(source),
                 "--destination", str(destination), "--disable-disk-cache"], cwd=source)


def build_log(result: subprocess.CompletedProcess) -> str:
    return (result.stdout + result.stderr).strip()


def assert_clean_build(result: subprocess.CompletedProcess, what: str) -> None:
    if result.returncode != 0:
        pytest.fail(f"jekyll build of {what} failed (exit {result.returncode}):\n{build_log(result)}",
                    pytrace=False)
    problems = [line for line in build_log(result).splitlines() if LOG_PROBLEM.search(line)]
    if problems:
        pytest.fail(f"jekyll build of {what} reported problems:\n" + "\n".join(problems), pytrace=False)


@pytest.fixture(scope="module")
def bundle() -> None:
    """Bundler resolved against the installed (Debian) gems; Gemfile.lock is local only."""
    for tool in ("ruby", "bundle"):
        need_tool(tool)
    if run_bundled(["bundle", "check"]).returncode != 0:
        result = run_bundled(["bundle", "install", "--local", "--quiet"])
        if result.returncode != 0:
            pytest.fail("`bundle install --local` failed; run `make setup`:\n" + build_log(result), pytrace=False)


def built_page(site: Path, url: str) -> Path:
    path = site / url.lstrip("/")
    return path / "index.html" if url.endswith("/") else path


def between(text: str, start: str, end: str) -> str:
    """The part of `text` from `start` up to the next `end` ('' if `start` is absent)."""
    begin = text.find(start)
    if begin < 0:
        return ""
    stop = text.find(end, begin)
    return text[begin:stop if stop >= 0 else len(text)]
