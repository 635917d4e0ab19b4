"""sw2sim port on every lesson package, Arm_Assembly and a raw exporter package (the exporter's
own 3-DOF arm, whose port gets the controllers of sw2sim.port.defaults), and the exporter's
four-wheeler copied without package.xml into a folder of another name: the ports
build with colcon (ament_cmake from PyPI), their URDFs load in MuJoCo and yourdfpy with
every mesh, and their launch files name only what Jazzy and the installed tree have.

The colcon build runs once, for all packages (test_colcon_build_installs_every_port).
"""

from __future__ import annotations

import ast
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
import trimesh
import yaml
from lxml import etree

import sw2sim
import ros2_environment
from repository import ROOT
from sw2sim.port import port

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "check"))
from exporter_packages import FOUR_WHEELER_NESTED, THREE_DOF_ARM, write_export  # noqa: E402
from test_port_raw_export import raw_copy  # noqa: E402

# colcon and ament_cmake from PyPI live in the ROS 2 environment (tests/ros2_environment.py)
VENV = ros2_environment.VENV
COLCON = shutil.which("colcon", path=str(VENV / "bin"))
JAZZY = json.loads((Path(__file__).with_name("jazzy_packages.json")).read_text())
WHEELS = "front_left_joint,front_right_joint,rear_left_joint,rear_right_joint"
# source -> (name of the port, options)
SOURCES = {"example_1": ("example_1", {"effort_joints": [WHEELS]}),
           "example_2": ("example_2", {}), "example_3": ("example_3", {}),
           "example_4": ("example_4", {}), "example_5": ("example_5", {}),
           "Arm_Assembly": ("arm_assembly", {}),
           THREE_DOF_ARM.name: ("r3_dof_arm_description", {}),
           # no package.xml, in my_repo/wheeler/: the name its mesh paths say, made legal
           "wheeler": ("r4_wheeler_nested_description", {})}


@pytest.fixture(scope="module")
def workspace(tmp_path_factory):
    """A colcon workspace whose src/ holds the port of every source."""
    top = tmp_path_factory.mktemp("port_ws")
    raw = write_export(THREE_DOF_ARM, top / "raw")
    raws = {THREE_DOF_ARM.name: raw, "wheeler": raw_copy(FOUR_WHEELER_NESTED, top, "wheeler")}
    finely_tessellated(raws["wheeler"] / "meshes" / "base_link.STL")
    reports = {}
    for source, (name, options) in SOURCES.items():
        folder = raws.get(source, ROOT / "examples" / source)
        reports[name] = port(folder, top / "src" / name, **options)
    return top, reports


def finely_tessellated(stl: Path) -> None:
    """The mesh with each triangle split in four until it has over 20,000 (the same shape):
    its port's <collision> names a simplified copy in meshes/simplified/."""
    mesh = trimesh.load(stl)
    while len(mesh.faces) <= 20_000:
        mesh = mesh.subdivide()
    mesh.export(stl)


def test_each_port_has_the_expected_name_and_files(workspace):
    top, reports = workspace
    for name, report in reports.items():
        assert report.name == name and report.package_dir == top / "src" / name
        for rel in ("package.xml", "CMakeLists.txt", "README.md", f"urdf/{name}.urdf",
                    "config/controllers.yaml", "launch/display.launch.py",
                    "launch/gazebo.launch.py"):
            assert (report.package_dir / rel).is_file(), (name, rel)
    assert any("r3_dof_arm_description" in c and "leading digit" in c
               for c in reports["r3_dof_arm_description"].choices)
    assert (reports["r4_wheeler_nested_description"].package_dir / "meshes" / "simplified"
            / "base_link.STL").is_file()
    assert reports["example_5"].controllers[0] == "joint_state_broadcaster"
    assert len(reports["example_5"].controllers) == 8


@pytest.fixture(scope="module")
def installed(workspace):
    """`colcon build` of every port, once; the install/ folder."""
    if COLCON is None or not (VENV / "share" / "ament_cmake").is_dir() and \
            not list(VENV.glob("lib/python3*/site-packages/ament_cmake")):
        pytest.skip(f"colcon or ament_cmake is not installed in {VENV} (requirements-ros2.txt; "
                    "the wheels exist for Linux only)")
    top, _ = workspace
    env = dict(os.environ, PATH=f"{VENV / 'bin'}{os.pathsep}{os.environ.get('PATH', '')}",
               AMENT_PREFIX_PATH=str(VENV), CMAKE_PREFIX_PATH=str(VENV))
    done = subprocess.run([COLCON, "--log-base", str(top / "log"), "build",
                           "--base-paths", str(top / "src"), "--build-base", str(top / "build"),
                           "--install-base", str(top / "install"),
                           # a package per core (colcon-parallel-executor)
                           "--executor", "parallel", "--parallel-workers", str(os.cpu_count() or 2)],
                          cwd=top, env=env, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stdout[-3000:] + done.stderr[-3000:]
    return top / "install"


def test_colcon_build_installs_every_port(workspace, installed):
    """COLCON: the one colcon build of all ports installs what the launch files read."""
    _, reports = workspace
    for name in reports:
        share = installed / name / "share" / name
        for folder in ("urdf", "meshes", "launch", "config"):
            assert (share / folder).is_dir(), (name, folder)
        assert (share / "urdf" / f"{name}.urdf").is_file()
        assert (share / "config" / "controllers.yaml").is_file()
        assert (installed / name / "share" / "ament_index" / "resource_index" / "packages"
                / name).is_file()

        meshes = sorted(p.relative_to(share).as_posix() for p in (share / "meshes").rglob("*"))
        assert meshes == sorted(p.relative_to(reports[name].package_dir).as_posix()
                                for p in (reports[name].package_dir / "meshes").rglob("*"))
        # every mesh path of the installed URDF resolves in the installed package
        for filename in _mesh_elements(share / "urdf" / f"{name}.urdf"):
            assert filename.startswith(f"package://{name}/"), (name, filename)
            assert (share / filename.split("/", 3)[3]).is_file(), (name, filename)
    # `source install/setup.bash`, as the pages have the reader type, finds every package
    # (colcon-bash writes the file; colcon-core alone writes only setup.sh)
    shown = subprocess.run(["bash", "-c", "source install/setup.bash && echo $AMENT_PREFIX_PATH"],
                           cwd=installed.parent, capture_output=True, text=True, timeout=60,
                           env={"PATH": os.environ["PATH"], "HOME": str(installed.parent)})
    assert shown.returncode == 0, shown.stderr
    prefixes = shown.stdout.strip().split(os.pathsep)
    assert all(str(installed / name) in prefixes for name in reports), prefixes
    # the exporter's arm, which has no controllers of its own, installs the one it was given
    arm = yaml.safe_load((installed / "r3_dof_arm_description" / "share" / "r3_dof_arm_description"
                          / "config" / "controllers.yaml").read_text())
    assert arm["joint_trajectory_controller"]["ros__parameters"]["joints"] == [
        "prox_joint", "dist_joint", "effector_joint"]


def _calls(tree: ast.AST) -> list[ast.Call]:
    return [n for n in ast.walk(tree) if isinstance(n, ast.Call)]


def _keyword(call: ast.Call, name: str):
    for k in call.keywords:
        if k.arg == name:
            return ast.literal_eval(k.value) if isinstance(k.value, ast.Constant) else k.value
    return None


def test_launch_files_compile_and_name_only_jazzy_packages_and_installed_files(workspace,
                                                                              installed):
    _, reports = workspace
    packages = JAZZY["packages"]
    for name in reports:
        share = installed / name / "share" / name
        for launch in ("display.launch.py", "gazebo.launch.py"):
            text = (share / "launch" / launch).read_text()
            compile(text, launch, "exec")
            tree = ast.parse(text)
            nodes = [c for c in _calls(tree) if getattr(c.func, "id", None) == "Node"]
            assert nodes, launch
            for node in nodes:
                pkg, exe = _keyword(node, "package"), _keyword(node, "executable")
                assert pkg in packages, (name, launch, pkg)
                assert exe in packages[pkg]["executables"], (name, launch, pkg, exe)
            # every file of this package it joins to the share folder exists once installed
            for call in _calls(tree):
                if getattr(call.func, "attr", None) == "join" and call.args and \
                        getattr(call.args[0], "id", None) == "share":
                    parts = [ast.literal_eval(a) for a in call.args[1:]]
                    assert share.joinpath(*parts).is_file(), (name, launch, parts)
                if getattr(call.func, "attr", None) == "join" and len(call.args) == 4 and \
                        isinstance(call.args[0], ast.Call):
                    owner = ast.literal_eval(call.args[0].args[0])
                    rel = "/".join(ast.literal_eval(a) for a in call.args[1:])
                    assert rel in JAZZY["launch_files"][owner], (owner, rel)
            shares = {ast.literal_eval(c.args[0]) for c in _calls(tree)
                      if getattr(c.func, "id", None) == "get_package_share_directory"
                      and isinstance(c.args[0], ast.Constant)}
            assert "PACKAGE" not in shares and shares <= set(packages), shares
            assert f'PACKAGE = "{name}"' in text
        xml = etree.parse(str(share / "package.xml")).getroot()
        depends = {d.text for d in xml.findall("exec_depend")}
        assert depends <= set(packages), depends - set(packages)
        config = (share / "config" / "controllers.yaml").read_text()
        manager = yaml.safe_load(config)["controller_manager"]["ros__parameters"]
        for controller, entry in manager.items():
            if controller != "update_rate":
                assert entry["type"] in JAZZY["controller_types"], entry["type"]
                assert entry["type"].split("/")[0] in depends


def _mesh_elements(urdf: Path) -> list[str]:
    return [m.get("filename") for m in etree.parse(str(urdf)).iter("mesh")]


def _empty(report, filename: str) -> bool:
    """A mesh file of an STL header and nothing else (Arm_Assembly's end_arm_link.STL, an
    exporter fault the port copies as it is, and reports)."""
    rel = filename.split("/", 3)[3]
    return (report.package_dir / rel).stat().st_size <= 84


def test_ported_urdfs_load_in_mujoco_with_every_mesh(workspace):
    import mujoco
    _, reports = workspace
    for name, report in reports.items():
        urdf = report.package_dir / "urdf" / f"{name}.urdf"
        meshes = set(_mesh_elements(urdf))
        if any(_empty(report, m) for m in meshes):
            # the source fails in MuJoCo on the same file, and the port says so
            with pytest.raises(sw2sim.LoadError, match="end_arm_link.STL"):
                sw2sim.load_package(ROOT / "examples" / "Arm_Assembly").compile()
            with pytest.raises(sw2sim.LoadError, match="end_arm_link.STL"):
                sw2sim.load_package(report.package_dir).compile()
            assert any("end_arm_link.STL" in c and "empty" in c for c in report.choices)
            continue
        model = sw2sim.load_package(report.package_dir).compile()
        assert model.nmesh == len(meshes) > 0, name
        data = mujoco.MjData(model)
        mujoco.mj_step(model, data)


def test_ported_urdfs_load_in_yourdfpy_with_every_mesh(workspace):
    yourdfpy = pytest.importorskip("yourdfpy")
    _, reports = workspace
    for name, report in reports.items():
        prefix = f"package://{name}/"

        def handler(fname, root=report.package_dir, prefix=prefix):
            assert fname.startswith(prefix), fname
            return str(root / fname[len(prefix):])

        urdf = report.package_dir / "urdf" / f"{name}.urdf"
        robot = yourdfpy.URDF.load(str(urdf), filename_handler=handler,
                                   build_collision_scene_graph=True, load_collision_meshes=True)
        visuals = [v.geometry.mesh.filename for link in robot.robot.links for v in link.visuals
                   if v.geometry.mesh is not None]
        collisions = [c.geometry.mesh.filename for link in robot.robot.links
                      for c in link.collisions if c.geometry.mesh is not None]
        assert len(visuals) + len(collisions) == len(_mesh_elements(urdf)), name
        for meshes, scene in ((visuals, robot.scene), (collisions, robot.collision_scene)):
            loaded = [g for g in scene.geometry.values() if len(g.faces)]
            assert len(loaded) == len([m for m in meshes if not _empty(report, m)]) > 0, name


def test_a_free_robot_is_spawned_on_the_ground_and_a_fixed_one_where_it_is(workspace):
    import mujoco
    from sw2sim.loader import lowest_collision_point
    from sw2sim.package import find_package
    _, reports = workspace
    free = 0
    for name, report in reports.items():
        tree = ast.parse((report.package_dir / "launch" / "gazebo.launch.py").read_text())
        (create,) = [c for c in _calls(tree) if getattr(c.func, "id", None) == "Node"
                     and _keyword(c, "executable") == "create"]
        arguments = [getattr(a, "value", None) for a in _keyword(create, "arguments").elts]
        package = find_package(report.package_dir)
        if package.world_fixed or any(_empty(report, m) for m in
                                      _mesh_elements(package.urdf)):
            assert "-z" not in arguments, name
            continue
        model = sw2sim.load_package(package).compile()
        data = mujoco.MjData(model)
        mujoco.mj_kinematics(model, data)
        low = lowest_collision_point(model, data)
        z = float(arguments[arguments.index("-z") + 1])
        assert 0 <= z + low < 2e-6, (name, z, low)
        assert any(f"z = {z:g} m" in c for c in report.choices), name
        free += 1
    assert free >= 2      # the exporter's arm and the renamed four-wheeler
