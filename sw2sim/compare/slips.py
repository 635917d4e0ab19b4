"""Numbers typed in another unit, or with the decimal point in another place.

URDF wants metres, radians, N (or N*m) and m/s (or rad/s), and the exporter writes what
its dialogs hold, so a joint's limits, and an origin typed or edited by hand, carry the
unit the student had in mind. Such a number is the lesson's times a unit's factor:
1000 for millimetres, 100 for centimetres, 57.3 for degrees typed for radians, 9.55 for
revolutions per minute; or the factor's inverse, when a number already in metres or
radians was converted once more (0.7854 rad taken for degrees gives 0.0137). A factor of
10, 100 or 1000 with no unit behind it is the decimal point moved.

A number is recognised as slipped when every value that differs from the lesson's
(each component of an origin that differs by more than its tolerance) is the lesson's
times the same factor, within UNIT_RATIO: so one component typed in millimetres is
found too, and a value the lesson has as 0 never is (no factor makes 0 anything else).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from . import tolerances as tol

DEGREE = 180 / math.pi

# What a number that is the lesson's times the factor was typed in, by quantity:
# factor -> (the unit in words, the question the line asks).
UNITS = {
    "length": {1000.0: ("millimetres", "typed in millimetres?"),
               100.0: ("centimetres", "typed in centimetres?"),
               1 / 0.0254: ("inches", "typed in inches?"),
               0.001: ("metres divided by 1000", "metres converted once more, as if they "
                       "were millimetres?"),
               0.01: ("metres divided by 100", "metres converted once more, as if they were "
                      "centimetres?")},
    "angle": {DEGREE: ("degrees", "typed in degrees?"),
              1 / DEGREE: ("radians divided by 57.3", "radians converted once more, as if "
                           "they were degrees?")},
    "velocity": {DEGREE: ("degrees per second", "typed in degrees per second?"),
                 30 / math.pi: ("revolutions per minute", "typed in revolutions per minute?")},
    "speed": {1000.0: ("mm/s", "typed in mm/s?"), 100.0: ("cm/s", "typed in cm/s?")},
    "effort": {1000.0: ("N*mm", "typed in N*mm (or mN)?")},
}
DECIMAL = (10.0, 100.0, 1000.0, 0.1, 0.01, 0.001)



def wanted(quantity: str, kind: str = "revolute") -> str:
    """The unit URDF wants for a quantity of a joint of `kind`."""
    return {"length": "metres", "angle": "radians", "velocity": "rad/s", "speed": "m/s",
            "effort": "N" if kind == "prismatic" else "N*m"}[quantity]


@dataclass
class Slip:
    factor: float
    unit: str           # what the number is in, in words ("millimetres"), or the point moved
    question: str       # "typed in millimetres?"
    mine: float         # the number that shows it best, and the lesson's
    ref: float

    @property
    def by(self) -> str:
        return f"{self.factor:.4g} times the reference's: {self.unit}"

    def example(self) -> str:
        """"269 where the lesson has 2.69: typed in centimetres?"."""
        return f"{_num(self.mine)} where the lesson has {_num(self.ref)}: {self.question}"


def slip(mine, ref, quantity: str, within: float) -> Slip | None:
    """The unit slip that makes `mine` of `ref` (numbers or vectors of one `quantity`,
    those closer than `within` agreeing), or None when there is none."""
    mine = np.atleast_1d(np.asarray(mine, dtype=float))
    ref = np.atleast_1d(np.asarray(ref, dtype=float))
    differs = np.abs(mine - ref) > within
    if not differs.any() or np.any(np.abs(ref[differs]) <= within):
        return None
    ratios = mine[differs] / ref[differs]
    shown = int(np.flatnonzero(differs)[np.argmax(np.abs(ref[differs]))])
    known = dict(UNITS[quantity])
    for factor in DECIMAL:
        if not any(abs(factor / k - 1) <= tol.UNIT_RATIO for k in known):
            places = ("one place", "two places", "three places")[round(abs(math.log10(factor))) - 1]
            side = "right" if factor > 1 else "left"
            known[factor] = ("the decimal point moved", f"the decimal point {places} too far "
                             f"{side}?")
    for factor, (unit, question) in known.items():
        if np.all(np.abs(ratios / factor - 1) <= tol.UNIT_RATIO):
            return Slip(factor, unit, question, float(mine[shown]), float(ref[shown]))
    return None


def _num(x: float) -> str:
    return "0" if abs(x) < 1e-9 else f"{x:.6g}"
