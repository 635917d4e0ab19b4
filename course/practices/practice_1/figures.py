"""The figures of Practice 1's pages, made from the example package and its scripts."""

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

PACKAGE = "examples/example_1"
WHEEL_JOINTS = [name.replace("_wheel", "_joint") for name in design.WHEELS]


def pulses():
    return load_script(f"{PACKAGE}/scripts/periodic_force.py")




def model_picture(path: Path) -> None:
    model = load_package(PACKAGE).compile()
    data = mujoco.MjData(model)
    save_render(path, lambda w, h: render(model, data, width=w, height=h, azimuth=135,
                                          elevation=-28), 960, 600)


def axes_picture(path: Path) -> None:
    """Joint axes drawn as arrows: two wheels share each axis line."""
    model = load_package(PACKAGE).compile()
    model.vis.scale.jointlength = 3.0
    model.vis.scale.jointwidth = 0.25
    model.geom_rgba[:, 3] = np.where(model.geom_group == 1, 0.45, model.geom_rgba[:, 3])
    data = mujoco.MjData(model)
    save_render(path, lambda w, h: render(model, data, width=w, height=h, azimuth=150,
                                          elevation=-50, show_joints=True, shadows=False),
                960, 600)


def base_run(fixed_base: bool, duration: float, frames=()):
    """Push the wheels with the pulse script; return (t, distance the base moved, pictures at `frames`)."""
    model = load_package(PACKAGE, fixed_base=fixed_base).compile()
    data = mujoco.MjData(model)
    node = pulses()
    base = model.body("base_link").id
    dofs = [model.joint(j).dofadr[0] for j in WHEEL_JOINTS]
    mujoco.mj_forward(model, data)
    start = data.xpos[base].copy()
    times, moved, pictures = [], [], []
    pending = sorted(frames)
    while data.time < duration:
        data.qfrc_applied[dofs] = node.wheel_torque(data.time)
        if pending and data.time >= pending[0] - 1e-9:
            pending.pop(0)
            pictures.append(render(model, data, width=640, height=360, lookat=[0.75, 0, 0.12],
                                   distance=1.9, azimuth=90, elevation=-8))
        times.append(data.time)
        moved.append(np.linalg.norm(data.xpos[base] - start))
        mujoco.mj_step(model, data)
    return np.array(times), np.array(moved), pictures


def unlocked_strip(path: Path) -> None:
    moments = [0.0, 0.5, 1.0, 1.5]
    _, _, pictures = base_run(False, max(moments) + 0.01, frames=moments)
    for fig, axes, _ in variants(path, 1, len(pictures), figsize=(12, 2.4), phone_grid=(2, 2),
                                    phone_figsize=(5.0, 3.5)):
        for ax, pic, t in zip(axes, pictures, moments):
            ax.imshow(pic)
            ax.set_title(f"t = {t:.1f} s")
            ax.set_axis_off()


def base_drift(path: Path) -> None:
    duration = 3.0
    t_free, x_free, _ = base_run(False, duration)
    t_locked, x_locked, _ = base_run(True, duration)
    for fig, ax, phone in variants(path, figsize=(8.0, 4.2)):
        ax.axvspan(0, 1, color="0.5", alpha=0.15, label="1 N·m on each wheel")
        ax.plot(t_free, x_free, label="base free (no world joint)")
        ax.plot(t_locked, x_locked, label="base locked to the world")
        ax.set_xlabel("time [s]")
        ax.set_ylabel("distance moved [m]" if phone else "distance the base has moved [m]")
        ax.legend(loc="upper left")


def wheel_velocity(path: Path) -> None:
    model = load_package(PACKAGE).compile()
    data = mujoco.MjData(model)
    t, tau, omega = pulses().run(model, data, WHEEL_JOINTS, duration=30.0)
    for fig, (ax_w, ax_t), phone in variants(path, 2, 1, sharex=True, figsize=(8, 5),
                                             gridspec_kw={"height_ratios": [3, 1]}):
        for i, name in enumerate(WHEEL_JOINTS):
            ax_w.plot(t, omega[:, i], label=name, lw=2.2 if i == 0 else 1.2,
                      ls="-" if i == 0 else (0, (4, 2 + i)))
        ax_w.set_ylabel("wheel speed [rad/s]")
        ax_w.legend(ncols=1, loc="lower right") if phone else ax_w.legend(ncols=2, loc="upper left")
        ax_t.plot(t, tau, color="tab:red", drawstyle="steps-post")
        ax_t.set_ylabel("torque [N·m]")
        ax_t.set_xlabel("time [s]")
        ax_t.set_xticks(np.arange(0, 31, 5))


MEDIA = "media/practice-1"
DESIGN = ["course/practices/practice_1/design.py", "course/parts.py", "course/drawing",
          "course/practices/shared.py"]
SIM = [PACKAGE, "sw2sim/loader.py", "sw2sim/render.py", "course/plotting.py"]

FIGURES = [
    *drawing_figures(MEDIA, "base", part_drawing, design.base, DESIGN, "Drawing of the base",
                      phone=True),
    *drawing_figures(MEDIA, "wheel", part_drawing, design.wheel, DESIGN, "Drawing of the wheel",
                      phone=True),
    *drawing_figures(MEDIA, "assembly", assembly_drawing, design.robot, DESIGN + ["course/exporter_format.py"], "Assembly",
                      phone=True),
    Figure(f"{MEDIA}/model.png", model_picture, SIM, "The model in MuJoCo", sharp=True),
    Figure(f"{MEDIA}/joint_axes.png", axes_picture, SIM, "Joint axes", sharp=True),
    Figure(f"{MEDIA}/unlocked_base.png", unlocked_strip, SIM, "A base that is not locked", phone=True),
    Figure(f"{MEDIA}/base_drift.png", base_drift, SIM, "Locked and free base", phone=True),
    Figure(f"{MEDIA}/wheel_velocity.png", wheel_velocity, SIM, "Wheel speed under pulses", phone=True),
    Figure(f"{MEDIA}/rviz.png", rviz_picture(PACKAGE), [PACKAGE], "Practice 1's robot in RViz, as display.launch opens it"),
]

from ...dialog_schematics_phone import joint_window_figure, link_window_figure, property_manager_figure  # noqa: E402
FIGURES += [
    Figure("media/practice-1/exporter_panel.svg", property_manager_figure, [], "The exporter's link tree panel",
           phone=True),
    Figure("media/practice-1/exporter_joints.svg", joint_window_figure, [], "Configure Joint Properties",
           phone=True),
    Figure("media/practice-1/exporter_links.svg", link_window_figure, [], "Configure Link Properties",
           phone=True),
]
