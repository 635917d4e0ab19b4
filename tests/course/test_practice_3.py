"""What the Practice 3 pages claim, checked against the model and its controllers."""

import math
import shutil

import mujoco
import numpy as np
import pytest
from page_text import squash, xml_blocks
import yaml

import sw2sim
from course.practices import ROOT, load_script
from course.practices.practice_3 import design, figures
from sw2sim.ros_control import add_motors, read_joint_limits, read_transmissions

PACKAGE = ROOT / "examples" / "example_3"
PAGES = ROOT / "_pages" / "practice-3"
CONFIG = PACKAGE / "config" / "joint_names_example_3.yaml"
LIMIT = 0.7854
CONTROLLERS = ["middle_arm_controller", "end_arm_controller"]


def page(name: str) -> str:
    return (PAGES / name).read_text()


@pytest.fixture(scope="module")
def ctl():
    return load_script("examples/example_3/scripts/arm_controller.py")


class Watch:
    """Step an Arm and keep the extremes of its joint speeds and positions, at every physics step."""

    def __init__(self, arm):
        self.arm = arm
        self.top_speed = np.zeros(2)
        self.lowest = np.full(2, np.inf)
        self.highest = np.full(2, -np.inf)
        self.largest_torque = 0.0

    def run(self, seconds, ctl):
        a = self.arm
        dofs = [c.dof for c in a.controllers.values()]
        for _ in range(round(seconds / ctl.TIMESTEP)):
            a.step()
            q, v = a.data.qpos[dofs], a.data.qvel[dofs]
            self.top_speed = np.maximum(self.top_speed, np.abs(v))
            self.lowest = np.minimum(self.lowest, q)
            self.highest = np.maximum(self.highest, q)
            self.largest_torque = max(self.largest_torque, float(np.abs(a.data.ctrl).max()))


def settle_time(arm, ctl, targets, seconds=2.5, tolerance=0.01):
    """Command `targets` and return, per controller, the last time (s after the command) its error exceeded tolerance."""
    arm.command(**dict(zip(CONTROLLERS, targets)))
    last = np.zeros(2)
    for k in range(round(seconds / ctl.TIMESTEP)):
        arm.step()
        for i, c in enumerate(arm.controllers.values()):
            if abs(c.setpoint - arm.data.qpos[c.qpos]) > tolerance:
                last[i] = (k + 1) * ctl.TIMESTEP
    return last


STEPS = [  # (start, target) for (middle, end)
    ((0, 0), (LIMIT, LIMIT)),
    ((-LIMIT, -LIMIT), (LIMIT, LIMIT)),
    ((LIMIT, -LIMIT), (-LIMIT, LIMIT)),
    ((0, 0), (LIMIT, 0)),
    ((0, 0), (0, -LIMIT)),
    ((0.3, -0.2), (0.32, -0.15)),
]


@pytest.mark.parametrize("start,target", STEPS)
def test_each_joint_settles_within_a_hundredth_of_a_radian_in_two_seconds(ctl, start, target):
    arm = ctl.Arm()
    settle_time(arm, ctl, start, seconds=2.5)
    last = settle_time(arm, ctl, target)
    assert np.all(last < 2.0), f"step {start} -> {target}: settled after {last} s"
    for c, goal in zip(arm.controllers.values(), target):
        assert arm.data.qpos[c.qpos] == pytest.approx(goal, abs=0.01)


@pytest.fixture(scope="module")
def hard_run(ctl):
    """Full-range steps, commands outside the limits and random set points, watched at every step."""
    random_script = load_script("examples/example_3/scripts/random_setpoints.py")
    arm = ctl.Arm()
    watch = Watch(arm)
    for targets in [(LIMIT, LIMIT), (-LIMIT, -LIMIT), (LIMIT, -LIMIT), (-LIMIT, LIMIT), (1.5, -3.0), (0, 0)]:
        arm.command(**dict(zip(CONTROLLERS, targets)))
        watch.run(2.0, ctl)
    rng = np.random.default_rng(11)
    for _ in range(12):
        arm.command(**{name: rng.uniform(-LIMIT, LIMIT) for name in CONTROLLERS})
        watch.run(1.5, ctl)
    arm.log.clear()
    start = arm.data.time
    random_script.random_setpoints(arm, 20, seed=3)
    return arm, watch, start, random_script


def test_positions_never_leave_the_limits_by_more_than_a_hundredth(hard_run):
    _, watch, *_ = hard_run
    assert np.all(watch.lowest >= -LIMIT - 0.01), watch.lowest
    assert np.all(watch.highest <= LIMIT + 0.01), watch.highest
    # and the runs did reach the limits: the test would catch a joint that went past them
    assert np.all(watch.highest > LIMIT - 0.01) and np.all(watch.lowest < -LIMIT + 0.01)


def test_joint_speed_never_exceeds_the_limit_by_more_than_five_percent(hard_run):
    _, watch, *_ = hard_run
    assert np.all(watch.top_speed <= 2.0 * 1.05), watch.top_speed
    assert np.all(watch.top_speed > 1.8), "the full-range steps should run near the limit"


def test_commands_outside_the_limits_are_clipped_to_them(ctl):
    arm = ctl.Arm()
    arm.command(middle_arm_controller=1.5, end_arm_controller=-3.0)
    assert [c.setpoint for c in arm.controllers.values()] == [LIMIT, -LIMIT]


def test_a_bare_pid_would_break_the_velocity_limit():
    """The velocity-limit figure's left panel: without the lead and the clamp, far over 2 rad/s."""
    _, speeds = figures.step_speeds(enforce=False, seconds=0.5)
    assert np.abs(speeds).max() > 5.0
    _, speeds = figures.step_speeds(enforce=True, seconds=0.5)
    assert np.abs(speeds).max() <= 2.0 * 1.05


def test_random_setpoints_change_every_five_seconds_within_the_limits(hard_run):
    arm, _, start, script = hard_run
    assert script.PERIOD == 5.0 and 1 / script.PERIOD == pytest.approx(0.2)
    t = arm.times() - start
    for name in CONTROLLERS:
        sp = arm.states(name, "set_point")
        changes = t[1:][np.diff(sp) != 0]
        assert changes == pytest.approx([5.0, 10.0, 15.0], abs=1e-6)
        assert np.all(np.abs(sp) <= LIMIT)
        error = np.abs(arm.states(name, "error"))
        held = (t + 1e-6) % 5.0 > 2.0
        assert error[held].max() < 0.01


def test_joint_states_are_sampled_at_the_yaml_rate(hard_run):
    arm, *_ = hard_run
    assert arm.state_rate == 20
    assert np.diff(arm.times()) == pytest.approx(np.full(len(arm.times()) - 1, 0.05), abs=1e-9)


def test_the_gains_used_are_the_yamls(ctl, tmp_path):
    config = yaml.safe_load(CONFIG.read_text())["example_3"]
    arm = ctl.Arm()
    for name, c in arm.controllers.items():
        expected = config[name]["pid"]
        assert (c.pid.p, c.pid.i, c.pid.d, c.pid.i_clamp) == (
            expected["p"], expected["i"], expected["d"], expected["i_clamp"])
        assert c.joint == config[name]["joint"]
    # Change the file: the controller follows it.
    package = tmp_path / "example_3"
    shutil.copytree(PACKAGE, package)
    edited = package / "config" / CONFIG.name
    edited.write_text(edited.read_text().replace("p: 100.0", "p: 37.5"))
    changed = ctl.Arm(package=package, config=edited)
    assert changed.controllers["middle_arm_controller"].pid.p == 37.5


def test_motors_come_from_the_transmissions_and_stop_at_the_effort_limit():
    transmissions = read_transmissions(PACKAGE)
    assert [t.joint for t in transmissions] == design.JOINTS
    assert all(t.interface == "hardware_interface/EffortJointInterface" for t in transmissions)
    spec = sw2sim.load_package(PACKAGE)
    assert spec.compile().nu == 0, "MuJoCo's importer ignores transmissions"
    motors = add_motors(spec, PACKAGE)
    model = spec.compile()
    assert model.nu == 2 and motors == ["middle_arm_motor", "end_arm_motor"]
    assert np.all(model.actuator_ctrlrange == [[-1000, 1000], [-1000, 1000]])
    limits = read_joint_limits(PACKAGE)
    assert all(limits[j].effort == 1000 and limits[j].velocity == 2 for j in design.JOINTS)


def test_the_joint_limits_are_45_degrees_in_radians():
    model = sw2sim.load_package(PACKAGE).compile()
    for joint in design.JOINTS:
        low, high = model.joint(joint).range
        assert (low, high) == (pytest.approx(-LIMIT), pytest.approx(LIMIT))
        assert math.degrees(high) == pytest.approx(45.0, abs=0.001)


def tip(model, data):
    hand = data.body("end_arm_link")
    return hand.xpos + hand.xmat.reshape(3, 3) @ np.array(design.tool_tip())


def test_with_both_joints_at_the_limit_the_end_is_67_5_degrees_from_the_pivot(ctl):
    model = sw2sim.load_package(PACKAGE).compile()
    data = mujoco.MjData(model)
    for sign in (1, -1):
        data.qpos[:] = sign * model.jnt_range[:, 1]
        mujoco.mj_kinematics(model, data)
        d = tip(model, data) - data.body("middle_arm_link").xpos
        assert math.degrees(math.atan2(d[1], d[0])) == pytest.approx(sign * 67.5, abs=0.1)
        assert math.hypot(d[0], d[1]) == pytest.approx(0.416, abs=0.0005)
    # and where the controllers take it
    arm = ctl.Arm()
    arm.command(middle_arm_controller=LIMIT, end_arm_controller=LIMIT)
    arm.run(2.0)
    d = tip(arm.model, arm.data) - arm.data.body("middle_arm_link").xpos
    assert math.degrees(math.atan2(d[1], d[0])) == pytest.approx(67.5, abs=0.1)


def test_the_fingertips_are_where_the_design_says():
    """The tool tip used above is the end of the mesh: 225 mm from the elbow axis."""
    mesh = design.end_arm().mesh
    assert mesh.bounds[1][0] == pytest.approx(design.ARM_LENGTH / 1000, abs=1e-6)
    model = sw2sim.load_package(PACKAGE).compile()
    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    elbow = data.body("end_arm_link").xpos - data.body("middle_arm_link").xpos
    assert math.hypot(elbow[0], elbow[1]) == pytest.approx(0.225, abs=1e-6)


def test_2_rad_per_s_is_about_0_9_m_per_s_at_the_tool_tip(ctl):
    arm = ctl.Arm()
    arm.command(middle_arm_controller=-LIMIT)
    arm.run(2.0)
    arm.command(middle_arm_controller=LIMIT)
    best = (0.0, 0.0)
    for _ in range(2000):
        before = tip(arm.model, arm.data).copy()
        arm.step()
        speed = np.linalg.norm(tip(arm.model, arm.data) - before) / ctl.TIMESTEP
        omega = abs(arm.data.qvel[arm.controllers["middle_arm_controller"].dof])
        if omega > best[1]:
            best = (speed, omega)
    speed, omega = best
    assert speed / omega == pytest.approx(0.45, rel=0.05), "tip speed per rad/s at the middle joint"
    assert 2.0 * speed / omega == pytest.approx(0.9, rel=0.05)
    assert omega == pytest.approx(2.0, rel=0.06), "the joint did run close to its limit"


def test_the_arm_never_needs_more_than_a_few_newton_metres(hard_run):
    _, watch, *_ = hard_run
    assert watch.largest_torque < 5.0


# --- the numbers the pages state --------------------------------------------------------------


def test_modelling_page_masses():
    text = page("01-modelling.md")
    # What the script prints, the meshes' masses; SolidWorks' exact ones: test_tool_facts.py.
    assert f"prints {design.middle_arm().mass:.3f} kg for the middle arm" in " ".join(text.split())


def test_exporting_page_numbers(ctl):
    text = page("02-exporting.md")
    assert f"{math.radians(45):.4f}" == "0.7854" and "0.7854" in text
    r = 2 * design.ARM_LENGTH / 1000 * math.cos(math.radians(22.5))
    assert f"{r:.3f}" in text
    model = sw2sim.load_package(PACKAGE).compile()
    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    mujoco.mj_comPos(model, data)
    jacp = np.zeros((3, model.nv))
    mujoco.mj_jac(model, data, jacp, None, tip(model, data), model.body("end_arm_link").id)
    middle, end, both = (np.linalg.norm(jacp @ np.array(w)) for w in ([2, 0], [0, 2], [2, 2]))
    assert f"= {middle:.1f}\\ \\text{{m/s}}" in text
    assert f"{end:.2f} m/s" in text and f"{middle:.1f} + {end:.2f} = {both:.2f} m/s" in text
    assert f'k_velocity="{design.K_VELOCITY["middle_arm_joint"]:g}"' in text
    assert f"`{design.K_VELOCITY['middle_arm_joint']:g}` (middle) / `{design.K_VELOCITY['end_arm_joint']:g}` (end)" in text


def test_xml_shown_on_the_pages_is_in_the_package():
    urdf = squash((PACKAGE / "urdf" / "example_3.urdf").read_text())
    package_xml = squash((PACKAGE / "package.xml").read_text())
    blocks = xml_blocks(page("02-exporting.md")) + xml_blocks(page("03-transmissions.md"))
    assert len(blocks) >= 4
    for block in blocks:
        assert squash(block) in urdf or squash(block) in package_xml, block


def test_controller_page_numbers():
    text = page("04-controllers.md")
    model = sw2sim.load_package(PACKAGE).compile()
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    M = np.zeros((model.nv, model.nv))
    mujoco.mj_fullM(model, data, M)
    assert "about ten times the inertia" in text and 9 <= M[0, 0] / M[1, 1] <= 11
    assert "20 times per second" in text and design.STATE_RATE == 20


def test_position_control_page_numbers(ctl):
    text = page("05-position-control.md")
    config = yaml.safe_load(CONFIG.read_text())["example_3"]
    p = config["middle_arm_controller"]["pid"]["p"]
    assert f"p \\cdot e = {p:g} \\cdot 1.57 \\approx {p * 2 * LIMIT:.0f}" in text
    assert ctl.TIMESTEP == 0.001 and "1 ms" in text
    assert round(1 / (20 * ctl.TIMESTEP)) == 50 and "every 50th step" in text
    assert ctl.CRUISE == 0.95 and "95 %" in text
    assert ctl.ACCELERATION == {"middle_arm_joint": 5.0, "end_arm_joint": 10.0}
    assert "5 rad/s² against the end joint's 10 rad/s²" in text
    model = sw2sim.load_package(PACKAGE).compile()
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    M = np.zeros((model.nv, model.nv))
    mujoco.mj_fullM(model, data, M)
    # "about 80 N·m·s/rad for the middle joint and 8 for the end joint": inertia / time step
    assert round(M[0, 0] / ctl.TIMESTEP, -1) == 80 and "about 80 N·m·s/rad" in text
    assert round(M[1, 1] / ctl.TIMESTEP) == 8 and "and 8 for the end joint" in text


def test_without_a_safety_controller_the_effort_is_saturated(ctl):
    """gazebo_ros_control's saturation handle: the effort limit, and no push further past
    the velocity limit or a position limit (practice-3/02-exporting.md)."""
    from sw2sim.ros_control import JointLimits
    arm = ctl.Arm()
    c = arm.controllers["middle_arm_controller"]
    c.limits = JointLimits(lower=-LIMIT, upper=LIMIT, effort=50.0, velocity=2.0)
    assert c.enforce_limits(80.0, q=0.0, v=1.0) == 50.0          # under the limits
    assert c.enforce_limits(80.0, q=0.0, v=5.0) == 0.0           # past the velocity limit
    assert c.enforce_limits(-10.0, q=0.0, v=5.0) == -10.0        # braking is allowed
    assert c.enforce_limits(-90.0, q=0.0, v=-5.0) == 0.0
    assert c.enforce_limits(-90.0, q=0.0, v=-1.0) == -50.0
    assert c.enforce_limits(30.0, q=LIMIT + 0.01, v=0.0) == 0.0  # past the upper limit
    assert c.enforce_limits(-30.0, q=LIMIT + 0.01, v=0.0) == -30.0
