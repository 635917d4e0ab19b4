"""Plots and renders for screens of 2 device pixels to the CSS pixel: their sharp files.

The pages show a picture at its own width (its PNG's pixels) and at most COLUMN_PX wide,
the text column of a wide window (assets/css/main.css, --wide). A laptop with 2 device
pixels to the CSS pixel would show each pixel of it twice across, soft. So every plot
(course/plotting.py) and every MuJoCo render (`save_render`) is also saved DENSITY times
as wide as it can be shown, min(its width, COLUMN_PX), beside itself with SUFFIX (x.png,
x-2x.png), and the page offers both to the browser (_plugins/sharp_images.rb), which
fetches the sharp one only for a screen that needs it.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import numpy as np

SUFFIX = "-2x"
COLUMN_PX = 1008   # 63rem: the widest the pages show a figure
DENSITY = 2.0


def sharp_path(path: str | Path) -> Path:
    """Where the sharp file of the picture at `path` goes: beside it, SUFFIX added."""
    path = Path(path)
    return path.with_name(f"{path.stem}{SUFFIX}{path.suffix}")


def sharp_pixels(width: float) -> int:
    """How wide the sharp file of a picture `width` pixels wide is."""
    return round(DENSITY * min(width, COLUMN_PX))


def save_render(path: str | Path, render_at: Callable[[int, int], np.ndarray], width: int,
                height: int) -> None:
    """A rendered picture, `render_at(width, height)`, at `path`, and its sharp file beside
    it: the same view rendered again sharp_pixels(width) wide, in 256 colours chosen by
    median cut (half the bytes of full colour; the octree palette of the plots' files
    shows steps in the floor's shading)."""
    from PIL import Image

    from sw2sim.render import save_png
    save_png(render_at(width, height), path)
    wide = sharp_pixels(width)
    picture = render_at(wide, round(height * wide / width))
    paletted = Image.fromarray(picture).quantize(256, method=Image.Quantize.MEDIANCUT)
    paletted.save(sharp_path(path), format="PNG", optimize=True)


def sharp_paths(path: str | Path) -> list[Path]:
    """The sharp file of the figure at `path` if it is a PNG (a plot or a render); an SVG
    is sharp on any screen."""
    return [sharp_path(path)] if Path(path).suffix == ".png" else []
