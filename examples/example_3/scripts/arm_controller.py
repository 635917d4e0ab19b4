"""Practice 3, MuJoCo version: effort-based position controllers, set up like ROS's.

In Gazebo, gazebo_ros_control and effort_controllers/JointPositionController do
this work; here the script does it, reading the same files:
- the PID gains and the joint-state rate from config/joint_names_example_3.yaml;
- one motor per <transmission> in the URDF, clipped at the joint's effort limit;
- the velocity limit and the <safety_controller> gains from the URDF, which
  MuJoCo's importer drops, enforced the way ros_control's limits interface does.

Run it from the repository root:
    python examples/example_3/scripts/arm_controller.py
"""

import math
from pathlib import Path

import mujoco
import numpy as np

import sw2sim
from sw2sim.ros_control import add_motors, read_controllers, read_joint_limits

PACKAGE = Path("examples/example_3")        # run from the repository root
CONFIG = PACKAGE / "config" / "joint_names_example_3.yaml"
POSITION_CONTROLLER = "effort_controllers/JointPositionController"
TIMESTEP = 0.001   # s: Gazebo's default step; the controllers run at every step
# rad/s²: how quickly each joint is brought up to speed and slowed down again.
# The middle joint is gentler: each change of its speed shakes the end arm.
ACCELERATION = {"middle_arm_joint": 5.0, "end_arm_joint": 10.0}
CRUISE = 0.95      # lead each joint at 95 % of its velocity limit


def clamp(value, low, high):
    """`value` kept between `low` and `high` (faster than np.clip on one number)."""
    return min(max(value, low), high)


class Pid:
    """A PID on the position error, as ROS's control_toolbox computes it: the integral
    term is i times the summed error, within ±i_clamp. With antiwindup the sum stops
    where the term reaches i_clamp; without, it keeps growing behind the clamp."""

    def __init__(self, p, i=0.0, d=0.0, i_clamp=0.0, antiwindup=False):
        self.p, self.i, self.d, self.i_clamp = p, i, d, abs(i_clamp)
        self.antiwindup = antiwindup
        self.summed = 0.0

    def __call__(self, error, error_rate, dt):
        self.summed += error * dt
        if self.antiwindup and self.i:
            bound = self.i_clamp / abs(self.i)
            self.summed = clamp(self.summed, -bound, bound)
        integral = clamp(self.i * self.summed, -self.i_clamp, self.i_clamp)
        return self.p * error + integral + self.d * error_rate


class JointPositionController:
    """Turns a position setpoint into a joint torque, within the joint's limits."""

    def __init__(self, model, joint, gains, limits, acceleration):
        self.joint = joint
        self.qpos = model.joint(joint).qposadr[0]
        self.dof = model.joint(joint).dofadr[0]
        self.pid = Pid(**gains)
        self.limits = limits
        self.acceleration = acceleration
        self.setpoint = 0.0
        self.reference = None     # where the joint is led, on its way to the setpoint
        self.reference_speed = 0.0

    def command(self, position):
        """A new setpoint, kept inside the limits (as the ROS controller does)."""
        self.setpoint = clamp(float(position), self.limits.lower, self.limits.upper)

    def effort(self, data, dt):
        q, v = float(data.qpos[self.qpos]), float(data.qvel[self.dof])
        if self.reference is None:
            self.reference = q
        self.lead(dt)
        torque = self.pid(self.reference - q, self.reference_speed - v, dt)
        return self.enforce_limits(torque, q, v)

    def lead(self, dt):
        """Move the reference towards the setpoint: speed up at `acceleration`,
        cruise just under the velocity limit, slow down in time to stop on it."""
        left = self.setpoint - self.reference
        acceleration = self.acceleration
        can_stop_from = math.sqrt(2 * acceleration * abs(left))
        top = CRUISE * self.limits.velocity
        wanted = math.copysign(min(top, can_stop_from), left)
        change = acceleration * dt
        self.reference_speed += clamp(wanted - self.reference_speed, -change, change)
        if abs(left) <= abs(self.reference_speed) * dt:
            self.reference, self.reference_speed = self.setpoint, 0.0
        else:
            self.reference += self.reference_speed * dt

    def enforce_limits(self, torque, q, v):
        """Clip the torque as gazebo_ros_control's default hardware does.

        With a <safety_controller> (ros_control's soft limits), the torque allowed
        in the direction of motion falls with the speed and is zero at the velocity
        limit; above it, only a braking torque is allowed. Near a soft position
        limit, the speed allowed towards it shrinks with the distance left
        (k_position). Without one (saturation), the torque is clamped to the effort
        limit and cut off in a direction that goes further past the velocity limit
        or a position limit.
        """
        lim, top = self.limits, self.limits.velocity
        if not lim.has_soft_limits:     # no <safety_controller>: saturation
            low, high = -lim.effort, lim.effort
            if v > top or (lim.upper is not None and q > lim.upper):
                high = 0.0
            if v < -top or (lim.lower is not None and q < lim.lower):
                low = 0.0
            return clamp(torque, low, high)
        v_min = clamp(-lim.k_position * (q - lim.soft_lower), -top, top)
        v_max = clamp(-lim.k_position * (q - lim.soft_upper), -top, top)
        low = clamp(-lim.k_velocity * (v - v_min), -lim.effort, lim.effort)
        high = clamp(-lim.k_velocity * (v - v_max), -lim.effort, lim.effort)
        return clamp(torque, low, high)


class Arm:
    """The arm in MuJoCo, its position controllers and a joint-state log."""

    def __init__(self, package=PACKAGE, config=CONFIG):
        spec = sw2sim.load_package(package)
        spec.option.timestep = TIMESTEP
        motors = add_motors(spec, package)
        self.model = spec.compile()
        self.data = mujoco.MjData(self.model)

        limits = read_joint_limits(package)
        settings = read_controllers(config)[spec.modelname]
        self.state_rate = settings["joint_state_controller"]["publish_rate"]
        self.controllers = {
            name: JointPositionController(self.model, c["joint"], c["pid"],
                                          limits[c["joint"]], ACCELERATION[c["joint"]])
            for name, c in settings.items() if c.get("type") == POSITION_CONTROLLER
        }
        # which entry of data.ctrl drives each controller's joint
        joint_motor = {self.model.actuator(m).trnid[0]: i for i, m in enumerate(motors)}
        self.motor = {name: joint_motor[self.model.joint(c.joint).id]
                      for name, c in self.controllers.items()}
        self.log = []
        self._every = max(1, round(1 / (self.state_rate * TIMESTEP)))
        self._steps = 0

    def command(self, **setpoints):
        """Like publishing to <controller>/command:
        arm.command(middle_arm_controller=0.5)."""
        for name, value in setpoints.items():
            self.controllers[name].command(value)

    def step(self):
        if self._steps % self._every == 0:
            self._record()
        for name, controller in self.controllers.items():
            torque = controller.effort(self.data, TIMESTEP)
            self.data.ctrl[self.motor[name]] = torque
        mujoco.mj_step(self.model, self.data)
        self._steps += 1

    def run(self, seconds):
        for _ in range(round(seconds / TIMESTEP)):
            self.step()

    def _record(self):
        row = {"time": self.data.time}
        for name, c in self.controllers.items():
            q = self.data.qpos[c.qpos]
            row[name] = {"set_point": c.setpoint, "process_value": q,
                         "process_value_dot": self.data.qvel[c.dof],
                         "error": c.setpoint - q}
        self.log.append(row)

    def states(self, controller, field):
        """One field of a controller's state over time (like `rostopic echo`)."""
        return np.array([row[controller][field] for row in self.log])

    def times(self):
        return np.array([row["time"] for row in self.log])


if __name__ == "__main__":
    arm = Arm()
    arm.command(middle_arm_controller=0.5, end_arm_controller=-0.7)
    arm.run(2.0)
    for name, c in arm.controllers.items():
        print(f"{name:22} set point {c.setpoint:+.4f} rad, "
              f"position {arm.states(name, 'process_value')[-1]:+.4f} rad")
