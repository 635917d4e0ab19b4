"""Practice 5, MuJoCo version: Ackermann steering and four driven wheels.

The driver turns the centre steering joint; the script reads its angle, sets the
two knuckles by Equation 4 and drives each wheel at the speed its own distance
from the turning centre needs. It reads example_5's own files:
- one actuator per <transmission> in the URDF, its kind from the controller type
  in config/joint_names_example_5.yaml: a JointPositionController becomes a
  MuJoCo position actuator (kp = p, kv = d), a JointVelocityController a
  velocity actuator (kv = p); both are held to the joint's effort limit;
- the wheelbase l, the track w and the wheel radius from the compiled model.

Run it from the repository root:
    python examples/example_5/scripts/ackermann.py
"""

import math
from dataclasses import dataclass
from pathlib import Path

import mujoco
import numpy as np

import sw2sim
from sw2sim.ros_control import read_controllers, read_transmissions

PACKAGE = Path("examples/example_5")        # run from the repository root
TIMESTEP = 0.001      # s
CONTROL_RATE = 100    # Hz: how often the script reads the steering joint
STEERING = "steering_joint"
KNUCKLES = {"left": "left_knuckle_joint", "right": "right_knuckle_joint"}
WHEELS = {"front_left": "front_left_wheel_joint", "front_right": "front_right_wheel_joint",
          "rear_left": "rear_left_wheel_joint", "rear_right": "rear_right_wheel_joint"}
GRIP = 1.0            # friction coefficient between the wheels and the floor


@dataclass(frozen=True)
class Geometry:
    wheelbase: float  # l, m: rear axle to the front steering axes
    track: float      # w, m: between the left and right steering axes
    radius: float     # r, m: of the wheels


def measure(model):
    """l, w and r from the compiled model: joint anchors and the wheel's mesh."""
    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)

    def anchor(joint):
        return data.xanchor[model.joint(joint).id]

    left, right = anchor(KNUCKLES["left"]), anchor(KNUCKLES["right"])
    rear = (anchor(WHEELS["rear_left"]) + anchor(WHEELS["rear_right"])) / 2
    wheel = model.joint(WHEELS["rear_left"])
    axis = data.xaxis[wheel.id]
    geom = next(g for g in range(model.ngeom) if model.geom_bodyid[g] == wheel.bodyid[0]
                and model.geom_contype[g] and model.geom_type[g] == mujoco.mjtGeom.mjGEOM_MESH)
    mesh = model.geom_dataid[geom]
    start, count = model.mesh_vertadr[mesh], model.mesh_vertnum[mesh]
    points = (model.mesh_vert[start:start + count] @ data.geom_xmat[geom].reshape(3, 3).T
              + data.geom_xpos[geom] - anchor(WHEELS["rear_left"]))
    off_axis = points - np.outer(points @ axis, axis)
    return Geometry(wheelbase=float((left + right)[0] / 2 - rear[0]),
                    track=float(left[1] - right[1]),
                    radius=float(np.linalg.norm(off_axis, axis=1).max()))


def knuckle_angles(phi, l, w):
    """Equation 4: the left and right knuckle angles for a centre angle `phi`
    (rad, positive to the left). The inner wheel, on the side the car turns to,
    gets the larger angle."""
    s, c = math.sin(phi), math.cos(phi)
    inner_if_left = math.atan2(2 * l * s, 2 * l * c - w * s)
    inner_if_right = math.atan2(2 * l * s, 2 * l * c + w * s)
    return inner_if_left, inner_if_right      # left, right


def wheel_speeds(speed, phi, geometry):
    """Each wheel's angular speed, rad/s, for the rear axle's centre at `speed` m/s.

    Every wheel runs at speed × (its distance from the turning centre) / R, with
    R = l / tan(phi) the rear axle centre's radius, so none is dragged or held
    back. Written with the curvature k = 1/R, it needs no special case for phi = 0.
    """
    l, w, r = geometry.wheelbase, geometry.track, geometry.radius
    k = math.tan(phi) / l
    rear = {"left": 1 - k * w / 2, "right": 1 + k * w / 2}
    out = {}
    for side, share in rear.items():
        out[f"rear_{side}"] = speed * share / r
        out[f"front_{side}"] = speed * math.hypot(share, k * l) / r
    return out


def add_actuators(spec, package=PACKAGE):
    """One MuJoCo actuator per transmission, the kind and gains from the YAML."""
    config = package / "config" / f"joint_names_{spec.modelname}.yaml"
    settings = read_controllers(config)[spec.modelname]
    by_joint = {c["joint"]: c for c in settings.values() if "joint" in c}
    names = []
    for t in read_transmissions(package):
        c = by_joint[t.joint]
        act = spec.add_actuator(name=t.actuator, target=t.joint,
                                trntype=mujoco.mjtTrn.mjTRN_JOINT)
        if c["type"].endswith("JointPositionController"):
            act.set_to_position(kp=c["pid"]["p"], kv=c["pid"]["d"])
        elif c["type"].endswith("JointVelocityController"):
            act.set_to_velocity(kv=c["pid"]["p"])
        else:
            raise ValueError(f"{t.joint}: no MuJoCo actuator for {c['type']}")
        act.gear[0] = t.reduction
        names.append(t.actuator)
    return names


def car_spec(package=PACKAGE, grip=GRIP):
    """The car on the floor, with its actuators and grippy wheels."""
    spec = sw2sim.load_package(package, fixed_base=False)
    spec.option.timestep = TIMESTEP
    for body in spec.bodies:
        if body.name.endswith("_wheel"):
            for geom in body.geoms:
                if geom.contype:
                    geom.friction = [grip, 0.005, 0.0001]
    add_actuators(spec, package)
    return spec


class Car:
    """The car in MuJoCo, driven like the ROS version: a speed and a steering angle.

    `ackermann=False` steers both knuckles to the centre angle (parallel steering);
    `own_speeds=False` drives all four wheels at the same speed. Both are there to
    show what goes wrong without them.
    """

    def __init__(self, package=PACKAGE, ackermann=True, own_speeds=True, grip=GRIP):
        package = Path(package)
        self.model = car_spec(package, grip).compile()
        self.data = mujoco.MjData(self.model)
        self.geometry = measure(self.model)
        self.ackermann, self.own_speeds = ackermann, own_speeds
        m = self.model
        self.act = {m.joint(m.actuator_trnid[a, 0]).name: a for a in range(m.nu)}
        self.qpos = {j: m.joint(j).qposadr[0] for j in (STEERING, *KNUCKLES.values())}
        self.steps_per_control = round(1 / (CONTROL_RATE * TIMESTEP))
        self.speed = 0.0
        self.knuckle_setpoints = (0.0, 0.0)
        self.log = []

    def command(self, speed=None, steering=None):
        """The driver's input: the rear axle centre's speed (m/s) and the centre
        steering angle (rad, positive to the left, kept inside its limits)."""
        if speed is not None:
            self.speed = float(speed)
        if steering is not None:
            low, high = self.model.jnt_range[self.model.joint(STEERING).id]
            self.data.ctrl[self.act[STEERING]] = min(max(float(steering), low), high)

    def steering_angle(self):
        """The centre steering joint's measured angle (what ROS's joint_states reports)."""
        return float(self.data.qpos[self.qpos[STEERING]])

    def knuckle_angles(self):
        return tuple(float(self.data.qpos[self.qpos[j]]) for j in KNUCKLES.values())

    def control(self):
        """Read the steering joint; set the knuckles and the wheels."""
        phi, g = self.steering_angle(), self.geometry
        if self.ackermann:
            self.knuckle_setpoints = knuckle_angles(phi, g.wheelbase, g.track)
        else:
            self.knuckle_setpoints = (phi, phi)
        for angle, joint in zip(self.knuckle_setpoints, KNUCKLES.values()):
            self.data.ctrl[self.act[joint]] = angle
        if self.own_speeds:
            speeds = wheel_speeds(self.speed, phi, g)
        else:
            speeds = dict.fromkeys(WHEELS, self.speed / g.radius)
        for key, joint in WHEELS.items():
            self.data.ctrl[self.act[joint]] = speeds[key]

    def step(self):
        """One control period: read, command, then run the physics until the next."""
        self.control()
        self._record()
        mujoco.mj_step(self.model, self.data, nstep=self.steps_per_control)

    def run(self, seconds):
        for _ in range(round(seconds * CONTROL_RATE)):
            self.step()

    def pose(self):
        """x, y (m) of the rear axle centre and the heading (rad)."""
        x, y = self.data.qpos[:2]
        qw, qx, qy, qz = self.data.qpos[3:7]
        return float(x), float(y), math.atan2(2 * (qw * qz + qx * qy), 1 - 2 * (qy * qy + qz * qz))

    def slip(self):
        """How fast each wheel's tread slides over the floor, m/s: the wheel centre's
        velocity along and across the wheel, less the tread's own speed (spin × r).
        A wheel that rolls exactly where it points slips 0."""
        m, d, r = self.model, self.data, self.geometry.radius
        out = {}
        velocity = np.zeros(6)
        for key, joint in WHEELS.items():
            j = m.joint(joint)
            mujoco.mj_objectVelocity(m, d, mujoco.mjtObj.mjOBJ_BODY, j.bodyid[0], velocity, 0)
            axle = d.xaxis[j.id]
            ahead = np.cross(axle, [0.0, 0.0, 1.0])
            ahead /= np.linalg.norm(ahead)
            v = velocity[3:]
            along = v @ ahead - d.qvel[j.dofadr[0]] * r
            across = v @ axle
            out[key] = float(math.hypot(along, across))
        return out

    def _record(self):
        self.log.append((self.data.time, *self.pose(), self.steering_angle(),
                         *self.knuckle_setpoints, *self.knuckle_angles()))

    def states(self):
        """The log as arrays: time, x, y, heading, centre angle, left and right
        knuckle set points, left and right knuckle angles."""
        return np.array(self.log).T


if __name__ == "__main__":
    car = Car()
    g = car.geometry
    print(f"l = {g.wheelbase:.3f} m, w = {g.track:.3f} m, r = {g.radius:.3f} m")
    car.command(speed=0.5, steering=0.3)
    car.run(10.0)
    left, right = car.knuckle_angles()
    print(f"centre {math.degrees(car.steering_angle()):.2f}°, "
          f"left knuckle {math.degrees(left):.2f}°, right {math.degrees(right):.2f}°")
    x, y, heading = car.pose()
    print(f"after 10 s: x = {x:.3f} m, y = {y:.3f} m, heading {math.degrees(heading):.1f}°")
