"""The figures of Practice 2's pages, made from the example package and Practice 1's pulse script."""

from pathlib import Path

import numpy as np

from sw2sim import load_package
from ...media import Figure
from ...plotting import variants
from ...rviz_picture import rviz_picture
from sw2sim.render import render, save_png
from ...sharp import save_render
from .. import load_script
from . import design
from ..shared import assembly_drawing, drawing_figures, part_drawing

import mujoco  # noqa: E402  (after sw2sim has chosen the GL platform)

PACKAGE = "examples/example_2"
PULSE_SCRIPT = "examples/example_1/scripts/periodic_force.py"
WHEEL_JOINTS = [design.joint_name(w) for w in design.SIDES]
FRICTION_WHEEL, FREE_WHEEL = "front_left_joint", "rear_left_joint"
AXIS_RED = (0.75, 0.12, 0.10, 1.0)


def pulses():
    """Practice 1's pulse script, imported from where it lives (no copy of it here)."""
    return load_script(PULSE_SCRIPT)



def model_picture(path: Path) -> None:
    model = load_package(PACKAGE).compile()
    data = mujoco.MjData(model)
    save_render(path, lambda w, h: render(model, data, width=w, height=h, azimuth=125,
                                          elevation=-35), 960, 600)


AXIS_COLOURS = {"front_left_joint": (0.80, 0.10, 0.10, 1), "front_right_joint": (0.10, 0.55, 0.15, 1),
                "rear_left_joint": (0.55, 0.15, 0.70, 1), "rear_right_joint": (0.05, 0.35, 0.80, 1)}


def _axis_lines(spec, length: float = 0.9, radius: float = 0.004) -> None:
    """A thin rod along each wheel's joint axis, through the wheel's centre (visual only), one
    colour per wheel."""
    model = spec.compile()
    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    for name in WHEEL_JOINTS:
        j = model.joint(name).id
        axis, anchor = data.xaxis[j], data.xanchor[j]
        quat = np.zeros(4)
        mujoco.mju_quatZ2Vec(quat, axis)
        spec.worldbody.add_geom(type=mujoco.mjtGeom.mjGEOM_CYLINDER, size=[radius, length / 2, 0],
                                pos=anchor, quat=quat, rgba=AXIS_COLOURS[name], contype=0, conaffinity=0,
                                group=1)


def axes_picture(path: Path) -> None:
    """Each joint's axis as a long line through its wheel, seen from above: four lines, no two alike."""
    spec = load_package(PACKAGE)
    _axis_lines(spec)
    model = spec.compile()
    model.vis.scale.jointlength = 2.0
    model.vis.scale.jointwidth = 0.2
    data = mujoco.MjData(model)
    save_render(path, lambda w, h: render(model, data, width=w, height=h, lookat=[0, 0, 0.15],
                                          distance=1.3, azimuth=90, elevation=-89,
                                          shadows=False, show_joints=True), 960, 600)


def wrong_axis_picture(path: Path) -> None:
    """The front-right wheel turned through half a revolution, with its own axis and with the
    front-left wheel's axis reused: every pose drawn faintly over the others."""
    poses = np.radians(np.arange(0, 180, 30))
    panels = []
    for reused in (False, True):
        spec = load_package(PACKAGE)
        if reused:  # the front-left axis, written in the front-right joint's frame
            spec.joint("front_right_joint").axis = wrong_axis_in_frame("front_right_wheel", "front_left_wheel")
        model = spec.compile()
        data = mujoco.MjData(model)
        q = model.joint("front_right_joint").qposadr[0]
        frames = []
        for angle in poses:
            data.qpos[q] = angle
            frames.append(render(model, data, width=480, height=400, lookat=[0.21, -0.17, 0.15],
                                 distance=0.8, azimuth=115, elevation=-22).astype(float))
        panels.append(np.mean(frames, axis=0).astype(np.uint8))
    titles = ["own axis: the wheel turns in its own plane",
              "front-left axis reused: it tumbles about a diameter"]
    for fig, axes, _ in variants(path, 1, 2, figsize=(10, 4.2)):
        for ax, picture, title in zip(axes, panels, titles):
            ax.imshow(picture)
            ax.set_title(title, fontsize=11)
            ax.set_axis_off()


def wrong_axis_in_frame(link: str, other: str) -> list[float]:
    """The axis of `other`'s joint, written in `link`'s joint frame: what the exporter writes
    when `link`'s joint is given `other`'s reference axis (it keeps only the axis' direction)."""
    yaw = np.radians(design.axle_yaw(*design.SIDES[link]))
    c, s = np.cos(yaw), np.sin(yaw)
    world = np.array(design.axle_direction(other))
    return list(np.round(np.array([[c, s, 0], [-s, c, 0], [0, 0, 1]]) @ world, 12))


def free_run(package: str, fixed_base: bool, duration: float = 3.0):
    """The pulse script's first pulse on every wheel; (times, base travel m, base yaw deg, wheel speeds)."""
    model = load_package(package, fixed_base=fixed_base).compile()
    data = mujoco.MjData(model)
    node = pulses()
    dofs = [model.joint(j).dofadr[0] for j in WHEEL_JOINTS]
    base = data.body("base_link")
    mujoco.mj_forward(model, data)
    start = base.xpos.copy()
    times, travel, yaw, speeds = [], [], [], []
    while data.time < duration:
        data.qfrc_applied[dofs] = node.wheel_torque(data.time)
        times.append(data.time)
        travel.append(np.linalg.norm((base.xpos - start)[:2]))
        R = base.xmat.reshape(3, 3)
        yaw.append(np.degrees(np.arctan2(R[1, 0], R[0, 0])))
        speeds.append(data.qvel[dofs].copy())
        mujoco.mj_step(model, data)
    return np.array(times), np.array(travel), np.array(yaw), np.array(speeds)


def rolling_directions(model, data) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """For each wheel: the point under it on the floor and the way a positive torque would carry it
    if it rolled (its axis crossed with the vertical)."""
    out = {}
    for name in WHEEL_JOINTS:
        j = model.joint(name).id
        axis = data.xaxis[j]
        out[name] = (data.xanchor[j] * [1, 1, 0], np.cross(axis, [0, 0, 1]))
    return out


def unlocked_picture(path: Path) -> None:
    """The free model on the floor at the end of the first pulse, each wheel's rolling direction
    drawn as an arrow on the floor."""
    model = load_package(PACKAGE, fixed_base=False).compile()
    data = mujoco.MjData(model)
    node = pulses()
    dofs = [model.joint(j).dofadr[0] for j in WHEEL_JOINTS]
    while data.time < node.PULSE - 1e-9:
        data.qfrc_applied[dofs] = node.wheel_torque(data.time)
        mujoco.mj_step(model, data)
    mujoco.mj_forward(model, data)
    cam = mujoco.MjvCamera()
    cam.type = mujoco.mjtCamera.mjCAMERA_FREE
    cam.lookat[:], cam.distance, cam.azimuth, cam.elevation = [0.05, 0, 0.0], 1.3, 90, -89
    with mujoco.Renderer(model, 600, 960) as renderer:
        renderer.update_scene(data, camera=cam)
        scene = renderer.scene
        scene.flags[mujoco.mjtRndFlag.mjRND_SHADOW] = False
        radius = design.WHEEL_DIAMETER / 2000
        for floor_point, direction in rolling_directions(model, data).values():
            start = floor_point + radius * direction + [0, 0, 0.004]  # from the front of the tyre
            geom = scene.geoms[scene.ngeom]
            mujoco.mjv_initGeom(geom, mujoco.mjtGeom.mjGEOM_ARROW, np.zeros(3), np.zeros(3), np.zeros(9),
                                np.array(AXIS_RED, dtype=np.float32))
            mujoco.mjv_connector(geom, mujoco.mjtGeom.mjGEOM_ARROW, 0.012, start, start + 0.18 * direction)
            scene.ngeom += 1
        save_png(renderer.render(), path)


def free_base_plot(path: Path) -> None:
    t1, travel1, _, _ = free_run("examples/example_1", False)
    t2, travel2, yaw2, speed2 = free_run(PACKAGE, False)
    t_locked, _, _, speed_locked = free_run(PACKAGE, True)
    i = WHEEL_JOINTS.index(FREE_WHEEL)
    for fig, (ax_x, ax_w), phone in variants(path, 1, 2, figsize=(11, 4)):
        for ax in (ax_x, ax_w):
            ax.axvspan(0, 1, color="0.5", alpha=0.15, label="1 N·m on each wheel")
            ax.set_xlabel("time [s]")
        ax_x.plot(t1, travel1, label="Practice 1, base free")
        ax_x.plot(t2, travel2, label="Practice 2, base free", lw=2.2)
        ax_x.set_ylabel("distance moved [m]" if phone else "distance the base has moved [m]")
        ax_x.legend(loc="upper left")
        ax_w.plot(t_locked, speed_locked[:, i], label="base locked to the world")
        ax_w.plot(t2, speed2[:, i], label="base free, wheels on the floor", lw=2.2)
        ax_w.set_ylabel(f"{FREE_WHEEL} speed [rad/s]")
        ax_w.legend(loc="center right")


def axial_inertia(model, data, joint: str) -> float:
    """The inertia a joint's torque has to accelerate: that joint's entry on the mass matrix' diagonal."""
    M = np.zeros((model.nv, model.nv))
    mujoco.mj_forward(model, data)
    mujoco.mj_fullM(model, data, M)
    dof = model.joint(joint).dofadr[0]
    return float(M[dof, dof])


def friction_velocity(path: Path) -> None:
    model = load_package(PACKAGE).compile()
    data = mujoco.MjData(model)
    inertia = axial_inertia(model, data, FRICTION_WHEEL)
    node = pulses()
    t, tau, omega = node.run(model, data, WHEEL_JOINTS, duration=30.0)
    fr, free = WHEEL_JOINTS.index(FRICTION_WHEEL), WHEEL_JOINTS.index(FREE_WHEEL)
    labels = {free: f"{FREE_WHEEL}: no friction", fr: f"{FRICTION_WHEEL}: friction {design.FRICTION} N·m"}
    up, down = (node.TORQUE - design.FRICTION) / inertia, design.FRICTION / inertia
    stop = node.PULSE + up * node.PULSE / down
    for fig, ((ax_w, ax_z), (ax_t, ax_tz)), phone in variants(
            path, 2, 2, figsize=(11, 5.2), sharex="col",
            gridspec_kw={"height_ratios": [3, 1], "width_ratios": [2, 1]}):
        for ax in (ax_w, ax_z):
            ax.plot(t, omega[:, free], label=labels[free], color="tab:blue")
            ax.plot(t, omega[:, fr], label=labels[fr], color="tab:orange", lw=2.2)
            ax.set_ylabel("wheel speed [rad/s]")
        ax_w.legend(loc="upper left")
        ax_z.set_xlim(-0.05, 2.0)
        ax_z.set_ylim(-1, 25)
        ax_z.set_title("the first 2 s, closer", fontsize=11)
        ax_z.annotate(f"{node.TORQUE - design.FRICTION:.1f} N·m net:\n+{up:.1f} rad/s²", (0.55, 0.55 * up),
                      xytext=(0.6, 3), fontsize=9, arrowprops={"arrowstyle": "-", "color": "0.4"})
        ax_z.annotate(f"friction alone:\n−{down:.1f} rad/s²,\nstops at {stop:.2f} s", (1.2, up - 0.2 * down),
                      xytext=(1.3, 12), fontsize=9, arrowprops={"arrowstyle": "-", "color": "0.4"})
        for ax in (ax_t, ax_tz):
            ax.plot(t, tau, color="tab:red", drawstyle="steps-post")
            ax.set_ylabel("torque [N·m]")
            ax.set_xlabel("time [s]")
        ax_t.set_xticks(np.arange(0, 31, 5))


MEDIA = "media/practice-2"
DESIGN = ["course/practices/practice_2/design.py", "course/practices/practice_1/design.py",
          "course/parts.py", "course/drawing",
          "course/practices/shared.py"]
SIM = [PACKAGE, "sw2sim/loader.py", "sw2sim/render.py", "course/plotting.py"]
PULSE = [PULSE_SCRIPT]

FIGURES = [
    *drawing_figures(MEDIA, "base", part_drawing, design.base, DESIGN, "Drawing of the base",
                      phone=True),
    *drawing_figures(MEDIA, "assembly", assembly_drawing, design.robot, DESIGN + ["course/exporter_format.py"], "Assembly",
                      phone=True),
    Figure(f"{MEDIA}/model.png", model_picture, SIM, "The model in MuJoCo", sharp=True),
    Figure(f"{MEDIA}/joint_axes.png", axes_picture, SIM, "Joint axes", sharp=True),
    Figure(f"{MEDIA}/wrong_axis.png", wrong_axis_picture, SIM + ["course/practices/practice_2/design.py"],
           "A reused axis", phone=True),
    Figure(f"{MEDIA}/unlocked_base.png", unlocked_picture, SIM + PULSE, "A base that is not locked"),
    Figure(f"{MEDIA}/free_base.png", free_base_plot, SIM + PULSE + ["examples/example_1"], "Free and locked base", phone=True),
    Figure(f"{MEDIA}/friction_velocity.png", friction_velocity, SIM + PULSE, "Wheel speed with and without friction", phone=True),
    Figure(f"{MEDIA}/rviz.png", rviz_picture(PACKAGE), [PACKAGE], "Practice 2's robot in RViz, as display.launch opens it"),
]
