"""How close a student's export must come to the lesson's package to match it, and why.

A correct SolidWorks model of the lesson's parts is not equal to the lesson's package
to the last digit, for two reasons. The package's masses and inertias come from its
meshes, where every round edge is a polygon of 96 sides, while SolidWorks measures the
exact solid: for the lessons' parts the two disagree by under 0.1 % (Practice 1's wheel
is 3.054 kg in SolidWorks, 3.051 kg in the package), and by up to about 0.5 % for a part
with many small round features. And the numbers a student types (limits, dimensions
rounded in a drawing) carry four or five digits. Every tolerance below accepts those
and stays far below the smallest real mistake:

- MASS, 1 %: twice the larger faceting difference. A wrong material is off by 35 % or more
  (SolidWorks' default 1000 kg/m^3 against aluminium's 2700 is 0.37 times), and a
  dimension 1 mm off on the lessons' thinnest 18 to 20 mm plates is 5 %.
- INERTIA, 2 %: a moment is a mass times a squared distance, so faceting moves it about
  twice as much as the mass. Principal moments under a twentieth of the largest are
  judged against that twentieth (SMALL_MOMENT): the faceting of the large features
  decides their error, not their own size.
- LENGTH, 1 mm (origins, centres of mass, prismatic limits): the exporter writes
  positions from the mates to a nanometre, so a correct model agrees to the rounding of
  the drawing's dimensions (0.01 mm). The smallest mistake the lessons' parts allow, a
  frame on the wrong face or mid-plane of the thinnest plate, is 9 mm.
- ANGLE, 0.5 degrees (origin orientations, axes, revolute limits): the exporter's rpy
  and the lessons' limits are written to four decimals (0.7854 for 45 degrees is 0.0001
  degrees off); mistakes are quarter or half turns, or degrees typed for radians.
- EFFORT_VELOCITY, 1 %: typed numbers, some converted from rpm or N*mm; 1 % covers the
  rounding of a conversion.
- MESH, 1 mm plus 1 % of the size: a STL's bounding box shrinks where its facets cut
  round edges (by r * (1 - cos(pi / n)) for n facets per circle, under 1 % of the
  radius from 23 facets on), so sizes are compared loosely: the check is for
  millimetres and wrong dimensions, not facets.

A difference that is a unit mistake is recognised when the ratio lies within UNIT_RATIO
of the unit's factor, and a density is called a material's when it is within DENSITY.
"""

from __future__ import annotations

import math

MASS = 0.01                     # relative
INERTIA = 0.02                  # relative, of each principal moment and of the tensor
SMALL_MOMENT = 0.05             # of the largest principal moment
LENGTH = 0.001                  # metres
ANGLE = math.radians(0.5)       # radians
EFFORT_VELOCITY = 0.01          # relative
MESH_ABSOLUTE, MESH_RELATIVE = 0.001, 0.01
UNIT_RATIO = 0.02               # relative
DENSITY = 0.03                  # relative

# The materials a SolidWorks user picks most, by density in kg/m^3 (SolidWorks' library
# values); the first is what a part without a material gets.
MATERIALS = {
    1000: "SolidWorks' default density (no material applied)",
    2700: "aluminium, 6061 or 1060 alloy",
    2810: "aluminium 7075",
    7800: "plain carbon steel",
    7850: "steel",
    8000: "stainless steel",
    8900: "copper",
    8500: "brass",
    1020: "ABS",
    1250: "PLA",
    1200: "acrylic (PMMA)",
    7200: "cast iron",
    4430: "titanium alloy",
    1140: "nylon",
}


def as_dict() -> dict[str, float]:
    """The tolerances, for the JSON report."""
    return {"mass_relative": MASS, "inertia_relative": INERTIA, "length_m": LENGTH,
            "angle_deg": math.degrees(ANGLE), "effort_velocity_relative": EFFORT_VELOCITY,
            "mesh_m": MESH_ABSOLUTE, "mesh_relative": MESH_RELATIVE}


def material(density: float) -> str | None:
    """The material whose density this is (within DENSITY), or None."""
    best = min(MATERIALS, key=lambda known: abs(density / known - 1))
    return MATERIALS[best] if abs(density / best - 1) <= DENSITY else None
