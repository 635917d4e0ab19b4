"""`sw2sim render`: a PNG of the package at its start pose, drawn off-screen."""

from __future__ import annotations

from pathlib import Path

from .options import EXIT_OK, EXIT_UNUSABLE, package_path, pixels, say, urdf_choice
from .shown_model import shown_model

HELP = """\
Saves a PNG picture of the model at its start pose, drawn off-screen (no display
needed). The camera looks from AZIMUTH and ELEVATION degrees and frames the whole
robot as it stands on the floor. An existing file is kept unless --force is given.

The package is checked first (without the simulation); findings are printed,
and the picture is made as long as MuJoCo can load the model.

examples:
  sw2sim render examples/example_4 -o example_4.png
  sw2sim render examples/example_5 -o car.png --width 1600 --height 1000 \
      --azimuth 210 --elevation -15 --shadows
"""


def add_arguments(parser) -> None:
    package_path(parser)
    urdf_choice(parser)
    parser.add_argument("-o", "--output", metavar="FILE", required=True, help="the PNG to write")
    parser.add_argument("--width", type=pixels, default=960, help="pixels (default 960)")
    parser.add_argument("--height", type=pixels, default=640, help="pixels (default 640)")
    parser.add_argument("--azimuth", type=float, default=135.0,
                        help="camera direction around the vertical, degrees (default 135)")
    parser.add_argument("--elevation", type=float, default=-25.0,
                        help="camera height, degrees; negative looks down (default -25)")
    parser.add_argument("--shadows", action="store_true",
                        help="draw shadows (software rendering can speckle them on large models)")
    parser.add_argument("--force", action="store_true", help="overwrite FILE if it exists")


def run(args) -> int:
    out = Path(args.output)
    if out.is_dir():
        say(f"sw2sim render: {out} is a folder; give the PNG file to write, "
            f"e.g. {out / 'picture.png'}")
        return EXIT_UNUSABLE
    if out.exists() and not args.force:
        say(f"sw2sim render: {out} exists; add --force to overwrite it, or choose another name.")
        return EXIT_UNUSABLE
    if not out.parent.is_dir():
        say(f"sw2sim render: the folder {out.parent} does not exist; create it first.")
        return EXIT_UNUSABLE
    model = shown_model(args, size=(args.width, args.height))
    if isinstance(model, int):
        return model
    import mujoco
    from ..render import render, save_png
    try:
        image = render(model, mujoco.MjData(model), width=args.width, height=args.height,
                       azimuth=args.azimuth, elevation=args.elevation, shadows=args.shadows,
                       frame=True)
    except Exception as exc:  # noqa: BLE001  (no OpenGL here: say how to get one)
        say(f"sw2sim render: cannot draw off-screen ({type(exc).__name__}: {exc}). On Debian or "
            "Ubuntu install libosmesa6 (sudo apt install libosmesa6), or set MUJOCO_GL=egl.")
        return EXIT_UNUSABLE
    try:
        save_png(image, out)
    except OSError as exc:
        say(f"sw2sim render: cannot write {out}: {exc.strerror or exc}")
        return EXIT_UNUSABLE
    print(f"wrote {out} ({args.width}x{args.height})")
    return EXIT_OK
