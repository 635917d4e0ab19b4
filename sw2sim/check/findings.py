"""Rules, findings and reports: the vocabulary every check speaks.

A *rule* is one kind of problem, written once with its symptom, cause and fix; the
troubleshooting page is generated from the same objects, so the page and the tool
cannot disagree. A *finding* is one occurrence of a rule in a user's package.
"""

from __future__ import annotations

import json
from dataclasses import asdict, dataclass, field

# Severities, from worst to mildest. "fatal": the input cannot be used at all (exit 2);
# "error": the model is wrong or will not load (exit 1); "warning": it loads, but look.
FATAL, ERROR, WARNING = "fatal", "error", "warning"
SEVERITIES = (FATAL, ERROR, WARNING)

# What a problem stands in the way of:
# - "simulation": the model is wrong or will not load; `convert` refuses the package;
# - "packaging": only ROS's build and package tools care (package.xml, package and folder
#   names); MuJoCo never reads them, so the package converts and the report lists them;
# - "advice": the model loads and runs; worth a look.
SIMULATION, PACKAGING, ADVICE = "simulation", "packaging", "advice"
BLOCKS = (SIMULATION, PACKAGING, ADVICE)
BLOCKS_SAYS = {SIMULATION: "stops the simulation", PACKAGING: "ROS packaging only",
               ADVICE: "advice"}

# Groups, in the order the troubleshooting page lists them.
GROUPS = {
    "input": "The file itself",
    "structure": "URDF structure",
    "package": "package.xml and names",
    "mesh": "Meshes",
    "inertia": "Mass and inertia",
    "joint": "Joints and limits",
    "collision": "Collisions",
    "simulation": "The stability run",
}


@dataclass(frozen=True)
class Rule:
    id: str          # kebab-case, stable: users search for it, the page anchors on it
    severity: str
    group: str       # a key of GROUPS
    title: str       # what is wrong, one line
    symptom: str     # what the user sees (in MuJoCo, Gazebo or the exporter)
    cause: str       # why it happens
    fix: str         # what to do, in SolidWorks or in the files
    seen_in: tuple[str, ...] = ()  # public reports, e.g. "solidworks_urdf_exporter#88"
    blocks: str = SIMULATION       # one of BLOCKS
    repair: str | None = None      # what `convert` does about it, when it has one right answer


RULES: dict[str, Rule] = {}


def rule(id: str, severity: str, group: str, title: str, *, symptom: str, cause: str,
         fix: str, seen_in: tuple[str, ...] = (), blocks: str | None = None,
         repair: str | None = None) -> Rule:
    """Register a rule (at import time of the module that checks it) and return it.

    What it blocks defaults to: "packaging" for the package group, "advice" for a
    warning, "simulation" for an error or a fatal problem. `repair` says what `sw2sim
    convert` does about the problem where it has exactly one right answer (the rule's check
    then hands each finding its `sw2sim.check.repairs.Repair`).
    """
    if id in RULES:
        raise ValueError(f"rule {id!r} registered twice")
    if severity not in SEVERITIES:
        raise ValueError(f"rule {id!r}: severity must be one of {SEVERITIES}")
    if group not in GROUPS:
        raise ValueError(f"rule {id!r}: group must be one of {tuple(GROUPS)}")
    if blocks is None:
        blocks = PACKAGING if group == "package" else ADVICE if severity == WARNING else SIMULATION
    if blocks not in BLOCKS:
        raise ValueError(f"rule {id!r}: blocks must be one of {BLOCKS}")
    if blocks == PACKAGING and severity == FATAL:
        raise ValueError(f"rule {id!r}: a problem of packaging alone cannot be fatal")
    if repair is not None and severity == FATAL:
        raise ValueError(f"rule {id!r}: a fatal problem leaves nothing to repair")
    RULES[id] = Rule(id, severity, group, title, symptom, cause, fix, tuple(seen_in), blocks,
                     repair)
    return RULES[id]


@dataclass(frozen=True)
class Finding:
    rule: str
    severity: str
    message: str               # what is wrong here, with the names and numbers involved
    fix: str                   # how to fix it here (defaults to the rule's fix)
    file: str | None = None
    line: int | None = None
    blocks: str = SIMULATION   # the rule's: what the problem stands in the way of
    repair: str | None = None  # what `convert` does about it here, and what it assumes

    @property
    def where(self) -> str:
        if self.file is None:
            return "-"
        return f"{self.file}:{self.line}" if self.line else self.file

    @property
    def stops_simulation(self) -> bool:
        """Whether `convert` refuses the package for it: an error that makes the model
        wrong or unloadable, and that convert cannot repair."""
        return (self.blocks == SIMULATION and self.severity in (FATAL, ERROR)
                and self.repair is None)

    @property
    def says(self) -> str:
        """What is wrong here and what to do: the line's text after the place, severity and
        rule (which the CI formats, sarif.py and workflow_commands.py, carry apart)."""
        text = f"{self.message}. Fix: {self.fix}"
        if self.repair:
            text = f"{text.rstrip('.')}. Convert repairs it: {self.repair}."
        return text

    def format(self) -> str:
        kind = self.severity if self.blocks == SIMULATION or self.severity == WARNING \
            else f"{self.severity} ({BLOCKS_SAYS[self.blocks]})"
        return f"{self.where}: {kind} [{self.rule}] {self.says}"


@dataclass
class Report:
    """Everything one check found about one package."""

    path: str
    findings: list[Finding] = field(default_factory=list)
    stability: dict | None = None   # figures from the stability run, when it ran

    @property
    def status(self) -> int:
        """The exit status: 2 the input cannot be used, 1 errors, 0 none (warnings allowed)."""
        severities = {f.severity for f in self.findings}
        if FATAL in severities:
            return 2
        return 1 if ERROR in severities else 0

    @property
    def simulation_stoppers(self) -> list[Finding]:
        """The findings that stop a conversion: errors that make the model wrong or
        unloadable and have no repair (problems of ROS packaging alone do not)."""
        return [f for f in self.findings if f.stops_simulation]

    @property
    def repaired(self) -> list[Finding]:
        """The findings `convert` repairs in its copy of the model."""
        return [f for f in self.findings if f.repair]

    def count(self, severity: str) -> int:
        return sum(f.severity == severity for f in self.findings)

    def rules(self) -> set[str]:
        return {f.rule for f in self.findings}

    def format(self) -> str:
        lines = [f.format() for f in self.findings]
        errors = self.count(FATAL) + self.count(ERROR)
        summary = f"{self.path}: {errors} error(s), {self.count(WARNING)} warning(s)"
        if self.stability is not None:
            summary += f"; stability run: {self.stability.get('summary', 'done')}"
        return "\n".join([*lines, summary])

    def to_json(self) -> str:
        return json.dumps({"path": self.path, "status": self.status,
                           "findings": [asdict(f) for f in self.findings],
                           "stability": self.stability}, indent=2)
