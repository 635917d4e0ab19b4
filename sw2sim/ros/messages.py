"""The ROS 1 message and service classes Debian lacks, generated from the definitions
below with Debian's own generator (genpy).

gazebo_msgs, control_msgs and controller_manager_msgs are not packaged by Debian. Their
definitions here hold only what the lessons and the stand-in use, field for field as
upstream ROS 1 writes them, so that the classes have upstream's md5sums and real ROS
nodes talk to them. `ensure()` generates them once into a cache folder and puts it on
sys.path; `folder()` is where, for child processes' PYTHONPATH.
"""

from __future__ import annotations

import hashlib
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

GENPY = Path("/usr/lib/genpy")
DEBIAN_PYTHON = "/usr/bin/python3"
# Where Debian keeps the definitions the generated ones build on.
INCLUDES = {"std_msgs": "/usr/share/std_msgs/msg", "geometry_msgs": "/usr/share/geometry_msgs/msg"}


# The definitions, field for field as upstream ROS 1 has them (their comments left out:
# the md5sums depend only on the fields and constants).
DEFINITIONS = {
    "control_msgs/msg/JointControllerState.msg": (
        "Header header\n"
        "float64 set_point\n"
        "float64 process_value\n"
        "float64 process_value_dot\n"
        "float64 error\n"
        "float64 time_step\n"
        "float64 command\n"
        "float64 p\n"
        "float64 i\n"
        "float64 d\n"
        "float64 i_clamp\n"
        "bool antiwindup\n"
    ),
    "controller_manager_msgs/srv/LoadController.srv": (
        "string name\n"
        "---\n"
        "bool ok\n"
    ),
    "controller_manager_msgs/srv/SwitchController.srv": (
        "string[] start_controllers\n"
        "string[] stop_controllers\n"
        "int32 strictness\n"
        "int32 BEST_EFFORT=1\n"
        "int32 STRICT=2\n"
        "bool start_asap\n"
        "float64 timeout\n"
        "---\n"
        "bool ok\n"
    ),
    "controller_manager_msgs/srv/UnloadController.srv": (
        "string name\n"
        "---\n"
        "bool ok\n"
    ),
    "gazebo_msgs/srv/ApplyJointEffort.srv": (
        "string joint_name\n"
        "float64 effort\n"
        "time start_time\n"
        "duration duration\n"
        "---\n"
        "bool success\n"
        "string status_message\n"
    ),
    "gazebo_msgs/srv/GetJointProperties.srv": (
        "string joint_name\n"
        "---\n"
        "uint8 REVOLUTE    = 0\n"
        "uint8 CONTINUOUS  = 1\n"
        "uint8 PRISMATIC   = 2\n"
        "uint8 FIXED       = 3\n"
        "uint8 BALL        = 4\n"
        "uint8 UNIVERSAL   = 5\n"
        "uint8 type\n"
        "float64[] damping\n"
        "float64[] position\n"
        "float64[] rate\n"
        "bool success\n"
        "string status_message\n"
    ),
    "gazebo_msgs/srv/JointRequest.srv": (
        "string joint_name\n"
        "---\n"
    ),
    "gazebo_msgs/srv/SpawnModel.srv": (
        "string model_name\n"
        "string model_xml\n"
        "string robot_namespace\n"
        "geometry_msgs/Pose initial_pose\n"
        "string reference_frame\n"
        "---\n"
        "bool success\n"
        "string status_message\n"
    ),
}


class MissingRos(Exception):
    """Debian's ROS 1 (genpy, the message definitions) is not installed."""


# Set by sw2sim.ros.run.environment() for the nodes it starts: the folder the caller
# generated, so that a node whose HOME differs (a test's, a reader's `sudo`) finds the
# classes instead of generating them again at every start.
FOLDER_VARIABLE = "SW2SIM_ROS_MESSAGES"


def folder() -> Path:
    """The cache folder of the generated classes, named by the definitions' hash."""
    digest = hashlib.sha256(repr(sorted(DEFINITIONS.items())).encode()).hexdigest()[:12]
    name = f"ros-messages-{digest}"
    given = Path(os.environ.get(FOLDER_VARIABLE) or "/nonexistent")
    if given.name == name and (given / ".done").is_file():
        return given
    base = Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache")
    return base / "sw2sim" / name


def ensure() -> Path:
    """Generate the classes unless the cache holds them; put the folder on sys.path."""
    out = folder()
    if not (out / ".done").is_file():
        # Generated aside and renamed into place, so that processes starting together
        # never read a half-written folder.
        out.parent.mkdir(parents=True, exist_ok=True)
        scratch = Path(tempfile.mkdtemp(prefix=out.name + "-", dir=out.parent))
        _generate(scratch)
        try:
            scratch.rename(out)
        except OSError:   # another process was first
            shutil.rmtree(scratch, ignore_errors=True)
    if str(out) not in sys.path:
        sys.path.insert(0, str(out))
    return out


def _generate(out: Path) -> None:
    if not (GENPY / "genmsg_py.py").is_file():
        raise MissingRos("genpy is not installed (Debian: python3-genpy, python3-genmsg)")
    source = out / "definitions"
    for name, text in DEFINITIONS.items():
        (source / name).parent.mkdir(parents=True, exist_ok=True)
        (source / name).write_text(text, encoding="utf-8")
    packages = sorted({name.split("/")[0] for name in DEFINITIONS})
    includes = [f"-I{name}:{path}" for name, path in INCLUDES.items()]
    includes += [f"-I{package}:{source / package / 'msg'}" for package in packages]
    for package in packages:
        (out / package).mkdir(parents=True, exist_ok=True)
        (out / package / "__init__.py").write_text("", encoding="utf-8")
        for kind, tool in (("msg", "genmsg_py.py"), ("srv", "gensrv_py.py")):
            files = sorted((source / package / kind).glob(f"*.{kind}"))
            if not files:
                continue
            target = out / package / kind
            subprocess.run([DEBIAN_PYTHON, str(GENPY / tool), "-p", package, *includes,
                            "-o", str(target), *map(str, files)], check=True,
                           capture_output=True)
            subprocess.run([DEBIAN_PYTHON, str(GENPY / tool), "--initpy", "-p", package,
                            "-o", str(target)], check=True, capture_output=True)
    (out / ".done").write_text("generated by sw2sim.ros.messages\n", encoding="utf-8")
