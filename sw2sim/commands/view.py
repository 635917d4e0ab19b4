"""`sw2sim view`: the package in MuJoCo's interactive viewer, a slider for each joint."""

from __future__ import annotations

import os

from .. import gl
from .options import EXIT_OK, EXIT_UNUSABLE, no_display, package_path, say, urdf_choice
from .shown_model import shown_model

HELP = """\
Opens MuJoCo's interactive viewer (it needs a display). Each joint gets a slider
in the viewer's Control panel: joints with a controller in the package's YAML
get that controller's actuator (as in `sw2sim convert`), the others a position
actuator over their limits, or a velocity actuator if they have none.

The package is checked first (without the simulation); findings are printed,
and the model opens as long as MuJoCo can load it, so you can look at a problem.
Without a display (a server, a container), use `sw2sim render` instead, or log in
with `ssh -X` so the window opens on your screen.

examples:
  sw2sim view examples/example_4
"""


def add_arguments(parser) -> None:
    package_path(parser)
    urdf_choice(parser)


def run(args) -> int:
    reason = no_display()
    if reason:
        say(f"sw2sim view: {reason}. Make a picture instead:\n"
            f"    sw2sim render {args.path} -o picture.png\n"
            "or log in with `ssh -X` (or run on a machine with a screen) so the viewer's "
            "window can open.")
        return EXIT_UNUSABLE
    # The viewer draws through GLFW; `import sw2sim` chose an off-screen platform for
    # pictures, and MuJoCo reads the choice once, when it is first imported.
    gl.for_window()
    if not _glfw_starts():
        say(f"sw2sim view: no window can open on display {_display_name()}. Check that "
            "the display works (`xeyes`, say), or make a picture instead:\n"
            f"    sw2sim render {args.path} -o picture.png")
        return EXIT_UNUSABLE
    model = shown_model(args, sliders=True)
    if isinstance(model, int):
        return model
    try:
        import mujoco.viewer
        mujoco.viewer.launch(model)
    except Exception as exc:  # noqa: BLE001  (GLFW and the display fail in many ways)
        say(f"sw2sim view: the viewer could not open a window ({type(exc).__name__}: {exc}). "
            f"Check that the display works, or make a picture instead: "
            f"sw2sim render {args.path} -o picture.png")
        return EXIT_UNUSABLE
    return EXIT_OK


def _display_name() -> str:
    return os.environ.get("WAYLAND_DISPLAY") or os.environ.get("DISPLAY") or "(default)"


def _glfw_starts() -> bool:
    """Whether GLFW can reach the display. The viewer would otherwise stop the whole
    process from inside MuJoCo, with no message but "could not initialize GLFW"."""
    try:
        import glfw
    except ImportError:
        return False
    reporting, glfw.ERROR_REPORTING = glfw.ERROR_REPORTING, "ignore"
    try:
        return bool(glfw.init())
    finally:
        glfw.ERROR_REPORTING = reporting
