"""`sw2sim check` against the reference URDF parsers, on the peer suites' cases.

peer_cases/*.urdf restate what the test suites of urdfdom, urdf_parser_py and yourdfpy
give their parsers (and the cases where sw2sim once disagreed with check_urdf);
peer_cases/verdicts.json records what each parser says of each (peer_verdicts.py writes
it). sw2sim refuses exactly what check_urdf refuses, except where MuJoCo has its own
opinion: there the case names the rules that refuse it, and each rule's text says what
check_urdf does instead, so that a student who runs both is told why they differ.
"""

from __future__ import annotations

import json
import shutil

import pytest

from peer_verdicts import (ACCEPTS, CASES, REFUSES, TABLE, check_urdf, sw2sim_errors,
                           urdf_parser_py, verdict, yourdfpy)
from sw2sim.check import all_rules

RECORDED = json.loads(TABLE.read_text())["cases"]
NAMES = sorted(RECORDED)


def _case(name: str):
    return CASES / f"{name}.urdf", RECORDED[name]


def test_the_table_holds_every_case_file_and_no_other():
    assert sorted(p.stem for p in CASES.glob("*.urdf")) == NAMES


def test_the_cases_come_from_each_peer_suite_and_both_verdicts_occur():
    sources = " ".join(source for case in RECORDED.values() for source in case["from"])
    for suite in ("urdfdom", "urdf_parser_py", "yourdfpy"):
        assert suite in sources, f"no case from {suite}'s tests"
    assert {c["check_urdf"]["verdict"] for c in RECORDED.values()} == {ACCEPTS, REFUSES}


@pytest.mark.parametrize("name", NAMES)
def test_sw2sim_refuses_what_check_urdf_refuses_or_says_why_not(name):
    path, case = _case(name)
    errors = sw2sim_errors(path)
    assert errors == case["sw2sim"]["errors"], \
        f"{name}: the table is stale; rewrite it with tests/tool/check/peer_verdicts.py"
    theirs = case["check_urdf"]["verdict"]
    if verdict(errors) == theirs:
        assert not case["differs"], f"{name}: marked as differing, but sw2sim agrees"
        return
    # sw2sim never accepts what ROS's own parser refuses.
    assert theirs == ACCEPTS, f"{name}: check_urdf refuses it ({case['check_urdf']['says']}), " \
                              "sw2sim finds no error"
    assert case["differs"] and set(case["differs"]) == set(errors), \
        f"{name}: sw2sim refuses it with {errors}, check_urdf accepts it; name the rules in " \
        "the case's \"differs\""
    rules = all_rules()
    for rule_id in case["differs"]:
        text = f"{rules[rule_id].symptom} {rules[rule_id].cause}"
        assert "check_urdf" in text, \
            f"{rule_id}: its symptom or cause must say what check_urdf does with {name}"


@pytest.mark.skipif(shutil.which("check_urdf") is None, reason="urdfdom's check_urdf is not "
                    "installed (Debian: liburdfdom-tools, in the Makefile's packages)")
@pytest.mark.parametrize("name", NAMES)
def test_check_urdf_says_what_the_table_records(name):
    path, case = _case(name)
    assert check_urdf(path) == case["check_urdf"]


@pytest.mark.parametrize("name", NAMES)
def test_yourdfpy_says_what_the_table_records(name):
    path, case = _case(name)
    assert yourdfpy(path)["verdict"] == case["yourdfpy"]["verdict"]


@pytest.mark.parametrize("name", NAMES)
def test_urdf_parser_py_says_what_the_table_records(name):
    path, case = _case(name)
    said = urdf_parser_py(path)
    assert said is not None, "urdf_parser_py is not installed: `make setup` installs it " \
                             "(requirements.txt), pip users get it with the test extra"
    assert said["verdict"] == case["urdf_parser_py"]["verdict"]
