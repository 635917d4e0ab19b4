"""Packages as people ship them: several URDFs in one package, a folder named otherwise
than the package, and packages that hold only a .xacro.

The packages are copies of the examples, changed as real repositories are: a copy of the
URDF beside it, an environment URDF, the URDF turned into a xacro with properties.
"""

from __future__ import annotations

import hashlib
import re
import shutil
from pathlib import Path

import mujoco
import pytest

from sw2sim.check import check
from sw2sim.cli import main
from sw2sim.package import find_package
from packages import copy_example, edit, line_of, urdf_of

ENVIRONMENT = """<?xml version="1.0"?>
<robot name="table">
  <link name="table_top">
    <inertial><mass value="20"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>
    <visual><geometry><box size="1.2 0.8 0.04"/></geometry></visual>
  </link>
</robot>
"""


def snapshot(folder: Path) -> dict[str, str]:
    return {p.relative_to(folder).as_posix(): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted(folder.rglob("*")) if p.is_file()}


def cloned_with_copies(folder: Path) -> Path:
    """Practice 3's arm cloned into a folder named like a repository, with "example_3 -
    Copy.urdf" (an older export, its mesh paths naming the assembly) and a table's URDF."""
    package = copy_example(3, folder, name="arm-description-main")
    urdf = urdf_of(package)
    copy = urdf.with_name("example_3 - Copy.urdf")
    shutil.copy(urdf, copy)
    edit(copy, "package://example_3/", "package://Arm_Assembly/", count=6)
    (urdf.parent / "aaa_environment.urdf").write_text(ENVIRONMENT)
    return package


def xacro_only(folder: Path, find: str | None = None) -> Path:
    """Practice 3's arm shipped as urdf/example_3.urdf.xacro: a property for the arm's
    reach, and its mesh paths written with $(find <package>)."""
    package = copy_example(3, folder)
    urdf = urdf_of(package)
    text = urdf.read_text()
    text = text.replace('<robot\n  name="example_3">',
                        '<robot\n  name="example_3" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                        '  <xacro:property name="reach" value="0.7854" />', 1)
    text = text.replace('lower="-0.7854"', 'lower="${-reach}"')
    text = text.replace('upper="0.7854"', 'upper="${reach}"')
    text = text.replace("package://example_3/meshes/",
                        f"file://$(find {find or 'example_3'})/meshes/")
    urdf.with_suffix(".urdf.xacro").write_text(text)
    urdf.unlink()
    return package


def broken_xacro(folder: Path) -> Path:
    package = xacro_only(folder)
    xacro = next((package / "urdf").glob("*.xacro"))
    edit(xacro, "${reach}", "${reach_typo}")
    return package


BATTERY = {"urdf-several": cloned_with_copies}


def test_the_urdf_named_after_the_package_is_chosen_and_said(tmp_path):
    package = cloned_with_copies(tmp_path)
    before = snapshot(package)
    report = check(package, stability=False)
    [several] = [f for f in report.findings if f.rule == "urdf-several"]
    assert "read urdf/example_3.urdf" in several.message
    assert "package.xml" in several.message and "example_3 - Copy.urdf" in several.message
    assert "--urdf" in several.fix
    assert report.status == 0, report.format()      # no package-name finding, no error
    assert not {"package-name-mismatch", "package-name-invalid"} & report.rules()
    assert snapshot(package) == before


def test_a_launch_file_decides_when_no_urdf_has_the_packages_name(tmp_path):
    package = cloned_with_copies(tmp_path)
    urdf = urdf_of(package)
    urdf.rename(urdf.with_name("arm.urdf"))
    (package / "launch" / "display.launch").write_text(
        '<launch>\n  <param name="robot_description" textfile="$(find example_3)/urdf/arm.urdf" />\n'
        '</launch>\n')
    found = find_package(package)
    assert found.urdf.name == "arm.urdf"
    assert found.chosen_because == "loaded by launch/display.launch"


def test_urdf_picks_another_and_a_wrong_one_lists_them(tmp_path, capsys):
    package = cloned_with_copies(tmp_path)
    assert main(["check", str(package), "--no-sim", "--urdf", "aaa_environment.urdf"]) == 0
    out = capsys.readouterr().out
    assert "read urdf/aaa_environment.urdf, asked for with --urdf" in out
    status = main(["check", str(package), "--urdf", "robot.urdf"])
    out = capsys.readouterr().out
    assert status == 2
    assert "example_3.urdf" in out and "aaa_environment.urdf" in out


def test_a_folder_named_otherwise_than_its_package_is_no_error(tmp_path):
    report = check(copy_example(3, tmp_path, name="arm-description-main"), stability=False)
    assert report.status == 0, report.format()
    assert all(f.severity == "warning" for f in report.findings)


def test_a_xacro_only_package_is_expanded_checked_and_converted(tmp_path, capsys):
    package = xacro_only(tmp_path)
    before = snapshot(package)
    report = check(package)
    assert report.status == 0, report.format()
    assert report.stability is not None
    out = tmp_path / "out"
    assert main(["convert", str(package), "-o", str(out)]) == 0
    model = mujoco.MjModel.from_xml_path(str(out / "scene.xml"))
    assert model.jnt_range[model.joint("middle_arm_joint").id][1] == pytest.approx(0.7854)
    assert snapshot(package) == before
    assert not list((package / "urdf").glob("*.urdf"))     # nothing written beside it


def test_a_finding_in_an_expanded_xacro_names_the_xacro_line_that_writes_it(tmp_path):
    package = xacro_only(tmp_path)
    xacro = next((package / "urdf").glob("*.xacro"))
    edit(xacro, 'effort="1000"', 'effort="0"')
    [finding] = [f for f in check(package, stability=False).findings
                 if f.rule == "effort-not-positive"]
    assert Path(finding.file).name == xacro.name
    assert finding.line == line_of(xacro, 'effort="0"')
    assert "expands to" not in finding.message


def test_a_finding_in_what_a_macro_writes_names_the_expanded_line_and_says_so(tmp_path):
    package = xacro_only(tmp_path)
    xacro = next((package / "urdf").glob("*.xacro"))
    text = xacro.read_text()
    # the last link, written by a macro called once
    start = text.index('<link\n    name="end_arm_link"')
    end = text.index("</link>", start) + len("</link>")
    body = text[start:end].replace('name="end_arm_link"', 'name="${name}"')
    body = re.sub(r'ixx="[^"]*"', 'ixx="-0.001"', body)
    text = (text[:start] + f'<xacro:macro name="part" params="name">{body}</xacro:macro>\n'
            '  <xacro:part name="end_arm_link" />' + text[end:])
    xacro.write_text(text)
    [finding] = [f for f in check(package, stability=False).findings
                 if f.rule == "inertia-not-positive-definite"]
    assert Path(finding.file).name == xacro.name and finding.line is None
    assert re.search(r"\(line \d+ of the URDF the xacro expands to; `xacro example_3.urdf.xacro` "
                     r"prints it\)", finding.message), finding.message


def test_a_xacro_needing_another_package_says_which(tmp_path):
    package = xacro_only(tmp_path, find="arm_meshes")
    report = check(package, stability=False)
    [finding] = report.findings
    assert finding.rule == "xacro-needs-package" and report.status == 2
    assert '"arm_meshes"' in finding.message and "xacro" in finding.fix


def test_a_xacro_that_does_not_expand_gives_xacros_message(tmp_path):
    report = check(broken_xacro(tmp_path), stability=False)
    [finding] = report.findings
    assert finding.rule == "xacro-failed" and report.status == 2
    assert "reach_typo" in finding.message
