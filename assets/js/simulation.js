// The Simulate mode of the 3D viewer (assets/js/model-viewer.js imports this file when the
// reader presses Simulate, so that pages stay as light as before until then). It starts the
// physics worker (simulation-worker.js), shows the download's progress, and then draws the
// robot where the worker says its joints are, with play, pause, reset, the speed against
// real time, the lesson's inputs (simulation-controls.js) and a live plot
// (simulation-plot.js). `viewer.simulation` gives the tests the trace and a fixed-time run.

import { buildControls } from "./simulation-controls.js";
import { PathPlot, TracePlot, legend } from "./simulation-plot.js";

const NO_WASM = "Your browser cannot run the simulation here (WebAssembly or Web Workers "
  + "are turned off or not supported), so this is a still picture of the model instead.";
const FAILED = "The simulation could not be started";
const PLOT_EVERY = 100; // ms

function element(tag, properties = {}, ...children) {
  const made = Object.assign(document.createElement(tag), properties);
  made.append(...children);
  return made;
}

function megabytes(bytes) {
  return `${(bytes / 1e6).toFixed(1)} MB`;
}

function plotSeries(lesson) {
  if (lesson.kind === "car") {
    return [{ label: "circle of Eq. 4's radius, l / tan \u03c6 (dashed)" },
      { label: "path of the rear axle's centre, seen from above" }];
  }
  if (lesson.kind === "pulse") {
    return lesson.joints.map((joint, i) => ({
      label: `${joint.replace(/_joint$/, "").replaceAll("_", " ")} wheel speed (rad/s)`,
      column: 1 + i }));
  }
  return lesson.controllers.flatMap((c, i) => {
    const name = c.name.replace(/_controller$/, "").replaceAll("_", " ");
    return [{ label: `${name} set point (${lesson.unit})`, column: 1 + 2 * i, step: true },
      { label: `${name} position (${lesson.unit})`, column: 2 + 2 * i }];
  });
}

// The circle through the points (x, y) by least squares, as the Practice 5 page fits it:
// x² + y² = a x + b y + c, centre (a/2, b/2), radius √(c + a²/4 + b²/4).
function fittedCircle(points) {
  const n = [[0, 0, 0], [0, 0, 0], [0, 0, 0]];
  const v = [0, 0, 0];
  for (const [x, y] of points) {
    const row = [x, y, 1];
    const rhs = x * x + y * y;
    for (let i = 0; i < 3; i++) {
      v[i] += row[i] * rhs;
      for (let j = 0; j < 3; j++) n[i][j] += row[i] * row[j];
    }
  }
  // Cramer's rule on the 3 × 3 normal equations
  const det = (m) => m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
    - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
    + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  const d = det(n);
  const [a, b, c] = [0, 1, 2].map((k) => det(n.map((row, i) => row.map(
    (value, j) => (j === k ? v[i] : value)))) / d);
  return { x: a / 2, y: b / 2, radius: Math.sqrt(c + (a * a) / 4 + (b * b) / 4) };
}

// SETTLE s after the last change of an input, the car's path is a circle: the page's run
// fits its circle from 3 s on.
const SETTLE = 3;
const FIT_AT_LEAST = 2; // s of path

// The car: the radius driven (the fitted circle) against Eq. 4's, l / tan φ with φ the
// centre joint's mean angle, and the error, as the page prints them.
function carReadout(lesson, trace, changedAt, plot) {
  const from = changedAt + SETTLE;
  const rows = trace.filter((row) => row[0] > from);
  plot.circle = null;
  if (!rows.length || rows[rows.length - 1][0] - from < FIT_AT_LEAST) {
    return `Radius: waiting for ${SETTLE + FIT_AT_LEAST} s of steady driving after the last change.`;
  }
  const phi = rows.reduce((sum, row) => sum + row[4], 0) / rows.length;
  if (Math.abs(Math.tan(phi)) < 1e-3) return "Driving straight: Eq. 4's radius is infinite.";
  const fitted = fittedCircle(rows.map((row) => [row[1], row[2]]));
  const predicted = lesson.geometry.wheelbase / Math.abs(Math.tan(phi));
  plot.circle = { x: fitted.x, y: fitted.y, radius: predicted };
  const error = 100 * (fitted.radius / predicted - 1);
  return `driven R = ${fitted.radius.toFixed(4)} m, predicted ${predicted.toFixed(4)} m, `
    + `error ${error >= 0 ? "+" : "\u2212"}${Math.abs(error).toFixed(2)} %`;
}

// Per position controller, how far the joint went past its set point since the set point
// last changed (the overshoot the lesson reads off its plot), else the speeds of the wheels.
function readout(lesson, trace) {
  if (!trace.length) return "";
  const last = trace[trace.length - 1];
  if (lesson.kind === "pulse") {
    return lesson.joints.map((joint, i) => `${joint.replace(/_joint$/, "").replaceAll("_", " ")}`
      + ` ${last[1 + i].toFixed(2).replace("-", "\u2212")} rad/s`).join(", ");
  }
  return lesson.controllers.map((c, i) => {
    const setpoint = last[1 + 2 * i];
    let start = trace.length - 1;
    while (start > 0 && trace[start - 1][1 + 2 * i] === setpoint) start -= 1;
    const from = trace[start][2 + 2 * i];
    const direction = Math.sign(setpoint - from);
    let past = 0;
    for (let k = start; k < trace.length; k++) {
      past = Math.max(past, direction * (trace[k][2 + 2 * i] - setpoint));
    }
    const scale = lesson.unit === "m" ? 1000 : 1;
    const unit = lesson.unit === "m" ? "mm" : "rad";
    const name = c.name.replace(/_controller$/, "").replaceAll("_", " ");
    return `${name}: error ${((setpoint - last[2 + 2 * i]) * scale).toFixed(lesson.unit === "m" ? 1 : 4)
      .replace("-", "\u2212")} ${unit}, overshoot ${(past * scale).toFixed(lesson.unit === "m" ? 1 : 4)} ${unit}`;
  }).join("; ");
}

// The free base's pose from qpos 0-6 (MuJoCo: z up, quaternion w x y z) on the robot of
// three (y up: the viewer turned the robot a quarter turn about x, which is kept).
const HALF = Math.SQRT1_2;
function placeBase(robot, qpos) {
  const [x, y, z, w, qx, qy, qz] = qpos;
  robot.position.set(x, z, -y);
  robot.quaternion.set(HALF * qx - HALF * w, HALF * qy + HALF * qz, HALF * qz - HALF * qy,
    HALF * w + HALF * qx);
}

export function startSimulation(viewer, { robot, render, still, part, controls }) {
  if (typeof WebAssembly !== "object" || typeof Worker !== "function") {
    still(NO_WASM);
    return;
  }
  const stylesheet = element("link", { rel: "stylesheet", href: viewer.dataset.simulationCss });
  document.head.append(stylesheet);

  const prefix = `${viewer.dataset.package}-simulation`;
  const progress = element("progress", { max: 1, value: 0, id: `${prefix}-progress` });
  const progressLabel = element("label", { htmlFor: progress.id }, "Downloading MuJoCo");
  const loading = element("div", { className: "simulation-loading" }, progressLabel, progress);
  const play = element("button", { type: "button", className: "simulation-play", disabled: true },
    "Play");
  const reset = element("button", { type: "button", className: "simulation-reset",
    disabled: true }, "Reset the simulation");
  const speed = element("output", { className: "simulation-speed" });
  const clock = element("output", { className: "simulation-time" });
  const buttons = element("div", { className: "simulation-buttons" }, play, reset, clock, speed);
  const inputs = element("fieldset", { className: "simulation-inputs" },
    element("legend", {}, "The lesson's inputs, within the model's limits"));
  const canvas = element("canvas", { className: "simulation-plot" });
  canvas.setAttribute("role", "img");
  const keys = element("ul", { className: "simulation-legend" });
  const numbers = element("p", { className: "simulation-readout" });
  numbers.setAttribute("aria-live", "off");
  const panel = element("section", { className: "simulation", hidden: false },
    element("h3", {}, "Simulated with MuJoCo in your browser"), loading, buttons, inputs,
    canvas, keys, numbers);
  part(viewer, "reset").after(panel);
  part(viewer, "joints").hidden = true;   // the physics moves the joints now
  const status = (text) => { part(viewer, "status").textContent = text; };
  status("Downloading MuJoCo\u2026");

  const worker = new Worker(new URL("./simulation-worker.js", import.meta.url),
    { type: "module" });
  const site = new URL(viewer.dataset.site, location.href).href.replace(/\/$/, "");
  let lesson = null;
  let plot = null;
  let free = false;
  let changedAt = 0;      // simulated time of the last input the reader changed
  let lastTime = 0;
  let joints = [];
  let playing = false;
  let trace = [];
  let waiting = null;   // a fixed-time run: {id, done}
  let runs = 0;
  let readyResolve;
  let readyReject;
  const ready = new Promise((resolve, reject) => { readyResolve = resolve; readyReject = reject; });

  // The newest frame is drawn once per display frame; the plot and the numbers, which cost
  // more, PLOT_EVERY ms at most, so that the page keeps answering on a slow machine.
  let latest = null;
  let drawing = 0;
  let plotted = 0;
  const show = (now) => {
    drawing = 0;
    for (const joint of joints) robot.setJointValue(joint.name, latest.qpos[joint.qpos]);
    if (free) {   // the car moves on the floor: the view follows it
      const before = robot.position.clone();
      placeBase(robot, latest.qpos);
      const moved = robot.position.clone().sub(before);
      controls.target.add(moved);
      controls.object.position.add(moved);
      controls.update();
    }
    render();
    clock.value = `t = ${latest.time.toFixed(2)} s`;
    if (playing) speed.value = `${latest.speed.toFixed(1)}\u00d7 real time`;
    if (now - plotted >= PLOT_EVERY || !playing) {
      plotted = now;
      numbers.textContent = lesson.kind === "car"
        ? carReadout(lesson, trace, changedAt, plot) : readout(lesson, trace);
      plot.draw();
    }
  };

  const setPlaying = (on) => {
    playing = on;
    play.textContent = on ? "Pause" : "Play";
    status(on ? "Simulating." : `Paused at ${clock.value || "t = 0.00 s"}.`);
    worker.postMessage({ type: on ? "play" : "pause" });
  };

  worker.onmessage = ({ data: message }) => {
    if (message.type === "progress") {
      progress.value = message.loaded / message.total;
      progressLabel.textContent = `Downloading MuJoCo: ${megabytes(message.loaded)} of `
        + `${megabytes(message.total)}`;
    } else if (message.type === "ready") {
      lesson = message.lesson;
      free = message.free;
      const movable = new Set(Object.keys(robot.joints));
      joints = message.joints.filter((joint) => movable.has(joint.name));
      loading.hidden = true;
      play.disabled = reset.disabled = false;
      buildControls(inputs, lesson, message.inputs, (name, value) => {
        changedAt = lastTime;
        worker.postMessage({ type: "set", name, value });
      }, prefix);
      const series = plotSeries(lesson);
      plot = lesson.kind === "car" ? new PathPlot(canvas) : new TracePlot(canvas, series, lesson.unit);
      legend(keys, series);
      canvas.setAttribute("aria-label", lesson.kind === "car"
        ? `A plot of the ${series.map((s) => s.label).join(" and the ")}.`
        : `A plot of ${series.map((s) => s.label).join(", ")} against time over the last 10 seconds.`);
      status(`The simulation is ready (MuJoCo ${message.version}): press Play.`);
      readyResolve(message);
    } else if (message.type === "frame") {
      for (const row of message.trace) trace.push(row);
      plot.add(message.trace);
      latest = message;
      lastTime = message.time;
      if (!drawing) drawing = requestAnimationFrame(show);
      if (waiting && message.ran === waiting.id) {
        const { done } = waiting;
        waiting = null;
        done(message.speed);
      }
    } else if (message.type === "error") {
      console.error("Simulation:", message.message);
      loading.hidden = true;
      status(`${FAILED}: ${message.message}`);
      readyReject(new Error(message.message));
    }
  };
  worker.onerror = (event) => {
    status(`${FAILED}: ${event.message || "the worker stopped"}.`);
    readyReject(new Error(event.message));
  };

  play.addEventListener("click", () => setPlaying(!playing));
  reset.addEventListener("click", () => {
    setPlaying(false);
    trace = [];
    changedAt = 0;
    plot.clear();
    speed.value = "";
    worker.postMessage({ type: "reset" });
  });

  viewer.simulation = {
    ready,
    trace: () => trace,
    // Steps `seconds` of simulated time at once; resolves with the real-time factor.
    run: (seconds) => new Promise((done) => {
      runs += 1;
      waiting = { id: runs, done };
      worker.postMessage({ type: "run", seconds, id: runs });
    }),
  };
  worker.postMessage({ type: "load", vendor: new URL(viewer.dataset.mujoco, location.href).href,
    lesson: new URL(viewer.dataset.simulation, location.href).href, site });
}
