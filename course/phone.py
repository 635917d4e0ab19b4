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


def phone_path(path: str | Path) -> Path:
    """Where the phone variant of the figure at `path` goes: beside it, SUFFIX added."""
    path = Path(path)
    return path.with_name(f"{path.stem}{SUFFIX}{path.suffix}")


def phone_output(output: str) -> str:
    """The phone variant's output path (from the repository root) of the figure `output`."""
    return phone_path(output).as_posix()
