"""The stability run: a few seconds of simulation, for what reading the files cannot show.

The package is loaded as `sw2sim.load_package` loads it. The base is fixed when the URDF
fixes it to a link named `world`, and free otherwise, as in Gazebo: MuJoCo's URDF import
would weld any jointless root to the world, and so hide a model that cannot stand.
MuJoCo then steps it for 2 s with no input and 2 s with small random input: the motors
of the URDF's transmissions where there are any (`ros_control.add_motors`), or else
random forces on each joint. Each input is sized to give its joint, on its own, an
acceleration of ACCELERATION, so a sound model only sways.
"""

from __future__ import annotations

import math
import random
import re
import time
from contextlib import contextmanager

import mujoco
import numpy as np

from ..actuators import joint_inertia
from ..loader import load_package
from .collision_hulls import hulls
from ..package import LoadError
from ..ros_control import add_motors
from .findings import ERROR, WARNING, rule

rule("mujoco-compile", ERROR, "simulation", "MuJoCo cannot compile the model",
     symptom="`sw2sim.load_package`, `MjSpec.compile` or `MjModel.from_xml_path` stops with "
             "an error message instead of a model, so nothing can be simulated.",
     cause="The URDF holds something URDF tools accept but MuJoCo's compiler refuses: most "
           "often a moving link with zero or tiny mass or inertia, an inertia whose principal "
           "moments break the triangle inequality (A + B >= C), or a mesh that does not "
           "enclose a volume.",
     fix="Read MuJoCo's message: it names the element at fault. Give that link its real mass "
         "and inertia (SolidWorks: Tools, Evaluate, Mass Properties) or repair and re-export "
         "its mesh, then check again.",
     seen_in=("mujoco#739", "mujoco#375", "mujoco#759", "mujoco#2491"))
rule("sim-unstable", ERROR, "simulation", "The simulation blows up",
     symptom="Within moments, joint positions or speeds become NaN or enormous. MuJoCo warns "
             "'Nan, Inf or huge value in QACC' or 'Inertia matrix is too close to singular' "
             "and resets the simulation, so the model snaps back to its start or never moves.",
     cause="Values that the integrator cannot follow at the time step: a link far lighter than "
           "the links it carries, an inertia off by a unit factor (g·mm² written as kg·m²), "
           "negative damping, or forces far larger than the masses can take.",
     fix="Look at the joint and the link the message names: compare their mass, inertia and "
         "<dynamics> values with SolidWorks' Mass Properties and correct the units. Try a "
         "smaller time step only once the numbers are right.")
rule("sim-warning", WARNING, "simulation", "MuJoCo warns during the run",
     symptom="MuJoCo prints a warning while the model loads or runs, such as 'Contact buffer "
             "full' or 'Bad ctrl', and writes it to MUJOCO_LOG.TXT in the working folder.",
     cause="Usually far more contacts than the model needs at once (detailed collision meshes "
           "that overlap, or many links resting on each other), or an input that is NaN or "
           "huge; when loading, a value MuJoCo reads differently from what it says.",
     fix="Read the warning: simplify or separate overlapping collision meshes, exclude contacts "
         "between links that touch by design, and keep inputs finite.")
rule("sim-flies-off", ERROR, "simulation", "A link flies off or falls away",
     symptom="In the viewer the model jumps, spins away or drops through the floor, although "
             "nothing pushes it.",
     cause="Collision meshes that overlap at the start pose push their links apart with large "
           "forces; a link without a collision shape falls through the floor; or a joint runs "
           "away because nothing limits or damps it.",
     fix="Look at the named link at the start pose (`sw2sim view`): move overlapping parts "
         "apart in SolidWorks or exclude their contact, give the links that rest on the floor "
         "a collision shape, and check the joint's axis and limits.",
     seen_in=("solidworks_urdf_exporter#97", "mujoco#1751"))

QUIET_SECONDS = 2.0     # with no input: does the model stand (or rest) by itself?
DRIVEN_SECONDS = 2.0    # with small random input: does it stay sound when moved?
CHUNK = 10              # steps between looks at the state
HOLD = 0.1              # s, how long each random input is held
ACCELERATION = 2.0      # rad/s² or m/s²: what a random input gives its joint on its own
SEED = 0
MIN_EXTENT = 0.1        # m: bounds for tiny models are taken as for a 10 cm one
SPEED_BOUND = 4.0       # × sqrt(g × extent): the speed of a fall from 8 model sizes
DISTANCE_BOUND = 5.0    # × extent: how far a link may get from where it started

_BLOW_UP = {  # MuJoCo's warnings that mean it gave up on the state and reset it
    mujoco.mjtWarning.mjWARN_BADQACC: "acceleration",
    mujoco.mjtWarning.mjWARN_BADQVEL: "speed",
    mujoco.mjtWarning.mjWARN_BADQPOS: "position",
    mujoco.mjtWarning.mjWARN_INERTIA: "inertia matrix",
}
_SOFT = {  # warnings after which the run goes on
    mujoco.mjtWarning.mjWARN_CONTACTFULL: "the contact buffer is full (too many contacts)",
    mujoco.mjtWarning.mjWARN_CNSTRFULL: "the constraint buffer is full",
    mujoco.mjtWarning.mjWARN_BADCTRL: "a control input was NaN or huge",
}


def check(ctx) -> dict:
    """Run the model; add findings to ctx; return the run's figures for the report."""
    started = time.perf_counter()
    with mujoco_warnings() as said:
        try:
            package = ctx.repaired_package()   # as convert writes it
            fixed = package.world_fixed
            spec = load_package(package, fixed_base=fixed, scene="floor",   # never drawn
                                hulls=hulls(ctx))
            try:
                motors = add_motors(spec, package)
            except (LoadError, ValueError):
                motors = []   # the joint checks report unreadable transmissions
            model = spec.compile()
        except LoadError as exc:
            return _not_compiled(ctx, exc.message, exc.file, exc.line, started)
        except Exception as exc:  # noqa: BLE001  (MuJoCo's errors come as several types)
            return _not_compiled(ctx, str(exc), None, None, started)
        for text in dict.fromkeys(said):
            ctx.add("sim-warning", f"MuJoCo warns while loading: {_flat(text)}",
                    element=_named_element(ctx, text),
                    fix="correct the element the warning names, so that MuJoCo reads it as "
                        "ROS does; MuJoCo has left it out or changed it")
        run = _Run(model, ctx, said)
        try:
            run.go()
        except Exception as exc:  # noqa: BLE001  (an error inside mj_step ends the run)
            ctx.add("sim-unstable", f"MuJoCo stopped with an error after {run.seconds:.3f} s: "
                    f"{_flat(exc)}")
            run.trouble = f"stopped after {run.seconds:.3f} s: MuJoCo raised an error"
    base = "fixed base (world link)" if fixed else "free base (no world link)"
    driven = (f"{len(motors)} motor(s) driven at random" if motors
              else f"random forces on {len(run.dofs)} joint(s)")
    figures = {
        "seconds": round(run.seconds, 4), "steps": run.steps,
        "wall_time": round(time.perf_counter() - started, 3),
        "max_speed": round(run.max_speed, 4), "max_distance": round(run.max_distance, 4),
        "fixed_base": fixed, "input": driven,
    }
    outcome = run.trouble or f"fastest link {run.max_speed:.2f} m/s"
    figures["summary"] = (f"{run.seconds:.1f} s simulated ({run.steps} steps) in "
                          f"{figures['wall_time']:.2f} s; {base}; {driven}; {outcome}")
    return figures


@contextmanager
def mujoco_warnings():
    """Collect MuJoCo's warnings instead of letting it print them and write MUJOCO_LOG.TXT
    into the user's working folder."""
    said: list[str] = []
    previous = mujoco.get_mju_user_warning()
    mujoco.set_mju_user_warning(said.append)
    try:
        yield said
    finally:
        mujoco.set_mju_user_warning(previous)


def _flat(text) -> str:
    """One line: findings are printed one per line."""
    return " ".join(str(text).split()).rstrip(".")


def _named_element(ctx, text: str):
    """The first joint or link that MuJoCo's message names in quotes, for its line."""
    for name in re.findall(r"'([^']+)'", text):
        if name in ctx.joints or name in ctx.links:
            return ctx.joints.get(name, ctx.links.get(name))
    return None


_COMPILE_FIXES = (
    ("mass and inertia", "give the named link a positive <mass> and <inertia> (its real "
                         "values, from SolidWorks' Mass Properties)"),
    ("A + B >= C", "the principal moments must satisfy A + B >= C: take the inertia from "
                   "SolidWorks' Mass Properties again instead of editing it by hand"),
    ("mesh", "open the named mesh in a mesh viewer; re-export it from SolidWorks as a closed "
             "solid in metres"),
)


def _not_compiled(ctx, message, file, line, started) -> dict:
    fix = next((f for key, f in _COMPILE_FIXES if key in message), None)
    ctx.add("mujoco-compile", _flat(message), file=file, line=line, fix=fix)
    return {"seconds": 0.0, "steps": 0, "wall_time": round(time.perf_counter() - started, 3),
            "max_speed": 0.0, "max_distance": 0.0,
            "summary": "not run: MuJoCo cannot compile the model"}


class _Run:
    """One stability run of a compiled model; findings go to ctx as they are seen."""

    def __init__(self, model: mujoco.MjModel, ctx, said: list[str]):
        self.model, self.ctx = model, ctx
        # MuJoCo says a warning the first time it counts it; reading the counters is slow,
        # so they are read only when something was said.
        self.said, self.heard = said, len(said)
        self.counts = [0] * int(mujoco.mjtWarning.mjNWARNING)
        # Python's own generator: numpy's takes a fiftieth of a second to import
        self.rng = random.Random(SEED)
        self.steps, self.seconds = 0, 0.0
        self.max_speed = self.max_distance = 0.0
        self.trouble: str | None = None
        self.extent = max(float(model.stat.extent), MIN_EXTENT)
        gravity = float(np.linalg.norm(model.opt.gravity)) or 9.81
        self.speed_bound = SPEED_BOUND * math.sqrt(gravity * self.extent)
        self.distance_bound = DISTANCE_BOUND * self.extent
        moving = (int(mujoco.mjtJoint.mjJNT_HINGE), int(mujoco.mjtJoint.mjJNT_SLIDE))
        self.joints = [j for j in range(model.njnt) if model.jnt_type[j] in moving]
        self.dofs = np.array([model.jnt_dofadr[j] for j in self.joints], dtype=int)

    def go(self) -> None:
        m = self.model
        self.data = mujoco.MjData(m)
        inertia = joint_inertia(m)
        self.dof_push = np.array([inertia[j] * ACCELERATION for j in self.joints])
        gears = np.maximum(np.abs(m.actuator_gear[:, 0]), 1e-9)
        self.ctrl_push = np.array([inertia[m.actuator_trnid[a, 0]] * ACCELERATION / gears[a]
                                   for a in range(m.nu)])
        self.warned: set[int] = set()
        mujoco.mj_forward(m, self.data)
        self.start = self.data.xipos[1:].copy()
        self.last = self.start.copy()
        if self._phase(QUIET_SECONDS, driven=False):
            self._phase(DRIVEN_SECONDS, driven=True)

    def _phase(self, seconds: float, driven: bool) -> bool:
        """Step for `seconds`; False when the run had to stop."""
        chunk_time = CHUNK * self.model.opt.timestep
        hold = max(1, round(HOLD / chunk_time))
        for n in range(max(1, round(seconds / chunk_time))):
            if driven and n % hold == 0:
                self._push()
            if not self._chunk(chunk_time):
                return False
        return True

    def _push(self) -> None:
        d, m = self.data, self.model
        if m.nu:
            ctrl = self._uniform(m.nu) * self.ctrl_push
            limited = m.actuator_ctrllimited.astype(bool)
            low, high = m.actuator_ctrlrange[:, 0], m.actuator_ctrlrange[:, 1]
            d.ctrl[:] = np.where(limited, np.clip(ctrl, low, high), ctrl)
        elif len(self.dofs):
            d.qfrc_applied[:] = 0
            d.qfrc_applied[self.dofs] = self._uniform(len(self.dofs)) * self.dof_push

    def _uniform(self, count: int) -> np.ndarray:
        """`count` numbers drawn evenly from -1 to 1."""
        return np.array([self.rng.uniform(-1.0, 1.0) for _ in range(count)])

    def _chunk(self, chunk_time: float) -> bool:
        m, d = self.model, self.data
        mujoco.mj_step(m, d, nstep=CHUNK)
        self.steps += CHUNK
        self.seconds += chunk_time
        if not (np.isfinite(d.qpos).all() and np.isfinite(d.qvel).all()):
            bad = int(np.flatnonzero(~np.isfinite(d.qvel))[0]) if not np.isfinite(d.qvel).all() \
                else self._dof_of_qpos(int(np.flatnonzero(~np.isfinite(d.qpos))[0]))
            self._unstable(bad, "the state became NaN or infinite")
            return False
        if len(self.said) == self.heard:
            return self._movement(chunk_time)
        self.heard = len(self.said)
        now = [w.number for w in d.warning]
        new = [after - before for after, before in zip(now, self.counts)]
        self.counts = now
        for kind, what in _BLOW_UP.items():
            if new[int(kind)] > 0:
                info = int(d.warning[kind].lastinfo)
                dof = self._dof_of_qpos(info) if kind == mujoco.mjtWarning.mjWARN_BADQPOS else info
                if kind == mujoco.mjtWarning.mjWARN_INERTIA:
                    self._unstable(dof, "the inertia matrix is too close to singular for "
                                        "MuJoCo to take a step")
                else:
                    self._unstable(dof, f"the {what} became NaN, infinite or huge, and MuJoCo "
                                        "reset the simulation")
                return False
        for kind, what in _SOFT.items():
            if new[int(kind)] > 0 and int(kind) not in self.warned:
                self.warned.add(int(kind))
                self.ctx.add("sim-warning", f"after {self.seconds:.2f} s, {what}")
        return self._movement(chunk_time)

    def _movement(self, chunk_time: float) -> bool:
        now = self.data.xipos[1:]
        speed = np.linalg.norm(now - self.last, axis=1) / chunk_time
        moved = np.linalg.norm(now - self.start, axis=1)
        self.last = now.copy()
        self.max_speed = max(self.max_speed, float(speed.max(initial=0.0)))
        self.max_distance = max(self.max_distance, float(moved.max(initial=0.0)))
        fast, far = speed > self.speed_bound, moved > self.distance_bound
        if not (fast.any() or far.any()):
            return True
        body = 1 + int(np.argmax(np.where(far, moved, 0) if far.any() else speed))
        name = self.model.body(body).name
        drop = self.start[body - 1, 2] - now[body - 1, 2]
        across = f"a model {self.extent:.2f} m across"
        if far.any() and drop > 0.7 * moved[body - 1]:
            message = (f"link {name!r} fell {drop:.2f} m, through the floor, within "
                       f"{self.seconds:.2f} s")
            fix = (f"give link {name!r} (or the links holding it up) a <collision> shape that "
                   "reaches the floor")
        elif far.any():
            message = (f"link {name!r} got {moved[body - 1]:.2f} m from where it started "
                       f"within {self.seconds:.2f} s; for {across} "
                       f"{self.distance_bound:.2f} m is the bound")
            fix = None
        else:
            message = (f"link {name!r} reached {speed[body - 1]:.1f} m/s after "
                       f"{self.seconds:.2f} s; for {across} {self.speed_bound:.1f} m/s "
                       "is the bound")
            fix = None
        self.ctx.add("sim-flies-off", message, element=self.ctx.links.get(name), fix=fix)
        self.trouble = f"stopped after {self.seconds:.2f} s: link {name!r} flew off"
        return False

    def _dof_of_qpos(self, index: int) -> int:
        """The first degree of freedom of the joint that owns qpos[index]."""
        m = self.model
        owners = [j for j in range(m.njnt) if m.jnt_qposadr[j] <= index]
        return int(m.jnt_dofadr[max(owners, key=lambda j: m.jnt_qposadr[j])]) if owners else 0

    def _unstable(self, dof: int, what: str) -> None:
        m = self.model
        dof = min(max(dof, 0), max(m.nv - 1, 0))
        if m.nv == 0:
            joint_words, joint, link = "the model", None, None
        else:
            link = m.body(m.dof_bodyid[dof]).name
            joint = m.joint(m.dof_jntid[dof]).name
            joint_words = f"joint {joint!r}" if joint else f"the free joint of link {link!r}"
        message = f"{joint_words}, within {self.seconds:.3f} s: {what}"
        fix = None
        if link:
            fix = (f"check the mass and inertia of link {link!r} (and of the links next to it) "
                   f"against SolidWorks' Mass Properties, and the <dynamics> of "
                   f"{joint_words}; no damping or friction value may be negative")
        element = self.ctx.joints.get(joint) if joint else self.ctx.links.get(link or "")
        self.ctx.add("sim-unstable", message, element=element, fix=fix)
        self.trouble = f"stopped after {self.seconds:.3f} s: the simulation blew up"
