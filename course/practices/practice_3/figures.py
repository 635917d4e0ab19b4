"""The figures of Practice 3's pages, made from the example package and its scripts."""

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

PACKAGE = "examples/example_3"
SCRIPTS = f"{PACKAGE}/scripts"


def controller():
    return load_script(f"{SCRIPTS}/arm_controller.py")




def posed(model, angles):
    data = mujoco.MjData(model)
    for joint, angle in zip(design.JOINTS, angles):
        data.qpos[model.joint(joint).qposadr[0]] = angle
    mujoco.mj_forward(model, data)
    return data


def model_picture(path: Path) -> None:
    model = load_package(PACKAGE).compile()
    data = posed(model, (0.35, -0.6))
    save_render(path, lambda w, h: render(model, data, width=w, height=h,
                                          lookat=[0.2, 0.06, 0.12], distance=0.78,
                                          azimuth=300, elevation=-35), 960, 600)


def tip_positions(model, angles):
    """Pivot, elbow and tool tip (x, y) for joint angles (rad), from the model's kinematics."""
    data = posed(model, angles)
    pivot = data.body("middle_arm_link").xpos
    elbow = data.body("end_arm_link").xpos
    end = data.body("end_arm_link")
    tip = end.xpos + end.xmat.reshape(3, 3) @ np.array(design.tool_tip())
    return pivot[:2], elbow[:2], tip[:2]


def reach(path: Path) -> None:
    """Top view: the arm straight, and with both joints at +45° and -45°; the 67.5° angle marked."""
    model = load_package(PACKAGE).compile()
    limit = model.jnt_range[model.joint("middle_arm_joint").id][1]
    L = design.ARM_LENGTH / 1000
    for fig, ax, phone in variants(path, figsize=(7, 6.2), phone_figsize=(5.0, 6.1)):
        a = np.linspace(0, 2 * np.pi, 200)
        ax.plot(L * np.cos(a), L * np.sin(a), color="0.75", lw=1, ls="--")
        for sign, colour in ((1, "tab:orange"), (-1, "tab:purple")):
            pivot, elbow, tip = tip_positions(model, (sign * limit, sign * limit))
            ax.plot(elbow[0] + L * np.cos(a), elbow[1] + L * np.sin(a), color=colour, lw=0.8, ls=":", alpha=0.7)
            ax.plot(*np.transpose([pivot, elbow, tip]), "-o", color=colour, lw=3,
                    label=f"both joints at {sign * math.degrees(limit):+.0f}°")
            phi = math.degrees(math.atan2(tip[1] - pivot[1], tip[0] - pivot[0]))
            ax.plot(*np.transpose([pivot, tip]), color=colour, lw=1.2, ls="--")
            arc = np.radians(np.linspace(0, phi, 60))
            ax.plot(0.13 * np.cos(arc), 0.13 * np.sin(arc), color=colour, lw=1.2)
            ax.annotate(f"{phi:+.1f}°", (0.15 * math.cos(math.radians(phi / 2)), 0.15 * math.sin(math.radians(phi / 2))),
                        color=colour, fontsize=12, va="center")
        pivot, elbow, tip = tip_positions(model, (0, 0))
        ax.plot(*np.transpose([pivot, elbow, tip]), "-o", color="0.35", lw=3, label="both joints at 0°")
        ax.set_aspect("equal")
        ax.set_xlim(-0.3, 0.55)
        ax.set_ylim(-0.64 if phone else -0.5, 0.5)   # on a phone the key goes under the arm
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
        ax.legend(loc="lower right" if phone else "lower left")


def pid_alone(c):
    """Make a controller a bare PID on the set point, as if the URDF had no velocity limit."""
    def lead(dt):
        c.reference, c.reference_speed = c.setpoint, 0.0
    c.lead = lead
    c.enforce_limits = lambda torque, q, v: torque


def step_speeds(enforce: bool, seconds=1.5):
    """Both joints stepped from -45° to +45°; return time and joint speeds (every physics step)."""
    ctl = controller()
    arm = ctl.Arm()
    arm.command(middle_arm_controller=-design.LIMIT, end_arm_controller=-design.LIMIT)
    arm.run(1.5)
    if not enforce:
        for c in arm.controllers.values():
            pid_alone(c)
    arm.command(middle_arm_controller=design.LIMIT, end_arm_controller=design.LIMIT)
    t0, times, speeds = arm.data.time, [], []
    for _ in range(round(seconds / ctl.TIMESTEP)):
        arm.step()
        times.append(arm.data.time - t0)
        speeds.append([arm.data.qvel[c.dof] for c in arm.controllers.values()])
    return np.array(times), np.array(speeds)


def velocity_limit(path: Path) -> None:
    runs = {enforce: step_speeds(enforce) for enforce in (False, True)}
    for fig, axes, phone in variants(path, 1, 2, sharey=True, figsize=(10, 3.6)):
        for ax, enforce, title in ((axes[0], False, "PID alone"), (axes[1], True, "velocity limit enforced")):
            t, w = runs[enforce]
            ax.plot(t, w[:, 0], label="middle_arm_joint")
            ax.plot(t, w[:, 1], label="end_arm_joint", ls="--")
            ax.axhline(design.VELOCITY, color="tab:red", lw=1, label="limit, 2 rad/s")
            ax.set_title(title)
            ax.set_xlabel("time after the step [s]")
            if phone or not enforce:
                ax.set_ylabel("joint speed [rad/s]")
        axes[1].legend(loc="upper right")


def random_run(seconds=30, seed=4):
    script = load_script(f"{SCRIPTS}/random_setpoints.py")
    arm = script.Arm()
    script.random_setpoints(arm, seconds, seed=seed)
    return arm


def setpoints(path: Path) -> None:
    arm = random_run()
    t = arm.times()
    for fig, axes, phone in variants(path, 2, 2, sharex=True, figsize=(11, 5.4),
                                     gridspec_kw={"height_ratios": [3, 1.4]}):
        for col, name in enumerate(arm.controllers):
            top, bottom = axes[0, col], axes[1, col]
            top.plot(t, arm.states(name, "set_point"), drawstyle="steps-post", color="tab:red", label="set point")
            top.plot(t, arm.states(name, "process_value"), color="tab:blue", label="position")
            top.axhline(design.LIMIT, color="0.6", lw=0.8, ls=":")
            top.axhline(-design.LIMIT, color="0.6", lw=0.8, ls=":")
            top.set_title(name)
            bottom.plot(t, arm.states(name, "error"), color="tab:green")
            bottom.set_xlabel("time [s]")
            bottom.set_xticks(np.arange(0, t[-1] + 1, 5))
            if phone or col == 0:
                top.set_ylabel("angle [rad]")
                bottom.set_ylabel("error [rad]")
        axes[0, 1].legend(loc="lower right")


MEDIA = "media/practice-3"
DESIGN = ["course/practices/practice_3/design.py", "course/parts.py", "course/drawing",
          "course/practices/shared.py"]
SIM = [PACKAGE, "sw2sim/loader.py", "sw2sim/ros_control.py", "sw2sim/render.py", "course/plotting.py"]

FIGURES = [
    *drawing_figures(MEDIA, "base", part_drawing, design.base, DESIGN, "Drawing of the base",
                      phone=True),
    *drawing_figures(MEDIA, "middle_arm", part_drawing, design.middle_arm, DESIGN, "Drawing of the middle arm",
                      phone=True),
    *drawing_figures(MEDIA, "end_arm", part_drawing, design.end_arm, DESIGN, "Drawing of the end arm",
                      phone=True),
    *drawing_figures(MEDIA, "assembly", assembly_drawing, design.robot, DESIGN + ["course/exporter_format.py"], "Assembly",
                      phone=True),
    Figure(f"{MEDIA}/model.png", model_picture, SIM, "The arm in MuJoCo", sharp=True),
    Figure(f"{MEDIA}/reach.png", reach, SIM, "The arm's reach at its limits", phone=True),
    Figure(f"{MEDIA}/velocity_limit.png", velocity_limit, SIM, "Joint speed with and without the limit", phone=True),
    Figure(f"{MEDIA}/random_setpoints.png", setpoints, SIM, "Set point, position and error", phone=True),
    Figure(f"{MEDIA}/rviz.png", rviz_picture(PACKAGE), [PACKAGE], "The arm in RViz, as display.launch opens it"),
]
