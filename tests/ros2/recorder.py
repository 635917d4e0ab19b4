"""An independent ROS 2 node (rclpy only, no sw2sim): it records what the stand-in serves,
sends the commands it is given, and prints one JSON object once the simulated clock
is UNTIL seconds past the moment its commands took effect (every joint a trajectory or
reference names has moved; without those, when it sent its commands; without commands,
past the first joint state it received) and /robot_description has arrived, or after
WALL_TIMEOUT seconds of wall time.

    python recorder.py UNTIL [--trajectory CONTROLLER JOINT POSITION SECONDS] ...
                             [--commands CONTROLLER V1,V2,...] [--reference CONTROLLER JOINT VALUE]
                             [--state CONTROLLER {jtc,pid}] [--tf LINK]

Commands are sent once the first joint state has arrived. A trajectory for several joints
names them and their positions with commas: --trajectory arm a,b 0.5,-0.2 2.
"""

import argparse
import json
import sys
import time

import rclpy
from rclpy.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64MultiArray, String
from tf2_msgs.msg import TFMessage
from trajectory_msgs.msg import JointTrajectory, JointTrajectoryPoint

MOVING = 1e-3   # rad/s or m/s: faster than this, a joint moves
RESEND = 0.05   # s of wall time between a command's or set point's sends
WALL_TIMEOUT = 40.0


def seconds(stamp) -> float:
    return stamp.sec + stamp.nanosec * 1e-9


def main() -> int:
    parser = argparse.ArgumentParser()
    parser.add_argument("until", type=float)
    parser.add_argument("--trajectory", nargs=4, action="append", default=[])
    parser.add_argument("--commands", nargs=2, action="append", default=[])
    parser.add_argument("--reference", nargs=3, action="append", default=[])
    parser.add_argument("--state", nargs=2, action="append", default=[])
    parser.add_argument("--moves", nargs=2, action="append", default=[],
                        metavar=("JOINT", "VELOCITY"),
                        help="a joint a --commands message turns, and at what velocity")
    args = parser.parse_args()
    rclpy.init()
    node = rclpy.create_node("recorder")
    latched = QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL,
                         reliability=ReliabilityPolicy.RELIABLE)
    out = {"clock": [], "states": [], "description": None, "tf_static": [], "tf": [],
           "controller_state": {}}

    def on_state(m):
        out["states"].append([seconds(m.header.stamp), dict(zip(m.name, m.position)),
                              dict(zip(m.name, m.velocity))])

    def on_tf(m):   # every message: /tf and /joint_states arrive in either order
        out["tf"].append([[t.header.frame_id, t.child_frame_id, seconds(t.header.stamp),
                      [t.transform.translation.x, t.transform.translation.y,
                       t.transform.translation.z],
                      [t.transform.rotation.x, t.transform.rotation.y, t.transform.rotation.z,
                       t.transform.rotation.w]] for t in m.transforms])

    def on_static(m):
        out["tf_static"] += [[t.header.frame_id, t.child_frame_id,
                              [t.transform.translation.x, t.transform.translation.y,
                               t.transform.translation.z],
                              [t.transform.rotation.x, t.transform.rotation.y,
                               t.transform.rotation.z, t.transform.rotation.w]]
                             for t in m.transforms]

    node.create_subscription(Clock, "/clock", lambda m: out["clock"].append(seconds(m.clock)), 10)
    node.create_subscription(JointState, "/joint_states", on_state, 10)
    node.create_subscription(String, "/robot_description",
                             lambda m: out.__setitem__("description", m.data), latched)
    node.create_subscription(TFMessage, "/tf_static", on_static, latched)
    node.create_subscription(TFMessage, "/tf", on_tf, 100)
    for controller, kind in args.state:
        if kind == "jtc":
            from control_msgs.msg import JointTrajectoryControllerState as T

            def keep(m, c=controller):
                out["controller_state"][c] = {
                    "joints": list(m.joint_names), "reference": list(m.reference.positions),
                    "feedback": list(m.feedback.positions), "error": list(m.error.positions),
                    "output": list(m.output.effort), "stamp": seconds(m.header.stamp)}
        else:
            from control_msgs.msg import MultiDOFStateStamped as T

            def keep(m, c=controller):
                out["controller_state"][c] = [
                    {"name": s.name, "reference": s.reference, "feedback": s.feedback,
                     "error": s.error, "output": s.output} for s in m.dof_states]
        node.create_subscription(T, f"/{controller}/controller_state", keep, 10)
    senders = []
    for controller, joint, position, duration in args.trajectory:
        publisher = node.create_publisher(JointTrajectory, f"/{controller}/joint_trajectory", 10)
        whole, part = divmod(float(duration), 1.0)
        point = JointTrajectoryPoint(positions=[float(p) for p in position.split(",")])
        point.time_from_start.sec, point.time_from_start.nanosec = int(whole), int(part * 1e9)
        senders.append((publisher, JointTrajectory(joint_names=joint.split(","),
                                                   points=[point])))
    repeated = []   # sent again every RESEND: the same command or set point has no other effect
    for controller, values in args.commands:
        publisher = node.create_publisher(Float64MultiArray, f"/{controller}/commands", 10)
        repeated.append((publisher,
                         Float64MultiArray(data=[float(v) for v in values.split(",")])))
    senders += repeated
    references = []
    for controller, joint, value in args.reference:
        from control_msgs.msg import MultiDOFCommand
        publisher = node.create_publisher(MultiDOFCommand, f"/{controller}/reference", 10)
        references.append((publisher, MultiDOFCommand(dof_names=[joint], values=[float(value)],
                                                       values_dot=[0.0])))
    senders += references
    repeated += references
    # the joints the commands move: UNTIL counts from when each has started to move, as the
    # commands' effect, not their sending, is what is timed: a message takes some wall time
    # to arrive, which a stand-in running faster than real time (--realtime 0) turns into
    # seconds of simulated time (a command sent at 8.46 s was not applied by 10.96 s)
    # (a joint moved toward its target by a twentieth of the way, or a --moves joint turning
    # at its velocity: a joint merely shaken by another's start does not count)
    targets = {j: float(p) for _, joint, position, _ in args.trajectory
               for j, p in zip(joint.split(","), position.split(","))}
    targets |= {joint: float(value) for _, joint, value in args.reference}

    turning = {joint: float(v) for joint, v in args.moves}

    def moved(joint, since):
        if joint in turning:   # at the commanded velocity, not merely shaken
            goal = turning[joint]
            return any(abs(state[2].get(joint, 0.0) - goal) <= 0.1 * abs(goal)
                       for state in since)
        start, goal = since[0][1].get(joint, 0.0), targets[joint]
        return any(abs(state[1].get(joint, start) - start) > 0.05 * abs(goal - start)
                   for state in since)
    deadline = time.monotonic() + WALL_TIMEOUT
    sent_at = base = moved_at = None
    resent = time.monotonic()
    while time.monotonic() < deadline:
        rclpy.spin_once(node, timeout_sec=0.01)
        if sent_at is None and out["states"] and all(
                p.get_subscription_count() for p, _ in senders):
            for publisher, message in senders:
                publisher.publish(message)
            sent_at = out["states"][-1][0]
            out["sent_at"] = sent_at
        elif sent_at is not None and time.monotonic() - resent > RESEND:
            # pid_controller takes its reference best effort: a message sent before the
            # controller's side has matched this publisher is lost, so it goes again, as
            # a node that holds a set point sends it; a command too, which a reliable
            # writer would otherwise repeat only at its next heartbeat, seconds of
            # simulated time later at --realtime 0
            for publisher, message in repeated:
                publisher.publish(message)
            resent = time.monotonic()
        if sent_at is not None and moved_at is None:
            since = [state for state in out["states"] if state[0] >= sent_at]
            if not targets.keys() | turning.keys() or since and all(
                    moved(j, since) for j in targets.keys() | turning.keys()):
                moved_at = out["moved_at"] = since[-1][0] if since else sent_at
        base = moved_at if senders else (out["states"][0][0] if out["states"] else None)
        if base is not None and out["clock"] and out["clock"][-1] >= base + args.until \
                and out["description"] is not None:   # latched, it may come after the states
            break
    print(json.dumps(out))
    node.destroy_node()
    rclpy.shutdown()
    return 0 if base is not None and out["clock"][-1] >= base + args.until else 1


if __name__ == "__main__":
    sys.exit(main())
