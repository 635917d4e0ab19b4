"""The reference pages: in the navigation, true to the code and the packages they describe,
and every link on them leads to a page (and a heading) that exists.

Their Python blocks are run by tests/course/test_pages.py, with every other page's; here they are
only read.
"""

from __future__ import annotations

import ast
import contextlib
import html
import io
import re
import subprocess
import sys
from pathlib import Path

import pytest
import yaml
from lxml import etree
from page_text import fenced_blocks, squash, xml_blocks
from jekyll import between, built_page, bundle, whole_site  # noqa: F401  (fixtures)

from course.exporter_format import EXPORTER_GREY
from course.practices import PRACTICES, design
from sw2sim.ros_control import read_joint_limits
from course.snippets import DEFAULT_TIMEOUT, parse_page

from repository import ROOT, practice_numbers
PAGES = ROOT / "_pages" / "reference"
EXAMPLE_3 = ROOT / "examples" / "example_3"
# The reference pages of this file, in reading order: (file, address). The first, Getting
# started, comes before the practices in the navigation; the others make its Reference section.
REFERENCE = [
    ("01-getting-started.md", "/reference/getting-started/"),
    ("02-exporter.md", "/reference/exporter/"),
    ("03-your-own-model.md", "/reference/your-own-model/"),
    ("04-troubleshooting.md", "/reference/troubleshooting/"),
    ("08-ros-without-gazebo.md", "/reference/ros-without-gazebo/"),
    ("05-ros1-to-ros2.md", "/reference/ros1-to-ros2/"),
    ("06-glossary.md", "/reference/glossary/"),
    ("07-writing-a-lesson.md", "/reference/writing-a-lesson/"),
]


def page(name: str) -> str:
    return (PAGES / name).read_text(encoding="utf-8")


def front_matter(text: str) -> dict:
    return yaml.safe_load(text.split("---\n", 2)[1])


def backticked(text: str) -> set[str]:
    """Inline code spans of a page's prose (fenced blocks left out)."""
    prose = re.sub(r"^[ \t]*(`{3,}).*?^[ \t]*\1", "", text, flags=re.S | re.M)
    return set(re.findall(r"(?<!`)`([^`\n]+)`(?!`)", prose))


# ---- navigation and front matter ---------------------------------------------------------


def test_reference_pages_are_a_section_of_the_navigation_in_order():
    nav = yaml.safe_load((ROOT / "_data" / "navigation.yml").read_text())
    sections = [item for item in nav if item.get("title") == "Reference"]
    assert len(sections) == 1, "one 'Reference' section in _data/navigation.yml"
    urls = [child["url"] for child in sections[0]["children"]]
    ours = [url for _, url in REFERENCE[1:]]
    assert [u for u in urls if u in ours] == ours, f"reference pages out of order: {urls}"
    practices = [i for i, item in enumerate(nav) if item.get("title", "").startswith("Practice")]
    assert practices and nav.index(sections[0]) > max(practices), "Reference follows the practices"
    # Getting started is read first: a top-level entry before the practices.
    [start] = [i for i, item in enumerate(nav) if item.get("url") == REFERENCE[0][1]]
    assert start < min(practices), "Getting started comes before Practice 1"
    assert REFERENCE[0][1] not in urls, "Getting started is listed once"


@pytest.mark.parametrize("name, url", REFERENCE)
def test_front_matter(name, url):
    front = front_matter(page(name))
    assert front["permalink"] == url and front["title"]
    # Formulas are typeset when the site is built, wherever they are: no page needs to
    # say it has some (a stale `math:` key would suggest otherwise).
    assert "math" not in front, name


def test_home_page_links_to_every_reference_page():
    home = (ROOT / "_pages" / "index.md").read_text()
    reference = home.split("## Reference", 1)[1]
    navigation = yaml.safe_load((ROOT / "_data" / "navigation.yml").read_text())
    urls = [entry["url"] for section in navigation
            for entry in [section, *section.get("children", [])]
            if entry.get("url", "").startswith("/reference/")]
    assert len(urls) == len(list((ROOT / "_pages" / "reference").glob("*.md")))
    for url in urls:
        assert f"]({url})" in reference, url


def test_what_the_home_page_says_is_not_run_is_what_the_pages_skip():
    """The home page: the ROS 1 blocks and the ROS 2 nodes run, and only blocks that open a
    window or need a full ROS 2 install are marked Not run here."""
    from course.snippets import find_pages
    home = " ".join((ROOT / "_pages" / "index.md").read_text().split())
    assert "The ROS commands and nodes run as well, under a real ROS 1 master" in home
    assert "each practice's ROS 2 nodes run under ROS 2 Jazzy's own rclpy" in home
    assert ("the few blocks that open a window or need what only a full ROS 2 install has "
            "(`ros2 launch`, Gazebo Sim) are marked *Not run here*") in home
    pages = [parse_page(path, ROOT) for path in find_pages(ROOT)]
    reasons = [(b.location, b.skip) for p in pages for b in p.skipped]
    reasons += [(b.location, needs) for p in pages for b, needs in p.ros2_needs]
    assert reasons
    for location, reason in reasons:
        assert "window" in reason or "ROS 2" in reason, (location, reason)
    assert sum(len(p.ros_blocks) for p in pages) >= 10
    assert sum(len(p.ros2_blocks) for p in pages) >= 10


# ---- Python blocks: which run and which are shown only ------------------------------------


def test_blocks_parse_and_the_ros_2_files_are_never_run():
    blocks = {}
    for name, _ in REFERENCE:
        parsed = parse_page(PAGES / name, ROOT)
        assert not parsed.errors, [str(e) for e in parsed.errors]
        blocks[name] = parsed
    assert blocks["01-getting-started.md"].runnable, "the installation check must run"
    check = blocks["01-getting-started.md"].runnable[0].code
    assert 'load_package("examples/example_1")' in check
    ros2 = blocks["05-ros1-to-ros2.md"]
    assert len(ros2.blocks) == 1 and not ros2.runnable
    assert all("ROS 2 Jazzy" in block.skip for block in ros2.skipped)
    assert len(blocks["02-exporter.md"].runnable) == 3


# ---- Getting started ----------------------------------------------------------------------


def test_getting_started_states_the_project_set_up():
    text = page("01-getting-started.md")
    pyproject = (ROOT / "pyproject.toml").read_text()
    assert 'requires-python = ">=3.10"' in pyproject
    assert 'requires-python = ">=3.10"' in text and "Python 3.10 or newer" in text
    assert '"mujoco>=4.0"' in pyproject and "MuJoCo 4.0 or newer" in text
    makefile = (ROOT / "Makefile").read_text()
    for command in ("pip install -q --disable-pip-version-check -r requirements.txt",
                    "pip install -q --disable-pip-version-check --no-deps --no-build-isolation -e ."):
        assert command in makefile, command
    assert ".venv/bin/pip install -r requirements.txt" in text
    assert ".venv/bin/pip install --no-deps --no-build-isolation -e ." in text
    apt = re.search(r"APT_PACKAGES := (.*?)\n\n", makefile, re.S).group(1)
    for package in ("libosmesa6", "liburdfdom-tools", "jekyll"):
        assert package in apt and package in text.lower(), package
    for path in ("_pages/practice-1/04-testing-and-modifying.md",
                 "examples/example_1/scripts/periodic_force.py"):
        assert path in text and (ROOT / path).is_file(), path


# ---- The exporter, option by option -------------------------------------------------------


def test_exporter_xml_is_copied_from_the_examples():
    urdfs = [squash(p.read_text()) for p in sorted((ROOT / "examples").glob("*/urdf/*.urdf"))]
    blocks = xml_blocks(page("02-exporter.md"))
    assert len(blocks) >= 6
    for block in blocks:
        assert any(squash(block) in urdf for urdf in urdfs), f"not in any example URDF:\n{block}"


def test_exporter_page_facts():
    text = page("02-exporter.md")
    grey = " ".join(f"{c:.3f}" if c < 1 else f"{c:g}" for c in EXPORTER_GREY)
    assert f"`{grey}`" in text, grey
    limits = read_joint_limits(EXAMPLE_3)["middle_arm_joint"]
    assert f'effort="{limits.effort:g}"' in text
    assert f"an effort limit of {limits.effort:g} N·m" in text
    assert f"up to {limits.velocity:g} rad/s" in text
    # The CSV columns the page reads exist in the exporter's CSV.
    header = (EXAMPLE_3 / "urdf" / "example_3.csv").read_text().splitlines()[0].split(",")
    for column in re.findall(r"row\['([^']+)'\]", text):
        assert column in header, column


# ---- From ROS 1 to ROS 2 ------------------------------------------------------------------


@pytest.fixture(scope="module")
def ros2(tmp_path_factory):
    """The page's text, its blocks, and what `sw2sim port examples/example_3` writes."""
    from sw2sim.port import port
    text = page("05-ros1-to-ros2.md")
    out = tmp_path_factory.mktemp("port") / "example_3"
    port(EXAMPLE_3, out)
    files = {name: (out / name).read_text(encoding="utf-8") for name in
             ("package.xml", "CMakeLists.txt", "urdf/example_3.urdf", "config/controllers.yaml",
              "launch/gazebo.launch.py")}
    python = [block.code for block in parse_page(PAGES / "05-ros1-to-ros2.md", ROOT).blocks]
    return text, files, python


def _without_comments(yaml_text: str) -> str:
    return "\n".join(line for line in yaml_text.splitlines()
                     if not line.lstrip().startswith("#")).strip()


def test_ros2_page_targets_jazzy(ros2):
    text = ros2[0]
    assert "ROS 2 Jazzy" in squash(text) and "Gazebo Sim" in text
    for n in practice_numbers():
        assert f"](/practice-{n}/ros2/)" in text, n


def test_ros2_page_shows_what_the_port_writes(ros2):
    """Every file the page shows is the port's, as `sw2sim port` writes it for example_3."""
    text, files, python = ros2
    manifest, urdf_end = xml_blocks(text)
    assert manifest == files["package.xml"]
    (cmake,) = fenced_blocks(text, "cmake")
    assert cmake == files["CMakeLists.txt"]
    assert squash(urdf_end) in squash(files["urdf/example_3.urdf"])
    assert squash(files["urdf/example_3.urdf"]).endswith(squash(urdf_end) + "</robot>")
    (controllers,) = fenced_blocks(text, "yaml")
    assert controllers.strip() == _without_comments(files["config/controllers.yaml"])
    (launch,) = python
    assert launch == files["launch/gazebo.launch.py"]


def test_practice_ros2_pages_show_the_ports_controllers(tmp_path):
    """A practice's ROS 2 page that shows config/controllers.yaml shows what its `sw2sim
    port` line writes: the whole file (its comments aside), or with "(part)" some of its
    lines, as they are."""
    from course.snippets.terminal import commands
    from sw2sim.port import port
    shown = 0
    for path in sorted((ROOT / "_pages").glob("practice-*/*-ros2.md")):
        text = path.read_text(encoding="utf-8")
        page_ = parse_page(path, ROOT)
        for m in re.finditer(r"```yaml\n(.*?)```\n\{: data-file=\"config/controllers\.yaml"
                             r"( \(part\))?\"\}", text, re.S):
            ported = [c.words for b in page_.ros2_commands for c in commands(b)
                      if c.words[:2] == ["sw2sim", "port"]]
            words = ported[0]
            options = words[words.index("--effort-joints") + 1:][:1] \
                if "--effort-joints" in words else []
            source = ROOT / "examples" / Path(words[2]).name
            out = port(source, tmp_path / path.stem / source.name, effort_joints=options)
            written = _without_comments((out.package_dir / "config" / "controllers.yaml")
                                        .read_text(encoding="utf-8"))
            block = m.group(1).strip()
            if m.group(2):
                missing = [line for line in block.splitlines() if line not in written.splitlines()]
                assert not missing, (path.name, missing)
            else:
                assert block == written, (path.name, written)
            shown += 1
    assert shown >= 3


def test_ros2_controllers_keep_practice_3s_gains_and_rates(ros2):
    text, files, _ = ros2
    controllers = yaml.safe_load(files["config/controllers.yaml"])
    ros1_file = EXAMPLE_3 / "config" / "joint_names_example_3.yaml"
    ros1 = yaml.safe_load(ros1_file.read_text())["example_3"]
    manager = controllers["controller_manager"]["ros__parameters"]
    arm = ROOT / "examples" / "example_3" / "scripts" / "arm_controller.py"
    timestep = float(re.search(r"^TIMESTEP = ([\d.]+)", arm.read_text(), re.M).group(1))
    assert manager["update_rate"] == round(1 / timestep)
    rate = controllers["joint_state_broadcaster"]["ros__parameters"]["update_rate"]
    assert rate == ros1["joint_state_controller"]["publish_rate"]
    # Each controller runs at its own update_rate: the trajectory controllers, which give
    # none, at the manager's; the broadcaster at its own, which the manager's is a multiple of.
    said = squash(text)
    assert (f"With `update_rate: {manager['update_rate']}`, `gz_ros2_control` updates the "
            f"controller manager every {1000 * timestep:g} ms of simulated time") in said
    assert f"so the two trajectory controllers run {manager['update_rate']} times a second" in said
    assert f"`update_rate: {rate}` makes it run {rate} times a second" in said
    assert manager["update_rate"] % rate == 0
    assert "every controller 1000 times a second" not in said
    for name, c in ros1.items():
        if c["type"] != "effort_controllers/JointPositionController":
            continue
        assert manager[name]["type"] == "joint_trajectory_controller/JointTrajectoryController"
        params = controllers[name]["ros__parameters"]
        assert "update_rate" not in params   # so it runs at the manager's rate, as the page says
        joint, pid = c["joint"], c["pid"]
        assert params["joints"] == [joint] and params["command_interfaces"] == ["effort"]
        gains = params["gains"][joint]
        assert {k: gains[k] for k in "pid"} == {k: pid[k] for k in "pid"}
        assert gains["i_clamp_max"] == pid["i_clamp"] == -gains["i_clamp_min"]


def test_ros2_control_joints_and_limits_are_the_urdfs(ros2):
    text, _, _ = ros2
    urdf_end = etree.fromstring(f"<robot>{xml_blocks(text)[1]}</robot>".encode())
    limits = read_joint_limits(EXAMPLE_3)
    joints = urdf_end.findall("ros2_control/joint")
    assert [j.get("name") for j in joints] == list(limits)
    for joint in joints:
        effort = limits[joint.get("name")].effort
        params = {p.get("name"): float(p.text) for p in joint.findall("command_interface/param")}
        assert params == {"min": -effort, "max": effort}
        assert f"the URDF's effort limit, {effort:g} N·m" in squash(text)
    # min and max are limits nothing enforces unless the controller manager is told to.
    assert "`enforce_command_limits` parameter is true, and in Jazzy it is false by default" \
        in squash(text)
    assert "give the command's range" not in squash(text)


# ---- Glossary -----------------------------------------------------------------------------

TERMS = ["urdf", "link", "joint", "continuous-joint", "revolute-joint", "prismatic-joint",
         "fixed-joint", "frame", "axis", "inertial", "inertia-tensor", "centre-of-mass",
         "collision-geometry", "visual-geometry", "mesh", "stl", "package", "package-url",
         "xacro", "transmission", "ros-control", "controller", "pid", "effort",
         "joint-limits", "safety-controller", "mjcf", "mjspec", "mjmodel-mjdata",
         "actuator", "timestep", "ackermann-steering", "wheelbase", "track",
         "turning-radius"]


def glossary_entries() -> list[tuple[str, str, str]]:
    """(title, anchor, text) of each glossary entry."""
    text = page("06-glossary.md")
    parts = re.split(r"^### (.+?) \{#([\w-]+)\}\n", text, flags=re.M)
    return [(parts[i], parts[i + 1], parts[i + 2]) for i in range(1, len(parts), 3)]


def test_glossary_has_the_course_terms_in_alphabetical_order():
    entries = glossary_entries()
    anchors = [anchor for _, anchor, _ in entries]
    assert sorted(set(TERMS) - set(anchors)) == []
    titles = [title.lower() for title, _, _ in entries]
    assert titles == sorted(titles)
    assert len(set(anchors)) == len(anchors)
    headings = re.findall(r"^#{2,3} .*$", page("06-glossary.md"), re.M)
    assert len(headings) == len(entries) + len({t[0] for t in titles}), "an entry without an anchor"


def test_every_glossary_entry_links_to_where_it_is_used():
    for title, _, text in glossary_entries():
        links = re.findall(r"\]\((/(?:practice-\d|reference)/[^)]*)\)", text)
        assert links, f"{title}: no link to the page where it is first used"


# ---- Writing a lesson ---------------------------------------------------------------------

# Placeholders and examples the page names on purpose.
NOT_FILES = re.compile(r"practice[_-](N|6)|example_(N|6)|_N\b|^/|^_site/|^\.venv/")


def test_writing_a_lesson_names_files_that_exist():
    text = page("07-writing-a-lesson.md")
    words = {token.split()[0] for token in backticked(text)}
    paths = {w for w in words
             if "/" in w and re.fullmatch(r"[\w./-]+", w) and not NOT_FILES.search(w)}
    assert len(paths) >= 10
    missing = sorted(p for p in paths if not (ROOT / p.rstrip("/")).exists())
    assert not missing, f"named on the page but not in the repository: {missing}"


def test_writing_a_lesson_commands_exist():
    text = page("07-writing-a-lesson.md")
    makefile = (ROOT / "Makefile").read_text()
    targets = set(re.findall(r"(?:^|`)make (\w+)", text, re.M))
    assert {"test", "serve", "build", "media"} <= targets
    for target in targets:
        assert re.search(rf"^{target}:", makefile, re.M), f"no `make {target}`"
    for module, options in (("media", re.findall(r"course\.media (--\w+)", text)),
                            ("__main__", re.findall(r"-m course (--\w+)", text))):
        assert options or module == "media", f"the page shows no `python -m course` option"
        for option in set(options):
            done = subprocess.run([sys.executable, "-m", "course" if module == "__main__" else f"course.{module}",
                                   "--help"], cwd=ROOT, capture_output=True, text=True, timeout=120)
            assert option in done.stdout, f"python -m course{'' if module == '__main__' else '.' + module} has no {option}"
    snippets = (ROOT / "course" / "snippets" / "__main__.py").read_text()
    assert "--timeout 30" in text and '"--timeout"' in snippets
    assert f"Each block gets {DEFAULT_TIMEOUT:g} s" in text
    assert "make test" in (ROOT / ".ci" / "run").read_text()
    assert "run: make test" in (ROOT / ".github" / "workflows" / "test.yml").read_text()
    assert "branches: [main]" in (ROOT / ".github" / "workflows" / "pages.yml").read_text()


def test_writing_a_lesson_describes_the_practice_registry():
    text = page("07-writing-a-lesson.md")
    assert "`PRACTICES`" in text and PRACTICES == [f"practice_{n}" for n in practice_numbers()]
    assert "finds every\n`practice_N` folder" in text and "Register it" not in text
    for practice in PRACTICES:
        module = design(practice)
        assert module.PACKAGE == practice.replace("practice", "example")
        assert module.ALUMINIUM.density > 0 and callable(module.write)
    assert ".ALUMINIUM.density" in (ROOT / "tests" / "course" / "test_examples.py").read_text()


def test_writing_a_lesson_shows_the_runner_report_it_prints(tmp_path, monkeypatch):
    import tempfile
    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path))   # where the block's mkdtemp goes
    text = page("07-writing-a-lesson.md")
    (block,) = [b for b in parse_page(PAGES / "07-writing-a-lesson.md", ROOT).runnable
                if "format_failure" in b.code]
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        exec(compile(block.code, "writing-a-lesson", "exec"), {"__name__": "sample"})
    lines = out.getvalue().splitlines()
    assert lines[1] == "_pages/sample.md:11: skipped: opens a window"
    assert f"The last line reads `{lines[-1]}`" in text


# ---- links --------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def site(whole_site) -> Path:  # noqa: F811  (whole_site is tests/jekyll.py's fixture)
    return whole_site


def page_body(html_text: str) -> str:
    """The page's own content, without code blocks (their text is not a link)."""
    body = html_text[html_text.index('<div class="page-body">'):]
    return re.sub(r"<pre\b.*?</pre>", "", body, flags=re.S)


@pytest.mark.parametrize("url", [url for _, url in REFERENCE] + ["/"])
def test_internal_links_lead_to_a_page_and_heading(site, url):
    problems, checked = [], 0
    for href in re.findall(r'href="([^"]+)"', page_body(built_page(site, url).read_text())):
        href = html.unescape(href)
        if re.match(r"[a-z]+:", href):
            continue
        checked += 1
        path, _, anchor = href.partition("#")
        target = built_page(site, path) if path else built_page(site, url)
        if not target.is_file():
            problems.append(f"{href}: no such page")
        elif anchor and f'id="{anchor}"' not in target.read_text():
            problems.append(f"{href}: no heading #{anchor} on {path or url}")
    assert checked >= 3, f"{url}: only {checked} internal links found"
    assert not problems, f"{url}:\n" + "\n".join(problems)


# ---- troubleshooting: the page and the checker read the same rules ---------------------------


def test_troubleshooting_data_is_the_rule_registry():
    from course import troubleshooting
    assert troubleshooting.main(["--check"]) == 0, (
        "_data/check_rules.json is stale: run `python -m course.troubleshooting`")


def test_troubleshooting_page_has_an_entry_per_rule(site):
    from sw2sim.check import all_rules
    from sw2sim.check.findings import BLOCKS_SAYS
    text = built_page(site, "/reference/troubleshooting/").read_text()
    for rule in all_rules().values():
        entry = between(text, f'<h3 id="{rule.id}">', "</section>")
        assert entry, f"no entry for {rule.id}"
        for part in ("Symptom", "Cause", "Fix"):
            assert f"<dt>{part}</dt><dd>" in entry, (rule.id, part)
        heading = entry[:entry.index("</h3>")]
        shown = html.unescape(re.sub(r"<[^>]+>", "", heading))
        assert shown == f"{rule.id} {rule.title.replace('`', '')}", shown
        # What it stands in the way of, in the words the checker's output uses.
        kind = re.search(r'<p class="rule-severity[^"]*">([^<]+)</p>', entry).group(1)
        said = BLOCKS_SAYS[rule.blocks]
        expected = rule.severity if (rule.severity, rule.blocks) == ("warning", "advice") \
            else f"{rule.severity}: {said}"
        assert kind == expected, (rule.id, kind)
        # What convert repairs, in the rule's words, where it repairs anything.
        assert ("<dt>Convert repairs it</dt>" in entry) == bool(rule.repair), rule.id


def test_your_own_model_lists_every_repair_from_the_registry(site):
    from sw2sim.check import all_rules
    text = built_page(site, "/reference/your-own-model/").read_text()
    section = between(text, 'id="what-convert-repairs"', "</table>")
    assert section, "no table under What convert repairs"
    listed = re.findall(r'href="/reference/troubleshooting/#([a-z0-9-]+)"', section)
    assert listed == [r.id for r in all_rules().values() if r.repair]
    assert len(listed) >= 8
