"""The lessons' calculators (_includes/calculator.html, assets/js/calculators.js) give the
numbers the pages give: typed into the built pages in the browser, and compared with the
page's own Python (Practice 1's conversion functions, Practice 5's knuckle_angles) or,
where the page has only the formula (Practice 3's reach), with that formula in Python.
"""

from __future__ import annotations

import contextlib
import io
import math
import re
from pathlib import Path

import pytest

import axe_audit
from page_text import fenced_blocks
from course.practices import load_script
from course.practices.practice_3 import design as arm_design
from course.practices.practice_5 import design as car_design

from repository import ROOT
PAGES = ROOT / "_pages"

# Which calculators each page has (every calculator in the site must be listed here).
CALCULATORS = {
    "/practice-1/exporting/": ["deg-rad", "rpm", "wheel-speed"],
    "/practice-3/exporting/": ["arm-reach"],
    "/practice-5/ackermann-geometry/": ["ackermann"],
}
NO_RESULT = "–"
TOLERANCE = 1e-12


def shown(x: float, decimals: int) -> str:
    """A number as the calculators show it: the page's decimals, and for numbers below 1
    enough more (at most four) for three significant digits unless they would still read
    as zero; never "-0"."""
    if 5e-5 <= abs(x) < 1:
        decimals = max(decimals, min(4, 2 - math.floor(math.log10(abs(x)))))
    text = f"{x:.{decimals}f}"
    return text[1:] if re.fullmatch(r"-0(\.0*)?", text) else text


@pytest.fixture(scope="module")
def conversions():
    """Practice 1's Equations 1 to 3, run from the page's own code, and what it prints."""
    page = (PAGES / "practice-1/02-exporting.md").read_text(encoding="utf-8")
    block = next(b for b in fenced_blocks(page, "python") if "def rpm_to_rad_s" in b)
    names: dict = {}
    printed = io.StringIO()
    with contextlib.redirect_stdout(printed):
        exec(block, names)
    names["printed"] = printed.getvalue()
    return names


@pytest.fixture(scope="module")
def ackermann():
    return load_script("examples/example_5/scripts/ackermann.py")


# Everything a calculator shows, read in one call into the page.
READ_FORM = """form => ({
    outputs: Object.fromEntries(Array.from(form.querySelectorAll("output"), output =>
        [output.name, [output.textContent, output.dataset.value ?? null]])),
    message: form.querySelector(".calc-message").textContent,
    invalid: Array.from(form.querySelectorAll('input[aria-invalid="true"]'), i => i.name),
})"""


class Calculator:
    """One calculator on the loaded page, driven as a reader would."""

    def __init__(self, page, kind: str):
        self.page = page
        self.form = page.locator(f'[data-calculator="{kind}"] form')
        self._shown = None

    def input(self, name: str):
        return self.form.locator(f'input[name="{name}"]')

    def enter(self, **values) -> Calculator:
        for name, value in values.items():
            self.input(name).fill(str(value))
        self._shown = None
        return self

    def type(self, name: str, keys: str) -> Calculator:
        """Typed key by key, for text the browser refuses as a number (such as "-")."""
        self.input(name).fill("")
        self.input(name).press_sequentially(keys)
        self._shown = None
        return self

    def shown(self) -> dict:
        if self._shown is None:
            self._shown = self.form.evaluate(READ_FORM)
        return self._shown

    def text(self, name: str) -> str:
        return self.shown()["outputs"][name][0]

    def value(self, name: str) -> float | None:
        value = self.shown()["outputs"][name][1]
        return None if value is None else float(value)

    def message(self) -> str:
        return self.shown()["message"]

    def invalid(self) -> list[str]:
        return self.shown()["invalid"]


@pytest.fixture(scope="module")
def loads() -> dict:
    """The Visit of each calculator page loaded by this module's tests, by path."""
    return {}


@pytest.fixture
def on(browser_page, loads):
    """Opens a calculator page, or puts the one this module left open back to its starting
    values (a page load costs more than all the checks of a test). After the test, the page
    must not have logged an error since it was loaded."""
    used = []

    def load(path: str):
        page = browser_page.page
        if path in loads and page.url == browser_page.site.url(path):
            page.evaluate("""() => document.querySelectorAll(".calculator form").forEach(form => {
                form.reset();
                form.dispatchEvent(new Event("input"));
            })""")
        else:
            loads.clear()
            loads[path] = browser_page.visit(path)
        used.append(loads[path])
        return lambda kind: Calculator(page, kind)

    yield load
    for visit in used:
        assert not visit.problems(), "\n".join(visit.problems())


def close(a: float | None, b: float) -> bool:
    return a is not None and math.isclose(a, b, rel_tol=TOLERANCE, abs_tol=TOLERANCE)


# ---- where they are -------------------------------------------------------------------


def test_the_calculators_are_on_their_pages(site):
    found = {}
    for page in site.root.rglob("index.html"):
        kinds = re.findall(r'data-calculator="([^"]+)"', page.read_text(encoding="utf-8"))
        if kinds:
            found["/" + page.parent.relative_to(site.root).as_posix() + "/"] = kinds
    assert found == CALCULATORS


def test_without_javascript_the_form_says_the_results_need_it(site):
    html = (site.root / "practice-5/ackermann-geometry/index.html").read_text(encoding="utf-8")
    calculator = html[html.index('<div class="calculator"'):]
    calculator = calculator[:calculator.index("</form>")]
    assert re.findall(r'<output [^>]*>([^<]*)</output>', calculator) == [NO_RESULT] * 3
    assert "<noscript>" in calculator and "need JavaScript" in calculator
    # Each input and result has a label of its own.
    ids = re.findall(r'<(?:input|output) [^>]*id="([^"]+)"', calculator)
    assert len(ids) == 6
    assert all(f'<label for="{i}">' in calculator for i in ids)


# ---- Practice 1: Equations 1, 2 and 3 ------------------------------------------------------


def test_equation_1_both_ways(on, conversions):
    calc = on("/practice-1/exporting/")("deg-rad")
    assert calc.input("deg").input_value() == "45"
    assert f"45 deg  = {calc.text('radians')}" in conversions["printed"]
    assert calc.text("degrees") == "45.00°"          # the URDF's 0.7854 rad

    for degrees in (30, -45, 0, 720, 0.5, 12.3456):
        calc.enter(deg=degrees)
        expected = conversions["deg_to_rad"](degrees)
        assert close(calc.value("radians"), expected), degrees
        assert calc.text("radians") == shown(expected, 4) + " rad"
    for radians in (0.6351, -1.5, 0, 3.14159, 0.01):
        calc.enter(rad=radians)
        expected = math.degrees(radians)
        assert close(calc.value("degrees"), expected), radians
        assert calc.text("degrees") == shown(expected, 2) + "°"

    calc.enter(deg="")
    assert calc.text("radians") == NO_RESULT and calc.value("radians") is None
    assert calc.message() == "Enter a number for “Angle in degrees”."
    assert calc.invalid() == ["deg"]
    assert calc.text("degrees") != NO_RESULT            # the other direction still works
    calc.enter(deg=90)
    assert calc.message() == "" and calc.invalid() == []
    assert calc.text("radians") == "1.5708 rad"


def test_equation_2(on, conversions):
    calc = on("/practice-1/exporting/")("rpm")
    assert f"600 rpm = {calc.text('omega')}" in conversions["printed"]
    for rpm in (600, 0, -120, 3000, 1, 2.5):
        calc.enter(rpm=rpm)
        expected = conversions["rpm_to_rad_s"](rpm)
        assert close(calc.value("omega"), expected), rpm
        assert calc.text("omega") == shown(expected, 2) + " rad/s"
    calc.type("rpm", "-")
    assert calc.text("omega") == NO_RESULT
    assert calc.message() == "Enter a number for “Speed, n”."


def test_equation_3(on, conversions):
    calc = on("/practice-1/exporting/")("wheel-speed")
    assert f"1 m/s on a 0.1 m wheel = {calc.text('omega')}" in conversions["printed"]
    for speed, radius in ((0.5, 0.06), (-1, 0.1), (0, 0.2), (0.05, 0.06), (30 * 0.06, 0.06)):
        calc.enter(v=speed, r=radius)
        expected = conversions["speed_to_rad_s"](speed, radius)
        assert close(calc.value("omega"), expected), (speed, radius)
        assert calc.text("omega") == shown(expected, 1) + " rad/s"
    assert calc.text("omega") == "30.0 rad/s"         # Practice 5's wheel limit, read back

    calc.enter(r=0)
    assert calc.text("omega") == NO_RESULT
    assert calc.message() == "The wheel radius r must be more than 0 m."
    assert calc.invalid() == ["r"]
    calc.enter(r=-0.1)
    assert calc.invalid() == ["r"] and calc.text("omega") == NO_RESULT
    calc.enter(r="", v="")
    assert calc.message() == ("Enter a number for “Ground speed, v”. "
                              "Enter a number for “Wheel radius, r”.")
    assert calc.invalid() == ["v", "r"]
    calc.enter(v=1.0, r=0.1)
    assert calc.message() == "" and calc.text("omega") == "10.0 rad/s"


# ---- accessible also when something is wrong ---------------------------------------------


def test_a_calculator_showing_a_problem_passes_axe(site, on):
    calc = on("/practice-1/exporting/")("wheel-speed").enter(r=0, v="")
    assert calc.invalid() == ["v", "r"]
    calc.page.add_script_tag(url=site.node_module_url(axe_audit.AXE))
    axe_audit.start(calc.page, "/practice-1/exporting/", context={"include": [[".calculator"]]})
    assert axe_audit.serious(axe_audit.collect(calc.page)) == []


# ---- Practice 5: Equation 4 -----------------------------------------------------------


def knuckles(ackermann, degrees: float, l: float, w: float) -> tuple[float, float]:
    """Inner and outer angle (rad) by the page's script; the inner wheel is the one on the
    side the car turns to (left for a positive angle)."""
    left, right = ackermann.knuckle_angles(math.radians(degrees), l, w)
    return (left, right) if degrees > 0 else (right, left)


def angle_text(rad: float) -> str:
    return f"{shown(math.degrees(rad), 2)}° ({shown(rad, 4)} rad)"


def test_equation_4_defaults_are_the_model_and_give_the_page_table(on, ackermann):
    calc = on("/practice-5/ackermann-geometry/")("ackermann")
    l, w = car_design.WHEELBASE / 1000, car_design.TRACK / 1000
    assert float(calc.input("l").input_value()) == l
    assert float(calc.input("w").input_value()) == w

    page = (PAGES / "practice-5/03-ackermann-geometry.md").read_text(encoding="utf-8")
    rows = re.findall(r"^\| (\d+)° \| ([\d.]+) m \| ([\d.]+)° \| ([\d.]+)° \|$", page, re.M)
    assert len(rows) == 4
    for degrees, radius, inner, outer in rows:
        calc.enter(phi=degrees)
        assert calc.text("radius") == f"{radius} m, turning left"
        assert calc.text("inner").startswith(f"{inner}° (")
        assert calc.text("outer").startswith(f"{outer}° (")


@pytest.mark.parametrize("degrees, l, w", [
    (20, 0.4, 0.3), (-20, 0.4, 0.3), (0.5, 0.4, 0.3), (-29.9, 0.4, 0.3), (45, 0.3, 0.2),
    (75, 0.4, 0.3), (10, 2.7, 1.6), (15, 0.4, 0),
])
def test_equation_4_is_the_scripts_knuckle_angles(on, ackermann, degrees, l, w):
    calc = on("/practice-5/ackermann-geometry/")("ackermann").enter(l=l, w=w, phi=degrees)
    inner, outer = knuckles(ackermann, degrees, l, w)
    side = ("left", "right") if degrees > 0 else ("right", "left")
    assert close(calc.value("inner"), inner) and close(calc.value("outer"), outer)
    assert calc.text("inner") == f"{angle_text(inner)}, {side[0]} wheel"
    assert calc.text("outer") == f"{angle_text(outer)}, {side[1]} wheel"
    radius = l / math.tan(math.radians(degrees))
    assert close(calc.value("radius"), radius)
    assert calc.text("radius") == f"{shown(abs(radius), 3)} m, turning {side[0]}"


def test_equation_4_straight_ahead_and_bad_input(on):
    calc = on("/practice-5/ackermann-geometry/")("ackermann").enter(phi=0)
    assert calc.text("radius") == "infinite: the car drives straight"
    assert calc.value("radius") == math.inf
    assert calc.text("inner") == calc.text("outer") == "0.00° (0.0000 rad), straight ahead"
    assert calc.message() == ""

    for values, message, invalid in [
        ({"phi": 90}, "The steering angle Φ must be between -90° and 90°.", ["phi"]),
        ({"phi": 20, "l": 0}, "The wheelbase l must be more than 0 m.", ["l"]),
        ({"l": 0.4, "w": -0.3}, "The track w cannot be negative.", ["w"]),
    ]:
        calc.enter(**values)
        assert calc.message() == message
        assert calc.invalid() == invalid
        texts = [calc.text(name) for name in ("radius", "inner", "outer")]
        # The turning radius does not depend on the track.
        expected = [NO_RESULT] * 3 if invalid != ["w"] else [texts[0], NO_RESULT, NO_RESULT]
        assert texts == expected
    calc.enter(w=0.3)
    assert calc.message() == "" and calc.text("inner").startswith("22.86°")


# ---- Practice 3: the arm's reach ------------------------------------------------------------


def arm_tip(l1: float, l2: float, t1: float, t2: float) -> tuple[float, float]:
    """The page's fingertip position, angles in degrees."""
    a, b = math.radians(t1), math.radians(t1) + math.radians(t2)
    return l1 * math.cos(a) + l2 * math.cos(b), l1 * math.sin(a) + l2 * math.sin(b)


def test_arm_reach_defaults_are_the_design_and_the_page(on):
    calc = on("/practice-3/exporting/")("arm-reach")
    length = arm_design.ARM_LENGTH / 1000
    assert [float(calc.input(n).input_value()) for n in ("l1", "l2", "t1", "t2")] == [
        length, length, 45, 45]
    # The page: φ = 45° + 45°/2 = 67.5°, r = 2 · 0.225 m · cos 22.5° = 0.416 m.
    assert calc.text("angle") == "67.50°"
    assert calc.text("distance") == "0.416 m"
    assert close(calc.value("distance"), 2 * length * math.cos(math.radians(22.5)))


@pytest.mark.parametrize("l1, l2, t1, t2", [
    (0.225, 0.225, 45, 45), (0.225, 0.225, -45, -45), (0.225, 0.225, 0, 0),
    (0.225, 0.225, 30, -45), (0.3, 0.2, 30, 60), (0.5, 0.1, 170, 30), (0.225, 0.225, -90, 135),
])
def test_arm_reach_is_the_page_formula(on, l1, l2, t1, t2):
    calc = on("/practice-3/exporting/")("arm-reach").enter(l1=l1, l2=l2, t1=t1, t2=t2)
    x, y = arm_tip(l1, l2, t1, t2)
    angle = math.degrees(math.atan2(y, x))
    for name, expected in (("x", x), ("y", y), ("distance", math.hypot(x, y))):
        assert close(calc.value(name), expected), name
        assert calc.text(name) == shown(expected, 3) + " m"
    assert close(calc.value("angle"), angle)
    assert calc.text("angle") == shown(angle, 2) + "°"
    if l1 == l2:  # the page's shortcut for equal arms
        assert angle == pytest.approx(t1 + t2 / 2)


def test_arm_reach_folded_back_and_bad_input(on):
    calc = on("/practice-3/exporting/")("arm-reach").enter(t1=30, t2=180)
    assert calc.text("distance") == "0.000 m"
    assert calc.text("angle") == "none: the fingertips are on the pivot"
    assert calc.value("angle") is None
    calc.enter(l2=0)
    assert calc.message() == "The end arm's length L2 must be more than 0 m."
    assert [calc.text(n) for n in ("x", "y", "distance", "angle")] == [NO_RESULT] * 4
    calc.type("t1", "-")
    assert calc.invalid() == ["l2", "t1"]
