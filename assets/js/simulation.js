// The Simulate mode of the 3D viewer (assets/js/model-viewer.js imports this file when the
// reader presses Simulate, so that pages stay as light as before until then). It starts the
// physics worker (simulation-worker.js), shows the download's progress, and then draws the
// robot where the worker says its joints are, with play, pause, reset, the speed against
// real time, the lesson's inputs (simulation-controls.js) and a live plot
// (simulation-plot.js). `viewer.simulation` gives the tests the trace and a fixed-time run.

import { buildControls } from "./simulation-controls.js";
import { TracePlot, legend } from "./simulation-plot.js";

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

export function startSimulation(viewer, { robot, render, still, part }) {
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
  let joints = [];
  let playing = false;
  let trace = [];
  let waiting = null;   // a fixed-time run's resolve
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
    render();
    clock.value = `t = ${latest.time.toFixed(2)} s`;
    if (playing) speed.value = `${latest.speed.toFixed(1)}\u00d7 real time`;
    if (now - plotted >= PLOT_EVERY || !playing) {
      plotted = now;
      plot.draw();
      numbers.textContent = readout(lesson, trace);
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
      const movable = new Set(Object.keys(robot.joints));
      joints = message.joints.filter((joint) => movable.has(joint.name));
      loading.hidden = true;
      play.disabled = reset.disabled = false;
      buildControls(inputs, lesson, message.inputs,
        (name, value) => worker.postMessage({ type: "set", name, value }), prefix);
      const series = plotSeries(lesson);
      plot = new TracePlot(canvas, series, lesson.unit);
      legend(keys, series);
      canvas.setAttribute("aria-label", `A plot of ${series.map((s) => s.label).join(", ")} `
        + "against time over the last 10 seconds.");
      status(`The simulation is ready (MuJoCo ${message.version}): press Play.`);
      readyResolve(message);
    } else if (message.type === "frame") {
      for (const row of message.trace) trace.push(row);
      plot.add(message.trace);
      latest = message;
      if (!drawing) drawing = requestAnimationFrame(show);
      if (waiting) { const done = waiting; waiting = null; done(message.speed); }
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
    plot.clear();
    speed.value = "";
    worker.postMessage({ type: "reset" });
  });

  viewer.simulation = {
    ready,
    trace: () => trace,
    // Steps `seconds` of simulated time at once; resolves with the real-time factor.
    run: (seconds) => new Promise((resolve) => {
      waiting = resolve;
      worker.postMessage({ type: "run", seconds });
    }),
  };
  worker.postMessage({ type: "load", vendor: new URL(viewer.dataset.mujoco, location.href).href,
    lesson: new URL(viewer.dataset.simulation, location.href).href, site });
}
