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
    """Every example at once, under one master: each robot_state_publisher reads its
    example's description in a namespace of its own, and one probe sets the joints of all."""
    import rosgraph
    master = rosgraph.Master("/test_urdf_import", master_uri=ros.uri)
    robots, expected = {}, {}
    for n in practice_numbers():
        ns, package = f"/example_{n}", EXAMPLES / f"example_{n}"
        master.setParam(f"{ns}/robot_description",
                        next((package / "urdf").glob("*.urdf")).read_text())
        ros.start(ROBOT_STATE_PUBLISHER, f"__ns:={ns}", f"/tf:={ns}/tf",
                  f"/tf_static:={ns}/tf_static", name=f"robot_state_publisher_{n}")
        robots[ns], expected[ns] = random_pose(package, n)

    done = ros.python(PROBE, json.dumps(robots))
    assert done.returncode == 0, done.stdout + done.stderr
    answers = json.loads(done.stdout.splitlines()[-1])
    for ns, poses in expected.items():
        seen = poses_from_tf(answers[ns])
        assert set(seen) == set(poses) - {BASE}, (ns, sorted(seen), sorted(poses))
        for frame, pose in seen.items():
            mine = poses[frame]
            assert np.allclose(pose[:3, 3], mine[:3, 3], atol=1e-4), (ns, frame)
            turn = pose[:3, :3].T @ mine[:3, :3]
            angle = np.arccos(np.clip((np.trace(turn) - 1) / 2, -1, 1))
            assert angle < 1e-4, (ns, frame, angle)


def random_pose(package: Path, n: int) -> tuple[dict, dict[str, np.ndarray]]:
    """Random positions of example n's joints (what the probe publishes, and how many
    frames to wait for), and MuJoCo's link poses for them in the base link's frame."""
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
    poses = poses_from_mujoco(model, data)
    # Every link but the base has a frame on /tf; a base fixed to "world" has one too.
    frames = len(poses) - 1 + (1 if world_fixed(package) else 0)
    return {"names": names, "positions": angles, "frames": frames}, poses
