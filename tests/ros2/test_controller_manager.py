"""The controller manager's services of `sw2sim ros2`, called on Practice 3's ported package
by an independent rclpy node (control_client.py) the way Jazzy's `ros2 control` verbs and
the spawner call them: three active controllers listed with their interfaces, the end
arm's controller deactivated (it stops commanding: the arm ignores a trajectory and gets
no force) and activated again (it follows once more), refusals with upstream's messages,
and the spawner's load, configure and activate after an unload. One `sw2sim ros2` run
serves the whole module."""

from __future__ import annotations

import json
import subprocess
import time

import pytest

from conftest import Ros2, group_alive
from ros2_environment import PYTHON, missing

JTC = "joint_trajectory_controller/JointTrajectoryController"
JSB = "joint_state_broadcaster/JointStateBroadcaster"
# what a spawner's --param-file gives the end arm's controller when it is loaded again
PARAMS = f"""\
end_arm_controller:
  ros__parameters:
    type: {JTC}
    update_rate: 50
    joints: [end_arm_joint]
    command_interfaces: [effort]
    state_interfaces: [position, velocity]
    gains:
      end_arm_joint: {{p: 40.0, i: 4.0, d: 2.0, i_clamp_max: 0.2, i_clamp_min: -0.2}}
"""


@pytest.fixture(scope="module")
def seen(tmp_path_factory, ported_example_3):
    """What the client saw, from one run of the stand-in (its wall time is printed)."""
    if missing():
        pytest.skip(missing())
    folder = tmp_path_factory.mktemp("controller_manager")
    (folder / "params.yaml").write_text(PARAMS, encoding="utf-8")
    world = Ros2(folder / "ros_home")
    began = time.monotonic()
    try:
        world.start(str(PYTHON), "-m", "sw2sim", "ros2", str(ported_example_3), "--realtime",
                    "0", "--duration", "60", name="standin")
        done = subprocess.run([str(PYTHON), str(world.here / "control_client.py"),
                               str(folder / "params.yaml")],
                              env=world.env, capture_output=True, text=True, timeout=90,
                              start_new_session=True)
        assert done.returncode == 0, f"{done.stderr[-3000:]}\n{world.log('standin')[-3000:]}"
        out = json.loads(done.stdout)
    finally:
        world.stop_all()
    print(f"\nthe controller manager's run: {time.monotonic() - began:.1f} s "
          f"(the client's calls {out['wall']:.1f} s)")
    assert not [p.pid for p in world.processes if group_alive(p.pid)]
    return out


def test_list_controllers_gives_three_active_controllers_and_their_interfaces(seen):
    listed = {c["name"]: c for c in seen["listed"]}
    assert {n: (c["type"], c["state"]) for n, c in listed.items()} == {
        "joint_state_broadcaster": (JSB, "active"),
        "middle_arm_controller": (JTC, "active"), "end_arm_controller": (JTC, "active")}
    end = listed["end_arm_controller"]
    assert end["claimed"] == end["required_command"] == ["end_arm_joint/effort"]
    assert end["required_state"] == ["end_arm_joint/position", "end_arm_joint/velocity"]
    assert (end["update_rate"], end["is_async"], end["is_chainable"],
            end["chain_connections"]) == (1000, False, False, 0)
    broadcaster = listed["joint_state_broadcaster"]
    assert broadcaster["update_rate"] == 20 and broadcaster["claimed"] == []
    assert "middle_arm_joint/effort" in broadcaster["required_state"]   # all of them


def test_the_types_and_the_hardware_are_listed(seen):
    assert seen["types"][JTC] == "controller_interface::ControllerInterface"
    assert seen["types"]["pid_controller/PidController"] == \
        "controller_interface::ChainableControllerInterface"
    assert seen["command_interfaces"] == [["end_arm_joint/effort", True, True],
                                          ["middle_arm_joint/effort", True, True]]
    assert "middle_arm_joint/position" in seen["state_interfaces"]
    name, kind, plugin, state, commands = seen["components"][0]
    assert (kind, plugin, state) == ("system", "gz_ros2_control/GazeboSimSystem", "active")
    assert commands == ["middle_arm_joint/effort", "end_arm_joint/effort"]


def test_a_deactivated_controller_stops_commanding_its_joint(seen):
    assert abs(seen["moved"] - 0.4) < 0.01
    assert seen["deactivate"] == {"ok": True, "message": "Successfully switched controllers!"}
    after = {c["name"]: c for c in seen["after_deactivate"]}
    assert after["end_arm_controller"]["state"] == "inactive"
    assert after["end_arm_controller"]["claimed"] == []
    assert seen["claimed_after_deactivate"] == ["middle_arm_joint/effort"]
    # 2 s of simulated time: the trajectory to -0.4 rad sent to the inactive controller is
    # dropped and the joint gets no force (gz-sim keeps the force component that effort
    # control made, so no hold either): the arm, at rest, stays where it was
    inactive = seen["inactive"]
    assert inactive[-1][0] - inactive[0][0] >= 1.9
    assert all(abs(q - seen["moved"]) < 0.01 for _, q, _ in inactive), inactive[::10]


def test_joint_states_carry_the_effort_state_gz_ros2_control_leaves_at_its_initial_value(seen):
    """gz_ros2_control 1.2.7 reads each joint's position and velocity from Gazebo Sim but
    not its force (the line is commented out), so the effort state interface keeps its
    initial_value (0 when the URDF gives none), also while the PID pushes the arm."""
    moving = seen["moving"]
    # the end arm turned under the PID's effort while these states were heard (at
    # --realtime 0 part of its way can be over before the first of them arrives)
    speeds = [abs(q1 - q0) / (t1 - t0) for (t0, q0, _), (t1, q1, _) in zip(moving, moving[1:])
              if t1 > t0]
    assert max(speeds) > 0.2, moving[:5]
    assert all(e == 0.0 for _, _, e in moving + seen["inactive"]), moving[:5]


def test_an_activated_controller_follows_again(seen):
    assert seen["activate"]["ok"], seen["activate"]
    assert seen["activate"]["message"] == (
        "Successfully switched controllers!\nActivated controllers: [ end_arm_controller ]")
    assert abs(seen["reactivated"] + 0.3) < 0.01


def test_switches_are_refused_as_upstream_refuses_them(seen):
    assert seen["unknown"] == {"ok": False, "message": (
        "Could not activate controller with name 'no_such_controller' because no "
        "controller with this name exists")}
    assert seen["again_strict"] == {
        "ok": False, "message": "Controller with name 'middle_arm_controller' is already active."}
    assert seen["again_best_effort"] == {"ok": True, "message": (
        "After checking the controllers, no controllers need to be activated or deactivated.")}


def test_the_spawners_sequence_after_an_unload(seen):
    """With --param-file: its parameters (an update_rate of 50) are the controller's."""
    assert seen["unload_active"] is False    # not while active
    assert seen["unload"] is True
    assert seen["after_unload"] == ["joint_state_broadcaster", "middle_arm_controller"]
    assert seen["configure_unloaded"] is False
    assert seen["parameters_set"] == [True, True]
    assert seen["load"] is True
    loaded = seen["loaded"][0]
    assert (loaded["state"], loaded["required_command"]) == ("unconfigured", [])
    assert loaded["update_rate"] == 50
    assert seen["activate_unconfigured"]["ok"] is False
    assert "is in 'unconfigured' state" in seen["activate_unconfigured"]["message"]
    assert seen["configure"] is True and seen["configured"] == ["inactive"]
    assert seen["spawned"]["ok"], seen["spawned"]
    assert seen["final"] == {"joint_state_broadcaster": "active",
                             "middle_arm_controller": "active", "end_arm_controller": "active"}
