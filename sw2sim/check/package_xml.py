"""Checks of package.xml and of the package name the URDF's mesh paths use.

MuJoCo only needs the meshes; ROS needs the package to be a valid catkin package whose
name matches the `package://<name>/` prefix of every mesh path. The name that counts is
the one `sw2sim.package.find_package` reads (package.xml's <name>, else the folder's name),
so this check and the loader agree; package.xml itself is read there, once. A package.xml
that is not well-formed XML never gets here: opening the package reports it, with its
line, as `xml-syntax`.
"""

from __future__ import annotations

import re

from ..mesh_paths import matches
from ..xmlsafe import source_line
from .findings import ERROR, SIMULATION, WARNING, rule
from .repairs import repair, set_attribute
from .urdf import owner

# catkin's rules for package names (catkin_pkg, REP 144): a name outside LENIENT_NAME is
# refused; one outside VALID_NAME is accepted with a warning, for old packages' sake.
VALID_NAME = re.compile(r"[a-z][a-z0-9_]*")
LENIENT_NAME = re.compile(r"[a-zA-Z0-9][a-zA-Z0-9_-]*")
FORMATS = ("1", "2", "3")
# Tags that exist from format 2 on; under format 1 catkin rejects them.
FORMAT_2_TAGS = ("depend", "exec_depend", "build_export_depend", "buildtool_export_depend",
                 "doc_depend")

rule("package-xml-missing", WARNING, "package", "The package has no package.xml",
     symptom="MuJoCo loads the model, but ROS does not see a package: `roslaunch`, "
             "`rospack find` and package:// paths in RViz and Gazebo fail.",
     cause="The URDF was copied out of its exported package, or package.xml was deleted.",
     fix="Check the package folder the exporter wrote (it holds package.xml next to urdf/ "
         "and meshes/), or export the assembly again.")
rule("package-xml-invalid", ERROR, "package", "package.xml is not a package manifest",
     symptom="catkin stops with an error reading package.xml; ROS does not find the "
             "package.",
     cause="Another XML file saved as package.xml, or a hand edit that replaced the "
           "top-level <package> element.",
     fix="Restore the exported package.xml, whose top element is <package format=\"2\">.")
rule("package-format-missing", ERROR, "package", "package.xml uses format 2 tags without "
     "declaring format 2",
     symptom="catkin_make stops on the <depend> tags (\"must not contain the following tags: "
             "depend\"); MuJoCo is not affected.",
     cause="Without a format attribute catkin reads package.xml as format 1, which has no "
           "<depend> tag. Exports made before the exporter was fixed omit the attribute.",
     fix="Write <package format=\"2\"> as the first tag of package.xml.",
     seen_in=("solidworks_urdf_exporter#84", "solidworks_urdf_exporter#71"))
rule("package-format-unknown", ERROR, "package", "package.xml declares a format catkin "
     "does not know",
     symptom="catkin stops with \"Unable to handle package.xml format\"; MuJoCo is not "
             "affected.",
     cause="A hand edit: catkin knows formats 1, 2 and 3 only.",
     fix="Write <package format=\"2\"> (format 3 also works, with ROS Noetic's catkin).")
rule("package-name-invalid", ERROR, "package", "catkin refuses the package name",
     symptom="catkin stops with \"Package name ... does not follow naming conventions\"; ROS "
             "tools cannot find the package by name.",
     cause="The package is named by what is typed in the exporter's save dialog, which "
           "offers the assembly's name; accepted as offered, a space, a dot or another sign "
           "in the assembly's name ends up in the package name. catkin accepts letters, "
           "digits, _ and - only.",
     fix="Export again and type a valid name (e.g. `my_robot`) in the save dialog, or "
         "change <name> in package.xml, the package:// paths in the URDF, the $(find ...) "
         "in the launch files and the folder name to the same valid name.",
     seen_in=("solidworks_urdf_exporter#84",))
rule("package-name-style", WARNING, "package", "The package name breaks ROS's naming rule",
     symptom="catkin builds the package but warns that the name \"does not follow the naming "
             "conventions\"; newer tools (catkin_create_pkg, the ROS 2 templates, the build "
             "farm) refuse such names.",
     cause="The save dialog offers the assembly's name, capital letters, leading digits "
           "and dashes included, and the exporter names the package by what the dialog "
           "returns; ROS names are lower-case letters, digits and _, starting with a letter.",
     fix="Export again and type the name in lower case (e.g. `my_robot`) in the save "
         "dialog, or rename the package, its mesh paths, its launch files and its folder "
         "alike.",
     seen_in=("solidworks_urdf_exporter#84",))
rule("package-name-mismatch", ERROR, "package", "The mesh paths name a different package "
     "than package.xml",
     symptom="MuJoCo, RViz and Gazebo report the meshes as not found, although the files are "
             "in meshes/.",
     cause="The package, its folder or its package.xml was renamed after the export, so the "
           "package://<name>/meshes/... paths in the URDF name a package that is not there.",
     fix="Make the names agree: change <name> in package.xml, or replace the package:// "
         "prefix in every mesh path of the URDF.",
     seen_in=("mujoco#273", "mujoco#1432", "mujoco#1569"), blocks=SIMULATION,
     repair="when every mesh path that names the other package, read inside this one, "
            "leads to exactly one of its files (ignoring capitals, with \\ read as /), the "
            "meshes are read from those files.")
rule("package-folder-name", WARNING, "package", "The folder's name differs from the "
     "package's name",
     symptom="ROS still finds the package by the name in package.xml, but tools outside ROS "
             "that resolve package:// paths by folder name do not find the meshes.",
     cause="The folder was renamed or copied under a new name after the export.",
     fix="Rename the folder to the name in package.xml (or change both the name and the "
         "mesh paths to the folder's name).")


def check(ctx) -> None:
    """Add a finding to ctx for every problem of this group."""
    package = ctx.package
    manifest = package.manifest_file
    if package.manifest is not None:
        _manifest(ctx, manifest, package.manifest)
    else:
        from ..port.naming import is_legal, legal_name
        ported = package.name if is_legal(package.name) else legal_name(package.name)
        ctx.add("package-xml-missing", f"no package.xml in {package.root.name}/; the package "
                f'name "{package.name}" is taken from {package.name_from}', file=manifest,
                fix=f"`sw2sim port` writes one in its place: a ROS 2 package.xml (format 3, "
                    f'ament_cmake) naming the package "{ported}", with every mesh path '
                    f'renamed to package://{ported}/ (--name NEW chooses another name); for '
                    "ROS 1, copy the package.xml the exporter wrote beside urdf/ and meshes/")
    _mesh_package_names(ctx, has_manifest=package.manifest is not None)


def _manifest(ctx, manifest, root) -> None:
    """The checks of package.xml, whose top element (as the package read it) is `root`."""
    if root.tag != "package":
        ctx.add("package-xml-invalid", f"the top element of package.xml is <{root.tag}>, not "
                "<package>", file=manifest, line=root.sourceline)
        return
    _format(ctx, manifest, root)
    name_element = root.find("name")
    name = (name_element.text or "").strip() if name_element is not None else ""
    if not name:
        ctx.add("package-name-invalid", "package.xml has no <name>", file=manifest,
                line=(name_element if name_element is not None else root).sourceline,
                fix=f"add <name>{_suggest(ctx.package.root.name)}</name> to package.xml")
        return
    if not VALID_NAME.fullmatch(name):
        refused = not LENIENT_NAME.fullmatch(name)
        ctx.add("package-name-invalid" if refused else "package-name-style",
                f'package name "{name}" ' + ("has characters catkin refuses" if refused else
                                             "has capitals, a leading digit or a dash"),
                file=manifest, line=name_element.sourceline,
                fix=f'rename the assembly (or the package) to e.g. "{_suggest(name)}" and '
                    "export again, or rename the package, its mesh paths and its folder alike")
    folder = ctx.package.root.name
    if folder != name:
        ctx.add("package-folder-name", f'the folder is called "{folder}" but package.xml names '
                f'the package "{name}"', file=manifest, line=name_element.sourceline,
                fix=f'rename the folder "{folder}" to "{name}"')


def _format(ctx, manifest, root) -> None:
    declared = root.get("format")
    if declared is not None and declared.strip() not in FORMATS:
        ctx.add("package-format-unknown", f'<package format="{declared[:20]}">: catkin knows '
                "formats 1, 2 and 3", file=manifest, line=root.sourceline)
        return
    # No format means format 1, which is fine for a manifest written in format 1's tags.
    newer = next((el for el in root if el.tag in FORMAT_2_TAGS), None)
    if newer is not None and (declared is None or declared.strip() == "1"):
        said = "has no format attribute" if declared is None else 'says format="1"'
        ctx.add("package-format-missing", f"<package> {said}, so catkin reads it as format 1, "
                f"but it uses <{newer.tag}>, a format 2 tag (line {newer.sourceline})",
                file=manifest, line=root.sourceline)


def _mesh_package_names(ctx, has_manifest: bool) -> None:
    """One finding per package name the mesh paths use that is not this package's name."""
    expected = ctx.package.name
    wrong: dict[str, list] = {}
    for mesh in ctx.robot.iter("mesh"):
        filename = mesh.get("filename") or ""
        if filename.startswith("package://"):
            name = filename[len("package://"):].partition("/")[0]
            if name != expected:
                wrong.setdefault(name, []).append(mesh)
    for name, meshes in wrong.items():
        source = "package.xml" if has_manifest else \
            f"{ctx.package.name_from} (there is no package.xml)"
        count = f"{len(meshes)} mesh path" + ("s" if len(meshes) > 1 else "")
        fix = (f'change <name> in package.xml to "{name}", or replace "package://{name}/" by '
               f'"package://{expected}/" in the URDF' if has_manifest else
               f'put the URDF back in its package folder "{name}" (with its package.xml), or '
               f'replace "package://{name}/" by "package://{expected}/" in the URDF')
        ctx.add("package-name-mismatch", f'{count} name package "{name}" (first in '
                f'{owner(meshes[0])}), but this package is "{expected}" according to '
                f"{source}", line=source_line(meshes[0], "filename"), fix=fix,
                repair=_read_inside(ctx, name, meshes))


def _read_inside(ctx, name: str, meshes):
    """The meshes read from this package's files, when each path leads to exactly one."""
    files, edits, read = ctx.package_files(), [], {}
    for mesh in meshes:
        found = matches(files, mesh.get("filename") or "")
        if len(found) != 1:
            return None
        read[found[0].as_posix()] = True
        edits.append((mesh, set_attribute(
            "filename", f"package://{ctx.package.name}/{found[0].as_posix()}")))
    return repair(f'the paths naming package "{name}" are read inside this package, each from '
                  f"the one file it can mean: {', '.join(read)}", *edits)


def _suggest(name: str) -> str:
    """A catkin-valid version of a name: lower case, underscores, starting with a letter."""
    cleaned = re.sub(r"[^a-z0-9_]+", "_", name.lower()).strip("_")
    if not cleaned or not cleaned[0].isalpha():
        cleaned = "robot_" + cleaned
    return cleaned.rstrip("_") or "robot"
