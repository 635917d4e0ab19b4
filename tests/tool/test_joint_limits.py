"""A joint's URDF limits as Gazebo Sim's physics holds them.

- In the model every command shares (`load_package`, and so `convert`'s files): a
  revolute or prismatic joint pushed outwards with its URDF effort limit stays within
  WITHIN of its position limit, with no MuJoCo warning (sw2sim.limits).
- In `sw2sim ros2`'s stand-in for DART (sw2sim.ros2.hardware): the velocity stays within
  the URDF's velocity limit whatever the effort, the joint lands on its position limit,
  a velocity command is clipped to the velocity limit, and the effort to its limit.
"""

from __future__ import annotations

import math
import shutil

import mujoco
import numpy as np
import pytest

import sw2sim
from repository import EXAMPLES
from sw2sim.convert import convert
from sw2sim.package import find_package
from sw2sim.ros2 import hardware
from sw2sim.ros_control import read_joint_limits

WITHIN = 0.02          # rad or m past the limit
PUSH = 2.0             # s
LIMITED = ("example_3", "example_4", "example_5", "Arm_Assembly")


def package_of(name, tmp_path):
    """An example package; Arm_Assembly with the fixes of the "Your own model" page (its
    end arm's mesh from Practice 3, and the limits typed in)."""
    if name != "Arm_Assembly":
        return EXAMPLES / name
    dst = tmp_path / name
    shutil.copytree(EXAMPLES / name, dst)
    shutil.copy(EXAMPLES / "example_3/meshes/end_arm_link.STL", dst / "meshes/end_arm_link.STL")
    urdf = dst / "urdf/Arm_Assembly.urdf"
    text = urdf.read_text()
    assert text.count('upper="0"') == 2
    urdf.write_text(text.replace('lower="0"', 'lower="-0.7854"').replace('upper="0"', 'upper="0.7854"')
                    .replace('effort="0"', 'effort="1000"').replace('velocity="0"', 'velocity="2"'))
    return dst


def limited_joints(model):
    moving = (int(mujoco.mjtJoint.mjJNT_HINGE), int(mujoco.mjtJoint.mjJNT_SLIDE))
    return [j for j in range(model.njnt) if model.jnt_limited[j] and model.jnt_type[j] in moving]


def push(model, joint, sign, effort, start=None):
    """Push one joint outwards (sign +1: past its upper limit) with `effort` for PUSH
    seconds from `start` (its position; None: the home pose). Returns, per step, how far
    it is past the limit, the speed it moved with in the step, and MuJoCo's warnings."""
    data = mujoco.MjData(model)
    qa, dof = model.jnt_qposadr[joint], model.jnt_dofadr[joint]
    limit = model.jnt_range[joint][1 if sign > 0 else 0]
    if start is not None:
        data.qpos[qa] = start
    mujoco.mj_forward(model, data)
    past, speed = [], []
    for _ in range(int(round(PUSH / model.opt.timestep))):
        data.qfrc_applied[dof] = sign * effort
        mujoco.mj_step(model, data)
        past.append(sign * (float(data.qpos[qa]) - limit))
        speed.append(abs(float(data.qvel[dof])))
    return np.array(past), np.array(speed), sum(int(w.number) for w in data.warning)


def cases(name, tmp_path):
    pkg = find_package(package_of(name, tmp_path))
    model = sw2sim.load_package(pkg, fixed_base=pkg.world_fixed, scene="floor").compile()
    efforts = {n: lim.effort for n, lim in read_joint_limits(pkg).items()}
    joints = limited_joints(model)
    assert joints, name
    return model, [(j, model.joint(j).name, efforts[model.joint(j).name], sign)
                   for j in joints for sign in (1, -1)]


@pytest.mark.parametrize("name", LIMITED)
def test_a_joint_at_its_limit_holds_there_under_its_full_effort(name, tmp_path):
    model, pushes = cases(name, tmp_path)
    for joint, joint_name, effort, sign in pushes:
        limit = model.jnt_range[joint][1 if sign > 0 else 0]
        past, _, warnings = push(model, joint, sign, effort, start=limit)
        assert past.max() <= WITHIN, (name, joint_name, sign, effort, past.max())
        assert warnings == 0, (name, joint_name, sign)


@pytest.mark.parametrize("name", LIMITED)
def test_a_joint_driven_into_its_limit_stops_there(name, tmp_path):
    """From the home pose the full effort reaches the limit at speed: MuJoCo looks at a limit
    at the start of each step, so the joint passes it by at most the step it took (the
    speed it moved with times the time step), and is held within WITHIN from then on."""
    model, pushes = cases(name, tmp_path)
    dt = model.opt.timestep
    for joint, joint_name, effort, sign in pushes:
        past, speed, warnings = push(model, joint, sign, effort)
        crossing = int(np.argmax(past > 0)) if (past > 0).any() else None
        assert crossing is not None, (name, joint_name, sign)        # it got there
        assert past.max() <= max(WITHIN, speed[crossing] * dt * 1.01), (
            name, joint_name, sign, past.max(), speed[crossing] * dt)
        settled = past[crossing + int(round(0.1 / dt)):]
        assert settled.max() <= WITHIN, (name, joint_name, sign, settled.max())
        assert warnings == 0, (name, joint_name, sign)


def test_the_model_convert_writes_holds_the_end_arm_at_its_limit(tmp_path):
    """The model folder `sw2sim convert` writes, loaded by MuJoCo alone: Practice 3's end arm
    pushed outwards with its URDF effort limit, 1000 N·m, for 2 s."""
    convert(EXAMPLES / "example_3", tmp_path / "arm")
    model = mujoco.MjModel.from_xml_path(str(tmp_path / "arm" / "scene.xml"))
    joint = model.joint("end_arm_joint").id
    past, speed, warnings = push(model, joint, 1, 1000.0, start=model.jnt_range[joint][1])
    assert past.max() <= WITHIN and warnings == 0, past.max()
    past, speed, warnings = push(model, joint, 1, 1000.0)
    assert past[int(round(0.5 / model.opt.timestep)):].max() <= WITHIN and warnings == 0
    readme = (tmp_path / "arm" / "README.md").read_text()
    assert "hard stop" in readme and "solreflimit" in readme


# ---- DART's rules in `sw2sim ros2`'s stand-in (sw2sim.ros2.hardware) ----------------------

def test_the_urdfs_limits_reach_dart_as_gz_physics_gives_them():
    bounds = hardware.joint_bounds(find_package(EXAMPLES / "example_5"))
    assert bounds["steering_joint"] == hardware.Bounds(-0.5236, 0.5236, 3.0, 5.0)
    # continuous: no position range, the velocity and effort limits all the same
    assert bounds["front_left_wheel_joint"] == hardware.Bounds(-math.inf, math.inf, 30.0, 10.0)
    # no <limit> at all: nothing
    bounds = hardware.joint_bounds(find_package(EXAMPLES / "example_1"))
    assert set(bounds.values()) == {hardware.Bounds()}


def test_the_velocity_dart_allows_in_a_step():
    b, dt = hardware.Bounds(-1.0, 1.0, 2.0, 10.0), 0.002
    assert hardware.velocity_range(b, 0.0, dt) == (-2.0, 2.0)            # the velocity limit
    assert hardware.velocity_range(b, 0.999, dt) == pytest.approx((-2.0, 0.5))  # lands on it
    # past a limit: back at the speed that undoes it in a step, at most 10
    assert hardware.velocity_range(b, 1.001, dt) == pytest.approx((-math.inf, -0.5))
    assert hardware.velocity_range(b, 1.5, dt) == (-math.inf, -10.0)
    assert hardware.velocity_range(b, -1.5, dt) == (10.0, math.inf)
    assert hardware.servo_range(b, 1.5, dt) is None                       # no servo there


def test_a_velocity_command_is_clipped_to_the_velocity_limit():
    b, dt, inertia = hardware.Bounds(-1.0, 1.0, 2.0, 1000.0), 0.002, 0.01
    allowed = hardware.servo_range(b, 0.0, dt)
    fast = hardware.joint_law({"velocity": 10.0}, 0.0, 0.0, effort_limit=b.effort,
                              inertia=inertia, dt=dt, position_gain=100.0, enforce=False,
                              interface_limits={}, allowed=allowed)
    limit = hardware.joint_law({"velocity": 2.0}, 0.0, 0.0, effort_limit=b.effort,
                               inertia=inertia, dt=dt, position_gain=100.0, enforce=False,
                               interface_limits={}, allowed=allowed)
    assert fast == limit


def stand_in(effort_of, seconds=1.5):
    """Practice 3's arm as `sw2sim ros2` steps it, each joint's effort from `effort_of(t)`
    clipped to its limit: the positions and velocities after each step."""
    package = find_package(EXAMPLES / "example_3")
    model = sw2sim.load_package(package, scene="floor").compile()
    data = mujoco.MjData(model)
    joints = hardware.constrained_joints(model, hardware.joint_bounds(package))
    q, v = [], []
    for _ in range(int(round(seconds / model.opt.timestep))):
        for (_, dof, b), force in zip(joints, effort_of(data.time)):
            data.qfrc_applied[dof] = min(max(force, -b.effort), b.effort)
        before = [float(data.qpos[qa]) for qa, _, _ in joints]
        mujoco.mj_step(model, data)
        hardware.constrain(model, data, joints, before)
        q.append(data.qpos.copy()), v.append(data.qvel.copy())
    return np.array(q), np.array(v), sum(int(w.number) for w in data.warning)


def test_the_arm_turns_no_faster_than_its_velocity_limit_and_lands_on_its_limit():
    """Both arms pushed with 10 times their effort limit (clipped to it): each turns at its
    URDF velocity limit, 2 rad/s, and stops on its limit, not past it."""
    q, v, warnings = stand_in(lambda t: (10000.0, -10000.0))
    assert np.abs(v).max() <= 2.0 + 1e-9
    assert np.abs(v[50]) == pytest.approx([2.0, 2.0])            # at the limit speed
    assert q[:, 0].max() <= 0.7854 + 1e-9 and q[:, 1].min() >= -0.7854 - 1e-9
    assert q[-1] == pytest.approx([0.7854, -0.7854], abs=1e-6)   # held there, 1000 N·m on it
    assert warnings == 0
