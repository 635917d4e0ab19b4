"""`sw2sim convert`: a MuJoCo model folder, in the Menagerie's layout, from a package."""

from __future__ import annotations

import shlex
from pathlib import Path

from .options import EXIT_ERRORS, EXIT_OK, EXIT_UNUSABLE, density, package_path, say, urdf_choice

HELP = """\
Writes a folder in the layout of the MuJoCo Menagerie's models:
  NAME.xml    the robot: bodies, joints, meshes, and actuators made from the
              package's transmissions and controller YAML
  scene.xml   includes NAME.xml and adds a floor, a light and a sky
  assets/     the mesh files, copied
  README.md   what came from where, and what was changed or dropped
The result needs plain MuJoCo only: python -m mujoco.viewer --mjcf=DIR/scene.xml

The package is checked first (as `sw2sim check`). Problems with exactly one right
answer are repaired in the written model, never in your package, and listed in
README.md under Repairs with the lasting fix: a mesh path that differs from its
file in capitals or slashes, the exporter's empty (all-zero) joint limits, an
effort of 0, an inertia that breaks A + B >= C by rounding, a placeholder
inertia no body of the link's mass could have. Problems that only
ROS's build tools care about (package.xml) are reported and do not stop it. Any
other error stops it: nothing is written, and the exit status is 1.

An existing non-empty DIR is refused unless --force is given; --force replaces
only the files convert writes and deletes nothing.

examples:
  sw2sim convert examples/example_5 -o example_5_mujoco
  sw2sim convert my_robot -o my_robot_mujoco --force
  sw2sim convert my_robot -o my_robot_mujoco --strict        # repair nothing
  sw2sim convert my_robot -o my_robot_mujoco --density 2700  # masses from the meshes
"""


def add_arguments(parser) -> None:
    package_path(parser)
    urdf_choice(parser)
    parser.add_argument("-o", "--output", metavar="DIR", required=True,
                        help="the folder to write (created if missing)")
    parser.add_argument("--force", action="store_true",
                        help="write into a non-empty DIR, replacing only convert's own files")
    parser.add_argument("--strict", action="store_true",
                        help="repair nothing: refuse the package on any error that affects the "
                             "simulation")
    parser.add_argument("--lock-default-limits", action="store_true",
                        help="lock joints whose limits are the exporter's empty ones (all 0) "
                             "instead of letting them move freely")
    parser.add_argument("--density", type=density, metavar="KG_PER_M3",
                        help="recompute zero or implausible masses and inertias from the "
                             "meshes, as solids of this density (aluminium 2700, steel 7850, "
                             "ABS 1050)")


def run(args) -> int:
    from ..check import PACKAGING, RULES, Options, check_package
    out = Path(args.output)
    if out.exists() and not out.is_dir():
        say(f"sw2sim convert: {out} is a file; give a folder to write the model into.")
        return EXIT_UNUSABLE
    if out.is_dir() and any(out.iterdir()) and not args.force:
        say(f"sw2sim convert: {out} is not empty, so nothing was written. Choose a new "
            "folder, or add --force to replace the files convert writes there (other files "
            "are left alone).")
        return EXIT_UNUSABLE
    options = Options(strict=args.strict, lock_default_limits=args.lock_default_limits,
                      density=args.density, command=_command(args))
    checked = check_package(args.path, options=options, urdf=args.urdf)
    report = checked.report
    if report.status == EXIT_UNUSABLE or report.simulation_stoppers:
        print(report.format())
        say("sw2sim convert: not converted; fix the errors above and run it again." + (
            "" if args.strict or not report.repaired else
            " (The problems marked \"Convert repairs it\" need nothing more.)"))
        masses = [f for f in report.simulation_stoppers
                  if "--density" in (RULES[f.rule].repair or "")]
        if masses and args.density is None and not args.strict:
            say(f"{len(masses)} of them are masses or inertias: "
                f"`{shlex.join([*_command(args), '--density', '2700'])}` (2700 kg/m^3: "
                "aluminium; give your material's) computes them from the meshes instead.")
        return report.status
    if report.findings:
        print(report.format())
    packaging = sum(f.severity == "error" and f.blocks == PACKAGING for f in report.findings)
    if packaging:
        print(f"{packaging} error(s) above matter only to ROS's build and package tools; "
              "MuJoCo does not read package.xml, so the model is converted anyway.")
    if report.repaired:
        print(f"{len(report.repaired)} problem(s) above are repaired in the written model "
              "(your package is unchanged); README.md lists them under Repairs, with the "
              "lasting fix for each.")
    return _write(checked, out, args.force)


def _command(args) -> tuple[str, ...]:
    """The command the user typed, as its options read it: what a fix suggesting one more
    flag repeats, with that flag added."""
    words = ["sw2sim", "convert", args.path, "-o", args.output]
    if args.urdf:
        words += ["--urdf", args.urdf]
    words += [flag for flag, given in (("--force", args.force),
                                       ("--lock-default-limits", args.lock_default_limits))
              if given]
    return tuple(words)


def _write(checked, out: Path, force: bool) -> int:
    from ..check.stability import mujoco_warnings
    from ..convert import OutputNotEmpty, convert
    from ..package import LoadError
    free = [r.unactuated for r in checked.repairs if r.unactuated]
    try:
        with mujoco_warnings():   # the check has reported them; no MUJOCO_LOG.TXT here
            result = convert(checked.repaired_package(), out, force=force,
                             repairs=checked.report.repaired, unactuated=free)
    except LoadError as exc:
        say(f"sw2sim convert: {exc}")
        return EXIT_ERRORS
    except OutputNotEmpty as exc:
        say(f"sw2sim convert: {exc}; nothing was written.")
        return EXIT_UNUSABLE
    except OSError as exc:
        say(f"sw2sim convert: cannot write into {out}: {exc.strerror or exc}")
        return EXIT_UNUSABLE
    if free:
        print(f"WARNING: {', '.join(free)} move(s) freely in the model, without limits and "
              "without an actuator: the package gives the exporter's empty limits (all 0). "
              "Enter the real limits in the exporter and export again, or convert with "
              "--lock-default-limits to lock them.")
    meshes = f" and {len(result.meshes)} mesh file(s) in assets/" if result.meshes else ""
    print(f"wrote {out}: {result.name}.xml, scene.xml, README.md{meshes}; "
          f"{len(result.actuators)} actuator(s)")
    print(f"open it with: python -m mujoco.viewer --mjcf={out / 'scene.xml'}")
    return EXIT_OK
