"""Every lesson edit survives a student's re-export: the course's exporter writer exports
each lesson's robot again over a copy of its package (every hand edit gone, as the real
exporter leaves it), `sw2sim edits restore` runs on the saved copy in hand_edits/, and the
package is the lesson's again, file for file."""

import shutil
from pathlib import Path

import pytest

import sw2sim
from course.exporter_format import write_exported
from course.practices import PRACTICES, design, package_dir
from sw2sim import cli
from sw2sim.check import check


def files(folder: Path) -> dict[str, bytes]:
    return {p.relative_to(folder).as_posix(): p.read_bytes()
            for p in sorted(folder.rglob("*")) if p.is_file()}


@pytest.mark.parametrize("practice", PRACTICES)
def test_a_re_export_then_restore_gives_back_the_lesson_package(practice, tmp_path, capsys):
    lesson = package_dir(practice)
    copy = tmp_path / lesson.name
    shutil.copytree(lesson, copy)
    write_exported(design(practice).robot(), copy)
    lost = [rel for rel, data in files(copy).items() if data != files(lesson)[rel]]
    assert f"urdf/{lesson.name}.urdf" in lost and "launch/gazebo.launch" in lost, lost
    assert cli.main(["edits", "restore", str(copy)]) == 0
    said = capsys.readouterr().out
    assert "WARNING" not in said, said
    assert files(copy) == files(lesson), [rel for rel, data in files(copy).items()
                                          if data != files(lesson).get(rel)]


def test_the_restored_arm_compiles_and_checks_as_the_lesson_does(tmp_path):
    lesson = package_dir("practice_3")
    copy = tmp_path / lesson.name
    shutil.copytree(lesson, copy)
    write_exported(design("practice_3").robot(), copy)
    assert cli.main(["edits", "restore", str(copy)]) == 0
    model = sw2sim.load_package(copy, fixed_base=True).compile()
    assert model.nu == 0 and model.njnt == 2
    found = {f.rule for f in check(copy, stability=False).findings}
    assert found <= {f.rule for f in check(lesson, stability=False).findings}, found
