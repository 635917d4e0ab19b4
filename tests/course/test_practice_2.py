"""What the Practice 2 pages claim, checked against the model, the exported package and the drawings."""

import ast
import math
import re
import xml.etree.ElementTree as ET
from dataclasses import replace

import numpy as np
import pytest
import shapely
import trimesh
from assembly_drawings import assembly

import sw2sim
import mujoco
from course.drawing import angle_degrees, link_poses, part_drawing_svg, text_width
from course.exporter_format import csv_text, urdf_text
from course.parts import Angle, Box, Dimension, Material, Part
from course.practices import ROOT, load_script
from course.practices.practice_1 import design as practice_1
from course.practices.practice_2 import design, figures

PAGES = ROOT / "_pages" / "practice-2"
PACKAGE = ROOT / "examples" / "example_2"
WHEELS = ["front_left_joint", "front_right_joint", "rear_left_joint", "rear_right_joint"]
FRICTION_WHEELS = list(design.FRICTION_JOINTS)
FREE_WHEELS = [w for w in WHEELS if w not in FRICTION_WHEELS]
RADIUS = design.WHEEL_DIAMETER / 2000
NS = {"s": "http://www.w3.org/2000/svg"}


def page(name: str) -> str:
    return (PAGES / name).read_text()


def flat(text: str) -> str:
    """Page text with line breaks as spaces, so that a phrase may wrap."""
    return re.sub(r"\s+", " ", text)


def urdf_joints() -> dict[str, ET.Element]:
    root = ET.parse(PACKAGE / "urdf" / "example_2.urdf").getroot()
    return {j.get("name"): j for j in root.iter("joint")}


def rim_top(body) -> np.ndarray:
    """The top of a wheel's rim at rest: the point a radius along the wheel's own z."""
    return body.xpos + body.xmat.reshape(3, 3) @ [0, 0, RADIUS]


@pytest.fixture(scope="module")
def pulses():
    return load_script("examples/example_1/scripts/periodic_force.py")


@pytest.fixture(scope="module")
def locked():
    model = sw2sim.load_package(PACKAGE).compile()
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    return model, data


@pytest.fixture(scope="module")
def pulse_run(pulses):
    model = sw2sim.load_package(PACKAGE).compile()
    data = mujoco.MjData(model)
    t, tau, omega = pulses.run(model, data, WHEELS, duration=30.0)
    inertia = figures.axial_inertia(model, mujoco.MjData(model), WHEELS[0])
    return t, tau, omega, inertia


# --- the same wheel, a new base ------------------------------------------------------------------


def test_the_wheel_is_practice_1s_part():
    assert design.wheel is practice_1.wheel
    robot = design.robot()
    parts = {id(lk.part) for lk in robot.links if lk.name != "base_link"}
    assert len(parts) == 1, "the four wheel links share one part"
    practice_1_stl = (ROOT / "examples" / "example_1" / "meshes" / "front_left_wheel.STL").read_bytes()
    for name in design.SIDES:
        assert (PACKAGE / "meshes" / f"{name}.STL").read_bytes() == practice_1_stl, name


def test_the_base_keeps_practice_1s_plate_and_stubs():
    assert design.PLATE == practice_1.PLATE
    assert design.ARM_WIDTH == practice_1.ARM[0]
    assert design.AXLE_DIAMETER == practice_1.BORE_DIAMETER == practice_1.AXLE_DIAMETER
    assert design.AXLE_LENGTH == practice_1.AXLE_LENGTH and design.WHEEL_GAP == practice_1.WHEEL_GAP
    assert design.BEND == 45


def test_wheels_clear_the_base_at_rest_and_a_tumbling_wheel_would_not():
    """At rest each wheel touches the base only where its bore fits the stub; a wheel turned a
    quarter turn about a diameter (the reused-axis mistake) cuts into its stub."""
    robot = design.robot()
    poses = link_poses(robot)
    base = design.base().mesh
    quarter = trimesh.transformations.rotation_matrix(math.pi / 2, [1, 0, 0])
    for link in robot.links[1:]:
        for extra, check in ((np.eye(4), lambda v: v < 1e-9), (quarter, lambda v: v > 1e-5)):
            wheel = link.part.mesh.copy()
            wheel.apply_transform(poses[link.name] @ extra)
            common = trimesh.boolean.intersection([base, wheel], engine="manifold")
            assert check(0.0 if common.is_empty else common.volume), link.name


def test_each_stub_lies_on_its_wheels_axis():
    """The base's stubs, as drawn, point along the joint axes and pass through the wheel centres."""
    stubs = [f for f in design.base().features if type(f).__name__ == "Cylinder"]
    assert len(stubs) == 4
    for name in design.SIDES:
        axis = np.array(design.axle_direction(name))
        centre = np.array(design.wheel_centre(name)) / 1000
        matching = []
        for stub in stubs:
            a = math.radians(stub.yaw)
            direction = np.array([-math.sin(a), math.cos(a), 0.0])
            off_line = np.cross(np.asarray(stub.center) - centre, axis)
            if abs(abs(direction @ axis) - 1) < 1e-12 and np.linalg.norm(off_line) < 1e-12:
                matching.append(stub)
        assert len(matching) == 1, name


# --- the export -----------------------------------------------------------------------------------


def test_joint_origins_and_axes_as_in_the_table():
    text = page("02-exporting.md")
    joints = urdf_joints()
    for name in WHEELS:
        j = joints[name]
        xyz, rpy, axis = j.find("origin").get("xyz"), j.find("origin").get("rpy"), j.find("axis").get("xyz")
        assert f"| `{name}` | `{xyz}` | `{rpy}` | `{axis}` |" in text, name
        link = name.replace("_joint", "_wheel")
        assert [float(v) for v in xyz.split()] == pytest.approx(np.array(design.wheel_centre(link)) / 1000,
                                                                  abs=5e-6)
        yaw = float(rpy.split()[2])
        assert abs(yaw) == pytest.approx(math.radians(45), abs=5e-5)
        assert axis == "0 1 0"
    assert f"$$45 \\cdot \\frac{{\\pi}}{{180}} = {math.radians(45):.4f}$$" in text


def test_joint_names_are_practice_1s():
    assert [j.name for j in design.robot().joints] == [j.name for j in practice_1.robot().joints]


def test_friction_is_added_by_hand_to_the_front_joints_only():
    robot = design.robot()
    assert "<dynamics" not in urdf_text(robot, as_exported=True)
    assert "Dynamics" not in csv_text(robot).splitlines()[1]  # the CSV is the export: no friction in it
    for name, j in urdf_joints().items():
        dyn = j.find("dynamics")
        if name in FRICTION_WHEELS:
            assert dyn is not None and float(dyn.get("friction")) == design.FRICTION == 0.7
            assert float(dyn.get("damping")) == 0
        else:
            assert dyn is None, name


def test_gazebo_launch_starts_practice_1s_node_from_its_package():
    launch = ET.parse(PACKAGE / "launch" / "gazebo.launch").getroot()
    nodes = {n.get("name"): n for n in launch.iter("node")}
    node = nodes["periodic_force"]
    assert node.get("pkg") == "example_1" and node.get("type") == "periodic_force_node.py"
    script = ROOT / "examples" / "example_1" / "scripts" / node.get("type")
    assert script.is_file() and not (PACKAGE / "scripts").exists(), "reused, not copied"
    tree = ast.parse(script.read_text())
    names = next(ast.literal_eval(a.value) for a in tree.body if isinstance(a, ast.Assign)
                 and getattr(a.targets[0], "id", "") == "WHEEL_JOINTS")
    assert names == WHEELS, "Practice 1's node must find this model's joints by name"
    manifest = ET.parse(PACKAGE / "package.xml").getroot()
    assert "example_1" in [d.text for d in manifest.iter("depend")]


def test_pulse_code_is_imported_not_copied():
    assert figures.PULSE_SCRIPT == "examples/example_1/scripts/periodic_force.py"
    assert not list(ROOT.glob("course/practices/practice_2/*periodic*"))
    text = page("04-friction.md")
    assert 'sys.path.insert(0, "examples/example_1/scripts")' in text and "import periodic_force" in text
    assert "periodic_force.run(model, data, wheels" in text


# --- every wheel about its own inclined axis, from the simulation ------------------------------------


def test_each_wheel_turns_about_its_own_inclined_axis(locked):
    model, data = locked
    lines = {}
    for name in WHEELS:
        j = model.joint(name).id
        axis, anchor = data.xaxis[j].copy(), data.xanchor[j].copy()
        link = name.replace("_joint", "_wheel")
        # the exporter keeps 5 digits of the yaw (0.7854 rad): a few micro-radians off 45°
        assert axis == pytest.approx(design.axle_direction(link), abs=1e-5)
        assert axis[2] == pytest.approx(0, abs=1e-12), "level"
        assert math.degrees(math.acos(abs(axis[1]))) == pytest.approx(45, abs=1e-3)
        centre = np.array(design.wheel_centre(link)) / 1000 + [0, 0, practice_1.STAND_HEIGHT / 1000]
        assert anchor == pytest.approx(centre, abs=5e-6)
        lines[name] = (anchor, axis)
    # no two wheels share a line: crossing directions, or parallel lines apart
    for i, a in enumerate(WHEELS):
        for b in WHEELS[i + 1:]:
            (pa, ua), (pb, ub) = lines[a], lines[b]
            if abs(abs(ua @ ub) - 1) < 1e-9:
                assert np.linalg.norm(np.cross(pb - pa, ua)) > 0.08, (a, b)
            else:
                assert abs(ua @ ub) < 1e-5, (a, b)  # here the others cross at 90°
    fl, rr = lines["front_left_joint"], lines["rear_right_joint"]
    gap = np.linalg.norm(np.cross(rr[0] - fl[0], fl[1]))
    for name in ("01-modelling.md", "03-testing-and-modifying.md"):
        assert f"{gap * 1000:.0f} mm apart" in flat(page(name))


def test_rims_stay_in_their_planes_while_driven(pulses):
    model = sw2sim.load_package(PACKAGE).compile()
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    bodies = {name: data.body(name.replace("_joint", "_wheel")) for name in WHEELS}
    rest = {n: (b.xpos.copy(), b.xmat.reshape(3, 3)[:, 1].copy(), rim_top(b).copy()) for n, b in bodies.items()}
    dofs = [model.joint(n).dofadr[0] for n in WHEELS]
    worst = dict.fromkeys(WHEELS, 0.0)
    while data.time < 0.5:
        data.qfrc_applied[dofs] = pulses.wheel_torque(data.time)
        mujoco.mj_step(model, data)
        for name, body in bodies.items():
            centre, normal, _ = rest[name]
            top = rim_top(body)
            worst[name] = max(worst[name], abs((top - centre) @ normal))
            assert np.linalg.norm(top - centre) == pytest.approx(RADIUS, abs=1e-9)
    for name, body in bodies.items():
        assert worst[name] < 1e-9, name
        assert np.linalg.norm(rim_top(body) - rest[name][2]) > 0.05, f"{name} did not turn"


def test_a_reused_axis_makes_the_wheel_tumble():
    assert figures.wrong_axis_in_frame("front_right_wheel", "front_left_wheel") == pytest.approx([1, 0, 0])
    assert figures.wrong_axis_in_frame("rear_right_wheel", "front_left_wheel") == pytest.approx([0, 1, 0])

    def out_of_plane(axis=None):
        spec = sw2sim.load_package(PACKAGE)
        if axis is not None:
            spec.joint("front_right_joint").axis = axis
        model = spec.compile()
        data = mujoco.MjData(model)
        body = data.body("front_right_wheel")
        mujoco.mj_forward(model, data)
        centre, normal = body.xpos.copy(), body.xmat.reshape(3, 3)[:, 1].copy()
        data.qpos[model.joint("front_right_joint").qposadr[0]] = math.pi / 2
        mujoco.mj_forward(model, data)
        return abs(float((rim_top(body) - centre) @ normal))

    assert out_of_plane() < 1e-12
    assert out_of_plane([1, 0, 0]) == pytest.approx(RADIUS, abs=1e-9)
    assert "it equals the wheel's radius" in flat(page("02-exporting.md"))


# --- the unlocked base ------------------------------------------------------------------------------


def test_free_base_stays_put_and_its_wheels_stop_on_the_floor():
    t1, travel1, _, _ = figures.free_run("examples/example_1", False)
    t2, travel2, yaw2, speed2 = figures.free_run(str(PACKAGE), False)
    assert travel1[-1] > 1.0, "Practice 1's free base drives off"
    assert travel2.max() < 0.01 and np.abs(yaw2).max() < 1.0, "Practice 2's does not move"
    landed = t2 > 0.3
    assert np.abs(speed2[landed]).max() < 0.1, "the floor holds every wheel"
    assert np.abs(speed2[~landed]).max() > 1.0, "they spin while the model drops"
    _, _, _, speed_locked = figures.free_run(str(PACKAGE), True)
    rear_left = WHEELS.index("rear_left_joint")
    assert speed_locked[-1, rear_left] == pytest.approx(62.6, abs=0.05)
    assert "gains 62.6 rad/s" in flat(page("03-testing-and-modifying.md"))


def test_the_floor_holds_more_than_the_push(locked):
    """The page: the floor's friction holds each wheel with far more than 10 N."""
    model, _ = locked
    weight = model.body_subtreemass[model.body("base_link").id] * -model.opt.gravity[2]
    floor = model.geom("floor").id
    wheel_geoms = [g for g in range(model.ngeom) if model.geom_group[g] == 0
                   and model.body(model.geom_bodyid[g]).name.endswith("_wheel")]
    mu = min(max(model.geom_friction[floor, 0], model.geom_friction[g, 0]) for g in wheel_geoms)
    push = 1.0 / RADIUS
    assert push == pytest.approx(10)
    assert mu * weight / 4 > 3 * push
    assert "more than the 10 N that 1 N·m makes at a 0.1 m tyre" in flat(page("03-testing-and-modifying.md"))


def test_reversed_right_axes_turn_the_free_base_on_the_spot():
    spec = sw2sim.load_package(PACKAGE, fixed_base=False)
    for name in ("front_right_joint", "rear_right_joint"):
        spec.joint(name).axis = [0, -1, 0]
    model = spec.compile()
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    base = data.body("base_link")
    start = base.xpos.copy()
    dofs = [model.joint(n).dofadr[0] for n in WHEELS]
    while data.time < 3.0:
        data.qfrc_applied[dofs] = 1.0 if data.time < 1.0 else 0.0
        mujoco.mj_step(model, data)
    heading = math.degrees(math.atan2(base.xmat[3], base.xmat[0]))
    assert abs(heading) > 20 and np.linalg.norm((base.xpos - start)[:2]) < 0.05


# --- friction -----------------------------------------------------------------------------------------


def test_urdf_friction_becomes_mujoco_frictionloss(locked):
    model, _ = locked
    for name in WHEELS:
        dof = model.joint(name).dofadr[0]
        assert model.dof_frictionloss[dof] == (0.7 if name in FRICTION_WHEELS else 0.0)
        assert model.dof_damping[dof] == 0.0


def test_friction_wheels_spin_slower_and_stop_between_pulses_while_the_others_coast(pulse_run):
    t, tau, omega, _ = pulse_run
    fr = [WHEELS.index(n) for n in FRICTION_WHEELS]
    free = [WHEELS.index(n) for n in FREE_WHEELS]
    assert omega[:, fr].max() < 0.35 * omega[:, free].max()
    for start in (0.0, 10.0, 20.0):
        between = (t > start + 2) & (t < start + 9.99)
        assert np.abs(omega[between][:, fr]).max() < 1e-3, "friction wheels stand still between pulses"
        coast = omega[between][:, free]
        assert np.ptp(coast, axis=0).max() < 1e-9 and coast.min() > 60, "the others keep their speed"
    assert omega[-1, free] == pytest.approx([3 * omega[np.searchsorted(t, 5.0), free[0]]] * 2, rel=1e-3)


def test_deceleration_after_a_pulse_is_friction_over_inertia(pulse_run, pulses):
    t, _, omega, inertia = pulse_run
    assert inertia == pytest.approx(design.wheel().mass_properties()[2][1, 1], rel=1e-6)
    i = WHEELS.index("front_left_joint")
    for start in (0.0, 10.0, 20.0):
        braking = (t > start + pulses.PULSE + 0.05) & (t < start + pulses.PULSE + 0.35)
        slope = np.polyfit(t[braking], omega[braking, i], 1)[0]
        assert -slope == pytest.approx(design.FRICTION / inertia, rel=0.05)
        rising = (t > start + 0.05) & (t < start + 0.95)
        gain = np.polyfit(t[rising], omega[rising, i], 1)[0]
        assert gain == pytest.approx((pulses.TORQUE - design.FRICTION) / inertia, rel=0.05)


def test_friction_numbers_on_the_page(pulse_run, pulses):
    t, _, omega, inertia = pulse_run
    torque, pulse, friction = pulses.TORQUE, pulses.PULSE, design.FRICTION
    peak = (torque - friction) * pulse / inertia
    stop = (torque - friction) * pulse / friction
    i = WHEELS.index("front_left_joint")
    assert omega[:, i].max() == pytest.approx(peak, rel=0.01)
    measured_stop = t[(t > pulse) & (omega[:, i] < 0.01 * peak)][0]
    assert measured_stop == pytest.approx(pulse + stop, abs=0.011)
    text = flat(page("04-friction.md"))
    assert "TORQUE, PULSE, FRICTION = 1.0, 1.0, 0.7" in text
    assert (torque, pulse, friction) == (1.0, 1.0, 0.7)
    claims = [f"{torque - friction:.1f} N·m net", f"{(torque - friction) / inertia:.1f} rad/s² for one second",
              f"{peak:.1f} rad/s when the pulse ends", f"{torque * pulse / inertia:.1f} rad/s without friction",
              f"{friction / inertia:.1f} rad/s² of braking", f"still {stop:.2f} s after the pulse",
              f"at {pulse + stop:.2f} s", f"climbs by {torque * pulse / inertia:.1f} rad/s with every pulse",
              f"climbs to only {peak:.1f} rad/s", f"stop {stop:.2f} s after each pulse"]
    for claim in claims:
        assert claim in text, claim


# --- numbers on the other pages ---------------------------------------------------------------------


def test_modelling_page_numbers():
    text = flat(page("01-modelling.md"))
    lx, ly, lz = design.PLATE
    assert f"{lx} × {ly} mm, {lz} mm thick" in text
    assert f"two {design.ARM_WIDTH} mm arms with {lx - 2 * design.ARM_WIDTH} mm between them" in text
    assert f"{design.BEND}° away from the middle after {design.STRAIGHT} mm" in text
    assert f"another {design.BENT} mm" in text
    assert f"Ø{design.AXLE_DIAMETER} mm and {design.AXLE_LENGTH} mm long" in text
    assert f"*distance* {design.WHEEL_GAP} mm" in text
    wheel, base, old_base = design.wheel().mass, design.base().mass, practice_1.base().mass
    # The exact solids' masses (what SolidWorks shows) are checked in test_tool_facts.py.
    assert f"prints {wheel:.3f} kg for the wheel" in text and f"base {base:.3f} kg" in text
    assert f"Practice 1's {old_base:.3f} kg" in text and base > old_base
    yaws = {name: design.axle_yaw(*design.SIDES[name]) for name in design.SIDES}
    assert yaws["front_left_wheel"] == yaws["rear_right_wheel"] == -45  # clockwise seen from above
    assert yaws["front_right_wheel"] == yaws["rear_left_wheel"] == 45
    assert "front-left and rear-right frames are turned 45° clockwise" in text


def test_testing_page_numbers(locked):
    model, data = locked
    text = flat(page("03-testing-and-modifying.md"))
    assert f"{practice_1.STAND_HEIGHT / 1000:g} m above the floor" in text
    assert data.body("base_link").xpos[2] == pytest.approx(practice_1.STAND_HEIGHT / 1000)
    assert f"the {RADIUS:g} m wheels" in text


# --- the drawings ---------------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def base_svg():
    return part_drawing_svg(design.base())


def view_texts(svg: str, view: str) -> list[ET.Element]:
    group = ET.fromstring(svg).find(f".//s:g[@id='view-{view}']", NS)
    return [el for el in group.iter() if el.tag.endswith("text") and el.text != view.upper()]


def expected(dim) -> str:
    """The text a dimension must show, worked out here from its points."""
    if dim.label is not None:
        return dim.label
    axes = {"front": (0, 2), "top": (0, 1), "side": (1, 2)}[dim.view]
    if isinstance(dim, Angle):
        a = np.array([dim.a[i] - dim.vertex[i] for i in axes])
        b = np.array([dim.b[i] - dim.vertex[i] for i in axes])
        return f"{math.degrees(math.acos(a @ b / np.linalg.norm(a) / np.linalg.norm(b))):.2f}".rstrip("0").rstrip(".") + "°"
    delta = np.array([dim.b[i] - dim.a[i] for i in axes])
    value = {"h": abs(delta[0]), "v": abs(delta[1]), "a": np.linalg.norm(delta)}[dim.direction]
    return f"{round(value * 1000, 2):g}"


def test_base_drawing_shows_every_dimension_with_its_value(base_svg):
    part = design.base()
    for view in ("front", "top", "side"):
        wanted = sorted(expected(d) for d in part.dimensions if d.view == view)
        assert sorted(el.text for el in view_texts(base_svg, view)) == wanted, view
    top = [el.text for el in view_texts(base_svg, "top")]
    for shown in ("45°", "220", "100", "30", "90", "50", "40", "Ø20"):
        assert shown in top


def test_the_45_degree_bend_is_an_angle_dimension(base_svg):
    angles = [d for d in design.base().dimensions if isinstance(d, Angle)]
    assert len(angles) == 1 and angle_degrees(angles[0]) == pytest.approx(design.BEND)
    k = 200.0  # 1:5
    assert "1:5" in base_svg
    top = ET.fromstring(base_svg).find(".//s:g[@id='view-top']", NS)
    arcs = [p for p in top.iter() if p.tag.endswith("path") and "A" in p.get("d", "")]
    assert [float(re.search(r"A([\d.]+) ", a.get("d")).group(1)) for a in arcs] == pytest.approx([k * angles[0].radius])


def test_base_drawing_texts_do_not_overlap(base_svg):
    for view in ("front", "top", "side"):
        boxes = []
        for el in view_texts(base_svg, view):
            x, y, size = float(el.get("x")), float(el.get("y")), float(el.get("font-size"))
            w = text_width(el.text, size)
            start = {"start": 0, "middle": -w / 2, "end": -w}[el.get("text-anchor", "start")]
            box = shapely.box(x + start, y - 0.8 * size, x + start + w, y + 0.2 * size)
            turn = re.search(r"rotate\((-?[\d.]+)", el.get("transform", ""))
            if turn:
                box = shapely.affinity.rotate(box, float(turn.group(1)), origin=(x, y))
            boxes.append(box)
        for i, a in enumerate(boxes):
            for b in boxes[i + 1:]:
                assert not a.intersects(b), view


def test_aligned_dimension_measures_along_a_turned_part():
    steel = Material("Steel", 7850.0)
    c, s = math.cos(math.radians(30)), math.sin(math.radians(30))
    bar = Part("bar", steel, [Box((0.01, 0.1, 0.01), yaw=30)],
               [Dimension("top", (0.05 * s, -0.05 * c, 0), (-0.05 * s, 0.05 * c, 0), "a", 0.02),
                Angle("top", (0, 0, 0), (0, 0.01, 0), (-s * 0.01, c * 0.01, 0), 0.04)])
    svg = part_drawing_svg(bar)
    shown = sorted(el.text for el in view_texts(svg, "top"))
    assert shown == ["100", "30°"]
    rotated = [el for el in view_texts(svg, "top") if el.text == "100"][0]
    assert rotated.get("transform", "").startswith("rotate(60 "), "it reads along the bar, down to the right"


def test_bad_dimensions_are_refused():
    base = design.base()
    with pytest.raises(ValueError, match=r"base_link.*'x'"):
        part_drawing_svg(replace(base, dimensions=[Dimension("top", (0, 0, 0), (0.1, 0, 0), "x")]))
    with pytest.raises(ValueError, match=r"base_link.*zero length"):
        part_drawing_svg(replace(base, dimensions=[Angle("top", (0, 0, 0), (0, 0, 0.1), (0.1, 0, 0))]))


def test_assembly_drawing_names_every_joint():
    _, svg = assembly("practice_2")
    texts = [el.text for el in ET.fromstring(svg).iter() if el.tag.endswith("text")]
    for name in WHEELS:
        assert name in texts
    assert "Wheel (wheel.SLDPRT)" in texts and "Base (base_link.SLDPRT)" in texts
