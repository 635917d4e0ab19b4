"""The `sw2sim` command line: the top-level parser, and one command run with care.

Every command lives in its own module under sw2sim/commands/ (its help, options and entry
point), named in `commands.COMMANDS`. Only the module of the command being run is
imported, and MuJoCo only inside a command: `view` must choose its GL platform first.
Every command takes the package folder (the one holding package.xml), its .urdf file or
a .zip of it (sw2sim.archive) and reads it once (`sw2sim.package.find_package`).
"""

from __future__ import annotations

import argparse
import contextlib
import os
import sys

from . import commands, gl
from .commands.options import EXIT_ERRORS, EXIT_OK, EXIT_UNUSABLE, say, version  # noqa: F401

EXIT_BROKEN_PIPE = 141   # 128 + SIGPIPE: what a shell reports when the reader went away

DESCRIPTION = """\
From a SolidWorks-exported URDF package to a MuJoCo simulation: check the package
and say how to fix what is wrong, compare it with a lesson's reference package,
convert it to a MuJoCo model folder, open it in MuJoCo's viewer, save a picture
of it, port it to ROS 2, or run it under ROS 1 or ROS 2 with MuJoCo in Gazebo's
place.

PATH is the package folder (the one holding package.xml), its .urdf file, or a .zip
of the package folder (read as it is; nothing is unpacked beside it).
Exit status: 0 done (warnings allowed), 1 the package has errors, 2 it cannot be
used at all (or the command could not run).
"""

EXAMPLES = """\
examples:
  sw2sim check examples/example_4
  sw2sim check my_robot/urdf/my_robot.urdf --json > report.json
  sw2sim check my_robot.zip
  sw2sim compare my_export examples/example_1
  sw2sim convert examples/example_4 -o example_4_mujoco
  sw2sim view examples/example_4
  sw2sim render examples/example_4 -o example_4.png --azimuth 200
  sw2sim edits save examples/example_1        # before exporting again
  sw2sim port examples/example_3 -o ~/ros2_ws/src/example_3
Run `sw2sim COMMAND --help` for each command's options.
"""


def main(argv: list[str] | None = None) -> int:
    """Run one command; return its exit status (never raise on bad input)."""
    words = sys.argv[1:] if argv is None else list(argv)
    named = _named(words)
    if named is not None and named not in commands.COMMANDS:
        guess = commands.closest(named)
        say(f"sw2sim: {named!r} is not a command" +
            (f"; did you mean `sw2sim {guess}`?" if guess else "") +
            " Run `sw2sim --help` for the list.")
        return EXIT_UNUSABLE
    parser = _parser(words)
    args = parser.parse_args(words)
    if args.command is None:
        parser.print_help()
        return EXIT_UNUSABLE
    if argv is None and args.command in FILE_COMMANDS:
        _one_blas_thread()
    try:
        with _drawing_for(args.command, argv):
            status = args.run(args)
        sys.stdout.flush()   # a closed pipe shows here, not in Python's flush at exit
        if argv is None and args.command in ENDS_AT_ONCE:
            _end_now(status)
        return status
    except KeyboardInterrupt:
        return 130
    except BrokenPipeError:
        # Whatever read the output stopped early (`sw2sim check PATH | head`): stop quietly,
        # as other command-line tools do, and keep Python from failing again on the pipe
        # when it flushes at exit.
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return EXIT_BROKEN_PIPE
    except Exception as exc:  # noqa: BLE001  (a bug in sw2sim: say so plainly, no traceback)
        say(f"sw2sim {args.command}: unexpected error ({type(exc).__name__}: {exc}). "
            "This is a fault in sw2sim, not necessarily in your package; please report it "
            "with the command you ran.")
        return EXIT_UNUSABLE


# Commands that, run from the command line, end the process as soon as their output is out
# (`_end_now`): they only read the user's files, and write nothing but their report.
ENDS_AT_ONCE = frozenset({"check"})


def _end_now(status: int) -> None:
    """End the process with `status` without Python's finalisation, which takes `sw2sim
    check` a tenth of a second (numpy's and MuJoCo's modules torn down one object at a
    time) after everything is said. The folders of unpacked archives are removed first, as
    at a normal exit; the command's output is flushed."""
    from . import archive
    archive.discard()
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(status)


# Commands that read and write files and start no other process.
FILE_COMMANDS = frozenset({"check", "compare", "convert", "render", "port", "edits"})


def _one_blas_thread() -> None:
    """Let numpy's OpenBLAS start one thread, not one per core, unless the user chose
    (OPENBLAS_NUM_THREADS set). The extra threads wait for work by spinning, which takes a
    `sw2sim check` on a lesson's package from 0.15 to 0.3 s of CPU, and twice the wall
    time on a machine whose other cores are busy (tools/benchmark.py load); the commands'
    small matrices gain nothing from them. It must be set before numpy is first imported,
    so only the command line's own run sets it: a caller that passes argv keeps its own."""
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")


def _drawing_for(command: str, argv: list[str] | None):
    """The GL platform a command runs with. The command line's own `sw2sim check` (no
    argv: the process ends with it) draws nothing, so MuJoCo, imported by the stability
    run, loads no OpenGL library; a caller that passes argv (a test, a notebook) may draw
    afterwards in the same process, and keeps its platform."""
    if argv is None and command == "check":
        return gl.not_drawing()
    return contextlib.nullcontext()


class _Version(argparse.Action):
    """--version, looked up only when asked for: reading the installed package's metadata
    costs every command a twentieth of a second of start-up."""

    def __init__(self, option_strings, dest=argparse.SUPPRESS, **kwargs):
        super().__init__(option_strings, dest, nargs=0, default=argparse.SUPPRESS,
                         help="show program's version number and exit")

    def __call__(self, parser, namespace, values, option_string=None):
        print(f"{parser.prog} {version()}")
        parser.exit()


def _parser(argv: list[str]) -> argparse.ArgumentParser:
    """The parser, with the options of the command argv names (and only that command's
    module imported); the others are listed with their summaries."""
    raw = argparse.RawDescriptionHelpFormatter
    parser = argparse.ArgumentParser(prog="sw2sim", description=DESCRIPTION, epilog=EXAMPLES,
                                     formatter_class=raw)
    parser.add_argument("--version", action=_Version)
    parser.set_defaults(command=None)
    subparsers = parser.add_subparsers(title="commands", metavar="COMMAND")
    named = _named(argv)
    for name, (_, summary) in commands.COMMANDS.items():
        sub = subparsers.add_parser(name, help=summary, formatter_class=raw)
        if name == named:
            module = commands.module(name)
            sub.description = module.HELP
            module.add_arguments(sub)
            sub.set_defaults(command=name, run=module.run)
    return parser


def _named(argv: list[str]) -> str | None:
    """The command argv names: its first word that is not an option."""
    return next((word for word in argv if not word.startswith("-")), None)
