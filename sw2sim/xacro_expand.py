"""A package that ships only a `.xacro`, expanded into its URDF without ROS.

Many packages hold `robot.urdf.xacro` and no URDF: ROS runs xacro when it launches. The
`xacro` package from PyPI expands such a file in the same way, as long as every
`$(find PKG)` names the package itself, which is resolved to its folder here. A `$(find)`
of another package needs that package (and a ROS workspace): `NeedsPackage` says which.
The expanded text is kept in memory; nothing is written into the user's package.
"""

from __future__ import annotations

import contextlib
import io
from pathlib import Path


class NeedsPackage(Exception):
    """The xacro names another package with $(find ...), which cannot be found without ROS."""

    def __init__(self, package: str):
        super().__init__(package)
        self.package = package


class ExpandError(Exception):
    """xacro refused the file; the message is xacro's own, with the file and line if given."""


def expand(xacro_file: Path, package_root: Path, package_name: str) -> bytes:
    """The URDF that `xacro_file` expands to, as UTF-8 bytes."""
    import xacro
    from xacro import substitution_args

    def find(name: str) -> str:
        if name == package_name:
            return str(package_root)
        raise NeedsPackage(name)

    saved = substitution_args._eval_find, substitution_args._eval_dict.get("find")
    substitution_args._eval_find = find
    substitution_args._eval_dict["find"] = find
    said = io.StringIO()
    try:
        with contextlib.redirect_stderr(said), contextlib.redirect_stdout(said):
            document = xacro.process_file(str(xacro_file))
    except NeedsPackage:
        raise
    except Exception as exc:  # noqa: BLE001  (xacro raises many kinds, all meaning "refused")
        inner = getattr(exc, "exc", None)
        if isinstance(inner, NeedsPackage):
            raise inner from None
        text = " ".join(str(exc).split()) or type(exc).__name__
        raise ExpandError(text) from None
    finally:
        substitution_args._eval_find = saved[0]
        if saved[1] is not None:
            substitution_args._eval_dict["find"] = saved[1]
    return document.toprettyxml(indent="  ", encoding="utf-8")
