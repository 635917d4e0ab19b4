"""The small nodes of the stand-in packages, as the launch files name them:

    python -m sw2sim.ros.nodes spawn_model -file F -urdf -model NAME [-x X -y Y -z Z]
    python -m sw2sim.ros.nodes spawner [--timeout S] CONTROLLER ...
    python -m sw2sim.ros.nodes static_transform_publisher x y z yaw pitch roll FRAME CHILD MS

`spawn_model` (gazebo_ros) sends the URDF to /gazebo/spawn_urdf_model and ends;
`spawner` (controller_manager) loads and starts the controllers in its namespace and stays
until shut down; `static_transform_publisher` (tf) latches one transform on /tf_static.
They speak ROS 1 through sw2sim.ros.wire, which starts in a fraction of rospy's time.
"""

from __future__ import annotations

import math
import struct
import sys

from . import wire


def _value(args: list[str], flag: str, default: str | None = None) -> str | None:
    return args[args.index(flag) + 1] if flag in args and args.index(flag) + 1 < len(args) \
        else default


def _srv(package: str, name: str) -> tuple[str, str, str]:
    return wire.definition(wire.module_of(package, "srv", name), name)


def spawn_model(args: list[str]) -> int:
    node = wire.Node("spawn_model", args)
    if "-file" in args:
        with open(_value(args, "-file"), encoding="utf-8") as stream:
            xml = stream.read()
    elif "-param" in args:
        xml = node.get_param(_value(args, "-param"))
    else:
        node.close()
        wire.log("ERROR", "spawn_model: give -file FILE or -param NAME")
        return 1
    namespace = _value(args, "-robot_namespace", "") or node.namespace.rstrip("/") + "/"
    position = (float(_value(args, f"-{a}", "0")) for a in "xyz")
    request = (wire.string(_value(args, "-model", "robot")) + wire.string(xml)
               + wire.string(namespace) + wire.float64s(*position, 0.0, 0.0, 0.0, 1.0)
               + wire.string(_value(args, "-reference_frame", "world")))
    try:
        success, status = wire.unpack_bool_and_string(
            node.call("/gazebo/spawn_urdf_model", _srv("gazebo_msgs", "SpawnModel"), request))
    except wire.RosError as error:
        success, status = False, str(error)
    finally:
        node.close()
    wire.log("INFO" if success else "ERROR", f"spawn_model: {status}")
    return 0 if success else 1


def spawner(args: list[str]) -> int:
    node = wire.Node("spawner", args)
    names, skip = [], False
    for arg in args:
        if skip:
            skip = False
        elif arg in ("--timeout", "--namespace", "--shutdown-timeout"):
            skip = True
        elif not arg.startswith("-") and ":=" not in arg:
            names.append(arg)
    base = node.resolve("controller_manager")
    timeout = float(_value(args, "--timeout", "60"))
    try:
        load = _srv("controller_manager_msgs", "LoadController")
        loaded = [n for n in names
                  if node.call(f"{base}/load_controller", load, wire.string(n), timeout)[0]]
        for name in names:
            if name not in loaded:
                wire.log("ERROR", f"spawner: controller {name} could not be loaded")
        request = (wire.strings(loaded) + wire.strings([]) + struct.pack("<i", 2)
                   + struct.pack("<B", 0) + wire.float64s(0.0))
        ok = node.call(f"{base}/switch_controller",
                       _srv("controller_manager_msgs", "SwitchController"), request, timeout)[0]
    except wire.RosError as error:
        wire.log("ERROR", f"spawner: {error}")
        node.close()
        return 1
    wire.log("INFO", f"spawner: started {', '.join(loaded) if ok else 'nothing'}")
    node.spin()
    return 0


def static_transform_publisher(args: list[str]) -> int:
    numbers = [a for a in args if ":=" not in a]
    x, y, z, yaw, pitch, roll = (float(v) for v in numbers[:6])
    parent, child = numbers[6], numbers[7]
    cy, sy, cp, sp, cr, sr = (math.cos(yaw / 2), math.sin(yaw / 2), math.cos(pitch / 2),
                              math.sin(pitch / 2), math.cos(roll / 2), math.sin(roll / 2))
    rotation = (sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy,
                cr * cp * sy - sr * sp * cy, cr * cp * cy + sr * sp * sy)   # x, y, z, w
    # tf2_msgs/TFMessage with one geometry_msgs/TransformStamped, stamped 0 (static)
    message = (struct.pack("<I", 1) + struct.pack("<3I", 0, 0, 0) + wire.string(parent)
               + wire.string(child) + wire.float64s(x, y, z, *rotation))
    node = wire.Node("static_transform_publisher", args)
    tf = wire.definition(wire.module_of("tf2_msgs", "msg", "TFMessage"), "TFMessage")
    node.latch("/tf_static", tf, message)
    node.spin()
    return 0


NODES = {"spawn_model": spawn_model, "spawner": spawner,
         "static_transform_publisher": static_transform_publisher}


def main(argv: list[str] | None = None) -> int:
    from . import messages
    argv = sys.argv[1:] if argv is None else argv
    if not argv or argv[0] not in NODES:
        print(f"usage: python -m sw2sim.ros.nodes {{{','.join(NODES)}}} ...", file=sys.stderr)
        return 2
    messages.ensure()
    try:
        return NODES[argv[0]](argv[1:])
    except KeyboardInterrupt:
        return 0
    except (wire.RosError, OSError) as error:
        wire.log("ERROR", f"{argv[0]}: {error}")
        return 1


if __name__ == "__main__":
    sys.exit(main())
