"""The figures of Practice 4's pages, made from the example package and its script."""

import shutil
import tempfile
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

PACKAGE = "examples/example_4"
SCRIPT = f"{PACKAGE}/scripts/slider_controller.py"
TYPO = 26.9                   # m: 2.69 with the decimal point one place too far right
FRICTIONS = np.arange(0.0, 301.0, 25.0)   # N, <dynamics friction> of the block's joint
STALL = 0.5                   # a move that covers less than this share in 3 s has stalled


def script():
    return load_script(SCRIPT)




def posed(model, position):
    data = mujoco.MjData(model)
    data.qpos[model.joint(design.JOINT).qposadr[0]] = position
    mujoco.mj_forward(model, data)
    return data


def picture(model, position, **view):
    settings = dict(width=960, height=520, lookat=[1.45, 0.0, 0.1], distance=3.1,
                    azimuth=240, elevation=-20, shadows=False)
    settings.update(view)
    return render(model, posed(model, position), **settings)


def model_picture(path: Path) -> None:
    model = load_package(PACKAGE).compile()
    save_render(path, lambda w, h: picture(model, 1.2, width=w, height=h), 960, 520)


def typo_package(folder: Path, upper: float = TYPO) -> Path:
    """A copy of example_4 whose upper limit (and soft upper limit) reads `upper`."""
    target = Path(folder) / "example_4"
    shutil.copytree(PACKAGE, target, ignore=shutil.ignore_patterns("scripts", "__pycache__"))
    urdf = target / "urdf" / "example_4.urdf"
    text = urdf.read_text()
    urdf.write_text(text.replace('upper="2.69"', f'upper="{upper:g}"')
                    .replace('soft_upper_limit="2.69"', f'soft_upper_limit="{upper:g}"'))
    return target


def drive_to_the_end(package, seconds):
    """Command the upper limit (the end of the GUI slider); return the slider and its log."""
    slider = script().Slider(package)
    slider.command(slider.limits.upper)
    slider.run(seconds)
    return slider


def limit_typo(path: Path) -> None:
    with tempfile.TemporaryDirectory() as tmp:
        right = drive_to_the_end(PACKAGE, 30.0)
        typo = drive_to_the_end(typo_package(Path(tmp)), 30.0)
        model = load_package(Path(tmp) / "example_4").compile()
        image = picture(model, 3.6, lookat=[2.8, 0.0, 0.1], distance=2.0, azimuth=250,
                        elevation=-12)
    for fig, (ax, pic), phone in variants(path, 1, 2, figsize=(12, 4.4),
                                          gridspec_kw={"width_ratios": [1, 1.25]}):
        for slider, label, colour in ((right, 'upper="2.69"', "tab:blue"), (typo, f'upper="{TYPO:g}"', "tab:red")):
            t, _, q, _, _ = slider.states()
            ax.plot(t, q, color=colour, lw=2, label=label)
        ax.axhspan(0, design.bar_end(), color="0.85", zorder=0)
        ax.text(29, design.bar_end() + 0.5, f"on the bar (up to {design.bar_end():.2f} m)", ha="right",
                va="bottom", fontsize=10, color="0.3")
        ax.set_xlabel("time after the command [s]")
        ax.set_ylabel("block position [m]")
        ax.set_xlim(0, 30)
        ax.set_ylim(0, 28)
        ax.legend(loc="upper left", title="the same command: go to the upper limit")
        pic.imshow(image)
        pic.set_axis_off()
        pic.set_title("with the typo, 3.6 m: the block has left the bar", fontsize=11)


def friction_run(friction, distance=1.0, seconds=3.0):
    """A move of `distance` from 0 with the joint's friction set to `friction` N.

    Returns (force to start, force to keep moving, share of the move done in `seconds`).
    The force to keep moving is the mean force while the block runs at a steady speed;
    it is nan when the block never got going.
    """
    slider = script().Slider()
    slider.model.dof_frictionloss[slider.controller.dof] = friction
    slider.command(distance)
    slider.run(seconds)
    t, _, q, v, f = slider.states()
    start = np.abs(f[t <= 0.5]).max()
    moving = np.abs(v) > 0.1
    keep = np.median(np.abs(f[moving])) if moving.sum() > 10 else np.nan
    return start, keep, q[-1] / distance


def effort_vs_friction(path: Path) -> None:
    runs = np.array([friction_run(f) for f in FRICTIONS])
    stalled = runs[:, 2] < STALL
    first = FRICTIONS[stalled][0]
    for fig, (ax, done), phone in variants(path, 1, 2, figsize=(11, 4.2),
                                           gridspec_kw={"width_ratios": [1.4, 1]}):
        ax.plot(FRICTIONS, runs[:, 0], "o-", color="tab:orange", label="to start (largest force)")
        ax.plot(FRICTIONS, runs[:, 1], "s-", color="tab:blue", label="to keep moving (median while it moves)")
        ax.axhline(design.EFFORT, color="tab:red", lw=1.2, ls="--", label=f"effort limit, {design.EFFORT:g} N")
        for a in (ax, done):
            a.axvspan(first - 12.5, FRICTIONS[-1] + 12.5, color="tab:red", alpha=0.08, zorder=0)
            a.set_xlabel('joint friction, <dynamics friction="…"> [N]')
            a.set_xlim(-12.5, FRICTIONS[-1] + 12.5)
        ax.text(first, 20, " stalls", color="tab:red", fontsize=10)
        ax.set_ylabel("force from the controller [N]")
        ax.set_ylim(0, 260)
        ax.legend(loc="upper left")
        done.bar(FRICTIONS, 100 * runs[:, 2], width=18, color=np.where(stalled, "tab:red", "tab:green"))
        done.set_ylabel("share of a 1 m move done in 3 s [%]")
        done.set_ylim(0, 110)


def long_move(seconds=4.0):
    """The whole travel, 0 to 2.69 m; the slider and its log at every physics step."""
    s = script()
    slider = s.Slider()
    slider._every = 1          # log every step, not 20 times a second
    slider.command(design.UPPER)
    slider.run(seconds)
    return slider


def velocity_limited_move(path: Path) -> None:
    slider = long_move()
    t, sp, q, v, f = slider.states()
    for fig, (a, b, c), phone in variants(path, 3, 1, sharex=True, figsize=(8, 7.2)):
        a.plot(t, sp, color="tab:red", drawstyle="steps-post", label="set point")
        a.plot(t, q, color="tab:blue", label="position")
        a.set_ylabel("position [m]")
        a.legend(loc="lower right")
        b.plot(t, v, color="tab:blue")
        b.axhline(design.VELOCITY, color="tab:red", ls="--", lw=1.2, label=f"velocity limit, {design.VELOCITY:g} m/s")
        b.set_ylabel("speed [m/s]")
        b.set_ylim(0, 1.2)
        b.legend(loc="lower center")
        c.plot(t, f, color="tab:blue", label="force from the controller")
        c.axhline(design.EFFORT, color="tab:red", ls="--", lw=1.2, label=f"effort limit, ±{design.EFFORT:g} N")
        c.axhline(-design.EFFORT, color="tab:red", ls="--", lw=1.2)
        c.set_ylabel("force [N]")
        c.set_ylim(-230, 230)
        c.set_xlabel("time [s]")
        if phone:   # one column, between the force and the lower limit
            c.legend(loc="center", bbox_to_anchor=(0.5, 0.27))
        else:
            c.legend(loc="upper right", ncols=2)


def viewer_sliders(path: Path) -> None:
    """The model with the viewer's position actuator, and a sketch of the viewer's Control panel."""
    model = script().viewer_model()
    name = model.actuator(0).name
    low, high = model.actuator_ctrlrange[0]
    value = 1.5
    data = mujoco.MjData(model)
    data.ctrl[0] = value
    for _ in range(round(3.0 / model.opt.timestep)):
        mujoco.mj_step(model, data)
    image = render(model, data, width=900, height=560, lookat=[1.45, 0.0, 0.1], distance=3.1,
                   azimuth=240, elevation=-20, shadows=False)
    for fig, (pic, panel), phone in variants(path, 1, 2, figsize=(12, 4.3),
                                             gridspec_kw={"width_ratios": [1.7, 1]}):
        pic.imshow(image)
        pic.set_axis_off()
        pic.set_title(f"the block after the slider was set to {value:g} m", fontsize=11)
        panel.set_xlim(0, 10)
        panel.set_ylim(0, 10)
        panel.set_axis_off()
        panel.add_patch(_box(0.2, 0.5, 9.6, 9.0, "#3b3f45"))
        panel.add_patch(_box(0.4, 8.2, 9.2, 1.0, "#5a6068"))
        panel.text(0.8, 8.7, "Control", color="white", fontsize=12, va="center", weight="bold")
        panel.add_patch(_box(0.8, 6.6, 3.6, 1.0, "#6c737c"))
        panel.text(2.6, 7.1, "Clear all", color="white", fontsize=10, ha="center", va="center")
        panel.text(0.8, 5.3, name, color="white", fontsize=11, va="center")
        panel.add_patch(_box(4.6, 4.85, 4.8, 0.9, "#23262a"))
        share = (value - low) / (high - low)
        panel.add_patch(_box(4.6, 4.85, 4.8 * share, 0.9, "#4f7fb8"))
        panel.text(7.0, 5.3, f"{value:.2f}", color="white", fontsize=10, ha="center", va="center")
        panel.text(4.6, 4.3, f"{low:g}", color="#c8ccd2", fontsize=9, va="top")
        panel.text(9.4, 4.3, f"{high:g}", color="#c8ccd2", fontsize=9, va="top", ha="right")
        panel.text(5.0, 2.2, "a sketch of the viewer's panel: one slider\nper actuator, from its ctrlrange",
                   color="#c8ccd2", fontsize=9.5, ha="center", va="center", style="italic")


def _box(x, y, w, h, colour):
    from matplotlib.patches import Rectangle
    return Rectangle((x, y), w, h, facecolor=colour, edgecolor="none")


MEDIA = "media/practice-4"
DESIGN = ["course/practices/practice_4/design.py", "course/parts.py", "course/drawing",
          "course/practices/shared.py"]
SIM = [PACKAGE, "examples/example_3/scripts/arm_controller.py", "sw2sim/loader.py",
       "sw2sim/ros_control.py", "sw2sim/render.py", "course/plotting.py"]

FIGURES = [
    *drawing_figures(MEDIA, "bar", part_drawing, design.bar, DESIGN, "Drawing of the bar with its end plates",
                      phone=True),
    *drawing_figures(MEDIA, "block", part_drawing, design.block, DESIGN, "Drawing of the block",
                      phone=True),
    *drawing_figures(MEDIA, "assembly", assembly_drawing, design.robot, DESIGN + ["course/exporter_format.py"], "Assembly",
                      phone=True),
    Figure(f"{MEDIA}/model.png", model_picture, SIM, "The bar and block in MuJoCo", sharp=True),
    Figure(f"{MEDIA}/limit_typo.png", limit_typo, SIM, "A typo in the upper limit", phone=True),
    Figure(f"{MEDIA}/viewer_sliders.png", viewer_sliders, SIM, "The viewer's slider, sketched", phone=True),
    Figure(f"{MEDIA}/velocity_limited_move.png", velocity_limited_move, SIM, "A move set by the velocity limit", phone=True),
    Figure(f"{MEDIA}/effort_vs_friction.png", effort_vs_friction, SIM, "Force needed against friction", phone=True),
    Figure(f"{MEDIA}/rviz.png", rviz_picture(PACKAGE), [PACKAGE], "The bar and its block in RViz, as display.launch opens it"),
]
