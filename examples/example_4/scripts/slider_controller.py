"""Practice 4, MuJoCo version: the block's effort-based position controller.

The controller is Practice 3's, imported from examples/example_3/scripts; only
the setup is new. It reads example_4's own files:
- the PID gains and the joint-state rate from config/joint_names_example_4.yaml;
- one motor per <transmission> in the URDF: for a prismatic joint its control
  is a force in newtons, clipped at the joint's effort limit;
- the velocity limit (m/s) and the <safety_controller> gains from the URDF.

Run it from the repository root:
    python examples/example_4/scripts/slider_controller.py
"""

import sys
from pathlib import Path

import mujoco
import numpy as np

import sw2sim
from sw2sim.ros_control import add_motors, read_controllers, read_joint_limits

sys.path.insert(0, "examples/example_3/scripts")   # run from the repository root
from arm_controller import JointPositionController  # noqa: E402  (Practice 3's)

PACKAGE = Path("examples/example_4")        # run from the repository root
POSITION_CONTROLLER = "effort_controllers/JointPositionController"
TIMESTEP = 0.001      # s, as in Practice 3
ACCELERATION = 2.0    # m/s²: up to 1 m/s in half a second, over 0.25 m
VIEWER_KP = 2000.0    # N/m: the stiffness of the viewer's position actuator


class Slider:
    """The bar and block in MuJoCo, the block's position controller and a log."""

    def __init__(self, package=PACKAGE):
        package = Path(package)
        spec = sw2sim.load_package(package)
        spec.option.timestep = TIMESTEP
        motors = add_motors(spec, package)
        self.model = spec.compile()
        self.data = mujoco.MjData(self.model)

        config = package / "config" / f"joint_names_{spec.modelname}.yaml"
        settings = read_controllers(config)[spec.modelname]
        self.state_rate = settings["joint_state_controller"]["publish_rate"]
        name, c = next((n, c) for n, c in settings.items()
                       if c.get("type") == POSITION_CONTROLLER)
        self.name = name
        self.limits = read_joint_limits(package)[c["joint"]]
        self.controller = JointPositionController(
            self.model, c["joint"], c["pid"], self.limits, ACCELERATION)
        self.motor = motors.index(next(
            m for m in motors
            if self.model.actuator(m).trnid[0] == self.model.joint(c["joint"]).id))
        self.log = []
        self._every = max(1, round(1 / (self.state_rate * TIMESTEP)))
        self._steps = 0

    def command(self, position):
        """Like publishing to .../block_controller/command: a position in metres."""
        self.controller.command(position)

    def position(self):
        return float(self.data.qpos[self.controller.qpos])

    def speed(self):
        return float(self.data.qvel[self.controller.dof])

    def force(self):
        return float(self.data.ctrl[self.motor])

    def step(self):
        if self._steps % self._every == 0:
            self.log.append((self.data.time, self.controller.setpoint,
                             self.position(), self.speed(), self.force()))
        self.data.ctrl[self.motor] = self.controller.effort(self.data, TIMESTEP)
        mujoco.mj_step(self.model, self.data)
        self._steps += 1

    def run(self, seconds):
        for _ in range(round(seconds / TIMESTEP)):
            self.step()

    def states(self):
        """The log as arrays: time, set point, position, speed, force."""
        return np.array(self.log).T


def viewer_model(package=PACKAGE, kp=VIEWER_KP):
    """The model with a MuJoCo position actuator on the block, for the viewer's
    Control panel: its slider runs from the lower to the upper limit."""
    package = Path(package)
    spec = sw2sim.load_package(package)
    joint, limits = next(iter(read_joint_limits(package).items()))
    servo = spec.add_actuator(name="block_position", target=joint,
                              trntype=mujoco.mjtTrn.mjTRN_JOINT)
    servo.set_to_position(kp=kp, dampratio=1.0)
    servo.ctrllimited = mujoco.mjtLimited.mjLIMITED_TRUE
    servo.ctrlrange = [limits.lower, limits.upper]
    return spec.compile()


if __name__ == "__main__":
    slider = Slider()
    slider.command(2.0)
    slider.run(3.5)
    print(f"{slider.name}: set point {slider.controller.setpoint:.3f} m, "
          f"block at {slider.position():.4f} m")
