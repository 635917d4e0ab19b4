"""Practice 5's turning-centre diagram: the car seen from above in a left turn, with the
triangles Equation 4 comes from. Every length is the design's, every angle design.ackermann()'s.

The car drives up the page (its x axis points up, its y axis to the left), so the turning
centre of a left turn lies to the left, on the line of the rear axle.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
from matplotlib.patches import Arc, Polygon, Rectangle

from .plotting import variants
from .practices.practice_5 import design

PHI_DEGREES = design.STEER_LIMIT_DEGREES     # the example: the centre joint at its limit, 30°
INNER, OUTER, CENTRE = "tab:blue", "tab:orange", "0.35"


def numbers(phi_degrees: float = PHI_DEGREES) -> dict[str, float]:
    """The diagram's numbers: l, w, R in m; phi, inner, outer in degrees."""
    l, w = design.mm(design.WHEELBASE), design.mm(design.TRACK)
    phi = math.radians(phi_degrees)
    inner, outer = design.ackermann(phi, l, w)
    return {"l": l, "w": w, "R": l / math.tan(phi), "phi": phi_degrees,
            "inner": math.degrees(inner), "outer": math.degrees(outer)}


def _p(x: float, y: float) -> tuple[float, float]:
    """The car's (x forward, y left) in page coordinates (right, up)."""
    return -y, x


def _wheel(ax, x, y, angle, colour):
    """A wheel (its outline seen from above) centred at (x, y), turned by `angle` rad."""
    r, half = design.mm(design.WHEEL_DIAMETER) / 2, design.mm(design.WHEEL_WIDTH) / 2
    c, s = math.cos(angle), math.sin(angle)
    corners = [(x + c * dx - s * dy, y + s * dx + c * dy) for dx, dy in
               ((r, half), (-r, half), (-r, -half), (r, -half))]
    ax.add_patch(Polygon([_p(*q) for q in corners], closed=True, fc=colour, ec="black", lw=1.0,
                         alpha=0.85, zorder=4))


def _right_angle(ax, corner, u, v, size=0.025):
    """A right-angle mark at `corner` between the directions u and v (car coordinates)."""
    a = np.add(corner, np.multiply(u, size))
    b = np.add(a, np.multiply(v, size))
    c = np.add(corner, np.multiply(v, size))
    ax.plot(*zip(*[_p(*a), _p(*b), _p(*c)]), color="black", lw=0.9, zorder=5)


# On a phone the lettering is this large (points): 11 px or more in a 360 px phone's column
# (course/phone.py's SHOWN_PX), the figure 5 in wide at 130 dots an inch.
PHONE_TEXT = 12.5


def _dimension(ax, p, q, label, offset, text_at=0.5, beside=None, size=11, **kw):
    """A dimension line between the page points p and q, moved by `offset` (page units).
    Its label sits on the line, in a gap; or, with `beside` (page units from the line's
    middle), next to the line, which then runs whole from arrow to arrow."""
    p = np.add(p, offset)
    q = np.add(q, offset)
    ax.annotate("", p, q, arrowprops=dict(arrowstyle="<|-|>", color="black", lw=0.9,
                                          shrinkA=0, shrinkB=0, mutation_scale=10))
    m = np.add(p, np.multiply(np.subtract(q, p), text_at))
    if beside is None:
        ax.text(*m, label, ha="center", va="center", fontsize=size, zorder=6,
                bbox=dict(fc="white", ec="none", pad=1.5), **kw)
    else:
        ax.text(*np.add(m, beside), label, fontsize=size, zorder=6, **kw)


def _limits(n: dict[str, float], phone: bool) -> tuple[tuple[float, float], tuple[float, float]]:
    """The drawing's page extent: x (from the turning centre's side to the l dimension's),
    y (from the R dimension's to the w dimension's), with a margin all round."""
    l, w, R = n["l"], n["w"], n["R"]
    if phone:
        return (-R - 0.1, w / 2 + 0.24), (-0.24, l + 0.27)
    return (-R - 0.08, w / 2 + 0.25), (-0.2, l + 0.2)


def draw(path: Path, phi_degrees: float = PHI_DEGREES) -> dict[str, float]:
    n = numbers(phi_degrees)
    (x0, x1), (y0, y1) = _limits(n, phone=True)
    # The phone figure has the drawing's own proportions: no empty band above or below.
    phone_size = (5.0, round(5.0 * (y1 - y0) / (x1 - x0), 2))
    for fig, ax, phone in variants(path, figsize=(8.6, 6.2), phone_figsize=phone_size):
        _diagram(ax, n, phone)
    return n


def _diagram(ax, n: dict[str, float], phone: bool) -> None:
    """The car, its wheels' axes to the turning centre, the angles and the dimensions. On a
    phone, where the lettering is larger against the car, the three angles' values are
    listed in the empty corner above the turning centre instead of over the wheels and the
    chassis, and each dimension's label sits beside its line, so that every line runs whole
    from arrow to arrow."""
    size = PHONE_TEXT if phone else 11
    l, w, R = n["l"], n["w"], n["R"]
    inner, outer, phi = (math.radians(n[k]) for k in ("inner", "outer", "phi"))
    ax.set_aspect("equal")
    ax.grid(False)
    ax.set_axis_off()
    # the chassis: the plate and the front and rear beams, as the top view of the drawing
    lx, ly, _ = (design.mm(v) for v in design.PLATE)
    back = design.mm(design.PLATE_BACK)
    beam = design.mm(design.CROSS_MEMBER[0])
    for x0, y0, dx, dy in ((back, -ly / 2, lx, ly),
                           (-beam / 2, -design.mm(design.BEAM_HALF), beam, 2 * design.mm(design.BEAM_HALF)),
                           (l - beam / 2, -w / 2, beam, w)):
        ax.add_patch(Rectangle(_p(x0, y0 + dy), dy, dx, fc="0.88", ec="0.3", lw=1.0, zorder=2))
    centre = (0.0, R)                 # the turning centre, on the rear axle's line
    # the rear axle's line, out to the turning centre
    ax.plot(*zip(_p(0, -w / 2 - 0.08), _p(0, R + 0.06)), color="black", lw=0.9, ls=(0, (8, 3, 2, 3)), zorder=3)
    wheels = {"inner": ((l, w / 2), inner, INNER), "outer": ((l, -w / 2), outer, OUTER),
              "centre": ((l, 0.0), phi, CENTRE)}
    for key, ((x, y), angle, colour) in wheels.items():
        # the wheel's axis, from its centre to the turning centre
        ax.plot(*zip(_p(x, y), _p(*centre)), color=colour, lw=1.6 if key != "centre" else 1.1,
                ls="-" if key != "centre" else "--", zorder=3)
        if key != "centre":
            _wheel(ax, x, y, angle, colour)
            # the wheel's heading is square to its axis
            heading = (math.cos(angle), math.sin(angle))
            to_centre = np.subtract(centre, (x, y)) / math.dist(centre, (x, y))
            _right_angle(ax, (x, y), heading, to_centre, 0.03)
            # straight ahead, and the angle the wheel is turned from it
            ax.plot(*zip(_p(x, y), _p(x + 0.13, y)), color="0.4", lw=0.8, ls=":", zorder=3)
            ax.plot(*zip(_p(x, y), _p(x + 0.13 * math.cos(angle), y + 0.13 * math.sin(angle))),
                    color=colour, lw=1.2, zorder=5)
            ax.add_patch(Arc(_p(x, y), 0.2, 0.2, theta1=90, theta2=90 + math.degrees(angle), color=colour,
                             lw=1.2, zorder=5))
    for x, y in ((0, w / 2), (0, -w / 2)):
        _wheel(ax, x, y, 0.0, "0.55")
    # the right angles of the two triangles, where the rear axle's line meets each wheel's track
    for y in (w / 2, -w / 2):
        _right_angle(ax, (0.0, y), (1.0, 0.0), (0.0, 1.0), 0.025)
    # the angles at the turning centre, between the rear axle's line and each wheel's axis
    cx, cy = _p(*centre)
    for radius, angle, colour, name in ((0.52, outer, OUTER, r"$\Phi_o$"), (0.40, phi, CENTRE, r"$\Phi$"),
                                        (0.28, inner, INNER, r"$\Phi_i$")):
        ax.add_patch(Arc((cx, cy), 2 * radius, 2 * radius, theta1=0, theta2=math.degrees(angle),
                         color=colour, lw=1.3, zorder=5))
        ax.text(cx + (radius + 0.012) * math.cos(angle / 2), cy + (radius + 0.012) * math.sin(angle / 2),
                name, color=colour, fontsize=size + 1, ha="left", va="center", zorder=6,
                bbox=dict(fc="white", ec="none", pad=0.5))
    # the same angles at the wheels, turned from straight ahead, and the centre's
    values = {key: rf"$\Phi_{symbol}$ = {math.degrees(wheels[key][1]):.2f}° ({key})"
              for key, symbol in (("inner", "i"), ("outer", "o"))}
    centre_value = rf"$\Phi$ = {n['phi']:.0f}°"
    if phone:
        for row, (text, colour) in enumerate(((values["inner"], INNER), (centre_value + " (centre)", CENTRE),
                                              (values["outer"], OUTER))):
            ax.text(cx - 0.03, l + 0.2 - 0.075 * row, text, color=colour, fontsize=size, ha="left", va="center")
    else:
        for key in ("inner", "outer"):
            (x, y), _, colour = wheels[key]
            px, py = _p(x, y)
            ax.text(px + (0.03 if key == "outer" else -0.03), py + 0.125, values[key], color=colour,
                    fontsize=size, ha="left" if key == "outer" else "right")
        ax.text(*_p(l + 0.03, 0.0), centre_value, color=CENTRE, fontsize=size, ha="center",
                va="bottom", zorder=6, bbox=dict(fc="white", ec="none", pad=0.5))
    ax.plot(cx, cy, "o", color="black", ms=5, zorder=6)
    if phone:
        ax.text(cx - 0.03, cy - 0.035, "turning centre", ha="left", va="top", fontsize=size)
    else:
        ax.text(cx, cy - 0.035, "turning centre", ha="center", va="top", fontsize=10.5)
    # l, w and R
    l_label, w_label, r_label = f"l = {l * 1000:.0f} mm", f"w = {w * 1000:.0f} mm", f"R = l / tan Φ = {R:.3f} m"
    if phone:
        _dimension(ax, _p(0, -w / 2), _p(l, -w / 2), l_label, (0.13, 0.0), beside=(0.025, 0.0),
                   size=size, rotation=90, ha="left", va="center")
        _dimension(ax, _p(l, w / 2), _p(l, -w / 2), w_label, (0.0, 0.175), beside=(0.0, 0.02),
                   size=size, ha="center", va="bottom")
        _dimension(ax, _p(*centre), _p(0, 0), r_label, (0.0, -0.15), beside=(0.0, -0.02),
                   size=size, ha="center", va="top")
    else:
        _dimension(ax, _p(0, -w / 2), _p(l, -w / 2), l_label, (0.13, 0.0))
        _dimension(ax, _p(l, w / 2), _p(l, -w / 2), w_label, (0.0, 0.11))
        _dimension(ax, _p(*centre), _p(0, 0), r_label, (0.0, -0.13), text_at=0.42)
    ax.plot(*_p(0, 0), "+", color="black", ms=9, zorder=6)
    (x0, x1), (y0, y1) = _limits(n, phone)
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
