"""What a terminal needs so that ROS 1's own commands use sw2sim's stand-in for Gazebo:
`sw2sim ros-env [FOLDER ...]` prints it as shell lines, for `eval "$(sw2sim ros-env)"`.

Debian 12 ships ROS 1 but neither Gazebo nor the message packages its interfaces use
(gazebo_msgs, control_msgs, controller_manager_msgs). Without these lines, a second
terminal's `rostopic echo .../state` cannot load control_msgs/JointControllerState, and
`rosservice call /gazebo/apply_joint_effort` cannot load gazebo_msgs/ApplyJointEffort.

- PYTHONPATH gets the generated message classes (sw2sim.ros.messages), which Debian's
  `rostopic`, `rosservice` and rospy nodes import like any installed ones;
- ROS_PACKAGE_PATH gets the FOLDERs (packages, or folders holding packages) and the
  stand-in packages (sw2sim.ros.packages: `gazebo_ros`, `controller_manager`, `tf`,
  `joint_state_publisher_gui`), so that a package's `roslaunch PKG gazebo.launch` runs
  with MuJoCo where gzserver would be, and its display.launch with a slider window;
- CMAKE_PREFIX_PATH gets the stand-ins' prefix, a folder laid out as an installed catkin
  workspace (a `.catkin` file and `share/`): a workspace built with it there keeps the
  stand-ins on ROS_PACKAGE_PATH when its `devel/setup.bash` is sourced, as Gazebo's stay
  for a Noetic user, whose workspace was built over /opt/ros/noetic. Sourcing it sets
  ROS_PACKAGE_PATH afresh from the catkin workspaces on CMAKE_PREFIX_PATH (Debian's
  /etc/catkin/profile.d/1.ros_package_path.sh, from ros_environment), and Debian's own
  packages in /usr/share are in none: the prefix's environment hook (DEBIAN_HOOK, which
  catkin's setup runs after that one) puts /usr/share back at the end;
- SW2SIM_PYTHON is the Python the stand-in nodes run on (the one running this), so they
  work in a terminal where the course's environment is not active;
- ROS_IP is 127.0.0.1 unless ROS_IP or ROS_HOSTNAME is set: ROS stays on this machine.

Every value is computed from the terminal's own, so running the line twice adds nothing.
"""

from __future__ import annotations

import os
import shlex
import sys
from pathlib import Path

STANDIN_PREFIX = "ros-prefix"   # folder name beside the generated messages
DEBIAN_PACKAGES = "/usr/share"  # where Debian's ROS packages are, when ROS_PACKAGE_PATH is unset
# A catkin environment hook of the prefix: a sourced workspace's setup runs it after it has
# set ROS_PACKAGE_PATH from the workspaces alone.
DEBIAN_HOOK = "etc/catkin/profile.d/50.sw2sim_debian_packages.sh"
HOOK_TEXT = f"""\
# Written by sw2sim ros-env: Debian's ROS packages ({DEBIAN_PACKAGES}) stay on ROS_PACKAGE_PATH.
case ":$ROS_PACKAGE_PATH:" in
  *:{DEBIAN_PACKAGES}:*) ;;
  *) export ROS_PACKAGE_PATH="${{ROS_PACKAGE_PATH:+$ROS_PACKAGE_PATH:}}{DEBIAN_PACKAGES}" ;;
esac
"""


def prefix() -> Path:
    """The stand-ins' catkin prefix, written (once per content) beside the message classes."""
    from . import messages, packages
    generated = messages.ensure()
    root = generated.parent / STANDIN_PREFIX
    packages.write(root / "share")
    marker = root / ".catkin"
    # Empty: an installed workspace's marker. (Naming folders in it would make them the
    # prefix's source folders, and roslaunch would then look for Debian's nodes, such as
    # rostopic, in this prefix alone, and not find them.)
    if not marker.is_file() or marker.read_text(encoding="utf-8"):
        marker.write_text("", encoding="utf-8")
    hook = root / DEBIAN_HOOK
    if not hook.is_file() or hook.read_text(encoding="utf-8") != HOOK_TEXT:
        hook.parent.mkdir(parents=True, exist_ok=True)
        hook.write_text(HOOK_TEXT, encoding="utf-8")
    return root


def _joined(first: list[str], present: str | None, last: list[str] = ()) -> str:
    """`first`, then the entries of `present`, then `last`, each once, in that order."""
    found: list[str] = []
    for entry in [*first, *(present or "").split(os.pathsep), *last]:
        if entry and entry not in found:
            found.append(entry)
    return os.pathsep.join(found)


def variables(folders: list[Path] = (), environ: dict[str, str] | None = None) -> dict[str, str]:
    """The variables to set, from the environment `environ` (this process's by default)."""
    from . import messages
    environ = dict(os.environ if environ is None else environ)
    root = prefix()
    generated = messages.folder()
    share = str(root / "share")
    # Where the stand-ins were before (an earlier sw2sim's prefix) is dropped by its name.
    packages = [p for p in (environ.get("ROS_PACKAGE_PATH") or DEBIAN_PACKAGES).split(os.pathsep)
                if p and not p.endswith(f"{STANDIN_PREFIX}{os.sep}share")]
    if DEBIAN_PACKAGES not in packages:
        packages.append(DEBIAN_PACKAGES)
    found = {
        "ROS_PACKAGE_PATH": _joined([str(Path(f).resolve()) for f in folders],
                                    os.pathsep.join(packages), [share]),
        "CMAKE_PREFIX_PATH": _joined([str(root)], environ.get("CMAKE_PREFIX_PATH")),
        "PYTHONPATH": _joined([str(generated)], environ.get("PYTHONPATH")),
        messages.FOLDER_VARIABLE: str(generated),
        "SW2SIM_PYTHON": sys.executable,
    }
    if not environ.get("ROS_IP") and not environ.get("ROS_HOSTNAME"):
        found["ROS_IP"] = "127.0.0.1"
    return found


def exports(found: dict[str, str]) -> str:
    """Shell lines that set `found`, for bash, zsh and sh."""
    return "".join(f"export {name}={shlex.quote(value)}\n" for name, value in found.items())


def main(folders: list[str], reason: str | None = None, say=print) -> int:
    """`sw2sim ros-env`: print the lines, or say what is missing (`reason`: ROS 1 itself,
    as sw2sim.ros.run.missing() says) on standard error, so that `eval` of an empty output
    changes nothing."""
    from .messages import MissingRos
    absent = [f for f in folders if not Path(f).is_dir()]
    if reason or absent:
        why = reason or f"{', '.join(absent)}: no such folder; give folders that hold packages"
        print(f"sw2sim ros-env: {why}", file=sys.stderr)
        return 2
    try:
        say(exports(variables([Path(f) for f in folders])), end="")
    except MissingRos as error:
        print(f"sw2sim ros-env: {error}", file=sys.stderr)
        return 2
    return 0
