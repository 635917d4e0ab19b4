"""The package rules of `sw2sim check`: package.xml and the package:// names of the meshes."""

from __future__ import annotations

from pathlib import Path

import pytest
from packages import EXAMPLES, copy_example, edit, fires_at, group_findings, line_of, urdf_of
from repository import practice_numbers

from sw2sim.check import all_rules, check, open_package, package_xml
from sw2sim.check.package_xml import _suggest

GROUP = "package"


def _manifest(folder: Path, old: str, new: str, name: str | None = None) -> Path:
    package = copy_example(1, folder, name)
    edit(package / "package.xml", old, new)
    return package


def _no_manifest(folder: Path) -> Path:
    package = copy_example(1, folder)
    (package / "package.xml").unlink()
    return package


def _not_a_manifest(folder: Path) -> Path:
    package = copy_example(1, folder)
    (package / "package.xml").write_text('<?xml version="1.0"?>\n<launch>\n</launch>\n')
    return package


def _renamed_consistently(folder: Path, name: str) -> Path:
    """The package under another name everywhere: folder, package.xml and mesh paths."""
    package = _manifest(folder, "<name>example_1</name>", f"<name>{name}</name>", name)
    edit(urdf_of(package), "package://example_1/", f"package://{name}/", count=10)
    return package


def _renamed(folder: Path) -> Path:
    # Folder and package.xml renamed after the export; the mesh paths still say example_1.
    return _manifest(folder, "<name>example_1</name>", "<name>my_robot</name>", "my_robot")


# Each maker breaks one thing; WHERE gives the file and the text on the finding's line
# (None: the finding names the file only).
BATTERY = {
    "package-xml-missing": _no_manifest,
    "package-xml-invalid": _not_a_manifest,
    "package-format-missing": lambda d: _manifest(d, '<package format="2">', "<package>"),
    "package-format-unknown": lambda d: _manifest(d, 'format="2"', 'format="two"'),
    # The exporter names the package after the assembly (PR #84): "My Robot.SLDASM".
    "package-name-invalid": lambda d: _renamed_consistently(d, "My Robot"),
    "package-name-style": lambda d: _renamed_consistently(d, "My_Robot"),
    "package-name-mismatch": _renamed,
    "package-folder-name": lambda d: copy_example(1, d, "my_robot"),
}
WHERE = {
    "package-xml-missing": ("package.xml", None),
    "package-xml-invalid": ("package.xml", "<launch>"),
    "package-format-missing": ("package.xml", "<package>"),
    "package-format-unknown": ("package.xml", 'format="two"'),
    "package-name-invalid": ("package.xml", "<name>My Robot</name>"),
    "package-name-style": ("package.xml", "<name>My_Robot</name>"),
    "package-name-mismatch": ("urdf/example_1.urdf", "package://example_1/meshes/base_link.STL"),
    "package-folder-name": ("package.xml", "<name>example_1</name>"),
}


def ours(report) -> list:
    return group_findings(report, GROUP)


def package_findings(path: Path, rule_id: str | None = None) -> list:
    """The package check's findings alone (the full check also loads every mesh)."""
    ctx = open_package(path)
    if ctx.usable:
        package_xml.check(ctx)
    return [f for f in ctx.findings if rule_id in (None, f.rule)]


def test_battery_covers_every_package_rule():
    # hand-edits-unsaved has its own module (sw2sim/check/hand_edits.py) and tests
    # (test_hand_edits_rule.py): it reads the launch files and hand_edits/, not package.xml.
    assert set(BATTERY) == set(WHERE) == {r.id for r in all_rules().values()
                                          if r.group == GROUP} - {"hand-edits-unsaved"}


@pytest.mark.parametrize("rule_id", sorted(BATTERY))
def test_rule_fires_at_the_offending_line(rule_id, tmp_path):
    package = BATTERY[rule_id](tmp_path)
    relative, needle = WHERE[rule_id]
    report, hits = fires_at(package, rule_id, needle, package / relative)


@pytest.mark.parametrize("n", practice_numbers())
def test_examples_are_clean(n):
    assert ours(check(EXAMPLES / f"example_{n}", stability=False)) == []


def test_a_package_xml_that_is_not_xml_stops_the_check_with_its_line(tmp_path):
    # Like sw2sim.load_package, the check cannot tell the package's name without it.
    package = _manifest(tmp_path, "</maintainer>", "</maintaner>")
    report = check(package, stability=False)
    (hit,) = report.findings
    assert hit.rule == "xml-syntax" and report.status == 2
    assert Path(hit.file).resolve() == (package / "package.xml").resolve()
    assert hit.line == line_of(package / "package.xml", "</maintaner>")


def test_a_lone_urdf_takes_its_folders_name(tmp_path):
    # A URDF copied out of its package: no package.xml, and the folder is not "example_1".
    urdf = tmp_path / "robot.urdf"
    urdf.write_text(urdf_of(EXAMPLES / "example_1").read_text())
    assert {f.rule for f in package_findings(urdf)} == {"package-xml-missing",
                                                         "package-name-mismatch"}
    (hit,) = package_findings(urdf, "package-name-mismatch")
    assert "10 mesh paths" in hit.message and 'link "base_link"' in hit.message
    assert "no package.xml" in hit.message


def test_the_exporters_own_example_name_is_a_style_warning(tmp_path):
    # The exporter's own example is called 4_WHEELER_description: catkin warns, and builds.
    package = _manifest(tmp_path, "<name>example_1</name>", "<name>4_WHEELER_description</name>")
    (hit,) = package_findings(package, "package-name-style")
    assert '"robot_4_wheeler_description"' in hit.fix
    assert package_findings(package, "package-name-invalid") == []


def test_an_empty_name_is_invalid(tmp_path):
    package = _manifest(tmp_path, "<name>example_1</name>", "<name> </name>")
    (hit,) = package_findings(package, "package-name-invalid")
    assert "no <name>" in hit.message and "<name>example_1</name>" in hit.fix


@pytest.mark.parametrize("declared, finding", [
    ('format="3"', None),
    ('format="1"', "package-format-missing"),   # format 1 has no <depend>, which it uses
    ('format=" 2 "', None),
    ('format=""', "package-format-unknown"),
    ('format="4"', "package-format-unknown"),
])
def test_formats(declared, finding, tmp_path):
    package = _manifest(tmp_path, 'format="2"', declared)
    assert {f.rule for f in package_findings(package)} == ({finding} - {None})


@pytest.mark.parametrize("declared", ['format="1"', ""])
def test_format_1_written_in_format_1_tags_is_fine(declared, tmp_path):
    package = _manifest(tmp_path, 'format="2"', declared)
    text = (package / "package.xml").read_text().replace("<depend>", "<run_depend>")
    (package / "package.xml").write_text(text.replace("</depend>", "</run_depend>"))
    assert package_findings(package) == []


def test_every_wrong_package_name_is_reported_once(tmp_path):
    package = copy_example(1, tmp_path)
    urdf = urdf_of(package)
    edit(urdf, "package://example_1/meshes/front_left", "package://other/meshes/front_left", 2)
    edit(urdf, "package://example_1/meshes/rear_left", "package://Other/meshes/rear_left", 2)
    hits = package_findings(package, "package-name-mismatch")
    assert sorted(h.message.split('"')[1] for h in hits) == ["Other", "other"]
    assert all(h.message.startswith("2 mesh paths") for h in hits)


def test_suggested_names_are_valid():
    assert _suggest("My Robot-2") == "my_robot_2"
    assert _suggest("3_DOF_ARM") == "robot_3_dof_arm"
    assert _suggest("---") == "robot"


@pytest.mark.parametrize("text", [
    '<package format="2"/>',                                     # no name at all
    '<package format="2"><name><b>x</b></name></package>',     # markup in the name
    '<package format="2"><name>x</name><depend/></package>',
    '<?xml version="1.0"?><!-- only a comment --><package/>',
])
def test_odd_manifests_do_not_raise(text, tmp_path):
    package = copy_example(1, tmp_path)
    (package / "package.xml").write_text(text)
    report = check(package, stability=False)
    report.format()
    assert report.status in (0, 1)


def test_a_wrong_package_name_hides_no_missing_mesh(tmp_path):
    # A folder named otherwise than the package, its meshes gone: the name is one finding,
    # and each missing file is one more, looked for in the folder given.
    package = _renamed(tmp_path)
    for mesh in (package / "meshes").iterdir():
        mesh.unlink()
    report = check(package, stability=False)
    assert [f.rule for f in report.findings if f.rule == "package-name-mismatch"] == [
        "package-name-mismatch"]
    missing = [f for f in report.findings if f.rule == "mesh-not-found"]
    assert len(missing) == len(list((EXAMPLES / "example_1" / "meshes").iterdir())) == 5
    assert all("package-name-mismatch" in f.message and "my_robot" in f.message
               for f in missing)


def test_the_meshes_behind_a_wrong_package_name_are_still_read(tmp_path):
    package = _renamed(tmp_path)
    (package / "meshes" / "base_link.STL").write_bytes(b"\0" * 84)   # a header, no triangle
    rules = check(package, stability=False).rules()
    assert {"package-name-mismatch", "mesh-empty"} <= rules, rules
