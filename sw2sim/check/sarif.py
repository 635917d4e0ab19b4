"""Reports as SARIF 2.1.0 (`sw2sim check --format sarif`), the format of static analysis
results that GitHub code scanning and other CI dashboards read.

One run of the tool is one SARIF run, whatever the number of packages: its driver lists
every rule of the registry (the one _data/check_rules.json and the Troubleshooting page
are made from), each result names its rule, level, message and the file and line, and
the run's properties keep each package's path, exit status and stability figures.
Locations are relative URIs, from the working folder (a workflow's repository root),
which is how code scanning ties a result to a file.
"""

from __future__ import annotations

import os
from pathlib import Path
from urllib.parse import quote

from .findings import WARNING, Finding, Report, Rule

SCHEMA = ("https://docs.oasis-open.org/sarif/sarif/v2.1.0/errata01/os/schemas/"
          "sarif-schema-2.1.0.json")
VERSION = "2.1.0"


def level(severity: str) -> str:
    """SARIF's level for a severity: it has no "fatal", and an unusable input is an error."""
    return "warning" if severity == WARNING else "error"


def log(reports: list[Report], rules: dict[str, Rule], tool_version: str) -> dict:
    """The SARIF log of one `sw2sim check` of `reports`, with the registry's `rules` (in
    troubleshooting-page order)."""
    index = {rule_id: i for i, rule_id in enumerate(rules)}
    results = [_result(f, index) for report in reports for f in report.findings]
    status = max((r.status for r in reports), default=0)
    return {
        "$schema": SCHEMA,
        "version": VERSION,
        "runs": [{
            "tool": {"driver": {"name": "sw2sim", "version": tool_version,
                                "rules": [_descriptor(rule) for rule in rules.values()]}},
            "invocations": [{"executionSuccessful": True, "exitCode": status}],
            "results": results,
            "properties": {"packages": [{"path": r.path, "status": r.status,
                                         "stability": r.stability} for r in reports]},
        }],
    }


def _descriptor(rule: Rule) -> dict:
    help_text = (f"Symptom: {rule.symptom}\nCause: {rule.cause}\nFix: {rule.fix}"
                 + (f"\nConvert repairs it: {rule.repair}" if rule.repair else ""))
    return {"id": rule.id,
            "shortDescription": {"text": rule.title},
            "fullDescription": {"text": rule.cause},
            "help": {"text": help_text},
            "defaultConfiguration": {"level": level(rule.severity)},
            "properties": {"severity": rule.severity, "group": rule.group,
                           "blocks": rule.blocks, "seenIn": list(rule.seen_in),
                           # unique, as the schema wants: a rule of the "simulation" group
                           # also stands in the way of the simulation
                           "tags": list(dict.fromkeys((rule.group, rule.blocks)))}}


def _result(finding: Finding, index: dict[str, int]) -> dict:
    result = {"ruleId": finding.rule, "level": level(finding.severity),
              "message": {"text": finding.says},
              "properties": {"severity": finding.severity, "blocks": finding.blocks,
                             "fix": finding.fix, "repair": finding.repair}}
    if finding.rule in index:
        result["ruleIndex"] = index[finding.rule]
    if finding.file:
        location: dict = {"artifactLocation": {"uri": uri(finding.file)}}
        if finding.line:
            location["region"] = {"startLine": finding.line}
        result["locations"] = [{"physicalLocation": location}]
    return result


def uri(path: str) -> str:
    """A report's path as a URI reference: relative ones stay relative, with /."""
    if os.path.isabs(path):
        return Path(path).as_uri()
    return quote(path.replace(os.sep, "/"), safe="/")
