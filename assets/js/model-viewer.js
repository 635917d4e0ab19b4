// The 3D model viewer of the practice pages (_includes/model-viewer.html): a practice's
// exported package, URDF and STL meshes, drawn with three and urdf-loader, with a slider
// per movable joint. The page loads only this file; three and urdf-loader (one minified
// module of about 150 kB compressed, tools/bundle-model-viewer.mjs) are imported when the
// reader asks for the 3D view, so that pages stay light. Where the browser cannot draw 3D (no WebGL 2, which three needs) or the model
// fails to load, the viewer shows the still picture of the model instead.

const DEGREE = Math.PI / 180;
// Neutral greys for the background and the grid, so that every tinted pixel is the model
// (tests/browser/test_model_viewer.py counts them).
const BACKGROUND = 0xf5f5f5;
const GRID_MAJOR = 0x9a9a9a;
const GRID_MINOR = 0xdadada;
const GRID_CELLS = [0.05, 0.1, 0.25, 0.5, 1]; // metres: the first that needs <= 30 cells
const VIEW_DIRECTION = [0.75, 0.65, 1.3]; // from the model's centre, in three's Y-up frame
const ASPECT = 5 / 3; // of the canvas
const FILL = 0.9; // of the canvas's width or height that the model may take

const NO_WEBGL = "Your browser cannot draw 3D graphics here (WebGL 2 is turned off or not "
  + "supported), so this is a still picture of the model instead.";
const LOAD_FAILED = "The 3D model could not be loaded, so this is a still picture of it "
  + "instead.";

export function webgl2Available() {
  try {
    return document.createElement("canvas").getContext("webgl2") !== null;
  } catch {
    return false;
  }
}

function part(viewer, name) {
  return viewer.querySelector(`.model-viewer-${name}`);
}

function setStatus(viewer, state, text) {
  viewer.dataset.state = state;
  part(viewer, "status").textContent = text;
}

function showStill(viewer, sentence) {
  part(viewer, "start").hidden = true;
  part(viewer, "view").hidden = true;
  part(viewer, "note").textContent = sentence;
  part(viewer, "still").hidden = false;
  setStatus(viewer, "still", "");
}

// Every file of the package through one LoadingManager: resolves with the robot once the
// URDF and all its meshes are in, rejects if any of them failed.
function loadRobot(THREE, URDFLoader, viewer) {
  return new Promise((resolve, reject) => {
    const manager = new THREE.LoadingManager();
    const loader = new URDFLoader(manager);
    loader.packages = { [viewer.dataset.package]: viewer.dataset.packageUrl };
    let robot = null;
    const failed = [];
    manager.onError = (url) => failed.push(url);
    manager.onLoad = () => {
      if (failed.length) reject(new Error(`could not load ${failed.join(", ")}`));
      else if (robot) resolve(robot);
    };
    loader.load(viewer.dataset.urdf, (loaded) => { robot = loaded; }, null, reject);
  });
}

// The exporter's colours are the numbers SolidWorks shows, as MuJoCo draws them; three
// would read them as linear light and show them paler.
function colorsAsSrgb(robot) {
  const done = new Set();
  robot.traverse((object) => {
    const material = object.material;
    if (material && material.color && !done.has(material)) {
      material.color.convertSRGBToLinear();
      done.add(material);
    }
  });
}

function movableJoints(robot) {
  return Object.values(robot.joints).filter((joint) =>
    ["revolute", "continuous", "prismatic"].includes(joint.jointType)
    && !("mimicJoint" in joint)); // a mimic joint follows the joint it copies
}

// The slider of one joint, in degrees or metres, kept inside the joint's limits (a
// continuous joint turns freely: one full turn, -180° to 180°).
function sliderRange(joint) {
  if (joint.jointType === "prismatic") {
    return { scale: 1, step: 0.01, unit: "m",
      min: Math.ceil(joint.limit.lower * 100) / 100,
      max: Math.floor(joint.limit.upper * 100) / 100 };
  }
  const free = joint.jointType === "continuous";
  const lower = free ? -Math.PI : joint.limit.lower;
  const upper = free ? Math.PI : joint.limit.upper;
  return { scale: DEGREE, step: 1, unit: "°",
    min: Math.ceil(lower / DEGREE - 1e-6), max: Math.floor(upper / DEGREE + 1e-6) };
}

function valueText(value, range) {
  if (range.unit === "m") return `${value.toFixed(2)} m`;
  const shown = value.toFixed(0).replace("-", "\u2212");
  return `${shown}° (${(value * DEGREE).toFixed(3).replace("-", "\u2212")} rad)`;
}

function addSlider(viewer, joint, index, onChange) {
  const range = sliderRange(joint);
  if (!(range.max > range.min)) return null;
  const id = `${viewer.dataset.package}-joint-${index}`;
  const row = document.createElement("div");
  row.className = "model-viewer-joint";
  const label = document.createElement("label");
  label.htmlFor = id;
  label.textContent = joint.name;
  const input = document.createElement("input");
  Object.assign(input, { type: "range", id, min: range.min, max: range.max, step: range.step });
  const start = Math.min(range.max, Math.max(range.min, 0));
  input.value = start;
  const output = document.createElement("output");
  output.htmlFor = id;
  const show = () => {
    const value = Number(input.value);
    output.value = valueText(value, range);
    input.setAttribute("aria-valuetext", output.value);
    onChange(joint.name, value * range.scale);
  };
  input.addEventListener("input", show);
  show();
  row.append(label, input, output);
  part(viewer, "joints").append(row);
  return () => { input.value = start; show(); };
}

// An empty scene on the viewers' background, lit from the sky and by a sun: the model
// viewer's, and the "Your own model" simulator's.
export function litScene(THREE) {
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(BACKGROUND);
  scene.add(new THREE.HemisphereLight(0xffffff, 0x8a8f96, 2.2));
  const sun = new THREE.DirectionalLight(0xffffff, 2.2);
  sun.position.set(2, 4, 3);
  scene.add(sun);
  return scene;
}

// Places the camera on VIEW_DIRECTION from the centre of the box, as close as it can be
// with every corner of the box inside the picture.
export function fitCamera(THREE, camera, box) {
  const center = box.getCenter(new THREE.Vector3());
  const direction = new THREE.Vector3(...VIEW_DIRECTION).normalize();
  camera.position.copy(center).add(direction);
  camera.lookAt(center);
  camera.updateMatrixWorld();
  const right = new THREE.Vector3().setFromMatrixColumn(camera.matrixWorld, 0);
  const up = new THREE.Vector3().setFromMatrixColumn(camera.matrixWorld, 1);
  const tanUp = FILL * Math.tan((camera.fov / 2) * DEGREE);
  const tanRight = tanUp * camera.aspect;
  let distance = 0;
  const corner = new THREE.Vector3();
  for (const x of [box.min.x, box.max.x]) {
    for (const y of [box.min.y, box.max.y]) {
      for (const z of [box.min.z, box.max.z]) {
        corner.set(x, y, z).sub(center);
        const nearer = corner.dot(direction);
        distance = Math.max(distance, nearer + Math.abs(corner.dot(right)) / tanRight,
          nearer + Math.abs(corner.dot(up)) / tanUp);
      }
    }
  }
  distance = Math.max(distance, 0.05);
  camera.position.copy(center).addScaledVector(direction, distance);
  camera.near = distance / 100;
  camera.far = distance * 20;
  camera.updateProjectionMatrix();
}

function buildScene(THREE, OrbitControls, viewer, robot) {
  const renderer = new THREE.WebGLRenderer({ antialias: true });
  renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
  const canvas = renderer.domElement;
  canvas.tabIndex = 0;
  canvas.setAttribute("role", "img");
  canvas.setAttribute("aria-label",
    "The model in 3D. Drag, or use the arrow keys, to move the view.");
  part(viewer, "stage").append(canvas);

  const scene = litScene(THREE);

  // URDF is Z-up, three is Y-up: a quarter turn about X stands the robot up.
  robot.rotation.x = -Math.PI / 2;
  colorsAsSrgb(robot);
  scene.add(robot);
  robot.updateMatrixWorld(true);

  const box = new THREE.Box3().setFromObject(robot);
  const center = box.getCenter(new THREE.Vector3());
  const size = box.getSize(new THREE.Vector3());
  // The ground of the URDF (z = 0), or below the model if part of it hangs lower; twice
  // as wide as the model.
  const extent = 2 * Math.max(size.x, size.z);
  const cell = GRID_CELLS.find((c) => extent / c <= 30) || GRID_CELLS[GRID_CELLS.length - 1];
  const cells = Math.max(4, 2 * Math.ceil(extent / cell / 2));
  const grid = new THREE.GridHelper(cells * cell, cells, GRID_MAJOR, GRID_MINOR);
  const onCell = (x) => Math.round(x / cell) * cell; // lines through the origin
  grid.position.set(onCell(center.x), Math.min(0, box.min.y) - 1e-3, onCell(center.z));
  scene.add(grid);

  const camera = new THREE.PerspectiveCamera(40, ASPECT);
  fitCamera(THREE, camera, box);

  const controls = new OrbitControls(camera, canvas);
  controls.target.copy(center);
  controls.update();
  controls.saveState();
  controls.listenToKeyEvents(canvas);

  const render = () => renderer.render(scene, camera);
  controls.addEventListener("change", render);
  const stage = part(viewer, "stage");
  const resize = () => {
    const width = stage.clientWidth;
    if (!width) return;
    renderer.setSize(width, Math.round(width / ASPECT));
    render();
  };
  new ResizeObserver(resize).observe(stage);
  return { render, resize, controls };
}

// Where the course build wrote a model for the browser's MuJoCo (the include sets
// data-simulation), the Simulate button loads assets/js/simulation.js and, through it,
// MuJoCo itself: nothing of either comes before the reader asks.
function offerSimulation(viewer, robot, scene) {
  const button = part(viewer, "simulate");
  if (!viewer.dataset.simulation || !button) return;
  button.hidden = false;
  button.addEventListener("click", async () => {
    button.disabled = true;
    try {
      const { startSimulation } = await import("./simulation.js");
      button.hidden = true;
      startSimulation(viewer, { robot, render: scene.render, part, controls: scene.controls,
        still: (sentence) => showStill(viewer, sentence) });
    } catch (error) {
      console.error("Model viewer:", error);
      setStatus(viewer, "ready", "The simulation could not be started.");
    }
  }, { once: true });
}

async function openViewer(viewer) {
  part(viewer, "open").disabled = true;
  if (!webgl2Available()) {
    showStill(viewer, NO_WEBGL);
    return;
  }
  setStatus(viewer, "loading", "Loading the model\u2026");
  try {
    // The bundle exports the classes of three the viewer uses, under their own names.
    const THREE = await import(viewer.dataset.libraries);
    const { OrbitControls, URDFLoader } = THREE;
    const robot = await loadRobot(THREE, URDFLoader, viewer);
    part(viewer, "start").hidden = true;
    part(viewer, "view").hidden = false;
    const scene = buildScene(THREE, OrbitControls, viewer, robot);
    const setJoint = (name, value) => {
      robot.setJointValue(name, value);
      scene.render();
    };
    const resets = movableJoints(robot)
      .map((joint, index) => addSlider(viewer, joint, index, setJoint))
      .filter(Boolean);
    part(viewer, "joints").hidden = resets.length === 0;
    part(viewer, "reset").addEventListener("click", () => {
      resets.forEach((reset) => reset());
      scene.controls.reset();
    });
    scene.resize();
    offerSimulation(viewer, robot, scene);
    const joints = resets.length === 1 ? "1 joint" : `${resets.length} joints`;
    setStatus(viewer, "ready", `The 3D model is ready, with ${joints} to move.`);
    part(viewer, "stage").querySelector("canvas").focus({ preventScroll: true });
  } catch (error) {
    console.error("Model viewer:", error);
    showStill(viewer, LOAD_FAILED);
  }
}

for (const viewer of document.querySelectorAll(".model-viewer")) {
  part(viewer, "open").addEventListener("click", () => openViewer(viewer), { once: true });
}
