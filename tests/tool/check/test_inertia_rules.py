"""The inertia rules of `sw2sim check`: masses, centres of mass and inertia tensors, with
MuJoCo as the judge of what is an error."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from lxml import etree
from packages import EXAMPLES, copy_example, edit, edit_re, fires_at, group_findings, urdf_of
from repository import practice_numbers

from sw2sim import LoadError, load_package
from sw2sim.loader import world_fixed
from sw2sim.check import RULES, all_rules, check
from sw2sim.check.geometry import inertial_of

GROUP = "inertia"
# Example 1's first wheel, front_left_wheel (all four wheels share these values).
MASS = 'value="3.05144834004229"'
INERTIA = '<inertia\n        ixx="0.00839752499701271"'
CENTRE = 'xyz="0 0 1.99860411864172E-18"'
WHEEL_INERTIAL = r'(name="front_left_wheel">\s*)<inertial>.*?</inertial>\s*'


def _example_1(folder: Path, old: str, new: str) -> Path:
    package = copy_example(1, folder)
    edit(urdf_of(package), old, new)
    return package


def _without_inertial(folder: Path) -> Path:
    package = copy_example(1, folder)
    edit_re(urdf_of(package), WHEEL_INERTIAL, r"\1")
    return package


def _free_base_without_mass(folder: Path) -> Path:
    """Practice 5's car (no world link: its base floats free) with a base of no mass."""
    package = copy_example(5, folder)
    edit(urdf_of(package), 'value="3.05678326799101"', 'value="0"')
    return package


# Each maker breaks front_left_wheel (the free base's rule: the car's base_link); WHERE gives the text on the line the finding must point
# at (an <inertia> written on one line makes its start unique).
BATTERY = {
    "inertial-missing": _without_inertial,
    "inertial-incomplete": lambda d: _example_1(
        d, INERTIA + '\n        ixy="3.81164826264435E-20"', '<inertia ixx="0.00839752499701271"'),
    "mass-not-positive": lambda d: _example_1(d, MASS, 'value="0"'),
    "mass-tiny": lambda d: _example_1(d, MASS, 'value="1e-9"'),
    "inertia-not-positive-definite": lambda d: _example_1(d, INERTIA, '<inertia ixx="-0.001"'),
    "inertia-triangle": lambda d: _example_1(d, INERTIA, '<inertia ixx="0.001"'),
    "com-outside-geometry": lambda d: _example_1(d, CENTRE, 'xyz="0.5 0 0"'),
    "density-implausible": lambda d: _example_1(d, MASS, 'value="500"'),
    "root-link-massless": _free_base_without_mass,
}
LINK = {"root-link-massless": "base_link"}
WHERE = {
    "inertial-missing": 'name="front_left_wheel"',
    "inertial-incomplete": '<inertia ixx="0.00839752499701271"',
    "mass-not-positive": 'value="0"',
    "mass-tiny": 'value="1e-9"',
    "inertia-not-positive-definite": '<inertia ixx="-0.001"',
    "inertia-triangle": '<inertia ixx="0.001"',
    "com-outside-geometry": 'xyz="0.5 0 0"',
    "density-implausible": 'value="500"',
    "root-link-massless": 'name="base_link"',
}


def ours(report) -> list:
    return group_findings(report, GROUP)


def test_battery_covers_every_inertia_rule():
    assert set(BATTERY) == set(WHERE) == {r.id for r in all_rules().values() if r.group == GROUP}


@pytest.mark.parametrize("rule_id", sorted(BATTERY))
def test_rule_fires_at_the_offending_line(rule_id, tmp_path):
    report, hits = fires_at(BATTERY[rule_id](tmp_path), rule_id, WHERE[rule_id])
    assert len(hits) == 1, report.format()
    assert f'"{LINK.get(rule_id, "front_left_wheel")}"' in hits[0].message
    assert f"[{rule_id}]" in report.format()


@pytest.mark.parametrize("rule_id", sorted(BATTERY))
def test_errors_are_what_mujoco_refuses_and_warnings_load(rule_id, tmp_path):
    package = BATTERY[rule_id](tmp_path)
    if RULES[rule_id].severity == "error":
        with pytest.raises(LoadError, match="mjMINVAL|eigenvalues|A \\+ B >= C|missing"):
            load_package(package, fixed_base=world_fixed(package)).compile()
    else:
        load_package(package, fixed_base=world_fixed(package)).compile()


@pytest.mark.parametrize("n", practice_numbers())
def test_examples_are_clean(n):
    assert ours(check(EXAMPLES / f"example_{n}", stability=False)) == []


def test_a_massless_link_held_by_the_world_is_a_frame_not_an_error(tmp_path):
    # base_link is fixed to the world link: MuJoCo accepts it without mass.
    package = copy_example(1, tmp_path)
    edit_re(urdf_of(package), r'value="2\.65\d*"', 'value="0"')
    assert ours(check(package, stability=False)) == []


def test_a_negative_mass_is_an_error_even_on_a_fixed_link(tmp_path):
    package = _example_1(tmp_path, 'value="2.65', 'value="-2.65')
    (hit,) = ours(check(package, stability=False))
    assert hit.rule == "mass-not-positive" and '"base_link"' in hit.message


def test_a_massless_wheel_with_a_heavy_hub_fixed_to_it_loads(tmp_path):
    package = _example_1(tmp_path, MASS, 'value="0"')
    hub = ('  <link name="hub"><inertial><mass value="0.2"/><inertia ixx="1e-4" ixy="0" '
           'ixz="0" iyy="1e-4" iyz="0" izz="1e-4"/></inertial></link>\n'
           '  <joint name="hub_joint" type="fixed"><parent link="front_left_wheel"/>'
           '<child link="hub"/></joint>\n</robot>')
    edit(urdf_of(package), "</robot>", hub)
    assert ours(check(package, stability=False)) == []
    load_package(package).compile()


def test_a_moving_link_with_nothing_to_weigh_is_an_error(tmp_path):
    package = copy_example(1, tmp_path)
    edit_re(urdf_of(package), r'(name="front_left_wheel">\s*)<inertial>.*?</link>', r"\1</link>")
    (hit,) = ours(check(package, stability=False))
    assert hit.rule == "mass-not-positive" and "no collision geometry" in hit.message
    with pytest.raises(LoadError, match="mjMINVAL"):
        load_package(package).compile()


def test_a_thin_disc_on_the_triangle_boundary_is_accepted(tmp_path):
    # A + B = C exactly: MuJoCo accepts it, and so does the check.
    package = _example_1(tmp_path, INERTIA, '<inertia ixx="0.008"')
    edit(urdf_of(package), 'iyy="0.0159813304730569"', 'iyy="0.016"')
    edit(urdf_of(package), 'izz="0.00839752499701271"', 'izz="0.008"')
    assert ours(check(package, stability=False)) == []
    load_package(package).compile()


def test_a_shortfall_below_the_fourth_digit_is_printed_with_the_digits_that_show_it(tmp_path):
    # The zero-mass arm's message read "1.702e-10 is less than 1.702e-10".
    package = _example_1(tmp_path, INERTIA, '<inertia ixx="8.51e-11"')
    edit(urdf_of(package), 'iyy="0.0159813304730569"', 'iyy="1.70200001e-10"')
    edit(urdf_of(package), 'izz="0.00839752499701271"', 'izz="8.51e-11"')
    [finding] = [f for f in check(package, stability=False).findings
                 if f.rule == "inertia-triangle"]
    total, limit = finding.message.rsplit(" = ", 1)[1].split(" is less than ")
    assert float(total) < float(limit), finding.message
    assert "1.702e-10 is less than 1.70200001e-10" in finding.message


def test_a_density_just_outside_the_range_reads_outside_it():
    from sw2sim.check.inertia import _density
    assert _density(99.6) == "99.6" and _density(25_000.4) == "25000.4"
    assert _density(30_000.2) == "30,000" and _density(0.5) == "0.5"


def test_an_all_zero_inertia_on_a_moving_link_is_an_error(tmp_path):
    package = copy_example(1, tmp_path)
    edit_re(urdf_of(package), r'(name="front_left_wheel">.*?<inertia)\s.*?/>',
            r'\1 ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0" />')
    (hit,) = ours(check(package, stability=False))
    assert hit.rule == "inertia-not-positive-definite" and "all six terms" in hit.message


def test_the_centre_of_mass_is_judged_against_the_meshes_where_they_are(tmp_path):
    # Moving the wheel's meshes by 0.5 m (a <visual>/<collision> origin) and its centre of
    # mass with them keeps the two together: no warning.
    package = copy_example(1, tmp_path)
    urdf = urdf_of(package)
    edit_re(urdf, r'(name="front_left_wheel">.*?)<visual>\s*<origin\s*xyz="0 0 0"',
            r'\1<visual>\n      <origin\n        xyz="0.5 0 0"')
    edit_re(urdf, r'(name="front_left_wheel">.*?)<collision>\s*<origin\s*xyz="0 0 0"',
            r'\1<collision>\n      <origin\n        xyz="0.5 0 0"')
    edit(urdf, CENTRE, 'xyz="0.5 0 0"')
    assert "com-outside-geometry" not in check(package, stability=False).rules()


def test_the_inertia_is_read_in_the_links_axes():
    link = etree.fromstring(
        '<link name="rod"><inertial><origin xyz="0.1 0 0" rpy="0 1.5707963267949 0"/>'
        '<mass value="2"/><inertia ixx="0.3" ixy="0" ixz="0" iyy="0.2" iyz="0" izz="0.1"/>'
        "</inertial></link>")
    inertial = inertial_of(link)
    assert np.allclose(inertial.centre, [0.1, 0, 0])
    # Turned a quarter about y: the x and z moments swap.
    assert np.allclose(np.diag(inertial.tensor), [0.1, 0.2, 0.3])
    assert inertial.spread == pytest.approx(np.sqrt(0.6 / 4))
    assert inertial.missing == ()
