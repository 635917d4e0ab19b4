"""The names `sw2sim plot` takes, in rqt_plot's form, and the numbers they name.

rqt_plot's command line (plot.py's `_parse_args`, the same in ROS 1 and in Jazzy:
https://github.com/ros-visualization/rqt_plot/blob/0.4.14/src/rqt_plot/plot.py#L70-L103,
https://github.com/ros-visualization/rqt_plot/blob/1.4.0/src/rqt_plot/plot.py#L94-L124):
each argument is one name or several joined by commas, and `/topic/a:b:c` is shorthand for
`/topic/a /topic/b /topic/c` (the fields after the first replace its last part). A name is
a topic followed by the path of a field in its message, parts joined by `/`, each part a
field name with an optional `[index]` into an array (rosplot.py's
`generate_field_evals`). A name that does not start with `/` is taken from the root
namespace (ROS_NAMESPACE under ROS 1), as rqt_plot resolves it.

Where a name ends on a message, rqt_plot plots each of its numeric fields that is not an
array, and on a fixed-size array, each element; a variable-size array needs an index
(plot_widget.py's `get_plot_fields`,
https://github.com/ros-visualization/rqt_plot/blob/0.4.14/src/rqt_plot/plot_widget.py#L50-L111).
This module does the same, and says what is wrong, and what to write instead, where
rqt_plot only leaves the name out.

The types come from the ROS in use as a table of `Slot`s per message type (`describe`),
so that this module needs neither rospy nor rclpy.
"""

from __future__ import annotations

import difflib
import os
import re
from collections.abc import Callable
from dataclasses import dataclass


class PlotError(Exception):
    """A name that cannot be plotted: what is wrong, and the fix."""


@dataclass(frozen=True)
class Slot:
    """One field of a message type."""

    type: str               # as the ROS in use spells it: float64, double, std_msgs/Header
    kind: str               # "number", "bool", "text" or "message"
    size: int | None = None  # None: a single value; -1: an array of any length; N: N values


@dataclass(frozen=True)
class Part:
    """One part of a field path: a field, and an index into it if it is an array."""

    name: str
    index: int | None = None

    def __str__(self) -> str:
        return self.name if self.index is None else f"{self.name}[{self.index}]"


@dataclass(frozen=True)
class Series:
    """One line of the plot: a number read from each message on `topic`."""

    name: str                # as shown: /joint_states/velocity[0]
    topic: str
    type: str                # the topic's message type
    path: tuple[Part, ...]


Describe = Callable[[str], "dict[str, Slot]"]

PART = re.compile(r"^([A-Za-z_][A-Za-z0-9_]*)(?:\[(-?\d+)\])?$")


def expand(arguments: list[str], namespace: str | None = None) -> list[str]:
    """The names the command-line arguments stand for, in order, each once."""
    names: list[str] = []
    for argument in arguments:
        for item in (x for x in argument.split(",") if x):
            if ":" in item:
                first, *more = item.split(":")
                if "/" not in first.strip("/"):
                    raise PlotError(f"{item}: the shorthand needs a topic and a field before the "
                                    f"first `:`, e.g. /joint_states/position:velocity")
                base = first[:first.rfind("/")]
                found = [first] + [f"{base}/{field}" for field in more if field]
            else:
                found = [item]
            for name in found:
                name = resolve(name, namespace)
                if name not in names:
                    names.append(name)
    if not names:
        raise PlotError("name a topic's field to plot, e.g. `sw2sim plot /joint_states/velocity[0]`")
    return names


def resolve(name: str, namespace: str | None = None) -> str:
    """A global name: a relative one is put in `namespace` (default ROS_NAMESPACE, or /)."""
    name = name.strip()
    if name.startswith("/"):
        return name
    if name.startswith("~"):
        raise PlotError(f"{name}: a private (~) name belongs to a node; give the topic's full "
                        f"name, e.g. /{name[1:].lstrip('/')}")
    namespace = namespace if namespace is not None else os.environ.get("ROS_NAMESPACE", "/")
    return "/" + "/".join(p for p in (*namespace.split("/"), *name.split("/")) if p)


def split(name: str, topics: dict[str, str]) -> tuple[str, str, str]:
    """(topic, its type, the rest of the name) for a name beginning with a published topic
    (the longest that fits: rqt_plot takes the first the master lists)."""
    fits = [t for t in topics if name == t or name.startswith(t.rstrip("/") + "/")]
    if not fits:
        raise PlotError(unpublished(name, topics))
    topic = max(fits, key=len)
    return topic, topics[topic], name[len(topic):]


def unpublished(name: str, topics: dict[str, str]) -> str:
    """What to say of a name that starts with no published topic."""
    shown = sorted(topics)
    close: list[str] = []
    # the name itself, and each shorter name it starts with (the topic, without fields)
    for candidate in [name, *(name.rsplit("/", k)[0] for k in range(1, name.count("/")))]:
        close += [t for t in difflib.get_close_matches(candidate, shown, n=2, cutoff=0.8)
                  if t not in close]
    text = f"{name}: no topic of that name is published"
    text += f"; did you mean {' or '.join(close[:3])}?" if close else "."
    if shown:
        listed = ", ".join(shown[:30]) + (", ..." if len(shown) > 30 else "")
        text += f" Published now: {listed}."
    else:
        text += (" Nothing is published yet: start the simulation first (`sw2sim ros PACKAGE` "
                 "or roslaunch; `sw2sim ros2 PACKAGE` under ROS 2).")
    return text


def parse_path(rest: str, whole: str = "") -> tuple[Part, ...]:
    """The field path after the topic: `/a/b[2]/c` -> (a, b[2], c)."""
    parts = []
    for text in (p for p in rest.split("/") if p):
        m = PART.match(text)
        if not m:
            raise PlotError(f"{whole or rest}: `{text}` is not a field: write a field name, "
                            f"with an index in brackets for an array, e.g. velocity[0]")
        parts.append(Part(m[1], None if m[2] is None else int(m[2])))
    return tuple(parts)


def plan(name: str, topic: str, kind: str, rest: str, describe: Describe) -> list[Series]:
    """The series a name stands for, checked against the topic's type `kind`."""
    path = parse_path(rest, name)
    current, slot = kind, Slot(kind, "message")
    for n, part in enumerate(path):
        if slot.size is not None:
            raise PlotError(f"{name}: {path[n - 1]} is an array; give an index, "
                            f"e.g. {_joined(topic, path[:n - 1], Part(path[n - 1].name, 0))}")
        if slot.kind != "message":
            raise PlotError(f"{name}: {path[n - 1]} is a {slot.type}, which has no field "
                            f"{part.name}")
        fields = describe(current)
        if part.name not in fields:
            raise PlotError(f"{name}: {current} has no field {part.name!r}"
                            + _suggestion(part.name, fields)
                            + f". Its fields: {', '.join(fields)}")
        slot = fields[part.name]
        if part.index is not None:
            if slot.size is None:
                raise PlotError(f"{name}: {part.name} is a single {slot.type}, not an array; "
                                f"leave out [{part.index}]")
            if slot.size > 0 and not -slot.size <= part.index < slot.size:
                raise PlotError(f"{name}: {part.name} holds {slot.size} values: the index goes "
                                f"from 0 to {slot.size - 1}")
            slot = Slot(slot.type, slot.kind)
        current = slot.type
    return _series_of(name, topic, kind, path, slot, describe)


def _series_of(name, topic, kind, path, slot, describe) -> list[Series]:
    if slot.kind == "text":
        raise PlotError(f"{name}: {path[-1] if path else topic} is text ({slot.type}), not a "
                        "number: name a numeric field")
    if slot.size is not None:
        if slot.kind == "message" or slot.size < 0:
            raise PlotError(f"{name}: {path[-1]} is an array of {slot.type} whose length the "
                            f"message sets; give an index, e.g. "
                            f"{_joined(topic, path[:-1], Part(path[-1].name, 0))}")
        return [Series(f"{name}[{i}]", topic, kind, (*path[:-1], Part(path[-1].name, i)))
                for i in range(slot.size)]
    if slot.kind in ("number", "bool"):
        return [Series(name, topic, kind, path)]
    fields = describe(slot.type)
    numbers = [f for f, s in fields.items() if s.kind in ("number", "bool") and s.size is None]
    if not numbers:
        raise PlotError(f"{name}: {slot.type} has no numeric field of its own; name one of its "
                        f"fields: {', '.join(fields)}")
    return [Series(f"{name.rstrip('/')}/{f}", topic, kind, (*path, Part(f))) for f in numbers]


def _joined(topic: str, path, last: Part) -> str:
    return "/".join([topic.rstrip("/"), *map(str, path), str(last)])


def _suggestion(name: str, fields) -> str:
    close = difflib.get_close_matches(name, list(fields), n=1, cutoff=0.6)
    return f" (did you mean {close[0]}?)" if close else ""


def value(message, series: Series) -> float:
    """The series' number in a message."""
    current = message
    for part in series.path:
        current = getattr(current, part.name)
        if part.index is not None:
            try:
                current = current[part.index]
            except IndexError:
                count = len(current)
                raise PlotError(f"{series.name}: this message's {part.name} holds "
                                + (f"{count} values (index 0 to {count - 1})" if count
                                   else "no values")
                                + f"; name an index below {count}") from None
    try:
        return float(current)
    except (TypeError, ValueError):
        raise PlotError(f"{series.name}: the message holds {current!r} there, not a "
                        "number") from None
