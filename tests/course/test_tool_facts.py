"""What the pages say about SolidWorks and the exporter, checked where it can be: the masses
SolidWorks shows (from the designs' exact solids), catkin's verdict on package names, what
makes up a link's mass, and the names the exporter's dialogs give their fields.
"""

from __future__ import annotations

import json
import math
import re
import shutil
import subprocess

import pytest
import yourdfpy
from exact_solids import exact_mass
from page_text import flat_page as flat

from course.parts import Part
from course.practices import ROOT, design

PAGES = ROOT / "_pages"


# ---- masses: SolidWorks weighs the exact solid, the script the 96-facet mesh ---------------

# For each modelling page: the parts it names in "should show", by the words before the mass.
SHOWN = {
    1: {"wheel": "wheel", "base": "base"},
    2: {"wheel": "wheel", "base": "base"},
    3: {"base": "base", "middle arm": "middle_arm", "end arm": "end_arm"},
    4: {"bar with end plates": "bar", "block": "block"},
    5: {"chassis": "chassis", "steering knuckle": "knuckle", "wheel": "wheel",
        "centre steering link": "steering_link"},
}


def parts():
    return [(n, part) for n in SHOWN for part in design(f"practice_{n}").parts()]


@pytest.mark.parametrize("practice", sorted(SHOWN))
def test_modelling_pages_give_the_exact_solids_mass_as_solidworks_shows_it(practice):
    text = flat(f"practice-{practice}/01-modelling.md")
    shown = text[text.index("should show"):]
    module = design(f"practice_{practice}")
    for words, factory in SHOWN[practice].items():
        mass = exact_mass(getattr(module, factory)())
        assert re.search(rf"\b{words} {mass:.3f} kg", shown), (words, f"{mass:.3f}")


def test_the_car_and_practice_2s_comparison_use_the_exact_masses():
    p5 = design("practice_5")
    car = sum(exact_mass(p) for p in (p5.chassis(), p5.steering_link())) \
        + 2 * exact_mass(p5.knuckle()) + 4 * exact_mass(p5.wheel())
    assert f"the car weighs {car:.3f} kg" in flat("practice-5/01-modelling.md")
    p1, p2 = design("practice_1"), design("practice_2")
    old, new = exact_mass(p1.base()), exact_mass(p2.base())
    assert new > old and f"Practice 1's {old:.3f} kg" in flat("practice-2/01-modelling.md")


def test_the_exact_masses_are_those_of_a_very_fine_mesh():
    """The sum in exact_solids counts every overlap of these parts once: a mesh of 1024
    facets per circle (0.0006 % short of a cylinder) weighs the same to 0.003 %."""
    for practice, part in parts():
        fine = Part(part.name, part.material, part.features, sections=1024)
        assert fine.mass == pytest.approx(exact_mass(part), rel=3e-5), (practice, part.title)


def test_the_mesh_differs_from_the_solid_by_less_than_a_tenth_of_a_percent():
    text = flat("practice-1/01-modelling.md")
    facets = Part.__dataclass_fields__["sections"].default
    assert facets == 96 and "a prism of 96 flat facets" in text
    # an inscribed 96-gon has sin(2π/n) / (2π/n) of the circle's area
    short = 1 - math.sin(2 * math.pi / facets) / (2 * math.pi / facets)
    assert f"({short:.2%} of the cylinder's volume)".replace("%", " %") in text
    worst = max(abs(p.mass / exact_mass(p) - 1) for _, p in parts())
    assert worst < 0.001 and "differ by less than 0.1 %" in text


def test_practice_1_says_what_the_script_prints_and_what_solidworks_shows():
    text = flat("practice-1/01-modelling.md")
    p1 = design("practice_1")
    wheel, base = p1.wheel(), p1.base()
    assert f"The script weighs the STL meshes: wheel {wheel.mass:.3f} kg, base {base.mass:.3f} kg" in text
    assert f"{base.mass:.3f}" == f"{exact_mass(base):.3f}", "the base: the same to three decimals"
    grams = (exact_mass(wheel) - wheel.mass) * 1000
    assert round(grams) == 2 and "about 2 g light" in text
    assert "look first at the material" in text and "2.7 times too light" in text
    assert p1.ALUMINIUM.density / 1000 == 2.7


def test_the_lesson_package_carries_the_meshes_masses_an_export_the_exact_ones():
    p1 = design("practice_1")
    robot = yourdfpy.URDF.load(str(ROOT / "examples/example_1/urdf/example_1.urdf"), load_meshes=False)
    urdf_wheel = robot.link_map["front_left_wheel"].inertial.mass
    wheel = p1.wheel()
    assert urdf_wheel == pytest.approx(wheel.mass, rel=1e-9) and urdf_wheel < exact_mass(wheel)
    text = flat("practice-1/01-modelling.md")
    assert f"carries SolidWorks' exact values, {exact_mass(wheel):.3f} kg for each wheel" in text
    assert f"carries their values, {urdf_wheel:.3f} kg" in text


def test_practice_4s_block_mesh_is_heavier_its_bar_lighter():
    p4 = design("practice_4")
    bar, block = p4.bar(), p4.block()
    assert bar.mass < exact_mass(bar) and 0 < (block.mass - exact_mass(block)) * 1000 < 1
    text = flat("practice-4/01-modelling.md")
    assert f"prints {bar.mass:.3f} kg for the bar" in text
    assert "a fraction of a gram heavier" in text


def test_every_script_value_a_modelling_page_quotes_is_the_mesh_mass():
    quoted = {1: [("wheel", "wheel")], 2: [("wheel", "wheel")], 3: [("middle_arm", "middle arm")],
              4: [("bar", "bar")], 5: [("wheel", "wheel")]}
    for practice, items in quoted.items():
        module = design(f"practice_{practice}")
        text = flat(f"practice-{practice}/01-modelling.md")
        for factory, words in items:
            part = getattr(module, factory)()
            assert f"{part.mass:.3f}" != f"{exact_mass(part):.3f}"
            assert f"{part.mass:.3f} kg" in text and f"{exact_mass(part):.3f} kg" in text


# ---- package names: catkin warns about capitals, it does not refuse them -------------------

CATKIN_CHECK = """
import json, sys
from catkin_pkg.package import InvalidPackage, Package, Person
result = {}
for name in sys.argv[1:]:
    package = Package(name=name, version="0.0.0", package_format=2, description="-",
                      maintainers=[Person("A", "a@example.com")], licenses=["BSD"])
    warnings = []
    try:
        package.validate(warnings=warnings)
        result[name] = ["warns" if warnings else "accepts", warnings]
    except InvalidPackage as exc:
        result[name] = ["refuses", [str(exc)]]
print(json.dumps(result))
"""


def catkin_verdicts(*names: str) -> dict:
    """What catkin_pkg (the package reader of catkin and roslaunch) says of each name."""
    for python in ("/usr/bin/python3", shutil.which("python3")):
        if python and subprocess.run([python, "-c", "import catkin_pkg"],
                                     capture_output=True).returncode == 0:
            out = subprocess.run([python, "-c", CATKIN_CHECK, *names], capture_output=True,
                                 text=True, check=True).stdout
            return json.loads(out)
    pytest.skip("catkin_pkg is not installed (Debian: python3-catkin-pkg)")


def test_catkin_warns_about_capitals_and_refuses_a_space():
    verdicts = catkin_verdicts("example_1", "Example_1", "Example 1", "example.1")
    assert verdicts["example_1"][0] == "accepts"
    assert verdicts["Example_1"][0] == "warns"
    assert "does not follow the naming conventions" in verdicts["Example_1"][1][0]
    assert verdicts["Example 1"][0] == verdicts["example.1"][0] == "refuses"


@pytest.mark.parametrize("path", ["practice-1/02-exporting.md", "reference/02-exporter.md"])
def test_the_pages_say_catkin_warns_about_capitals(path):
    text = flat(path)
    assert not re.search(r"refuses (capitals|package names with capitals)", text)
    assert re.search(r"catkin (still )?accepts capital", text) and "warns" in text
    assert "a space or a dot" in text and "PR #84" in text


def test_the_checker_and_its_page_agree_a_capital_is_a_warning():
    rules = {rule["id"]: rule for group in json.loads((ROOT / "_data/check_rules.json").read_text())["groups"]
             for rule in group["rules"]}
    assert rules["package-name-style"]["severity"] == "warning"
    assert "catkin builds the package but warns" in rules["package-name-style"]["symptom"]
    assert "a warning" in flat("reference/03-your-own-model.md").split("package-name-style")[1][:40]


# ---- what counts towards a link's mass ------------------------------------------------------

EXPORT_PAGES = ["practice-1/02-exporting.md", "reference/02-exporter.md"]


@pytest.mark.parametrize("path", EXPORT_PAGES)
def test_hidden_and_suppressed_parts_are_described_as_they_behave(path):
    """The exporter weighs the solid bodies of the picked components (SW2URDF's
    ExportHelperExtension.GetBodies and MassProperty.AddBodies); SolidWorks leaves
    suppressed components out of mass properties; #101 is about hidden parts not picked."""
    text = flat(path)
    assert not re.search(r"hidden or suppressed bodies still count", text, re.I)
    assert "(#101)" in text and "leaves suppressed components out of mass properties" in text


@pytest.mark.parametrize("path", EXPORT_PAGES)
def test_the_pages_warn_that_the_exporter_ignores_override_mass_properties(path):
    text = flat(path)
    assert "edits are sometimes lost" not in text
    assert "*Override Mass Properties*" in text and "#172" in text
    assert re.search(r"give it a material", text)


def test_the_worked_override_example_of_172():
    text = flat("reference/02-exporter.md")
    side, wanted = 0.020, 0.050                      # m, kg: the cube of #172
    volume = side ** 3
    assert f"weighs {volume * 1000 * 1000:.0f} g at 1000 kg/m³" in text
    assert f"{wanted:.3f} kg / {volume * 1e6:.0f} cm³ = {wanted / volume:.0f} kg/m³" in text


# ---- the exporter's dialogs, in their own words ---------------------------------------------

# The texts of the exporter's assembly dialog, as SW2URDF/UI/AssemblyExportForm.Designer.cs
# of ros/solidworks_urdf_exporter sets them (release 1.6.1 and the current source): step 2,
# Configure Joint Properties, and step 3, Configure Link Properties. Spelling as in the
# source, "Course" included.
ASSEMBLY_DIALOG = {
    "Configure Joint Properties", "Parent Link:", "Child Link:", "Joint Name", "Joint Type",
    "Coordinates", "Axis", "Origin", "Position (m)", "Orientation (rad)", "Roll", "Pitch",
    "Yaw", "x", "y", "z", "Limit", "lower (rad)", "upper (rad)", "effort (N-m)",
    "velocity (m/s)", "Calibration", "rising", "falling", "Dynamics", "damping (N*m*s*rad^-1)",
    "friction (N*m)", "Safety Controller", "soft lower limit (rad)", "soft upper limit (rad)",
    "k position", "k velocity", "Mimic Other Joint", "Joint to Mimic:", "Multiplier",
    "Offset (rad)", "Next", "Cancel",
    "Configure Link Properties", "Inertial", "Origin (m)", "Mass (kg)",
    "Moment of Inertia (Kg * m^-2)", "ixx", "ixy", "ixz", "iyy", "iyz", "izz",
    "Visual and Collision Meshes", "Mesh Detail", "Course", "Fine", "Material name", "Color",
    "Red", "Green", "Blue", "Alpha", "Texture (Replaces Color)", "Browse...", "Previous",
    "Export URDF and Meshes...", "Export URDF Only...",
}
# Added to the same dialog after release 1.6.1 (#154).
ASSEMBLY_DIALOG_AFTER_1_6_1 = {"Mesh Format", "STL (grayscale)", "3dxml (color)"}
# Step 1, the panel beside the feature tree: the captions SW2URDF/URDFExport/
# ExportPropertyManager.cs gives its controls, and the choices of its boxes
# (ExportHelperExtension.cs compares with "Automatically Generate" and "Automatically Detect").
PROPERTY_MANAGER = {
    "URDF Exporter", "Configure and Organize Links", "Parent Link", "Link Name", "Joint Name",
    "Global Origin Coordinate System", "Reference Coordinate System", "Reference Axis",
    "Joint Type", "Link Components", "Number of child links", "Load Configuration...",
    "Compute Mass and Inertia", "Compute Visual and Collision", "Compute Joint Kinematics",
    "Compute Joint Limits", "Preview and Export...", "Link Tree", "Add Child Link", "Remove",
    "Automatically Generate", "Automatically Detect",
}
# The add-in's name in Tools > Add-Ins and its menu item (SW2URDF/SW/SwAddin.cs).
ADD_IN = {"SW2URDF", "Tools > Export as URDF", "File > Export as URDF"}
# Only in the window for exporting a single part (SW2URDF/UI/PartExportForm.Designer.cs).
PART_DIALOG_ONLY = {"Visual Mesh Detail", "Collision Mesh Detail", "Visual", "Collision"}

# Italics on these pages that are not the exporter's words: SolidWorks' own menus and
# windows, MuJoCo's and URDF's terms, and plain emphasis.
NOT_THE_EXPORTERS = {
    "Tools > Add-Ins", "Evaluate > Mass Properties", "Override Mass Properties",
    "continuous", "revolute", "slide", "where", "which way", "no", "is", "direction",
}

DIALOG_PAGES = ["practice-1/02-exporting.md", "practice-2/02-exporting.md",
                "practice-3/02-exporting.md", "practice-4/02-exporting.md",
                "practice-5/02-exporting.md", "reference/02-exporter.md"]


def without_unit(label: str) -> str:
    """A label as a sentence may name it: 'friction (N*m)' -> 'friction', 'Parent Link:' ->
    'Parent Link'; a unit in brackets that is part of the name stays ('Texture (Replaces Color)')."""
    label = label.rstrip(":")
    return re.sub(r" \((?:m|rad|kg|N-m|m/s|N\*m|N\*m\*s\*rad\^-1)\)$", "", label)


def italics(path: str) -> list[str]:
    """The *italic* phrases of a page's prose and tables, captions and code left out."""
    text = (PAGES / path).read_text(encoding="utf-8")
    text = re.sub(r"^[ \t]*(`{3,}).*?^[ \t]*\1", "", text, flags=re.S | re.M)
    text = re.sub(r"\$\$.*?\$\$", "", text, flags=re.S)
    text = re.sub(r"`[^`\n]*`", "", text)
    text = re.sub(r"^\*[^*\s].*?\*[ \t]*$", "", text, flags=re.S | re.M)   # figure captions
    text = re.sub(r"\*\*[^*]+\*\*", "", text)
    return [" ".join(m.split()) for m in re.findall(r"(?<![*\w])\*([^*\s](?:[^*]*?[^*\s])?)\*(?![*\w])", text)]


def test_the_label_lists_name_each_text_once_as_the_source_does():
    assert "Visual Mesh Detail" not in ASSEMBLY_DIALOG and "Mesh Detail" in ASSEMBLY_DIALOG
    assert "Course" in ASSEMBLY_DIALOG and "Coarse" not in ASSEMBLY_DIALOG


@pytest.mark.parametrize("path", DIALOG_PAGES)
def test_the_exporters_words_in_italics_are_its_dialogs_words(path):
    known = {without_unit(label) for label in
             ASSEMBLY_DIALOG | ASSEMBLY_DIALOG_AFTER_1_6_1 | PROPERTY_MANAGER | ADD_IN}
    unknown = [name for name in italics(path) if name not in known | NOT_THE_EXPORTERS]
    assert not unknown, f"italic names that no exporter dialog shows: {unknown}"


@pytest.mark.parametrize("path", ["practice-1/02-exporting.md", "reference/02-exporter.md"])
def test_the_mesh_detail_field_has_the_assembly_dialogs_name(path):
    text = flat(path)
    assert "Mesh quality" not in text and "*Visual Mesh Detail*" not in text
    assert "*Mesh Detail*" in text and "*Visual and Collision Meshes*" in text
    assert "*Course*" in text and "*Fine*" in text


def test_the_exporter_reference_gives_the_link_window_no_collision_fields():
    text = (PAGES / "reference/02-exporter.md").read_text(encoding="utf-8")
    step_3 = text[text.index("## Step 3"):text.index("### Mass and inertia")]
    rows = [line.split("|")[1].strip() for line in step_3.splitlines()
            if line.startswith("| ") and not line.startswith("| Group")]
    assert set(rows) == {"Inertial", "Visual and Collision Meshes"}
    assert "There are no collision fields" in " ".join(step_3.split())
    # the one place the part window's name may appear: where it is said to be the part window's
    for name in PART_DIALOG_ONLY - {"Visual", "Collision"}:
        for hit in re.finditer(re.escape(name), text):
            assert "single part" in text[hit.start() - 120:hit.start()], name
