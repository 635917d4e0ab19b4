"""The SolidWorks-to-URDF exporter's own 3-DOF arm, as the exporter writes it (no
transmissions, no controllers), given to `sw2sim ros2` as it is: the run ports it first,
and the port's joint_trajectory_controller moves all three joints to a goal sent by an
independent rclpy node. (Its colcon build is in tests/tool/port/test_port_packages.py.)"""

from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tool" / "check"))
from exporter_packages import THREE_DOF_ARM, write_export  # noqa: E402

GOAL = {"prox_joint": 0.5, "dist_joint": -0.6, "effector_joint": 1.0}


def test_the_exporters_arm_ported_by_the_run_follows_a_trajectory(ros2, tmp_path):
    raw = write_export(THREE_DOF_ARM, tmp_path / "export")
    ros2.standin(raw)
    out = ros2.record("4", "--trajectory", "joint_trajectory_controller", ",".join(GOAL),
                      ",".join(str(x) for x in GOAL.values()), "2",
                      "--state", "joint_trajectory_controller", "jtc")
    log = ros2.log("standin")
    assert "is a ROS 1 package: ported for this run" in log, log
    assert "controllers: joint_state_broadcaster, joint_trajectory_controller" in log, log
    # at rest where the exporter left it when the goal went out, at the goal 2 s after the
    # trajectory's end
    sent = out["sent_at"]
    _, before, _ = max((s for s in out["states"] if s[0] <= sent), key=lambda s: s[0])
    assert all(abs(before[j]) < 0.01 for j in GOAL), before
    _, q, _ = out["states"][-1]
    assert all(abs(q[j] - x) < 0.01 for j, x in GOAL.items()), q
    state = out["controller_state"]["joint_trajectory_controller"]
    assert state["joints"] == list(GOAL) and state["reference"] == list(GOAL.values())
