"""MuJoCo's import of each example URDF against ROS's own reading of it: for random joint
angles, robot_state_publisher's transforms equal MuJoCo's forward kinematics of the model
`sw2sim.load_package` makes (1e-4 m, 1e-4 rad)."""

from __future__ import annotations

import json
from pathlib import Path

import mujoco
import numpy as np

from sw2sim.loader import load_package, world_fixed
from packages import EXAMPLES
from repository import practice_numbers

PROBE = Path(__file__).with_name("tf_probe.py")
ROBOT_STATE_PUBLISHER = "/usr/lib/robot_state_publisher/robot_state_publisher"   # Debian's
BASE = "base_link"


def quaternion_matrix(xyzw) -> np.ndarray:
    x, y, z, w = xyzw
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def poses_from_tf(transforms: dict) -> dict[str, np.ndarray]:
    """Each frame's 4 x 4 pose in the base link's frame, chaining parent -> child."""
    poses = {BASE: np.eye(4)}

    def pose(frame: str) -> np.ndarray:
        if frame in poses:
            return poses[frame]
        parent, xyz, xyzw = transforms[frame]
        local = np.eye(4)
        local[:3, :3], local[:3, 3] = quaternion_matrix(xyzw), xyz
        poses[frame] = pose(parent) @ local
        return poses[frame]

    return {frame: pose(frame) for frame in transforms if frame != BASE and
            _below_base(frame, transforms)}


def _below_base(frame: str, transforms: dict) -> bool:
    while frame in transforms:
        frame = transforms[frame][0]
        if frame == BASE:
            return True
    return False


def poses_from_mujoco(model, data) -> dict[str, np.ndarray]:
    base = model.body(BASE).id
    world_base = np.eye(4)
    world_base[:3, :3], world_base[:3, 3] = data.xmat[base].reshape(3, 3), data.xpos[base]
    inverse = np.linalg.inv(world_base)
    poses = {}
    for b in range(1, model.nbody):
        pose = np.eye(4)
        pose[:3, :3], pose[:3, 3] = data.xmat[b].reshape(3, 3), data.xpos[b]
        poses[model.body(b).name] = inverse @ pose
    return poses


def test_robot_state_publisher_agrees_with_mujoco(ros):
    """Every example in turn, under one master: the publisher is started on the example's
    description and stopped before the next."""
    from sw2sim.ros.run import stop
    for n in practice_numbers():
        publisher = agrees(ros, n)
        stop(publisher)


def agrees(ros, n: int):
    """Check example n; return its robot_state_publisher process."""
    package = EXAMPLES / f"example_{n}"
    urdf = next((package / "urdf").glob("*.urdf")).read_text()
    assert ros.run("rosparam", "set", "/robot_description", urdf).returncode == 0
    publisher = ros.start(ROBOT_STATE_PUBLISHER, name=f"robot_state_publisher_{n}")

    model = load_package(package, fixed_base=world_fixed(package), scene=False).compile()
    data = mujoco.MjData(model)
    rng = np.random.default_rng(n)
    names, angles = [], []
    for j in range(model.njnt):
        if int(model.jnt_type[j]) in (mujoco.mjtJoint.mjJNT_HINGE, mujoco.mjtJoint.mjJNT_SLIDE):
            low, high = model.jnt_range[j] if model.jnt_limited[j] else (-1.0, 1.0)
            value = float(rng.uniform(low, high))
            data.qpos[model.jnt_qposadr[j]] = value
            names.append(model.joint(j).name)
            angles.append(value)
    mujoco.mj_kinematics(model, data)
    expected = poses_from_mujoco(model, data)

    # Every link but the base has a frame on /tf; a base fixed to "world" has one too.
    frames = len(expected) - 1 + (1 if world_fixed(package) else 0)
    done = ros.python(PROBE, json.dumps(names), json.dumps(angles), str(frames))
    assert done.returncode == 0, done.stdout + done.stderr
    seen = poses_from_tf(json.loads(done.stdout.splitlines()[-1]))
    assert set(seen) == set(expected) - {BASE}, (sorted(seen), sorted(expected))
    for frame, pose in seen.items():
        mine = expected[frame]
        assert np.allclose(pose[:3, 3], mine[:3, 3], atol=1e-4), (n, frame)
        turn = pose[:3, :3].T @ mine[:3, :3]
        angle = np.arccos(np.clip((np.trace(turn) - 1) / 2, -1, 1))
        assert angle < 1e-4, (n, frame, angle)
    return publisher
