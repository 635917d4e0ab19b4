"""Regenerate the example packages (meshes, URDF, CSV, config, launch files) from the designs,
and the raw sample export of the "Your own model" page (examples/Arm_Assembly).

    python -m course.practices                 every package
    python -m course.practices practice_3      one practice's package
    python -m course.practices --check         list packages that differ from their designs; exit 1 if any
"""

import argparse
import sys
import tempfile
from pathlib import Path

from . import PRACTICES, ROOT, design, sample_export


def writers(chosen: list[str]) -> list:
    """The write() functions of the chosen practices (all, and the sample export, by default)."""
    return [design(p).write for p in chosen or PRACTICES] + ([] if chosen else [sample_export.write])


def stale(chosen: list[str]) -> list[str]:
    """Generated files under examples/ that differ from what the designs write now."""
    differ = []
    with tempfile.TemporaryDirectory() as tmp:
        for write in writers(chosen):
            for path in write(Path(tmp)):
                rel = path.relative_to(tmp)
                committed = ROOT / "examples" / rel
                if not committed.is_file() or committed.read_bytes() != path.read_bytes():
                    differ.append(f"examples/{rel.as_posix()}")
    return differ


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m course.practices", description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true",
                        help="only list generated files that differ from their designs; exit 1 if any")
    parser.add_argument("practices", nargs="*", help=f"some of {', '.join(PRACTICES)} (default: all)")
    args = parser.parse_args(argv)
    unknown = [p for p in args.practices if p not in PRACTICES]
    if unknown:
        print(f"unknown practice {unknown[0]!r}; choose from {', '.join(PRACTICES)}", file=sys.stderr)
        return 2
    if args.check:
        differ = stale(args.practices)
        for rel in differ:
            print(f"stale: {rel}")
        return 1 if differ else 0
    changed = stale(args.practices)
    for write in writers(args.practices):
        write()
    print(f"example packages: {len(changed)} files rewritten" if changed else
          "example packages: all up to date")
    for rel in changed:
        print(f"  {rel}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
