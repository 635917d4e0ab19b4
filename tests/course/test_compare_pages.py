"""Each practice's "Compare your export" section: the command for its own package, the
tolerances sw2sim compare really uses, and what it says of the exporter's raw output."""

from __future__ import annotations

import math
import re

import pytest

from repository import ROOT, practice_numbers
from sw2sim.compare import compare, tolerances

SECTION = "## Compare your export"


def compare_sections() -> dict[int, str]:
    """Practice number -> the text of its page's compare section."""
    found = {}
    for n in practice_numbers():
        for page in sorted((ROOT / "_pages" / f"practice-{n}").glob("*.md")):
            text = page.read_text(encoding="utf-8")
            if SECTION in text:
                body = text.split(SECTION, 1)[1]
                found[n] = body.split("\n## ", 1)[0]
    return found


def test_every_practice_tells_the_student_to_compare():
    assert sorted(compare_sections()) == practice_numbers()


@pytest.mark.parametrize("n", practice_numbers())
def test_the_section_compares_with_its_own_package_at_the_tools_tolerances(n):
    text = " ".join(compare_sections()[n].split())
    assert f"sw2sim compare my_export examples/example_{n}" in text
    assert f"{tolerances.MASS * 100:g} % of mass" in text
    assert f"{tolerances.INERTIA * 100:g} % of inertia" in text
    assert f"{tolerances.LENGTH * 1000:g} mm" in text
    assert f"{math.degrees(tolerances.ANGLE):g}°" in text


def test_practice_3_counts_what_the_raw_export_lacks():
    result = compare(ROOT / "examples" / "Arm_Assembly", ROOT / "examples" / "example_3")
    codes = sorted(d.code for d in result.differences)
    assert codes == ["limits-empty", "limits-empty", "mesh-empty", "world-missing"]
    assert result.status == 1
    words = {4: "Four"}
    assert re.search(rf"{words[len(codes)]} lines: no world link; the exporter's empty "
                     r"limits on both joints, .*; and the end arm's mesh with no triangles",
                     " ".join(compare_sections()[3].split()))
