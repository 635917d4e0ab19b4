"""What the Practice 1 pages claim, checked against the model."""

import math
import re

import numpy as np
import pytest

import sw2sim
import mujoco
from course.practices import ROOT, load_script
from course.practices.practice_1 import design

PAGES = ROOT / "_pages" / "practice-1"
WHEELS = ["front_left_joint", "front_right_joint", "rear_left_joint", "rear_right_joint"]


def page(name: str) -> str:
    return (PAGES / name).read_text()


@pytest.fixture(scope="module")
def pulses():
    return load_script("examples/example_1/scripts/periodic_force.py")


@pytest.fixture(scope="module")
def pulse_run(pulses):
    model = sw2sim.load_package("examples/example_1").compile()
    data = mujoco.MjData(model)
    base = data.body("base_link")
    mujoco.mj_forward(model, data)
    start = base.xpos.copy()
    t, tau, omega = pulses.run(model, data, WHEELS, duration=30.0)
    return model, data, t, tau, omega, float(np.linalg.norm(base.xpos - start))


def wheel_inertia(model, data):
    M = np.zeros((model.nv, model.nv))
    mujoco.mj_fullM(model, data, M)
    dof = model.joint(WHEELS[0]).dofadr[0]
    return M[dof, dof]


def test_locked_base_stays_within_a_millimetre_while_the_wheels_are_driven(pulse_run):
    *_, moved = pulse_run
    assert moved < 0.001


def test_free_base_drives_off(pulses):
    model = sw2sim.load_package("examples/example_1", fixed_base=False).compile()
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    start = data.body("base_link").xpos.copy()
    pulses.run(model, data, WHEELS, duration=3.0)
    travel = data.body("base_link").xpos - start
    assert abs(travel[0]) > 1.0, f"the free base moved only {travel} m"
    assert abs(travel[1]) < 0.1 * abs(travel[0]), "it should drive straight, along x"


def test_wheel_speed_rises_only_during_each_pulse(pulse_run):
    _, _, t, tau, omega, _ = pulse_run
    domega = np.diff(omega, axis=0)
    on = (tau[:-1] > 0) & (tau[1:] > 0)    # intervals wholly inside a pulse
    off = (tau[:-1] == 0) & (tau[1:] == 0)  # and wholly between pulses
    assert on.sum() > 250 and off.sum() > 2500
    assert np.all(domega[on] > 0), "speed must rise while the torque is on"
    assert np.allclose(domega[off], 0, atol=1e-6), "speed must hold while the torque is off"


def test_the_pattern_repeats_every_ten_seconds(pulse_run, pulses):
    _, _, t, tau, omega, _ = pulse_run
    starts = t[1:][(tau[1:] > 0) & (tau[:-1] == 0)]
    starts = np.concatenate([[t[0]] if tau[0] > 0 else [], starts])
    assert starts == pytest.approx([0.0, 10.0, 20.0], abs=0.011)
    assert pulses.PERIOD == 10.0 and 1 / pulses.PERIOD == pytest.approx(0.1)
    lengths = [np.sum((t >= s) & (t < s + 5) & (tau > 0)) / 100 for s in starts]
    assert lengths == pytest.approx([1.0] * 3, abs=0.011)
    gains = [omega[np.searchsorted(t, s + 5), 0] - omega[np.searchsorted(t, s - 0.001), 0] for s in starts]
    assert gains == pytest.approx([gains[0]] * 3, rel=0.01), "each pulse adds the same speed"


def test_speed_step_is_torque_times_time_over_inertia(pulse_run, pulses):
    model, data, t, _, omega, _ = pulse_run
    inertia = wheel_inertia(model, data)
    assert inertia == pytest.approx(design.wheel().mass_properties()[2][1, 1], rel=1e-6)
    expected = pulses.TORQUE * pulses.PULSE / inertia
    measured = omega[np.searchsorted(t, 5.0), 0]
    assert measured == pytest.approx(expected, rel=0.01)
    # The page states the step and its rpm.
    text = page("05-custom-node.md")
    assert f"About {measured:.1f} rad/s" in text
    assert f"or {measured * 60 / (2 * math.pi):.0f} rpm" in text


def test_masses_on_the_modelling_page():
    text = page("01-modelling.md")
    assert f"wheel {design.wheel().mass:.3f} kg, base {design.base().mass:.3f} kg" in text
    assert design.ALUMINIUM.density == 2700 and "2700 kg/m³" in text


def test_drawing_numbers_on_the_modelling_page():
    text = page("01-modelling.md")
    assert f"{design.PLATE[0]} × {design.PLATE[1]} mm" in text
    assert f"Ø{design.WHEEL_DIAMETER} mm" in text and f"{design.WHEEL_WIDTH} mm" in text
    assert f"Ø{design.BORE_DIAMETER} mm bore" in text
    assert f"Ø{design.HOLE_DIAMETER} mm holes on a\n   Ø{design.HOLE_PITCH_DIAMETER} mm pitch" in text
    assert f"centred {design.AXLE_X} mm in front" in text
    assert f"distance* {design.WHEEL_GAP} mm" in text


def test_conversions_on_the_exporting_page():
    text = page("02-exporting.md")
    assert f'lower="-{math.radians(45):.4f}" upper="{math.radians(45):.4f}"' in text
    assert f"= {2 * math.pi / 60 * 600:.2f}" in text
    radius = design.WHEEL_DIAMETER / 2000
    assert f"$$r$$ = {radius:g} m" in text and f"= {1.0 / radius:g} rad/s" in text


def test_stand_height_on_the_modifying_page():
    text = page("04-testing-and-modifying.md")
    clearance = design.STAND_HEIGHT - design.WHEEL_DIAMETER / 2
    assert f'xyz="0 0 {design.STAND_HEIGHT / 1000:g}"' in text
    assert f"{clearance:g} mm" in text and f"{design.WHEEL_DIAMETER / 2000:g} m wheels" in text


def test_wheel_axes_in_the_simulation_are_the_axles():
    """Each wheel turns about the y axis of the base: both wheels of an axle share one line."""
    model = sw2sim.load_package("examples/example_1").compile()
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    for name in WHEELS:
        j = model.joint(name).id
        assert data.xaxis[j] == pytest.approx([0, 1, 0], abs=1e-9)
        assert data.xanchor[j][0] == pytest.approx(np.sign(data.xanchor[j][0]) * design.AXLE_X / 1000)
