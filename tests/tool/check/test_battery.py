"""The battery: one broken package for every rule of `sw2sim check`, and every exit status.

Each rule's test module (tests/tool/check/test_*.py) exposes BATTERY = {rule id: maker}, where a
maker takes an empty folder and returns the path to check; those modules prove that each maker
triggers its rule. This module adds the makers for the input rules, which belong to no group
module, and checks the whole: no registered rule lacks a maker, no maker names an unknown rule,
and the exit statuses 0, 1 and 2 are each reached.
"""

from __future__ import annotations

import importlib
import re
from pathlib import Path

import pytest

from sw2sim.check import ERROR, FATAL, RULES, all_rules, check
from packages import copy_example, edit, urdf_of
from test_package_choice import broken_xacro, xacro_only

HERE = Path(__file__).parent


def _broken_urdf(folder: Path, text: bytes) -> Path:
    package = copy_example(4, folder)
    urdf_of(package).write_bytes(text)
    return package


def _truncated(folder: Path) -> Path:
    package = copy_example(4, folder)
    urdf = urdf_of(package)
    urdf.write_bytes(urdf.read_bytes()[:700])
    return package


def _with_doctype(folder: Path) -> Path:
    package = copy_example(4, folder)
    edit(urdf_of(package), "<robot", '<!DOCTYPE robot [<!ENTITY mass "2.5">]>\n<robot')
    return package


def _not_urdf(folder: Path) -> Path:
    model = folder / "model.urdf"
    model.write_text('<?xml version="1.0"?>\n<mujoco model="arm">\n  <worldbody/>\n</mujoco>\n')
    return model


# The input rules: what makes a file unusable before any group's check runs (exit status 2).
BATTERY = {
    "input-missing": lambda d: d / "no_such_package",
    "input-unreadable": lambda d: _broken_urdf(d, b"  \n"),
    "xml-syntax": _truncated,
    "xml-doctype": _with_doctype,
    "not-urdf": _not_urdf,
    "xacro-needs-package": lambda d: xacro_only(d, find="arm_meshes"),
    "xacro-failed": broken_xacro,
}


def batteries() -> dict[str, tuple[str, object]]:
    """Rule id -> (module, maker), from every test module of this folder that has a BATTERY."""
    found = {rule: (Path(__file__).stem, maker) for rule, maker in BATTERY.items()}
    for path in sorted(HERE.glob("test_*.py")):
        if path.stem == Path(__file__).stem:
            continue
        if not re.search(r"^BATTERY\s*[:=]", path.read_text(), re.M):
            continue
        module = importlib.import_module(path.stem)
        for rule, maker in module.BATTERY.items():
            assert rule not in found, f"{rule!r} has makers in {found[rule][0]} and {path.stem}"
            found[rule] = (path.stem, maker)
    return found


def test_every_rule_has_a_maker():
    makers = batteries()
    missing = sorted(rule for rule in all_rules() if rule not in makers)
    by_group = {}
    for rule in missing:
        by_group.setdefault(RULES[rule].group, []).append(rule)
    assert not missing, f"rules without a maker in any BATTERY: {by_group}"


def test_every_maker_names_a_registered_rule():
    rules = all_rules()
    unknown = {rule: module for rule, (module, _) in batteries().items() if rule not in rules}
    assert not unknown, f"makers for rules that are not registered: {unknown}"


@pytest.mark.parametrize("rule_id", sorted(BATTERY))
def test_each_input_rule_stops_the_check_with_status_2(rule_id, tmp_path):
    path = BATTERY[rule_id](tmp_path)
    report = check(path, stability=False)
    hits = [f for f in report.findings if f.rule == rule_id]
    assert hits and report.status == 2, report.format()
    assert hits[0].severity == FATAL and hits[0].file, report.format()
    if rule_id in ("xml-syntax", "xml-doctype", "not-urdf"):
        assert hits[0].line, report.format()


def test_each_exit_status_is_reached(tmp_path):
    statuses = {}
    clean = check(copy_example(4, tmp_path / "clean"), stability=False)
    statuses[clean.status] = "examples/example_4"
    missing = check(BATTERY["input-missing"](tmp_path), stability=False)
    statuses[missing.status] = "input-missing"
    errors = sorted(rule for rule, (_, maker) in batteries().items()
                    if RULES.get(rule) and RULES[rule].severity == ERROR
                    and RULES[rule].group != "simulation")
    assert errors, "no maker for any error rule"
    folder = tmp_path / "error"
    folder.mkdir()
    report = check(batteries()[errors[0]][1](folder), stability=False)
    statuses[report.status] = errors[0]
    assert set(statuses) == {0, 1, 2}, statuses
