"""The Troubleshooting page's data, written from the rule registry.

    python -m course.troubleshooting           # rewrite _data/check_rules.json
    python -m course.troubleshooting --check   # exit 1 if it is out of date

The page (_pages/reference/troubleshooting.md) lists these entries with Liquid, so the
page and `sw2sim check` read the same words; a test fails when the file is stale.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

from sw2sim.check import GROUPS, all_rules
from sw2sim.check.findings import BLOCKS_SAYS

from . import ROOT

DATA = ROOT / "_data" / "check_rules.json"

# Public reports cited in a rule's seen_in, by the short name used there.
REPOSITORIES = {
    "solidworks_urdf_exporter": "https://github.com/ros/solidworks_urdf_exporter",
    "mujoco": "https://github.com/google-deepmind/mujoco",
    "mujoco_menagerie": "https://github.com/google-deepmind/mujoco_menagerie",
    "onshape-to-robot": "https://github.com/Rhoban/onshape-to-robot",
}


def _link(report: str) -> dict:
    repo, _, number = report.partition("#")
    base = REPOSITORIES.get(repo)
    url = f"{base}/issues/{number}" if base and number.isdigit() else None
    return {"text": report, "url": url}


def _html(text: str) -> str:
    # Rendered here, with raw HTML off, so that `<inertial>` in a rule's words shows as
    # text on the page instead of becoming a tag.
    from markdown_it import MarkdownIt
    return MarkdownIt("commonmark", {"html": False}).renderInline(text)


def _sentence(text: str) -> str:
    """A rule's repair, which reads on from "convert repairs it:", as a sentence."""
    return text[0].upper() + text[1:]


def rules_data() -> dict:
    """The registry as plain data: groups in page order, each with its rules."""
    groups = []
    for group, title in GROUPS.items():
        entries = [{"id": r.id, "severity": r.severity, "blocks": r.blocks,
                    "blocks_says": BLOCKS_SAYS[r.blocks], "title": _html(r.title),
                    "symptom": _html(r.symptom), "cause": _html(r.cause), "fix": _html(r.fix),
                    "repair": _html(_sentence(r.repair)) if r.repair else None,
                    "seen_in": [_link(s) for s in r.seen_in]}
                   for r in all_rules().values() if r.group == group]
        if entries:
            groups.append({"id": group, "title": title, "rules": entries})
    return {"generated_by": "python -m course.troubleshooting",
            "count": sum(len(g["rules"]) for g in groups), "groups": groups}


def render() -> str:
    return json.dumps(rules_data(), indent=2, ensure_ascii=False) + "\n"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m course.troubleshooting",
                                     description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true",
                        help="only report whether the data file is up to date")
    args = parser.parse_args(argv)
    text = render()
    current = DATA.read_text(encoding="utf-8") if DATA.is_file() else None
    if args.check:
        if current != text:
            print(f"{DATA} is out of date; run `python -m course.troubleshooting`",
                  file=sys.stderr)
            return 1
        return 0
    if current != text:
        DATA.write_text(text, encoding="utf-8")
        print(f"wrote {DATA} ({rules_data()['count']} rules)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
