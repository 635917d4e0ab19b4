"""`sw2sim convert`: a model folder that loads in plain MuJoCo and keeps the package's model."""

import json
import os
import subprocess
import sys
from pathlib import Path

import mujoco
import pytest

import sw2sim
from sw2sim.convert import _asset_name, convert, file_stem
from sw2sim.loader import world_fixed

from repository import EXAMPLES, practice_numbers
NUMBERS = practice_numbers()
# The actuators each practice's controllers and transmissions make.
ACTUATORS = {1: 0, 2: 0, 3: 2, 4: 1, 5: 7}

# Loads each scene.xml with nothing but mujoco, steps 1 s, and reports what it found.
PLAIN = """
import json, sys
import mujoco
out = {}
for folder in sys.argv[1:]:
    m = mujoco.MjModel.from_xml_path(folder + "/scene.xml")
    d = mujoco.MjData(m)
    mujoco.mj_step(m, d, nstep=round(1.0 / m.opt.timestep))
    out[folder] = dict(nbody=m.nbody, njnt=m.njnt, ngeom=m.ngeom, nmesh=m.nmesh, nu=m.nu,
                       finite=bool(abs(d.qpos).max() < 1e6),
                       warnings=sum(w.number for w in d.warning))
out["sw2sim imported"] = any(name.startswith("sw2sim") for name in sys.modules)
print(json.dumps(out))
"""


@pytest.fixture(scope="module")
def converted(tmp_path_factory):
    """Every example converted once: {n: output folder}. (The command, which checks the
    package first, is tested in test_cli.py.)"""
    root = tmp_path_factory.mktemp("converted")
    folders = {n: root / f"example_{n}_mujoco" for n in NUMBERS}
    for n, folder in folders.items():
        convert(EXAMPLES / f"example_{n}", folder)
    return folders


@pytest.fixture(scope="module")
def plain(converted, tmp_path_factory):
    """What plain MuJoCo, in a fresh process started elsewhere, makes of every scene.xml."""
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    result = subprocess.run([sys.executable, "-c", PLAIN, *map(str, converted.values())],
                            cwd=tmp_path_factory.mktemp("elsewhere"), env=env,
                            capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stderr
    return json.loads(result.stdout)


def reference(n):
    """The model as sw2sim.load_package makes it, with the same base."""
    package = EXAMPLES / f"example_{n}"
    return sw2sim.load_package(package, fixed_base=world_fixed(package)).compile()


def test_plain_mujoco_loads_them_without_sw2sim(plain):
    assert plain.pop("sw2sim imported") is False


@pytest.mark.parametrize("n", NUMBERS)
def test_the_folder_holds_the_robot_the_scene_the_meshes_and_a_readme(converted, n):
    folder = converted[n]
    assert sorted(p.name for p in folder.iterdir()) == sorted(
        ["assets", "README.md", "scene.xml", f"example_{n}.xml"])
    meshes = sorted((EXAMPLES / f"example_{n}" / "meshes").iterdir())
    assert sorted(p.name for p in (folder / "assets").iterdir()) == [m.name for m in meshes]
    for mesh in meshes:
        assert (folder / "assets" / mesh.name).read_bytes() == mesh.read_bytes()
    robot = (folder / f"example_{n}.xml").read_text()
    assert 'meshdir="assets"' in robot and str(EXAMPLES) not in robot, "no absolute paths"
    assert f'<include file="example_{n}.xml"/>' in (folder / "scene.xml").read_text()


@pytest.mark.parametrize("n", NUMBERS)
def test_plain_mujoco_gets_the_same_model_and_it_runs(converted, plain, n):
    found = plain[str(converted[n])]
    ref = reference(n)
    assert (found["nbody"], found["njnt"], found["nmesh"]) == (ref.nbody, ref.njnt, ref.nmesh)
    assert found["ngeom"] == ref.ngeom, "the robot's geoms and one floor, as load_package"
    assert n in ACTUATORS, f"example_{n} is new: add its count of actuators to ACTUATORS"
    assert found["nu"] == ACTUATORS[n]
    assert found["finite"] and found["warnings"] == 0


@pytest.mark.parametrize("n", NUMBERS)
def test_masses_and_joints_are_the_packages(converted, n):
    model = mujoco.MjModel.from_xml_path(str(converted[n] / "scene.xml"))
    ref = reference(n)
    assert model.body_mass.tolist() == pytest.approx(ref.body_mass.tolist(), rel=1e-5)
    assert model.jnt_range.ravel().tolist() == pytest.approx(ref.jnt_range.ravel().tolist())
    assert model.ngeom == ref.ngeom


def test_the_blocks_controller_becomes_a_position_actuator_that_holds_its_target(converted):
    model = mujoco.MjModel.from_xml_path(str(converted[4] / "scene.xml"))
    servo = model.actuator("block_controller")
    assert servo.gainprm[0] == 2000 and servo.biasprm[1:3].tolist() == [-2000, -200]
    assert servo.ctrlrange.tolist() == pytest.approx([0.0, 2.69])
    assert servo.forcerange.tolist() == [-200, 200]
    data = mujoco.MjData(model)
    data.ctrl[0] = 1.5
    mujoco.mj_step(model, data, nstep=round(3.0 / model.opt.timestep))
    assert data.joint("block_joint").qpos[0] == pytest.approx(1.5, abs=0.002)


def test_the_vehicle_is_free_and_rests_on_the_floor(converted):
    model = mujoco.MjModel.from_xml_path(str(converted[5] / "scene.xml"))
    assert model.jnt_type[0] == mujoco.mjtJoint.mjJNT_FREE
    assert model.actuator("front_left_wheel_controller").gainprm[0] == 5    # velocity, kv = p
    data = mujoco.MjData(model)
    start = data.qpos[2]
    mujoco.mj_step(model, data, nstep=round(1.0 / model.opt.timestep))
    assert abs(data.qpos[2] - start) < 0.005, "settles by at most a few millimetres"


def _velocity_interface_arm(folder: Path, yaml: str) -> Path:
    """Practice 3's arm with its controllers on the velocity interface, as arms driven by
    velocity-controlled servos are configured."""
    from packages import copy_example
    package = copy_example(3, folder)
    (package / "config" / "controllers.yaml").write_text(yaml)
    for other in (package / "config").glob("*.yaml"):
        if other.name != "controllers.yaml" and "type:" in other.read_text():
            other.unlink()
    return package


def test_velocity_controllers_become_a_servo_on_position_and_one_on_velocity(tmp_path):
    package = _velocity_interface_arm(tmp_path, """example_3:
  middle_arm_controller:
    type: velocity_controllers/JointPositionController
    joint: middle_arm_joint
    pid: {p: 5.0, i: 0.0, d: 0.0}
  end_arm_controller:
    type: velocity_controllers/JointVelocityController
    joint: end_arm_joint
""")
    result = convert(package, tmp_path / "out")
    kinds = {a.name: (a.kind, a.source) for a in result.actuators}
    assert kinds["middle_arm_controller"][0] == "position"
    assert kinds["end_arm_controller"][0] == "velocity"
    assert "velocity_controllers/JointPositionController" in kinds["middle_arm_controller"][1]
    assert not result.skipped, result.skipped
    model = mujoco.MjModel.from_xml_path(str(tmp_path / "out" / "scene.xml"))
    position = model.actuator("middle_arm_controller")
    # kp = K p, kv = K: the velocity command p (target - q) followed by a stiff servo K
    assert -position.biasprm[1] == pytest.approx(5 * -position.biasprm[2], rel=1e-5)
    data = mujoco.MjData(model)
    data.ctrl[position.id] = 0.3
    data.ctrl[model.actuator("end_arm_controller").id] = 0.5
    mujoco.mj_step(model, data, nstep=round(0.2 / model.opt.timestep))
    # the position error closes as exp(-p t), from 0.3 to 0.3 e^-1 after 0.2 s
    assert data.joint("middle_arm_joint").qpos[0] == pytest.approx(0.3 * (1 - 1 / 2.718),
                                                                  abs=0.02)
    assert data.joint("end_arm_joint").qvel[0] == pytest.approx(0.5, abs=0.01)


def test_a_group_velocity_controller_drives_each_of_its_joints(tmp_path):
    package = _velocity_interface_arm(tmp_path, """example_3:
  arm_controller:
    type: velocity_controllers/JointGroupVelocityController
    joints: [middle_arm_joint, end_arm_joint]
""")
    result = convert(package, tmp_path / "out")
    assert [(a.name, a.joint, a.kind) for a in result.actuators] == [
        ("arm_controller_middle_arm_joint", "middle_arm_joint", "velocity"),
        ("arm_controller_end_arm_joint", "end_arm_joint", "velocity")]


def test_the_readme_says_what_came_from_where_and_what_changed(converted):
    text = (converted[4] / "README.md").read_text()
    for claim in ("`block_controller`", "kp 2000, kv 200", "i 500", "i_clamp 50",
                  "`block_joint` 1", "Velocity limits were dropped", "soft limits",
                  "`base_link`–`block_link`", "fixed, because the URDF fixes its root",
                  "`assets/block_link.STL` from `meshes/block_link.STL`"):
        assert claim in text, claim
    assert "free (a free joint)" in (converted[5] / "README.md").read_text()
    assert "None: the package has no `<transmission>`" in (converted[1] / "README.md").read_text()


def test_names_that_would_clash_are_changed():
    assert file_stem("scene") == "robot" and file_stem("my robot/2") == "my_robot_2"
    root = Path("/pkg")
    first = _asset_name(root, root / "meshes" / "a" / "wheel.STL", set())
    second = _asset_name(root, root / "meshes" / "b" / "wheel.STL", {first})
    assert (first, second) == ("a/wheel.STL", "b/wheel.STL")
    assert _asset_name(root, root / "meshes" / "wheel.STL", {"wheel.STL"}) == "wheel_2.STL"
