"""What the commands share: exit statuses, the options several take, value checks, and
how a command speaks to the reader."""

from __future__ import annotations

import argparse
import os
import sys

EXIT_OK, EXIT_ERRORS, EXIT_UNUSABLE = 0, 1, 2


def say(message: str) -> None:
    """A message for the reader (an error, a hint): on stderr, apart from the report."""
    print(message, file=sys.stderr)


def package_path(parser, help_text: str = "package folder, .urdf file or .zip of the "
                                          "package") -> None:
    parser.add_argument("path", metavar="PATH", help=help_text)


def urdf_choice(parser) -> None:
    parser.add_argument("--urdf", metavar="NAME", help="which URDF to read, where the package "
                        "holds several (its file name)")


def simulation(parser) -> None:
    """The options `ros` and `ros2` share: how long, how fast, and the viewer."""
    parser.add_argument("--duration", type=float, metavar="S", help="stop after S seconds")
    parser.add_argument("--realtime", type=float, default=1.0, metavar="F",
                        help="real-time factor: 1 (default) as in Gazebo, 0 as fast as possible")
    parser.add_argument("--view", action="store_true",
                        help="show the simulation in MuJoCo's viewer (needs a display)")


def pixels(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a whole number of pixels") from None
    if not 16 <= value <= 4096:
        raise argparse.ArgumentTypeError(f"{value} is outside 16 to 4096 pixels")
    return value


def density(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number of kg/m^3") from None
    if not 1 <= value <= 25_000:
        raise argparse.ArgumentTypeError(f"{value:g} kg/m^3 is outside 1 to 25,000; write the "
                                         "density in kg/m^3 (aluminium: 2700)")
    return value


def no_display() -> str | None:
    """Why no window can open here, or None when one can."""
    if sys.platform == "darwin" or sys.platform.startswith("win"):
        return None
    if os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY"):
        return None
    return "neither DISPLAY nor WAYLAND_DISPLAY is set, so there is no screen to open a window on"


def viewer_or_not(command: str, wanted: bool) -> bool:
    """Whether `ros` or `ros2` opens the viewer it was asked for (--view)."""
    if wanted and (reason := no_display()):
        say(f"sw2sim {command}: --view: {reason}; the simulation runs without the viewer")
        return False
    return wanted


def version() -> str:
    from importlib.metadata import PackageNotFoundError, version
    try:
        return version("sw2sim")
    except PackageNotFoundError:
        return "(not installed)"
