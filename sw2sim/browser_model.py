"""A model as MuJoCo's WebAssembly build reads it: the one place where the two MuJoCo
versions of this repository stand side by side.

The Python lessons and `sw2sim` run on pip's `mujoco` (pinned in requirements.txt); the
site's Simulate mode runs on npm's `@mujoco/mujoco` (pinned in package.json), which is a
release behind. A model written by `MjSpec.to_xml` in the first may hold what the second
cannot read; `browser_form` rewrites those parts, each one only where the rewrite leaves the
compiled model's dynamics unchanged (tests/tool/test_browser_model.py checks that in Python,
and that the browser's version loads every practice's model under Node).
"""

from __future__ import annotations

from lxml import etree

from .xmlsafe import parse_bytes

PYTHON_MUJOCO = "4.0.0"    # requirements.txt: mujoco==
BROWSER_MUJOCO = "3.14.0"  # package.json: "@mujoco/mujoco"

# MuJoCo 4.0 writes a position or velocity actuator as <general input="pos"> (or "vel"):
# its input signature, `actuator_ctrlspec`, which 4.0 declares in mjtCtrlInput (mjtype.h)
# and uses only to name the control; the force comes from gainprm, biasprm and biastype
# alone. 3.14 knows `input` only for so3, pid and dcmotor actuators and refuses the model,
# so it is left out where the gain is the plain fixed one.
SIGNATURE_ONLY = {"pos", "vel"}
ACTUATORS = ("general", "position", "velocity")


def browser_form(xml: str) -> str:
    """`xml` (a model written by MuJoCo PYTHON_MUJOCO) in the form BROWSER_MUJOCO also reads."""
    root = parse_bytes(xml.encode("utf-8"))
    changed = False
    for element in root.iter(*ACTUATORS):
        if (element.get("input") in SIGNATURE_ONLY
                and element.get("gaintype", "fixed") == "fixed"):
            del element.attrib["input"]
            changed = True
    if not changed:
        return xml
    return etree.tostring(root, encoding="unicode") + "\n"

