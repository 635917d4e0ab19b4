"""What `sw2sim ros` reads in roslaunch's error output (sw2sim.ros.launch_faults), on lines
as roslaunch 1.15 prints them (roslaunch/launch.py, pmon.py, nodeprocess.py; printerrlog
wraps each in a red colour escape), without ROS."""

from __future__ import annotations

import os
import time

from sw2sim.ros.launch_faults import ErrorPassage, FaultReader, summary

RED, PLAIN = "\x1b[31m", "\x1b[0m"
NODES = [("gazebo", "gazebo_ros", "gzserver"), ("spawn_model", "gazebo_ros", "spawn_model"),
         ("example_3/controller_spawner", "controller_manager", "spawner"),
         ("left", "example_1", "arm_node.py"), ("right", "example_1", "arm_node.py")]


def _read(*lines: str) -> list[str]:
    reader = FaultReader()
    for line in lines:
        reader.read(line)
    return summary(reader.faults, NODES)


def test_a_node_that_died_is_named_with_its_package_and_type():
    said = _read(f"{RED}[gazebo-1] process has died [pid 4242, exit code 1, cmd /x/gazebo_ros/"
                 f"nodes/gzserver __name:=gazebo __log:=/r/gazebo-1.log].\n",
                 f"log file: /r/gazebo-1*.log{PLAIN}\n")
    assert said == ["node gazebo (gazebo_ros/gzserver) died: exit code 1; see the lines above"]


def test_a_node_killed_by_a_signal_says_which_and_a_namespaced_node_keeps_its_namespace():
    said = _read("[example_3/controller_spawner-6] process has died [pid 7, exit code -11, "
                 "cmd /x/spawner a b __name:=controller_spawner].")
    assert said == ["node example_3/controller_spawner (controller_manager/spawner) died: "
                    "killed by SIGSEGV (exit code -11); see the lines above"]


def test_a_node_that_finishes_with_status_0_is_no_fault():
    assert _read("\x1b[1m[spawn_model-3] process has finished cleanly\n",
                 "[spawn_model-3] process has died [pid 9, exit code 0, cmd x].") == []


def test_a_required_node_is_named_from_the_line_before_its_exit_code():
    said = _read(f"{RED}{'=' * 80}REQUIRED process [gazebo-1] has died!\n",
                 "process has died [pid 5, exit code 2, cmd /x/gzserver __name:=gazebo].\n",
                 "log file: /r/gazebo-1*.log\n", "Initiating shutdown!\n", f"{'=' * 80}{PLAIN}\n")
    assert said == ["node gazebo (gazebo_ros/gzserver) died: exit code 2; see the lines above"]


def test_a_node_that_cannot_start_is_named_from_the_launch_file_in_its_order():
    reason = ("Cannot locate node of type [arm_node.py] in package [example_1]. Make sure file "
              "exists in package path and permission is set to executable (chmod +x)")
    line = f"{RED}ERROR: cannot launch node of type [example_1/arm_node.py]: {reason}{PLAIN}\n"
    assert _read(line, line) == [f"could not start node left (example_1/arm_node.py): {reason}",
                                 f"could not start node right (example_1/arm_node.py): {reason}"]


def test_a_missing_package_says_so_rather_than_only_its_name():
    said = _read(f"{RED}ERROR: cannot launch node of type [no_pkg/x]: no_pkg\n",
                 f"ROS path [0]=/usr/share{PLAIN}\n")
    assert said == ["could not start a node of type no_pkg/x: there is no package no_pkg on "
                    "ROS_PACKAGE_PATH (check the node's pkg= in the launch file)"]


def test_other_error_lines_are_no_faults():
    assert _read("[ERROR] [1795821292.7]: something a node logged\n",
                 "Traceback (most recent call last):\n",
                 "[gazebo-1] escalating to SIGTERM\n") == []


def test_the_lines_pass_through_unchanged_and_are_watched_until_told_not_to():
    died = f"{RED}[a-1] process has died [pid 1, exit code 3, cmd a].{PLAIN}\n".encode()
    later = [b"[b-2] process has died [pid 2, exit code 1, cmd b].\n",
             "\u00fcn\u00efcode \xff\n".encode("latin-1"), b"no newline at the end"]
    read_end, write_end = os.pipe()
    out_read, out_write = os.pipe()
    with os.fdopen(read_end, "rb") as stream:
        passage = ErrorPassage(stream, out=out_write)
        os.write(write_end, died)
        deadline = time.monotonic() + 10
        while not passage.faults and time.monotonic() < deadline:
            time.sleep(0.01)
        passage.stop_watching()     # the run is stopping: b's end is no fault
        os.write(write_end, b"".join(later))
        os.close(write_end)
        passage.wait(10)
    os.close(out_write)
    with os.fdopen(out_read, "rb") as out:
        assert out.read() == died + b"".join(later)
    assert [f.node for f in passage.faults] == ["a"]
