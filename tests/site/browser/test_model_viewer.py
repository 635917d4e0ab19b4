"""The 3D model viewer of each practice (_includes/model-viewer.html): it loads the
practice's own URDF and STL meshes from the published site, draws them, has one slider per
movable joint within the joint's limits, and falls back to the still picture without WebGL.

Headless Chromium has no GPU here; it draws WebGL 2 with SwiftShader, its software
renderer, with the session's usual flags.
"""

import gzip
import io
import math
import re
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
from PIL import Image, ImageChops

import axe_audit

from repository import ROOT
from repository import practice_numbers

PRACTICES = practice_numbers()
MOVABLE = ("revolute", "continuous", "prismatic")
VIEWER = re.compile(r'<section class="model-viewer"[^>]*?data-package="(example_\d+)"'
                    r'[^>]*?data-package-url="([^"]+)"[^>]*?data-urdf="([^"]+)"')
READY_S = 20.0
# The viewer's background and grid are neutral greys (equal channels); the exporter's part
# colours are not. A pixel whose channels spread at least this far apart is the model.
TINTED_SPREAD = 4
# Enough of the canvas to be the model, not a stray edge (the thin bar and small block of
# Practice 4 take least, near 3%).
MIN_MODEL_FRACTION = 0.01
# Two pictures of an unchanged scene are identical; turning a wheel by 72° changes about
# 0.1% of the canvas, swinging an arm several per cent.
MIN_CHANGED_FRACTION = 0.0003


def viewer_pages(site):
    """practice number -> [(page path, package, package URL, URDF URL)] of the built site."""
    found = {n: [] for n in PRACTICES}
    for path in site.pages:
        html = (site.root / path.strip("/") / "index.html").read_text(encoding="utf-8")
        for package, package_url, urdf_url in VIEWER.findall(html):
            found[int(package.split("_")[1])].append((path, package, package_url, urdf_url))
    return found


def movable_joints(practice):
    """(name, type, lower, upper) of each joint a slider should move, in URDF order."""
    urdf = ROOT / f"examples/example_{practice}/urdf/example_{practice}.urdf"
    joints = []
    for joint in ET.parse(urdf).getroot().iter("joint"):
        if joint.get("type") in MOVABLE and joint.find("mimic") is None:
            limit = joint.find("limit")
            lower = float(limit.get("lower", 0)) if limit is not None else 0.0
            upper = float(limit.get("upper", 0)) if limit is not None else 0.0
            joints.append((joint.get("name"), joint.get("type"), lower, upper))
    return joints


def slider_range(kind, lower, upper):
    """The slider's (min, max) as the page should show them: whole degrees, or centimetres
    in metres, inside the joint's limits; a continuous joint gets one turn."""
    if kind == "prismatic":
        return math.ceil(lower * 100) / 100, math.floor(upper * 100) / 100
    if kind == "continuous":
        return -180, 180
    return math.ceil(math.degrees(lower) - 1e-6), math.floor(math.degrees(upper) + 1e-6)


def canvas_picture(page) -> Image.Image:
    return Image.open(io.BytesIO(page.locator(".model-viewer canvas").screenshot())).convert("RGB")


def tinted_fraction(picture: Image.Image) -> float:
    channels = picture.split()
    spread = ImageChops.subtract(ImageChops.lighter(ImageChops.lighter(*channels[:2]), channels[2]),
                                 ImageChops.darker(ImageChops.darker(*channels[:2]), channels[2]))
    histogram = spread.histogram()
    return sum(histogram[TINTED_SPREAD:]) / (picture.width * picture.height)


def changed_fraction(before: Image.Image, after: Image.Image) -> float:
    difference = ImageChops.difference(before, after).convert("L")
    return sum(difference.histogram()[30:]) / (before.width * before.height)


def open_viewer(page):
    page.get_by_role("button", name="Turn the model in 3D").click()
    page.wait_for_function(
        "() => ['ready', 'still'].includes(document.querySelector('.model-viewer').dataset.state)",
        timeout=READY_S * 1000)


def test_each_practice_has_one_viewer_of_its_own_package(site):
    found = viewer_pages(site)
    assert all(len(pages) == 1 for pages in found.values()), (
        f"expected one viewer per practice, found {found}")
    for practice, [(path, package, package_url, urdf_url)] in found.items():
        assert package == f"example_{practice}" and f"/practice-{practice}/" in path
        urdf = site.root / urdf_url.lstrip("/")
        assert urdf.is_file(), f"{path}: {urdf_url} is not published"
        for mesh in ET.parse(urdf).getroot().iter("mesh"):
            relative = mesh.get("filename").removeprefix(f"package://{package}/")
            assert (site.root / package_url.lstrip("/") / relative).is_file(), (
                f"{path}: {mesh.get('filename')} is not published under {package_url}")


# The viewer's libraries, bundled by tools/bundle-model-viewer.mjs. Before the bundle the
# viewer loaded 10 modules of three and urdf-loader: 2.35 MB, 467 kB gzipped.
LIBRARIES = "/assets/vendor/model-viewer/libraries.min.js"
MAX_GZIPPED = 200_000   # bytes; the bundle is about 150 kB


def test_the_viewer_loads_one_small_minified_bundle(site):
    [(path, *_)] = viewer_pages(site)[1]
    html = (site.root / path.strip("/") / "index.html").read_text(encoding="utf-8")
    assert f'data-libraries="{LIBRARIES}"' in html
    assert "importmap" not in html
    bundle = (site.root / LIBRARIES.lstrip("/")).read_bytes()
    text = bundle.decode("utf-8")
    assert len(gzip.compress(bundle, 9)) < MAX_GZIPPED
    assert not re.search(r"^\s*import\b|\bimport\s*\(|from\s*[\"']", text, re.M), \
        "the bundle imports nothing more"
    assert "@param" not in text and "* Constructs a new" not in text, "minified: no doc comments"
    for name in ("OrbitControls", "URDFLoader", "WebGLRenderer", "LoadingManager"):
        assert re.search(rf"\bas {name}\b", text), f"the bundle does not export {name}"
    assert "STLLoader" in text or "solid" in text, "the STL loader is in"
    assert "library_visual_scenes" not in text, "the Collada parser is left out"
    assert "Copyright 2010-" in text, "three's licence notice is kept"
    notices = site.root / "assets/vendor/model-viewer"
    assert (notices / "LICENSE-three").is_file() and (notices / "README-urdf-loader.md").is_file()


def test_the_first_load_leaves_three_for_later(site, browser_page):
    [(path, *_)] = viewer_pages(site)[5]
    visit = browser_page.visit(path)
    assert not visit.problems(), visit.problems()
    loaded = [r.url for r in visit.responses if "/assets/vendor/" in r.url]
    assert not loaded, f"the page loaded the viewer's libraries before it was asked: {loaded}"
    assert browser_page.page.get_by_role("button", name="Turn the model in 3D").is_visible()


@pytest.mark.parametrize("practice", PRACTICES)
def test_viewer_draws_the_model_and_a_slider_moves_a_joint(site, browser_page, practice):
    [(path, *_)] = viewer_pages(site)[practice]
    page = browser_page.page
    shots = {}

    def open_and_move(page):
        open_viewer(page)
        shots["before"] = canvas_picture(page)
        first = page.locator(".model-viewer-joint input").first
        shots["value"] = first.input_value()
        first.focus()
        first.press("PageUp")
        first.press("PageUp")
        shots["moved"] = first.input_value()
        shots["after"] = canvas_picture(page)

    visit = browser_page.visit(path, then=open_and_move)
    assert not visit.problems(), visit.problems()
    viewer = page.locator(".model-viewer")
    assert viewer.get_attribute("data-state") == "ready", page.locator(
        ".model-viewer-note").text_content()

    drawn = tinted_fraction(shots["before"])
    assert drawn > MIN_MODEL_FRACTION, f"the model covers only {drawn:.2%} of the canvas"

    expected = movable_joints(practice)
    rows = page.locator(".model-viewer-joint")
    assert rows.count() == len(expected)
    for row, (name, kind, lower, upper) in zip(rows.all(), expected):
        assert row.locator("label").text_content() == name
        slider = row.get_by_label(name)
        low, high = slider_range(kind, lower, upper)
        assert (float(slider.get_attribute("min")), float(slider.get_attribute("max"))) \
            == (low, high), f"{name}: slider range against limits {lower}..{upper}"
        unit = " m" if kind == "prismatic" else "°"
        assert unit in row.locator("output").text_content()

    assert shots["moved"] != shots["value"], "PageUp did not move the first slider"
    changed = changed_fraction(shots["before"], shots["after"])
    assert changed > MIN_CHANGED_FRACTION, (
        f"moving {expected[0][0]} from {shots['value']} to {shots['moved']} changed only "
        f"{changed:.3%} of the picture")


def test_the_open_viewer_is_accessible(site, browser_page):
    """The canvas, the labelled sliders and their values pass axe once the viewer is open."""
    [(path, *_)] = viewer_pages(site)[5]
    axe_url = site.node_module_url(axe_audit.AXE)

    def open_and_audit(page):
        open_viewer(page)
        page.add_script_tag(url=axe_url)
        axe_audit.start(page, path, context={"include": [[".model-viewer"]]})

    visit = browser_page.visit(path, then=open_and_audit)
    violations = axe_audit.serious(axe_audit.collect(browser_page.page))
    assert not visit.problems(), visit.problems()
    assert browser_page.page.locator(".model-viewer-joint input").count() == 7
    assert not violations, violations


def test_without_webgl_the_still_picture_is_shown(site, browser_page):
    [(path, *_)] = viewer_pages(site)[3]

    def open_without_webgl(page):
        page.evaluate("""() => {
            const getContext = HTMLCanvasElement.prototype.getContext;
            HTMLCanvasElement.prototype.getContext = function (kind, ...rest) {
                return /webgl/.test(kind) ? null : getContext.call(this, kind, ...rest);
            };
        }""")
        open_viewer(page)
        page.wait_for_function("() => document.querySelector('.model-viewer-still img').complete")

    visit = browser_page.visit(path, then=open_without_webgl)
    assert not visit.problems(), visit.problems()
    page = browser_page.page
    still = page.locator(".model-viewer-still img")
    assert still.is_visible()
    assert still.get_attribute("src").endswith("/media/practice-3/model.png")
    assert "Practice 3 arm" in still.get_attribute("alt")
    assert still.evaluate("img => img.naturalWidth") > 0
    assert "WebGL" in page.locator(".model-viewer-note").text_content()
    assert page.locator(".model-viewer canvas").count() == 0
    assert not [r.url for r in visit.responses if "/assets/vendor/model-viewer/" in r.url]
