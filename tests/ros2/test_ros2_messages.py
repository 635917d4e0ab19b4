"""tf2_msgs, control_msgs and controller_manager_msgs as built here have upstream Jazzy's
type hashes (the values below are those of upstream's own .msg, .srv and .action files,
geometry2 jazzy, control_msgs 5.8.0 and ros2_control 4.46.0, built with the same
generators; an action's hash covers its goal, result and feedback): real
ROS 2 nodes and tools exchange them with the stand-in."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from ros2_environment import missing, run

UPSTREAM = {
    "tf2_msgs/msg/TFMessage":
        "RIHS01_e369d0f05a23ae52508854b66f6aa0437f3449d652e8cbf22d5abe85d020f087",
    "control_msgs/msg/JointTrajectoryControllerState":
        "RIHS01_51d8dd89cc624cbe9daaeeb4d80d6de9b86168ffdc3be41fefc0953e3c26e480",
    "control_msgs/msg/MultiDOFCommand":
        "RIHS01_033fb0fa1ffc63a872ca73c61a49ded83a22daa5cc3f074cc28949f73359e677",
    "control_msgs/msg/MultiDOFStateStamped":
        "RIHS01_08e47e3e734a7d08131b57e14e9f740782f3bf9a1aadabd2a16b54d27e551f0a",
    "control_msgs/msg/SingleDOFState":
        "RIHS01_fe8365f86265bddfefbd26698975a818bf024a1c267c8ce577cd366ef06d7163",
    "control_msgs/msg/SingleDOFStateStamped":
        "RIHS01_33859c01b46943f1458f83f2627249d34332b38e545c723ddbdabea2b6675af1",
    "control_msgs/msg/JointTolerance":
        "RIHS01_c254f9cece0f3b733017b6990fd46d1326e25242d6b8844398c97d9a88e7d648",
    "control_msgs/msg/JointComponentTolerance":
        "RIHS01_739ea7566931944d33830fa10f1bf5e7a7fbdc3172bce7a7eaac642bd6e3ffa4",
    "control_msgs/action/FollowJointTrajectory":
        "RIHS01_738ebcb7a2d7cfa42f9f1001cc99ce3a4383d1cfe508015d9be8485e4b1c66f6",
    "controller_manager_msgs/msg/ChainConnection":
        "RIHS01_2daecd1da4b171f48b291c79747657a651eb1ab8821b68e38b1c88c736bba91c",
    "controller_manager_msgs/msg/ControllerState":
        "RIHS01_9a8780ab9814b6032978a07c6c7033cf1a7894ac8d948a6fb72afea07b04cc83",
    "controller_manager_msgs/msg/HardwareComponentState":
        "RIHS01_8723f76b60e3ea54920065e3e777d93c68b76fc12839ad6a6ca4e0a6439b384c",
    "controller_manager_msgs/msg/HardwareInterface":
        "RIHS01_b4c556991db81ca56a49338b5e8f0675a6707faee54fba161d2bbd4d963d418a",
    "controller_manager_msgs/srv/CleanupController":
        "RIHS01_0e5e0da84cf97150abbb3a4e2249c67e6f43dba01ed9b7228b4deaab8838ec4b",
    "controller_manager_msgs/srv/ConfigureController":
        "RIHS01_b5de498113f4eabc7b932e019ca0498d67304b1ca465fe8a426ea89644865ff9",
    "controller_manager_msgs/srv/ListControllerTypes":
        "RIHS01_873e8d2bb81b8b5903ca736d299ba959f929efec4b4a18d17354b8b322822e05",
    "controller_manager_msgs/srv/ListControllers":
        "RIHS01_4f8e36bb1fa5afdeba45c2d56ae6a2097b1493a253f961dd6290c085033bd189",
    "controller_manager_msgs/srv/ListHardwareComponents":
        "RIHS01_2ff105e609928671af16413362c0fdd089e1dd50c5a49d830db603ba8e4439c8",
    "controller_manager_msgs/srv/ListHardwareInterfaces":
        "RIHS01_c3e561a6e8cc7b9d577d8065c783038e51f6950cbe9bed67fb117a3e2e04d8f1",
    "controller_manager_msgs/srv/LoadController":
        "RIHS01_e37f7596c50c88cf8cb7a10cd376ff7579850cc63b5e787e9c8f11981f9ab4d2",
    "controller_manager_msgs/srv/ReloadControllerLibraries":
        "RIHS01_485cd0040f8a343a9596155b967363e1bc715f034bbb111f795c73d9d8056a9b",
    "controller_manager_msgs/srv/SwitchController":
        "RIHS01_d4ad10aa5da7808bc522d55d4123d8ef79de73d049d165639d7663ac37cc9895",
    "controller_manager_msgs/srv/UnloadController":
        "RIHS01_4055728e84c041348648d7f808c6681562000e3a9ce9fbb42c3350df25773f16",
}


def test_the_built_messages_have_upstreams_type_hashes():
    if missing():
        pytest.skip(missing())
    done = run("from sw2sim.ros2 import messages; print(messages.ensure())")
    assert done.returncode == 0, done.stderr
    where = Path(done.stdout.strip().splitlines()[-1])
    for name, expected in UPSTREAM.items():
        described = json.loads((where / "share" / f"{name}.json").read_text())
        assert described["type_hashes"][0]["hash_string"] == expected, name


def test_the_generation_entry_point_is_a_quick_no_op_when_done():
    """`make setup` runs it on every set-up: once built, it builds nothing again."""
    if missing():
        pytest.skip(missing())
    done = run("import os; from sw2sim.ros2 import messages; messages.ensure(); "
               "marker = messages._marker(messages.prefix()); before = os.stat(marker).st_mtime_ns; "
               "messages.ensure(); print(messages.ready(), os.stat(marker).st_mtime_ns == before)")
    assert done.returncode == 0, done.stderr
    assert done.stdout.split() == ["True", "True"], done.stdout
