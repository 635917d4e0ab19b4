"""hand-edits-unsaved: a package whose exporter-written files carry hand edits is warned
about until `sw2sim edits save` has copied them into hand_edits/, and again when the copy is
older than the edits; the lessons' packages ship theirs and stay quiet."""

import shutil
from pathlib import Path

from packages import copy_example, edit, urdf_of
from sw2sim import cli
from sw2sim.check import check


def unsaved(folder: Path) -> Path:
    package = copy_example(3, folder)
    shutil.rmtree(package / "hand_edits")
    return package


BATTERY = {"hand-edits-unsaved": unsaved}


def rules(package: Path) -> list:
    return [f for f in check(package, stability=False).findings if f.rule == "hand-edits-unsaved"]


def test_the_lessons_packages_ship_their_saved_edits():
    assert not rules(Path(__file__).resolve().parents[3] / "examples" / "example_3")


def test_unsaved_edits_are_named_with_the_save_command(tmp_path):
    package = unsaved(tmp_path)
    found = rules(package)
    assert len(found) == 1 and found[0].severity == "warning"
    assert "<transmission>" in found[0].message and "node controller_spawner" in found[0].message
    assert "catkin_install_python" in found[0].message
    assert f"sw2sim edits save {package}" in found[0].fix
    assert cli.main(["edits", "save", str(package)]) == 0
    assert not rules(package)


def test_an_edit_after_the_save_is_warned_about_again(tmp_path):
    package = copy_example(2, tmp_path)
    edit(urdf_of(package), 'friction="', 'friction="1')
    found = rules(package)
    assert len(found) == 1 and "holds an older copy" in found[0].message
    assert found[0].file.endswith("example_2.urdf")


def test_a_bare_export_is_not_warned_about(tmp_path):
    package = tmp_path / "Arm_Assembly"
    shutil.copytree(Path(__file__).resolve().parents[3] / "examples" / "Arm_Assembly", package)
    assert not rules(package)
