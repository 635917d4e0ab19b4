"""A package is found and read once per command, and everything takes the Package read.

Every XML file sw2sim reads goes through lxml's parsers (test_structure_of_the_tool.py makes
sure only sw2sim.xmlsafe calls them); counting those calls per file shows how often each
command reads the URDF and package.xml.
"""

from __future__ import annotations

import copy
import os
import shutil
from collections import Counter
from pathlib import Path

import pytest
from lxml import etree

import sw2sim
from sw2sim import browser_model, cli, xmlsafe
from sw2sim.actuators import add_actuators
from sw2sim.check import check, check_package, open_package
from sw2sim.convert import convert
from sw2sim.loader import LoadError, find_package, load_package, world_fixed
from sw2sim.package import Package, as_package
from sw2sim.ros_control import add_motors, read_joint_limits, read_transmissions

from repository import EXAMPLES

EXAMPLE_3 = EXAMPLES / "example_3"   # transmissions, limits and controllers
EXAMPLE_4 = EXAMPLES / "example_4"   # small meshes: quick to check and convert


@pytest.fixture
def parses(monkeypatch):
    """Counter: file name -> how many times lxml parsed it, from now on."""
    counted: Counter = Counter()

    def counting(real, name_of):
        def parse(*args, **kwargs):
            name = Path(name_of(args, kwargs) or "<string>").name
            if name != browser_model.WRITTEN:   # MuJoCo's own XML, rewritten for the browser
                counted[name] += 1
            return real(*args, **kwargs)
        return parse

    monkeypatch.setattr(etree, "fromstring", counting(etree.fromstring,
                                                      lambda a, k: k.get("base_url")))
    monkeypatch.setattr(etree, "XML", counting(etree.XML, lambda a, k: k.get("base_url")))
    monkeypatch.setattr(etree, "parse", counting(etree.parse, lambda a, k: str(a[0])))
    monkeypatch.setattr(etree, "iterparse", counting(etree.iterparse, lambda a, k: str(a[0])))
    return counted


def test_the_counter_sees_the_safe_reader(parses):
    find_package(EXAMPLE_4)
    assert parses == {"example_4.urdf": 1, "package.xml": 1}


@pytest.mark.parametrize("command", ["check", "convert", "render"])
def test_each_command_reads_the_urdf_and_package_xml_once(command, parses, tmp_path, capsys):
    argv = {"check": ["check", str(EXAMPLE_4)],
            "convert": ["convert", str(EXAMPLE_4), "-o", str(tmp_path / "out")],
            "render": ["render", str(EXAMPLE_4), "-o", str(tmp_path / "x.png"),
                       "--width", "64", "--height", "48"]}[command]
    assert cli.main(argv) == 0, capsys.readouterr()
    assert parses == {"example_4.urdf": 1, "package.xml": 1}


def test_check_with_its_stability_run_reads_the_urdf_once(parses):
    report = check(EXAMPLE_3)
    assert report.status == 0 and report.stability is not None
    assert parses == {"example_3.urdf": 1, "package.xml": 1}


def test_convert_of_a_path_reads_the_urdf_once(parses, tmp_path):
    convert(EXAMPLE_3, tmp_path / "out")
    assert parses == {"example_3.urdf": 1, "package.xml": 1}


def test_everything_takes_a_package_and_reads_nothing_more(parses, tmp_path):
    package = find_package(EXAMPLE_3)
    parses.clear()
    assert world_fixed(package) is package.world_fixed
    spec = load_package(package, fixed_base=package.world_fixed)
    add_actuators(spec, package)
    add_motors(load_package(package), package)
    assert read_joint_limits(package) == read_joint_limits(EXAMPLE_3)
    assert read_transmissions(package) == read_transmissions(EXAMPLE_3)
    parses.clear()
    convert(package, tmp_path / "out")
    assert check(package).status == 0
    assert open_package(package).package is package
    assert not parses


def test_a_path_and_its_package_give_the_same_results(tmp_path):
    package = as_package(EXAMPLE_3)
    assert as_package(package) is package
    assert check(package, stability=False).format() == check(EXAMPLE_3, stability=False).format()
    a = load_package(package).compile()
    b = load_package(EXAMPLE_3).compile()
    assert (a.nbody, a.ngeom, a.nmesh) == (b.nbody, b.ngeom, b.nmesh)
    one, two = convert(package, tmp_path / "a"), convert(EXAMPLE_3, tmp_path / "b")
    assert (tmp_path / "a" / "README.md").read_text() == (tmp_path / "b" / "README.md").read_text()
    assert [a.name for a in one.actuators] == [a.name for a in two.actuators]


def test_the_package_holds_what_the_commands_need():
    package = find_package(EXAMPLE_3)
    assert isinstance(package, Package)
    assert package.root == EXAMPLE_3.resolve() and package.name == "example_3"
    assert package.urdf == (EXAMPLE_3 / "urdf" / "example_3.urdf").resolve()
    assert package.robot.tag == "robot" and package.manifest.tag == "package"
    assert package.world_fixed
    assert set(package.links) >= {"world", "base_link"} and package.joints
    assert package.links["base_link"].get("name") == "base_link"
    mesh = package.robot.find("link/visual/geometry/mesh").get("filename")
    assert package.resolve_mesh(mesh).is_file()
    with pytest.raises(LoadError, match="outside the package"):
        package.resolve_mesh("../../x.STL")


def test_load_package_leaves_the_shared_tree_as_it_was():
    package = find_package(EXAMPLE_3)
    before = etree.tostring(package.robot)
    load_package(package)
    load_package(package, fixed_base=False, scene=False)
    assert etree.tostring(package.robot) == before
    assert all(m.get("filename").startswith("package://") for m in package.robot.iter("mesh"))


def test_the_check_context_of_a_package_reports_under_the_path_given(tmp_path):
    ctx = check_package(str(EXAMPLE_4), stability=False)
    assert ctx.package is not None and ctx.report.path == str(EXAMPLE_4)
    again = check(ctx.package, stability=False)
    assert again.format() == ctx.report.format()


def test_an_unusable_package_gives_no_package_and_a_fatal_finding(tmp_path):
    package = tmp_path / "example_4"
    shutil.copytree(EXAMPLE_4, package)
    (package / "urdf" / "example_4.urdf").write_text("not XML\n")
    ctx = check_package(package)
    assert ctx.package is None and ctx.report.status == 2
    with pytest.raises(LoadError) as err:
        find_package(package)
    assert err.value.kind == "syntax" and "not well-formed XML" in str(err.value)


@pytest.mark.parametrize("case", ["doctype", "pipe", "empty", "folder", "not-urdf"])
def test_every_reader_refuses_what_the_check_refuses(case, tmp_path):
    package = tmp_path / "example_4"
    shutil.copytree(EXAMPLE_4, package)
    urdf = package / "urdf" / "example_4.urdf"
    text = urdf.read_text()
    if case == "doctype":
        urdf.write_text(text.replace("<robot", '<!DOCTYPE robot [<!ENTITY x "y">]>\n<robot', 1))
    elif case == "pipe":
        urdf.unlink()
        os.mkfifo(urdf)
    elif case == "empty":
        urdf.write_text(" \n")
    elif case == "folder":
        urdf.unlink()
        urdf.mkdir()
    else:
        urdf.write_text('<?xml version="1.0"?>\n<sdf version="1.6"/>\n')
    assert check(package).status == 2
    kind = {"doctype": "doctype", "not-urdf": "not-urdf"}.get(case, "unreadable")
    for reader in (sw2sim.load_package, world_fixed, read_joint_limits, read_transmissions):
        with pytest.raises(LoadError) as err:
            reader(package)
        assert err.value.kind == kind and err.value.file == str(urdf.resolve())


def test_source_line_finds_the_attribute_in_a_copy_too():
    package = find_package(EXAMPLE_3)
    joint = package.joints["middle_arm_joint"]
    lines = package.urdf.read_text().split("\n")
    line = xmlsafe.source_line(joint, "name")
    assert 'name="middle_arm_joint"' in lines[line - 1]
    assert joint.sourceline >= line
    twin = copy.deepcopy(package.robot).find("joint[@name='middle_arm_joint']")
    assert xmlsafe.source_line(twin, "name") == line


def test_a_urdf_given_from_inside_its_urdf_folder_belongs_to_the_package_above(tmp_path, monkeypatch):
    """`sw2sim check my_robot.urdf` typed in urdf/: the package is the folder above, its name
    is that folder's, and the meshes are found there."""
    from sw2sim.check import check
    from sw2sim.package import find_package
    shutil.copytree(Path(__file__).parents[2] / "examples" / "example_1", tmp_path / "example_1")
    monkeypatch.chdir(tmp_path / "example_1" / "urdf")
    package = find_package("example_1.urdf")
    assert package.name == "example_1"
    assert (package.root / "package.xml").is_file()
    report = check("example_1.urdf", stability=False)
    assert not [f for f in report.findings if f.severity == "error"], report.findings
