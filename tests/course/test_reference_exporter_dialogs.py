"""The schematics of the exporter's windows use the exporter's own words only, and those words
(course/exporter_dialogs.py) are the ones its source has, where the list says."""

import xml.etree.ElementTree as ET

import pytest

from course import dialog_schematics as d
from course import exporter_dialogs as e

SVG = "{http://www.w3.org/2000/svg}"
DRAWINGS = {"panel": d.property_manager, "joints": d.joint_window, "links": d.link_window}


def texts(svg: str) -> list[tuple[str, str, float]]:
    """(class, text, font size in px as shown 736 px wide) of every text of a drawing."""
    root = ET.fromstring(svg)
    width = float(root.attrib["viewBox"].split()[2])
    out = []
    for t in root.iter(f"{SVG}text"):
        style = dict(part.split(":") for part in t.attrib.get("style", "").split(";") if part)
        size = float(style.get("font-size", f"{d.SIZE}px").rstrip("px"))
        cls = t.attrib["class"]
        if "title" in cls:
            size = 12
        out.append((cls, t.text, size * min(1.0, 736 / width)))
    return out


def known_words() -> set[str]:
    return ({c.text for c in e.ASSEMBLY_FORM if c.text} | set(e.property_manager_strings())
            | {e.FORM_TITLE[0]})


@pytest.mark.parametrize("name", DRAWINGS)
def test_every_label_drawn_is_one_of_the_exporters(name):
    labels = [(cls, t) for cls, t, _ in texts(DRAWINGS[name]()) if cls.split()[0] == "label"]
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
