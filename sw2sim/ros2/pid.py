"""control_toolbox's Pid (4.11.0, the release that Jazzy's ros2_controllers 4.x build on),
as joint_trajectory_controller and pid_controller use it: `compute_command` step for step
(pid.cpp), with the command also given as a law affine in the joint's position and
velocity for sw2sim.ros2.hardware (`affine`)."""

from __future__ import annotations

import math

from .controller_base import ConfigError, Controller, gains_of, value


STRATEGIES = ("back_calculation", "conditional_integration", "legacy", "none")
EPSILON = 2.220446049250313e-16   # std::numeric_limits<double>::epsilon(), control_toolbox's is_zero


def _is_zero(x: float, tolerance: float = EPSILON) -> bool:
    return abs(x) <= tolerance


def _clamp(x: float, low: float, high: float) -> float:
    return min(max(x, low), high)


class Pid:
    """control_toolbox's Pid (4.11.0, the release Jazzy's ros2_controllers 4.x build on),
    `compute_command` step for step:

    - the proportional and derivative terms, `p * error` and `d * error_dot`;
    - `legacy` (the default): the integral `i * dt * error` is added before the command
      (clamped to [i_clamp_min, i_clamp_max] there only with `antiwindup: true`, else
      only its share of the command is clamped); `none`, `conditional_integration` (no
      integration while the output is saturated and the error pushes further) and
      `back_calculation` (the saturation's excess fed back over `tracking_time_constant`)
      integrate after the command;
    - the command clamped to [u_clamp_min, u_clamp_max];
    - no integration while |error| <= error_deadband;
    - and for every strategy the stored integral clamped to [i_clamp_min, i_clamp_max]
      at the end of the step.

    `flavour` says which controller reads the gains: "jtc" (joint_trajectory_controller's
    update_pids: i_clamp_max/min, else the deprecated i_clamp; no `antiwindup`; deadband
    0 by default) or "pid" (pid_controller through PidROS: i_clamp_max/min, `antiwindup`,
    `saturation`, deadband 1e-16 by default, `save_i_term`)."""

    def __init__(self, gains: dict, flavour: str = "jtc", where: str = "gains"):
        def number(key, default):
            try:
                return float(gains.get(key, default))
            except (TypeError, ValueError):
                raise ConfigError(f"{where}.{key}: {gains.get(key)!r} is not a number") from None
        self.p, self.i, self.d = number("p", 0.0), number("i", 0.0), number("d", 0.0)
        self.i_max = number("i_clamp_max", math.inf)
        self.i_min = number("i_clamp_min", -math.inf)
        if flavour == "jtc":   # the deprecated symmetric i_clamp, when the pair is not given
            i_clamp = number("i_clamp", math.inf)
            if not math.isfinite(self.i_max):
                self.i_max = i_clamp
            if not math.isfinite(self.i_min):
                self.i_min = -i_clamp
        self.u_max, self.u_min = number("u_clamp_max", math.inf), number("u_clamp_min", -math.inf)
        if flavour == "pid" and not bool(gains.get("saturation", math.isfinite(self.u_max)
                                                   or math.isfinite(self.u_min))):
            self.u_max, self.u_min = math.inf, -math.inf
        self.strategy = str(gains.get("antiwindup_strategy", "legacy"))
        self.legacy_antiwindup = flavour == "pid" and bool(gains.get("antiwindup", False))
        self.deadband = number("error_deadband", 0.0 if flavour == "jtc" else 1e-16)
        self.tracking = number("tracking_time_constant", 0.0)
        self.save_i_term = flavour == "pid" and bool(gains.get("save_i_term", True))
        problem = None
        if self.strategy not in STRATEGIES:
            problem = (f"antiwindup_strategy {self.strategy!r} is not one of "
                       f"{', '.join(STRATEGIES)}")
        elif not self.u_min < self.u_max:
            problem = f"u_clamp_min ({self.u_min}) must be less than u_clamp_max ({self.u_max})"
        elif self.i_min > 0 or self.i_max < 0:
            problem = (f"i_clamp_min ({self.i_min}) must be <= 0 and i_clamp_max ({self.i_max}) "
                       ">= 0")
        elif self.strategy == "back_calculation" and not (
                self.tracking >= 0 and math.isfinite(self.tracking)):
            problem = f"tracking_time_constant ({self.tracking}) must be a positive number"
        if problem:
            raise ConfigError(f"{where}: {problem}")
        if self.strategy == "back_calculation" and _is_zero(self.tracking) and \
                not _is_zero(self.i):   # set_gains' default time constant
            self.tracking = math.sqrt(self.d / self.i) if not _is_zero(self.d) else self.p / self.i
        self.i_term = 0.0
        self.reset()

    def reset(self, save_i_term: bool = False) -> None:
        """Pid::reset: the errors and the command to zero, the integral too unless kept."""
        self.last_error = self.p_error = self.d_error = self.cmd = 0.0
        self.cmd_unsat = self.i_used = 0.0
        if not save_i_term:
            self.i_term = 0.0

    def command(self, error: float, error_dot: float, dt: float) -> float:
        """compute_command(error, error_dot, dt): the command, with the integral updated."""
        if _is_zero(dt):
            return self.cmd
        if dt < 0:
            raise ValueError("Pid is called with negative dt")
        self.p_error, self.d_error = error, error_dot
        if not (math.isfinite(error) and math.isfinite(error_dot)):
            self.cmd = math.nan
            return self.cmd
        p_term, d_term = self.p * error, self.d * error_dot
        outside = not _is_zero(error, self.deadband)
        legacy = self.strategy == "legacy"
        if outside and legacy:
            if self.legacy_antiwindup:
                self.i_term = _clamp(self.i_term + self.i * dt * error, self.i_min, self.i_max)
            else:
                self.i_term += self.i * dt * error
        if legacy and not self.legacy_antiwindup:
            self.i_used = _clamp(self.i_term, self.i_min, self.i_max)
        else:
            self.i_used = self.i_term
        self.cmd_unsat = p_term + self.i_used + d_term
        if math.isfinite(self.u_min) or math.isfinite(self.u_max):
            self.cmd = _clamp(self.cmd_unsat, self.u_min, self.u_max)
        else:
            self.cmd = self.cmd_unsat
        if outside:
            if self.strategy == "back_calculation" and not _is_zero(self.i):
                gain = 1 / self.tracking if self.tracking else math.inf
                self.i_term += dt * (self.i * error + gain * (self.cmd - self.cmd_unsat))
            elif self.strategy == "conditional_integration":
                if not (not _is_zero(self.cmd_unsat - self.cmd) and error * self.cmd_unsat > 0):
                    self.i_term += dt * self.i * error
            elif self.strategy == "none":
                self.i_term += dt * self.i * error
        self.i_term = _clamp(self.i_term, self.i_min, self.i_max)
        return self.cmd

    def command_from_error(self, error: float, dt: float) -> float:
        """compute_command(error, dt): the error's rate from the last call's error."""
        if _is_zero(dt):
            return self.cmd
        if dt < 0:
            raise ValueError("Pid is called with negative dt")
        if not math.isfinite(error):
            self.cmd = math.nan
            return self.cmd
        rate = (error - self.last_error) / dt
        self.last_error = error
        return self.command(error, rate, dt)

    @property
    def saturated(self) -> bool:
        return self.cmd != self.cmd_unsat

    def affine(self, c0: float, cq: float, cv: float, feedforward: float = 0.0):
        """The last command as a law (c0', cq, cv) in the joint's q and v, given the affine
        form of p * error + d * error_dot at this update (without the integral): it holds
        the command's value at the update's q and v, and between updates follows the
        joint as the P and D terms would (a saturated command stays constant).
        `feedforward` is added outside the clamp, as the controllers add it."""
        if not math.isfinite(self.cmd):
            return (math.nan, 0.0, 0.0)
        if self.saturated:
            return (self.cmd + feedforward, 0.0, 0.0)
        return (c0 + self.i_used + feedforward, cq, cv)


class PidController(Controller):
    """pid_controller/PidController (ros2_controllers 4.42.1, pid_controller.cpp): a PID
    per degree of freedom on the first reference-and-state interface's error, with the
    second's (its derivative) as error_dot when both are finite, else the error's change
    since the last update. The feed-forward term (`feedforward_gain` times the reference's
    derivative, or the reference itself with one interface) is added only while
    feed-forward is on: `enable_feedforward` (false by default), or the
    `~/set_feedforward_control` service."""

    chainable = True

    def __init__(self, name, kind, params, joints):
        super().__init__(name, kind, params, joints)
        self.joints = self.check_joints(params.get("dof_names"))
        if len(set(self.joints)) != len(self.joints):
            raise ConfigError(f"{name}: dof_names has a name twice")
        self.interface = str(params.get("command_interface", ""))
        self.measured = [str(i) for i in params.get("reference_and_state_interfaces") or []]
        if not self.interface or not 1 <= len(self.measured) <= 2:
            raise ConfigError(f"{name}: command_interface and one or two "
                              "reference_and_state_interfaces must be given")
        for joint in self.joints:
            if self.interface not in self.available[joint].command:
                raise ConfigError(f"{name}: joint {joint} has no {self.interface!r} command "
                                  "interface in the URDF's <ros2_control> block")
        gains = {j: gains_of(params, j) for j in self.joints}
        self.pids = {j: Pid(gains[j], "pid", f"{name}: gains.{j}") for j in self.joints}
        self.feedforward = {j: float(gains[j].get("feedforward_gain", 0.0)) for j in self.joints}
        self.wraparound = {j: bool(gains[j].get("angle_wraparound", False)) for j in self.joints}
        self.feedforward_on = bool(params.get("enable_feedforward", False))
        self.reference = {j: [math.nan, math.nan] for j in self.joints}
        self.incoming = None
        self.last = {}
        self.errors: list[str] = []
        self.warnings: list[str] = []

    def _measure(self, joint, state):
        q, v = state[joint]
        pick = {"position": (q, v), "velocity": (v, math.nan), "effort": (math.nan, math.nan)}
        first = pick.get(self.measured[0], (math.nan, math.nan))
        second = pick.get(self.measured[1])[0] if len(self.measured) == 2 and \
            self.measured[1] in pick else math.nan
        return first[0], second

    def activate(self, state):
        # a reference that came while inactive is dropped; the references start as NaN,
        # or as the state with set_current_state_as_first_setpoint (true by default)
        with self.lock:
            self.incoming = None
        first = bool(self.params.get("set_current_state_as_first_setpoint", True))
        for joint in self.joints:
            self.reference[joint] = list(self._measure(joint, state)) if first else \
                [math.nan, math.nan]
            if len(self.measured) == 1:
                self.reference[joint][1] = math.nan
        for pid in self.pids.values():   # PidROS::reset: the integral kept with save_i_term
            pid.reset(pid.save_i_term)

    def set_feedforward(self, on: bool) -> None:
        """The `~/set_feedforward_control` service (std_srvs/SetBool)."""
        self.feedforward_on = bool(on)
        self.warnings.append("This service will be deprecated in favour of setting the "
                             "``feedforward_gain`` parameter to a non-zero value.")

    def receive(self, names, values, values_dot) -> None:
        """reference_callback: a message is taken when it has as many values as the
        controller has degrees of freedom and either no names or as many names; its values
        are taken in the controller's order, whatever the names say (as upstream's)."""
        names, values, values_dot = list(names), list(values), list(values_dot)
        n = len(self.joints)
        if not names and len(values) == n:
            self.warnings.append("Reference massage does not have DoF names defined. "
                                 "Assuming that value have order as defined state DoFs")
        elif not (len(names) == n and len(values) == n):
            self.errors.append(f"Size of input data names ({len(names)}) and/or values "
                               f"({len(values)}) is not matching the expected size ({n}).")
            return
        values_dot = (values_dot + [math.nan] * n)[:n]
        with self.lock:
            self.incoming = [(float(values[k]), float(values_dot[k])) for k in range(n)]

    def update(self, now, period, state):
        with self.lock:
            incoming, self.incoming = self.incoming, None
        if incoming:   # update_reference_from_subscribers
            for joint, (x, x_dot) in zip(self.joints, incoming):
                if not math.isnan(x):
                    self.reference[joint][0] = x
                    if len(self.measured) == 2 and not math.isnan(x_dot):
                        self.reference[joint][1] = x_dot
        output = {}
        two = len(self.measured) == 2
        for joint in self.joints:
            q, v = state[joint]
            ref, ref_dot = self.reference[joint]
            measured, measured_dot = self._measure(joint, state)
            if not (math.isfinite(ref) and math.isfinite(measured)):
                self.last[joint] = (ref, measured, measured_dot, ref - measured,
                                    ref_dot - measured_dot if two else 0.0, period,
                                    self.last.get(joint, (math.nan,) * 7)[6])
                continue
            ff = 0.0
            if self.feedforward_on:
                if two:
                    ff = ref_dot * self.feedforward[joint] if math.isfinite(ref_dot) else 0.0
                else:
                    ff = ref * self.feedforward[joint]
            pid = self.pids[joint]
            error = ref - measured
            if self.wraparound[joint]:
                error = math.remainder(ref - measured, 2 * math.pi)
            # p * error as a law in the joint's q and v
            on = {"position": (ref, -1.0, 0.0), "velocity": (ref, 0.0, -1.0)}.get(
                self.measured[0], (error, 0.0, 0.0))
            if self.wraparound[joint]:
                on = (error + (measured if self.measured[0] in ("position", "velocity") else 0),
                      on[1], on[2])
            if two and math.isfinite(ref_dot) and math.isfinite(measured_dot):
                pid.command(error, ref_dot - measured_dot, period)
                rate = (ref_dot, 0.0, -1.0) if self.measured[0] == "position" else \
                    (ref_dot - measured_dot, 0.0, 0.0)
            else:
                pid.command_from_error(error, period)
                rate = (pid.d_error, 0.0, 0.0)
            law = pid.affine(pid.p * on[0] + pid.d * rate[0], pid.p * on[1] + pid.d * rate[1],
                             pid.p * on[2] + pid.d * rate[2], feedforward=ff)
            output[joint] = {self.interface: law if self.interface == "effort"
                             else value(law, q, v)}
            self.last[joint] = (ref, measured, measured_dot, error,
                                (ref_dot - measured_dot) if two else 0.0,
                                period, value(law, q, v))
        return output

    def command_interface_names(self):
        return [f"{j}/{self.interface}" for j in self.joints]

    def state_interface_names(self, available):
        return [f"{j}/{i}" for i in self.measured for j in self.joints]

    def exported_interface_names(self):
        return [f"{j}/{i}" for i in self.measured for j in self.joints]

    def state_message(self, stamp, state):
        from control_msgs.msg import MultiDOFStateStamped, SingleDOFState
        message = MultiDOFStateStamped()
        message.header.stamp = stamp
        for joint in self.joints:
            ref, measured, measured_dot, error, error_dot, step, out = self.last.get(
                joint, (math.nan,) * 7)
            message.dof_states.append(SingleDOFState(
                name=joint, reference=float(ref), feedback=float(measured),
                feedback_dot=float(measured_dot if len(self.measured) == 2 else 0.0),
                error=float(error), error_dot=float(error_dot), time_step=float(step),
                output=float(out)))
        return message
