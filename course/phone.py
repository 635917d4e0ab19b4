"""Figures for phones: where a figure's phone variant goes, and how it is shown there.

A phone shows the pages' text column some 330 px wide, less than half the 736 px the
figures are laid out for: their lettering would be 4 to 6 px high. A figure that has
lettering is therefore made twice by the same code, once as the pages show it on wider
screens and once for phones, narrower, its parts one above the other and its lettering at
least MIN_TEXT_PX high in a column SHOWN_PX wide. The phone variant lies beside the
figure, its name with SUFFIX (x.png, x-phone.png), and the site serves it to narrow
windows (_plugins/phone_figures.rb); media/manifest.json records both files.
"""

from __future__ import annotations

from pathlib import Path

SUFFIX = "-phone"
# The text column of a 360 px wide phone, 1 rem of margin each side (assets/css/main.css);
# a 390 px phone shows it 30 px wider.
SHOWN_PX = 328.0
MIN_TEXT_PX = 9.0
# The engineering drawings' lettering, as dimensions and balloons are read one by one
# rather than at a glance: at least this high in the column (course/drawing/narrow.py).
DRAWING_MIN_TEXT_PX = 11.0


# A plot's phone variant (a PNG) is drawn for screens of 2 device pixels to the CSS pixel
# (its own file) and, beside it, for screens of 3 (DENSE_SUFFIX added: x-phone-3x.png); the
# page lets the browser choose (_plugins/phone_figures.rb). A drawing (SVG) is sharp on any.
DENSE_SUFFIX = "-3x"


def phone_path(path: str | Path) -> Path:
    """Where the phone variant of the figure at `path` goes: beside it, SUFFIX added."""
    path = Path(path)
    return path.with_name(f"{path.stem}{SUFFIX}{path.suffix}")


def dense_path(path: str | Path) -> Path:
    """Where the 3 pixels to the CSS pixel file of the phone variant of the plot at `path`
    goes: beside the phone variant, DENSE_SUFFIX added."""
    phone = phone_path(path)
    return phone.with_name(f"{phone.stem}{DENSE_SUFFIX}{phone.suffix}")


def phone_paths(path: str | Path) -> list[Path]:
    """Every file of the phone variant of the figure at `path`: the variant, and for a plot
    (a PNG) its file for screens of 3 pixels to the CSS pixel."""
    path = Path(path)
    return [phone_path(path), *([dense_path(path)] if path.suffix == ".png" else [])]
