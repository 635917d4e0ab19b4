"""Every sentence of the pages that says what the exporter, gazebo_ros_control or ros_control
does, or on the ROS 2 side gz_ros2_control, ros2_control, a ros2_controllers controller,
control_toolbox, robot_state_publisher, ros_gz or rclpy, links to the lines of the tool's source
that do it (course/sources.py, _data/sources.yml).

"A statement about a tool's behaviour" is the narrow rule of course.sources.STATEMENT: a
sentence of a page's prose (not code, not HTML, not a heading) whose subject is the exporter
("the exporter", *Export URDF and Meshes...*, *Export URDF Only...*, *Automatically
Generate*), gazebo_ros_control, ros_control, joint_limits_interface or the controller manager,
or a ROS 2 tool by name (gz_ros2_control, `joint_state_broadcaster`, `rclpy.spin`, the
trajectory controller, ...; on a ROS 2 page also "the controller"), followed by a verb of doing
(writes, reads, takes, sets, skips, ...) or a negation of one. Such a sentence carries
`{% include source.html id="..." %}` inside it or right after it.

The ROS 2 versions are those /reference/ros2-controllers/ states: every link to those tools, on
a page or in the data file, is at that release's tag.

The links are checked offline: each is a github blob URL at a release tag (or a maintained
branch) with its lines, and agrees with the entry's tool, tag, file and lines. Where a copy of
the tool's repository has been fetched (/work/.mirror/<owner>+<name>/repo, as
test_reference_exporter_dialogs.py reads the exporter's), the cited lines are read at that tag
and must exist and contain the entry's anchor.
"""

from __future__ import annotations

import re
import subprocess
from pathlib import Path

import pytest

from course import sources
from course.notebooks import build
from repository import ROOT

MIRRORS = Path("/work/.mirror")
# Refs a link may name besides release tags: branches that no longer move.
FIXED_BRANCHES = {"noetic-devel", "jazzy"}
# A release: 1.2.3, or as Gazebo's libraries and DART name theirs (sdformat14_14.8.0, v6.13.2).
RELEASE_TAG = re.compile(r"^(?:[a-z][a-z-]*\d+_|v)?\d+\.\d+\.\d+$")
PAGES = sorted(sources.PAGES.rglob("*.md"))


@pytest.fixture(scope="module")
def entries() -> dict[str, sources.Source]:
    return sources.load()


def page_ids() -> dict[str, list[str]]:
    """id -> the pages that cite it."""
    cited: dict[str, list[str]] = {}
    for path in PAGES:
        for id in sources.included_ids(path.read_text(encoding="utf-8")):
            cited.setdefault(id, []).append(path.relative_to(ROOT).as_posix())
    return cited


# ---- the rule: which sentences are statements, and which cite ----------------------------

@pytest.mark.parametrize("sentence", [
    "The exporter writes each mesh in its link's frame.",
    "Left alone, the exporter then writes zeros for all four.",
    "What the exporter does not read is a mass set by hand.",
    "*Export URDF Only...* skips only the meshes.",
    "**Export URDF and Meshes...** writes the whole package.",
    "ROS's `gazebo_ros_control` applies them; MuJoCo does not.",
    "The controller manager runs every controller 1000 times a second.",
    "a joint held by a mate has no freedom left, and the exporter would make it fixed.",
    "With `update_rate: 1000`, `gz_ros2_control` updates the controller manager every 1 ms.",
    "The `joint_state_broadcaster` publishes every joint's position on `/joint_states`.",
    "`rclpy.spin_once` waits for the next callback that is due.",
    "Jazzy's `ackermann_steering_controller` refuses to start without two traction joints.",
    "Gazebo Sim's plugin reads the names `position`, `velocity` and `effort`.",
    "When only positions are given, the trajectory controller moves the reference in a line.",
    "`min` and `max` are the command's range as ros2_control reads it.",
])
def test_the_rule_takes_these_for_statements(sentence):
    assert sources.STATEMENT.search(sentence), sentence


@pytest.mark.parametrize("sentence", [
    "Older versions of the exporter misspelt the attributes.",   # the subject is "versions"
    "The exporter's dialogs ask for the limits.",                 # the subject is "dialogs"
    "`enforce_limits` is the rule of ros_control's soft joint limits.",
    "Then add the reference geometry the exporter will need.",    # not a verb of doing
    "The pages before this one use ROS 1, as the exporter does.",
    "[The exporter, option by option](/reference/exporter/) explains every field.",
    "The controller keeps the efforts it got last.",      # "the controller" only on ROS 2 pages
    "Gazebo Sim's ROS 2 plugin is gz_ros2_control.",      # not a verb of doing
    "The trajectory controllers keep their ROS 1 names.",  # the plural is no tool's name
    "`ros2_control`'s parameters sit under the manager.",  # the subject is "parameters"
])
def test_the_rule_leaves_these_out(sentence):
    assert not sources.STATEMENT.search(sentence), sentence


def test_on_a_ros2_page_the_controller_is_a_ros2_controller():
    sentence = "The controller keeps applying the efforts it got last until it is told otherwise."
    assert sources.ROS2_STATEMENT.search(sentence) and not sources.STATEMENT.search(sentence)
    assert not sources.ROS2_STATEMENT.search("The controller manager's section names the types.")
    assert not sources.ROS2_STATEMENT.search("The controller's topic is `~/commands`.")
    assert sources.is_ros2_page(sources.PAGES / "practice-1/06-ros2.md")
    assert not sources.is_ros2_page(sources.PAGES / "practice-3/04-controllers.md")


def test_an_include_belongs_to_the_sentence_it_follows():
    text = ('The exporter writes one mesh.{% include source.html id="one-mesh" %} '
            'The exporter copies the colour. It ends *Export URDF Only...* here, '
            'where Lxx ... Lzz are values.{% include source.html id="colour" %}')
    assert sources.sentences(text) == [
        'The exporter writes one mesh.{% include source.html id="one-mesh" %}',
        "The exporter copies the colour.",
        "It ends *Export URDF Only...* here, where Lxx ... Lzz are values."
        '{% include source.html id="colour" %}']


def test_prose_leaves_out_code_html_headings_and_raw_examples(tmp_path):
    page = tmp_path / "page.md"
    page.write_text('---\ntitle: The exporter writes a title.\n---\n\n'
                    "## The exporter writes a heading\n\n"
                    "```python\n# The exporter writes a comment.\n```\n\n"
                    '<div markdown="0">The exporter writes HTML.</div>\n\n'
                    "{% raw %}The exporter writes an example.{% endraw %}\n\n"
                    "| a | b |\n|---|---|\n| x | The exporter writes a cell. |\n\n"
                    "- The exporter writes a list item.\n", encoding="utf-8")
    found = [text for _, text in sources.prose(page) if "exporter" in text]
    assert found == ["The exporter writes a cell.", "The exporter writes a list item."]


# ---- the pages ---------------------------------------------------------------------------

def test_every_statement_about_a_tools_behaviour_cites_its_source():
    statements = [s for path in PAGES for s in sources.statements(path)]
    # The rule finds the statements it is meant for: at least these pages make some.
    pages = {s.page for s in statements}
    assert {"reference/02-exporter.md", "practice-1/02-exporting.md",
            "practice-3/03-transmissions.md", "reference/05-ros1-to-ros2.md",
            "reference/09-ros2-controllers.md", "practice-1/06-ros2.md"} <= pages
    bare = [str(s) for s in statements if not s.cited]
    assert not bare, ("Sentences that say what a tool does without a source link: end each with "
                      '{% include source.html id="..." %} (an entry of _data/sources.yml):\n'
                      + "\n".join(bare))


def test_the_exceptions_to_the_rule_still_match_a_sentence():
    """An exception for a sentence the pages no longer have would hide a new one."""
    for (page, words), why in sources.NOT_THE_TOOL.items():
        text = " ".join((sources.PAGES / page).read_text(encoding="utf-8").split())
        assert words in text, (page, words, why)


def test_every_cited_id_is_an_entry_and_every_entry_is_cited(entries):
    cited = page_ids()
    unknown = {id: where for id, where in cited.items() if id not in entries}
    assert not unknown, f"ids cited by pages but missing from {sources.DATA}: {unknown}"
    unused = sorted(set(entries) - set(cited))
    assert not unused, f"entries of {sources.DATA} no page cites (remove or cite them): {unused}"


# ---- the data file -----------------------------------------------------------------------

def test_every_url_is_a_blob_at_a_tag_with_its_lines(entries):
    for id, source in entries.items():
        m = sources.URL.match(source.url)
        assert m, (id, source.url)
        assert m["repo"] == sources.REPOSITORIES[source.tool], (id, source.tool)
        assert RELEASE_TAG.match(m["ref"]) or m["ref"] in FIXED_BRANCHES, (id, m["ref"])
        assert (m["ref"], m["file"]) == (source.tag, source.file), id
        first, last = source.first_last
        assert 0 < first <= last, (id, source.lines)
        assert (int(m["first"]), int(m["last"] or m["first"])) == (first, last), id
        assert re.fullmatch(r"[\w.<>\[\]-]+", source.anchor), (id, source.anchor)


# ---- the ROS 2 versions ------------------------------------------------------------------

VERSIONS_PAGE = sources.PAGES / "reference" / "09-ros2-controllers.md"
# A link to a file or folder of a repository on GitHub, at a ref.
GITHUB_LINK = re.compile(r"https://github\.com/(?P<repo>[\w.-]+/[\w.-]+)/(?:blob|tree)/(?P<ref>[\w.-]+)")
ROS2_TOOLS = ("gz_ros2_control", "ros2_control", "ros2_controllers", "control_toolbox",
              "robot_state_publisher", "ros_gz", "rclpy", "rmw")


def stated_versions() -> dict[str, str]:
    """tool -> the release the ROS 2 controllers page says its lines are read at."""
    text = " ".join(VERSIONS_PAGE.read_text(encoding="utf-8").split())
    listed = re.search(r"at these release tags: (.*?)\.(?:\s|$)", text)
    assert listed, f"{VERSIONS_PAGE}: no sentence 'at these release tags: TOOL X.Y.Z, ...'"
    versions = dict(re.findall(r"(\w+) (\d+\.\d+\.\d+)", listed.group(1)))
    assert {"gz_ros2_control", "ros2_control", "ros2_controllers", "control_toolbox"} <= set(versions)
    return versions


def test_every_link_to_a_ros2_tool_is_at_the_version_the_pages_state(entries):
    """The versions /reference/ros2-controllers/ states are the tags of every link to those
    tools: on any page, and in the data file the source includes show."""
    versions = stated_versions()
    repos = {sources.REPOSITORIES[tool]: (tool, tag) for tool, tag in versions.items()}
    wrong = []
    for path in PAGES:
        for m in GITHUB_LINK.finditer(path.read_text(encoding="utf-8")):
            if m["repo"] in repos and m["ref"] != repos[m["repo"]][1]:
                tool, tag = repos[m["repo"]]
                wrong.append(f"{path.relative_to(ROOT)}: {m.group(0)} is at {m['ref']}, but "
                             f"{VERSIONS_PAGE.relative_to(ROOT)} says {tool} {tag}")
    for id, source in entries.items():
        if source.tool in versions and source.tag != versions[source.tool]:
            wrong.append(f"{sources.DATA.relative_to(ROOT)}: {id} is at {source.tool} "
                         f"{source.tag}, but the page says {versions[source.tool]}")
    assert not wrong, "\n".join(wrong)


def test_each_ros2_tool_is_read_at_one_release(entries):
    tags: dict[str, set[str]] = {}
    for source in entries.values():
        if source.tool in ROS2_TOOLS:
            tags.setdefault(source.tool, set()).add(source.tag)
    assert {tool: tag for tool, tag in tags.items() if len(tag) > 1} == {}
    assert set(ROS2_TOOLS) <= set(sources.REPOSITORIES)


def test_a_bad_entry_is_named_with_its_fix(tmp_path):
    data = tmp_path / "sources.yml"
    data.write_text("one-mesh:\n  url: https://github.com/x/y/blob/1.0.0/f#L1\n", encoding="utf-8")
    with pytest.raises(sources.SourcesError, match=r"sources\.yml: entry 'one-mesh' lacks"):
        sources.load(data)
    with pytest.raises(sources.SourcesError, match=r"no entry 'nowhere' in .*sources\.yml"):
        sources.as_markdown('X.{% include source.html id="nowhere" %}', {})


def mirror(repo: str) -> Path:
    return MIRRORS / repo.replace("/", "+") / "repo"


def test_the_cited_lines_hold_what_the_entry_names(entries):
    """Read at its tag in a fetched copy of the tool's repository, each cited range exists
    and contains the entry's anchor."""
    present = {tool for tool, repo in sources.REPOSITORIES.items() if mirror(repo).exists()}
    checked = [s for s in entries.values() if s.tool in present]
    if not checked:
        pytest.skip(f"no copy of the tools' repositories under {MIRRORS}: the lines cannot be "
                    "read here")
    wrong = []
    for source in checked:
        shown = subprocess.run(["git", "-C", str(mirror(sources.REPOSITORIES[source.tool])),
                                "show", f"{source.tag}:{source.file}"],
                               capture_output=True, text=True)
        if shown.returncode != 0:
            wrong.append(f"{source.id}: {source.file} at {source.tag}: {shown.stderr.strip()}")
            continue
        lines = shown.stdout.splitlines()
        first, last = source.first_last
        if last > len(lines):
            wrong.append(f"{source.id}: lines {source.lines}, but the file has {len(lines)}")
        elif not any(source.anchor in line for line in lines[first - 1:last]):
            wrong.append(f"{source.id}: {source.anchor!r} is not in lines {source.lines}")
    assert not wrong, "\n".join(wrong)


# ---- what a reader gets ------------------------------------------------------------------

def test_a_notebook_shows_the_link_and_keeps_the_sentence(entries):
    """A page's source include becomes a Markdown link in its notebook; the line it sits on
    stays prose (other Liquid would turn it into a note that the site builds something)."""
    page = ROOT / "_pages/practice-2/02-exporting.md"
    cited = sources.included_ids(page.read_text(encoding="utf-8"))
    assert cited
    markdown = "\n".join(c.source for c in build(page).cells if c.cell_type == "markdown")
    assert "include source.html" not in markdown
    for id in set(cited):
        assert f"<sup>[source]({entries[id].url} " in markdown, id
    assert "so the exporter writes the same mesh.<sup>[source]" in " ".join(markdown.split())
