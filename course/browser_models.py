"""Each practice's model and lesson settings for the Simulate mode of its 3D viewer,
written to media/practice-N/simulate.json; `python -m course.browser_models` brings them
up to date (`--check`: list the stale ones, exit 1).

The model is built as the practice's Python lesson builds it (`sw2sim.load_package`, the
lesson script's time step, `add_motors` where the lesson drives motors), written by MuJoCo
itself and put in the form the browser's MuJoCo reads (`sw2sim.browser_model`). Its meshes
are not copied: the file names where the browser fetches each one, in the published
package. The settings are the lesson script's own constants and the package's files, so
that assets/js/simulation-worker.js runs the lesson's controllers with the same numbers.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import mujoco

import sw2sim
from sw2sim.browser_model import BROWSER_MUJOCO, PYTHON_MUJOCO, browser_form
from sw2sim.ros_control import add_motors, read_controllers, read_joint_limits

from .practices import ROOT, load_script

WHEELS = ["front_left_joint", "front_right_joint", "rear_left_joint", "rear_right_joint"]
FRICTION_RANGE = (0.0, 2.0)   # N·m: from none to twice the pulse's torque
# N·m: the wheels' joints are continuous with no <limit>, so no effort limit: the control
# offers five times the lesson's torque either way.
TORQUE_RANGE = (-5.0, 5.0)
CAR_TOP_SPEED = 1.5   # m/s either way, as drive.py's keys allow (TOP_SPEED)
# m/s and rad the car starts with: the run of _pages/practice-5/04-control-script.md,
# car.command(speed=0.5, steering=0.3), whose path the page compares with Eq. 4's radius
CAR_START = {"speed": 0.5, "steering": 0.3}
POSITION_SCRIPTS = {3: "examples/example_3/scripts/arm_controller.py",
                    4: "examples/example_4/scripts/slider_controller.py"}


def model_xml(practice: int, spec: mujoco.MjSpec) -> tuple[str, dict[str, str]]:
    """The model's XML as MuJoCo writes it, with mesh files named from the package root, and
    where the browser fetches each one (a path from the site's root)."""
    package = ROOT / f"examples/example_{practice}"
    files = {}
    for mesh in spec.meshes:
        relative = Path(mesh.file).resolve().relative_to(package).as_posix()
        files[relative] = f"examples/example_{practice}/{relative}"
        mesh.file = relative
    spec.meshdir = ""
    spec.modelfiledir = str(package)   # to_xml compiles: it must find the meshes
    return spec.to_xml(), files


def _limits(limits) -> dict:
    return {key: getattr(limits, key) for key in (
        "lower", "upper", "effort", "velocity", "soft_lower", "soft_upper",
        "k_position", "k_velocity")}


def _pulse(practice: int) -> tuple[mujoco.MjSpec, dict]:
    """Practices 1 and 2: Practice 1's periodic torque on every wheel (periodic_force.py)."""
    periodic = load_script("examples/example_1/scripts/periodic_force.py")
    spec = sw2sim.load_package(ROOT / f"examples/example_{practice}")
    model = spec.compile()
    settings = {"kind": "pulse", "joints": WHEELS, "period": periodic.PERIOD,
                "pulse": periodic.PULSE, "torque": periodic.TORQUE,
                "torque_range": list(TORQUE_RANGE)}
    if practice == 2:
        settings["friction"] = {j: float(model.dof_frictionloss[model.joint(j).dofadr[0]])
                                for j in WHEELS}
        settings["friction_range"] = list(FRICTION_RANGE)
    return spec, settings


def _position(practice: int) -> tuple[mujoco.MjSpec, dict]:
    """Practices 3 and 4: effort-based position controllers (arm_controller.py's)."""
    lesson = load_script(POSITION_SCRIPTS[practice])
    package = ROOT / f"examples/example_{practice}"
    spec = sw2sim.load_package(package)
    spec.option.timestep = lesson.TIMESTEP
    motors = add_motors(spec, package)
    settings = read_controllers(package / "config" / f"joint_names_{spec.modelname}.yaml")
    limits = read_joint_limits(package)
    model = spec.compile()
    motor_of = {model.actuator(m).trnid[0]: i for i, m in enumerate(motors)}
    controllers = []
    for name, c in settings[spec.modelname].items():
        if c.get("type") != lesson.POSITION_CONTROLLER:
            continue
        acceleration = (lesson.ACCELERATION[c["joint"]] if isinstance(lesson.ACCELERATION, dict)
                        else lesson.ACCELERATION)
        controllers.append({
            "name": name, "joint": c["joint"], "motor": motor_of[model.joint(c["joint"]).id],
            "pid": {"p": 0.0, "i": 0.0, "d": 0.0, "i_clamp": 0.0, "antiwindup": False, **c["pid"]},
            "limits": _limits(limits[c["joint"]]), "acceleration": acceleration})
    cruise = load_script(POSITION_SCRIPTS[3]).CRUISE
    return spec, {"kind": "position", "controllers": controllers, "cruise": cruise,
                  "unit": "m" if practice == 4 else "rad"}


def _car(practice: int) -> tuple[mujoco.MjSpec, dict]:
    """Practice 5: the car of ackermann.py, driven by a speed and a steering angle."""
    lesson = load_script("examples/example_5/scripts/ackermann.py")
    package = ROOT / f"examples/example_{practice}"
    spec = lesson.car_spec(package)
    model = spec.compile()
    geometry = lesson.measure(model)
    actuator = {model.joint(model.actuator_trnid[a, 0]).name: a for a in range(model.nu)}
    steering = model.joint(lesson.STEERING)
    return spec, {
        "kind": "car", "steering": lesson.STEERING, "knuckles": list(lesson.KNUCKLES.values()),
        "wheels": lesson.WHEELS, "actuator": actuator, "control_rate": lesson.CONTROL_RATE,
        "geometry": {"wheelbase": geometry.wheelbase, "track": geometry.track,
                     "radius": geometry.radius},
        "steering_range": [float(x) for x in model.jnt_range[steering.id]],
        "speed_range": [-CAR_TOP_SPEED, CAR_TOP_SPEED], "start": CAR_START}


LESSONS = {1: _pulse, 2: _pulse, 3: _position, 4: _position, 5: _car}


def output(practice: int) -> Path:
    return ROOT / f"media/practice-{practice}/simulate.json"


def build(practice: int) -> str:
    """The text of media/practice-N/simulate.json."""
    spec, settings = LESSONS[practice](practice)
    xml, files = model_xml(practice, spec)
    return json.dumps({
        "practice": practice, "mujoco": {"python": PYTHON_MUJOCO, "browser": BROWSER_MUJOCO},
        "timestep": spec.option.timestep, "model": browser_form(xml), "files": files,
        "lesson": settings,
    }, indent=1) + "\n"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m course.browser_models",
                                     description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="change nothing; exit 1 if stale")
    args = parser.parse_args(argv)
    stale = []
    for practice in LESSONS:
        text, path = build(practice), output(practice)
        if path.exists() and path.read_text(encoding="utf-8") == text:
            continue
        stale.append(path.relative_to(ROOT).as_posix())
        if not args.check:
            path.write_text(text, encoding="utf-8", newline="\n")
    for name in stale:
        print(f"   {'stale' if args.check else 'wrote'} {name}")
    return 1 if args.check and stale else 0


if __name__ == "__main__":
    sys.exit(main())
