"""The figures of Practice 5's pages, made from the example package and its script."""

import math
from pathlib import Path

import numpy as np

from sw2sim import load_package
from ...media import Figure
from ...plotting import variants
from ...rviz_picture import rviz_picture
from sw2sim.render import render
from ...sharp import save_render
from .. import load_script
from . import design
from ..shared import assembly_drawing, drawing_figures, part_drawing

import mujoco  # noqa: E402  (after sw2sim has chosen the GL platform)

PACKAGE = "examples/example_5"
SCRIPT = f"{PACKAGE}/scripts/ackermann.py"
SPEED = 0.5                       # m/s, of the rear axle's centre
STEER = 0.3                       # rad, the centre angle of the turns (17.2°)
SETTLE = 3.0                      # s: what the fits leave out at the start of a run
CASES = {                         # the comparison of "moved, but not ideally"
    "Ackermann angles, each wheel its own speed": dict(ackermann=True, own_speeds=True),
    "Ackermann angles, equal wheel speeds": dict(ackermann=True, own_speeds=False),
    "parallel steering, each wheel its own speed": dict(ackermann=False, own_speeds=True),
}
COLOURS = ["tab:blue", "tab:red", "tab:orange"]


def script():
    return load_script(SCRIPT)




def fit_circle(x, y):
    """The circle through the points in the least-squares sense: centre x, y and radius."""
    a = np.c_[x, y, np.ones_like(x)]
    c = np.linalg.lstsq(a, x ** 2 + y ** 2, rcond=None)[0]
    cx, cy = c[0] / 2, c[1] / 2
    return cx, cy, math.sqrt(c[2] + cx ** 2 + cy ** 2)


def turn(seconds=12.0, steer=STEER, speed=SPEED, **options):
    """A turn at a constant command. Returns the car (with its log) and the mean slip
    of the wheels over the last 2 s, m/s."""
    car = script().Car(**options)
    car.command(speed=speed, steering=steer)
    car.run(seconds - 2.0)
    slips = []
    for _ in range(200):
        car.step()
        slips.append(np.mean(list(car.slip().values())))
    return car, float(np.mean(slips))


def steady_radius(car):
    """The fitted radius of the rear axle centre's path once the turn is steady, and the
    radius the geometry predicts for the measured centre angle, l / tan(phi)."""
    t, x, y, _, phi, *_ = car.states()
    steady = t > SETTLE
    radius = fit_circle(x[steady], y[steady])[2]
    return radius, car.geometry.wheelbase / math.tan(float(np.mean(phi[steady])))


def model_picture(path: Path) -> None:
    s = script()
    car = s.Car()
    car.command(speed=0.0, steering=0.35)
    car.run(1.0)
    save_render(path, lambda w, h: render(car.model, car.data, width=w, height=h,
                                          lookat=[0.2, 0.0, 0.02], distance=1.25,
                                          azimuth=215, elevation=-28), 960, 560)


def _predicted(ax, radius, colour="0.35", label="predicted circle"):
    a = np.linspace(0, 2 * np.pi, 400)
    ax.plot(radius * np.sin(a), radius - radius * np.cos(a), color=colour, ls="--", lw=1.4, label=label)


def path_vs_circle(path: Path) -> None:
    runs = []
    for steer, colour in ((0.15, "tab:green"), (STEER, "tab:blue"), (0.5, "tab:purple")):
        car, _ = turn(seconds=16.0, steer=steer)
        _, x, y, *_ = car.states()
        runs.append((steer, colour, x, y, *steady_radius(car)))
    for fig, ax, phone in variants(path, figsize=(7.6, 6.4), phone_figsize=(5.0, 6.6)):
        for steer, colour, x, y, measured, predicted in runs:
            ax.plot(x, y, color=colour, lw=2.4, alpha=0.75,
                    label=f"driven, {math.degrees(steer):.1f}°: R = {measured:.3f} m")
            _predicted(ax, predicted, "black", f"l / tan φ = {predicted:.3f} m")
        ax.set_aspect("equal")
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
        if phone:   # no room beside the plot: the key goes under it
            ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.12), fontsize=9,
                      title="rear axle centre, 0.5 m/s")
        else:
            ax.legend(loc="upper left", bbox_to_anchor=(1.0, 1.0), fontsize=9,
                      title="rear axle centre, 0.5 m/s")


def sweep(seconds=12.0):
    """The centre angle swept from its right limit to its left one and back, rolling at
    0.2 m/s; returns the car and its log."""
    car = script().Car()
    limit = design.STEER_LIMIT
    car.command(speed=0.2, steering=-limit)
    car.run(1.0)
    steps = round(seconds * script().CONTROL_RATE)
    for i in range(steps):
        share = i / (steps - 1)
        car.command(steering=-limit * math.cos(2 * math.pi * share))
        car.step()
    return car


def knuckle_angles(path: Path) -> None:
    car = sweep()
    t, _, _, _, phi, left_sp, right_sp, left, right = car.states()
    keep = t > 1.0
    phi, left, right = phi[keep], left[keep], right[keep]
    g = car.geometry
    grid = np.linspace(-design.STEER_LIMIT, design.STEER_LIMIT, 200)
    eq4 = np.array([script().knuckle_angles(p, g.wheelbase, g.track) for p in grid])
    for fig, (ax, err), phone in variants(path, 1, 2, figsize=(12, 4.6),
                                          gridspec_kw={"width_ratios": [1.3, 1]}):
        _knuckle_panels(ax, err, phone, grid, eq4, t[keep], phi, left, right,
                        left_sp[keep] - left, right_sp[keep] - right)


def _knuckle_panels(ax, err, phone, grid, eq4, t, phi, left, right, left_error, right_error):
    """Knuckle angles against the centre angle, and the commanded minus measured angles."""
    deg = np.degrees
    ax.plot(deg(grid), deg(grid), color="0.6", ls=":", label="parallel steering (both = φ)")
    ax.plot(deg(grid), deg(eq4[:, 0]), color="tab:blue", lw=1.2, label="left, Equation 4")
    ax.plot(deg(grid), deg(eq4[:, 1]), color="tab:orange", lw=1.2, label="right, Equation 4")
    ax.plot(deg(phi[::8]), deg(left[::8]), "o", ms=3.5, color="tab:blue", label="left, measured")
    ax.plot(deg(phi[::8]), deg(right[::8]), "s", ms=3.5, color="tab:orange", label="right, measured")
    for limit in (design.KNUCKLE_LIMIT, -design.KNUCKLE_LIMIT):
        ax.axhline(deg(limit), color="tab:red", ls="--", lw=1)
    ax.text(-29, deg(design.KNUCKLE_LIMIT) - 3.2, f"knuckle limit ±{design.KNUCKLE_LIMIT} rad",
            color="tab:red", fontsize=9)
    ax.set_xlabel("centre steering angle φ, measured [°]")
    ax.set_ylabel("knuckle angle [°]")
    ax.legend(loc="lower right", fontsize=9)
    err.plot(t, deg(left_error), color="tab:blue", label="left")
    err.plot(t, deg(right_error), color="tab:orange", label="right")
    err.axhspan(-0.5, 0.5, color="tab:green", alpha=0.1, zorder=0, label="±0.5°")
    err.set_ylim(-0.6, 0.6)
    err.set_xlabel("time [s]")
    err.set_ylabel("commanded − measured [°]")
    err.legend(loc="upper right", ncols=3, fontsize=9)


def not_ideal(path: Path) -> None:
    rows, paths = [], []
    predicted = None
    for (label, options), colour in zip(CASES.items(), COLOURS):
        car, slip = turn(**options)
        measured, predicted = steady_radius(car)
        _, x, y, *_ = car.states()
        paths.append((x, y, colour, label))
        rows.append((label, 100 * (measured / predicted - 1), 1000 * slip))
    for fig, (ax, bars), _ in variants(path, 1, 2, figsize=(11, 5.4),
                                       gridspec_kw={"width_ratios": [1, 1.1]}):
        _not_ideal_panels(ax, bars, paths, rows, predicted)


def _not_ideal_panels(ax, bars, paths, rows, predicted):
    """The driven paths against the predicted circle, and each case's radius error and slip."""
    for x, y, colour, label in paths:
        ax.plot(x, y, color=colour, lw=2.2, label=label)
    _predicted(ax, predicted, "black", f"predicted, R = {predicted:.3f} m")
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.legend(loc="lower center", bbox_to_anchor=(0.5, 1.0), fontsize=9)
    names = ["Ackermann,\nown speeds", "Ackermann,\nequal speeds", "parallel,\nown speeds"]
    at = np.arange(len(rows))
    bars.bar(at - 0.2, [r[1] for r in rows], 0.4, color=COLOURS, label="radius error [%]")
    bars.bar(at + 0.2, [r[2] for r in rows], 0.4, color=COLOURS, alpha=0.45, hatch="//",
             label="mean wheel slip [mm/s]")
    for i, (_, e, s) in enumerate(rows):
        bars.text(i - 0.2, e + 0.5, f"{e:+.1f} %", ha="center", fontsize=9)
        bars.text(i + 0.2, s + 0.5, f"{s:.0f}", ha="center", fontsize=9)
    bars.set_xticks(at, names)
    bars.set_ylabel("radius error [%] / wheel slip [mm/s]")
    bars.set_ylim(0, 50)
    bars.legend(loc="upper left")


MEDIA = "media/practice-5"
DESIGN = ["course/practices/practice_5/design.py", "course/parts.py", "course/drawing",
          "course/practices/shared.py"]
SIM = [PACKAGE, "sw2sim/loader.py", "sw2sim/ros_control.py", "sw2sim/render.py", "course/plotting.py"]

FIGURES = [
    *drawing_figures(MEDIA, "chassis", part_drawing, design.chassis, DESIGN, "Drawing of the chassis",
                      phone=True),
    *drawing_figures(MEDIA, "knuckle", part_drawing, design.knuckle, DESIGN, "Drawing of a steering knuckle",
                      phone=True),
    *drawing_figures(MEDIA, "wheel", part_drawing, design.wheel, DESIGN, "Drawing of a wheel",
                      phone=True),
    *drawing_figures(MEDIA, "steering_link", part_drawing, design.steering_link, DESIGN, "Drawing of the steering link",
                      phone=True),
    *drawing_figures(MEDIA, "assembly", assembly_drawing, design.robot, DESIGN + ["course/exporter_format.py"], "Assembly",
                      phone=True),
    Figure(f"{MEDIA}/model.png", model_picture, SIM, "The car in MuJoCo", sharp=True),
    Figure(f"{MEDIA}/path_vs_circle.png", path_vs_circle, SIM, "Driven paths against the predicted circles", phone=True),
    Figure(f"{MEDIA}/knuckle_angles.png", knuckle_angles, SIM, "Knuckle angles against Equation 4", phone=True),
    Figure(f"{MEDIA}/not_ideal.png", not_ideal, SIM, "Equal speeds and parallel steering", phone=True),
    Figure(f"{MEDIA}/rviz.png", rviz_picture(PACKAGE), [PACKAGE], "The vehicle in RViz, as display.launch opens it"),
]

from ...ackermann_diagram import draw as turning_centre  # noqa: E402
FIGURES.append(Figure(f"{MEDIA}/turning_centre.png", turning_centre, ["course/practices/practice_5/design.py"],
                      "The turning centre and Equation 4's triangles", phone=True))
