"""`sw2sim check --format github` and `--format sarif`: the findings where a CI shows them.

The SARIF is validated against the published SARIF 2.1.0 JSON schema, kept here as
sarif-2.1.0.json: the OASIS standard's schema with its errata 01, as the OASIS SARIF
technical committee's repository (github.com/oasis-tcs/sarif-spec,
sarif-2.1/schema/sarif-schema-2.1.0.json) holds it, so the test runs offline.
"""

from __future__ import annotations

import json
import re
from pathlib import Path

import jsonschema
import pytest
from packages import copy_example

from sw2sim.check import all_rules, check
from sw2sim.check.findings import Finding
from sw2sim.check.workflow_commands import command
from sw2sim.cli import main

ROOT = Path(__file__).resolve().parents[3]
SCHEMA = json.loads((Path(__file__).parent / "sarif-2.1.0.json").read_text())
COMMAND = re.compile(r"::(error|warning) (?:file=([^,:]+)(?:,line=(\d+))?,)?title=([a-z0-9-]+)"
                     r"::(.+)")


@pytest.fixture
def two_packages(tmp_path, monkeypatch):
    """A class's folder: one clean export, one raw export with errors; the working folder
    is the class's, as a workflow's is the repository's root."""
    copy_example(4, tmp_path / "exports", "alice")
    broken = tmp_path / "exports" / "bob"
    copy_example(3, tmp_path / "exports", "bob")
    (broken / "meshes" / "end_arm_link.STL").write_bytes(b"\0" * 80)   # a header, no triangle
    monkeypatch.chdir(tmp_path)
    return ["exports/alice", "exports/bob"]


def _run(capsys, *args) -> tuple[int, str]:
    status = main(["check", *args])
    out = capsys.readouterr()
    assert out.err == ""
    return status, out.out


def test_github_prints_one_workflow_command_per_finding(two_packages, capsys):
    findings = [f for path in two_packages for f in check(path, stability=False).findings]
    status, out = _run(capsys, *two_packages, "--no-sim", "--format", "github")
    assert status == 1
    commands = [line for line in out.splitlines() if line.startswith("::")]
    assert len(commands) == len(findings) and any(f.severity == "error" for f in findings)
    for line, finding in zip(commands, findings):
        kind, file, number, rule, message = COMMAND.fullmatch(line).groups()
        assert kind == ("warning" if finding.severity == "warning" else "error")
        assert rule == finding.rule and message.startswith(finding.message)
        assert file == finding.file and not Path(file).is_absolute() and Path(file).is_file()
        assert number == (str(finding.line) if finding.line else None)
    assert "mesh-empty" in {COMMAND.fullmatch(c).group(4) for c in commands}
    # Anything else is the summaries, which the log shows as text.
    assert [line for line in out.splitlines() if not line.startswith("::")][-1].startswith(
        "2 packages checked: 1 without errors, 1 with errors")


def test_github_escapes_what_would_break_a_command():
    finding = Finding(rule="mesh-not-found", severity="error", message="100% of\nit",
                      fix="see a, b: c", file="odd, name: here.urdf", line=3)
    line = command(finding)
    assert line == ("::error file=odd%2C name%3A here.urdf,line=3,title=mesh-not-found::"
                    "100%25 of%0Ait. Fix: see a, b: c")


def test_github_says_what_a_packaging_error_stands_in_the_way_of():
    finding = Finding(rule="package-format-missing", severity="error", message="m", fix="f",
                      file="package.xml", blocks="packaging")
    assert command(finding).endswith("::ROS packaging only: m. Fix: f")


def test_an_input_that_cannot_be_used_is_an_error_command(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    status, out = _run(capsys, "nothing_here", "--format", "github")
    assert status == 2
    assert out.splitlines()[0].startswith("::error file=nothing_here,title=input-missing::")


def test_json_stays_as_it_was_and_is_also_format_json(two_packages, capsys):
    _, plain = _run(capsys, *two_packages, "--no-sim", "--json")
    _, named = _run(capsys, *two_packages, "--no-sim", "--format", "json")
    assert plain == named and [r["path"] for r in json.loads(plain)] == two_packages


def test_json_and_another_format_together_are_refused(two_packages, capsys):
    assert main(["check", two_packages[0], "--json", "--format", "sarif"]) == 2
    assert "--json and --format sarif" in capsys.readouterr().err


def _sarif(capsys, *args) -> tuple[int, dict]:
    status, out = _run(capsys, *args, "--format", "sarif")
    return status, json.loads(out)


def test_sarif_is_valid_sarif_2_1_0(two_packages, capsys):
    _, log = _sarif(capsys, *two_packages, "--no-sim")
    jsonschema.Draft4Validator.check_schema(SCHEMA)
    errors = [f"{list(e.absolute_path)}: {e.message}"
              for e in jsonschema.Draft4Validator(SCHEMA).iter_errors(log)]
    assert not errors, errors
    # and the schema is strict enough to tell: a wrong version, a level it does not know
    log["runs"][0]["results"][0]["level"] = "fatal"
    assert not jsonschema.Draft4Validator(SCHEMA).is_valid(log)


def test_sarif_lists_the_troubleshooting_pages_rules(two_packages, capsys):
    _, log = _sarif(capsys, two_packages[0], "--no-sim")
    driver = log["runs"][0]["tool"]["driver"]
    page = json.loads((ROOT / "_data" / "check_rules.json").read_text())
    assert [r["id"] for r in driver["rules"]] == [r["id"] for g in page["groups"]
                                                  for r in g["rules"]]
    rules = all_rules()
    for descriptor in driver["rules"]:
        rule = rules[descriptor["id"]]
        assert descriptor["shortDescription"]["text"] == rule.title
        assert descriptor["defaultConfiguration"]["level"] == (
            "warning" if rule.severity == "warning" else "error")
        assert rule.fix in descriptor["help"]["text"]


def test_sarif_results_are_the_findings(two_packages, capsys):
    status, log = _sarif(capsys, *two_packages, "--no-sim")
    findings = [f for path in two_packages for f in check(path, stability=False).findings]
    run = log["runs"][0]
    assert len(run["results"]) == len(findings) and status == 1
    assert run["invocations"][0]["exitCode"] == 1
    for result, finding in zip(run["results"], findings):
        assert result["ruleId"] == finding.rule
        assert run["tool"]["driver"]["rules"][result["ruleIndex"]]["id"] == finding.rule
        assert result["level"] == ("warning" if finding.severity == "warning" else "error")
        assert result["message"]["text"].startswith(finding.message)
        location = result["locations"][0]["physicalLocation"]
        assert location["artifactLocation"]["uri"] == finding.file
        assert location.get("region", {}).get("startLine") == finding.line
    assert [p["path"] for p in run["properties"]["packages"]] == two_packages


def test_sarif_of_an_unusable_input(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    status, log = _sarif(capsys, "no such folder")
    (result,) = log["runs"][0]["results"]
    assert status == 2 and log["runs"][0]["invocations"][0]["exitCode"] == 2
    assert result["ruleId"] == "input-missing" and result["level"] == "error"
    assert result["locations"][0]["physicalLocation"]["artifactLocation"]["uri"] == \
        "no%20such%20folder"
    assert jsonschema.Draft4Validator(SCHEMA).is_valid(log)
