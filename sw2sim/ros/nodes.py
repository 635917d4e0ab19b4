"""The small nodes of the stand-in packages, as the launch files name them:

    python -m sw2sim.ros.nodes spawn_model -file F -urdf -model NAME [-x X -y Y -z Z]
    python -m sw2sim.ros.nodes spawner [--timeout S] CONTROLLER ...
    python -m sw2sim.ros.nodes static_transform_publisher x y z yaw pitch roll FRAME CHILD MS

`spawn_model` (gazebo_ros) sends the URDF to /gazebo/spawn_urdf_model and ends;
`spawner` (controller_manager) loads and starts the controllers in its namespace and stays
until shut down; `static_transform_publisher` (tf) latches one transform on /tf_static.
"""

from __future__ import annotations

import math
import sys


def _value(args: list[str], flag: str, default: str | None = None) -> str | None:
    return args[args.index(flag) + 1] if flag in args and args.index(flag) + 1 < len(args) \
        else default


def spawn_model(args: list[str]) -> int:
    import rospy
    from geometry_msgs.msg import Point, Pose, Quaternion
    from gazebo_msgs.srv import SpawnModel
    rospy.init_node("spawn_model", anonymous=True, disable_signals=True)
    if "-file" in args:
        with open(_value(args, "-file"), encoding="utf-8") as stream:
            xml = stream.read()
    elif "-param" in args:
        xml = rospy.get_param(_value(args, "-param"))
    else:
        rospy.logerr("spawn_model: give -file FILE or -param NAME")
        return 1
    pose = Pose(position=Point(*(float(_value(args, f"-{a}", "0")) for a in "xyz")),
                orientation=Quaternion(0, 0, 0, 1))
    rospy.wait_for_service("/gazebo/spawn_urdf_model", timeout=60)
    answer = rospy.ServiceProxy("/gazebo/spawn_urdf_model", SpawnModel)(
        model_name=_value(args, "-model", "robot"), model_xml=xml,
        robot_namespace=_value(args, "-robot_namespace", "") or rospy.get_namespace(),
        initial_pose=pose, reference_frame=_value(args, "-reference_frame", "world"))
    (rospy.loginfo if answer.success else rospy.logerr)("spawn_model: %s", answer.status_message)
    return 0 if answer.success else 1


def spawner(args: list[str]) -> int:
    import rospy
    from controller_manager_msgs.srv import LoadController, SwitchController
    rospy.init_node("spawner", anonymous=True, disable_signals=True)
    names, skip = [], False
    for arg in args:
        if skip:
            skip = False
        elif arg in ("--timeout", "--namespace", "--shutdown-timeout"):
            skip = True
        elif not arg.startswith("-") and not arg.startswith("__"):
            names.append(arg)
    base = rospy.resolve_name("controller_manager")
    rospy.wait_for_service(f"{base}/load_controller", timeout=float(_value(args, "--timeout", "60")))
    load = rospy.ServiceProxy(f"{base}/load_controller", LoadController)
    loaded = [n for n in names if load(n).ok]
    for name in set(names) - set(loaded):
        rospy.logerr("spawner: controller %s could not be loaded", name)
    switch = rospy.ServiceProxy(f"{base}/switch_controller", SwitchController)
    ok = switch(start_controllers=loaded, stop_controllers=[], strictness=2, start_asap=False,
                timeout=0.0).ok
    rospy.loginfo("spawner: started %s", ", ".join(loaded) if ok else "nothing")
    rospy.spin()
    return 0


def static_transform_publisher(args: list[str]) -> int:
    import rospy
    from geometry_msgs.msg import TransformStamped
    from tf2_msgs.msg import TFMessage
    numbers = [a for a in args if not a.startswith("__")]
    x, y, z, yaw, pitch, roll = (float(v) for v in numbers[:6])
    parent, child = numbers[6], numbers[7]
    rospy.init_node("static_transform_publisher", anonymous=True, disable_signals=True)
    cy, sy, cp, sp, cr, sr = (math.cos(yaw / 2), math.sin(yaw / 2), math.cos(pitch / 2),
                              math.sin(pitch / 2), math.cos(roll / 2), math.sin(roll / 2))
    t = TransformStamped()
    t.header.stamp, t.header.frame_id, t.child_frame_id = rospy.Time(0), parent, child
    t.transform.translation.x, t.transform.translation.y, t.transform.translation.z = x, y, z
    r = t.transform.rotation
    r.w = cr * cp * cy + sr * sp * sy
    r.x = sr * cp * cy - cr * sp * sy
    r.y = cr * sp * cy + sr * cp * sy
    r.z = cr * cp * sy - sr * sp * cy
    rospy.Publisher("/tf_static", TFMessage, queue_size=1, latch=True).publish(TFMessage([t]))
    rospy.spin()
    return 0


def _without_clock() -> None:
    """Keep rospy from following /clock in these nodes: none of them reads the time, and
    at a high real-time factor the clock's messages would cost them more than their work."""
    import rospy.impl.simtime
    import rospy.rostime

    def wall_time() -> bool:
        rospy.rostime.set_rostime_initialized(True)
        return True

    rospy.impl.simtime.init_simtime = wall_time


NODES = {"spawn_model": spawn_model, "spawner": spawner,
         "static_transform_publisher": static_transform_publisher}


def main(argv: list[str] | None = None) -> int:
    from . import messages
    argv = sys.argv[1:] if argv is None else argv
    if not argv or argv[0] not in NODES:
        print(f"usage: python -m sw2sim.ros.nodes {{{','.join(NODES)}}} ...", file=sys.stderr)
        return 2
    messages.ensure()
    _without_clock()
    try:
        return NODES[argv[0]](argv[1:])
    except KeyboardInterrupt:
        return 0


if __name__ == "__main__":
    sys.exit(main())
