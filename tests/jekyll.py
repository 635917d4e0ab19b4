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

# What Jekyll reads to build the site (see _config.yml): newer files mean a stale _site.
SITE_SOURCES = ["_config.yml", "404.html", "_pages", "_layouts", "_includes", "_plugins", "_data",
                "assets", "media", "examples", "notebooks"]
# Files Jekyll leaves out of the site anyway (_plugins/verbatim_dirs.rb, _config.yml).
NOT_PUBLISHED = {"__pycache__", "MUJOCO_LOG.TXT"}
# `make site` builds _site/ and keeps Jekyll's report of that build here.
MADE_SITE = ROOT / "_site"
MADE_SITE_LOG = ROOT / ".cache" / "jekyll-build.log"


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


def jekyll_build(source: Path, destination: Path, config: Path | None = None) -> subprocess.CompletedProcess:
    """Build `source` into `destination`; `config`, a YAML file read after the site's own
    _config.yml, overrides its keys (as the Pages workflow sets url and repository)."""
    configs = ["--config", f"{source / '_config.yml'},{config}"] if config else []
    return run_bundled(["bundle", "exec", "jekyll", "build", "--source", str(source),
                        "--destination", str(destination), "--disable-disk-cache", *configs],
                       cwd=source)


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


# ---- the site `make site` built ----------------------------------------------------------


def source_files():
    """Every file Jekyll reads to build the site."""
    for name in SITE_SOURCES:
        path = ROOT / name
        if path.is_file():
            yield path
        elif path.is_dir():
            for file in path.rglob("*"):
                parts = file.relative_to(ROOT).parts
                hidden = any(p.startswith(".") or p in NOT_PUBLISHED for p in parts)
                if file.is_file() and not hidden:
                    yield file


def newer_sources(site: Path) -> list[Path]:
    """The sources changed since `site` was built (all of them when it was not built)."""
    sitemap = site / "sitemap.xml"
    if not sitemap.is_file():
        return list(source_files())
    built = sitemap.stat().st_mtime
    return [f for f in source_files() if f.stat().st_mtime > built]


def made_site_log() -> str | None:
    """Jekyll's report of the build `make site` made of _site/, if _site/ is that build and
    no source has changed since; None otherwise."""
    sitemap = MADE_SITE / "sitemap.xml"
    if not (MADE_SITE_LOG.is_file() and sitemap.is_file()):
        return None
    log = MADE_SITE_LOG.read_text(encoding="utf-8", errors="replace")
    # The log is written as the build runs, so it is at least as new as the sitemap.
    if "done in" not in log or MADE_SITE_LOG.stat().st_mtime < sitemap.stat().st_mtime:
        return None
    return None if newer_sources(MADE_SITE) else log


@pytest.fixture(scope="module")
def whole_site(bundle, tmp_path_factory) -> Path:
    """The whole site, built from this repository with no problem in Jekyll's report:
    _site/ when `make site` (run by `make test`) has just built it from the sources as
    they are, else a build of its own."""
    log = made_site_log()
    if log is not None:
        problems = [line for line in log.splitlines() if LOG_PROBLEM.search(line)]
        if problems:
            pytest.fail(f"jekyll build of the site ({MADE_SITE_LOG.relative_to(ROOT)}) reported "
                        "problems:\n" + "\n".join(problems), pytrace=False)
        return MADE_SITE
    destination = tmp_path_factory.mktemp("site")
    assert_clean_build(jekyll_build(ROOT, destination), "the site")
    return destination


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


def tiny_site(root: Path, pages: dict[str, str]) -> Path:
    """A site in `root` with this repository's configuration, layout and plugins."""
    root.mkdir(parents=True, exist_ok=True)
    for name in SITE_MACHINERY:
        source = ROOT / name
        if source.is_dir():
            shutil.copytree(source, root / name)
        else:
            shutil.copy2(source, root / name)
    # tools/render-math.mjs typesets the math with KaTeX from this repository's node_modules
    # (Node finds it from the script's real path).
    (root / "tools").symlink_to(ROOT / "tools", target_is_directory=True)
    for relative, text in pages.items():
        (root / relative).parent.mkdir(parents=True, exist_ok=True)
        (root / relative).write_text(text, encoding="utf-8")
    return root
