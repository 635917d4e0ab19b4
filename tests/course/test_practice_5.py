"""What the Practice 5 pages claim, checked against the model, its script and its figures."""

import ast
import math

import numpy as np
import pytest

import sw2sim
import mujoco
from course.practices import ROOT, load_script
from course.practices.practice_5 import design, figures

PACKAGE = ROOT / "examples" / "example_5"
PAGES = ROOT / "_pages" / "practice-5"
STEER = 0.3


def page(name: str) -> str:
    return (PAGES / name).read_text()


@pytest.fixture(scope="module")
def script():
    return load_script("examples/example_5/scripts/ackermann.py")


@pytest.fixture(scope="module")
def geometry(script):
    return script.measure(sw2sim.load_package(PACKAGE, fixed_base=False).compile())


@pytest.fixture(scope="module")
def turns():
    """The page's comparison: the same turn with and without each idea."""
    return {name: figures.turn(**options) for name, options in figures.CASES.items()}


@pytest.fixture(scope="module")
def sweep():
    return figures.sweep()


# --- the model ---------------------------------------------------------------------------


def test_geometry_read_from_the_model_is_the_design(geometry):
    assert geometry.wheelbase == pytest.approx(0.4, abs=1e-6)
    assert geometry.track == pytest.approx(0.3, abs=1e-6)
    assert geometry.radius == pytest.approx(0.06, abs=1e-5)


def test_part_masses_on_the_modelling_page():
    """What the script prints, the meshes' masses; SolidWorks' exact ones: test_tool_facts.py."""
    text = " ".join(page("01-modelling.md").split())
    total = (design.chassis().mass + design.steering_link().mass + 2 * design.knuckle().mass
             + 4 * design.wheel().mass)
    assert f"prints {design.wheel().mass:.3f} kg for the wheel" in text
    assert f"the meshes add up to {total:.3f} kg for the car" in text


def test_joints_limits_and_no_world_link():
    model = sw2sim.load_package(PACKAGE, fixed_base=False).compile()
    assert mujoco.mjtJoint(model.jnt_type[0]) == mujoco.mjtJoint.mjJNT_FREE
    urdf = (PACKAGE / "urdf" / "example_5.urdf").read_text()
    assert 'name="world"' not in urdf
    rng = {model.joint(j).name: model.jnt_range[j] for j in range(1, model.njnt)}
    assert rng["steering_joint"][1] == pytest.approx(0.5236)
    for side in ("left", "right"):
        assert rng[f"{side}_knuckle_joint"][1] == pytest.approx(0.6351)
    wheels = [j for j in range(model.njnt) if model.joint(j).name.endswith("wheel_joint")]
    assert len(wheels) == 4 and not any(model.jnt_limited[j] for j in wheels)
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    assert data.qpos[2] == pytest.approx(0.06, abs=0.001)    # set down 1 mm above; test_lesson_facts.py


def test_knuckle_limit_is_equation_4_at_the_steering_limit_rounded_up(script, geometry):
    inner, outer = script.knuckle_angles(design.STEER_LIMIT, geometry.wheelbase, geometry.track)
    assert inner == pytest.approx(0.63506, abs=5e-6)
    assert inner <= design.KNUCKLE_LIMIT < inner + 1e-4
    assert math.degrees(inner - outer) == pytest.approx(11.0, abs=0.05)
    assert "0.63506 rad" in page("03-ackermann-geometry.md")


def test_equation_4_is_the_thesis_form_and_the_radius_form(script):
    l, w = 0.4, 0.3
    for phi in np.radians([1, 5, 10, 20, 30]):
        r = l / math.tan(phi)
        left, right = script.knuckle_angles(phi, l, w)
        assert left == pytest.approx(math.atan(l / (r - w / 2)))
        assert right == pytest.approx(math.atan(l / (r + w / 2)))
        assert (left, right) == pytest.approx(design.ackermann(phi))
        assert script.knuckle_angles(-phi, l, w) == pytest.approx((-right, -left))


def test_the_angle_table(script, geometry):
    text = page("03-ackermann-geometry.md")
    for degrees in (5, 10, 20, 30):
        phi = math.radians(degrees)
        inner, outer = script.knuckle_angles(phi, geometry.wheelbase, geometry.track)
        radius = geometry.wheelbase / math.tan(phi)
        row = (f"| {degrees}° | {radius:.3f} m | {math.degrees(inner):.2f}° | "
               f"{math.degrees(outer):.2f}° |")
        assert row in text


def test_wheel_speeds_and_the_page_numbers(script, geometry):
    speeds = script.wheel_speeds(0.5, math.radians(20), geometry)
    r = geometry.radius
    assert speeds["rear_left"] * r == pytest.approx(0.432, abs=5e-4)
    assert speeds["front_right"] * r == pytest.approx(0.597, abs=5e-4)
    assert speeds["front_right"] / speeds["rear_left"] == pytest.approx(1.38, abs=0.01)
    straight = script.wheel_speeds(0.5, 0.0, geometry)
    assert all(v == pytest.approx(0.5 / r) for v in straight.values())
    assert "0.597 m/s" in page("03-ackermann-geometry.md")


def test_ros_node_computes_what_the_mujoco_script_does(script, geometry):
    """The ROS node cannot be imported here (no rospy); run its two functions."""
    source = (PACKAGE / "scripts" / "ackermann_node.py").read_text()
    tree = ast.parse(source)
    keep = [n for n in tree.body if isinstance(n, ast.FunctionDef) and n.name in
            ("knuckle_angles", "wheel_speeds") or isinstance(n, ast.Assign)
            and n.targets[0].id in ("WHEELBASE", "TRACK", "RADIUS")]
    namespace = {"math": math}
    exec(compile(ast.Module(keep, []), "ackermann_node.py", "exec"), namespace)
    for phi in (-0.5, -0.1, 0.0, 0.2, 0.5236):
        assert namespace["knuckle_angles"](phi) == pytest.approx(
            script.knuckle_angles(phi, geometry.wheelbase, geometry.track))
        assert namespace["wheel_speeds"](0.7, phi) == pytest.approx(
            script.wheel_speeds(0.7, phi, geometry), rel=1e-4)


# --- the four claims -------------------------------------------------------------


def test_knuckles_follow_equation_4_within_half_a_degree(script, sweep):
    """Measured knuckle angles against Equation 4 of the measured centre angle, over a
    sweep of the whole steering range; and the page's 0.3° while turning."""
    t, _, _, _, phi, left_sp, right_sp, left, right = sweep.states()
    g = sweep.geometry
    moving = t > 1.0
    eq4 = np.array([script.knuckle_angles(p, g.wheelbase, g.track) for p in phi[moving]])
    error = np.degrees(np.abs(eq4 - np.c_[left[moving], right[moving]]))
    assert error.max() < 0.5
    assert np.degrees(np.abs(np.c_[left_sp - left, right_sp - right][moving])).max() < 0.3
    assert phi[moving].min() < -0.52 and phi[moving].max() > 0.52     # the whole range
    assert np.degrees(max(abs(left).max(), abs(right).max())) > 36.0  # reaches the limit


def test_knuckles_settle_within_a_tenth_of_a_degree(turns):
    car, _ = next(iter(turns.values()))
    _, _, _, _, _, left_sp, right_sp, left, right = car.states()
    assert math.degrees(abs(left_sp[-1] - left[-1])) < 0.1
    assert math.degrees(abs(right_sp[-1] - right[-1])) < 0.1


@pytest.mark.parametrize("steer", [0.15, 0.5])
def test_steady_radius_within_3_percent_at_other_angles(steer):
    car, _ = figures.turn(seconds=16.0, steer=steer)
    measured, predicted = figures.steady_radius(car)
    assert abs(measured / predicted - 1) < 0.005                      # "within half a per cent"


def test_steady_radius_within_3_percent_of_the_geometric_radius(turns):
    car, _ = turns["Ackermann angles, each wheel its own speed"]
    measured, predicted = figures.steady_radius(car)
    assert abs(measured / predicted - 1) < 0.03
    # the page's numbers
    assert round(measured, 3) == 1.299 and round(predicted, 3) == 1.293
    assert round(100 * (measured / predicted - 1), 1) == 0.4


def test_straight_drift_under_1_percent(script):
    car = script.Car()
    car.command(speed=0.5, steering=0.0)
    car.run(10.0)
    x, y, heading = car.pose()
    assert x == pytest.approx(5.0, abs=0.1)
    _, xs, ys, *_ = car.states()
    assert np.abs(ys).max() < 0.01 * x
    assert np.abs(ys).max() < 0.001                                  # "far less than a millimetre"


def test_30_seconds_of_driving_without_warnings(script):
    car = script.Car()
    commands = [(0.8, 0.0), (1.2, 0.5), (0.6, -0.5), (-0.5, 0.3), (1.5, -0.2), (0.0, 0.0)]
    for speed, steer in commands:
        car.command(speed=speed, steering=steer)
        car.run(5.0)
    assert car.data.time == pytest.approx(30.0, abs=0.01)
    assert np.all(np.isfinite(car.data.qpos)) and np.all(np.isfinite(car.data.qvel))
    warnings = {mujoco.mjtWarning(i).name: int(car.data.warning[i].number)
                for i in range(len(car.data.warning)) if car.data.warning[i].number}
    assert not warnings, warnings
    _, x, y, *_ = car.states()
    assert np.hypot(x, y).max() > 3.0                                  # it went somewhere
    up = car.data.xmat[car.model.body("base_link").id].reshape(3, 3)[:, 2]
    assert up[2] > 0.99                                                # on its wheels
    assert abs(car.data.qpos[2] - 0.06) < 0.005


# --- "moved, but not ideally" ------------------------------------------------------------


def test_the_comparison(turns):
    rows = {}
    for name, (car, slip) in turns.items():
        measured, predicted = figures.steady_radius(car)
        rows[name] = (measured, 100 * (measured / predicted - 1), 1000 * slip)
    good = rows["Ackermann angles, each wheel its own speed"]
    equal = rows["Ackermann angles, equal wheel speeds"]
    parallel = rows["parallel steering, each wheel its own speed"]
    assert round(good[2]) == 2 and good[2] / 500 < 0.005            # under half a per cent
    assert round(equal[0], 3) == 1.535 and round(equal[1]) == 19 and round(equal[2]) == 42
    assert round(parallel[1], 1) == 1.3 and round(parallel[2]) == 9
    assert round(parallel[2] / good[2]) == 4
    text = page("05-why-it-moved-not-ideally.md")
    for shown in ("1.299 m, 0.4 % wide", "1.535 m, 19 % wide", "42 mm/s", "1.3 % wide", "9 mm/s"):
        assert shown in text


# --- the control script and the keyboard --------------------------------------------------


def test_script_main_prints_the_page_numbers(script):
    car = script.Car()
    car.command(speed=0.5, steering=0.3)
    car.run(10.0)
    left, right = car.knuckle_angles()
    assert round(math.degrees(car.steering_angle()), 2) == 17.19
    assert round(math.degrees(left), 2) == 19.27 and round(math.degrees(right), 2) == 15.48
    text = page("04-control-script.md")
    assert "19.27°" in text and "15.48°" in text and "(17.19°)" in text


def test_keys_map_to_commands():
    drive = load_script("examples/example_5/scripts/drive.py")
    c = drive.Command()
    for key in (drive.KEY_UP, drive.KEY_UP, drive.KEY_LEFT, drive.KEY_LEFT, drive.KEY_LEFT):
        c = drive.on_key(c, key, steer_limit=0.5236)
    assert c.speed == pytest.approx(0.2) and math.degrees(c.steering) == pytest.approx(15)
    for _ in range(10):
        c = drive.on_key(c, drive.KEY_RIGHT, steer_limit=0.5236)
    assert c.steering == pytest.approx(-0.5236)
    for _ in range(30):
        c = drive.on_key(c, drive.KEY_DOWN, steer_limit=0.5236)
    assert c.speed == pytest.approx(-drive.TOP_SPEED)
    assert drive.on_key(c, ord("A"), steer_limit=0.5236) == c
    assert drive.on_key(c, drive.KEY_SPACE, steer_limit=0.5236) == drive.Command()


def test_controllers_become_the_right_actuators(script):
    car = script.Car()
    m = car.model
    assert m.nu == 7
    for j in ("steering_joint", "left_knuckle_joint", "right_knuckle_joint"):
        a = car.act[j]
        assert m.actuator_biasprm[a, 1] == pytest.approx(-m.actuator_gainprm[a, 0])   # position
    assert m.actuator_gainprm[car.act["left_knuckle_joint"], 0] == pytest.approx(200.0)
    for j in script.WHEELS.values():
        a = car.act[j]
        assert m.actuator_biasprm[a, 1] == 0 and m.actuator_biasprm[a, 2] == pytest.approx(-5.0)


def test_page_states_the_ranges_and_rates():
    text = page("02-exporting.md")
    assert "$$v = \\omega r = 1.8$$" in text and design.WHEEL_VELOCITY * 0.06 == pytest.approx(1.8)
    assert "±0.6351 rad" in text and "±0.5236 rad (±30°)" in text
