"""The joint rules of `sw2sim check`: axes, limits and safety controllers."""

from __future__ import annotations

from pathlib import Path

import pytest
from packages import EXAMPLES, copy_example, edit, edit_re, fires_at, group_findings, urdf_of
from repository import practice_numbers

from sw2sim.check import all_rules, check, joints, open_package

GROUP = "joint"
# Practice 3's first revolute joint, as exported: the limit every edit below starts from.
ARM_LIMIT = ('<limit\n      lower="-0.7854"\n      upper="0.7854"\n      effort="1000"\n'
             '      velocity="2" />')


def _example(n: int, folder: Path, old: str, new: str) -> Path:
    package = copy_example(n, folder)
    edit(urdf_of(package), old, new)
    return package


def _arm_limit(folder: Path, new: str) -> Path:
    return _example(3, folder, ARM_LIMIT, new)


# Each maker breaks one thing; WHERE gives the text on the line the finding must point at
# (doubled spaces make an edited line unique where the plain text repeats).
BATTERY = {
    "mimic-joint-missing": lambda d: _example(3, d, '<child\n      link="end_arm_link" />',
                                              '<child\n      link="end_arm_link" />\n'
                                              '    <mimic  joint="midle_arm_joint" />'),
    "mimic-joint-not-movable": lambda d: _example(3, d, '<child\n      link="end_arm_link" />',
                                                  '<child\n      link="end_arm_link" />\n'
                                                  '    <mimic  joint="world_joint" />'),
    "axis-zero": lambda d: _example(1, d, 'xyz="0 1 0"', 'xyz="0  0 0"'),
    "axis-not-unit": lambda d: _example(1, d, 'xyz="0 1 0"', 'xyz="0 10 0"'),
    "limit-missing": lambda d: _arm_limit(d, "<!-- limit deleted -->"),
    "limit-incomplete": lambda d: _arm_limit(
        d, '<limit\n      lower="-0.7854"\n      upper="0.7854"\n      velocity="2" />'),
    "limit-exporter-default": lambda d: _arm_limit(
        d, '<limit\n      lower="0"\n      upper="0"\n      effort="0"\n      velocity="0" />'),
    "limit-range-empty": lambda d: _arm_limit(
        d, '<limit\n      lower="0.9"\n      upper="0.7854"\n      effort="1000"\n'
           '      velocity="2" />'),
    "effort-not-positive": lambda d: _arm_limit(d, ARM_LIMIT.replace('"1000"', '"-5"')),
    "velocity-not-positive": lambda d: _arm_limit(d, ARM_LIMIT.replace('"2"', '"0"')),
    "limit-on-continuous": lambda d: _example(
        5, d, 'lower="0"\n      upper="0"\n      effort="10"',
        'lower="-1"\n      upper="1"\n      effort="10"'),
    "safety-limits-misspelt": lambda d: _example(
        3, d, 'soft_lower_limit="-0.7854"\n      soft_upper_limit="0.7854"',
        'soft_upper="0.7854"\n      soft_lower="-0.7854"'),
}
WHERE = {
    "mimic-joint-missing": '<mimic  joint="midle_arm_joint"',
    "mimic-joint-not-movable": '<mimic  joint="world_joint"',
    "axis-zero": 'xyz="0  0 0"',
    "axis-not-unit": 'xyz="0 10 0"',
    "limit-missing": 'name="middle_arm_joint"',
    "limit-incomplete": "<limit",
    "limit-exporter-default": "<limit",
    "limit-range-empty": 'lower="0.9"',
    "effort-not-positive": 'effort="-5"',
    "velocity-not-positive": 'velocity="0"',
    "limit-on-continuous": 'lower="-1"',
    "safety-limits-misspelt": 'soft_lower="-0.7854"',
}


def ours(report) -> list:
    return group_findings(report, GROUP)


def joint_findings(package: Path) -> list:
    """The joint check's findings alone (the full check also loads every mesh)."""
    ctx = open_package(package)
    joints.check(ctx)
    return ctx.findings


def rules_of(package: Path) -> list[str]:
    return sorted(f.rule for f in joint_findings(package))


def test_battery_covers_every_joint_rule():
    assert set(BATTERY) == set(WHERE) == {r.id for r in all_rules().values() if r.group == GROUP}


@pytest.mark.parametrize("rule_id", sorted(BATTERY))
def test_rule_fires_at_the_offending_line(rule_id, tmp_path):
    report, _ = fires_at(BATTERY[rule_id](tmp_path), rule_id, WHERE[rule_id])
    # One broken thing, one finding of this group.
    assert [f.rule for f in ours(report)] == [rule_id]


@pytest.mark.parametrize("n", practice_numbers())
def test_examples_are_clean(n):
    assert ours(check(EXAMPLES / f"example_{n}", stability=False)) == []


def test_the_exporters_zero_limit_is_one_finding_naming_the_joint(tmp_path):
    (hit,) = joint_findings(BATTERY["limit-exporter-default"](tmp_path))
    assert '"middle_arm_joint"' in hit.message and "= 0" in hit.message


def test_older_exports_zero_limit_without_lower_and_upper(tmp_path):
    # Early exports wrote only effort and velocity, both 0; lower and upper default to 0.
    package = _arm_limit(tmp_path, '<limit\n      effort="0"\n      velocity="0" />')
    assert rules_of(package) == ["limit-exporter-default"]


def test_a_zero_limit_on_a_fixed_joint_is_ignored(tmp_path):
    # URDF allows a <limit> on a fixed joint and nobody reads it.
    package = _example(1, tmp_path, '<child\n      link="base_link" />',
                       '<child\n      link="base_link" />\n    <limit lower="0" upper="0" '
                       'effort="0" velocity="0" />')
    assert rules_of(package) == []


def test_a_zero_axis_on_a_fixed_joint_is_ignored(tmp_path):
    # Older exports wrote <axis xyz="0 0 0"/> on fixed joints (exporter PR #8).
    package = _example(1, tmp_path, '<child\n      link="base_link" />',
                       '<child\n      link="base_link" />\n    <axis xyz="0 0 0" />')
    assert rules_of(package) == []


def test_a_continuous_joint_with_the_exporters_zero_limit(tmp_path):
    package = _example(5, tmp_path, 'effort="10"\n      velocity="30"',
                       'effort="0"\n      velocity="0"')
    assert rules_of(package) == ["limit-exporter-default"]


def test_a_real_range_with_zero_effort_is_an_effort_finding_only(tmp_path):
    package = _arm_limit(tmp_path, ARM_LIMIT.replace('"1000"', '"0"'))
    assert rules_of(package) == ["effort-not-positive"]


def test_equal_limits_with_a_real_effort_leave_no_range(tmp_path):
    package = _arm_limit(tmp_path, '<limit lower="0" upper="0" effort="10" velocity="1"/>')
    (hit,) = joint_findings(package)
    assert hit.rule == "limit-range-empty" and "fixed" in hit.fix


def test_a_prismatic_joint_without_a_limit(tmp_path):
    package = copy_example(4, tmp_path)
    edit_re(urdf_of(package), r"<limit.*?/>", "")
    (hit,) = joint_findings(package)
    assert hit.rule == "limit-missing" and 'prismatic joint "block_joint"' in hit.message


def test_a_diagonal_axis_rounded_to_five_digits_is_unit(tmp_path):
    package = _example(1, tmp_path, 'xyz="0 1 0"', 'xyz="0 0.70711 0.70711"')
    assert rules_of(package) == []


def test_the_unit_axis_is_suggested(tmp_path):
    package = _example(1, tmp_path, 'xyz="0 1 0"', 'xyz="0 1 1"')
    (hit,) = joint_findings(package)
    assert "1.414" in hit.message and 'xyz="0 0.70711 0.70711"' in hit.fix


def test_correct_and_misspelt_soft_limits_together_are_fine(tmp_path):
    package = _example(3, tmp_path, 'soft_upper_limit="0.7854"',
                       'soft_upper_limit="0.7854"\n      soft_upper="0.7854"')
    assert rules_of(package) == []


@pytest.mark.parametrize("limit", [
    '<limit lower="abc" upper="1" effort="1" velocity="1"/>',
    '<limit lower="1" upper="nan" effort="" velocity="1e999"/>',
    "<limit/>",
    '<limit lower="-1" upper="1" effort="1" velocity="1"><limit velocity="?"/></limit>',
])
def test_malformed_limits_do_not_raise(limit, tmp_path):
    report = check(_arm_limit(tmp_path, limit), stability=False)
    report.format()
    assert report.status == 1


@pytest.mark.parametrize("axis", ['<axis/>', '<axis xyz=""/>', '<axis xyz="1 0"/>',
                                  '<axis xyz="x y z"/>'])
def test_malformed_axes_do_not_raise(axis, tmp_path):
    package = _example(1, tmp_path, '<axis\n      xyz="0 1 0" />', axis)
    assert "axis-zero" not in rules_of(package)


def test_a_joint_without_a_type_or_name_is_left_to_the_structure_rules(tmp_path):
    package = _example(3, tmp_path, 'name="middle_arm_joint"\n    type="revolute"', "")
    assert rules_of(package) == []
