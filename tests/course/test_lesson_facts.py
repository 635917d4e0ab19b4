"""Numbers and words of the lessons that other tests did not reach, checked against the
designs, the example packages, the simulation and the figures' code.
"""

from __future__ import annotations

import ast
import inspect
import math
import re

import pytest
import mujoco
import numpy as np
import sw2sim
from lxml import etree
from page_text import flat_page as flat

from course.practices import ROOT, design
from course.practices.practice_3 import figures as practice_3_figures
from course.practices.practice_4 import figures as practice_4_figures

PAGES = ROOT / "_pages"


# ---- Practice 5's export page: the controllers the launch starts, the car's height ----------

def test_practice_5_counts_the_controllers_its_launch_file_spawns():
    launch = etree.parse(str(ROOT / "examples/example_5/launch/gazebo.launch"))
    spawner, = launch.xpath("//node[@pkg='controller_manager' and @type='spawner']")
    spawned = spawner.get("args").split()
    joints = etree.parse(str(ROOT / "examples/example_5/urdf/example_5.urdf")).xpath(
        "//joint[@type!='fixed']")
    assert len(spawned) == 8 == len(joints) + 1 and spawned[0] == "joint_state_controller"
    text = flat("practice-5/02-exporting.md")
    assert "nine controllers" not in text
    assert "starts eight controllers" in text and "each of the seven joints" in text


def test_practice_5_explains_the_height_it_prints():
    p5 = design("practice_5")
    model = sw2sim.load_package(ROOT / "examples/example_5", fixed_base=False).compile()
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    radius = p5.WHEEL_RADIUS / 1000
    printed = f"{data.qpos[2]:.3f}"
    assert data.qpos[2] == pytest.approx(radius + 0.001, abs=1e-6)
    while data.time < 1.0:
        mujoco.mj_step(model, data)
    assert radius - 0.001 < data.qpos[2] < radius, "settles a fraction of a millimetre lower"
    text = flat("practice-5/02-exporting.md")
    assert f"the printout says {printed} m" in text and f"{radius:.2f} m, the wheels' radius" in text
    assert "1 mm above the floor" in text


# ---- Practice 2: a turn on the spot needs sideways slip --------------------------------------

def test_practice_2s_turn_on_the_spot_slips_sideways():
    p2 = design("practice_2")
    miss, reach = set(), set()
    for link in p2.SIDES:
        x, y, _ = (v / 1000 for v in p2.wheel_centre(link))
        ax, ay, _ = p2.axle_direction(link)
        miss.add(round(abs(x * ay - y * ax), 6))           # axle line to the centre
        reach.add(round(math.hypot(x, y), 6))              # wheel to the centre
    (d,), (r,) = miss, reach
    lever = math.sqrt(r * r - d * d)                        # the push's lever about the centre
    text = flat("practice-2/03-testing-and-modifying.md")
    assert "which these wheels can do by rolling" not in text
    assert f"passes {d * 1000:.0f} mm from the base's centre" in text
    assert f"sideways {d / r * 100:.0f} cm for every metre it travels" in text
    assert f"a lever of only {d * 1000:.0f} mm" in text and f"one of {lever * 1000:.0f} mm" in text
    # "The pushes win": 1 N·m at each 0.1 m tyre against the most friction the floor can
    # give each wheel sideways (a quarter of the weight, times the friction coefficient)
    model = sw2sim.load_package(ROOT / "examples/example_2", fixed_base=False).compile()
    weight = model.body_subtreemass[model.body("base_link").id] * -model.opt.gravity[2]
    floor = model.geom("floor").id
    wheels = [g for g in range(model.ngeom) if model.geom_group[g] == 0
              and model.body(model.geom_bodyid[g]).name.endswith("_wheel")]
    mu = max(max(model.geom_friction[floor, 0], model.geom_friction[g, 0]) for g in wheels)
    push = 1.0 / (p2.WHEEL_DIAMETER / 2000)
    assert 4 * push * lever > 4 * mu * weight / 4 * d
    assert mujoco.mjtJoint.mjJNT_FREE in list(model.jnt_type)


# ---- Practice 4: how long the whole travel takes ---------------------------------------------

def test_practice_4s_pages_agree_on_how_long_the_whole_travel_takes():
    p4 = design("practice_4")
    t, _, q, _, _ = practice_4_figures.long_move().states()
    arrived = t[np.argmax(np.abs(q - p4.UPPER) < 0.001)]          # within the 1 mm tolerance
    exporting = flat("practice-4/02-exporting.md")
    testing = flat("practice-4/04-testing-and-scripting.md")
    assert "under three seconds" not in exporting
    assert f"travel in {p4.UPPER / p4.VELOCITY:.2f} s" in exporting
    assert 3.0 < arrived < 3.5 and "a little over three seconds" in exporting
    said = float(re.search(r"The move takes about (\d\.\d) s", testing).group(1))
    assert 3.0 < said < 3.5 and abs(said - arrived) <= 0.1, (said, arrived)


# ---- the home page's promise about the scripts -----------------------------------------------

def test_the_home_page_describes_the_scripts_as_the_pages_present_them():
    text = flat("index.md")
    assert "line by line" not in text
    assert "Every script is printed whole on its page" in text
    long_ones = {"practice-3/05-position-control.md": "examples/example_3/scripts/arm_controller.py",
                 "practice-5/04-control-script.md": "examples/example_5/scripts/ackermann.py"}
    for page, script in long_ones.items():
        assert f"{{% include_code {script} %}}" in (PAGES / page).read_text(encoding="utf-8")
        source = (ROOT / script).read_text(encoding="utf-8")
        assert len(source.splitlines()) > 150, f"{script} is one of the two long ones"
        assert source.startswith('"""'), f"{script} opens with a docstring"
    assert "the arm controller of Practice 3 and the car's script of Practice 5" in text
    pages = " ".join(path.read_text(encoding="utf-8") for path in PAGES.glob("*/*.md"))
    scripts = sorted(ROOT.glob("examples/example_*/scripts/*.py"))
    for script in scripts:
        assert f"{{% include_code {script.relative_to(ROOT).as_posix()} %}}" in pages, script
    long = {s.relative_to(ROOT).as_posix() for s in scripts if len(s.read_text().splitlines()) > 150}
    assert long == set(long_ones.values())


# ---- Practice 3: the colours a caption names are the figure's --------------------------------

def test_the_random_setpoints_caption_names_the_colours_figures_py_draws():
    """The figure is drawn by setpoints() in course/practices/practice_3/figures.py."""
    colours = {}
    for call in ast.walk(ast.parse(inspect.getsource(practice_3_figures.setpoints))):
        if isinstance(call, ast.Call) and getattr(call.func, "attr", None) == "plot":
            words = {k.arg: k.value.value for k in call.keywords if isinstance(k.value, ast.Constant)}
            what = ast.unparse(call.args[-1])
            name = next(n for n in ("set_point", "process_value", "error") if n in what)
            colours[name] = words["color"].removeprefix("tab:")
    text = (PAGES / "practice-3/05-position-control.md").read_text(encoding="utf-8")
    caption = text[text.index("(/media/practice-3/random_setpoints.png)"):].split("\n")[1]
    assert f"set point ({colours['set_point']})" in caption
    assert f"the position ({colours['process_value']})" in caption
    assert f"The error ({colours['error']})" in caption
