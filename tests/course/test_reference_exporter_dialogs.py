"""The schematics of the exporter's windows use the exporter's own words only, and those words
(course/exporter_dialogs.py) are the ones its source has, where the list says. Their phone
variants (course/dialog_schematics_phone.py) show the same words, readable in a phone's
column."""

import xml.etree.ElementTree as ET
from collections import Counter

import pytest

from course import dialog_schematics as d
from course import dialog_schematics_phone as p
from course import exporter_dialogs as e
from course.phone import MIN_TEXT_PX, SHOWN_PX

SVG = "{http://www.w3.org/2000/svg}"
DRAWINGS = {"panel": d.property_manager, "joints": d.joint_window, "links": d.link_window}
PHONE = {"panel": p.property_manager_phone, "joints": p.joint_window_phone, "links": p.link_window_phone}


def texts(svg: str, shown: float = 736) -> list[tuple[str, str, float]]:
    """(class, text, font size in px as shown `shown` px wide) of every text of a drawing."""
    root = ET.fromstring(svg)
    width = float(root.attrib["viewBox"].split()[2])
    out = []
    for t in root.iter(f"{SVG}text"):
        style = dict(part.split(":") for part in t.attrib.get("style", "").split(";") if part)
        size = float(style.get("font-size", f"{d.SIZE}px").rstrip("px"))
        cls = t.attrib["class"]
        if "title" in cls:
            size = 12
        out.append((cls, t.text, size * min(1.0, shown / width)))
    return out


def known_words() -> set[str]:
    return ({c.text for c in e.ASSEMBLY_FORM if c.text} | set(e.property_manager_strings())
            | {e.FORM_TITLE[0]})


@pytest.mark.parametrize("draw", [*DRAWINGS.values(), *PHONE.values()],
                         ids=[*DRAWINGS, *(f"{name}-phone" for name in PHONE)])
def test_every_label_drawn_is_one_of_the_exporters(draw):
    labels = [(cls, t) for cls, t, _ in texts(draw()) if cls.split()[0] == "label"]
    assert labels
    words = known_words()
    # a long tooltip is drawn on two lines: each line is a piece of one of the exporter's words
    unknown = [t for cls, t in labels if t not in words
               and not ("tip" in cls and any(f" {t} " in f" {w} " for w in words))]
    assert not unknown


@pytest.mark.parametrize("name", DRAWINGS)
def test_every_text_is_readable_on_the_page(name):
    small = [(t, round(size, 1)) for _, t, size in texts(DRAWINGS[name]()) if size < 10]
    assert not small


def test_the_assembly_windows_show_every_field_the_source_gives_them():
    shown = {t for name in ("joints", "links") for _, t, _ in texts(DRAWINGS[name]())}
    words = {c.text for c in e.ASSEMBLY_FORM if c.text and c.kind != "DomainUpDown"}
    assert words <= shown


def shown_words(svg: str) -> tuple[Counter, str]:
    """What a schematic shows of the window, the course's notes left out: each text with
    its class, and the tooltips' words in order (their lines break where there is room)."""
    found = texts(svg)
    return (Counter((cls, t) for cls, t, _ in found if "note" not in cls and "tip" not in cls),
            " ".join(t for cls, t, _ in found if "tip" in cls))


@pytest.mark.parametrize("name", PHONE)
def test_on_a_phone_each_window_shows_the_same_words_at_least_9_px_high(name):
    svg = PHONE[name]()
    assert shown_words(svg) == shown_words(DRAWINGS[name]())
    small = [(t, round(size, 1)) for _, t, size in texts(svg, SHOWN_PX) if size < MIN_TEXT_PX]
    assert not small
    assert float(ET.fromstring(svg).attrib["viewBox"].split()[2]) == p.WIDTH


def test_a_phone_layout_that_leaves_out_a_control_or_draws_one_twice_is_refused():
    parts = p.JOINT_PARTS
    with pytest.raises(ValueError, match=r"buttonJointNext \(0 times\)"):
        p.assembly_phone("form", d.JOINT_VALUES, d.JOINT_TREE, parts[:-1], [], "joints")
    with pytest.raises(ValueError, match=r"label7 \(2 times\)"):
        p.assembly_phone("form", d.JOINT_VALUES, d.JOINT_TREE, (parts[0], *parts), [], "joints")
    wide = p.row(p.Cut(0, 0, 330, 30), p.Cut(535, 115, 705, 162))
    with pytest.raises(ValueError, match="more than"):
        p.assembly_phone("form", d.JOINT_VALUES, d.JOINT_TREE, (wide, *parts[1:]), [], "joints")


@pytest.fixture(scope="module")
def source():
    if not (e.MIRROR.exists()):
        pytest.skip(f"no copy of {e.REPOSITORY} at {e.MIRROR}: the lists cannot be re-read here")
    return {f: e.read_source(e.MIRROR, f).splitlines() for f in (e.DESIGNER, e.PROPERTY_MANAGER_SOURCE)}


def test_the_assembly_window_is_as_designer_cs_has_it(source):
    assert e.read_designer("\n".join(source[e.DESIGNER])) == e.ASSEMBLY_FORM
    for c in e.ASSEMBLY_FORM:
        if c.text:
            assert f'"{c.text}"'.replace("'", "\\'") in source[e.DESIGNER][c.line - 1] or \
                f'"{c.text}"' in source[e.DESIGNER][c.line - 1], c


def test_the_panels_words_are_where_the_list_says(source):
    lines = source[e.PROPERTY_MANAGER_SOURCE]
    for text, line in e.property_manager_strings().items():
        assert any(f'"{text}"' in ln for ln in lines[line - 1:line + 11]), (text, line)
    # the four labels said to be no longer added: their captions are set, never added
    for c in e.PROPERTY_MANAGER:
        if not c.added:
            block = "\n".join(lines[c.line - 1:c.line + 6])
            assert "AddControl2(" not in block.split("//Create")[0], c
