"""`sw2sim compare`: a reader's export against the lesson's package, link by link."""

from __future__ import annotations

HELP = """\
Compares your export of a lesson's model (MINE) with the lesson's package
(REFERENCE, examples/example_N), link by link and joint by joint: the link tree,
joint types, origins, axes and limits, and each link's mass, centre of mass,
inertia and mesh size. Links are matched by name, or by their place in the tree
where the names differ (which is reported). Directions are the model's: the axes
of the base link's frame. A mesh with no triangles or no volume, a number off by
a unit's factor (millimetres, centimetres, degrees, or the decimal point) and an
inertia taken about the link's origin instead of its centre of mass are named so.

A correct SolidWorks model matches within: mass 1 %, inertia 2 % (the lesson's
masses come from faceted meshes, SolidWorks' from the exact solid), 1 mm and
0.5 degrees. Each difference is one line:
  FILE:LINE: [CODE] joint or link: yours, the reference's (by how much). Cause and fix
Packages of two different robots are not compared: when under half of the links
are alike (by name, or by place and joint type), or when MINE agrees (place and
mass) with another lesson's package in examples/ in at least half of its links
and with REFERENCE in fewer, the message says it looks like another lesson's
package and names the one it resembles most.
Exit status: 0 the export matches, 1 it differs, 2 nothing was compared (a
package cannot be read, or it looks like another lesson's package).

examples:
  sw2sim compare my_export examples/example_1
  sw2sim compare my_arm/urdf/my_arm.urdf examples/example_3 --json
"""


def add_arguments(parser) -> None:
    parser.add_argument("mine", metavar="MINE", help="your package folder, .urdf file or .zip")
    parser.add_argument("reference", metavar="REFERENCE", help="the lesson's package folder "
                        "(examples/example_N) or .urdf file")
    parser.add_argument("--urdf", metavar="NAME", help="which URDF of MINE to read, where it "
                        "holds several (its file name)")
    parser.add_argument("--reference-urdf", metavar="NAME", help="the same for REFERENCE")
    parser.add_argument("--json", action="store_true", help="print the differences as JSON")


def run(args) -> int:
    from ..compare import compare
    from .options import say
    result = compare(args.mine, args.reference, urdf=args.urdf,
                     reference_urdf=args.reference_urdf)
    if result.error and not args.json:
        say(result.format())
    else:
        print(result.to_json() if args.json else result.format())
    return result.status
