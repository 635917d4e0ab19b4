"""The collision rules of `sw2sim check`: links whose meshes pass through each other at the
rest pose, and links MuJoCo makes touch there because it collides convex hulls."""

from __future__ import annotations

import time
from pathlib import Path

import mujoco
import numpy as np
import pytest
from packages import (EXAMPLES, copy_example, edit, edit_re, fires_at,
                      group_findings, line_of, urdf_of)
from repository import practice_numbers

from sw2sim import load_package
from sw2sim.check import all_rules, check, open_package
from sw2sim.check.geometry import Tree

GROUP = "collision"
# Example 3's end_arm_link gets a 2 cm cube that sits in the hollow of base_link's convex
# hull (beside its column, above its plate) without touching the mesh itself.
PROBE = ('\n    <collision name="probe">\n      <origin xyz="-0.175 0.05 -0.13" rpy="0 0 0" />\n'
         '      <geometry>\n        <box size="0.02 0.02 0.02" />\n      </geometry>\n'
         "    </collision>")


def _wheel_in_the_plate(folder: Path, shape: str | None = None) -> Path:
    """Example 1 with front_left_wheel moved 8 cm inwards, through the base plate; its
    <collision> is named "tyre" (and its geometry replaced by `shape`, if given)."""
    package = copy_example(1, folder)
    urdf = urdf_of(package)
    edit(urdf, 'xyz="0.13 0.18 0"', 'xyz="0.13 0.1 0"')
    edit_re(urdf, r'(name="front_left_wheel">.*?)<collision>', r'\1<collision name="tyre">')
    if shape:
        edit_re(urdf, r'(<collision name="tyre">.*?<geometry>).*?(</geometry>)',
                rf"\1{shape}\2")
    return package


def _probe_in_the_base_hull(folder: Path) -> Path:
    package = copy_example(3, folder)
    edit_re(urdf_of(package), r'(name="end_arm_link">.*?</collision>)', rf"\1{PROBE}")
    return package


BATTERY = {
    "collision-overlap": _wheel_in_the_plate,
    "collision-hull-contact": _probe_in_the_base_hull,
}
WHERE = {
    "collision-overlap": '<collision name="tyre">',
    "collision-hull-contact": '<collision name="probe">',
}


def ours(report) -> list:
    return group_findings(report, GROUP)


def test_battery_covers_every_collision_rule():
    assert set(BATTERY) == set(WHERE) == {r.id for r in all_rules().values() if r.group == GROUP}


@pytest.mark.parametrize("rule_id", sorted(BATTERY))
def test_rule_fires_at_the_offending_line(rule_id, tmp_path):
    report, hits = fires_at(BATTERY[rule_id](tmp_path), rule_id, WHERE[rule_id])
    assert len(hits) == 1 and len(ours(report)) == 1, report.format()
    assert report.status == 0 and "cm^3" in hits[0].message, report.format()


@pytest.mark.parametrize("n", practice_numbers())
def test_examples_are_clean_and_mujoco_agrees(n):
    assert ours(check(EXAMPLES / f"example_{n}", stability=False)) == []
    assert _contacts_at_rest(EXAMPLES / f"example_{n}") == set()


def test_mujoco_makes_the_contact_the_hull_rule_predicts(tmp_path):
    package = BATTERY["collision-hull-contact"](tmp_path)
    assert _contacts_at_rest(package) == {("base_link", "end_arm_link")}


def test_the_overlap_is_measured_in_volume_and_share(tmp_path):
    (hit,) = ours(check(_wheel_in_the_plate(tmp_path), stability=False))
    # The 2 cm plate cuts a band through the wheel: about 19 cm^3 of it.
    volume = float(hit.message.split(": ")[-1].split(" cm^3")[0])
    assert 15 < volume < 25
    assert '(parent and child, joint "front_left_joint")' in hit.message


def test_primitive_collision_shapes_are_measured_too(tmp_path):
    cylinder = ('\n        <cylinder radius="0.1" length="0.04" />\n      ')
    package = _wheel_in_the_plate(tmp_path, cylinder)
    # A cylinder's axis is z: the default orientation puts it flat in the plate.
    (hit,) = ours(check(package, stability=False))
    assert hit.rule == "collision-overlap"
    assert hit.line == line_of(urdf_of(package), '<collision name="tyre">')


def test_an_open_mesh_is_not_measured_as_a_solid(tmp_path):
    package = _wheel_in_the_plate(tmp_path)
    stl = package / "meshes" / "front_left_wheel.STL"
    data = stl.read_bytes()
    # Drop the last 100 triangles: the wheel is no longer closed.
    kept = (len(data) - 84) // 50 - 100
    stl.write_bytes(data[:80] + kept.to_bytes(4, "little") + data[84:84 + 50 * kept])
    assert "collision-overlap" not in check(package, stability=False).rules()


def test_the_tree_places_links_and_knows_which_pairs_mujoco_skips():
    tree = Tree(open_package(EXAMPLES / "example_5"))
    assert np.allclose(tree.pose("front_left_wheel")[:3, 3], [0.4, 0.15, 0.0])
    assert tree.body("base_link") is None
    assert tree.body("front_left_wheel") == "front_left_wheel"
    assert tree.mujoco_ignores("left_knuckle", "front_left_wheel")     # parent moves
    assert tree.mujoco_ignores("base_link", "rear_left_wheel")         # load_package excludes
    assert not tree.mujoco_ignores("base_link", "front_left_wheel")    # grandparent
    assert not tree.mujoco_ignores("steering_link", "left_knuckle")    # siblings


def test_the_check_of_example_5_is_quick():
    check(EXAMPLES / "example_5", stability=False)   # modules and caches warmed up
    start = time.perf_counter()
    check(EXAMPLES / "example_5", stability=False)
    assert time.perf_counter() - start < 3.0


def _contacts_at_rest(package: Path) -> set[tuple[str, str]]:
    """The pairs of links MuJoCo finds in contact with every joint at zero, as
    sw2sim.load_package builds the model (floor contacts left out)."""
    model = load_package(package).compile()
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    pairs = set()
    for contact in data.contact[:data.ncon]:
        bodies = sorted(model.body(model.geom_bodyid[g]).name for g in contact.geom)
        if model.geom(contact.geom[0]).name != "floor" and \
                model.geom(contact.geom[1]).name != "floor":
            pairs.add(tuple(bodies))
    return pairs
