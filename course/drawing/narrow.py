"""A drawing's views for a phone's column, when the views the pages show are too wide for it.

The pages show a drawing's views (`views_only`) as wide as the text column. On a phone the
column is course.phone.SHOWN_PX wide, and the views' smallest lettering reads
course.phone.DRAWING_MIN_TEXT_PX high there only if the views' box is at most that lettering's
size × SHOWN_PX / DRAWING_MIN_TEXT_PX wide (104.4 mm for 3.5 mm lettering). Views wider than that get
a narrow variant, the phone variant of the figure (course/phone.py): a part's three views
one above the other (the sheet puts the side view beside the front view), and, if that is
still too wide, an assembly's or a part's views drawn smaller, the lettering as large as
ever. The sheet, linked under the views, keeps its standard scale; the variant's views are
at whatever scale fits, and say no scale.
"""

from __future__ import annotations

import re

from ..phone import DRAWING_MIN_TEXT_PX, SHOWN_PX
from .assembly import assembly_drawing_svg
from .sheet import part_views_narrow_svg
from .svg import VIEWS_MARGIN

VIEW_BOX = re.compile(r'viewBox="[-\d.]+ [-\d.]+ ([\d.]+) [\d.]+"')
FONT_SIZE = re.compile(r'font-size="([\d.]+)"')


def readable_width(svg: str) -> float:
    """The widest box (mm) the drawing's views may have for their smallest lettering to read
    DRAWING_MIN_TEXT_PX high in a column SHOWN_PX wide."""
    return min(float(s) for s in FONT_SIZE.findall(svg)) * SHOWN_PX / DRAWING_MIN_TEXT_PX


def too_wide(svg: str) -> bool:
    """Whether the views (an SVG of `views_only`) read too small in a phone's column."""
    return float(VIEW_BOX.search(svg).group(1)) > readable_width(svg)


def _views_width(svg: str) -> float:
    """The width the views themselves may take in the box: less the margins `views_box`
    adds, each rounded out to a whole millimetre."""
    return readable_width(svg) - 2 * (VIEWS_MARGIN + 1.0)


def part_views_narrow(part, views: str) -> str:
    """The narrow variant of a part's views, `views` being the ones the pages show."""
    return _checked(part_views_narrow_svg(part, _views_width(views)), part.name)


def assembly_views_narrow(robot, views: str) -> str:
    """The narrow variant of an assembly's views, `views` being the ones the pages show."""
    return _checked(assembly_drawing_svg(robot, views_only=True, width=_views_width(views)), robot.name)


def _checked(svg: str, name: str) -> str:
    if too_wide(svg):
        raise ValueError(f"{name}: the phone variant of its drawing is still too wide for its "
                         f"lettering ({VIEW_BOX.search(svg).group(1)} mm, at most "
                         f"{readable_width(svg):.1f} mm): course/drawing/narrow.py")
    return svg
