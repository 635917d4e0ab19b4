"""Property tests: `sw2sim check` on mangled URDFs never raises and always reports soundly.

The URDFs to mangle are those of examples/example_1..5 and of two packages written exactly as
the exporter writes them (tests/tool/check/exporter_packages.py). Mutations work on the XML tree
(delete, duplicate or swap elements; delete attributes or give them odd values: text, NaN,
infinities, huge or negative numbers, wrong counts; rename links) or on the bytes (truncate,
insert or delete bytes, flip the bits of one). Whatever comes out, `check` must return a Report
whose status is 0, 1 or 2 and whose every finding belongs to a registered rule and carries a
message and a fix; the report must print and serialise to strict JSON. When the bytes are no
longer well-formed XML the status must be 2, with the line of the fault.

Examples are derandomised, so every run tries the same cases. The examples' larger meshes are
replaced by their convex hulls in the copies checked here: the URDF is what is being mangled,
and the hulls keep each check to a tenth of a second.
"""

from __future__ import annotations

import copy
import dataclasses
import json
import shutil

import pytest
import trimesh
from hypothesis import HealthCheck, event, given, settings
from hypothesis import strategies as st
from lxml import etree

from sw2sim.check import RULES, Report, check
from sw2sim.check.findings import FATAL, SEVERITIES
from exporter_packages import FOUR_WHEELER_NESTED, ORIGINAL_3_DOF_ARM, write_export
from packages import EXAMPLES, urdf_of
from repository import practice_numbers

FAST = dict(deadline=None, derandomize=True, database=None,
            suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])

# Attribute values a hand edit or a broken export can leave behind.
ODD_VALUES = ["", " ", "nan", "NaN", "-nan", "inf", "-inf", "Infinity", "1e308", "-1e308",
              "1e999", "1e-400", "-1", "0", "-0", "1.0.0", "0x10", "1,5", "1 2", "1 2 3 4",
              "nan nan nan", "inf 0 0", "0 0 1e999", "-1 -1 -1", "1e-30 1e-30 1e-30", "true",
              "package://", "package://nowhere/meshes/x.STL", "../../x.STL", "x" * 300]
TEXT = st.text(st.characters(codec="utf-8", exclude_categories=("Cs", "Cc", "Cn")), max_size=24)
NUMBER = st.floats(allow_nan=True, allow_infinity=True).map(repr)
NUMBERS = st.lists(st.floats(allow_nan=True, allow_infinity=True), min_size=1,
                   max_size=5).map(lambda xs: " ".join(map(repr, xs)))
VALUES = st.one_of(st.sampled_from(ODD_VALUES), TEXT, NUMBER, NUMBERS,
                   st.integers(-10**12, 10**12).map(str))


@pytest.fixture(scope="module")
def bases(tmp_path_factory):
    """Name -> (package folder, its URDF, the URDF's original bytes), copies free to overwrite."""
    folder = tmp_path_factory.mktemp("fuzz")
    found = {}
    for n in practice_numbers():
        package = folder / f"example_{n}"
        shutil.copytree(EXAMPLES / f"example_{n}", package,
                        ignore=shutil.ignore_patterns("scripts"))
        for stl in (package / "meshes").glob("*.STL"):
            mesh = trimesh.load(stl, force="mesh")
            if len(mesh.faces) > 1000:
                stl.write_bytes(mesh.convex_hull.export(file_type="stl"))
        found[package.name] = package
    for export in (FOUR_WHEELER_NESTED, ORIGINAL_3_DOF_ARM):
        lower = dataclasses.replace(export, name=export.name.lower().replace("4_", "four_"))
        found[lower.name] = write_export(lower, folder)
    return {name: (package, urdf_of(package), urdf_of(package).read_bytes())
            for name, package in found.items()}


def assert_sound(report) -> None:
    """What every report must satisfy, whatever the input."""
    assert isinstance(report, Report)
    assert report.status in (0, 1, 2)
    for f in report.findings:
        assert f.rule in RULES, f"unregistered rule {f.rule!r}"
        assert f.severity in SEVERITIES and f.severity == RULES[f.rule].severity
        assert isinstance(f.message, str) and f.message.strip(), f
        assert isinstance(f.fix, str) and f.fix.strip(), f
        assert f.line is None or (isinstance(f.line, int) and f.line >= 1), f
    assert isinstance(report.format(), str)

    def strict(constant):
        raise AssertionError(f"to_json() wrote {constant}, which is not JSON")

    doc = json.loads(report.to_json(), parse_constant=strict)
    assert doc["status"] == report.status and len(doc["findings"]) == len(report.findings)


# --- mutations of the XML tree ---------------------------------------------------------------


def elements(root):
    return [e for e in root.iter() if isinstance(e.tag, str)]


def delete_element(root, data):
    victim = data.draw(st.sampled_from(elements(root)[1:]))
    victim.getparent().remove(victim)


def delete_attribute(root, data):
    holders = [e for e in elements(root) if e.attrib]
    victim = data.draw(st.sampled_from(holders))
    del victim.attrib[data.draw(st.sampled_from(sorted(victim.attrib)))]


def set_attribute(root, data):
    target = data.draw(st.sampled_from(elements(root)))
    names = sorted(target.attrib) or ["name"]
    key = data.draw(st.sampled_from(names + ["xyz", "value"]))
    target.set(key, data.draw(VALUES))


def duplicate_element(root, data):
    original = data.draw(st.sampled_from(elements(root)[1:]))
    original.addnext(copy.deepcopy(original))


def swap_elements(root, data):
    candidates = elements(root)[1:]
    a = data.draw(st.sampled_from(candidates))
    b = data.draw(st.sampled_from(candidates))
    if a is b or a in b.iterancestors() or b in a.iterancestors():
        return
    marker = etree.Element("marker")
    a.addnext(marker)
    b.addnext(a)
    marker.addnext(b)
    marker.getparent().remove(marker)


def rename_link(root, data):
    links = root.findall("link")
    if not links:
        return
    link = data.draw(st.sampled_from(links))
    old = link.get("name")
    new = data.draw(st.one_of(st.sampled_from([e.get("name", "") for e in links] + [""]), TEXT))
    link.set("name", new)
    if data.draw(st.booleans()):   # rename it everywhere, as a careful hand edit would
        for ref in root.iter("parent", "child"):
            if ref.get("link") == old:
                ref.set("link", new)


TREE_MUTATIONS = [delete_element, delete_attribute, set_attribute, duplicate_element,
                  swap_elements, rename_link]


def mangle(original: bytes, data, mutations, count) -> bytes:
    tree = etree.ElementTree(etree.fromstring(original, etree.XMLParser(remove_comments=False)))
    for _ in range(data.draw(count)):
        data.draw(st.sampled_from(mutations))(tree.getroot(), data)
    return etree.tostring(tree, xml_declaration=True, encoding="utf-8")


@settings(max_examples=50, **FAST)
@given(data=st.data())
def test_a_mangled_tree_is_reported_soundly(bases, data):
    name = data.draw(st.sampled_from(sorted(bases)), label="package")
    package, urdf, original = bases[name]
    urdf.write_bytes(mangle(original, data, TREE_MUTATIONS, st.integers(1, 4)))
    report = check(package, stability=False)
    assert_sound(report)
    event(f"status {report.status}")


# --- mutations of the bytes ------------------------------------------------------------------


def well_formed(raw: bytes) -> bool:
    try:
        etree.fromstring(raw, etree.XMLParser(resolve_entities=False, no_network=True))
    except etree.XMLSyntaxError:
        return False
    return True


def garble(raw: bytes, data) -> bytes:
    at = data.draw(st.integers(0, len(raw) - 1), label="at")
    how = data.draw(st.sampled_from(["truncate", "insert", "delete", "flip"]), label="how")
    if how == "truncate":
        return raw[:at]
    if how == "insert":
        return raw[:at] + data.draw(st.binary(min_size=1, max_size=8)) + raw[at:]
    if how == "delete":
        return raw[:at] + raw[at + data.draw(st.integers(1, 40)):]
    return raw[:at] + bytes([raw[at] ^ data.draw(st.integers(1, 255))]) + raw[at + 1:]


@settings(max_examples=50, **FAST)
@given(data=st.data())
def test_truncated_or_garbled_bytes_give_status_2_with_a_line(bases, data):
    name = data.draw(st.sampled_from(sorted(bases)), label="package")
    package, urdf, original = bases[name]
    raw = garble(original, data)
    urdf.write_bytes(raw)
    report = check(package, stability=False)
    assert_sound(report)
    event(f"status {report.status}")
    if raw.strip() and not well_formed(raw):
        fatal = [f for f in report.findings if f.severity == FATAL]
        assert report.status == 2 and fatal, report.format()
        assert any(f.line for f in fatal), f"no line number: {report.format()}"


# --- the stability run -----------------------------------------------------------------------

NUMERIC = ("value", "ixx", "iyy", "izz", "ixy", "xyz", "rpy", "effort", "velocity", "lower",
           "upper", "damping", "friction")


def scale_number(root, data):
    """Multiply one number by a plausible-but-wrong factor, so the model still compiles."""
    holders = [(e, k) for e in elements(root) for k in e.attrib if k in NUMERIC]
    target, key = data.draw(st.sampled_from(holders))
    factor = data.draw(st.sampled_from([1e-6, 1e-3, 0.1, 10.0, 1e3, 1e6, -1.0]))
    try:
        numbers = [float(v) * factor for v in target.get(key).split()]
    except ValueError:
        return
    target.set(key, " ".join(repr(v) for v in numbers))


@settings(max_examples=6, **FAST)
@given(data=st.data())
def test_the_stability_run_survives_odd_numbers(bases, data):
    name = data.draw(st.sampled_from(["example_3", "example_4", "four_wheeler_nested_description"]))
    package, urdf, original = bases[name]
    urdf.write_bytes(mangle(original, data, [scale_number], st.integers(1, 2)))
    report = check(package, stability=True)
    assert_sound(report)
    event("stability run" if report.stability is not None else "no stability run")
