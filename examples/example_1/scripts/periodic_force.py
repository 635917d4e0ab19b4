"""Practice 1's custom node, MuJoCo version: 1 N·m on every wheel for 1 s, every 10 s.

Run it from the repository root:  python examples/example_1/scripts/periodic_force.py
Other practices import `wheel_torque` and `run` from here instead of copying them.
"""

import mujoco
import numpy as np

import sw2sim

PERIOD = 10.0   # s between the starts of two pulses: 1 / 10 s = 0.1 Hz
PULSE = 1.0     # s that each pulse lasts
TORQUE = 1.0    # N·m on each wheel during a pulse


def wheel_torque(t, period=PERIOD, pulse=PULSE, torque=TORQUE):
    """The torque at time t: `torque` during the first `pulse` seconds of every period, else 0."""
    return torque if t % period < pulse else 0.0


def run(model, data, joints, duration, sample_rate=100.0, **pulse):
    """Step the simulation for `duration` s, pushing every joint in `joints` with wheel_torque.

    Returns the sample times, the torque applied and each joint's velocity (rad/s),
    sampled `sample_rate` times per second.
    """
    dofs = [model.joint(name).dofadr[0] for name in joints]
    every = max(1, round(1.0 / (sample_rate * model.opt.timestep)))
    times, torques, speeds = [], [], []
    step = 0
    while data.time < duration - 1e-9:
        tau = wheel_torque(data.time, **pulse)
        data.qfrc_applied[dofs] = tau       # like Gazebo's apply_joint_effort, on the joint itself
        if step % every == 0:
            times.append(data.time)
            torques.append(tau)
            speeds.append(data.qvel[dofs].copy())
        mujoco.mj_step(model, data)
        step += 1
    return np.array(times), np.array(torques), np.array(speeds)


if __name__ == "__main__":
    model = sw2sim.load_package("examples/example_1").compile()
    data = mujoco.MjData(model)
    wheels = ["front_left_joint", "front_right_joint", "rear_left_joint", "rear_right_joint"]
    t, tau, omega = run(model, data, wheels, duration=30.0)
    for second in range(0, 31, 5):
        i = min(np.searchsorted(t, second), len(t) - 1)
        print(f"t = {t[i]:5.1f} s   torque = {tau[i]:.1f} N·m   front-left wheel = {omega[i, 0]:6.1f} rad/s")
