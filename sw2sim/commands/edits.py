"""`sw2sim edits`: keep a package's hand edits across a re-export (save, then restore)."""

from __future__ import annotations

from pathlib import Path

from .options import EXIT_ERRORS, EXIT_OK, EXIT_UNUSABLE, say

HELP = """\
Both of the exporter's buttons rewrite the URDF and its CSV, package.xml,
CMakeLists.txt, config/joint_names_NAME.yaml and the two launch files, so exporting
again wipes what was added to them by hand. Keep the hand edits across a re-export:

  save     copies those files into PKG/hand_edits/ (with a manifest and a README),
           a folder the exporter never writes. Run it after each hand edit.
  restore  after the re-export: puts the saved package.xml, CMakeLists.txt, launch
           files and joint-names YAML back, and carries into the new URDF what the
           exporter never writes (transmissions, <gazebo> elements, a `world` link and
           its joint, joints' <dynamics>, links' colours), keeping the new numbers.
           Each restored item is one line; what it does not carry is named. A file
           changed more than a minute after the new URDF was written is not
           overwritten (--force does), and joints that are gone or new are named.

Exit status: 0 done, 1 restore refused (a file edited since the re-export) or save
refused (the saved copy has hand edits the URDF lacks: restore first), 2 nothing
saved, or the package cannot be read.

examples:
  sw2sim edits save examples/example_1
  sw2sim edits restore examples/example_1
"""


def add_arguments(parser) -> None:
    parser.add_argument("action", choices=("save", "restore"),
                        help="save before exporting again, restore after")
    parser.add_argument("path", metavar="PKG", help="the package folder")
    parser.add_argument("--force", action="store_true", help="save over a copy with more hand "
                        "edits, or restore over files edited since the re-export")


def run(args) -> int:
    from .. import edits
    from ..package import LoadError
    where = args.path
    saved = Path(where) / edits.FOLDER
    try:
        if args.action == "save":
            files = edits.save(args.path, force=args.force)
            print(f"saved {len(files)} file(s) in {saved}: {', '.join(files)}")
            return EXIT_OK
        result = edits.restore(args.path, force=args.force)
    except LoadError as exc:
        say(f"sw2sim edits: {exc}")
        return EXIT_UNUSABLE
    except edits.NothingSaved as exc:
        say(f"sw2sim edits restore: nothing saved ({exc}). Run `sw2sim edits save {where}` "
            "before re-exporting; the hand edits a re-export removed must now be made again.")
        return EXIT_UNUSABLE
    except edits.WouldLoseEdits as exc:
        say(f"sw2sim edits save: the saved copy in {saved} has hand edits the URDF lacks "
            f"({exc}): after a re-export, run `sw2sim edits restore {where}` first. If you "
            "removed them on purpose, add --force.")
        return EXIT_ERRORS
    except edits.EditedSince as exc:
        say(f"sw2sim edits restore: nothing restored: {exc} changed after the re-export (more "
            "than a minute after the URDF), and restoring would overwrite that. Copy what you "
            f"want to keep into {saved} (the saved copies), or add --force.")
        return EXIT_ERRORS
    except (OSError, ValueError, SyntaxError) as exc:   # lxml's XMLSyntaxError is a SyntaxError
        say(f"sw2sim edits {args.action}: {exc}")
        return EXIT_UNUSABLE
    for line in result.done:
        print(line)
    for line in result.warnings:
        print(f"WARNING: {line}")
    return EXIT_OK
