"""The `ros2 launch` and `ros2 run` lines that the pages show for ROS 2 Jazzy name launch
files that `sw2sim port` writes and node files that the pages write, in packages that a
page ports (their `ros2 topic` lines are checked on each page's run, in
test_ros2_page_blocks.py). Needs sw2sim port only, not rclpy."""

from __future__ import annotations

from pathlib import Path

import pytest

from course.snippets import find_pages, parse_page
from course.snippets.ros2 import node_blocks, ported_source
from course.snippets.terminal import commands
from jazzy_commands import jazzy_commands, name_problems
from repository import ROOT
from sw2sim.port import port

PAGES = [parse_page(p, ROOT) for p in find_pages(ROOT)]


@pytest.fixture(scope="module")
def ported(tmp_path_factory) -> dict[str, Path]:
    """Every package a page ports (`sw2sim port .../examples/NAME -o .../NAME`), ported
    once."""
    out = tmp_path_factory.mktemp("ported")
    found = {}
    for page in PAGES:
        for block in page.ros2_commands:
            for command in commands(block):
                source = ported_source(command)
                if source:
                    words = command.words
                    name = Path(words[words.index("-o") + 1] if "-o" in words
                                else source).name
                    if name not in found:
                        found[name] = port(ROOT / source, out / name).package_dir
    return found


def test_the_pages_show_jazzy_launch_and_run_lines():
    lines = [c for p in PAGES for c in jazzy_commands(p)]
    assert sum(c.words[1] == "launch" for c in lines) >= 5, "a ros2 launch line per practice"
    assert sum(c.words[1] == "run" for c in lines) >= 3
    assert sum(c.words[1] == "topic" for c in lines) >= 4


def test_every_launch_and_run_line_names_what_the_port_and_the_pages_write(ported):
    assert {"example_1", "example_3", "example_5"} <= set(ported)
    nodes = {Path(key).name for key in node_blocks(ROOT)}
    assert "wheel_pulse.py" in nodes
    problems = [p for page in PAGES for c in jazzy_commands(page)
                for p in name_problems(c, ported, nodes)]
    assert not problems, "\n".join(problems)


def test_a_wrong_name_is_caught(ported, tmp_path):
    """The check can fail: a launch file the port does not write, and a node no page has."""
    page = tmp_path / "page.md"
    page.write_text("---\ntitle: t\n---\n\n```bash\nros2 launch example_3 world.launch.py\n"
                    "ros2 run example_3 missing_node.py\n```\n"
                    '{: data-ros2-needs="ROS 2 Jazzy"}\n', encoding="utf-8")
    lines = jazzy_commands(parse_page(page, tmp_path))
    problems = [p for c in lines for p in name_problems(c, ported, {"wheel_pulse.py"})]
    assert len(problems) == 2, problems
    assert "launch/world.launch.py" in problems[0] and "missing_node.py" in problems[1]


def _problems(folder, name, commands, tables_of, problems_of) -> list[str]:
    """What the checks find in a page holding `commands` in a ROS 2 block: the field
    tables made from the page's lines by `tables_of`, then `problems_of(line, tables)`."""
    page = folder / f"{name}.md"
    page.write_text(f"---\ntitle: t\n---\n\n```bash\n{commands}```\n"
                    '{: data-ros2-needs="ROS 2 Jazzy"}\n', encoding="utf-8")
    lines = jazzy_commands(parse_page(page, folder))
    tables = tables_of(lines)
    return [p for line in lines for p in problems_of(line, tables)]


def test_a_wrong_topic_type_or_field_is_caught(tmp_path):
    from jazzy_commands import field_tables, topic_problems, topic_types
    from ros2_environment import missing
    if reason := missing():
        pytest.skip(reason)
    graph = {"/arm_controller/joint_trajectory": ["trajectory_msgs/msg/JointTrajectory"],
             "/arm_controller/controller_state":
                 ["control_msgs/msg/JointTrajectoryControllerState"]}
    good = ('ros2 topic pub --once /arm_controller/joint_trajectory '
            'trajectory_msgs/msg/JointTrajectory "{joint_names: [a], points: '
            '[{positions: [0.5], time_from_start: {sec: 2}}]}"\n'
            'ros2 topic echo /arm_controller/controller_state --field error.positions\n')
    bad = ('ros2 topic pub --once /arm_controller/joint_trajectory '
           'trajectory_msgs/msg/JointTrajectory "{joint_names: [a], points: [{position: [0.5]}]}"\n'
           'ros2 topic pub --once /arm_controller/joint_trajectory std_msgs/msg/Float64 "{data: 1}"\n'
           'ros2 topic echo /arm_controller/state\n'
           'ros2 topic echo /arm_controller/controller_state --field error.position\n')
    found = {name: _problems(tmp_path, name, text, lambda lines: field_tables(
                 topic_types(lines, graph)), lambda c, t: topic_problems(c, graph, t))
             for name, text in (("good", good), ("bad", bad))}
    assert found["good"] == []
    assert len(found["bad"]) == 4, found["bad"]
    assert "no field 'position'" in found["bad"][0]
    assert "not std_msgs/msg/Float64" in found["bad"][1]
    assert "/arm_controller/state is not a topic" in found["bad"][2]
    assert "--field error.position" in found["bad"][3]


def test_a_wrong_action_type_or_goal_field_is_caught(tmp_path):
    from jazzy_commands import action_problems, action_types, field_tables
    from ros2_environment import missing
    if reason := missing():
        pytest.skip(reason)
    graph = {"/arm_controller/follow_joint_trajectory/_action/feedback":
             ["control_msgs/action/FollowJointTrajectory_FeedbackMessage"]}
    send = "ros2 action send_goal --feedback"
    good = (f'{send} /arm_controller/follow_joint_trajectory control_msgs/action/'
            'FollowJointTrajectory "{trajectory: {joint_names: [a], points: [{positions: [0.5], '
            'time_from_start: {sec: 2}}]}}"\n')
    bad = (f'{send} /arm/follow_joint_trajectory control_msgs/action/FollowJointTrajectory '
           '"{trajectory: {joint_names: [a]}}"\n'
           f'{send} /arm_controller/follow_joint_trajectory control_msgs/action/GripperCommand '
           '"{command: {position: 0.1}}"\n'
           f'{send} /arm_controller/follow_joint_trajectory control_msgs/action/'
           'FollowJointTrajectory "{trajectory: {points: [{position: [0.5]}]}}"\n')
    found = {name: _problems(tmp_path, name, text,
                             lambda lines: field_tables(action_types(lines)),
                             lambda c, t: action_problems(c, graph, t))
             for name, text in (("good", good), ("bad", bad))}
    assert found["good"] == []
    assert len(found["bad"]) == 3, found["bad"]
    assert "no action /arm/follow_joint_trajectory" in found["bad"][0]
    assert "not a control_msgs/action/GripperCommand" in found["bad"][1]
    assert "no field 'position'" in found["bad"][2]
