"""`sw2sim check` agrees with the reference URDF parser (urdfdom, as Debian and ROS 1 ship
it) on what a URDF is, and MuJoCo's own messages reach the user as findings only.

The rules' batteries live with their groups (test_structure_rules.py, test_inertia_rules.py);
these are the cases around them.
"""

from __future__ import annotations

import json
import shutil
import subprocess
import sys

import pytest

from sw2sim.check import check
from sw2sim.cli import main
from packages import copy_example, edit, edit_re, urdf_of

ROBOT = '<robot\n  name="example_3">'


def test_a_namespaced_robot_is_a_urdf_and_converts(tmp_path, capsys):
    package = copy_example(3, tmp_path)
    edit(urdf_of(package), ROBOT, '<robot xmlns="http://www.ros.org"\n  name="example_3">')
    report = check(package, stability=False)
    assert report.status == 0, report.format()
    assert main(["convert", str(package), "-o", str(tmp_path / "out")]) == 0
    assert "xmlns" not in (tmp_path / "out" / "example_3.xml").read_text()


@pytest.mark.parametrize("version, fires", [
    (None, False), ("1.0", False), ("1", True), ("1.1", True), ("2.0", True), ("foo", True)])
def test_only_version_1_0_is_a_urdf_version(tmp_path, version, fires):
    package = copy_example(3, tmp_path)
    if version is not None:
        edit(urdf_of(package), ROBOT, f'<robot version="{version}"\n  name="example_3">')
    report = check(package, stability=False)
    assert ("urdf-version" in report.rules()) == fires, report.format()
    if fires:   # ROS refuses it, MuJoCo does not care: a model still comes out
        assert not report.simulation_stoppers


@pytest.mark.skipif(shutil.which("check_urdf") is None, reason="urdfdom's check_urdf is not "
                    "installed (Debian: liburdfdom-tools)")
@pytest.mark.parametrize("version", ["1.0", "1", "1.1", "2.0", "foo"])
def test_the_version_rule_says_what_urdfdom_does(tmp_path, version):
    urdf = tmp_path / "v.urdf"
    urdf.write_text(f'<robot name="r" version="{version}"><link name="a"/></robot>')
    refused = subprocess.run(["check_urdf", str(urdf)], capture_output=True).returncode != 0
    assert refused == ("urdf-version" in check(urdf, stability=False).rules())


def test_a_capsule_is_read_by_mujoco_and_only_ros_refuses_it(tmp_path, capsys):
    package = copy_example(3, tmp_path)
    edit_re(urdf_of(package), r'(name="end_arm_link">.*?<collision>.*?<geometry>\s*)<mesh[^>]*/>',
            r'\1<capsule radius="0.02" length="0.2" />')
    report = check(package, stability=False)
    assert "geometry-capsule" in report.rules() and not report.simulation_stoppers
    assert main(["convert", str(package), "-o", str(tmp_path / "out")]) == 0


def test_a_free_base_without_mass_names_both_ways_out(tmp_path):
    package = copy_example(5, tmp_path)
    edit(urdf_of(package), 'value="3.05678326799101"', 'value="0"')
    [finding] = [f for f in check(package, stability=False).findings
                 if f.rule == "root-link-massless"]
    assert "mass and inertia" in finding.fix and '<link name="world"/>' in finding.fix


def test_a_free_base_without_inertial_is_reported(tmp_path):
    package = copy_example(5, tmp_path)
    edit_re(urdf_of(package), r'(name="base_link">\s*)<inertial>.*?</inertial>', r"\1")
    rules = check(package, stability=False).rules()
    assert "inertial-missing" in rules or "root-link-massless" in rules


def test_mujocos_printed_warning_becomes_a_finding_and_stdout_stays_clean(tmp_path):
    package = copy_example(3, tmp_path)
    edit(urdf_of(package), "<visual>", '<visual name="shape">')
    edit(urdf_of(package), "<visual>", '<visual name="shape">')
    run = subprocess.run([sys.executable, "-m", "sw2sim", "check", str(package), "--json"],
                         capture_output=True, text=True, cwd=tmp_path)
    report = json.loads(run.stdout)             # nothing but the report on stdout
    assert "geom-name-duplicate" in {f["rule"] for f in report["findings"]}
    assert run.stderr == ""
    assert not (tmp_path / "MUJOCO_LOG.TXT").exists()
