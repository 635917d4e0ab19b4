"""`sw2sim compare`: a student's export against the lesson's package.

Every reference matches itself and a copy with the faceting difference of a real
SolidWorks export; copies altered the way students get them wrong differ, each with the
right diagnosis on its line; unreadable input gives status 2 and names the file, and so
does another lesson's package, naming the lesson it resembles. The mistakes include
meshes with no triangles or no volume, numbers typed in another unit, and an inertia
taken about the link's origin.
"""

import json
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from packages import EXAMPLES, copy_example, edit, edit_re, urdf_of
from repository import practice_numbers
from sw2sim import cli
from sw2sim.check.urdf import vector
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

@pytest.mark.parametrize("n", practice_numbers())
def test_each_reference_matches_itself(n):
    result = against(n, EXAMPLES / f"example_{n}")
    assert result.status == 0 and not result.differences, result.format()
    assert " matches " in result.format() and len(result.links) == result.counts[0]


@pytest.mark.parametrize("n", practice_numbers())
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


# --- meshes with nothing in them ----------------------------------------------------------

def with_mesh(n: int, tmp_path, link: str, data: bytes):
    """A copy of examples/example_<n> whose mesh of `link` holds `data`."""
    package = copy_example(n, tmp_path)
    (package / "meshes" / f"{link}.STL").write_bytes(data)
    return package


@pytest.mark.parametrize("data, said", [
    (bytes(80), "is 80 bytes long: a binary STL's header and not a single "
                              "triangle"),
    (bytes(84), "is a binary STL header that announces 0 triangles"),
    (b"solid end_arm_link\nendsolid end_arm_link\n", "is a text STL without a single facet"),
    (b"", "is empty (0 bytes)")], ids=["exporter-80-bytes", "count-0", "text", "0-bytes"])
def test_a_mesh_with_no_triangles(tmp_path, data, said):
    line = the_line(against(3, with_mesh(3, tmp_path, "end_arm_link", data)), "mesh-empty")
    assert f'link "end_arm_link": its mesh meshes/end_arm_link.STL {said}' in line
    assert "the reference's measures 0.25 0.08 0.02 m" in line
    assert "hidden or suppressed, or had no solid body" in line and "export again" in line


def test_the_exporters_sample_with_its_empty_mesh(tmp_path):
    # The raw export course/practices/sample_export.py writes: its end arm's STL is the
    # 80-byte header the exporter leaves for a part it could not mesh. (Imported here:
    # the course's part modules load trimesh, seconds on a busy machine.)
    from course.practices import sample_export
    sample_export.write(tmp_path)
    assert (tmp_path / sample_export.PACKAGE / "meshes" /
            f"{sample_export.EMPTY_MESH}.STL").read_bytes() == bytes(80)
    result = against(3, tmp_path / sample_export.PACKAGE)
    empty = [d for d in result.differences if d.code == "mesh-empty"]
    assert result.status == 1 and len(empty) == 1, result.format()
    assert empty[0].subject == f'link "{sample_export.EMPTY_MESH}"'


def test_an_empty_mesh_in_a_package_as_the_exporter_writes_it(tmp_path):
    # Byte for byte the exporter's layout (CRLF, its version comment, its STL headers):
    # one export as the reference, the same export with a wheel's STL left empty as yours.
    sys.path.insert(0, str(Path(__file__).resolve().parent / "check"))
    from exporter_packages import FOUR_WHEELER_NESTED, write_export   # loads trimesh: here
    reference = write_export(FOUR_WHEELER_NESTED, tmp_path / "reference")
    package = write_export(FOUR_WHEELER_NESTED, tmp_path / "yours")
    wheel = FOUR_WHEELER_NESTED.links[1].name
    (package / "meshes" / f"{wheel}.STL").write_bytes(bytes(80))
    assert compare(reference, reference).status == 0
    line = the_line(compare(package, reference), "mesh-empty")
    assert f'link "{wheel}": its mesh meshes/{wheel}.STL is 80 bytes long' in line


def flattened(axis: int | None):
    """An edit of a binary STL file: every vertex moved onto a plane (a coordinate set
    to 0), or with `axis` None onto a line (two coordinates set to 0)."""
    def change(path):
        data = bytearray(path.read_bytes())
        count = int.from_bytes(data[80:84], "little")
        records = np.frombuffer(bytes(data[84:]), dtype=np.dtype(
            [("normal", "<f4", (3,)), ("points", "<f4", (3, 3)), ("attr", "<u2")]),
            count=count).copy()
        for gone in ([axis] if axis is not None else [1, 2]):
            records["points"][:, :, gone] = 0
        path.write_bytes(bytes(data[:84]) + records.tobytes())
    return change


@pytest.mark.parametrize("axis, said", [(2, "in one plane"), (None, "on one line")])
def test_a_mesh_with_no_volume(tmp_path, axis, said):
    package = copy_example(3, tmp_path)
    flattened(axis)(package / "meshes" / "middle_arm_link.STL")
    line = the_line(against(3, package), "mesh-flat")
    assert f"meshes/middle_arm_link.STL has all its vertices {said}, so it encloses no volume" \
        in line
    assert "a surface or a sketch, not a solid" in line


def test_a_mesh_scaled_flat(tmp_path):
    package = altered(3, tmp_path, ('middle_arm_link.STL" />',
                                    'middle_arm_link.STL" scale="1 1 0" />'))
    line = the_line(against(3, package), "mesh-flat")
    assert "<mesh scale> has a 0 in it" in line


# --- another lesson's package ----------------------------------------------------------------

@pytest.mark.parametrize("mine, reference", [(2, 4), (4, 2), (3, 5), (5, 3), (1, 3), (4, 1)])
def test_another_lessons_package_is_not_compared(mine, reference):
    result = compare(EXAMPLES / f"example_{mine}", EXAMPLES / f"example_{reference}")
    assert result.status == 2 and not result.differences, result.format()
    assert "have little in common" in result.error
    assert "This looks like another lesson's package" in result.error
    assert f"resembles {EXAMPLES / f'example_{mine}'} (Practice {mine}'s package) most" \
        in result.error or f"example_{mine} (Practice {mine}'s package) most" in result.error
    assert result.resembles.endswith(f"example_{mine}")


@pytest.mark.parametrize("mine, reference", [(2, 1), (1, 2), (1, 5)])
def test_a_lesson_of_the_same_names_is_told_by_its_numbers(mine, reference):
    # Practices 1 and 2 both have a base_link and four wheels of the same names, and
    # Practice 5 has them too: the tree alone is alike, where each link sits is not.
    result = compare(EXAMPLES / f"example_{mine}", EXAMPLES / f"example_{reference}")
    assert result.status == 2, result.format()
    assert f"agrees with {EXAMPLES / f'example_{mine}'}" in result.error or \
        f"agrees with examples/example_{mine}" in result.error
    assert "This looks like another lesson's package" in result.error
    assert result.resembles.endswith(f"example_{mine}")


def test_a_student_export_of_another_lesson_names_that_lesson(tmp_path):
    # Practice 2's robot with its own mistakes (no material on the base, an origin in
    # millimetres), held against Practice 4's package.
    package = altered(2, tmp_path, masses(1000 / 2700, "base_link"),
                      ('xyz="0.20899 0.15071 0"', 'xyz="208.99 150.71 0"'))
    result = against(4, package)
    assert result.status == 2 and "1 of 5 links match" in result.error, result.format()
    assert "Practice 2's package" in result.error
    assert f"sw2sim compare {package} " in result.error and result.error.endswith(
        "Nothing was compared.")


def test_a_reference_that_is_no_lesson_is_questioned(tmp_path):
    reference = copy_example(4, tmp_path, name="their_reference")
    result = compare(EXAMPLES / "example_2", reference)
    assert result.status == 2 and result.resembles is None, result.format()
    assert f"check that {reference} is the package of your lesson" in result.error


def test_a_robot_like_no_lesson(tmp_path):
    urdf = tmp_path / "crane.urdf"
    links = "".join(f'<link name="{n}"><inertial><mass value="1"/><inertia ixx="1" ixy="0" '
                    f'ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>'
                    for n in ("mast", "jib", "trolley", "hook"))
    joints = "".join(f'<joint name="{c}_joint" type="prismatic"><parent link="{p}"/><child '
                     f'link="{c}"/><origin xyz="0 0 {i}"/><axis xyz="1 0 0"/><limit lower="0" '
                     f'upper="1" effort="1" velocity="1"/></joint>'
                     for i, (p, c) in enumerate([("mast", "jib"), ("jib", "trolley"),
                                                 ("trolley", "hook")], start=1))
    urdf.write_text(f'<robot name="crane">{links}{joints}</robot>')
    result = compare(urdf, EXAMPLES / "example_3")
    assert result.status == 2 and result.resembles is None, result.format()
    assert "none of the lessons' packages in" in result.error


def test_a_package_missing_half_its_links_is_still_compared(tmp_path):
    package = altered(1, tmp_path, *[lambda urdf, side=side: edit_re(
        urdf, rf'<link\s+name="{side}_wheel">.*?</joint>', "") for side in ("front_left",
                                                                           "front_right")])
    result = against(1, package)
    assert result.status == 1, result.format()
    assert [d.code for d in result.differences] == ["link-missing"] * 2


def test_the_command_says_so_with_status_2(capsys):
    assert cli.main(["compare", str(EXAMPLES / "example_2"), str(EXAMPLES / "example_4")]) == 2
    out, err = capsys.readouterr()
    assert not out and err.startswith("sw2sim compare: ")
    assert "another lesson's package" in err and "Practice 2's package" in err
    assert cli.main(["compare", str(EXAMPLES / "example_2"), str(EXAMPLES / "example_4"),
                     "--json"]) == 2
    report = json.loads(capsys.readouterr().out)
    assert report["status"] == 2 and report["resembles"].endswith("example_2")
    assert report["differences"] == []


# --- numbers in another unit ----------------------------------------------------------------

@pytest.mark.parametrize("n, old, new, said", [
    (4, 'upper="2.69"', 'upper="269"', "269 where the lesson has 2.69: typed in centimetres?"),
    (4, 'upper="2.69"', 'upper="2690"', "2690 where the lesson has 2.69: typed in millimetres?"),
    (4, 'upper="2.69"', 'upper="26.9"', "the decimal point one place too far right?"),
    (4, 'upper="2.69"', 'upper="0.00269"', "metres converted once more, as if they were "
                                           "millimetres?"),
    (4, 'velocity="1" />', 'velocity="100" />', "100 where the lesson has 1: typed in cm/s?"),
    (3, 'velocity="2" />', 'velocity="114.6" />', "typed in degrees per second?"),
    (3, 'effort="1000"', 'effort="100"', "the decimal point one place too far left?")])
def test_a_limit_in_another_unit(tmp_path, n, old, new, said):
    line = the_line(against(n, altered(n, tmp_path, (old, new))), "limit-units")
    assert said in line


def test_limits_in_radians_converted_once_more(tmp_path):
    package = altered(3, tmp_path, ('lower="-0.7854"\n      upper="0.7854"',
                                    'lower="-0.0137"\n      upper="0.0137"'))
    result = against(3, package)
    assert [d.code for d in result.differences] == ["limit-units"] * 2, result.format()
    assert "0.0137 where the lesson has 0.7854: radians converted once more, as if they were " \
           "degrees?" in result.differences[1].text
    assert "enter the upper limit in radians" in result.differences[1].text


@pytest.mark.parametrize("xyz, said", [
    ('xyz="22.5 0 2"', "22.5 where the lesson has 0.225: typed in centimetres?"),
    ('xyz="2.25 0 0.2"', "2.25 where the lesson has 0.225: the decimal point one place too "
                         "far right?"),
    ('xyz="0.225 0 20"', "20 where the lesson has 0.02: typed in millimetres?"),
    ('xyz="0.000225 0 0.00002"', "metres converted once more, as if they were millimetres?")])
def test_an_origin_in_another_unit(tmp_path, xyz, said):
    line = the_line(against(3, altered(3, tmp_path, ('xyz="0.225 0 0.02"', xyz))),
                    "origin-units")
    assert 'joint "end_arm_joint": origin xyz' in line and said in line


def test_an_origin_turned_in_degrees(tmp_path):
    package = altered(2, tmp_path, ('xyz="0.20899 0.15071 0"\n      rpy="0 0 -0.7854"',
                                    'xyz="0.20899 0.15071 0"\n      rpy="0 0 -45"'))
    result = against(2, package)
    first = result.differences[0]
    assert first.code == "rpy-units" and first.subject == 'joint "front_left_joint"', \
        result.format()
    assert "-45 where the lesson has -0.7854: typed in degrees?" in first.text
    assert "origin-turned" not in [d.code for d in result.differences]


# --- an inertia about the link's origin ---------------------------------------------------

def about_origin(link: str):
    """An edit writing `link`'s inertia as taken about its frame's origin: the tensor
    about the centre of mass plus the parallel-axis term m(|d|^2 1 - d d^T)."""
    def change(urdf):
        text = urdf.read_text()
        start = text.index(f'name="{link}"')
        end = text.index("/>", re.compile(r"<inertia\s").search(text, start).start())
        block = text[start:end]
        centre = np.array(vector(re.search(r'<origin\s+xyz="([^"]+)"', block)[1], 3))
        mass = float(re.search(r'<mass\s+value="([^"]+)"', block)[1])
        terms = {k: float(v) for k, v in re.findall(INERTIA_TERMS, block)}
        tensor = np.array([[terms["ixx"], terms["ixy"], terms["ixz"]],
                           [terms["ixy"], terms["iyy"], terms["iyz"]],
                           [terms["ixz"], terms["iyz"], terms["izz"]]])
        moved = tensor + mass * (centre @ centre * np.eye(3) - np.outer(centre, centre))
        at = {"ixx": (0, 0), "ixy": (0, 1), "ixz": (0, 2), "iyy": (1, 1), "iyz": (1, 2),
              "izz": (2, 2)}
        block = re.sub(INERTIA_TERMS, lambda m: f'{m[1]}="{float(moved[at[m[1]]])!r}"', block)
        urdf.write_text(text[:start] + block + text[end:])
    return change


@pytest.mark.parametrize("n, link", [(3, "middle_arm_link"), (5, "base_link"),
                                     (4, "base_link")])
def test_an_inertia_about_the_link_origin(tmp_path, n, link):
    line = the_line(against(n, altered(n, tmp_path, about_origin(link))), "inertia-origin")
    assert f'link "{link}": principal moments' in line
    assert "the reference's plus m(|d|^2*1 - d*d^T)" in line
    assert "taken about the joint's frame (the link's origin) instead of the centre of mass" \
        in line
    assert '"taken at the center of mass" (Lxx, Lxy, ...)' in line


def test_an_inertia_spread_otherwise_is_not_taken_for_one_about_the_origin(tmp_path):
    package = altered(3, tmp_path, inertias(1.5, "middle_arm_link"))
    assert "taken about" not in the_line(against(3, package), "inertia")
