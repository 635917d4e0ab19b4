"""The `ros2` command lines the pages show for a reader with ROS 2 Jazzy (blocks marked
`data-ros2-needs`): nothing here runs them, so what they name is checked instead.

- `ros2 launch PACKAGE FILE`: the launch file `sw2sim port` wrote into that package;
- `ros2 run PACKAGE PROGRAM`: a node file the pages write into a package's `scripts/`;
- `ros2 topic pub|echo|hz|info TOPIC [TYPE] [MESSAGE]`: a topic the page's run had, with
  that type; the message's fields and an `--field` path exist in the type;
- `ros2 action send_goal [--feedback] ACTION TYPE GOAL`: an action the page's run served
  (its hidden `ACTION/_action/feedback` topic, of that action's type), and the goal's
  fields exist in the action's Goal.
"""

from __future__ import annotations

import json
import re
from pathlib import Path

import yaml

from course.snippets.parse import Page
from course.snippets.terminal import Command, commands

# Jazzy tools the pages name that are no package of the course's.
OTHER_PACKAGES = {"rqt_joint_trajectory_controller"}


def jazzy_commands(page: Page) -> list[Command]:
    """The `ros2 ...` command lines of the page's blocks marked data-ros2-needs."""
    found = []
    for block, _ in page.ros2_needs:
        if block.language == "bash":
            found += [c for c in commands(block) if c.words[:1] == ["ros2"]]
    return found


# Run by the ROS 2 environment's Python: the fields of each message type named on the
# command line and of the types they hold, as {type: {field: field type}}.
_FIELDS = """
import importlib, json, re, sys
table, todo = {}, list(sys.argv[1:])
while todo:
    name = todo.pop()
    if name in table:
        continue
    package, *middle, message = name.split("/")
    try:
        if middle == ["action"]:   # an action's Goal: pkg/action/Name_Goal
            cls = getattr(importlib.import_module(package + ".action"),
                          message.removesuffix("_Goal")).Goal
        else:
            cls = getattr(importlib.import_module(package + ".msg"), message)
    except (ImportError, AttributeError):
        table[name] = None
        continue
    table[name] = cls.get_fields_and_field_types()
    for kind in table[name].values():
        inner = re.fullmatch(r"(?:sequence<)?([\\w]+/[\\w]+)(?:, \\d+)?>?", kind)
        if inner:
            todo.append(inner.group(1))
print(json.dumps(table))
"""


def field_tables(type_names: set[str]) -> dict[str, dict[str, str] | None]:
    """The fields of these message types and of those they hold (None: not installed),
    read by the ROS 2 environment, where the message packages are."""
    from ros2_environment import run
    done = run(_FIELDS, *sorted(type_names))
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


def _short(type_name: str) -> str:
    """`pkg/msg/Name` as `pkg/Name`, the form the field tables name nested types in."""
    parts = type_name.split("/")
    return f"{parts[0]}/{parts[-1]}"


def field_problems(tables: dict, type_name: str, data, where: str) -> list[str]:
    """The keys of a YAML message (nested dicts and lists of dicts) that its type lacks."""
    fields = tables.get(_short(type_name)) or tables.get(type_name)
    if not isinstance(data, dict) or not fields:
        return []
    problems = []
    for key, value in data.items():
        if key not in fields:
            problems.append(f"{where}: {type_name} has no field {key!r}")
            continue
        inner = re.fullmatch(r"(?:sequence<)?(\w+/\w+)(?:, \d+)?>?", fields[key])
        if not inner:
            continue
        items = value if isinstance(value, list) else [value]
        for item in items:
            problems += field_problems(tables, inner.group(1), item, where)
    return problems


def path_problem(tables: dict, type_name: str, path: str, where: str) -> str | None:
    """An `--field a.b` path that the type does not have."""
    for name in path.split("."):
        fields = tables.get(_short(type_name)) or tables.get(type_name)
        if not fields:
            return None
        if name not in fields:
            return f"{where}: {type_name} has no field {name!r} (--field {path})"
        inner = re.fullmatch(r"(?:sequence<)?(\w+/\w+)(?:, \d+)?>?", fields[name])
        if not inner:
            return None
        type_name = inner.group(1)
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


def topic_line(command: Command) -> tuple[str | None, str | None, str | None, str | None]:
    """A `ros2 topic` line's (verb, topic, type, --field path); verb None for other lines."""
    w = command.words
    if w[1:2] != ["topic"] or len(w) < 3 or w[2] == "list":
        return None, None, None, None
    rest = [x for x in w[3:] if x not in ("--once", "-1")]
    field = None
    if "--field" in rest:
        i = rest.index("--field")
        field = rest[i + 1] if i + 1 < len(rest) else None
        rest = rest[:i] + rest[i + 2:]
    topic = rest[0] if rest else None
    type_name = rest[1] if w[2] == "pub" and len(rest) > 1 else None
    return w[2], topic, type_name, field


def topic_types(lines: list[Command], graph: dict[str, list[str]]) -> set[str]:
    """The message types the `ros2 topic` lines name or the run gave their topics."""
    found = set()
    for command in lines:
        verb, topic, type_name, _ = topic_line(command)
        if verb:
            found.add(type_name or (graph.get(topic) or ["?"])[0])
    return found - {"?"}


def topic_problems(command: Command, graph: dict[str, list[str]], tables: dict) -> list[str]:
    """What a `ros2 topic` line names that the run did not have: the topic, its type, the
    message's fields, the `--field` path. `tables`: field_tables() of topic_types()."""
    verb, topic, type_name, field = topic_line(command)
    where = command.location
    if verb is None:
        return []
    if topic is None:
        return [f"{where}: `{command.text}` names no topic"]
    if topic not in graph:
        return [f"{where}: {topic} is not a topic of the run (it had {sorted(graph)})"]
    types = graph[topic]
    problems = []
    type_name = type_name or types[0]
    if type_name not in types:
        problems.append(f"{where}: {topic} carries {types}, not {type_name}")
    if not (tables.get(_short(type_name)) or tables.get(type_name)):
        return problems + [f"{where}: the type {type_name} is not installed here"]
    w = command.words
    rest = [x for x in w[3:] if x not in ("--once", "-1", "--field", field)]
    if verb == "pub" and len(rest) > 2:
        try:
            data = yaml.safe_load(rest[2])
        except yaml.YAMLError as exc:
            return problems + [f"{where}: the message is not YAML: {exc}"]
        problems += field_problems(tables, type_name, data, where)
    if field:
        problem = path_problem(tables, type_name, field, where)
        problems += [problem] if problem else []
    return problems


def action_line(command: Command) -> tuple[str | None, str | None, str | None]:
    """A `ros2 action send_goal` line's (action, type, goal); all None for other lines."""
    w = command.words
    if w[1:3] != ["action", "send_goal"]:
        return None, None, None
    rest = [x for x in w[3:] if x not in ("--feedback", "-f")]
    return tuple((rest + [None, None, None])[:3])


def action_types(lines: list[Command]) -> set[str]:
    """The Goal types (`pkg/action/Name_Goal`) the `ros2 action send_goal` lines name."""
    return {f"{t}_Goal" for c in lines if (t := action_line(c)[1])}


def action_problems(command: Command, graph: dict[str, list[str]], tables: dict) -> list[str]:
    """What a `ros2 action send_goal` line names that the run did not serve: the action,
    its type, the goal's fields. `tables`: field_tables() of action_types()."""
    action, type_name, goal = action_line(command)
    where = command.location
    if action is None:
        return []
    if type_name is None:
        return [f"{where}: `{command.text}` names no action type"]
    feedback = graph.get(f"{action}/_action/feedback")
    if feedback is None:
        return [f"{where}: the run served no action {action}"]
    if f"{type_name}_FeedbackMessage" not in feedback:
        return [f"{where}: {action} is a {feedback}, not a {type_name}"]
    if not tables.get(f"{type_name}_Goal"):
        return [f"{where}: the action type {type_name} is not installed here"]
    try:
        data = yaml.safe_load(goal) if goal else {}
    except yaml.YAMLError as exc:
        return [f"{where}: the goal is not YAML: {exc}"]
    return field_problems(tables, f"{type_name}_Goal", data, where)
