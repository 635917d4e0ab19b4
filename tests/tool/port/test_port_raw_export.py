"""A raw export copied into another repository: the exporter's urdf/, meshes/, launch/,
config/, export.log and CSV in a folder of another name, without package.xml (nor
CMakeLists.txt). Its package name is the one its own files say (the URDF's package://
paths, else export.log, else the CSV); port renames every mesh path to the new package in
one line, and check and convert read it without a mismatch. The colcon build of such a port
is in test_port_packages.py (its one build of every port)."""

from __future__ import annotations

import shutil
import sys
from pathlib import Path

from lxml import etree

import sw2sim
from sw2sim.check import check
from sw2sim.cli import main
from sw2sim.package import find_package
from sw2sim.package_name import from_files
from sw2sim.port import port

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "check"))
from exporter_packages import THREE_DOF_ARM, write_export  # noqa: E402  (tests/tool/check)


def raw_copy(export, folder: Path, renamed: str) -> Path:
    """`export` as the exporter writes it, moved to folder/renamed without package.xml and
    CMakeLists.txt: what a repository holding 'the robot's files' looks like."""
    written = write_export(export, folder / "export")
    (written / "package.xml").unlink()
    (written / "CMakeLists.txt").unlink()
    target = folder / "my_repo" / renamed
    target.parent.mkdir(parents=True)
    shutil.move(str(written), str(target))
    return target


def _meshes(urdf: Path) -> list[str]:
    return [m.get("filename") for m in etree.parse(str(urdf)).iter("mesh")]


def test_the_name_comes_from_the_mesh_paths_and_port_renames_them_in_one_line(tmp_path, capsys):
    src = raw_copy(THREE_DOF_ARM, tmp_path, "arm")
    package = find_package(src)
    assert package.name == "3_DOF_ARM_description"
    assert package.name_from == "the URDF's package:// mesh paths"
    out = tmp_path / "out"
    assert main(["port", str(src), "-o", str(out)]) == 0
    printed = capsys.readouterr().out
    assert "another package" not in printed
    lines = [line for line in printed.splitlines() if "mesh path(s)" in line]
    assert lines == ["  - 8 mesh path(s) now start with package://r3_dof_arm_description/ "
                     "(they named package://3_DOF_ARM_description/)."]
    assert "no package.xml: its name `3_DOF_ARM_description` was read from the URDF's" in printed
    urdf = out / "urdf" / "r3_dof_arm_description.urdf"
    meshes = _meshes(urdf)
    assert len(meshes) == 8
    for filename in meshes:
        assert filename.startswith("package://r3_dof_arm_description/meshes/"), filename
        assert (out / filename.split("/", 3)[3]).is_file(), filename
    assert etree.parse(str(out / "package.xml")).findtext("name") == "r3_dof_arm_description"
    # the ported package loads with every mesh, as MuJoCo reads package:// paths
    model = sw2sim.load_package(out).compile()
    assert model.nmesh == 4


def test_name_gives_the_paths_the_chosen_name(tmp_path):
    src = raw_copy(THREE_DOF_ARM, tmp_path, "arm")
    report = port(src, tmp_path / "out", name="arm")
    assert set(_meshes(tmp_path / "out" / "urdf" / "arm.urdf")) == {
        f"package://arm/meshes/{link.name}.STL" for link in THREE_DOF_ARM.links}
    assert sum("mesh path(s)" in c for c in report.choices) == 1


def test_check_and_convert_resolve_it_and_say_once_what_port_writes(tmp_path):
    src = raw_copy(THREE_DOF_ARM, tmp_path, "arm")
    report = check(src, stability=False)
    rules = [f.rule for f in report.findings]
    assert "package-name-mismatch" not in rules and report.status == 0
    (missing,) = [f for f in report.findings if f.rule == "package-xml-missing"]
    assert '"3_DOF_ARM_description" is taken from the URDF\'s package:// mesh paths' \
        in missing.message
    assert "sw2sim port" in missing.fix and '"r3_dof_arm_description"' in missing.fix
    assert main(["convert", str(src), "-o", str(tmp_path / "mjcf")]) == 0
    assert len(list((tmp_path / "mjcf").rglob("*.STL"))) == 4


def test_without_usable_mesh_paths_the_log_then_the_csv_then_the_folder_name(tmp_path):
    src = raw_copy(THREE_DOF_ARM, tmp_path, "arm")
    urdf = src / "urdf" / "3_DOF_ARM_description.urdf"
    assert from_files(src, None, urdf) == ("3_DOF_ARM_description", "the exporter's export.log")
    (src / "export.log").unlink()
    assert from_files(src, None, urdf) == (
        "3_DOF_ARM_description", "the exporter's urdf/3_DOF_ARM_description.csv")
    (src / "urdf" / "3_DOF_ARM_description.csv").unlink()
    assert from_files(src, None, urdf) == ("arm", "the folder's name")
    # mesh paths whose files are not here name another package, not this one
    shutil.rmtree(src / "meshes")
    assert find_package(src).name == "arm"
