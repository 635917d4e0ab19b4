"""CMakeLists.txt of an ament_cmake package that has nothing to compile: it installs its
folders into share/<name>, where `ros2 launch`, FindPackageShare and package:// look."""

from __future__ import annotations

INSTALLED = ("config", "launch", "meshes", "rviz", "urdf")


def cmakelists(name: str, folders: list[str]) -> str:
    """The file for package `name` installing those of INSTALLED that are in `folders`."""
    installed = [f for f in INSTALLED if f in folders]
    return "\n".join([
        "cmake_minimum_required(VERSION 3.8)",
        f"project({name} NONE)",
        "",
        "find_package(ament_cmake REQUIRED)",
        "",
        f"install(DIRECTORY {' '.join(installed)}",
        "  DESTINATION share/${PROJECT_NAME})",
        "",
        "ament_package()",
        ""])
