"""What the Practice 4 pages claim, checked against the model, its controller and its figures."""

import math

import mujoco
import numpy as np
import pytest
from page_text import squash, xml_blocks
import yaml

import sw2sim
from course.practices import ROOT, load_script
from course.practices.practice_4 import design, figures
from sw2sim.ros_control import add_motors, read_joint_limits, read_transmissions

PACKAGE = ROOT / "examples" / "example_4"
PAGES = ROOT / "_pages" / "practice-4"
CONFIG = PACKAGE / "config" / "joint_names_example_4.yaml"
UPPER = 2.69
TOLERANCE = 0.001   # m: "within [0, 2.69] m with a tolerance of 1 mm"


def page(name: str) -> str:
    return (PAGES / name).read_text()


@pytest.fixture(scope="module")
def script():
    return load_script("examples/example_4/scripts/slider_controller.py")


def watch(slider, seconds):
    """Step and return the lowest and highest position, seen at every physics step."""
    low = high = slider.position()
    for _ in range(round(seconds / slider.model.opt.timestep)):
        slider.step()
        q = slider.position()
        low, high = min(low, q), max(high, q)
    return low, high


@pytest.fixture(scope="module")
def hard_run(script):
    """Commands far outside the limits, then random ones; extremes at every step."""
    slider = script.Slider()
    low, high = 0.0, 0.0
    for command in (-5.0, 10.0, -5.0, 26.9, 0.0, UPPER, -1e6):
        slider.command(command)
        lo, hi = watch(slider, 3.5)
        low, high = min(low, lo), max(high, hi)
    rng = np.random.default_rng(7)
    for command in rng.uniform(-30, 30, 8):
        slider.command(command)
        lo, hi = watch(slider, 1.5)
        low, high = min(low, lo), max(high, hi)
    return low, high


def test_the_block_stays_within_its_travel_under_any_command(hard_run):
    low, high = hard_run
    assert low >= -TOLERANCE and high <= UPPER + TOLERANCE, (low, high)
    # the run did reach both ends: a block that went past them would have been caught
    assert low < TOLERANCE and high > UPPER - TOLERANCE


def test_commands_outside_the_limits_are_clipped(script):
    slider = script.Slider()
    for command, expected in ((-5.0, 0.0), (10.0, UPPER), (26.9, UPPER), (1.2, 1.2)):
        slider.command(command)
        assert slider.controller.setpoint == pytest.approx(expected)


def test_the_controller_is_practice_3s_not_a_copy(script):
    arm = load_script("examples/example_3/scripts/arm_controller.py")
    assert script.JointPositionController.__qualname__ == "JointPositionController"
    assert script.JointPositionController.__module__ == "arm_controller"
    assert "class JointPositionController" not in (PACKAGE / "scripts" / "slider_controller.py").read_text()
    assert arm.CRUISE == 0.95


def test_the_gains_and_rate_are_the_yamls(script):
    config = yaml.safe_load(CONFIG.read_text())["example_4"]
    slider = script.Slider()
    pid = config["block_controller"]["pid"]
    c = slider.controller
    assert (c.pid.p, c.pid.i, c.pid.d, c.pid.i_clamp) == (pid["p"], pid["i"], pid["d"], pid["i_clamp"])
    assert pid == design.GAINS and slider.state_rate == 20
    assert config["block_controller"]["type"] == "effort_controllers/JointPositionController"


def test_the_motor_is_a_force_clipped_at_the_effort_limit():
    transmissions = read_transmissions(PACKAGE)
    assert [(t.joint, t.actuator, t.reduction) for t in transmissions] == [("block_joint", "block_motor", 1.0)]
    assert transmissions[0].interface == "hardware_interface/EffortJointInterface"
    spec = sw2sim.load_package(PACKAGE)
    assert spec.compile().nu == 0
    add_motors(spec, PACKAGE)
    model = spec.compile()
    assert model.actuator_ctrlrange.tolist() == [[-200.0, 200.0]]
    limits = read_joint_limits(PACKAGE)["block_joint"]
    assert (limits.lower, limits.upper, limits.effort, limits.velocity) == (0, UPPER, 200, 1)
    assert (limits.soft_lower, limits.soft_upper, limits.k_position, limits.k_velocity) == (0, UPPER, 20, 400)


def test_the_joint_is_a_slide_along_the_bar_with_the_limits_as_range():
    model = sw2sim.load_package(PACKAGE).compile()
    j = model.joint("block_joint")
    assert j.type[0] == mujoco.mjtJoint.mjJNT_SLIDE
    assert j.range.tolist() == pytest.approx([0.0, UPPER])
    assert model.jnt_actfrcrange[j.id].tolist() == [-200.0, 200.0]
    data = mujoco.MjData(model)
    for q, x in ((0.0, 0.105), (1.0, 1.105), (UPPER, 2.795)):
        data.qpos[j.qposadr[0]] = q
        mujoco.mj_kinematics(model, data)
        assert data.body("block_link").xpos.tolist() == pytest.approx([x, 0.0, 0.1], abs=1e-9)


def test_the_block_is_free_to_slide_and_clear_of_the_bar_and_floor(script):
    slider = script.Slider()
    slider.command(1.0)
    slider.run(2.0)
    assert slider.position() == pytest.approx(1.0, abs=0.001)
    assert slider.data.ncon == 0


def test_the_travel_fits_between_the_end_plates():
    bar, block = design.bar().mesh.bounds, design.block().mesh.bounds
    assert bar[1][0] == pytest.approx(2.9, abs=1e-6)
    x0 = design.joint_origin()[0]
    inner_right = 2.9 - 0.02
    assert x0 + block[0][0] == pytest.approx(0.02 + 0.01)          # 10 mm from the left plate at 0
    assert x0 + UPPER + block[1][0] == pytest.approx(inner_right - 0.01)   # and from the right at 2.69
    assert design.bar_end() == pytest.approx(2.87)


def test_the_viewer_model_has_a_slider_over_the_limits_that_moves_the_block(script):
    model = script.viewer_model()
    assert model.nu == 1 and model.actuator(0).name == "block_position"
    assert model.actuator_ctrlrange[0].tolist() == pytest.approx([0.0, UPPER])
    assert model.actuator_ctrllimited[0]
    data = mujoco.MjData(model)
    data.ctrl[0] = 1.5
    for _ in range(round(3.0 / model.opt.timestep)):
        mujoco.mj_step(model, data)
    assert data.joint("block_joint").qpos[0] == pytest.approx(1.5, abs=0.001)


# --- the figures' claims --------------------------------------------------------------------


def test_with_the_typo_the_block_runs_off_the_bar(tmp_path):
    right = figures.drive_to_the_end(figures.PACKAGE, 4.0)
    typo = figures.drive_to_the_end(figures.typo_package(tmp_path), 4.0)
    assert right.limits.upper == UPPER and typo.limits.upper == 26.9
    assert right.position() == pytest.approx(UPPER, abs=TOLERANCE)
    assert typo.position() > design.bar_end(), "past the end of the bar after 4 s"
    t, _, q, _, _ = typo.states()
    leaves = t[np.argmax(q > design.bar_end())]
    assert 2.5 < leaves < 3.5, "about 3 s"


def test_the_typo_is_accepted_by_the_loader(tmp_path):
    model = sw2sim.load_package(figures.typo_package(tmp_path)).compile()
    assert model.joint("block_joint").range.tolist() == pytest.approx([0.0, 26.9])


def test_a_long_move_is_paced_by_the_velocity_limit_not_the_force(script):
    slider = figures.long_move()
    t, _, q, v, f = slider.states()
    assert q[-1] == pytest.approx(UPPER, abs=TOLERANCE)
    assert 0.9 * design.VELOCITY <= np.abs(v).max() <= 1.05 * design.VELOCITY
    cruising = (t > 0.8) & (t < 2.7)
    assert np.all(np.abs(v[cruising] - 0.95) < 0.01), "95 % of the limit while cruising"
    assert np.abs(f).max() < 0.1 * design.EFFORT and np.abs(f).max() < 15
    arrived = t[np.argmax(np.abs(q - UPPER) < 0.001)]
    assert 3.25 <= arrived < 3.35, f"about 3.3 s, took {arrived:.2f}"
    assert script.ACCELERATION == 2.0


def test_the_force_grows_with_friction_and_the_block_stalls_beyond_the_effort_limit():
    frictions = [0.0, 50.0, 100.0, 150.0, 250.0]
    runs = np.array([figures.friction_run(f) for f in frictions])
    start, keep, done = runs.T
    assert np.all(np.diff(start[:4]) > 0) and np.all(np.diff(keep[:4]) > 0)
    for friction, k, s in zip(frictions[1:4], keep[1:4], start[1:4]):
        assert k == pytest.approx(friction, rel=0.05), "keeping it moving costs the friction"
        assert friction < s <= design.EFFORT
    assert np.all(done[:4] > 0.95)
    assert start[4] == pytest.approx(design.EFFORT) and done[4] < figures.STALL
    assert done[4] * 1.0 == pytest.approx(0.17, abs=0.01), "creeps about 17 cm in 3 s"


# --- the numbers the pages state ------------------------------------------------------------


def test_modelling_page_numbers():
    text = page("01-modelling.md")
    bar, block = design.parts()
    # What the script prints, the meshes' masses; SolidWorks' exact ones: test_tool_facts.py.
    assert f"prints {bar.mass:.3f} kg for the bar" in " ".join(text.split())
    assert design.BAR_LENGTH == 2860 and design.OVERALL == 2900 and "2860 mm" in text
    assert design.joint_origin() == (0.105, 0.0, 0.1) and "105 mm" in text
    assert "0.105 m to 2.795 m" in text


def test_exporting_page_numbers():
    text = page("02-exporting.md")
    mass = design.block().mass
    assert f"200 / {mass:.3f} \\approx {200 / mass:.0f}" in text
    assert "almost six times gravity" in text and 5.5 < 200 / mass / 9.81 < 6
    assert UPPER / design.VELOCITY == 2.69 and "in 2.69 s" in text   # the move: test_lesson_facts.py
    assert "0.105 + 2.69 = 2.795" in text and "2.795 + 0.075 = 2.870" in text
    assert "2.880 m" in text


def test_modifying_page_numbers():
    text = page("03-modifying-the-urdf.md")
    m = design.block().mass
    assert f"\\approx {2 * math.sqrt(design.GAINS['p'] * m):.0f}$$ N·s/m" in text
    assert f"2\\sqrt{{2000 \\cdot {m:.3f}}}" in text
    assert f"{design.bar_end():.2f} m out" in text
    assert round(26.9 - design.bar_end()) == 24 and "another 24 m" in text


def test_testing_page_numbers(script):
    text = page("04-testing-and-scripting.md")
    assert "2 m/s²" in text and script.ACCELERATION == 2.0
    assert "95 %" in text and "about 3.3 s" in text and "about 17 cm in 3 s" in text
    assert "tolerance of 1 mm" in text and TOLERANCE == 0.001


def test_xml_shown_on_the_pages_is_in_the_package():
    urdf = squash((PACKAGE / "urdf" / "example_4.urdf").read_text())
    blocks = xml_blocks(page("02-exporting.md")) + xml_blocks(page("03-modifying-the-urdf.md"))
    blocks = [b for b in blocks if "include_code" not in b]
    assert len(blocks) >= 4
    for block in blocks:
        assert squash(block) in urdf, block
