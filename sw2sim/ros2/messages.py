"""The ROS 2 message packages PyPI lacks, built once with ROS 2's own generators.

PyPI has no wheels of tf2_msgs (robot_state_publisher's /tf), of control_msgs (the
controllers' state, the PID controller's reference and joint_trajectory_controller's
FollowJointTrajectory action) nor of controller_manager_msgs (the controller manager's
services). DEFINITIONS holds the messages, services and actions the stand-in uses,
field for field as upstream Jazzy has them (tf2_msgs 0.36, the jazzy branches of
control_msgs 5.x and ros2_control 4.x), so that the type names and type hashes are
upstream's and real ROS 2 nodes and tools exchange them with the stand-in.
The comments of upstream's files are left out: they do not enter the type hash.

`ensure()` builds the ament_cmake packages with rosidl (CMake from the `cmake` wheel,
the generators from the ros-jazzy wheels), with only the generators whose output rclpy
loads over Fast DDS (GENERATORS), and installs them into the running Python's
virtual environment: libraries into <venv>/lib, which the wheels' bootstrapper puts on
LD_LIBRARY_PATH, the Python modules into site-packages and the ament index into
<venv>/share, beside the wheels' own packages. A separate Python of the same environment
(an rclpy node that does not import sw2sim) then imports them as it imports std_msgs.
Outside a writable virtual environment they go to a cache folder instead, which
`environment()` adds to a process's paths.

    python -m sw2sim.ros2.messages     # build them if needed (half a minute once; then a no-op)
"""

from __future__ import annotations

import fcntl
import hashlib
import os
import shutil
import subprocess
import sys
import sysconfig
import tempfile
import time
from pathlib import Path

# package -> (dependencies, {file: text}); the text of each is upstream's fields in order.
DEFINITIONS: dict[str, tuple[tuple[str, ...], dict[str, str]]] = {
    "tf2_msgs": (("builtin_interfaces", "geometry_msgs"), {
        "msg/TFMessage.msg": "geometry_msgs/TransformStamped[] transforms\n",
    }),
    "control_msgs": (("action_msgs", "builtin_interfaces", "geometry_msgs", "std_msgs",
                      "trajectory_msgs"), {
        "msg/JointTrajectoryControllerState.msg": (
            "# joint_trajectory_controller's state, once per update\n"
            "std_msgs/Header header\n"
            "\n"
            "string[] joint_names\n"
            "trajectory_msgs/JointTrajectoryPoint reference\n"
            "trajectory_msgs/JointTrajectoryPoint feedback\n"
            "trajectory_msgs/JointTrajectoryPoint error\n"
            "trajectory_msgs/JointTrajectoryPoint output\n"
            "\n"
            "string[] multi_dof_joint_names\n"
            "trajectory_msgs/MultiDOFJointTrajectoryPoint multi_dof_reference\n"
            "trajectory_msgs/MultiDOFJointTrajectoryPoint multi_dof_feedback\n"
            "trajectory_msgs/MultiDOFJointTrajectoryPoint multi_dof_error\n"
            "trajectory_msgs/MultiDOFJointTrajectoryPoint multi_dof_output\n"
            "float64 speed_scaling_factor\n"
        ),
        "msg/MultiDOFCommand.msg": (
            "# a target per degree of freedom (pid_controller's ~/reference)\n"
            "string[] dof_names\n"
            "float64[] values\n"
            "float64[] values_dot\n"
        ),
        "msg/SingleDOFState.msg": (
            "# one degree of freedom of a controller's state\n"
            "string name\n"
            "float64 reference\n"
            "float64 feedback\n"
            "float64 feedback_dot\n"
            "float64 error\n"
            "float64 error_dot\n"
            "float64 time_step\n"
            "float64 output\n"
        ),
        "msg/SingleDOFStateStamped.msg": (
            "std_msgs/Header header\n"
            "SingleDOFState dof_state\n"
        ),
        "msg/MultiDOFStateStamped.msg": (
            "# pid_controller's ~/controller_state\n"
            "std_msgs/Header header\n"
            "SingleDOFState[] dof_states\n"
        ),
        "msg/JointTolerance.msg": (
            "# 0: the controller's default; -1: none\n"
            "string name\n"
            "float64 position\n"
            "float64 velocity\n"
            "float64 acceleration\n"
        ),
        "msg/JointComponentTolerance.msg": (
            "uint16 X_AXIS=1\n"
            "uint16 Y_AXIS=2\n"
            "uint16 Z_AXIS=3\n"
            "uint16 TRANSLATION=4\n"
            "uint16 ROTATION=5\n"
            "\n"
            "string joint_name\n"
            "uint16 component\n"
            "float64 position\n"
            "float64 velocity\n"
            "float64 acceleration\n"
        ),
        "action/FollowJointTrajectory.action": (
            "# joint_trajectory_controller's ~/follow_joint_trajectory\n"
            "trajectory_msgs/JointTrajectory trajectory\n"
            "trajectory_msgs/MultiDOFJointTrajectory multi_dof_trajectory\n"
            "JointTolerance[] path_tolerance\n"
            "JointComponentTolerance[] component_path_tolerance\n"
            "JointTolerance[] goal_tolerance\n"
            "JointComponentTolerance[] component_goal_tolerance\n"
            "builtin_interfaces/Duration goal_time_tolerance\n"
            "---\n"
            "int32 error_code\n"
            "int32 SUCCESSFUL = 0\n"
            "int32 INVALID_GOAL = -1\n"
            "int32 INVALID_JOINTS = -2\n"
            "int32 OLD_HEADER_TIMESTAMP = -3\n"
            "int32 PATH_TOLERANCE_VIOLATED = -4\n"
            "int32 GOAL_TOLERANCE_VIOLATED = -5\n"
            "string error_string\n"
            "---\n"
            "std_msgs/Header header\n"
            "string[] joint_names\n"
            "trajectory_msgs/JointTrajectoryPoint desired\n"
            "trajectory_msgs/JointTrajectoryPoint actual\n"
            "trajectory_msgs/JointTrajectoryPoint error\n"
            "string[] multi_dof_joint_names\n"
            "trajectory_msgs/MultiDOFJointTrajectoryPoint multi_dof_desired\n"
            "trajectory_msgs/MultiDOFJointTrajectoryPoint multi_dof_actual\n"
            "trajectory_msgs/MultiDOFJointTrajectoryPoint multi_dof_error\n"
        ),
    }),
}

# controller_manager_msgs (ros2_control 4.46.0, the jazzy branch): the services the
# controller manager serves here (sw2sim.ros2.manager), which `ros2 control ...` and the
# spawner call, and the messages they hold (not the ~/activity topic's messages nor
# set_hardware_component_state, which it does not offer: every interface costs build time).
_HARDWARE_INTERFACE = "string name\nstring data_type\nbool is_available\nbool is_claimed\n"
DEFINITIONS["controller_manager_msgs"] = (("builtin_interfaces", "lifecycle_msgs", "std_msgs"), {
    "msg/ChainConnection.msg": "string name\nstring[] reference_interfaces\n",
    "msg/ControllerState.msg": (
        "string name\n"
        "string state\n"
        "string type\n"
        "bool is_async\n"
        "uint16 update_rate\n"
        "string[] claimed_interfaces\n"
        "string[] required_command_interfaces\n"
        "string[] required_state_interfaces\n"
        "bool is_chainable\n"
        "bool is_chained\n"
        "string[] exported_state_interfaces\n"
        "string[] reference_interfaces\n"
        "ChainConnection[] chain_connections\n"
    ),
    "msg/HardwareInterface.msg": _HARDWARE_INTERFACE,
    "msg/HardwareComponentState.msg": (
        "string name\n"
        "string type\n"
        "bool is_async\n"
        "uint16 rw_rate\n"
        "string class_type\n"
        "string plugin_name\n"
        "lifecycle_msgs/State state\n"
        "HardwareInterface[] command_interfaces\n"
        "HardwareInterface[] state_interfaces\n"
    ),
    "srv/CleanupController.srv": "string name\n---\nbool ok\n",
    "srv/ConfigureController.srv": "string name\n---\nbool ok\n",
    "srv/ListControllerTypes.srv": "---\nstring[] types\nstring[] base_classes\n",
    "srv/ListControllers.srv": "---\ncontroller_manager_msgs/ControllerState[] controller\n",
    "srv/ListHardwareComponents.srv": "---\nHardwareComponentState[] component\n",
    "srv/ListHardwareInterfaces.srv": (
        "---\nHardwareInterface[] command_interfaces\nHardwareInterface[] state_interfaces\n"),
    "srv/LoadController.srv": "string name\n---\nbool ok\n",
    "srv/ReloadControllerLibraries.srv": "bool force_kill\n---\nbool ok\n",
    "srv/SwitchController.srv": (
        "string[] activate_controllers\n"
        "string[] deactivate_controllers\n"
        "int32 strictness\n"
        "int32 BEST_EFFORT=1\n"
        "int32 STRICT=2\n"
        "int32 AUTO=3\n"
        "int32 FORCE_AUTO=4\n"
        "bool activate_asap\n"
        "builtin_interfaces/Duration timeout\n"
        "---\n"
        "bool ok\n"
        "string message\n"
    ),
    "srv/UnloadController.srv": "string name\n---\nbool ok\n",
})

VERSIONS = {"tf2_msgs": "0.36.4", "control_msgs": "5.8.0",   # upstream's, for package.xml
            "controller_manager_msgs": "4.46.0"}
PYPI_HINT = 'pip install "sw2sim[ros2]"'

# The generators run, in this order: what rclpy over rmw_fastrtps_cpp, the one RMW PyPI
# has, loads of a message package. rclpy imports <package>_s__rosidl_typesupport_c
# (rosidl_generator_py), whose handle dispatches by typesupport (rosidl_typesupport_c);
# rmw_fastrtps_cpp asks it for rosidl_typesupport_fastrtps_c to (de)serialize and for
# rosidl_typesupport_introspection_c to register the type's XTypes type object (each C++
# counterpart only where the C one is missing); the type hash and description come from
# rosidl_generator_c's code, made from the type description generator's JSON.
# rosidl_default_generators adds the C++ headers and typesupports, which nothing here
# loads (PyPI has no rclcpp), at more than twice the build time.
GENERATORS = ("rosidl_generator_type_description", "rosidl_generator_c",
              "rosidl_typesupport_fastrtps_c", "rosidl_typesupport_introspection_c",
              "rosidl_typesupport_c", "rosidl_generator_py")


class MessagesError(RuntimeError):
    """The message packages could not be built (the reason, with the build's last lines)."""


def digest() -> str:
    """Of every file the packages are built from: a change to one builds them again."""
    files = [(name, sorted(package_files(name).items())) for name in DEFINITIONS]
    return hashlib.sha256(repr(files).encode()).hexdigest()[:12]


def _in_writable_venv() -> bool:
    return sys.prefix != sys.base_prefix and os.access(Path(sys.prefix) / "lib", os.W_OK)


def prefix() -> Path:
    """Where the packages are installed: this virtual environment, or a cache folder."""
    if _in_writable_venv():
        return Path(sys.prefix)
    base = Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache")
    return base / "sw2sim" / f"ros2-messages-{digest()}"


def _marker(where: Path) -> Path:
    return where / "share" / "sw2sim_ros2_messages" / f"{digest()}.done"


def site_packages(where: Path) -> Path:
    """Where ament_cmake_python installs Python modules below a prefix."""
    if where == Path(sys.prefix):
        return Path(sysconfig.get_paths()["purelib"])
    return where / "lib" / f"python{sys.version_info.major}.{sys.version_info.minor}" / "site-packages"


def ready() -> bool:
    return _marker(prefix()).is_file()


def environment(env: dict[str, str] | None = None) -> dict[str, str]:
    """`env` (default os.environ) with the paths a process needs to load the packages
    (nothing to add inside the virtual environment, where they sit with the wheels)."""
    env = dict(os.environ if env is None else env)
    where = prefix()
    if where == Path(sys.prefix):
        return env
    for name, path in (("LD_LIBRARY_PATH", where / "lib"), ("PYTHONPATH", site_packages(where)),
                       ("AMENT_PREFIX_PATH", where)):
        parts = [p for p in env.get(name, "").split(os.pathsep) if p]
        if str(path) not in parts:
            env[name] = os.pathsep.join([str(path), *parts])
    return env


def ensure(say=None) -> Path:
    """Build and install the packages unless done; return the prefix. `say` gets one line
    before a build starts."""
    where = prefix()
    if _marker(where).is_file():
        return where
    lock_dir = Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache") / "sw2sim"
    lock_dir.mkdir(parents=True, exist_ok=True)
    with open(lock_dir / "ros2-messages.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)   # one build at a time; the others wait for it
        if _marker(where).is_file():
            return where
        if say:
            say(f"sw2sim ros2: building the {', '.join(DEFINITIONS)} message packages into "
                f"{where} (once, about half a minute)")
        began = time.monotonic()
        with tempfile.TemporaryDirectory(prefix="sw2sim-ros2-messages-") as scratch:
            _build_all(Path(scratch), where)
        _marker(where).parent.mkdir(parents=True, exist_ok=True)
        _marker(where).write_text(f"built in {time.monotonic() - began:.0f} s\n", encoding="utf-8")
    return where


def write_package(name: str, folder: Path) -> None:
    """The ament_cmake package `name` in `folder`: package.xml, CMakeLists.txt, msg/."""
    for file, text in package_files(name).items():
        (folder / file).parent.mkdir(parents=True, exist_ok=True)
        (folder / file).write_text(text, encoding="utf-8")


def package_files(name: str) -> dict[str, str]:
    """The files of the ament_cmake package `name`, by path in its folder."""
    depends, files = DEFINITIONS[name]
    depend_lines = "".join(f"  <depend>{d}</depend>\n" for d in depends)
    generator_lines = "".join(f"  <buildtool_depend>{g}</buildtool_depend>\n"
                              for g in GENERATORS)
    package_xml = (
        '<?xml version="1.0"?>\n<package format="3">\n'
        f"  <name>{name}</name>\n  <version>{VERSIONS[name]}</version>\n"
        f"  <description>The {name} messages sw2sim ros2 uses, as upstream defines them"
        "</description>\n"
        '  <maintainer email="sw2sim@example.com">sw2sim</maintainer>\n'
        "  <license>BSD-3-Clause</license>\n"
        "  <buildtool_depend>ament_cmake</buildtool_depend>\n"
        f"{generator_lines}"
        f"{depend_lines}"
        "  <exec_depend>rosidl_default_runtime</exec_depend>\n"
        "  <member_of_group>rosidl_interface_packages</member_of_group>\n"
        "  <export><build_type>ament_cmake</build_type></export>\n"
        "</package>\n")
    finds = "".join(f"find_package({d} REQUIRED)\n" for d in depends)
    # The wheels' CMake exports name the include folder of the machine that built them
    # on their Python targets (for every package find_package brought in, dependencies
    # of dependencies too); CMake refuses a missing folder, so point them at ours.
    fixes = (
        "get_property(imported DIRECTORY PROPERTY IMPORTED_TARGETS)\n"
        "foreach(target ${imported})\n"
        "  if(target MATCHES \"__rosidl_generator_py$\")\n"
        "    set_target_properties(${target} PROPERTIES\n"
        "      INTERFACE_INCLUDE_DIRECTORIES \"${Python3_INCLUDE_DIRS}\")\n"
        "  endif()\n"
        "endforeach()\n")
    interfaces = " ".join(f'"{f}"' for f in files)
    cmake_lists = (
        "cmake_minimum_required(VERSION 3.16)\n"
        f"project({name})\n"
        "find_package(ament_cmake REQUIRED)\n"
        "find_package(rosidl_cmake REQUIRED)\n"
        f"set(STATIC_ROSIDL_TYPESUPPORT_C {';'.join(GENERATORS[2:4])})\n"
        f"foreach(generator {' '.join(GENERATORS)})\n"
        "  find_package(${generator} REQUIRED)\n"
        "endforeach()\n"
        f"{finds}"
        "find_package(Python3 REQUIRED COMPONENTS Interpreter Development)\n"
        f"{fixes}"
        # the dependencies' packages may bring other generators in: only these run
        "list(FILTER AMENT_EXTENSIONS_rosidl_generate_idl_interfaces INCLUDE REGEX\n"
        f'  "^({"|".join(GENERATORS)}):")\n'
        f"rosidl_generate_interfaces(${{PROJECT_NAME}} {interfaces}\n"
        f"  DEPENDENCIES {' '.join(depends)})\n"
        # Each library's generated files compiled as one unit, which reads the headers
        # (Fast CDR's C++ ones above all) once instead of once a file; but the type
        # descriptions, which all define the same static names.
        f"foreach(library {' '.join(GENERATORS[1:])})\n"
        "  set_target_properties(${PROJECT_NAME}__${library} PROPERTIES\n"
        "    UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE 0)\n"
        "endforeach()\n"
        "get_target_property(sources ${PROJECT_NAME}__rosidl_generator_c SOURCES)\n"
        'list(FILTER sources INCLUDE REGEX "__description[.]c$")\n'
        "set_source_files_properties(${sources} PROPERTIES SKIP_UNITY_BUILD_INCLUSION ON)\n"
        "ament_export_dependencies(rosidl_default_runtime)\n"
        "ament_package()\n")
    return {**files, "package.xml": package_xml, "CMakeLists.txt": cmake_lists}


def _build_all(scratch: Path, where: Path) -> None:
    venv = Path(sys.prefix)
    env = dict(os.environ)
    env["PATH"] = os.pathsep.join([str(venv / "bin"), env.get("PATH", "")])
    for name in ("AMENT_PREFIX_PATH", "CMAKE_PREFIX_PATH"):
        env[name] = os.pathsep.join(p for p in [str(venv), env.get(name)] if p)
    env["LD_LIBRARY_PATH"] = os.pathsep.join(
        p for p in [str(venv / "lib"), env.get("LD_LIBRARY_PATH")] if p)
    cmake = shutil.which("cmake", path=env["PATH"])
    if cmake is None:
        raise MessagesError(f"cmake is not installed ({PYPI_HINT} brings it)")
    jobs = str(max(1, os.cpu_count() or 1))
    running = []
    for name in DEFINITIONS:
        source, build = scratch / name, scratch / f"build-{name}"
        write_package(name, source)
        log = open(scratch / f"{name}.log", "w")
        command = " && ".join([
            f'"{cmake}" -S "{source}" -B "{build}" -DCMAKE_BUILD_TYPE=Release '
            f'-DCMAKE_INSTALL_PREFIX="{where}" -DPython3_EXECUTABLE="{sys.executable}" '
            f'-DPYTHON_EXECUTABLE="{sys.executable}" -DBUILD_TESTING=OFF '
            f'-DPYTHON_INSTALL_DIR="{site_packages(where).relative_to(where)}"',
            f'"{cmake}" --build "{build}" -j {jobs}',
            f'"{cmake}" --install "{build}"'])
        # The packages are independent: built side by side.
        running.append((name, log, subprocess.Popen(command, shell=True, env=env, stdout=log,
                                                    stderr=subprocess.STDOUT)))
    failed = []
    for name, log, process in running:
        process.wait()
        log.close()
        if process.returncode:
            tail = (scratch / f"{name}.log").read_text(errors="replace").splitlines()[-15:]
            failed.append(f"{name}:\n" + "\n".join(tail))
    if failed:
        raise MessagesError("building the message packages failed:\n" + "\n".join(failed))


def main() -> int:
    began = time.monotonic()
    try:
        import rclpy  # noqa: F401
    except ImportError:
        print(f"sw2sim ros2: rclpy is not installed ({PYPI_HINT} or `make setup`); "
              "nothing to build", file=sys.stderr)
        return 2
    try:
        where = ensure(say=lambda text: print(text, flush=True))
    except MessagesError as exc:
        print(f"sw2sim ros2: {exc}", file=sys.stderr)
        return 1
    print(f"sw2sim ros2: {', '.join(DEFINITIONS)} are in {where} "
          f"({time.monotonic() - began:.1f} s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
