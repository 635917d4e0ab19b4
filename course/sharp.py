"""Plots for screens of 2 device pixels to the CSS pixel: where a plot's sharp file goes.

The pages show a plot at its own width (its PNG's pixels) and at most COLUMN_PX wide, the
text column of a wide window (assets/css/main.css, --wide). A laptop with 2 device pixels
to the CSS pixel would show each pixel of it twice across, soft. So every plot is also
saved DENSITY times as wide as it can be shown, min(its width, COLUMN_PX), beside itself
with SUFFIX (x.png, x-2x.png), and the page offers both to the browser
(_plugins/sharp_images.rb), which fetches the sharp one only for such a screen.
"""

from __future__ import annotations

from pathlib import Path

SUFFIX = "-2x"
COLUMN_PX = 1008   # 63rem: the widest the pages show a figure
DENSITY = 2.0


def sharp_path(path: str | Path) -> Path:
    """Where the sharp file of the plot at `path` goes: beside it, SUFFIX added."""
    path = Path(path)
    return path.with_name(f"{path.stem}{SUFFIX}{path.suffix}")


def sharp_pixels(width: float) -> int:
    """How wide the sharp file of a plot `width` pixels wide is."""
    return round(DENSITY * min(width, COLUMN_PX))


def sharp_paths(path: str | Path) -> list[Path]:
    """The sharp file of the figure at `path` if it is a plot (a PNG); an SVG is sharp on
    any screen."""
    return [sharp_path(path)] if Path(path).suffix == ".png" else []
