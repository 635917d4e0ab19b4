"""The source behind what the pages say the exporter, gazebo_ros_control and ros_control do,
and on the ROS 2 side gz_ros2_control, ros2_control, the ros2_controllers, control_toolbox,
robot_state_publisher, ros_gz and rclpy.

A page that states how one of these tools behaves ("the exporter writes ...") backs the
sentence with a link to the lines of the tool's source that do it:
`{% include source.html id="export-buttons" %}` right after the sentence. The links live in
one file, _data/sources.yml (id -> url, tool, tag, file, lines, anchor, claim), so that a
new release of a tool means editing one list, not hunting through pages; the include
(_includes/source.html) shows a small "source" link, and a notebook made from the page
(course.notebooks) gets the same link as Markdown.

`statements` finds the sentences a reader takes for a statement about a tool's behaviour,
by a narrow rule so that it never has to be argued with: the tool is the sentence's
subject, named as the pages name it, and a verb of doing follows it (on a ROS 2 page "the
controller" is a subject too: there it is one of ros2_controllers'). tests/course/
test_sources.py requires each such sentence to carry a link; `python -m course.sources`
lists those that do not.
"""

from __future__ import annotations

import re
import sys
from dataclasses import dataclass
from pathlib import Path

import yaml
from markdown_it import MarkdownIt

from .practices import ROOT

DATA = ROOT / "_data" / "sources.yml"
PAGES = ROOT / "_pages"
FIELDS = ("url", "tool", "tag", "file", "lines", "anchor", "claim")
# The repository each tool's source is read from.
REPOSITORIES = {"solidworks_urdf_exporter": "ros/solidworks_urdf_exporter",
                "gazebo_ros_control": "ros-simulation/gazebo_ros_pkgs",
                "ros_control": "ros-controls/ros_control",
                "ros_controllers": "ros-controls/ros_controllers",
                "gz_ros2_control": "ros-controls/gz_ros2_control",
                "ros2_control": "ros-controls/ros2_control",
                "ros2_controllers": "ros-controls/ros2_controllers",
                "control_toolbox": "ros-controls/control_toolbox",
                "robot_state_publisher": "ros/robot_state_publisher",
                # ROS 1's, as Noetic and Debian 12 ship it (1.15), read at another release
                "robot_state_publisher_noetic": "ros/robot_state_publisher",
                "gazebo_ros": "ros-simulation/gazebo_ros_pkgs",
                "gazebo_plugins": "ros-simulation/gazebo_ros_pkgs",
                "rostopic": "ros/ros_comm",
                "kdl_parser": "ros/kdl_parser",
                "ros_gz": "gazebosim/ros_gz",
                "rclpy": "ros2/rclpy",
                "rmw": "ros2/rmw",
                "sdformat": "gazebosim/sdformat",
                "gz-physics": "gazebosim/gz-physics",
                "gz-sim": "gazebosim/gz-sim",
                "dart": "dartsim/dart"}
# A link to lines of a file at a tag or branch: blob/<ref>/<file>#L<a>[-L<b>].
URL = re.compile(r"^https://github\.com/(?P<repo>[\w.-]+/[\w.-]+)/blob/(?P<ref>[\w.-]+)/"
                 r"(?P<file>[^#\s]+)#L(?P<first>\d+)(?:-L(?P<last>\d+))?$")
INCLUDE = re.compile(r"""\{%-?\s*include\s+source\.html\s+id=(?:"(?P<dq>[^"]*)"|'(?P<sq>[^']*)')"""
                     r"\s*-?%\}")


@dataclass(frozen=True)
class Source:
    """Lines of a tool's source that do what a page says the tool does."""

    id: str
    url: str
    tool: str
    tag: str        # the release tag (or maintained branch) the lines are read at
    file: str       # path in the tool's repository
    lines: str      # "144-235", or "87" for one line
    anchor: str     # an identifier that appears in those lines
    claim: str      # what the pages say those lines do, in a few words

    @property
    def first_last(self) -> tuple[int, int]:
        first, _, last = self.lines.partition("-")
        return int(first), int(last or first)


class SourcesError(ValueError):
    """_data/sources.yml is not what the pages and the include expect."""


def load(path: Path = DATA) -> dict[str, Source]:
    """Every entry of the data file, checked for the fields the include and the tests use."""
    try:
        data = yaml.safe_load(path.read_text(encoding="utf-8"))
    except (OSError, yaml.YAMLError) as error:
        raise SourcesError(f"{path}: cannot be read as YAML ({error}); fix the file") from None
    if not isinstance(data, dict):
        raise SourcesError(f"{path}: expected a mapping of id -> fields at the top level")
    out = {}
    for key, entry in data.items():
        if not isinstance(entry, dict):
            raise SourcesError(f"{path}: entry {key!r} is not a mapping of fields")
        missing = [f for f in FIELDS if not str(entry.get(f, "")).strip()]
        unknown = sorted(set(entry) - set(FIELDS))
        if missing or unknown:
            raise SourcesError(f"{path}: entry {key!r} lacks {missing or 'nothing'} and has "
                               f"unknown fields {unknown or 'none'}; give it exactly {FIELDS}")
        if entry["tool"] not in REPOSITORIES:
            raise SourcesError(f"{path}: entry {key!r} names the tool {entry['tool']!r}; "
                               f"use one of {sorted(REPOSITORIES)} (course/sources.py)")
        out[str(key)] = Source(id=str(key), **{f: str(entry[f]) for f in FIELDS})
    return out


def included_ids(text: str) -> list[str]:
    """The ids of the source includes in a piece of page text, in order."""
    return [m["dq"] if m["dq"] is not None else m["sq"] for m in INCLUDE.finditer(text)]


def as_markdown(text: str, sources: dict[str, Source]) -> str:
    """A page line with each source include as the link the include renders, for a notebook."""
    def link(m: re.Match) -> str:
        id = m["dq"] if m["dq"] is not None else m["sq"]
        if id not in sources:
            raise SourcesError(f"{m.group(0)}: no entry {id!r} in {DATA}; add it there or "
                               "correct the id")
        source = sources[id]
        return f'<sup>[source]({source.url} "{source.file}:{source.lines} at {source.tag}")</sup>'
    return INCLUDE.sub(link, text)


# ---- which sentences state what a tool does -----------------------------------------------

# The tools as the pages name them when they are a sentence's subject.
_SUBJECT = (r"(?:(?<!of )\b[Tt]he exporter(?!'s)"
            r"|\*{1,2}Export URDF(?: and Meshes| Only)?(?:\.\.\.)?\*{1,2}"
            r"|\*?Automatically Generate\*?"
            r"|(?:[Tt]he )?`?\b(?:gazebo_ros_control|ros_control|joint_limits_interface)\b`?"
            r"(?![\'/])(?: plugin)?"
            r"|\b[Tt]he controller manager"
            # ROS 2: gz_ros2_control, ros2_control and the ros2_controllers, control_toolbox,
            # robot_state_publisher, ros_gz and rclpy, by name or as the ROS 2 pages call them
            r"|(?:[Tt]he )?`?\b(?:gz_ros2_control|ros2_control|control_toolbox|robot_state_publisher"
            r"|ros_gz_bridge|ros_gz_sim|joint_state_broadcaster|joint_trajectory_controller"
            r"|pid_controller|forward_command_controller|GazeboSimROS2ControlPlugin|GazeboSimSystem"
            r"|JointGroupEffortController|JointTrajectoryController|PidController"
            r"|JointStateBroadcaster|spawner|rclpy(?:\.\w+)*)\b`?(?![\'/])"
            r"(?: (?:plugin|controller|broadcaster|program|node))?"
            r"|\b[Tt]he (?:joint )?trajectory controller(?!s)|\b[Tt]he (?:joint state )?broadcaster(?!s)"
            r"|\b[Tt]he PID controller|\b[Tt]he spawner|\bJazzy's (?:PID|`\w+`)"
            r"|\b[Gg]azebo Sim's (?:ROS 2 )?plugin|\b[Ii]ts hardware plugin|\b[Ii]ts `create` program)")
# On a ROS 2 page (one whose file name says ros2), "the controller" is one of ros2_controllers'.
_ROS2_SUBJECT = _SUBJECT[:-1] + r"|\b[Tt]he controller(?! manager)(?!')" + ")"
_ADVERB = r"(?:,?\s+(?:itself|also|then|only|still|always|never|now|first|just|therefore|"\
          r"instead|simply|again),?)*"
# Verbs of doing, as the third person present and as they follow a negation or a modal.
_DOING = ("write", "set", "read", "name", "copy", "call", "fill", "rewrite", "leave", "put",
          "take", "add", "export", "skip", "negate", "make", "turn", "ask", "weigh", "keep",
          "use", "change", "apply", "limit", "find", "connect", "start", "run", "load", "try",
          "infer", "hold", "clip", "cut", "slow", "produce", "work", "give", "create",
          "convert", "compute", "misspell", "describe", "save", "store", "refuse", "publish",
          "send", "place", "multiply", "cap", "enforce", "ignore", "overwrite", "declare",
          "measure", "round", "list", "treat", "spawn", "stop", "reset", "pass", "see",
          "check", "touch", "update", "clamp", "move", "carry", "replace", "report", "wait",
          "subscribe", "interpolate", "accept", "print", "warn", "offer", "drive", "fire", "end",
          "follow")


def _third_person(verb: str) -> str:
    if verb.endswith("y") and verb not in ("say",):
        return verb[:-1] + "ies"
    return verb + ("es" if verb.endswith(("sh", "ss", "o")) else "s")


_THIRD = "(?:" + "|".join(map(_third_person, _DOING)) + "|misspelt)"
_BASE = "(?:" + "|".join(_DOING) + ")"
_NEGATION = r"\s+(?:does not|doesn't|do not|cannot|can't|will|would|can|did not)"
_DOES = rf"{_ADVERB}(?:\s+{_THIRD}\b|{_NEGATION}{_ADVERB}\s+{_BASE}\b)"
STATEMENT = re.compile(_SUBJECT + _DOES)
ROS2_STATEMENT = re.compile(_ROS2_SUBJECT + _DOES)


def is_ros2_page(path: Path) -> bool:
    """A page about ROS 2 (each practice's last page, the ROS 2 reference pages)."""
    return "ros2" in path.name

# The end of a sentence: . ! ? (and closing marks), then the source includes that back it.
# An ellipsis ("Export URDF Only...", "Lxx ... Lzz") does not end a sentence.
_SENTENCE = re.compile(r".*?(?<!\.)[.!?](?!\.)[*_\"')\]]*(?:\s*" + INCLUDE.pattern + r")*(?=\s|$)|.+$")
_MARKDOWN = MarkdownIt("commonmark").enable("table")
_RAW = re.compile(r"\{%-?\s*raw\s*-?%\}.*?\{%-?\s*endraw\s*-?%\}", re.S)


# Sentences the rule takes for a tool's behaviour that are about something else, each with
# the reason: (page, words of the sentence) -> why it needs no link to the tool's source.
NOT_THE_TOOL = {
    ("reference/08-ros-without-gazebo.md", "the controller manager refuses to load them"):
        "the controller manager there is sw2sim's stand-in (sw2sim/ros), not ros_control's",
}


@dataclass(frozen=True)
class Statement:
    """A sentence of a page that states what a tool does, and the sources it cites."""

    page: str       # path under _pages/
    line: int       # 1-based line the sentence's paragraph starts on
    sentence: str   # with its whitespace squashed
    cited: tuple[str, ...]

    def __str__(self) -> str:
        return f"_pages/{self.page}:{self.line}: {self.sentence}"


def sentences(text: str) -> list[str]:
    """The sentences of a paragraph, each with the source includes that follow it."""
    flat = " ".join(text.split())
    return [m.group(0).strip() for m in _SENTENCE.finditer(flat) if m.group(0).strip()]


def prose(path: Path) -> list[tuple[int, str]]:
    """(1-based line, text) of each paragraph, heading, list item and table cell of a page:
    its Markdown outside code, HTML blocks, front matter and {% raw %} examples."""
    text = path.read_text(encoding="utf-8")
    # blank the front matter and raw regions line for line, so the line numbers stay right
    front = re.match(r"---\n.*?\n---\n", text, re.S)
    if front:
        text = re.sub(r"[^\n]", "", front.group(0)) + text[front.end():]
    text = _RAW.sub(lambda m: re.sub(r"[^\n]", "", m.group(0)), text)
    out = []
    tokens = _MARKDOWN.parse(text)
    for before, token in zip([None, *tokens], tokens):
        if token.type == "inline" and token.map and before.type != "heading_open":
            out.append((token.map[0] + 1, token.content))
    return out


def statements(path: Path) -> list[Statement]:
    """The sentences of a page whose subject is one of the tools, doing something."""
    page = path.relative_to(PAGES).as_posix()
    rule = ROS2_STATEMENT if is_ros2_page(path) else STATEMENT
    found = []
    for line, text in prose(path):
        for sentence in sentences(text):
            bare = INCLUDE.sub("", sentence)
            if rule.search(bare) and not any(
                    page == where and words in bare for where, words in NOT_THE_TOOL):
                found.append(Statement(page, line, sentence, tuple(included_ids(sentence))))
    return found


def main(argv: list[str]) -> int:
    """List the statements about a tool's behaviour that cite no source."""
    bare = [s for path in sorted(PAGES.rglob("*.md")) for s in statements(path) if not s.cited]
    for statement in bare:
        print(statement)
    print(f"{len(bare)} statement(s) without a source include", file=sys.stderr)
    return 1 if bare else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
