"""An independent ROS 2 node (rclpy and controller_manager_msgs only, no sw2sim) that calls
the controller manager's services the way Jazzy's ros2controlcli verbs and the spawner do
(controller_manager/controller_manager_services.py of ros2_control 4.46.0: each request
built as there, the call through call_async and spin_until_future_complete), on Practice
3's ported package, and prints one JSON object of what it saw:

    python control_client.py PARAMS

1. `ros2 control list_controllers`, `list_controller_types`, `list_hardware_interfaces`,
   `list_hardware_components`;
2. the end arm sent to 0.4 rad; `ros2 control switch_controllers --deactivate
   end_arm_controller --strict`; a trajectory sent to the inactive controller; the arm
   watched for 2 s of simulated time;
3. `--activate end_arm_controller --activate-asap` (best effort), a trajectory to -0.3 rad;
4. refusals: an unknown name, an active controller activated again (strict and best effort);
5. the spawner's sequence after an unload, with `--param-file PARAMS` (the file given as
   the one argument): `<name>.params_file` and `<name>.type` set on the controller
   manager's node (set_controller_parameters_from_param_files), `load_controller`,
   `configure_controller`, `switch_controller`.
"""

import json
import sys
import time

import rclpy
from builtin_interfaces.msg import Duration
from controller_manager_msgs.srv import (ConfigureController, ListControllers,
                                         ListControllerTypes, ListHardwareComponents,
                                         ListHardwareInterfaces, LoadController,
                                         SwitchController, UnloadController)
from rcl_interfaces.msg import Parameter
from rcl_interfaces.srv import SetParameters
from rclpy.parameter import get_parameter_value
from sensor_msgs.msg import JointState
from trajectory_msgs.msg import JointTrajectory, JointTrajectoryPoint

MANAGER = "/controller_manager"
WALL_TIMEOUT = 30.0


class Client:
    def __init__(self):
        self.node = rclpy.create_node("control_client")
        self.clients = {}
        self.states = []   # (stamp, positions, efforts)
        self.node.create_subscription(JointState, "/joint_states", self._state, 10)
        self.publishers = {}

    def _state(self, m):
        self.states.append((m.header.stamp.sec + m.header.stamp.nanosec * 1e-9,
                            dict(zip(m.name, m.position)), dict(zip(m.name, m.effort))))

    def call(self, kind, service, request, call_timeout=10.0):
        """controller_manager_services.service_caller: wait for the service, then up to
        three attempts of call_async with spin_until_future_complete."""
        name = f"{MANAGER}/{service}"
        if name not in self.clients:
            self.clients[name] = self.node.create_client(kind, name)
        client = self.clients[name]
        if not client.wait_for_service(timeout_sec=WALL_TIMEOUT):
            raise RuntimeError(f"Could not contact service {name}")
        for _ in range(3):
            future = client.call_async(request)
            rclpy.spin_until_future_complete(self.node, future, timeout_sec=call_timeout)
            if future.result() is not None:
                return future.result()
        raise RuntimeError(f"Could not successfully call service {name} after 3 attempts.")

    def list_controllers(self):
        reply = self.call(ListControllers, "list_controllers", ListControllers.Request())
        return [{"name": c.name, "type": c.type, "state": c.state, "update_rate": c.update_rate,
                 "is_async": c.is_async, "claimed": list(c.claimed_interfaces),
                 "required_command": list(c.required_command_interfaces),
                 "required_state": list(c.required_state_interfaces),
                 "is_chainable": c.is_chainable, "chain_connections": len(c.chain_connections)}
                for c in reply.controller]

    def switch(self, deactivate, activate, strictness, activate_asap, timeout):
        """controller_manager_services.switch_controllers."""
        request = SwitchController.Request()
        request.activate_controllers = activate
        request.deactivate_controllers = deactivate
        request.strictness = strictness
        request.activate_asap = activate_asap
        request.timeout = Duration(sec=int(timeout), nanosec=int(timeout % 1 * 1e9))
        reply = self.call(SwitchController, "switch_controller", request)
        return {"ok": reply.ok, "message": reply.message}

    def set_parameter(self, name, value):
        """controller_manager_services.set_controller_parameters: the value as a string
        read back as YAML, through the node's set_parameters service."""
        request = SetParameters.Request(parameters=[Parameter(
            name=name, value=get_parameter_value(string_value=str(value)))])
        return self.call(SetParameters, "set_parameters", request).results[0].successful

    def named(self, kind, service, name):
        request = kind.Request()
        request.name = name
        return self.call(kind, service, request).ok

    def send(self, controller, joint, position, seconds):
        topic = f"/{controller}/joint_trajectory"
        if topic not in self.publishers:
            self.publishers[topic] = self.node.create_publisher(JointTrajectory, topic, 10)
        publisher = self.publishers[topic]
        deadline = time.monotonic() + WALL_TIMEOUT
        while not publisher.get_subscription_count():
            assert time.monotonic() < deadline, f"nobody subscribes to {topic}"
            rclpy.spin_once(self.node, timeout_sec=0.01)
        point = JointTrajectoryPoint(positions=[float(position)])
        point.time_from_start.sec = int(seconds)
        point.time_from_start.nanosec = int(seconds % 1 * 1e9)
        publisher.publish(JointTrajectory(joint_names=[joint], points=[point]))

    def run_for(self, seconds, until=None):
        """Spin until the joint states are `seconds` of simulated time past the last one
        heard now (or, given `until`, until the end arm is within 5 mrad of it, at most
        5 s); the end arm's states of that span: (stamp, position, effort)."""
        deadline = time.monotonic() + WALL_TIMEOUT
        while not self.states:
            assert time.monotonic() < deadline, "no joint states"
            rclpy.spin_once(self.node, timeout_sec=0.01)
        start, first = self.states[-1][0], len(self.states)
        while self.states[-1][0] < start + (5.0 if until is not None else seconds):
            assert time.monotonic() < deadline, "the simulated time did not advance"
            rclpy.spin_once(self.node, timeout_sec=0.01)
            if until is not None and abs(self.states[-1][1]["end_arm_joint"] - until) < 0.005:
                break
        return [(t, q["end_arm_joint"], e.get("end_arm_joint")) for t, q, e in
                self.states[first:]]


def main() -> int:
    rclpy.init()
    c = Client()
    out = {}
    began = time.monotonic()
    out["listed"] = c.list_controllers()
    types = c.call(ListControllerTypes, "list_controller_types", ListControllerTypes.Request())
    out["types"] = dict(zip(types.types, types.base_classes))
    interfaces = c.call(ListHardwareInterfaces, "list_hardware_interfaces",
                        ListHardwareInterfaces.Request())
    out["command_interfaces"] = [[i.name, i.is_available, i.is_claimed]
                                 for i in interfaces.command_interfaces]
    out["state_interfaces"] = [i.name for i in interfaces.state_interfaces]
    components = c.call(ListHardwareComponents, "list_hardware_components",
                        ListHardwareComponents.Request())
    out["components"] = [[h.name, h.type, h.plugin_name, h.state.label,
                          [i.name for i in h.command_interfaces]] for h in components.component]

    c.send("end_arm_controller", "end_arm_joint", 0.4, 1.0)
    out["moving"] = c.run_for(None, until=0.4)
    out["moved"] = c.run_for(0.5)[-1][1]   # settled
    out["deactivate"] = c.switch(["end_arm_controller"], [], SwitchController.Request.STRICT,
                                 False, 5.0)
    out["after_deactivate"] = c.list_controllers()
    interfaces = c.call(ListHardwareInterfaces, "list_hardware_interfaces",
                        ListHardwareInterfaces.Request())
    out["claimed_after_deactivate"] = [i.name for i in interfaces.command_interfaces
                                       if i.is_claimed]
    c.send("end_arm_controller", "end_arm_joint", -0.4, 0.5)   # to an inactive controller
    out["inactive"] = c.run_for(2.0)
    out["activate"] = c.switch([], ["end_arm_controller"], SwitchController.Request.BEST_EFFORT,
                               True, 5.0)
    c.send("end_arm_controller", "end_arm_joint", -0.3, 1.0)
    out["reactivated"] = c.run_for(None, until=-0.3)[-1][1]

    strict, best = SwitchController.Request.STRICT, SwitchController.Request.BEST_EFFORT
    out["unknown"] = c.switch([], ["no_such_controller"], strict, False, 5.0)
    out["again_strict"] = c.switch([], ["middle_arm_controller"], strict, False, 5.0)
    out["again_best_effort"] = c.switch([], ["middle_arm_controller"], best, False, 5.0)

    out["unload_active"] = c.named(UnloadController, "unload_controller", "end_arm_controller")
    c.switch(["end_arm_controller"], [], strict, False, 5.0)
    out["unload"] = c.named(UnloadController, "unload_controller", "end_arm_controller")
    out["after_unload"] = [x["name"] for x in c.list_controllers()]
    out["configure_unloaded"] = c.named(ConfigureController, "configure_controller",
                                        "end_arm_controller")
    out["parameters_set"] = [
        c.set_parameter("end_arm_controller.params_file", [sys.argv[1]]),
        c.set_parameter("end_arm_controller.type",
                        "joint_trajectory_controller/JointTrajectoryController")]
    out["load"] = c.named(LoadController, "load_controller", "end_arm_controller")
    out["loaded"] = [x for x in c.list_controllers() if x["name"] == "end_arm_controller"]
    out["activate_unconfigured"] = c.switch([], ["end_arm_controller"], strict, False, 5.0)
    out["configure"] = c.named(ConfigureController, "configure_controller", "end_arm_controller")
    out["configured"] = [x["state"] for x in c.list_controllers()
                         if x["name"] == "end_arm_controller"]
    out["spawned"] = c.switch([], ["end_arm_controller"], strict, True, 5.0)
    out["final"] = {x["name"]: x["state"] for x in c.list_controllers()}
    out["wall"] = time.monotonic() - began
    print(json.dumps(out))
    c.node.destroy_node()
    rclpy.shutdown()
    return 0


if __name__ == "__main__":
    sys.exit(main())
