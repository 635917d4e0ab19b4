"""Engineering drawings (SVG) made from the same features as the part meshes.

`part_drawing_svg` draws one part in three orthographic views (first-angle
projection), with ISO-style dimensions and a title block. `assembly_drawing_svg`
draws a robot's links in a front and a top view, with balloons, a parts list and
the joints' origins and axes. Both are A4 landscape sheets (297 x 210 mm) drawn in
millimetres at a standard scale, and both are deterministic: the same input gives
the same bytes.

The modules, each importing only those listed before it:

- `svg`: sheet primitives (lines, arcs, texts, fills), line styles, text metrics, the document
- `solids`: a part's features as an exact solid (boxes and cylinders, added or cut)
- `projection`: the visible and hidden lines of a view, and its centre lines
- `dimensions`: dimensions (ISO 129), their texts and checks
- `sheet`: frame, title block, scales, layout of the views and `part_drawing_svg`
- `assembly`: link poses, balloons, joint marks, parts list and `assembly_drawing_svg`
"""

from .assembly import BALLOON_R, assembly_drawing_svg, link_poses
from .dimensions import angle_degrees, check_dimensions, dimension_text
from .sheet import PartSheet, part_drawing_svg, part_sheet
from .svg import text_width

__all__ = [
    "BALLOON_R",
    "angle_degrees",
    "assembly_drawing_svg",
    "check_dimensions",
    "dimension_text",
    "link_poses",
    "PartSheet",
    "part_drawing_svg",
    "part_sheet",
    "text_width",
]
