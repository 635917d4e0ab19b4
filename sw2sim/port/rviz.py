"""A ROS 1 RViz configuration (`urdf.rviz`) made readable by RViz 2.

The file format is the same YAML; the plugin class names differ. RViz 1's `rviz/<Name>`
panels are `rviz_common/<Name>` in RViz 2 and its displays, tools and views
`rviz_default_plugins/<Name>` (the class lists of ros2/rviz's jazzy branch:
rviz_common/plugins_description.xml, rviz_default_plugins/plugins_description.xml). RViz 2's
RobotModel reads the URDF from a topic, not from a parameter.
"""

from __future__ import annotations

import re
from pathlib import Path

import yaml

PANELS = {"Displays", "Selection", "Tool Properties", "Views", "Time"}
WHERE = ("", "rviz", "urdf", "config", "launch")   # folders of the package searched, in order


def find(root: Path) -> Path | None:
    """The package's RViz configuration: urdf.rviz at its root (as the lessons' packages have
    it), else the first .rviz file of its root, rviz/, urdf/, config/ or launch/ folder."""
    for folder in WHERE:
        base = root / folder
        if base.is_dir():
            found = sorted(p for p in base.glob("*.rviz") if p.is_file())
            preferred = [p for p in found if p.name == "urdf.rviz"]
            if preferred or found:
                return (preferred or found)[0]
    return None


def convert(text: str) -> tuple[str, int]:
    """The configuration for RViz 2, and how many class names were changed."""
    data = yaml.safe_load(text)
    count = [0]

    def walk(node):
        if isinstance(node, dict):
            kind = node.get("Class")
            if isinstance(kind, str) and kind.startswith("rviz/"):
                bare = kind[len("rviz/"):]
                node["Class"] = ("rviz_common/" if bare in PANELS else "rviz_default_plugins/") + bare
                count[0] += 1
                if bare == "RobotModel" and "Robot Description" in node:
                    del node["Robot Description"]
                    node["Description Source"] = "Topic"
                    node["Description Topic"] = {"Value": "/robot_description"}
            for value in node.values():
                walk(value)
        elif isinstance(node, list):
            for value in node:
                walk(value)

    walk(data)
    return yaml.safe_dump(data, sort_keys=False, default_flow_style=False), count[0]


def looks_like_rviz1(text: str) -> bool:
    return bool(re.search(r"Class:\s*rviz/", text))
