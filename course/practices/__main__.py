"""Regenerate the example packages (meshes, URDF, CSV, config, launch files) from the designs,
and the raw sample export of the "Your own model" page (examples/Arm_Assembly)."""

import sys

from . import PRACTICES, ROOT, design, sample_export


def main(argv: list[str]) -> int:
    chosen = argv or PRACTICES
    for practice in chosen:
        if practice not in PRACTICES:
            print(f"unknown practice {practice!r}; choose from {', '.join(PRACTICES)}", file=sys.stderr)
            return 2
        written = design(practice).write()
        for path in written:
            print(path.relative_to(ROOT))
    if not argv:
        for path in sample_export.write():
            print(path.relative_to(ROOT))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
