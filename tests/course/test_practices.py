"""Every practice the registry finds is whole, and a new one is found from its folders alone."""

import shutil

import pytest

import course.practices as registry
from course.practices import Practice, practices
from repository import ROOT


@pytest.mark.parametrize("practice", practices(), ids=lambda p: p.name)
def test_every_practice_has_all_its_parts(practice):
    assert practice.missing() == [], f"{practice.name} lacks: {practice.missing()}"


def test_the_registry_finds_the_practices_in_number_order():
    numbers = [p.number for p in practices()]
    assert numbers == sorted(numbers) and numbers[0] == 1
    folders = sorted(p.name for p in (ROOT / "course" / "practices").glob("practice_*") if p.is_dir())
    assert sorted(p.name for p in practices()) == folders


def test_a_practice_with_nothing_yet_is_told_what_each_part_is_and_where_it_goes():
    gaps = Practice("practice_99").missing()
    kinds = [gap.split(":")[0] for gap in gaps]
    assert kinds == ["design", "figures", "pages", "navigation", "tests"]
    assert "course/practices/practice_99/design.py" in gaps[0]
    assert "/practice-99/" in gaps[3] and "_data/navigation.yml" in gaps[3]


def test_a_new_folder_is_a_new_practice(tmp_path):
    # A copy of the practices folder with a sixth practice made from the fifth: found by
    # its folder, with no list to edit.
    here = tmp_path / "practices"
    shutil.copytree(ROOT / "course" / "practices", here, ignore=shutil.ignore_patterns("__pycache__"))
    shutil.copytree(here / "practice_5", here / "practice_6")
    assert registry.discover(here)[-2:] == ["practice_5", "practice_6"]
