// A model the reader dropped on "Your own model", made ready in the simulation worker
// (assets/js/simulation-worker.js imports this file only for such a model): its files
// written to MuJoCo's in-memory file system, refused with the file and the fix where the
// browser's MuJoCo cannot read it, a slider actuator for every joint nothing drives (as
// `sw2sim view` adds them, sw2sim/actuators.py), and the shapes three draws.

const SLIDER_HZ = 2.0;          // natural frequency of a slider's position actuator
const SLIDER_TIME = 0.1;        // s, time constant of a slider's velocity actuator
const SLIDER_SPEED = 2 * Math.PI; // rad/s or m/s, a free joint's velocity slider range
const HINGE = 3;
const SLIDE = 2;
const PLANE = 0;
const TRN_JOINT = 0;
const CONVERT = "sw2sim convert YOUR_PACKAGE -o FOLDER --force";
let drops = 0;

function folderOf(path) {
  return path.includes("/") ? path.slice(0, path.lastIndexOf("/") + 1) : "";
}

// What the browser's MuJoCo refuses that sw2sim convert wrote before it wrote the form
// both versions read (sw2sim/browser_model.py).
function refuseOldForm(files) {
  const decoder = new TextDecoder();
  for (const [path, bytes] of Object.entries(files)) {
    if (!path.toLowerCase().endsWith(".xml")) continue;
    const found = decoder.decode(bytes).match(/<(general|position|velocity)\b[^>]*\sinput="(pos|vel)"/);
    if (found) {
      throw new Error(`${path}: an actuator has input="${found[2]}", which MuJoCo 4 writes and `
        + "the MuJoCo in your browser (3.14) cannot read: an older sw2sim convert wrote this "
        + `folder. Convert your package again with this version, \`${CONVERT}\`, and drop the `
        + "new folder.");
    }
  }
}

function load(mujoco, path, shown) {
  try {
    return mujoco.MjModel.from_xml_path(path);
  } catch (error) {
    throw new Error(`${shown}: the MuJoCo in your browser (${mujoco.mj_versionString()}) cannot `
      + `load it: ${String(error.message ?? error).trim()} If the folder did not come from `
      + `sw2sim convert, convert your exported package first: \`${CONVERT}\`.`);
  }
}

function jointName(mujoco, model, j) {
  return mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_JOINT.value, j);
}

function drivingActuator(model, j) {
  for (let a = 0; a < model.nu; a++) {
    if (model.actuator_trntype[a] === TRN_JOINT && model.actuator_trnid[2 * a] === j) return a;
  }
  return -1;
}

// The bindings of 3.14 cannot read MuJoCo's byte arrays (jnt_limited, actuator_ctrllimited
// throw "_emval_take_value has unknown type memory_view<bool>"): a range with its lower end
// below its upper one is taken as limited, as MuJoCo leaves an unlimited range at 0 0.
function limited(range, i) {
  return range[2 * i] < range[2 * i + 1];
}

function number(value) {
  return Number(value.toPrecision(9)).toString();
}

// An <actuator> section with a slider actuator for each named hinge or slide joint that no
// actuator drives: a position actuator over its range (kp for SLIDER_HZ from the joint's
// own inertia, critically damped), or a velocity actuator where it has no range.
function sliderActuators(mujoco, model) {
  const lines = [];
  for (let j = 0; j < model.njnt; j++) {
    const type = model.jnt_type[j];
    const name = jointName(mujoco, model, j);
    if ((type !== HINGE && type !== SLIDE) || !name || drivingActuator(model, j) >= 0) continue;
    const inertia = model.dof_M0[model.jnt_dofadr[j]];
    if (limited(model.jnt_range, j)) {
      const kp = inertia * (2 * Math.PI * SLIDER_HZ) ** 2;
      lines.push(`<position name="${name}_slider" joint="${name}" kp="${number(kp)}" `
        + `dampratio="1" ctrlrange="${number(model.jnt_range[2 * j])} `
        + `${number(model.jnt_range[2 * j + 1])}"/>`);
    } else {
      lines.push(`<velocity name="${name}_slider" joint="${name}" `
        + `kv="${number(inertia / SLIDER_TIME)}" ctrlrange="${number(-SLIDER_SPEED)} `
        + `${number(SLIDER_SPEED)}"/>`);
    }
  }
  return lines.length ? `<actuator>\n${lines.join("\n")}\n</actuator>\n` : "";
}

// One slider per hinge or slide joint, on the actuator that drives it.
function sliders(mujoco, model) {
  const found = [];
  for (let j = 0; j < model.njnt; j++) {
    const type = model.jnt_type[j];
    const a = drivingActuator(model, j);
    if ((type !== HINGE && type !== SLIDE) || a < 0) continue;
    const gain = model.actuator_gainprm[10 * a];
    const bias = [1, 2].map((k) => model.actuator_biasprm[10 * a + k]);
    const affine = model.actuator_biastype[a] === 1;
    const kind = affine && bias[0] === -gain ? "position"
      : affine && bias[0] === 0 && bias[1] !== 0 ? "velocity" : "force";
    const units = type === HINGE ? { position: "rad", velocity: "rad/s", force: "N·m" }
      : { position: "m", velocity: "m/s", force: "N" };
    let range = [-1, 1];
    if (limited(model.actuator_ctrlrange, a)) {
      range = [model.actuator_ctrlrange[2 * a], model.actuator_ctrlrange[2 * a + 1]];
    } else if (kind === "position" && limited(model.jnt_range, j)) {
      range = [model.jnt_range[2 * j], model.jnt_range[2 * j + 1]];
    } else if (kind === "velocity") {
      range = [-SLIDER_SPEED, SLIDER_SPEED];
    }
    const rest = kind === "position" ? model.qpos0[model.jnt_qposadr[j]] : 0;
    found.push({ joint: jointName(mujoco, model, j), actuator: a, kind, unit: units[kind],
      min: range[0], max: range[1], start: Math.min(range[1], Math.max(range[0], rest)) });
  }
  return found;
}

// The shapes to draw: the visual geoms (group 1, as sw2sim's loader keeps the visual
// meshes), else every geom but planes, each with its size, colour and mesh.
function shapes(model) {
  const all = [...Array(model.ngeom).keys()];
  const visual = all.filter((g) => model.geom_group[g] === 1 && model.geom_type[g] !== PLANE);
  const drawn = visual.length ? visual : all.filter((g) => model.geom_type[g] !== PLANE);
  const geoms = drawn.map((g) => {
    const material = model.geom_matid[g];
    const rgba = material >= 0 ? model.mat_rgba.subarray(4 * material, 4 * material + 4)
      : model.geom_rgba.subarray(4 * g, 4 * g + 4);
    const shape = { type: model.geom_type[g], size: Array.from(model.geom_size.subarray(3 * g, 3 * g + 3)),
      rgba: Array.from(rgba) };
    const mesh = model.geom_dataid[g];
    if (mesh >= 0 && shape.type === 7) {
      const v = model.mesh_vertadr[mesh];
      const f = model.mesh_faceadr[mesh];
      shape.vertices = Float32Array.from(model.mesh_vert.subarray(3 * v, 3 * (v + model.mesh_vertnum[mesh])));
      shape.faces = Uint32Array.from(model.mesh_face.subarray(3 * f, 3 * (f + model.mesh_facenum[mesh])));
    }
    return shape;
  });
  const plane = all.find((g) => model.geom_type[g] === PLANE);
  return { drawn, geoms, floor: plane === undefined ? null : model.geom_pos[3 * plane + 2] };
}

// files: {path: ArrayBuffer}, scene: the path of the file to load. Returns the model, the
// lesson settings for the worker and the shapes for the page.
export function prepare(mujoco, files, scene, writeFile) {
  refuseOldForm(files);
  drops += 1;
  const root = `/own${drops}`;
  for (const [path, bytes] of Object.entries(files)) writeFile(`${root}/${path}`, new Uint8Array(bytes));
  let model = load(mujoco, `${root}/${scene}`, scene);
  const extra = sliderActuators(mujoco, model);
  if (extra) {   // a scene of its own beside the dropped one, so that includes still resolve
    const text = new TextDecoder().decode(files[scene]);
    const end = text.lastIndexOf("</mujoco>");
    const withSliders = `${folderOf(scene)}sw2sim-sliders-${drops}.xml`;
    writeFile(`${root}/${withSliders}`, `${text.slice(0, end)}${extra}${text.slice(end)}`);
    model.delete();
    model = load(mujoco, `${root}/${withSliders}`, scene);
  }
  const { drawn, geoms, floor } = shapes(model);
  return { model, version: mujoco.mj_versionString(), geoms: { shapes: geoms, floor },
    lesson: { kind: "own", sliders: sliders(mujoco, model), drawn } };
}
