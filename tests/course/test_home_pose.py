"""The home pose and the frames, as Practice 1 teaches them and Practices 3 to 5 apply them:
every joint's zero is the pose the pages say the assembly is exported in, and the wheel's
centre is where the *Center of Face* of its bore puts it."""

from __future__ import annotations

import math

import mujoco
import numpy as np
import pytest

import sw2sim
from course.practices import PRACTICES, design
from page_text import flat_page
from repository import ROOT

HOME = "/practice-1/modelling/#the-home-pose"


def at_zero(n: int, fixed_base: bool = True):
    model = sw2sim.load_package(ROOT / "examples" / f"example_{n}", fixed_base=fixed_base).compile()
    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    return model, data


def test_practice_1_teaches_the_home_pose_and_the_frames_pick_by_pick():
    text = flat_page(ROOT / "_pages" / "practice-1" / "01-modelling.md")
    for words in ("### The home pose", "**suppress** those mates", "*Center of Face*",
                  "*Cylindrical/Conical Face*", "its X, Y and Z become the link's x, y and z"):
        assert words in text, words


@pytest.mark.parametrize("page", ["practice-3/01-modelling.md", "practice-4/01-modelling.md",
                                  "practice-5/01-modelling.md"])
def test_the_later_practices_apply_the_home_pose(page):
    text = flat_page(ROOT / "_pages" / page)
    assert f"[home pose]({HOME})" in text and "uppress" in text


def test_the_bore_runs_through_the_wheel_so_its_face_centre_is_the_wheels_centre():
    """Practice 1: the bore's cylindrical face is as long as the wheel is thick (or longer,
    cut through), so the centre of that face is the wheel's centre: the joint origin."""
    p1 = design(PRACTICES[0])
    wheel = p1.wheel()
    disc, bore = wheel.features[0], wheel.features[1]
    assert bore.cut and bore.length >= disc.length and bore.axis == disc.axis == "y"
    model, data = at_zero(1)
    for name, (x, y) in p1.WHEELS.items():
        body = model.body(name)
        assert np.allclose(data.xpos[body.id][:2], [x / 1000, y / 1000], atol=1e-6), name


def test_practice_3s_zero_is_the_arm_straight_ahead():
    model, data = at_zero(3)
    base = data.xpos[model.body("base_link").id]
    for link in ("middle_arm_link", "end_arm_link"):
        frame = data.xmat[model.body(link).id].reshape(3, 3)
        assert np.allclose(frame[:, 0], [1, 0, 0], atol=1e-9), link       # its X along the foot's
    tip = data.xpos[model.body("end_arm_link").id] - base
    assert abs(tip[1]) < 1e-9 and tip[0] > 0


def test_practice_4s_zero_is_the_block_at_the_start_of_its_travel():
    model, data = at_zero(4)
    joint = model.joint("block_joint")
    low, high = model.jnt_range[joint.id]
    assert low == 0.0 and high == pytest.approx(2.69)
    text = flat_page(ROOT / "_pages" / "practice-4" / "01-modelling.md")
    assert "the joint's zero, from which the 2.69 m of travel count" in text


def test_practice_5s_zero_is_driving_straight():
    model, data = at_zero(5, fixed_base=False)
    for wheel in ("front_left", "front_right", "rear_left", "rear_right"):
        j = model.joint(f"{wheel}_wheel_joint").id
        axis = data.xaxis[j]
        assert np.allclose(np.abs(axis), [0, 1, 0], atol=1e-9), wheel           # axles across
    p5 = design(PRACTICES[4])
    limit = model.jnt_range[model.joint("left_knuckle_joint").id][1]
    inner, _ = p5.ackermann(math.radians(30), p5.mm(p5.WHEELBASE), p5.mm(p5.TRACK))
    assert limit == pytest.approx(0.6351) and inner == pytest.approx(limit, abs=1e-4)
