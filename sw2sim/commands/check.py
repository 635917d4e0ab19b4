"""`sw2sim check`: what is wrong with one or more packages, with the fix for each."""

from __future__ import annotations

from .options import EXIT_UNUSABLE, say, urdf_choice, version

FORMATS = ("text", "json", "github", "sarif")

HELP = """\
Reads the package as ROS, Gazebo and MuJoCo would: the XML, package.xml, the
meshes, masses and inertias, joints and limits, collisions. Then, unless --no-sim
is given, it simulates the model for 4 s (2 s at rest, 2 s with small random
inputs) to catch a model that blows up or flies apart. The base is fixed when the
URDF joins it to a link named `world`, free otherwise, as in Gazebo.

Each finding is one line:
  FILE:LINE: SEVERITY [RULE-ID] what is wrong. Fix: what to do
ending with "Convert repairs it: ..." where `sw2sim convert` would repair it in
the model it writes, followed by a summary. Exit status: 0 no errors (warnings allowed), 1 errors,
2 the input cannot be used (missing path, not XML, not a URDF).

Several PATHs are checked one after the other, each with its own summary, then a
line for them all; the exit status is the worst of theirs, and --json prints a list.

For CI, --format github prints each finding as a GitHub Actions workflow command
(::error file=FILE,line=LINE,title=RULE-ID::what is wrong. Fix: ...; warnings as
::warning), which a workflow shows as annotations on the files, and --format sarif
prints SARIF 2.1.0, the format code scanning reads. Their paths are relative to the
working folder: run it from the repository's root.

examples:
  sw2sim check examples/example_4
  sw2sim check my_robot --no-sim
  sw2sim check my_robot --json | python -m json.tool
  sw2sim check submissions/*.zip --no-sim
  sw2sim check exports/* --format github       # in a GitHub Actions step
  sw2sim check exports/* --format sarif > sw2sim.sarif
"""


def add_arguments(parser) -> None:
    parser.add_argument("path", metavar="PATH", nargs="+",
                        help="package folder, .urdf file or .zip of the package (several: each "
                             "is checked in turn)")
    urdf_choice(parser)
    parser.add_argument("--json", action="store_true", help="print the report as JSON "
                        "(the same as --format json)")
    parser.add_argument("--format", choices=FORMATS, help="how to print the findings: text "
                        "(the default), json, github (GitHub Actions workflow commands) or "
                        "sarif (SARIF 2.1.0)")
    parser.add_argument("--no-sim", action="store_true", help="skip the 4 s stability run")


def run(args) -> int:
    from .. import archive
    from ..check import check
    from ..check.workflow_commands import commands
    if args.urdf and len(args.path) > 1:
        say("sw2sim check: --urdf picks a URDF of one package; give one PATH with it")
        return EXIT_UNUSABLE
    if args.json and args.format not in (None, "json"):
        say(f"sw2sim check: --json and --format {args.format} ask for two formats; give one")
        return EXIT_UNUSABLE
    form = "json" if args.json else args.format or "text"
    reports = []
    for path in args.path:
        reports.append(check(path, stability=not args.no_sim, urdf=args.urdf))
        archive.discard()   # a class's worth of zips needs no disk for all of them at once
        if form in ("text", "github"):   # as each package is done: a class takes minutes
            shown = reports[-1].format() if form == "text" else commands(reports[-1])
            print(("\n" if len(reports) > 1 and form == "text" else "") + shown, flush=True)
    if form == "json":
        print(reports[0].to_json() if len(reports) == 1 else
              "[\n" + ",\n".join(r.to_json() for r in reports) + "\n]")
    elif form == "sarif":
        print(_sarif(reports))
    elif len(reports) > 1:
        print(("\n" if form == "text" else "") + _checked(reports))
    return max(r.status for r in reports)


def _sarif(reports) -> str:
    import json
    from ..check import all_rules
    from ..check.sarif import log
    return json.dumps(log(reports, all_rules(), version()), indent=2)


def _checked(reports) -> str:
    """The line that sums up the check of several packages."""
    counts = {status: sum(r.status == status for r in reports) for status in (0, 1, 2)}
    return (f"{len(reports)} packages checked: {counts[0]} without errors, {counts[1]} with "
            f"errors, {counts[2]} that could not be used")
