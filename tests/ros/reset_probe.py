"""Drive a running simulation through Gazebo's resets and record what it publishes, then
print it as JSON:

    python reset_probe.py block    # Practice 4: the block at 1.5 m, reset_world, reset_simulation
    python reset_probe.py wheels   # Practice 1: reset_simulation while its node runs

{"clock": [t, ...], "states": [[stamp, {joint: position}, {joint: velocity}], ...],
 "controller": [stamp, ...], "tf": [stamp, ...], "marks": {name: value}}
`tf` holds the stamps of robot_state_publisher's transforms to the frame TF_FRAME names
(Practice 4's block, the child of its moving joint).
`clock` and `states` are in the order they arrived; `marks` holds the times and positions
the probe read around each reset. Run by test_reset.py in a process of its own, as a
separate rospy node.
"""

import json
import sys
import time

import rosgraph
import rospy
from gazebo_msgs.srv import GetJointProperties
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64
from std_srvs.srv import Empty
from tf2_msgs.msg import TFMessage

WALL_TIMEOUT = 60.0
TF_FRAME = "block_link"
PULSE = 62.6          # rad/s a pulse of periodic_force_node.py adds to each wheel


def wait_for(condition, what: str) -> None:
    deadline = time.monotonic() + WALL_TIMEOUT
    while not condition():
        if time.monotonic() > deadline:
            raise SystemExit(f"reset_probe: timed out waiting for {what}")
        time.sleep(0.01)


class Probe:
    def __init__(self, states_topic: str, controller_topic: str | None = None):
        master = rosgraph.Master("/reset_probe")
        wait_for(lambda: master.hasParam("/use_sim_time") and master.getParam("/use_sim_time"),
                 "use_sim_time")
        rospy.init_node("reset_probe", anonymous=True, disable_signals=True)
        self.clock, self.states, self.controller, self.marks = [], [], [], {}
        self.tf = []
        rospy.Subscriber("/clock", Clock, lambda m: self.clock.append(m.clock.to_sec()))
        rospy.Subscriber("/tf", TFMessage, self.on_tf)
        rospy.Subscriber(states_topic, JointState, self.on_state)
        if controller_topic:
            from control_msgs.msg import JointControllerState
            rospy.Subscriber(controller_topic, JointControllerState,
                             lambda m: self.controller.append(m.header.stamp.to_sec()))
        names = ("reset_simulation", "reset_world", "pause_physics", "unpause_physics",
                 "get_joint_properties")
        for name in names:
            rospy.wait_for_service(f"/gazebo/{name}", timeout=WALL_TIMEOUT)
        self.reset_simulation = rospy.ServiceProxy("/gazebo/reset_simulation", Empty)
        self.reset_world = rospy.ServiceProxy("/gazebo/reset_world", Empty)
        self.pause = rospy.ServiceProxy("/gazebo/pause_physics", Empty)
        self.unpause = rospy.ServiceProxy("/gazebo/unpause_physics", Empty)
        self.properties = rospy.ServiceProxy("/gazebo/get_joint_properties", GetJointProperties)

    def on_state(self, message):
        self.states.append([message.header.stamp.to_sec(),
                            dict(zip(message.name, message.position)),
                            dict(zip(message.name, message.velocity))])

    def on_tf(self, message):
        self.tf += [t.header.stamp.to_sec() for t in message.transforms
                    if t.child_frame_id == TF_FRAME]

    def position(self, joint: str) -> float:
        return self.properties(joint).position[0]

    def until(self, t: float) -> None:
        """Wait for the clock to reach `t` (after the last reset)."""
        wait_for(lambda: self.clock and self.clock[-1] >= t, f"the clock to reach {t} s")

    def report(self) -> None:
        print(json.dumps({"clock": self.clock, "states": self.states,
                          "controller": self.controller, "tf": self.tf,
                          "marks": self.marks}))


def block(probe: Probe) -> None:
    """Practice 4: the block commanded to 1.5 m; reset_world, then reset_simulation, each
    with the physics paused so that the position read is the reset's own."""
    command = rospy.Publisher("/example_4/block_controller/command", Float64, queue_size=1,
                              latch=True)
    wait_for(lambda: probe.controller, "the block controller")
    wait_for(lambda: probe.clock, "the clock")
    command.publish(Float64(1.5))
    probe.until(probe.clock[-1] + 5.0)
    marks = probe.marks
    probe.pause()
    marks["before"] = probe.position("block_joint")
    probe.reset_world()
    marks["world_time"] = rospy.get_time()
    marks["after_world"] = probe.position("block_joint")
    marks["clock_at_world"] = len(probe.clock)
    probe.unpause()
    probe.until(marks["world_time"] + 5.0)
    probe.pause()
    marks["back"] = probe.position("block_joint")
    marks["old_time"] = probe.clock[-1]
    probe.reset_simulation()
    marks["after_simulation"] = probe.position("block_joint")
    marks["clock_at_simulation"] = len(probe.clock)
    probe.unpause()
    # JointStateController is silent until the clock passes its time before the reset
    wait_for(lambda: probe.clock[-1] < marks["old_time"], "the clock to go back")
    probe.until(marks["old_time"] + 1.0)
    probe.report()


def wheels(probe: Probe) -> None:
    """Practice 1: reset_simulation while periodic_force_node.py runs, after its second
    pulse (the node then sleeps from a time after 10 s, which the clock is sure to be found
    under once it is set back); its next pulse comes from the new time."""
    wait_for(lambda: probe.states and probe.states[-1][2]["front_left_joint"] > 1.5 * PULSE,
             "a second pulse")
    probe.until(probe.clock[-1] + 1.5)     # past that pulse's end
    probe.marks["old_time"] = probe.clock[-1]
    probe.reset_simulation()
    wait_for(lambda: probe.clock[-1] < probe.marks["old_time"], "the clock to go back")
    probe.until(2.5)
    try:
        probe.marks["node"] = rosgraph.Master("/reset_probe").lookupNode("/periodic_force")
    except rosgraph.MasterError:
        probe.marks["node"] = None
    probe.report()


def main() -> int:
    kind = sys.argv[1]
    if kind == "block":
        block(Probe("/example_4/joint_states", "/example_4/block_controller/state"))
    else:
        wheels(Probe("/joint_states"))
    rospy.signal_shutdown("done")
    return 0


if __name__ == "__main__":
    sys.exit(main())
