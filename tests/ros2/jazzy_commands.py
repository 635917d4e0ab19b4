"""The `ros2` command lines the pages show for a reader with ROS 2 Jazzy (blocks marked
`data-ros2-needs`): nothing here runs them, so what they name is checked instead.

- `ros2 launch PACKAGE FILE`: the launch file `sw2sim port` wrote into that package;
- `ros2 run PACKAGE PROGRAM`: a node file the pages write into a package's `scripts/`;
- `ros2 topic pub|echo|hz|info TOPIC [TYPE] [MESSAGE]`: a topic the page's run had, with
  that type; the message's fields and an `--field` path exist in the type.
"""

from __future__ import annotations

import importlib
import re
from pathlib import Path

import yaml

from course.snippets.parse import Page
from course.snippets.ros import Command, commands

# Jazzy tools the pages name that are no package of the course's.
OTHER_PACKAGES = {"rqt_joint_trajectory_controller"}


def jazzy_commands(page: Page) -> list[Command]:
    """The `ros2 ...` command lines of the page's blocks marked data-ros2-needs."""
    found = []
    for block, _ in page.ros2_needs:
        if block.language == "bash":
            found += [c for c in commands(block) if c.words[:1] == ["ros2"]]
    return found


def message_class(type_name: str):
    """`pkg/msg/Name` (or `pkg/Name`) as the rclpy class, or None where it is not
    installed."""
    parts = type_name.split("/")
    package, name = parts[0], parts[-1]
    try:
        return getattr(importlib.import_module(f"{package}.msg"), name)
    except (ImportError, AttributeError):
        return None


def field_problems(cls, data, where: str) -> list[str]:
    """The keys of a YAML message (nested dicts and lists of dicts) that its type lacks."""
    if not isinstance(data, dict):
        return []
    fields = cls.get_fields_and_field_types()
    problems = []
    for key, value in data.items():
        if key not in fields:
            problems.append(f"{where}: {cls.__name__} has no field {key!r}")
            continue
        kind = fields[key]
        inner = re.fullmatch(r"sequence<([\w/]+)(?:, \d+)?>", kind)
        if inner and isinstance(value, list):
            element = message_class(inner.group(1))
            for item in value:
                problems += field_problems(element, item, where) if element else []
        elif "/" in kind and isinstance(value, dict):
            nested = message_class(kind)
            problems += field_problems(nested, value, where) if nested else []
    return problems


def path_problem(cls, path: str, where: str) -> str | None:
    """An `--field a.b` path that the type does not have."""
    for name in path.split("."):
        fields = cls.get_fields_and_field_types()
        if name not in fields:
            return f"{where}: {cls.__name__} has no field {name!r} (--field {path})"
        inner = re.fullmatch(r"(?:sequence<)?([\w/]+)(?:, \d+)?>?", fields[name])
        cls = message_class(inner.group(1)) if inner and "/" in inner.group(1) else None
        if cls is None:
            return None
    return None


def name_problems(command: Command, ported: dict[str, Path], nodes: set[str]) -> list[str]:
    """What a `ros2 launch` or `ros2 run` line names that the ported packages and the
    pages' node files do not have."""
    w, where = command.words, command.location
    if w[1:2] == ["launch"] and len(w) >= 4:
        package = ported.get(w[2])
        if package is None:
            return [f"{where}: ros2 launch {w[2]}: no page ports a package of that name"]
        if not (package / "launch" / w[3]).is_file():
            return [f"{where}: sw2sim port writes no launch/{w[3]} into {w[2]}"]
    if w[1:2] == ["run"] and len(w) >= 4 and w[2] not in OTHER_PACKAGES:
        if w[2] not in ported:
            return [f"{where}: ros2 run {w[2]}: no page ports a package of that name"]
        if w[3] not in nodes:
            return [f"{where}: ros2 run {w[2]} {w[3]}: no page writes a node file {w[3]}"]
    return []


def topic_problems(command: Command, graph: dict[str, list[str]]) -> list[str]:
    """What a `ros2 topic` line names that the run did not have: the topic, its type, the
    message's fields, the `--field` path."""
    w, where = command.words, command.location
    if w[1:2] != ["topic"] or len(w) < 3 or w[2] == "list":
        return []
    rest = [x for x in w[3:] if x not in ("--once", "-1")]
    field = None
    if "--field" in rest:
        i = rest.index("--field")
        field = rest[i + 1] if i + 1 < len(rest) else None
        rest = rest[:i] + rest[i + 2:]
    topic = rest[0] if rest else None
    if topic is None:
        return [f"{where}: `{command.text}` names no topic"]
    if topic not in graph:
        return [f"{where}: {topic} is not a topic of the run (it had {sorted(graph)})"]
    types = graph[topic]
    problems = []
    type_name = rest[1] if w[2] == "pub" and len(rest) > 1 else types[0]
    if type_name not in types:
        problems.append(f"{where}: {topic} carries {types}, not {type_name}")
    cls = message_class(type_name)
    if cls is None:
        return problems + [f"{where}: the type {type_name} is not installed here"]
    if w[2] == "pub" and len(rest) > 2:
        try:
            data = yaml.safe_load(rest[2])
        except yaml.YAMLError as exc:
            return problems + [f"{where}: the message is not YAML: {exc}"]
        problems += field_problems(cls, data, where)
    if field:
        problem = path_problem(cls, field, where)
        problems += [problem] if problem else []
    return problems
