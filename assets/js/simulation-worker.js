// The physics of the 3D viewer's Simulate mode, in a Web Worker so that the page stays
// responsive: MuJoCo's own WebAssembly build (@mujoco/mujoco, vendored by
// tools/copy-vendor.sh), the practice's model as the course build wrote it
// (media/practice-N/simulate.json, from course/browser_models.py) and the lesson's
// controllers, written as the Python lesson scripts write them, with the same names.
// (One difference of the bindings: `model.jnt(name).qposadr` is a number here, where
// Python's `model.joint(name).qposadr` is an array of one.)
//
// Messages in:  load {vendor, lesson, site}, own {vendor, files, scene} (a dropped model),
//               play, pause, reset, set {name, value},
//               run {seconds, id} (steps as fast as it can, for the tests and the benchmark)
// Messages out: progress {loaded, total}, ready {joints, lesson, inputs, free}, frame
//               {time, qpos, speed, trace, ran: the id of the run it ends}, error {message}

let mujoco = null;
let model = null;
let data = null;
let lesson = null;
let inputs = {};
let controllers = [];
let wheelDofs = [];      // a pulse lesson's joints' entries in qvel and qfrc_applied
let steeringQpos = 0;    // the car's centre steering joint in qpos
let stepsPerControl = 1; // physics steps per run of the car's control (CONTROL_RATE)
let playing = false;
let timer = null;
let trace = [];          // [time, ...the lesson's plotted values], TRACE_RATE per second
const TRACE_RATE = 100;  // samples per second of simulated time, as periodic_force.run's
const TICK = 16;         // ms between two frames sent to the page
const MOST_PER_TICK = 0.1; // s of simulated time at most per tick: a slow machine runs slower

// Where a joint's position and velocity are in qpos and qvel. The accessor is a C++ object
// on MuJoCo's heap, freed at once (the bindings' objects are not garbage-collected).
function address(name) {
  const joint = model.jnt(name);
  const found = { qpos: joint.qposadr, dof: joint.dofadr };
  joint.delete();
  return found;
}

function clamp(value, low, high) {
  return Math.min(Math.max(value, low), high);
}

// ---- Practice 3's arm_controller.py, line for line -------------------------------------

// A PID on the position error, as ROS's control_toolbox computes it (arm_controller.Pid).
class Pid {
  constructor({ p, i = 0, d = 0, i_clamp = 0, antiwindup = false }) {
    Object.assign(this, { p, i, d, i_clamp: Math.abs(i_clamp), antiwindup });
    this.summed = 0;
  }

  call(error, errorRate, dt) {
    this.summed += error * dt;
    if (this.antiwindup && this.i) {
      const bound = this.i_clamp / Math.abs(this.i);
      this.summed = clamp(this.summed, -bound, bound);
    }
    const integral = clamp(this.i * this.summed, -this.i_clamp, this.i_clamp);
    return this.p * error + integral + this.d * errorRate;
  }
}

// arm_controller.JointPositionController: a set point to a joint torque, within limits.
class JointPositionController {
  constructor(settings, cruise) {
    const joint = address(settings.joint);
    this.name = settings.name;
    this.qpos = joint.qpos;
    this.dof = joint.dof;
    this.motor = settings.motor;
    this.pid = new Pid(settings.pid);
    this.limits = settings.limits;
    this.acceleration = settings.acceleration;
    this.cruise = cruise;
    this.setpoint = 0;
    this.reference = null;
    this.reference_speed = 0;
  }

  command(position) {
    this.setpoint = clamp(Number(position), this.limits.lower, this.limits.upper);
  }

  effort(dt) {
    const q = data.qpos[this.qpos];
    const v = data.qvel[this.dof];
    if (this.reference === null) this.reference = q;
    this.lead(dt);
    const torque = this.pid.call(this.reference - q, this.reference_speed - v, dt);
    return this.enforce_limits(torque, q, v);
  }

  lead(dt) {
    const left = this.setpoint - this.reference;
    const acceleration = this.acceleration;
    const canStopFrom = Math.sqrt(2 * acceleration * Math.abs(left));
    const top = this.cruise * this.limits.velocity;
    const wanted = Math.sign(left || 1) * Math.min(top, canStopFrom);
    const change = acceleration * dt;
    this.reference_speed += clamp(wanted - this.reference_speed, -change, change);
    if (Math.abs(left) <= Math.abs(this.reference_speed) * dt) {
      this.reference = this.setpoint;
      this.reference_speed = 0;
    } else {
      this.reference += this.reference_speed * dt;
    }
  }

  enforce_limits(torque, q, v) {
    const lim = this.limits;
    const top = lim.velocity;
    if (lim.k_velocity === null) {   // no <safety_controller>: saturation
      let low = -lim.effort;
      let high = lim.effort;
      if (v > top || (lim.upper !== null && q > lim.upper)) high = 0;
      if (v < -top || (lim.lower !== null && q < lim.lower)) low = 0;
      return clamp(torque, low, high);
    }
    const vMin = clamp(-lim.k_position * (q - lim.soft_lower), -top, top);
    const vMax = clamp(-lim.k_position * (q - lim.soft_upper), -top, top);
    const low = clamp(-lim.k_velocity * (v - vMin), -lim.effort, lim.effort);
    const high = clamp(-lim.k_velocity * (v - vMax), -lim.effort, lim.effort);
    return clamp(torque, low, high);
  }
}

// ---- Practice 1's periodic_force.py ---------------------------------------------------

// periodic_force.wheel_torque: `torque` during the first `pulse` s of every period, else 0.
function wheel_torque(t, period, pulse, torque) {
  return t % period < pulse ? torque : 0;
}

// ---- Practice 5's ackermann.py ----------------------------------------------------------

// Equation 4: the left and right knuckle angles for a centre angle `phi` (rad).
function knuckle_angles(phi, l, w) {
  const s = Math.sin(phi);
  const c = Math.cos(phi);
  return [Math.atan2(2 * l * s, 2 * l * c - w * s), Math.atan2(2 * l * s, 2 * l * c + w * s)];
}

// Each wheel's angular speed, rad/s, for the rear axle's centre at `speed` m/s.
function wheel_speeds(speed, phi, { wheelbase: l, track: w, radius: r }) {
  const k = Math.tan(phi) / l;
  const out = {};
  for (const [side, share] of [["left", 1 - (k * w) / 2], ["right", 1 + (k * w) / 2]]) {
    out[`rear_${side}`] = (speed * share) / r;
    out[`front_${side}`] = (speed * Math.hypot(share, k * l)) / r;
  }
  return out;
}

// Car.control: read the steering joint; set the knuckles and the wheels.
function carControl() {
  const ctrl = data.ctrl;
  const phi = data.qpos[steeringQpos];
  const angles = knuckle_angles(phi, lesson.geometry.wheelbase, lesson.geometry.track);
  lesson.knuckles.forEach((joint, i) => { ctrl[lesson.actuator[joint]] = angles[i]; });
  const speeds = wheel_speeds(inputs.speed, phi, lesson.geometry);
  for (const [key, joint] of Object.entries(lesson.wheels)) {
    ctrl[lesson.actuator[joint]] = speeds[key];
  }
}

// Car.pose: x, y (m) of the rear axle centre and the heading (rad).
function pose() {
  const q = data.qpos;
  const [qw, qx, qy, qz] = [q[3], q[4], q[5], q[6]];
  return [q[0], q[1], Math.atan2(2 * (qw * qz + qx * qy), 1 - 2 * (qy * qy + qz * qz))];
}

// ---- The lesson's inputs and one step -------------------------------------------------

function applyInputs() {
  if (lesson.kind === "pulse" && lesson.friction) {
    lesson.joints.forEach((joint, i) => {
      model.dof_frictionloss[wheelDofs[i]] = inputs[`friction:${joint}`];
    });
  }
  if (lesson.kind === "own") {
    const ctrl = data.ctrl;
    for (const s of lesson.sliders) ctrl[s.actuator] = inputs[`ctrl:${s.actuator}`];
  }
  if (lesson.kind === "car") {   // Car.command: the steering actuator's set point
    const [low, high] = lesson.steering_range;
    data.ctrl[lesson.actuator[lesson.steering]] = clamp(inputs.steering, low, high);
  }
  if (lesson.kind === "position") {
    for (const c of controllers) {
      c.command(inputs[`setpoint:${c.name}`]);
      for (const gain of ["p", "i", "d"]) c.pid[gain] = inputs[`${gain}:${c.name}`];
    }
  }
}

function traced() {
  if (lesson.kind === "own") return [];
  if (lesson.kind === "car") return [...pose(), data.qpos[steeringQpos]];
  if (lesson.kind === "pulse") {
    const qvel = data.qvel;
    return wheelDofs.map((dof) => qvel[dof]);
  }
  return controllers.flatMap((c) => [c.setpoint, data.qpos[c.qpos]]);
}

let steps = 0;
let traceEvery = 1;
let timestep = 0;

function step() {
  const dt = timestep;
  if (lesson.kind === "car" && steps % stepsPerControl === 0) carControl();
  if (steps % traceEvery === 0) trace.push([data.time, ...traced()]);
  if (lesson.kind === "pulse") {
    const qfrc = data.qfrc_applied;
    lesson.joints.forEach((joint, i) => {
      qfrc[wheelDofs[i]] = wheel_torque(data.time, inputs.period, inputs.pulse,
        inputs[`torque:${joint}`]);
    });
  } else if (lesson.kind === "position") {
    const ctrl = data.ctrl;
    for (const c of controllers) ctrl[c.motor] = c.effort(dt);
  }
  mujoco.mj_step(model, data);
  steps += 1;
}

function defaults() {
  const values = {};
  if (lesson.kind === "car") return { ...lesson.start };
  if (lesson.kind === "own") {
    return Object.fromEntries(lesson.sliders.map((s) => [`ctrl:${s.actuator}`, s.start]));
  }
  if (lesson.kind === "pulse") {
    values.period = lesson.period;
    values.pulse = lesson.pulse;
    for (const joint of lesson.joints) {
      values[`torque:${joint}`] = lesson.torque;
      if (lesson.friction) values[`friction:${joint}`] = lesson.friction[joint];
    }
  } else {
    for (const c of lesson.controllers) {
      values[`setpoint:${c.name}`] = 0;
      for (const gain of ["p", "i", "d"]) values[`${gain}:${c.name}`] = c.pid[gain];
    }
  }
  return values;
}

// Whether the model's first joint is a free joint (a car on the floor): its qpos 0-6 are
// then the base's position and orientation.
function hasFreeBase() {
  return model.njnt > 0 && model.jnt_type[0] === 0;   // mjJNT_FREE
}

function reset() {
  mujoco.mj_resetData(model, data);
  steps = 0;
  trace = [];
  if (lesson.kind === "position") {
    controllers = lesson.controllers.map((c) => new JointPositionController(c, lesson.cruise));
  }
  applyInputs();
  mujoco.mj_forward(model, data);
}

function frame(speed, ran = null) {
  const sent = trace;
  trace = [];
  const message = { type: "frame", time: data.time, qpos: Float64Array.from(data.qpos), speed,
    trace: sent, ran };
  if (lesson.kind === "own") {   // where each drawn geom is: position, then rotation matrix
    const xpos = data.geom_xpos;
    const xmat = data.geom_xmat;
    message.poses = new Float64Array(12 * lesson.drawn.length);
    lesson.drawn.forEach((g, i) => {
      message.poses.set(xpos.subarray(3 * g, 3 * g + 3), 12 * i);
      message.poses.set(xmat.subarray(9 * g, 9 * g + 9), 12 * i + 3);
    });
  }
  postMessage(message);
}

// ---- Real time --------------------------------------------------------------------------

let wallStart = 0;
let simStart = 0;

function tick() {
  const now = performance.now();
  const target = simStart + (now - wallStart) / 1000;
  const limit = data.time + MOST_PER_TICK;
  while (data.time < Math.min(target, limit)) step();
  if (target > limit) { // fell behind: run on from here instead of catching up
    wallStart = now;
    simStart = data.time;
  }
  const elapsed = (now - speedWall) / 1000;
  if (elapsed >= 0.5) {
    speed = (data.time - speedSim) / elapsed;
    speedWall = now;
    speedSim = data.time;
  }
  frame(speed);
}

let speed = 1;
let speedWall = 0;
let speedSim = 0;

function play() {
  if (playing) return;
  playing = true;
  wallStart = speedWall = performance.now();
  simStart = speedSim = data.time;
  timer = setInterval(tick, TICK);
}

function pause() {
  playing = false;
  clearInterval(timer);
}

// ---- Loading ----------------------------------------------------------------------------

// The wasm file, read as it arrives so that the page can show the download's progress.
// mujoco.json gives its size: a server that compresses it sends no usable length.
async function fetchWasm(vendor) {
  const about = await (await fetch(`${vendor}/mujoco.json`)).json();
  const response = await fetch(`${vendor}/mujoco.wasm`);
  if (!response.ok) throw new Error(`${vendor}/mujoco.wasm: HTTP ${response.status}`);
  const reader = response.body.getReader();
  const bytes = new Uint8Array(about.wasm_bytes);
  let loaded = 0;
  for (;;) {
    const { done, value } = await reader.read();
    if (done) break;
    bytes.set(value, loaded);
    loaded += value.length;
    postMessage({ type: "progress", loaded, total: about.wasm_bytes });
  }
  if (loaded !== about.wasm_bytes) {
    throw new Error(`mujoco.wasm: ${loaded} bytes arrived, ${about.wasm_bytes} expected`);
  }
  return bytes.buffer;
}

async function fetchBytes(url) {
  const response = await fetch(url);
  if (!response.ok) throw new Error(`${url}: HTTP ${response.status}`);
  return new Uint8Array(await response.arrayBuffer());
}

function writeFile(path, content) {
  const parts = path.split("/").filter(Boolean);
  for (let i = 1; i < parts.length; i++) {
    const dir = `/${parts.slice(0, i).join("/")}`;
    if (!mujoco.FS.analyzePath(dir).exists) mujoco.FS.mkdir(dir);
  }
  mujoco.FS.writeFile(path, content);
}

async function loadMujoco(vendor) {
  if (mujoco) return;
  const [wasmBinary, { default: factory }] = await Promise.all([
    fetchWasm(vendor), import(`${vendor}/mujoco.js`)]);
  mujoco = await factory({ wasmBinary });
}

// Starts the lesson on the loaded `model`: its settings, the inputs' defaults, the ready
// message (with `extra`, what the page needs besides) and the first frame.
function begin(settings, version, extra = {}) {
  data = new mujoco.MjData(model);
  lesson = settings;
  const option = model.opt;   // a copy on MuJoCo's heap: read once, then freed
  timestep = option.timestep;
  option.delete();
  if (lesson.kind === "pulse") wheelDofs = lesson.joints.map((joint) => address(joint).dof);
  if (lesson.kind === "car") {
    steeringQpos = address(lesson.steering).qpos;
    stepsPerControl = Math.round(1 / (lesson.control_rate * timestep));
  }
  traceEvery = Math.max(1, Math.round(1 / (TRACE_RATE * timestep)));
  inputs = defaults();
  reset();
  const joints = [];
  for (let j = 0; j < model.njnt; j++) {
    const joint = model.jnt(j);
    joints.push({ name: joint.name, qpos: joint.qposadr });
    joint.delete();
  }
  postMessage({ type: "ready", joints, lesson, inputs, timestep, free: hasFreeBase(),
    version, ...extra });
  frame(0);
}

async function load({ vendor, lesson: lessonUrl, site }) {
  const [, built] = await Promise.all([loadMujoco(vendor),
    fetch(lessonUrl).then((r) => r.json())]);
  const files = await Promise.all(Object.entries(built.files).map(
    async ([path, url]) => [path, await fetchBytes(`${site}/${url}`)]));
  for (const [path, bytes] of files) writeFile(`/model/${path}`, bytes);
  writeFile("/model/model.xml", built.model);
  model = mujoco.MjModel.from_xml_path("/model/model.xml");
  begin(built.lesson, built.mujoco.browser);
}

// A model the reader dropped on "Your own model" (assets/js/own-model.js): its files,
// checked and given a slider per joint by own-model-loading.js.
async function loadOwn({ vendor, files, scene }) {
  await loadMujoco(vendor);
  const { prepare } = await import("./own-model-loading.js");
  if (model) { data.delete(); model.delete(); }
  const prepared = prepare(mujoco, files, scene, writeFile);
  model = prepared.model;
  begin(prepared.lesson, prepared.version, { geoms: prepared.geoms });
}

onmessage = async ({ data: message }) => {
  try {
    switch (message.type) {
      case "load": await load(message); break;
      case "own": pause(); await loadOwn(message); break;
      case "play": play(); break;
      case "pause": pause(); frame(0); break;
      case "reset": pause(); reset(); frame(0); break;
      case "set":
        inputs[message.name] = message.value;
        applyInputs();
        break;
      case "run": {  // a fixed time, as fast as the machine steps it
        pause();
        const began = performance.now();
        const end = data.time + message.seconds;
        while (data.time < end - 1e-9) step();
        frame(message.seconds / ((performance.now() - began) / 1000), message.id);
        break;
      }
      default: throw new Error(`unknown message ${message.type}`);
    }
  } catch (error) {
    postMessage({ type: "error", message: String(error.message ?? error) });
  }
};
