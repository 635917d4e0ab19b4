"""The stand-in's PID, pid_controller and gz_ros2_control rules, without ROS, as their
sources have them: control_toolbox 4.11.0's Pid::compute_command (the stored integral
clamped for every anti-windup strategy, conditional integration, back calculation, the
output clamp apart from the feed-forward), ros2_controllers 4.42.1's pid_controller (the
feed-forward only when enabled; a reference taken by its size, whatever its names) and
gz_ros2_control 1.2.7's `hold_joints` with gz-sim 8's command components."""

from __future__ import annotations

import shutil

import pytest

from sw2sim.ros2 import config, hardware
from sw2sim.ros2 import controllers as ctl

JOINTS = {name: config.JointInterfaces(name, ["effort"], ["position", "velocity"], {}, {})
          for name in ("a", "b")}
STILL = {"a": (0.0, 0.0), "b": (0.0, 0.0)}


def trajectory_controller(gains: dict) -> ctl.Controller:
    c = ctl.create("arm", ctl.JTC, {"joints": ["a"], "command_interfaces": ["effort"],
                                    "state_interfaces": ["position", "velocity"],
                                    "gains": {"a": gains}}, JOINTS)
    c.activate(STILL)   # holds a at 0
    c.active = True
    return c


def effort(c, t: float, q: float, v: float = 0.0, period: float = 0.01) -> float:
    out = c.update(t, period, {"a": (q, v), "b": (0.0, 0.0)})
    return ctl.value(out["a"]["effort"], q, v)


def test_the_stored_integral_is_clamped_so_that_it_unwinds_at_once():
    """pid.cpp line 438: after 2 s held 1 rad off, the legacy strategy's integral is
    i_clamp_max (0.5), not 20; the first step the other way takes it below 0.5 (the
    output-only clamp of before kept 0.5 until the sum of 20 had come back down)."""
    c = trajectory_controller({"p": 0.0, "i": 10.0, "d": 0.0, "i_clamp_max": 0.5,
                               "i_clamp_min": -0.5})
    t = 0.0
    for _ in range(200):
        assert effort(c, t, -1.0) <= 0.5 + 1e-12
        t += 0.01
    assert effort(c, t, 0.1) == pytest.approx(0.5 - 10 * 0.01 * 0.1)


def test_conditional_integration_stops_while_saturated():
    c = trajectory_controller({"p": 10.0, "i": 1.0, "u_clamp_max": 1.0, "u_clamp_min": -1.0,
                               "antiwindup_strategy": "conditional_integration"})
    for k in range(10):
        assert effort(c, k * 0.1, -1.0, period=0.1) == 1.0   # saturated, error pushing on
    assert effort(c, 1.0, -0.05, period=0.1) == pytest.approx(0.5)   # no integral built up


def test_back_calculation_feeds_the_saturation_back():
    """tracking_time_constant 0 with d = 0 is p / i = 10 s; the first step adds
    dt * (i * e + (cmd - cmd_unsat) / 10) = 0.1 * (1 - 0.9) to the integral, after the
    command (so the second command holds it, not the first)."""
    c = trajectory_controller({"p": 10.0, "i": 1.0, "u_clamp_max": 1.0, "u_clamp_min": -1.0,
                               "antiwindup_strategy": "back_calculation"})
    assert effort(c, 0.0, -1.0, period=0.1) == 1.0
    assert effort(c, 0.1, -0.05, period=0.1) == pytest.approx(0.5 + 0.01)


def test_the_velocity_feed_forward_is_added_outside_the_pid_clamp():
    """JTC: ff_velocity_scale * velocity + clamp(PID): 5 + 2 * 1 rad/s on a 1 rad/s ramp."""
    c = trajectory_controller({"p": 1000.0, "u_clamp_max": 5.0, "u_clamp_min": -5.0,
                               "ff_velocity_scale": 2.0})
    c.receive(["a"], 0.0, [(1.0, [1.0], [], [])])
    effort(c, 0.0, 0.0)
    assert effort(c, 0.5, 0.0) == pytest.approx(7.0)


def test_bad_gains_are_refused_naming_the_gain():
    with pytest.raises(ctl.ConfigError, match=r"arm: gains\.a: u_clamp_min"):
        trajectory_controller({"p": 1.0, "u_clamp_max": -1.0, "u_clamp_min": 1.0})
    with pytest.raises(ctl.ConfigError, match="antiwindup_strategy 'windup'"):
        trajectory_controller({"p": 1.0, "antiwindup_strategy": "windup"})


def pid_controller(params: dict, dofs=("a",)) -> ctl.Controller:
    base = {"dof_names": list(dofs), "command_interface": "effort",
            "reference_and_state_interfaces": ["velocity"]}
    c = ctl.create("pid", ctl.PID, {**base, **params}, JOINTS)
    c.activate({"a": (0.0, 1.0), "b": (0.0, 2.0)})   # references: the velocities, 1 and 2
    c.active = True
    return c


def pid_efforts(c, state=None) -> dict:
    state = state or {"a": (0.0, 1.0), "b": (0.0, 2.0)}
    out = c.update(0.0, 0.01, state)
    return {j: ctl.value(out[j]["effort"], *state[j]) for j in out}


def test_the_feed_forward_waits_for_enable_feedforward():
    """pid_controller.cpp: feedforward_gain * reference only when feed-forward is on
    (`enable_feedforward`, false by default, or ~/set_feedforward_control)."""
    gains = {"gains": {"a": {"p": 0.0, "feedforward_gain": 2.0}}}
    assert pid_efforts(pid_controller(gains)) == {"a": 0.0}
    assert pid_efforts(pid_controller({**gains, "enable_feedforward": True})) == {"a": 2.0}
    c = pid_controller(gains)
    c.set_feedforward(True)
    assert pid_efforts(c) == {"a": 2.0}


def test_a_reference_is_taken_by_its_size_whatever_its_names():
    """reference_callback sorts the values by the controller's own names (it resets the
    message's names before looking them up): values are taken in order."""
    gains = {"gains": {"a": {"p": 1.0}, "b": {"p": 1.0}}}
    c = pid_controller(gains, dofs=("a", "b"))
    c.receive(["elsewhere", "unknown"], [3.0, 4.0], [])
    assert pid_efforts(c, {"a": (0.0, 0.0), "b": (0.0, 0.0)}) == {"a": 3.0, "b": 4.0}
    c.receive(["b", "a"], [5.0, 6.0], [])
    assert pid_efforts(c, {"a": (0.0, 0.0), "b": (0.0, 0.0)}) == {"a": 5.0, "b": 6.0}
    c.receive(["a"], [7.0], [])   # the wrong size is refused, the references stay
    assert pid_efforts(c, {"a": (0.0, 0.0), "b": (0.0, 0.0)}) == {"a": 5.0, "b": 6.0}
    assert "is not matching the expected size (2)" in c.errors[-1]


@pytest.fixture
def ported(tmp_path):
    from sw2sim.port import port
    return port("examples/example_3", tmp_path / "example_3").package_dir


def setup_with(ported, text: str | None):
    from sw2sim.package import find_package
    urdf = ported / "urdf" / "example_3.urdf"
    source = urdf.read_text(encoding="utf-8")
    if text is not None:
        end = source.rindex("</plugin>")   # the gz_ros2_control plugin's
        source = source[:end] + f"<hold_joints>{text}</hold_joints>" + source[end:]
    urdf.write_text(source, encoding="utf-8")
    return config.read(find_package(ported))


def test_hold_joints_is_read_from_the_plugin(ported):
    copy = ported.parent / "again"
    shutil.copytree(ported, copy)
    assert setup_with(ported, None).hold_joints is True
    assert setup_with(ported, "false").hold_joints is False
    wrong = setup_with(copy, "maybe")
    assert wrong.hold_joints is True and "<hold_joints> is 'maybe'" in wrong.problems[0]


@pytest.mark.parametrize("hold", [True, False])
def test_what_reaches_a_joint_no_controller_drives(hold):
    """gz_system's write with gz-sim's Physics: before any controller, a velocity of 0
    with hold_joints, nothing without; once a controller has driven the joint, its command
    component stays: a velocity of 0 after a velocity controller, no force after an effort
    one (the force component wins over the hold's velocity), hold_joints or not."""
    idle = hardware.JointCommand(actuated=True, hold=hold)
    assert idle.step(set(), {}) == ({"velocity": 0.0} if hold else {"effort": 0.0})
    was_velocity = hardware.JointCommand(actuated=True, hold=hold)
    assert was_velocity.step({"velocity"}, {"velocity": 0.3}) == {"velocity": 0.0}  # created
    assert was_velocity.step({"velocity"}, {"velocity": 0.3}) == {"velocity": 0.3}
    assert was_velocity.step(set(), {"velocity": 0.3}) == {"velocity": 0.0}
    was_effort = hardware.JointCommand(actuated=True, hold=hold)
    assert was_effort.step({"effort"}, {"effort": 2.0}) == {"effort": 0.0}   # created
    assert was_effort.step({"effort"}, {"effort": 2.0}) == {"effort": 2.0}
    assert was_effort.step(set(), {"effort": 2.0}) == {"effort": 0.0}
    assert was_effort.step({"velocity"}, {"velocity": 0.3}) == {"effort": 0.0}
    passive = hardware.JointCommand(actuated=False, hold=hold)
    assert passive.step(set(), {}) == {"effort": 0.0}
