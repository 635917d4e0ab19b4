"""`sw2sim compare`: a student's export against the lesson's package.

Every reference matches itself and a copy with the faceting difference of a real
SolidWorks export; copies altered the way students get them wrong differ, each with the
right diagnosis on its line; unreadable input gives status 2 and names the file.
"""

import json
import re
import subprocess
import sys

import pytest

from packages import EXAMPLES, copy_example, edit, edit_re, urdf_of
from sw2sim import cli
from sw2sim.compare import compare
from sw2sim.compare.causes import FLIPPED

LINE = re.compile(r"^\S+\.urdf(:\d+)?: \[[a-z-]+\] .+: .+\. .+\.$")
INERTIA_TERMS = r'\b(i[xyz][xyz])="([^"]+)"'


def altered(n: int, tmp_path, *edits):
    """A copy of examples/example_<n> with its URDF text edited: each edit is (old, new)
    for packages.edit, or a function of the URDF's path."""
    package = copy_example(n, tmp_path)
    urdf = urdf_of(package)
    for change in edits:
        change(urdf) if callable(change) else edit(urdf, *change)
    return package


def against(n: int, package):
    return compare(package, EXAMPLES / f"example_{n}")


def the_line(result, code: str) -> str:
    """The one difference of kind `code`, after checking that the package differs, that
    every line reads as one, and that nothing else was reported."""
    assert result.status == 1, result.format()
    assert all(LINE.match(d.text) for d in result.differences), result.format()
    assert [d.code for d in result.differences] == [code], result.format()
    return result.differences[0].text


def scaled(pattern: str, factor: float, link: str | None = None):
    """An edit multiplying every number `pattern` captures (as group 2), in one link or all."""
    def change(urdf):
        text = urdf.read_text()
        start, end = 0, len(text)
        if link:
            start = text.index(f'name="{link}"')
            end = text.index("</link>", start)
        part = re.sub(pattern, lambda m: f'{m.group(1)}="{float(m.group(2)) * factor!r}"',
                      text[start:end])
        urdf.write_text(text[:start] + part + text[end:])
    return change


def masses(factor: float, link: str | None = None):
    return scaled(r'(<mass\s+value)="([^"]+)"', factor, link)


def inertias(factor: float, link: str | None = None):
    return scaled(INERTIA_TERMS, factor, link)


# --- what must match ----------------------------------------------------------------------

@pytest.mark.parametrize("n", [1, 2, 3, 4, 5])
def test_each_reference_matches_itself(n):
    result = against(n, EXAMPLES / f"example_{n}")
    assert result.status == 0 and not result.differences, result.format()
    assert " matches " in result.format() and len(result.links) == result.counts[0]


@pytest.mark.parametrize("n", [1, 2, 3, 4, 5])
def test_an_exact_solidworks_export_matches_the_faceted_reference(tmp_path, n):
    result = against(n, altered(n, tmp_path, masses(1.004), inertias(1.006)))
    assert result.status == 0, result.format()


# --- what students get wrong --------------------------------------------------------------

def test_a_flipped_axis(tmp_path):
    package = altered(3, tmp_path, ('<axis\n      xyz="0 0 1" />', '<axis\n      xyz="0 0 -1" />'))
    line = the_line(against(3, package), "axis-flipped")
    assert 'joint "middle_arm_joint": axis 0 0 -1 in yours, 0 0 1 in the reference' in line
    assert FLIPPED[1:] in line


def test_an_axis_along_another_direction(tmp_path):
    package = altered(4, tmp_path, ('<axis\n      xyz="1 0 0" />', '<axis\n      xyz="0 1 0" />'))
    line = the_line(against(4, package), "axis-direction")
    assert "90 degrees apart: +y in yours, +x in the reference" in line
    assert "Reference Axis is another edge or face" in line


def test_a_frame_on_the_wrong_face_of_a_plate(tmp_path):
    # The end arm's joint on the middle arm's lower face instead of its upper: 20 mm down.
    package = altered(3, tmp_path, ('xyz="0.225 0 0.02"', 'xyz="0.225 0 0"'))
    line = the_line(against(3, package), "origin-face")
    assert 'joint "end_arm_joint": origin xyz 0.225 0 0 in yours, 0.225 0 0.02' in line
    assert "-20 mm along z, the thickness of" in line and "opposite face" in line


def test_a_frame_on_the_wrong_face_with_the_part_in_place(tmp_path):
    # As SolidWorks exports it: the frame moved, the part did not, so the centre of mass
    # written in the frame moves the other way. One line, not two.
    package = altered(3, tmp_path, ('xyz="0.225 0 0.02"', 'xyz="0.225 0 0"'),
                      ('0.0937452926258486 -8.51289014284469E-19 0.00999999977648258',
                       '0.0937452926258486 -8.51289014284469E-19 0.02999999977648258'))
    line = the_line(against(3, package), "origin-face")
    assert "only the joint's frame" in line


def test_a_wheel_frame_on_its_face_instead_of_its_mid_plane(tmp_path):
    package = altered(1, tmp_path, ('xyz="0.13 0.18 0"', 'xyz="0.13 0.2 0"'))
    line = the_line(against(1, package), "origin-face")
    assert '+20 mm along y, half the thickness of "front_left_wheel"' in line


def test_the_wheel_of_the_other_side(tmp_path):
    package = altered(1, tmp_path, ('xyz="0.13 0.18 0"', 'xyz="0.13 -0.18 0"'))
    assert "other side along y" in the_line(against(1, package), "origin-mirrored")


def test_a_joint_frame_turned_over(tmp_path):
    package = altered(4, tmp_path, ('xyz="0.105 0 0.1"\n      rpy="0 0 0"',
                                    'xyz="0.105 0 0.1"\n      rpy="0 0 3.14159"'))
    result = against(4, package)
    codes = [d.code for d in result.differences]
    assert codes[:2] == ["origin-turned", "axis-flipped"], result.format()
    assert "turned 180 degrees about the joint's frame's z axis" in result.differences[0].text
    assert "the link's frame is turned" in result.differences[1].text


def test_no_material_gives_solidworks_default_density(tmp_path):
    ratio = 1000 / 2700
    package = altered(3, tmp_path, masses(ratio, "middle_arm_link"),
                      inertias(ratio, "middle_arm_link"))
    line = the_line(against(3, package), "mass-material")
    assert 'link "middle_arm_link": mass 0.264242 kg in yours, 0.713453 kg' in line
    assert "default density 1000 kg/m^3" in line and "aluminium" in line
    assert "Its inertia differs by the same factor" in line


def test_another_material(tmp_path):
    steel = 7850 / 2700
    package = altered(1, tmp_path, masses(steel, "base_link"), inertias(steel, "base_link"))
    line = the_line(against(1, package), "mass-material")
    assert "7850 kg/m^3 against 2700" in line and "steel" in line


@pytest.mark.parametrize("value, code", [("0", "mass-zero"), ("1", "mass-placeholder"),
                                         ("713.453064709223", "mass-units")])
def test_masses_that_are_not_the_parts(tmp_path, value, code):
    package = altered(3, tmp_path, ('value="0.713453064709223"', f'value="{value}"'))
    result = against(3, package)
    assert result.differences[0].code == code, result.format()
    assert result.differences[0].subject == 'link "middle_arm_link"'


def test_a_part_of_another_size(tmp_path):
    package = altered(3, tmp_path, masses(1.1, "end_arm_link"), inertias(1.1, "end_arm_link"),
                      lambda urdf: urdf.write_text(urdf.read_text().replace(
                          'end_arm_link.STL" />', 'end_arm_link.STL" scale="1 1 1.1" />')))
    result = against(3, package)
    assert [d.code for d in result.differences] == ["mass-volume", "mesh-size"], result.format()
    assert "the same density, 2700 kg/m^3" in result.differences[0].text
    assert "+2 mm along z" in result.differences[1].text


def test_millimetres_in_the_origins(tmp_path):
    package = altered(1, tmp_path, ('xyz="0.13 0.18 0"', 'xyz="130 180 0"'),
                      ('xyz="-0.13 -0.18 0"', 'xyz="-130 -180 0"'))
    result = against(1, package)
    assert [d.code for d in result.differences] == ["origin-units"] * 2, result.format()
    assert "1000 times the reference's: millimetres" in result.differences[0].text


def test_a_mesh_in_millimetres(tmp_path):
    package = altered(3, tmp_path, lambda urdf: urdf.write_text(urdf.read_text().replace(
        'middle_arm_link.STL" />', 'middle_arm_link.STL" scale="1000 1000 1000" />')))
    line = the_line(against(3, package), "mesh-units")
    assert "mesh size 275 50 20 m in yours, 0.275 0.05 0.02 m" in line and "millimetres" in line


@pytest.mark.parametrize("n, joint, mine, said", [
    (1, "front_left_joint", "revolute", "choose continuous"),
    (3, "middle_arm_joint", "continuous", "choose revolute"),
    (3, "end_arm_joint", "fixed", "Automatically Detect")])
def test_a_joint_of_the_wrong_type(tmp_path, n, joint, mine, said):
    reference = urdf_of(EXAMPLES / f"example_{n}").read_text()
    old = re.search(rf'name="{joint}"\s+type="\w+"', reference)[0]
    package = altered(n, tmp_path, (old, re.sub(r'type="\w+"', f'type="{mine}"', old)))
    result = against(n, package)
    assert result.differences[0].code == "joint-type", result.format()
    assert f'joint "{joint}": type {mine} in yours' in result.differences[0].text
    assert said in result.differences[0].text


@pytest.mark.parametrize("limit, said", [
    ('<limit lower="0" upper="0" effort="0" velocity="0" />',
     "lower 0 upper 0 effort 0 velocity 0"),
    ("", "none")])
def test_the_exporters_empty_limits_or_none(tmp_path, limit, said):
    package = altered(5, tmp_path, lambda urdf: edit_re(
        urdf, r'<limit\s+lower="-0.5236"\s*upper="0.5236"\s*effort="5"\s*velocity="3" />', limit))
    line = the_line(against(5, package), "limits-empty")
    assert f'joint "steering_joint": limit {said} in yours, lower -0.5236 upper 0.5236' in line
    assert "exporter's empty default" in line


def test_limits_in_degrees(tmp_path):
    package = altered(3, tmp_path, ('lower="-0.7854"\n      upper="0.7854"',
                                    'lower="-45"\n      upper="45"'))
    result = against(3, package)
    assert [d.code for d in result.differences] == ["limit-units"] * 2, result.format()
    assert "in degrees" in result.differences[0].text


def test_renamed_links_are_matched_by_their_place(tmp_path):
    names = {"front_left": "w3", "front_right": "w1", "rear_left": "w4", "rear_right": "w2"}

    def rename(urdf):
        text = urdf.read_text()
        for old, new in names.items():
            for attribute in ("name", "link"):
                text = text.replace(f'{attribute}="{old}_wheel"', f'{attribute}="{new}_link"')
            text = text.replace(f'name="{old}_joint"', f'name="{new}_joint"')
        urdf.write_text(text)
    result = against(1, altered(1, tmp_path, rename))
    assert {result.links[f"{old}_wheel"] for old in names} == {f"{n}_link" for n in names.values()}
    assert all(result.links[f"{old}_wheel"] == f"{new}_link" for old, new in names.items())
    assert sorted(d.code for d in result.differences) == ["joint-name"] * 4 + ["link-name"] * 4
    assert any('link "w3_link" (the reference\'s "front_left_wheel")' in d.text and
               "matched by its place in the tree" in d.text for d in result.differences)


def test_a_missing_link(tmp_path):
    package = altered(5, tmp_path, lambda urdf: edit_re(
        urdf, r'<link\s+name="steering_link">.*?</joint>', ""))
    line = the_line(against(5, package), "link-missing")
    assert 'link "steering_link": missing in yours' in line and '"steering_joint"' in line


def test_a_link_merged_into_its_parent(tmp_path):
    package = altered(5, tmp_path,
                      lambda urdf: edit_re(urdf, r'<link\s+name="steering_link">.*?</joint>', ""),
                      ('value="3.05678326799101"', 'value="3.13216024834083"'))
    result = against(5, package)
    assert [d.code for d in result.differences] == ["mass-parts", "link-missing"], result.format()
    assert "Link Components" in result.differences[1].text


def test_an_extra_link(tmp_path):
    package = altered(3, tmp_path, ("</robot>", '<link name="camera"/><joint name="camera_joint" '
                                    'type="fixed"><parent link="end_arm_link"/><child '
                                    'link="camera"/></joint></robot>'))
    line = the_line(against(3, package), "link-extra")
    assert 'link "camera": not in the reference' in line


def test_a_link_under_another_parent(tmp_path):
    package = altered(5, tmp_path, ('<origin\n      xyz="0 0 0"\n      rpy="0 0 0" />\n    '
                                    '<parent\n      link="left_knuckle" />',
                                    '<origin\n      xyz="0.4 0.15 0"\n      rpy="0 0 0" />\n    '
                                    '<parent\n      link="base_link" />'))
    line = the_line(against(5, package), "link-parent")
    assert 'hangs from "base_link" in yours, from "left_knuckle"' in line


def test_no_world_link_as_the_exporter_writes_it(tmp_path):
    package = altered(3, tmp_path, lambda urdf: edit_re(
        urdf, r'<link\s+name="world" />.*?<link', "<link"),
        lambda urdf: edit_re(urdf, r'<joint\s+name="world_joint".*?</joint>', ""))
    line = the_line(against(3, package), "world-missing")
    assert 'bolts "base_link" to the world with the fixed joint "world_joint"' in line
    assert "Gazebo lets the robot fall free" in line


def test_a_world_link_the_reference_has_not(tmp_path):
    package = altered(5, tmp_path, ('<link\n    name="base_link">',
                                    '<link name="world"/><joint name="world_joint" type="fixed">'
                                    '<parent link="world"/><child link="base_link"/></joint>'
                                    '<link\n    name="base_link">'))
    assert "the reference's robot is free" in the_line(against(5, package), "world-extra")


def test_another_root(tmp_path):
    package = altered(4, tmp_path, ('<child\n      link="base_link" />', "ROOT"),
                      ('<parent\n      link="base_link" />', '<parent\n      link="block_link" />'),
                      ('<child\n      link="block_link" />', '<child\n      link="base_link" />'),
                      ("ROOT", '<child\n      link="block_link" />'))
    line = the_line(against(4, package), "tree-root")
    assert 'starts at link "block_link" in yours, at "base_link" in the reference' in line


def test_a_model_lying_on_its_side(tmp_path):
    # A Global Origin Coordinate System with Y up: everything in the base's frame is
    # turned a quarter turn about x; the world joint still stands it on the floor.
    quarter = 'rpy="1.5707963267949 0 0"'
    wheels = [(f'xyz="{x} {y} 0"\n      rpy="0 0 0"', f'xyz="{x} 0 {y}"\n      {quarter}')
              for x in ("0.13", "-0.13") for y in ("0.18", "-0.18")]
    base = [("xyz=\"4.59663050055618E-18 0 3.59111757855952E-20\"\n        rpy=\"0 0 0\"",
             f"xyz=\"0 0 0\"\n        {quarter}"),
            lambda urdf: edit_re(urdf, r'(name="base_link">.*?<visual>\s*<origin\s*xyz="0 0 0"\s*)'
                                       r'rpy="0 0 0"', rf"\1{quarter}")]
    line = the_line(against(1, altered(1, tmp_path, *wheels, *base)), "base-turned")
    assert "turned 90 degrees about the model's x axis" in line and "Z pointing up" in line


def test_a_model_measured_from_another_point(tmp_path):
    wheels = [(f'xyz="{x} {y} 0"', f'xyz="{x} {y} 0.01"') for x in ("0.13", "-0.13")
              for y in ("0.18", "-0.18")]
    package = altered(1, tmp_path, *wheels, ('xyz="0 0 0.15"', 'xyz="0 0 0.14"'),
                      ('xyz="4.59663050055618E-18 0 3.59111757855952E-20"', 'xyz="0 0 0.01"'))
    line = the_line(against(1, package), "base-origin")
    assert "-10 mm along z from the reference's" in line


# --- input that cannot be compared ---------------------------------------------------------

def test_a_missing_package_is_status_2_naming_it(tmp_path):
    result = compare(tmp_path / "nothing", EXAMPLES / "example_1")
    assert result.status == 2 and str(tmp_path / "nothing") in result.error


@pytest.mark.parametrize("text, said", [
    ("not XML", "not well-formed XML"),
    ('<robot name="r"><link name="a"/><joint name="j" type="fixed"><parent link="a"/>'
     '<child link="b"/></joint></robot>', 'names child link "b"'),
    ('<robot name="r"><link name="a"/><link name="b"/></robot>', "do not form one tree"),
    ('<robot name="r"><link name="a"/><link name="a"/></robot>', 'two links are named "a"'),
    ('<robot name="r"><link name="a"><inertial><mass value="heavy"/></inertial></link></robot>',
     "incomplete")])
def test_an_unreadable_urdf_is_status_2_naming_the_file(tmp_path, text, said):
    package = copy_example(1, tmp_path)
    urdf_of(package).write_text(text)
    result = compare(package, EXAMPLES / "example_1")
    assert result.status == 2 and said in result.error and "example_1.urdf" in result.error


# --- the command ---------------------------------------------------------------------------

def test_the_command_prints_one_line_per_difference_and_exits_1(tmp_path):
    package = altered(3, tmp_path, ('<axis\n      xyz="0 0 1" />', '<axis\n      xyz="0 0 -1" />'))
    done = subprocess.run([sys.executable, "-m", "sw2sim", "compare", str(package),
                           str(EXAMPLES / "example_3")], capture_output=True, text=True, timeout=60)
    lines = done.stdout.splitlines()
    assert done.returncode == 1 and "Traceback" not in done.stdout + done.stderr
    assert "[axis-flipped]" in lines[0] and "1 difference(s)" in lines[-1]


def test_the_command_in_json_and_its_statuses(tmp_path, capsys):
    package = altered(1, tmp_path, ('xyz="0.13 0.18 0"', 'xyz="0.13 0.2 0"'))
    assert cli.main(["compare", str(package), str(EXAMPLES / "example_1"), "--json"]) == 1
    report = json.loads(capsys.readouterr().out)
    assert report["status"] == 1 and report["tolerances"]["length_m"] == 0.001
    (found,) = report["differences"]
    assert found["code"] == "origin-face" and found["mine"] == "0.13 0.2 0"
    assert cli.main(["compare", str(EXAMPLES / "example_2"), str(EXAMPLES / "example_2"),
                     "--urdf", "example_2.urdf"]) == 0
    assert " matches " in capsys.readouterr().out
    assert cli.main(["compare", str(tmp_path / "none"), str(EXAMPLES / "example_2")]) == 2
    out, err = capsys.readouterr()
    assert not out and err.startswith("sw2sim compare: ") and "none" in err


def test_the_command_has_help_with_examples(capsys):
    with pytest.raises(SystemExit) as exit_:
        cli.main(["compare", "--help"])
    out = capsys.readouterr().out
    assert exit_.value.code == 0
    assert "examples:" in out and "sw2sim compare " in out and "MINE" in out and "REFERENCE" in out
    with pytest.raises(SystemExit):
        cli.main(["--help"])
    assert re.search(r"^\s+compare\s+\S", capsys.readouterr().out, re.M)
