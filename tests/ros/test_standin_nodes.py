"""The stand-in's small nodes (sw2sim.ros.nodes) speak ROS 1 without rospy
(sw2sim.ros.wire): Debian's own rospy tools read what they publish, and a node that cannot
do its work says why in the launch log's terms."""

from __future__ import annotations

import math
import sys

import yaml


def test_the_small_nodes_talk_with_rospy_and_say_what_failed(ros):
    """static_transform_publisher latches its transform, read by Debian's rostopic (rospy);
    a spawner with no controller manager to talk to says which service it waited for."""
    ros.start(sys.executable, "-m", "sw2sim.ros.nodes", "static_transform_publisher",
              "0.1", "0.2", "0.3", "0.5", "0", "0", "base_link", "base_footprint", "40",
              "__name:=tf_footprint_base", name="static_transform_publisher")
    done = ros.run("rostopic", "echo", "-n", "1", "/tf_static", timeout=30)
    assert done.returncode == 0, done.stdout + done.stderr
    message = yaml.safe_load(done.stdout.split("---")[0])
    (transform,) = message["transforms"]
    assert transform["header"]["frame_id"] == "base_link"
    assert transform["child_frame_id"] == "base_footprint"
    t, q = transform["transform"]["translation"], transform["transform"]["rotation"]
    assert (t["x"], t["y"], t["z"]) == (0.1, 0.2, 0.3)
    # a yaw of 0.5 rad about z
    assert math.isclose(q["z"], math.sin(0.25)) and math.isclose(q["w"], math.cos(0.25))
    assert abs(q["x"]) < 1e-12 and abs(q["y"]) < 1e-12
    done = ros.run(sys.executable, "-m", "sw2sim.ros.nodes", "spawner", "--timeout", "1",
                   "arm_controller", timeout=30)
    assert done.returncode == 1
    assert "[ERROR]" in done.stderr and "/controller_manager/load_controller" in done.stderr
