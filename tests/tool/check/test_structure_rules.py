"""The structure rules of `sw2sim check`: names, joint types, the link tree, numbers."""

from __future__ import annotations

from pathlib import Path

import pytest
from packages import (EXAMPLES, copy_example, edit, edit_re, fires_at,
                      group_findings, line_of, urdf_of)
from repository import practice_numbers

from sw2sim.check import all_rules, check, open_package, structure
from sw2sim.check.urdf import number, vector
from course.exporter_format import urdf_text
from course.practices import PRACTICES, design

GROUP = "structure"


def _example_1(folder: Path, old: str, new: str) -> Path:
    package = copy_example(1, folder)
    edit(urdf_of(package), old, new)
    return package


BASE_MESH = '<mesh\n          filename="package://example_1/meshes/base_link.STL" />'


def _two_visuals_named_alike(folder: Path) -> Path:
    package = _example_1(folder, "<visual>", '<visual name="shape">')
    edit(urdf_of(package), "<visual>", '<visual  name="shape">')
    return package


def _roots_several(folder: Path) -> Path:
    package = copy_example(1, folder)
    edit_re(urdf_of(package), r'  <joint\s+name="world_joint".*?</joint>\n', "")
    return package


def _no_links(folder: Path) -> Path:
    package = copy_example(1, folder)
    urdf_of(package).write_text('<robot\n  name="example_1">\n</robot>\n')
    return package


# Each maker breaks one thing; WHERE gives the text on the line the finding must point at
# (spaces around "=" make an edited line unique where the plain text repeats).
BATTERY = {
    "name-missing": lambda d: _example_1(d, 'name="front_left_joint"', 'name=" "'),
    "name-duplicate": lambda d: _example_1(d, 'name="front_right_joint"',
                                           'name = "front_left_joint"'),
    "joint-type-unknown": lambda d: _example_1(d, 'type="continuous"', 'type="hinge"'),
    "joint-parent-missing": lambda d: _example_1(d, '<parent\n      link="base_link"',
                                                 '<parent\n      link="base_lnk"'),
    "joint-child-missing": lambda d: _example_1(d, 'link="front_left_wheel"',
                                                'link="front_left_wheal"'),
    "link-two-parents": lambda d: _example_1(d, 'link="rear_right_wheel"',
                                             'link = "front_left_wheel"'),
    "kinematic-cycle": lambda d: _example_1(d, '<parent\n      link="world"',
                                            '<parent\n      link="front_left_wheel"'),
    "roots-several": _roots_several,
    "urdf-no-links": _no_links,
    "number-invalid": lambda d: _example_1(d, 'xyz="0.13 0.18 0"', 'xyz="0.13 0,18 0"'),
    "urdf-version": lambda d: _example_1(d, '<robot\n  name="example_1"',
                                         '<robot\n  version="2.0"\n  name="example_1"'),
    "geometry-unknown": lambda d: _example_1(d, BASE_MESH, '<cone radius="0.05" length="0.1" />'),
    "geometry-capsule": lambda d: _example_1(d, BASE_MESH,
                                             '<capsule radius="0.05" length="0.1" />'),
    "geom-name-duplicate": _two_visuals_named_alike,
}
WHERE = {
    "name-missing": 'name=" "',
    "name-duplicate": 'name = "front_left_joint"',
    "joint-type-unknown": 'type="hinge"',
    "joint-parent-missing": 'link="base_lnk"',
    "joint-child-missing": 'link="front_left_wheal"',
    "link-two-parents": 'link = "front_left_wheel"',
    "kinematic-cycle": 'name="world_joint"',
    "roots-several": 'name="base_link"',
    "urdf-no-links": 'name="example_1"',
    "number-invalid": 'xyz="0.13 0,18 0"',
    "urdf-version": 'version="2.0"',
    "geometry-unknown": "<cone",
    "geometry-capsule": "<capsule",
    "geom-name-duplicate": '<visual  name="shape">',
}


def ours(report) -> list:
    return group_findings(report, GROUP)


def test_battery_covers_every_structure_rule():
    assert set(BATTERY) == set(WHERE) == {r.id for r in all_rules().values() if r.group == GROUP}


@pytest.mark.parametrize("rule_id", sorted(BATTERY))
def test_rule_fires_at_the_offending_line(rule_id, tmp_path):
    fires_at(BATTERY[rule_id](tmp_path), rule_id, WHERE[rule_id])


@pytest.mark.parametrize("n", practice_numbers())
def test_examples_are_clean(n):
    assert ours(check(EXAMPLES / f"example_{n}", stability=False)) == []


@pytest.mark.parametrize("practice", PRACTICES)
def test_the_exporters_own_output_is_clean(practice, tmp_path):
    # The URDF exactly as the exporter writes it: no world link, no transmissions.
    package = copy_example(PRACTICES.index(practice) + 1, tmp_path)
    urdf_of(package).write_text(urdf_text(design(practice).robot(), as_exported=True))
    assert ours(check(package, stability=False)) == []


# --- small robots for the tree logic ---------------------------------------------------------

def robot(folder: Path, links: str, joints: list[tuple[str, str, str]]) -> Path:
    """A URDF of bare links (names separated by spaces) and fixed joints (name, parent, child),
    one element per line so that each finding's line names one element."""
    lines = ['<robot name="tree">']
    lines += [f'  <link name="{name}"/>' for name in links.split()]
    lines += [f'  <joint name="{n}" type="fixed"><parent link="{p}"/><child link="{c}"/></joint>'
              for n, p, c in joints]
    path = folder / "tree.urdf"
    path.write_text("\n".join([*lines, "</robot>", ""]))
    return path


def findings(path: Path, rule_id: str) -> list:
    """The findings of one structure rule, from the structure check alone (the full check
    also loads every mesh, which the tree logic does not need)."""
    ctx = open_package(path)
    structure.check(ctx)
    return [f for f in ctx.findings if f.rule == rule_id]


def test_a_tree_under_a_world_link_is_one_tree(tmp_path):
    path = robot(tmp_path, "world base wheel",
                 [("fix", "world", "base"), ("axle", "base", "wheel")])
    assert ours(check(path, stability=False)) == []


def test_an_unconnected_link_is_a_second_root(tmp_path):
    path = robot(tmp_path, "world base spare", [("fix", "world", "base")])
    (hit,) = findings(path, "roots-several")
    assert '"world", "spare"' in hit.message and hit.line == line_of(path, '"spare"')


def test_a_self_loop_is_a_cycle(tmp_path):
    path = robot(tmp_path, "base arm", [("j1", "base", "arm"), ("loop", "arm", "arm")])
    (hit,) = findings(path, "kinematic-cycle")
    assert '"loop"' in hit.message and hit.line == line_of(path, 'name="loop"')


def test_a_cycle_below_a_root_is_found_once_with_its_joints(tmp_path):
    path = robot(tmp_path, "base a b c tail",
                 [("up", "base", "a"), ("ab", "a", "b"), ("bc", "b", "c"), ("ca", "c", "a"),
                  ("tail", "c", "tail")])
    (hit,) = findings(path, "kinematic-cycle")
    assert all(f'"{j}"' in hit.message for j in ("ab", "bc", "ca"))
    assert '"up"' not in hit.message and '"tail"' not in hit.message
    assert hit.line == line_of(path, 'name="ab"')
    # "a" has two parents ("up" and "ca"), which is reported on its own.
    assert len(findings(path, "link-two-parents")) == 1


def test_two_separate_cycles_are_two_findings(tmp_path):
    path = robot(tmp_path, "p q r s", [("pq", "p", "q"), ("qp", "q", "p"),
                                        ("rs", "r", "s"), ("sr", "s", "r")])
    assert len(findings(path, "kinematic-cycle")) == 2
    assert findings(path, "roots-several") == []   # no link is a root at all


def test_a_closed_loop_without_a_cycle_is_two_parents_not_a_cycle(tmp_path):
    # A four-bar closed in the URDF: "coupler" hangs from both cranks.
    path = robot(tmp_path, "ground left right coupler",
                 [("l", "ground", "left"), ("r", "ground", "right"),
                  ("lc", "left", "coupler"), ("rc", "right", "coupler")])
    (hit,) = findings(path, "link-two-parents")
    assert '"coupler"' in hit.message and '"lc"' in hit.message and '"rc"' in hit.message
    assert hit.line == line_of(path, 'name="rc"')
    assert findings(path, "kinematic-cycle") == []


def test_a_long_chain_needs_no_recursion(tmp_path):
    n = 3000
    names = " ".join(f"l{i}" for i in range(n))
    joints = [(f"j{i}", f"l{i}", f"l{i + 1}") for i in range(n - 1)] + [("back", f"l{n - 1}", "l0")]
    assert len(findings(robot(tmp_path, names, joints), "kinematic-cycle")) == 1


def test_a_misspelt_link_gets_a_suggestion(tmp_path):
    path = robot(tmp_path, "base_link wheel", [("axle", "base_link", "whel")])
    (hit,) = findings(path, "joint-child-missing")
    assert '"whel"' in hit.message and '"wheel"' in hit.fix
    # The orphaned "wheel" is what the joint meant, not a second root.
    assert findings(path, "roots-several") == []


def test_a_joint_type_in_capitals_gets_a_suggestion(tmp_path):
    path = robot(tmp_path, "a b", [("j", "a", "b")])
    edit(path, 'type="fixed"', 'type="Revolute"')
    (hit,) = findings(path, "joint-type-unknown")
    assert 'type="revolute"' in hit.fix


def test_a_name_missing_altogether_points_at_the_tag(tmp_path):
    path = _example_1(tmp_path, '<joint\n    name="front_left_joint"\n', "<joint\n")
    (hit,) = findings(path, "name-missing")
    assert hit.line == line_of(urdf_of(path), 'type="continuous"') - 1


# --- bad input never raises -------------------------------------------------------------------

MALFORMED = {
    "bare joint": "<joint/>",
    "parent without link": '<joint name="j" type="fixed"><parent/><child link=""/></joint>',
    "empty names": '<link name=""/><joint name="" type=""/>',
    "words for numbers": '<joint name="j" type="revolute"><parent link="a"/><child link="b"/>'
                         '<origin xyz="abc" rpy="nan 0 inf"/><axis xyz="1e999 0 0"/>'
                         '<limit lower="" upper="1.0.0" effort="--1" velocity="0x10"/></joint>',
    "short vector": '<link name="c"><visual><origin xyz="1 2"/></visual></link>',
    "comment and text": "<!-- a comment --> loose text <link name='d'>text<inertial/></link>",
    "unicode digits": '<link name="e"><inertial><mass value="\u0663"/></inertial></link>',
}


@pytest.mark.parametrize("case", sorted(MALFORMED))
def test_malformed_values_do_not_raise(case, tmp_path):
    path = tmp_path / "bad.urdf"
    path.write_text(f'<robot name="bad"><link name="a"/><link name="b"/>{MALFORMED[case]}</robot>')
    report = check(path, stability=False)
    assert report.status == 1, report.format()
    report.format()
    report.to_json()


def test_each_bad_number_is_reported_with_its_attribute(tmp_path):
    path = tmp_path / "bad.urdf"
    path.write_text(f'<robot name="bad"><link name="a"/><link name="b"/>'
                    f'{MALFORMED["words for numbers"]}</robot>')
    messages = [f.message for f in findings(path, "number-invalid")]
    for fragment in ('xyz="abc"', 'rpy="nan 0 inf"', 'xyz="1e999 0 0"', 'lower=""',
                     'upper="1.0.0"', 'effort="--1"', 'velocity="0x10"'):
        assert any(fragment in m for m in messages), (fragment, messages)
    assert len(messages) == 7


def test_number_reads_what_urdf_parsers_read():
    assert number("1E-05") == 1e-05 and number(" -0.5 ") == -0.5 and number("5.") == 5.0
    for bad in (None, "", "abc", "1.0.0", "nan", "inf", "1e999", "1_000", "0,5", "\u0663"):
        assert number(bad) is None, bad
    assert vector("0 0.70711 0.70711", 3) == (0.0, 0.70711, 0.70711)
    assert vector("1 2", 3) is None and vector("1 2 x", 3) is None and vector(None, 3) is None
