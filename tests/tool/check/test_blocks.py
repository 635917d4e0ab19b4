"""Every finding says what it stands in the way of: the simulation, ROS packaging alone, or
nothing (advice). `check` lists them all; `convert` refuses only what stops the simulation,
so a package whose only problems are ROS packaging, such as every package written by
the exporter's 1.4 releases (package.xml without format="2"), converts."""

import json

import pytest

from packages import copy_example, edit
from sw2sim import cli
from sw2sim.check import (ADVICE, BLOCKS, ERROR, PACKAGING, SIMULATION, WARNING, all_rules,
                          check)
from sw2sim.check.findings import rule


def exporter_1_5(folder):
    """A package as exporter 1.4 wrote it: package.xml uses <depend> without format="2"."""
    package = copy_example(1, folder)
    edit(package / "package.xml", '<package format="2">', "<package>")
    return package


def test_every_rule_says_what_it_blocks():
    rules = all_rules()
    assert {r.blocks for r in rules.values()} == set(BLOCKS)
    for r in rules.values():
        if r.severity == WARNING:   # a model with warnings loads and runs
            assert r.blocks in (ADVICE, PACKAGING), r.id
    packaging = {r.id for r in rules.values() if r.blocks == PACKAGING}
    assert {"package-format-missing", "package-name-invalid", "package-xml-invalid"} <= packaging
    # A mesh path naming another package stops the meshes from loading: not packaging alone.
    assert rules["package-name-mismatch"].blocks == SIMULATION


def test_a_rule_of_packaging_alone_cannot_be_fatal_or_unknown():
    with pytest.raises(ValueError, match="cannot be fatal"):
        rule("test-packaging-fatal", "fatal", "package", "x", symptom="", cause="", fix="",
             blocks=PACKAGING)
    with pytest.raises(ValueError, match="blocks must be one of"):
        rule("test-blocks-unknown", ERROR, "package", "x", symptom="", cause="", fix="",
             blocks="ros")


def test_check_lists_the_packaging_error_and_still_runs_the_simulation(tmp_path):
    report = check(exporter_1_5(tmp_path))
    [finding] = [f for f in report.findings if f.rule == "package-format-missing"]
    assert finding.severity == ERROR and finding.blocks == PACKAGING
    assert "(ROS packaging only)" in finding.format()
    assert report.status == 1 and not report.simulation_stoppers
    assert report.stability is not None, "the stability run was left out"
    listed = json.loads(report.to_json())["findings"]
    assert {f["rule"]: f["blocks"] for f in listed}["package-format-missing"] == PACKAGING


def test_a_package_from_exporter_1_5_converts_and_its_report_says_why(tmp_path, capsys):
    status = cli.main(["convert", str(exporter_1_5(tmp_path)), "-o", str(tmp_path / "model")])
    out, err = capsys.readouterr()
    assert status == 0, out + err
    assert "[package-format-missing]" in out
    assert "matter only to ROS" in out and "converted anyway" in out
    assert (tmp_path / "model" / "scene.xml").is_file()


def test_convert_still_refuses_what_stops_the_simulation(tmp_path, capsys):
    package = exporter_1_5(tmp_path)
    (package / "meshes" / "base_link.STL").unlink()
    status = cli.main(["convert", str(package), "-o", str(tmp_path / "model")])
    out, err = capsys.readouterr()
    assert status == 1 and "[mesh-not-found]" in out and "not converted" in err
    assert not (tmp_path / "model").exists()
