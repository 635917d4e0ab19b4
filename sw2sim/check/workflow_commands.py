"""Findings as GitHub Actions workflow commands (`sw2sim check --format github`).

A workflow step that prints

    ::error file=urdf/arm.urdf,line=12,title=limit-missing::revolute joint "elbow" has ...

gets an annotation on that file and line: in the run's summary, and on a pull request's
changed lines. So a course repository whose workflow checks every student's export shows
each finding where the class already looks, without a tool of its own. Errors (and
inputs that cannot be used at all) are ::error, warnings ::warning.

File paths are the report's: relative to the working folder, where a workflow runs from
the repository's root, which is what GitHub matches them against. Values are escaped as
GitHub's own toolkit (@actions/core) escapes them: `%`, CR and LF everywhere, and `:` and
`,` in the properties too, since they separate them.
"""

from __future__ import annotations

import os

from .findings import BLOCKS_SAYS, SIMULATION, WARNING, Finding, Report


def escape_data(text: str) -> str:
    return text.replace("%", "%25").replace("\r", "%0D").replace("\n", "%0A")


def escape_property(text: str) -> str:
    return escape_data(text).replace(":", "%3A").replace(",", "%2C")


def said(finding: Finding) -> str:
    """What a finding says (the command carries its file, line and rule as properties),
    after what it stands in the way of where the text report says it in its severity."""
    if finding.blocks != SIMULATION and finding.severity != WARNING:
        return f"{BLOCKS_SAYS[finding.blocks]}: {finding.says}"   # "ROS packaging only: ..."
    return finding.says


def command(finding: Finding) -> str:
    """One finding as one workflow command."""
    kind = "warning" if finding.severity == WARNING else "error"
    properties = []
    if finding.file:
        properties.append(f"file={escape_property(posix(finding.file))}")
        if finding.line:
            properties.append(f"line={finding.line}")
    properties.append(f"title={escape_property(finding.rule)}")
    return f"::{kind} {','.join(properties)}::{escape_data(said(finding))}"


def commands(report: Report) -> str:
    """A report as workflow commands, one per finding, then its summary as plain text (a
    line the log shows as it is)."""
    lines = [command(f) for f in report.findings]
    return "\n".join([*lines, report.format().splitlines()[-1]])


def posix(path: str) -> str:
    """A path with / between folders, as GitHub names a repository's files (a Windows
    runner's report has \\)."""
    return path.replace(os.sep, "/")
