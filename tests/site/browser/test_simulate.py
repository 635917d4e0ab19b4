"""The Simulate mode of each practice's 3D viewer (assets/js/simulation.js and its worker):
in headless Chromium, the page's simulation of a fixed input for a fixed time against the
Python lesson's run of the same input, the number the page states met by both, the
controls moving the model as the page says, and out-of-range values refused.

Two comparisons, each with its own tolerance:
- against MuJoCo 4.0 in Python running the very model the page loads (the same text of
  media/practice-N/simulate.json) with the lesson's own code: this isolates the engines
  (3.14 in the page, 4.0 in Python) and the controllers' port, so SAME_MODEL is tight;
- against the lesson's own run, on the model the lesson builds in memory: `MjSpec.to_xml`
  writes each number to 6 significant digits (an inertia of 0.01598133... becomes
  0.0159813), so the page's model differs from the lesson's by up to 5e-7 of each value,
  and a wheel spun for a second by 2e-6 of its speed. LESSON allows 1e-5 of the value
  (62.6 rad/s, as the page prints it, is then exact to 6e-4, a sixth of its last digit)
  and 1e-6 absolute near zero. A wrong gain, a lost step or a limit not applied
  differs by orders of magnitude more.
"""

import re

import mujoco
import numpy as np
import pytest

import axe_audit
from course import browser_models
from course.practices import load_script
from repository import ROOT

SAME_MODEL = 1e-9        # absolute, in rad, rad/s or m
LESSON = (1e-5, 1e-6)    # relative, absolute
# Practice 5's car rolls on four wheels in contact with the floor, which amplifies the last
# bit of a number: in MuJoCo 4.0 alone, the knuckle angles changed by one unit in the last
# place (np.nextafter) move the car 0.3 mm after 12 s. The page computes Eq. 4 with the
# browser's Math.atan2 and Math.hypot, whose last bits may differ from C's: its path
# differs from Python's by 0.5-0.9 mm. CAR_PATH is ten times the 1-ulp figure.
CAR_PATH = 3e-3          # m
CAR_STEERING = 1e-5      # rad: the steering joint follows its own actuator, no contact
READY_S = 30.0
SAMPLE = 0.01   # s between two rows of the page's trace (the worker's TRACE_RATE)
WHEELS = browser_models.WHEELS


def stated(page_output, pattern):
    """A number the page shows under one of its Python blocks (_data/outputs/<page>.json),
    found by `pattern` (one group)."""
    import json

    outputs = json.loads((ROOT / "_data/outputs" / f"{page_output}.json").read_text())
    text = "\n".join(block["output"] or "" for block in outputs["blocks"])
    found = re.search(pattern, text)
    assert found, f"{page_output} no longer prints {pattern!r}"
    return found.group(1)


def simulation_page(site, practice):
    pattern = f'data-simulation="[^"]*/media/practice-{practice}/simulate.json"'
    for path in site.pages:
        html = (site.root / path.strip("/") / "index.html").read_text(encoding="utf-8")
        if re.search(pattern, html):
            return path, html
    pytest.fail(f"no page has Practice {practice}'s Simulate mode")


def start(page):
    page.get_by_role("button", name="Turn the model in 3D").click()
    page.get_by_role("button", name="Simulate").click(timeout=READY_S * 1000)
    page.wait_for_function("() => document.querySelector('.model-viewer').simulation",
                           timeout=READY_S * 1000)
    page.evaluate("() => document.querySelector('.model-viewer').simulation.ready")


def set_input(page, name, value):
    field = page.locator(f'.simulation-input input[data-name="{name}"]')
    field.fill(str(value))
    field.dispatch_event("change")
    return field


def run(page, seconds):
    """Steps the page's simulation `seconds` at once: (trace as an array, speed factor)."""
    speed = page.evaluate(f"() => document.querySelector('.model-viewer').simulation.run({seconds})")
    trace = page.evaluate("() => document.querySelector('.model-viewer').simulation.trace()")
    return np.array(trace, dtype=float), speed


def reset(page):
    page.get_by_role("button", name="Reset the simulation").click()


def page_model(practice):
    """The model the page loads, compiled by MuJoCo 4.0."""
    import json

    built = json.loads(browser_models.output(practice).read_text())
    return mujoco.MjModel.from_xml_string(built["model"], {
        path: (ROOT / url).read_bytes() for path, url in built["files"].items()})


def python_pulse(practice, seconds, friction=None, same_model=False):
    """The lesson's run: periodic_force.run on the lesson's model (or the page's), rows of
    [t, speeds...]."""
    periodic = load_script("examples/example_1/scripts/periodic_force.py")
    if same_model:
        model = page_model(practice)
    else:
        spec, _ = browser_models.LESSONS[practice](practice)
        model = spec.compile()
    for joint, value in (friction or {}).items():
        model.dof_frictionloss[model.joint(joint).dofadr[0]] = value
    t, _, omega = periodic.run(model, mujoco.MjData(model), WHEELS, duration=seconds)
    return np.column_stack([t, omega])


def python_position(practice, commands, same_model=False):
    """The lesson's controller class stepped through `commands` [(set points, seconds)],
    sampled every SAMPLE s: rows of [t, set point, position, ...] per controller. With
    `same_model`, on the model the page loads (same joints, motors and time step)."""
    lesson = load_script(browser_models.POSITION_SCRIPTS[practice])
    robot = lesson.Arm() if practice == 3 else lesson.Slider()
    if same_model:
        robot.model = page_model(practice)
        robot.data = mujoco.MjData(robot.model)
    controllers = list(robot.controllers.values()) if practice == 3 else [robot.controller]
    every = round(SAMPLE / robot.model.opt.timestep)
    rows, steps = [], 0
    for setpoints, seconds in commands:
        for controller, value in zip(controllers, setpoints):
            controller.command(value)
        for _ in range(round(seconds / robot.model.opt.timestep)):
            if steps % every == 0:
                rows.append([robot.data.time] + [x for c in controllers for x in (
                    c.setpoint, robot.data.qpos[c.qpos])])
            robot.step()
            steps += 1
    return np.array(rows), robot


def compare(page_trace, run):
    """The page's trace against `run(same_model)`, the Python run of the same input."""
    same, lesson = run(True), run(False)
    for python_trace in (same, lesson):
        assert page_trace.shape == python_trace.shape, (page_trace.shape, python_trace.shape)
        np.testing.assert_allclose(page_trace[:, 0], python_trace[:, 0], atol=1e-9)
    worst = np.abs(page_trace[:, 1:] - same[:, 1:]).max()
    assert worst <= SAME_MODEL, f"MuJoCo 3.14 and 4.0 differ by {worst:.2e} on one model"
    np.testing.assert_allclose(page_trace[:, 1:], lesson[:, 1:], rtol=LESSON[0], atol=LESSON[1],
                               err_msg="the page's run against the lesson's")


def test_practice_1_pulse_matches_the_lesson(site, browser_page):
    path, _ = simulation_page(site, 1)
    step = stated("practice-1__05-custom-node", r"measured after the first pulse: ([\d.]+) rad/s")
    found = {}

    def steps(page):
        start(page)
        found["default"], found["speed"] = run(page, 2.0)
        reset(page)
        set_input(page, "torque:front_left_joint", 2)
        found["doubled"], _ = run(page, 2.0)

    visit = browser_page.visit(path, then=steps)
    assert not visit.problems(), visit.problems()
    compare(found["default"], lambda same: python_pulse(1, 2.0, same_model=same))
    # The page's number: each pulse adds 62.6 rad/s to every wheel.
    assert f"{found['default'][-1, 1]:.1f}" == step
    # Twice the torque on one wheel: twice its step, the other wheels as before.
    assert found["doubled"][-1, 1] == pytest.approx(2 * found["default"][-1, 1], rel=1e-6)
    assert found["doubled"][-1, 2] == pytest.approx(found["default"][-1, 2], rel=1e-9)
    print(f"Practice 1: {found['speed']:.1f}x real time stepping 2 s at once")


def test_practice_2_friction_slides_or_sticks_as_the_page_says(site, browser_page):
    path, _ = simulation_page(site, 2)
    found = {}

    def steps(page):
        start(page)
        found["default"], found["speed"] = run(page, 2.0)
        reset(page)
        # more friction than the pulse's 1 N·m: the page predicts the wheel never turns
        set_input(page, "friction:front_left_joint", 1.2)
        field = set_input(page, "friction:front_right_joint", 3)   # outside 0 to 2 N·m
        found["refused"] = field.get_attribute("aria-invalid")
        found["refused_text"] = page.locator(
            '.simulation-input[data-refused] .simulation-range').text_content()
        found["stuck"], _ = run(page, 2.0)

    visit = browser_page.visit(path, then=steps)
    assert not visit.problems(), visit.problems()
    compare(found["default"], lambda same: python_pulse(2, 2.0, same_model=same))
    trace = found["default"]
    fric = trace[:, 1]
    # The page: "friction wheel: peak 18.8 rad/s ... below 1 % of its peak from 1.43 s"
    page = "practice-2__04-friction"
    assert f"{fric.max():.1f}" == stated(page, r"friction wheel: peak ([\d.]+) rad/s")
    t = trace[:, 0]
    assert f"{t[(t > 1.0) & (fric < 0.01 * fric.max())][0]:.2f}" == stated(
        page, r"below 1 % of its peak from ([\d.]+) s")
    # The page's net torque, 1 N·m less the friction, is below zero: the wheel sticks (it
    # creeps, as MuJoCo's friction is a soft constraint, at well under 1 % of the slide's peak)
    stuck = found["stuck"]
    assert np.abs(stuck[:, 1]).max() < 0.01 * fric.max()
    compare(stuck, lambda same: python_pulse(2, 2.0, {"front_left_joint": 1.2}, same))
    assert found["refused"] == "true" and "Refused" in found["refused_text"]
    print(f"Practice 2: {found['speed']:.1f}x real time stepping 2 s at once")


def test_practice_3_position_control_matches_the_lesson(site, browser_page):
    path, _ = simulation_page(site, 3)
    found = {}
    names = ["middle_arm_controller", "end_arm_controller"]

    def steps(page):
        start(page)
        for name in names:
            set_input(page, f"setpoint:{name}", -0.7854)
        run(page, 2.0)
        for name in names:
            set_input(page, f"setpoint:{name}", 0.7854)
        found["trace"], found["speed"] = run(page, 2.0)
        field = set_input(page, f"setpoint:{names[0]}", 1.0)   # past the 0.7854 rad limit
        found["refused"] = field.get_attribute("aria-invalid")

    visit = browser_page.visit(path, then=steps)
    assert not visit.problems(), visit.problems()
    commands = [((-0.7854, -0.7854), 2.0), ((0.7854, 0.7854), 2.0)]
    compare(found["trace"], lambda same: python_position(3, commands, same)[0])
    # The page: "error after 2 s +0.00000 rad" for both joints, in both runs
    last = found["trace"][-1]
    assert abs(last[1] - last[2]) < 5e-6 and abs(last[3] - last[4]) < 5e-6
    assert found["refused"] == "true"
    print(f"Practice 3: {found['speed']:.1f}x real time stepping 2 s at once")


def test_practice_4_block_reaches_its_set_point_as_the_lesson(site, browser_page):
    path, _ = simulation_page(site, 4)
    found = {}

    def steps(page):
        start(page)
        set_input(page, "setpoint:block_controller", 2.0)
        found["trace"], found["speed"] = run(page, 3.5)
        found["readout"] = page.locator(".simulation-readout").text_content()
        field = set_input(page, "setpoint:block_controller", 3.0)   # past the 2.69 m limit
        found["refused"] = field.get_attribute("aria-invalid")

    visit = browser_page.visit(path, then=steps)
    assert not visit.problems(), visit.problems()
    compare(found["trace"], lambda same: python_position(4, [((2.0,), 3.5)], same)[0])
    # The page: "set point 2.000 m, block at 1.9999 m" after 3.5 s
    assert f"{found['trace'][-1, 2]:.4f}" == stated(
        "practice-4__04-testing-and-scripting", r"set point 2.000 m, block at ([\d.]+) m")
    assert "overshoot" in found["readout"]
    assert found["refused"] == "true"
    print(f"Practice 4: {found['speed']:.1f}x real time stepping 3.5 s at once")


def test_pages_load_no_simulation_before_simulate_is_pressed(site, browser_page):
    path, _ = simulation_page(site, 3)
    visit = browser_page.visit(path)
    assert not visit.problems(), visit.problems()
    early = [r.url for r in visit.responses
             if "/assets/vendor/mujoco/" in r.url or "simulat" in r.url]
    assert not early, f"loaded before Simulate was pressed: {early}"


def test_the_simulation_panel_is_accessible(site, browser_page):
    """Its buttons, labelled fields with their ranges, plot and legend pass axe, a refused
    value included."""
    path, _ = simulation_page(site, 4)
    axe_url = site.node_module_url(axe_audit.AXE)

    def start_and_audit(page):
        start(page)
        set_input(page, "setpoint:block_controller", 3.0)
        page.add_script_tag(url=axe_url)
        axe_audit.start(page, path, context={"include": [[".simulation"]]})

    visit = browser_page.visit(path, then=start_and_audit)
    violations = axe_audit.serious(axe_audit.collect(browser_page.page))
    assert not visit.problems(), visit.problems()
    assert not violations, violations


def test_without_webassembly_simulate_shows_the_still_picture_and_why(site, browser_page):
    path, _ = simulation_page(site, 1)

    def simulate_without_webassembly(page):
        page.evaluate("() => { delete window.WebAssembly; }")
        page.get_by_role("button", name="Turn the model in 3D").click()
        page.get_by_role("button", name="Simulate").click(timeout=READY_S * 1000)
        page.wait_for_function("() => document.querySelector('.model-viewer-still img').complete")

    visit = browser_page.visit(path, then=simulate_without_webassembly)
    assert not visit.problems(), visit.problems()
    page = browser_page.page
    assert page.locator(".model-viewer-still img").is_visible()
    assert "WebAssembly" in page.locator(".model-viewer-note").text_content()
    assert not [r.url for r in visit.responses if "/assets/vendor/mujoco/" in r.url]


def python_car(commands, same_model=False):
    """ackermann.Car driven through `commands` [(speed, steering, seconds)]: rows of
    [t, x, y, heading, centre angle] at its control rate (its own log)."""
    lesson = load_script("examples/example_5/scripts/ackermann.py")
    car = lesson.Car(package=ROOT / "examples/example_5")
    if same_model:
        car.model = page_model(5)
        car.data = mujoco.MjData(car.model)
    for speed, steering, seconds in commands:
        car.command(speed=speed, steering=steering)
        car.run(seconds)
    return np.array(car.log)[:, :5]


def test_practice_5_car_drives_eq_4s_circle(site, browser_page):
    path, _ = simulation_page(site, 5)
    found = {}

    def steps(page):
        start(page)
        found["circle"], found["speed"] = run(page, 12.0)
        page.wait_for_function("() => /driven R/.test("
                               "document.querySelector('.simulation-readout').textContent)")
        found["readout"] = page.locator(".simulation-readout").text_content()
        reset(page)
        set_input(page, "steering", 0)
        found["straight"], _ = run(page, 10.0)
        field = set_input(page, "steering", 0.6)   # past the 0.5236 rad limit
        found["refused"] = field.get_attribute("aria-invalid")

    visit = browser_page.visit(path, then=steps)
    assert not visit.problems(), visit.problems()
    circle = found["circle"]
    for python in (python_car([(0.5, 0.3, 12.0)], same_model=True),
                   python_car([(0.5, 0.3, 12.0)])):
        assert circle.shape == python.shape
        np.testing.assert_allclose(circle[:, 0], python[:, 0], atol=1e-9)
        assert np.abs(circle[:, 1:3] - python[:, 1:3]).max() <= CAR_PATH
        assert np.abs(circle[:, 3] - python[:, 3]).max() <= CAR_PATH / 0.4   # over l = 0.4 m
        assert np.abs(circle[:, 4] - python[:, 4]).max() <= CAR_STEERING
    # The page: "driven R = 1.2987 m, predicted 1.2931 m, error +0.44 %"
    page_line = stated("practice-5__04-control-script",
                       r"(driven R = [\d.]+ m, predicted [\d.]+ m, error [-+][\d.]+ %)")
    numbers = [float(x) for x in re.findall(r"[\d.]+", page_line)]
    shown = [float(x) for x in re.findall(r"[\d.]+", found["readout"].replace("\u2212", "-"))]
    assert len(shown) == 3, found["readout"]
    assert abs(shown[0] - numbers[0]) <= 1e-4 and shown[1] == numbers[1]
    assert abs(shown[2] - numbers[2]) <= 0.01
    # Straight ahead: the page's "0.0090 mm to the side" after 10 s
    assert abs(found["straight"][-1, 2]) < 1e-4
    assert found["straight"][-1, 1] > 4.9
    assert found["refused"] == "true"
    print(f"Practice 5: {found['speed']:.1f}x real time stepping 12 s at once")
