"""A model as MuJoCo's WebAssembly build reads it: the one place where the two MuJoCo
versions of this repository stand side by side.

The Python lessons and `sw2sim` run on pip's `mujoco` (pinned in requirements.txt); the
site's Simulate mode runs on npm's `@mujoco/mujoco` (pinned in package.json), which is a
release behind. A model written by `MjSpec.to_xml` in the first may hold what the second
cannot read, or steps differently; `browser_form` rewrites those parts, each one only where
the rewrite leaves the motion in the Python version unchanged
(tests/course/test_browser_models.py checks that in Python, and under Node that the
browser's version loads every practice's model and steps the rewritten one as Python
steps the original).
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
ACTUATORS = ("general", "position", "velocity", "motor")

# A joint's `actuatorfrcrange` (the URDF's effort limit, as the loader writes it) caps the
# force of the actuators on the joint. With a velocity term in the bias (a position
# actuator's kv) and the implicitfast integrator, 3.14 and 4.0 step such a joint apart
# once the cap acts (Practice 5's steering: 0.0328 against 0.0362 rad after 10 ms), while
# both step alike with the same cap on the actuator's own `forcerange`, and 4.0 gives the
# same motion either way. So where one actuator drives a joint, its cap moves there.


# The name the XML of MuJoCo's to_xml is parsed under: text MuJoCo wrote, no file of the user's.
WRITTEN = "mujoco-to_xml"


def browser_form(xml: str) -> str:
    """`xml` (a model written by MuJoCo PYTHON_MUJOCO) in the form BROWSER_MUJOCO reads and
    steps as PYTHON_MUJOCO steps the original."""
    root = parse_bytes(xml.encode("utf-8"), url=WRITTEN)
    changed = False
    actuators = [element for element in root.iter(*ACTUATORS)]
    for element in actuators:
        if (element.get("input") in SIGNATURE_ONLY
                and element.get("gaintype", "fixed") == "fixed"):
            del element.attrib["input"]
            changed = True
    for joint in root.iter("joint"):
        limit = joint.get("actuatorfrcrange")
        driving = [a for a in actuators if a.get("joint") == joint.get("name")]
        if limit is None or len(driving) != 1 or joint.get("actuatorfrclimited") == "false":
            continue
        actuator = driving[0]
        gear = float((actuator.get("gear") or "1").split()[0])
        if gear == 0:
            continue
        low, high = sorted(float(x) / gear for x in limit.split())
        if actuator.get("forcelimited") == "true" and actuator.get("forcerange"):
            own_low, own_high = (float(x) for x in actuator.get("forcerange").split())
            low, high = max(low, own_low), min(high, own_high)
        actuator.set("forcelimited", "true")
        actuator.set("forcerange", f"{low!r} {high!r}")
        del joint.attrib["actuatorfrcrange"]
        joint.attrib.pop("actuatorfrclimited", None)
        changed = True
    if not changed:
        return xml
    return etree.tostring(root, encoding="unicode") + "\n"
