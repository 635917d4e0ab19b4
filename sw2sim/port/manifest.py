"""package.xml in format 3 for an ament_cmake package that only installs files.

Every dependency is needed at run time only (`exec_depend`): what the launch files start
and the controllers' plugins. Name, version, description, licence and maintainers are the
source's where catkin_pkg would accept them; what is replaced is reported.
"""

from __future__ import annotations

import re
from html import escape

from lxml import etree

# What the generated launch files and the URDF's plugin need, in the order they are listed.
LAUNCH_DEPENDS = ("ament_index_python", "launch", "launch_ros", "robot_state_publisher",
                  "joint_state_publisher_gui", "rviz2", "xacro", "ros_gz_sim", "ros_gz_bridge",
                  "gz_ros2_control", "controller_manager")
PLACEHOLDER_EMAIL = "maintainer@example.com"
# catkin_pkg's own patterns (catkin_pkg/package.py: Person.validate and Package.validate)
EMAIL = re.compile(r"^[-a-zA-Z0-9_%+]+(\.[-a-zA-Z0-9_%+]+)*@[-a-zA-Z0-9%]+(\.[-a-zA-Z0-9%]+)*"
                   r"\.[a-zA-Z]{2,}$")
VERSION = re.compile(r"^(0|[1-9][0-9]*)\.(0|[1-9][0-9]*)\.(0|[1-9][0-9]*)$")


def parse_maintainer(text: str) -> tuple[str, str]:
    """--maintainer "Name <e-mail>" as (name, e-mail); ValueError with the reason when
    catkin_pkg would refuse it."""
    match = re.fullmatch(r"\s*([^<>]*?)\s*<\s*([^<>\s]+)\s*>\s*", text)
    if not match or not match.group(1):
        raise ValueError(f"{text!r} is not NAME <E-MAIL>; write it as \"Ada Lovelace "
                         "<ada@example.org>\", quoted")
    who, email = match.groups()
    if not EMAIL.match(email):
        raise ValueError(f"{email!r} is not an e-mail address catkin_pkg accepts")
    return who, email


def package_xml(name: str, manifest: etree._Element | None, controller_packages: list[str],
                choices: list[str], *, maintainer: tuple[str, str] | None = None,
                license: str | None = None) -> str:
    """The text of package.xml; what was replaced is appended to `choices`. `maintainer`
    (name, e-mail) and `license` (--maintainer, --license) replace the source's."""
    get = (lambda tag: (manifest.findtext(tag) or "").strip()) if manifest is not None \
        else (lambda tag: "")
    version = get("version")
    if not VERSION.match(version):
        choices.append(f"package.xml: version {version or '(none)'} is not X.Y.Z; it is 1.0.0.")
        version = "1.0.0"
    description = _description(manifest)
    if not description:
        description = f"{name}: a robot description exported from SolidWorks, for ROS 2"
        choices.append("package.xml: the source has no description; a one-line one was written.")
    licenses = [(e.text or "").strip() for e in manifest.findall("license")] \
        if manifest is not None else []
    licenses = [lic for lic in licenses if lic]
    if license is not None:
        licenses = [license.strip()]
    elif not licenses:
        licenses = ["TODO"]
        choices.append("package.xml: the source names no licence; `TODO` was written. Put "
                       "your licence there (BSD-3-Clause, Apache-2.0, ...), or port again "
                       "with --license.")
    maintainers = []
    people = manifest.findall("maintainer") if manifest is not None and maintainer is None \
        else []
    if maintainer is not None:
        maintainers.append(maintainer)
    for person in people:
        who, email = (person.text or "").strip(), (person.get("email") or "").strip()
        if not EMAIL.match(email):
            choices.append(f"package.xml: the maintainer e-mail {email or '(none)'!r} is not one "
                           f"catkin_pkg accepts (colcon stops on it); {PLACEHOLDER_EMAIL} was "
                           "written. Put your own.")
            email = PLACEHOLDER_EMAIL
        maintainers.append((who or "TODO", email))
    if not maintainers:
        maintainers = [("TODO", PLACEHOLDER_EMAIL)]
        choices.append(f"package.xml: the source has no maintainer; TODO <{PLACEHOLDER_EMAIL}> "
                       "was written. Put your own name and e-mail, or port again with "
                       "--maintainer \"NAME <E-MAIL>\".")
    elif any(who == "TODO" or email.lower().startswith("todo@") for who, email in maintainers):
        choices.append("package.xml: the maintainer is the exporter's placeholder (TODO); "
                       "put your own name and e-mail, or port again with --maintainer "
                       "\"NAME <E-MAIL>\".")
    depends = list(dict.fromkeys([*LAUNCH_DEPENDS, *controller_packages]))
    lines = ['<?xml version="1.0"?>',
             '<?xml-model href="http://download.ros.org/schema/package_format3.xsd" '
             'schematypens="http://www.w3.org/2001/XMLSchema"?>',
             '<package format="3">',
             f"  <name>{escape(name)}</name>",
             f"  <version>{version}</version>",
             f"  <description>{escape(description)}</description>",
             *(f"  <maintainer email=\"{escape(email)}\">{escape(who)}</maintainer>"
               for who, email in maintainers),
             *(f"  <license>{escape(lic)}</license>" for lic in licenses),
             "",
             "  <buildtool_depend>ament_cmake</buildtool_depend>",
             "",
             *(f"  <exec_depend>{d}</exec_depend>" for d in depends),
             "",
             "  <export>",
             "    <build_type>ament_cmake</build_type>",
             "  </export>",
             "</package>", ""]
    return "\n".join(lines)


def _description(manifest) -> str:
    """The source's description as one line of plain text (the exporter's holds <p>s)."""
    if manifest is None:
        return ""
    element = manifest.find("description")
    if element is None:
        return ""
    return " ".join("".join(element.itertext()).split())
