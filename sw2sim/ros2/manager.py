"""The controller manager of `sw2sim ros2`: the controllers' lifecycle and the services
of ros2_control's controller_manager (4.46.0, jazzy), so that Jazzy's `ros2 control ...`
commands, the spawner and rqt's tools work against the stand-in.

Its node, `controller_manager`, holds `update_rate` and `<name>.type` from the package's
YAML, takes others (the spawner's `<name>.params_file`), and serves, with
controller_manager_msgs' types and upstream's reply messages, `~/list_controllers`
(states "unconfigured", "inactive", "active", claimed and required interfaces, no chain
connections), `~/list_controller_types`, `~/list_hardware_interfaces`,
`~/list_hardware_components`, `~/load_controller`, `~/configure_controller`,
`~/cleanup_controller`, `~/unload_controller`, `~/reload_controller_libraries` and
`~/switch_controller`: STRICT (any problem aborts it) or BEST_EFFORT (the default, also
for AUTO and FORCE_AUTO: what cannot be switched is left out), done between two
controller updates, the call waiting up to `timeout` (1 s when 0).

A deactivated controller is no longer updated, publishes nothing, and releases its
interfaces (its joints then get what Gazebo Sim gives a joint no controller drives:
sw2sim.ros2.hardware.JointCommand); activated again, it starts as `on_activate` does. At
start-up every controller of the YAML is loaded, configured and activated, as the
package's launch file's spawner does.
"""

from __future__ import annotations

import dataclasses
import threading
from pathlib import Path

from . import config as config_module
from . import controllers as ctl

UNCONFIGURED, INACTIVE, ACTIVE = "unconfigured", "inactive", "active"
BEST_EFFORT, STRICT, AUTO, FORCE_AUTO = 1, 2, 3, 4
KINDS = ("position", "velocity", "effort")   # the interfaces gz_system registers
BASE = "controller_interface::ControllerInterface"
CHAINABLE_BASE = "controller_interface::ChainableControllerInterface"


@dataclasses.dataclass
class Spec:
    """One loaded controller."""

    name: str
    type: str
    state: str = UNCONFIGURED
    controller: ctl.Controller | None = None
    claimed: list[str] = dataclasses.field(default_factory=list)
    entities: list = dataclasses.field(default_factory=list)   # what configure made on ROS


@dataclasses.dataclass
class Switch:
    """A switch the service asked for, done by the simulation between two updates."""

    activate: list[str]
    deactivate: list[str]
    strictness: int
    done: threading.Event = dataclasses.field(default_factory=threading.Event)


def no_such(action: str, name: str) -> str:
    return f"Could not {action} controller with name '{name}' because no controller with " \
        "this name exists"


class ControllerManager:
    """The controllers' lifecycle for a sw2sim.ros2.node.Simulation (`sim`)."""

    def __init__(self, sim):
        self.sim = sim
        self.specs: dict[str, Spec] = {}
        self.pending: Switch | None = None
        self.joint_modes: dict[str, set[str]] = {}   # joint -> its claimed interfaces
        self.failures: list[str] = []   # why the last operations failed
        self.node = None
        self.log = lambda level, text: None

    # -- the hardware's interfaces ------------------------------------------------------
    def hardware_command_interfaces(self, joints=None) -> list[str]:
        """gz_system's: each joint's position, velocity and effort interfaces, in order."""
        table = self.sim.setup.joints
        return [f"{j}/{i}" for j in (table if joints is None else joints) if j in table
                for i in table[j].command if i in KINDS]

    def hardware_state_interfaces(self, joints=None) -> list[str]:
        table = self.sim.setup.joints
        return [f"{j}/{i}" for j in (table if joints is None else joints) if j in table
                for i in table[j].state if i in KINDS]

    def available_state_interfaces(self) -> list[str]:
        found = self.hardware_state_interfaces()
        for spec in self.specs.values():
            if spec.state == ACTIVE and spec.controller.chainable:
                found += [f"{spec.name}/{i}" for i in spec.controller.exported_interface_names()]
        return found

    def claimed(self) -> dict[str, str]:
        """command interface -> the active controller holding it."""
        return {i: s.name for s in self.specs.values() if s.state == ACTIVE for i in s.claimed}

    def _claims_changed(self) -> None:
        modes: dict[str, set[str]] = {}
        for interface in self.claimed():
            joint, _, kind = interface.rpartition("/")
            modes.setdefault(joint, set()).add(kind)
        self.joint_modes = modes

    # -- parameters ---------------------------------------------------------------------
    def parameter(self, name: str):
        if self.node is not None:
            found = self.node.get_parameter_or(name, None)
            value = getattr(found, "value", None)
            if value is not None:
                return value
        if name.endswith(".type"):
            return self.sim.setup.controllers.get(name[:-5])
        return None

    def controller_parameters(self, name: str) -> dict:
        """The package YAML's parameters of the controller, with those of the files a
        spawner named in `<name>.params_file` over them."""
        params = dict(self.sim.setup.params(name))
        files = self.parameter(f"{name}.params_file")
        if isinstance(files, str):
            files = [files]
        import yaml
        for file in files or []:
            document = yaml.safe_load(Path(file).read_text(encoding="utf-8"))
            params.update(config_module.parameters_of(document).get(name, {}))
        return params

    # -- lifecycle (the caller holds sim.lock) --------------------------------------------
    def load(self, name: str) -> bool:
        kind = self.parameter(f"{name}.type")
        if not kind:
            return self._fail(f"The 'type' param was not defined for '{name}'.")
        if kind not in ctl.SUPPORTED:
            return self._fail(f"Loader for controller '{name}' (type '{kind}') not found. "
                              f"Available classes: {', '.join(ctl.SUPPORTED)}")
        if name in self.specs:
            return self._fail(f"A controller named '{name}' was already loaded inside the "
                              "controller manager")
        self.specs[name] = Spec(name, str(kind))
        self.log("info", f"Loading controller : '{name}' of type '{kind}'")
        return True

    def configure(self, name: str) -> bool:
        spec = self.specs.get(name)
        if spec is None:
            return self._fail(no_such("configure", name))
        if spec.state == ACTIVE:
            return self._fail(f"Controller '{name}' can not be configured from 'active' state.")
        if spec.state == INACTIVE:
            self.cleanup(name)
        try:
            controller = ctl.create(name, spec.type, self.controller_parameters(name),
                                    self.sim.setup.joints)
        except (ctl.ConfigError, OSError, ValueError) as exc:
            self.failures.append(str(exc))
            return self._fail(f"After configuring, controller '{name}' is in state "
                              f"'unconfigured' , expected inactive. ({exc})")
        spec.controller, spec.state = controller, INACTIVE
        spec.entities = self.sim.configured(controller)
        self.log("info", f"Configuring controller: '{name}'")
        return True

    def cleanup(self, name: str) -> bool:
        spec = self.specs.get(name)
        if spec is None:
            return self._fail(no_such("cleanup", name))
        if spec.state == UNCONFIGURED:
            return True
        if spec.state == ACTIVE:
            return self._fail(f"Controller '{name}' can not be cleaned-up from 'active' state.")
        self.sim.cleaned_up(spec.controller, spec.entities)
        spec.controller, spec.state, spec.entities = None, UNCONFIGURED, []
        return True

    def unload(self, name: str) -> bool:
        spec = self.specs.get(name)
        if spec is None:
            return self._fail(no_such("unload", name))
        if spec.state == ACTIVE:
            return self._fail(f"Could not unload controller with name '{name}' because it is "
                              "still active")
        if not self.cleanup(name):
            return False
        del self.specs[name]
        return True

    def _fail(self, message: str) -> bool:
        self.log("error", message)
        self.failures.append(message)
        return False

    # -- switching ------------------------------------------------------------------------
    def check_switch(self, activate, deactivate, strictness: int):
        """switch_controller_cb's checks: (lists to activate and deactivate, or None when the
        switch is refused, message)."""
        if strictness == 0 or strictness in (AUTO, FORCE_AUTO):
            strictness = BEST_EFFORT   # the default strictness is best_effort
        message = ""
        lists = {}
        for action, names in (("deactivate", deactivate), ("activate", activate)):
            found, ok = [], True
            for name in names:
                if name in self.specs:
                    found.append(name)
                    ok = True
                    continue
                error = no_such(action, name)
                if strictness == STRICT:
                    return None, None, error, strictness
                message += error + "\n"
                ok = bool(found)   # best effort: an error only while nothing was found
            if not ok:
                return None, None, message, strictness
            lists[action] = found
        to_activate, to_deactivate = list(lists["activate"]), list(lists["deactivate"])
        message = ""
        for name in list(to_activate):
            spec = self.specs[name]
            problem = None
            if spec.state == UNCONFIGURED:
                problem = (f"Controller with name '{name}' is in 'unconfigured' state. The "
                           "controller needs to be configured to be in 'inactive' state before "
                           "it can be checked and activated.")
            elif spec.state == ACTIVE and name not in to_deactivate:
                problem = f"Controller with name '{name}' is already active."
            if problem:
                if strictness == STRICT:
                    return None, None, problem, strictness
                to_activate.remove(name)
        for name in list(to_deactivate):
            if self.specs[name].state != ACTIVE:
                problem = (f"Controller with name '{name}' can not be deactivated since it is "
                           "not active.")
                if strictness == STRICT:
                    return None, None, problem, strictness
                to_deactivate.remove(name)
        if not to_activate and not to_deactivate:
            return [], [], ("After checking the controllers, no controllers need to be "
                            "activated or deactivated."), strictness
        problem = self._interfaces_problem(to_activate, to_deactivate)
        if problem:
            return None, None, problem, strictness
        return to_activate, to_deactivate, "", strictness

    def _interfaces_problem(self, to_activate, to_deactivate) -> str | None:
        """check_for_interfaces_availability_to_activate."""
        freed = [i for n in to_deactivate for i in self.specs[n].claimed]
        claimed = self.claimed()
        commands = set(self.hardware_command_interfaces())
        states = set(self.available_state_interfaces())
        coming = []
        for name in to_activate:
            if name in to_deactivate:
                continue
            c = self.specs[name].controller
            for interface in c.command_interface_names():
                if interface not in commands:
                    return (f"Unable to activate controller '{name}' since the command "
                            f"interface '{interface}' is not available.")
                if interface in claimed and interface not in freed:
                    return (f"Unable to activate controller '{name}' since the command "
                            f"interface '{interface}' is currently claimed by another "
                            "controller.")
                if interface in coming:
                    return (f"Unable to activate controller '{name}' since the command "
                            f"interface '{interface}' will be used by another controller that "
                            "is being activated.")
                coming.append(interface)
            for interface in c.state_interface_names(self.available_state_interfaces()):
                if interface not in states:
                    return (f"Unable to activate controller '{name}' since the state "
                            f"interface '{interface}' is not available.")
        return None

    def switch(self, activate, deactivate, strictness: int, timeout: float):
        """The service: check, hand the switch to the simulation, wait for it. (ok, message)"""
        with self.sim.lock:
            to_activate, to_deactivate, message, strictness = self.check_switch(
                list(activate), list(deactivate), strictness)
            if to_activate is None:
                self.log("error", message.strip())
                return False, message
            if not to_activate and not to_deactivate:
                return True, message
            request = Switch(to_activate, to_deactivate, strictness)
            self.pending = request
        timeout = timeout if timeout > 0 else 1.0
        if not request.done.wait(timeout):
            with self.sim.lock:
                if not request.done.is_set():
                    self.pending = None
                    message = f"Switch controller timed out after {timeout:g} seconds!"
                    self.log("error", message)
                    return False, message
        return self.result(request)

    def apply(self, state) -> None:
        """Called by the simulation before a controller update (holding sim.lock): the
        pending switch, deactivations first."""
        request, self.pending = self.pending, None
        if request is not None:
            self.perform(request, state)

    def perform(self, request: Switch, state) -> None:
        for name in request.deactivate:
            spec = self.specs.get(name)
            if spec is None or spec.state != ACTIVE:
                continue
            self.sim.write_commands(spec.controller.deactivate() or {})
            spec.controller.active = False
            spec.state, spec.claimed = INACTIVE, []
        for name in request.activate:
            spec = self.specs.get(name)
            if spec is None or spec.state != INACTIVE:
                continue
            spec.controller.activate(state)
            spec.controller.active = True
            spec.state, spec.claimed = ACTIVE, spec.controller.command_interface_names()
        self._claims_changed()
        request.done.set()

    def result(self, request: Switch):
        """evaluate_switch_result: (ok, message)."""
        failed_on = [n for n in request.activate if self.specs.get(n) is None
                     or self.specs[n].state != ACTIVE]
        failed_off = [n for n in request.deactivate if n not in request.activate
                      and self.specs.get(n) is not None and self.specs[n].state == ACTIVE]
        if failed_on or failed_off:
            message = "Failed switching controllers.... "
            if failed_on:
                message += f"\nUnable to activate controllers: [ {' '.join(failed_on)} ]"
            if failed_off:
                message += f"\nUnable to deactivate controllers: [ {' '.join(failed_off)} ]"
            return False, message
        message = "Successfully switched controllers!"
        if request.strictness != STRICT:
            if request.deactivate:
                message += f"\nDeactivated controllers: [ {' '.join(request.deactivate)} ]"
            if request.activate:
                message += f"\nActivated controllers: [ {' '.join(request.activate)} ]"
        return True, message

    # -- start-up -------------------------------------------------------------------------
    def start(self, state) -> tuple[list[str], list[str]]:
        """Every controller of the YAML loaded, configured and activated (the spawner of
        the package's launch file): the names of those that came up, and why the others
        did not."""
        up, failures = [], []
        log, self.log = self.log, lambda level, text: None   # the start-up line says it
        for name in self.sim.setup.controllers:
            self.failures = []
            if self.load(name) and self.configure(name):
                to_activate, _, message, _ = self.check_switch([name], [], STRICT)
                if to_activate:
                    self.perform(Switch(to_activate, [], STRICT), state)
                    up.append(name)
                    continue
                self._fail(message)
            failures.append(self.failures[0] if self.failures else name)
        self.log = log
        return up, failures

    # -- ROS ------------------------------------------------------------------------------
    def serve(self, context) -> None:
        """The controller_manager node and its services."""
        import rclpy
        from controller_manager_msgs import srv
        from rclpy.parameter import Parameter
        from rclpy.qos import (DurabilityPolicy, HistoryPolicy, QoSProfile,
                               ReliabilityPolicy)
        overrides = [Parameter("update_rate", value=int(round(self.sim.setup.update_rate)))]
        overrides += [Parameter(f"{name}.type", value=kind)
                      for name, kind in self.sim.setup.controllers.items()]
        self.node = rclpy.create_node(
            "controller_manager", context=context, allow_undeclared_parameters=True,
            automatically_declare_parameters_from_overrides=True,
            parameter_overrides=overrides)
        logger = self.node.get_logger()

        def log(level, text):   # (rclpy wants one severity per line that logs)
            if level == "error":
                logger.error(text)
            else:
                logger.info(text)
        self.log = log
        services = QoSProfile(history=HistoryPolicy.KEEP_ALL, depth=1,
                              reliability=ReliabilityPolicy.RELIABLE,
                              durability=DurabilityPolicy.VOLATILE)
        for name, kind, handler in (
                ("list_controllers", srv.ListControllers, self._list_controllers),
                ("list_controller_types", srv.ListControllerTypes, self._list_types),
                ("list_hardware_components", srv.ListHardwareComponents, self._components),
                ("list_hardware_interfaces", srv.ListHardwareInterfaces, self._interfaces),
                ("load_controller", srv.LoadController, self._named(self.load)),
                ("configure_controller", srv.ConfigureController, self._named(self.configure)),
                ("cleanup_controller", srv.CleanupController, self._named(self.cleanup)),
                ("unload_controller", srv.UnloadController, self._named(self.unload)),
                ("reload_controller_libraries", srv.ReloadControllerLibraries, self._reload),
                ("switch_controller", srv.SwitchController, self._switch)):
            self.node.create_service(kind, f"~/{name}", handler, qos_profile=services)

    def _named(self, operation):
        def handler(request, response):
            with self.sim.lock:
                response.ok = bool(operation(request.name))
            return response
        return handler

    def _list_controllers(self, request, response):
        from controller_manager_msgs.msg import ControllerState
        with self.sim.lock:
            available = self.available_state_interfaces()
            for spec in self.specs.values():
                item = ControllerState(name=spec.name, type=spec.type, state=spec.state,
                                       is_async=False, is_chained=False)
                c = spec.controller
                item.update_rate = int(self.controller_parameters(spec.name).get(
                    "update_rate") or self.sim.setup.update_rate)
                item.is_chainable = ctl.CLASSES[spec.type].chainable
                item.claimed_interfaces = list(spec.claimed) if spec.state == ACTIVE else []
                if c is not None:
                    item.required_command_interfaces = c.command_interface_names()
                    item.required_state_interfaces = c.state_interface_names(available)
                    if c.chainable:
                        item.reference_interfaces = c.exported_interface_names()
                        item.exported_state_interfaces = c.exported_interface_names()
                response.controller.append(item)
        return response

    def _list_types(self, request, response):
        for kind in ctl.SUPPORTED:
            response.types.append(kind)
            chainable = ctl.CLASSES[kind].chainable
            response.base_classes.append(CHAINABLE_BASE if chainable else BASE)
        return response

    def _hardware_interface(self, name, claimed, available=True):
        from controller_manager_msgs.msg import HardwareInterface
        return HardwareInterface(name=name, data_type="double", is_available=available,
                                 is_claimed=name in claimed)

    def _interfaces(self, request, response):
        with self.sim.lock:
            claimed = self.claimed()
            available = set(self.available_state_interfaces())
            commands = {i: True for i in self.hardware_command_interfaces()}
            states = {i: True for i in self.hardware_state_interfaces()}
            for spec in self.specs.values():   # a configured chainable controller's own
                if spec.controller is not None and spec.controller.chainable:
                    for i in spec.controller.exported_interface_names():
                        commands[f"{spec.name}/{i}"] = spec.state == ACTIVE
                        states[f"{spec.name}/{i}"] = f"{spec.name}/{i}" in available
            response.command_interfaces = [self._hardware_interface(n, claimed, a)
                                           for n, a in sorted(commands.items())]
            response.state_interfaces = [self._hardware_interface(n, {}, a)
                                         for n, a in sorted(states.items())]
        return response

    def _components(self, request, response):
        from controller_manager_msgs.msg import HardwareComponentState
        from lifecycle_msgs.msg import State
        with self.sim.lock:
            claimed = self.claimed()
            for name, plugin, joints in self.sim.setup.hardware:
                item = HardwareComponentState(name=name, type="system", is_async=False,
                                              plugin_name=plugin)
                item.rw_rate = int(round(self.sim.setup.update_rate))
                item.state = State(id=State.PRIMARY_STATE_ACTIVE, label="active")
                item.command_interfaces = [self._hardware_interface(i, claimed) for i in
                                           self.hardware_command_interfaces(joints)]
                item.state_interfaces = [self._hardware_interface(i, {}) for i in
                                         self.hardware_state_interfaces(joints)]
                response.component.append(item)
        return response

    def _reload(self, request, response):
        with self.sim.lock:
            active = [s.name for s in self.specs.values() if s.state == ACTIVE]
        response.ok = not active or bool(request.force_kill)
        if not response.ok:
            self.log("error", "Controller manager: Cannot reload controller libraries because "
                     f"there are still {len(active)} active controllers")
        elif active:   # force_kill: every controller deactivated, then all unloaded
            response.ok = self.switch([], active, BEST_EFFORT, 1.0)[0]
        if response.ok:
            with self.sim.lock:
                response.ok = all(self.unload(name) for name in list(self.specs))
        return response

    def _switch(self, request, response):
        timeout = request.timeout.sec + request.timeout.nanosec * 1e-9
        response.ok, response.message = self.switch(
            request.activate_controllers, request.deactivate_controllers, request.strictness,
            timeout)
        return response
