"""Hand edits in the files the exporter rewrites, with no saved copy to restore them from.

Exporting again (either button) rewrites the URDF, package.xml, CMakeLists.txt, the
joint-names YAML and both launch files, so anything added to them by hand is lost unless
`sw2sim edits save` kept a copy in hand_edits/ (`sw2sim.edits`). The check sees the hand
edits it can tell for certain are not the exporter's: in the URDF a <transmission>, a
<gazebo> element, a `world` link or a joint's <dynamics>; in gazebo.launch a node or
parameter beyond the exporter's three nodes; in CMakeLists.txt catkin_install_python.
"""

from __future__ import annotations

import json
import re

from .. import archive
from ..edits import FOLDER, MANIFEST, copy_of
from .context import display
from .findings import ADVICE, WARNING, rule

rule("hand-edits-unsaved", WARNING, "package", "Hand edits that exporting again would lose",
     symptom="After exporting the assembly again, the colours, the world link, the "
             "transmissions, the <gazebo> plugins or the launch file's nodes are gone.",
     cause="Both of the exporter's buttons rewrite the URDF, its CSV, package.xml, "
           "CMakeLists.txt, config/joint_names_<name>.yaml and both launch files; what was "
           "added to them by hand is not kept. The package holds such edits, and "
           "hand_edits/ has no copy of them (or an older one).",
     fix="Run `sw2sim edits save PKG` now and after each hand edit; after exporting again, "
         "`sw2sim edits restore PKG` puts the edits back.",
     blocks=ADVICE)

# The nodes the exporter's gazebo.launch starts; anything else there was added by hand.
EXPORTER_NODES = {"tf_footprint_base", "spawn_model", "fake_joint_calibration"}
_NODE = re.compile(r"<node\b[^>]*?\bname\s*=\s*[\"']([^\"']*)[\"']", re.S)


def check(ctx) -> None:
    package = ctx.package
    if package.expanded_from is not None or archive.shown(package.urdf) is not None:
        return   # a xacro is no export, and a .zip has no folder to save into
    edited = {}
    urdf = package.urdf.relative_to(package.root).as_posix()
    marks = _urdf_marks(ctx.robot)
    if marks:
        edited[urdf] = marks
    launch = package.root / "launch" / "gazebo.launch"
    if launch.is_file():
        text = launch.read_text(errors="replace")
        extra = [n for n in _NODE.findall(text) if n not in EXPORTER_NODES]
        marks = [f"node {n}" for n in extra] + (["<param>"] if "<param" in text
                                                else []) + (["<rosparam>"] if "<rosparam"
                                                            in text else [])
        if marks:
            edited["launch/gazebo.launch"] = marks
    cmake = package.root / "CMakeLists.txt"
    if cmake.is_file() and "catkin_install_python" in cmake.read_text(errors="replace"):
        edited["CMakeLists.txt"] = ["catkin_install_python"]
    if not edited:
        return
    saved = package.root / FOLDER
    unsaved = [rel for rel in edited if not _saved(saved, rel, package.root / rel)]
    if not unsaved:
        return
    has_copy = (saved / MANIFEST).is_file()
    where = display(package.root)
    said = "; ".join(f"{rel}: {', '.join(edited[rel])}" for rel in unsaved)
    ctx.add("hand-edits-unsaved",
            f"exporting again would lose hand edits ({said}), and {FOLDER}/ "
            + ("holds an older copy of them" if has_copy else "holds no copy of them"),
            file=package.root / unsaved[0],
            fix=f"run `sw2sim edits save {where}` now and after each hand edit; after "
                f"exporting again, `sw2sim edits restore {where}` puts them back")


def _urdf_marks(robot) -> list[str]:
    marks = [f"<{tag}>" for tag in ("transmission", "gazebo") if robot.find(tag) is not None]
    if any(link.get("name") == "world" for link in robot.findall("link")):
        marks.append("the world link")
    if any(joint.find("dynamics") is not None for joint in robot.findall("joint")):
        marks.append("<dynamics>")
    return marks


def _saved(folder, rel: str, current) -> bool:
    """Whether hand_edits/ holds this file as it is now."""
    try:
        listed = rel in json.loads((folder / MANIFEST).read_text())["files"]
        return listed and copy_of(folder, rel).read_bytes() == current.read_bytes()
    except (OSError, ValueError, KeyError, TypeError):
        return False
