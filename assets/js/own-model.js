// "Your own model" in the browser (_includes/own-model-simulator.html): the reader drops
// the folder `sw2sim convert` wrote, or a zip of it, and it simulates with MuJoCo's
// WebAssembly build in the simulation worker (simulation-worker.js, own-model-loading.js),
// gravity on, with a slider per joint; three draws MuJoCo's own shapes where the worker
// says they are. The files are read by the browser and never sent anywhere.

// Only this file loads with the page; the rest comes once the reader drops a model.

const NO_3D = "Your browser cannot run this here: it needs WebGL 2 and WebAssembly, and one "
  + "of them is turned off or not supported.";
const CONVERT = "sw2sim convert YOUR_PACKAGE -o FOLDER";
const MESH = 7;

function part(section, name) {
  return section.querySelector(`.own-model-${name}`);
}

function say(section, text, problem = false) {
  const status = part(section, "status");
  status.textContent = text;
  status.classList.toggle("own-model-problem", problem);
  if (problem) section.dataset.state = "problem";
}

// ---- The dropped files --------------------------------------------------------------

function readEntry(entry, into) {
  if (entry.isFile) {
    return new Promise((resolve, reject) => entry.file(async (file) => {
      into[entry.fullPath.replace(/^\//, "")] = await file.arrayBuffer();
      resolve();
    }, reject));
  }
  const reader = entry.createReader();
  return new Promise((resolve, reject) => {
    const all = [];
    const more = () => reader.readEntries(async (batch) => {
      if (batch.length) { all.push(...batch); more(); return; }
      await Promise.all(all.map((child) => readEntry(child, into)));
      resolve();
    }, reject);
    more();
  });
}

// {path: ArrayBuffer} from a drop (folders included) or from a file input.
async function collect(items, fileList) {
  const files = {};
  const entries = items ? [...items].map((item) => item.webkitGetAsEntry?.()).filter(Boolean) : [];
  if (entries.length) {
    await Promise.all(entries.map((entry) => readEntry(entry, files)));
  } else {
    for (const file of fileList) files[file.webkitRelativePath || file.name] = await file.arrayBuffer();
  }
  const names = Object.keys(files);
  if (names.length === 1 && names[0].toLowerCase().endsWith(".zip")) {
    const { readZip } = await import("./zip-reader.js");
    return readZip(files[names[0]], names[0]);
  }
  return files;
}

// The file to load: the scene.xml nearest the top, else the only .xml. A raw export (a
// .urdf and no MJCF) or anything else gets the sentence that says what to drop instead.
function sceneOf(files) {
  const paths = Object.keys(files);
  const scenes = paths.filter((p) => p.split("/").pop() === "scene.xml")
    .sort((a, b) => a.split("/").length - b.split("/").length);
  if (scenes.length) return scenes[0];
  const urdf = paths.find((p) => p.toLowerCase().endsWith(".urdf"));
  if (urdf) {
    const name = urdf.split("/")[0].replace(/\.urdf$/i, "");
    throw new Error(`${urdf} is an exported package, not the folder sw2sim convert writes. `
      + `Convert it first, \`sw2sim convert ${name} -o ${name}_mujoco\`, and drop ${name}_mujoco.`);
  }
  const xml = paths.filter((p) => p.toLowerCase().endsWith(".xml"));
  if (xml.length === 1) return xml[0];
  throw new Error("No scene.xml among the dropped files: drop the folder sw2sim convert wrote "
    + `(it holds scene.xml, the robot's .xml and assets/), or run \`${CONVERT}\` first.`);
}

// ---- Drawing ------------------------------------------------------------------------

function shapeGeometry(THREE, shape) {
  const [a, b, c] = shape.size;
  switch (shape.type) {
    case 2: return new THREE.SphereGeometry(a, 24, 16);
    case 3: return new THREE.CapsuleGeometry(a, 2 * b, 8, 16).rotateX(Math.PI / 2);
    case 4: return new THREE.SphereGeometry(1, 24, 16).scale(a, b, c);
    case 5: return new THREE.CylinderGeometry(a, a, 2 * b, 24).rotateX(Math.PI / 2);
    case 6: return new THREE.BoxGeometry(2 * a, 2 * b, 2 * c);
    case MESH: {
      const geometry = new THREE.BufferGeometry();
      geometry.setAttribute("position", new THREE.BufferAttribute(shape.vertices, 3));
      geometry.setIndex(new THREE.BufferAttribute(shape.faces, 1));
      geometry.computeVertexNormals();
      return geometry;
    }
    default: return null;
  }
}

function buildScene(THREE, OrbitControls, { fitCamera, litScene }, section, shapes) {
  const renderer = new THREE.WebGLRenderer({ antialias: true });
  renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
  const canvas = renderer.domElement;
  canvas.tabIndex = 0;
  canvas.setAttribute("role", "img");
  canvas.setAttribute("aria-label", "Your model, simulated. Drag, or use the arrow keys, to move the view.");
  const stage = part(section, "stage");
  stage.replaceChildren(canvas);
  const scene = litScene(THREE);
  const world = new THREE.Group();   // MuJoCo's z-up world in three's y-up one
  world.rotation.x = -Math.PI / 2;
  scene.add(world);
  const meshes = shapes.shapes.map((shape) => {
    const geometry = shapeGeometry(THREE, shape);
    const color = new THREE.Color(...shape.rgba.slice(0, 3)).convertSRGBToLinear();
    const mesh = new THREE.Mesh(geometry ?? new THREE.BufferGeometry(),
      new THREE.MeshPhongMaterial({ color, transparent: shape.rgba[3] < 1, opacity: shape.rgba[3] }));
    mesh.matrixAutoUpdate = false;
    world.add(mesh);
    return mesh;
  });
  const camera = new THREE.PerspectiveCamera(40, 5 / 3);
  const controls = new OrbitControls(camera, canvas);
  controls.listenToKeyEvents(canvas);
  const render = () => renderer.render(scene, camera);
  controls.addEventListener("change", render);
  const resize = () => {
    const width = stage.clientWidth;
    if (!width) return;
    renderer.setSize(width, Math.round((width * 3) / 5));
    render();
  };
  new ResizeObserver(resize).observe(stage);
  const matrix = new THREE.Matrix4();
  let framed = false;
  const place = (poses) => {
    meshes.forEach((mesh, i) => {
      const [x, y, z, ...r] = poses.subarray(12 * i, 12 * i + 12);
      matrix.set(r[0], r[1], r[2], x, r[3], r[4], r[5], y, r[6], r[7], r[8], z, 0, 0, 0, 1);
      mesh.matrix.copy(matrix);
    });
    world.updateMatrixWorld(true);
    if (!framed) {   // the first pose frames the model, over a grid on the floor
      framed = true;
      const box = new THREE.Box3().setFromObject(world);
      const size = box.getSize(new THREE.Vector3());
      const cell = [0.05, 0.1, 0.25, 0.5, 1].find((c) => (2 * Math.max(size.x, size.z)) / c <= 30) ?? 1;
      const grid = new THREE.GridHelper(30 * cell, 30, 0x9a9a9a, 0xdadada);
      grid.position.y = shapes.floor ?? Math.min(0, box.min.y);
      scene.add(grid);
      fitCamera(THREE, camera, box);
      controls.target.copy(box.getCenter(new THREE.Vector3()));
      controls.update();
    }
    render();
  };
  return { place, resize };
}

// ---- The controls -------------------------------------------------------------------

function valueText(value, unit) {
  return `${value.toFixed(unit === "rad" || unit === "m" ? 3 : 2).replace("-", "\u2212")} ${unit}`;
}

function buildSliders(section, sliders, send) {
  const fieldset = part(section, "joints");
  fieldset.querySelectorAll(".own-model-joint").forEach((row) => row.remove());
  sliders.forEach((slider, index) => {
    const id = `own-model-joint-${index}`;
    const row = document.createElement("div");
    row.className = "own-model-joint";
    const label = document.createElement("label");
    label.htmlFor = id;
    label.textContent = `${slider.joint} (${slider.kind}, ${slider.unit})`;
    const input = document.createElement("input");
    const step = (slider.max - slider.min) / 200;
    Object.assign(input, { type: "range", id, min: slider.min, max: slider.max, step,
      value: slider.start });
    const output = document.createElement("output");
    output.htmlFor = id;
    const show = () => {
      output.value = valueText(Number(input.value), slider.unit);
      input.setAttribute("aria-valuetext", output.value);
    };
    input.addEventListener("input", () => { show(); send(`ctrl:${slider.actuator}`, Number(input.value)); });
    show();
    row.append(label, input, output);
    fieldset.append(row);
  });
  fieldset.hidden = sliders.length === 0;
}

// ---- Running ------------------------------------------------------------------------

function simulate(section, files, scene) {
  let worker = section.ownWorker;
  if (!worker) {
    worker = new Worker(new URL("./simulation-worker.js", import.meta.url), { type: "module" });
    section.ownWorker = worker;
  }
  const play = part(section, "play");
  const reset = part(section, "reset");
  let drawn = null;
  let latest = null;
  let runs = 0;
  let waiting = null;
  let playing = false;
  let ready;
  const started = new Promise((resolve, reject) => { ready = { resolve, reject }; });
  started.catch(() => {});   // the status says what went wrong; the tests await it
  const setPlaying = (on) => {
    playing = on;
    play.textContent = on ? "Pause" : "Play";
    worker.postMessage({ type: on ? "play" : "pause" });
  };
  worker.onmessage = async ({ data: message }) => {
    if (message.type === "progress") {
      say(section, `Downloading MuJoCo: ${(message.loaded / 1e6).toFixed(1)} of `
        + `${(message.total / 1e6).toFixed(1)} MB`);
    } else if (message.type === "ready") {
      const [THREE, viewer] = await Promise.all([import(section.dataset.libraries),
        import("./model-viewer.js")]);
      part(section, "view").hidden = false;
      drawn = buildScene(THREE, THREE.OrbitControls, viewer, section, message.geoms);
      drawn.resize();
      buildSliders(section, message.lesson.sliders,
        (name, value) => worker.postMessage({ type: "set", name, value }));
      if (latest) drawn.place(latest.poses);
      const joints = message.lesson.sliders.length;
      say(section, `${scene} simulates with MuJoCo ${message.version}, gravity on, `
        + `${joints === 1 ? "1 joint" : `${joints} joints`} with a slider.`);
      section.dataset.state = "ready";
      ready.resolve(message);
      setPlaying(true);
    } else if (message.type === "frame") {
      latest = message;
      if (drawn) requestAnimationFrame(() => drawn.place(latest.poses));
      if (waiting && message.ran === waiting.id) { waiting.done(message.speed); waiting = null; }
    } else if (message.type === "error") {
      say(section, message.message, true);
      ready.reject(new Error(message.message));
    }
  };
  play.onclick = () => setPlaying(!playing);
  reset.onclick = () => { setPlaying(false); worker.postMessage({ type: "reset" }); };
  section.simulation = {
    ready: started,
    qpos: () => Array.from(latest?.qpos ?? []),
    run: (seconds) => new Promise((done) => {
      runs += 1;
      waiting = { id: runs, done };
      worker.postMessage({ type: "run", seconds, id: runs });
    }),
  };
  const vendor = new URL(section.dataset.mujoco, location.href).href;
  worker.postMessage({ type: "own", vendor, files, scene }, Object.values(files));
}

async function accept(section, items, fileList) {
  section.dataset.state = "loading";
  try {
    const { webgl2Available } = await import("./model-viewer.js");
    if (!webgl2Available() || typeof WebAssembly !== "object") throw new Error(NO_3D);
    say(section, "Reading the files\u2026");
    const files = await collect(items, fileList);
    const scene = sceneOf(files);
    simulate(section, files, scene);
  } catch (error) {
    say(section, error.message, true);
  }
}

for (const section of document.querySelectorAll(".own-model")) {
  const drop = part(section, "drop");
  drop.addEventListener("dragover", (event) => { event.preventDefault(); drop.dataset.over = "true"; });
  drop.addEventListener("dragleave", () => { delete drop.dataset.over; });
  drop.addEventListener("drop", (event) => {
    event.preventDefault();
    delete drop.dataset.over;
    accept(section, event.dataTransfer.items, event.dataTransfer.files);
  });
  for (const input of section.querySelectorAll("input[type=file]")) {
    input.addEventListener("change", () => accept(section, null, input.files));
  }
}
