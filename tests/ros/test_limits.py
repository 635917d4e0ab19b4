"""The effort gazebo_ros_control puts on an effort joint (sw2sim.ros.hardware), checked
against its source: joint_limits_interface.h's two handles worked by hand from the URDFs'
numbers, and control_toolbox's integral term. What the pages' ROS commands make the
vehicles do is checked on the pages' own runs (test_page_blocks.py)."""

from __future__ import annotations

import numpy as np
import pytest

from packages import EXAMPLES

# (example, joint, q, v, the controller's effort) -> the effort gazebo_ros_control applies:
# joint_limits_interface.h's two handles, worked by hand from the URDFs' numbers.
HANDLED = [
    # example_4's block: <safety_controller> k_position 20, k_velocity 400; 1 m/s, 200 N
    ("example_4", "block_joint", 1.0, 0.0, 3000.0, 200.0),        # effort limit
    ("example_4", "block_joint", 1.0, 0.9, 3000.0, 40.0),         # 400 * (1 - 0.9)
    ("example_4", "block_joint", 1.0, 1.2, 3000.0, -80.0),        # over the limit: brakes
    ("example_4", "block_joint", 1.0, 1.2, -3000.0, -200.0),
    ("example_4", "block_joint", 2.68, 0.0, 3000.0, 80.0),        # 400 * 20 * 0.01
    ("example_4", "block_joint", 1.0, 0.5, 50.0, 50.0),           # inside: as asked
    # example_5's steering joint: k_position 20, k_velocity 1; 3 rad/s, 5 N·m
    ("example_5", "steering_joint", 0.0, 0.0, 4.0, 3.0),          # 1 * (3 - 0)
    ("example_5", "steering_joint", 0.6, 0.0, 0.0, -1.528),       # past the soft limit
    # example_5's wheels: no <safety_controller>, continuous; 30 rad/s, 10 N·m
    ("example_5", "rear_left_wheel_joint", 0.0, 0.0, 25.0, 10.0),
    ("example_5", "rear_left_wheel_joint", 0.0, 31.0, 5.0, 0.0),  # past the velocity limit
    ("example_5", "rear_left_wheel_joint", 0.0, 31.0, -5.0, -5.0),
]


@pytest.mark.parametrize("example, joint, q, v, asked, applied", HANDLED)
def test_the_effort_is_limited_as_gazebo_ros_control_limits_it(example, joint, q, v, asked,
                                                               applied):
    from sw2sim.package import find_package
    from sw2sim.ros import hardware
    handle = hardware.handles(find_package(EXAMPLES / example))[joint]
    law = hardware.effort((asked, 0.0, 0.0), handle, q, v)
    assert hardware.value(law, q, v) == pytest.approx(applied, abs=1e-9)


def test_the_integral_term_is_control_toolboxs():
    """pid.cpp computeCommand: without antiwindup the sum grows and only the term is
    clamped; with it the sum stops where the term reaches i_clamp."""
    from sw2sim.ros import hardware
    pid = {"i": 500.0, "i_clamp": 50.0}
    total, term = 0.0, 0.0
    for _ in range(1000):                      # 1 m of error for 1 s, 1 ms steps
        total, term = hardware.integral(pid, total, 1.0, 0.001)
    assert total == pytest.approx(1.0) and term == pytest.approx(50.0)
    total, term = hardware.integral(pid, total, -1.0, 0.5)   # the error turns: still wound up
    assert term == pytest.approx(50.0)
    pid["antiwindup"] = True
    total, term = 0.0, 0.0
    for _ in range(1000):
        total, term = hardware.integral(pid, total, 1.0, 0.001)
    assert total == pytest.approx(0.1) and term == pytest.approx(50.0)
    total, term = hardware.integral(pid, total, -1.0, 0.05)   # unwinds at once
    assert term == pytest.approx(25.0)
    assert hardware.integral({"p": 1.0}, 0.0, 1.0, 0.001) == (0.0, 0.0)


def test_practice_5s_steering_joint_is_too_light_for_an_explicit_d_term():
    """_pages/reference/08-ros-without-gazebo.md: Gazebo applies a controller's force once
    per 1 ms step, stable only while d * step < 2 * inertia; Practice 5's centre steering
    joint (d = 0.5 N·m·s/rad) would need over 0.25 g·m² and has less."""
    import mujoco

    import sw2sim
    from course.practices import PRACTICES, design
    step, d = 0.001, design(PRACTICES[4]).STEERING_GAINS["d"]
    assert d == 0.5
    needed = d * step / 2
    assert needed == pytest.approx(0.25e-3)
    model = sw2sim.load_package(EXAMPLES / "example_5", fixed_base=False).compile()
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    dof = model.joint("steering_joint").dofadr[0]
    full = np.zeros((model.nv, model.nv))
    mujoco.mj_fullM(model, data, full)
    assert full[dof, dof] < needed, full[dof, dof]


@pytest.mark.parametrize("example, joint", [("example_3", "middle_arm_joint"),
                                            ("example_3", "end_arm_joint"),
                                            ("example_4", "block_joint")])
@pytest.mark.parametrize("soft", [True, False])
def test_the_mujoco_scripts_limit_the_torque_as_the_stand_in_does(example, joint, soft):
    """examples/example_3/scripts/arm_controller.py's enforce_limits (the position
    controllers of Practices 3 and 4) and sw2sim.ros.hardware give the same torque, with
    and without the <safety_controller>, over states inside and past every limit."""
    import dataclasses
    import importlib.util
    import sys

    from sw2sim.package import find_package
    from sw2sim.ros import hardware
    scripts = EXAMPLES / "example_3" / "scripts"
    sys.path.insert(0, str(scripts))
    try:
        spec = importlib.util.spec_from_file_location("arm_controller", scripts / "arm_controller.py")
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
    finally:
        sys.path.remove(str(scripts))
    handle = hardware.handles(find_package(EXAMPLES / example))[joint]
    if not soft:
        limits = dataclasses.replace(handle.limits, k_position=None, k_velocity=None,
                                     soft_lower=None, soft_upper=None)
        handle = dataclasses.replace(handle, limits=limits)
    assert handle.soft == soft
    controller = object.__new__(module.JointPositionController)
    controller.limits = handle.limits
    lim = handle.limits
    rng = np.random.default_rng(3)
    span = max(abs(lim.lower or 1.0), abs(lim.upper or 1.0)) * 1.2
    for _ in range(300):
        q = rng.uniform(-span, span) if handle.positional else rng.uniform(-10, 10)
        v = rng.uniform(-1.5, 1.5) * lim.velocity
        torque = rng.uniform(-2, 2) * lim.effort
        expected = hardware.value(hardware.effort((torque, 0.0, 0.0), handle, q, v), q, v)
        assert controller.enforce_limits(torque, q, v) == pytest.approx(expected, abs=1e-9), \
            (q, v, torque)
