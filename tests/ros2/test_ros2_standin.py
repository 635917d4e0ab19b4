"""`sw2sim ros2` on example_3 as `sw2sim port` writes it, seen by an independent rclpy node:
the arm follows a trajectory to each controller, the end arm sent past its limit stops
on it at its velocity limit (as DART holds it), /clock advances, /robot_description
holds the URDF, and /tf_static and /tf give MuJoCo's kinematics."""

from __future__ import annotations

import math

import mujoco
import numpy as np

import sw2sim
from sw2sim.ros2 import description


def compose(chain):
    """world -> link from a list of (translation, quaternion xyzw) transforms."""
    position, rotation = np.zeros(3), (0.0, 0.0, 0.0, 1.0)
    for t, q in chain:
        position = position + np.array(description.rotate(rotation, t))
        rotation = description.multiply(rotation, tuple(q))
    return position, rotation


def test_an_independent_node_drives_the_arm_and_sees_mujocos_kinematics(ros2, ported_example_3):
    ros2.standin(ported_example_3)
    out = ros2.record("4", "--trajectory", "middle_arm_controller", "middle_arm_joint", "0.5", "2",
                      "--trajectory", "end_arm_controller", "end_arm_joint", "-5.0", "2",
                      "--state", "middle_arm_controller", "jtc")
    assert "ROS_DOMAIN_ID=" in ros2.log("standin")
    # /clock advances; the last joint state is at the targets
    assert out["clock"] == sorted(out["clock"]) and out["clock"][-1] > out["clock"][0] + 3.5
    t, q, v = out["states"][-1]
    log = ros2.log("standin")[-3000:]
    assert abs(q["middle_arm_joint"] - 0.5) < 0.01, (q, out.get("sent_at"), log)
    # the end arm, sent to -5 rad, stops on its -0.7854 rad limit and never passes it, and
    # turns no faster than its URDF velocity limit of 2 rad/s, however hard its PID pushes
    assert abs(q["end_arm_joint"] + 0.7854) < 0.02, (q, out.get("sent_at"), log)
    assert min(s[1]["end_arm_joint"] for s in out["states"]) > -0.7854 - 0.02
    assert max(abs(s[2]["end_arm_joint"]) for s in out["states"]) < 2.0 + 1e-6
    # on the way for about the trajectory's 2 s (a linear reference), not a jump to it: the
    # pace of the states heard between 10 % and 90 % of the way (a busy machine's recorder
    # misses messages, so the first one heard past a mark may come late)
    ramp = np.array([(s[0], s[1]["middle_arm_joint"]) for s in out["states"]
                     if 0.05 < s[1]["middle_arm_joint"] < 0.45])
    assert len(ramp) >= 3 and np.ptp(ramp[:, 0]) > 0.3, ramp
    pace = np.polyfit(ramp[:, 0], ramp[:, 1], 1)[0]   # rad per simulated second
    assert 1.8 < 0.5 / pace < 2.2, (pace, ramp)
    # /robot_description is the URDF; /tf_static holds the fixed joint
    assert out["description"] == (ported_example_3 / "urdf" / "example_3.urdf").read_text()
    assert ["world", "base_link"] == out["tf_static"][0][:2]
    # /tf at the last joint state that came with one gives MuJoCo's pose of end_arm_link
    stamps = {s[0]: s[1] for s in out["states"]}
    tf = next(m for m in reversed(out["tf"]) if m and m[0][2] in stamps)
    angles = stamps[tf[0][2]]
    frames = {child: (parent, tr, rot) for parent, child, _, tr, rot in tf}
    frames["base_link"] = ("world", *out["tf_static"][0][2:])
    chain, link = [], "end_arm_link"
    while link != "world":
        parent, tr, rot = frames[link]
        chain.insert(0, (tr, rot))
        link = parent
    position, _ = compose(chain)
    model = sw2sim.load_package(ported_example_3).compile()
    data = mujoco.MjData(model)
    for name, value in angles.items():
        data.qpos[model.jnt_qposadr[model.joint(name).id]] = value
    mujoco.mj_kinematics(model, data)
    assert np.allclose(position, data.body("end_arm_link").xpos, atol=1e-4)
    # the trajectory controller's state
    state = out["controller_state"]["middle_arm_controller"]
    assert state["joints"] == ["middle_arm_joint"]
    assert math.isclose(state["reference"][0], 0.5, abs_tol=1e-9)
    assert abs(state["error"][0]) < 0.01 and abs(state["feedback"][0] - 0.5) < 0.01
    assert len(state["output"]) == 1
